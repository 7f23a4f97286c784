//! The library's entry points refuse what the command line refuses, with the same error
//! type (issue 13, item 9).

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use workcell::cell::{check_precision, parse_scene};
use workcell::collision::{check, try_check, CheckOptions, Method, Scene};

/// A passes through B between its two samples: a collision at any positive δ.
fn tunnelling() -> Scene {
    let text = r#"{"delta": 0.01, "robots": [
      {"name": "A", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
       "trajectory": [{"t": 0, "x": 0, "y": 0}, {"t": 1, "x": 10, "y": 0}]},
      {"name": "B", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
       "trajectory": [{"t": 0, "x": 5, "y": 0}, {"t": 1, "x": 5, "y": 0}]}]}"#;
    parse_scene(text, Path::new("tunnel.json")).unwrap().scene
}

const BAD_DELTAS: [f64; 5] = [f64::NAN, 0.0, -1.0, f64::INFINITY, -0.0];

#[test]
fn try_check_refuses_a_delta_that_is_not_positive() {
    for delta in BAD_DELTAS {
        // From the scene, and from the options.
        let scene = Scene {
            delta,
            ..tunnelling()
        };
        let e = try_check(&scene, &CheckOptions::default()).expect_err("scene delta");
        assert_eq!(e.field, "delta", "{delta}: {e}");
        let opts = CheckOptions {
            delta: Some(delta),
            ..CheckOptions::default()
        };
        let e = try_check(&tunnelling(), &opts).expect_err("option delta");
        assert_eq!(e.field, "delta", "{delta}: {e}");
        assert!(e.file.as_os_str().is_empty(), "no file: {e}");
        assert!(
            e.to_string()
                .starts_with("field `delta`: must be a positive"),
            "{e}"
        );
    }
    let report = try_check(&tunnelling(), &CheckOptions::default()).unwrap();
    assert!(report.collision);
}

#[test]
fn try_check_refuses_bad_tolerances_and_steps() {
    let cases: [(CheckOptions, &str); 5] = [
        (
            CheckOptions {
                time_tol: Some(f64::NAN),
                ..CheckOptions::default()
            },
            "time_tol",
        ),
        (
            CheckOptions {
                time_tol: Some(-1.0),
                ..CheckOptions::default()
            },
            "time_tol",
        ),
        (
            CheckOptions {
                grazing_tol: 1.0,
                ..CheckOptions::default()
            },
            "grazing_tol",
        ),
        (
            CheckOptions {
                method: Method::Sampled { step: 1e-300 },
                ..CheckOptions::default()
            },
            "method",
        ),
        (
            CheckOptions {
                method: Method::Sampled { step: f64::NAN },
                ..CheckOptions::default()
            },
            "method",
        ),
    ];
    for (opts, field) in cases {
        let e = try_check(&tunnelling(), &opts).expect_err(field);
        assert_eq!(e.field, field, "{e}");
    }
}

/// `check` itself no longer reports "free, certified" for δ = 0 or −1: it panics, naming
/// the field, as its documentation says.
#[test]
fn check_refuses_a_non_positive_delta_instead_of_proving_it_free() {
    for delta in [0.0, -1.0] {
        let scene = Scene {
            delta,
            ..tunnelling()
        };
        let result = catch_unwind(AssertUnwindSafe(|| check(&scene, &CheckOptions::default())));
        let report = result
            .err()
            .map(|p| p.downcast_ref::<String>().cloned().unwrap_or_default());
        let message = report.expect("check must refuse, not return a report");
        assert!(message.contains("field `delta`"), "{message}");
    }
}

#[test]
fn check_precision_refuses_a_delta_that_is_not_positive() {
    let scene = tunnelling();
    let file = Path::new("tunnel.json");
    for delta in BAD_DELTAS {
        let e = check_precision(&scene, delta, file).expect_err("refused");
        assert_eq!(e.field, "delta", "{delta}: {e}");
        assert!(e.reason.contains("positive"), "{e}");
        assert!(!e.reason.contains("-2.7"), "no negative limit: {e}");
    }
    assert!(check_precision(&scene, 0.01, file).is_ok());
}

/// `try_check` also refuses what `workcell check` refuses for precision.
#[test]
fn try_check_refuses_scenes_the_precision_check_refuses() {
    let scene = tunnelling();
    let opts = CheckOptions {
        delta: Some(1e-12),
        ..CheckOptions::default()
    };
    let e = try_check(&scene, &opts).expect_err("coordinates too large for delta 1e-12");
    assert!(e.field.starts_with("robots[0]"), "{e}");
}
