//! A schedule being shortened (`tighten.rs`), and what its two ways of shortening
//! (`straighten.rs`, `shorten.rs`) ask of it: a robot's plan with one leg changed, and
//! whether that plan clears every other robot.

use super::Search;
use crate::wcp::feedback::clearing::clears;
use crate::wcp::legs::{with_leg, Leg, Legs};
use crate::wcp::schedule::RobotSchedule;
use std::sync::Arc;

/// A schedule being shortened: node `id`'s routes, with the legs and plans shortened so far.
pub(super) struct Draft<'d> {
    pub(super) id: usize,
    pub(super) routes: &'d [Vec<usize>],
    pub(super) legs: &'d Legs,
    pub(super) robots: &'d [Arc<RobotSchedule>],
}

impl Search<'_> {
    /// Robot `r`'s plan in `draft` with its leg `m` replaced by `leg`; `None` if it cannot
    /// be timed.
    pub(super) fn rebuilt(
        &self,
        draft: &Draft,
        r: usize,
        m: usize,
        leg: Leg,
    ) -> Option<RobotSchedule> {
        let moves = &self.prepared_of(draft.id).moves;
        let changed = with_leg(draft.legs, r, m, leg);
        RobotSchedule::build(self.cell, r, &draft.routes[r], &changed[r], moves).ok()
    }

    /// Whether the checker proves robot `r`, on plan `s`, clear of every other robot of
    /// `draft` from `t0` on (to the later of the two ends).
    pub(super) fn clears_all(&self, draft: &Draft, r: usize, s: &RobotSchedule, t0: f64) -> bool {
        let robots = draft.robots;
        (0..robots.len()).filter(|&y| y != r).all(|y| {
            let t1 = s.end.max(robots[y].end);
            clears(
                self.cell,
                (r, s),
                (y, &robots[y]),
                (t0, t1),
                &self.opts.check,
            )
        })
    }
}
