//! Reconfiguring: an arm in a collision takes another of its configurations at the task it
//! moves to, works at, or moves from (elbow up for elbow down, another tool angle), with its
//! moves into and out of that task planned for the new configuration. Only that arm's
//! schedule changes; below the new node, the sequencer re-plans on the bounds of the new
//! configurations. This is how the search switches configurations: the choice made with
//! the routes (`choose.rs`) weighs travel times only, and a collision may be what tells two
//! configurations apart.

use super::remedies::{Child, View};
use super::{Remedy, RemedyKind};
use crate::cell::Cell;
use crate::wcp::legs::{leg, with_leg, Leg, Legs};
use crate::wcp::prepare::Prepared;
use crate::wcp::schedule::{route_nodes, Collision, RobotSchedule};
use std::sync::Arc;

/// At most this many other configurations tried per task, nearest the current one first
/// (largest joint change): sampled free angles may give many.
const MAX_ALTERNATIVES: usize = 3;

/// A reconfiguration not made yet: arm `x` takes configuration `k` at the task at position
/// `p` of its route's nodes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Reconfig {
    pub x: usize,
    pub p: usize,
    pub k: usize,
}

/// The reconfigurations that collision `c` suggests: for each arm of the pair, the other
/// configurations at the task its leg under way leads to (or works at), then at the one it
/// leaves. Each task is reconfigured once on a branch: only where `prepared` still takes
/// the configuration `root` took (no branch flips an elbow back and forth).
pub(super) fn reconfigurations(
    cell: &Cell,
    (root, prepared): (&Prepared, &Prepared),
    routes: &[Vec<usize>],
    c: &Collision,
) -> Vec<Reconfig> {
    let (Some(b), Some(sb)) = (c.robots.1, c.segments.1) else {
        return Vec::new();
    };
    let assignment = prepared.moves.assignment();
    let mut out = Vec::new();
    for (x, sx) in [(c.robots.0, c.segments.0), (b, sb)] {
        let (Some(m), Some(_)) = (sx.leg, cell.robots[x].as_arm()) else {
            continue;
        };
        let nodes = route_nodes(&routes[x]);
        for p in [m + 1, m] {
            let Some(&n) = nodes.get(p).filter(|&&n| n != 0) else {
                continue;
            };
            let t = n - 1;
            let now = assignment.index(x, t);
            if now != root.moves.assignment().index(x, t) {
                continue;
            }
            let found = assignment.configurations().at(x, t);
            let change = |k: &usize| {
                (found[*k].iter().zip(found[now].iter()))
                    .fold(0.0, |d: f64, (a, b)| d.max((a - b).abs()))
            };
            let mut others: Vec<usize> = (0..found.len()).filter(|&k| k != now).collect();
            others.sort_by(|a, b| change(a).total_cmp(&change(b)));
            let others = others.into_iter().take(MAX_ALTERNATIVES);
            out.extend(others.map(|k| Reconfig { x, p, k }));
        }
    }
    out
}

/// The remedy `r` stands for, in the terms of `routes`.
pub(super) fn remedy(routes: &[Vec<usize>], prepared: &Prepared, r: Reconfig) -> Remedy {
    let nodes = route_nodes(&routes[r.x]);
    let t = nodes[r.p] - 1;
    let joints = prepared.moves.assignment().configurations().at(r.x, t)[r.k].to_vec();
    let kind = RemedyKind::Reconfigure { task: t, joints };
    Remedy::on(r.x, r.p - 1, (nodes[r.p - 1], nodes[r.p]), kind)
}

/// Makes reconfiguration `r` of the schedule `view`: the arm's legs into and out of the task
/// as planned for the new configuration (their waits kept), its schedule rebuilt, and the
/// preparation of the new configurations; `None` when a move cannot be planned.
pub(super) fn reconfigured(
    cell: &Cell,
    prepared: &Prepared,
    view: &View,
    r: Reconfig,
) -> Option<(Child, Arc<Prepared>)> {
    let Reconfig { x, p, k } = r;
    let nodes = route_nodes(&view.routes[x]);
    let t = nodes[p] - 1;
    let next = Arc::new(prepared.reassigned(cell, prepared.moves.assignment().with(x, t, k)));
    let mut legs: Legs = view.legs.clone();
    for l in [p - 1, p] {
        if l + 1 < nodes.len() {
            let old = leg(&legs, x, l).clone();
            legs = with_leg(
                &legs,
                x,
                l,
                Leg {
                    pieces: None,
                    ..old
                },
            );
        }
    }
    let schedule = RobotSchedule::build(cell, x, &view.routes[x], &legs[x], &next.moves).ok()?;
    let child = Child {
        legs,
        changed: vec![(x, Arc::new(schedule))],
        remedy: remedy(view.routes, prepared, r),
        last_resort: false,
    };
    Some((child, next))
}
