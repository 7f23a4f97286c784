//! Stepping aside: a robot in the other's way goes to a free parking pose nearby (found
//! on rings about where it stands), waits there and goes on.

use super::context::{
    apart, body_radius, by_parking, child, earliest, horizons, least_clearing, leg_nodes,
    leg_window, occupancy, Child, Ctx, Side, View,
};
use crate::collision::Body;
use crate::geometry::{closest_features, Posed, Vec2, WalkTolerances};
use crate::motion::{Motion, Pose};
use crate::wcp::feedback::{Remedy, RemedyKind};
use crate::wcp::legs::leg;
use crate::wcp::moves::node_pose;
use crate::wcp::schedule::Activity;
use std::cell::Cell;

/// Parking rings, in the parking robot's radii, and directions per ring.
const PARK_RINGS: [f64; 5] = [2.0, 3.0, 4.5, 6.5, 9.0];
const PARK_DIRECTIONS: usize = 12;
/// Parking poses examined in full (planned, timed, checked) per remedy, nearest first.
const PARK_TRIES: usize = 3;

/// Poses on rings about `q` where robot `x` is clear of the fixtures and of where robot `y`
/// passes over `[t0, t1]`: the discs a rigid `y` sweeps, the region an arm sweeps.
fn parking_poses(
    ctx: &Ctx,
    view: &View,
    x: usize,
    y: usize,
    q: Pose,
    (t0, t1): (f64, f64),
) -> Vec<Pose> {
    let cell = ctx.cell;
    let rx = cell.rigid(x).shape.radius();
    let ry = body_radius(cell, y);
    let ys = &view.robots[y];
    // An arm's links sweep far from its tool: the region itself.
    let swept = cell.robots[y]
        .as_arm()
        .map(|_| occupancy(ctx, view, y, t0, t1));
    let passes: Vec<Vec2> = ys
        .samples
        .iter()
        .filter(|s| s.t >= t0 && s.t <= t1)
        .map(|s| s.pos)
        .chain([ys.pose_at(t0).pos, ys.pose_at(t1).pos])
        .collect();
    let obstacles: Vec<Body> = ctx.moves.obstacles().to_vec();
    let tol = WalkTolerances::default();
    // Part by part: a robot of parts may park inside a bay its hull would not fit.
    let clear_of_fixtures = |p: Pose| {
        cell.rigid(x).pieces().iter().all(|piece| {
            let posed = Posed::new(piece, p.pos.x, p.pos.y, p.theta);
            obstacles.iter().all(|o| {
                let Motion::Fixed(at) = &o.motion else {
                    return true;
                };
                let pieces = o
                    .parts
                    .as_ref()
                    .map_or(std::slice::from_ref(&o.shape), |p| p.parts());
                pieces.iter().all(|q| {
                    let other = Posed::new(q, at.pos.x, at.pos.y, at.theta);
                    closest_features(&posed, &other, None, &tol).distance > 2.0 * cell.delta
                })
            })
        })
    };
    let mut out = Vec::new();
    for ring in PARK_RINGS {
        for k in 0..PARK_DIRECTIONS {
            let (s, c) = (k as f64 * std::f64::consts::TAU / PARK_DIRECTIONS as f64).sin_cos();
            let p = Pose {
                pos: q.pos + ring * rx * Vec2::new(c, s),
                theta: q.theta,
            };
            let away = match &swept {
                Some(region) => apart(&[(cell.rigid(x).pieces(), p)], region, 2.0 * cell.delta),
                None => (passes.iter()).all(|g| (g - p.pos).norm() > rx + ry + 2.0 * cell.delta),
            };
            if away && clear_of_fixtures(p) {
                out.push(p);
            }
        }
    }
    out
}

/// The leg of `side.x` that a step aside changes, if it can step aside where it is.
pub(super) fn aside_leg(view: &View, side: &Side) -> Option<usize> {
    let route = &view.routes[side.x];
    match side.sx.activity {
        // Waiting at the leg's start node, or already on the way: it leaves that node for
        // the parking pose instead, and lets the other pass.
        Activity::Wait(_) | Activity::Move { .. } => side.sx.leg,
        // Home for good: a robot without tasks makes an excursion from home to home; one
        // with tasks goes home from its last task by way of the parking pose.
        Activity::Done if route.is_empty() => Some(0),
        Activity::Done => Some(route.len()),
        _ => None,
    }
}

/// A robot standing in the other's way goes to a parking pose nearby, waits there, and goes
/// on to where its leg leads (or back home).
pub(super) fn step_aside(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let t = side.t;
    let x = side.x;
    let route = &view.routes[x];
    let m = aside_leg(view, side)?;
    let (from, to) = leg_nodes(view, x, m);
    let xs = &view.robots[x];
    let q = match side.sx.activity {
        Activity::Move { .. } => node_pose(ctx.cell, x, from),
        _ => xs.pose_at(t),
    };
    let t0 = if route.is_empty() {
        0.0
    } else {
        leg_window(xs, m).0
    };
    let horizons = horizons(view, side.y, &side.sy, t0);
    let until = t0 + horizons.last().copied().unwrap_or(0.0);
    let (a, b) = (node_pose(ctx.cell, x, from), node_pose(ctx.cell, x, to));
    let old = leg(view.legs, x, m).clone();
    let keep_wait = matches!(side.sx.activity, Activity::Done);
    let bound = Cell::new(ctx.cap);
    let tried = parking_poses(ctx, view, x, side.y, q, (t.min(t0.max(0.0)), until))
        .into_iter()
        .filter_map(|p| {
            let there = ctx.moves.between(x, a, p, &[])?;
            let back = ctx.moves.between(x, p, b, &[])?;
            Some((p, there, back))
        })
        .take(PARK_TRIES)
        .filter_map(|(p, there, back)| {
            // A farther pose wins only by ending sooner than the best so far.
            let ctx = ctx.capped(bound.get());
            let wait = if keep_wait { old.wait } else { 0.0 };
            let make = |d: f64| Some(by_parking(wait, (&there, &back), d));
            let (d, new, s) = least_clearing(&ctx, view, side, (m, t0), &horizons, make)?;
            bound.set(s.end);
            Some((s.end, (p, d, new, s)))
        });
    let (park, d, new, s) = earliest(tried)?;
    let remedy = Remedy::on(
        x,
        m,
        (from, to),
        RemedyKind::StepAside { park, duration: d },
    );
    Some(child(view, x, m, new, s, remedy))
}

#[cfg(test)]
mod tests {
    use super::super::context::TestCell;
    use super::*;

    /// A parking pose keeps 2δ of clearance from where the other robot passes, as the
    /// checker's δ needs on both sides: a pose only δ beyond the two radii is refused, one
    /// 3δ beyond them taken.
    #[test]
    fn a_parking_pose_keeps_two_deltas_from_the_other_robot() {
        let (delta, half, other) = (0.01, 0.5, 0.2);
        let (rx, ry) = (half * 2f64.sqrt(), other * 2f64.sqrt());
        // The first ring's pose due east of home is at 2 rx.
        let east = Vec2::new(2.0 * rx, 0.0);
        for (gap, taken) in [(delta, false), (3.0 * delta, true)] {
            let y = east.x + rx + ry + gap;
            let text = format!(
                r#"{{"delta": {delta}, "robots": [
                {{"name": "X", "shape": [[-{half}, -{half}], [{half}, -{half}], [{half}, {half}], [-{half}, {half}]],
                  "home": [0, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1}},
                {{"name": "Y", "shape": [[-{other}, -{other}], [{other}, -{other}], [{other}, {other}], [-{other}, {other}]],
                  "home": [{y}, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1}}],
                "obstacles": [],
                "tasks": [{{"name": "t", "at": [-3, 0], "duration": 1}}]}}"#
            );
            let test = TestCell::new(&text, vec![vec![], vec![]]);
            let home = test.cell.rigid(0).home;
            let poses = parking_poses(&test.ctx(), &test.view(), 0, 1, home, (0.0, 1.0));
            let found = poses.iter().any(|p| (p.pos - east).norm() < 1e-9);
            assert_eq!(found, taken, "Y {gap} beyond the radii");
            assert!(
                poses.iter().any(|p| (p.pos + east).norm() < 1e-9),
                "west is free"
            );
        }
    }

    /// A gripper may park with a post between its fingers, where its hull would not fit.
    #[test]
    fn a_robot_of_parts_parks_where_its_parts_fit() {
        let gripper = r#"[[[-0.4, -0.5], [0.0, -0.5], [0.0, 0.5], [-0.4, 0.5]],
                          [[0.0, 0.3], [0.8, 0.3], [0.8, 0.5], [0.0, 0.5]],
                          [[0.0, -0.5], [0.8, -0.5], [0.8, -0.3], [0.0, -0.3]]]"#;
        let radius = (0.8f64).hypot(0.5);
        // On the first ring, due east: the post between the fingers there.
        let x = 2.0 * radius + 0.55;
        let text = format!(
            r#"{{"delta": 0.01, "robots": [
            {{"name": "G", "parts": {gripper}, "home": [0, 0], "max_speed": 1, "max_accel": 2,
              "max_turn_rate": 1}},
            {{"name": "Y", "shape": [[-0.2, -0.2], [0.2, -0.2], [0.2, 0.2], [-0.2, 0.2]],
              "home": [0, 9], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1}}],
            "obstacles": [{{"name": "post", "shape": [[{a}, -0.15], [{b}, -0.15], [{b}, 0.15], [{a}, 0.15]]}}],
            "tasks": [{{"name": "t", "at": [-3, 0], "duration": 1}}]}}"#,
            a = x - 0.15,
            b = x + 0.15,
        );
        let test = TestCell::new(&text, vec![vec![], vec![]]);
        let cell = &test.cell;
        let home = cell.rigid(0).home;
        let poses = parking_poses(&test.ctx(), &test.view(), 0, 1, home, (0.0, 1.0));
        let east = poses
            .iter()
            .find(|p| (p.pos - Vec2::new(2.0 * radius, 0.0)).norm() < 1e-9)
            .expect("the pose with the post between the fingers");
        // Its hull there would overlap the post.
        let hull = Posed::new(&cell.rigid(0).shape, east.pos.x, east.pos.y, east.theta);
        let post = Posed::new(&cell.obstacles[0].shape, 0.0, 0.0, 0.0);
        let d = closest_features(&hull, &post, None, &WalkTolerances::default()).distance;
        assert_eq!(d, 0.0);
    }
}
