//! Iterated local search: independent seeded restarts, each a chain of
//! ruin-and-recreate perturbations followed by local search.

use std::time::Instant;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use super::construct::{initial_order, insert_all_until, kick, ruin_recreate};
use super::granular::{self, Active};
use super::local_search::{local_search, Exchanges};
use super::model::Model;
use super::plan::{Plan, Scratch};
use super::SequencerOptions;

/// Where the restarts begin.
pub(super) enum Start {
    /// From their own construction; restart 0 from this plan when given.
    Fresh(Option<Plan>),
    /// Every restart from this plan (a warm start after travel times changed).
    All(Plan),
}

/// Restarts run in the first wave of a search with an aim ([`SequencerOptions::target`]):
/// two, one per core of the machines the project is measured on.
const AIMED_WAVE: usize = 2;

/// A granular search makes this many times `iterations` rounds per restart: its rounds cost
/// what the perturbation touched, not the whole plan.
const GRANULAR_ROUNDS: usize = 10;

/// The best plan over `opts.restarts` restarts, each searched for `opts.effort` epochs.
/// Ties go to the lowest restart index, so the result does not depend on how the threads
/// ran. `on_best` hears every makespan that improves a restart's best, from any thread.
pub(super) fn search(
    model: &Model,
    opts: &SequencerOptions,
    start: Start,
    on_best: &(dyn Fn(f64) + Sync),
) -> Plan {
    // The first epoch exchanges route ends at local optima only: the default solve (one
    // epoch) is about as fast as before exchanges existed. Later epochs, which an effort buys, and a
    // search to a deadline exchange them in every round, which finds deeper optima
    // sooner (eil76 with two robots under a 1 s limit: 280.85, against 286.02 with the
    // first epoch at optima only). Effort n + 1 still repeats effort n and goes on.
    let (first, later) = match (opts.route_exchanges, opts.deadline) {
        (false, _) => (Exchanges::Never, Exchanges::Never),
        (true, None) => (Exchanges::AtOptima, Exchanges::EveryRound),
        (true, Some(_)) => (Exchanges::EveryRound, Exchanges::EveryRound),
    };
    // Every restart's first descent from a shared plan is the same (a descent draws no
    // random numbers): made once.
    let shared = match &start {
        Start::All(plan) => {
            let mut plan = plan.clone();
            descend(model, opts, first, &mut plan, &mut Scratch::default(), None);
            Some(plan)
        }
        Start::Fresh(_) => None,
    };
    let restarts = opts.restarts.max(1);
    let first_chain = |k: usize| {
        let begin = match (&start, &shared) {
            (_, Some(descended)) => Begin::Descended(descended.clone()),
            (Start::Fresh(Some(plan)), None) if k == 0 => Begin::From(plan.clone()),
            _ => Begin::Built,
        };
        restart(
            model,
            (opts, first),
            &mut stream(opts.seed, k),
            begin,
            k,
            on_best,
        )
    };
    let mut chains: Vec<Plan> = match opts.target {
        // With an aim, the first restarts (restart 0 from the given plan) run first: a
        // repair usually meets its aim there, and the others are not needed. A fixed wave,
        // not one per thread, so that the result does not depend on the threads.
        Some(_) => {
            let wave = AIMED_WAVE.min(restarts);
            let mut chains: Vec<Plan> = (0..wave).into_par_iter().map(first_chain).collect();
            let best = &chains[best_index(&chains)];
            if reached(opts, best) {
                return best.clone();
            }
            chains.par_extend((wave..restarts).into_par_iter().map(first_chain));
            chains
        }
        None => (0..restarts).into_par_iter().map(first_chain).collect(),
    };
    // Iterated local search over epochs. Chain 0 is kicked (a large ruin and recreate) from
    // the best plan of all and searched again: it intensifies. Every other chain is kicked
    // from its own best while that keeps improving, and starts afresh from a new
    // construction once it stalls: it diversifies. The epochs' streams follow the first
    // epoch's, so that effort `n + 1` repeats effort `n` and goes on.
    let mut leader = chains[best_index(&chains)].clone();
    let mut improving = vec![true; restarts];
    for epoch in 1..opts.effort.max(1) {
        if opts.deadline.is_some_and(|d| Instant::now() >= d) || reached(opts, &leader) {
            break;
        }
        let next: Vec<(Plan, bool)> = chains
            .into_par_iter()
            .enumerate()
            .map(|(k, own)| {
                let mut rng = stream(opts.seed, epoch * restarts + k);
                let mut scratch = Scratch::default();
                let from = match k == 0 {
                    true => &leader,
                    false => &own,
                };
                if k > 0 && !improving[k] {
                    return (
                        restart(model, (opts, later), &mut rng, Begin::Built, k, on_best),
                        true,
                    );
                }
                let mut plan = from.clone();
                let touched = kick(model, &mut plan, &mut rng, &mut scratch);
                descend(model, opts, later, &mut plan, &mut scratch, Some(&touched));
                let found = chain(model, (opts, later), &mut rng, &mut scratch, plan, on_best);
                match found.obj().better(&own.obj()) {
                    true => (found, true),
                    false => (own, false),
                }
            })
            .collect();
        (chains, improving) = next.into_iter().unzip();
        let best = &chains[best_index(&chains)];
        if best.obj().better(&leader.obj()) {
            leader = best.clone();
        }
    }
    leader
}

/// Whether `plan` meets the search's aim ([`SequencerOptions::target`]).
fn reached(opts: &SequencerOptions, plan: &Plan) -> bool {
    let obj = plan.obj();
    opts.target
        .is_some_and(|aim| obj.viol == 0 && obj.makespan <= aim * (1.0 + TARGET_TOL))
}

/// Relative tolerance of [`reached`]: a plan equal to the aim but for rounding meets it.
const TARGET_TOL: f64 = 1e-9;

/// The index of the best plan, the lowest on ties (so that the result does not depend on
/// how the threads ran).
fn best_index(plans: &[Plan]) -> usize {
    let mut best = 0;
    for (k, plan) in plans.iter().enumerate().skip(1) {
        if plan.obj().better(&plans[best].obj()) {
            best = k;
        }
    }
    best
}

/// The random stream `k` of the seed: restarts and epochs are independent of each other.
fn stream(seed: u64, k: usize) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(k as u64);
    rng
}

/// Where one restart begins.
enum Begin {
    /// Its own construction, then a descent.
    Built,
    /// This plan, then a descent.
    From(Plan),
    /// This plan, a local optimum already.
    Descended(Plan),
}

/// How much longer than the best makespan an accepted plan may be.
const RECORD_SLACK: f64 = 0.02;
/// The same for a granular search: its chains are long (many small perturbations), and a
/// wide slack lets them drift (12 robots × 500 tasks: 240.7 with 0.02, 239.0 with 0.005).
const GRANULAR_RECORD_SLACK: f64 = 0.005;

/// A chain of the first epoch (exchanges at local optima) stops after `rounds /
/// PATIENCE_SHARE` rounds in a row without a better plan. On the twelve cells of
/// `../shared/mtsp/`, a fifth took about a sixth less CPU than a quarter, with the same
/// makespans but eil76-m3's (196.70 instead of 195.72); a sixth lost 2 % on eil76-m2.
/// Longer searches are what `effort` and `deadline` are for.
const PATIENCE_SHARE: usize = 5;
/// The same for other chains: a repair's (no exchanges; with a fifth for repairs too, and
/// exchanges in every round of the blind plan's descents, the search over remedies of
/// conflict cell `workpiece-4` checked 1,365 schedules instead of 443) and later epochs'
/// (exchanges in every round).
const PLAIN_PATIENCE_SHARE: usize = 4;
/// The same for a granular search, whose rounds are many and small.
const GRANULAR_PATIENCE_SHARE: usize = 4;

/// A descent: the full neighbourhoods, or the granular ones from the `touched` nodes (all
/// tasks when `None`).
/// A granular descent stops at `deadline` (the plan is whole at every step).
fn descend(
    model: &Model,
    opts: &SequencerOptions,
    exchanges: Exchanges,
    plan: &mut Plan,
    scratch: &mut Scratch,
    touched: Option<&[usize]>,
) {
    let deadline = opts.deadline;
    if model.neighbours.is_none() {
        return local_search(model, plan, scratch, exchanges);
    }
    let mut active = match touched {
        None => Active::all(model),
        Some(nodes) => {
            let mut active = Active::none(model);
            for &node in nodes {
                active.push_node(node);
            }
            active
        }
    };
    granular::local_search(model, plan, scratch, &mut active, deadline);
}

/// One chain from `start`; a construction takes the first order of restart `k` (see
/// [`initial_order`]).
fn restart(
    model: &Model,
    (opts, exchanges): (&SequencerOptions, Exchanges),
    rng: &mut ChaCha8Rng,
    start: Begin,
    k: usize,
    on_best: &(dyn Fn(f64) + Sync),
) -> Plan {
    let mut scratch = Scratch::default();
    let (mut current, descended) = match start {
        Begin::Descended(plan) => (plan, true),
        Begin::From(plan) => (plan, false),
        Begin::Built => {
            let mut plan = Plan::empty(model);
            let order = initial_order(model, k, rng);
            let hurry = opts.construction_deadline.or(opts.deadline);
            insert_all_until(model, &mut plan, &order, &mut scratch, hurry);
            (plan, false)
        }
    };
    if !descended {
        descend(model, opts, exchanges, &mut current, &mut scratch, None);
    }
    chain(
        model,
        (opts, exchanges),
        rng,
        &mut scratch,
        current,
        on_best,
    )
}

/// A chain of ruin-and-recreate perturbations, each followed by a descent, from `current`
/// (a local optimum); the best plan it met.
fn chain(
    model: &Model,
    (opts, exchanges): (&SequencerOptions, Exchanges),
    rng: &mut ChaCha8Rng,
    scratch: &mut Scratch,
    mut current: Plan,
    on_best: &(dyn Fn(f64) + Sync),
) -> Plan {
    let mut best = current.clone();
    on_best(best.obj().makespan);
    if reached(opts, &best) {
        return best;
    }
    let (rounds, slack, share) = if model.neighbours.is_some() {
        let rounds = opts.iterations * GRANULAR_ROUNDS;
        (rounds, GRANULAR_RECORD_SLACK, GRANULAR_PATIENCE_SHARE)
    } else {
        let share = match exchanges {
            Exchanges::AtOptima => PATIENCE_SHARE,
            Exchanges::Never | Exchanges::EveryRound => PLAIN_PATIENCE_SHARE,
        };
        (opts.iterations, RECORD_SLACK, share)
    };
    // Counted in rounds, not time, so that the result stays deterministic (a deadline, when
    // given, ends the search early).
    let patience = (rounds / share).max(1);
    let mut since = 0;
    for _ in 0..rounds {
        if since == patience || opts.deadline.is_some_and(|d| Instant::now() >= d) {
            break;
        }
        since += 1;
        let mut candidate = current.clone();
        let touched = ruin_recreate(model, &mut candidate, rng, scratch);
        descend(
            model,
            opts,
            exchanges,
            &mut candidate,
            scratch,
            Some(&touched),
        );
        if candidate.obj().better(&best.obj()) {
            best = candidate.clone();
            on_best(best.obj().makespan);
            since = 0;
            if reached(opts, &best) {
                break;
            }
        }
        // Record-to-record travel: plans a little worse than the best are
        // accepted too, so the chain can leave a basin without drifting away.
        let (c, b) = (candidate.obj(), best.obj());
        let accept = !current.obj().better(&c)
            || (c.viol <= b.viol && c.makespan <= b.makespan * (1.0 + slack));
        if accept {
            current = candidate;
        }
    }
    best
}
