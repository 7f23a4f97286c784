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
mod offers;
mod plan;
mod terms;

pub use bounds::{BoundLimits, Bounds, JointNodes};
pub use instance::{ExactArcs, Instance};
pub use model::GRANULAR_FROM_TASKS;
pub use terms::{
    count_violations, node_task, steps, task_node, Conflict, SequencerError, SequencerOptions,
    Solution, Step,
};

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
