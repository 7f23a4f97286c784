//! Time windows of robot-obstacle pairs: the stretches of the horizon in which a robot's
//! swept box may come within δ of an obstacle's box.
//!
//! A long trajectory (thousands of moves through a cell of hundreds of fixtures) passes
//! each fixture only now and then. The scene's windows ([`super::candidate_pairs`]) are
//! too coarse to see that, so each such pair was walked over the whole horizon: work and
//! memory grew as tasks × fixtures. Here a robot's samples are cut into chunks of
//! [`CHUNK`] samples, each with the box that holds the robot throughout it; a pair is
//! checked only in the chunks whose box meets the obstacle's, and is proven δ apart in the
//! others by the boxes (the same argument as the broad phase's).

use super::aabb::Aabb;
use super::fixed_box;
use crate::collision::{Body, Scene};
use crate::motion::{Motion, Sample};
use rayon::prelude::*;

/// Samples per chunk. A chunk's box holds a few moves' worth of motion: small enough to
/// pass a fixture briefly, large enough that the boxes cost little beside the check.
const CHUNK: usize = 8;
/// Chunks per group: a group's box is tried first, so that a pair far from the robot's
/// path costs one test per group.
const GROUP: usize = 32;
/// Robots with fewer samples are checked over the whole horizon: their chunks would save
/// less than they cost.
pub(in crate::collision) const MIN_SAMPLES: usize = 4 * CHUNK;
/// Below this many pairs with windows to find, they are found on the calling thread.
const PARALLEL_MIN_PAIRS: usize = 64;

/// Sorted, disjoint closed time ranges outside which a pair is proven δ apart.
pub(in crate::collision) type Windows = Vec<(f64, f64)>;

/// A robot's chunks: the time each covers and its box, grown by the robot's disc and δ/2.
struct Chunks {
    spans: Vec<(f64, f64, Aabb)>,
    /// The hull of each [`GROUP`] consecutive chunks.
    groups: Vec<Aabb>,
}

impl Chunks {
    fn new(s: &[Sample], horizon: (f64, f64), grow: f64) -> Chunks {
        let last = s.len() - 1;
        let mut spans = Vec::with_capacity(last.div_ceil(CHUNK));
        let mut first = 0;
        while first < last {
            let end = (first + CHUNK).min(last);
            // Positions are linear between samples, and held before the first and after
            // the last: the hull of the chunk's samples holds the robot's centre throughout.
            let mut hull = Aabb::EMPTY;
            s[first..=end].iter().for_each(|p| hull.add(&p.pos));
            let t0 = if first == 0 { horizon.0 } else { s[first].t };
            let t1 = if end == last { horizon.1 } else { s[end].t };
            spans.push((t0, t1, hull.grown(grow, hull.magnitude())));
            first = end;
        }
        let groups = spans
            .chunks(GROUP)
            .map(|g| g.iter().fold(Aabb::EMPTY, |h, c| h.hull(&c.2)))
            .collect();
        Chunks { spans, groups }
    }

    /// The windows in which the robot's box meets `fixed`, adjacent chunks merged.
    fn meeting(&self, fixed: &Aabb) -> Windows {
        let mut windows: Windows = Vec::new();
        for (g, group) in self.groups.iter().enumerate() {
            if !group.may_meet(fixed) {
                continue;
            }
            let from = g * GROUP;
            let chunks = &self.spans[from..(from + GROUP).min(self.spans.len())];
            for &(t0, t1, _) in chunks.iter().filter(|c| c.2.may_meet(fixed)) {
                match windows.last_mut() {
                    Some(w) if w.1 >= t0 => w.1 = t1,
                    _ => windows.push((t0, t1)),
                }
            }
        }
        windows
    }
}

/// For each pair, in order: the windows outside which it is proven `delta` apart, or `None`
/// when it is checked over the whole horizon (robot-robot pairs, arms, robots with few
/// samples). An empty list: the pair never comes within `delta`.
pub(in crate::collision) fn pair_windows(
    scene: &Scene,
    pairs: &[(usize, usize)],
    delta: f64,
) -> Vec<Option<Windows>> {
    let half = delta.max(0.0) / 2.0;
    let bodies = &scene.bodies;
    let long =
        |b: &Body| matches!(&b.motion, Motion::Sampled(tr) if tr.samples().len() >= MIN_SAMPLES);
    let fixed = |b: &Body| matches!(b.motion, Motion::Fixed(_));
    let wanted = |&(i, j): &(usize, usize)| long(&bodies[i]) && fixed(&bodies[j]);
    if delta.is_nan() || !pairs.iter().any(wanted) {
        return vec![None; pairs.len()];
    }
    // Each robot's chunks once.
    let mut chunks: Vec<Option<Chunks>> = (0..bodies.len()).map(|_| None).collect();
    for &(i, _) in pairs.iter().filter(|p| wanted(p)) {
        if chunks[i].is_none() {
            let Motion::Sampled(tr) = &bodies[i].motion else {
                unreachable!("a robot with samples")
            };
            let grow = bodies[i].shape.radius() + half;
            chunks[i] = Some(Chunks::new(tr.samples(), scene.horizon(), grow));
        }
    }
    let of = |&(i, j): &(usize, usize)| {
        let robot = chunks[i].as_ref().filter(|_| wanted(&(i, j)))?;
        Some(robot.meeting(&fixed_box(&bodies[j], half)))
    };
    match pairs.len() >= PARALLEL_MIN_PAIRS {
        true => pairs.par_iter().map(of).collect(),
        false => pairs.iter().map(of).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{ConvexPolygon, Vec2};
    use crate::motion::{Pose, Trajectory};

    /// A unit square going right along y = 0 from x = 0 to x = 100 in 100 s, one sample a
    /// second, past a post at x = 50 (and one far off its path).
    fn scene(post_y: f64) -> Scene {
        let square = ConvexPolygon::rectangle(1.0, 1.0).unwrap();
        let poses = (0..=100).map(|k| (k as f64, Pose::new(k as f64, 0.0, 0.0)));
        let robot = Body::robot("R", square.clone(), Trajectory::from_poses(poses).unwrap());
        // `translated` subtracts its offset.
        let post = Body::obstacle("post", &square.translated(&Vec2::new(-50.0, -post_y)));
        Scene::with_bodies(0.01, [robot, post]).unwrap()
    }

    #[test]
    fn a_pair_is_checked_only_where_the_robot_passes_the_obstacle() {
        let s = scene(0.0);
        let w = pair_windows(&s, &[(0, 1)], s.delta)[0].clone().unwrap();
        // One window, about the time the robot passes x = 50 (chunks of 8 s), not the
        // whole horizon.
        assert_eq!(w.len(), 1);
        let (t0, t1) = w[0];
        assert!(
            t0 <= 48.0 && t1 >= 52.0 && t1 - t0 <= 3.0 * CHUNK as f64,
            "{w:?}"
        );
        // Far from the path: never within δ.
        let far = scene(10.0);
        assert_eq!(pair_windows(&far, &[(0, 1)], far.delta)[0], Some(vec![]));
        // The windows grow with δ.
        let wide = pair_windows(&s, &[(0, 1)], 20.0)[0].clone().unwrap();
        assert!(wide[0].0 < t0 && wide[0].1 > t1);
    }
}
