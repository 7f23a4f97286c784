//! Descent to a local optimum: shift segments of 1 to 3 tasks (relocate and
//! or-opt, in place or reversed, within a route or to another robot), swap
//! two tasks, reverse part of a route (2-opt).
//!
//! Route times of candidates come from O(1) differences of arc costs; the
//! plan recomputes them exactly when a move is made.

use super::model::Model;
use super::plan::{Move, Obj, Plan, Scratch};

/// Improves `plan` until no move of any neighbourhood does.
pub(super) fn local_search(model: &Model, plan: &mut Plan, scratch: &mut Scratch) {
    loop {
        let mut improved = false;
        improved |= shift_pass(model, plan, scratch, 1);
        improved |= swap_pass(model, plan, scratch);
        improved |= reverse_pass(model, plan, scratch);
        improved |= shift_pass(model, plan, scratch, 2);
        improved |= shift_pass(model, plan, scratch, 3);
        if !improved {
            return;
        }
    }
}

/// The best of the moves offered from one anchor, if it beats the plan.
pub(super) struct Pick {
    bar: Obj,
    pub best: Option<Move>,
}

impl Pick {
    pub fn new(plan: &Plan) -> Pick {
        Pick {
            bar: plan.obj(),
            best: None,
        }
    }

    pub fn offer(
        &mut self,
        model: &Model,
        plan: &Plan,
        mv: Move,
        times: &[(usize, f64)],
        scratch: &mut Scratch,
    ) {
        #[cfg(test)]
        check_times(model, plan, &mv, times, scratch);
        if let Some(obj) = plan.evaluate(model, &mv, times, &self.bar, scratch) {
            self.bar = obj;
            self.best = Some(mv);
        }
    }

    fn commit(self, model: &Model, plan: &mut Plan, scratch: &mut Scratch) -> bool {
        match self.best {
            Some(mv) => {
                plan.apply(model, &mv, scratch);
                true
            }
            None => false,
        }
    }
}

/// Moves the segment of `len` tasks starting at each task elsewhere.
fn shift_pass(model: &Model, plan: &mut Plan, scratch: &mut Scratch, len: usize) -> bool {
    let c = |r: usize, a: usize, b: usize| model.c(r, a, b);
    let mut improved = false;
    for t in 0..model.tasks {
        let (r1, i) = plan.pos[t];
        let route = &plan.routes[r1];
        let l = route.len() - 2;
        if i + len - 1 > l {
            continue;
        }
        let seg = &route[i..i + len];
        let (p, n, s0, sl) = (route[i - 1], route[i + len], seg[0], seg[len - 1]);
        let dur: f64 = seg.iter().map(|&v| model.dn[v]).sum();
        let inner = |r: usize, rev: bool| -> f64 {
            let arc = |w: &[usize]| {
                if rev {
                    c(r, w[1], w[0])
                } else {
                    c(r, w[0], w[1])
                }
            };
            seg.windows(2).map(arc).sum()
        };
        let cut = c(r1, p, n) - (c(r1, p, s0) + inner(r1, false) + dur + c(r1, sl, n));
        let base = plan.time[r1] + cut;
        let mut pick = Pick::new(plan);
        for &r2 in &model.capable_robots[t] {
            if !seg.iter().all(|&v| model.can(r2, v - 1)) {
                continue;
            }
            for rev in [false, true] {
                if rev && len == 1 {
                    continue;
                }
                let (first, last, mid) = if rev {
                    (sl, s0, inner(r2, true))
                } else {
                    (s0, sl, inner(r2, false))
                };
                let add = |r: usize, a: usize, b: usize| {
                    (c(r, a, first) + mid + dur + c(r, last, b)) - c(r, a, b)
                };
                let mv = |gap: usize| Move::Shift {
                    r1,
                    i,
                    len,
                    r2,
                    gap,
                    rev,
                };
                if r2 == r1 {
                    // Gaps of the route once the segment is cut out.
                    let node = |k: usize| if k < i { route[k] } else { route[k + len] };
                    for gap in (0..=l - len).filter(|&g| g + 1 != i) {
                        let new = base + add(r1, node(gap), node(gap + 1));
                        pick.offer(model, plan, mv(gap), &[(r1, new)], scratch);
                    }
                } else {
                    let other = &plan.routes[r2];
                    for gap in 0..other.len() - 1 {
                        let new = plan.time[r2] + add(r2, other[gap], other[gap + 1]);
                        let times = [(r1, base), (r2, new)];
                        pick.offer(model, plan, mv(gap), &times, scratch);
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
    let c = |r: usize, a: usize, b: usize| model.c(r, a, b);
    let dn = &model.dn;
    let mut improved = false;
    for t1 in 0..model.tasks {
        let (r1, i) = plan.pos[t1];
        let ra = &plan.routes[r1];
        let x = t1 + 1;
        let mut pick = Pick::new(plan);
        for t2 in t1 + 1..model.tasks {
            let (r2, j) = plan.pos[t2];
            let y = t2 + 1;
            if r1 != r2 {
                if !model.can(r2, t1) || !model.can(r1, t2) {
                    continue;
                }
                let rb = &plan.routes[r2];
                let (p1, n1, p2, n2) = (ra[i - 1], ra[i + 1], rb[j - 1], rb[j + 1]);
                let d1 =
                    (c(r1, p1, y) + dn[y] + c(r1, y, n1)) - (c(r1, p1, x) + dn[x] + c(r1, x, n1));
                let d2 =
                    (c(r2, p2, x) + dn[x] + c(r2, x, n2)) - (c(r2, p2, y) + dn[y] + c(r2, y, n2));
                let times = [(r1, plan.time[r1] + d1), (r2, plan.time[r2] + d2)];
                pick.offer(model, plan, Move::Swap { r1, i, r2, j }, &times, scratch);
            } else {
                let (lo, hi) = (i.min(j), i.max(j));
                let (u, v) = (ra[lo], ra[hi]);
                let delta = if hi == lo + 1 {
                    let (p, n) = (ra[lo - 1], ra[hi + 1]);
                    (c(r1, p, v) + c(r1, v, u) + c(r1, u, n))
                        - (c(r1, p, u) + c(r1, u, v) + c(r1, v, n))
                } else {
                    let (p1, n1, p2, n2) = (ra[lo - 1], ra[lo + 1], ra[hi - 1], ra[hi + 1]);
                    (c(r1, p1, v) + c(r1, v, n1) + c(r1, p2, u) + c(r1, u, n2))
                        - (c(r1, p1, u) + c(r1, u, n1) + c(r1, p2, v) + c(r1, v, n2))
                };
                let mv = Move::Swap {
                    r1,
                    i: lo,
                    r2: r1,
                    j: hi,
                };
                pick.offer(model, plan, mv, &[(r1, plan.time[r1] + delta)], scratch);
            }
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
                let (p, n) = (route[i - 1], route[j + 1]);
                let delta = (c(r, p, route[j]) + rev + c(r, route[i], n))
                    - (c(r, p, route[i]) + fwd + c(r, route[j], n));
                let times = [(r, plan.time[r] + delta)];
                pick.offer(model, plan, Move::Reverse { r, i, j }, &times, scratch);
            }
            improved |= pick.commit(model, plan, scratch);
            i += 1;
        }
    }
    improved
}

/// The O(1) route times and the counted violations agree with a
/// recomputation of the rebuilt routes.
#[cfg(test)]
fn check_times(
    model: &Model,
    plan: &Plan,
    mv: &Move,
    times: &[(usize, f64)],
    scratch: &mut Scratch,
) {
    let mut moved = plan.clone();
    moved.apply(model, mv, scratch);
    assert_eq!(plan.viol_after(model, mv, scratch), moved.viol, "{mv:?}");
    let exact = plan.times_after(model, mv);
    assert_eq!(exact.len(), times.len(), "{mv:?}");
    for (&(r, t), &(q, e)) in times.iter().zip(&exact) {
        assert_eq!(r, q, "{mv:?}");
        assert!(
            (t - e).abs() <= 1e-9 * e.abs().max(1.0),
            "{mv:?}: {t} vs {e}"
        );
    }
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
            for _ in 0..5 {
                local_search(&model, &mut plan, &mut scratch);
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
            local_search(&model, &mut plan, &mut scratch, &mut Active::all(&model));
            plan.assert_consistent(&model);
            for _ in 0..3 {
                let touched = ruin_recreate(&model, &mut plan, &mut rng, &mut scratch);
                plan.assert_consistent(&model);
                let mut active = Active::none(&model);
                for node in touched {
                    active.push_node(node);
                }
                local_search(&model, &mut plan, &mut scratch, &mut active);
                plan.assert_consistent(&model);
            }
        }
    }
}
