//! Closest points between points and segments of the plane.

use super::{cross, Vec2};

/// Parameter in [0, 1] of the point of segment `a`→`b` closest to `p`.
#[inline]
pub fn project_on_segment(p: &Vec2, a: &Vec2, b: &Vec2) -> f64 {
    let ab = b - a;
    let len2 = ab.norm_squared();
    if len2 == 0.0 {
        return 0.0;
    }
    ((p - a).dot(&ab) / len2).clamp(0.0, 1.0)
}

/// Whether segments `p0`→`p1` and `q0`→`q1` are parallel within `parallel_tol` (the sine
/// of the angle between them).
#[inline]
pub fn nearly_parallel(p0: &Vec2, p1: &Vec2, q0: &Vec2, q1: &Vec2, parallel_tol: f64) -> bool {
    let (d1, d2) = (p1 - p0, q1 - q0);
    cross(&d1, &d2).abs() <= parallel_tol * d1.norm() * d2.norm()
}

/// Closest points `(on first, on second)` of segments `p0`→`p1` and `q0`→`q1`.
///
/// Parallel segments whose projections overlap get the middle of the overlap: a point
/// strictly inside both edges' Voronoi strips, which keeps the feature walk from
/// oscillating between the end vertices of two parallel edges (Feyeux & Landry, Table 4).
/// For edges that are only nearly parallel the middle is not the closest pair: the walk
/// then takes [`closest_ends`] once the features are settled.
pub fn segment_segment(
    p0: &Vec2,
    p1: &Vec2,
    q0: &Vec2,
    q1: &Vec2,
    parallel_tol: f64,
) -> (Vec2, Vec2) {
    let d1 = p1 - p0;
    let d2 = q1 - q0;
    if nearly_parallel(p0, p1, q0, q1, parallel_tol) {
        // Parallel: overlap of the projections of q0, q1 on the first segment.
        let len1sq = d1.norm_squared();
        let s0 = (q0 - p0).dot(&d1) / len1sq;
        let s1 = (q1 - p0).dot(&d1) / len1sq;
        let lo = s0.min(s1).max(0.0);
        let hi = s0.max(s1).min(1.0);
        if lo <= hi {
            let s = 0.5 * (lo + hi);
            let pa = p0 + d1 * s;
            let t = project_on_segment(&pa, q0, q1);
            return (pa, q0 + d2 * t);
        }
    } else if let Some(x) = crossing(p0, p1, q0, q1) {
        return (x, x);
    }
    let (_, pa, pb) = closest_ends(p0, p1, q0, q1);
    (pa, pb)
}

/// The point where the segments cross, when both parameters of the intersection of their
/// lines lie in [0, 1]; `None` for parallel lines.
pub fn crossing(p0: &Vec2, p1: &Vec2, q0: &Vec2, q1: &Vec2) -> Option<Vec2> {
    let (d1, d2) = (p1 - p0, q1 - q0);
    let denom = cross(&d1, &d2);
    if denom == 0.0 {
        return None;
    }
    let r = q0 - p0;
    let s = cross(&r, &d2) / denom;
    let t = cross(&r, &d1) / denom;
    ((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t)).then(|| p0 + d1 * s)
}

/// The closest pair of two segments that do not cross: an end point of one and its
/// projection on the other. Returns which (0: `p0`, 1: `p1`, 2: `q0`, 3: `q1`) and the
/// points `(on first, on second)`.
pub fn closest_ends(p0: &Vec2, p1: &Vec2, q0: &Vec2, q1: &Vec2) -> (usize, Vec2, Vec2) {
    let (d1, d2) = (p1 - p0, q1 - q0);
    let candidates = [
        (*p0, q0 + d2 * project_on_segment(p0, q0, q1)),
        (*p1, q0 + d2 * project_on_segment(p1, q0, q1)),
        (p0 + d1 * project_on_segment(q0, p0, p1), *q0),
        (p0 + d1 * project_on_segment(q1, p0, p1), *q1),
    ];
    let mut best = 0;
    let mut best_d = (candidates[0].1 - candidates[0].0).norm_squared();
    for (k, c) in candidates.iter().enumerate().skip(1) {
        let d = (c.1 - c.0).norm_squared();
        if d < best_d {
            best = k;
            best_d = d;
        }
    }
    (best, candidates[best].0, candidates[best].1)
}
