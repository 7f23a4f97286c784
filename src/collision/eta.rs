//! η(t): a lower bound of the distance between two bodies at time t.

use super::{Body, Stats};
use crate::geometry::{closest_features, FeaturePair, Posed, WalkTolerances};
use crate::motion::{Piece, Pose};

/// A pair's state at one instant: both poses and η.
#[derive(Clone, Copy, Debug)]
pub struct Instant {
    pub t: f64,
    pub pose_a: Pose,
    pub pose_b: Pose,
    /// Lower bound of the distance; exact whenever it is below δ.
    pub eta: f64,
}

/// Evaluates η for one pair, keeping the last closest features for the next warm start.
pub struct Eta<'s> {
    pub a: &'s Body,
    pub b: &'s Body,
    delta: f64,
    walk: WalkTolerances,
    warm: Option<FeaturePair>,
}

impl<'s> Eta<'s> {
    pub fn new(a: &'s Body, b: &'s Body, delta: f64, walk: WalkTolerances) -> Self {
        Eta {
            a,
            b,
            delta,
            walk,
            warm: None,
        }
    }

    /// η(t): the gap between the bounding discs (eq. 13) while it is at least δ, else the
    /// exact distance from the closest-feature walk, warm-started from the previous call.
    /// `pieces` are the pieces of A's and B's motions that hold `t`.
    pub fn at(&mut self, t: f64, pieces: &(Piece, Piece), stats: &mut Stats) -> Instant {
        let pose_a = pieces.0.pose_at(t);
        let pose_b = pieces.1.pose_at(t);
        // Work in a frame centred on A: far from the origin, positions lose digits but
        // their difference does not.
        let rel = pose_b.pos - pose_a.pos;
        let disc_gap = rel.norm() - self.a.shape.radius() - self.b.shape.radius();
        let eta = if disc_gap >= self.delta {
            disc_gap
        } else {
            stats.narrow_phase_calls += 1;
            let pa = Posed::new(&self.a.shape, 0.0, 0.0, pose_a.theta);
            let pb = Posed::new(&self.b.shape, rel.x, rel.y, pose_b.theta);
            let d = closest_features(&pa, &pb, self.warm, &self.walk);
            stats.feature_steps += u64::from(d.steps);
            stats.walk_fallbacks += u64::from(d.fell_back);
            self.warm = Some(d.features);
            d.distance
        };
        Instant {
            t,
            pose_a,
            pose_b,
            eta,
        }
    }
}
