//! Every move a robot may make, planned and then certified obstacle-free by the checker.
//!
//! Node indices are those of the sequencer: for each robot, 0 is its home and `1 + t` is
//! task `t`. A move and its reverse visit the same poses (the motion model is symmetric in
//! time), so one plan and one certificate serve both directions.

use crate::cell::{Cell, CellRobot};
use crate::collision::{check, Body, CheckOptions, Scene};
use crate::motion::{Motion, Pose, Sample, Trajectory};
use crate::planning::{plan_move, PlanError, PlannedMove, PlannerOptions, RobotLimits};
use rayon::prelude::*;
use std::fmt;

/// Why a robot has no move between two nodes.
#[derive(Clone, Debug, PartialEq)]
pub enum MoveFailure {
    /// The planner found no obstacle-free path.
    Plan(PlanError),
    /// An end of the move is too close to an obstacle for the planner's clearance, swept
    /// over the move's rotation, and turning apart found no way either.
    Blocked {
        /// `"start"` or `"goal"`.
        end: &'static str,
        /// The obstacle.
        obstacle: String,
    },
    /// The checker found the planned move within δ of an obstacle (a planner defect, kept
    /// out of every schedule).
    Collides {
        /// Time into the move of the first contact.
        time: f64,
        /// The obstacle touched.
        obstacle: String,
    },
    /// The checker could neither certify nor refute the move (it grazes δ).
    NotCertified,
}

impl fmt::Display for MoveFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MoveFailure::Plan(e) => write!(f, "{e}"),
            MoveFailure::Blocked { end, obstacle } => write!(
                f,
                "at the {end} pose the robot cannot turn as the move requires without coming \
                 closer than the planning clearance (delta + 2%) to obstacle \"{obstacle}\", \
                 and no turning point nearby helps"
            ),
            MoveFailure::Collides { time, obstacle } => write!(
                f,
                "the planned move comes within delta of obstacle \"{obstacle}\" at t = {time:.6} \
                 (refused by the checker)"
            ),
            MoveFailure::NotCertified => {
                write!(
                    f,
                    "the checker cannot certify the planned move: it grazes delta"
                )
            }
        }
    }
}

/// The pose of node `node` for robot `r`: its home for 0, task `node - 1` otherwise.
pub fn node_pose(cell: &Cell, r: usize, node: usize) -> Pose {
    match node {
        0 => cell.robots[r].home,
        n => cell.tasks[n - 1].at,
    }
}

/// The name of node `node` for robot `r`: the robot's name for its home, else the task's.
pub fn node_name(cell: &Cell, r: usize, node: usize) -> &str {
    match node {
        0 => &cell.robots[r].name,
        n => &cell.tasks[n - 1].name,
    }
}

/// The nodes robot `r` may visit: its home, then its allowed tasks in file order.
pub fn robot_nodes(cell: &Cell, r: usize) -> Vec<usize> {
    let tasks = cell.tasks.iter().enumerate();
    std::iter::once(0)
        .chain(
            tasks
                .filter(|(_, t)| t.robots.contains(&r))
                .map(|(k, _)| k + 1),
        )
        .collect()
}

fn limits(robot: &CellRobot) -> RobotLimits {
    RobotLimits {
        max_speed: robot.max_speed,
        max_accel: robot.max_accel,
        max_turn_rate: robot.max_turn_rate,
    }
}

/// Plans robot `r`'s move between two nodes and has the checker certify it against every
/// obstacle. The planner is deterministic: planning the same move again gives the same one.
pub fn certified_move(
    cell: &Cell,
    r: usize,
    from: usize,
    to: usize,
    planner: &PlannerOptions,
    obstacles: &[Body],
) -> Result<PlannedMove, MoveFailure> {
    let robot = &cell.robots[r];
    let shapes: Vec<_> = cell.obstacles.iter().map(|o| o.shape.clone()).collect();
    let (a, b) = (node_pose(cell, r, from), node_pose(cell, r, to));
    let planned = plan_move(
        &robot.shape,
        &limits(robot),
        &shapes,
        cell.delta,
        a,
        b,
        planner,
    )
    .map_err(|e| match e {
        PlanError::StartBlocked { obstacle } => MoveFailure::Blocked {
            end: "start",
            obstacle: cell.obstacles[obstacle].name.clone(),
        },
        PlanError::GoalBlocked { obstacle } => MoveFailure::Blocked {
            end: "goal",
            obstacle: cell.obstacles[obstacle].name.clone(),
        },
        other => MoveFailure::Plan(other),
    })?;
    certify(cell, r, &planned.samples, obstacles)?;
    Ok(planned)
}

/// The checker's verdict on one robot's samples against the obstacles.
pub(crate) fn certify(
    cell: &Cell,
    r: usize,
    samples: &[Sample],
    obstacles: &[Body],
) -> Result<(), MoveFailure> {
    if obstacles.is_empty() {
        return Ok(());
    }
    let robot = &cell.robots[r];
    let trajectory = Trajectory::new(samples.to_vec())
        .expect("the planner emits finite samples at increasing times");
    let mut bodies = Vec::with_capacity(obstacles.len() + 1);
    bodies.push(Body {
        name: robot.name.clone(),
        shape: robot.shape.clone(),
        motion: Motion::Sampled(trajectory),
    });
    bodies.extend_from_slice(obstacles);
    let report = check(
        &Scene {
            delta: cell.delta,
            bodies,
        },
        &CheckOptions::default(),
    );
    match report.first_contact {
        Some(c) => Err(MoveFailure::Collides {
            time: c.time,
            obstacle: c.bodies[1].clone(),
        }),
        None if !report.certified => Err(MoveFailure::NotCertified),
        None => Ok(()),
    }
}

/// Travel times of every robot between every pair of its nodes, each move certified.
#[derive(Clone, Debug)]
pub struct MoveTable {
    tasks: usize,
    /// Per robot, `(tasks + 1)²` row-major; infinite where no move exists.
    travel: Vec<Vec<f64>>,
    /// Per robot, the moves that failed: `(from, to, why)` with `from < to`.
    pub failures: Vec<Vec<(usize, usize, MoveFailure)>>,
    /// Moves planned and certified (one per unordered node pair).
    pub certified: usize,
}

impl MoveTable {
    /// Plans and certifies every move of every robot, in parallel. `progress` is called once
    /// per move planned, from any thread.
    pub fn build(cell: &Cell, planner: &PlannerOptions, progress: &(dyn Fn() + Sync)) -> Self {
        let obstacles = cell.obstacle_bodies();
        let n = cell.tasks.len() + 1;
        let jobs: Vec<(usize, usize, usize)> = (0..cell.robots.len())
            .flat_map(|r| {
                let nodes = robot_nodes(cell, r);
                let mut pairs = Vec::with_capacity(nodes.len() * nodes.len() / 2);
                for (i, &a) in nodes.iter().enumerate() {
                    pairs.extend(nodes[i + 1..].iter().map(move |&b| (r, a, b)));
                }
                pairs
            })
            .collect();
        let results: Vec<Result<f64, MoveFailure>> = jobs
            .par_iter()
            .map(|&(r, a, b)| {
                let m = certified_move(cell, r, a, b, planner, &obstacles).map(|m| m.duration);
                progress();
                m
            })
            .collect();
        let mut travel = vec![vec![f64::INFINITY; n * n]; cell.robots.len()];
        let mut failures = vec![Vec::new(); cell.robots.len()];
        let mut certified = 0;
        for (r, row) in travel.iter_mut().enumerate() {
            row[0] = 0.0;
            for node in robot_nodes(cell, r) {
                row[node * n + node] = 0.0;
            }
        }
        for (&(r, a, b), result) in jobs.iter().zip(results) {
            match result {
                Ok(time) => {
                    travel[r][a * n + b] = time;
                    travel[r][b * n + a] = time;
                    certified += 1;
                }
                Err(why) => failures[r].push((a, b, why)),
            }
        }
        MoveTable {
            tasks: cell.tasks.len(),
            travel,
            failures,
            certified,
        }
    }

    /// Travel time of robot `r` from node `from` to node `to`; infinite if it has no move.
    pub fn travel(&self, r: usize, from: usize, to: usize) -> f64 {
        self.travel[r][from * (self.tasks + 1) + to]
    }
}
