//! `solve` stage by stage on the shipped cells: preparing (bounds, and the moves planned
//! before sequencing), sequencing (collision-blind best schedule, on a fresh store of moves
//! each time, so that its planning counts), checking (the final schedule, all pairs), and
//! the whole solve.

use criterion::{criterion_group, criterion_main, Criterion};
use std::path::Path;
use std::time::Duration;
use workcell::cell::{load_cell, Cell};
use workcell::collision::check;
use workcell::wcp::{self, SolveOptions};

const CELLS: [&str; 4] = [
    "paper-cell",
    "feedback-cell",
    "four-robots-cell",
    "hall-cell",
];

fn cell(name: &str) -> Cell {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("cells")
        .join(format!("{name}.json"));
    load_cell(&path).unwrap().cell
}

fn stages(c: &mut Criterion) {
    let opts = SolveOptions::default();
    for name in CELLS {
        let cell = cell(name);
        let prepared = wcp::prepare(&cell, &opts, &()).unwrap();
        let solved = wcp::solve(&cell, &prepared, &opts, &()).unwrap();
        let scene = solved.schedule.scene(&cell);
        let mut group = c.benchmark_group(format!("solve/{name}"));
        if name == "hall-cell" {
            group
                .sample_size(10)
                .measurement_time(Duration::from_secs(20));
        }
        group.bench_function("preparing", |b| {
            b.iter(|| wcp::prepare(&cell, &opts, &()).unwrap().moves.planned())
        });
        group.bench_function("sequencing", |b| {
            b.iter_batched(
                || wcp::prepare(&cell, &opts, &()).unwrap(),
                |prepared| {
                    wcp::sequence(&cell, &prepared, &[], &opts)
                        .unwrap()
                        .makespan
                },
                criterion::BatchSize::LargeInput,
            )
        });
        group.bench_function("checking", |b| {
            b.iter(|| check(&scene, &opts.check).collision)
        });
        group.bench_function("whole", |b| {
            b.iter(|| {
                let prepared = wcp::prepare(&cell, &opts, &()).unwrap();
                wcp::solve(&cell, &prepared, &opts, &())
                    .unwrap()
                    .schedule
                    .makespan
            })
        });
        group.finish();
    }
}

criterion_group!(benches, stages);
criterion_main!(benches);
