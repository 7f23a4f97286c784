//! Running ahead of the probes on a pair with a link of an arm: the merged intervals after
//! the last probe are proven free by its η and the motion bound summed over them, and only
//! where the sum reaches η − δ is the next probe made. Far from each other, two arms then
//! cost a few sums per interval instead of the kinematics of both links and an η.
//!
//! For every τ after the probe at t, d(τ) ≥ η(t) − λ(t, τ): the first-order bound of
//! Schwarzer, Saha & Latombe, one-sided, with λ summed over the intervals in between.

use super::eta::Eta;
use super::grid::MergedGrid;
use super::span::{LinkEnds, PairSettings, Probe, Stop};
use super::{Body, Stats};
use crate::motion::{lambda, BoundKind, Motion};

/// Where a pair has run ahead of its last probe.
#[derive(Clone, Copy, Default)]
pub(super) struct RunAhead {
    ahead: Option<Ahead>,
}

#[derive(Clone, Copy)]
struct Ahead {
    /// The end of the proven prefix, a time of the merged grid.
    t: f64,
    /// The samples of each body at or before `t`.
    afters: (usize, usize),
    /// λ1 + λ2 summed from the last probe to `t`.
    used: f64,
}

impl RunAhead {
    /// The end of the proven prefix, given the last probe.
    pub fn from(&self, probe: &Probe) -> f64 {
        self.ahead.map_or(probe.t, |a| a.t)
    }

    /// The merged interval ending at `t` that starts after `afters` samples of each body, its
    /// work counted already: `Ok(true)` when proven from `probe` by the motion bound, else
    /// `Ok(false)` with `probe` moved to its start, to search it. Stopped when the work budget
    /// ran out at its start, or when the probe moved there is closer than δ (only rounding
    /// of the bound's sum can do that; a witness all the same).
    pub fn step(
        &mut self,
        eta: &mut Eta,
        grid: &MergedGrid,
        probe: &mut Probe,
        (afters, t): ((usize, usize), f64),
        s: &PairSettings,
        stats: &mut Stats,
    ) -> Result<bool, Stop> {
        let from = self.from(probe);
        if s.out_of_work(stats) {
            return Err(Stop::OutOfWork(from));
        }
        let used = self.ahead.map_or(0.0, |a| a.used) + bound_over(eta, grid, afters, from, t);
        if probe.eta - used >= s.delta {
            let afters = grid.afters();
            self.ahead = Some(Ahead { t, afters, used });
            return Ok(true);
        }
        if let Some(a) = self.ahead.take() {
            *probe = eta.at(a.t, grid.poses_with(a.afters, a.t), stats);
            if probe.eta < s.delta {
                return Err(Stop::Contact(*probe, a.t));
            }
        }
        Ok(false)
    }
}

/// λ1 + λ2 over the merged interval `[t0, t1]`, which starts after `afters` samples of each
/// body: a link's from its joints, without its kinematics; a rigid body's from its poses.
fn bound_over(eta: &Eta, grid: &MergedGrid, afters: (usize, usize), t0: f64, t1: f64) -> f64 {
    let ends = grid.afters();
    let one = |body: &Body, b: bool, after: usize, end: usize| match &body.motion {
        Motion::Link(l) => LinkEnds::new(l, after, t0, t1).lambda,
        Motion::Fixed(_) => 0.0,
        motion @ Motion::Sampled(_) => {
            let (p, q) = (grid.pose_of(b, after, t0), grid.pose_of(b, end, t1));
            let radius = body.shape.radius();
            lambda(BoundKind::Rigorous, motion, radius, (t0, &p), (t1, &q))
        }
    };
    one(eta.a, false, afters.0, ends.0) + one(eta.b, true, afters.1, ends.1)
}
