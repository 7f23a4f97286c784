//! Reading scene files: `parse_scene` (validated scene, errors naming file, body and field)
//! against a syntax-only scan of the same bytes (`serde::de::IgnoredAny`: JSON read, nothing
//! kept), on the vendored corpus (48 scenes, one after the other) and on the generated hall
//! of 1000 robots (100 samples each) written as `solve --export-scene` writes scenes.
//!
//! `cargo bench --bench load`, then `criterion_table load/ --ratio parse/syntax`; before
//! measuring, the bench prints the ratio measured with the two interleaved.

use criterion::{criterion_group, criterion_main, Criterion};
use serde::de::IgnoredAny;
use std::hint::black_box;
use std::path::Path;
use std::time::{Duration, Instant};
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

fn parse_all(texts: &[String]) -> usize {
    let file = Path::new("bench.json");
    texts
        .iter()
        .map(|t| parse_scene(black_box(t), file).unwrap().scene.bodies.len())
        .sum()
}

fn scan_all(texts: &[String]) {
    for t in texts {
        let _: IgnoredAny = serde_json::from_str(black_box(t)).unwrap();
    }
}

/// parse / syntax from 31 rounds that time one then the other, at most 0.2 s each: the
/// median ratio of one round's two times. Criterion times all of one before the other, and
/// this machine's speed drifts between them by as much as their ratio is to be told apart.
fn interleaved_ratio(texts: &[String]) -> f64 {
    let time = |f: &dyn Fn()| {
        let (start, mut runs) = (Instant::now(), 0u32);
        while runs == 0 || start.elapsed() < Duration::from_millis(200) {
            f();
            runs += 1;
        }
        start.elapsed().as_secs_f64() / f64::from(runs)
    };
    let mut ratios: Vec<f64> = (0..31)
        .map(|_| {
            let parse = time(&|| {
                black_box(parse_all(texts));
            });
            parse / time(&|| scan_all(texts))
        })
        .collect();
    ratios.sort_by(f64::total_cmp);
    ratios[ratios.len() / 2]
}

fn bench_texts(c: &mut Criterion, name: &str, texts: &[String]) {
    let bytes: usize = texts.iter().map(String::len).sum();
    eprintln!("{name}: {} documents, {bytes} bytes", texts.len());
    eprintln!(
        "{name}: parse / syntax, interleaved, median of 31 rounds: {:.2}",
        interleaved_ratio(texts)
    );
    let mut group = c.benchmark_group(format!("load/{name}"));
    group.throughput(criterion::Throughput::Bytes(bytes as u64));
    group.bench_function("parse", |b| b.iter(|| parse_all(texts)));
    group.bench_function("syntax", |b| b.iter(|| scan_all(texts)));
    group.finish();
}

fn loading(c: &mut Criterion) {
    bench_texts(c, "corpus-48", &corpus());
    bench_texts(c, "hall-1000", &[hall(1000)]);
}

criterion_group!(benches, loading);
criterion_main!(benches);
