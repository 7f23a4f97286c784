//! Arms (contract section 6): the two-arm SCARA scenes one by one, and every method on the
//! corpus of generated arm scenes beside the tests' exact reference.
//!
//! `cargo bench --bench arms`. Before measuring it prints, for the corpus (the seven arm kinds,
//! seeds 1 to 3, ten scenes each, halls of 4 arms and 4 robots), each method's misses and invented
//! contacts against the reference, and the largest step of `sampled` with no miss; then it
//! times:
//! - `arms/two-arm-scene/k`: `check` of scene k of `generate --kind arms --seed 1` (two 2-link
//!   SCARA arms, 100 samples each); `cargo run --release --example criterion_table --
//!   arms/two-arm-scene` lists the ten medians;
//! - `arms/corpus/<method>`: one pass over the corpus with each method (`adaptive`,
//!   `adaptive-paper`, `sampled:<h>` at the no-miss step, and the reference).

use criterion::{criterion_group, criterion_main, Criterion};
use std::time::Duration;
use workcell::collision::{check, CheckOptions, Method, Scene};
use workcell::generate::{generate_scene, Kind};

#[allow(dead_code)]
#[path = "../tests/integration/common/arm_reference.rs"]
mod arm_reference;
#[allow(dead_code)]
#[path = "../tests/integration/common/oracle.rs"]
mod oracle;

use arm_reference::{scene_first_contact, SceneSpec};
#[allow(unused_imports)] // what `arm_reference` reads through `super::`
use oracle::{advance_to_contact, exact_distance, place, pose_at, Shape};

/// Steps tried for `sampled`, coarse to fine.
const STEPS: [f64; 10] = [0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001, 5e-4, 2e-4, 1e-4];

fn corpus() -> Vec<(String, Scene)> {
    Kind::ARMS
        .iter()
        .flat_map(|&kind| {
            (1..=3).flat_map(move |seed| {
                (0..10).map(move |k| {
                    let name = format!("{}-{seed}-{k}", kind.name());
                    (name, generate_scene(kind, seed, k, 4))
                })
            })
        })
        .collect()
}

/// The reference's verdict on each scene: `Some(contact time)`, or `None` when free. A graze
/// it cannot decide is left out of the counts (`None` in the outer option).
fn reference(scenes: &[(String, Scene)]) -> Vec<Option<Option<f64>>> {
    scenes
        .iter()
        .map(|(_, s)| {
            let tol = CheckOptions::default().time_tol_for(s.horizon());
            let spec = SceneSpec::of_scene(s);
            scene_first_contact(&spec, s.delta, tol / 8.0)
                .ok()
                .map(|c| c.map(|(_, hit, _)| hit))
        })
        .collect()
}

/// Misses and invented contacts of `method` against the reference.
fn score(
    scenes: &[(String, Scene)],
    truth: &[Option<Option<f64>>],
    method: Method,
) -> (usize, usize) {
    let opts = CheckOptions {
        method,
        ..CheckOptions::default()
    };
    let (mut missed, mut invented) = (0, 0);
    for ((_, s), t) in scenes.iter().zip(truth) {
        let Some(t) = t else { continue };
        let found = check(s, &opts).collision;
        missed += usize::from(t.is_some() && !found);
        invented += usize::from(t.is_none() && found);
    }
    (missed, invented)
}

fn arms(c: &mut Criterion) {
    let scenes = corpus();
    let truth = reference(&scenes);
    let decided = truth.iter().flatten().count();
    let hits = truth.iter().flatten().filter(|t| t.is_some()).count();
    eprintln!(
        "corpus: {} scenes, {decided} decided by the reference ({hits} collide)",
        scenes.len()
    );
    let no_miss = STEPS
        .into_iter()
        .find(|&step| score(&scenes, &truth, Method::Sampled { step }).0 == 0);
    let mut methods = vec![Method::DEFAULT, "adaptive-paper".parse().unwrap()];
    methods.extend(STEPS.iter().map(|&step| Method::Sampled { step }));
    eprintln!("| method | missed | invented |");
    for &m in &methods {
        let (missed, invented) = score(&scenes, &truth, m);
        eprintln!("| {m} | {missed} | {invented} |");
    }
    match no_miss {
        Some(step) => eprintln!("sampled needs a step of {step} for no miss"),
        None => eprintln!("sampled misses at every step down to {}", STEPS[9]),
    }

    let opts = CheckOptions::default();
    let mut group = c.benchmark_group("arms/two-arm-scene");
    group
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2));
    for (k, scene) in (0..10).map(|k| (k, generate_scene(Kind::Arms, 1, k, 0))) {
        group.bench_function(k.to_string(), |b| b.iter(|| check(&scene, &opts).collision));
    }
    group.finish();

    let mut group = c.benchmark_group("arms/corpus");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    let mut timed = vec![Method::DEFAULT, "adaptive-paper".parse().unwrap()];
    timed.extend(no_miss.map(|step| Method::Sampled { step }));
    for method in timed {
        let opts = CheckOptions {
            method,
            ..CheckOptions::default()
        };
        group.bench_function(method.to_string(), |b| {
            b.iter(|| {
                scenes
                    .iter()
                    .filter(|(_, s)| check(s, &opts).collision)
                    .count()
            })
        });
    }
    group.bench_function("reference", |b| b.iter(|| reference(&scenes)));
    group.finish();
}

criterion_group!(benches, arms);
criterion_main!(benches);
