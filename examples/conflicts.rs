//! The feedback loop on the conflict cells, as the README's table shows it:
//!
//! ```sh
//! cargo run --release --example conflicts -- [--seed S] [--count K] [--family NAME]... [--greedy]
//!     [--remedies LIST]
//! ```
//!
//! For every family of `workcell generate --kind conflict` (or those named) and cells
//! 0..K of seed S (default 1 and 5), solves each cell with the search and, with `--greedy`,
//! with the greedy loop too, and prints a Markdown table: robots, tasks, the collision-blind
//! makespan (a lower bound of every collision-free makespan when it is proven optimal,
//! marked *), the makespan found and its overhead, the rounds along the answer's branch and
//! the schedules checked, and the wall time of the solve (planning included). The last
//! rows give each family's mean overhead over the cells solved and, with `--greedy`, over the
//! cells both feedbacks solve. `--remedies` names the search's remedies as `workcell solve
//! --remedies` does (default: its default set).

use std::path::Path;
use std::time::Instant;
use workcell::cell::parse_cell;
use workcell::generate::{generate_conflict_cell, ConflictKind};
use workcell::wcp::{self, Feedback, Remedies, SearchOptions, SolveOptions};

struct Row {
    family: &'static str,
    k: u64,
    robots: usize,
    tasks: usize,
    blind: f64,
    optimal: bool,
    runs: Vec<Run>,
}

struct Run {
    makespan: Option<f64>,
    rounds: usize,
    nodes: usize,
    seconds: f64,
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let seed: u64 = value("--seed").map_or(1, |s| s.parse().expect("--seed S"));
    let count: u64 = value("--count").map_or(5, |s| s.parse().expect("--count K"));
    let named: Vec<ConflictKind> = args
        .windows(2)
        .filter(|w| w[0] == "--family")
        .map(|w| ConflictKind::from_name(&w[1]).expect("a family of `generate --kind conflict`"))
        .collect();
    let families = if named.is_empty() {
        ConflictKind::ALL.to_vec()
    } else {
        named
    };
    let greedy = args.iter().any(|a| a == "--greedy");
    let remedies = value("--remedies").map_or_else(Remedies::default, |list| {
        Remedies::of_names(list.split(',')).expect("--remedies LIST")
    });
    let feedbacks: Vec<Feedback> = if greedy {
        vec![Feedback::Search, Feedback::Greedy]
    } else {
        vec![Feedback::Search]
    };
    let mut rows = Vec::new();
    for &family in &families {
        for k in 0..count {
            let text = generate_conflict_cell(family, seed, k).to_string();
            let cell = parse_cell(&text, Path::new(family.name()))
                .expect("generated cells are valid")
                .cell;
            let mut row = Row {
                family: family.name(),
                k,
                robots: cell.robots.len(),
                tasks: cell.tasks.len(),
                blind: 0.0,
                optimal: false,
                runs: Vec::new(),
            };
            for &feedback in &feedbacks {
                let defaults = SolveOptions::default();
                let opts = SolveOptions {
                    feedback,
                    search: SearchOptions {
                        remedies,
                        ..defaults.search
                    },
                    ..defaults
                };
                let clock = Instant::now();
                let prepared = wcp::prepare(&cell, &opts, &()).expect("a valid cell");
                let solved = wcp::solve(&cell, &prepared, &opts, &()).expect("a valid cell");
                row.blind = solved.blind_makespan;
                row.optimal = solved.blind_optimal;
                row.runs.push(Run {
                    makespan: solved.collision_free.then_some(solved.schedule.makespan),
                    rounds: solved.iterations.len(),
                    nodes: solved.nodes,
                    seconds: clock.elapsed().as_secs_f64(),
                });
            }
            eprintln!("{} {k} done", family.name());
            rows.push(row);
        }
    }
    print(&rows, &feedbacks);
}

fn print(rows: &[Row], feedbacks: &[Feedback]) {
    let name = |f: &Feedback| match f {
        Feedback::Search => "search",
        Feedback::Greedy => "greedy",
    };
    let mut head = "| cell | robots | tasks | blind |".to_owned();
    let mut rule = "|---|---:|---:|---:|".to_owned();
    for f in feedbacks {
        let n = name(f);
        head += &format!(" {n} | overhead | rounds / checked | s |");
        rule += "---:|---:|---:|---:|";
    }
    println!("{head}\n{rule}");
    let overhead = |run: &Run, blind: f64| run.makespan.map(|m| 100.0 * (m / blind - 1.0));
    for row in rows {
        let star = if row.optimal { "*" } else { "" };
        let mut line = format!(
            "| {}-{} | {} | {} | {:.2}{star} |",
            row.family, row.k, row.robots, row.tasks, row.blind
        );
        for run in &row.runs {
            match (run.makespan, overhead(run, row.blind)) {
                (Some(m), Some(o)) => {
                    let o = if o.abs() < 0.05 { 0.0 } else { o };
                    line += &format!(" {m:.2} | {o:.1} % |")
                }
                _ => line += " not solved | |",
            }
            line += &format!(" {} / {} | {:.2} |", run.rounds, run.nodes, run.seconds);
        }
        println!("{line}");
    }
    println!();
    let pct = |v: f64| format!("{:.1} %", if v.abs() < 0.05 { 0.0 } else { v });
    let mean = |v: &[f64]| (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64);
    let mut head = "| family |".to_owned();
    let mut rule = "|---|".to_owned();
    for f in feedbacks {
        head += &format!(" {} solved | mean overhead |", name(f));
        rule += "---:|---:|";
    }
    if feedbacks.len() > 1 {
        head += " mean overhead where all solve |";
        rule += "---:|";
    }
    println!("{head}\n{rule}");
    let mut families: Vec<&str> = rows.iter().map(|r| r.family).collect();
    families.dedup();
    families.push("all");
    for family in families {
        let of: Vec<&Row> = rows
            .iter()
            .filter(|r| family == "all" || r.family == family)
            .collect();
        let mut line = format!("| {family} |");
        for i in 0..feedbacks.len() {
            let solved: Vec<f64> = of
                .iter()
                .filter_map(|r| overhead(&r.runs[i], r.blind))
                .collect();
            let m = mean(&solved).map_or("–".to_owned(), pct);
            line += &format!(" {} of {} | {m} |", solved.len(), of.len());
        }
        if feedbacks.len() > 1 {
            let all: Vec<&&Row> = of
                .iter()
                .filter(|r| r.runs.iter().all(|run| run.makespan.is_some()))
                .collect();
            let each: Vec<String> = (0..feedbacks.len())
                .map(|i| {
                    let v: Vec<f64> = all
                        .iter()
                        .filter_map(|r| overhead(&r.runs[i], r.blind))
                        .collect();
                    mean(&v).map_or("–".to_owned(), pct)
                })
                .collect();
            line += &format!(" {} ({} cells) |", each.join(" vs "), all.len());
        }
        println!("{line}");
    }
}
