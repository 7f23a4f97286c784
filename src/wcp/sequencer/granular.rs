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
use std::time::Instant;

use super::model::Model;
use super::offers::{offer_reverse, offer_swap, Cut, Pick};
use super::plan::{Plan, Scratch};

/// Tasks looked at between two looks at the clock.
const LOOKS_PER_CLOCK: usize = 64;

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
    deadline: Option<Instant>,
) {
    let mut critical = plan.critical();
    let mut looked = 0usize;
    while let Some(t) = active.pop() {
        // Every plan on the way is whole: past the deadline, the descent stops where it is.
        looked += 1;
        if looked.is_multiple_of(LOOKS_PER_CLOCK) && deadline.is_some_and(|d| Instant::now() >= d) {
            return;
        }
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
    let Some(cut) = Cut::new(model, plan, t, len) else {
        return;
    };
    let (r1, i, seg) = (cut.r1, cut.i, cut.seg);
    let route = &plan.routes[r1];
    let gaps = near_gaps(model, plan, scratch, &cut, t);
    for &(r2, gap) in &gaps {
        if (r2 == r1 && gap + 1 == i) || !seg.iter().all(|&v| model.can(r2, v - 1)) {
            continue;
        }
        let ends = if r2 == r1 {
            let node = |k: usize| if k < i { route[k] } else { route[k + len] };
            (node(gap), node(gap + 1))
        } else {
            (plan.routes[r2][gap], plan.routes[r2][gap + 1])
        };
        for rev in [false, true] {
            if rev && len == 1 {
                continue;
            }
            let mid = cut.inner(model, r2, rev);
            cut.offer(model, plan, scratch, pick, (r2, gap), ends, rev, mid);
        }
    }
    scratch.gaps = gaps;
}

/// The (robot, gap) pairs a shift of `cut` may go to: the gaps next to a near task of its
/// first or last task, and the ends of the routes of the robots with the nearest homes. Gaps
/// of `r1` count in its route once the segment is cut; a gap named twice is listed once, at
/// its first place (the order stays deterministic). Hands back `scratch.gaps`' buffer.
fn near_gaps(
    model: &Model,
    plan: &Plan,
    scratch: &mut Scratch,
    cut: &Cut,
    t: usize,
) -> Vec<(usize, usize)> {
    let near = model.neighbours.as_ref().expect("a granular model");
    let (r1, i, len) = (cut.r1, cut.i, cut.len);
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
    let anchors = near.of(cut.seg[0] - 1).chain(near.of(cut.seg[len - 1] - 1));
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
    let l = plan.routes[r1].len() - 2;
    for &r2 in &near.homes[t] {
        let last = if r2 == r1 {
            l - len
        } else {
            plan.routes[r2].len() - 2
        };
        push(r2, 0);
        push(r2, last);
    }
    gaps
}

/// Exchanges task `t` with each of its near tasks that fits the other's robot.
fn swaps(model: &Model, plan: &Plan, scratch: &mut Scratch, pick: &mut Pick, t: usize) {
    let near = model.neighbours.as_ref().expect("a granular model");
    for u in near.of(t) {
        offer_swap(model, plan, scratch, pick, (t, u));
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
    if let Some(&far) = after.iter().max() {
        let (mut fwd, mut rev) = (0.0, 0.0);
        for hi in i + 2..=far {
            fwd += c(r, route[hi - 1], route[hi]);
            rev += c(r, route[hi], route[hi - 1]);
            if after.contains(&hi) {
                offer_reverse(model, plan, scratch, pick, r, (i + 1, hi), fwd, rev);
            }
        }
    }
    if let Some(&far) = before.iter().min() {
        let (mut fwd, mut rev) = (0.0, 0.0);
        for lo in (far + 1..i).rev() {
            fwd += c(r, route[lo], route[lo + 1]);
            rev += c(r, route[lo + 1], route[lo]);
            if before.contains(&(lo - 1)) {
                offer_reverse(model, plan, scratch, pick, r, (lo, i), fwd, rev);
            }
        }
    }
}
