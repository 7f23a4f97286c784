//! Halls of N robots (`generate_scene(Kind::Hall, ..)`, 100 samples each): the broad phase
//! alone and the whole check, each on 1 and 2 threads.
//!
//! `hall-N` is the generator's hall: its crossing lanes make contacts early in the horizon,
//! and once the earliest is known the other pairs stop there, so its check covers the
//! horizon only up to that contact. `hall-free-N` is the same hall with the robot of each first contact removed
//! until none is left: there every candidate pair is checked over the whole horizon. The
//! scenes' pair counts and verdicts are printed once, before measuring. `arm-hall-N` and
//! `arm-hall-free-N` are the same for N arms and N rigid robots (`Kind::ArmHall`).

use criterion::{criterion_group, criterion_main, Criterion};
use rayon::{ThreadPool, ThreadPoolBuilder};
use std::time::Duration;
use workcell::collision::{candidate_pairs, check, CheckOptions, Scene};
use workcell::generate::{generate_scene, Kind};

const SEED: u64 = 1;

/// Removes the robot named first in each first contact until the scene is free.
fn thinned(mut scene: Scene) -> Scene {
    while let Some(c) = check(&scene, &CheckOptions::default()).first_contact {
        scene.bodies.retain(|b| b.name != c.bodies[0]);
    }
    scene
}

fn describe(name: &str, scene: &Scene) {
    let r = check(scene, &CheckOptions::default());
    let robots = scene.bodies.iter().filter(|b| b.is_robot()).count();
    let verdict = match &r.first_contact {
        Some(c) => format!(
            "collides at t = {} ({} - {})",
            c.time, c.bodies[0], c.bodies[1]
        ),
        None => "free".into(),
    };
    eprintln!(
        "{name}: {robots} robots, {} bodies; {} pairs checked, {} pruned; {verdict}; {} intervals",
        scene.bodies.len(),
        r.pairs,
        r.pairs_pruned,
        r.stats.intervals
    );
}

fn bench_checks(c: &mut Criterion, name: &str, scene: &Scene, pools: &[(usize, ThreadPool)]) {
    let opts = CheckOptions::default();
    let mut group = c.benchmark_group(name);
    group
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    for (k, pool) in pools {
        group.bench_function(format!("broad-phase-{k}-thread"), |b| {
            b.iter(|| pool.install(|| candidate_pairs(scene, scene.delta)))
        });
        group.bench_function(format!("check-{k}-thread"), |b| {
            b.iter(|| pool.install(|| check(scene, &opts)))
        });
    }
    group.finish();
}

fn halls(c: &mut Criterion) {
    let pools: Vec<(usize, ThreadPool)> = [1, 2]
        .map(|k| (k, ThreadPoolBuilder::new().num_threads(k).build().unwrap()))
        .into();
    let scenes: Vec<(String, Scene)> = [10, 100, 1000]
        .into_iter()
        .flat_map(|n| {
            let hall = generate_scene(Kind::Hall, SEED, 0, n);
            [
                (format!("hall-free-{n}"), thinned(hall.clone())),
                (format!("hall-{n}"), hall),
            ]
        })
        .chain([100, 1000].into_iter().flat_map(|n| {
            let hall = generate_scene(Kind::ArmHall, SEED, 0, n);
            [
                (format!("arm-hall-free-{n}"), thinned(hall.clone())),
                (format!("arm-hall-{n}"), hall),
            ]
        }))
        .collect();
    for (name, scene) in &scenes {
        describe(name, scene);
    }
    for (name, scene) in &scenes {
        bench_checks(c, name, scene, &pools);
    }
}

criterion_group!(benches, halls);
criterion_main!(benches);
