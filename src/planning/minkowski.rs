//! Convex hulls, Minkowski sums and the robot's swept shape, on plain vertex lists.
//!
//! Polygons here are counter-clockwise vertex lists without the validation of
//! [`ConvexPolygon`](crate::geometry::ConvexPolygon): they are built from validated ones and
//! only ever grow when rounding makes a vertex reflex, so they stay conservative.

use crate::geometry::{convex_hull, cross, Vec2};

/// Number of sides of the polygon that stands for the clearance disc.
pub(crate) const DISC_SIDES: usize = 16;

/// Index of the lowest vertex (smallest y, then smallest x): where the edges' polar angles
/// start from 0.
fn lowest(poly: &[Vec2]) -> usize {
    (0..poly.len())
        .min_by(|&i, &j| {
            let (p, q) = (poly[i], poly[j]);
            p.y.total_cmp(&q.y).then(p.x.total_cmp(&q.x))
        })
        .unwrap_or(0)
}

/// Minkowski sum of two convex counter-clockwise polygons by merging their edges in polar
/// order, O(n + m). The result starts at its lowest vertex.
///
/// Rounding can order two nearly parallel edges the wrong way and leave a vertex very
/// slightly reflex; [`convex_cleanup`] removes it, which only grows the polygon.
pub(crate) fn minkowski_sum(a: &[Vec2], b: &[Vec2]) -> Vec<Vec2> {
    let (n, m) = (a.len(), b.len());
    let (ia, ib) = (lowest(a), lowest(b));
    let va = |i: usize| a[(ia + i) % n];
    let vb = |j: usize| b[(ib + j) % m];
    let mut out = Vec::with_capacity(n + m);
    let (mut i, mut j) = (0, 0);
    while i < n || j < m {
        out.push(va(i) + vb(j));
        let (ea, eb) = (va(i + 1) - va(i), vb(j + 1) - vb(j));
        // Positive: a's edge comes first in polar order. Both edge sequences start at angle
        // 0 and turn by less than a half-turn each, so the cross product orders them.
        let order = if i == n {
            -1.0
        } else if j == m {
            1.0
        } else {
            let c = cross(&ea, &eb);
            if c == 0.0 && ea.dot(&eb) < 0.0 {
                1.0
            } else {
                c
            }
        };
        if order >= 0.0 {
            i += 1;
        }
        if order <= 0.0 {
            j += 1;
        }
    }
    convex_cleanup(out)
}

/// Removes the vertices of a counter-clockwise polygon where it does not turn strictly
/// left, in one stack pass. The first vertex must be extreme (the sum's lowest vertex is).
/// Removing a reflex or straight vertex adds a triangle, so the polygon never shrinks.
pub(crate) fn convex_cleanup(poly: Vec<Vec2>) -> Vec<Vec2> {
    let mut out: Vec<Vec2> = Vec::with_capacity(poly.len());
    let left = |a: &Vec2, b: &Vec2, c: &Vec2| cross(&(b - a), &(c - b)) > 0.0;
    for p in poly {
        while out.len() >= 2 && !left(&out[out.len() - 2], &out[out.len() - 1], &p) {
            out.pop();
        }
        if out.last() != Some(&p) {
            out.push(p);
        }
    }
    // The seam: the last vertices against the first.
    while out.len() >= 3 && !left(&out[out.len() - 2], &out[out.len() - 1], &out[0]) {
        out.pop();
    }
    out
}

/// Vertices of `body` rotated by `theta`.
pub(crate) fn rotated(body: &[Vec2], theta: f64) -> Vec<Vec2> {
    let (s, c) = theta.sin_cos();
    body.iter()
        .map(|v| Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y))
        .collect()
}

/// A convex polygon containing the region swept by `body` (in its frame, about the origin)
/// as its orientation runs from `theta` to `theta + turn`.
///
/// Without rotation it is the body itself. Otherwise each vertex's arc is cut into `k`
/// equal steps `h ≤ step`, and the hull takes the vertex at both end orientations plus, at
/// every step, the vertex pushed out to radius `|v| / cos(h/2)`: consecutive pushed points
/// span a segment tangent to the arc, so the arc lies inside the quadrilateral they form
/// with the unpushed vertices, and each rotated body, the hull of its rotated vertices,
/// lies inside the hull.
pub(crate) fn swept_shape(body: &[Vec2], theta: f64, turn: f64, step: f64) -> Vec<Vec2> {
    if turn == 0.0 {
        return rotated(body, theta);
    }
    let steps = (turn.abs() / step).ceil().max(1.0);
    let h = turn / steps;
    let out = 1.0 / (0.5 * h).cos();
    let mut points = rotated(body, theta);
    points.extend(rotated(body, theta + turn));
    let pushed: Vec<Vec2> = body.iter().map(|v| v * out).collect();
    for k in 0..=steps as usize {
        points.extend(rotated(&pushed, theta + k as f64 * h));
    }
    convex_hull(points)
}

/// A polygon circumscribing the disc of radius `r` about the origin: its edges are tangent
/// to the circle, its vertices at `r / cos(π/DISC_SIDES)`. The edges facing the axes are
/// tangent at the axes, so axis-aligned obstacles grow by exactly `r`.
pub(crate) fn disc(r: f64) -> Vec<Vec2> {
    let n = DISC_SIDES as f64;
    let big = r / (std::f64::consts::PI / n).cos();
    (0..DISC_SIDES)
        .map(|k| {
            let a = std::f64::consts::PI * (2 * k + 1) as f64 / n;
            Vec2::new(big * a.cos(), big * a.sin())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn area(p: &[Vec2]) -> f64 {
        let n = p.len();
        0.5 * (0..n).map(|i| cross(&p[i], &p[(i + 1) % n])).sum::<f64>()
    }

    fn square(h: f64) -> Vec<Vec2> {
        vec![
            Vec2::new(-h, -h),
            Vec2::new(h, -h),
            Vec2::new(h, h),
            Vec2::new(-h, h),
        ]
    }

    /// Weakly inside a counter-clockwise convex polygon, up to `tol`.
    fn inside(p: &Vec2, poly: &[Vec2], tol: f64) -> bool {
        let n = poly.len();
        (0..n).all(|i| {
            let e = poly[(i + 1) % n] - poly[i];
            cross(&e, &(p - poly[i])) >= -tol * e.norm()
        })
    }

    #[test]
    fn hull_drops_interior_and_collinear_points() {
        let mut pts = square(1.0);
        pts.extend([
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.3, 0.2),
        ]);
        pts.push(Vec2::new(1.0, 1.0));
        let h = convex_hull(pts);
        assert_eq!(h.len(), 4);
        assert!((area(&h) - 4.0).abs() < 1e-12);
    }

    #[test]
    fn sum_of_squares_is_a_square_and_sum_with_a_triangle_is_exact() {
        let s = minkowski_sum(&square(1.0), &square(0.5));
        assert_eq!(s.len(), 4);
        assert!((area(&s) - 9.0).abs() < 1e-12);
        let tri = vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
        ];
        let s = minkowski_sum(&square(1.0), &tri);
        let mut brute = Vec::new();
        for p in square(1.0) {
            brute.extend(tri.iter().map(|q| p + q));
        }
        let h = convex_hull(brute);
        assert_eq!(s.len(), h.len());
        assert!((area(&s) - area(&h)).abs() < 1e-12);
        assert!(s.iter().all(|p| h.contains(p)));
    }

    #[test]
    fn swept_shape_contains_every_intermediate_orientation() {
        let body = vec![
            Vec2::new(0.2, -0.1),
            Vec2::new(1.5, 0.0),
            Vec2::new(0.3, 0.4),
        ];
        for turn in [0.3, -1.0, PI, 2.9] {
            let s = swept_shape(&body, 0.7, turn, PI / 8.0);
            for k in 0..=200 {
                let th = 0.7 + turn * k as f64 / 200.0;
                for v in rotated(&body, th) {
                    assert!(inside(&v, &s, 1e-12), "turn {turn} at {th}");
                }
            }
        }
        assert_eq!(swept_shape(&body, 0.5, 0.0, 0.1), rotated(&body, 0.5));
    }

    #[test]
    fn disc_polygon_circumscribes_the_circle() {
        let d = disc(2.0);
        for k in 0..1000 {
            let a = k as f64 * 0.00628;
            assert!(inside(&Vec2::new(2.0 * a.cos(), 2.0 * a.sin()), &d, 1e-12));
        }
        assert!(d.iter().all(|v| v.norm() < 2.0 * 1.02));
        assert!(d.iter().any(|v| (v.x - 2.0).abs() < 1e-15));
    }
}
