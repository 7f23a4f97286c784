//! Whole checks of the shipped scenes (cells/*.json) and of the vendored corpus.

use criterion::{criterion_group, criterion_main, Criterion};
use std::path::Path;
use workcell::cell::load_scene;
use workcell::collision::{check, CheckOptions};

fn scenes(dir: &Path) -> Vec<(String, workcell::collision::Scene)> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        // `*-cell.json` are cells for `solve`, not scenes.
        .filter(|p| !p.to_string_lossy().ends_with("-cell.json"))
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|p| {
            (
                p.file_stem().unwrap().to_string_lossy().into_owned(),
                load_scene(&p).unwrap().scene,
            )
        })
        .collect()
}

fn shipped(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let opts = CheckOptions::default();
    let mut group = c.benchmark_group("check");
    for (name, scene) in scenes(&root.join("cells")) {
        group.bench_function(name, |b| b.iter(|| check(&scene, &opts)));
    }
    let corpus = scenes(&root.join("tests/corpus"));
    group.bench_function("corpus-48", |b| {
        b.iter(|| {
            corpus
                .iter()
                .map(|(_, s)| check(s, &opts).stats.intervals)
                .sum::<u64>()
        })
    });
    group.finish();
}

criterion_group!(benches, shipped);
criterion_main!(benches);
