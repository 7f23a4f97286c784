//! The command line of large cells: `generate --kind cell`, `solve --time-limit`,
//! `--progress`, `--planning` and the exact flags of `--export-graph`.

use crate::common::{temp_dir_absent, workcell};
use std::path::{Path, PathBuf};

fn generate(dir: &Path, robots: &str, tasks: &str, fixtures: &str, seed: &str) -> PathBuf {
    let out = workcell(&[
        "generate",
        "--kind",
        "cell",
        "--robots",
        robots,
        "--tasks",
        tasks,
        "--fixtures",
        fixtures,
        "--seed",
        seed,
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let file = dir.join(format!(
        "cell-{robots}r-{tasks}t-{fixtures}f-{seed}-0-cell.json"
    ));
    assert!(String::from_utf8_lossy(&out.stdout).contains(file.to_str().unwrap()));
    file
}

#[test]
fn generated_cells_are_deterministic_and_solvable() {
    let dir = temp_dir_absent("cli-scale", "generate");
    let a = std::fs::read_to_string(generate(&dir, "3", "12", "2", "5")).unwrap();
    let again = temp_dir_absent("cli-scale", "generate-again");
    let b = std::fs::read_to_string(generate(&again, "3", "12", "2", "5")).unwrap();
    assert_eq!(a, b);
    let other = std::fs::read_to_string(generate(&again, "3", "12", "2", "6")).unwrap();
    assert_ne!(a, other);
    let doc: serde_json::Value = serde_json::from_str(&a).unwrap();
    assert_eq!(doc["robots"].as_array().unwrap().len(), 3);
    assert_eq!(doc["tasks"].as_array().unwrap().len(), 12);
    assert_eq!(doc["obstacles"].as_array().unwrap().len(), 2);
    let solved = workcell(&[
        "solve",
        "--json",
        dir.join("cell-3r-12t-2f-5-0-cell.json").to_str().unwrap(),
    ]);
    assert!(matches!(solved.status.code(), Some(0 | 1)), "{solved:?}");
}

#[test]
fn impossible_cell_requests_are_refused() {
    let dir = temp_dir_absent("cli-scale", "refused");
    let d = dir.to_str().unwrap();
    for args in [
        vec![
            "generate", "--kind", "cell", "--robots", "2", "--seed", "1", "--out", d,
        ],
        vec![
            "generate", "--kind", "cell", "--robots", "2000", "--tasks", "5", "--seed", "1",
            "--out", d,
        ],
        vec![
            "generate",
            "--kind",
            "cell",
            "--robots",
            "2",
            "--tasks",
            "5",
            "--fixtures",
            "20000",
            "--seed",
            "1",
            "--out",
            d,
        ],
        vec![
            "generate", "--kind", "pairs", "--tasks", "5", "--seed", "1", "--out", d,
        ],
    ] {
        let out = workcell(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {out:?}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("error:"),
            "{out:?}"
        );
    }
    assert!(!dir.exists(), "nothing is written for a refused request");
}

#[test]
fn time_limit_progress_and_exported_graph() {
    let dir = temp_dir_absent("cli-scale", "solve");
    let cell = generate(&dir, "4", "40", "3", "2");
    let graph = dir.join("graph.json");
    let out = workcell(&[
        "solve",
        "--json",
        "--progress",
        "--planning",
        "lazy",
        "--time-limit",
        "5",
        "--export-graph",
        graph.to_str().unwrap(),
        cell.to_str().unwrap(),
    ]);
    assert!(matches!(out.status.code(), Some(0 | 1)), "{out:?}");
    let result: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(result["makespan"].as_f64().unwrap() > 0.0);
    // At least the last line, whatever the speed of the machine.
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr
            .lines()
            .any(|l| l.starts_with("progress: ") && l.contains("best makespan")),
        "{stderr}"
    );
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&graph).unwrap()).unwrap();
    let arcs = doc["arcs"].as_array().unwrap();
    let exact = arcs.iter().filter(|a| a["exact"] == true).count();
    assert!(exact > 0 && exact < arcs.len(), "{exact} of {}", arcs.len());
    // Planned whole, every arc is exact.
    let out = workcell(&[
        "solve",
        "--planning",
        "all",
        "--export-graph",
        graph.to_str().unwrap(),
        cell.to_str().unwrap(),
    ]);
    assert!(matches!(out.status.code(), Some(0 | 1)), "{out:?}");
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&graph).unwrap()).unwrap();
    assert!(doc["arcs"]
        .as_array()
        .unwrap()
        .iter()
        .all(|a| a["exact"] == true));
}

/// Once a schedule is collision-free, `--progress` reports the best such makespan (the
/// answer's, at the end), not the sequencer's unchecked plans.
#[test]
fn progress_reports_the_best_collision_free_makespan() {
    let cell = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    let out = workcell(&["solve", "--json", "--progress", cell]);
    assert_eq!(out.status.code(), Some(0));
    let result: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let makespan = result["makespan"].as_f64().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let last = stderr
        .lines()
        .rfind(|l| l.starts_with("progress: "))
        .unwrap();
    let (best, bound) = last
        .split_once(", lower bound ")
        .expect("the bound, after planning");
    assert!(
        best.ends_with(&format!("best makespan {makespan:.3}, collision-free")),
        "{stderr}"
    );
    assert!(bound.parse::<f64>().unwrap() <= makespan, "{stderr}");
    // The blind plan (shorter, colliding) is not reported as the best any more.
    assert!(result["blind_makespan"].as_f64().unwrap() < makespan);
}

/// A time limit that runs out while the moves are planned: exit 1 at once, saying how far
/// planning got, and no output file replaced (there is no schedule to draw).
#[test]
fn a_time_limit_spent_in_planning_is_reported_not_overrun() {
    let dir = temp_dir_absent("cli-scale", "planning-limit");
    let cell = generate(&dir, "2", "30", "4", "1");
    let svg = dir.join("kept.svg");
    std::fs::write(&svg, "before").unwrap();
    for json in [false, true] {
        let mut args = vec!["solve", cell.to_str().unwrap(), "--time-limit", "1e-9"];
        args.extend(["--svg", svg.to_str().unwrap()]);
        if json {
            args.push("--json");
        }
        let out = workcell(&args);
        assert_eq!(out.status.code(), Some(1), "{out:?}");
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            stdout.contains("time limit ran out while planning"),
            "{stdout}"
        );
        if json {
            let doc: serde_json::Value = serde_json::from_str(&stdout).unwrap();
            assert_eq!(doc["collision_free"], false);
        } else {
            assert!(
                stdout.contains("NO schedule: ") && stdout.contains(" planned and certified"),
                "{stdout}"
            );
        }
        assert_eq!(std::fs::read_to_string(&svg).unwrap(), "before");
    }
}
