//! Lazy sequencing: the sequencer works on lower bounds of the moves not planned yet, the
//! moves its plan uses are then planned and certified, and it runs again on what it learnt
//! until every move of its plan is exact.
//!
//! Each round costs the plan's moves that were still bounds: far fewer than every pair of
//! nodes. Bounds never exceed the planned times, so a plan all of whose moves are exact is
//! also a local optimum (an optimum, when the exact search solved it) of the fully planned
//! problem: every alternative it rejected only gets longer once planned.
//!
//! The rounds stop when the plan's moves were all exact already (or their bounds were their
//! times), when planning them left its makespan as the search saw it, when
//! [`STALL_ROUNDS`] rounds in a row found no better certified plan (not for the exact
//! search, which converges), or when the time limit is out; the best certified plan of all
//! rounds is returned.
//!
//! A call starts from the moves of [`Prepared::known`] and learns only from the moves its own
//! rounds plan (the store plans each move once for everyone): its result never depends on
//! what other calls, in other threads, planned before it.

use super::options::SolveOptions;
use super::prepare::{sequencer_error, Prepared, Progress};
use super::sequencer::{self, steps, ExactArcs, Instance, Solution, Step};
use crate::cell::{Cell, InputError};
use std::sync::Arc;
use std::time::Instant;

/// Later rounds search this many times less than the first.
const WARM_ROUND_SHARE: usize = 8;
/// A plan whose makespan, once its moves are exact, is within this relative amount of what
/// the search saw is settled: the moves that changed do not lie on its longest route.
const SETTLED_TOL: f64 = 1e-12;
/// Rounds in a row without a better certified plan after which the best one is kept.
const STALL_ROUNDS: usize = 3;

/// The plan of the sequencer for `conflicts` (see [`sequencer::solve`]), every move of it
/// planned and certified, its makespan computed on them. With a time limit the best such
/// plan found when it runs out (the round under way still plans its moves, so that there is
/// one).
///
/// ```
/// use workcell::wcp::sequencer::{Conflict, Step};
/// use workcell::wcp::{prepare, sequence, SolveOptions};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let opts = SolveOptions::default();
/// let prepared = prepare(&cell, &opts, &())?;
/// let blind = sequence(&cell, &prepared, &[], &opts)?;
/// assert_eq!(blind.sequences.iter().map(Vec::len).sum::<usize>(), 4); // every weld, once
/// // Forbid R1 at weld-2 (node 2) while R2 is at weld-4 (node 4).
/// let c = Conflict { a: (0, Step::Stay { node: 2 }), b: (1, Step::Stay { node: 4 }) };
/// let apart = sequence(&cell, &prepared, &[c], &opts)?;
/// assert_eq!(apart.violations, 0);
/// assert!(apart.makespan >= blind.makespan);
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn sequence(
    cell: &Cell,
    prepared: &Prepared,
    conflicts: &[sequencer::Conflict],
    opts: &SolveOptions,
) -> Result<Solution, InputError> {
    sequence_with(cell, prepared, conflicts, opts, None, &())
}

/// As [`sequence`]; the local search starts from `start` (one route per robot) when given,
/// and `progress` hears the rounds and the makespans found.
///
/// ```
/// use workcell::wcp::{prepare, sequence, sequence_with, SolveOptions};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let opts = SolveOptions::default();
/// let prepared = prepare(&cell, &opts, &())?;
/// let start = [vec![0, 1, 2, 3], vec![]];
/// let sol = sequence_with(&cell, &prepared, &[], &opts, Some(&start), &())?;
/// // No worse than the start, and here as good as without one.
/// assert_eq!(sol.makespan, sequence(&cell, &prepared, &[], &opts)?.makespan);
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn sequence_with(
    cell: &Cell,
    prepared: &Prepared,
    conflicts: &[sequencer::Conflict],
    opts: &SolveOptions,
    start: Option<&[Vec<usize>]>,
    progress: &dyn Progress,
) -> Result<Solution, InputError> {
    let duration: Vec<f64> = cell.tasks.iter().map(|t| t.duration).collect();
    let allowed: Vec<Vec<bool>> = (0..cell.robots.len())
        .map(|r| cell.tasks.iter().map(|t| t.robots.contains(&r)).collect())
        .collect();
    let mut seq_opts = opts.sequencer.clone();
    // The search stops early enough to plan its plan's moves within the limit; the first
    // plan is built in full until the limit itself.
    seq_opts.construction_deadline = prepared.deadline;
    let limit = prepared
        .deadline
        .map(|d| d.checked_sub(prepared.reserve).unwrap_or_else(Instant::now));
    // A caller's own deadline (a share of the time) may come first.
    seq_opts.deadline = match (opts.sequencer.deadline, limit) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    };
    let mut known: Arc<ExactArcs> = prepared.known.clone();
    let mut start: Option<Vec<Vec<usize>>> = start.map(<[_]>::to_vec);
    let mut best: Option<Solution> = None;
    let mut stalled = 0;
    for round in 1.. {
        progress.sequencing(round);
        let inst = Instance::bounded(
            duration.clone(),
            allowed.clone(),
            prepared.bounds.clone(),
            known.clone(),
        )
        .map_err(|e| sequencer_error(cell, e))?;
        let on_best = |m: f64| progress.best(m);
        let sol =
            match sequencer::solve_from(&inst, conflicts, &seq_opts, start.as_deref(), &on_best) {
                Ok(sol) => sol,
                // A plan through a move that turned out impossible may be the only one the
                // bounds allowed: with a certified plan in hand, keep it.
                Err(sequencer::SequencerError::Infeasible) if best.is_some() => break,
                Err(e) => return Err(sequencer_error(cell, e)),
            };
        // Every move of the plan is known now: its true costs.
        let exact = learn_moves(prepared, &inst, &sol, &mut known);
        let mut certified = evaluate(prepared, &inst, &known, conflicts, sol.clone(), exact);
        // The makespan the search aimed at is the true one: the moves that changed lie off
        // the longest route. An optimum on bounds that keeps its makespan once exact is an
        // optimum: no plan is shorter on the exact times than on their bounds.
        let settled = certified.violations == sol.violations
            && certified.makespan <= sol.makespan * (1.0 + SETTLED_TOL);
        certified.optimal = sol.optimal && (exact || settled);
        progress.best(certified.makespan);
        stalled += 1;
        if certified.makespan.is_finite() {
            if best.as_ref().is_none_or(|b| better(&certified, b)) {
                stalled = 0;
            }
            // Ties go to the later round: it knows more (and may have proved its plan
            // optimal).
            if best.as_ref().is_none_or(|b| !better(b, &certified)) {
                best = Some(certified);
            }
        }
        let out_of_time = prepared.deadline.is_some_and(|d| Instant::now() >= d);
        // The exact search converges on its own: every round plans moves it had not.
        let stalled_out = stalled >= STALL_ROUNDS && !sol.optimal;
        let stop = exact || settled || out_of_time || stalled_out;
        if stop && best.is_some() {
            break;
        }
        start = Some(sol.sequences);
        // Later rounds start from the last plan, on mostly the same times: a shorter search
        // repairs what the new times changed.
        seq_opts.iterations = (opts.sequencer.iterations / WARM_ROUND_SHARE).max(1);
        seq_opts.effort = 1;
    }
    best.ok_or_else(|| sequencer_error(cell, sequencer::SequencerError::Infeasible))
}

/// The settings of a sequencing that repairs a plan (a re-sequencing, a choice of
/// configurations): one epoch of the local search, whatever effort the blind plan gets, and
/// no route-end exchanges ([`SequencerOptions::route_exchanges`]).
///
/// [`SequencerOptions::route_exchanges`]: crate::wcp::sequencer::SequencerOptions::route_exchanges
pub(crate) fn repairing(opts: &SolveOptions) -> SolveOptions {
    let mut opts = opts.clone();
    opts.sequencer.effort = 1;
    opts.sequencer.route_exchanges = false;
    opts
}

/// The collision-blind plan of a solve: [`sequence_with`] from no start, where, with a time
/// limit and an effort beyond one epoch, the sequencer may take
/// [`SolveOptions::blind_share`] of the time left, so that the search over remedies gets the
/// rest when the plan collides (and the plan is refined with it when it does not).
pub(crate) fn sequence_blind(
    cell: &Cell,
    prepared: &Prepared,
    opts: &SolveOptions,
    progress: &dyn Progress,
) -> Result<Solution, InputError> {
    let opts = blind_options(opts, prepared);
    sequence_with(cell, prepared, &[], &opts, None, progress)
}

fn blind_options(opts: &SolveOptions, prepared: &Prepared) -> SolveOptions {
    let mut opts = opts.clone();
    if let (Some(deadline), true) = (prepared.deadline, opts.sequencer.effort > 1) {
        let now = Instant::now();
        let share = deadline
            .saturating_duration_since(now)
            // A NaN share is 0 (`clamp` keeps NaN, and `mul_f64` panics on it).
            .mul_f64(match opts.blind_share.is_nan() {
                true => 0.0,
                false => opts.blind_share.clamp(0.0, 1.0),
            });
        opts.sequencer.deadline = Some(now + share);
    }
    opts
}

/// Plans the moves of `sol` that `inst` only bounds and adds their times to `known` (both
/// ways); whether the plan's costs were exact already (no move missing, or each bound met).
fn learn_moves(
    prepared: &Prepared,
    inst: &Instance,
    sol: &Solution,
    known: &mut Arc<ExactArcs>,
) -> bool {
    let missing = bounded_moves(inst, &sol.sequences);
    let times = prepared.moves.plan_all(&missing, &|| ());
    let exact_all = missing
        .iter()
        .zip(&times)
        .all(|(&(r, a, b), &t)| t == inst.travel(r, a, b) && t == inst.travel(r, b, a));
    let table = Arc::make_mut(known);
    for (&(r, a, b), &t) in missing.iter().zip(&times) {
        table[r].insert((a, b), t);
        table[r].insert((b, a), t);
    }
    missing.is_empty() || exact_all
}

/// The moves of `sequences` whose travel time `inst` only bounds, as `(robot, a, b)` with
/// `a < b`, sorted, each once.
fn bounded_moves(inst: &Instance, sequences: &[Vec<usize>]) -> Vec<(usize, usize, usize)> {
    let mut out = Vec::new();
    for (r, route) in sequences.iter().enumerate() {
        for step in steps(route) {
            if let Step::Move { from, to } = step {
                if !inst.is_exact(r, from, to) {
                    out.push((r, from.min(to), from.max(to)));
                }
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// `sol` costed on the known moves (all of its own are); optimal only if its moves' bounds
/// were their exact times.
fn evaluate(
    prepared: &Prepared,
    inst: &Instance,
    known: &Arc<ExactArcs>,
    conflicts: &[sequencer::Conflict],
    sol: Solution,
    exact: bool,
) -> Solution {
    let exact_inst = Instance::bounded(
        inst.duration.clone(),
        inst.allowed.clone(),
        prepared.bounds.clone(),
        known.clone(),
    )
    .expect("the same data, with more exact times");
    Solution {
        makespan: exact_inst.makespan(&sol.sequences),
        total: exact_inst.total(&sol.sequences),
        violations: sequencer::count_violations(conflicts, &sol.sequences),
        optimal: sol.optimal && exact,
        sequences: sol.sequences,
    }
}

/// Fewer violations, then a smaller makespan, then a smaller total.
fn better(a: &Solution, b: &Solution) -> bool {
    (a.violations, a.makespan, a.total) < (b.violations, b.makespan, b.total)
}
