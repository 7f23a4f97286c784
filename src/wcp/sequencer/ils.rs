//! Iterated local search: independent seeded restarts, each a chain of
//! ruin-and-recreate perturbations followed by local search.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use super::construct::{initial_order, insert_all, ruin_recreate};
use super::local_search::local_search;
use super::model::Model;
use super::plan::{Plan, Scratch};
use super::SequencerOptions;

/// The best plan over `opts.restarts` restarts; restart 0 starts from
/// `start` when given. Ties go to the lowest restart index, so the result
/// does not depend on how the threads ran.
pub(super) fn search(model: &Model, opts: &SequencerOptions, start: Option<Plan>) -> Plan {
    let plans: Vec<Plan> = (0..opts.restarts.max(1))
        .into_par_iter()
        .map(|k| {
            let first = if k == 0 { start.clone() } else { None };
            restart(model, opts, k, first)
        })
        .collect();
    let mut best: Option<Plan> = None;
    for plan in plans {
        let wins = match &best {
            None => true,
            Some(b) => plan.obj().better(&b.obj()),
        };
        if wins {
            best = Some(plan);
        }
    }
    best.expect("at least one restart")
}

/// How much longer than the best makespan an accepted plan may be.
const RECORD_SLACK: f64 = 0.02;

fn restart(model: &Model, opts: &SequencerOptions, k: usize, start: Option<Plan>) -> Plan {
    // One stream of the seed per restart: restarts are independent of each other.
    let mut rng = ChaCha8Rng::seed_from_u64(opts.seed);
    rng.set_stream(k as u64);
    let mut scratch = Scratch::default();
    let mut current = start.unwrap_or_else(|| {
        let mut plan = Plan::empty(model);
        let order = initial_order(model, k, &mut rng);
        insert_all(model, &mut plan, &order, &mut scratch);
        plan
    });
    local_search(model, &mut current, &mut scratch);
    let mut best = current.clone();
    // Counted in rounds, not time, so that the result stays deterministic.
    let patience = (opts.iterations / 4).max(1);
    let mut since = 0;
    for _ in 0..opts.iterations {
        if since == patience {
            break;
        }
        since += 1;
        let mut candidate = current.clone();
        ruin_recreate(model, &mut candidate, &mut rng, &mut scratch);
        local_search(model, &mut candidate, &mut scratch);
        if candidate.obj().better(&best.obj()) {
            best = candidate.clone();
            since = 0;
        }
        // Record-to-record travel: plans a little worse than the best are
        // accepted too, so the chain can leave a basin without drifting away.
        let (c, b) = (candidate.obj(), best.obj());
        let accept = !current.obj().better(&c)
            || (c.viol <= b.viol && c.makespan <= b.makespan * (1.0 + RECORD_SLACK));
        if accept {
            current = candidate;
        }
    }
    best
}
