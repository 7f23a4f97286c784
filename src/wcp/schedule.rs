//! The timed schedule: every robot's moves, waits and tasks, sampled into trajectories.

use super::moves::{node_name, node_pose, MoveFailure, MoveStore};
use super::sequencer::Step;
use crate::cell::Cell;
use crate::collision::{Body, CheckReport, Scene};
use crate::geometry::{closest_features, Posed, Vec2, WalkTolerances};
use crate::motion::{Motion, Pose, Sample, Trajectory};
use std::f64::consts::TAU;

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
    /// At home after the last move, until the end of time.
    Done,
}

impl Activity {
    /// The sequencer's step for this activity.
    pub fn step(self) -> Step {
        match self {
            Activity::Move { from, to } => Step::Move { from, to },
            Activity::Work(t) => Step::Stay { node: t + 1 },
            Activity::Wait(node) => Step::Stay { node },
            Activity::Done => Step::Stay { node: 0 },
        }
    }

    /// Human description, e.g. `move weld-1 -> weld-4`.
    pub fn describe(self, cell: &Cell, r: usize) -> String {
        match self {
            Activity::Move { from, to } => {
                format!("move {} -> {}", place(cell, r, from), place(cell, r, to))
            }
            Activity::Work(t) => format!("task {}", cell.tasks[t].name),
            Activity::Wait(node) => format!("wait at {}", place(cell, r, node)),
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
    /// The move that a delay would postpone to push this segment later: the move itself, the
    /// move into the task, or the move after the wait. `None` once the robot is done.
    pub delayable_move: Option<usize>,
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
    /// The segment under way at time `t`.
    pub fn segment_at(&self, t: f64) -> &Segment {
        let k = self.segments.partition_point(|s| s.end <= t);
        &self.segments[k.min(self.segments.len() - 1)]
    }
}

/// The timed schedule of every robot.
#[derive(Clone, Debug)]
pub struct Schedule {
    /// One per robot, in the cell's order.
    pub robots: Vec<RobotSchedule>,
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
            BuildError::Move { robot, .. } | BuildError::Precision { robot, .. } => *robot,
        }
    }

    /// Why, in words.
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
    /// Times every robot's route: from home at t = 0, each move as planned, each task held
    /// for its duration, back home; `delays` insert waits before given moves. The moves come
    /// from the store (planned there if they were not yet).
    pub fn build(
        cell: &Cell,
        routes: &[Vec<usize>],
        delays: &[Delay],
        moves: &MoveStore,
    ) -> Result<Schedule, BuildError> {
        let mut robots = Vec::with_capacity(routes.len());
        for (r, route) in routes.iter().enumerate() {
            robots.push(build_robot(cell, r, route, delays, moves)?);
        }
        let makespan = robots.iter().map(|s| s.end).fold(0.0, f64::max);
        Ok(Schedule { robots, makespan })
    }

    /// The schedule as a scene for the checker (and `--export-scene`): robots with their
    /// trajectories, then the obstacles.
    pub fn scene(&self, cell: &Cell) -> Scene {
        let robots = (0..self.robots.len()).map(|r| self.body(cell, r));
        Scene {
            delta: cell.delta,
            bodies: robots.chain(cell.obstacle_bodies()).collect(),
        }
    }

    /// Robots `a` and `b` alone: the scene of one pair.
    pub fn pair_scene(&self, cell: &Cell, a: usize, b: usize) -> Scene {
        Scene {
            delta: cell.delta,
            bodies: vec![self.body(cell, a), self.body(cell, b)],
        }
    }

    fn body(&self, cell: &Cell, r: usize) -> Body {
        Body {
            name: cell.robots[r].name.clone(),
            shape: cell.robots[r].shape.clone(),
            motion: Motion::Sampled(
                Trajectory::new(self.robots[r].samples.clone())
                    .expect("schedules sample increasing times"),
            ),
        }
    }

    /// The first collision of a check of [`Schedule::scene`], located in the schedule.
    pub fn collision(&self, cell: &Cell, report: &CheckReport) -> Option<Collision> {
        let contact = report.first_contact.as_ref()?;
        let robot = |name: &str| cell.robots.iter().position(|r| r.name == name);
        let a = robot(&contact.bodies[0]).expect("the checker names a robot first");
        let b = robot(&contact.bodies[1]);
        let shape_a = &cell.robots[a].shape;
        let pose_a = pose_at(&self.robots[a].samples, contact.time);
        let (shape_b, pose_b) = match b {
            Some(b) => (
                &cell.robots[b].shape,
                pose_at(&self.robots[b].samples, contact.time),
            ),
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

fn pose_at(samples: &[Sample], t: f64) -> Pose {
    Trajectory::new(samples.to_vec())
        .expect("schedules sample increasing times")
        .pose_at(t)
}

/// Appends a rest at the robot's current pose, unless it falls on the last sample's time
/// (a zero or negligible hold: the pose is the same either way).
fn hold(samples: &mut Vec<Sample>, rest: Sample) {
    if rest.t > samples.last().expect("starts with a sample").t {
        samples.push(rest);
    }
}

fn build_robot(
    cell: &Cell,
    r: usize,
    route: &[usize],
    delays: &[Delay],
    moves: &MoveStore,
) -> Result<RobotSchedule, BuildError> {
    let home = node_pose(cell, r, 0);
    let rest = |t: f64, pose: Pose| Sample {
        t,
        pos: pose.pos,
        theta: pose.theta,
        vel: Vec2::zeros(),
        omega: 0.0,
    };
    let mut samples = vec![rest(0.0, home)];
    let mut segments = Vec::with_capacity(3 * route.len() + 2);
    let mut path = vec![home.pos];
    let mut now = 0.0;
    let mut theta = home.theta;
    // A robot without tasks stays home: no move, not even home to home.
    let nodes: Vec<usize> = if route.is_empty() {
        Vec::new()
    } else {
        std::iter::once(0)
            .chain(route.iter().map(|t| t + 1))
            .chain([0])
            .collect()
    };
    let precision = |time: f64| BuildError::Precision { robot: r, time };
    for (m, pair) in nodes.windows(2).enumerate() {
        let (from, to) = (pair[0], pair[1]);
        let wait: f64 = delays
            .iter()
            .filter(|d| d.robot == r && d.before_move == m)
            .map(|d| d.duration)
            .sum();
        if wait > 0.0 {
            let pose = Pose {
                pos: node_pose(cell, r, from).pos,
                theta,
            };
            segments.push(Segment {
                activity: Activity::Wait(from),
                start: now,
                end: now + wait,
                delayable_move: Some(m),
            });
            now += wait;
            hold(&mut samples, rest(now, pose));
        }
        let planned = moves.get(r, from, to).map_err(|why| BuildError::Move {
            robot: r,
            from,
            to,
            why,
        })?;
        // Keep the angle continuous: a planned move starts at the node's angle, the robot
        // may have arrived at the same angle plus turns.
        let turns = TAU * ((theta - planned.samples[0].theta) / TAU).round();
        // The first sample is where the robot already is; every later one must come later
        // on the time axis, or the move would silently vanish.
        for s in &planned.samples[1..] {
            let t = now + s.t;
            if t <= samples.last().expect("starts with a sample").t {
                return Err(precision(t));
            }
            samples.push(Sample {
                t,
                theta: s.theta + turns,
                ..*s
            });
        }
        segments.push(Segment {
            activity: Activity::Move { from, to },
            start: now,
            end: now + planned.duration,
            delayable_move: Some(m),
        });
        path.extend(planned.path.iter().skip(1));
        now += planned.duration;
        theta = planned.samples.last().expect("a move has samples").theta + turns;
        if to != 0 {
            let task = to - 1;
            let duration = cell.tasks[task].duration;
            segments.push(Segment {
                activity: Activity::Work(task),
                start: now,
                end: now + duration,
                delayable_move: Some(m),
            });
            now += duration;
            let pose = Pose {
                pos: node_pose(cell, r, to).pos,
                theta,
            };
            hold(&mut samples, rest(now, pose));
        }
    }
    // The last sample is the arrival home (or the start, for an empty route).
    let end = samples.last().expect("starts with a sample").t;
    segments.push(Segment {
        activity: Activity::Done,
        start: end,
        end: f64::INFINITY,
        delayable_move: None,
    });
    Ok(RobotSchedule {
        route: route.to_vec(),
        segments,
        samples,
        path,
        end,
    })
}
