//! Point-to-point moves: the fastest obstacle-free move of one robot between two poses.
//!
//! [`plan_move`] plans a move of a robot (one convex polygon, or the union of convex parts)
//! among fixed convex obstacles (a fixture of parts gives each part) and returns it as time
//! samples that the checker ([`crate::collision`]) certifies.
//!
//! # Motion model
//!
//! * **Poses.** A pose is the position of the robot's origin G (its rotation centre) and an
//!   angle θ; a world vertex is `R(θ)·P + G`. The move turns by the shortest signed angle
//!   `Δθ = angle_between(from.theta, to.theta)`, in (−π, π], so the orientation runs
//!   from `from.theta` to `from.theta + Δθ` (the last sample's θ, equal to `to.theta`
//!   modulo 2π).
//! * **Clearance.** The robot keeps a distance of at least δ from every obstacle. For one
//!   move, each obstacle O is grown into the region G must not enter,
//!   `O ⊕ −(S ⊕ D)`: S contains the robot in every orientation of the move and D the disc
//!   of radius `δ·(1 + clearance_margin)`. Without rotation S is the robot itself and the
//!   growing is exact up to D; with rotation, S is the convex hull of the robot's vertices
//!   at both end orientations and of each vertex sampled every
//!   [`rotation_step`](PlannerOptions::rotation_step) or less along its arc at radius
//!   `|v| / cos(step/2)`, so that the hull circumscribes every arc. D is a 16-gon
//!   circumscribing the disc. G may touch a grown obstacle but not enter its interior;
//!   the margin absorbs the rounding of the construction and of the boundary tests. A
//!   robot of parts P₁ … Pₖ is the union of them, free where each part is: every obstacle
//!   is grown by each part's S in turn (k grown obstacles per obstacle), so the gap between
//!   two fingers stays open where the hull of the robot would close it.
//! * **Path.** If the straight segment from start to goal crosses no grown obstacle it is
//!   the path. Otherwise the path is the fastest one in the visibility graph of the grown
//!   obstacles' vertices, start and goal (built over the obstacles that block the path
//!   found so far, until it crosses no other: the same answer as over all of them), among taut paths (each waypoint wraps an
//!   obstacle corner): an edge may touch a grown obstacle or run along its boundary.
//!   Overlapping grown obstacles are fine; a vertex inside another one is not used.
//!   Where the path wraps a rounded grown obstacle (the clearance polygon, the arcs of a
//!   rotating robot) it has many close waypoints, each a full stop; a run of them is then
//!   replaced by the corner where the segments before and after it meet, whenever that
//!   is faster and the new segments are free.
//! * **Translation.** G stops at every waypoint: each path segment is a rest-to-rest
//!   trapezoidal profile, accelerating at `max_accel` up to `max_speed` (a triangle when
//!   the segment is short; see [`rest_to_rest_time`]). The graph's edge weights are these
//!   times, so the graph search minimises the translation time `T_trans`.
//! * **Rotation.** The angular acceleration is limited to `α = max_accel / radius`, with
//!   `radius` the robot's [`radius`](ConvexPolygon::radius) (its farthest part's), so that no point of the robot
//!   accelerates tangentially by more than `max_accel`; the turn rate is limited to
//!   `max_turn_rate`. The rotation's fastest time is `T_rot = rest_to_rest_time(|Δθ|,
//!   max_turn_rate, α)`.
//! * **Duration.** `T = max(T_trans, T_rot)`. The rotation takes the whole of `[0, T]` as
//!   one trapezoid, at the smallest cruise rate that finishes in time; the translation
//!   takes `[0, T_trans]`, then G rests at the goal while the rotation finishes.
//! * **Samples.** At 0, at `T`, at every phase boundary of every profile (so at every
//!   waypoint), and at [`samples_per_phase`](PlannerOptions::samples_per_phase) − 1
//!   evenly spaced times inside each phase; times closer than 10⁻¹² T are merged. Each
//!   sample carries the exact position, velocity, angle and angular velocity of the
//!   profiles at its time. Between samples the checker interpolates linearly: G stays on
//!   the path segment and θ within the swept range, so the interpolated motion stays
//!   inside the region the planner proved clear.
//! * **Turning apart.** When the move cannot turn on the way (its start or goal too close
//!   to an obstacle for the swept robot, or no path for it), it is planned as three moves
//!   of this model: at the start angle to a turning point, a turn in place there, at the
//!   goal angle to the goal; the fastest over a few turning points (the start, the goal,
//!   rings around them) wins. See `turn_apart.rs`.
//! * **No motion.** When `from` and `to` are the same pose (same position, `Δθ = 0`) the
//!   move lasts 0 and has a single sample, at t = 0 (the start is still checked).
//!
//! ```
//! use workcell::geometry::{ConvexPolygon, Vec2};
//! use workcell::motion::Pose;
//! use workcell::planning::{plan_move, PlannerOptions, RobotLimits};
//! let square = |x: f64, y: f64, h: f64| {
//!     ConvexPolygon::new(&[[x - h, y - h], [x + h, y - h], [x + h, y + h], [x - h, y + h]])
//!         .unwrap()
//!         .0
//! };
//! let robot = square(0.0, 0.0, 0.5);
//! let limits = RobotLimits { max_speed: 1.0, max_accel: 2.0, max_turn_rate: 1.0 };
//! let pose = |x, y| Pose { pos: Vec2::new(x, y), theta: 0.0 };
//! let wall = square(5.0, 0.0, 1.0);
//! let planned = plan_move(&[robot], &limits, &[wall], 0.01, pose(0.0, 0.0), pose(10.0, 0.0),
//!     &PlannerOptions::default()).unwrap();
//! assert!(planned.path.len() > 2); // around the wall
//! assert_eq!(planned.samples.last().unwrap().pos, Vec2::new(10.0, 0.0));
//! ```

mod arm_reach;
mod corners;
mod grown;
mod joint_move;
mod joint_paths;
mod minkowski;
mod plan;
mod sampling;
mod timed;
mod turn_apart;
mod visibility;

pub use crate::motion::rest_to_rest_time;
pub use arm_reach::{ArmModel, Refusal};
pub use joint_move::{joint_move, joint_move_time, JointMove};
pub use joint_paths::{JointPath, JointPathSettings};
pub use timed::{time_primitives, Primitive};
pub use turn_apart::plan_move;

#[cfg(doc)]
use crate::geometry::ConvexPolygon;
use crate::geometry::Vec2;
use crate::motion::{JointSample, Sample};

/// A robot's kinematic limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobotLimits {
    /// Largest speed of G, in length per time unit.
    pub max_speed: f64,
    /// Largest acceleration of G; also bounds the tangential acceleration that rotation
    /// gives the robot's outermost point.
    pub max_accel: f64,
    /// Largest angular speed, in radians per time unit.
    pub max_turn_rate: f64,
}

/// How the planner trades safety margins and sample counts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlannerOptions {
    /// Relative extra clearance: obstacles are grown by `δ·(1 + clearance_margin)`. It pays
    /// for rounding and leaves the checker room to certify; 0 risks rejecting paths that
    /// only touch a grown obstacle. Default 0.02.
    pub clearance_margin: f64,
    /// Samples per profile phase (at least 1): the phase's end plus this many minus one
    /// inside it. Default 4.
    pub samples_per_phase: usize,
    /// Largest angular step, in (0, π/2], at which the vertices' arcs are sampled to build
    /// the swept robot; smaller steps give a tighter shape with more vertices.
    /// Default π/8 (vertices pushed out by at most 2%).
    pub rotation_step: f64,
}

impl Default for PlannerOptions {
    fn default() -> Self {
        PlannerOptions {
            clearance_margin: 0.02,
            samples_per_phase: 4,
            rotation_step: std::f64::consts::PI / 8.0,
        }
    }
}

/// A planned move.
#[derive(Clone, Debug, PartialEq)]
pub struct PlannedMove {
    /// Duration, from rest at the start to rest at the goal.
    pub duration: f64,
    /// Waypoints of G, start and goal included (two points for a straight move, even of
    /// length 0).
    pub path: Vec<Vec2>,
    /// Time samples from 0 to `duration`, strictly increasing, ready for
    /// [`Trajectory::new`](crate::motion::Trajectory::new).
    pub samples: Vec<Sample>,
    /// The rest-to-rest pieces the move is made of, one after the other (three for a move
    /// that turns apart): [`time_primitives`] of them gives these samples again.
    pub primitives: Vec<Primitive>,
    /// For an arm's move, the joint angles and rates at each of `samples`' times: the
    /// motion itself, which the checker certifies (`samples` and `path` then follow the
    /// tool, for pictures, and `primitives` is empty). Empty for a rigid robot.
    pub joints: Vec<JointSample>,
}

/// Why a move could not be planned. Obstacle indices are positions in the slice given.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PlanError {
    /// At the start, the robot (swept over the move's rotation) is closer than the
    /// planning clearance to an obstacle.
    #[error("the start pose is too close to obstacle {obstacle} for the move's rotation")]
    StartBlocked {
        /// Index of the obstacle.
        obstacle: usize,
    },
    /// At the goal, the robot (swept over the move's rotation) is closer than the planning
    /// clearance to an obstacle.
    #[error("the goal pose is too close to obstacle {obstacle} for the move's rotation")]
    GoalBlocked {
        /// Index of the obstacle.
        obstacle: usize,
    },
    /// The obstacles separate the start from the goal.
    #[error("no collision-free path from the start to the goal")]
    NoPath,
    /// A robot limit is not a positive finite number.
    #[error("robot limit `{name}` must be a positive finite number, got {value}")]
    InvalidLimits {
        /// Field name in [`RobotLimits`].
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// δ, a pose or an option is out of range.
    #[error("`{name}` must be {expected}, got {value}")]
    InvalidArgument {
        /// Argument or field name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What is accepted.
        expected: &'static str,
    },
}

/// The shortest signed rotation from angle `from` to angle `to`, in (−π, π].
///
/// ```
/// use workcell::planning::angle_between;
/// use std::f64::consts::PI;
/// assert!((angle_between(0.1, -0.1) + 0.2).abs() < 1e-15);
/// assert!((angle_between(3.0, -3.0) - (2.0 * PI - 6.0)).abs() < 1e-15);
/// assert_eq!(angle_between(0.0, PI), PI);
/// assert_eq!(angle_between(PI, 0.0), PI);
/// ```
pub fn angle_between(from: f64, to: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let d = to - from;
    // Already in range: return it unrounded, so that small turns stay exact.
    if d > -PI && d <= PI {
        return d;
    }
    let r = d.rem_euclid(TAU);
    if r > PI {
        r - TAU
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn angle_between_is_the_short_way_round() {
        assert_eq!(angle_between(1.0, 1.0), 0.0);
        assert!((angle_between(0.0, 3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-15);
        assert!((angle_between(10.0 * PI, 10.0 * PI + 0.5) - 0.5).abs() < 1e-12);
        assert_eq!(angle_between(-1e-300, 0.0), 1e-300);
        assert_eq!(angle_between(1e-300, 0.0), -1e-300);
        let d = angle_between(0.0, -PI);
        assert!(d > 0.0 && (d - PI).abs() < 1e-15);
    }
}
