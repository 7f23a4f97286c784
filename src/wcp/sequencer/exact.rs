//! Exact search for small conflict-free instances: Held-Karp gives each
//! robot's best route time for every subset of its tasks, then a dynamic
//! programme over subsets of tasks assigns them to robots.

use super::model::Model;
use super::Instance;

/// Hard caps whatever the limit: the tables grow as 2^tasks.
const MAX_TASKS: usize = 24;
const MAX_ROBOT_TASKS: usize = 18;
const MAX_TABLE: f64 = (1u64 << 23) as f64;

/// Estimated elementary updates of [`solve`], or infinity when its tables
/// would not fit the caps.
pub(super) fn work(model: &Model) -> f64 {
    let n = model.tasks;
    if n > MAX_TASKS || model.robots as f64 * 2f64.powi(n as i32) > MAX_TABLE {
        return f64::INFINITY;
    }
    let mut w = 0.0;
    for r in 0..model.robots {
        let a = model.capable_tasks(r).len();
        if a > MAX_ROBOT_TASKS {
            return f64::INFINITY;
        }
        let (a, n) = (a as i32, n as i32);
        // Held-Karp; two passes over (mask, submask) pairs; locating masks.
        w += 2f64.powi(a) * (a * a) as f64;
        w += 2.0 * 2f64.powi(n - a) * 3f64.powi(a);
        w += 2f64.powi(n) * a as f64;
    }
    w
}

/// Per robot: its capable tasks, their best route time for every subset
/// (local bit k = `tasks[k]`) and the global task mask of each subset.
struct RobotTable {
    tasks: Vec<usize>,
    best: Vec<f64>,
    global: Vec<u32>,
}

impl RobotTable {
    fn new(inst: &Instance, model: &Model, r: usize) -> RobotTable {
        let tasks = model.capable_tasks(r);
        let (best, _) = held_karp(inst, r, &tasks);
        let mut global = vec![0u32; best.len()];
        for m in 1..global.len() {
            let k = m.trailing_zeros() as usize;
            global[m] = global[m & (m - 1)] | (1 << tasks[k]);
        }
        RobotTable {
            tasks,
            best,
            global,
        }
    }

    /// The local mask of the robot's tasks in global mask `m`.
    fn local(&self, m: usize) -> usize {
        let mut out = 0;
        for (k, &t) in self.tasks.iter().enumerate() {
            out |= ((m >> t) & 1) << k;
        }
        out
    }
}

/// Held-Karp over `tasks` for robot `r`: returns the best route time of
/// every subset, and the table `dp[mask * k + last]` (best time from home
/// through `mask`, ending at `tasks[last]` once its duration is over).
fn held_karp(inst: &Instance, r: usize, tasks: &[usize]) -> (Vec<f64>, Vec<f64>) {
    let k = tasks.len();
    let size = 1usize << k;
    let node = |j: usize| tasks[j] + 1;
    let mut dp = vec![f64::INFINITY; size * k];
    let mut best = vec![f64::INFINITY; size];
    best[0] = 0.0;
    for (j, &t) in tasks.iter().enumerate() {
        // Same order of additions as `Instance::route_time`.
        let mut acc = 0.0;
        acc += inst.travel(r, 0, node(j));
        acc += inst.duration[t];
        dp[(1 << j) * k + j] = acc;
    }
    for mask in 1..size {
        for last in 0..k {
            let here = dp[mask * k + last];
            if mask >> last & 1 == 0 || here == f64::INFINITY {
                continue;
            }
            best[mask] = best[mask].min(here + inst.travel(r, node(last), 0));
            for next in 0..k {
                if mask >> next & 1 == 1 {
                    continue;
                }
                let mut acc = here + inst.travel(r, node(last), node(next));
                acc += inst.duration[tasks[next]];
                let slot = &mut dp[(mask | 1 << next) * k + next];
                if acc < *slot {
                    *slot = acc;
                }
            }
        }
    }
    (best, dp)
}

/// The fastest order of `tasks` for robot `r` (their best route time is finite).
fn best_order(inst: &Instance, r: usize, tasks: &[usize]) -> Vec<usize> {
    let k = tasks.len();
    if k == 0 {
        return Vec::new();
    }
    let (best, dp) = held_karp(inst, r, tasks);
    let node = |j: usize| tasks[j] + 1;
    let mut mask = (1usize << k) - 1;
    // The table recomputes the same sums, so equality finds the argmins.
    let mut last = (0..k)
        .find(|&j| dp[mask * k + j] + inst.travel(r, node(j), 0) == best[mask])
        .expect("some last task attains the best time");
    let mut order = vec![tasks[last]];
    while mask != 1 << last {
        let here = dp[mask * k + last];
        mask &= !(1 << last);
        last = (0..k)
            .filter(|&p| mask >> p & 1 == 1)
            .find(|&p| {
                let mut acc = dp[mask * k + p] + inst.travel(r, node(p), node(last));
                acc += inst.duration[tasks[last]];
                acc == here
            })
            .expect("some predecessor attains the best time");
        order.push(tasks[last]);
    }
    order.reverse();
    order
}

/// A plan of minimal makespan and, among those, of minimal total; `None`
/// when every plan needs an infinite arc.
pub(super) fn solve(inst: &Instance, model: &Model) -> Option<Vec<Vec<usize>>> {
    let n = model.tasks;
    let full = (1usize << n) - 1;
    let tables: Vec<RobotTable> = (0..model.robots)
        .map(|r| RobotTable::new(inst, model, r))
        .collect();
    let mut start = vec![f64::INFINITY; full + 1];
    start[0] = 0.0;

    // Pass 1: the smallest makespan.
    let mut layer = start.clone();
    for table in &tables {
        layer = combine(&layer, table, |prev, cost| Some(prev.max(cost)));
    }
    let makespan = layer[full];
    if makespan == f64::INFINITY {
        return None;
    }

    // Pass 2: the smallest total with every route within that makespan.
    let mut layers = vec![start];
    for table in &tables {
        let prev = layers.last().expect("start layer");
        let next = combine(prev, table, |p, cost| {
            (cost <= makespan).then_some(p + cost)
        });
        layers.push(next);
    }

    // Walk back through the layers; exact equality finds the choices made.
    let mut mask = full;
    let mut seqs = vec![Vec::new(); model.robots];
    for (r, table) in tables.iter().enumerate().rev() {
        let (prev, here) = (&layers[r], layers[r + 1][mask]);
        let sub = submasks(table.local(mask))
            .find(|&s| {
                let cost = table.best[s];
                cost <= makespan && prev[mask ^ table.global[s] as usize] + cost == here
            })
            .expect("some subset attains the layer's value");
        let tasks: Vec<usize> = (0..table.tasks.len())
            .filter(|k| sub >> k & 1 == 1)
            .map(|k| table.tasks[k])
            .collect();
        seqs[r] = best_order(inst, r, &tasks);
        mask ^= table.global[sub] as usize;
    }
    Some(seqs)
}

/// One robot more: `out[m]` = min over the robot's subsets `s` of `m` of
/// `join(prev[m \ s], best[s])` (`None` = not allowed).
fn combine(prev: &[f64], table: &RobotTable, join: impl Fn(f64, f64) -> Option<f64>) -> Vec<f64> {
    let mut out = vec![f64::INFINITY; prev.len()];
    for (m, slot) in out.iter_mut().enumerate() {
        for s in submasks(table.local(m)) {
            let p = prev[m ^ table.global[s] as usize];
            if p == f64::INFINITY {
                continue;
            }
            if let Some(v) = join(p, table.best[s]) {
                if v < *slot {
                    *slot = v;
                }
            }
        }
    }
    out
}

/// Every submask of `m`, from `m` down to 0.
fn submasks(m: usize) -> impl Iterator<Item = usize> {
    let mut next = Some(m);
    std::iter::from_fn(move || {
        let s = next?;
        next = (s != 0).then(|| (s - 1) & m);
        Some(s)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn submasks_cover_every_subset_once() {
        let mut all: Vec<usize> = submasks(0b1011).collect();
        all.sort_unstable();
        assert_eq!(all, vec![0, 1, 2, 3, 8, 9, 10, 11]);
        assert_eq!(submasks(0).collect::<Vec<_>>(), vec![0]);
    }

    #[test]
    fn best_order_matches_permutations() {
        // Asymmetric travel times make the order matter.
        let inst = Instance::from_fn(vec![1.0, 2.0, 0.5, 0.0], vec![vec![true; 4]], |_, a, b| {
            ((a * 7 + b * 3) % 5) as f64 + 0.25 * a as f64
        })
        .unwrap();
        let tasks = [0, 1, 2, 3];
        let order = best_order(&inst, 0, &tasks);
        let mut best = f64::INFINITY;
        let mut perm = tasks;
        permute(&mut perm, 0, &mut |p| {
            best = best.min(inst.route_time(0, p))
        });
        assert_eq!(inst.route_time(0, &order), best);
    }

    fn permute(p: &mut [usize; 4], k: usize, f: &mut impl FnMut(&[usize])) {
        if k == p.len() {
            return f(p);
        }
        for i in k..p.len() {
            p.swap(k, i);
            permute(p, k + 1, f);
            p.swap(k, i);
        }
    }
}
