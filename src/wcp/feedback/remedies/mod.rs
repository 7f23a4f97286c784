//! The ways out of one collision: for each of the two robots, the changes to one of its
//! legs that separate it from the other robot, each the least of its kind that does.
//!
//! * **wait**: wait longer at the start node of the leg (the robot reaches the place later);
//! * **pause**: stop at a point of the path short of the place of contact, wait there, go
//!   on (the move is cut there into two rest-to-rest moves);
//! * **slow**: run the leg's motions slower (time scaling keeps every limit);
//! * **detour**: re-plan the leg with the other robot as an obstacle: its pose if it
//!   stands, the region it sweeps during the conflict if it moves (as a last resort, up to
//!   the contact only: the way round the other side of a loop);
//! * **step aside**: a robot standing in the other's way (waiting at a node, or home for
//!   good) goes to a free parking pose nearby, waits there and goes on (or back home); a
//!   robot on its way leaves its start node for a parking pose near it instead, and lets
//!   the other pass;
//! * **pass aside**: a robot on its way pulls in at a passing place beside it, short of
//!   the contact (a bay off a corridor), holds there the least that lets the other pass,
//!   and goes on; offered only in the search's second pass (`search/pending.rs`);
//! * **make way**, of both robots at once: the one standing in the other's way (at work, or
//!   waiting at a node) leaves ahead of it, round where it comes from, and the other waits
//!   (a last resort, like the detour's);
//! * **tune**, of both robots at once, for a pair that collided before on the search's
//!   branch: both keep their paths, and their coordination diagram says where each holds
//!   and how long (a last resort too);
//! * **convoy**, of every robot of a closed corridor at once, for a pair that collided
//!   before or that nothing else separates: all go round it together, the same way (a last
//!   resort).
//!
//! Every candidate is judged by [`clears`] on the window of the changed leg; the search
//! decides among the survivors by makespan. Motions are planned by the planner and
//! certified clear of the fixtures by the checker, so the limits and the clearance hold.

use super::{Remedy, RemedyKind};
use crate::wcp::legs::{leg, Leg};
use crate::wcp::schedule::{Activity, Collision};
use rayon::prelude::*;

mod arm;
mod context;
mod convoy;
mod coordination;
mod detour;
mod lanes;
mod make_way;
mod pause;
mod step_aside;
mod tune;

use context::{child, horizons, least_clearing, leg_nodes, leg_window, Side};
pub(super) use context::{Child, Ctx, View};

use convoy::convoy;
use detour::detour;
use lanes::lanes;
use make_way::make_way;
use pause::{pause, slow};
use step_aside::{pass_aside, step_aside};
use tune::tune;

/// The candidates for collision `c`: for each robot of the pair, each remedy allowed that
/// separates it from the other, in a fixed order (first robot first; wait, pause, slow,
/// detour, step aside, make way, pass aside), then the two tuned together. Evaluated in
/// parallel, collected in that order.
pub(super) fn candidates(ctx: &Ctx, view: &View, c: &Collision, again: bool) -> Vec<Child> {
    let (Some(b), Some(sb)) = (c.robots.1, c.segments.1) else {
        return Vec::new();
    };
    let a = c.robots.0;
    let sa = c.segments.0;
    let set = ctx.opts.search.remedies;
    type Job = fn(&Ctx, &View, &Side) -> Option<Child>;
    // An arm pauses, detours and steps aside in joint space.
    let kinds = |x: usize| -> [(bool, Job); 7] {
        let arm = ctx.cell.robots[x].as_arm().is_some();
        [
            (set.wait, wait),
            (set.pause, if arm { arm::pause } else { pause }),
            (set.slow, slow),
            (set.detour, if arm { arm::detour } else { detour }),
            (
                set.step_aside,
                if arm { arm::step_aside } else { step_aside },
            ),
            // Two robots at once: a detour of the one that leaves, a wait of the other.
            (set.detour, make_way),
            (set.pass_aside && ctx.passing && !arm, pass_aside),
        ]
    };
    let t = c.time;
    let sides = [
        Side {
            x: a,
            y: b,
            sx: sa,
            sy: sb,
            t,
        },
        Side {
            x: b,
            y: a,
            sx: sb,
            sy: sa,
            t,
        },
    ];
    let mut jobs: Vec<(&Side, Job)> = sides
        .iter()
        .flat_map(|side| {
            (kinds(side.x).into_iter())
                .filter(|k| k.0)
                .map(move |k| (side, k.1))
        })
        .collect();
    // Both robots at once, each keeping to its side of the line they meet along: like
    // passing places, in the second pass only.
    if set.lanes && ctx.passing {
        jobs.push((&sides[0], lanes));
    }
    // Both robots at once, in one diagram, once per collision: for a pair that met before
    // on the branch, whose single changes did not keep it apart.
    if set.tune && again {
        jobs.push((&sides[0], tune));
    }
    let mut children: Vec<Child> = jobs
        .par_iter()
        .map(|(side, job)| job(ctx, view, side))
        .collect::<Vec<_>>()
        .into_iter()
        .flatten()
        .collect();
    // Every robot of a loop at once: for a pair that met before, or that nothing else
    // separates (robots on a ring corridor that cannot pass each other).
    if set.convoy && (again || children.is_empty()) {
        children.extend(
            sides
                .iter()
                .find_map(|side| convoy(ctx, view, side))
                .into_iter()
                .flatten(),
        );
    }
    children
}

/// Wait longer at the leg's start node.
fn wait(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let m = side.sx.leg?;
    if matches!(side.sx.activity, Activity::Wait(_) | Activity::Done) {
        // Standing where it is hit: waiting longer keeps it there.
        return None;
    }
    let old = leg(view.legs, side.x, m).clone();
    let t0 = leg_window(&view.robots[side.x], m).0;
    let horizons = horizons(view, side.y, &side.sy, t0);
    let (d, new, s) = least_clearing(ctx, view, side, (m, t0), &horizons, |d| {
        Some(Leg {
            wait: old.wait + d,
            ..old.clone()
        })
    })?;
    let nodes = leg_nodes(view, side.x, m);
    let remedy = Remedy::on(side.x, m, nodes, RemedyKind::Wait { duration: d });
    Some(child(view, side.x, m, new, s, remedy))
}

#[cfg(test)]
mod tests {
    use super::context::TestCell;
    use super::*;
    use crate::collision::check;
    use crate::wcp::schedule::Schedule;

    /// Two robots of side 0.7 crossing in the open, X (to a task of 4 s) and Y (1 s) at the
    /// crossing together, with a pillar beside it: every single remedy finds something.
    const CROSSING: &str = r#"{"delta": 0.01, "robots": [
        {"name": "X", "shape": [[-0.35, -0.35], [0.35, -0.35], [0.35, 0.35], [-0.35, 0.35]],
         "home": [-5, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1},
        {"name": "Y", "shape": [[-0.35, -0.35], [0.35, -0.35], [0.35, 0.35], [-0.35, 0.35]],
         "home": [0, -5], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1}],
        "obstacles": [{"name": "pillar", "shape": [[1.5, 1.5], [2.5, 1.5], [2.5, 2.5], [1.5, 2.5]]}],
        "tasks": [{"name": "x", "at": [5, 0], "duration": 4, "robots": ["X"]},
                  {"name": "y", "at": [0, 5], "duration": 1, "robots": ["Y"]}]}"#;

    /// Each child's remedy and the latest end of the robots it changes.
    fn ends(children: &[Child]) -> Vec<(Remedy, f64)> {
        (children.iter())
            .map(|c| {
                let end = c.changed.iter().map(|(_, s)| s.end).fold(0.0, f64::max);
                (c.remedy.clone(), end)
            })
            .collect()
    }

    /// A cap drops only children the search would drop: capped, the candidates that end
    /// before the cap are the uncapped ones that do, each the same, and fewer are made;
    /// the two robots tuned together (a pair met again) included.
    #[test]
    fn a_cap_drops_only_the_children_that_end_at_or_after_it() {
        let test = TestCell::new(CROSSING, vec![vec![0], vec![1]]);
        let view = test.view();
        let schedule = Schedule::of(view.robots.to_vec());
        let report = check(&schedule.scene(&test.cell), &Default::default());
        let c = schedule.collision(&test.cell, &report).expect("they cross");
        for again in [false, true] {
            capped_as_uncapped(&test, &c, again);
        }
    }

    fn capped_as_uncapped(test: &TestCell, c: &Collision, again: bool) {
        let view = test.view();
        let all = ends(&candidates(&test.ctx(), &view, c, again));
        assert!(all.len() >= 6, "{all:?}");
        let tuned = |a: &&(Remedy, f64)| matches!(a.0.kind, RemedyKind::Tune { .. });
        assert_eq!(all.iter().filter(tuned).count(), again as usize, "{all:?}");
        let mut cuts: Vec<f64> = all.iter().map(|a| a.1).collect();
        cuts.sort_by(f64::total_cmp);
        // At a child's own end (dropped: not sooner), and between two ends; at and just
        // past the tuned child's (its diagram's grid ends a step later than its legs).
        let mut caps = vec![cuts[cuts.len() / 2], 0.5 * (cuts[1] + cuts[2])];
        if let Some(t) = all.iter().find(tuned) {
            caps.extend([t.1, t.1 + 1e-6]);
        }
        for cap in caps {
            let capped = ends(&candidates(&test.ctx().capped(cap), &view, c, again));
            let before = |v: &[(Remedy, f64)]| -> Vec<_> {
                v.iter().filter(|a| a.1 < cap).cloned().collect()
            };
            let kept = before(&all);
            assert!(!kept.is_empty() && capped.len() < all.len(), "cap {cap}");
            assert_eq!(before(&capped), kept, "cap {cap}");
            // What ends later is made as before, by a remedy that stopped refining it; no
            // detour that ends later is made (its check is spared).
            assert!(capped.iter().all(|a| all.contains(a)), "cap {cap}");
            let detour = |a: &&(Remedy, f64)| matches!(a.0.kind, RemedyKind::Detour { .. });
            assert!(capped.iter().filter(detour).all(|a| a.1 < cap), "cap {cap}");
            assert!(all.iter().filter(detour).any(|a| a.1 >= cap), "cap {cap}");
        }
    }
}
