//! Arms in scene files (contract section 6): read, written back, and every fault named by
//! file, body and field.

use serde_json::{json, Value};
use std::path::Path;
use workcell::cell::{parse_scene, scene_document};
use workcell::collision::{check, CheckOptions};

fn arm() -> Value {
    json!({"name": "A1", "base": [0.0, 0.0, 0.0],
           "links": [{"length": 0.8, "shape": [[-0.1, -0.1], [0.9, -0.1], [0.9, 0.1], [-0.1, 0.1]]},
                     {"length": 0.6, "parts": [[[-0.08, -0.08], [0.6, -0.08], [0.6, 0.08], [-0.08, 0.08]],
                                               [[0.6, -0.15], [0.7, -0.15], [0.7, 0.15], [0.6, 0.15]]]}],
           "trajectory": [{"t": 0.0, "q": [0.0, 0.0]}, {"t": 2.0, "q": [1.2, -0.6], "qd": [0.0, 0.0]}]})
}

/// A scene of the arm (changed by `edit`) and a post its tool sweeps past, then into.
fn scene(edit: impl FnOnce(&mut Value)) -> String {
    let mut a = arm();
    edit(&mut a);
    json!({"delta": 0.01, "robots": [a],
           "obstacles": [{"name": "post", "shape": [[0.8, 1.0], [1.0, 1.0], [1.0, 1.2], [0.8, 1.2]]}]})
    .to_string()
}

fn refused(edit: impl FnOnce(&mut Value), field: &str, says: &str) {
    let e = parse_scene(&scene(edit), Path::new("arm.json")).unwrap_err();
    assert_eq!(
        (e.body.as_deref(), e.field.as_str()),
        (Some("A1"), field),
        "{e}"
    );
    assert!(e.reason.contains(says), "{e}");
    assert!(e.to_string().starts_with("arm.json: body \"A1\""), "{e}");
}

#[test]
fn bad_arms_are_named() {
    refused(
        |a| a["trajectory"][1]["q"] = json!([1.0]),
        "robots[0].trajectory[1].q",
        "one per link",
    );
    refused(
        |a| a["trajectory"][0]["qd"] = json!([1.0, 2.0, 3.0]),
        "robots[0].trajectory[0].qd",
        "one per link",
    );
    refused(
        |a| {
            a.as_object_mut().unwrap().remove("links");
        },
        "robots[0].links",
        "needs `links`",
    );
    refused(
        |a| a["links"][1]["length"] = json!(-0.5),
        "robots[0].links[1].length",
        ">= 0",
    );
    refused(
        |a| a["links"] = json!([]),
        "robots[0].links",
        "at least one link",
    );
    refused(
        |a| a["shape"] = json!([[0, 0], [1, 0], [1, 1]]),
        "robots[0].shape",
        "not `shape`",
    );
    refused(
        |a| a["base"] = json!([0]),
        "robots[0].base",
        "[x, y, theta]",
    );
    refused(
        |a| a["links"][0]["shape"] = json!([[0, 0], [1, 0], [2, 0]]),
        "robots[0].links[0].shape",
        "",
    );
    refused(
        |a| {
            a["links"][0].as_object_mut().unwrap().remove("shape");
        },
        "robots[0].links[0].shape",
        "one of `shape`, `parts` or `outline`",
    );
    refused(
        |a| a["trajectory"][1]["t"] = json!(0.0),
        "robots[0].trajectory[1].t",
        "strictly increase",
    );
    refused(
        |a| a["trajectory"] = json!([{"t": 0, "x": 0, "y": 0}]),
        "robots[0].trajectory[0]",
        "joint angles",
    );
    // A pose beside joint angles, or samples of both kinds, are refused too.
    let e = parse_scene(
        &scene(|a| a["trajectory"][1]["x"] = json!(1.0)),
        Path::new("arm.json"),
    )
    .unwrap_err();
    assert_eq!(e.field, "robots[0].trajectory[1]", "{e}");
    let rigid = json!({"delta": 0.01, "robots": [{"name": "R", "shape": [[0, 0], [1, 0], [1, 1]],
        "trajectory": [{"t": 0, "x": 0, "y": 0}, {"t": 1, "q": [0.0]}]}]});
    let e = parse_scene(&rigid.to_string(), Path::new("r.json")).unwrap_err();
    assert!(e.field.starts_with("robots[0].trajectory"), "{e}");
}

#[test]
fn arms_are_read_checked_and_written_back() {
    let text = scene(|_| {});
    let loaded = parse_scene(&text, Path::new("arm.json")).unwrap().scene;
    // Two links, then the post; the links are one robot.
    assert_eq!(loaded.bodies.len(), 3);
    assert_eq!(
        (loaded.bodies[0].link(), loaded.bodies[1].link()),
        (Some(0), Some(1))
    );
    assert_eq!(loaded.pairs(), [(0, 2), (1, 2)]);
    let report = check(&loaded, &CheckOptions::default());
    let c = report
        .first_contact
        .as_ref()
        .expect("the tool meets the post");
    assert_eq!(c.bodies, ["A1".to_owned(), "post".to_owned()]);
    assert_eq!(c.links, Some([Some(1), None]));
    assert!(c.time > 0.0 && report.safe_until <= c.time);
    let json = serde_json::to_value(&report).unwrap();
    assert_eq!(json["first_contact"]["links"], json!([1, null]));
    // Written and read back: the same scene, the same verdict.
    let doc = scene_document(&loaded);
    assert_eq!(
        doc["robots"][0]["links"][1]["parts"]
            .as_array()
            .unwrap()
            .len(),
        2
    );
    let again = parse_scene(&doc.to_string(), Path::new("copy.json"))
        .unwrap()
        .scene;
    assert_eq!(check(&again, &CheckOptions::default()), report);
}

/// Fields are named by the file's robots, an arm counting once: a rigid robot after a
/// two-link arm is `robots[1]`, the arm's second link `robots[0].links[1]`.
#[test]
fn fields_count_an_arm_once() {
    let mut doc: Value = serde_json::from_str(&scene(|_| {})).unwrap();
    doc["robots"]
        .as_array_mut()
        .unwrap()
        .push(json!({"name": "R",
        "shape": [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]],
        "trajectory": [{"t": 0, "x": 3, "y": 0}, {"t": 1, "x": 1e12, "y": 0}]}));
    let loaded = parse_scene(&doc.to_string(), Path::new("arm.json"))
        .unwrap()
        .scene;
    assert_eq!(loaded.field_of(1), "robots[0].links[1]");
    assert_eq!(loaded.field_of(2), "robots[1]");
    assert_eq!(loaded.field_of(3), "obstacles[0]");
    let e =
        workcell::cell::check_precision(&loaded, loaded.delta, Path::new("arm.json")).unwrap_err();
    assert_eq!(
        (e.body.as_deref(), e.field.as_str()),
        (Some("R"), "robots[1].trajectory[1].x")
    );
}

/// `check --svg` draws the arm where it starts: each link's body in the arm's colour (its
/// second link as its two parts), its base as a square, the joint past it as a dot where
/// forward kinematics puts it; `--svg` and `--html` may not name one file.
#[cfg(feature = "cli")]
#[test]
fn the_still_picture_draws_an_arm() {
    let dir = crate::common::temp_dir_made("arm_files", "still_picture");
    let file = dir.join("arm.json");
    std::fs::write(&file, scene(|_| {})).unwrap();
    let svg = dir.join("arm.svg");
    let out = crate::common::workcell(&[
        "check",
        file.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(text.matches("class=\"base\"").count(), 1, "one base");
    assert_eq!(
        text.matches("class=\"joint\"").count(),
        1,
        "one joint past the base"
    );
    let colour = workcell::view::COLOURS[0];
    let bodies = text
        .matches(&format!("fill=\"{colour}\" fill-opacity=\"0.3\""))
        .count();
    assert_eq!(bodies, 3, "link 0, and link 1's two parts");
    // The joint is the elbow at q = (0, 0), 0.8 right of the base: drawn level with it and
    // to its right (the picture's y axis points down, its x axis right).
    let attribute = |element: &str, name: &str| -> f64 {
        let i = text.find(element).unwrap();
        let tag = &text[i..i + text[i..].find('>').unwrap()];
        let at = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        tag[at..].split('"').next().unwrap().parse().unwrap()
    };
    let base = (
        attribute("<rect class=\"base\"", "x") + 5.0,
        attribute("<rect class=\"base\"", "y") + 5.0,
    );
    let elbow = (
        attribute("<circle class=\"joint\"", "cx"),
        attribute("<circle class=\"joint\"", "cy"),
    );
    assert!(
        (elbow.1 - base.1).abs() < 1e-6 && elbow.0 > base.0 + 10.0,
        "base {base:?}, elbow {elbow:?}"
    );
    let same = crate::common::workcell(&[
        "check",
        file.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
        "--html",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(same.status.code(), Some(2));
}
