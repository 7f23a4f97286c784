//! Inputs `solve` and `evaluate` refuse, each with the file, the body and the field named
//! and exit status 2, and outputs they will not write over.

use super::*;

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

/// An unknown remedy is refused (exit 2), with every name the search knows listed: the
/// command line offers the library's names, not a copy of them.
#[test]
fn an_unknown_remedy_is_refused_with_every_name_listed() {
    let out = workcell(&[
        "solve",
        &shipped("paper-cell.json"),
        "--remedies",
        "wait,bogus",
    ]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let err = text(&out.stderr);
    assert!(err.contains("bogus"), "{err}");
    for name in workcell::wcp::Remedies::NAMES {
        assert!(err.contains(name), "{name} not offered: {err}");
    }
}
