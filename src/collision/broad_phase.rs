//! Space-time broad phase: the pairs that may come within δ, found without looking at all N².
//!
//! The horizon is cut into equal time windows. In each, every body gets an axis-aligned box
//! that holds it throughout the window, grown by δ/2: bodies whose boxes do not meet are
//! more than δ apart in the window (along the axis that separates the boxes). Meeting boxes
//! are found per window with a uniform grid, so a window costs O(N log N) for a scene of
//! bounded density (the sort of the grid entries), not the N² of [`Scene::pairs`]. From
//! [`PARALLEL_MIN_ROBOTS`] robots on, the robots' boxes and then the windows are spread over
//! rayon's thread pool.

use super::Scene;
use crate::geometry::{Posed, Vec2};
use crate::motion::{Motion, Sample};
use rayon::prelude::*;

/// Relative slack added to every box: covers the rounding of interpolated poses and of the
/// narrow phase's own arithmetic (a few units in the last place of the coordinates), with
/// orders of magnitude to spare, while staying far below any δ the scene loader accepts.
const SLACK: f64 = 1e-12;
/// At most this many windows: beyond it the boxes hardly shrink, while each window costs a
/// sort of the grid entries.
const MAX_WINDOWS: usize = 64;
/// From this many robots on, the boxes are computed and the windows searched in parallel.
pub(super) const PARALLEL_MIN_ROBOTS: usize = 64;
/// Robots per parallel task when their boxes are computed: fewer cost more in scheduling
/// than they save.
const ROBOTS_PER_TASK: usize = 32;
/// Fewer boxes than this are tested against each other directly: cheaper than a grid.
const GRID_MIN_BOXES: usize = 32;
/// A box covering more grid cells than this is tested against every box of its window
/// directly, so that one long box cannot flood the grid.
const MAX_CELLS: i128 = 64;

/// An axis-aligned box: NaN once a NaN point was added, infinite once an infinite one was.
#[derive(Clone, Copy, Debug)]
struct Aabb {
    lo: [f64; 2],
    hi: [f64; 2],
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        lo: [f64::INFINITY; 2],
        hi: [f64::NEG_INFINITY; 2],
    };

    fn add(&mut self, p: &Vec2) {
        // An infinite point makes the box infinite by itself; NaN would be skipped by the
        // comparisons below, so it sets the box to NaN, where comparisons keep it.
        if p.x.is_nan() || p.y.is_nan() {
            *self = Aabb {
                lo: [f64::NAN; 2],
                hi: [f64::NAN; 2],
            };
        }
        // Plain comparisons: f64::min and max handle NaN, which costs here.
        for (k, x) in [p.x, p.y].into_iter().enumerate() {
            self.lo[k] = if x < self.lo[k] { x } else { self.lo[k] };
            self.hi[k] = if x > self.hi[k] { x } else { self.hi[k] };
        }
    }

    /// Grown by `by` on every side, plus [`SLACK`] relative to `by` and to `scale`, the
    /// magnitude of the coordinates the box was computed from.
    fn grown(self, by: f64, scale: f64) -> Aabb {
        let by = by + SLACK * (scale + by);
        Aabb {
            lo: self.lo.map(|x| x - by),
            hi: self.hi.map(|x| x + by),
        }
    }

    fn magnitude(&self) -> f64 {
        self.lo
            .iter()
            .chain(&self.hi)
            .fold(0.0, |m, x| m.max(x.abs()))
    }

    fn size(&self) -> f64 {
        (self.hi[0] - self.lo[0]).max(self.hi[1] - self.lo[1])
    }

    fn is_finite(&self) -> bool {
        self.lo.iter().chain(&self.hi).all(|x| x.is_finite())
    }

    fn meets(&self, o: &Aabb) -> bool {
        (0..2).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }
}

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
    let (mut tracks, mut fixed, mut links) = (Vec::new(), Vec::new(), Vec::new());
    for (i, b) in bodies.iter().enumerate() {
        match &b.motion {
            Motion::Sampled(tr) => tracks.push((i, tr.samples())),
            // A link stays within its lever about the arm's base, all the time.
            Motion::Link(l) => {
                let base = l.arm.base().pos;
                let mut hull = Aabb::EMPTY;
                hull.add(&base);
                let reach = l.arm.lever(0, l.link);
                links.push((i, hull.grown(reach + half, base.amax() + reach)));
            }
            // Obstacles never move: one box each, from their vertices in world position.
            Motion::Fixed(p) => {
                let posed = Posed::new(&b.shape, p.pos.x, p.pos.y, p.theta);
                let mut hull = Aabb::EMPTY;
                (0..posed.len()).for_each(|k| hull.add(&posed.vertex(k)));
                fixed.push((i, hull.grown(half, p.pos.amax() + b.shape.radius())));
            }
        }
    }
    if tracks.is_empty() && links.is_empty() {
        return Vec::new();
    }
    let windows = window_count(scene, &tracks);
    let (t0, t1) = scene.horizon();
    // Window ends, non-decreasing from t0 to t1 exactly; interpolated, not t0 + f·(t1 − t0),
    // which could overflow.
    let mut ends = vec![t0];
    for w in 1..windows {
        let f = w as f64 / windows as f64;
        ends.push((t0 * (1.0 - f) + t1 * f).clamp(ends[w - 1], t1));
    }
    ends.push(t1);
    // Every robot's box in every window (row by robot), robots in parallel: reading the
    // samples is most of the broad phase's work, and each robot's are read once.
    let mut swept = vec![Aabb::EMPTY; tracks.len() * windows];
    let fill = |(row, &(i, s)): (&mut [Aabb], &(usize, &[Sample]))| {
        window_boxes(s, &ends, bodies[i].shape.radius() + half, row)
    };
    if parallel {
        let rows = swept.par_chunks_mut(windows).zip(&tracks);
        rows.with_min_len(ROBOTS_PER_TASK).for_each(fill);
    } else {
        swept.chunks_mut(windows).zip(&tracks).for_each(fill);
    }
    // Then the windows, in parallel, each with its own grid.
    let in_window = |w: usize| {
        let rows = swept.chunks_exact(windows);
        let boxes: Vec<(usize, Aabb)> = tracks
            .iter()
            .zip(rows)
            .map(|(&(i, _), row)| (i, row[w]))
            .chain(links.iter().copied())
            .chain(fixed.iter().copied())
            .collect();
        let mut found = Vec::new();
        meeting(&boxes, &mut found);
        found
    };
    let found: Vec<(usize, usize)> = if parallel {
        (0..windows)
            .into_par_iter()
            .flat_map_iter(in_window)
            .collect()
    } else {
        (0..windows).flat_map(in_window).collect()
    };
    // Report order: robot-robot pairs by (i, j), then robot-obstacle pairs by (robot, obstacle).
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

/// The number of windows: enough that the median robot moves across about its bounding
/// disc in each, so that its window's box is at most about twice its own. More windows
/// hardly shrink the boxes but each costs a sort; robots that stay near one spot (as in a
/// hall) need one or two. Only a trade-off of cost, so each robot's extent is taken from
/// about 16 of its samples.
fn window_count(scene: &Scene, tracks: &[(usize, &[Sample])]) -> usize {
    let mut ratios: Vec<f64> = tracks
        .iter()
        .map(|&(i, s)| {
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
        return 1; // arms only: their boxes do not change with the window
    }
    let mid = ratios.len() / 2;
    let ratio = *ratios.select_nth_unstable_by(mid, f64::total_cmp).1;
    // NaN casts to 0: one window.
    (ratio.ceil() as usize).clamp(1, MAX_WINDOWS)
}

/// Appends to `out` the pairs of bodies of `boxes` (body, box) whose boxes meet, each once,
/// and every pair with a box that is not finite.
///
/// From [`GRID_MIN_BOXES`] finite boxes on, a uniform grid with cells the size of the median
/// box: a box enters the cells it covers, and a pair is tested in the cells both enter, but
/// reported only in the first of them (the one at the larger of their lower cell indices),
/// so nothing needs deduplicating.
fn meeting(boxes: &[(usize, Aabb)], out: &mut Vec<(usize, usize)>) {
    let (finite, wild): (Vec<_>, Vec<_>) = boxes.iter().partition(|(_, b)| b.is_finite());
    for (k, &&(i, _)) in wild.iter().enumerate() {
        let others = finite.iter().chain(&wild[k + 1..]);
        out.extend(others.map(|&&(j, _)| (i, j)));
    }
    if finite.len() < GRID_MIN_BOXES {
        for (k, &&(i, b)) in finite.iter().enumerate() {
            let meet = finite[k + 1..].iter().filter(|(_, c)| b.meets(c));
            out.extend(meet.map(|&&(j, _)| (i, j)));
        }
        return;
    }
    let mut sizes: Vec<f64> = finite.iter().map(|(_, b)| b.size()).collect();
    let mid = sizes.len() / 2;
    let cell = *sizes.select_nth_unstable_by(mid, f64::total_cmp).1;
    let cell = if cell.is_finite() && cell > 0.0 {
        cell
    } else {
        f64::MAX
    };
    let origin = [0, 1].map(|k| {
        finite
            .iter()
            .fold(f64::INFINITY, |m, (_, b)| m.min(b.lo[k]))
    });
    // Monotone in x (floor, then a saturating cast), so boxes that meet share a cell; no
    // NaN can arise since x ≥ origin and 0 < cell < ∞.
    let index = |x: f64, k: usize| ((x - origin[k]) / cell).floor() as i64;
    let mut lower = Vec::with_capacity(finite.len());
    let mut entries: Vec<(i64, i64, usize)> = Vec::with_capacity(4 * finite.len());
    let mut big = Vec::new();
    for (n, (_, b)) in finite.iter().enumerate() {
        let (x0, x1) = (index(b.lo[0], 0), index(b.hi[0], 0));
        let (y0, y1) = (index(b.lo[1], 1), index(b.hi[1], 1));
        lower.push((x0, y0));
        let cells = (x1 as i128 - x0 as i128 + 1) * (y1 as i128 - y0 as i128 + 1);
        if cells > MAX_CELLS {
            big.push(n);
        } else {
            entries.extend((x0..=x1).flat_map(|x| (y0..=y1).map(move |y| (x, y, n))));
        }
    }
    // Big boxes against all others (against each other once).
    for (k, &n) in big.iter().enumerate() {
        let (i, b) = finite[n];
        for (m, (j, c)) in finite.iter().enumerate() {
            let other_big = big.binary_search(&m).is_ok_and(|l| l <= k);
            if !other_big && b.meets(c) {
                out.push((*i, *j));
            }
        }
    }
    entries.sort_unstable();
    for run in entries.chunk_by(|p, q| (p.0, p.1) == (q.0, q.1)) {
        for (k, &(x, y, n)) in run.iter().enumerate() {
            for &(_, _, m) in &run[k + 1..] {
                let first = (lower[n].0.max(lower[m].0), lower[n].1.max(lower[m].1));
                if first == (x, y) && finite[n].1.meets(&finite[m].1) {
                    out.push((finite[n].0, finite[m].0));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::pair::{check_pair, SharedLimit};
    use super::super::span::PairSettings;
    use super::*;
    use crate::collision::Body;
    use crate::generate::{generate_scene, Kind};
    use crate::geometry::{brute_force_distance, ConvexPolygon};
    use crate::motion::{Pose, Trajectory};

    /// Candidates come in report order, and every pair left out is δ apart: the adaptive
    /// check finds no contact on it, nor does the exact distance at 200 instants.
    fn pruning_is_safe(scene: &Scene, delta: f64) -> usize {
        let (candidates, all) = (candidate_pairs(scene, delta), scene.pairs());
        let mut rest = all.iter();
        assert!(
            candidates.iter().all(|c| rest.any(|p| p == c)),
            "not in order"
        );
        let (t0, t1) = scene.horizon();
        let settings = PairSettings {
            delta,
            grazing_tol: 1e-4 * delta,
            time_tol: 1e-6 * (t1 - t0),
            start: t0,
            walk: Default::default(),
            max_work: crate::collision::DEFAULT_MAX_WORK_PER_PAIR,
        };
        let pruned: Vec<_> = all.iter().filter(|p| !candidates.contains(p)).collect();
        for &&(i, j) in &pruned {
            let (a, b) = (&scene.bodies[i], &scene.bodies[j]);
            let outcome = check_pair(
                a,
                b,
                (t0, t1),
                crate::collision::Method::DEFAULT,
                &settings,
                &SharedLimit::new(),
                &mut Default::default(),
            );
            assert_eq!(outcome.contact, None, "{} - {} pruned", a.name, b.name);
            for k in 0..=200 {
                let t = t0 + (t1 - t0) * k as f64 / 200.0;
                fn posed(body: &Body, t: f64) -> Posed<'_> {
                    let p = body.motion.pose_at(t);
                    Posed::new(&body.shape, p.pos.x, p.pos.y, p.theta)
                }
                let d = brute_force_distance(&posed(a, t), &posed(b, t)).distance;
                assert!(
                    d >= delta,
                    "{} - {} pruned, {d} apart at {t}",
                    a.name,
                    b.name
                );
            }
        }
        pruned.len()
    }

    #[test]
    fn pruned_pairs_never_come_within_delta() {
        let mut pruned = 0;
        for seed in 0..12 {
            // Up to 12 robots the boxes are tested pairwise; 40 robots and 5 obstacles make
            // 45 boxes, which go through the grid.
            let sizes: &[usize] = if seed < 3 {
                &[2, 5, 12, 40]
            } else {
                &[2, 5, 12]
            };
            for &n in sizes {
                let hall = generate_scene(Kind::Hall, seed, 0, n);
                // The scene's δ, and larger ones that bring boxes to the edge of meeting.
                for delta in [hall.delta, 0.3, 1.5] {
                    pruned += pruning_is_safe(&hall, delta);
                }
            }
            for kind in Kind::ALL.into_iter().filter(|&k| k != Kind::Hall) {
                let scene = generate_scene(kind, seed, 0, 0);
                for delta in [scene.delta, 0.5, 2.0] {
                    pruned += pruning_is_safe(&scene, delta);
                }
            }
        }
        assert!(
            pruned > 500,
            "only {pruned} pairs pruned: the test shows little"
        );
    }

    /// A 0.8 × 0.8 square moving linearly through `(t, x, y)`.
    fn robot(name: &str, samples: &[(f64, f64, f64)]) -> Body {
        let sample = |&(t, x, y): &(f64, f64, f64)| Sample {
            t,
            pos: Vec2::new(x, y),
            theta: 0.0,
            vel: Vec2::zeros(),
            omega: 0.0,
        };
        let square = [[-0.4, -0.4], [0.4, -0.4], [0.4, 0.4], [-0.4, 0.4]];
        Body::robot(
            name,
            ConvexPolygon::new(&square).unwrap().0,
            Trajectory::new(samples.iter().map(sample).collect()).unwrap(),
        )
    }

    #[test]
    fn robots_sweeping_across_a_hall_are_pruned_safely() {
        // Their boxes cover far more grid cells than the hall's: tested against all boxes.
        let mut hall = generate_scene(Kind::Hall, 5, 0, 30);
        hall.bodies
            .push(robot("S1", &[(0.0, -30.0, -30.0), (20.0, 50.0, 50.0)]));
        hall.bodies
            .push(robot("S2", &[(0.0, 50.0, -30.0), (20.0, -30.0, 50.0)]));
        assert!(pruning_is_safe(&hall, hall.delta) > 300);
        assert!(pruning_is_safe(&hall, 0.8) > 200);
    }

    #[test]
    fn a_hall_of_1000_robots_has_few_candidates() {
        let hall = generate_scene(Kind::Hall, 1, 0, 1000);
        let n = candidate_pairs(&hall, hall.delta).len();
        assert!(n < 20 * 1000, "{n} candidates of {}", hall.pair_count());
        let all = candidate_pairs(&hall, f64::INFINITY);
        assert_eq!(all.len(), hall.pair_count(), "an infinite δ keeps all");
    }

    #[test]
    fn the_thread_pool_changes_nothing() {
        let pools = [1, 2, 4].map(|n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
        });
        for (seed, n) in [(1, 70), (2, 300), (3, 1000)] {
            let hall = generate_scene(Kind::Hall, seed, 0, n);
            for delta in [hall.delta, 0.4, 1.5] {
                let serial = candidates(&hall, delta, false);
                assert!(!serial.is_empty());
                for pool in &pools {
                    let parallel = pool.install(|| candidates(&hall, delta, true));
                    assert_eq!(parallel, serial, "{n} robots, δ {delta}");
                }
            }
        }
    }

    /// A deterministic box of sides up to `size` with its corner in a square of side 100.
    fn random_box(state: &mut u64, size: f64) -> Aabb {
        let mut next = || {
            // SplitMix64 steps, as uniform numbers in [0, 1).
            *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = *state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            (z ^ (z >> 31)) as f64 / 2f64.powi(64)
        };
        let (x, y) = (100.0 * next(), 100.0 * next());
        let (w, h) = (size * next(), size * next());
        Aabb {
            lo: [x, y],
            hi: [x + w, y + h],
        }
    }

    #[test]
    fn the_grid_finds_what_testing_every_pair_finds() {
        let mut state = 7;
        for (n, size) in [(40, 20.0), (300, 8.0), (2000, 3.0)] {
            // Mostly small boxes; one in fifty covers a large part of the square (more than
            // MAX_CELLS grid cells), one in fifty has no width.
            let boxes: Vec<(usize, Aabb)> = (0..n)
                .map(|i| {
                    let b = match i % 50 {
                        0 => random_box(&mut state, 80.0),
                        1 => {
                            let b = random_box(&mut state, size);
                            Aabb {
                                hi: [b.lo[0], b.hi[1]],
                                ..b
                            }
                        }
                        _ => random_box(&mut state, size),
                    };
                    (i, b)
                })
                .collect();
            let mut expected = Vec::new();
            for (k, (i, b)) in boxes.iter().enumerate() {
                for (j, c) in &boxes[k + 1..] {
                    if b.meets(c) {
                        expected.push((*i, *j));
                    }
                }
            }
            let mut found = Vec::new();
            meeting(&boxes, &mut found);
            let mut found: Vec<_> = found
                .into_iter()
                .map(|(i, j)| (i.min(j), i.max(j)))
                .collect();
            found.sort_unstable();
            let count = found.len();
            found.dedup();
            assert_eq!(found.len(), count, "a pair twice, {n} boxes");
            assert_eq!(found, expected, "{n} boxes");
            assert!(
                expected.len() > n / 4,
                "{n} boxes, few meet: the test shows little"
            );
        }
    }

    #[test]
    fn non_finite_input_keeps_pairs() {
        let mut scene = generate_scene(Kind::Hall, 3, 0, 6);
        assert_eq!(candidate_pairs(&scene, f64::NAN), scene.pairs());
        let first_odd = scene.bodies.len();
        for x in [f64::NAN, f64::INFINITY] {
            let mut obstacle = robot("O", &[(0.0, 0.0, 0.0)]);
            obstacle.motion = Motion::Fixed(Pose {
                pos: Vec2::new(x, 0.0),
                theta: 0.0,
            });
            scene.bodies.push(obstacle);
        }
        // Far from everything, but every interpolated pose overflows.
        let far = [(0.0, -1.5e308, 1e300), (1.0, 1.5e308, 1e300)];
        scene.bodies.push(robot("far", &far));
        let candidates = candidate_pairs(&scene, scene.delta);
        for (i, j) in scene.pairs() {
            if i.max(j) >= first_odd {
                assert!(candidates.contains(&(i, j)), "{i} - {j} dropped");
            }
        }
    }
}
