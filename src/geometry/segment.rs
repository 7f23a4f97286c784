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

/// Closest points `(on first, on second)` of segments `p0`→`p1` and `q0`→`q1`.
///
/// Parallel segments whose projections overlap get the middle of the overlap: a point
/// strictly inside both edges' Voronoi strips, which keeps the feature walk from
/// oscillating between the end vertices of two parallel edges (Feyeux & Landry, Table 4).
pub fn segment_segment(
    p0: &Vec2,
    p1: &Vec2,
    q0: &Vec2,
    q1: &Vec2,
    parallel_tol: f64,
) -> (Vec2, Vec2) {
    let d1 = p1 - p0;
    let d2 = q1 - q0;
    let denom = cross(&d1, &d2);
    let len1 = d1.norm();
    let len2 = d2.norm();
    if denom.abs() <= parallel_tol * len1 * len2 {
        // Parallel: overlap of the projections of q0, q1 on the first segment.
        let len1sq = len1 * len1;
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
    } else {
        // Proper intersection test: both parameters inside [0, 1].
        let r = q0 - p0;
        let s = cross(&r, &d2) / denom;
        let t = cross(&r, &d1) / denom;
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
            let x = p0 + d1 * s;
            return (x, x);
        }
    }
    // Disjoint: the minimum is reached at an end point of one of the segments.
    let candidates = [
        (*p0, q0 + d2 * project_on_segment(p0, q0, q1)),
        (*p1, q0 + d2 * project_on_segment(p1, q0, q1)),
        (p0 + d1 * project_on_segment(q0, p0, p1), *q0),
        (p0 + d1 * project_on_segment(q1, p0, p1), *q1),
    ];
    let mut best = candidates[0];
    let mut best_d = (best.1 - best.0).norm_squared();
    for c in &candidates[1..] {
        let d = (c.1 - c.0).norm_squared();
        if d < best_d {
            best = *c;
            best_d = d;
        }
    }
    best
}
