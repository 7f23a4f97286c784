//! The loop of the Work-Cell Problem: sequence, schedule, check, feed the first collision
//! back, until the schedule is collision-free.
//!
//! Two ways to feed a collision back: [`Feedback::Search`] (the default) searches over
//! remedies best-first on makespan, in the manner of conflict-based search (see
//! `search.rs`); [`Feedback::Greedy`] takes the best of two remedies each round and never
//! looks back (see `greedy.rs`), kept to compare against.

mod clearing;
mod greedy;
mod remedies;
mod search;

pub use remedies::Remedies;
pub use search::SearchOptions;

use super::graph::{check_reachable, plan_reaches};
use super::legs::Legs;
use super::moves::{bounds, robot_nodes, MoveStore};
use super::schedule::{Activity, BuildError, Collision, Delay, Schedule};
use super::sequencer::{Bounds, ExactArcs, SequencerError, SequencerOptions};
use super::time_axis::culprit;
use crate::cell::{Cell, InputError};
use crate::collision::{CheckOptions, CheckReport, Verdict};
use crate::geometry::Vec2;
use crate::motion::Pose;
use crate::planning::PlannerOptions;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How collisions are fed back.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Feedback {
    /// Best-first search over remedies (`search.rs`).
    #[default]
    Search,
    /// Each round, the better of re-sequencing and one wait at a node (`greedy.rs`).
    Greedy,
}

/// Settings of a solve.
#[derive(Clone, Debug)]
pub struct SolveOptions {
    /// Rounds of sequencing, checking and feedback before giving up (for the search: along
    /// one branch).
    pub max_iterations: usize,
    /// How collisions are fed back.
    pub feedback: Feedback,
    /// The search's budgets and remedies (for [`Feedback::Search`]).
    pub search: SearchOptions,
    /// The sequencer's settings, its seed among them.
    pub sequencer: SequencerOptions,
    /// The planner's settings.
    pub planner: PlannerOptions,
    /// The checker's settings for the schedules.
    pub check: CheckOptions,
    /// Wall time for the whole solve, from [`prepare`] on: the sequencer then returns the
    /// best certified plan found so far, and the search its best certified schedule. `None`:
    /// no limit, and the result depends only on the input and the seed.
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
            max_iterations: 200,
            feedback: Feedback::default(),
            search: SearchOptions::default(),
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
///
/// ```
/// use std::sync::atomic::{AtomicUsize, Ordering};
/// use std::sync::Mutex;
/// use workcell::wcp::{prepare, solve, Collision, Progress, SolveOptions};
/// /// Counts the moves planned and keeps each round's makespan.
/// #[derive(Default)]
/// struct Log { moves: AtomicUsize, rounds: Mutex<Vec<f64>> }
/// impl Progress for Log {
///     fn move_planned(&self) { self.moves.fetch_add(1, Ordering::Relaxed); }
///     fn iteration(&self, _k: usize, makespan: f64, _c: Option<&Collision>) {
///         self.rounds.lock().unwrap().push(makespan);
///     }
/// }
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let (opts, log) = (SolveOptions::default(), Log::default());
/// let solved = solve(&cell, &prepare(&cell, &opts, &log)?, &opts, &log)?;
/// assert!(log.moves.into_inner() > 0);
/// // The last round checked is the final schedule.
/// assert_eq!(log.rounds.into_inner().unwrap().last(), Some(&solved.schedule.makespan));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
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
#[derive(Clone, Debug, PartialEq)]
pub enum Remedy {
    /// The sequencer re-planned with the colliding pair of steps forbidden.
    Resequence,
    /// A robot waits at a node before one of its moves.
    Delay(Delay),
    /// A robot stops at a point of a move's path and waits there.
    Pause {
        /// The robot.
        robot: usize,
        /// The leg (move of its route) that pauses.
        leg: usize,
        /// The leg's nodes.
        nodes: (usize, usize),
        /// Where it stops.
        at: Vec2,
        /// How long it waits there.
        duration: f64,
    },
    /// A robot makes a move slower.
    Slow {
        /// The robot.
        robot: usize,
        /// The leg that is slowed down.
        leg: usize,
        /// The leg's nodes.
        nodes: (usize, usize),
        /// How many times slower than planned.
        factor: f64,
    },
    /// A robot makes a move by another way, around another robot.
    Detour {
        /// The robot.
        robot: usize,
        /// The leg re-planned.
        leg: usize,
        /// The leg's nodes.
        nodes: (usize, usize),
        /// The robot gone around.
        around: usize,
        /// The new path of G.
        path: Vec<Vec2>,
    },
    /// A robot steps aside to a parking pose, waits there and goes on.
    StepAside {
        /// The robot.
        robot: usize,
        /// The leg that goes by way of the parking pose.
        leg: usize,
        /// The leg's nodes.
        nodes: (usize, usize),
        /// The parking pose.
        park: Pose,
        /// How long it waits there.
        duration: f64,
    },
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
    /// Every robot's legs as the loop changed them (waits, pauses, detours, parking).
    pub legs: Legs,
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
    /// Schedules checked: the rounds for the greedy loop, the search nodes for the search.
    pub nodes: usize,
    /// Wall time per stage.
    pub times: StageTimes,
}

/// Builds the lower bounds, plans and certifies for every task the move from the home of
/// its nearest allowed robot (the next nearest when that one fails), or every move (see
/// [`Planning`]). A task that no allowed robot
/// can reach is an input error. The time limit counts from here.
///
/// ```
/// use workcell::wcp::{prepare, SolveOptions};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
/// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
/// let prepared = prepare(&cell, &SolveOptions::default(), &())?;
/// // A small cell has every move planned before sequencing: R1's from its home (node 0)
/// // to the first task (node 1), both ways.
/// assert!(prepared.known[0].contains_key(&(0, 1)) && prepared.known[0].contains_key(&(1, 0)));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
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
///
/// ```
/// use workcell::wcp::{sequencer::SequencerError, sequencer_error};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let e = sequencer_error(&cell, SequencerError::TaskUnassignable { task: 2 });
/// assert_eq!((e.body.as_deref(), e.field.as_str()), (Some("weld-3"), "tasks[2]"));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
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

/// Solves the cell: sequences it collision-blind, then feeds collisions back as
/// `opts.feedback` says, until the checker certifies a schedule or the limits are reached.
///
/// ```
/// use workcell::wcp::{prepare, solve, SolveOptions};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
/// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
/// let opts = SolveOptions::default();
/// let solved = solve(&cell, &prepare(&cell, &opts, &())?, &opts, &())?;
/// assert!(solved.collision_free && solved.report.verdict().is_certified_free());
/// // Collisions cost time: the final makespan is no shorter than the collision-blind one.
/// assert!(solved.schedule.makespan >= solved.blind_makespan);
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn solve(
    cell: &Cell,
    prepared: &Prepared,
    opts: &SolveOptions,
    progress: &dyn Progress,
) -> Result<Solved, InputError> {
    match opts.feedback {
        Feedback::Greedy => greedy::solve(cell, prepared, opts, progress),
        Feedback::Search => search::solve(cell, prepared, opts, progress),
    }
}

impl Solved {
    /// The waits at nodes of the final schedule.
    ///
    /// ```
    /// use workcell::wcp::{prepare, solve, Feedback, SolveOptions};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// // The greedy loop ends by making R2 wait at home (README, "feedback cell").
    /// let opts = SolveOptions { feedback: Feedback::Greedy, ..SolveOptions::default() };
    /// let solved = solve(&cell, &prepare(&cell, &opts, &())?, &opts, &())?;
    /// let delays = solved.delays();
    /// assert_eq!((delays.len(), delays[0].robot, delays[0].before_move), (1, 1, 0));
    /// assert!(solved.collision_free && delays[0].duration > 0.0);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn delays(&self) -> Vec<Delay> {
        Delay::of_legs(&self.routes, &self.legs)
    }
}

/// The schedule of `routes` with `legs`; a failure is an error in the cell's terms.
fn build(
    cell: &Cell,
    routes: &[Vec<usize>],
    legs: &Legs,
    cache: &MoveStore,
) -> Result<Schedule, InputError> {
    Schedule::build(cell, routes, legs, cache)
        .map_err(|e| build_error(cell, routes, legs, cache, e))
}

fn build_error(
    cell: &Cell,
    routes: &[Vec<usize>],
    legs: &Legs,
    cache: &MoveStore,
    e: BuildError,
) -> InputError {
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
        // Blame the task whose duration stretched the axis, as `evaluate` does, and the
        // robot's limits otherwise (its waits are the solver's, never the user's).
        BuildError::Precision { robot: r, time } => {
            let delays = Delay::of_legs(routes, legs);
            let blamed = culprit(cell, r, &routes[r], &delays, cache, time).map(|m| m.blamed);
            match blamed.map(|b| b.activity) {
                Some(Activity::Work(k)) => cell.error(
                    Some(&cell.tasks[k].name),
                    format!("tasks[{k}].duration"),
                    format!(
                        "this duration of {:e} stretches the time axis: {}",
                        cell.tasks[k].duration,
                        e.reason(cell)
                    ),
                ),
                _ => cell.error(Some(robot), format!("robots[{r}]"), e.reason(cell)),
            }
        }
        // Remedies are made to start where the robot is: a jump is a defect of ours.
        BuildError::Discontinuous { .. } => cell.error(
            Some(robot),
            "",
            format!("internal error: {}", e.reason(cell)),
        ),
    }
}

/// Why the checker did not certify a schedule in which it found no collision: its work
/// budget ran out on a pair, or two bodies graze δ too closely to prove either way.
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::wcp::uncertified;
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/near-miss.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// // One evaluation per pair is not enough to prove the near miss free.
/// let report = check(&scene, &CheckOptions { max_work_per_pair: 1, ..CheckOptions::default() });
/// assert!(uncertified(&report).starts_with("the checker spent its work budget"));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn uncertified(report: &CheckReport) -> String {
    match report.verdict() {
        Verdict::Unresolved { budget: b } => format!(
            "the checker spent its work budget ({} evaluations) on {} and {} after t = {:.6} \
             without a proof or a witness",
            b.work, b.bodies[0], b.bodies[1], b.time
        ),
        _ => "the checker cannot certify the schedule: two bodies graze delta".to_owned(),
    }
}

/// One line about a collision: `R1 (move weld-1 -> weld-2) and R2 (task weld-5) at t = 3.2`.
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::planning::PlannerOptions;
/// use workcell::wcp::{describe, legs::default_legs, MoveStore, Schedule};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let store = MoveStore::new(&cell, &PlannerOptions::default());
/// let schedule = Schedule::build(&cell, &[vec![1, 0, 2], vec![3]], &default_legs(2), &store).unwrap();
/// let report = check(&schedule.scene(&cell), &CheckOptions::default());
/// let line = describe(&cell, &schedule.collision(&cell, &report).expect("a collision"));
/// assert!(line.starts_with("R1 (") && line.contains(") and R2 (") && line.contains(" at t = "), "{line}");
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
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
