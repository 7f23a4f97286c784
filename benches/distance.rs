//! Narrow phase: the closest-feature walk, cold and warm-started, against the exact
//! O(n·m) brute force, on regular polygons of 4 to 64 vertices.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
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

fn distance(c: &mut Criterion) {
    let tol = WalkTolerances::default();
    let mut group = c.benchmark_group("distance");
    for n in [4usize, 8, 16, 64] {
        let (a, b) = (regular(n, 1.0), regular(n, 0.7));
        // A sequence of nearby poses, as the checker visits them along a trajectory.
        let poses: Vec<(Posed, Posed)> = (0..64)
            .map(|k| {
                let s = k as f64 / 64.0;
                (
                    Posed::new(&a, 0.0, 0.0, 0.3 * s),
                    Posed::new(&b, 2.0, 0.5 * s, -0.5 * s),
                )
            })
            .collect();
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
    }
    group.finish();
    black_box(());
}

criterion_group!(benches, distance);
criterion_main!(benches);
