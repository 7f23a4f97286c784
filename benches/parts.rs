//! Bodies of parts against the same scenes made convex (issue 20, item 7):
//!
//! * `parts/far`: two combs of 20 parts (a back and 19 teeth) gliding past each other 0.3
//!   apart, their bounding discs overlapping all along, against the same scene with each comb
//!   as its hull: hull first, the parts should cost next to nothing more.
//! * `parts/close`: the second comb lowered between the first's teeth, 3δ from them, and
//!   raised again (the part level throughout), against two bars sliding past each other 3δ
//!   apart on the same time grid.
//!
//! `cargo bench --bench parts`, then `criterion_table parts/ --ratio 20-parts/hulls
//! --ratio 20x20-parts/convex-pair`.

use criterion::{criterion_group, criterion_main, Criterion};
use workcell::collision::{check, Body, CheckOptions, Scene};
use workcell::geometry::{ConvexPolygon, Parts};
use workcell::motion::{Pose, Trajectory};

const DELTA: f64 = 0.01;
const SAMPLES: usize = 100;

fn bar(x0: f64, y0: f64, x1: f64, y1: f64) -> ConvexPolygon {
    ConvexPolygon::from_vertices(&[[x0, y0], [x1, y0], [x1, y1], [x0, y1]]).unwrap()
}

/// A comb of 19 teeth `tooth` wide at pitch `pitch` from `offset`, pointing up (or down).
fn comb(offset: f64, tooth: f64, pitch: f64, up: bool) -> Parts {
    let (back, teeth) = if up {
        ((-0.1, 0.0), (0.0, 0.5))
    } else {
        ((0.0, 0.1), (-0.5, 0.0))
    };
    let width = 19.0 * pitch + offset + tooth;
    let mut parts = vec![bar(0.0, back.0, width, back.1)];
    parts.extend((0..19).map(|k| {
        let x = offset + k as f64 * pitch;
        bar(x, teeth.0, x + tooth, teeth.1)
    }));
    Parts::new(parts).unwrap()
}

/// `SAMPLES` poses from `pose(u)` for u from 0 to 1, over 10 time units.
fn path(pose: impl Fn(f64) -> Pose) -> Trajectory {
    let last = (SAMPLES - 1) as f64;
    Trajectory::from_poses((0..SAMPLES).map(|k| (10.0 * k as f64 / last, pose(k as f64 / last))))
        .unwrap()
}

fn scene(bodies: [Body; 2]) -> Scene {
    Scene::with_bodies(DELTA, bodies).unwrap()
}

/// Two combs back to back 0.3 apart, one gliding along the other; `hulls` makes each its hull.
fn far(hulls: bool) -> Scene {
    let (tooth, pitch) = (0.05, 0.1);
    let body = |name: &str, parts: Parts, trajectory| match hulls {
        true => Body::robot(name, parts.hull().clone(), trajectory),
        false => Body::robot_of_parts(name, parts, trajectory),
    };
    let still = path(|_| Pose::new(0.0, 0.0, 0.0));
    // The upper comb's back (0 to 0.1 in its frame) 0.3 below the lower's (-0.1 to 0).
    let gliding = path(|u| Pose::new(-1.0 + 2.0 * u, -0.5, 0.0));
    scene([
        body("lower", comb(0.0, tooth, pitch, true), still),
        body("upper", comb(0.0, tooth, pitch, false), gliding),
    ])
}

/// The upper comb lowered between the lower's teeth, 3δ from them, and raised again.
fn close() -> Scene {
    let (tooth, gap) = (0.05, 3.0 * DELTA);
    let pitch = 2.0 * (tooth + gap);
    let still = path(|_| Pose::new(0.0, 0.0, 0.0));
    let dive = path(|u| Pose::new(0.0, 1.3 - 0.7 * (std::f64::consts::PI * u).sin(), 0.0));
    scene([
        Body::robot_of_parts("lower", comb(0.0, tooth, pitch, true), still),
        Body::robot_of_parts("upper", comb(tooth + gap, tooth, pitch, false), dive),
    ])
}

/// Two bars sliding past each other 3δ apart on the same time grid as [`close`].
fn convex_pair() -> Scene {
    let still = path(|_| Pose::new(0.0, 0.0, 0.0));
    let sliding = path(|u| Pose::new(-1.0 + 2.0 * u, 0.2 + 3.0 * DELTA, 0.0));
    scene([
        Body::robot("lower", bar(-1.0, -0.1, 1.0, 0.1), still),
        Body::robot("upper", bar(-1.0, -0.1, 1.0, 0.1), sliding),
    ])
}

fn parts(c: &mut Criterion) {
    let opts = CheckOptions::default();
    let cases = [
        ("far", "20-parts", far(false)),
        ("far", "hulls", far(true)),
        ("close", "20x20-parts", close()),
        ("close", "convex-pair", convex_pair()),
    ];
    for (group, name, scene) in &cases {
        let r = check(scene, &opts);
        println!(
            "parts/{group}/{name}: collision {}, certified {}, {} intervals, {} narrow-phase calls",
            r.collision, r.certified, r.stats.intervals, r.stats.narrow_phase_calls
        );
        assert!(
            !r.collision && r.certified,
            "every case is free by construction"
        );
    }
    for group_name in ["far", "close"] {
        let mut group = c.benchmark_group(format!("parts/{group_name}"));
        for (_, name, scene) in cases.iter().filter(|(g, _, _)| *g == group_name) {
            group.bench_function(*name, |b| b.iter(|| check(scene, &opts).collision));
        }
        group.finish();
    }
}

criterion_group!(benches, parts);
criterion_main!(benches);
