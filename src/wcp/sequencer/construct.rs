//! Cheapest insertion, for the first plan of a restart and to recreate a
//! plan after part of it was ruined.

use super::terms::task_node;
use rand::seq::SliceRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

use super::model::Model;
use super::plan::{Move, Obj, Plan, Scratch};

/// The insertion of unassigned task `t` that gives the best objective
/// (first one found on ties: robots, then positions, in increasing order).
fn best_insertion(model: &Model, plan: &Plan, t: usize, scratch: &mut Scratch) -> Move {
    let x = task_node(t);
    let mut best = (Obj::WORST, None);
    for &r in &model.capable_robots[t] {
        let route = &plan.routes[r];
        for gap in 0..route.len() - 1 {
            let (a, b) = (route[gap], route[gap + 1]);
            let added = model.c(r, a, x) + model.dn[x] + model.c(r, x, b) - model.c(r, a, b);
            let mv = Move::Insert { t, r, gap };
            let times = [(r, plan.time[r] + added)];
            if let Some(obj) = plan.evaluate(model, &mv, &times, &best.0, scratch) {
                best = (obj, Some(mv));
            }
        }
    }
    best.1.expect("every task has a capable robot")
}

/// The best insertion of unassigned task `t` next to one of its near tasks or at an end of
/// the route of a robot with a near home (granular models; robots, then gaps, in increasing
/// order on ties).
fn near_insertion(model: &Model, plan: &Plan, t: usize, scratch: &mut Scratch) -> Move {
    let near = model.neighbours.as_ref().expect("a granular model");
    let x = task_node(t);
    let mut gaps: Vec<(usize, usize)> = Vec::new();
    for u in near.of(t) {
        let (r, q) = plan.pos[u];
        if r != usize::MAX && model.can(r, t) {
            gaps.extend([(r, q - 1), (r, q)]);
        }
    }
    for &r in &near.homes[t] {
        gaps.extend([(r, 0), (r, plan.routes[r].len() - 2)]);
    }
    gaps.sort_unstable();
    gaps.dedup();
    let mut best = (Obj::WORST, None);
    for (r, gap) in gaps {
        let route = &plan.routes[r];
        let (a, b) = (route[gap], route[gap + 1]);
        let added = model.c(r, a, x) + model.dn[x] + model.c(r, x, b) - model.c(r, a, b);
        let mv = Move::Insert { t, r, gap };
        let times = [(r, plan.time[r] + added)];
        if let Some(obj) = plan.evaluate(model, &mv, &times, &best.0, scratch) {
            best = (obj, Some(mv));
        }
    }
    best.1.expect("every task has a capable robot")
}

/// Tasks inserted between two looks at the clock.
const CLOCK_EVERY: usize = 64;

/// Inserts the tasks of `order`, one after the other, where they cost least.
pub(super) fn insert_all(model: &Model, plan: &mut Plan, order: &[usize], scratch: &mut Scratch) {
    insert_all_until(model, plan, order, scratch, None);
}

/// [`insert_all`], but once `deadline` has passed a granular model inserts the tasks left
/// at the places [`near_insertion`] looks: cheapest insertion tries every place of every
/// route, tasks × places in all, and a plan in time is worth more than a better one late.
pub(super) fn insert_all_until(
    model: &Model,
    plan: &mut Plan,
    order: &[usize],
    scratch: &mut Scratch,
    deadline: Option<Instant>,
) {
    let mut late = false;
    for (k, &t) in order.iter().enumerate() {
        if !late && k.is_multiple_of(CLOCK_EVERY) && model.neighbours.is_some() {
            late = deadline.is_some_and(|d| Instant::now() >= d);
        }
        let mv = match late {
            true => near_insertion(model, plan, t, scratch),
            false => best_insertion(model, plan, t, scratch),
        };
        plan.apply(model, &mv, scratch);
    }
}

/// As [`insert_all`], at the places [`near_insertion`] looks; every node whose arcs change
/// goes to `touched`.
fn insert_near(
    model: &Model,
    plan: &mut Plan,
    order: &[usize],
    scratch: &mut Scratch,
    touched: &mut Vec<usize>,
) {
    for &t in order {
        let mv = near_insertion(model, plan, t, scratch);
        touched.extend(plan.touched(&mv));
        plan.apply(model, &mv, scratch);
    }
}

/// The order of the first plan of restart `k`: the most constrained and
/// longest tasks first for restart 0, a random order for the others.
pub(super) fn initial_order(model: &Model, k: usize, rng: &mut ChaCha8Rng) -> Vec<usize> {
    let mut order: Vec<usize> = (0..model.tasks).collect();
    if k == 0 {
        order.sort_by(|&a, &b| {
            let key = |t: usize| model.capable_robots[t].len();
            key(a)
                .cmp(&key(b))
                .then(model.dn[b + 1].total_cmp(&model.dn[a + 1]))
                .then(a.cmp(&b))
        });
    } else {
        order.shuffle(rng);
    }
    order
}

/// Removes a random handful of tasks and inserts them again in a random
/// order. The tasks are picked at random, from a longest route, or close
/// to a random task, so that both balance and geometry get shaken. Returns the nodes whose
/// arcs changed when the model is granular (empty otherwise).
pub(super) fn ruin_recreate(
    model: &Model,
    plan: &mut Plan,
    rng: &mut ChaCha8Rng,
    scratch: &mut Scratch,
) -> Vec<usize> {
    // At least 20 (or all): smaller ruins keep falling back into the same
    // local optimum on small instances.
    let most = (model.tasks / 6).clamp(20, 30);
    ruin_recreate_between(model, plan, rng, scratch, 1, most)
}

/// A kick between two chains of an anytime search ([`ruin_recreate`], with `KICK_SHARE` to
/// twice that of the tasks ruined): far enough to leave the basin the chain settled in.
pub(super) fn kick(
    model: &Model,
    plan: &mut Plan,
    rng: &mut ChaCha8Rng,
    scratch: &mut Scratch,
) -> Vec<usize> {
    let least = (model.tasks as f64 * KICK_SHARE).ceil() as usize;
    ruin_recreate_between(model, plan, rng, scratch, least.max(1), 2 * least.max(1))
}

/// The least share of the tasks a [`kick`] ruins.
const KICK_SHARE: f64 = 0.15;

/// [`ruin_recreate`] of `least..=most` tasks (at most all).
fn ruin_recreate_between(
    model: &Model,
    plan: &mut Plan,
    rng: &mut ChaCha8Rng,
    scratch: &mut Scratch,
    least: usize,
    most: usize,
) -> Vec<usize> {
    let n = model.tasks;
    let mut touched = Vec::new();
    if n == 0 {
        return touched;
    }
    let most = most.min(n);
    let q = rng.random_range(least.min(most)..=most);
    let mut picked: Vec<usize> = match rng.random_range(0..3) {
        0 => {
            let mut all: Vec<usize> = (0..n).collect();
            all.partial_shuffle(rng, q);
            all.truncate(q);
            all
        }
        1 => {
            let route = &plan.routes[plan.critical()];
            let mut tasks: Vec<usize> = route[1..route.len() - 1].iter().map(|v| v - 1).collect();
            tasks.shuffle(rng);
            tasks.truncate(q);
            tasks
        }
        _ if model.neighbours.is_some() => related_near(model, rng.random_range(0..n), q),
        _ => related(model, rng.random_range(0..n), q),
    };
    if picked.is_empty() {
        picked.push(rng.random_range(0..n));
    }
    let granular = model.neighbours.is_some();
    for &t in &picked {
        let (r, i) = plan.pos[t];
        let mv = Move::Remove { r, i };
        if granular {
            touched.extend(plan.touched(&mv));
        }
        plan.apply(model, &mv, scratch);
    }
    picked.shuffle(rng);
    if granular {
        insert_near(model, plan, &picked, scratch, &mut touched);
    } else {
        insert_all(model, plan, &picked, scratch);
    }
    touched
}

/// `seed` and the `q - 1` tasks found first by a breadth-first walk over the near tasks
/// (granular models: the cost does not grow with the number of tasks).
fn related_near(model: &Model, seed: usize, q: usize) -> Vec<usize> {
    let near = model.neighbours.as_ref().expect("a granular model");
    let mut out = vec![seed];
    let mut k = 0;
    while out.len() < q && k < out.len() {
        for u in near.of(out[k]) {
            if out.len() < q && !out.contains(&u) {
                out.push(u);
            }
        }
        k += 1;
    }
    out
}

/// `seed` and the `q - 1` tasks closest to it (round trip, fastest robot
/// able to do both; ties by index).
fn related(model: &Model, seed: usize, q: usize) -> Vec<usize> {
    let x = seed + 1;
    let mut near: Vec<(f64, usize)> = (0..model.tasks)
        .map(|t| {
            let d = model.capable_robots[t]
                .iter()
                .filter(|&&r| model.can(r, seed))
                .map(|&r| model.c(r, x, task_node(t)) + model.c(r, task_node(t), x))
                .fold(f64::INFINITY, f64::min);
            (if t == seed { -1.0 } else { d }, t)
        })
        .collect();
    near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    near.into_iter().take(q).map(|(_, t)| t).collect()
}
