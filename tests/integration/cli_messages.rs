//! What the command line says matches what it does (issue 14, item 7): plurals, number
//! arguments refused by our own messages, a cell given to `check`, the method list of
//! `compare`, the help of `evaluate --svg`, `evaluate --blind`, and the generator script.

use crate::common::{shipped, temp_dir_made, workcell};
use std::process::Command;

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn one_pair_on_one_thread_is_singular() {
    // tunnelling.json has two bodies: one pair.
    let o = Command::new(env!("CARGO_BIN_EXE_workcell"))
        .args(["check", &shipped("tunnelling.json")])
        .env("RAYON_NUM_THREADS", "1")
        .output()
        .unwrap();
    let out = text(&o.stdout);
    assert!(out.contains("\n1 pair checked ("), "{out}");
    assert!(out.contains(" on 1 thread\n"), "{out}");
    let o = workcell(&["check", &shipped("paper-fig12a.json")]);
    assert!(
        text(&o.stdout).contains("\n9 pairs checked ("),
        "{}",
        text(&o.stdout)
    );
}

#[test]
fn one_iteration_is_singular() {
    for feedback in ["greedy", "search"] {
        let o = workcell(&[
            "solve",
            &shipped("feedback-cell.json"),
            "--max-iterations",
            "1",
            "--feedback",
            feedback,
        ]);
        assert_eq!(o.status.code(), Some(1), "{}", text(&o.stderr));
        let out = text(&o.stdout);
        assert!(
            out.contains("the limit of 1 round ran out;")
                || out.contains("the limit of 1 round cut 1 line of remedies short"),
            "{out}"
        );
    }
}

#[test]
fn negative_numbers_get_our_message_not_clap_tip() {
    let cases: [&[&str]; 4] = [
        &["check", "x.json", "--delta", "-1"],
        &["check", "x.json", "--time-tol", "-0.5"],
        &["solve", "x.json", "--time-limit", "-3"],
        &["solve", "x.json", "--search-time", "-3"],
    ];
    for args in cases {
        let o = workcell(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = text(&o.stderr);
        assert!(
            err.contains("expected a positive number"),
            "{args:?}: {err}"
        );
        assert!(!err.contains("tip:"), "{args:?}: clap's tip: {err}");
    }
}

/// A time limit of any positive size is taken (beyond what a duration holds, it is no limit),
/// not refused by a hidden cap.
#[test]
fn huge_time_limits_are_taken() {
    let cell = crate::common::shipped("feedback-cell.json");
    for limit in ["1e9", "1e300"] {
        for option in ["--search-time", "--time-limit"] {
            let o = workcell(&["solve", &cell, option, limit]);
            assert_eq!(
                o.status.code(),
                Some(0),
                "{option} {limit}: {}",
                text(&o.stderr)
            );
        }
    }
}

/// The second pass's share of the search's budget is a share: from 0 to 1, nothing else.
#[test]
fn a_share_outside_zero_to_one_is_refused() {
    for share in ["-0.5", "1.5", "nan", "a third"] {
        let o = workcell(&["solve", "x.json", "--second-pass-share", share]);
        assert_eq!(o.status.code(), Some(2), "{share}");
        let err = text(&o.stderr);
        assert!(
            err.contains(&format!("expected a share from 0 to 1, got `{share}`")),
            "{share}: {err}"
        );
        assert!(!err.contains("tip:"), "{share}: clap's tip: {err}");
    }
    let cell = shipped("feedback-cell.json");
    for share in ["0", "1"] {
        let o = workcell(&["solve", &cell, "--second-pass-share", share]);
        assert_eq!(o.status.code(), Some(0), "{share}: {}", text(&o.stderr));
    }
}

#[test]
fn zero_counts_say_at_least_one() {
    let cases: [&[&str]; 3] = [
        &["solve", "x.json", "--max-iterations", "0"],
        &["solve", "x.json", "--search-nodes", "0"],
        &["check", "x.json", "--max-work", "0"],
    ];
    for args in cases {
        let o = workcell(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = text(&o.stderr);
        assert!(err.contains("at least 1, got `0`"), "{args:?}: {err}");
        assert!(!err.contains("18446744073709551615"), "{args:?}: {err}");
    }
    let o = workcell(&["solve", "x.json", "--max-iterations", "-1"]);
    assert!(text(&o.stderr).contains("at least 1, got `-1`"));
}

#[test]
fn check_on_a_cell_says_to_solve_it() {
    let o = workcell(&["check", &shipped("paper-cell.json")]);
    assert_eq!(o.status.code(), Some(2));
    let err = text(&o.stderr);
    assert!(err.contains("this is a cell"), "{err}");
    assert!(err.contains("workcell solve"), "{err}");
    assert!(!err.contains("trajectory"), "{err}");
    // A broken scene is still told what is wrong with it.
    let scene = temp_dir_made("msg", "broken").join("scene.json");
    std::fs::write(&scene, r#"{"robots": [{"name": "A", "shape": []}]}"#).unwrap();
    let err = text(&workcell(&["check", scene.to_str().unwrap()]).stderr);
    assert!(
        err.contains("trajectory") && !err.contains("this is a cell"),
        "{err}"
    );
}

#[test]
fn compare_lists_parry_among_the_methods() {
    let o = workcell(&["compare", &shipped("near-miss.json"), "--methods", "foo"]);
    assert_eq!(o.status.code(), Some(2));
    let err = text(&o.stderr);
    assert!(err.contains("unknown method `foo`"), "{err}");
    assert!(err.contains("advance or parry"), "{err}");
}

#[test]
fn evaluate_help_describes_its_own_picture() {
    let help = text(&workcell(&["evaluate", "--help"]).stdout);
    let svg = help.split("--svg").nth(1).expect("--svg is listed");
    let svg = svg.split("\n      --").next().unwrap();
    assert!(!svg.contains("fed back"), "{svg}");
    assert!(svg.contains("first collision"), "{svg}");
    assert!(help.contains("--blind"), "{help}");
    let help = text(&workcell(&["solve", "--help"]).stdout);
    assert!(help.contains("collisions fed back"), "{help}");
}

#[test]
fn evaluate_blind_replays_the_collision_blind_sequences() {
    let result = temp_dir_made("msg", "blind").join("result.json");
    let o = workcell(&["solve", &shipped("feedback-cell.json"), "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    std::fs::write(&result, &o.stdout).unwrap();
    let solved: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let cell = shipped("feedback-cell.json");
    let res = result.to_str().unwrap();
    // The final sequences are certified; the blind ones are what the feedback had to fix.
    assert_eq!(workcell(&["evaluate", &cell, res]).status.code(), Some(0));
    let o = workcell(&["evaluate", &cell, res, "--blind", "--json"]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o.stderr));
    let blind: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(blind["sequences"], solved["blind_sequences"]);
    assert_eq!(blind["makespan"], solved["blind_makespan"]);
    assert!(
        blind["waits"].is_null() && blind["legs"].is_null(),
        "{blind}"
    );
    // Plain sequences have no blind ones.
    let plain = temp_dir_made("msg", "blind").join("plain.json");
    std::fs::write(&plain, solved["sequences"].to_string()).unwrap();
    let o = workcell(&["evaluate", &cell, plain.to_str().unwrap(), "--blind"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o.stderr).contains("not a whole `solve --json` result"));
}

#[test]
fn make_cells_verifies_against_the_checker() {
    // The generator of the shipped scenes runs the checker with its current options.
    if Command::new("python3").arg("--version").output().is_err() {
        eprintln!("python3 not found: cells/make_cells.py not run");
        return;
    }
    let out = temp_dir_made("msg", "make-cells").join("scenes");
    let o = Command::new("python3")
        .arg(shipped("make_cells.py"))
        .args(["--checker", env!("CARGO_BIN_EXE_workcell"), "--table"])
        .args(["--only", "near-miss", "bad-velocities", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}{}", text(&o.stdout), text(&o.stderr));
    assert!(text(&o.stdout).contains("all scenes as expected"));
    // What it wrote is what is shipped.
    for name in ["near-miss.json", "bad-velocities.json"] {
        let made = std::fs::read(out.join(name)).unwrap();
        assert_eq!(made, std::fs::read(shipped(name)).unwrap(), "{name}");
    }
}
