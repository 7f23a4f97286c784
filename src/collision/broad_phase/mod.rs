//! Space-time broad phase: the pairs that may come within δ, found without looking at all N².
//!
//! The horizon is cut into equal time windows. In each, every body gets an axis-aligned box
//! that holds it throughout the window, grown by δ/2: bodies whose boxes do not meet are
//! more than δ apart in the window (along the axis that separates the boxes). Meeting boxes
//! are found per window with a uniform grid, so a window costs O(N log N) for a scene of
//! bounded density (the sort of the grid entries), not the N² of [`Scene::pairs`]. From
//! [`PARALLEL_MIN_ROBOTS`] robots on, the robots' boxes and then the windows are spread over
//! rayon's thread pool.

mod aabb;
mod arms;
mod grid;
mod windows;

use super::{Body, Scene};
use crate::geometry::{Posed, Vec2};
use crate::motion::{ArmMotion, Motion, Sample};
use aabb::Aabb;
use arms::{arms_of, ArmBoxes};
use grid::meeting;
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::Arc;
pub(super) use windows::{pair_windows, Windows};

/// At most this many windows: beyond it the boxes hardly shrink, while each window costs a
/// sort of the grid entries.
const MAX_WINDOWS: usize = 64;
/// From this many robots on, the boxes are computed and the windows searched in parallel.
pub(super) const PARALLEL_MIN_ROBOTS: usize = 64;
/// Robots per parallel task when their boxes are computed: fewer cost more in scheduling
/// than they save.
const ROBOTS_PER_TASK: usize = 32;

/// The pairs that may come within `delta` of each other, in the report order of
/// [`Scene::pairs`].
///
/// Conservative: every pair left out stays at least `delta` apart at all times of the
/// horizon. Nothing is left out on non-finite input (a NaN δ, a pose or a box that is not
/// finite).
///
/// ```
/// use workcell::collision::candidate_pairs;
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/paper-fig12a.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// let all = scene.pairs();
/// let near = candidate_pairs(&scene, scene.delta);
/// assert!(near.len() <= all.len() && near.iter().all(|p| all.contains(p)));
/// // With a δ as large as the hall, no pair can be left out.
/// assert_eq!(candidate_pairs(&scene, 1e9), all);
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn candidate_pairs(scene: &Scene, delta: f64) -> Vec<(usize, usize)> {
    // Handing a few robots to the thread pool costs more than it saves.
    candidates(scene, delta, scene.robot_count() >= PARALLEL_MIN_ROBOTS)
}

/// [`candidate_pairs`], on the thread pool or not: the same pairs either way.
fn candidates(scene: &Scene, delta: f64, parallel: bool) -> Vec<(usize, usize)> {
    if delta.is_nan() {
        return scene.pairs();
    }
    let half = delta.max(0.0) / 2.0;
    let bodies = &scene.bodies;
    let (tracks, fixed) = tracks_and_fixed(bodies, half);
    let arms = arms_of(bodies);
    if tracks.is_empty() && arms.is_empty() {
        return Vec::new();
    }
    let windows = window_count(scene, &tracks, &arms);
    let ends = window_ends(scene.horizon(), windows);
    // Every robot's box in every window (row by robot), robots in parallel: reading the
    // samples is most of the broad phase's work, and each robot's are read once.
    let mut swept = vec![Aabb::EMPTY; tracks.len() * windows];
    let fill = |(row, &(i, s)): (&mut [Aabb], &(usize, &[Sample]))| {
        window_boxes(s, &ends, bodies[i].shape.radius() + half, row)
    };
    let boxes_of_arm = |(arm, links): &(Arc<ArmMotion>, Vec<usize>)| {
        ArmBoxes::new(arm.clone(), links, bodies, &ends, half)
    };
    let arms: Vec<ArmBoxes> = if parallel {
        let rows = swept.par_chunks_mut(windows).zip(&tracks);
        rows.with_min_len(ROBOTS_PER_TASK).for_each(fill);
        let arms = arms.par_iter().with_min_len(ROBOTS_PER_TASK);
        arms.map(boxes_of_arm).collect()
    } else {
        swept.chunks_mut(windows).zip(&tracks).for_each(fill);
        arms.iter().map(boxes_of_arm).collect()
    };
    // Then the windows, in parallel, each with its own grid. The grid sees an arm as one
    // box, its reach, with the id `bodies.len()` + its index.
    let in_window = |w: usize| {
        let rows = swept.chunks_exact(windows);
        let reach = arms.iter().enumerate();
        let boxes: Vec<(usize, Aabb)> = tracks
            .iter()
            .zip(rows)
            .map(|(&(i, _), row)| (i, row[w]))
            .chain(reach.map(|(k, arm)| (bodies.len() + k, arm.reach[w])))
            .chain(fixed.iter().copied())
            .collect();
        let mut found = Vec::new();
        meeting(&boxes, &mut found);
        if arms.is_empty() {
            return found;
        }
        let mut by_id = vec![Aabb::EMPTY; bodies.len() + arms.len()];
        boxes.iter().for_each(|&(i, b)| by_id[i] = b);
        links_meeting(&found, &arms, w, &by_id, bodies)
    };
    let found: Vec<(usize, usize)> = if parallel {
        (0..windows)
            .into_par_iter()
            .flat_map_iter(in_window)
            .collect()
    } else {
        (0..windows).flat_map(in_window).collect()
    };
    report_order(bodies, found)
}

/// The robots' samples, and the obstacles' boxes grown by `half` (arms are gathered apart).
type TracksAndFixed<'s> = (Vec<(usize, &'s [Sample])>, Vec<(usize, Aabb)>);

fn tracks_and_fixed(bodies: &[Body], half: f64) -> TracksAndFixed<'_> {
    let (mut tracks, mut fixed) = (Vec::new(), Vec::new());
    for (i, b) in bodies.iter().enumerate() {
        match &b.motion {
            Motion::Sampled(tr) => tracks.push((i, tr.samples())),
            Motion::Link(_) => {}
            Motion::Fixed(_) => fixed.push((i, fixed_box(b, half))),
        }
    }
    (tracks, fixed)
}

/// The box of an obstacle (it never moves), from its vertices in world position, grown by
/// `half`; an empty box for a body that moves.
fn fixed_box(b: &Body, half: f64) -> Aabb {
    let Motion::Fixed(p) = &b.motion else {
        return Aabb::EMPTY;
    };
    let posed = Posed::new(&b.shape, p.pos.x, p.pos.y, p.theta);
    let mut hull = Aabb::EMPTY;
    (0..posed.len()).for_each(|k| hull.add(&posed.vertex(k)));
    hull.grown(half, p.pos.amax() + b.shape.radius())
}

/// Window ends, non-decreasing from t0 to t1 exactly; interpolated, not t0 + f·(t1 − t0),
/// which could overflow.
fn window_ends((t0, t1): (f64, f64), windows: usize) -> Vec<f64> {
    let mut ends = vec![t0];
    for w in 1..windows {
        let f = w as f64 / windows as f64;
        ends.push((t0 * (1.0 - f) + t1 * f).clamp(ends[w - 1], t1));
    }
    ends.push(t1);
    ends
}

/// The pairs `found` in report order, each once: robot-robot pairs by (i, j), then
/// robot-obstacle pairs by (robot, obstacle).
fn report_order(bodies: &[Body], found: Vec<(usize, usize)>) -> Vec<(usize, usize)> {
    let robot = |i: usize| bodies[i].is_robot();
    let mut pairs: Vec<_> = found
        .into_iter()
        .filter(|&(i, j)| !bodies[i].same_arm(&bodies[j]))
        .filter_map(|(i, j)| match (robot(i), robot(j)) {
            (true, true) => Some((false, i.min(j), i.max(j))),
            (true, false) => Some((true, i, j)),
            (false, true) => Some((true, j, i)),
            (false, false) => None,
        })
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    pairs.into_iter().map(|(_, i, j)| (i, j)).collect()
}

/// The pairs of bodies among `found`, pairs of ids whose boxes meet in window `w`: an arm's
/// id (from the number of bodies on) stands for those of its links whose own swept box
/// meets the other's, computed here for the arms that meet something. `by_id` holds every
/// id's box in the window.
fn links_meeting(
    found: &[(usize, usize)],
    arms: &[ArmBoxes],
    w: usize,
    by_id: &[Aabb],
    bodies: &[Body],
) -> Vec<(usize, usize)> {
    let n = bodies.len();
    let mut link_boxes: HashMap<usize, Vec<(usize, Aabb)>> = HashMap::new();
    let mut out = Vec::with_capacity(found.len());
    for &(i, j) in found {
        if i < n && j < n {
            out.push((i, j));
            continue;
        }
        // An id's bodies with their boxes: a body alone, or an arm's links.
        let mut parts = |id: usize| -> Vec<(usize, Aabb)> {
            match id.checked_sub(n) {
                None => vec![(id, by_id[id])],
                Some(k) => (link_boxes.entry(k))
                    .or_insert_with(|| {
                        let boxes = arms[k].link_boxes(w, bodies);
                        arms[k].links.iter().map(|l| l.0).zip(boxes).collect()
                    })
                    .clone(),
            }
        };
        let (near, far) = (parts(i), parts(j));
        for (a, box_a) in &near {
            let meet = far.iter().filter(|(_, box_b)| box_a.may_meet(box_b));
            out.extend(meet.map(|&(b, _)| (*a, b)));
        }
    }
    out
}

/// Fills `row` with the boxes, grown by `grow`, that hold the disc of radius `grow` about G
/// of the robot with samples `s` throughout each window between consecutive `ends`.
fn window_boxes(s: &[Sample], ends: &[f64], grow: f64, row: &mut [Aabb]) {
    // Windows go forward in time: the samples are scanned once in all.
    let mut k = 0;
    for (span, out) in ends.windows(2).zip(row) {
        let (a, b) = (span[0], span[1]);
        // G moves linearly between samples: the hull of its positions at the window's ends
        // and at the samples strictly inside holds it throughout.
        let mut hull = Aabb::EMPTY;
        let (start, scale_a) = position_at(s, &mut k, a);
        hull.add(&start);
        while k < s.len() && s[k].t < b {
            hull.add(&s[k].pos);
            k += 1;
        }
        let (end, scale_b) = position_at(s, &mut k, b);
        hull.add(&end);
        let scale = hull.magnitude().max(scale_a).max(scale_b);
        *out = hull.grown(grow, scale);
    }
}

/// The position of G at `t`, as [`Motion::pose_at`] computes it, and the magnitude of the
/// samples it comes from. `k` holds an index at or before the first sample after `t`, and is
/// left at that sample.
fn position_at(s: &[Sample], k: &mut usize, t: f64) -> (Vec2, f64) {
    while *k < s.len() && s[*k].t <= t {
        *k += 1;
    }
    match *k {
        0 => (s[0].pos, s[0].pos.amax()),
        k if k == s.len() => (s[k - 1].pos, s[k - 1].pos.amax()),
        k => {
            let (p, q) = (&s[k - 1], &s[k]);
            let u = (t - p.t) / (q.t - p.t);
            (p.pos + (q.pos - p.pos) * u, p.pos.amax().max(q.pos.amax()))
        }
    }
}

/// The number of windows: enough that the median robot (or link) moves across about its
/// bounding disc in each, so that its window's box is at most about twice its own. More
/// windows hardly shrink the boxes but each costs a sort; robots that stay near one spot (as
/// in a hall) need one or two. Only a trade-off of cost, so each one's extent is taken from
/// about 16 of its samples.
fn window_count(
    scene: &Scene,
    tracks: &[(usize, &[Sample])],
    arms: &[(Arc<ArmMotion>, Vec<usize>)],
) -> usize {
    let links = arms.iter().flat_map(|(_, links)| links).map(|&i| {
        let Motion::Link(l) = &scene.bodies[i].motion else {
            unreachable!("the bodies of an arm's links")
        };
        (i, l.frames())
    });
    let mut ratios: Vec<f64> = (tracks.iter().copied())
        .chain(links)
        .map(|(i, s)| {
            let mut hull = Aabb::EMPTY;
            let every = s.len().div_ceil(16);
            s.iter()
                .step_by(every)
                .chain(s.last())
                .for_each(|s| hull.add(&s.pos));
            hull.size() / (2.0 * scene.bodies[i].shape.radius())
        })
        .collect();
    if ratios.is_empty() {
        return 1;
    }
    let mid = ratios.len() / 2;
    let ratio = *ratios.select_nth_unstable_by(mid, f64::total_cmp).1;
    // NaN casts to 0: one window.
    (ratio.ceil() as usize).clamp(1, MAX_WINDOWS)
}

#[cfg(test)]
mod tests;
