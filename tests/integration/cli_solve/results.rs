//! What `solve` prints and writes, and `evaluate` replaying it: the contract's JSON, the
//! exports, the summary, the feedback, changed moves, convoys and tuned moves.

use super::*;

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
    replays_to_the_same(cell, &solved, "waits", &["makespan"]);
}

/// `tune` times two robots' moves together: the round says so under `"tune"` (both robots,
/// both moves, every hold), the text in a sentence, and `evaluate` replays the held moves
/// to the same makespan. Without it (`--remedies` naming the others) the ring is refused
/// (exit 1).
#[test]
fn two_moves_timed_together_are_reported_and_replayed() {
    let cell = generated("tune", "ring", 6);
    let cell = cell.as_str();
    let (solved, result) = solved_only_with(cell, "resequence,wait,pause,slow,detour,step-aside");
    let change = &round_of(&result, "tune")["tune"];
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
    replays_to_the_same(cell, &solved, "tune", &["makespan", "legs"]);
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
    let (solved, result) = solved_only_with(cell, others);
    let change = &round_of(&result, "convoy")["convoy"];
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
    replays_to_the_same(cell, &solved, "convoy", &["makespan", "legs"]);
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
    replays_to_the_same(cell, &solved, "legs", &["makespan", "legs"]);
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

/// `cell` refused (exit 1) with only the remedies `others`, then solved (exit 0) with all of
/// them: the output and its JSON.
fn solved_only_with(cell: &str, others: &str) -> (Output, Value) {
    let refused = workcell(&["solve", cell, "--remedies", others]);
    assert_eq!(refused.status.code(), Some(1), "{}", text(&refused.stdout));
    let solved = workcell(&["solve", cell, "--json"]);
    assert_eq!(solved.status.code(), Some(0), "{}", text(&solved.stderr));
    let result = json(&solved);
    (solved, result)
}

/// The first round of the result's feedback that took `remedy`.
fn round_of<'a>(result: &'a Value, remedy: &str) -> &'a Value {
    (result["feedback"].as_array().unwrap().iter())
        .find(|r| r["remedy"] == remedy)
        .unwrap_or_else(|| panic!("a round of {remedy}"))
}
