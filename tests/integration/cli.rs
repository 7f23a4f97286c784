//! The command line as a user meets it: verdicts, exit statuses, and errors that name the
//! file, the body and the field.

use crate::common::workcell;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Writes `text` to a fresh file in a per-test temporary folder.
fn scene_file(test: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("workcell-cli-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.json");
    std::fs::write(&path, text).unwrap();
    path
}

const SQUARE: &str = "[[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]]";

/// Two unit squares; B sits at x = 5 and A moves from x = 0 to `a_end` in one step.
fn two_squares(a_end: f64) -> String {
    format!(
        r#"{{"delta": 0.01, "robots": [
        {{"name": "A", "shape": {SQUARE}, "trajectory": [{{"t": 0, "x": 0, "y": 0}}, {{"t": 1, "x": {a_end}, "y": 0}}]}},
        {{"name": "B", "shape": {SQUARE}, "trajectory": [{{"t": 0, "x": 5, "y": 0}}, {{"t": 0.5, "x": 5, "y": 0}}]}}]}}"#
    )
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn free_scene_exits_0_and_prints_the_contract_json() {
    let path = scene_file("free", &two_squares(3.0));
    let o = workcell(&["check", path.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["collision"], false);
    assert!(v["first_contact"].is_null());
    assert_eq!(v["safe_until"], 1.0);
    for counter in [
        "intervals",
        "bisections",
        "narrow_phase_calls",
        "feature_steps",
    ] {
        assert!(v["stats"][counter].is_u64(), "missing counter {counter}");
    }
}

#[test]
fn tunnelling_collision_exits_1_with_time_and_pair() {
    // A jumps from x = 0 to x = 10 in one step: clear at both samples, through B between.
    let path = scene_file("tunnel", &two_squares(10.0));
    let o = workcell(&["check", path.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["collision"], true);
    assert_eq!(v["first_contact"]["bodies"], serde_json::json!(["A", "B"]));
    // Faces meet when A's right face (x + 0.5) is within 0.01 of B's left face (4.5).
    let t = v["first_contact"]["time"].as_f64().unwrap();
    let exact = (4.0 - 0.01) / 10.0;
    assert!(
        t >= exact && t - exact <= 1e-6,
        "first contact {t}, exact {exact}"
    );
    assert!(v["safe_until"].as_f64().unwrap() <= t);
    // The human summary says the same.
    let o = workcell(&["check", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stdout).contains("COLLISION between A and B"));
}

#[test]
fn delta_and_time_tolerance_options_apply() {
    let path = scene_file("options", &two_squares(3.0));
    // A ends at x = 3, B's face at 4.5: 1.0 apart, so delta 1.5 collides at the end.
    let o = workcell(&[
        "check",
        path.to_str().unwrap(),
        "--json",
        "--delta",
        "1.5",
        "--time-tol",
        "1e-9",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let t = v["first_contact"]["time"].as_f64().unwrap();
    let exact = (4.0 - 1.5) / 3.0;
    assert!(
        t >= exact && t - exact <= 1e-9,
        "first contact {t}, exact {exact}"
    );
    assert_eq!(v["time_tol"], 1e-9);
}

#[test]
fn clockwise_shape_is_reversed_with_a_warning() {
    let text =
        two_squares(3.0).replacen(SQUARE, "[[-0.5,0.5],[0.5,0.5],[0.5,-0.5],[-0.5,-0.5]]", 1);
    let path = scene_file("clockwise", &text);
    let o = workcell(&["check", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("warning") && err.contains("\"A\"") && err.contains("clockwise"),
        "{err}"
    );
}

/// Asserts exit status 2 and that stderr names every one of `needles`.
fn refused(test: &str, text: &str, needles: &[&str]) {
    let path = scene_file(test, text);
    let o = workcell(&["check", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{test}: {}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains(path.to_str().unwrap()),
        "{test}: no file name in {err}"
    );
    for n in needles {
        assert!(err.contains(n), "{test}: `{n}` missing from {err}");
    }
}

#[test]
fn bad_shapes_are_refused_naming_body_and_vertex() {
    let good = two_squares(3.0);
    let cases = [
        (
            "nonconvex",
            "[[0,0],[2,0],[1,0.5],[2,2],[0,2]]",
            vec!["\"A\"", "robots[0].shape[2]", "not convex"],
        ),
        (
            "two-vertices",
            "[[0,0],[1,0],[1,0]]",
            vec!["\"A\"", "robots[0].shape", "3 distinct"],
        ),
        ("flat", "[[0,0],[1,0],[2,0]]", vec!["\"A\"", "zero area"]),
    ];
    for (name, shape, needles) in cases {
        refused(name, &good.replacen(SQUARE, shape, 1), &needles);
    }
}

#[test]
fn bad_trajectories_and_documents_are_refused() {
    let good = two_squares(3.0);
    refused(
        "time",
        &good.replace(r#""t": 1, "x": 3"#, r#""t": 0, "x": 3"#),
        &["\"A\"", "robots[0].trajectory[1].t"],
    );
    refused(
        "missing-x",
        &good.replace(r#""t": 1, "x": 3, "#, r#""t": 1, "#),
        &["robots[0].trajectory[1]", "missing field `x`"],
    );
    refused(
        "type",
        &good.replace(r#""x": 3"#, r#""x": "three""#),
        &["robots[0].trajectory[1].x"],
    );
    refused(
        "empty",
        &good.replace(
            r#"[{"t": 0, "x": 5, "y": 0}, {"t": 0.5, "x": 5, "y": 0}]"#,
            "[]",
        ),
        &["\"B\"", "robots[1].trajectory"],
    );
    refused(
        "duplicate",
        &good.replace(r#""name": "B""#, r#""name": "A""#),
        &["\"A\"", "robots[1].name", "same name"],
    );
    refused(
        "delta",
        &good.replace(r#""delta": 0.01"#, r#""delta": -1"#),
        &["delta", "positive"],
    );
    refused("syntax", &good[..good.len() - 3], &["line"]);
    refused(
        "huge",
        &good.replace(r#""x": 3"#, r#""x": 1e999"#),
        &["robots[0].trajectory[1].x"],
    );
    // A number out of f64's range still names its body.
    refused(
        "out-of-range",
        &good.replace(r#""t": 1, "x": 3"#, r#""t": 1e400, "x": 3"#),
        &["\"A\"", "robots[0].trajectory[1].t", "out of range"],
    );
    refused(
        "overflowing-velocity",
        &good.replace(r#""t": 1, "x": 3"#, r#""t": 1e-300, "x": 1e10"#),
        &[
            "\"A\"",
            "robots[0].trajectory[0]",
            "velocity derived from the positions",
        ],
    );
    refused(
        "three-numbers",
        &good.replacen("[-0.5,-0.5],", "[-0.5,-0.5,0],", 1),
        &["\"A\"", "robots[0].shape[0]", "[x, y]"],
    );
    refused(
        "trailing",
        &format!("{good} {{"),
        &["after the scene document"],
    );
    refused("not-an-object", "[]", &["a scene: an object with `robots`"]);
}

/// serde reads a struct from an array of its fields too: `[t, x, y, theta]` was taken as
/// t, x, y, vx with θ = 0. Only the documented objects are accepted (issue 13, item 7).
#[test]
fn records_written_as_arrays_are_refused() {
    let good = two_squares(10.0);
    refused(
        "sample-array",
        &good.replace(r#"{"t": 1, "x": 10, "y": 0}"#, "[1, 10, 0, 1.5]"),
        &["\"A\"", "robots[0].trajectory[1]", "a sample: an object"],
    );
    let b = format!(
        r#"{{"name": "B", "shape": {SQUARE}, "trajectory": [{{"t": 0, "x": 5, "y": 0}}]}}"#
    );
    let a_as_array =
        format!(r#"["A", {SQUARE}, [{{"t": 0, "x": 0, "y": 0}}, {{"t": 1, "x": 10, "y": 0}}]]"#);
    refused(
        "robot-array",
        &format!(r#"{{"robots": [{a_as_array}, {b}]}}"#),
        &["robots[0]", "a robot: an object"],
    );
    refused(
        "document-array",
        &format!("[0.01, [{b}], []]"),
        &["a scene: an object"],
    );
}

#[test]
fn missing_file_and_bad_options_exit_2() {
    let o = workcell(&["check", "/nonexistent/scene.json"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("/nonexistent/scene.json"));
    let path = scene_file("options-bad", &two_squares(3.0));
    for bad in [
        ["--delta", "-1"],
        ["--time-tol", "0"],
        ["--method", "fast"],
        ["--method", "sampled:0"],
    ] {
        let o = workcell(&["check", path.to_str().unwrap(), bad[0], bad[1]]);
        assert_eq!(o.status.code(), Some(2), "{bad:?}");
    }
}

/// Runs workcell and kills it if it is still running after `limit`: a guard against a
/// hang, not a timing assertion (what it guards finishes in milliseconds, or never).
fn workcell_unless_hung(args: &[&str], limit: Duration) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_workcell"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let start = Instant::now();
    while child.try_wait().expect("waits").is_none() {
        if start.elapsed() > limit {
            child.kill().expect("kills");
            panic!("workcell {args:?} still runs after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("output")
}

/// A `sampled` step so fine that its looks never end (the f64 counter stopped advancing
/// past 2^53) is refused, by `check` and by `compare` (issue 13, item 6).
#[test]
fn sampled_steps_that_would_never_finish_are_refused() {
    let path = scene_file("sampled-fine", &two_squares(3.0));
    let limit = Duration::from_secs(120);
    for step in ["sampled:1e-300", "sampled:5e-324"] {
        let o = workcell_unless_hung(&["check", path.to_str().unwrap(), "--method", step], limit);
        assert_eq!(o.status.code(), Some(2), "{step}: {}", stderr(&o));
        let err = stderr(&o);
        assert!(err.contains(path.to_str().unwrap()), "{err}");
        assert!(
            err.contains("field `method`") && err.contains("looks"),
            "{err}"
        );
        let o = workcell_unless_hung(
            &["compare", path.to_str().unwrap(), "--methods", step],
            limit,
        );
        assert_eq!(o.status.code(), Some(2), "compare {step}: {}", stderr(&o));
        assert!(stderr(&o).contains("looks"), "{}", stderr(&o));
    }
    // A fine step that does finish is still run.
    let o = workcell(&["check", path.to_str().unwrap(), "--method", "sampled:1e-6"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

#[test]
fn shipped_cells_give_their_expected_verdicts() {
    let cells = Path::new(env!("CARGO_MANIFEST_DIR")).join("cells");
    let expected = [
        ("paper-fig12a.json", 0),
        ("paper-fig12b.json", 1),
        ("tunnelling.json", 1),
        ("spin-hit.json", 1),
        ("near-miss.json", 0),
        ("bad-velocities.json", 1),
        ("grippers-interleave.json", 0),
    ];
    for (file, code) in expected {
        let o = workcell(&["check", cells.join(file).to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(code), "{file}: {}", stderr(&o));
    }
    // The paper's velocity bound is fooled by the inconsistent velocities.
    let o = workcell(&[
        "check",
        cells.join("bad-velocities.json").to_str().unwrap(),
        "--method",
        "adaptive-paper",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

/// `compare --svg` never replaces one of the scenes it reads (issue 13, item 10).
#[test]
fn compare_refuses_to_draw_over_a_scene() {
    let path = scene_file("compare-over", &two_squares(3.0));
    let o = workcell(&[
        "compare",
        path.to_str().unwrap(),
        "--methods",
        "adaptive",
        "--svg",
        path.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("input file"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&path).unwrap(), two_squares(3.0));
}
