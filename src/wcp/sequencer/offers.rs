//! The moves of the local searches, each offered with its route times from O(1) differences
//! of arc costs: one copy for the full descent ([`super::local_search`]) and the granular
//! one ([`super::granular`]), which differ only in which moves they look at.

use super::model::Model;
use super::plan::{Ends, Move, Obj, Plan, Scratch};
use super::terms::task_node;

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

    /// Makes the best move offered, if any; whether one was made.
    pub fn commit(self, model: &Model, plan: &mut Plan, scratch: &mut Scratch) -> bool {
        match self.best {
            Some(mv) => {
                plan.apply(model, &mv, scratch);
                true
            }
            None => false,
        }
    }
}

/// The segment of `len` tasks that starts at task `t`, cut out of its route: what a shift
/// (relocate, or-opt) moves, and its robot's time once it is cut.
pub(super) struct Cut<'p> {
    pub r1: usize,
    pub i: usize,
    pub len: usize,
    pub seg: &'p [usize],
    /// The segment's task durations.
    dur: f64,
    /// Robot `r1`'s time without the segment.
    pub base: f64,
}

impl<'p> Cut<'p> {
    /// The segment, or `None` if the route has fewer than `len` tasks from `t` on.
    pub fn new(model: &Model, plan: &'p Plan, t: usize, len: usize) -> Option<Cut<'p>> {
        let (r1, i) = plan.pos[t];
        let route = &plan.routes[r1];
        if i + len - 1 > route.len() - 2 {
            return None;
        }
        let seg = &route[i..i + len];
        let dur: f64 = seg.iter().map(|&v| model.dn[v]).sum();
        let (p, n, s0, sl) = (route[i - 1], route[i + len], seg[0], seg[len - 1]);
        let mut cut = Cut {
            r1,
            i,
            len,
            seg,
            dur,
            base: 0.0,
        };
        let c = |a: usize, b: usize| model.c(r1, a, b);
        let saved = c(p, n) - (c(p, s0) + cut.inner(model, r1, false) + dur + c(sl, n));
        cut.base = plan.time[r1] + saved;
        Some(cut)
    }

    /// The arcs inside the segment for robot `r`, run forwards or reversed.
    pub fn inner(&self, model: &Model, r: usize, rev: bool) -> f64 {
        let arc = |w: &[usize]| {
            if rev {
                model.c(r, w[1], w[0])
            } else {
                model.c(r, w[0], w[1])
            }
        };
        self.seg.windows(2).map(arc).sum()
    }

    /// Offers the segment put between nodes `a` and `b`, gap `gap` of robot `r2`'s route (for
    /// `r2 == r1`, counted once the segment is cut), reversed if `rev`; `mid` is
    /// [`Cut::inner`] for `r2` that way round.
    #[allow(clippy::too_many_arguments)] // the move's coordinates, spelled out
    pub fn offer(
        &self,
        model: &Model,
        plan: &Plan,
        scratch: &mut Scratch,
        pick: &mut Pick,
        (r2, gap): (usize, usize),
        (a, b): (usize, usize),
        rev: bool,
        mid: f64,
    ) {
        let c = |a: usize, b: usize| model.c(r2, a, b);
        let (s0, sl) = (self.seg[0], self.seg[self.len - 1]);
        let (first, last) = if rev { (sl, s0) } else { (s0, sl) };
        let add = (c(a, first) + mid + self.dur + c(last, b)) - c(a, b);
        let (r1, i, len) = (self.r1, self.i, self.len);
        let mv = Move::Shift {
            r1,
            i,
            len,
            r2,
            gap,
            rev,
        };
        if r2 == r1 {
            pick.offer(model, plan, mv, &[(r1, self.base + add)], scratch);
        } else {
            let times = [(r1, self.base), (r2, plan.time[r2] + add)];
            pick.offer(model, plan, mv, &times, scratch);
        }
    }
}

/// Offers the exchange of tasks `t1` and `t2`, if each fits the other's robot.
pub(super) fn offer_swap(
    model: &Model,
    plan: &Plan,
    scratch: &mut Scratch,
    pick: &mut Pick,
    (t1, t2): (usize, usize),
) {
    let c = |r: usize, a: usize, b: usize| model.c(r, a, b);
    let dn = &model.dn;
    let ((r1, i), (r2, j)) = (plan.pos[t1], plan.pos[t2]);
    let (x, y) = (task_node(t1), task_node(t2));
    let ra = &plan.routes[r1];
    if r1 != r2 {
        if !model.can(r2, t1) || !model.can(r1, t2) {
            return;
        }
        let rb = &plan.routes[r2];
        let (p1, n1, p2, n2) = (ra[i - 1], ra[i + 1], rb[j - 1], rb[j + 1]);
        let d1 = (c(r1, p1, y) + dn[y] + c(r1, y, n1)) - (c(r1, p1, x) + dn[x] + c(r1, x, n1));
        let d2 = (c(r2, p2, x) + dn[x] + c(r2, x, n2)) - (c(r2, p2, y) + dn[y] + c(r2, y, n2));
        let times = [(r1, plan.time[r1] + d1), (r2, plan.time[r2] + d2)];
        pick.offer(model, plan, Move::Swap { r1, i, r2, j }, &times, scratch);
    } else {
        let (lo, hi) = (i.min(j), i.max(j));
        let (u, v) = (ra[lo], ra[hi]);
        let delta = if hi == lo + 1 {
            let (p, n) = (ra[lo - 1], ra[hi + 1]);
            (c(r1, p, v) + c(r1, v, u) + c(r1, u, n)) - (c(r1, p, u) + c(r1, u, v) + c(r1, v, n))
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

/// Offers the reversal of positions `lo..=hi` of robot `r`'s route (2-opt), whose arcs sum
/// to `fwd` forwards and `rev` backwards.
#[allow(clippy::too_many_arguments)] // the move's coordinates, spelled out
pub(super) fn offer_reverse(
    model: &Model,
    plan: &Plan,
    scratch: &mut Scratch,
    pick: &mut Pick,
    r: usize,
    (lo, hi): (usize, usize),
    fwd: f64,
    rev: f64,
) {
    let c = |a: usize, b: usize| model.c(r, a, b);
    let route = &plan.routes[r];
    let (p, n) = (route[lo - 1], route[hi + 1]);
    let delta =
        (c(p, route[hi]) + rev + c(route[lo], n)) - (c(p, route[lo]) + fwd + c(route[hi], n));
    let times = [(r, plan.time[r] + delta)];
    pick.offer(
        model,
        plan,
        Move::Reverse { r, i: lo, j: hi },
        &times,
        scratch,
    );
}

impl Ends {
    /// Sums robot `r`'s times over its route `own` and the other's, `other`.
    fn sum(&mut self, model: &Model, r: usize, own: &[usize], other: &[usize]) {
        let c = |a: usize, b: usize| model.c(r, a, b);
        let dn = &model.dn;
        let fits = |v: usize| v == 0 || model.can(r, v - 1);
        let (n, m) = (own.len(), other.len());
        let reset = |v: &mut Vec<f64>, len: usize| {
            v.clear();
            v.resize(len, 0.0);
        };
        reset(&mut self.head, n);
        reset(&mut self.own_tail, n);
        for p in 1..n {
            self.head[p] = self.head[p - 1] + c(own[p - 1], own[p]) + dn[own[p]];
        }
        for p in (0..n - 1).rev() {
            self.own_tail[p] = c(own[p], own[p + 1]) + dn[own[p + 1]] + self.own_tail[p + 1];
        }
        reset(&mut self.tail, m);
        reset(&mut self.back, m);
        reset(&mut self.back_head, m);
        self.fits_after.clear();
        self.fits_after.resize(m, true);
        self.fits_before.clear();
        self.fits_before.resize(m, true);
        for p in (0..m - 1).rev() {
            let (u, v) = (other[p], other[p + 1]);
            self.tail[p] = c(u, v) + dn[v] + self.tail[p + 1];
            self.back_head[p] = self.back_head[p + 1] + c(v, u) + dn[u];
            self.fits_after[p] = self.fits_after[p + 1] && fits(u);
        }
        for p in 1..m {
            let (u, v) = (other[p - 1], other[p]);
            self.back[p] = c(v, u) + dn[u] + self.back[p - 1];
            self.fits_before[p] = self.fits_before[p - 1] && fits(v);
        }
    }
}

/// Offers every exchange of the ends of the routes of `r1` and `r2` (2-opt*, Potvin &
/// Rousseau, "An exchange heuristic for routing problems with time windows", 1995), plain
/// and with the pieces reversed (for symmetric costs, the two ways to reconnect two routes
/// cut once each): the inter-route move that splits a long route where another one would
/// take its end. Each robot's times over the heads and tails of both routes are summed
/// once ([`Ends`]), so that each exchange is costed in O(1).
pub(super) fn offer_crosses(
    model: &Model,
    plan: &Plan,
    scratch: &mut Scratch,
    pick: &mut Pick,
    (r1, r2): (usize, usize),
) {
    let (x, y) = (&plan.routes[r1], &plan.routes[r2]);
    let [mut e1, mut e2] = std::mem::take(&mut scratch.ends);
    e1.sum(model, r1, x, y);
    e2.sum(model, r2, y, x);
    let (c1, c2) = (|a, b| model.c(r1, a, b), |a, b| model.c(r2, a, b));
    let dn = &model.dn;
    let (nx, ny) = (x.len(), y.len());
    for i in 0..nx - 1 {
        // r2 takes r1's nodes after i, either way.
        if !e2.fits_after[i + 1] {
            continue;
        }
        let v = x[i + 1];
        for j in 0..ny - 1 {
            let u = y[j + 1];
            // Both ends home alone: the plan itself.
            if e1.fits_after[j + 1] && !(i == nx - 2 && j == ny - 2) {
                let t1 = e1.head[i] + c1(x[i], u) + dn[u] + e1.tail[j + 1];
                let t2 = e2.head[j] + c2(y[j], v) + dn[v] + e2.tail[i + 1];
                let mv = Move::Cross {
                    r1,
                    i,
                    r2,
                    j,
                    rev: false,
                };
                pick.offer(model, plan, mv, &[(r1, t1), (r2, t2)], scratch);
            }
            if e1.fits_before[j] {
                let w = y[j];
                let t1 = e1.head[i] + c1(x[i], w) + dn[w] + e1.back[j];
                let t2 = e2.back_head[i + 1] + c2(v, u) + dn[u] + e2.own_tail[j + 1];
                let mv = Move::Cross {
                    r1,
                    i,
                    r2,
                    j,
                    rev: true,
                };
                pick.offer(model, plan, mv, &[(r1, t1), (r2, t2)], scratch);
            }
        }
    }
    scratch.ends = [e1, e2];
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
