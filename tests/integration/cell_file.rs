//! Cell files: every refusal names the file, the body and the field.

use std::path::Path;
use workcell::cell::{parse_cell, parse_sequences, Cell, InputError, Wait};

const FILE: &str = "cell.json";

fn cell(robots: &str, obstacles: &str, tasks: &str) -> String {
    format!(
        r#"{{"delta": 0.01, "robots": [{robots}], "obstacles": [{obstacles}], "tasks": [{tasks}]}}"#
    )
}

fn robot(name: &str, home: &str) -> String {
    format!(
        r#"{{"name": "{name}", "shape": [[-0.3,-0.3],[0.3,-0.3],[0.3,0.3],[-0.3,0.3]], "home": {home},
            "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5}}"#
    )
}

const WALL: &str = r#"{"name": "wall", "shape": [[2,-1],[3,-1],[3,1],[2,1]]}"#;

fn task(name: &str, at: &str, extra: &str) -> String {
    format!(r#"{{"name": "{name}", "at": {at}, "duration": 1.0{extra}}}"#)
}

fn refused(text: &str) -> InputError {
    parse_cell(text, Path::new(FILE)).expect_err("the cell must be refused")
}

fn ok(text: &str) -> Cell {
    parse_cell(text, Path::new(FILE))
        .expect("a valid cell")
        .cell
}

#[test]
fn a_valid_cell_reads_with_defaults() {
    let c = ok(&cell(
        &[robot("R1", "[0, 0]"), robot("R2", "[5, 0, 1.0]")].join(","),
        WALL,
        &[
            task("t1", "[1, 2]", ""),
            task("t2", "[4, 2, 0.5]", r#", "robots": ["R2"]"#),
        ]
        .join(","),
    ));
    assert_eq!(c.rigid(0).home.theta, 0.0);
    assert_eq!(c.rigid(1).home.theta, 1.0);
    assert_eq!(c.tasks[0].robots, vec![0, 1], "default: every robot");
    assert_eq!(c.tasks[1].robots, vec![1]);
    assert_eq!(c.tasks[1].at.theta, 0.5);
}

#[test]
fn duplicate_names_are_refused_across_kinds() {
    let e = refused(&cell(
        &robot("R1", "[0, 0]"),
        WALL,
        &task("R1", "[1, 2]", ""),
    ));
    assert_eq!(e.field, "tasks[0].name");
    assert_eq!(e.body.as_deref(), Some("R1"));
    assert!(e.reason.contains("robots[0]"), "{e}");
    let e = refused(&cell(
        &[robot("R1", "[0, 0]"), robot("R1", "[5, 5]")].join(","),
        "",
        "",
    ));
    assert_eq!(e.field, "robots[1].name");
}

/// A missing limit is named by its field; an arm (contract section 7) is read, and one
/// without `links` is named by them.
#[test]
fn missing_limits_and_arms_are_named() {
    for field in ["max_speed", "max_accel", "max_turn_rate"] {
        let text = cell(&robot("R1", "[0, 0]"), "", "")
            .replace(&format!(r#""{field}": "#), r#""_other": "#);
        let e = refused(&text);
        assert_eq!(
            (e.body.as_deref(), e.field.as_str()),
            (Some("R1"), format!("robots[0].{field}").as_str()),
            "{e}"
        );
        assert!(e.reason.contains("missing"), "{e}");
    }
    let arm = r#"{"name": "A1", "base": [0, 5, 0], "home": [1.57],
        "links": [{"length": 0.8, "shape": [[-0.1,-0.1],[0.9,-0.1],[0.9,0.1],[-0.1,0.1]]}],
        "max_joint_speed": 2, "max_joint_accel": 4}"#;
    let text = cell(&format!("{}, {arm}", robot("R1", "[0, 0]")), "", "");
    let read = parse_cell(&text, Path::new("c.json")).unwrap().cell;
    assert_eq!(
        read.robots[1].as_arm().map(|a| a.home.clone()),
        Some(vec![1.57])
    );
    let opts = workcell::wcp::SolveOptions::default();
    assert!(workcell::wcp::prepare(&read, &opts, &()).is_ok());
    let base_only = text.replace(r#""links": "#, r#""_other": "#);
    assert_eq!(refused(&base_only).field, "robots[1].links");
}

#[test]
fn non_positive_limits_are_refused() {
    for field in ["max_speed", "max_accel", "max_turn_rate"] {
        for bad in ["0", "-1", "1e400"] {
            let text = cell(&robot("R1", "[0, 0]"), "", "").replace(
                &format!(r#""{field}": "#),
                &format!(r#""{field}": {bad}, "_{field}": "#),
            );
            let e = parse_cell(&text, Path::new(FILE));
            let e = match e {
                Err(e) => e,
                Ok(_) => panic!("{field} = {bad} accepted"),
            };
            assert_eq!(e.body.as_deref(), Some("R1"), "{e}");
            assert_eq!(e.field, format!("robots[0].{field}"), "{e}");
        }
    }
}

#[test]
fn a_home_or_task_inside_an_obstacle_or_homes_touching_are_refused() {
    let e = refused(&cell(&robot("R1", "[2.5, 0]"), WALL, ""));
    assert_eq!(
        (e.field.as_str(), e.body.as_deref()),
        ("robots[0].home", Some("R1"))
    );
    assert!(e.reason.contains("wall"), "{e}");
    // Touching the wall within delta is a collision at home too.
    let e = refused(&cell(&robot("R1", "[1.695, 0]"), WALL, ""));
    assert_eq!(e.field, "robots[0].home");
    let e = refused(&cell(
        &robot("R1", "[0, 0]"),
        WALL,
        &task("t1", "[2.5, 0.5]", ""),
    ));
    assert_eq!(
        (e.field.as_str(), e.body.as_deref()),
        ("tasks[0].at", Some("t1"))
    );
    assert!(e.reason.contains("inside obstacle \"wall\""), "{e}");
}

#[test]
fn a_task_no_robot_may_do_is_refused() {
    let e = refused(&cell(
        &robot("R1", "[0, 0]"),
        "",
        &task("t1", "[1, 2]", r#", "robots": []"#),
    ));
    assert_eq!(
        (e.field.as_str(), e.body.as_deref()),
        ("tasks[0].robots", Some("t1"))
    );
    let e = refused(&cell(
        &robot("R1", "[0, 0]"),
        "",
        &task("t1", "[1, 2]", r#", "robots": ["R7"]"#),
    ));
    assert_eq!(e.field, "tasks[0].robots[0]");
    assert!(e.reason.contains("R7"), "{e}");
}

#[test]
fn a_fault_of_reading_is_reported_before_a_geometric_one() {
    // The home inside the wall comes first in the file, the unknown robot later: the document
    // is read whole before its geometry is checked.
    let e = refused(&cell(
        &robot("R1", "[2.5, 0]"),
        WALL,
        &task("t1", "[1, 2]", r#", "robots": ["R7"]"#),
    ));
    assert_eq!(e.field, "tasks[0].robots[0]", "{e}");
}

#[test]
fn malformed_fields_name_their_path() {
    let e = refused(&cell(&robot("R1", "[0]"), "", ""));
    assert_eq!(e.field, "robots[0].home");
    let e = refused(&cell(
        &robot("R1", "[0, 0]"),
        "",
        &task("t1", "[1, 2]", "").replace("1.0", "-2"),
    ));
    assert_eq!(e.field, "tasks[0].duration");
    let e = refused(&cell(
        &robot("R1", "[0, 0]"),
        "",
        &task("t1", "[1, 2]", "").replace("\"at\"", "\"where\""),
    ));
    assert_eq!(e.body.as_deref(), Some("t1"), "{e}");
    let e = refused(&cell("", "", ""));
    assert_eq!(e.field, "robots");
    let e = refused(&cell(
        &robot("R1", "[0, 0]"),
        "",
        &task("t1", "[1, 2, 9007199254740992]", ""),
    ));
    assert_eq!(
        (e.field.as_str(), e.body.as_deref()),
        ("tasks[0].at", Some("t1"))
    );
    assert!(e.reason.contains("angle"), "{e}");
    let e = refused(&cell(&robot("R1", "[1e300, 0]"), "", ""));
    assert_eq!(e.field, "robots[0].home");
    assert!(
        e.to_string()
            .starts_with("cell.json: body \"R1\", field `robots[0].home`:"),
        "{e}"
    );
}

#[test]
fn sequences_are_checked_against_the_cell() {
    let c = ok(&cell(
        &[robot("R1", "[0, 0]"), robot("R2", "[5, 0]")].join(","),
        "",
        &[
            task("t1", "[1, 2]", ""),
            task("t2", "[4, 2]", r#", "robots": ["R2"]"#),
        ]
        .join(","),
    ));
    let file = Path::new("seq.json");
    // `sequences` is a robot's name here, not a whole result (which has a `makespan`).
    let named = parse_sequences(r#"{"sequences": ["t1"], "R2": ["t2"]}"#, file, &c);
    assert_eq!(
        named.unwrap_err().field,
        "sequences",
        "the robot `sequences` is unknown"
    );
    let routes = parse_sequences(r#"{"R2": ["t2", "t1"]}"#, file, &c).unwrap();
    assert_eq!(routes.routes, vec![vec![], vec![1, 0]]);
    assert!(routes.waits.is_empty());
    let routes = parse_sequences(
        r#"{"makespan": 3, "sequences": {"R1": ["t1"], "R2": ["t2"]},
            "waits": [{"robot": "R2", "before_move": 1, "duration": 0.5}]}"#,
        file,
        &c,
    )
    .unwrap();
    assert_eq!(routes.routes, vec![vec![0], vec![1]]);
    assert_eq!(
        routes.waits,
        vec![Wait {
            robot: 1,
            before_move: 1,
            duration: 0.5
        }]
    );
    let wait = |w: &str| {
        format!(r#"{{"makespan": 1, "sequences": {{"R1": ["t1"], "R2": ["t2"]}}, "waits": [{w}]}}"#)
    };
    for (w, field) in [
        (
            r#"{"robot": "R3", "before_move": 0, "duration": 1}"#,
            "waits[0].robot",
        ),
        (
            r#"{"robot": "R1", "before_move": 2, "duration": 1}"#,
            "waits[0].before_move",
        ),
        (
            r#"{"robot": "R1", "before_move": 0, "duration": -1}"#,
            "waits[0].duration",
        ),
    ] {
        let e = parse_sequences(&wait(w), file, &c).expect_err(w);
        assert_eq!(e.field, field, "{e}");
    }
    let cases = [
        (r#"{"R1": ["t1", "t2"]}"#, "R1[1]", "not allowed"),
        (
            r#"{"R1": ["t1"], "R2": ["t1", "t2"]}"#,
            "R2[0]",
            "already done",
        ),
        (r#"{"R1": ["t1"]}"#, "(every robot's list)", "t2"),
        (r#"{"R2": ["t2"], "R1": ["t1"], "R2": []}"#, "R2", "twice"),
        (r#"{"R9": []}"#, "R9", "no robot"),
        (r#"{"R1": ["t3"]}"#, "R1[0]", "no task"),
        (r#"{"R1": "t1"}"#, "R1", "list"),
        (r#"[1]"#, "", "object"),
        // Found by `cargo fuzz run sequences_reader`: the empty key named no field.
        (r#"{"": ["t1"]}"#, r#""""#, "no robot"),
    ];
    for (text, field, reason) in cases {
        let e = parse_sequences(text, file, &c).expect_err(text);
        assert_eq!(e.field, field, "{text}: {e}");
        assert!(e.reason.contains(reason), "{text}: {e}");
        assert_eq!(e.file, file);
    }
}

/// A record written as an array of its field values (serde's sequence form of a struct) is
/// refused, not read positionally (issue 13, item 7).
#[test]
fn records_written_as_arrays_are_refused() {
    let square = "[[-0.3,-0.3],[0.3,-0.3],[0.3,0.3],[-0.3,0.3]]";
    let good_robot = robot("R1", "[0, 0]");
    let cases = [
        (
            cell(
                &format!(r#"["R1", {square}, [0, 0], 1.0, 2.0, 1.5]"#),
                "",
                "",
            ),
            "robots[0]",
            "a robot: an object",
        ),
        (
            cell(&good_robot, r#"["wall", [[2,-1],[3,-1],[3,1],[2,1]]]"#, ""),
            "obstacles[0]",
            "an obstacle: an object",
        ),
        (
            cell(&good_robot, "", r#"["t1", [1, 2], 1.0]"#),
            "tasks[0]",
            "a task: an object",
        ),
        (
            format!(r#"[0.01, [{good_robot}], [], []]"#),
            "",
            "a cell: an object",
        ),
    ];
    for (text, field, reason) in cases {
        let e = refused(&text);
        assert_eq!(e.field, field, "{e}");
        assert!(e.reason.contains(reason), "{e}");
    }
}

/// Limits and durations that f64 cannot place on one time axis are refused when the cell is
/// read, naming the field (issue 13, items 4 and 5).
#[test]
fn limits_and_durations_off_the_time_axis_are_refused() {
    let task1 = task("t1", "[1, 2]", "");
    for field in ["max_speed", "max_accel", "max_turn_rate"] {
        for bad in ["5e-324", "1e-310"] {
            let text = cell(&robot("R1", "[0, 0]"), "", &task1).replace(
                &format!(r#""{field}": "#),
                &format!(r#""{field}": {bad}, "_{field}": "#),
            );
            let e = parse_cell(&text, Path::new(FILE)).expect_err(bad);
            assert_eq!(e.field, format!("robots[0].{field}"), "{e}");
            assert!(e.reason.contains("subnormal"), "{e}");
        }
    }
    // So slow that the task of 1000 would start at 2.5e20 and occupy [2.5e20, 2.5e20].
    for slow in ["1e-20", "1e-300"] {
        let text = cell(&robot("R1", "[0, 0]"), "", &task1.replace("1.0", "1000"))
            .replace(r#""max_speed": 1.0"#, &format!(r#""max_speed": {slow}"#));
        let e = refused(&text);
        assert_eq!(
            (e.field.as_str(), e.body.as_deref()),
            ("tasks[0].duration", Some("t1")),
            "{e}"
        );
        assert!(
            e.reason.contains("\"R1\"") && e.reason.contains(slow),
            "{e}"
        );
    }
    // A duration lost in rounding at the task's earliest start (2 + 1e-16 = 2).
    let e = refused(&cell(
        &robot("R1", "[0, 0]"),
        "",
        &task1.replace("1.0", "1e-16"),
    ));
    assert_eq!(e.field, "tasks[0].duration", "{e}");
    // Found by the fuzz test: max_accel 1e308 over a radius of 0.42 is an infinite angular
    // acceleration, and the planner's angles came out NaN (a panic). Ratios of limits out
    // of f64's normal range are refused.
    for (field, bad) in [
        ("max_accel", "1e308"),
        ("max_speed", "1e-300"),
        ("max_turn_rate", "1e-300"),
    ] {
        let text = cell(&robot("R1", "[0, 0]"), "", &task1)
            .replace(r#""max_accel": 2.0"#, r#""max_accel": 1e10"#)
            .replace(
                &format!(r#""{field}": "#),
                &format!(r#""{field}": {bad}, "_{field}": "#),
            );
        let e = parse_cell(&text, Path::new(FILE)).expect_err(bad);
        assert_eq!(e.field, format!("robots[0].{field}"), "{e}");
        assert!(e.reason.contains("normal f64"), "{e}");
    }
    // A move whose time overflows f64 at normal limits.
    let far = cell(&robot("R1", "[0, 0]"), "", &task("t1", "[1e300, 0]", ""))
        .replace(r#""delta": 0.01"#, r#""delta": 1e290"#)
        .replace(r#""max_speed": 1.0"#, r#""max_speed": 1e-10"#);
    let e = refused(&far);
    assert_eq!(e.field, "robots[0].max_speed", "{e}");
    assert!(e.reason.contains("longer than f64 holds"), "{e}");
    // An instant, and a long task at ordinary limits, are fine.
    ok(&cell(
        &robot("R1", "[0, 0]"),
        "",
        &[
            task("t1", "[1, 2]", "").replace("1.0", "0"),
            task("t2", "[2, 2]", "").replace("1.0", "1e9"),
        ]
        .join(","),
    ));
}

#[test]
fn a_shape_clean_up_that_moves_the_boundary_is_refused_in_cells_too() {
    // As in scenes (issue 13, item 2): vertex 1 lies 2.4e-4 from vertex 0 on a fixture
    // 2.5e8 long, within the shape tolerance; dropping it would move the boundary by
    // 0.24 δ.
    let obstacle =
        r#"{"name": "big", "shape": [[0, 10], [0.00024, 9.99976], [2.5e8, 10], [0, 2.5e8]]}"#;
    let e = refused(&cell(
        &robot("R1", "[0, 0]"),
        obstacle,
        &task("t", "[-3, 0]", ""),
    ));
    assert_eq!(
        (e.body.as_deref(), e.field.as_str()),
        (Some("big"), "obstacles[0].shape[1]")
    );
    assert!(e.reason.contains("repeated or collinear"), "{e}");
}

/// Names with control characters (an escape sequence, a NUL, U+FFFE) are refused in cells,
/// scenes and the library, the field named and the name not repeated: they would reach a
/// terminal, an SVG (which XML refuses) and a page.
#[test]
fn names_with_control_characters_are_refused() {
    use workcell::cell::parse_scene;
    use workcell::collision::{Body, Scene};
    use workcell::geometry::ConvexPolygon;
    for bad in ["R\u{1b}[2J", "R\u{0}", "R\u{1}", "R\u{fffe}"] {
        let json_name = serde_json::to_string(bad).unwrap();
        let text = cell(&robot("R1", "[0, 0]"), "", "").replace("\"R1\"", &json_name);
        let e = refused(&text);
        assert_eq!(
            (e.body.as_deref(), e.field.as_str()),
            (None, "robots[0].name"),
            "{e}"
        );
        assert!(
            e.reason.contains("control characters") && !e.to_string().contains(bad),
            "{e}"
        );
        let scene = format!(
            r#"{{"delta": 0.01, "robots": [{{"name": {json_name}, "shape": [[0,0],[1,0],[0,1]],
                "trajectory": [{{"t": 0, "x": 0, "y": 0}}]}}]}}"#
        );
        let e = parse_scene(&scene, Path::new("s.json")).unwrap_err();
        assert_eq!(e.field, "robots[0].name", "{e}");
        let mut library = Scene::new(0.01).unwrap();
        let square = ConvexPolygon::rectangle(1.0, 1.0).unwrap();
        assert!(library.add(Body::obstacle(bad, &square)).is_err());
    }
    // A name of a megabyte would be copied into every search node: refused by length.
    let long = "R".repeat(workcell::collision::MAX_NAME_CHARS + 1);
    let text = cell(&robot("R1", "[0, 0]"), "", "").replace("\"R1\"", &format!("\"{long}\""));
    let e = refused(&text);
    assert_eq!(e.field, "robots[0].name", "{e}");
    assert!(
        e.reason
            .contains("at most 256 characters (this one has 257)"),
        "{e}"
    );
    let longest = "R".repeat(workcell::collision::MAX_NAME_CHARS);
    let text = cell(&robot("R1", "[0, 0]"), "", "").replace("\"R1\"", &format!("\"{longest}\""));
    assert_eq!(ok(&text).robots[0].name, longest);
    // Letters of any script, spaces and symbols are names.
    let fine = cell(&robot("R1", "[0, 0]"), "", "").replace("\"R1\"", "\"Schweißroboter 1 ⟂ Ω\"");
    assert_eq!(ok(&fine).robots[0].name, "Schweißroboter 1 ⟂ Ω");
}

/// An unknown key is refused by its path with the nearest known key (a typo of `delta` must
/// not leave δ at its default, nor `robot` drop a task's restriction); keys beginning with
/// `_` are comments, skipped everywhere: in cells, scenes and sequences.
#[test]
fn unknown_keys_are_refused_and_underscored_keys_ignored() {
    use workcell::cell::parse_scene;
    let base = cell(
        &robot("R1", "[0, 0]"),
        WALL,
        &task("t1", "[1, 2]", r#", "robots": ["R1"]"#),
    );
    let cases = [
        (base.replace("\"delta\"", "\"delat\""), "delat", "delta"),
        (
            base.replace("\"robots\": [\"R1\"]", "\"robot\": [\"R1\"]"),
            "tasks[0].robot",
            "robots",
        ),
        (
            base.replace("\"max_speed\"", "\"max_sped\""),
            "robots[0].max_sped",
            "max_speed",
        ),
        (
            base.replace("\"name\": \"wall\"", "\"nam\": \"wall\""),
            "obstacles[0].nam",
            "name",
        ),
    ];
    for (text, field, nearest) in cases {
        let e = refused(&text);
        assert_eq!(e.field, field, "{e}");
        assert!(
            e.reason.contains(&format!("did you mean `{nearest}`?")),
            "{e}"
        );
    }
    // Comments at every level are skipped, and change nothing.
    let commented = base
        .replacen(
            '{',
            r#"{"_comment": "a cell", "_tool": {"any": [1, 2]}, "#,
            1,
        )
        .replace("\"name\": \"R1\"", "\"_note\": null, \"name\": \"R1\"")
        .replace("\"name\": \"t1\"", "\"_by\": \"me\", \"name\": \"t1\"");
    assert_eq!(ok(&commented).tasks, ok(&base).tasks);
    assert_eq!(ok(&commented).robots[0].name, "R1");
    // Scenes: a sample's key too.
    let scene = r#"{"delta": 0.01, "_c": 1, "robots": [{"name": "R1", "shape": [[0,0],[1,0],[0,1]],
        "trajectory": [{"t": 0, "x": 0, "y": 0, "_k": 2}]}]}"#;
    assert!(parse_scene(scene, Path::new("s.json")).is_ok());
    let e = parse_scene(&scene.replace("\"x\": 0", "\"xx\": 0"), Path::new("s.json")).unwrap_err();
    assert_eq!(e.field, "robots[0].trajectory[0].xx", "{e}");
    assert!(e.reason.contains("did you mean `x`?"), "{e}");
    // Sequences: a comment beside the robots' lists.
    let two = cell(
        &[robot("R1", "[0, 0]"), robot("R2", "[5, 0]")].join(","),
        "",
        &task("t1", "[1, 2]", ""),
    );
    let c = ok(&two);
    let s = parse_sequences(
        r#"{"_why": "R1 alone", "R1": ["t1"]}"#,
        Path::new("s.json"),
        &c,
    );
    assert_eq!(s.unwrap().routes, [vec![0], vec![]]);
}
