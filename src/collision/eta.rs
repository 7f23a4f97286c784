//! η(t): a lower bound of the distance between two bodies at time t.

use super::span::Probe;
use super::{Body, Stats};
use crate::geometry::{closest_features, FeaturePair, Posed, Vec2, WalkTolerances};
use crate::motion::{lambda, BoundKind, Pose};

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

    /// Sum of the two bounding-disc radii (eq. 13).
    pub fn radii(&self) -> f64 {
        self.a.shape.radius() + self.b.shape.radius()
    }

    /// λ1 + λ2 from probe `l` to probe `r`, between which both poses are linear in time.
    pub fn lambda(&self, bound: BoundKind, l: &Probe, r: &Probe) -> f64 {
        let one = |body: &Body, p: &Pose, q: &Pose| {
            lambda(bound, &body.motion, body.shape.radius(), (l.t, p), (r.t, q))
        };
        one(self.a, &l.pose_a, &r.pose_a) + one(self.b, &l.pose_b, &r.pose_b)
    }

    /// η(t): the gap between the bounding discs (eq. 13) while it is at least δ, else the
    /// exact distance from the closest-feature walk, warm-started from the previous call.
    /// `poses` are A's and B's poses at time `t`.
    pub fn at(&mut self, t: f64, (pose_a, pose_b): (Pose, Pose), stats: &mut Stats) -> Probe {
        // Work in a frame centred on A: far from the origin, positions lose digits but
        // their difference does not.
        let rel = pose_b.pos - pose_a.pos;
        let disc_gap = rel.norm() - self.radii();
        let (eta, exact, normal) = if disc_gap >= self.delta {
            (disc_gap, false, Vec2::zeros())
        } else {
            stats.narrow_phase_calls += 1;
            let pa = Posed::new(&self.a.shape, 0.0, 0.0, pose_a.theta);
            let pb = Posed::new(&self.b.shape, rel.x, rel.y, pose_b.theta);
            let d = closest_features(&pa, &pb, self.warm, &self.walk);
            stats.feature_steps += u64::from(d.steps);
            stats.walk_fallbacks += u64::from(d.fell_back);
            self.warm = Some(d.features);
            let normal = if d.distance > 0.0 {
                (d.point_b - d.point_a) / d.distance
            } else {
                Vec2::zeros()
            };
            (d.distance, true, normal)
        };
        Probe {
            t,
            u: 0.0,
            pose_a,
            pose_b,
            eta,
            exact,
            normal,
        }
    }
}
