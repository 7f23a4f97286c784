//! The remedies that change where an arm goes, in joint space: a pause at a configuration
//! on its way, a detour re-planned in the joints around the other robot, a step aside to a
//! retracted configuration and back. Every new move is certified clear of the fixtures by
//! the checker (as the move store certifies an arm's moves), then judged against the other
//! robot by [`least_clearing`] or [`clears`], as the rigid remedies are.

use super::context::{
    apart, by_parking, child, detoured, earliest, horizons, least_clearing, leg_nodes, leg_window,
    occupancy, paused, pieces_of, Child, Ctx, Side, View,
};
use super::pause::piece_index;
use super::step_aside::aside_leg;
use crate::cell::ArmRobot;
use crate::collision::Body;
use crate::geometry::ConvexPolygon;
use crate::motion::tool_pose;
use crate::planning::{ArmModel, JointMove, JointPathSettings, PlannedMove};
use crate::wcp::feedback::{Remedy, RemedyKind};
use crate::wcp::legs::{leg, Piece};
use crate::wcp::legs_json::rests;
use crate::wcp::schedule::{joints_at, Activity};
use std::sync::Arc;

/// Where an arm pauses on its way: at these shares of the time it took from the piece's
/// start to the contact (the latest first).
const PAUSE_SHARES: [f64; 3] = [0.75, 0.5, 0.25];
/// Half-width of the short detour window about the contact, as a share of the arm's
/// motion under way there.
const DETOUR_SHARE: f64 = 0.25;
/// Random samples of a detour's or a step aside's joint-space search, at most: a remedy is
/// one of many children, and a hard one is left to the others.
const REMEDY_SAMPLES: usize = 400;
/// Shoulder turns of a retracted configuration (radians, either way), nearest first.
const SHOULDER_TURNS: [f64; 6] = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5];
/// How far a retracted configuration folds each joint after the shoulder (radians, either
/// way, within its limits).
const FOLD: f64 = 2.5;
/// Retracted configurations examined in full (planned, timed, checked) per remedy, nearest
/// first.
const PARK_TRIES: usize = 3;

fn model<'a>(ctx: &Ctx<'a>, x: usize) -> Option<(ArmModel, &'a ArmRobot)> {
    let arm = ctx.cell.robots[x].as_arm()?;
    Some((ArmModel::new(&ctx.cell.robots[x].name, arm), arm))
}

fn settings(ctx: &Ctx) -> JointPathSettings {
    JointPathSettings {
        max_samples: REMEDY_SAMPLES,
        samples_per_phase: ctx.opts.planner.samples_per_phase,
        ..JointPathSettings::default()
    }
}

/// The move through `waypoints`, when the checker certifies it clear of the fixtures.
fn certified(ctx: &Ctx, model: &ArmModel, waypoints: &[Vec<f64>]) -> Option<Arc<PlannedMove>> {
    let m: JointMove = model.through(waypoints, ctx.opts.planner.samples_per_phase);
    let clear = model.move_is_clear(&m, ctx.moves.obstacles(), ctx.cell.delta);
    clear.then(|| Arc::new(model.planned(&m)))
}

/// Stop at a configuration on the way, short of the contact, wait there, go on.
pub(super) fn pause(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let m = side.sx.leg?;
    if !matches!(side.sx.activity, Activity::Move { .. }) {
        return None;
    }
    let (model, _) = model(ctx, side.x)?;
    let pieces = pieces_of(ctx, view, side.x, m)?;
    let k = piece_index(view, side.x, m, &side.sx)?;
    let Piece::Go { motion, scale } = pieces.get(k)?.clone() else {
        return None;
    };
    let joints = &motion.joints;
    let tau = ((side.t - side.sx.start) / scale).clamp(0.0, motion.duration);
    // The waypoints where the arm rests, with their times.
    let last = joints.len() - 1;
    let rest_times: Vec<(f64, &[f64])> = (joints.iter().enumerate())
        .filter(|&(i, s)| i == 0 || i == last || s.qd.iter().all(|&v| v == 0.0))
        .map(|(_, s)| (s.t, &s.q[..]))
        .collect();
    let old = leg(view.legs, side.x, m).clone();
    let t0 = leg_window(&view.robots[side.x], m).0;
    let horizons = horizons(view, side.y, &side.sy, t0);
    let apart_in_time = 1e-9 * motion.duration;
    let tried = PAUSE_SHARES.iter().filter_map(|share| {
        let at = tau * share;
        if at <= apart_in_time {
            return None;
        }
        let stop = joints_at(joints, at);
        let before: Vec<Vec<f64>> = (rest_times.iter())
            .filter(|(t, _)| *t < at - apart_in_time)
            .map(|(_, q)| q.to_vec())
            .chain([stop.clone()])
            .collect();
        let after: Vec<Vec<f64>> = [stop.clone()]
            .into_iter()
            .chain(
                (rest_times.iter())
                    .filter(|(t, _)| *t > at + apart_in_time)
                    .map(|(_, q)| q.to_vec()),
            )
            .collect();
        let (first, second) = (
            certified(ctx, &model, &before)?,
            certified(ctx, &model, &after)?,
        );
        let make = |d: f64| Some(paused(&old, &pieces, k, (&first, &second, scale), d));
        let (d, new, s) = least_clearing(ctx, view, side, (m, t0), &horizons, make)?;
        let tool = first.samples.last()?.pos;
        Some((s.end, (d, tool, new, s)))
    });
    // On ties the stop nearest the contact (tried first).
    let (d, at, new, s) = earliest(tried)?;
    let kind = RemedyKind::Pause { at, duration: d };
    let remedy = Remedy::on(side.x, m, leg_nodes(view, side.x, m), kind);
    Some(child(view, side.x, m, new, s, remedy))
}

/// The fixtures, and `region` as obstacles.
fn with_region(ctx: &Ctx, region: &[ConvexPolygon]) -> Vec<Body> {
    let mut out = ctx.moves.obstacles().to_vec();
    out.extend(region.iter().map(|p| Body::obstacle("other robot", p)));
    out
}

/// Re-plan the leg in joint space around the other robot: what it sweeps while both move
/// (or where it stands), and, when it moves, only what it sweeps about the contact.
pub(super) fn detour(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let m = side.sx.leg?;
    if !matches!(side.sx.activity, Activity::Move { .. }) {
        return None;
    }
    let (model, arm) = model(ctx, side.x)?;
    let (t0, t1) = leg_window(&view.robots[side.x], m);
    let mut windows = vec![match side.sy.activity {
        Activity::Move { .. } => (side.sy.start.max(t0), side.sy.end.min(t1)),
        _ => (t0, t1),
    }];
    if matches!(side.sy.activity, Activity::Move { .. }) {
        let tau = DETOUR_SHARE * (side.sx.end - side.sx.start);
        let (w0, w1) = windows[0];
        let near = ((side.t - tau).max(w0), (side.t + tau).min(w1));
        if near != windows[0] {
            windows.push(near);
        }
    }
    let (from, to) = leg_nodes(view, side.x, m);
    let joints = |n| ctx.moves.assignment().joints(ctx.cell, side.x, n);
    let (qa, qb) = (joints(from)?, joints(to)?);
    let current = pieces_of(ctx, view, side.x, m)?;
    let tried = windows.into_iter().filter_map(|(w0, w1)| {
        let region = occupancy(ctx, view, side.y, w0, w1.max(w0));
        // Where the other robot covers either end, no way round it.
        let margin = ctx.cell.delta;
        if !apart(&arm.placed(qa), &region, margin) || !apart(&arm.placed(qb), &region, margin) {
            return None;
        }
        let obstacles = with_region(ctx, &region);
        let path = model.joint_path(qa, qb, &obstacles, ctx.cell.delta, &settings(ctx))?;
        if matches!(current.as_slice(), [Piece::Go { motion, .. }] if rests(&motion.joints) == path.waypoints)
        {
            return None;
        }
        let motion = Arc::new(model.planned(&path.motion));
        let (new, s) = detoured(ctx, view, side, (m, t0), &motion)?.ok()?;
        Some((s.end, (motion, new, s)))
    });
    // On ties the first window tried.
    let (motion, new, s) = earliest(tried)?;
    let kind = RemedyKind::Detour {
        around: side.y,
        path: motion.path.clone(),
    };
    let remedy = Remedy::on(side.x, m, (from, to), kind);
    Some(child(view, side.x, m, new, s, remedy))
}

/// Configurations near `q` with the arm drawn in: the shoulder turned either way by each of
/// [`SHOULDER_TURNS`], every later joint as it is or folded either way by [`FOLD`]; within
/// the joint limits, nearest first (largest joint change, then order made).
fn retracted(arm: &ArmRobot, q: &[f64]) -> Vec<Vec<f64>> {
    let within =
        |j: usize, a: f64| arm.limits.range[j].is_none_or(|[lo, hi]| (lo..=hi).contains(&a));
    let mut out: Vec<Vec<f64>> = vec![Vec::new()];
    for (j, &a) in q.iter().enumerate() {
        let options: Vec<f64> = if j == 0 {
            (SHOULDER_TURNS.iter())
                .flat_map(|&d| [a + d, a - d])
                .collect()
        } else {
            vec![a, FOLD, -FOLD]
        };
        let mut options: Vec<f64> = options.into_iter().filter(|&b| within(j, b)).collect();
        options.dedup();
        out = (out.iter())
            .flat_map(|p| {
                options.iter().map(move |&b| {
                    let mut p = p.clone();
                    p.push(b);
                    p
                })
            })
            .collect();
    }
    let change = |p: &[f64]| (p.iter().zip(q)).fold(0.0, |m: f64, (a, b)| m.max((a - b).abs()));
    out.retain(|p| change(p) > 0.0);
    out.sort_by(|a, b| change(a).total_cmp(&change(b)));
    out
}

/// An arm in the other's way draws in: it moves to a retracted configuration clear of where
/// the other passes, waits there, and goes on to where its leg leads (or back home). Both
/// moves are straight in joint space (a retracted configuration is near): one that a
/// fixture blocks is passed over for the next, not planned around.
pub(super) fn step_aside(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let (t, x) = (side.t, side.x);
    let (model, arm) = model(ctx, x)?;
    let m = aside_leg(view, side)?;
    let (from, to) = leg_nodes(view, x, m);
    let xs = &view.robots[x];
    let joints = |n| ctx.moves.assignment().joints(ctx.cell, x, n);
    let (qa, qb) = (joints(from)?, joints(to)?);
    let q = match side.sx.activity {
        Activity::Move { .. } => qa.to_vec(),
        _ => xs.q_at(t),
    };
    let t0 = if view.routes[x].is_empty() {
        0.0
    } else {
        leg_window(xs, m).0
    };
    let horizons = horizons(view, side.y, &side.sy, t0);
    let until = t0 + horizons.last().copied().unwrap_or(0.0);
    let region = occupancy(ctx, view, side.y, t.min(t0.max(0.0)), until);
    let fixtures: Vec<ConvexPolygon> = (ctx.cell.obstacles.iter())
        .flat_map(|o| o.pieces().iter().cloned())
        .collect();
    let margin = 2.0 * ctx.cell.delta;
    let old = leg(view.legs, x, m).clone();
    let keep_wait = matches!(side.sx.activity, Activity::Done);
    let tried = retracted(arm, &q)
        .into_iter()
        .filter(|p| {
            let placed = arm.placed(p);
            apart(&placed, &region, margin) && apart(&placed, &fixtures, margin)
        })
        .filter_map(|p| {
            let there = certified(ctx, &model, &[qa.to_vec(), p.clone()])?;
            let back = certified(ctx, &model, &[p.clone(), qb.to_vec()])?;
            Some((p, there, back))
        })
        .take(PARK_TRIES)
        .filter_map(|(p, there, back)| {
            let wait = if keep_wait { old.wait } else { 0.0 };
            let make = |d: f64| Some(by_parking(wait, (&there, &back), d));
            let (d, new, s) = least_clearing(ctx, view, side, (m, t0), &horizons, make)?;
            Some((s.end, (p, d, new, s)))
        });
    let (p, d, new, s) = earliest(tried)?;
    let park = tool_pose(arm.base, &arm.lengths(), &p);
    let kind = RemedyKind::StepAside { park, duration: d };
    let remedy = Remedy::on(x, m, (from, to), kind);
    Some(child(view, x, m, new, s, remedy))
}

#[cfg(test)]
mod tests {
    use super::super::context::TestCell;
    use super::*;
    use crate::collision::check;
    use crate::wcp::schedule::Schedule;

    /// Arm A turns its shoulder half a turn to its task; arm B, idle at home, reaches down
    /// into the half disc A's outstretched arm sweeps, not into what A sweeps folded.
    const CROSSING: &str = include_str!("../../../../tests/cells/arm-crossing.json");

    /// The crossing's first collision, as the side where `x` yields.
    fn side(test: &TestCell, x: usize) -> Side {
        let view = test.view();
        let schedule = Schedule::of(view.robots.to_vec());
        let report = check(&schedule.scene(&test.cell), &Default::default());
        let c = schedule
            .collision(&test.cell, &report)
            .expect("B in A's way");
        let (sa, sb) = (c.segments.0, c.segments.1.expect("two robots"));
        let (sx, sy) = if c.robots.0 == x { (sa, sb) } else { (sb, sa) };
        Side {
            x,
            y: 1 - x,
            sx,
            sy,
            t: c.time,
        }
    }

    /// Whether the schedule with `child` is certified free of collisions until A has done
    /// its task (on its way home it crosses B again: the next round's business).
    fn clear_until_done(test: &TestCell, child: &Child) -> bool {
        let mut robots = test.view().robots.to_vec();
        for (r, s) in &child.changed {
            robots[*r] = s.clone();
        }
        let done = leg_window(&robots[0], 0).1;
        let schedule = Schedule::of(robots);
        let report = check(&schedule.scene(&test.cell), &Default::default());
        let first = schedule.collision(&test.cell, &report).map(|c| c.time);
        report.verdict().is_certified_free() || first.is_some_and(|t| t >= done)
    }

    #[test]
    fn an_arm_detours_in_joint_space_around_an_arm_in_its_way() {
        let test = TestCell::new(CROSSING, vec![vec![0], vec![]]);
        let (ctx, view) = (test.ctx(), test.view());
        let child = detour(&ctx, &view, &side(&test, 0)).expect("a way round");
        assert!(matches!(
            child.remedy.kind,
            RemedyKind::Detour { around: 1, .. }
        ));
        assert!(clear_until_done(&test, &child));
        // Round B, not straight: the elbow folds on the way, at rest at each waypoint.
        let Some(pieces) = &crate::wcp::legs::leg(&child.legs, 0, 0).pieces else {
            panic!("a changed leg")
        };
        let [Piece::Go { motion, .. }] = &pieces[..] else {
            panic!("one motion")
        };
        assert!(rests(&motion.joints).len() > 2);
    }

    #[test]
    fn an_idle_arm_draws_in_while_the_other_passes() {
        let test = TestCell::new(CROSSING, vec![vec![0], vec![]]);
        let (ctx, view) = (test.ctx(), test.view());
        let child = step_aside(&ctx, &view, &side(&test, 1)).expect("room to draw in");
        assert!(matches!(child.remedy.kind, RemedyKind::StepAside { .. }));
        assert!(clear_until_done(&test, &child));
        // Home again at the end, having moved.
        let b = &child.changed[0].1;
        let home = &test.cell.robots[1].as_arm().unwrap().home;
        assert_eq!(&b.joints.last().unwrap().q, home);
        assert!(b.joints.iter().any(|s| (s.q[0] - home[0]).abs() > 0.4));
    }

    #[test]
    fn retracted_configurations_keep_the_limits_nearest_first() {
        let cell = crate::cell::parse_cell(CROSSING, "t.json".as_ref())
            .unwrap()
            .cell;
        let a = cell.robots[0].as_arm().unwrap();
        let q = [3.0, 0.2];
        let out = retracted(a, &q);
        let change =
            |p: &[f64]| (p.iter().zip(&q)).fold(0.0, |m: f64, (a, b)| m.max((a - b).abs()));
        assert!(!out.is_empty() && out.iter().all(|p| change(p) > 0.0));
        assert!(out.windows(2).all(|w| change(&w[0]) <= change(&w[1])));
        for p in &out {
            assert!(p[0] >= -0.5 && p[0] <= 3.6 && p[1].abs() <= 2.8, "{p:?}");
        }
        // Folded both ways, and the shoulder turned both ways within its limits.
        assert!(out.iter().any(|p| p[1] == FOLD) && out.iter().any(|p| p[1] == -FOLD));
        assert!(out.iter().any(|p| p[0] == 3.5) && out.iter().any(|p| p[0] == 2.5));
        assert!(!out.iter().any(|p| p[0] > 3.6));
    }
}
