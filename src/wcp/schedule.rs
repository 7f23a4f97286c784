//! The timed schedule: every robot's moves, waits and tasks, sampled into trajectories.

use super::legs::{default_legs, leg, with_leg, HoldReason, Leg, Legs, Piece};
use super::moves::{node_name, node_pose, MoveFailure, MoveStore};
use super::sequencer::Step;
use crate::cell::Cell;
use crate::collision::{Body, CheckReport, Scene};
use crate::geometry::{closest_features, Posed, Vec2, WalkTolerances};
use crate::motion::{Pose, Sample, Trajectory};
use crate::planning::PlannedMove;
use std::f64::consts::TAU;
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
    /// Its trajectory: starts at home at t = 0, ends at home.
    pub samples: Vec<Sample>,
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
    /// assert_eq!(r1.pose_at(0.0), cell.robots[0].home);
    /// let at_weld = r1.segments[1].start; // after the move out
    /// assert_eq!(r1.pose_at(at_weld).pos, node_pose(&cell, 0, 1).pos);
    /// assert_eq!(r1.pose_at(r1.end + 5.0), cell.robots[0].home);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn pose_at(&self, t: f64) -> Pose {
        let s = &self.samples;
        let k = s.partition_point(|p| p.t <= t);
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
}

/// The timed schedule of every robot.
#[derive(Clone, Debug)]
pub struct Schedule {
    /// One per robot, in the cell's order (shared between schedules that differ in other
    /// robots only).
    pub robots: Vec<Arc<RobotSchedule>>,
    /// When the last robot is back home.
    pub makespan: f64,
}

/// Why a schedule cannot be built.
#[derive(Clone, Debug, PartialEq)]
pub enum BuildError {
    /// A robot has no certified move between two of its nodes.
    Move {
        /// The robot.
        robot: usize,
        /// The move's source node.
        from: usize,
        /// Its target node.
        to: usize,
        /// Why.
        why: MoveFailure,
    },
    /// A changed leg's motion does not start where the robot is, or the leg does not end at
    /// its end node.
    Discontinuous {
        /// The robot.
        robot: usize,
        /// The leg.
        leg: usize,
        /// When the robot would jump.
        time: f64,
    },
    /// At time `time`, f64 can no longer tell a robot's samples apart: durations and limits
    /// span too many orders of magnitude for one time axis.
    Precision {
        /// The robot.
        robot: usize,
        /// Where its samples merge.
        time: f64,
    },
}

impl BuildError {
    /// The robot concerned.
    pub fn robot(&self) -> usize {
        match self {
            BuildError::Move { robot, .. }
            | BuildError::Precision { robot, .. }
            | BuildError::Discontinuous { robot, .. } => *robot,
        }
    }

    /// Why, in words.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::legs::{default_legs, with_leg, Leg, Piece};
    /// use workcell::wcp::{BuildError, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// // R2's first leg replaced by R1's move out of its home, far from R2.
    /// let wrong = [Piece::Go { motion: store.get(0, 0, 1).unwrap(), scale: 1.0 }];
    /// let legs = with_leg(&default_legs(2), 1, 0, Leg { wait: 0.0, pieces: Some(Arc::from(wrong)) });
    /// let e = Schedule::build(&cell, &[vec![0], vec![1]], &legs, &store).unwrap_err();
    /// assert!(matches!(e, BuildError::Discontinuous { robot: 1, leg: 0, .. }));
    /// assert!(e.reason(&cell).starts_with("its move 0 is not continuous"));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn reason(&self, cell: &Cell) -> String {
        match self {
            BuildError::Move {
                robot,
                from,
                to,
                why,
            } => format!(
                "{} cannot move from {} to {}: {why}",
                cell.robots[*robot].name,
                node_name(cell, *robot, *from),
                node_name(cell, *robot, *to)
            ),
            BuildError::Discontinuous { leg, time, .. } => format!(
                "its move {leg} is not continuous at t = {time}: each motion must start where \
                 the robot is (same position, same angle up to whole turns) and the move must \
                 end at its end node"
            ),
            BuildError::Precision { time, .. } => format!(
                "at t = {time:e} the time steps of its moves fall below what f64 resolves there \
                 ({:e}): task durations, waits and move times span too many orders of \
                 magnitude; rescale the time unit or the limits",
                time.abs() * f64::EPSILON
            ),
        }
    }
}

impl Schedule {
    /// Times every robot's route: from home at t = 0, each leg (by default the planned
    /// move, at once; see [`Leg`]), each task held for its duration, back home. The moves
    /// come from the store (planned there if they were not yet).
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{legs::default_legs, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let routes = [vec![0, 2], vec![3, 1]];
    /// let schedule = Schedule::build(&cell, &routes, &default_legs(2), &store).unwrap();
    /// assert_eq!(schedule.robots[1].route, [3, 1]);
    /// assert_eq!(schedule.makespan, schedule.robots[0].end.max(schedule.robots[1].end));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn build(
        cell: &Cell,
        routes: &[Vec<usize>],
        legs: &[Arc<Vec<Leg>>],
        moves: &MoveStore,
    ) -> Result<Schedule, BuildError> {
        let robots = (0..routes.len())
            .map(|r| {
                let list = legs.get(r).map_or(&[][..], |l| l.as_slice());
                RobotSchedule::build(cell, r, &routes[r], list, moves).map(Arc::new)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Schedule::of(robots))
    }

    /// The schedule of these robot schedules, in robot order.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{MoveStore, RobotSchedule, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let r1 = RobotSchedule::build(&cell, 0, &[0, 1], &[], &store).unwrap();
    /// let r2 = RobotSchedule::build(&cell, 1, &[2, 3], &[], &store).unwrap();
    /// let (e1, e2) = (r1.end, r2.end);
    /// let schedule = Schedule::of(vec![Arc::new(r1), Arc::new(r2)]);
    /// assert_eq!(schedule.makespan, e1.max(e2));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn of(robots: Vec<Arc<RobotSchedule>>) -> Schedule {
        let makespan = robots.iter().map(|s| s.end).fold(0.0, f64::max);
        Schedule { robots, makespan }
    }

    /// The schedule as a scene for the checker (and `--export-scene`): robots with their
    /// trajectories, then the obstacles.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{legs::default_legs, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let schedule = Schedule::build(&cell, &[vec![0, 1], vec![2, 3]], &default_legs(2), &store).unwrap();
    /// let scene = schedule.scene(&cell);
    /// let names: Vec<&str> = scene.bodies.iter().map(|b| b.name.as_str()).collect();
    /// assert_eq!(names, ["R1", "R2", "fixture"]);
    /// assert_eq!((scene.delta, scene.horizon()), (cell.delta, (0.0, schedule.makespan)));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn scene(&self, cell: &Cell) -> Scene {
        let robots = (0..self.robots.len()).map(|r| self.body(cell, r));
        Scene {
            delta: cell.delta,
            bodies: robots.chain(cell.obstacle_bodies()).collect(),
        }
    }

    /// Robots `a` and `b` alone: the scene of one pair.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{legs::default_legs, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let schedule = Schedule::build(&cell, &[vec![0, 1], vec![2, 3]], &default_legs(2), &store).unwrap();
    /// let pair = schedule.pair_scene(&cell, 1, 0);
    /// let names: Vec<&str> = pair.bodies.iter().map(|b| b.name.as_str()).collect();
    /// assert_eq!(names, ["R2", "R1"]); // no fixture
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn pair_scene(&self, cell: &Cell, a: usize, b: usize) -> Scene {
        Scene {
            delta: cell.delta,
            bodies: vec![self.body(cell, a), self.body(cell, b)],
        }
    }

    fn body(&self, cell: &Cell, r: usize) -> Body {
        Body::robot(
            cell.robots[r].name.clone(),
            cell.robots[r].shape.clone(),
            Trajectory::new(self.robots[r].samples.clone())
                .expect("schedules sample increasing times"),
        )
    }

    /// The first collision of a check of [`Schedule::scene`], located in the schedule.
    ///
    /// ```
    /// use workcell::collision::{check, CheckOptions};
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{legs::default_legs, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// // Welds 2 and 4 lie too close for R1 and R2 at once.
    /// let routes = [vec![1, 0, 2], vec![3]];
    /// let schedule = Schedule::build(&cell, &routes, &default_legs(2), &store).unwrap();
    /// let report = check(&schedule.scene(&cell), &CheckOptions::default());
    /// let c = schedule.collision(&cell, &report).expect("a collision");
    /// assert_eq!((c.robots, c.bodies.clone()), ((0, Some(1)), ["R1".into(), "R2".into()]));
    /// assert!(c.segments.0.start <= c.time && c.time <= c.segments.0.end);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn collision(&self, cell: &Cell, report: &CheckReport) -> Option<Collision> {
        let contact = report.first_contact.as_ref()?;
        let robot = |name: &str| cell.robots.iter().position(|r| r.name == name);
        let a = robot(&contact.bodies[0]).expect("the checker names a robot first");
        let b = robot(&contact.bodies[1]);
        let shape_a = &cell.robots[a].shape;
        let pose_a = self.robots[a].pose_at(contact.time);
        let (shape_b, pose_b) = match b {
            Some(b) => (&cell.robots[b].shape, self.robots[b].pose_at(contact.time)),
            None => {
                let o = cell
                    .obstacles
                    .iter()
                    .find(|o| o.name == contact.bodies[1])?;
                (
                    &o.shape,
                    Pose {
                        pos: Vec2::zeros(),
                        theta: 0.0,
                    },
                )
            }
        };
        let posed = |s, p: Pose| Posed::new(s, p.pos.x, p.pos.y, p.theta);
        let d = closest_features(
            &posed(shape_a, pose_a),
            &posed(shape_b, pose_b),
            None,
            &WalkTolerances::default(),
        );
        Some(Collision {
            time: contact.time,
            bodies: contact.bodies.clone(),
            robots: (a, b),
            segments: (
                *self.robots[a].segment_at(contact.time),
                b.map(|b| *self.robots[b].segment_at(contact.time)),
            ),
            point: (d.point_a + d.point_b) / 2.0,
        })
    }
}

/// Where and when two bodies of a schedule first come closer than δ.
#[derive(Clone, Debug, PartialEq)]
pub struct Collision {
    /// Time of the first contact.
    pub time: f64,
    /// The two bodies, robot first.
    pub bodies: [String; 2],
    /// The robot, and the other robot (`None` for an obstacle).
    pub robots: (usize, Option<usize>),
    /// What each robot was doing.
    pub segments: (Segment, Option<Segment>),
    /// Midpoint of the closest points at that time.
    pub point: Vec2,
}

impl RobotSchedule {
    /// Times robot `r`'s route with its legs (missing ones default): from home at t = 0,
    /// every leg, every task held for its duration, back home. A robot without tasks stays
    /// home, unless its one leg is an excursion from home to home.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{Activity, MoveStore, RobotSchedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// // R1 does weld-1: out, the weld, back, then done.
    /// let r1 = RobotSchedule::build(&cell, 0, &[0], &[], &store).unwrap();
    /// let kinds: Vec<Activity> = r1.segments.iter().map(|s| s.activity).collect();
    /// assert_eq!(kinds, [Activity::Move { from: 0, to: 1 }, Activity::Work(0), Activity::Move { from: 1, to: 0 }, Activity::Done]);
    /// assert_eq!(r1.end, 2.0 * store.duration(0, 0, 1).unwrap() + 1.2);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn build(
        cell: &Cell,
        r: usize,
        route: &[usize],
        legs: &[Leg],
        moves: &MoveStore,
    ) -> Result<RobotSchedule, BuildError> {
        let mut line = Timeline::start(cell, r);
        let nodes = route_nodes(route);
        let leg_count = if route.is_empty() {
            legs.len().min(1)
        } else {
            nodes.len() - 1
        };
        for m in 0..leg_count {
            let (from, to) = (nodes[m], nodes[m + 1]);
            let leg = legs.get(m).unwrap_or(&Leg::DEFAULT);
            line.wait(leg.wait, Activity::Wait(from), m)?;
            match &leg.pieces {
                None => {
                    let planned = moves.get(r, from, to).map_err(|why| BuildError::Move {
                        robot: r,
                        from,
                        to,
                        why,
                    })?;
                    line.go(&planned, Activity::Move { from, to }, m)?;
                }
                Some(pieces) => {
                    for piece in pieces.iter() {
                        match piece {
                            Piece::Go { motion, scale } if *scale == 1.0 => {
                                line.go(motion, Activity::Move { from, to }, m)?
                            }
                            Piece::Go { motion, scale } => {
                                line.go(&motion.slowed(*scale), Activity::Move { from, to }, m)?
                            }
                            Piece::Hold { duration, reason } => {
                                let activity = match reason {
                                    HoldReason::Pause => Activity::Pause { from, to },
                                    HoldReason::Park => Activity::Park { from, to },
                                };
                                line.wait(*duration, activity, m)?;
                            }
                        }
                    }
                }
            }
            if line.position() != node_pose(cell, r, to).pos {
                return Err(line.jump(m));
            }
            if to != 0 {
                let task = to - 1;
                line.wait(cell.tasks[task].duration, Activity::Work(task), m)?;
            }
        }
        Ok(line.finish(route))
    }
}

/// How far (radians, relative to the angle's size) a motion's first angle may be from the
/// robot's, up to whole turns: rounding of the turns added to keep the angle continuous.
const ANGLE_JOIN_TOL: f64 = 1e-9;

/// A robot's schedule under construction: samples, segments and path so far.
struct Timeline {
    robot: usize,
    samples: Vec<Sample>,
    segments: Vec<Segment>,
    path: Vec<Vec2>,
    now: f64,
    /// The angle so far, continuous: a move planned from a node's angle starts at that angle
    /// plus the whole turns the robot has made.
    theta: f64,
}

impl Timeline {
    fn start(cell: &Cell, r: usize) -> Timeline {
        let home = node_pose(cell, r, 0);
        Timeline {
            robot: r,
            samples: vec![rest(0.0, home.pos, home.theta)],
            segments: Vec::new(),
            path: vec![home.pos],
            now: 0.0,
            theta: home.theta,
        }
    }

    fn precision(&self, time: f64) -> BuildError {
        BuildError::Precision {
            robot: self.robot,
            time,
        }
    }

    /// Stands still for `duration` doing `activity`. A positive hold must leave a trace on
    /// the time axis: one that f64 rounds away would vanish from the schedule.
    fn wait(&mut self, duration: f64, activity: Activity, leg: usize) -> Result<(), BuildError> {
        if duration <= 0.0 {
            if activity_is_task(activity) {
                self.push(activity, self.now, leg);
            }
            return Ok(());
        }
        let end = self.now + duration;
        if end <= self.now || !end.is_finite() {
            return Err(self.precision(self.now));
        }
        let pos = self.samples.last().expect("starts with a sample").pos;
        self.push(activity, end, leg);
        self.samples.push(rest(end, pos, self.theta));
        Ok(())
    }

    fn position(&self) -> Vec2 {
        self.samples.last().expect("starts with a sample").pos
    }

    fn jump(&self, leg: usize) -> BuildError {
        BuildError::Discontinuous {
            robot: self.robot,
            leg,
            time: self.now,
        }
    }

    /// Makes a planned motion from where the robot is.
    fn go(
        &mut self,
        planned: &PlannedMove,
        activity: Activity,
        leg: usize,
    ) -> Result<(), BuildError> {
        let first = &planned.samples[0];
        let turns = TAU * ((self.theta - first.theta) / TAU).round();
        let off = (self.theta - first.theta - turns).abs();
        if first.pos != self.position() || off > ANGLE_JOIN_TOL * (1.0 + self.theta.abs()) {
            return Err(self.jump(leg));
        }
        // The first sample is where the robot already is; every later one must come later
        // on the time axis, or the move would silently vanish.
        for s in &planned.samples[1..] {
            let t = self.now + s.t;
            if t <= self.samples.last().expect("starts with a sample").t {
                return Err(self.precision(t));
            }
            self.samples.push(Sample {
                t,
                theta: s.theta + turns,
                ..*s
            });
        }
        self.path.extend(planned.path.iter().skip(1));
        self.theta = planned.samples.last().expect("a move has samples").theta + turns;
        self.push(activity, self.now + planned.duration, leg);
        Ok(())
    }

    fn push(&mut self, activity: Activity, end: f64, leg: usize) {
        self.segments.push(Segment {
            activity,
            start: self.now,
            end,
            leg: Some(leg),
        });
        self.now = end;
    }

    fn finish(mut self, route: &[usize]) -> RobotSchedule {
        // The last sample is the arrival home (or the start, for a robot that stays home).
        let end = self.samples.last().expect("starts with a sample").t;
        self.segments.push(Segment {
            activity: Activity::Done,
            start: end,
            end: f64::INFINITY,
            leg: None,
        });
        RobotSchedule {
            route: route.to_vec(),
            segments: self.segments,
            samples: self.samples,
            path: self.path,
            end,
        }
    }
}

fn activity_is_task(a: Activity) -> bool {
    matches!(a, Activity::Work(_))
}

fn rest(t: f64, pos: Vec2, theta: f64) -> Sample {
    Sample {
        t,
        pos,
        theta,
        vel: Vec2::zeros(),
        omega: 0.0,
    }
}
