//! Moves that cannot turn on the way: drive, turn in place where there is room, drive on.
//!
//! A move turns over its whole length, so its obstacles are grown by the robot swept over
//! the whole rotation. Near a fixture that is often too much: a robot 5 cm from a box can
//! reach that pose at its final angle, but not while still turning. Such a move is planned
//! in three legs instead: at the start angle to a turning point P, a turn in place at P, and
//! at the goal angle to the goal. P is the start, the goal, or a point on rings of 1, 2 and
//! 4 robot radii around them; the fastest plan wins. Each leg is an ordinary move, so all
//! the clearance guarantees hold leg by leg.

use super::plan::{plan_direct, radius};
use super::timed::chain;
use super::{angle_between, PlanError, PlannedMove, PlannerOptions, RobotLimits};
use crate::geometry::{ConvexPolygon, Vec2};
use crate::motion::Pose;

/// Directions tried around the start and the goal for the turning point.
const DIRECTIONS: usize = 8;
/// Ring radii, in robot radii.
const RINGS: [f64; 3] = [1.0, 2.0, 4.0];

/// Plans the fastest move of the robot (the union of its convex `pieces`, in its body frame:
/// one for a convex robot) from `from` to `to` that keeps at least `delta` from every
/// obstacle (convex polygons in world coordinates), under `limits`.
///
/// See the [module documentation](super) for the motion model. When the move cannot turn
/// on the way (its start or goal too close to an obstacle for the rotation, or no path for
/// the swept robot), it turns in place where it has room (see this file's notes). Errors:
/// invalid limits, δ, poses or options; a start or goal too close to an obstacle (the first
/// in slice order) even without turning; no path.
///
/// ```
/// use workcell::geometry::{ConvexPolygon, Vec2};
/// use workcell::motion::Pose;
/// use workcell::planning::{plan_move, rest_to_rest_time, PlanError, PlannerOptions, RobotLimits};
/// let robot = ConvexPolygon::rectangle(1.0, 1.0)?;
/// let limits = RobotLimits { max_speed: 1.0, max_accel: 2.0, max_turn_rate: 1.0 };
/// let opts = PlannerOptions::default();
/// let (from, to) = (Pose::new(0.0, 0.0, 0.0), Pose::new(10.0, 0.0, 0.0));
/// // Nothing in the way: straight, rest to rest at the limits.
/// let straight = plan_move(std::slice::from_ref(&robot), &limits, &[], 0.01, from, to, &opts)?;
/// assert_eq!(straight.path, [Vec2::new(0.0, 0.0), Vec2::new(10.0, 0.0)]);
/// assert_eq!(straight.duration, rest_to_rest_time(10.0, 1.0, 2.0));
/// // A goal inside an obstacle cannot be reached.
/// let post = ConvexPolygon::from_vertices(&[[9.0, -1.0], [11.0, -1.0], [11.0, 1.0], [9.0, 1.0]])?;
/// let e = plan_move(std::slice::from_ref(&robot), &limits, &[post], 0.01, from, to, &opts).unwrap_err();
/// assert_eq!(e, PlanError::GoalBlocked { obstacle: 0 });
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn plan_move(
    pieces: &[ConvexPolygon],
    limits: &RobotLimits,
    obstacles: &[ConvexPolygon],
    delta: f64,
    from: Pose,
    to: Pose,
    opts: &PlannerOptions,
) -> Result<PlannedMove, PlanError> {
    let plan = |a: Pose, b: Pose| plan_direct(pieces, limits, obstacles, delta, a, b, opts);
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
    let at = |pos: Vec2, theta: f64| Pose { pos, theta };
    // No turning point helps a robot that cannot stand at its start or goal even without
    // turning, nor one that finds no way at either fixed angle: say so at once.
    let stands = |p: Pose| plan(p, p).is_ok();
    if !stands(from) || !stands(at(to.pos, end_theta)) {
        return Err(error);
    }
    if error == PlanError::NoPath
        && plan(from, at(to.pos, from.theta)) == Err(PlanError::NoPath)
        && plan(at(from.pos, end_theta), at(to.pos, end_theta)) == Err(PlanError::NoPath)
    {
        return Err(error);
    }
    let legs = |p: Vec2| -> Option<PlannedMove> {
        let first = plan(from, at(p, from.theta)).ok()?;
        // The turn is asked with the goal's own angle, as the direct move asks it: the same
        // shortest turn, even for a half turn, where from.theta + turn could round to the
        // other way round.
        let spin = plan(at(p, from.theta), at(p, to.theta)).ok()?;
        let last = plan(at(p, end_theta), at(to.pos, end_theta)).ok()?;
        let legs = [first, spin, last];
        // Each leg must start where and at the angle the previous one stopped.
        let joined = legs.windows(2).all(|w| {
            let (a, b) = (
                w[0].samples.last().expect("a move has samples"),
                &w[1].samples[0],
            );
            a.pos == b.pos && a.theta == b.theta
        });
        joined.then(|| chain(&legs))
    };
    let radius = radius(pieces);
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
