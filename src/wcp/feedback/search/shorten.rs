//! A certified schedule's slack shortened, one robot's at a time (`tighten.rs` decides the
//! order): its first wait, hold or slowed motion in time order that can be cut is cut to
//! the least of [`FRACTIONS`] of it that clears, then bisected.

use super::draft::Draft;
use super::Search;
use crate::wcp::feedback::outcome::Shortening;
use crate::wcp::legs::{HoldReason, Leg, Legs, Piece};
use crate::wcp::schedule::RobotSchedule;
use rayon::prelude::*;

/// Fractions of a slack tried first, together: the least one that clears is kept.
const FRACTIONS: [f64; 6] = [0.0, 0.25, 0.5, 0.75, 0.9, 0.97];
/// Bisections between the fraction kept and the one below it.
const BISECTIONS: usize = 3;

/// Slack in a robot's legs: the wait at the start of leg `leg`, or its piece `piece` (a
/// hold, or a motion run slower than planned).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Slack {
    pub(super) leg: usize,
    pub(super) piece: Option<usize>,
}

impl Search<'_> {
    /// The first slack of robot `r` (in time order) that can be shortened, with its
    /// [`excess`] before and after and the robot's new plan.
    pub(super) fn shorten(
        &self,
        draft: &Draft,
        r: usize,
    ) -> Option<(Slack, f64, f64, RobotSchedule)> {
        let (legs, robots) = (draft.legs, draft.robots);
        for slack in slacks(legs, r) {
            let before = excess(legs, r, slack);
            // When the leg starts: its first segment (its wait, or its first piece).
            let Some(t0) = robots[r]
                .segments
                .iter()
                .find(|g| g.leg == Some(slack.leg))
                .map(|g| g.start)
            else {
                continue;
            };
            let attempt = |d: f64| -> Option<RobotSchedule> {
                let s = self.rebuilt(draft, r, slack.leg, with_excess(legs, r, slack, d))?;
                self.clears_all(draft, r, &s, t0).then_some(s)
            };
            let tries: Vec<Option<RobotSchedule>> =
                FRACTIONS.par_iter().map(|f| attempt(f * before)).collect();
            let Some(k) = tries.iter().position(Option::is_some) else {
                continue;
            };
            let Some(s) = tries.into_iter().nth(k).flatten() else {
                continue;
            };
            let mut best = (FRACTIONS[k] * before, s);
            let mut below = match k {
                0 => None,
                _ => Some(FRACTIONS[k - 1] * before),
            };
            for _ in 0..BISECTIONS {
                let Some(lo) = below else { break };
                let mid = 0.5 * (lo + best.0);
                match attempt(mid) {
                    Some(s) => best = (mid, s),
                    None => below = Some(mid),
                }
            }
            return Some((slack, before, best.0, best.1));
        }
        None
    }
}

/// Robot `r`'s slack, in time order: each leg's wait, then its holds and its motions run
/// slower than planned.
pub(super) fn slacks(legs: &Legs, r: usize) -> Vec<Slack> {
    let mut out = Vec::new();
    for (m, leg) in legs[r].iter().enumerate() {
        if leg.wait > 0.0 {
            out.push(Slack {
                leg: m,
                piece: None,
            });
        }
        for (j, p) in leg.pieces.iter().flat_map(|p| p.iter()).enumerate() {
            let slack = match p {
                Piece::Hold { duration, .. } => *duration > 0.0,
                Piece::Go { scale, .. } => *scale > 1.0,
            };
            if slack {
                out.push(Slack {
                    leg: m,
                    piece: Some(j),
                });
            }
        }
    }
    out
}

/// What the slack is.
pub(super) fn kind(legs: &Legs, r: usize, slack: Slack) -> Shortening {
    let Some(j) = slack.piece else {
        return Shortening::Wait;
    };
    match legs[r][slack.leg].pieces.as_ref().map(|p| &p[j]) {
        Some(Piece::Hold {
            reason: HoldReason::Pause,
            ..
        }) => Shortening::Pause,
        Some(Piece::Hold {
            reason: HoldReason::Park,
            ..
        }) => Shortening::Park,
        Some(Piece::Go { .. }) | None => Shortening::Slow,
    }
}

/// How much slack: a wait's or a hold's seconds; a slowed motion's stretch beyond 1.
pub(super) fn excess(legs: &Legs, r: usize, slack: Slack) -> f64 {
    let leg = &legs[r][slack.leg];
    match (slack.piece, leg.pieces.as_deref()) {
        (None, _) | (Some(_), None) => leg.wait,
        (Some(j), Some(pieces)) => match &pieces[j] {
            Piece::Hold { duration, .. } => *duration,
            Piece::Go { scale, .. } => scale - 1.0,
        },
    }
}

/// Robot `r`'s leg with `slack` cut to `e` (an [`excess`]).
pub(super) fn with_excess(legs: &Legs, r: usize, slack: Slack, e: f64) -> Leg {
    let mut leg = legs[r][slack.leg].clone();
    match slack.piece {
        None => leg.wait = e,
        Some(j) => {
            let mut pieces = leg.pieces.as_deref().unwrap_or_default().to_vec();
            match &mut pieces[j] {
                Piece::Hold { duration, .. } => *duration = e,
                Piece::Go { scale, .. } => *scale = 1.0 + e,
            }
            leg.pieces = Some(pieces.into());
        }
    }
    leg
}
