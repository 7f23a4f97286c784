//! The sequencer's terms: the steps of a route, a conflict between two steps, the options,
//! the solution and why there may be none.

use std::collections::HashSet;
use std::time::Instant;

/// The node of task `t` in every route, graph and instance: node 0 is the robot's home,
/// task `t` is node `t + 1`.
///
/// ```
/// use workcell::wcp::sequencer::{node_task, task_node};
/// assert_eq!((task_node(0), node_task(task_node(7))), (1, 7));
/// ```
#[inline]
pub const fn task_node(t: usize) -> usize {
    t + 1
}

/// The task at node `n` (`n ≥ 1`; node 0 is home).
///
/// ```
/// use workcell::wcp::sequencer::node_task;
/// assert_eq!(node_task(1), 0);
/// ```
#[inline]
pub const fn node_task(n: usize) -> usize {
    n - 1
}

/// One thing a robot does on its route, in the node indices of [`Instance`](super::Instance)
/// (0 = the robot's home, `1 + t` = task `t`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
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
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Conflict {
    /// The first robot and its step.
    pub a: (usize, Step),
    /// The second robot and its step.
    pub b: (usize, Step),
}

/// Knobs of [`solve`](super::solve).
#[derive(Clone, Debug, PartialEq)]
pub struct SequencerOptions {
    /// Seed of the random perturbations; the result depends only on it and the input.
    pub seed: u64,
    /// Independent runs of the local search (run in parallel, at least one);
    /// the best one wins, the first one on ties.
    pub restarts: usize,
    /// Most perturbation rounds (ruin and recreate, then local search) per
    /// restart; a restart stops earlier after `iterations / 5` rounds in a
    /// row that do not improve its best plan in the first epoch without a `deadline`,
    /// `iterations / 4` in later epochs, with a deadline or without `route_exchanges`
    /// (a granular search: a quarter of its rounds).
    pub iterations: usize,
    /// Epochs of the local search: after the first, every restart's chain is kicked (a large
    /// ruin and recreate) and searched again, `effort - 1` times (1: one chain per restart).
    /// The work grows linearly with it and the result depends on it only, not on the
    /// machine; `usize::MAX` with a `deadline`: until the deadline.
    pub effort: usize,
    /// Largest estimated work (elementary DP updates) for the exact search; 0 disables it.
    pub exact_limit: u64,
    /// When given, the local search stops at this instant and returns the best plan found so
    /// far (the result then depends on the machine's speed).
    pub deadline: Option<Instant>,
    /// When given, the first plan of a restart is built faster once this instant has passed
    /// (a granular model then inserts the tasks left near their neighbours): the solve's own
    /// limit, while `deadline` leaves time to plan the plan found.
    pub construction_deadline: Option<Instant>,
    /// When given, a makespan good enough: a restart stops once its plan is this short with
    /// no violation, and restart 0 runs alone first, the others only when it falls short.
    /// A repair's aim (the search over remedies gives the collision-blind makespan, which a
    /// plan under more conflicts is not expected to beat). Deterministic: every restart
    /// stops by its own plan alone.
    pub target: Option<f64>,
    /// Whether the local search exchanges the ends of two routes (2-opt*): at its local
    /// optima only in the first epoch without a `deadline` (the default solve), in every
    /// round otherwise. On by default;
    /// off for a repair (`wcp::sequence::repairing`: the re-sequencings of the search over
    /// remedies and of the greedy loop, the choice of arm configurations), which should
    /// stay near the routes it repairs: moving whole route ends spreads a repair over more
    /// robots, whose schedules must all be checked again. With exchanges in every round of
    /// a repair, 4 arms x 40 tasks (`generate --kind scara --seed 1`) took 9.3 s instead of
    /// 3.9 (21.801 instead of 21.759), and `workpiece-4` of the conflict cells 1,628
    /// schedules instead of 443; only `workpiece-3` gained (21.50 instead of 21.78, which
    /// the search's second pass now finds by asking again, with exchanges, only the
    /// repairs that led to its best schedule). With
    /// exchanges at local optima (as the default solve makes them), `workpiece-4` took 605
    /// schedules instead of 581.
    pub route_exchanges: bool,
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
            effort: 1,
            exact_limit: 10_000_000,
            deadline: None,
            construction_deadline: None,
            target: None,
            route_exchanges: true,
        }
    }
}

/// The sequences found by [`solve`](super::solve) and their costs.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// Per robot, its tasks in visiting order.
    pub sequences: Vec<Vec<usize>>,
    /// Longest route time, as [`Instance::makespan`](super::Instance::makespan) computes it.
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

/// Why [`solve`](super::solve) or [`Instance::new`](super::Instance::new) gave up.
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
        /// Index of the conflict in the list given to [`solve`](super::solve).
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
            to: task_node(t),
        });
        out.push(Step::Stay { node: task_node(t) });
        prev = task_node(t);
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
