//! A way that a remedy changed, back to its planned move: an early detour, stay aside,
//! pause or convoy's lap may be needless once later remedies have moved the other robots.
//! The planned move takes the leg where it clears every other robot from the leg on and
//! ends the robot no later, or, `waiting`, after a longer wait at the leg's start that
//! still ends it sooner (`tighten.rs` decides when).

use super::draft::Draft;
use super::Search;
use crate::wcp::legs::Leg;
use crate::wcp::schedule::{Activity, RobotSchedule};

/// Waits tried before a changed way's planned move, in shares of the time the planned move
/// saves: the least that clears is kept, then bisected [`BISECTIONS`] times.
const WAIT_FRACTIONS: [f64; 4] = [0.25, 0.5, 0.75, 0.9];
/// Bisections between the fraction of a wait kept and the one below it.
const BISECTIONS: usize = 3;

impl Search<'_> {
    /// The first leg of robot `r` (in time order) whose way a remedy changed (a detour, a
    /// stay at a parking pose, a pause, a convoy's lap) and that can take its planned move
    /// again: clear of every other robot from the leg on, and ending the robot no later;
    /// `waiting`, also after a longer wait at the leg's start that ends it sooner (the
    /// least of [`WAIT_FRACTIONS`] of the time saved that clears, bisected). With the leg's
    /// time before and after, the new leg and the robot's new plan.
    pub(super) fn straighten(
        &self,
        draft: &Draft,
        r: usize,
        waiting: bool,
    ) -> Option<(usize, f64, f64, Leg, RobotSchedule)> {
        let (legs, robots) = (draft.legs, draft.robots);
        let old = &robots[r];
        legs[r].iter().enumerate().find_map(|(m, leg)| {
            leg.pieces.as_ref()?;
            let (t0, before) = leg_span(old, m)?;
            let planned = |extra: f64| Leg {
                pieces: None,
                wait: leg.wait + extra,
            };
            let build = |extra: f64| self.rebuilt(draft, r, m, planned(extra));
            // The plan `s` if it ends the robot no later and clears every other robot.
            let cleared = |s: RobotSchedule| -> Option<RobotSchedule> {
                (s.end <= old.end && self.clears_all(draft, r, &s, t0)).then_some(s)
            };
            let attempt = |extra: f64| cleared(build(extra)?);
            let plain = build(0.0)?;
            // What the planned move saves: the longest wait that still ends the robot sooner,
            // less a share, so that the robot gains.
            let saved = old.end - plain.end;
            let (extra, s) = match cleared(plain) {
                Some(s) => (0.0, s),
                None if waiting => {
                    if saved <= 0.0 {
                        return None;
                    }
                    let (k, mut kept) = (WAIT_FRACTIONS.iter().enumerate())
                        .find_map(|(k, f)| Some((k, attempt(f * saved)?)))?;
                    let mut below = k.checked_sub(1).map_or(0.0, |j| WAIT_FRACTIONS[j] * saved);
                    let mut wait = WAIT_FRACTIONS[k] * saved;
                    for _ in 0..BISECTIONS {
                        let mid = 0.5 * (below + wait);
                        match attempt(mid) {
                            Some(s) => (wait, kept) = (mid, s),
                            None => below = mid,
                        }
                    }
                    (wait, kept)
                }
                None => return None,
            };
            let (_, after) = leg_span(&s, m)?;
            Some((m, before, after, planned(extra), s))
        })
    }
}

/// When leg `m` of a robot's plan starts, and how long it takes to where it leads (its
/// wait, way and stops; not the task there).
fn leg_span(s: &RobotSchedule, m: usize) -> Option<(f64, f64)> {
    let mut of_leg = (s.segments.iter())
        .filter(|g| g.leg == Some(m) && !matches!(g.activity, Activity::Work(_)));
    let first = of_leg.next()?;
    let end = of_leg.next_back().map_or(first.end, |g| g.end);
    Some((first.start, end - first.start))
}
