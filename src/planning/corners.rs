//! Cutting corners: fewer stops where a rounded grown obstacle made many.
//!
//! A taut path wraps a grown obstacle vertex by vertex, and the robot stops at each. Where
//! the obstacle is rounded (the clearance polygon, the swept robot's arcs), the stops are
//! close together and each costs a full deceleration. Replacing a run of waypoints by the
//! point where the lines of the segments before and after the run meet leaves one stop
//! instead; the replacement is kept only if it is faster and its segments are free.

use super::grown::Grown;
use crate::geometry::{cross, Vec2};

/// Replaces runs of waypoints of `path` by single corners where that lowers the total
/// `cost` of the segments, keeping every segment clear of `obstacles` (up to `tol`).
/// The ends never move.
pub(crate) fn cut_corners(
    mut path: Vec<Vec2>,
    obstacles: &[Grown],
    tol: f64,
    cost: impl Fn(f64) -> f64,
) -> Vec<Vec2> {
    let free = |a: &Vec2, b: &Vec2| obstacles.iter().all(|g| !g.blocks(a, b, tol));
    let mut i = 1;
    while i + 1 < path.len() {
        // Waypoints i..=j become one corner; the longest run first.
        let cut = (i + 1..path.len() - 1).rev().find_map(|j| {
            let p = apex(&path[i - 1], &path[i], &path[j], &path[j + 1])?;
            let old: f64 = path[i - 1..=j + 1]
                .windows(2)
                .map(|w| cost((w[1] - w[0]).norm()))
                .sum();
            let new = cost((p - path[i - 1]).norm()) + cost((path[j + 1] - p).norm());
            (new < old && free(&path[i - 1], &p) && free(&p, &path[j + 1])).then_some((j, p))
        });
        match cut {
            // The new corner may merge with what follows: try again from it.
            Some((j, p)) => {
                path.splice(i..=j, [p]);
            }
            None => i += 1,
        }
    }
    path
}

/// Where the segment `a`→`b`, extended beyond `b`, meets the segment `c`→`d` extended
/// back before `c`: the corner that skips the waypoints from `b` to `c`.
fn apex(a: &Vec2, b: &Vec2, c: &Vec2, d: &Vec2) -> Option<Vec2> {
    let (u, v) = (b - a, d - c);
    let denom = cross(&u, &v);
    if denom == 0.0 {
        return None;
    }
    // a + s·u = c + r·v with s ≥ 1 (beyond b) and r ≤ 0 (before c).
    let s = cross(&(c - a), &v) / denom;
    let r = cross(&(c - a), &u) / denom;
    (s >= 1.0 && r <= 0.0 && s.is_finite()).then(|| a + u * s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Vec2 {
        Vec2::new(x, y)
    }

    #[test]
    fn apex_of_a_wrapped_corner() {
        // Around the corner of the unit square, cut at 45 degrees.
        let q = apex(&p(-1.0, 0.0), &p(0.0, 0.0), &p(1.0, 1.0), &p(1.0, 2.0)).unwrap();
        assert!((q - p(1.0, 0.0)).norm() < 1e-15);
        // An S-bend has no single corner, nor have parallel segments.
        assert!(apex(&p(0.0, 0.0), &p(1.0, 0.0), &p(3.0, 1.0), &p(4.0, 0.0)).is_none());
        assert!(apex(&p(0.0, 0.0), &p(1.0, 0.0), &p(2.0, 1.0), &p(3.0, 1.0)).is_none());
    }

    #[test]
    fn a_chamfered_corner_becomes_one_stop_unless_blocked() {
        let path = vec![
            p(-2.0, 0.0),
            p(0.0, 0.0),
            p(0.1, 0.02),
            p(0.2, 0.1),
            p(0.2, 2.0),
        ];
        // Each stop costs 1 on top of the length.
        let cost = |l: f64| if l > 0.0 { l + 1.0 } else { 0.0 };
        let cut = cut_corners(path.clone(), &[], 1e-12, cost);
        assert_eq!(cut.len(), 3);
        assert!((cut[1] - p(0.2, 0.0)).norm() < 1e-12);
        // An obstacle in the corner allows only a smaller cut.
        let block = Grown::new(vec![
            p(0.15, -0.05),
            p(0.25, -0.05),
            p(0.25, 0.03),
            p(0.15, 0.03),
        ]);
        let cut = cut_corners(path, std::slice::from_ref(&block), 1e-12, cost);
        assert_eq!(cut.len(), 4);
        assert!((cut[1] - p(0.075, 0.0)).norm() < 1e-12);
        assert!(cut.windows(2).all(|w| !block.blocks(&w[0], &w[1], 1e-12)));
    }
}
