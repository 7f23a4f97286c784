//! `solve` on arm cells (issue 22, item 8): the shipped SCARA cell, and generated cells of
//! 4 arms × 40 tasks and 8 arms × 120 tasks (`generate --kind scara --seed 1`): solved
//! whole with the default options, and the generated ones with a budget of 200 schedules
//! checked (`--search-nodes 200`). Both searches end by their own (the queue runs dry)
//! before any time limit, so the answers are the same on every machine. Every answer is
//! certified collision-free before it is timed.

use criterion::{criterion_group, criterion_main, Criterion};
use std::path::Path;
use std::time::Duration;
use workcell::cell::{load_cell, parse_cell, Cell};
use workcell::generate::{generate_scara_cell, ScaraRequest};
use workcell::wcp::{self, SolveOptions};

fn solve(cell: &Cell, opts: &SolveOptions) -> f64 {
    let prepared = wcp::prepare(cell, opts, &()).unwrap();
    let solved = wcp::solve(cell, &prepared, opts, &()).unwrap();
    assert!(solved.collision_free && solved.report.verdict().is_certified_free());
    solved.schedule.makespan
}

fn arm_cells(c: &mut Criterion) {
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("cells/scara-cell.json");
    let mut cells = vec![("scara-cell".to_owned(), load_cell(&shipped).unwrap().cell)];
    for (arms, tasks) in [(4, 40), (8, 120)] {
        let doc = generate_scara_cell(&ScaraRequest { arms, tasks }, 1, 0).unwrap();
        let name = format!("scara-{arms}x{tasks}-1-0");
        let cell = parse_cell(&doc.to_string(), name.as_ref()).unwrap().cell;
        cells.push((name, cell));
    }
    let budget = SolveOptions {
        search: wcp::SearchOptions {
            max_nodes: 200,
            ..Default::default()
        },
        ..Default::default()
    };
    for (name, cell) in &cells {
        let mut group = c.benchmark_group(format!("arm-solve/{name}"));
        if name != "scara-cell" {
            group
                .sample_size(10)
                .measurement_time(Duration::from_secs(60));
        }
        group.bench_function("whole", |b| {
            b.iter(|| solve(cell, &SolveOptions::default()))
        });
        if name != "scara-cell" {
            group.bench_function("200-schedules", |b| b.iter(|| solve(cell, &budget)));
        }
        group.finish();
    }
}

criterion_group!(benches, arm_cells);
criterion_main!(benches);
