//! The instance as the searches see it: who can really do what, finite
//! penalised travel times and an index of the conflicts.

use super::terms::task_node;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::instance::Travel;
use super::lazy_costs::{self, LazyCosts};
use super::{Conflict, Instance, SequencerError, Step};

/// Largest number of stored arcs (robots × nodes²) for a dense cost matrix (8 bytes each);
/// larger instances compute their lower bounds when asked and store only the exact arcs.
const DENSE_MAX_ARCS: usize = 1 << 24;
/// From this many tasks on, the local search looks only at each task's nearest tasks
/// (granular neighbourhoods) and re-examines only what a change touched.
pub const GRANULAR_FROM_TASKS: usize = 200;
/// Nearest tasks per task in a granular neighbourhood.
const NEIGHBOURS: usize = 8;
/// Robots per task (those with the nearest homes) whose routes' ends a granular search tries.
const HOME_CANDIDATES: usize = 4;

/// Travel costs: a matrix, or lower bounds computed when asked plus the exact arcs.
enum Costs {
    /// `[r][slot[from]][slot[to]]` (see [`Model::slot`]).
    Dense(Vec<f64>),
    /// Bounds, the exact arcs and a band of precomputed costs.
    Lazy(LazyCosts),
}

/// The nearest tasks of every task, and the robots whose homes are nearest to it.
pub(super) struct Neighbours {
    /// `[t * NEIGHBOURS + k]`: the k-th nearest task of t (fewer when there are fewer tasks;
    /// `usize::MAX` pads).
    near: Vec<usize>,
    /// Per task, the capable robots whose home is nearest, nearest first.
    pub homes: Vec<Vec<usize>>,
}

impl Neighbours {
    /// The nearest tasks of task `t`, nearest first.
    #[inline]
    pub fn of(&self, t: usize) -> impl Iterator<Item = usize> + '_ {
        self.near[t * NEIGHBOURS..(t + 1) * NEIGHBOURS]
            .iter()
            .copied()
            .take_while(|&u| u != usize::MAX)
    }
}

/// Read-only data shared by every restart.
pub(super) struct Model {
    pub robots: usize,
    pub tasks: usize,
    /// Nodes per robot: home and the tasks.
    pub n1: usize,
    /// Infinite arcs cost `penalty`, home → home costs 0.
    cost: Costs,
    /// Duration of staying at each node (0 at home).
    pub dn: Vec<f64>,
    /// `[r * tasks + t]`: allowed, and reachable from home and back with finite arcs.
    capable: Vec<bool>,
    /// Per task, the capable robots in increasing order.
    pub capable_robots: Vec<Vec<usize>>,
    pub conflicts: Option<ConflictIndex>,
    /// Granular neighbourhoods, from [`GRANULAR_FROM_TASKS`] tasks on.
    pub neighbours: Option<Neighbours>,
    /// Row (and column) of each node in the dense cost matrix: granular models with task
    /// positions lay the tasks out along a Hilbert curve, so that the arcs a search asks
    /// for (between near tasks) share cache lines; the order of the search is unchanged.
    slot: Vec<usize>,
}

/// Conflicts keyed by (robot, step id), see [`Model::step_id`]. Each (robot, step id) that
/// some conflict names gets a dense id: memory grows with the conflicts, not with robots ×
/// nodes² (every possible step).
pub(super) struct ConflictIndex {
    /// The id of each (robot, step id) some conflict names; only looked up, never iterated.
    ids: FxHashMap<(usize, usize), usize>,
    /// Robots named by some conflict.
    pub hot_robot: Vec<bool>,
    /// Per id, the conflicts naming it.
    naming: Vec<Vec<usize>>,
    /// Both sides of each conflict as (robot, id); no id for a step never made.
    pub sides: Vec<[(usize, Option<usize>); 2]>,
}

impl ConflictIndex {
    /// The id of robot `r` doing step `s`, if some conflict names it.
    #[inline]
    pub fn id(&self, r: usize, s: usize) -> Option<usize> {
        self.ids.get(&(r, s)).copied()
    }

    /// Number of ids: the length of a plan's use counts.
    pub fn len(&self) -> usize {
        self.naming.len()
    }

    /// Violated conflicts after `changes` (id, ±1 uses) to the use counts `used`, which
    /// violate `viol` now. Only conflicts naming a step whose use really changes are
    /// looked at.
    pub fn violations_after(
        &self,
        used: &[u8],
        viol: usize,
        changes: &mut Vec<(usize, i32)>,
        ids: &mut Vec<usize>,
    ) -> usize {
        changes.sort_unstable();
        // Net change per id.
        let mut merged = 0;
        for k in 0..changes.len() {
            let (h, d) = changes[k];
            if merged > 0 && changes[merged - 1].0 == h {
                changes[merged - 1].1 += d;
            } else {
                changes[merged] = (h, d);
                merged += 1;
            }
        }
        changes.truncate(merged);
        changes.retain(|c| c.1 != 0);
        ids.clear();
        for &(h, _) in changes.iter() {
            ids.extend_from_slice(&self.naming[h]);
        }
        ids.sort_unstable();
        ids.dedup();
        let now = |(_, h): (usize, Option<usize>)| h.is_some_and(|h| used[h] > 0);
        let after = |(_, h): (usize, Option<usize>)| {
            h.is_some_and(|h| {
                let delta = changes
                    .binary_search_by(|c| c.0.cmp(&h))
                    .map_or(0, |k| changes[k].1);
                used[h] as i32 + delta > 0
            })
        };
        let mut out = viol as i64;
        for &k in ids.iter() {
            let [x, y] = self.sides[k];
            out += (after(x) && after(y)) as i64;
            out -= (now(x) && now(y)) as i64;
        }
        out as usize
    }
}

impl Model {
    pub fn new(inst: &Instance, conflicts: &[Conflict]) -> Result<Model, SequencerError> {
        let (robots, tasks, n1) = (inst.robots, inst.tasks, inst.tasks + 1);
        let mut capable = vec![false; robots * tasks];
        let bounded = matches!(inst.travel, Travel::Bounded { .. });
        for r in 0..robots {
            if bounded {
                // Unknown arcs are finite as far as anyone knows: a task is within reach
                // unless its moves from and to home are known to fail (every task's are
                // planned before sequencing).
                for t in 0..tasks {
                    capable[r * tasks + t] = inst.allowed[r][t]
                        && inst.travel(r, 0, task_node(t)).is_finite()
                        && inst.travel(r, task_node(t), 0).is_finite();
                }
                continue;
            }
            let there = reachable(inst, r, true);
            let back = reachable(inst, r, false);
            for t in 0..tasks {
                capable[r * tasks + t] =
                    inst.allowed[r][t] && there[task_node(t)] && back[task_node(t)];
            }
        }
        let capable_robots: Vec<Vec<usize>> = (0..tasks)
            .map(|t| (0..robots).filter(|&r| capable[r * tasks + t]).collect())
            .collect();
        if let Some(task) = capable_robots.iter().position(Vec::is_empty) {
            return Err(SequencerError::TaskUnassignable { task });
        }
        let mut dn = vec![0.0; n1];
        dn[1..].copy_from_slice(&inst.duration);
        let mut model = Model {
            robots,
            tasks,
            n1,
            cost: Costs::Dense(Vec::new()),
            dn,
            capable,
            capable_robots,
            conflicts: None,
            neighbours: None,
            slot: (0..n1).collect(),
        };
        if tasks >= GRANULAR_FROM_TASKS {
            if let Some(bounds) = inst.bounds() {
                model.slot = lazy_costs::hilbert_slots(bounds);
            }
        }
        model.cost = model.fill_costs(inst);
        if !conflicts.is_empty() {
            model.conflicts = Some(model.index_conflicts(conflicts));
        }
        if tasks >= GRANULAR_FROM_TASKS {
            model.neighbours = Some(model.neighbours(inst));
        }
        Ok(model)
    }

    /// A finite stand-in for infinite arcs, longer than any route without
    /// them: plans that need one still compare, and lose against any other.
    fn fill_costs(&self, inst: &Instance) -> Costs {
        let n1 = self.n1;
        let mut longest: f64 = 0.0;
        match &inst.travel {
            Travel::Dense(m) => {
                for (k, &v) in m.iter().flatten().enumerate() {
                    if (k / n1) % n1 != k % n1 && v.is_finite() {
                        longest = longest.max(v);
                    }
                }
            }
            Travel::Bounded { bounds, exact } => {
                longest = bounds.longest();
                for &v in exact.iter().flat_map(|m| m.values()) {
                    if v.is_finite() {
                        longest = longest.max(v);
                    }
                }
            }
        }
        let bound = self.dn.iter().sum::<f64>() + n1 as f64 * longest;
        let mut penalty = 2.0 * bound + 1.0;
        if !penalty.is_finite() {
            // Absurd scales: keep sums of n1 penalties finite at least.
            penalty = f64::MAX / (4.0 * (n1 as f64 + 1.0));
        }
        let finite = |v: f64| if v.is_finite() { v } else { penalty };
        match &inst.travel {
            Travel::Bounded { bounds, exact } if self.robots * n1 * n1 > DENSE_MAX_ARCS => {
                Costs::Lazy(LazyCosts::new(
                    self.robots,
                    &self.slot,
                    bounds.clone(),
                    exact,
                    &finite,
                ))
            }
            travel => {
                let slot = &self.slot;
                let mut node = vec![0; n1];
                for (v, &k) in slot.iter().enumerate() {
                    node[k] = v;
                }
                let mut cost = vec![0.0; self.robots * n1 * n1];
                cost.par_chunks_mut(n1 * n1)
                    .enumerate()
                    .for_each(|(r, m)| match travel {
                        Travel::Dense(t) => {
                            for (k, c) in m.iter_mut().enumerate() {
                                let (a, b) = (node[k / n1], node[k % n1]);
                                if a != b {
                                    *c = finite(t[r][a * n1 + b]);
                                }
                            }
                        }
                        Travel::Bounded { bounds, exact } => {
                            for (k, c) in m.iter_mut().enumerate() {
                                let (a, b) = (node[k / n1], node[k % n1]);
                                if a != b {
                                    *c = bounds.bound(r, a, b);
                                }
                            }
                            for (&(a, b), &v) in &exact[r] {
                                if a != b {
                                    m[slot[a] * n1 + slot[b]] = finite(v);
                                }
                            }
                        }
                    });
                Costs::Dense(cost)
            }
        }
    }

    /// Each task's nearest tasks (by position when the bounds know them, else by the
    /// fastest round trip of a robot), ties by index; and its robots by the bound of the
    /// move from their home.
    fn neighbours(&self, inst: &Instance) -> Neighbours {
        let n = self.tasks;
        let bounds = inst.bounds();
        let distance = |a: usize, b: usize| match bounds {
            Some(bounds) => bounds.task_distance(a, b),
            None => (0..self.robots)
                .map(|r| self.c(r, a + 1, b + 1) + self.c(r, b + 1, a + 1))
                .fold(f64::INFINITY, f64::min),
        };
        let near: Vec<usize> = (0..n)
            .into_par_iter()
            .flat_map_iter(|t| {
                let mut all: Vec<(f64, usize)> = (0..n)
                    .filter(|&u| u != t)
                    .map(|u| (distance(t, u), u))
                    .collect();
                let k = NEIGHBOURS.min(all.len());
                let order =
                    |x: &(f64, usize), y: &(f64, usize)| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1));
                if k < all.len() {
                    all.select_nth_unstable_by(k, order);
                    all.truncate(k);
                }
                all.sort_by(order);
                let mut row: Vec<usize> = all.into_iter().map(|(_, u)| u).collect();
                row.resize(NEIGHBOURS, usize::MAX);
                row
            })
            .collect();
        let homes = (0..n)
            .map(|t| {
                let mut rs = self.capable_robots[t].clone();
                rs.sort_by(|&a, &b| {
                    self.c(a, 0, task_node(t))
                        .total_cmp(&self.c(b, 0, task_node(t)))
                        .then(a.cmp(&b))
                });
                rs.truncate(HOME_CANDIDATES);
                rs
            })
            .collect();
        Neighbours { near, homes }
    }

    fn index_conflicts(&self, conflicts: &[Conflict]) -> ConflictIndex {
        let mut index = ConflictIndex {
            ids: FxHashMap::default(),
            hot_robot: vec![false; self.robots],
            naming: Vec::new(),
            sides: Vec::with_capacity(conflicts.len()),
        };
        for (k, c) in conflicts.iter().enumerate() {
            let sides = [c.a, c.b].map(|(r, s)| {
                let s = self.step_id(s);
                // A move from a node to itself is never made: it cannot matter.
                if self.never_used(s) {
                    return (r, None);
                }
                index.hot_robot[r] = true;
                let fresh = index.naming.len();
                let h = *index.ids.entry((r, s)).or_insert(fresh);
                if h == fresh {
                    index.naming.push(Vec::new());
                }
                if index.naming[h].last() != Some(&k) {
                    index.naming[h].push(k);
                }
                (r, Some(h))
            });
            index.sides.push(sides);
        }
        index
    }

    /// Dense id of a step: moves first (`from * n1 + to`), then stays.
    pub fn step_id(&self, s: Step) -> usize {
        match s {
            Step::Move { from, to } => from * self.n1 + to,
            Step::Stay { node } => self.n1 * self.n1 + node,
        }
    }

    fn never_used(&self, s: usize) -> bool {
        s < self.n1 * self.n1 && s / self.n1 == s % self.n1
    }

    /// Calls `f` with the id of every step of a route given as nodes with
    /// home at both ends; home → home (the empty route) is no move.
    pub fn for_each_step(&self, nodes: &[usize], mut f: impl FnMut(usize)) {
        f(self.n1 * self.n1);
        if nodes.len() > 2 {
            for w in nodes.windows(2) {
                f(w[0] * self.n1 + w[1]);
            }
            for &v in &nodes[1..nodes.len() - 1] {
                f(self.n1 * self.n1 + v);
            }
        }
    }

    #[inline(always)]
    pub fn c(&self, r: usize, a: usize, b: usize) -> f64 {
        match &self.cost {
            Costs::Dense(m) => m[(r * self.n1 + self.slot[a]) * self.n1 + self.slot[b]],
            Costs::Lazy(lazy) => lazy.get(r, a, b),
        }
    }

    #[inline]
    pub fn can(&self, r: usize, t: usize) -> bool {
        self.capable[r * self.tasks + t]
    }

    pub fn capable_tasks(&self, r: usize) -> Vec<usize> {
        (0..self.tasks).filter(|&t| self.can(r, t)).collect()
    }

    /// Route time of a node list (home at both ends), summed left to right
    /// like [`Instance::route_time`] so that plans without infinite arcs cost
    /// exactly the same here and there.
    pub fn route_time(&self, r: usize, nodes: &[usize]) -> f64 {
        let mut acc = 0.0;
        for w in nodes.windows(2) {
            acc += self.c(r, w[0], w[1]);
            acc += self.dn[w[1]];
        }
        acc
    }
}

/// Nodes robot `r` reaches from home (`forward`) or from which it reaches
/// home, through finite arcs and the tasks it is allowed to do.
fn reachable(inst: &Instance, r: usize, forward: bool) -> Vec<bool> {
    let n1 = inst.tasks + 1;
    let open = |v: usize| v == 0 || inst.allowed[r][v - 1];
    let mut seen = vec![false; n1];
    let mut stack = vec![0];
    seen[0] = true;
    while let Some(v) = stack.pop() {
        for (w, mark) in seen.iter_mut().enumerate() {
            let arc = if forward {
                inst.travel(r, v, w)
            } else {
                inst.travel(r, w, v)
            };
            if !*mark && w != v && open(w) && arc.is_finite() {
                *mark = true;
                stack.push(w);
            }
        }
    }
    seen
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Vec2;
    use crate::wcp::sequencer::{BoundLimits, Bounds, ExactArcs};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::sync::Arc;

    /// Lazy costs (too many arcs for a matrix) with their band give the instance's travel
    /// times: exact ones where known, bounds elsewhere.
    #[test]
    fn lazy_costs_are_the_instance_travel_times() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let (robots, tasks) = (5, 2000);
        assert!(robots * (tasks + 1) * (tasks + 1) > DENSE_MAX_ARCS);
        let mut pose = || {
            (
                Vec2::new(rng.random_range(0.0..100.0), rng.random_range(0.0..80.0)),
                rng.random_range(-3.0..3.0),
            )
        };
        let homes = (0..robots).map(|_| pose()).collect();
        let task_poses = (0..tasks).map(|_| pose()).collect();
        let limits = (0..robots)
            .map(|r| BoundLimits {
                max_speed: 1.0 + r as f64 * 0.1,
                max_accel: 2.0,
                max_angular_accel: 4.0,
                max_turn_rate: 1.5,
            })
            .collect();
        let bounds = Arc::new(Bounds::new(limits, homes, task_poses));
        let mut exact: ExactArcs = vec![Default::default(); robots];
        let mut arcs = Vec::new();
        for _ in 0..20_000 {
            let (r, a, b) = (
                rng.random_range(0..robots),
                rng.random_range(0..=tasks),
                rng.random_range(0..=tasks),
            );
            arcs.push((r, a, b));
            if rng.random_bool(0.3) && a != b {
                exact[r].insert((a, b), bounds.bound(r, a, b) * 1.5);
            }
        }
        let allowed = vec![vec![true; tasks]; robots];
        let inst = Instance::bounded(vec![1.0; tasks], allowed, bounds, Arc::new(exact)).unwrap();
        let model = Model::new(&inst, &[]).unwrap();
        assert!(matches!(model.cost, Costs::Lazy(_)));
        let nb = model.neighbours.as_ref().unwrap();
        let mut node = vec![0; tasks + 1];
        for (v, &k) in model.slot.iter().enumerate() {
            node[k] = v;
        }
        for t in 0..50 {
            for u in nb.of(t) {
                arcs.push((t % robots, task_node(t), task_node(u)));
                arcs.push((t % robots, task_node(u), task_node(t)));
            }
            // Both ends of the band, and just beyond.
            let s = model.slot[task_node(t)];
            for d in [
                1,
                lazy_costs::BAND - 1,
                lazy_costs::BAND,
                lazy_costs::BAND + 1,
            ] {
                for other in [s + d, s.wrapping_sub(d)] {
                    if other <= tasks {
                        arcs.push((t % robots, task_node(t), node[other]));
                        arcs.push((t % robots, node[other], task_node(t)));
                    }
                }
            }
        }
        for (r, a, b) in arcs {
            assert_eq!(
                model.c(r, a, b),
                inst.travel(r, a, b),
                "robot {r} {a} -> {b}"
            );
        }
    }
}
