//! Reading scene files: `parse_scene` (validated scene, errors naming file, body and field)
//! against a syntax-only scan of the same bytes (`serde::de::IgnoredAny`: JSON read, nothing
//! kept), on the vendored corpus (48 scenes, one after the other) and on the generated hall
//! of 1000 robots (100 samples each) written as `solve --export-scene` writes scenes.
//!
//! `cargo bench --bench load`, then `criterion_table load/ --ratio parse/syntax`.

use criterion::{criterion_group, criterion_main, Criterion};
use serde::de::IgnoredAny;
use std::hint::black_box;
use std::path::Path;
use workcell::cell::{parse_scene, scene_document};
use workcell::generate::{generate_scene, Kind};

fn corpus() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect()
}

fn hall(robots: usize) -> String {
    let scene = generate_scene(Kind::Hall, 1, 0, robots);
    serde_json::to_string_pretty(&scene_document(&scene)).unwrap()
}

fn bench_texts(c: &mut Criterion, name: &str, texts: &[String]) {
    let file = Path::new("bench.json");
    let bytes: usize = texts.iter().map(String::len).sum();
    eprintln!("{name}: {} documents, {bytes} bytes", texts.len());
    let mut group = c.benchmark_group(format!("load/{name}"));
    group.throughput(criterion::Throughput::Bytes(bytes as u64));
    group.bench_function("parse", |b| {
        b.iter(|| {
            texts
                .iter()
                .map(|t| parse_scene(black_box(t), file).unwrap().scene.bodies.len())
                .sum::<usize>()
        })
    });
    group.bench_function("syntax", |b| {
        b.iter(|| {
            for t in texts {
                let _: IgnoredAny = serde_json::from_str(black_box(t)).unwrap();
            }
        })
    });
    group.finish();
}

fn loading(c: &mut Criterion) {
    bench_texts(c, "corpus-48", &corpus());
    bench_texts(c, "hall-1000", &[hall(1000)]);
}

criterion_group!(benches, loading);
criterion_main!(benches);
