//! One robot's timed plan: what it does when ([`Activity`] over a [`Segment`]), the waits
//! added before its moves ([`Delay`]), the nodes of a route, and its samples
//! ([`RobotSchedule`], read back by pose and by segment).

use crate::cell::{Cell, CellRobot, RobotKind};
use crate::geometry::{ConvexPolygon, Vec2};
use crate::motion::{JointSample, Pose, Sample};
use crate::wcp::legs::{default_legs, leg, with_leg, Leg, Legs};
use crate::wcp::moves::node_name;
use crate::wcp::sequencer::Step;
use std::sync::Arc;

/// What a robot does during a segment of its schedule. Nodes are robot-local: 0 is home,
/// `1 + t` is task `t`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Activity {
    /// Moving between two nodes.
    Move {
        /// Where the move starts.
        from: usize,
        /// Where it ends.
        to: usize,
    },
    /// Doing task `.0` (index into the cell's tasks) for its duration.
    Work(usize),
    /// Waiting at a node before moving on: a delay added by the feedback loop.
    Wait(usize),
    /// Holding still at a point of the move between two nodes, for another robot to pass.
    Pause {
        /// Where the move starts.
        from: usize,
        /// Where it ends.
        to: usize,
    },
    /// Parked out of another robot's way, on the way between two nodes.
    Park {
        /// Where the move starts.
        from: usize,
        /// Where it ends.
        to: usize,
    },
    /// At home after the last move, until the end of time.
    Done,
}

impl Activity {
    /// The sequencer's step for this activity.
    ///
    /// ```
    /// use workcell::wcp::sequencer::Step;
    /// use workcell::wcp::Activity;
    /// assert_eq!(Activity::Work(2).step(), Step::Stay { node: 3 }); // task 2 is node 3
    /// assert_eq!(Activity::Pause { from: 0, to: 3 }.step(), Step::Move { from: 0, to: 3 });
    /// ```
    pub fn step(self) -> Step {
        match self {
            Activity::Move { from, to }
            | Activity::Pause { from, to }
            | Activity::Park { from, to } => Step::Move { from, to },
            Activity::Work(t) => Step::Stay { node: t + 1 },
            Activity::Wait(node) => Step::Stay { node },
            Activity::Done => Step::Stay { node: 0 },
        }
    }

    /// Human description, e.g. `move weld-1 -> weld-4`.
    ///
    /// ```
    /// use workcell::wcp::Activity;
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// assert_eq!(Activity::Move { from: 0, to: 4 }.describe(&cell, 1), "move home -> weld-4");
    /// assert_eq!(Activity::Work(0).describe(&cell, 0), "task weld-1");
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn describe(self, cell: &Cell, r: usize) -> String {
        match self {
            // A robot without tasks may leave home out of another's way and come back.
            Activity::Move { from: 0, to: 0 } => "excursion from home".to_owned(),
            Activity::Move { from, to } => {
                format!("move {} -> {}", place(cell, r, from), place(cell, r, to))
            }
            Activity::Work(t) => format!("task {}", cell.tasks[t].name),
            Activity::Wait(node) => format!("wait at {}", place(cell, r, node)),
            Activity::Pause { from, to } => {
                format!("pause on {}", Activity::Move { from, to }.describe(cell, r))
            }
            Activity::Park { from, to } => {
                format!(
                    "parked aside on {}",
                    Activity::Move { from, to }.describe(cell, r)
                )
            }
            Activity::Done => "back home".to_owned(),
        }
    }
}

/// `home` or the task's name: how people call a node in sentences.
fn place(cell: &Cell, r: usize, node: usize) -> &str {
    if node == 0 {
        "home"
    } else {
        node_name(cell, r, node)
    }
}

/// One activity of one robot over `[start, end]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// What the robot does.
    pub activity: Activity,
    /// When it starts.
    pub start: f64,
    /// When it ends (infinite for [`Activity::Done`]).
    pub end: f64,
    /// The leg (move of the route, 0 out of home) this segment belongs to: the leg itself
    /// (its wait, motion, pauses), or the leg that led into the task. A wait at that leg's
    /// start pushes this segment later. `None` once the robot is done.
    pub leg: Option<usize>,
}

/// A wait inserted before one of a robot's moves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Delay {
    /// The robot that waits.
    pub robot: usize,
    /// Index of the move it waits before (0: the move out of home).
    pub before_move: usize,
    /// That move's source and target nodes, for reports.
    pub nodes: (usize, usize),
    /// How long it waits.
    pub duration: f64,
}

impl Delay {
    /// The waits of `legs` on the routes `routes`, robot by robot, leg by leg.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::wcp::legs::{default_legs, with_leg, Leg};
    /// use workcell::wcp::Delay;
    /// let routes = [vec![0, 2], vec![3, 1]];
    /// // R2 waits 1.5 before its second move (weld-4 -> weld-2, nodes 4 -> 2).
    /// let legs = with_leg(&default_legs(2), 1, 1, Leg { wait: 1.5, ..Leg::DEFAULT });
    /// let delays = Delay::of_legs(&routes, &legs);
    /// assert_eq!(delays.len(), 1);
    /// assert_eq!((delays[0].robot, delays[0].before_move, delays[0].nodes, delays[0].duration), (1, 1, (4, 2), 1.5));
    /// assert_eq!(Delay::legs(2, &delays), legs);
    /// # let _: Vec<Arc<Vec<Leg>>> = legs;
    /// ```
    pub fn of_legs(routes: &[Vec<usize>], legs: &[Arc<Vec<Leg>>]) -> Vec<Delay> {
        let mut out = Vec::new();
        for (r, list) in legs.iter().enumerate() {
            let nodes = route_nodes(routes.get(r).map_or(&[][..], Vec::as_slice));
            for (m, leg) in list.iter().enumerate().filter(|(_, l)| l.wait > 0.0) {
                out.push(Delay {
                    robot: r,
                    before_move: m,
                    nodes: (nodes[m], nodes[(m + 1).min(nodes.len() - 1)]),
                    duration: leg.wait,
                });
            }
        }
        out
    }

    /// Legs with these waits, each added to its leg's wait, and nothing else changed.
    ///
    /// ```
    /// use workcell::wcp::legs::leg;
    /// use workcell::wcp::Delay;
    /// let wait = Delay { robot: 0, before_move: 2, nodes: (3, 0), duration: 0.5 };
    /// let legs = Delay::legs(2, &[wait, wait]); // waits at the same leg add up
    /// assert_eq!(leg(&legs, 0, 2).wait, 1.0);
    /// assert!(leg(&legs, 0, 1).is_default() && leg(&legs, 1, 0).is_default());
    /// ```
    pub fn legs(robots: usize, delays: &[Delay]) -> Legs {
        let mut legs = default_legs(robots);
        for d in delays {
            let old = leg(&legs, d.robot, d.before_move).clone();
            let new = Leg {
                wait: old.wait + d.duration,
                ..old
            };
            legs = with_leg(&legs, d.robot, d.before_move, new);
        }
        legs
    }
}

/// The nodes a route visits: home, its tasks (`1 + t`), home; home twice for no task (its
/// one leg, home to home, is the excursion a remedy may give it).
///
/// ```
/// use workcell::wcp::route_nodes;
/// assert_eq!(route_nodes(&[2, 0]), [0, 3, 1, 0]);
/// assert_eq!(route_nodes(&[]), [0, 0]);
/// ```
pub fn route_nodes(route: &[usize]) -> Vec<usize> {
    if route.is_empty() {
        return vec![0, 0];
    }
    std::iter::once(0)
        .chain(route.iter().map(|t| t + 1))
        .chain([0])
        .collect()
}

/// One robot's timed plan.
#[derive(Clone, Debug)]
pub struct RobotSchedule {
    /// Its tasks in order.
    pub route: Vec<usize>,
    /// Its activities in time order, ending with [`Activity::Done`].
    pub segments: Vec<Segment>,
    /// Its trajectory: starts at home at t = 0, ends at home (for an arm, its tool's).
    pub samples: Vec<Sample>,
    /// An arm's joint angles and rates at the times of `samples`: what the checker checks.
    /// Empty for a rigid robot.
    pub joints: Vec<JointSample>,
    /// The path of G (waypoints of the moves), for pictures.
    pub path: Vec<Vec2>,
    /// When it is back home.
    pub end: f64,
}

impl RobotSchedule {
    /// The pose at time `t`, interpolated as the checker interpolates it.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{node_pose, MoveStore, RobotSchedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let r1 = RobotSchedule::build(&cell, 0, &[0], &[], &store).unwrap();
    /// assert_eq!(r1.pose_at(0.0), cell.rigid(0).home);
    /// let at_weld = r1.segments[1].start; // after the move out
    /// assert_eq!(r1.pose_at(at_weld).pos, node_pose(&cell, 0, 1).pos);
    /// assert_eq!(r1.pose_at(r1.end + 5.0), cell.rigid(0).home);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn pose_at(&self, t: f64) -> Pose {
        interpolate(&self.samples, self.samples.partition_point(|p| p.t <= t), t)
    }

    /// The robot's convex pieces placed as at time `t` (as the checker interpolates): its
    /// body at [`RobotSchedule::pose_at`], or an arm's links at its joints then.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{MoveStore, RobotSchedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let r1 = RobotSchedule::build(&cell, 0, &[0], &[], &store).unwrap();
    /// assert_eq!(r1.placed(&cell.robots[0], 0.0), cell.robots[0].at_home());
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn placed<'a>(&self, robot: &'a CellRobot, t: f64) -> Vec<(&'a [ConvexPolygon], Pose)> {
        match &robot.kind {
            RobotKind::Rigid(rigid) => vec![(rigid.pieces(), self.pose_at(t))],
            RobotKind::Arm(arm) => arm.placed(&self.q_at(t)),
        }
    }

    /// An arm's joint angles at time `t`, interpolated linearly as the checker does (empty
    /// for a rigid robot).
    ///
    /// ```
    /// use workcell::wcp::{prepare, solve, SolveOptions};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/scara-cell.json").as_ref())?.cell;
    /// let opts = SolveOptions::default();
    /// let solved = solve(&cell, &prepare(&cell, &opts, &())?, &opts, &())?;
    /// let a1 = &solved.schedule.robots[0];
    /// assert_eq!(a1.q_at(0.0), cell.robots[0].as_arm().unwrap().home);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn q_at(&self, t: f64) -> Vec<f64> {
        joints_at(&self.joints, t)
    }

    /// The segment under way at time `t`.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{Activity, MoveStore, RobotSchedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let r1 = RobotSchedule::build(&cell, 0, &[0], &[], &store).unwrap();
    /// let at_weld = r1.segments[1].start;
    /// assert_eq!(r1.segment_at(at_weld / 2.0).activity, Activity::Move { from: 0, to: 1 });
    /// assert_eq!(r1.segment_at(at_weld + 0.6).activity, Activity::Work(0)); // weld-1 lasts 1.2
    /// assert_eq!(r1.segment_at(r1.end + 1.0).activity, Activity::Done);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn segment_at(&self, t: f64) -> &Segment {
        let k = self.segments.partition_point(|s| s.end <= t);
        &self.segments[k.min(self.segments.len() - 1)]
    }

    /// When the robot has left the place of its segment `seg`: the end of `seg` for a move;
    /// for a robot standing there (working or waiting), the end of the move that next takes
    /// it away; never (infinite) once it is done or when no move follows. Waiting only until
    /// it stops standing there would start both robots at once, at the same spot.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{MoveStore, RobotSchedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let r1 = RobotSchedule::build(&cell, 0, &[0], &[], &store).unwrap();
    /// let (out, work, back) = (&r1.segments[0], &r1.segments[1], &r1.segments[2]);
    /// assert_eq!(r1.left(out), out.end); // a move is over at its end
    /// assert_eq!(r1.left(work), back.end); // at the task until the move home is over
    /// assert_eq!(r1.left(r1.segments.last().unwrap()), f64::INFINITY); // home for good
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn left(&self, seg: &Segment) -> f64 {
        match seg.activity {
            Activity::Move { .. } => seg.end,
            Activity::Done => f64::INFINITY,
            _ => self
                .segments
                .iter()
                .skip_while(|g| g.start < seg.end)
                .find(|g| matches!(g.activity, Activity::Move { .. }))
                .map_or(f64::INFINITY, |g| g.end),
        }
    }
}

/// The joint angles of `joints` at time `t`, interpolated linearly as the checker does
/// (held before the first sample and after the last; empty for no samples).
pub(crate) fn joints_at(joints: &[JointSample], t: f64) -> Vec<f64> {
    let s = joints;
    let k = s.partition_point(|p| p.t <= t);
    match k {
        _ if s.is_empty() => Vec::new(),
        0 => s[0].q.clone(),
        k if k == s.len() => s[k - 1].q.clone(),
        k => {
            let (p, q) = (&s[k - 1], &s[k]);
            let u = (t - p.t) / (q.t - p.t);
            (p.q.iter().zip(&q.q))
                .map(|(a, b)| a + (b - a) * u)
                .collect()
        }
    }
}

/// The pose at `t` between samples `k - 1` and `k`, `k` the first sample after `t` (the first
/// or last pose outside the samples).
fn interpolate(s: &[Sample], k: usize, t: f64) -> Pose {
    if k == 0 {
        return Pose {
            pos: s[0].pos,
            theta: s[0].theta,
        };
    }
    if k == s.len() {
        let l = &s[s.len() - 1];
        return Pose {
            pos: l.pos,
            theta: l.theta,
        };
    }
    let (p, q) = (&s[k - 1], &s[k]);
    let u = (t - p.t) / (q.t - p.t);
    Pose {
        pos: p.pos + (q.pos - p.pos) * u,
        theta: p.theta + (q.theta - p.theta) * u,
    }
}

/// [`RobotSchedule::pose_at`] at times that never go back: the sample after the last time
/// asked is kept, so a walk over another robot's sample instants steps instead of
/// searching the whole schedule each time.
pub(crate) struct PoseCursor<'a> {
    samples: &'a [Sample],
    k: usize,
}

impl<'a> PoseCursor<'a> {
    /// A cursor for `schedule` at times from `t0` on.
    pub(crate) fn new(schedule: &'a RobotSchedule, t0: f64) -> Self {
        let samples = &schedule.samples[..];
        let k = samples.partition_point(|p| p.t <= t0);
        PoseCursor { samples, k }
    }

    /// The pose at `t`, exactly as [`RobotSchedule::pose_at`] gives it; `t` at least the
    /// last time asked (and `t0`).
    pub(crate) fn at(&mut self, t: f64) -> Pose {
        debug_assert!(
            self.k == 0 || self.samples[self.k - 1].t <= t,
            "times go back"
        );
        while self.samples.get(self.k).is_some_and(|p| p.t <= t) {
            self.k += 1;
        }
        interpolate(self.samples, self.k, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planning::PlannerOptions;
    use crate::wcp::MoveStore;

    /// The cursor poses the robot exactly as `pose_at` does: at, between, before and after
    /// the samples, and when asked the same time twice.
    #[test]
    fn cursor_poses_as_pose_at() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
        let cell = crate::cell::load_cell(path.as_ref()).unwrap().cell;
        let store = MoveStore::new(&cell, &PlannerOptions::default());
        let s = RobotSchedule::build(&cell, 0, &[0], &[], &store).unwrap();
        let mut times: Vec<f64> = (s.samples.windows(2))
            .flat_map(|w| [w[0].t, w[0].t, 0.5 * (w[0].t + w[1].t)])
            .chain([-1.0, s.end, s.end + 3.0])
            .collect();
        times.sort_by(f64::total_cmp);
        for t0 in [-1.0, 0.5 * s.end] {
            let mut cursor = PoseCursor::new(&s, t0);
            for &t in times.iter().filter(|&&t| t >= t0) {
                assert_eq!(cursor.at(t), s.pose_at(t), "at t = {t}");
            }
        }
        assert!(times.len() > 20);
    }
}
