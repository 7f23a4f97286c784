//! The loop of the Work-Cell Problem: sequence, schedule, check, feed the first collision
//! back, until the schedule is collision-free.

use super::graph::{check_reachable, plan_reaches};
use super::moves::{bounds, robot_nodes, MoveStore};
use super::schedule::{Activity, BuildError, Collision, Delay, Schedule, Segment};
use super::sequence::sequence_with;
use super::sequencer::{Bounds, Conflict, ExactArcs, SequencerError, SequencerOptions};
use crate::cell::{Cell, InputError};
use crate::collision::{check, CheckOptions, CheckReport};
use crate::planning::PlannerOptions;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Settings of a solve.
#[derive(Clone, Debug)]
pub struct SolveOptions {
    /// Rounds of sequencing, checking and feedback before giving up.
    pub max_iterations: usize,
    /// The sequencer's settings, its seed among them.
    pub sequencer: SequencerOptions,
    /// The planner's settings.
    pub planner: PlannerOptions,
    /// The checker's settings for the schedules.
    pub check: CheckOptions,
    /// Wall time for the whole solve, from [`prepare`] on: the sequencer then returns the
    /// best certified plan found so far. `None`: no limit, and the result depends only on
    /// the input and the seed.
    pub time_limit: Option<Duration>,
    /// Which moves are planned before sequencing.
    pub planning: Planning,
}

/// Which moves [`prepare`] plans and certifies.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Planning {
    /// [`Planning::All`] for cells of at most [`AUTO_ALL_MAX_MOVES`] moves, else
    /// [`Planning::Lazy`].
    #[default]
    Auto,
    /// For each task, the move from the home of its nearest allowed robot that can reach it;
    /// the sequencer works on lower bounds of the others and plans those its plans use.
    Lazy,
    /// Every move of every robot between every two of its nodes (robots × nodes² / 2).
    All,
}

/// Cells with at most this many moves (robots × unordered pairs of their nodes) are planned
/// whole under [`Planning::Auto`]: a second or two of planning, and the sequencer then
/// searches on exact times from the start.
pub const AUTO_ALL_MAX_MOVES: usize = 100_000;

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            max_iterations: 50,
            sequencer: SequencerOptions::default(),
            planner: PlannerOptions::default(),
            check: CheckOptions::default(),
            time_limit: None,
            planning: Planning::Auto,
        }
    }
}

/// Progress of a solve, for a progress bar. Called from the solving thread, except
/// `move_planned`, which planning threads call.
pub trait Progress: Sync {
    /// Planning starts: `total` moves to plan and certify.
    fn planning(&self, _total: usize) {}
    /// One more move planned.
    fn move_planned(&self) {}
    /// Round `k` (from 1) checked a schedule of this makespan.
    fn iteration(&self, _k: usize, _makespan: f64, _collision: Option<&Collision>) {}
    /// The sequencer starts its round `round` (from 1) on the travel times known so far.
    fn sequencing(&self, _round: usize) {}
    /// The sequencer found a plan of this makespan (on the travel times it knows; from any
    /// thread).
    fn best(&self, _makespan: f64) {}
}

impl Progress for () {}

/// Wall time spent in each stage.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageTimes {
    /// Planning and certifying the moves [`prepare`] plans (see [`Planning`]).
    pub planning: Duration,
    /// Building the lower bounds.
    pub graph: Duration,
    /// Sequencer runs, with the moves they plan.
    pub sequencing: Duration,
    /// Timing the schedules (including moves planned on demand).
    pub scheduling: Duration,
    /// Collision checks of the schedules.
    pub checking: Duration,
}

/// How one round's collision was removed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Remedy {
    /// The sequencer re-planned with the colliding pair of steps forbidden.
    Resequence,
    /// A robot waits before one of its moves.
    Delay(Delay),
}

/// One round of the loop.
#[derive(Clone, Debug)]
pub struct Iteration {
    /// Makespan of the schedule checked in this round.
    pub makespan: f64,
    /// Its first collision, if any.
    pub collision: Option<Collision>,
    /// What was done about it (`None` in the last round).
    pub remedy: Option<Remedy>,
}

/// The cell's moves and bounds, ready for sequencing.
pub struct Prepared {
    /// The one store of planned and certified moves.
    pub moves: MoveStore,
    /// The lower bound of every move.
    pub bounds: Arc<Bounds>,
    /// The moves every sequencing starts from: those [`prepare`] planned, per robot, both
    /// ways.
    pub known: Arc<ExactArcs>,
    /// When [`SolveOptions::time_limit`] runs out.
    pub deadline: Option<Instant>,
    /// Time spent so far.
    pub times: StageTimes,
}

/// A solve's result.
#[derive(Clone, Debug)]
pub struct Solved {
    /// Each robot's tasks in order.
    pub routes: Vec<Vec<usize>>,
    /// Waits added by the loop.
    pub delays: Vec<Delay>,
    /// The final schedule.
    pub schedule: Schedule,
    /// The checker's report on the final schedule.
    pub report: CheckReport,
    /// True when the final schedule is certified collision-free.
    pub collision_free: bool,
    /// Every round, in order; the last one checked the final schedule.
    pub iterations: Vec<Iteration>,
    /// The collision-blind best sequences (the first round's).
    pub blind_routes: Vec<Vec<usize>>,
    /// Makespan of the collision-blind best schedule.
    pub blind_makespan: f64,
    /// Whether the sequencer proved that one optimal.
    pub blind_optimal: bool,
    /// Why the loop stopped without a collision-free schedule.
    pub failure: Option<String>,
    /// Wall time per stage.
    pub times: StageTimes,
}

/// Builds the lower bounds, plans and certifies for every task the move from the home of
/// its nearest allowed robot (the next nearest when that one fails), or every move (see
/// [`Planning`]). A task that no allowed robot
/// can reach is an input error. The time limit counts from here.
pub fn prepare(
    cell: &Cell,
    opts: &SolveOptions,
    progress: &dyn Progress,
) -> Result<Prepared, InputError> {
    let deadline = opts
        .time_limit
        .and_then(|limit| Instant::now().checked_add(limit));
    let mut times = StageTimes::default();
    let clock = Instant::now();
    let bounds = Arc::new(bounds(cell));
    times.graph = clock.elapsed();
    let clock = Instant::now();
    let moves = MoveStore::new(cell, &opts.planner);
    let all_moves: usize = (0..cell.robots.len())
        .map(|r| {
            let n = robot_nodes(cell, r).len();
            n * (n - 1) / 2
        })
        .sum();
    let plan_all = match opts.planning {
        Planning::Auto => all_moves <= AUTO_ALL_MAX_MOVES,
        Planning::Lazy => false,
        Planning::All => true,
    };
    let pairs: Vec<(usize, usize, usize)> = if plan_all {
        let mut pairs = Vec::with_capacity(all_moves);
        for r in 0..cell.robots.len() {
            let nodes = robot_nodes(cell, r);
            for (i, &a) in nodes.iter().enumerate() {
                pairs.extend(nodes[i + 1..].iter().map(|&b| (r, a, b)));
            }
        }
        progress.planning(pairs.len());
        moves.plan_all(&pairs, &|| progress.move_planned());
        pairs
    } else {
        progress.planning(cell.tasks.len());
        plan_reaches(cell, &moves, &bounds, &|| progress.move_planned())
    };
    check_reachable(cell, &moves)?;
    let mut known: ExactArcs = vec![Default::default(); cell.robots.len()];
    for &(r, a, b) in &pairs {
        let d = moves.duration(r, a, b).unwrap_or(f64::INFINITY);
        known[r].insert((a, b), d);
        known[r].insert((b, a), d);
    }
    times.planning = clock.elapsed();
    Ok(Prepared {
        moves,
        bounds,
        known: Arc::new(known),
        deadline,
        times,
    })
}

/// A sequencer error in the cell's terms.
pub fn sequencer_error(cell: &Cell, e: SequencerError) -> InputError {
    match e {
        SequencerError::TaskUnassignable { task } => cell.error(
            Some(&cell.tasks[task].name),
            format!("tasks[{task}]"),
            "no allowed robot can travel to this task and back home",
        ),
        other => cell.error(None, "", other),
    }
}

/// Solves the cell: the loop of the module's documentation, at most
/// `opts.max_iterations` rounds.
pub fn solve(
    cell: &Cell,
    prepared: &Prepared,
    opts: &SolveOptions,
    progress: &dyn Progress,
) -> Result<Solved, InputError> {
    let mut times = prepared.times;
    let cache = &prepared.moves;
    let mut conflicts: Vec<Conflict> = Vec::new();
    let clock = Instant::now();
    let blind = sequence_with(cell, prepared, &[], opts, None, progress)?;
    times.sequencing += clock.elapsed();
    let mut routes = blind.sequences.clone();
    let mut delays: Vec<Delay> = Vec::new();
    let mut iterations = Vec::new();
    loop {
        let clock = Instant::now();
        let schedule = build(cell, &routes, &delays, cache)?;
        times.scheduling += clock.elapsed();
        let clock = Instant::now();
        let report = check(&schedule.scene(cell), &opts.check);
        times.checking += clock.elapsed();
        let collision = schedule.collision(cell, &report);
        progress.iteration(iterations.len() + 1, schedule.makespan, collision.as_ref());
        let done = |failure: Option<String>, iterations, times| {
            Ok(Solved {
                collision_free: failure.is_none(),
                routes: routes.clone(),
                delays: delays.clone(),
                schedule: schedule.clone(),
                report: report.clone(),
                iterations,
                blind_routes: blind.sequences.clone(),
                blind_makespan: blind.makespan,
                blind_optimal: blind.optimal,
                failure,
                times,
            })
        };
        let Some(c) = collision else {
            iterations.push(Iteration {
                makespan: schedule.makespan,
                collision: None,
                remedy: None,
            });
            let failure = if report.collision {
                Some(
                    "internal error: the checker's first contact names no body of the cell"
                        .to_owned(),
                )
            } else {
                (!report.certified).then(|| {
                    "the checker cannot certify the schedule: two bodies graze delta".to_owned()
                })
            };
            return done(failure, iterations, times);
        };
        if iterations.len() + 1 >= opts.max_iterations {
            let failure = format!(
                "no collision-free schedule within {} iterations; the last one collides: {}",
                opts.max_iterations,
                describe(cell, &c)
            );
            iterations.push(Iteration {
                makespan: schedule.makespan,
                collision: Some(c),
                remedy: None,
            });
            return done(Some(failure), iterations, times);
        }
        // Candidates: re-sequencing with the colliding steps forbidden together, or one of
        // the two robots waiting until the other's activity is over. The smaller makespan wins;
        // re-sequencing wins ties, since it removes the conflict rather than timing around it.
        let mut best: Option<Candidate> = None;
        if let (Some(b), Some(seg_b)) = (c.robots.1, c.segments.1) {
            let a = c.robots.0;
            conflicts.push(Conflict {
                a: (a, c.segments.0.activity.step()),
                b: (b, seg_b.activity.step()),
            });
            let clock = Instant::now();
            let resequenced = sequence_with(cell, prepared, &conflicts, opts, None, progress)?;
            times.sequencing += clock.elapsed();
            if resequenced.violations == 0 {
                best = Some(Candidate {
                    makespan: resequenced.makespan,
                    remedy: Remedy::Resequence,
                    routes: resequenced.sequences,
                    delays: Vec::new(),
                });
            }
            let clock = Instant::now();
            for (x, seg_x, seg_y) in [(a, c.segments.0, seg_b), (b, seg_b, c.segments.0)] {
                let y = if x == a { b } else { a };
                let Some(full) = delay_until(
                    &schedule.robots[x].segments,
                    x,
                    seg_x.delayable_move,
                    gone(&schedule.robots[y].segments, &seg_y),
                ) else {
                    continue;
                };
                let delay =
                    shortest_delay(cell, &routes, &delays, cache, full, y, seg_x.end, opts)?;
                let mut candidate = delays.clone();
                candidate.push(delay);
                let makespan = build(cell, &routes, &candidate, cache)?.makespan;
                if best.as_ref().is_none_or(|b| makespan < b.makespan) {
                    best = Some(Candidate {
                        makespan,
                        remedy: Remedy::Delay(delay),
                        routes: routes.clone(),
                        delays: candidate,
                    });
                }
            }
            times.scheduling += clock.elapsed();
        }
        let Some(Candidate {
            remedy,
            routes: next_routes,
            delays: next_delays,
            ..
        }) = best
        else {
            let failure = format!("no remedy for the collision: {}", describe(cell, &c));
            iterations.push(Iteration {
                makespan: schedule.makespan,
                collision: Some(c),
                remedy: None,
            });
            return done(Some(failure), iterations, times);
        };
        iterations.push(Iteration {
            makespan: schedule.makespan,
            collision: Some(c),
            remedy: Some(remedy),
        });
        routes = next_routes;
        delays = next_delays;
    }
}

/// A way out of a collision, and the makespan it leads to.
struct Candidate {
    makespan: f64,
    remedy: Remedy,
    routes: Vec<Vec<usize>>,
    delays: Vec<Delay>,
}

/// Fractions of the full delay tried before it, shortest first. Waiting until the other
/// robot's activity is over clears this conflict, but often by far more than needed.
const DELAY_FRACTIONS: [f64; 3] = [0.125, 0.25, 0.5];

/// The shortest of the tried fractions of `full` after which the two robots no longer meet
/// while the delayed robot's conflicting activity (`segment_end`, shifted by the wait) lasts,
/// nor meet later with one of them back home; `full` if none of them does.
#[allow(clippy::too_many_arguments)]
fn shortest_delay(
    cell: &Cell,
    routes: &[Vec<usize>],
    delays: &[Delay],
    cache: &MoveStore,
    full: Delay,
    other: usize,
    segment_end: f64,
    opts: &SolveOptions,
) -> Result<Delay, InputError> {
    for fraction in DELAY_FRACTIONS {
        let delay = Delay {
            duration: fraction * full.duration,
            ..full
        };
        let mut trial = delays.to_vec();
        trial.push(delay);
        let schedule = build(cell, routes, &trial, cache)?;
        let report = check(&schedule.pair_scene(cell, full.robot, other), &opts.check);
        // The pair must not meet while the conflicting activity lasts, nor later with one of
        // them already home for good: no wait could separate them then.
        let cleared = match report.first_contact {
            None => report.certified,
            Some(c) => {
                let done =
                    |r: usize| schedule.robots[r].segment_at(c.time).activity == Activity::Done;
                c.time >= segment_end + delay.duration && !done(full.robot) && !done(other)
            }
        };
        if cleared {
            return Ok(delay);
        }
    }
    Ok(full)
}

/// When a robot has left the place of its segment `seg`: the end of a move, or, for a
/// robot standing still (working or waiting), the end of the move that takes it away. Waiting
/// only until it stops standing there would start both robots at once, at the same spot.
fn gone(segments: &[Segment], seg: &Segment) -> f64 {
    let next = segments
        .iter()
        .skip_while(|s| *s != seg)
        .nth(1)
        .filter(|s| matches!(s.activity, Activity::Move { .. }));
    match (seg.activity, next) {
        (Activity::Work(_) | Activity::Wait(_), Some(leave)) => leave.end,
        _ => seg.end,
    }
}

/// A wait that makes robot `x` start move `m` when the other robot's activity ends.
fn delay_until(
    segments: &[super::schedule::Segment],
    x: usize,
    m: Option<usize>,
    other_end: f64,
) -> Option<Delay> {
    let m = m?;
    let (start, nodes) = segments.iter().find_map(|s| match s.activity {
        Activity::Move { from, to } if s.delayable_move == Some(m) => Some((s.start, (from, to))),
        _ => None,
    })?;
    let duration = other_end - start;
    (duration.is_finite() && duration > 0.0).then_some(Delay {
        robot: x,
        before_move: m,
        nodes,
        duration,
    })
}

fn build(
    cell: &Cell,
    routes: &[Vec<usize>],
    delays: &[Delay],
    cache: &MoveStore,
) -> Result<Schedule, InputError> {
    Schedule::build(cell, routes, delays, cache).map_err(|e| {
        let robot = &cell.robots[e.robot()].name;
        match e {
            // The table certified every move the sequencer may choose: a failure here means
            // the planner is not deterministic, a defect to report rather than hide.
            BuildError::Move { .. } => cell.error(
                Some(robot),
                "",
                format!(
                    "internal error: a move certified before fails now: {}",
                    e.reason(cell)
                ),
            ),
            BuildError::Precision { .. } => cell.error(
                Some(robot),
                format!("robots[{}]", e.robot()),
                e.reason(cell),
            ),
        }
    })
}

/// One line about a collision: `R1 (move weld-1 -> weld-2) and R2 (task weld-5) at t = 3.2`.
pub fn describe(cell: &Cell, c: &Collision) -> String {
    let a = format!(
        "{} ({})",
        c.bodies[0],
        c.segments.0.activity.describe(cell, c.robots.0)
    );
    let b = match (c.robots.1, c.segments.1) {
        (Some(b), Some(s)) => format!("{} ({})", c.bodies[1], s.activity.describe(cell, b)),
        _ => format!("obstacle {}", c.bodies[1]),
    };
    format!("{a} and {b} at t = {:.6}", c.time)
}
