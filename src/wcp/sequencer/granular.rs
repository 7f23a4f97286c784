//! Granular local search for large instances (Toth & Vigo 2003): the moves of
//! [`super::local_search`], but each task is only moved next to one of its nearest tasks or to
//! the ends of the routes of the robots with the nearest homes, swapped with a near task, or
//! joined to a near task by reversing part of its route. Only the tasks that a change touched
//! are looked at again (don't-look bits, Bentley 1992), plus the whole longest route whenever
//! it changes, since any of its tasks may then shorten the makespan.
//!
//! The work of a descent is then proportional to what changed, not to the number of tasks.

use super::terms::{node_task, task_node};
use std::collections::VecDeque;

use super::local_search::Pick;
use super::model::Model;
use super::plan::{Move, Plan, Scratch};

/// The tasks still to look at, in first-in first-out order.
pub(super) struct Active {
    queue: VecDeque<usize>,
    queued: Vec<bool>,
}

impl Active {
    /// Every task of the plan, in task order.
    pub fn all(model: &Model) -> Active {
        Active {
            queue: (0..model.tasks).collect(),
            queued: vec![true; model.tasks],
        }
    }

    /// Nothing to look at.
    pub fn none(model: &Model) -> Active {
        Active {
            queue: VecDeque::new(),
            queued: vec![false; model.tasks],
        }
    }

    /// Looks at task `t` again (nodes: 0 is a home, not a task).
    pub fn push_node(&mut self, node: usize) {
        if node > 0 && !self.queued[node_task(node)] {
            self.queued[node_task(node)] = true;
            self.queue.push_back(node_task(node));
        }
    }

    fn pop(&mut self) -> Option<usize> {
        let t = self.queue.pop_front()?;
        self.queued[t] = false;
        Some(t)
    }
}

/// Improves `plan` until no granular move from an active task does.
pub(super) fn local_search(
    model: &Model,
    plan: &mut Plan,
    scratch: &mut Scratch,
    active: &mut Active,
) {
    let mut critical = plan.critical();
    while let Some(t) = active.pop() {
        let mut pick = Pick::new(plan);
        for len in 1..=3 {
            shifts(model, plan, scratch, &mut pick, t, len);
        }
        swaps(model, plan, scratch, &mut pick, t);
        reversals(model, plan, scratch, &mut pick, t);
        let Some(mv) = pick.best else {
            continue;
        };
        for node in plan.touched(&mv) {
            active.push_node(node);
        }
        active.push_node(task_node(t));
        plan.apply(model, &mv, scratch);
        if plan.critical() != critical {
            critical = plan.critical();
            for &node in &plan.routes[critical] {
                active.push_node(node);
            }
        }
    }
}

/// Moves the segment of `len` tasks that starts at task `t` next to a near task of its first
/// or last task, or to an end of a near robot's route, in place or reversed.
fn shifts(
    model: &Model,
    plan: &Plan,
    scratch: &mut Scratch,
    pick: &mut Pick,
    t: usize,
    len: usize,
) {
    let near = model.neighbours.as_ref().expect("a granular model");
    let c = |r: usize, a: usize, b: usize| model.c(r, a, b);
    let (r1, i) = plan.pos[t];
    let route = &plan.routes[r1];
    let l = route.len() - 2;
    if i + len - 1 > l {
        return;
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
    // Candidate (robot, gap) pairs; gaps of r1 count in its route once the segment is cut.
    // A gap named twice is looked at once (first place kept: the order stays deterministic).
    let mut gaps = std::mem::take(&mut scratch.gaps);
    gaps.clear();
    scratch.stamp = scratch.stamp.wrapping_add(1);
    if scratch.stamp == 0 || scratch.seen.len() < model.robots {
        scratch.seen = vec![Vec::new(); model.robots];
        scratch.stamp = 1;
    }
    let (seen, stamp) = (&mut scratch.seen, scratch.stamp);
    let mut push = |r2: usize, gap: usize| {
        let row = &mut seen[r2];
        if row.len() <= gap {
            row.resize(gap + 1, 0);
        }
        if row[gap] != stamp {
            row[gap] = stamp;
            gaps.push((r2, gap));
        }
    };
    let anchors = near.of(s0 - 1).chain(near.of(sl - 1));
    for u in anchors {
        let (r2, q) = plan.pos[u];
        if r2 == r1 {
            if (i..i + len).contains(&q) {
                continue;
            }
            let q = if q < i { q } else { q - len };
            push(r1, q - 1);
            push(r1, q);
        } else {
            push(r2, q - 1);
            push(r2, q);
        }
    }
    for &r2 in &near.homes[t] {
        let last = if r2 == r1 {
            l - len
        } else {
            plan.routes[r2].len() - 2
        };
        push(r2, 0);
        push(r2, last);
    }
    for &(r2, gap) in &gaps {
        if (r2 == r1 && gap + 1 == i) || !seg.iter().all(|&v| model.can(r2, v - 1)) {
            continue;
        }
        let (a, b) = if r2 == r1 {
            let node = |k: usize| if k < i { route[k] } else { route[k + len] };
            (node(gap), node(gap + 1))
        } else {
            (plan.routes[r2][gap], plan.routes[r2][gap + 1])
        };
        for rev in [false, true] {
            if rev && len == 1 {
                continue;
            }
            let (first, last, mid) = if rev {
                (sl, s0, inner(r2, true))
            } else {
                (s0, sl, inner(r2, false))
            };
            let add = (c(r2, a, first) + mid + dur + c(r2, last, b)) - c(r2, a, b);
            let mv = Move::Shift {
                r1,
                i,
                len,
                r2,
                gap,
                rev,
            };
            if r2 == r1 {
                pick.offer(model, plan, mv, &[(r1, base + add)], scratch);
            } else {
                let times = [(r1, base), (r2, plan.time[r2] + add)];
                pick.offer(model, plan, mv, &times, scratch);
            }
        }
    }
    scratch.gaps = gaps;
}

/// Exchanges task `t` with each of its near tasks that fits the other's robot.
fn swaps(model: &Model, plan: &Plan, scratch: &mut Scratch, pick: &mut Pick, t: usize) {
    let near = model.neighbours.as_ref().expect("a granular model");
    let c = |r: usize, a: usize, b: usize| model.c(r, a, b);
    let dn = &model.dn;
    for u in near.of(t) {
        let ((r1, i), (r2, j)) = (plan.pos[t], plan.pos[u]);
        let (x, y) = (task_node(t), task_node(u));
        let (ra, rb) = (&plan.routes[r1], &plan.routes[r2]);
        if r1 != r2 {
            if !model.can(r2, t) || !model.can(r1, u) {
                continue;
            }
            let (p1, n1, p2, n2) = (ra[i - 1], ra[i + 1], rb[j - 1], rb[j + 1]);
            let d1 = (c(r1, p1, y) + dn[y] + c(r1, y, n1)) - (c(r1, p1, x) + dn[x] + c(r1, x, n1));
            let d2 = (c(r2, p2, x) + dn[x] + c(r2, x, n2)) - (c(r2, p2, y) + dn[y] + c(r2, y, n2));
            let times = [(r1, plan.time[r1] + d1), (r2, plan.time[r2] + d2)];
            pick.offer(model, plan, Move::Swap { r1, i, r2, j }, &times, scratch);
        } else {
            let (lo, hi) = (i.min(j), i.max(j));
            let (v, w) = (ra[lo], ra[hi]);
            let delta = if hi == lo + 1 {
                let (p, n) = (ra[lo - 1], ra[hi + 1]);
                (c(r1, p, w) + c(r1, w, v) + c(r1, v, n))
                    - (c(r1, p, v) + c(r1, v, w) + c(r1, w, n))
            } else {
                let (p1, n1, p2, n2) = (ra[lo - 1], ra[lo + 1], ra[hi - 1], ra[hi + 1]);
                (c(r1, p1, w) + c(r1, w, n1) + c(r1, p2, v) + c(r1, v, n2))
                    - (c(r1, p1, v) + c(r1, v, n1) + c(r1, p2, w) + c(r1, w, n2))
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
}

/// Reverses the stretch between task `t` and a near task on its route so that the two become
/// joined by an arc (2-opt). The arc sums of the stretches grow outwards from `t`, once.
fn reversals(model: &Model, plan: &Plan, scratch: &mut Scratch, pick: &mut Pick, t: usize) {
    let near = model.neighbours.as_ref().expect("a granular model");
    let c = |r: usize, a: usize, b: usize| model.c(r, a, b);
    let (r, i) = plan.pos[t];
    let route = &plan.routes[r];
    // Positions of the near tasks on t's route: after t (reverse i + 1..=q, t → u) and
    // before it (reverse q + 1..=i, u → t).
    let mut after: Vec<usize> = Vec::new();
    let mut before: Vec<usize> = Vec::new();
    for u in near.of(t) {
        let (ru, q) = plan.pos[u];
        if ru == r && q > i + 1 {
            after.push(q);
        } else if ru == r && q + 1 < i {
            before.push(q);
        }
    }
    let mut offer = |lo: usize, hi: usize, fwd: f64, rev: f64| {
        let (p, n) = (route[lo - 1], route[hi + 1]);
        let delta = (c(r, p, route[hi]) + rev + c(r, route[lo], n))
            - (c(r, p, route[lo]) + fwd + c(r, route[hi], n));
        let times = [(r, plan.time[r] + delta)];
        pick.offer(
            model,
            plan,
            Move::Reverse { r, i: lo, j: hi },
            &times,
            scratch,
        );
    };
    if let Some(&far) = after.iter().max() {
        let (mut fwd, mut rev) = (0.0, 0.0);
        for hi in i + 2..=far {
            fwd += c(r, route[hi - 1], route[hi]);
            rev += c(r, route[hi], route[hi - 1]);
            if after.contains(&hi) {
                offer(i + 1, hi, fwd, rev);
            }
        }
    }
    if let Some(&far) = before.iter().min() {
        let (mut fwd, mut rev) = (0.0, 0.0);
        for lo in (far + 1..i).rev() {
            fwd += c(r, route[lo], route[lo + 1]);
            rev += c(r, route[lo + 1], route[lo]);
            if before.contains(&(lo - 1)) {
                offer(lo, i, fwd, rev);
            }
        }
    }
}
