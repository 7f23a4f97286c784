//! Narrow phase: the closest-feature walk, cold and warm-started, against the exact
//! O(n·m) brute force and against parry2d-f64's `query::distance` (GJK), the peer, on
//! regular polygons of 4 to 64 vertices.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use parry2d_f64::math::{Pose as ParryPose, Vector as ParryVector};
use parry2d_f64::shape::ConvexPolygon as ParryPolygon;
use workcell::geometry::{
    brute_force_distance, closest_features, ConvexPolygon, Posed, WalkTolerances,
};

fn regular(n: usize, radius: f64) -> ConvexPolygon {
    let pts: Vec<[f64; 2]> = (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            [radius * a.cos(), radius * a.sin()]
        })
        .collect();
    ConvexPolygon::new(&pts).unwrap().0
}

/// The same polygon, same vertices in the same order, as parry's.
fn parry_polygon(p: &ConvexPolygon) -> ParryPolygon {
    let points = p
        .vertices()
        .iter()
        .map(|v| ParryVector::new(v.x, v.y))
        .collect();
    let q = ParryPolygon::from_convex_polyline(points).unwrap();
    assert_eq!(q.points().len(), p.len(), "parry dropped a vertex");
    q
}

/// `(x, y, theta)` of a body.
type Placement = [f64; 3];

fn parry_pose(&[x, y, theta]: &Placement) -> ParryPose {
    ParryPose::new(ParryVector::new(x, y), theta)
}

fn distance(c: &mut Criterion) {
    let tol = WalkTolerances::default();
    let mut group = c.benchmark_group("distance");
    for n in [4usize, 8, 16, 64] {
        let (a, b) = (regular(n, 1.0), regular(n, 0.7));
        // A sequence of nearby poses, as the checker visits them along a trajectory.
        let placements: Vec<(Placement, Placement)> = (0..64)
            .map(|k| {
                let s = k as f64 / 64.0;
                ([0.0, 0.0, 0.3 * s], [2.0, 0.5 * s, -0.5 * s])
            })
            .collect();
        let poses: Vec<(Posed, Posed)> = placements
            .iter()
            .map(|&([xa, ya, ta], [xb, yb, tb])| {
                (Posed::new(&a, xa, ya, ta), Posed::new(&b, xb, yb, tb))
            })
            .collect();
        // The peer on the same pairs in the same poses.
        let (pa, pb) = (parry_polygon(&a), parry_polygon(&b));
        let parry_poses: Vec<(ParryPose, ParryPose)> = placements
            .iter()
            .map(|(p, q)| (parry_pose(p), parry_pose(q)))
            .collect();
        let parry = |p: &ParryPose, q: &ParryPose| {
            parry2d_f64::query::distance(p, &pa, q, &pb)
                .unwrap()
                .distance
        };
        // Checked once, outside the timed loops: both answer the same question.
        for ((wa, wb), (p, q)) in poses.iter().zip(&parry_poses) {
            let (ours, theirs) = (closest_features(wa, wb, None, &tol).distance, parry(p, q));
            assert!(
                (ours - theirs).abs() <= 1e-9,
                "n = {n}: walk {ours}, parry {theirs}"
            );
        }
        group.bench_with_input(BenchmarkId::new("walk-cold", n), &poses, |bench, poses| {
            bench.iter(|| {
                poses
                    .iter()
                    .map(|(pa, pb)| closest_features(pa, pb, None, &tol).distance)
                    .sum::<f64>()
            })
        });
        group.bench_with_input(BenchmarkId::new("walk-warm", n), &poses, |bench, poses| {
            bench.iter(|| {
                let mut warm = None;
                poses
                    .iter()
                    .map(|(pa, pb)| {
                        let d = closest_features(pa, pb, warm, &tol);
                        warm = Some(d.features);
                        d.distance
                    })
                    .sum::<f64>()
            })
        });
        group.bench_with_input(
            BenchmarkId::new("brute-force", n),
            &poses,
            |bench, poses| {
                bench.iter(|| {
                    poses
                        .iter()
                        .map(|(pa, pb)| brute_force_distance(pa, pb).distance)
                        .sum::<f64>()
                })
            },
        );
        group.bench_with_input(
            BenchmarkId::new("parry", n),
            &parry_poses,
            |bench, poses| bench.iter(|| poses.iter().map(|(p, q)| parry(p, q)).sum::<f64>()),
        );
    }
    group.finish();
    black_box(());
}

criterion_group!(benches, distance);
criterion_main!(benches);
