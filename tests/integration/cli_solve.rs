//! `workcell solve` and `workcell evaluate` as a user meets them: exit statuses, the
//! contract's JSON, the exports, and errors that name the file, the body and the field.

use crate::common::{shipped, temp_dir_made, workcell};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn json(o: &Output) -> Value {
    serde_json::from_slice(&o.stdout).expect("stdout is JSON")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn solve_prints_the_contract_json_and_writes_every_export() {
    let (scene, graph, svg) = (
        temp_dir_made("solve", "exports").join("scene.json"),
        temp_dir_made("solve", "exports").join("graph.json"),
        temp_dir_made("solve", "exports").join("cell.svg"),
    );
    let out = workcell(&[
        "solve",
        &shipped("paper-cell.json"),
        "--json",
        "--export-scene",
        scene.to_str().unwrap(),
        "--export-graph",
        graph.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(
        out.stderr.is_empty(),
        "no progress bar with --json: {}",
        text(&out.stderr)
    );
    let result = json(&out);
    assert_eq!(result["collision_free"], true);
    assert!(result["makespan"].as_f64().unwrap() > 0.0);
    assert!(result["iterations"].as_u64().unwrap() >= 1);
    let sequences = result["sequences"].as_object().unwrap();
    let tasks: usize = sequences
        .values()
        .map(|s| s.as_array().unwrap().len())
        .sum();
    assert_eq!((sequences.len(), tasks), (2, 12));

    // The exported scene is what `check` certifies, up to the makespan.
    let checked = workcell(&["check", scene.to_str().unwrap(), "--json"]);
    assert_eq!(checked.status.code(), Some(0), "{}", text(&checked.stdout));
    let report = json(&checked);
    assert_eq!(report["safe_until"], result["makespan"]);

    let graph: Value = serde_json::from_str(&std::fs::read_to_string(&graph).unwrap()).unwrap();
    let nodes = graph["nodes"].as_array().unwrap();
    assert_eq!(nodes.len(), 14);
    assert_eq!(nodes.iter().filter(|n| n["kind"] == "home").count(), 2);
    let arcs = graph["arcs"].as_array().unwrap();
    // Both robots may do all 12 tasks: 13·12 ordered pairs each.
    assert_eq!(arcs.len(), 2 * 13 * 12);
    assert!(arcs.iter().all(|a| a["travel_time"].as_f64().unwrap() > 0.0
        && a["robot"].is_string()
        && a["from"].is_string()
        && a["to"].is_string()));

    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.starts_with("<svg") && picture.contains("weld-12"));
}

#[test]
fn solve_reports_the_feedback_and_evaluate_rejects_the_blind_schedule() {
    let cell = shipped("feedback-cell.json");
    let out = workcell(&["solve", &cell, "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let result = json(&out);
    let rounds = result["feedback"].as_array().unwrap();
    assert!(rounds[0]["collision"].is_object());
    assert!(rounds.iter().any(|r| r["remedy"] == "resequence"));
    assert_eq!(rounds.len() as u64, result["iterations"].as_u64().unwrap());

    // The blind sequences collide: evaluate says so with exit 1 and names the pair.
    let blind = temp_dir_made("solve", "feedback").join("blind.json");
    std::fs::write(&blind, result["blind_sequences"].to_string()).unwrap();
    let out = workcell(&["evaluate", &cell, blind.to_str().unwrap(), "--json"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stdout));
    let verdict = json(&out);
    assert_eq!(verdict["collision_free"], false);
    let first = &rounds[0]["collision"];
    assert_eq!(verdict["first_collision"]["bodies"], first["bodies"]);
    assert_eq!(verdict["first_collision"]["time"], first["time"]);
    assert_eq!(
        verdict["first_collision"]["activities"],
        first["activities"]
    );

    // The whole solve result is accepted as a sequences file and reproduces the makespan.
    let whole = temp_dir_made("solve", "feedback").join("result.json");
    std::fs::write(&whole, workcell(&["solve", &cell, "--json"]).stdout).unwrap();
    let out = workcell(&["evaluate", &cell, whole.to_str().unwrap(), "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
    assert_eq!(json(&out)["makespan"], result["makespan"]);
    let human = workcell(&["evaluate", &cell, whole.to_str().unwrap()]);
    assert!(
        text(&human.stdout).contains("collision-free"),
        "{}",
        text(&human.stdout)
    );
}

#[test]
fn solve_without_enough_iterations_exits_1_with_the_reason() {
    let out = workcell(&[
        "solve",
        &shipped("feedback-cell.json"),
        "--max-iterations",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("NO collision-free schedule"), "{stdout}");
    assert!(stdout.contains("R1") && stdout.contains("R2"), "{stdout}");
}

#[test]
fn the_same_seed_gives_the_same_answer() {
    let cell = shipped("four-robots-cell.json");
    let strip = |o: Output| {
        let mut v = json(&o);
        v.as_object_mut().unwrap().remove("stages_ms");
        v
    };
    let a = strip(workcell(&["solve", &cell, "--json", "--seed", "3"]));
    let b = strip(workcell(&["solve", &cell, "--json", "--seed", "3"]));
    assert_eq!(a, b);
}

#[test]
fn the_human_summary_lists_robots_rounds_and_stages() {
    let out = workcell(&["solve", &shipped("paper-cell.json")]);
    assert_eq!(out.status.code(), Some(0));
    let s = text(&out.stdout);
    for needle in [
        "collision-free schedule",
        "makespan",
        "R1 ",
        "R2 ",
        "round 1",
        "planning",
        "checking",
    ] {
        assert!(s.contains(needle), "`{needle}` missing from:\n{s}");
    }
}

#[test]
fn bad_cells_and_sequences_exit_2_naming_file_body_and_field() {
    let bad = temp_dir_made("solve", "bad").join("cell.json");
    std::fs::write(
        &bad,
        r#"{"robots": [{"name": "R1", "shape": [[0,0],[1,0],[0,1]], "home": [0, 0],
            "max_speed": 0, "max_accel": 1, "max_turn_rate": 1}], "tasks": []}"#,
    )
    .unwrap();
    let out = workcell(&["solve", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert!(
        err.contains("cell.json") && err.contains("\"R1\"") && err.contains("robots[0].max_speed"),
        "{err}"
    );

    let out = workcell(&["solve", "no/such/cell.json"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("no/such/cell.json"));

    let seq = temp_dir_made("solve", "bad").join("seq.json");
    std::fs::write(&seq, r#"{"R1": ["weld-1", "weld-1"]}"#).unwrap();
    let out = workcell(&[
        "evaluate",
        &shipped("paper-cell.json"),
        seq.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert!(
        err.contains("seq.json") && err.contains("R1[1]") && err.contains("weld-1"),
        "{err}"
    );

    // An export into a folder that does not exist: refused before any work, naming it.
    let out = workcell(&[
        "solve",
        &shipped("paper-cell.json"),
        "--svg",
        "/no/such/dir/x.svg",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!text(&out.stdout).contains("makespan"));
    let err = text(&out.stderr);
    assert!(
        err.contains("/no/such/dir/x.svg") && err.contains("/no/such/dir, which does not exist"),
        "{err}"
    );
}

#[test]
fn evaluate_reproduces_results_with_waits_and_its_own_output() {
    let robot = |name: &str, x: f64| {
        format!(
            r#"{{"name": "{name}", "shape": [[-0.3,-0.3],[0.3,-0.3],[0.3,0.3],[-0.3,0.3]],
                "home": [{x}, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1.5}}"#
        )
    };
    let cell = temp_dir_made("solve", "waits").join("crossing.json");
    std::fs::write(
        &cell,
        format!(
            r#"{{"delta": 0.01, "robots": [{}, {}], "tasks": [
                {{"name": "east", "at": [10, 3], "duration": 1, "robots": ["R1"]}},
                {{"name": "west", "at": [0, 3], "duration": 1, "robots": ["R2"]}}]}}"#,
            robot("R1", 0.0),
            robot("R2", 10.0)
        ),
    )
    .unwrap();
    let cell = cell.to_str().unwrap();
    // The greedy loop's only remedies are re-sequencing and waits at nodes.
    let solved = workcell(&["solve", cell, "--json", "--feedback", "greedy"]);
    assert_eq!(solved.status.code(), Some(0));
    let result = json(&solved);
    assert!(
        !result["waits"].as_array().unwrap().is_empty(),
        "the crossing needs a wait"
    );
    let mut document = temp_dir_made("solve", "waits").join("result.json");
    std::fs::write(&document, &solved.stdout).unwrap();
    // Twice: on the solve result, then on evaluate's own output.
    for round in 0..2 {
        let out = workcell(&["evaluate", cell, document.to_str().unwrap(), "--json"]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "round {round}: {}",
            text(&out.stdout)
        );
        assert_eq!(json(&out)["makespan"], result["makespan"]);
        document = temp_dir_made("solve", "waits").join(format!("evaluated-{round}.json"));
        std::fs::write(&document, &out.stdout).unwrap();
    }
}

/// Cell `k` of `workcell generate --kind <kind> --seed 1`, written into a folder of the
/// test `tag`: its path.
fn generated(tag: &str, kind: &str, k: usize) -> String {
    let dir = temp_dir_made("solve", tag).join("cells");
    let count = (k + 1).to_string();
    let out = workcell(&[
        "generate",
        "--kind",
        kind,
        "--seed",
        "1",
        "--count",
        &count,
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let cell = dir.join(format!("{kind}-1-{k}-cell.json"));
    cell.to_str().unwrap().to_owned()
}

/// `evaluate` replays a solve's result document (its changed moves and holds) to the same
/// makespan.
fn replays_to_the_same_makespan(cell: &str, solved: &std::process::Output, tag: &str) {
    let document = temp_dir_made("solve", tag).join("result.json");
    std::fs::write(&document, &solved.stdout).unwrap();
    let out = workcell(&["evaluate", cell, document.to_str().unwrap(), "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
    assert_eq!(json(&out)["makespan"], json(solved)["makespan"]);
}

/// `tune` times two robots' moves together: the round says so under `"tune"` (both robots,
/// both moves, every hold), the text in a sentence, and `evaluate` replays the held moves
/// to the same makespan. Without it (`--remedies` naming the others) the ring is refused
/// (exit 1).
#[test]
fn two_moves_timed_together_are_reported_and_replayed() {
    let cell = generated("tune", "ring", 6);
    let cell = cell.as_str();
    let others = "resequence,wait,pause,slow,detour,step-aside";
    let refused = workcell(&["solve", cell, "--remedies", others]);
    assert_eq!(refused.status.code(), Some(1), "{}", text(&refused.stdout));
    let solved = workcell(&["solve", cell, "--json"]);
    assert_eq!(solved.status.code(), Some(0), "{}", text(&solved.stderr));
    let result = json(&solved);
    let rounds = result["feedback"].as_array().unwrap();
    let tuned = (rounds.iter())
        .find(|r| r["remedy"] == "tune")
        .expect("a round of two moves timed together");
    let change = &tuned["tune"];
    for key in ["robot", "on", "with", "with_on"] {
        assert!(change[key].is_string(), "{change}");
    }
    assert_ne!(change["robot"], change["with"]);
    let holds = change["holds"].as_array().unwrap();
    assert!(!holds.is_empty());
    for hold in holds {
        assert!(hold["duration"].as_f64().unwrap() > 0.0);
        assert_eq!(hold["at"].as_array().unwrap().len(), 2);
        assert!(hold["robot"] == change["robot"] || hold["robot"] == change["with"]);
    }
    let words = workcell(&["solve", cell]);
    assert!(text(&words.stdout).contains("time their moves together"));
    replays_to_the_same_makespan(cell, &solved, "tune");
}

/// A convoy sends every robot of a ring round it together: the round says so under
/// `"convoy"` (the robots, the way round, the laps, the loop), the text in a sentence, and
/// `evaluate` replays the convoy's moves and holds to the same makespan. Without it the
/// ring is refused (exit 1).
#[test]
fn a_convoy_is_reported_and_replayed() {
    let cell = generated("convoy", "ring", 8);
    let cell = cell.as_str();
    let others = "resequence,wait,pause,slow,detour,step-aside,tune";
    let refused = workcell(&["solve", cell, "--remedies", others]);
    assert_eq!(refused.status.code(), Some(1), "{}", text(&refused.stdout));
    let solved = workcell(&["solve", cell, "--json"]);
    assert_eq!(solved.status.code(), Some(0), "{}", text(&solved.stderr));
    let result = json(&solved);
    let rounds = result["feedback"].as_array().unwrap();
    let round = (rounds.iter())
        .find(|r| r["remedy"] == "convoy")
        .expect("a round of a convoy");
    let change = &round["convoy"];
    assert!(
        change["robot"].is_string() && change["on"].is_string(),
        "{change}"
    );
    let robots: Vec<&str> = (change["robots"].as_array().unwrap().iter())
        .map(|r| r.as_str().unwrap())
        .collect();
    assert_eq!(robots, ["R1", "R2", "R3", "R4", "R5", "R6", "R7"]);
    assert!(["clockwise", "counter-clockwise"].contains(&change["direction"].as_str().unwrap()));
    assert_eq!(
        (&change["laps"], &change["following"]),
        (&1.into(), &true.into())
    );
    assert!(change["path"].as_array().unwrap().len() >= 3);
    let words = workcell(&["solve", cell]);
    assert!(text(&words.stdout).contains("go round the loop together, "));
    assert!(text(&words.stdout).contains("each following the one ahead"));
    replays_to_the_same_makespan(cell, &solved, "convoy");
}

#[test]
fn evaluate_replays_the_changed_moves_of_a_search_and_refuses_tampered_ones() {
    let cell = generated("legs", "junction", 0);
    let cell = cell.as_str();
    let solved = workcell(&["solve", cell, "--json", "--search-nodes", "300"]);
    assert_eq!(solved.status.code(), Some(0), "{}", text(&solved.stderr));
    let result = json(&solved);
    let legs = result["legs"]
        .as_array()
        .expect("the junction needs changed moves");
    assert!(!legs.is_empty());
    let kinds: Vec<&str> = result["feedback"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|r| r["remedy"].as_str())
        .collect();
    for round in result["feedback"].as_array().unwrap() {
        if let Some(name) = round["remedy"].as_str().filter(|n| *n != "resequence") {
            let key = name.replace('-', "_");
            assert!(round[&key].is_object(), "round {round} names its change");
        }
    }
    assert!(!kinds.is_empty());
    let mut document = temp_dir_made("solve", "legs").join("result.json");
    std::fs::write(&document, &solved.stdout).unwrap();
    for round in 0..2 {
        let out = workcell(&["evaluate", cell, document.to_str().unwrap(), "--json"]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "round {round}: {}",
            text(&out.stdout)
        );
        assert_eq!(json(&out)["makespan"], result["makespan"]);
        assert_eq!(json(&out)["legs"], result["legs"]);
        document = temp_dir_made("solve", "legs").join(format!("evaluated-{round}.json"));
        std::fs::write(&document, &out.stdout).unwrap();
    }
    // A motion run faster than planned would break the limits: refused, naming the field.
    let tampered = |change: &dyn Fn(&mut Value)| {
        let mut doc = result.clone();
        change(&mut doc);
        let file = temp_dir_made("solve", "legs").join("tampered.json");
        std::fs::write(&file, doc.to_string()).unwrap();
        workcell(&["evaluate", cell, file.to_str().unwrap()])
    };
    let go = |doc: &mut Value| -> (usize, usize) {
        let legs = doc["legs"].as_array().unwrap();
        for (k, leg) in legs.iter().enumerate() {
            for (j, p) in leg["pieces"].as_array().unwrap().iter().enumerate() {
                if p.get("go").is_some() {
                    return (k, j);
                }
            }
        }
        unreachable!("a changed leg moves")
    };
    let out = tampered(&|doc| {
        let (k, j) = go(doc);
        doc["legs"][k]["pieces"][j]["go"]["scale"] = 0.5.into();
    });
    assert_eq!(out.status.code(), Some(2));
    let e = text(&out.stderr);
    assert!(e.contains(".go.scale") && e.contains("at least 1"), "{e}");
    // A motion that starts away from where the robot is: a jump, refused.
    let out = tampered(&|doc| {
        let (k, j) = go(doc);
        let first = &mut doc["legs"][k]["pieces"][j]["go"]["primitives"][0]["path"][0][0];
        *first = (first.as_f64().unwrap() + 0.5).into();
    });
    assert_eq!(out.status.code(), Some(2));
    let e = text(&out.stderr);
    assert!(e.contains("legs[") && e.contains("not continuous"), "{e}");
}

/// The feedback cell with `edit` applied, written to a per-test file.
fn edited_cell(test: &str, edit: impl FnOnce(&mut Value)) -> PathBuf {
    let text = std::fs::read_to_string(shipped("feedback-cell.json")).unwrap();
    let mut cell: Value = serde_json::from_str(&text).unwrap();
    edit(&mut cell);
    let path = temp_dir_made("solve", test).join("cell.json");
    std::fs::write(&path, cell.to_string()).unwrap();
    path
}

/// Writes a sequences document to a per-test file.
fn sequences_file(test: &str, doc: &Value) -> PathBuf {
    let path = temp_dir_made("solve", test).join("sequences.json");
    std::fs::write(&path, doc.to_string()).unwrap();
    path
}

/// Asserts exit status 2 and that stderr names `file` and every one of `needles`.
fn refused_naming(out: &Output, file: &Path, needles: &[&str]) {
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}{}", text(&out.stdout));
    assert!(
        err.contains(&format!("error: {}: ", file.display())),
        "not about {}: {err}",
        file.display()
    );
    for n in needles {
        assert!(err.contains(n), "`{n}` missing from {err}");
    }
}

/// All four tasks done by R1, in file order.
fn r1_does_everything() -> Value {
    serde_json::json!({"R1": ["weld-1", "weld-2", "weld-3", "weld-4"]})
}

/// A subnormal limit made `evaluate` panic ("schedules sample increasing times:
/// NotFinite"); both commands now refuse the cell, naming the limit (issue 13, item 4).
#[test]
fn subnormal_limits_are_refused_by_solve_and_evaluate() {
    let sequences = sequences_file("subnormal", &r1_does_everything());
    for field in ["max_speed", "max_accel", "max_turn_rate"] {
        for value in [5e-324, 1e-310] {
            let cell = edited_cell("subnormal", |c| c["robots"][0][field] = value.into());
            let named = format!("robots[0].{field}");
            let out = workcell(&["solve", cell.to_str().unwrap()]);
            refused_naming(&out, &cell, &["\"R1\"", &named, "subnormal"]);
            let out = workcell(&[
                "evaluate",
                cell.to_str().unwrap(),
                sequences.to_str().unwrap(),
            ]);
            refused_naming(&out, &cell, &["\"R1\"", &named, "subnormal"]);
        }
    }
}

/// With `max_speed` 1e-20 a task of 1000 s sat at [2e20, 2e20] and `solve` exited 0; now
/// the cell is refused when read, naming the duration and the slow robot (issue 13, item 5).
#[test]
fn tasks_the_time_axis_cannot_hold_are_refused() {
    for slow in [1e-20, 1e-300] {
        let cell = edited_cell("vanishing", |c| {
            c["robots"][0]["max_speed"] = slow.into();
            c["tasks"][0]["duration"] = 1000.0.into();
            for task in c["tasks"].as_array_mut().unwrap() {
                task["robots"] = serde_json::json!(["R1"]);
            }
        });
        let out = workcell(&["solve", cell.to_str().unwrap()]);
        refused_naming(&out, &cell, &["\"weld-1\"", "tasks[0].duration", "\"R1\""]);
        let sequences = sequences_file("vanishing", &r1_does_everything());
        let out = workcell(&[
            "evaluate",
            cell.to_str().unwrap(),
            sequences.to_str().unwrap(),
        ]);
        refused_naming(&out, &cell, &["tasks[0].duration"]);
    }
}

/// A task of 1e300 leaves no room for the moves after it: `evaluate` blamed the sequences
/// file (field `R1`) and `solve` the robot; both name the cell's `tasks[2].duration`, and a wait of 1e300 in a
/// solve result is blamed on that wait (issue 13, item 8).
#[test]
fn a_time_axis_too_long_is_blamed_on_what_stretched_it() {
    let cell = edited_cell("blame", |c| c["tasks"][2]["duration"] = 1e300.into());
    // The greedy loop's result has a wait, which the second half stretches.
    let solved = workcell(&[
        "solve",
        &shipped("feedback-cell.json"),
        "--json",
        "--feedback",
        "greedy",
    ]);
    let mut result = json(&solved);
    let sequences = sequences_file("blame", &result);
    let out = workcell(&[
        "evaluate",
        cell.to_str().unwrap(),
        sequences.to_str().unwrap(),
    ]);
    refused_naming(&out, &cell, &["\"weld-3\"", "tasks[2].duration", "1e300"]);
    // `solve` blamed the robot (`robots[1]`) for the same cell.
    let out = workcell(&["solve", cell.to_str().unwrap()]);
    refused_naming(&out, &cell, &["\"weld-3\"", "tasks[2].duration", "1e300"]);

    result["waits"][0]["duration"] = 1e300.into();
    let sequences = sequences_file("blame-wait", &result);
    let out = workcell(&[
        "evaluate",
        &shipped("feedback-cell.json"),
        sequences.to_str().unwrap(),
    ]);
    refused_naming(&out, &sequences, &["\"R2\"", "waits[0].duration", "1e300"]);
}

/// On a full disk `--export-scene` left a truncated file. Exports now go to a temporary file
/// beside the target, renamed once whole: the previous file stays, and nothing else is left
/// (issue 13, item 10). A file-size limit (`ulimit -f`, its signal ignored) stands in for
/// the full disk.
#[cfg(unix)]
#[test]
fn an_export_that_cannot_be_written_whole_leaves_the_previous_file() {
    let scene = temp_dir_made("solve", "full-disk").join("scene.json");
    let folder = scene.parent().unwrap();
    std::fs::write(&scene, "previous").unwrap();
    let out = Command::new("sh")
        .args(["-c", r#"trap '' XFSZ; ulimit -f 4; exec "$0" "$@""#])
        .arg(env!("CARGO_BIN_EXE_workcell"))
        .args(["solve", &shipped("paper-cell.json"), "--export-scene"])
        .arg(&scene)
        .output()
        .expect("sh runs");
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("cannot write the file"),
        "{}",
        text(&out.stderr)
    );
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), "previous");
    let left: Vec<_> = std::fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, ["scene.json"], "no temporary file is left behind");
    // Without the limit the export replaces the file, readable as before.
    let out = workcell(&[
        "solve",
        &shipped("paper-cell.json"),
        "--export-scene",
        scene.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(std::fs::read_to_string(&scene).unwrap().starts_with('{'));
}

/// `--export-scene` given the input cell's path overwrote it; an output that names an input,
/// however spelled, or another output, is refused before any work (issue 13, item 10).
#[test]
fn an_output_path_that_is_an_input_is_refused() {
    let cell = temp_dir_made("solve", "overwrite").join("cell.json");
    let original = std::fs::read_to_string(shipped("feedback-cell.json")).unwrap();
    std::fs::write(&cell, &original).unwrap();
    let folder = cell.parent().unwrap();
    let respelled = folder
        .join("..")
        .join(folder.file_name().unwrap())
        .join("cell.json");
    let mut spellings = vec![cell.clone(), respelled];
    #[cfg(unix)]
    {
        let link = folder.join("link.json");
        let _ = std::fs::remove_file(&link);
        std::os::unix::fs::symlink(&cell, &link).unwrap();
        spellings.push(link);
    }
    let cell_arg = cell.to_str().unwrap();
    for output in &spellings {
        for option in ["--export-scene", "--svg", "--export-graph"] {
            let out = workcell(&["solve", cell_arg, option, output.to_str().unwrap()]);
            refused_naming(&out, output, &[option, "input file"]);
        }
    }
    let sequences = sequences_file(
        "overwrite",
        &serde_json::json!({"R1": ["weld-1", "weld-2", "weld-3", "weld-4"]}),
    );
    let out = workcell(&[
        "evaluate",
        cell_arg,
        sequences.to_str().unwrap(),
        "--svg",
        sequences.to_str().unwrap(),
    ]);
    refused_naming(&out, &sequences, &["--svg", "input file"]);
    let both = folder.join("both.json");
    let out = workcell(&[
        "solve",
        cell_arg,
        "--export-scene",
        both.to_str().unwrap(),
        "--svg",
        both.to_str().unwrap(),
    ]);
    refused_naming(&out, &both, &["--svg", "same file as `--export-scene`"]);
    assert_eq!(
        std::fs::read_to_string(&cell).unwrap(),
        original,
        "the cell is untouched"
    );
    assert!(!both.exists());
}

/// `evaluate` blames a result's legs for what they hold: a hold so long that the moves after
/// it cannot keep their length, a hold too short to keep its own, a slowing factor that
/// stretches the time axis; each names the result file and the piece's field, not the cell.
#[test]
fn evaluate_names_the_piece_of_a_leg_that_breaks_the_time_axis() {
    let cell = shipped("feedback-cell.json");
    let solved = workcell(&["solve", &cell, "--json"]);
    let result = json(&solved);
    let legs = result["legs"].as_array().expect("legs");
    let (k, i) = (legs.iter().enumerate())
        .find_map(|(k, l)| {
            let pieces = l["pieces"].as_array()?;
            let hold = pieces.iter().position(|p| p.get("hold").is_some())?;
            let go = pieces.iter().position(|p| p.get("go").is_some())?;
            Some((k, (hold, go)))
        })
        .expect("a leg with a hold and a motion");
    let dir = temp_dir_made("solve", "legs_blamed");
    let cases = [
        (
            format!("/legs/{k}/pieces/{}/hold", i.0),
            1e17,
            format!("legs[{k}].pieces[{}].hold", i.0),
            "stretches",
        ),
        (
            format!("/legs/{k}/pieces/{}/hold", i.0),
            1e-300,
            format!("legs[{k}].pieces[{}].hold", i.0),
            "too short",
        ),
        (
            format!("/legs/{k}/pieces/{}/go/scale", i.1),
            1e300,
            format!("legs[{k}].pieces[{}].go.scale", i.1),
            "stretches",
        ),
    ];
    evaluate_refuses_each(&cell, &result, &dir, &cases, &[]);
}

/// A leg's angle or coordinate beyond what f64 resolves at δ (as the cell's own are) is
/// refused, naming the result file and the field: at 2π·10¹⁵ an angle is rounded to whole
/// turns and would silently become the robot's angle.
#[test]
fn evaluate_refuses_leg_angles_and_coordinates_f64_cannot_resolve() {
    let cell = shipped("feedback-cell.json");
    let result = json(&workcell(&["solve", &cell, "--json"]));
    let legs = result["legs"].as_array().expect("legs");
    let (k, i) = (legs.iter().enumerate())
        .find_map(|(k, l)| {
            let pieces = l["pieces"].as_array()?;
            Some((k, pieces.iter().position(|p| p.get("go").is_some())?))
        })
        .expect("a leg with a motion");
    let at = format!("/legs/{k}/pieces/{i}/go/primitives/0");
    let field = format!("legs[{k}].pieces[{i}].go.primitives[0]");
    let dir = temp_dir_made("solve", "leg_extents");
    let turns = std::f64::consts::TAU * 1e15;
    let cases = [
        (
            format!("{at}/theta"),
            turns,
            format!("{field}.theta"),
            "angle",
        ),
        (
            format!("{at}/path/1/0"),
            1e300,
            format!("{field}.path[1]"),
            "coordinate",
        ),
    ];
    evaluate_refuses_each(&cell, &result, &dir, &cases, &["too large"]);
    // The result as solved is still taken.
    let file = dir.join("good.json");
    std::fs::write(&file, result.to_string()).unwrap();
    let o = workcell(&["evaluate", &cell, file.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
}

/// Outputs that are not plain files (issue 26): a symlink is followed (its target replaced,
/// the link kept); a FIFO nobody reads is refused at once, never waited on (nor opened to
/// compare it with the inputs); a FIFO with a reader gets the picture; a full character
/// device is written through and its failure is exit 2, the device kept (root only: the
/// test makes its own full device with mknod).
#[cfg(unix)]
#[test]
fn outputs_that_are_not_plain_files() {
    use std::os::unix::fs::FileTypeExt;
    let cell = shipped("feedback-cell.json");
    let dir = temp_dir_made("solve", "not_plain_outputs");
    let (target, link) = (dir.join("target.svg"), dir.join("link.svg"));
    std::fs::write(&target, "old").unwrap();
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let o = workcell(&["solve", &cell, "--svg", link.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read_to_string(&target)
        .unwrap()
        .starts_with("<svg"));

    let fifo = dir.join("pipe.svg");
    let made = Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    // No reader: refused within the run, not after an endless wait.
    let mut child = Command::new(env!("CARGO_BIN_EXE_workcell"))
        .args(["solve", &cell, "--svg", fifo.to_str().unwrap()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > std::time::Duration::from_secs(60) {
            child.kill().unwrap();
            panic!("solve blocked on a FIFO nobody reads");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    refused_naming(&out, &fifo, &["FIFO", "no process reads"]);
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());
    // A reader, there before the writer (opened without waiting for one, so no race): it
    // gets the whole picture, which fits the pipe's buffer.
    let mut reader = {
        use std::os::unix::fs::OpenOptionsExt;
        let open = std::fs::OpenOptions::new()
            .read(true)
            .custom_flags(libc::O_NONBLOCK)
            .open(&fifo);
        open.unwrap()
    };
    let o = workcell(&["solve", &cell, "--svg", fifo.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let mut got = String::new();
    std::io::Read::read_to_string(&mut reader, &mut got).unwrap();
    assert!(got.starts_with("<svg") && got.trim_end().ends_with("</svg>"));
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());

    // A full device of our own (1, 7 is /dev/full), where root may make one.
    let full = dir.join("full");
    let made = Command::new("mknod")
        .arg(&full)
        .args(["c", "1", "7"])
        .status();
    if made.is_ok_and(|s| s.success()) {
        let o = workcell(&["solve", &cell, "--svg", full.to_str().unwrap()]);
        refused_naming(&o, &full, &["cannot write", "No space left"]);
        let kind = std::fs::symlink_metadata(&full).unwrap().file_type();
        assert!(kind.is_char_device(), "the device was replaced");
    } else {
        eprintln!("skipped the full device: mknod needs root");
    }
}

/// A result given to `evaluate` holds only the keys `solve` writes (and comments beginning
/// with `_`): a misspelt `waits`, a wait's, a leg's, a piece's or a primitive's key is
/// refused by its path with the nearest known one, never dropped.
#[test]
fn evaluate_refuses_unknown_keys_in_a_result() {
    let cell = shipped("feedback-cell.json");
    let result = json(&workcell(&["solve", &cell, "--json"]));
    let legs = result["legs"].as_array().expect("legs");
    let k = (legs.iter())
        .position(|l| l["pieces"][0].get("go").is_some())
        .expect("a leg that starts with a motion");
    let dir = temp_dir_made("solve", "unknown_result_keys");
    let wait = serde_json::json!([{"robot": "R1", "befor_move": 0, "duration": 0.0}]);
    let cases: [(&str, &str, Value, String, &str); 5] = [
        ("", "wait", serde_json::json!([]), "wait".into(), "waits"),
        (
            "",
            "waits",
            wait,
            "waits[0].befor_move".into(),
            "before_move",
        ),
        (
            &format!("/legs/{k}"),
            "piece",
            Value::Null,
            format!("legs[{k}].piece"),
            "pieces",
        ),
        (
            &format!("/legs/{k}/pieces/0/go"),
            "scal",
            serde_json::json!(1.0),
            format!("legs[{k}].pieces[0].go.scal"),
            "scale",
        ),
        (
            &format!("/legs/{k}/pieces/0/go/primitives/0"),
            "thetta",
            serde_json::json!(0.0),
            format!("legs[{k}].pieces[0].go.primitives[0].thetta"),
            "theta",
        ),
    ];
    for (n, (at, key, value, field, nearest)) in cases.into_iter().enumerate() {
        let mut bad = result.clone();
        bad.pointer_mut(at).unwrap()[key] = value;
        let file = dir.join(format!("bad-{n}.json"));
        std::fs::write(&file, bad.to_string()).unwrap();
        let o = workcell(&["evaluate", &cell, file.to_str().unwrap()]);
        refused_naming(
            &o,
            &file,
            &[&format!("`{field}`"), &format!("did you mean `{nearest}`?")],
        );
    }
    // Comments anywhere are skipped.
    let mut commented = result.clone();
    commented["_note"] = serde_json::json!("checked by hand");
    commented["legs"][k]["_why"] = serde_json::json!({"any": 1});
    commented["legs"][k]["pieces"][0]["go"]["_c"] = serde_json::json!(2);
    let file = dir.join("commented.json");
    std::fs::write(&file, commented.to_string()).unwrap();
    let o = workcell(&["evaluate", &cell, file.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
}

/// Every summary that claims collision-free says for which δ (a cell's own, here 0.02, not
/// the default): `solve`'s first line and `evaluate`'s verdict.
#[test]
fn summaries_that_claim_collision_free_give_delta() {
    let dir = temp_dir_made("solve", "summary_delta");
    let text = std::fs::read_to_string(shipped("feedback-cell.json")).unwrap();
    let mut doc: Value = serde_json::from_str(&text).unwrap();
    doc["delta"] = serde_json::json!(0.02);
    let cell = dir.join("cell.json");
    std::fs::write(&cell, doc.to_string()).unwrap();
    let cell = cell.to_str().unwrap();
    let solved = workcell(&["solve", cell]);
    let first = text_of_first_line(&solved);
    assert!(
        first.contains("collision-free schedule (delta 0.02;"),
        "{first}"
    );
    let result = dir.join("result.json");
    std::fs::write(&result, workcell(&["solve", cell, "--json"]).stdout).unwrap();
    let evaluated = workcell(&["evaluate", cell, result.to_str().unwrap()]);
    let first = text_of_first_line(&evaluated);
    assert!(first.ends_with(": collision-free (delta 0.02)"), "{first}");
}

fn text_of_first_line(o: &Output) -> String {
    text(&o.stdout)
        .lines()
        .next()
        .unwrap_or_default()
        .to_owned()
}

/// `evaluate` on `result` with each case's value put at its JSON pointer: exit 2, naming the
/// file written and the case's field, saying the case's words and every one of `also`.
fn evaluate_refuses_each(
    cell: &str,
    result: &Value,
    dir: &Path,
    cases: &[(String, f64, String, &str)],
    also: &[&str],
) {
    for (n, (pointer, value, field, says)) in cases.iter().enumerate() {
        let mut bad = result.clone();
        *bad.pointer_mut(pointer).unwrap() = serde_json::json!(value);
        let file = dir.join(format!("bad-{n}.json"));
        std::fs::write(&file, bad.to_string()).unwrap();
        let o = workcell(&["evaluate", cell, file.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "{pointer} = {value}");
        let err = text(&o.stderr);
        assert!(
            err.contains(file.to_str().unwrap()) && err.contains(&format!("`{field}`")),
            "{err}"
        );
        assert!(err.contains(says), "{err}");
        assert!(also.iter().all(|w| err.contains(w)), "{err}");
    }
}

/// `solve` and `evaluate` given a scene say so, as `check` given a cell does, rather than
/// refusing its `trajectory` as an unknown key.
#[test]
fn solve_and_evaluate_on_a_scene_say_it_is_a_scene() {
    let scene = shipped("paper-fig12b.json");
    let dir = temp_dir_made("solve", "scene_given");
    let sequences = dir.join("s.json");
    std::fs::write(&sequences, r#"{"R1": []}"#).unwrap();
    for args in [
        vec!["solve", scene.as_str()],
        vec!["evaluate", scene.as_str(), sequences.to_str().unwrap()],
    ] {
        let o = workcell(&args);
        let words = ["this is a scene", "use `workcell check` on it"];
        refused_naming(&o, Path::new(&scene), &words);
    }
}

/// A task pose where the robot's body overlaps a fixture (or comes within δ of it) is
/// refused as such, naming the fixture, not as a turn the move cannot make.
#[test]
fn a_task_pose_overlapping_a_fixture_is_told_as_such() {
    let original = std::fs::read_to_string(shipped("feedback-cell.json")).unwrap();
    let dir = temp_dir_made("solve", "pose_overlaps");
    // R1's half-width is 0.5; the fixture starts at x = 4.
    for (x, says) in [
        (3.7, "overlaps obstacle \"fixture\""),
        (3.495, "comes within delta"),
    ] {
        let mut doc: Value = serde_json::from_str(&original).unwrap();
        doc["tasks"][0]["at"] = serde_json::json!([x, 3.0, 0.0]);
        let cell = dir.join(format!("cell-{x}.json"));
        std::fs::write(&cell, doc.to_string()).unwrap();
        let o = workcell(&["solve", cell.to_str().unwrap()]);
        refused_naming(
            &o,
            &cell,
            &["`tasks[0].at`", "at the goal pose the robot's body", says],
        );
        assert!(
            !text(&o.stderr).contains("cannot turn"),
            "{}",
            text(&o.stderr)
        );
    }
}

/// `--idle-roots` reaches the search: on the doorway of seven robots, the plan without R1
/// is searched beside the collision-blind one, and the answer leaves R1 at home.
#[test]
fn idle_roots_leave_a_robot_at_home() {
    let doorway =
        workcell::generate::generate_conflict_cell(workcell::generate::ConflictKind::Doorway, 1, 3);
    let cell = temp_dir_made("solve", "idle").join("doorway-3.json");
    std::fs::write(&cell, doorway.to_string()).unwrap();
    let cell = cell.to_str().unwrap();
    let out = workcell(&["solve", cell, "--json", "--idle-roots", "1"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let result = json(&out);
    assert_eq!(result["sequences"]["R1"], serde_json::json!([]));
    let blind = &result["blind_sequences"]["R1"];
    assert!(
        !blind.as_array().unwrap().is_empty(),
        "R1 works in the blind plan"
    );
}
