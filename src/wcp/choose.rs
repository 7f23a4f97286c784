//! Which configuration each arm takes at each task (issue 22, item 3).
//!
//! With arms, the Work-Cell Problem is a min-max multiple generalised TSP (Spensieri et al.,
//! T-ASE 2016): each task is a cluster of (task, configuration) nodes, one of which is
//! visited. It is solved here by alternation. The sequencer orders and assigns the tasks for
//! the configurations chosen (each arm's task one node, as for a rigid robot); then, for each
//! arm's route, the best configuration of every task on it is a shortest path through the
//! layers of its configurations (the GTSP's "cluster optimisation", Fischetti, Salazar &
//! Toth 1997), on the certified move times; and the sequencer runs again from those routes
//! with the new configurations. Each step only shortens routes it is given, so the makespan
//! never grows from one round to the next; the rounds stop when the configurations stay,
//! when the makespan stops falling, after [`MAX_ROUNDS`], or when the time limit is out.
//!
//! The shortest path is lazy, as the sequencer is: it runs on the straight joint-space
//! times (lower bounds, and the certified times whenever the straight move is clear), has
//! the moves of its path certified, and runs again until its path's moves are all exact.

use super::configurations::Assignment;
use super::prepare::{Prepared, Progress};
use super::sequence::{repairing, sequence_with};
use super::sequencer::task_node;
use super::{ConfigurationChoice, SolveOptions};
use crate::cell::{Cell, InputError};
use crate::planning::joint_move_time;
use std::collections::HashMap;
use std::time::Instant;

/// Most rounds of re-choosing configurations and sequencing again.
pub const MAX_ROUNDS: usize = 8;

/// The arms' configurations chosen with the routes, as a [`Prepared`] whose store and
/// bounds take them; `None` when nothing changes (no arm, a single configuration each, or
/// [`SolveOptions::configurations`] other than [`ConfigurationChoice::Chosen`]).
///
/// ```
/// use workcell::wcp::{choose_configurations, prepare, sequence, SolveOptions};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/scara-cell.json").as_ref())?.cell;
/// let opts = SolveOptions::default();
/// let prepared = prepare(&cell, &opts, &())?;
/// let before = sequence(&cell, &prepared, &[], &opts)?.makespan;
/// let chosen = choose_configurations(&cell, &prepared, &opts, &())?.unwrap_or(prepared);
/// assert!(sequence(&cell, &chosen, &[], &opts)?.makespan <= before);
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn choose_configurations(
    cell: &Cell,
    prepared: &Prepared,
    opts: &SolveOptions,
    progress: &dyn Progress,
) -> Result<Option<Prepared>, InputError> {
    let arms: Vec<usize> = (0..cell.robots.len())
        .filter(|&r| cell.robots[r].as_arm().is_some())
        .collect();
    let several = |r: &usize| {
        (0..cell.tasks.len())
            .any(|t| prepared.moves.assignment().configurations().at(*r, t).len() > 1)
    };
    if opts.configurations != ConfigurationChoice::Chosen || !arms.iter().any(several) {
        return Ok(None);
    }
    // From the configurations nearest home, and from the first ones: alternation is a
    // local search, and the two starts end in different optima.
    // The two run side by side: each is mostly one sequencer run after another.
    let first = Assignment::first(cell, prepared.moves.assignment().configurations_arc());
    let from_first = prepared.reassigned(cell, first);
    let (near, other) = rayon::join(
        || alternate(cell, prepared, &arms, opts, progress),
        || alternate(cell, &from_first, &arms, opts, progress),
    );
    let ((near, near_makespan), (other, other_makespan)) = (near?, other?);
    if other_makespan < near_makespan {
        return Ok(Some(other.unwrap_or(from_first)));
    }
    Ok(near)
}

/// Alternates sequencing and choosing configurations from `prepared`'s: the last
/// preparation that shortened the makespan (`None`: none did) and that makespan.
fn alternate(
    cell: &Cell,
    prepared: &Prepared,
    arms: &[usize],
    opts: &SolveOptions,
    progress: &dyn Progress,
) -> Result<(Option<Prepared>, f64), InputError> {
    // Choosing is a repair loop: the blind plan's full effort comes after it.
    let opts = &repairing(opts);
    let mut sol = sequence_with(cell, prepared, &[], opts, None, progress)?;
    let mut current: Option<Prepared> = None;
    for _ in 0..MAX_ROUNDS {
        let here = current.as_ref().unwrap_or(prepared);
        let mut next = here.moves.assignment().clone();
        for &r in arms {
            next = best_along(here, cell, r, &sol.sequences[r], next);
        }
        if &next == here.moves.assignment() {
            break;
        }
        let chosen = here.reassigned(cell, next);
        let again = sequence_with(cell, &chosen, &[], opts, Some(&sol.sequences), progress)?;
        if again.makespan >= sol.makespan {
            break;
        }
        sol = again;
        current = Some(chosen);
        if prepared.deadline.is_some_and(|d| Instant::now() >= d) {
            break;
        }
    }
    Ok((current, sol.makespan))
}

/// `assignment` with arm `r`'s configurations at the tasks of `route` those of its shortest
/// way through them (home, the tasks in order, home), on certified move times.
fn best_along(
    prepared: &Prepared,
    cell: &Cell,
    r: usize,
    route: &[usize],
    assignment: Assignment,
) -> Assignment {
    if route.is_empty() {
        return assignment;
    }
    let arm = cell.robots[r].as_arm().expect("an arm");
    let found = assignment.configurations();
    // The layers: home (one configuration), each task's, home.
    let nodes: Vec<usize> = std::iter::once(0)
        .chain(route.iter().map(|&t| task_node(t)))
        .chain([0])
        .collect();
    let layer = |n: usize| match n {
        0 => 1,
        n => found.at(r, n - 1).len(),
    };
    let joints = |n: usize, k: usize| -> &[f64] {
        match n {
            0 => &arm.home,
            n => &found.at(r, n - 1)[k],
        }
    };
    let mut exact: HashMap<(usize, usize, usize), f64> = HashMap::new();
    loop {
        let cost = |i: usize, a: usize, b: usize| {
            exact.get(&(i, a, b)).copied().unwrap_or_else(|| {
                joint_move_time(joints(nodes[i], a), joints(nodes[i + 1], b), &arm.limits)
            })
        };
        let path = shortest_path(&nodes, layer, cost);
        let mut settled = true;
        for i in 0..nodes.len() - 1 {
            let (a, b) = (path[i], path[i + 1]);
            if exact.contains_key(&(i, a, b)) {
                continue;
            }
            let bound = joint_move_time(joints(nodes[i], a), joints(nodes[i + 1], b), &arm.limits);
            let time = (prepared.moves)
                .arm_duration(r, (nodes[i], a), (nodes[i + 1], b))
                .unwrap_or(f64::INFINITY);
            settled &= time == bound;
            exact.insert((i, a, b), time);
        }
        if settled {
            let mut out = assignment.clone();
            for (i, &t) in route.iter().enumerate() {
                out = out.with(r, t, path[i + 1]);
            }
            return out;
        }
    }
}

/// The configuration index per layer of the cheapest way through the layers (Viterbi):
/// `cost(i, a, b)` from configuration `a` of layer `i` to `b` of layer `i + 1`. Ties go to
/// the lower index, so the result is deterministic.
fn shortest_path(
    nodes: &[usize],
    layer: impl Fn(usize) -> usize,
    cost: impl Fn(usize, usize, usize) -> f64,
) -> Vec<usize> {
    let mut best: Vec<f64> = vec![0.0; layer(nodes[0])];
    let mut from: Vec<Vec<usize>> = Vec::with_capacity(nodes.len());
    for i in 0..nodes.len() - 1 {
        let (prev, next) = (&best, layer(nodes[i + 1]));
        let (mut values, mut back) = (vec![f64::INFINITY; next], vec![0; next]);
        for b in 0..next {
            for (a, &v) in prev.iter().enumerate() {
                let c = v + cost(i, a, b);
                if c < values[b] {
                    (values[b], back[b]) = (c, a);
                }
            }
        }
        from.push(back);
        best = values;
    }
    let mut k = (0..best.len())
        .min_by(|&a, &b| best[a].total_cmp(&best[b]))
        .unwrap_or(0);
    let mut path = vec![k];
    for back in from.iter().rev() {
        k = back[k];
        path.push(k);
    }
    path.reverse();
    path
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cheapest_way_through_the_layers() {
        // Two layers of two between single ends: going through 1 then 0 costs 1 + 1 + 1,
        // any other way more.
        let nodes = [0, 1, 2, 0];
        let layer = |n: usize| if n == 0 { 1 } else { 2 };
        let cost = |i: usize, a: usize, b: usize| match (i, a, b) {
            (0, 0, 1) | (1, 1, 0) | (2, 0, 0) => 1.0,
            _ => 5.0,
        };
        assert_eq!(shortest_path(&nodes, layer, cost), [0, 1, 0, 0]);
        // Equal costs: the lower index.
        assert_eq!(shortest_path(&nodes, layer, |_, _, _| 1.0), [0, 0, 0, 0]);
    }
}
