//! Before sequencing: the lower bounds of every move and the moves planned up front
//! ([`prepare`]), and what a solve reports as it goes ([`Progress`], [`StageTimes`]).

use super::configurations::{task_configurations, Assignment};
use super::graph::{check_reachable, plan_reaches};
use super::moves::{bounds, robot_nodes, MoveStore};
use super::options::{
    ConfigurationChoice, Planning, SolveOptions, AUTO_ALL_LIMIT_SHARE, AUTO_ALL_MAX_MOVES,
};
use super::schedule::Collision;
use super::sequencer::{Bounds, ExactArcs, SequencerError};
use crate::cell::{Cell, InputError};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Progress of a solve, for a progress bar. Called from the solving thread, except
/// `move_planned`, which planning threads call.
///
/// ```
/// use std::sync::atomic::{AtomicUsize, Ordering};
/// use std::sync::Mutex;
/// use workcell::wcp::{prepare, solve, Collision, Progress, SolveOptions};
/// /// Counts the moves planned, keeps each round's makespan and the best certified one.
/// #[derive(Default)]
/// struct Log { moves: AtomicUsize, rounds: Mutex<Vec<f64>>, certified: Mutex<Option<f64>> }
/// impl Progress for Log {
///     fn move_planned(&self) { self.moves.fetch_add(1, Ordering::Relaxed); }
///     fn iteration(&self, _k: usize, makespan: f64, _c: Option<&Collision>) {
///         self.rounds.lock().unwrap().push(makespan);
///     }
///     fn certified(&self, makespan: f64) { *self.certified.lock().unwrap() = Some(makespan); }
/// }
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let (opts, log) = (SolveOptions::default(), Log::default());
/// let solved = solve(&cell, &prepare(&cell, &opts, &log)?, &opts, &log)?;
/// assert!(log.moves.into_inner() > 0);
/// // The last round checked is the final schedule, and the last certified one too.
/// assert_eq!(log.rounds.into_inner().unwrap().last(), Some(&solved.schedule.makespan));
/// assert_eq!(log.certified.into_inner().unwrap(), Some(solved.schedule.makespan));
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
    /// A schedule of this makespan was certified collision-free and is the best answer so far
    /// (after its [`iteration`](Progress::iteration)): the last one heard is the solve's.
    fn certified(&self, _makespan: f64) {}
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

/// What [`prepare`] left unplanned when the time limit ran out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Unfinished {
    /// Moves (or, when planning for each task the move from its nearest robot's home,
    /// tasks) planned.
    pub done: usize,
    /// Of how many.
    pub total: usize,
    /// Whether the count is of tasks (see `done`), else of moves.
    pub tasks: bool,
}

impl std::fmt::Display for Unfinished {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        let what = match self.tasks {
            true => "tasks' moves from home",
            false => "moves",
        };
        write!(
            f,
            "the time limit ran out while planning: {} of {} {what} planned and certified, \
             and a schedule needs them all; give a longer time limit",
            self.done, self.total
        )
    }
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
    /// When the time limit ran out before every move [`prepare`] plans was planned: how
    /// many were left. No schedule can be built in the time given; [`solve`](crate::wcp::solve)
    /// would plan the rest on demand, past the limit.
    pub unfinished: Option<Unfinished>,
    /// The time a plan's moves still to plan are expected to take, at the pace [`prepare`]
    /// planned its own: the sequencer stops searching that much before the deadline, so that
    /// planning its plan ends within the limit. Zero when every move was planned.
    pub(crate) reserve: Duration,
    /// Time spent so far.
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
    // Every task reached by one of its robots, or refused with each arm's reason.
    let found = match cell.robots.iter().any(|r| r.as_arm().is_some()) {
        true => task_configurations(cell, &opts.ik)?,
        false => Default::default(),
    };
    let assignment = match opts.configurations {
        ConfigurationChoice::First => Assignment::first(cell, Arc::new(found)),
        _ => Assignment::nearest_home(cell, Arc::new(found)),
    };
    let moves = MoveStore::with_assignment(cell, &opts.planner, assignment);
    let bounds = Arc::new(bounds(cell, moves.assignment()));
    times.graph = clock.elapsed();
    let clock = Instant::now();
    let all_moves: usize = (0..cell.robots.len())
        .map(|r| {
            let n = robot_nodes(cell, r).len();
            n * (n - 1) / 2
        })
        .sum();
    // Under a time limit, `Auto` plans lazily first and the rest only if it fits (below).
    let mut plan_all = match opts.planning {
        Planning::Auto => all_moves <= AUTO_ALL_MAX_MOVES && deadline.is_none(),
        Planning::Lazy => false,
        Planning::All => true,
    };
    let every_pair = || {
        let mut pairs = Vec::with_capacity(all_moves);
        for r in 0..cell.robots.len() {
            let nodes = robot_nodes(cell, r);
            for (i, &a) in nodes.iter().enumerate() {
                pairs.extend(nodes[i + 1..].iter().map(|&b| (r, a, b)));
            }
        }
        pairs
    };
    let mut unfinished;
    let mut pairs: Vec<(usize, usize, usize)> = if plan_all {
        let pairs = every_pair();
        progress.planning(pairs.len());
        let planned = plan_until(&moves, &pairs, deadline, &|| progress.move_planned());
        let done = planned.len();
        let total = pairs.len();
        unfinished = (done < total).then_some(Unfinished {
            done,
            total,
            tasks: false,
        });
        planned
    } else {
        progress.planning(cell.tasks.len());
        let tick = || progress.move_planned();
        let (planned, left) = plan_reaches(cell, &moves, &bounds, &tick, deadline);
        let total = cell.tasks.len();
        unfinished = (left > 0).then_some(Unfinished {
            done: total - left,
            total,
            tasks: true,
        });
        planned
    };
    // The rest of the moves, when planning them at the pace so far takes at most
    // `AUTO_ALL_LIMIT_SHARE` of the time limit: exact times from the start, and time left.
    if let (Planning::Auto, Some(limit), None) = (opts.planning, opts.time_limit, unfinished) {
        let pace = clock.elapsed().as_secs_f64() / pairs.len().max(1) as f64;
        let rest = all_moves.saturating_sub(pairs.len()) as f64;
        if all_moves <= AUTO_ALL_MAX_MOVES
            && pace * rest <= limit.as_secs_f64() * AUTO_ALL_LIMIT_SHARE
        {
            let all = every_pair();
            progress.planning(all.len());
            // The moves planned already come from the store, at once.
            let planned = plan_until(&moves, &all, deadline, &|| progress.move_planned());
            plan_all = planned.len() == all.len();
            // Out of time part way: a lazy preparation that knows more moves.
            pairs.extend(planned);
            pairs.sort_unstable();
            pairs.dedup();
            unfinished = None;
        }
    }
    // Out of time, the tasks not reached yet stay unknown: finding whether they can be
    // reached is the planning that did not fit.
    if unfinished.is_none() {
        check_reachable(cell, &moves)?;
    }
    let mut known: ExactArcs = vec![Default::default(); cell.robots.len()];
    for &(r, a, b) in &pairs {
        let d = moves.duration(r, a, b).unwrap_or(f64::INFINITY);
        known[r].insert((a, b), d);
        known[r].insert((b, a), d);
    }
    times.planning = clock.elapsed();
    // A lazy plan needs about one move per task and per robot that was not planned here.
    let reserve = match (plan_all, pairs.len()) {
        (true, _) | (false, 0) => Duration::ZERO,
        (false, planned) => {
            let moves = (cell.tasks.len() + cell.robots.len()) as u32;
            let pace = times.planning / u32::try_from(planned).unwrap_or(u32::MAX);
            pace.checked_mul(moves).unwrap_or(Duration::MAX)
        }
    };
    Ok(Prepared {
        moves,
        bounds,
        known: Arc::new(known),
        deadline,
        unfinished,
        reserve,
        times,
    })
}

/// Plans `pairs` in parallel, starting none once `deadline` has passed; the pairs planned.
fn plan_until(
    moves: &MoveStore,
    pairs: &[(usize, usize, usize)],
    deadline: Option<Instant>,
    progress: &(dyn Fn() + Sync),
) -> Vec<(usize, usize, usize)> {
    use rayon::prelude::*;
    let late = || deadline.is_some_and(|d| Instant::now() >= d);
    let planned = pairs.par_iter().map(|&(r, a, b)| {
        if late() {
            return None;
        }
        let _ = moves.duration(r, a, b);
        progress();
        Some((r, a, b))
    });
    planned.flatten().collect()
}

impl Prepared {
    /// A lower bound of the collision-blind makespan (and so of any schedule's): the longest
    /// of the tasks' shortest round trips, each from the home of the robot that does it
    /// soonest, on the moves' lower bounds or their planned times where known.
    ///
    /// ```
    /// use workcell::wcp::{prepare, sequence, SolveOptions};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let opts = SolveOptions::default();
    /// let prepared = prepare(&cell, &opts, &())?;
    /// let bound = prepared.makespan_lower_bound(&cell);
    /// assert!(bound > 0.0 && bound <= sequence(&cell, &prepared, &[], &opts)?.makespan);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn makespan_lower_bound(&self, cell: &Cell) -> f64 {
        let leg = |r: usize, a: usize, b: usize| {
            let known = self.known.get(r).and_then(|k| k.get(&(a, b)).copied());
            known.unwrap_or_else(|| self.bounds.bound(r, a, b))
        };
        let trip = |t: usize| {
            let node = crate::wcp::sequencer::task_node(t);
            (cell.tasks[t].robots.iter())
                .map(|&r| leg(r, 0, node) + cell.tasks[t].duration + leg(r, node, 0))
                .filter(|trip| trip.is_finite())
                .fold(f64::INFINITY, f64::min)
        };
        (0..cell.tasks.len())
            .map(trip)
            .filter(|trip| trip.is_finite())
            .fold(0.0, f64::max)
    }

    /// The same preparation with the arms in the configurations of `assignment`: the store
    /// shares every move planned so far, the bounds and the known moves are those of the
    /// new configurations.
    pub(super) fn reassigned(&self, cell: &Cell, assignment: Assignment) -> Prepared {
        let moves = self.moves.assigned(assignment);
        let bounds = Arc::new(bounds(cell, moves.assignment()));
        let mut known = (*self.known).clone();
        for (r, arcs) in known.iter_mut().enumerate() {
            if cell.robots[r].as_arm().is_none() {
                continue;
            }
            // The moves of the new configurations planned already, both ways.
            let pairs: Vec<(usize, usize)> = arcs.keys().copied().collect();
            arcs.clear();
            for (a, b) in pairs {
                if let Some(outcome) = moves.known(r, a, b) {
                    arcs.insert((a, b), outcome.unwrap_or(f64::INFINITY));
                }
            }
        }
        Prepared {
            moves,
            bounds,
            known: Arc::new(known),
            deadline: self.deadline,
            unfinished: self.unfinished,
            reserve: self.reserve,
            times: self.times,
        }
    }
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
