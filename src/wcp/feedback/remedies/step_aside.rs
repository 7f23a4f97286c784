//! Stepping aside: a robot in the other's way goes to a free parking pose nearby (found
//! on rings about where it stands), waits there and goes on.

use super::context::{
    apart, body_radius, by_parking, child, earliest, horizons, least_clearing, leg_nodes,
    leg_window, occupancy, Child, Ctx, FixtureDiscs, Side, View,
};
use crate::geometry::Vec2;
use crate::motion::Pose;
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
/// Offsets of a passing place from the robot's way, in its radii: a robot of radius r
/// beside another of radius r needs more than 2r between their centres.
const PASS_OFFSETS: [f64; 5] = [2.0, 2.25, 2.5, 2.75, 3.0];
/// Points of the way where passing places are looked for, at most, each side of the contact.
const MAX_PASS_STEPS: usize = 200;

/// Poses on rings about `q` where robot `x` is clear of the fixtures and of where robot `y`
/// passes over `[t0, t1]`: the discs a rigid `y` sweeps, the region an arm sweeps.
fn parking_poses<'a>(
    ctx: &Ctx<'a>,
    view: &View,
    x: usize,
    y: usize,
    q: Pose,
    (t0, t1): (f64, f64),
) -> impl Iterator<Item = Pose> + 'a {
    let rx = ctx.cell.rigid(x).shape.radius();
    let on_rings = PARK_RINGS.iter().flat_map(move |ring| {
        (0..PARK_DIRECTIONS).map(move |k| {
            let (s, c) = (k as f64 * std::f64::consts::TAU / PARK_DIRECTIONS as f64).sin_cos();
            Pose {
                pos: q.pos + ring * rx * Vec2::new(c, s),
                theta: q.theta,
            }
        })
    });
    free_poses(ctx, view, x, y, (t0, t1), on_rings)
}

/// Poses beside robot `x`'s way on its leg in play, a passing place: walked from where it is
/// at the contact back to where the leg starts and on to where its move ends, every radius
/// of the robot, at [`PASS_OFFSETS`] of its radius either side, those clear as a parking
/// pose is (see [`free_poses`]), nearest the contact first (behind it before ahead).
fn passing_places<'a>(
    ctx: &Ctx<'a>,
    view: &View,
    side: &Side,
    (t0, t1): (f64, f64),
    start: f64,
) -> impl Iterator<Item = Pose> + 'a {
    let x = side.x;
    let rx = ctx.cell.rigid(x).shape.radius();
    let xs = &view.robots[x];
    // Along the way, a point about every radius of arc (at full speed), nearest the contact
    // first, behind it (a bay passed) and ahead of it (the mouth of a side aisle the robot
    // may reach before the other comes), from the leg's start to the end of the move.
    let dt = rx / ctx.cell.rigid(x).max_speed;
    let end = side.sx.end;
    let points = |span: f64| (span / dt).ceil().clamp(0.0, MAX_PASS_STEPS as f64) as usize;
    let (back, ahead) = (points(side.t - start), points(end - side.t));
    let times = (1..=back.max(ahead)).flat_map(move |k| {
        let along = k as f64 * dt;
        [
            (k <= back).then_some((side.t - along).max(start)),
            (k <= ahead).then_some((side.t + along).min(end)),
        ]
        .into_iter()
        .flatten()
    });
    let beside: Vec<Pose> = times
        .filter_map(|u| {
            // Across the point, so that a point at a bend has a direction too.
            let p = xs.pose_at(u);
            let q = xs.pose_at((u + dt).min(end));
            let o = xs.pose_at((u - dt).max(start));
            let d = q.pos - o.pos;
            (d.norm() > 0.0).then_some((p, d.normalize()))
        })
        .flat_map(|(p, along)| {
            let normal = Vec2::new(-along.y, along.x);
            PASS_OFFSETS.iter().flat_map(move |k| {
                [1.0, -1.0].map(|sign| Pose {
                    pos: p.pos + sign * k * rx * normal,
                    theta: p.theta,
                })
            })
        })
        .collect();
    free_poses(ctx, view, x, side.y, (t0, t1), beside.into_iter())
}

/// The poses of `tried` where robot `x` is clear of the fixtures (each part by 2δ) and of
/// where robot `y` passes over `[t0, t1]`: the discs a rigid `y` sweeps, the region an arm
/// sweeps. Lazy, in the order tried: a remedy stops once it has the few it tries in full.
fn free_poses<'a>(
    ctx: &Ctx<'a>,
    view: &View,
    x: usize,
    y: usize,
    (t0, t1): (f64, f64),
    tried: impl Iterator<Item = Pose> + 'a,
) -> impl Iterator<Item = Pose> + 'a {
    let cell = ctx.cell;
    let delta = cell.delta;
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
    let fixtures = FixtureDiscs::of(ctx);
    let pieces = cell.rigid(x).pieces();
    tried.filter(move |&p| {
        let away = match &swept {
            Some(region) => apart(&[(pieces, p)], region, 2.0 * delta),
            None => (passes.iter()).all(|g| (g - p.pos).norm() > rx + ry + 2.0 * delta),
        };
        away && fixtures.clear(cell, x, p, 2.0 * delta)
    })
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
    let (t, x) = (side.t, side.x);
    let m = aside_leg(view, side)?;
    let q = match side.sx.activity {
        Activity::Move { .. } => node_pose(ctx.cell, x, leg_nodes(view, x, m).0),
        _ => view.robots[x].pose_at(t),
    };
    let keep_wait = matches!(side.sx.activity, Activity::Done);
    park(ctx, view, side, m, keep_wait, |window| {
        parking_poses(ctx, view, x, side.y, q, window)
    })
}

/// A robot on its way, in the other's way further on, pulls in at a passing place beside
/// its way (a bay off a corridor, the mouth of a side aisle), lets the other pass, and goes
/// on; it leaves when it did. Offered only in the search's second pass: as one more child
/// of every collision it spread the budget thinner and cost cells their answers.
pub(super) fn pass_aside(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    if !matches!(side.sx.activity, Activity::Move { .. }) {
        return None;
    }
    let m = side.sx.leg?;
    let start = leg_window(&view.robots[side.x], m).0;
    park(ctx, view, side, m, true, |window| {
        passing_places(ctx, view, side, window, start)
    })
}

/// Robot `side.x`'s leg `m` by way of the parking pose among `poses` (given the window over
/// which the other robot must be clear of it) that ends it soonest, held there as little as
/// clears; `keep_wait`: the leg's wait is kept (else the robot leaves at once).
fn park<I>(
    ctx: &Ctx,
    view: &View,
    side: &Side,
    m: usize,
    keep_wait: bool,
    poses: impl FnOnce((f64, f64)) -> I,
) -> Option<Child>
where
    I: Iterator<Item = Pose>,
{
    let x = side.x;
    let (from, to) = leg_nodes(view, x, m);
    let xs = &view.robots[x];
    let t0 = if view.routes[x].is_empty() {
        0.0
    } else {
        leg_window(xs, m).0
    };
    let horizons = horizons(view, side.y, &side.sy, t0);
    let until = t0 + horizons.last().copied().unwrap_or(0.0);
    let (a, b) = (node_pose(ctx.cell, x, from), node_pose(ctx.cell, x, to));
    let old = leg(view.legs, x, m).clone();
    let bound = Cell::new(ctx.cap);
    let tried = poses((side.t.min(t0.max(0.0)), until))
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
    use crate::geometry::{closest_features, Posed, WalkTolerances};

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
            let poses: Vec<Pose> =
                parking_poses(&test.ctx(), &test.view(), 0, 1, home, (0.0, 1.0)).collect();
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
        let poses: Vec<Pose> =
            parking_poses(&test.ctx(), &test.view(), 0, 1, home, (0.0, 1.0)).collect();
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

    /// Passing places lie beside the robot's way, either side of the contact, nearest it
    /// first: X goes east and Y west along y = 0, head on, with a wall along the north side
    /// of the way from x = 1 to 3. Each place is 2 to 3 of X's radii off the way, between
    /// where X's leg starts and where its move ends, on the south side only over the wall's
    /// stretch; on each side of the contact they come nearest first, a step (a radius of
    /// arc) apart, the two sides in turn.
    #[test]
    fn passing_places_lie_beside_the_way_either_side_of_the_contact() {
        let text = r#"{"delta": 0.01, "robots": [
            {"name": "X", "shape": [[-0.35, -0.35], [0.35, -0.35], [0.35, 0.35], [-0.35, 0.35]],
             "home": [-4, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1.5},
            {"name": "Y", "shape": [[-0.35, -0.35], [0.35, -0.35], [0.35, 0.35], [-0.35, 0.35]],
             "home": [8, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1.5}],
            "obstacles": [{"name": "wall", "shape": [[1, 0.9], [3, 0.9], [3, 1.3], [1, 1.3]]}],
            "tasks": [{"name": "east", "at": [9, 0], "duration": 1, "robots": ["X"]},
                      {"name": "west", "at": [-5, 0], "duration": 1, "robots": ["Y"]}]}"#;
        let test = TestCell::new(text, vec![vec![0], vec![1]]);
        let view = test.view();
        let schedule = crate::wcp::schedule::Schedule::of(view.robots.to_vec());
        let report = crate::collision::check(&schedule.scene(&test.cell), &Default::default());
        let c = schedule.collision(&test.cell, &report).expect("head on");
        let (x, y) = (c.robots.0, c.robots.1.expect("two robots"));
        let side = Side {
            x,
            y,
            sx: c.segments.0,
            sy: c.segments.1.expect("two robots"),
            t: c.time,
        };
        assert_eq!(test.cell.robots[x].name, "X");
        let start = leg_window(&view.robots[x], 0).0;
        let until = view.robots[y].end;
        let places: Vec<Pose> =
            passing_places(&test.ctx(), &view, &side, (side.t, until), start).collect();
        let rx = test.cell.rigid(x).shape.radius();
        let at_contact = view.robots[x].pose_at(side.t).pos.x;
        assert!(!places.is_empty());
        for p in &places {
            let off = p.pos.y.abs() / rx;
            assert!((2.0 - 1e-9..=3.0 + 1e-9).contains(&off), "{p:?}");
            assert!((-4.0..=9.0).contains(&p.pos.x), "{p:?}");
            // The wall (1 to 3, 0.9 to 1.3) leaves no room north of the way there.
            assert!(!(p.pos.y > 0.0 && (0.7..3.3).contains(&p.pos.x)), "{p:?}");
        }
        assert!(places
            .iter()
            .any(|p| p.pos.y < 0.0 && (1.0..3.0).contains(&p.pos.x)));
        // Nearest first on each side, the first a step from the contact.
        let gaps = |ahead: bool| -> Vec<f64> {
            (places.iter())
                .map(|p| p.pos.x - at_contact)
                .filter(|d| (*d > 0.0) == ahead)
                .map(f64::abs)
                .collect()
        };
        for ahead in [false, true] {
            let g = gaps(ahead);
            assert!((rx * 0.5..=rx + 1e-9).contains(&g[0]), "{ahead}: {g:?}");
            assert!(g.windows(2).all(|w| w[0] <= w[1] + 1e-12), "{ahead}: {g:?}");
        }
        // The two sides in turn: the first place ahead comes before the behind places two
        // steps or more from the contact.
        let first_ahead = places.iter().position(|p| p.pos.x > at_contact).unwrap();
        assert!(places[..first_ahead]
            .iter()
            .all(|p| at_contact - p.pos.x < 1.5 * rx));
    }
}
