//! A plan under construction or search: routes, their costs, and the moves
//! that change them.

use super::model::Model;
use super::terms::task_node;

/// Relative tolerance of every comparison: rounding never makes a move look
/// like an improvement, so the search cannot cycle.
const EPS: f64 = 1e-12;

/// `a` is smaller than `b` by more than rounding.
#[inline]
fn less(a: f64, b: f64) -> bool {
    a < b - EPS * b.abs()
}

/// The objective, compared lexicographically.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Obj {
    pub viol: usize,
    pub makespan: f64,
    pub total: f64,
}

impl Obj {
    /// Worse than any plan.
    pub const WORST: Obj = Obj {
        viol: usize::MAX,
        makespan: f64::MAX,
        total: f64::MAX,
    };

    pub fn better(&self, o: &Obj) -> bool {
        if self.viol != o.viol {
            return self.viol < o.viol;
        }
        if less(self.makespan, o.makespan) {
            return true;
        }
        !less(o.makespan, self.makespan) && less(self.total, o.total)
    }
}

/// A change of one or two routes. Positions index node lists, which hold
/// home at both ends: the tasks of a route sit at `1..len - 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Move {
    /// Insert unassigned task `t` into robot `r` after position `gap`.
    Insert { t: usize, r: usize, gap: usize },
    /// Take the task at position `i` of robot `r` out (it becomes unassigned).
    Remove { r: usize, i: usize },
    /// Cut `len` tasks from position `i` of `r1`, insert them (reversed if
    /// `rev`) after position `gap` of `r2` as it is once they are cut.
    Shift {
        r1: usize,
        i: usize,
        len: usize,
        r2: usize,
        gap: usize,
        rev: bool,
    },
    /// Exchange position `i` of `r1` with position `j` of `r2`.
    Swap {
        r1: usize,
        i: usize,
        r2: usize,
        j: usize,
    },
    /// Reverse positions `i..=j` of robot `r`.
    Reverse { r: usize, i: usize, j: usize },
    /// Exchange the ends of two routes (2-opt*): `r1` keeps its nodes up to position `i`
    /// and goes on with those of `r2` after position `j`, and `r2` the other way round;
    /// `rev`: `r1` goes on with `r2`'s nodes up to `j` backwards, and `r2` does `r1`'s
    /// nodes after `i` backwards, then its own after `j`.
    Cross {
        r1: usize,
        i: usize,
        r2: usize,
        j: usize,
        rev: bool,
    },
}

/// Reusable buffers, so that evaluating a move allocates nothing.
#[derive(Default)]
pub(super) struct Scratch {
    a: Vec<usize>,
    b: Vec<usize>,
    changes: Vec<(usize, i32)>,
    ids: Vec<usize>,
    /// The granular search's candidate places (robot, gap), each once.
    pub gaps: Vec<(usize, usize)>,
    /// A 2-opt* pass's sums, per robot of the pair (see `offers::offer_crosses`).
    pub ends: [Ends; 2],
    /// `[robot][gap]`: the stamp of the last call that listed that place.
    pub seen: Vec<Vec<u32>>,
    pub stamp: u32,
}

/// One robot's times over the pieces of its own route and of the other's that a 2-opt*
/// exchange joins (see `offers::offer_crosses`), each on the robot's own arc costs. "Stay
/// included" counts the task's duration at the node named.
#[derive(Default)]
pub(super) struct Ends {
    /// `[p]`: from home along its own route to its node `p`, stay included.
    pub(super) head: Vec<f64>,
    /// `[p]`: from its own node `p` along its route home, stay excluded.
    pub(super) own_tail: Vec<f64>,
    /// `[p]`: from the other's node `p` along the other's route home, stay excluded.
    pub(super) tail: Vec<f64>,
    /// `[p]`: from the other's node `p` back along the other's route to its start, stay
    /// excluded.
    pub(super) back: Vec<f64>,
    /// `[p]`: from the other's end back along the other's route to its node `p`, stay
    /// included.
    pub(super) back_head: Vec<f64>,
    /// `[p]`: the robot may do every task of the other's route from its node `p` on.
    pub(super) fits_after: Vec<bool>,
    /// `[p]`: the robot may do every task of the other's route up to its node `p`.
    pub(super) fits_before: Vec<bool>,
}

/// Marks a task that no route holds.
const NONE: (usize, usize) = (usize::MAX, usize::MAX);

#[derive(Clone, Debug)]
pub(super) struct Plan {
    /// Per robot, its nodes from home back to home.
    pub routes: Vec<Vec<usize>>,
    /// Per robot, its (penalised) route time.
    pub time: Vec<f64>,
    /// Per task, (robot, position), or `NONE`.
    pub pos: Vec<(usize, usize)>,
    pub total: f64,
    /// The three longest routes as (time, robot), for the makespan without some robots.
    top: [(f64, usize); 3],
    /// With conflicts: per id of [`super::model::ConflictIndex`], how often its robot's
    /// route uses its step.
    used: Vec<u8>,
    pub viol: usize,
    /// Per robot, the violated conflicts that name it.
    involved: Vec<usize>,
}

impl Plan {
    pub fn empty(model: &Model) -> Plan {
        let mut plan = Plan {
            routes: vec![vec![0, 0]; model.robots],
            time: vec![0.0; model.robots],
            pos: vec![NONE; model.tasks],
            total: 0.0,
            top: [(0.0, usize::MAX); 3],
            used: Vec::new(),
            viol: 0,
            involved: vec![0; model.robots],
        };
        if let Some(ci) = &model.conflicts {
            plan.used = vec![0; ci.len()];
            for r in 0..model.robots {
                plan.count_steps(model, r, 1);
            }
        }
        plan.summarise(model);
        plan
    }

    pub fn from_sequences(model: &Model, seqs: &[Vec<usize>]) -> Plan {
        let mut plan = Plan::empty(model);
        for (r, seq) in seqs.iter().enumerate() {
            plan.count_steps(model, r, -1);
            plan.routes[r] = std::iter::once(0)
                .chain(seq.iter().map(|&t| task_node(t)))
                .chain(std::iter::once(0))
                .collect();
            plan.count_steps(model, r, 1);
            plan.refresh(model, r);
        }
        plan.summarise(model);
        plan
    }

    pub fn sequences(&self) -> Vec<Vec<usize>> {
        self.routes
            .iter()
            .map(|nodes| nodes[1..nodes.len() - 1].iter().map(|v| v - 1).collect())
            .collect()
    }

    pub fn obj(&self) -> Obj {
        Obj {
            viol: self.viol,
            makespan: self.top[0].0,
            total: self.total,
        }
    }

    /// Index of a longest route.
    pub fn critical(&self) -> usize {
        self.top[0].1
    }

    /// Longest route time among the robots other than `a` and `b`.
    #[inline]
    pub fn max_excluding(&self, a: usize, b: usize) -> f64 {
        self.top
            .iter()
            .find(|&&(_, r)| r != a && r != b)
            .map_or(0.0, |&(v, _)| v)
    }

    /// The objective once `mv` is made, given the new times of the robots
    /// it touches, if it beats `bar`. The conflicts are counted only when
    /// the move could win even if it repaired every violation of its robots.
    #[inline]
    pub fn evaluate(
        &self,
        model: &Model,
        mv: &Move,
        times: &[(usize, f64)],
        bar: &Obj,
        scratch: &mut Scratch,
    ) -> Option<Obj> {
        let (a, b) = (times[0].0, times[times.len() - 1].0);
        let mut makespan = self.max_excluding(a, b);
        let mut total = self.total;
        for &(r, t) in times {
            makespan = makespan.max(t);
            total += t - self.time[r];
        }
        let mut obj = Obj {
            viol: self.viol,
            makespan,
            total,
        };
        let quiet = match &model.conflicts {
            None => true,
            Some(ci) => !times.iter().any(|&(r, _)| ci.hot_robot[r]),
        };
        if quiet {
            return obj.better(bar).then_some(obj);
        }
        let involved = self.involved[a] + if b == a { 0 } else { self.involved[b] };
        obj.viol = self.viol.saturating_sub(involved);
        if !obj.better(bar) {
            return None;
        }
        obj.viol = self.viol_after(model, mv, scratch);
        obj.better(bar).then_some(obj)
    }

    pub fn apply(&mut self, model: &Model, mv: &Move, scratch: &mut Scratch) {
        if let Move::Remove { r, i } = *mv {
            let t = self.routes[r][i] - 1;
            self.pos[t] = NONE;
        }
        let (r1, r2) = self.rebuild(mv, &mut scratch.a, &mut scratch.b);
        let touched = [(r1, &mut scratch.a), (r2.unwrap_or(r1), &mut scratch.b)];
        for (k, (r, buf)) in touched.into_iter().enumerate() {
            if k == 1 && r2.is_none() {
                break;
            }
            self.count_steps(model, r, -1);
            std::mem::swap(&mut self.routes[r], buf);
            self.count_steps(model, r, 1);
            self.refresh(model, r);
        }
        self.summarise(model);
    }

    /// Writes the routes `mv` produces into `a` (and `b` when it touches
    /// two robots); returns the robots.
    fn rebuild(&self, mv: &Move, a: &mut Vec<usize>, b: &mut Vec<usize>) -> (usize, Option<usize>) {
        let load = |buf: &mut Vec<usize>, r: usize| {
            buf.clear();
            buf.extend_from_slice(&self.routes[r]);
        };
        match *mv {
            Move::Insert { t, r, gap } => {
                load(a, r);
                a.insert(gap + 1, task_node(t));
                (r, None)
            }
            Move::Remove { r, i } => {
                load(a, r);
                a.remove(i);
                (r, None)
            }
            Move::Shift {
                r1,
                i,
                len,
                r2,
                gap,
                rev,
            } => {
                load(a, r1);
                a.drain(i..i + len);
                let target = if r1 == r2 {
                    &mut *a
                } else {
                    load(b, r2);
                    &mut *b
                };
                let seg = self.routes[r1][i..i + len].iter().copied();
                if rev {
                    target.splice(gap + 1..gap + 1, seg.rev());
                } else {
                    target.splice(gap + 1..gap + 1, seg);
                }
                (r1, (r1 != r2).then_some(r2))
            }
            Move::Swap { r1, i, r2, j } => {
                load(a, r1);
                if r1 == r2 {
                    a.swap(i, j);
                    (r1, None)
                } else {
                    load(b, r2);
                    std::mem::swap(&mut a[i], &mut b[j]);
                    (r1, Some(r2))
                }
            }
            Move::Reverse { r, i, j } => {
                load(a, r);
                a[i..=j].reverse();
                (r, None)
            }
            Move::Cross { r1, i, r2, j, rev } => {
                let (x, y) = (&self.routes[r1], &self.routes[r2]);
                a.clear();
                a.extend_from_slice(&x[..=i]);
                b.clear();
                if rev {
                    // r1: its head, then r2's head backwards home; r2: r1's tail backwards
                    // from home, then its own tail.
                    a.extend(y[..=j].iter().rev());
                    b.extend(x[i + 1..].iter().rev());
                    b.extend_from_slice(&y[j + 1..]);
                } else {
                    a.extend_from_slice(&y[j + 1..]);
                    b.extend_from_slice(&y[..=j]);
                    b.extend_from_slice(&x[i + 1..]);
                }
                (r1, Some(r2))
            }
        }
    }

    /// The nodes whose arcs `mv` changes (the ends of every arc it removes or adds), in the
    /// plan as it is before the move; homes (0) included.
    pub fn touched(&self, mv: &Move) -> Vec<usize> {
        let at = |r: usize, k: usize| self.routes[r][k];
        match *mv {
            Move::Insert { t, r, gap } => vec![task_node(t), at(r, gap), at(r, gap + 1)],
            Move::Remove { r, i } => vec![at(r, i - 1), at(r, i), at(r, i + 1)],
            Move::Shift {
                r1,
                i,
                len,
                r2,
                gap,
                ..
            } => {
                let mut out = vec![
                    at(r1, i - 1),
                    at(r1, i),
                    at(r1, i + len - 1),
                    at(r1, i + len),
                ];
                if r1 == r2 {
                    let node = |k: usize| if k < i { at(r1, k) } else { at(r1, k + len) };
                    out.extend([node(gap), node(gap + 1)]);
                } else {
                    out.extend([at(r2, gap), at(r2, gap + 1)]);
                }
                out
            }
            Move::Swap { r1, i, r2, j } => vec![
                at(r1, i - 1),
                at(r1, i),
                at(r1, i + 1),
                at(r2, j - 1),
                at(r2, j),
                at(r2, j + 1),
            ],
            Move::Reverse { r, i, j } => vec![at(r, i - 1), at(r, i), at(r, j), at(r, j + 1)],
            Move::Cross { r1, i, r2, j, .. } => {
                vec![at(r1, i), at(r1, i + 1), at(r2, j), at(r2, j + 1)]
            }
        }
    }

    /// Violated conflicts once `mv` is made: only conflicts naming a step
    /// that some touched route gains or loses can change.
    pub fn viol_after(&self, model: &Model, mv: &Move, scratch: &mut Scratch) -> usize {
        let Some(ci) = &model.conflicts else {
            return 0;
        };
        let (r1, r2) = self.rebuild(mv, &mut scratch.a, &mut scratch.b);
        let changes = &mut scratch.changes;
        changes.clear();
        let touched = [(r1, &scratch.a), (r2.unwrap_or(r1), &scratch.b)];
        for (r, new) in touched.into_iter().take(1 + r2.is_some() as usize) {
            if !ci.hot_robot[r] {
                continue;
            }
            model.for_each_step(&self.routes[r], |s| {
                if let Some(h) = ci.id(r, s) {
                    changes.push((h, -1));
                }
            });
            model.for_each_step(new, |s| {
                if let Some(h) = ci.id(r, s) {
                    changes.push((h, 1));
                }
            });
        }
        ci.violations_after(&self.used, self.viol, changes, &mut scratch.ids)
    }

    /// Adds `sign` to the use counts of robot `r`'s steps.
    fn count_steps(&mut self, model: &Model, r: usize, sign: i8) {
        let Some(ci) = &model.conflicts else {
            return;
        };
        if !ci.hot_robot[r] {
            return;
        }
        let used = &mut self.used;
        model.for_each_step(&self.routes[r], |s| {
            if let Some(h) = ci.id(r, s) {
                used[h] = used[h].wrapping_add_signed(sign);
            }
        });
    }

    /// Recomputes robot `r`'s time and the positions of its tasks.
    fn refresh(&mut self, model: &Model, r: usize) {
        self.time[r] = model.route_time(r, &self.routes[r]);
        let nodes = &self.routes[r];
        for (i, &v) in nodes.iter().enumerate().take(nodes.len() - 1).skip(1) {
            self.pos[v - 1] = (r, i);
        }
    }

    /// Recomputes the total, the longest routes and the violations from scratch.
    fn summarise(&mut self, model: &Model) {
        self.total = self.time.iter().sum();
        let mut top = [(0.0, usize::MAX); 3];
        for (r, &t) in self.time.iter().enumerate() {
            if let Some(k) = top.iter().position(|&(v, q)| q == usize::MAX || t > v) {
                top[k..].rotate_right(1);
                top[k] = (t, r);
            }
        }
        self.top = top;
        if let Some(ci) = &model.conflicts {
            let used = |(_, h): (usize, Option<usize>)| h.is_some_and(|h| self.used[h] > 0);
            self.viol = 0;
            self.involved.fill(0);
            for [x, y] in ci.sides.iter().filter(|[x, y]| used(*x) && used(*y)) {
                self.viol += 1;
                self.involved[x.0] += 1;
                if y.0 != x.0 {
                    self.involved[y.0] += 1;
                }
            }
        }
    }

    /// Checks the cached data against a recomputation (tests only).
    #[cfg(test)]
    pub fn assert_consistent(&self, model: &Model) {
        let fresh = Plan::from_sequences(model, &self.sequences());
        assert_eq!(self.routes, fresh.routes);
        assert_eq!(self.time, fresh.time);
        assert_eq!(self.used, fresh.used);
        assert_eq!(self.obj(), fresh.obj());
        for (t, &p) in self.pos.iter().enumerate() {
            assert!(p == NONE || self.routes[p.0][p.1] == task_node(t));
        }
    }

    /// The times of the robots `mv` touches, recomputed from the rebuilt routes (tests only).
    #[cfg(test)]
    pub fn times_after(&self, model: &Model, mv: &Move) -> Vec<(usize, f64)> {
        let (mut a, mut b) = (Vec::new(), Vec::new());
        let (r1, r2) = self.rebuild(mv, &mut a, &mut b);
        let mut out = vec![(r1, model.route_time(r1, &a))];
        if let Some(r2) = r2 {
            out.push((r2, model.route_time(r2, &b)));
        }
        out
    }
}
