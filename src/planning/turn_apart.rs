//! Moves that cannot turn on the way: drive, turn in place where there is room, drive on.
//!
//! A move turns over its whole length, so its obstacles are grown by the robot swept over
//! the whole rotation. Near a fixture that is often too much: a robot 5 cm from a box can
//! reach that pose at its final angle, but not while still turning. Such a move is planned
//! in three legs instead: at the start angle to a turning point P, a turn in place at P, and
//! at the goal angle to the goal. P is the start, the goal, or a point on rings of 1, 2 and
//! 4 robot radii around them; the fastest plan wins. Each leg is an ordinary move, so all
//! the clearance guarantees hold leg by leg.

use super::plan::plan_direct;
use super::{angle_between, PlanError, PlannedMove, PlannerOptions, RobotLimits};
use crate::geometry::{ConvexPolygon, Vec2};
use crate::motion::Pose;

/// Directions tried around the start and the goal for the turning point.
const DIRECTIONS: usize = 8;
/// Ring radii, in robot radii.
const RINGS: [f64; 3] = [1.0, 2.0, 4.0];

/// Plans the fastest move of the robot `shape` from `from` to `to` that keeps at least
/// `delta` from every obstacle (convex polygons in world coordinates), under `limits`.
///
/// See the [module documentation](super) for the motion model. When the move cannot turn
/// on the way (its start or goal too close to an obstacle for the rotation, or no path for
/// the swept robot), it turns in place where it has room (see this file's notes). Errors:
/// invalid limits, δ, poses or options; a start or goal too close to an obstacle (the first
/// in slice order) even without turning; no path.
pub fn plan_move(
    shape: &ConvexPolygon,
    limits: &RobotLimits,
    obstacles: &[ConvexPolygon],
    delta: f64,
    from: Pose,
    to: Pose,
    opts: &PlannerOptions,
) -> Result<PlannedMove, PlanError> {
    let plan = |a: Pose, b: Pose| plan_direct(shape, limits, obstacles, delta, a, b, opts);
    let error = match plan(from, to) {
        Ok(m) => return Ok(m),
        Err(e @ (PlanError::InvalidLimits { .. } | PlanError::InvalidArgument { .. })) => {
            return Err(e)
        }
        Err(e) => e,
    };
    let turn = angle_between(from.theta, to.theta);
    if turn == 0.0 {
        return Err(error);
    }
    // The goal angle as the direct move would end: the start angle plus the shortest turn.
    let end_theta = from.theta + turn;
    let legs = |p: Vec2| -> Option<PlannedMove> {
        let first = plan(
            from,
            Pose {
                pos: p,
                theta: from.theta,
            },
        )
        .ok()?;
        let spin = plan(
            Pose {
                pos: p,
                theta: from.theta,
            },
            Pose {
                pos: p,
                theta: end_theta,
            },
        )
        .ok()?;
        let last = plan(
            Pose {
                pos: p,
                theta: end_theta,
            },
            Pose {
                pos: to.pos,
                theta: end_theta,
            },
        )
        .ok()?;
        Some(chain(&[first, spin, last]))
    };
    let radius = shape.radius();
    let mut points = vec![from.pos, to.pos];
    for centre in [from.pos, to.pos] {
        for ring in RINGS {
            for k in 0..DIRECTIONS {
                let (s, c) = (k as f64 * std::f64::consts::TAU / DIRECTIONS as f64).sin_cos();
                points.push(centre + ring * radius * Vec2::new(c, s));
            }
        }
    }
    points
        .into_iter()
        .filter_map(legs)
        .min_by(|a, b| a.duration.total_cmp(&b.duration))
        .ok_or(error)
}

/// The legs one after the other, each starting where and when the previous one stops.
fn chain(legs: &[PlannedMove]) -> PlannedMove {
    let mut samples = legs[0].samples.clone();
    let mut path = legs[0].path.clone();
    let mut start = legs[0].duration;
    for leg in &legs[1..] {
        // A leg's first sample is the previous leg's last: at rest, at the same pose.
        samples.extend(leg.samples[1..].iter().map(|s| crate::motion::Sample {
            t: start + s.t,
            ..*s
        }));
        path.extend(leg.path.iter().skip(1));
        start += leg.duration;
    }
    // A turn in place repeats its point.
    path.dedup();
    path.dedup();
    // The last sample carries the duration exactly, as for a direct move.
    PlannedMove {
        duration: samples.last().map_or(0.0, |s| s.t),
        path,
        samples,
    }
}
