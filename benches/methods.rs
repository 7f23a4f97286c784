//! Pair checks: every method and the parry peer on the same generated scenes, kind by kind.
//!
//! `cargo bench --features parry-peer --bench methods`. Each measurement is one check of each
//! of the kind's ten scenes (seed 1, halls of 10 robots), so time per check is a tenth of it.

use criterion::{criterion_group, criterion_main, Criterion};
use workcell::collision::{candidate_pairs, check, check_with_parry, CheckOptions, Method, Scene};
use workcell::generate::{generate_scene, Kind};

fn methods(c: &mut Criterion) {
    let ours = [
        Method::DEFAULT,
        "adaptive-paper".parse().unwrap(),
        Method::Advance,
        Method::Sampled { step: 0.01 },
    ];
    for kind in Kind::ALL {
        let scenes: Vec<Scene> = (0..10).map(|k| generate_scene(kind, 1, k, 10)).collect();
        let mut group = c.benchmark_group(format!("methods/{}", kind.name()));
        for method in ours {
            let opts = CheckOptions {
                method,
                ..CheckOptions::default()
            };
            group.bench_function(method.to_string(), |b| {
                b.iter(|| scenes.iter().filter(|s| check(s, &opts).collision).count())
            });
        }
        // parry has no motion for a linkage: the peer would only count unsupported pairs.
        if Kind::ARMS.contains(&kind) {
            group.finish();
            continue;
        }
        // The same broad phase for both: the peer is compared pair check against pair check.
        let pairs: Vec<_> = scenes.iter().map(|s| candidate_pairs(s, s.delta)).collect();
        group.bench_function("parry", |b| {
            b.iter(|| {
                scenes
                    .iter()
                    .zip(&pairs)
                    .filter(|(s, p)| check_with_parry(s, p, s.delta).first_contact.is_some())
                    .count()
            })
        });
        group.finish();
    }
}

/// The scenes of the shared corpus whose bodies overlap at the start: a check ends at its
/// first evaluation of each pair, so the per-pair setup and the thread hand-over are all it
/// costs (issue 14, item 4).
fn start_overlap(c: &mut Criterion) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    let opts = CheckOptions::default();
    let scenes: Vec<Scene> = files
        .iter()
        .map(|p| workcell::cell::load_scene(p).unwrap().scene)
        .filter(|s| {
            let r = check(s, &opts);
            r.first_contact.is_some_and(|c| c.time == r.horizon[0])
        })
        .collect();
    let pairs: Vec<_> = scenes.iter().map(|s| candidate_pairs(s, s.delta)).collect();
    let mut group = c.benchmark_group(format!("start-overlap/{}-scenes", scenes.len()));
    group.bench_function("adaptive", |b| {
        b.iter(|| scenes.iter().filter(|s| check(s, &opts).collision).count())
    });
    group.bench_function("parry", |b| {
        b.iter(|| {
            scenes
                .iter()
                .zip(&pairs)
                .filter(|(s, p)| check_with_parry(s, p, s.delta).first_contact.is_some())
                .count()
        })
    });
    group.finish();
}

criterion_group!(benches, methods, start_overlap);
criterion_main!(benches);
