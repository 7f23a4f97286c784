//! `workcell evaluate`: the schedule of given sequences, checked.

use super::feedback::{SolveOptions, StageTimes};
use super::legs::{leg, with_leg, HoldReason, Leg, Legs, Piece};
use super::moves::MoveStore;
use super::schedule::{BuildError, Collision, Delay, Schedule};
use crate::cell::{Cell, InputError, PieceSpec, Sequences};
use crate::collision::{check, CheckReport};
use crate::geometry::Vec2;
use crate::planning::{time_primitives, Primitive, RobotLimits};
use std::path::Path;
use std::sync::Arc;
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
    /// The routes, as given.
    pub routes: Vec<Vec<usize>>,
    /// The legs applied: the waits and changed moves, as given.
    pub legs: Legs,
    /// The waits applied, as given.
    pub delays: Vec<Delay>,
    /// True when the schedule is certified collision-free.
    pub collision_free: bool,
    /// Wall time per stage (planning counts the moves planned for these sequences only).
    pub times: StageTimes,
}

/// Times the given sequences (each robot's tasks, its waits and its changed moves, as
/// [`crate::cell::parse_sequences`] gives them) and checks the schedule. A move the planner
/// cannot make, or a changed move that does not start where the robot is or end where its
/// leg ends, is an input error about `sequences_file`; one that comes too close to an
/// obstacle or a robot is a collision the check reports.
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
    let mut legs = Delay::legs(cell.robots.len(), &delays);
    for spec in &sequences.legs {
        let old = leg(&legs, spec.robot, spec.leg).clone();
        let pieces: Vec<Piece> = spec
            .pieces
            .iter()
            .map(|p| piece(cell, spec.robot, p, opts))
            .collect();
        let new = Leg {
            pieces: Some(pieces.into()),
            ..old
        };
        legs = with_leg(&legs, spec.robot, spec.leg, new);
    }
    let schedule = Schedule::build(cell, routes, &legs, &cache).map_err(|e| {
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
            BuildError::Discontinuous { leg, .. } => {
                let k = sequences
                    .legs
                    .iter()
                    .position(|l| l.robot == r && l.leg == leg);
                k.map_or(robot.clone(), |k| format!("legs[{k}]"))
            }
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
        routes: routes.clone(),
        legs,
        delays,
        schedule,
        report,
        collision,
        collision_free,
        times,
    })
}

/// A piece as read, timed by the motion model at the robot's limits.
fn piece(cell: &Cell, r: usize, spec: &PieceSpec, opts: &SolveOptions) -> Piece {
    match spec {
        PieceSpec::Hold { duration, park } => Piece::Hold {
            duration: *duration,
            reason: if *park {
                HoldReason::Park
            } else {
                HoldReason::Pause
            },
        },
        PieceSpec::Go { primitives, scale } => {
            let robot = &cell.robots[r];
            let limits = RobotLimits {
                max_speed: robot.max_speed,
                max_accel: robot.max_accel,
                max_turn_rate: robot.max_turn_rate,
            };
            let primitives: Vec<Primitive> = primitives
                .iter()
                .map(|p| Primitive {
                    path: p.path.iter().map(|&[x, y]| Vec2::new(x, y)).collect(),
                    theta: p.theta,
                    turn: p.turn,
                })
                .collect();
            let motion = time_primitives(
                robot.shape.radius(),
                &limits,
                &primitives,
                opts.planner.samples_per_phase,
            );
            Piece::Go {
                motion: Arc::new(motion),
                scale: *scale,
            }
        }
    }
}
