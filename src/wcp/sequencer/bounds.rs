//! Admissible lower bounds of travel times, from the poses and the robots' limits alone.
//!
//! The bound of a move is the planner's time for the straight, obstacle-free move between the
//! same poses: `max(T_trans(|b − a|), T_rot(|Δθ|))` with the planner's own profiles
//! ([`rest_to_rest_time`]) and rotation limits (`α = max_accel / radius`). It is never above
//! the planned time:
//! * a planned path is a chain of segments at least as long as the straight one, each a
//!   rest-to-rest profile; the profile's time is increasing and concave in the length with
//!   value 0 at 0 (`2·√(d/a)`, then `d/v + v/a`), hence subadditive, so the chain takes at
//!   least `T_trans` of the straight distance;
//! * every plan turns by the same shortest angle Δθ, at most as fast, so it takes at least
//!   `T_rot`; a move turned apart (translate, turn in place, translate) takes the sum.
//!
//! Without obstacles in the way the bound is the planned time, bit for bit: the planner times
//! the straight move with the same operations.

use super::terms::node_task;
use crate::geometry::Vec2;
use crate::planning::{angle_between, rest_to_rest_time};

/// One robot's limits as the bounds need them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundLimits {
    /// Largest speed of G.
    pub max_speed: f64,
    /// Largest acceleration of G.
    pub max_accel: f64,
    /// Largest angular acceleration: `max_accel / radius`, as the planner takes it.
    pub max_angular_accel: f64,
    /// Largest angular speed.
    pub max_turn_rate: f64,
}

/// The poses of every node and the robots' limits: a lower bound for every move.
#[derive(Clone, Debug, PartialEq)]
pub struct Bounds {
    limits: Vec<BoundLimits>,
    /// Per robot, its home `(position, θ)`.
    homes: Vec<(Vec2, f64)>,
    /// Per task, its pose.
    tasks: Vec<(Vec2, f64)>,
}

impl Bounds {
    /// Bounds for robots with these limits and homes, and these task poses.
    ///
    /// ```
    /// use workcell::geometry::Vec2;
    /// use workcell::wcp::sequencer::{BoundLimits, Bounds};
    /// use workcell::planning::rest_to_rest_time;
    /// // One robot at the origin, tasks at (3, 4) and (6, 8), nothing turning.
    /// let limits = BoundLimits { max_speed: 1.0, max_accel: 2.0, max_angular_accel: 2.0, max_turn_rate: 1.0 };
    /// let at = |x: f64, y: f64| (Vec2::new(x, y), 0.0);
    /// let b = Bounds::new(vec![limits], vec![at(0.0, 0.0)], vec![at(3.0, 4.0), at(6.0, 8.0)]);
    /// assert_eq!((b.robots(), b.tasks()), (1, 2));
    /// assert_eq!(b.bound(0, 0, 1), rest_to_rest_time(5.0, 1.0, 2.0));
    /// ```
    pub fn new(limits: Vec<BoundLimits>, homes: Vec<(Vec2, f64)>, tasks: Vec<(Vec2, f64)>) -> Self {
        assert_eq!(limits.len(), homes.len(), "one home per robot");
        Bounds {
            limits,
            homes,
            tasks,
        }
    }

    /// Number of robots.
    pub fn robots(&self) -> usize {
        self.limits.len()
    }

    /// Number of tasks.
    pub fn tasks(&self) -> usize {
        self.tasks.len()
    }

    /// Pose of node `node` (0 = home, `1 + t` = task `t`) for robot `r`.
    ///
    /// ```
    /// use workcell::geometry::Vec2;
    /// use workcell::wcp::sequencer::{BoundLimits, Bounds};
    /// let limits = BoundLimits { max_speed: 1.0, max_accel: 2.0, max_angular_accel: 2.0, max_turn_rate: 1.0 };
    /// let at = |x: f64, y: f64| (Vec2::new(x, y), 0.0);
    /// let b = Bounds::new(vec![limits], vec![at(0.0, 0.0)], vec![at(3.0, 4.0), at(6.0, 8.0)]);
    /// assert_eq!(b.pose(0, 0), at(0.0, 0.0)); // the home
    /// assert_eq!(b.pose(0, 2), at(6.0, 8.0)); // task 1
    /// ```
    #[inline]
    pub fn pose(&self, r: usize, node: usize) -> (Vec2, f64) {
        match node {
            0 => self.homes[r],
            n => self.tasks[node_task(n)],
        }
    }

    /// Lower bound of robot `r`'s move from node `from` to node `to`.
    ///
    /// ```
    /// use workcell::geometry::Vec2;
    /// use workcell::wcp::sequencer::{BoundLimits, Bounds};
    /// use workcell::planning::rest_to_rest_time;
    /// let limits = BoundLimits { max_speed: 1.0, max_accel: 2.0, max_angular_accel: 2.0, max_turn_rate: 1.0 };
    /// let at = |x: f64, y: f64| (Vec2::new(x, y), 0.0);
    /// let b = Bounds::new(vec![limits], vec![at(0.0, 0.0)], vec![at(3.0, 4.0), at(6.0, 8.0)]);
    /// assert_eq!(b.bound(0, 1, 2), rest_to_rest_time(5.0, 1.0, 2.0));
    /// assert_eq!(b.bound(0, 2, 1), b.bound(0, 1, 2));
    /// assert!(b.bound(0, 0, 2) > b.bound(0, 0, 1));
    /// ```
    #[inline]
    pub fn bound(&self, r: usize, from: usize, to: usize) -> f64 {
        let ((a, ta), (b, tb)) = (self.pose(r, from), self.pose(r, to));
        let l = &self.limits[r];
        // The planner measures the straight segment as `(to − from).norm()`, and the turn
        // from the start's angle to the goal's.
        let trans = rest_to_rest_time((b - a).norm(), l.max_speed, l.max_accel);
        let rot = rest_to_rest_time(angle_between(ta, tb), l.max_turn_rate, l.max_angular_accel);
        trans.max(rot)
    }

    /// A bound at least as long as every bound: the longest straight move (the diagonal of
    /// the box around every pose) with a half-turn, for the slowest robot.
    ///
    /// ```
    /// use workcell::geometry::Vec2;
    /// use workcell::wcp::sequencer::{BoundLimits, Bounds};
    /// let limits = BoundLimits { max_speed: 1.0, max_accel: 2.0, max_angular_accel: 2.0, max_turn_rate: 1.0 };
    /// let at = |x: f64, y: f64| (Vec2::new(x, y), 0.0);
    /// let b = Bounds::new(vec![limits], vec![at(0.0, 0.0)], vec![at(3.0, 4.0), at(6.0, 8.0)]);
    /// assert!((0..3).all(|x| (0..3).all(|y| b.bound(0, x, y) <= b.longest())));
    /// ```
    pub fn longest(&self) -> f64 {
        let poses = self.homes.iter().chain(&self.tasks).map(|p| p.0);
        let (lo, hi) = poses.fold(
            (Vec2::repeat(f64::INFINITY), Vec2::repeat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.inf(&p), hi.sup(&p)),
        );
        let diagonal = if lo.x <= hi.x { (hi - lo).norm() } else { 0.0 };
        self.limits
            .iter()
            .map(|l| {
                let trans = rest_to_rest_time(diagonal, l.max_speed, l.max_accel);
                let rot =
                    rest_to_rest_time(std::f64::consts::PI, l.max_turn_rate, l.max_angular_accel);
                trans.max(rot)
            })
            .fold(0.0, f64::max)
    }

    /// Position of task `t`.
    ///
    /// ```
    /// use workcell::geometry::Vec2;
    /// use workcell::wcp::sequencer::{BoundLimits, Bounds};
    /// let limits = BoundLimits { max_speed: 1.0, max_accel: 2.0, max_angular_accel: 2.0, max_turn_rate: 1.0 };
    /// let at = |x: f64, y: f64| (Vec2::new(x, y), 0.0);
    /// let b = Bounds::new(vec![limits], vec![at(0.0, 0.0)], vec![at(3.0, 4.0), at(6.0, 8.0)]);
    /// assert_eq!(b.task_position(1), Vec2::new(6.0, 8.0));
    /// ```
    #[inline]
    pub fn task_position(&self, t: usize) -> Vec2 {
        self.tasks[t].0
    }

    /// Distance between the positions of two tasks.
    ///
    /// ```
    /// use workcell::geometry::Vec2;
    /// use workcell::wcp::sequencer::{BoundLimits, Bounds};
    /// let limits = BoundLimits { max_speed: 1.0, max_accel: 2.0, max_angular_accel: 2.0, max_turn_rate: 1.0 };
    /// let at = |x: f64, y: f64| (Vec2::new(x, y), 0.0);
    /// let b = Bounds::new(vec![limits], vec![at(0.0, 0.0)], vec![at(3.0, 4.0), at(6.0, 8.0)]);
    /// assert_eq!(b.task_distance(0, 1), 5.0);
    /// ```
    #[inline]
    pub fn task_distance(&self, a: usize, b: usize) -> f64 {
        (self.tasks[a].0 - self.tasks[b].0).norm()
    }
}
