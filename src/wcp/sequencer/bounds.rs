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
use crate::motion::JointLimits;
use crate::planning::{angle_between, joint_move_time, rest_to_rest_time};
use std::f64::consts::PI;
use std::sync::Arc;

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

/// An arm's joint angles at each of its nodes and its joint limits: its moves' bounds are
/// the straight joint-space moves' times ([`joint_move_time`]), which every path between
/// the same angles takes at least.
#[derive(Clone, Debug, PartialEq)]
pub struct JointNodes {
    /// Per node (0 = home, `1 + t` = task `t`), the joint angles; `None` where the arm
    /// cannot go.
    pub nodes: Vec<Option<Arc<[f64]>>>,
    /// The arm's joint limits.
    pub limits: JointLimits,
}

/// The poses of every node and the robots' limits: a lower bound for every move.
#[derive(Clone, Debug, PartialEq)]
pub struct Bounds {
    limits: Vec<BoundLimits>,
    /// Per robot, its joints' nodes when it is an arm.
    joints: Vec<Option<Arc<JointNodes>>>,
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
            joints: vec![None; limits.len()],
            limits,
            homes,
            tasks,
        }
    }

    /// The same bounds with robot `r` an arm whose moves are bounded in joint space (its
    /// `limits` and home pose are then not used, but for picking tasks near each other).
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::geometry::Vec2;
    /// use workcell::motion::JointLimits;
    /// use workcell::planning::joint_move_time;
    /// use workcell::wcp::sequencer::{BoundLimits, Bounds, JointNodes};
    /// let limits = BoundLimits { max_speed: 1.0, max_accel: 2.0, max_angular_accel: 2.0, max_turn_rate: 1.0 };
    /// let at = |x: f64, y: f64| (Vec2::new(x, y), 0.0);
    /// let joints = JointLimits { range: vec![None], max_speed: vec![1.0], max_accel: vec![1.0] };
    /// let nodes = vec![Some(Arc::from([0.0])), Some(Arc::from([1.0])), None];
    /// let b = Bounds::new(vec![limits], vec![at(0.0, 0.0)], vec![at(1.0, 0.0), at(2.0, 0.0)])
    ///     .with_joints(0, JointNodes { nodes, limits: joints.clone() });
    /// assert_eq!(b.bound(0, 0, 1), joint_move_time(&[0.0], &[1.0], &joints));
    /// assert_eq!(b.bound(0, 0, 2), f64::INFINITY); // a task the arm cannot reach
    /// ```
    pub fn with_joints(mut self, r: usize, joints: JointNodes) -> Bounds {
        self.joints[r] = Some(Arc::new(joints));
        self
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
        if let Some(arm) = &self.joints[r] {
            return match (&arm.nodes[from], &arm.nodes[to]) {
                (Some(a), Some(b)) => joint_move_time(a, b, &arm.limits),
                _ => f64::INFINITY,
            };
        }
        let ((a, ta), (b, tb)) = (self.pose(r, from), self.pose(r, to));
        let l = &self.limits[r];
        // The planner measures the straight segment as `(to − from).norm()`, and the turn
        // from the start's angle to the goal's.
        let trans = rest_to_rest_time((b - a).norm(), l.max_speed, l.max_accel);
        let rot = rest_to_rest_time(angle_between(ta, tb), l.max_turn_rate, l.max_angular_accel);
        trans.max(rot)
    }

    /// A bound at least as long as every bound: the longest straight move (the diagonal of
    /// the box around every pose) with a half-turn, for the slowest robot; for an arm, its
    /// slowest joint across its range.
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
        let rigid = (self.limits.iter().zip(&self.joints)).filter(|(_, j)| j.is_none());
        let rigid = rigid.map(|(l, _)| {
            let trans = rest_to_rest_time(diagonal, l.max_speed, l.max_accel);
            let rot = rest_to_rest_time(PI, l.max_turn_rate, l.max_angular_accel);
            trans.max(rot)
        });
        // An arm's joint turns at most across its range, or half a turn when it is free.
        let arms = self.joints.iter().flatten().map(|arm| {
            let l = &arm.limits;
            (0..l.max_speed.len())
                .map(|j| {
                    let span = l.range[j].map_or(PI, |[lo, hi]| hi - lo);
                    rest_to_rest_time(span, l.max_speed[j], l.max_accel[j])
                })
                .fold(0.0, f64::max)
        });
        rigid.chain(arms).fold(0.0, f64::max)
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
