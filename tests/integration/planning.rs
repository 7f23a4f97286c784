//! The planner against the checker: every planned move is certified collision-free, and
//! its samples follow the motion model (recomputed here independently).

use crate::common::{ellipse_shape, hull_shape, polygon, Shape};
use proptest::prelude::*;
use std::f64::consts::PI;
use workcell::collision::{check, Body, CheckOptions, Scene};
use workcell::geometry::{ConvexPolygon, Vec2};
use workcell::motion::{Pose, Trajectory};
use workcell::planning::{
    angle_between, plan_move, rest_to_rest_time, time_primitives, PlanError, PlannedMove,
    PlannerOptions, RobotLimits,
};

const DELTA: f64 = 0.01;
const LIMITS: RobotLimits = RobotLimits {
    max_speed: 1.5,
    max_accel: 2.0,
    max_turn_rate: 0.8,
};
/// Relative slack on limits and times.
const REL: f64 = 1e-9;

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> ConvexPolygon {
    polygon(&[[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
}

fn pose(x: f64, y: f64, theta: f64) -> Pose {
    Pose {
        pos: Vec2::new(x, y),
        theta,
    }
}

fn plan(robot: &ConvexPolygon, obstacles: &[ConvexPolygon], from: Pose, to: Pose) -> PlannedMove {
    plan_move(
        std::slice::from_ref(robot),
        &LIMITS,
        obstacles,
        DELTA,
        from,
        to,
        &PlannerOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// Distance covered and speed at `t` of the fastest rest-to-rest motion over `d`, or of
/// the one stretched to last `duration`: written afresh from the model.
fn trapezoid(d: f64, v_max: f64, a: f64, duration: Option<f64>, t: f64) -> (f64, f64) {
    let fastest = rest_to_rest_time(d, v_max, a);
    let total = duration.unwrap_or(fastest);
    // Cruise rate. At the fastest time directly: the quadratic below has a double root for
    // a triangle, where rounding would blur it by √ε.
    let w = if total <= fastest * (1.0 + 1e-12) {
        v_max.min((a * d).sqrt())
    } else {
        // The smaller root of w² − a·T·w + a·d = 0.
        let disc = (a * total).powi(2) - 4.0 * a * d;
        (0.5 * (a * total - disc.max(0.0).sqrt())).min(v_max)
    };
    let ta = (w / a).min(total / 2.0);
    let t = t.clamp(0.0, total);
    if t < ta {
        (0.5 * a * t * t, a * t)
    } else if t <= total - ta {
        (0.5 * a * ta * ta + w * (t - ta), w)
    } else {
        let r = total - t;
        (d - 0.5 * a * r * r, a * r)
    }
}

/// The checker's verdict on the planned move among the obstacles.
fn certify(robot: &ConvexPolygon, obstacles: &[ConvexPolygon], planned: &PlannedMove) {
    let samples = planned.samples.clone();
    let mut bodies = vec![Body::robot(
        "robot",
        robot.clone(),
        Trajectory::new(samples).expect("valid samples"),
    )];
    for (k, o) in obstacles.iter().enumerate() {
        bodies.push(Body::obstacle(format!("obstacle {k}"), o));
    }
    let report = check(
        &Scene {
            delta: DELTA,
            bodies,
        },
        &CheckOptions::default(),
    );
    assert!(!report.collision, "{:?}", report.first_contact);
    assert!(report.certified, "{:?}", report.stats);
}

/// The samples follow the model: ends, limits, and the profiles recomputed from the path.
fn check_model(robot: &ConvexPolygon, from: Pose, to: Pose, planned: &PlannedMove) {
    let s = &planned.samples;
    let turn = angle_between(from.theta, to.theta);
    let path = &planned.path;
    assert_eq!((path[0], path[path.len() - 1]), (from.pos, to.pos));
    let seg_times: Vec<f64> = path
        .windows(2)
        .map(|w| rest_to_rest_time((w[1] - w[0]).norm(), LIMITS.max_speed, LIMITS.max_accel))
        .collect();
    let t_trans: f64 = seg_times.iter().sum();
    let alpha = LIMITS.max_accel / robot.radius();
    let t_rot = rest_to_rest_time(turn, LIMITS.max_turn_rate, alpha);
    let duration = planned.duration;
    assert!((duration - t_trans.max(t_rot)).abs() <= REL * duration);
    let straight = rest_to_rest_time(
        (to.pos - from.pos).norm(),
        LIMITS.max_speed,
        LIMITS.max_accel,
    );
    assert!(duration >= straight * (1.0 - REL));

    let (first, last) = (s[0], s[s.len() - 1]);
    assert_eq!(
        (first.t, first.pos, first.theta),
        (0.0, from.pos, from.theta)
    );
    assert_eq!((first.vel, first.omega), (Vec2::zeros(), 0.0));
    assert_eq!(
        (last.t, last.pos, last.theta),
        (duration, to.pos, from.theta + turn)
    );
    assert_eq!((last.vel, last.omega), (Vec2::zeros(), 0.0));

    let scale = 1.0 + from.pos.amax().max(to.pos.amax());
    for (k, p) in s.iter().enumerate() {
        if k > 0 {
            let q = &s[k - 1];
            assert!(p.t > q.t, "times must increase");
            let dt = p.t - q.t;
            let dv = (p.vel - q.vel).norm();
            assert!(
                dv <= LIMITS.max_accel * dt * (1.0 + 1e-6) + 1e-9,
                "accel at {k}"
            );
            let dw = (p.omega - q.omega).abs();
            assert!(
                dw <= alpha * dt * (1.0 + 1e-6) + 1e-9,
                "angular accel at {k}"
            );
        }
        assert!(p.vel.norm() <= LIMITS.max_speed * (1.0 + REL));
        assert!(p.omega.abs() <= LIMITS.max_turn_rate * (1.0 + REL));
        // Position from the path and the segment profiles.
        let (mut t0, mut expect) = (0.0, (to.pos, Vec2::zeros()));
        for (w, &dt) in path.windows(2).zip(&seg_times) {
            if p.t < t0 + dt {
                let len = (w[1] - w[0]).norm();
                let (d, v) = trapezoid(len, LIMITS.max_speed, LIMITS.max_accel, None, p.t - t0);
                let u = (w[1] - w[0]) / len;
                expect = (w[0] + u * d, u * v);
                break;
            }
            t0 += dt;
        }
        assert!((p.pos - expect.0).norm() <= 1e-9 * scale, "pos at {}", p.t);
        assert!(
            (p.vel - expect.1).norm() <= 1e-9 * scale,
            "vel at {}: {} vs {}",
            p.t,
            p.vel,
            expect.1
        );
        // Orientation from the one rotation profile over the whole move.
        let (a, w) = trapezoid(turn.abs(), LIMITS.max_turn_rate, alpha, Some(duration), p.t);
        assert!((p.theta - (from.theta + turn.signum() * a)).abs() <= 1e-9);
        assert!((p.omega - turn.signum() * w).abs() <= 1e-9);
    }
}

#[test]
fn straight_free_move_is_one_segment() {
    let robot = rect(-0.3, -0.2, 0.5, 0.2);
    let (from, to) = (pose(0.0, 0.0, 0.2), pose(6.0, -2.0, 0.5));
    let planned = plan(&robot, &[rect(0.0, 3.0, 2.0, 4.0)], from, to);
    assert_eq!(planned.path, vec![from.pos, to.pos]);
    let d = (to.pos - from.pos).norm();
    let alpha = LIMITS.max_accel / robot.radius();
    let expected = rest_to_rest_time(d, LIMITS.max_speed, LIMITS.max_accel).max(rest_to_rest_time(
        0.3,
        LIMITS.max_turn_rate,
        alpha,
    ));
    assert!((planned.duration - expected).abs() <= 1e-12 * expected);
    check_model(&robot, from, to, &planned);
    certify(&robot, &[rect(0.0, 3.0, 2.0, 4.0)], &planned);
}

#[test]
fn goes_around_a_wall() {
    let robot = polygon(&[[-0.4, -0.3], [0.6, 0.0], [-0.4, 0.3]]);
    let wall = [rect(2.0, -3.0, 2.5, 3.0)];
    for turn in [0.0, 1.0, -2.5, PI] {
        let (from, to) = (pose(0.0, 0.5, 0.3), pose(5.0, 0.0, 0.3 + turn));
        let planned = plan(&robot, &wall, from, to);
        // Around one end of the wall.
        let n = planned.path.len();
        assert!(n >= 3, "{:?}", planned.path);
        let side = planned.path[1].y.signum();
        assert!(planned.path[1..n - 1].iter().all(|p| p.y * side > 2.5));
        check_model(&robot, from, to, &planned);
        certify(&robot, &wall, &planned);
    }
}

#[test]
fn rotation_dominated_move_takes_the_rotation_time() {
    let robot = rect(-1.0, -0.2, 1.0, 0.2);
    let (from, to) = (pose(0.0, 0.0, 0.0), pose(0.3, 0.0, 3.0));
    let planned = plan(&robot, &[], from, to);
    let alpha = LIMITS.max_accel / robot.radius();
    let t_rot = rest_to_rest_time(3.0, LIMITS.max_turn_rate, alpha);
    assert!(t_rot > rest_to_rest_time(0.3, LIMITS.max_speed, LIMITS.max_accel));
    assert_eq!(planned.duration, t_rot);
    // The translation is over early; G waits at the goal while the robot turns.
    let t_trans = rest_to_rest_time(0.3, LIMITS.max_speed, LIMITS.max_accel);
    let waiting: Vec<_> = planned.samples.iter().filter(|s| s.t >= t_trans).collect();
    assert!(waiting.len() > 4 && waiting.iter().all(|s| s.pos == to.pos));
    assert!(planned
        .samples
        .iter()
        .any(|s| s.omega >= LIMITS.max_turn_rate * (1.0 - REL)));
    check_model(&robot, from, to, &planned);
}

#[test]
fn blocked_start_and_goal_name_the_obstacle() {
    let robot = rect(-0.5, -0.5, 0.5, 0.5);
    let obstacles = [
        rect(10.0, 10.0, 11.0, 11.0),
        rect(0.52, -1.0, 1.0, 1.0),
        rect(4.0, -1.0, 4.495, 1.0),
    ];
    let opts = PlannerOptions::default();
    let go = |from, to| {
        plan_move(
            std::slice::from_ref(&robot),
            &LIMITS,
            &obstacles,
            DELTA,
            from,
            to,
            &opts,
        )
    };
    // 0.02 from obstacle 1 is clear (the planning clearance is δ·1.02 = 0.0102), 0.005
    // is not.
    assert!(go(pose(0.0, 0.0, 0.0), pose(0.0, -3.0, 0.0)).is_ok());
    let e = go(pose(0.015, 0.0, 0.0), pose(0.0, -3.0, 0.0)).unwrap_err();
    assert_eq!(e, PlanError::StartBlocked { obstacle: 1 });
    let e = go(pose(0.0, -3.0, 0.0), pose(5.0, 0.0, 0.0)).unwrap_err();
    assert_eq!(e, PlanError::GoalBlocked { obstacle: 2 });
    assert!(e.to_string().contains("obstacle 2"));
}

#[test]
fn enclosed_goal_has_no_path() {
    let robot = rect(-0.5, -0.5, 0.5, 0.5);
    // A ring of four walls with gaps of 0.5, narrower than the robot.
    let ring = [
        rect(-3.0, -3.0, 3.0, -2.0),
        rect(-3.0, 2.0, 2.5, 3.0),
        rect(-3.0, -1.75, -2.0, 1.75),
        rect(2.0, -2.0, 3.0, 1.5),
    ];
    let e = plan_move(
        std::slice::from_ref(&robot),
        &LIMITS,
        &ring,
        DELTA,
        pose(-6.0, 0.0, 0.0),
        pose(0.0, 0.0, 0.0),
        &PlannerOptions::default(),
    )
    .unwrap_err();
    assert_eq!(e, PlanError::NoPath);
    assert_eq!(
        e.to_string(),
        "no collision-free path from the start to the goal"
    );
}

/// A gripper reaches round a post, which ends between its fingers: its parts are grown one by
/// one, so the gap between them stays open; its hull is stopped at the post. Turning on the
/// way in, it sweeps each part, and the checker, given the parts, certifies the move.
#[test]
fn a_robot_of_parts_reaches_round_a_post_its_hull_could_not() {
    let palm = rect(-0.4, -0.5, 0.0, 0.5);
    let fingers = [rect(0.0, 0.3, 0.8, 0.5), rect(0.0, -0.5, 0.8, -0.3)];
    let gripper = [palm, fingers[0].clone(), fingers[1].clone()];
    let post = rect(2.5, -0.15, 2.8, 0.15);
    let opts = PlannerOptions::default();
    let obstacles = std::slice::from_ref(&post);
    for from in [pose(-3.0, 0.0, 0.0), pose(-3.0, 2.0, 0.4)] {
        let to = pose(2.1, 0.0, 0.0);
        let planned = plan_move(&gripper, &LIMITS, obstacles, DELTA, from, to, &opts).unwrap();
        let parts = workcell::geometry::Parts::new(gripper.to_vec()).unwrap();
        let trajectory = Trajectory::new(planned.samples.clone()).unwrap();
        let scene = Scene {
            delta: DELTA,
            bodies: vec![
                Body::robot_of_parts("gripper", parts.clone(), trajectory),
                Body::obstacle("post", &post),
            ],
        };
        let report = check(&scene, &CheckOptions::default());
        assert!(!report.collision && report.certified, "{report:?}");
        let hull = parts.hull().clone();
        let e = plan_move(&[hull], &LIMITS, obstacles, DELTA, from, to, &opts).unwrap_err();
        assert_eq!(e, PlanError::GoalBlocked { obstacle: 0 });
    }
}

#[test]
fn squeezes_through_a_gap_just_wide_enough() {
    let robot = rect(-0.5, -0.5, 0.5, 0.5);
    let clearance = DELTA * (1.0 + PlannerOptions::default().clearance_margin);
    let (from, to) = (pose(-3.0, 0.0, 0.0), pose(3.0, 0.0, 0.0));
    for (slack, through) in [(1e-9, true), (-1e-6, false)] {
        let half = 0.5 + clearance + slack;
        let walls = [rect(-0.5, half, 0.5, 20.0), rect(-0.5, -20.0, 0.5, -half)];
        let planned = plan(&robot, &walls, from, to);
        assert_eq!(planned.path.len() == 2, through, "{:?}", planned.path);
        check_model(&robot, from, to, &planned);
        certify(&robot, &walls, &planned);
    }
}

#[test]
fn follows_a_bent_corridor_just_wide_enough() {
    // An L-shaped corridor whose grown walls leave G a band 2·10⁻⁹ wide: the path runs
    // along the grown walls' boundaries, which rounding must not reject.
    let robot = rect(-0.5, -0.5, 0.5, 0.5);
    let h = 0.5 + DELTA * (1.0 + PlannerOptions::default().clearance_margin) + 1e-9;
    let walls = [
        rect(-6.0, -3.0, 3.0, -h),
        rect(h, -h, 3.0, 6.0),
        rect(-6.0, h, -h, 6.0),
    ];
    let (from, to) = (pose(-5.0, 0.0, 0.0), pose(0.0, 5.0, 0.0));
    let planned = plan(&robot, &walls, from, to);
    assert!(planned.path.len() <= 4, "{:?}", planned.path);
    let leg = rest_to_rest_time(5.0, LIMITS.max_speed, LIMITS.max_accel);
    assert!(planned.duration < 2.0 * leg + 0.1, "{}", planned.duration);
    check_model(&robot, from, to, &planned);
    certify(&robot, &walls, &planned);
}

fn scene_strategy() -> impl Strategy<Value = (Shape, Vec<Shape>, [f64; 6])> {
    (
        ellipse_shape(3..=7, 0.2..0.8, -0.3..0.3),
        prop::collection::vec(hull_shape(0.5..2.0, -5.0..5.0), 3..=6),
        (-6.0f64..6.0, -PI..PI, -6.0f64..6.0, -PI..PI),
    )
        .prop_map(|(robot, obstacles, (y0, th0, y1, th1))| {
            (robot, obstacles, [-9.0, y0, th0, 9.0, y1, th1])
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_moves_are_certified((robot, obstacles, ends) in scene_strategy()) {
        let robot = polygon(&robot);
        let obstacles: Vec<ConvexPolygon> = obstacles.iter().map(|o| polygon(o)).collect();
        let from = pose(ends[0], ends[1], ends[2]);
        let to = pose(ends[3], ends[4], ends[5]);
        match plan_move(std::slice::from_ref(&robot), &LIMITS, &obstacles, DELTA, from, to, &PlannerOptions::default()) {
            Ok(planned) => {
                check_model(&robot, from, to, &planned);
                certify(&robot, &obstacles, &planned);
                retimes_exactly(&robot, &planned);
            }
            // The ends are outside the obstacles' area: the start and goal are free, and
            // the obstacles never enclose one of them.
            Err(e) => prop_assert!(false, "{e}"),
        }
    }
}

/// Timing a move's primitives again gives its samples bit for bit: what `evaluate` relies on
/// to replay the moves the feedback loop changed.
fn retimes_exactly(robot: &ConvexPolygon, planned: &PlannedMove) {
    let again = time_primitives(robot.radius(), &LIMITS, &planned.primitives, 4);
    assert_eq!(&again, planned);
}

/// A pose 5 cm from a box, at a quarter turn from the start: reachable at its final angle,
/// not while still turning. The move turns in place where there is room instead.
#[test]
fn a_goal_too_close_to_turn_at_is_reached_by_turning_apart() {
    let robot = rect(-0.3, -0.3, 0.3, 0.3);
    let boxed = [rect(2.0, 2.0, 3.0, 3.0)];
    let (from, to) = (pose(0.0, 0.0, 0.0), pose(1.65, 2.5, PI / 2.0));
    let m = plan(&robot, &boxed, from, to);
    certify(&robot, &boxed, &m);
    let (first, last) = (m.samples[0], *m.samples.last().unwrap());
    assert_eq!(
        (first.t, first.pos, first.theta),
        (0.0, from.pos, from.theta)
    );
    assert_eq!((last.t, last.pos), (m.duration, to.pos));
    assert!((last.theta - to.theta).abs() < 1e-12);
    assert!(m.samples.windows(2).all(|w| w[1].t > w[0].t));
    for s in &m.samples {
        assert!(s.vel.norm() <= LIMITS.max_speed * (1.0 + REL));
        assert!(s.omega.abs() <= LIMITS.max_turn_rate * (1.0 + REL));
    }
    // The robot has finished turning before it drives in: after the last sample off the
    // goal angle, it still moves.
    let turned = m
        .samples
        .iter()
        .rposition(|s| (s.theta - to.theta).abs() > 1e-12)
        .unwrap();
    assert!(m.samples[turned + 1..].iter().any(|s| s.pos != to.pos));
    assert!(m.duration >= rest_to_rest_time((to.pos - from.pos).norm(), 1.5, 2.0));
    assert_eq!(m.primitives.len(), 3);
    retimes_exactly(&robot, &m);
}

/// A half turn near a box: the turn in place must go the way the direct move would, not
/// flip to the other half turn and leave a full turn to jump over at the next leg.
#[test]
fn a_half_turn_apart_turns_one_way_within_the_turn_rate() {
    let robot = rect(-0.3, -0.3, 0.3, 0.3);
    let boxed = [rect(2.0, 2.0, 3.0, 3.0)];
    let (from, to) = (pose(0.0, 0.0, 3.23), pose(1.65, 2.5, 0.08840734641020687));
    let m = plan(&robot, &boxed, from, to);
    certify(&robot, &boxed, &m);
    let last = m.samples.last().unwrap();
    assert_eq!(last.theta, from.theta + angle_between(from.theta, to.theta));
    for w in m.samples.windows(2) {
        let rate = (w[1].theta - w[0].theta).abs() / (w[1].t - w[0].t);
        assert!(
            rate <= LIMITS.max_turn_rate * (1.0 + REL),
            "{rate} rad/s at t = {}",
            w[0].t
        );
    }
}
