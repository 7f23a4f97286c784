//! The narrow phase (the Lin-Canny walk, cold and warm-started) against the exact O(n·m)
//! brute force, on convex polygons made from arbitrary points.
#![no_main]

use arbitrary::Arbitrary;
use workcell::geometry::{
    brute_force_distance, closest_features, ConvexPolygon, Posed, WalkTolerances,
};

/// Coordinates of shapes and poses are kept within this, so that the tolerance below means
/// something.
const EXTENT: f64 = 1e3;

#[derive(Arbitrary, Debug)]
struct Case {
    a: Vec<(i32, i32)>,
    b: Vec<(i32, i32)>,
    pose_a: (i32, i32, i16),
    pose_b: (i32, i32, i16),
    warm_from: (i32, i32, i16),
}

/// Integers scaled into [-EXTENT, EXTENT]: every value finite, degenerate ones reachable.
fn coordinate(v: i32) -> f64 {
    f64::from(v) / f64::from(i32::MAX) * EXTENT
}

fn polygon(points: &[(i32, i32)]) -> Option<ConvexPolygon> {
    let points: Vec<[f64; 2]> = points
        .iter()
        .map(|&(x, y)| [coordinate(x), coordinate(y)])
        .collect();
    ConvexPolygon::new(&points).ok().map(|(p, _)| p)
}

fn posed(shape: &ConvexPolygon, (x, y, t): (i32, i32, i16)) -> Posed<'_> {
    Posed::new(shape, coordinate(x), coordinate(y), f64::from(t) / 1000.0)
}

libfuzzer_sys::fuzz_target!(|case: Case| {
    let (Some(a), Some(b)) = (polygon(&case.a), polygon(&case.b)) else {
        return;
    };
    let walk = WalkTolerances::default();
    let (pa, pb) = (posed(&a, case.pose_a), posed(&b, case.pose_b));
    let exact = brute_force_distance(&pa, &pb).distance;
    let tol = 1e-9 * (EXTENT + a.radius() + b.radius());
    let cold = closest_features(&pa, &pb, None, &walk);
    assert!(
        (cold.distance - exact).abs() <= tol,
        "cold walk {} vs exact {exact}: {case:?}",
        cold.distance
    );
    // Warm-started from the closest pair at another pose of `a`.
    let earlier = closest_features(&posed(&a, case.warm_from), &pb, None, &walk);
    let warm = closest_features(&pa, &pb, Some(earlier.features), &walk);
    assert!(
        (warm.distance - exact).abs() <= tol,
        "warm walk {} vs exact {exact}: {case:?}",
        warm.distance
    );
});
