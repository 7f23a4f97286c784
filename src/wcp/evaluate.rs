//! `workcell evaluate`: the schedule of given sequences, checked.

use super::configurations::{task_configurations, Assignment};
use super::legs::{leg, with_leg, HoldReason, Leg, Legs, Piece};
use super::moves::{limits, MoveStore};
use super::options::SolveOptions;
use super::prepare::StageTimes;
use super::schedule::{route_nodes, Activity, BuildError, Collision, Delay, Schedule};
use super::time_axis::{culprit, first_infinite_time, Stretch};
use crate::cell::{number, Cell, InputError, PieceSpec, Sequences};
use crate::collision::CheckReport;
use crate::geometry::Vec2;
use crate::planning::ArmModel;
use crate::planning::{time_primitives, Primitive};
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
/// obstacle or a robot is a collision the check reports. A schedule that f64 cannot place on one time axis is an
/// error about what stretched the axis: a task's duration or a robot's limits (the cell),
/// or a wait (`sequences_file`).
///
/// ```
/// use workcell::cell::{load_cell, parse_sequences};
/// use workcell::wcp::{evaluate, SolveOptions};
/// let cell = load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let file = "seq.json".as_ref();
/// let opts = SolveOptions::default();
/// // R1 does every weld, R2 stays home: nothing meets.
/// let alone = parse_sequences(r#"{"R1": ["weld-1", "weld-3", "weld-2", "weld-4"]}"#, file, &cell)?;
/// let e = evaluate(&cell, &alone, &opts, file)?;
/// assert!(e.collision_free && e.collision.is_none() && e.report.verdict().is_certified_free());
/// assert!(e.schedule.makespan > 1.2 + 1.3 + 1.7 + 2.3); // the welds and the moves between them
/// // Welds 2 and 4 lie too close for both robots at once.
/// let both = parse_sequences(r#"{"R1": ["weld-2", "weld-1", "weld-3"], "R2": ["weld-4"]}"#, file, &cell)?;
/// let e = evaluate(&cell, &both, &opts, file)?;
/// let verdict = e.report.verdict();
/// assert_eq!(verdict.contact().expect("a collision").bodies, ["R1", "R2"]);
/// assert!(!e.collision_free && e.collision.is_some());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn evaluate(
    cell: &Cell,
    sequences: &Sequences,
    opts: &SolveOptions,
    sequences_file: &Path,
) -> Result<Evaluated, InputError> {
    let mut times = StageTimes::default();
    let clock = Instant::now();
    let moves = match cell.robots.iter().any(|r| r.as_arm().is_some()) {
        true => {
            let assignment = given_configurations(cell, sequences, sequences_file, opts)?;
            MoveStore::with_assignment(cell, &opts.planner, assignment)
        }
        false => MoveStore::new(cell, &opts.planner),
    };
    let routes = &sequences.routes;
    let (delays, legs) = given_legs(cell, sequences, opts, &moves);
    let schedule = Schedule::build(cell, routes, &legs, &moves)
        .map_err(|e| build_error(cell, sequences, sequences_file, &moves, &delays, e))?;
    // A move whose time overflowed leaves samples the checker cannot take.
    if let Some((robot, time)) = schedule
        .robots
        .iter()
        .enumerate()
        .find_map(|(r, s)| first_infinite_time(s).map(|t| (r, t)))
    {
        let at = Placement {
            robot,
            time,
            delays: &delays,
        };
        return Err(precision_error(cell, sequences, sequences_file, &moves, at));
    }
    times.scheduling = clock.elapsed();
    let clock = Instant::now();
    let report = schedule.check(&schedule.scene(cell), &opts.check);
    times.checking = clock.elapsed();
    let collision = schedule.collision(cell, &report);
    let collision_free = collision.is_none() && report.verdict().is_certified_free();
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

/// Each arm's configuration at each task: as given in the result's `configurations`, each
/// one of the arm's configurations there (to within rounding: the tool on the task, within
/// the limits, clear of the fixtures), else the one it reaches soonest from home.
fn given_configurations(
    cell: &Cell,
    sequences: &Sequences,
    sequences_file: &Path,
    opts: &SolveOptions,
) -> Result<Assignment, InputError> {
    let found = task_configurations(cell, &opts.ik)?;
    let mut assignment = Assignment::nearest_home(cell, std::sync::Arc::new(found));
    for (r, given) in sequences.configurations.iter().enumerate() {
        for (k, q) in given.iter().enumerate() {
            let t = sequences.routes[r][k];
            let same = |c: &[f64]| {
                (c.iter().zip(q)).all(|(a, b)| (a - b).abs() <= JOINT_MATCH_TOL * (1.0 + a.abs()))
            };
            let at = assignment.configurations().at(r, t);
            let Some(i) = at.iter().position(|c| same(c)) else {
                let name = &cell.robots[r].name;
                let reason = format!(
                    "these joint angles are not a configuration of {name} at task \"{}\" (the \
                     tool on the task, within the joint limits, clear of the fixtures)",
                    cell.tasks[t].name
                );
                let field = format!("configurations.{name}[{k}]");
                return Err(InputError::new(sequences_file, Some(name), field, reason));
            };
            assignment = assignment.with(r, t, i);
        }
    }
    Ok(assignment)
}

/// How far (relative to the angle's size) a given joint angle may be from the configuration
/// found: the rounding of a result written and read back.
const JOINT_MATCH_TOL: f64 = 1e-9;

/// The waits and the changed moves given, as the schedule's legs.
fn given_legs(
    cell: &Cell,
    sequences: &Sequences,
    opts: &SolveOptions,
    moves: &MoveStore,
) -> (Vec<Delay>, Legs) {
    let routes = &sequences.routes;
    let delays: Vec<Delay> = sequences
        .waits
        .iter()
        .map(|w| {
            let nodes = route_nodes(&routes[w.robot]);
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
            .map(|p| match (cell.robots[spec.robot].as_arm(), p) {
                // An arm's motion is its leg's joint-space move, maybe slower.
                (Some(arm), PieceSpec::Go { scale, joints, .. }) if !joints.is_empty() => {
                    let model = ArmModel::new(&cell.robots[spec.robot].name, arm);
                    let through = model.through(joints, opts.planner.samples_per_phase);
                    Piece::Go {
                        motion: Arc::new(model.planned(&through)),
                        scale: *scale,
                    }
                }
                (Some(_), PieceSpec::Go { scale, .. }) => {
                    let nodes = route_nodes(&routes[spec.robot]);
                    let (from, to) = (nodes[spec.leg], nodes[(spec.leg + 1).min(nodes.len() - 1)]);
                    match moves.get(spec.robot, from, to) {
                        Ok(motion) => Piece::Go {
                            motion,
                            scale: *scale,
                        },
                        // No move: the leg stays where it starts, and the schedule refuses
                        // it as a leg that does not reach its end.
                        Err(_) => Piece::Hold {
                            duration: 0.0,
                            reason: HoldReason::Pause,
                        },
                    }
                }
                _ => piece(cell, spec.robot, p, opts),
            })
            .collect();
        let new = Leg {
            pieces: Some(pieces.into()),
            ..old
        };
        legs = with_leg(&legs, spec.robot, spec.leg, new);
    }
    (delays, legs)
}

/// The input error for sequences whose schedule cannot be built: a move the planner cannot
/// make (named by the task it leads to), a changed move that does not join its neighbours
/// (`legs[k]`), or a schedule f64 cannot place.
fn build_error(
    cell: &Cell,
    sequences: &Sequences,
    sequences_file: &Path,
    moves: &MoveStore,
    delays: &[Delay],
    e: BuildError,
) -> InputError {
    let routes = &sequences.routes;
    match e {
        BuildError::Precision { robot, time } => {
            let at = Placement {
                robot,
                time,
                delays,
            };
            precision_error(cell, sequences, sequences_file, moves, at)
        }
        e @ BuildError::Discontinuous { .. } => {
            let (r, BuildError::Discontinuous { leg, .. }) = (e.robot(), &e) else {
                unreachable!("matched above")
            };
            let robot = &cell.robots[r].name;
            let k = sequences
                .legs
                .iter()
                .position(|l| l.robot == r && l.leg == *leg);
            let field = k.map_or(robot.clone(), |k| format!("legs[{k}]"));
            InputError::new(sequences_file, Some(robot), field, e.reason(cell))
        }
        e => {
            let r = e.robot();
            let robot = &cell.robots[r].name;
            let BuildError::Move { from, to, .. } = e else {
                unreachable!("handled above")
            };
            // The position in the robot's list of the task the move leads to (or leaves,
            // for the way home).
            let task = if to != 0 { to } else { from }.saturating_sub(1);
            let k = routes[r].iter().position(|&t| t == task).unwrap_or(0);
            let reason = e.reason(cell);
            InputError::new(sequences_file, Some(robot), format!("{robot}[{k}]"), reason)
        }
    }
}

/// Where a schedule left f64's time axis: robot, time, and the waits it was built with.
struct Placement<'a> {
    robot: usize,
    time: f64,
    delays: &'a [Delay],
}

/// The error for a schedule f64 cannot place, about the activity that stretched the axis
/// (see [`culprit`]): a task's `duration` or the robot's limits in the cell, or a wait in
/// the sequences file.
fn precision_error(
    cell: &Cell,
    sequences: &Sequences,
    sequences_file: &Path,
    moves: &MoveStore,
    at: Placement,
) -> InputError {
    let (r, time) = (at.robot, at.time);
    let name = &cell.robots[r].name;
    let route = &sequences.routes[r];
    let Some(misplaced) = culprit(cell, r, route, at.delays, moves, time) else {
        let reason = format!("at t = {time:e} f64 cannot place the robot's schedule");
        return cell.error(Some(name), format!("robots[{r}]"), reason);
    };
    let (lost, blamed) = (misplaced.lost, misplaced.blamed);
    let resolution = format!(
        "at t = {}, where f64 spaces times {} apart",
        number(time),
        number(time.abs() * f64::EPSILON)
    );
    let what_lost = format!(
        "{resolution}, {name}'s {} ({} long) cannot keep its length",
        lost.activity.describe(cell, r),
        number(lost.length)
    );
    match blamed.activity {
        Activity::Work(k) => {
            let reason = if blamed == lost {
                format!(
                    "this duration of {} is too short for the time axis: {resolution}, it \
                     cannot keep its length; rescale the time unit, or give 0 for an instant",
                    number(blamed.length)
                )
            } else {
                format!(
                    "this duration of {} stretches the time axis: {what_lost}; rescale the \
                     time unit",
                    number(blamed.length)
                )
            };
            cell.error(
                Some(&cell.tasks[k].name),
                format!("tasks[{k}].duration"),
                reason,
            )
        }
        Activity::Wait(_) => {
            let i = longest_wait(sequences, r, blamed.step);
            let reason = format!(
                "this wait of {} stretches the time axis: {what_lost}",
                number(sequences.waits.get(i).map_or(blamed.length, |w| w.duration))
            );
            InputError::new(
                sequences_file,
                Some(name),
                format!("waits[{i}].duration"),
                reason,
            )
        }
        Activity::Move { .. } | Activity::Pause { .. } | Activity::Park { .. } | Activity::Done => {
            if let Some((field, reason)) = leg_blamed(sequences, r, blamed, &what_lost) {
                return InputError::new(sequences_file, Some(name), field, reason);
            }
            let reason = limits_reason(cell, r, blamed, lost, &resolution, &what_lost);
            cell.error(Some(name), format!("robots[{r}]"), reason)
        }
    }
}

/// When the move that stretched the axis is a leg the result file changed, the piece of it
/// to blame, as a field of that file and a reason: a hold too short to keep its length where
/// the leg starts, else the piece that lasts longest (a hold, or a motion by its slowing
/// factor times the planned move's duration).
fn leg_blamed(
    sequences: &Sequences,
    r: usize,
    blamed: Stretch,
    what_lost: &str,
) -> Option<(String, String)> {
    use crate::cell::PieceSpec;
    let k = (sequences.legs.iter()).position(|l| l.robot == r && l.leg == blamed.step)?;
    let pieces = &sequences.legs[k].pieces;
    let field = |i: usize| match pieces[i] {
        PieceSpec::Hold { .. } => "hold",
        PieceSpec::Go { .. } => "go.scale",
    };
    let start = blamed.start;
    let too_short = (0..pieces.len()).find(|&i| {
        matches!(pieces[i], PieceSpec::Hold { duration, .. }
            if duration > 0.0 && start + duration == start)
    });
    if let Some(i) = too_short {
        let PieceSpec::Hold { duration, .. } = pieces[i] else {
            unreachable!("a hold")
        };
        let reason = format!(
            "this hold of {} is too short for the time axis: at t = {}, where f64 spaces times \
             {} apart, it cannot keep its length; give 0 for no hold",
            number(duration),
            number(start),
            number(start.abs() * f64::EPSILON)
        );
        return Some((format!("legs[{k}].pieces[{i}].hold"), reason));
    }
    let lasts = |i: &usize| match pieces[*i] {
        PieceSpec::Hold { duration, .. } => duration,
        PieceSpec::Go { scale, .. } => scale * blamed.length,
    };
    let i = (0..pieces.len()).max_by(|a, b| lasts(a).total_cmp(&lasts(b)))?;
    let (what, value) = match pieces[i] {
        PieceSpec::Hold { duration, .. } => ("hold", duration),
        PieceSpec::Go { scale, .. } => ("slowing factor", scale),
    };
    let reason = format!(
        "this {what} of {} stretches the time axis: {what_lost}",
        number(value)
    );
    Some((format!("legs[{k}].pieces[{i}].{}", field(i)), reason))
}

/// The index of the longest of the waits given to robot `r` before move `step` (0 if none).
fn longest_wait(sequences: &Sequences, r: usize, step: usize) -> usize {
    (0..sequences.waits.len())
        .filter(|&i| {
            let w = &sequences.waits[i];
            w.robot == r && w.before_move == step
        })
        .max_by(|&a, &b| {
            sequences.waits[a]
                .duration
                .total_cmp(&sequences.waits[b].duration)
        })
        .unwrap_or(0)
}

/// Why robot `r`'s limits are to blame: its move takes longer than f64 holds, is too short
/// for the axis where it lies, or stretches the axis so that `lost` cannot keep its length.
fn limits_reason(
    cell: &Cell,
    r: usize,
    blamed: Stretch,
    lost: Stretch,
    resolution: &str,
    what_lost: &str,
) -> String {
    let list = |v: &[f64]| v.iter().map(|&x| number(x)).collect::<Vec<_>>().join(", ");
    let limits = match cell.robots[r].as_arm() {
        Some(arm) => format!(
            "max_joint_speed [{}], max_joint_accel [{}]",
            list(&arm.limits.max_speed),
            list(&arm.limits.max_accel)
        ),
        None => {
            let robot = cell.rigid(r);
            format!(
                "max_speed {}, max_accel {}, max_turn_rate {}",
                number(robot.max_speed),
                number(robot.max_accel),
                number(robot.max_turn_rate)
            )
        }
    };
    let the_move = blamed.activity.describe(cell, r);
    let length = number(blamed.length);
    if !blamed.length.is_finite() {
        format!("at its limits ({limits}) the robot's {the_move} takes longer than f64 holds")
    } else if blamed == lost {
        format!(
            "at its limits ({limits}) the robot's {the_move} takes only {length}, which \
             cannot keep its length {resolution}; lower the limits or rescale the time \
             unit"
        )
    } else {
        format!(
            "at its limits ({limits}) the robot's {the_move} takes {length}: \
             {what_lost}; raise the limits or rescale the time unit"
        )
    }
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
        PieceSpec::Go {
            primitives, scale, ..
        } => {
            let robot = cell.rigid(r);
            let limits = limits(robot);
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
