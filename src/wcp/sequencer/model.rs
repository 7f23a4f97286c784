//! The instance as the searches see it: who can really do what, finite
//! penalised travel times and an index of the conflicts.

use std::collections::HashMap;

use super::{Conflict, Instance, SequencerError, Step};

/// Read-only data shared by every restart.
pub(super) struct Model {
    pub robots: usize,
    pub tasks: usize,
    /// Nodes per robot: home and the tasks.
    pub n1: usize,
    /// `[r][from][to]`; infinite arcs cost `penalty`, home → home costs 0.
    cost: Vec<f64>,
    /// Duration of staying at each node (0 at home).
    pub dn: Vec<f64>,
    /// `[r * tasks + t]`: allowed, and reachable from home and back with finite arcs.
    capable: Vec<bool>,
    /// Per task, the capable robots in increasing order.
    pub capable_robots: Vec<Vec<usize>>,
    pub conflicts: Option<ConflictIndex>,
}

/// Conflicts keyed by (robot, step id), see [`Model::step_id`].
pub(super) struct ConflictIndex {
    /// Step ids per robot.
    pub steps: usize,
    /// `[r * steps + s]`: some conflict names robot r doing step s.
    hot: Vec<bool>,
    /// Robots named by some conflict.
    pub hot_robot: Vec<bool>,
    /// Conflicts naming (robot, step id); only looked up, never iterated.
    by_step: HashMap<(usize, usize), Vec<usize>>,
    /// Both sides of each conflict as (robot, step id).
    pub sides: Vec<[(usize, usize); 2]>,
}

impl ConflictIndex {
    #[inline]
    pub fn hot(&self, r: usize, s: usize) -> bool {
        self.hot[r * self.steps + s]
    }

    fn naming(&self, r: usize, s: usize) -> &[usize] {
        self.by_step.get(&(r, s)).map_or(&[], |v| v.as_slice())
    }

    /// Violated conflicts after `changes` (robot, step id, ±1 uses) to the
    /// use counts `used`, which violate `viol` now. Only conflicts naming a
    /// step whose use really changes are looked at.
    pub fn violations_after(
        &self,
        used: &[u8],
        viol: usize,
        changes: &mut Vec<(usize, usize, i32)>,
        ids: &mut Vec<usize>,
    ) -> usize {
        changes.sort_unstable();
        // Net change per (robot, step).
        let mut merged = 0;
        for k in 0..changes.len() {
            let (r, s, d) = changes[k];
            if merged > 0 && changes[merged - 1].0 == r && changes[merged - 1].1 == s {
                changes[merged - 1].2 += d;
            } else {
                changes[merged] = (r, s, d);
                merged += 1;
            }
        }
        changes.truncate(merged);
        changes.retain(|c| c.2 != 0);
        ids.clear();
        for &(r, s, _) in changes.iter() {
            ids.extend_from_slice(self.naming(r, s));
        }
        ids.sort_unstable();
        ids.dedup();
        let now = |(r, s): (usize, usize)| used[r * self.steps + s] > 0;
        let after = |(r, s): (usize, usize)| {
            let delta = changes
                .binary_search_by(|c| (c.0, c.1).cmp(&(r, s)))
                .map_or(0, |k| changes[k].2);
            used[r * self.steps + s] as i32 + delta > 0
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
        for r in 0..robots {
            let there = reachable(inst, r, true);
            let back = reachable(inst, r, false);
            for t in 0..tasks {
                capable[r * tasks + t] = inst.allowed[r][t] && there[t + 1] && back[t + 1];
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
            cost: Vec::with_capacity(robots * n1 * n1),
            dn,
            capable,
            capable_robots,
            conflicts: None,
        };
        model.fill_costs(inst);
        if !conflicts.is_empty() {
            model.conflicts = Some(model.index_conflicts(conflicts));
        }
        Ok(model)
    }

    /// A finite stand-in for infinite arcs, longer than any route without
    /// them: plans that need one still compare, and lose against any other.
    fn fill_costs(&mut self, inst: &Instance) {
        let n1 = self.n1;
        let mut longest: f64 = 0.0;
        for r in 0..self.robots {
            for a in 0..n1 {
                for b in 0..n1 {
                    let v = inst.travel(r, a, b);
                    if a != b && v.is_finite() {
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
        for r in 0..self.robots {
            for a in 0..n1 {
                for b in 0..n1 {
                    let v = inst.travel(r, a, b);
                    let c = if a == b {
                        0.0
                    } else if v.is_finite() {
                        v
                    } else {
                        penalty
                    };
                    self.cost.push(c);
                }
            }
        }
    }

    fn index_conflicts(&self, conflicts: &[Conflict]) -> ConflictIndex {
        let steps = self.n1 * self.n1 + self.n1;
        let mut index = ConflictIndex {
            steps,
            hot: vec![false; self.robots * steps],
            hot_robot: vec![false; self.robots],
            by_step: HashMap::new(),
            sides: Vec::with_capacity(conflicts.len()),
        };
        for (k, c) in conflicts.iter().enumerate() {
            let sides = [c.a, c.b].map(|(r, s)| (r, self.step_id(s)));
            for (r, s) in sides {
                // A move from a node to itself is never made: it cannot matter.
                if !self.never_used(s) {
                    index.hot[r * steps + s] = true;
                    index.hot_robot[r] = true;
                    index.by_step.entry((r, s)).or_default().push(k);
                }
            }
            index.sides.push(sides);
        }
        for v in index.by_step.values_mut() {
            v.dedup();
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

    #[inline]
    pub fn c(&self, r: usize, a: usize, b: usize) -> f64 {
        self.cost[(r * self.n1 + a) * self.n1 + b]
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
