//! `workcell evaluate`: the schedule of given sequences, checked.

use super::feedback::{SolveOptions, StageTimes};
use super::moves::MoveStore;
use super::schedule::{BuildError, Collision, Delay, Schedule};
use crate::cell::{Cell, InputError, Sequences};
use crate::collision::{check, CheckReport};
use std::path::Path;
use std::time::Instant;

/// The verdict on given sequences.
#[derive(Clone, Debug)]
pub struct Evaluated {
    /// Their schedule.
    pub schedule: Schedule,
    /// The checker's report on it.
    pub report: CheckReport,
    /// Its first collision, if any.
    pub collision: Option<Collision>,
    /// The waits applied, as given.
    pub delays: Vec<Delay>,
    /// True when the schedule is certified collision-free.
    pub collision_free: bool,
    /// Wall time per stage (planning counts the moves planned for these sequences only).
    pub times: StageTimes,
}

/// Times the given sequences (each robot's tasks and its waits, as
/// [`crate::cell::parse_sequences`] gives them) and checks the schedule. A move the planner cannot make, or that the
/// checker does not certify against the obstacles, is an input error about
/// `sequences_file`.
pub fn evaluate(
    cell: &Cell,
    sequences: &Sequences,
    opts: &SolveOptions,
    sequences_file: &Path,
) -> Result<Evaluated, InputError> {
    let mut times = StageTimes::default();
    let clock = Instant::now();
    let cache = MoveStore::new(cell, &opts.planner);
    let routes = &sequences.routes;
    let delays: Vec<Delay> = sequences
        .waits
        .iter()
        .map(|w| {
            let nodes: Vec<usize> = std::iter::once(0)
                .chain(routes[w.robot].iter().map(|t| t + 1))
                .chain([0])
                .collect();
            Delay {
                robot: w.robot,
                before_move: w.before_move,
                nodes: (nodes[w.before_move], nodes[w.before_move + 1]),
                duration: w.duration,
            }
        })
        .collect();
    let schedule = Schedule::build(cell, routes, &delays, &cache).map_err(|e| {
        let r = e.robot();
        let robot = &cell.robots[r].name;
        let field = match e {
            // The position in the robot's list of the task the move leads to (or leaves,
            // for the way home).
            BuildError::Move { from, to, .. } => {
                let task = if to != 0 { to } else { from }.saturating_sub(1);
                let k = routes[r].iter().position(|&t| t == task).unwrap_or(0);
                format!("{robot}[{k}]")
            }
            BuildError::Precision { .. } => robot.clone(),
        };
        InputError::new(sequences_file, Some(robot), field, e.reason(cell))
    })?;
    times.scheduling = clock.elapsed();
    let clock = Instant::now();
    let report = check(&schedule.scene(cell), &opts.check);
    times.checking = clock.elapsed();
    let collision = schedule.collision(cell, &report);
    let collision_free = collision.is_none() && report.certified;
    Ok(Evaluated {
        delays,
        schedule,
        report,
        collision,
        collision_free,
        times,
    })
}
