//! The sequencer: which robot does which task, and in which order.
//!
//! Each robot leaves its home at time 0, visits its tasks in order, stays at
//! each task for the task's duration and comes back home. The sequencer
//! minimises the makespan (the longest route time), then the sum of the route
//! times, while every task is done exactly once by a robot allowed to do it.
//!
//! Travel times are per robot and may be infinite (no move exists); an
//! infinite arc is never used. The collision checker may forbid pairs of
//! [`Step`]s of two robots as [`Conflict`]s; the number of violated conflicts
//! comes first in the objective.
//!
//! Small instances are solved exactly, ignoring conflicts: Held-Karp gives
//! each robot's best route time for every subset of its tasks, then a dynamic
//! programme over subsets of tasks assigns them to robots. The others, and
//! small ones whose optimum violates a conflict, go to an iterated local
//! search: cheapest insertion, then descents (relocate and or-opt within and
//! between routes, swap, 2-opt) alternating with seeded ruin-and-recreate
//! perturbations, over independent restarts run in parallel. From
//! [`GRANULAR_FROM_TASKS`] tasks on, the descents are granular: each task is
//! only moved next to its nearest tasks, and only what a change touched is
//! looked at again. The result depends only on the input and the seed: no
//! clock, no thread timing, no hash order (unless a deadline ends the search).
//!
//! Travel times come from matrices ([`Instance::new`]) or, for large cells,
//! from lower bounds with the exact times known so far
//! ([`Instance::bounded`]): beyond 2²⁴ arcs only the costs between nodes near each other
//! along a Hilbert curve of the task positions are stored, in memory linear in the nodes.
//!
//! ```
//! use workcell::wcp::sequencer::{solve, Instance, SequencerOptions};
//! // One robot, two tasks on a line at 1 and 2, home at 0, unit speed.
//! let pos = [0.0, 1.0, 2.0];
//! let inst = Instance::from_fn(vec![0.5, 0.5], vec![vec![true, true]], |_, a, b| {
//!     f64::abs(pos[a] - pos[b])
//! })
//! .unwrap();
//! let sol = solve(&inst, &[], &SequencerOptions::default()).unwrap();
//! assert_eq!(sol.makespan, 5.0);
//! assert!(sol.optimal);
//! ```

mod bounds;
mod construct;
mod exact;
mod granular;
mod ils;
mod instance;
mod lazy_costs;
mod local_search;
mod model;
mod plan;

use std::collections::HashSet;
use std::time::Instant;

pub use bounds::{BoundLimits, Bounds};
pub use instance::{ExactArcs, Instance};
pub use model::GRANULAR_FROM_TASKS;

/// One thing a robot does on its route, in the node indices of [`Instance`]
/// (0 = the robot's home, `1 + t` = task `t`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Step {
    /// The robot travels from node `from` to node `to`.
    Move {
        /// Node the move starts from.
        from: usize,
        /// Node the move ends at.
        to: usize,
    },
    /// The robot stays at `node`: at home (every robot, always) or at a task it does.
    Stay {
        /// Node the robot stays at.
        node: usize,
    },
}

/// Feedback from the collision checker: robot `a.0` doing step `a.1` and
/// robot `b.0` doing step `b.1` may not both be chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Conflict {
    /// The first robot and its step.
    pub a: (usize, Step),
    /// The second robot and its step.
    pub b: (usize, Step),
}

/// Knobs of [`solve`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SequencerOptions {
    /// Seed of the random perturbations; the result depends only on it and the input.
    pub seed: u64,
    /// Independent runs of the local search (run in parallel, at least one);
    /// the best one wins, the first one on ties.
    pub restarts: usize,
    /// Most perturbation rounds (ruin and recreate, then local search) per
    /// restart; a restart stops earlier after `iterations / 4` rounds in a
    /// row that do not improve its best plan.
    pub iterations: usize,
    /// Largest estimated work (elementary DP updates) for the exact search; 0 disables it.
    pub exact_limit: u64,
    /// When given, the local search stops at this instant and returns the best plan found so
    /// far (the result then depends on the machine's speed).
    pub deadline: Option<Instant>,
}

impl Default for SequencerOptions {
    /// The exact search covers up to 12 tasks for up to 5 robots when every
    /// task is allowed to every robot, more when tasks are restricted (a few
    /// tens of milliseconds at most).
    fn default() -> Self {
        SequencerOptions {
            seed: 0,
            restarts: 4,
            iterations: 400,
            exact_limit: 10_000_000,
            deadline: None,
        }
    }
}

/// The sequences found by [`solve`] and their costs.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// Per robot, its tasks in visiting order.
    pub sequences: Vec<Vec<usize>>,
    /// Longest route time, as [`Instance::makespan`] computes it.
    pub makespan: f64,
    /// Sum of the route times.
    pub total: f64,
    /// Number of conflicts the sequences violate.
    pub violations: usize,
    /// The exact search proved the makespan minimal, with the total minimal
    /// among makespan-optimal plans (up to rounding); with conflicts, only
    /// when the collision-blind optimum violates none of them.
    pub optimal: bool,
}

/// Why [`solve`] or [`Instance::new`] gave up.
#[derive(thiserror::Error, Debug, Clone, PartialEq)]
pub enum SequencerError {
    /// No allowed robot has a finite way from its home to the task and back
    /// (directly or through other tasks it may do).
    #[error("task {task}: no allowed robot can reach it from home and come back")]
    TaskUnassignable {
        /// The task.
        task: usize,
    },
    /// Inconsistent sizes, or durations or travel times that are NaN or negative.
    #[error("bad instance: {0}")]
    BadInstance(String),
    /// A conflict names a robot or a node the instance does not have.
    #[error("conflict {index}: {reason}")]
    BadConflict {
        /// Index of the conflict in the list given to [`solve`].
        index: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// Every plan found uses an infinite travel time (proved when the search was exact).
    #[error("no plan found that avoids infinite travel times")]
    Infeasible,
}

/// The steps a route uses: `Stay{0}` (home, always), `Move{0, 1+t1}`,
/// `Stay{1+t1}`, `Move{1+t1, 1+t2}`, …, `Move{1+tk, 0}`.
/// An empty route uses only `Stay{0}`.
///
/// ```
/// use workcell::wcp::sequencer::{steps, Step};
/// let (stay, go) = (|node| Step::Stay { node }, |from, to| Step::Move { from, to });
/// assert_eq!(steps(&[2, 0]), [stay(0), go(0, 3), stay(3), go(3, 1), stay(1), go(1, 0)]);
/// assert_eq!(steps(&[]), [stay(0)]);
/// ```
pub fn steps(route: &[usize]) -> Vec<Step> {
    let mut out = Vec::with_capacity(2 * route.len() + 2);
    out.push(Step::Stay { node: 0 });
    let mut prev = 0;
    for &t in route {
        out.push(Step::Move {
            from: prev,
            to: t + 1,
        });
        out.push(Step::Stay { node: t + 1 });
        prev = t + 1;
    }
    if !route.is_empty() {
        out.push(Step::Move { from: prev, to: 0 });
    }
    out
}

/// Number of `conflicts` violated by `sequences` (one route per robot): robot
/// `a.0` uses step `a.1` and robot `b.0` uses step `b.1`. Robots beyond
/// `sequences` use no step.
///
/// ```
/// use workcell::wcp::sequencer::{count_violations, Conflict, Step};
/// // Robot 0 at task 0 (node 1) and robot 1 at task 1 (node 2) may not both happen.
/// let c = Conflict { a: (0, Step::Stay { node: 1 }), b: (1, Step::Stay { node: 2 }) };
/// assert_eq!(count_violations(&[c], &[vec![0], vec![1]]), 1);
/// assert_eq!(count_violations(&[c], &[vec![0, 1], vec![]]), 0);
/// assert_eq!(count_violations(&[c], &[vec![0]]), 0); // robot 1 does nothing
/// ```
pub fn count_violations(conflicts: &[Conflict], sequences: &[Vec<usize>]) -> usize {
    let used: Vec<HashSet<Step>> = sequences
        .iter()
        .map(|s| steps(s).into_iter().collect())
        .collect();
    let uses = |(r, s): (usize, Step)| used.get(r).is_some_and(|set| set.contains(&s));
    conflicts.iter().filter(|c| uses(c.a) && uses(c.b)).count()
}

/// Assigns and orders the tasks, minimising (violated conflicts, makespan,
/// total route time) lexicographically.
///
/// The result is deterministic for a given input and `opts.seed`.
///
/// ```
/// use workcell::wcp::sequencer::solve;
/// use workcell::wcp::sequencer::{Conflict, Instance, SequencerOptions, Step};
/// // Two robots with homes at 0 and 4, tasks at 1 and 3 on a line, each lasting 0.5.
/// let (homes, tasks) = ([0.0, 4.0], [1.0, 3.0]);
/// let at = |r: usize, n: usize| if n == 0 { homes[r] } else { tasks[n - 1] };
/// let inst = Instance::from_fn(vec![0.5, 0.5], vec![vec![true, true]; 2], |r, a, b| f64::abs(at(r, a) - at(r, b)))?;
/// // The checker forbids robot 0 at task 0 while robot 1 is at task 1.
/// let conflict = Conflict { a: (0, Step::Stay { node: 1 }), b: (1, Step::Stay { node: 2 }) };
/// let free = solve(&inst, &[], &SequencerOptions::default())?;
/// assert_eq!((free.sequences.clone(), free.makespan), (vec![vec![0], vec![1]], 2.5));
/// let apart = solve(&inst, &[conflict], &SequencerOptions::default())?;
/// assert_eq!(apart.violations, 0);
/// assert!(apart.makespan > 2.5); // one robot now does both tasks
/// # Ok::<(), workcell::wcp::sequencer::SequencerError>(())
/// ```
pub fn solve(
    inst: &Instance,
    conflicts: &[Conflict],
    opts: &SequencerOptions,
) -> Result<Solution, SequencerError> {
    solve_from(inst, conflicts, opts, None, &|_| {})
}

/// As [`solve`]; when the exact search does not settle it, every restart of the local search
/// starts from `start` (one route per robot, as [`Solution::sequences`]) when given.
/// `on_best` hears each makespan that improves a restart's best (from any thread; infinite
/// travel times count as a large penalty there).
///
/// ```
/// use std::sync::Mutex;
/// use workcell::wcp::sequencer::solve_from;
/// use workcell::wcp::sequencer::{Conflict, Instance, SequencerOptions, Step};
/// // Two robots with homes at 0 and 4, tasks at 1 and 3 on a line, each lasting 0.5.
/// let (homes, tasks) = ([0.0, 4.0], [1.0, 3.0]);
/// let at = |r: usize, n: usize| if n == 0 { homes[r] } else { tasks[n - 1] };
/// let inst = Instance::from_fn(vec![0.5, 0.5], vec![vec![true, true]; 2], |r, a, b| f64::abs(at(r, a) - at(r, b)))?;
/// // The checker forbids robot 0 at task 0 while robot 1 is at task 1.
/// let conflict = Conflict { a: (0, Step::Stay { node: 1 }), b: (1, Step::Stay { node: 2 }) };
/// // Beyond the exact search (exact_limit 0), from a given start.
/// let opts = SequencerOptions { exact_limit: 0, ..SequencerOptions::default() };
/// let heard = Mutex::new(Vec::new());
/// let start = [vec![0, 1], vec![]];
/// let sol = solve_from(&inst, &[conflict], &opts, Some(&start), &|m| heard.lock().unwrap().push(m))?;
/// assert_eq!(sol.violations, 0);
/// assert!(sol.makespan <= inst.makespan(&start));
/// assert!(heard.into_inner().unwrap().iter().all(|&m| m >= sol.makespan));
/// # Ok::<(), workcell::wcp::sequencer::SequencerError>(())
/// ```
pub fn solve_from(
    inst: &Instance,
    conflicts: &[Conflict],
    opts: &SequencerOptions,
    start: Option<&[Vec<usize>]>,
    on_best: &(dyn Fn(f64) + Sync),
) -> Result<Solution, SequencerError> {
    inst.check()?;
    check_conflicts(inst, conflicts)?;
    let model = model::Model::new(inst, conflicts)?;
    let exact = if exact::work(&model) <= opts.exact_limit as f64 {
        Some(exact::solve(inst, &model).ok_or(SequencerError::Infeasible)?)
    } else {
        None
    };
    if let Some(seqs) = &exact {
        if conflicts.is_empty() || count_violations(conflicts, seqs) == 0 {
            return finish(inst, conflicts, seqs.clone(), true);
        }
    }
    // The blind optimum seeds the search: it is often one repair away.
    let start = match (exact, start) {
        (Some(seqs), _) => ils::Start::Fresh(Some(plan::Plan::from_sequences(&model, &seqs))),
        (None, Some(seqs)) => {
            check_start(inst, &model, seqs)?;
            ils::Start::All(plan::Plan::from_sequences(&model, seqs))
        }
        (None, None) => ils::Start::Fresh(None),
    };
    let best = ils::search(&model, opts, start, on_best);
    finish(inst, conflicts, best.sequences(), false)
}

fn finish(
    inst: &Instance,
    conflicts: &[Conflict],
    sequences: Vec<Vec<usize>>,
    optimal: bool,
) -> Result<Solution, SequencerError> {
    let makespan = inst.makespan(&sequences);
    if !makespan.is_finite() {
        return Err(SequencerError::Infeasible);
    }
    Ok(Solution {
        total: inst.total(&sequences),
        violations: count_violations(conflicts, &sequences),
        makespan,
        sequences,
        optimal,
    })
}

/// A start must give every task once to a robot able to do it.
fn check_start(
    inst: &Instance,
    model: &model::Model,
    seqs: &[Vec<usize>],
) -> Result<(), SequencerError> {
    let mut seen = vec![false; inst.tasks];
    let bad = |msg: String| Err(SequencerError::BadInstance(format!("start: {msg}")));
    if seqs.len() != inst.robots {
        return bad(format!("{} routes for {} robots", seqs.len(), inst.robots));
    }
    for (r, seq) in seqs.iter().enumerate() {
        for &t in seq {
            if t >= inst.tasks || seen[t] || !model.can(r, t) {
                return bad(format!("robot {r} cannot take task {t}"));
            }
            seen[t] = true;
        }
    }
    match seen.iter().position(|s| !s) {
        Some(t) => bad(format!("task {t} has no robot")),
        None => Ok(()),
    }
}

fn check_conflicts(inst: &Instance, conflicts: &[Conflict]) -> Result<(), SequencerError> {
    let nodes = inst.tasks + 1;
    for (index, c) in conflicts.iter().enumerate() {
        for (r, step) in [c.a, c.b] {
            let bad = |reason: String| SequencerError::BadConflict { index, reason };
            if r >= inst.robots {
                return Err(bad(format!("robot {r} of {}", inst.robots)));
            }
            let node = match step {
                Step::Move { from, to } => from.max(to),
                Step::Stay { node } => node,
            };
            if node >= nodes {
                return Err(bad(format!("node {node} of {nodes}")));
            }
        }
    }
    Ok(())
}
