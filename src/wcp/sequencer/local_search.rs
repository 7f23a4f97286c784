//! Descent to a local optimum: shift segments of 1 to 3 tasks (relocate and
//! or-opt, in place or reversed, within a route or to another robot), swap
//! two tasks, reverse part of a route (2-opt), exchange the tails of two routes (2-opt*).
//!
//! Route times of candidates come from O(1) differences of arc costs; the
//! plan recomputes them exactly when a move is made.

use super::model::Model;
use super::offers::{offer_crosses, offer_reverse, offer_swap, Cut, Pick};
use super::plan::{Plan, Scratch};

/// When a descent exchanges route ends (2-opt*), the costliest neighbourhood.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Exchanges {
    /// Never (a repair: `SequencerOptions::route_exchanges` off).
    Never,
    /// At local optima of the other neighbourhoods only, followed by a 2-opt pass over the
    /// routes they joined: a variable neighbourhood descent (Mladenović & Hansen, 1997).
    /// The default solve's: with exchanges in every round it took 10 % more CPU on the
    /// cells of `../shared/mtsp/`, and eil51-m2 ended at 223.06 instead of its optimum
    /// 222.73.
    AtOptima,
    /// In every round, with the other neighbourhoods.
    EveryRound,
}

/// Improves `plan` until no move of any neighbourhood does; route ends are exchanged as
/// `exchanges` says.
pub(super) fn local_search(
    model: &Model,
    plan: &mut Plan,
    scratch: &mut Scratch,
    exchanges: Exchanges,
) {
    loop {
        let mut improved = false;
        improved |= shift_pass(model, plan, scratch, 1);
        improved |= swap_pass(model, plan, scratch);
        improved |= reverse_pass(model, plan, scratch);
        if exchanges == Exchanges::EveryRound {
            improved |= cross_pass(model, plan, scratch);
        }
        improved |= shift_pass(model, plan, scratch, 2);
        improved |= shift_pass(model, plan, scratch, 3);
        if !improved && exchanges == Exchanges::AtOptima && cross_pass(model, plan, scratch) {
            reverse_pass(model, plan, scratch);
            improved = true;
        }
        if !improved {
            return;
        }
    }
}

/// Moves the segment of `len` tasks starting at each task elsewhere.
fn shift_pass(model: &Model, plan: &mut Plan, scratch: &mut Scratch, len: usize) -> bool {
    let mut improved = false;
    for t in 0..model.tasks {
        let Some(cut) = Cut::new(model, plan, t, len) else {
            continue;
        };
        let (r1, i) = (cut.r1, cut.i);
        let route = &plan.routes[r1];
        let mut pick = Pick::new(plan);
        for &r2 in &model.capable_robots[t] {
            if !cut.seg.iter().all(|&v| model.can(r2, v - 1)) {
                continue;
            }
            for rev in [false, true] {
                if rev && len == 1 {
                    continue;
                }
                let mid = cut.inner(model, r2, rev);
                let mut offer = |gap: usize, ends: (usize, usize)| {
                    cut.offer(model, plan, scratch, &mut pick, (r2, gap), ends, rev, mid);
                };
                if r2 == r1 {
                    // Gaps of the route once the segment is cut out.
                    let node = |k: usize| if k < i { route[k] } else { route[k + len] };
                    for gap in (0..=route.len() - 2 - len).filter(|&g| g + 1 != i) {
                        offer(gap, (node(gap), node(gap + 1)));
                    }
                } else {
                    let other = &plan.routes[r2];
                    for gap in 0..other.len() - 1 {
                        offer(gap, (other[gap], other[gap + 1]));
                    }
                }
            }
        }
        improved |= pick.commit(model, plan, scratch);
    }
    improved
}

/// Exchanges each task with every later one that fits the other's robot.
fn swap_pass(model: &Model, plan: &mut Plan, scratch: &mut Scratch) -> bool {
    let mut improved = false;
    for t1 in 0..model.tasks {
        let mut pick = Pick::new(plan);
        for t2 in t1 + 1..model.tasks {
            offer_swap(model, plan, scratch, &mut pick, (t1, t2));
        }
        improved |= pick.commit(model, plan, scratch);
    }
    improved
}

/// Reverses every stretch of every route (2-opt; arcs inside the stretch
/// change direction, which matters when travel times are asymmetric).
fn reverse_pass(model: &Model, plan: &mut Plan, scratch: &mut Scratch) -> bool {
    let c = |r: usize, a: usize, b: usize| model.c(r, a, b);
    let mut improved = false;
    for r in 0..model.robots {
        let mut i = 1;
        while i + 2 < plan.routes[r].len() {
            let route = &plan.routes[r];
            let l = route.len() - 2;
            let mut pick = Pick::new(plan);
            let (mut fwd, mut rev) = (0.0, 0.0);
            for j in i + 1..=l {
                fwd += c(r, route[j - 1], route[j]);
                rev += c(r, route[j], route[j - 1]);
                offer_reverse(model, plan, scratch, &mut pick, r, (i, j), fwd, rev);
            }
            improved |= pick.commit(model, plan, scratch);
            i += 1;
        }
    }
    improved
}

/// Exchanges the tails of every pair of routes (2-opt*).
fn cross_pass(model: &Model, plan: &mut Plan, scratch: &mut Scratch) -> bool {
    let mut improved = false;
    for r1 in 0..model.robots {
        for r2 in r1 + 1..model.robots {
            let mut pick = Pick::new(plan);
            offer_crosses(model, plan, scratch, &mut pick, (r1, r2));
            improved |= pick.commit(model, plan, scratch);
        }
    }
    improved
}

#[cfg(test)]
mod tests {
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::wcp::sequencer::construct::{insert_all, ruin_recreate};
    use crate::wcp::sequencer::{Conflict, Instance, Step};

    fn random_step(rng: &mut ChaCha8Rng, nodes: usize) -> Step {
        if rng.random_bool(0.5) {
            Step::Stay {
                node: rng.random_range(0..nodes),
            }
        } else {
            Step::Move {
                from: rng.random_range(0..nodes),
                to: rng.random_range(0..nodes),
            }
        }
    }

    /// Every candidate's O(1) times are checked by `Pick::offer`; the plan's
    /// caches are checked after each descent and perturbation.
    #[test]
    fn deltas_and_caches_match_recomputation() {
        let mut used = 0;
        for seed in 0..24u64 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let (robots, tasks) = (1 + seed as usize % 3, 4 + seed as usize % 9);
            // Every task allowed to some robot whose moves from and to home exist, so that
            // every seed gives a usable model (none is skipped).
            let allowed: Vec<Vec<bool>> = (0..robots)
                .map(|r| {
                    (0..tasks)
                        .map(|t| t % robots == r || rng.random_bool(0.7))
                        .collect()
                })
                .collect();
            let duration = (0..tasks).map(|_| rng.random_range(0.0..2.0)).collect();
            let inst = Instance::from_fn(duration, allowed, |r, a, b| {
                let home_arc = (a == 0 && (b + robots - 1) % robots == r % robots)
                    || (b == 0 && (a + robots - 1) % robots == r % robots);
                if !home_arc && rng.random_bool(0.05) {
                    f64::INFINITY
                } else {
                    rng.random_range(1.0..10.0)
                }
            })
            .unwrap();
            let conflicts: Vec<Conflict> = (0..seed % 2 * 12)
                .map(|_| Conflict {
                    a: (
                        rng.random_range(0..robots),
                        random_step(&mut rng, tasks + 1),
                    ),
                    b: (
                        rng.random_range(0..robots),
                        random_step(&mut rng, tasks + 1),
                    ),
                })
                .collect();
            let model = Model::new(&inst, &conflicts).expect("every task has a capable robot");
            used += 1;
            let mut scratch = Scratch::default();
            let mut plan = Plan::empty(&model);
            let order: Vec<usize> = (0..tasks).collect();
            insert_all(&model, &mut plan, &order, &mut scratch);
            plan.assert_consistent(&model);
            for round in 0..6 {
                let exchanges = [Exchanges::EveryRound, Exchanges::AtOptima][round % 2];
                local_search(&model, &mut plan, &mut scratch, exchanges);
                plan.assert_consistent(&model);
                ruin_recreate(&model, &mut plan, &mut rng, &mut scratch);
                plan.assert_consistent(&model);
            }
        }
        assert_eq!(used, 24, "every seed is checked");
    }
}

#[cfg(test)]
mod granular_tests {
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use crate::wcp::sequencer::construct::{insert_all, ruin_recreate};
    use crate::wcp::sequencer::granular::{local_search, Active};
    use crate::wcp::sequencer::model::{Model, GRANULAR_FROM_TASKS};
    use crate::wcp::sequencer::plan::{Plan, Scratch};
    use crate::wcp::sequencer::Instance;

    /// The granular moves' O(1) times are checked by `Pick::offer` as the full ones are, and
    /// the plan's caches after each descent and perturbation.
    #[test]
    fn granular_deltas_and_caches_match_recomputation() {
        for seed in 0..2u64 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let (robots, tasks) = (3, GRANULAR_FROM_TASKS);
            let pos: Vec<(f64, f64)> = (0..=tasks)
                .map(|_| (rng.random_range(0.0..30.0), rng.random_range(0.0..30.0)))
                .collect();
            let allowed = (0..robots)
                .map(|r| {
                    (0..tasks)
                        .map(|t| t % robots == r || rng.random_bool(0.5))
                        .collect()
                })
                .collect();
            let duration = (0..tasks).map(|_| rng.random_range(0.0..2.0)).collect();
            // Asymmetric: slower going up.
            let inst = Instance::from_fn(duration, allowed, |r, a, b| {
                let (p, q) = (pos[a], pos[b]);
                let d = (p.0 - q.0).hypot(p.1 - q.1);
                d * (1.0 + 0.1 * r as f64) + 0.2 * (q.1 - p.1).max(0.0)
            })
            .unwrap();
            let model = Model::new(&inst, &[]).unwrap();
            assert!(model.neighbours.is_some());
            let mut scratch = Scratch::default();
            let mut plan = Plan::empty(&model);
            let order: Vec<usize> = (0..tasks).collect();
            insert_all(&model, &mut plan, &order, &mut scratch);
            local_search(
                &model,
                &mut plan,
                &mut scratch,
                &mut Active::all(&model),
                None,
            );
            plan.assert_consistent(&model);
            for _ in 0..3 {
                let touched = ruin_recreate(&model, &mut plan, &mut rng, &mut scratch);
                plan.assert_consistent(&model);
                let mut active = Active::none(&model);
                for node in touched {
                    active.push_node(node);
                }
                local_search(&model, &mut plan, &mut scratch, &mut active, None);
                plan.assert_consistent(&model);
            }
        }
    }
}
