//! Planning one move: grow the obstacles, find the path, time it, sample it.

use super::corners::cut_corners;
use super::grown::Grown;
use super::minkowski::{disc, minkowski_sum, swept_shape};
use super::timed::{time_primitive, Primitive};
use super::visibility::shortest_path;
use super::{angle_between, PlanError, PlannedMove, PlannerOptions, RobotLimits};
use crate::geometry::{ConvexPolygon, Vec2};
use crate::motion::rest_to_rest_time;
use crate::motion::Pose;

/// Boundary tolerance relative to the largest coordinate: thousands of times the rounding
/// of the construction, so that paths along a grown obstacle's edge are not rejected.
const TOL_REL: f64 = 1e-12;

/// Plans the fastest move of the robot (the union of its convex `pieces`, in its body frame)
/// from `from` to `to` that keeps at least `delta` from every obstacle (convex polygons in
/// world coordinates), under `limits`.
///
/// See the [module documentation](super) for the motion model. Errors: invalid limits,
/// δ, poses or options; a start or goal too close to an obstacle (the first in slice
/// order); no path.
pub(super) fn plan_direct(
    pieces: &[ConvexPolygon],
    limits: &RobotLimits,
    obstacles: &[ConvexPolygon],
    delta: f64,
    from: Pose,
    to: Pose,
    opts: &PlannerOptions,
) -> Result<PlannedMove, PlanError> {
    validate(limits, delta, &from, &to, opts)?;
    if pieces.is_empty() {
        return Err(PlanError::InvalidArgument {
            name: "pieces",
            value: 0.0,
            expected: "at least one convex piece",
        });
    }
    let turn = angle_between(from.theta, to.theta);

    // The region G must avoid: each obstacle grown by each swept piece of the robot and the
    // clearance (the robot is the union of its pieces: G is free where every piece is).
    let clearance = delta * (1.0 + opts.clearance_margin);
    let grow_by: Vec<Vec<Vec2>> = pieces
        .iter()
        .map(|piece| {
            let swept = swept_shape(piece.vertices(), from.theta, turn, opts.rotation_step);
            // −S is S turned by a half-turn: still counter-clockwise.
            let reflected: Vec<Vec2> = swept.iter().map(|v| -v).collect();
            minkowski_sum(&reflected, &disc(clearance))
        })
        .collect();
    // Obstacle k grown by piece j is `grown[k * pieces + j]`.
    let grown: Vec<Grown> = obstacles
        .iter()
        .flat_map(|o| {
            grow_by
                .iter()
                .map(|g| Grown::new(minkowski_sum(o.vertices(), g)))
        })
        .collect();
    let obstacle_of = |g: usize| g / pieces.len();
    let extent = grown
        .iter()
        .map(Grown::extent)
        .fold(from.pos.amax().max(to.pos.amax()), f64::max);
    // Penetrating a grown obstacle by `tol` still leaves half the margin above δ.
    let tol = (TOL_REL * extent).min(0.5 * delta * opts.clearance_margin);

    if let Some(g) = grown.iter().position(|g| g.contains(&from.pos, tol)) {
        let obstacle = obstacle_of(g);
        return Err(PlanError::StartBlocked { obstacle });
    }
    if let Some(g) = grown.iter().position(|g| g.contains(&to.pos, tol)) {
        let obstacle = obstacle_of(g);
        return Err(PlanError::GoalBlocked { obstacle });
    }
    let segment_time = |length: f64| rest_to_rest_time(length, limits.max_speed, limits.max_accel);
    let blocking =
        |path: &[Vec2], k: usize| path.windows(2).any(|w| grown[k].blocks(&w[0], &w[1], tol));
    let path = if grown.iter().any(|g| g.blocks(&from.pos, &to.pos, tol)) {
        // Lazy obstacles: search among those that block the path found so far, and add
        // the ones its answer crosses. Obstacles only remove paths, so the cheapest path
        // among a subset that also misses all the others is the cheapest of all; and no
        // path among a subset means none at all. A hall of many obstacles then costs a
        // graph over the few near the move, not over all of them.
        let mut active: Vec<usize> = Vec::new();
        let mut candidate = vec![from.pos, to.pos];
        loop {
            let more: Vec<usize> = (0..grown.len())
                .filter(|&k| !active.contains(&k) && blocking(&candidate, k))
                .collect();
            if more.is_empty() {
                break;
            }
            active.extend(more);
            let subset: Vec<Grown> = active.iter().map(|&k| grown[k].clone()).collect();
            candidate = shortest_path(&subset, from.pos, to.pos, tol, segment_time)
                .ok_or(PlanError::NoPath)?;
        }
        cut_corners(candidate, &grown, tol, segment_time)
    } else {
        vec![from.pos, to.pos]
    };

    // A move from a pose to itself is a primitive of no length and no turn: one sample.
    Ok(time_primitive(
        radius(pieces),
        limits,
        &Primitive {
            path,
            theta: from.theta,
            turn,
        },
        opts.samples_per_phase,
    ))
}

/// The robot's radius: the farthest point of any piece from its rotation centre.
pub(super) fn radius(pieces: &[ConvexPolygon]) -> f64 {
    pieces.iter().map(ConvexPolygon::radius).fold(0.0, f64::max)
}

/// Refuses limits, δ, poses and options the model cannot use.
fn validate(
    limits: &RobotLimits,
    delta: f64,
    from: &Pose,
    to: &Pose,
    opts: &PlannerOptions,
) -> Result<(), PlanError> {
    for (name, value) in [
        ("max_speed", limits.max_speed),
        ("max_accel", limits.max_accel),
        ("max_turn_rate", limits.max_turn_rate),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return Err(PlanError::InvalidLimits { name, value });
        }
    }
    let finite = "a finite number";
    let checks = [
        ("delta", delta, delta > 0.0, "a positive finite number"),
        ("from.pos.x", from.pos.x, true, finite),
        ("from.pos.y", from.pos.y, true, finite),
        ("from.theta", from.theta, true, finite),
        ("to.pos.x", to.pos.x, true, finite),
        ("to.pos.y", to.pos.y, true, finite),
        ("to.theta", to.theta, true, finite),
        (
            "clearance_margin",
            opts.clearance_margin,
            opts.clearance_margin >= 0.0,
            "a non-negative finite number",
        ),
        (
            "samples_per_phase",
            opts.samples_per_phase as f64,
            opts.samples_per_phase >= 1,
            "at least 1",
        ),
        (
            "rotation_step",
            opts.rotation_step,
            opts.rotation_step > 0.0 && opts.rotation_step <= std::f64::consts::FRAC_PI_2,
            "in (0, π/2]",
        ),
    ];
    for (name, value, ok, expected) in checks {
        if !(ok && value.is_finite()) {
            return Err(PlanError::InvalidArgument {
                name,
                value,
                expected,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, h: f64) -> ConvexPolygon {
        ConvexPolygon::new(&[
            [x - h, y - h],
            [x + h, y - h],
            [x + h, y + h],
            [x - h, y + h],
        ])
        .unwrap()
        .0
    }

    fn pose(x: f64, y: f64, theta: f64) -> Pose {
        Pose {
            pos: Vec2::new(x, y),
            theta,
        }
    }

    const LIMITS: RobotLimits = RobotLimits {
        max_speed: 1.0,
        max_accel: 2.0,
        max_turn_rate: 0.5,
    };

    #[test]
    fn invalid_inputs_are_named() {
        let robot = square(0.0, 0.0, 0.5);
        let opts = PlannerOptions::default();
        let (a, b) = (pose(0.0, 0.0, 0.0), pose(1.0, 0.0, 0.0));
        let bad = RobotLimits {
            max_accel: 0.0,
            ..LIMITS
        };
        let e = plan_direct(std::slice::from_ref(&robot), &bad, &[], 0.1, a, b, &opts).unwrap_err();
        assert_eq!(
            e,
            PlanError::InvalidLimits {
                name: "max_accel",
                value: 0.0
            }
        );
        let e = plan_direct(
            std::slice::from_ref(&robot),
            &LIMITS,
            &[],
            -1.0,
            a,
            b,
            &opts,
        )
        .unwrap_err();
        assert!(matches!(
            e,
            PlanError::InvalidArgument { name: "delta", .. }
        ));
        let e = plan_direct(
            std::slice::from_ref(&robot),
            &LIMITS,
            &[],
            0.1,
            a,
            pose(f64::NAN, 0.0, 0.0),
            &opts,
        );
        assert!(e.unwrap_err().to_string().contains("to.pos.x"));
        let opts = PlannerOptions {
            rotation_step: 2.0,
            ..opts
        };
        let e =
            plan_direct(std::slice::from_ref(&robot), &LIMITS, &[], 0.1, a, b, &opts).unwrap_err();
        assert!(matches!(
            e,
            PlanError::InvalidArgument {
                name: "rotation_step",
                ..
            }
        ));
    }

    #[test]
    fn no_motion_is_one_sample() {
        let robot = square(0.0, 0.0, 0.5);
        let p = pose(1.0, 2.0, 0.3);
        let m = plan_direct(
            std::slice::from_ref(&robot),
            &LIMITS,
            &[],
            0.1,
            p,
            p,
            &PlannerOptions::default(),
        )
        .unwrap();
        assert_eq!(m.duration, 0.0);
        assert_eq!(m.samples.len(), 1);
        assert_eq!((m.samples[0].pos, m.samples[0].theta), (p.pos, p.theta));
    }

    #[test]
    fn pure_rotation_takes_the_rotation_time() {
        let robot = square(0.0, 0.0, 0.5);
        let (a, b) = (pose(1.0, 2.0, 0.0), pose(1.0, 2.0, 2.0));
        let m = plan_direct(
            std::slice::from_ref(&robot),
            &LIMITS,
            &[],
            0.1,
            a,
            b,
            &PlannerOptions::default(),
        )
        .unwrap();
        let alpha = LIMITS.max_accel / robot.radius();
        assert_eq!(
            m.duration,
            rest_to_rest_time(2.0, LIMITS.max_turn_rate, alpha)
        );
        assert!(m.samples.iter().all(|s| s.pos == a.pos));
        assert_eq!(m.samples.last().unwrap().theta, 2.0);
    }

    #[test]
    fn a_close_obstacle_blocks_only_when_the_robot_turns() {
        // Square of half side 0.5 beside a wall 0.6 from its centre: clear while still,
        // hit by its corners (at 0.707) when turned by 45 degrees.
        let robot = square(0.0, 0.0, 0.5);
        let wall = square(1.6, 0.0, 1.0);
        let opts = PlannerOptions::default();
        let (a, b) = (pose(0.0, 0.0, 0.0), pose(0.0, -3.0, 0.0));
        assert!(plan_direct(
            std::slice::from_ref(&robot),
            &LIMITS,
            std::slice::from_ref(&wall),
            0.01,
            a,
            b,
            &opts
        )
        .is_ok());
        let turned = pose(0.0, -3.0, 0.8);
        let e = plan_direct(
            std::slice::from_ref(&robot),
            &LIMITS,
            &[wall],
            0.01,
            a,
            turned,
            &opts,
        )
        .unwrap_err();
        assert_eq!(e, PlanError::StartBlocked { obstacle: 0 });
    }
}
