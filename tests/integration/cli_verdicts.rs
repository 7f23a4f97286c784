//! What `workcell check` says and how it exits when the answer is not a plain proof: a work
//! budget spent (exit 3), methods that certify nothing, and scenes f64 cannot check.

use crate::common::{spinning_tip, workcell};
use std::path::PathBuf;
use std::process::Output;

fn scene_file(test: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("workcell-verdicts-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.json");
    std::fs::write(&path, text).unwrap();
    path
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

const SQUARE: &str = "[[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]]";

#[test]
fn a_spent_work_budget_exits_3_and_says_unresolved() {
    let path = scene_file("budget", &spinning_tip(300));
    let o = workcell(&["check", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(3), "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("UNRESOLVED: tip and wall used their work budget"),
        "{out}"
    );
    assert!(!out.contains("collision-free over"), "{out}");
    let o = workcell(&["check", path.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(3));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["collision"], false);
    assert_eq!(v["certified"], false);
    assert_eq!(
        v["budget_exhausted"]["bodies"],
        serde_json::json!(["tip", "wall"])
    );
    assert_eq!(v["budget_exhausted"]["work"], 1_000_000);
    // A smaller budget stops the ten-turn tip too; the default does not.
    let path = scene_file("budget-small", &spinning_tip(10));
    let o = workcell(&["check", path.to_str().unwrap(), "--max-work", "1000"]);
    assert_eq!(o.status.code(), Some(3), "{}", stdout(&o));
    let o = workcell(&["check", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    let o = workcell(&["check", path.to_str().unwrap(), "--max-work", "0"]);
    assert_eq!(o.status.code(), Some(2));
}

/// Square A passes square B at a distance of 2 between samples 0 and 1.
fn pass() -> String {
    format!(
        r#"{{"delta": 0.01, "robots": [
        {{"name": "A", "shape": {SQUARE}, "trajectory": [{{"t": 0, "x": -5, "y": 0}}, {{"t": 1, "x": 5, "y": 0}}]}},
        {{"name": "B", "shape": {SQUARE}, "trajectory": [{{"t": 0, "x": 0, "y": 3}}]}}]}}"#
    )
}

#[test]
fn methods_that_prove_nothing_say_so() {
    let path = scene_file("methods", &pass());
    let path = path.to_str().unwrap();
    for method in ["sampled:0.1", "adaptive-paper"] {
        let o = workcell(&["check", path, "--method", method]);
        assert_eq!(o.status.code(), Some(0));
        let out = stdout(&o);
        assert!(out.contains("no collision found over"), "{method}: {out}");
        assert!(
            out.contains(&format!("`{method}` certifies nothing")),
            "{method}: {out}"
        );
        assert!(!out.contains("grazing"), "{method}: nothing grazed: {out}");
    }
    for method in ["adaptive", "advance"] {
        let out = stdout(&workcell(&["check", path, "--method", method]));
        assert!(
            out.contains("collision-free over [0, 1] (delta 0.01; certified)"),
            "{method}: {out}"
        );
    }
    // A collision found by a method that proves nothing has no proven prefix either.
    let path = scene_file("methods-hit", &pass().replace(r#""y": 3"#, r#""y": 0.5"#));
    let o = workcell(&["check", path.to_str().unwrap(), "--method", "sampled:0.1"]);
    assert_eq!(o.status.code(), Some(1));
    let out = stdout(&o);
    assert!(out.contains("no collision found before t ="), "{out}");
    assert!(out.contains("`sampled:0.1` certifies nothing"), "{out}");
}

#[test]
fn time_stamps_too_coarse_for_the_tolerance_exit_2_naming_the_field() {
    let text = format!(
        r#"{{"delta": 0.001, "robots": [{{"name": "A", "shape": {SQUARE},
        "trajectory": [{{"t": 1e15, "x": -1000, "y": 0}}, {{"t": 1.000000000001e15, "x": 1000, "y": 0}}]}}],
        "obstacles": [{{"name": "wall", "shape": [[-1,-5],[1,-5],[1,5],[-1,5]]}}]}}"#
    );
    let path = scene_file("coarse-time", &text);
    let path = path.to_str().unwrap();
    for method in ["adaptive", "adaptive-paper"] {
        let o = workcell(&["check", path, "--method", method]);
        assert_eq!(o.status.code(), Some(2), "{method}: {}", stdout(&o));
        assert!(stdout(&o).is_empty(), "{method}: no verdict is printed");
        let e = stderr(&o);
        assert!(
            e.contains(r#"body "A", field `robots[0].trajectory[1].t`"#),
            "{e}"
        );
        assert!(e.contains("--time-tol"), "{e}");
    }
    // A tolerance f64 can hold is accepted, and the contact found.
    let o = workcell(&["check", path, "--time-tol", "4"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
}

#[test]
fn a_shape_clean_up_that_moves_the_boundary_exits_2_naming_the_vertex() {
    let text = format!(
        r#"{{"delta": 0.001, "robots": [{{"name": "R", "shape": {SQUARE},
        "trajectory": [{{"t": 0, "x": 0.00024, "y": -0.50114}}]}}],
        "obstacles": [{{"name": "big", "shape": [[0,0],[0.00024,-0.00024],[250000000,0],[0,250000000]]}}]}}"#
    );
    let path = scene_file("clean-up", &text);
    let o = workcell(&["check", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stdout(&o));
    let e = stderr(&o);
    assert!(
        e.contains(r#"body "big", field `obstacles[0].shape[1]`"#),
        "{e}"
    );
}
