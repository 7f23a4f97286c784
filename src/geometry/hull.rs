//! The convex hull of a set of points (Andrew's monotone chain), shared by the planner
//! (swept shapes, the region a robot sweeps) and by bodies of parts (their outer level).

use super::{cross, Vec2};

/// Andrew's monotone chain: the counter-clockwise convex hull of `points`, without
/// collinear or repeated vertices, starting at the lowest-x (then lowest-y) point.
pub(crate) fn convex_hull(mut points: Vec<Vec2>) -> Vec<Vec2> {
    points.sort_unstable_by(|p, q| p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y)));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let mut hull: Vec<Vec2> = Vec::with_capacity(points.len() + 1);
    // Lower chain left to right, then upper chain right to left; each drops its last
    // point, which starts the other chain.
    for pass in 0..2 {
        let start = hull.len();
        let mut push = |p: Vec2| {
            while hull.len() >= start + 2 {
                let (a, b) = (hull[hull.len() - 2], hull[hull.len() - 1]);
                if cross(&(b - a), &(p - a)) > 0.0 {
                    break;
                }
                hull.pop();
            }
            hull.push(p);
        };
        if pass == 0 {
            points.iter().for_each(|&p| push(p));
        } else {
            points.iter().rev().for_each(|&p| push(p));
        }
        hull.pop();
    }
    hull
}
