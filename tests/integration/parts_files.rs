//! Bodies of parts in files (contract section 5): what is read, what is refused and how the
//! refusal names the file, the body and the field; the result's `first_contact.parts`.

use serde_json::{json, Value};
use std::path::Path;
use workcell::cell::{parse_cell, parse_scene, scene_document};
use workcell::collision::{check, CheckOptions};

/// A scene of one robot `R` at rest, its geometry given by `body` (an object of keys).
fn scene_with(body: Value) -> String {
    let mut robot = json!({"name": "R", "trajectory": [{"t": 0, "x": 0, "y": 0}]});
    for (k, v) in body.as_object().unwrap() {
        robot[k] = v.clone();
    }
    json!({"robots": [robot]}).to_string()
}

/// The refusal of a scene: field and reason.
fn refusal(body: Value) -> (String, String) {
    let e = parse_scene(&scene_with(body), Path::new("cell.json")).unwrap_err();
    assert_eq!(e.body.as_deref(), Some("R"));
    assert!(e.to_string().starts_with("cell.json: body \"R\""), "{e}");
    (e.field, e.reason)
}

#[test]
fn bad_parts_and_outlines_are_refused_by_field() {
    let square = json!([[0, 0], [1, 0], [1, 1], [0, 1]]);
    let cases = [
        (
            json!({}),
            "robots[0].shape",
            "one of `shape`, `parts` or `outline`",
        ),
        (
            json!({"parts": []}),
            "robots[0].parts",
            "at least one convex polygon",
        ),
        (
            json!({"shape": square, "parts": [square]}),
            "robots[0].parts",
            "`shape` and `parts` are both given",
        ),
        (
            json!({"parts": [square, [[0, 0], [2, 0], [1, 0.2], [2, 2], [0, 2]]]}),
            "robots[0].parts[1][2]",
            "not convex at vertex 2",
        ),
        (
            json!({"parts": [square, [[0, 0], [1, 1], [2, 2]]]}),
            "robots[0].parts[1]",
            "zero area",
        ),
        (
            json!({"outline": [[0, 0], [2, 2], [2, 0], [0, 2]]}),
            "robots[0].outline",
            "edges 0 and 2 cross",
        ),
        (
            json!({"outline": [[0, 0], [2, 0], [2, 1], [3, 1], [2, 1], [0, 1]]}),
            "robots[0].outline[3]",
            "doubles back at vertex 3",
        ),
        (
            // Vertex 5 repeats vertex 2: a figure eight that touches itself there.
            json!({"outline": [[0, 0], [2, 0], [1, 1], [2, 2], [0, 2], [1, 1]]}),
            "robots[0].outline",
            "cross",
        ),
        (
            json!({"outline": [[0, 0], [1, 1], [2, 2]]}),
            "robots[0].outline",
            "no area",
        ),
        (
            json!({"outline": [[0, 0], [1, 0, 3], [0, 1]]}),
            "robots[0].outline[1]",
            "[x, y]",
        ),
    ];
    for (body, field, reason) in cases {
        let (f, r) = refusal(body.clone());
        assert_eq!(f, field, "{body}: {r}");
        assert!(r.contains(reason), "{body}: {r}");
    }
}

/// Repairs are warnings, as for `shape`: a clockwise outline reversed, a straight vertex
/// dropped, named with the body and field.
#[test]
fn outline_repairs_are_warnings() {
    let text =
        scene_with(json!({"outline": [[0, 0], [0, 3], [1, 3], [1, 1], [2, 1], [4, 1], [4, 0]]}));
    let loaded = parse_scene(&text, Path::new("s.json")).unwrap();
    assert_eq!(loaded.warnings.len(), 2, "{:?}", loaded.warnings);
    assert!(
        loaded.warnings[0].starts_with("s.json: body \"R\", field `robots[0].outline`: vertex 4")
    );
    assert!(loaded.warnings[1].ends_with("vertices were clockwise; reversed"));
    assert_eq!(
        loaded.scene.bodies[0].parts.as_ref().map(|p| p.len()),
        Some(2)
    );
}

/// A scene of parts written and read back is the same scene; `outline` stays an outline.
#[test]
fn parts_and_outlines_are_written_as_given() {
    let text = json!({
        "robots": [{"name": "G", "parts": [[[-0.3, -0.3], [0.1, -0.3], [0.1, 0.3], [-0.3, 0.3]],
                                         [[0.1, 0.15], [0.6, 0.15], [0.6, 0.25], [0.1, 0.25]]],
                    "trajectory": [{"t": 0, "x": 0, "y": 0}, {"t": 1, "x": 1, "y": 0, "theta": 0.5}]}],
        "obstacles": [{"name": "U", "outline": [[2, -1], [3, -1], [3, 1], [2, 1], [2, 0.8],
                                                [2.8, 0.8], [2.8, -0.8], [2, -0.8]]}]
    })
    .to_string();
    let scene = parse_scene(&text, Path::new("s.json")).unwrap().scene;
    let doc = scene_document(&scene);
    assert_eq!(doc["robots"][0]["parts"].as_array().map(Vec::len), Some(2));
    assert_eq!(
        doc["obstacles"][0]["outline"].as_array().map(Vec::len),
        Some(8)
    );
    let again = parse_scene(&doc.to_string(), Path::new("copy.json"))
        .unwrap()
        .scene;
    assert_eq!(again.bodies[0], scene.bodies[0]);
    assert_eq!(
        again.bodies[1].parts.as_ref().unwrap().len(),
        scene.bodies[1].parts.as_ref().unwrap().len()
    );
}

/// `first_contact.parts` names the part of a body given by parts, null for a convex one,
/// and is left out between convex bodies.
#[test]
fn first_contact_names_the_parts() {
    let scene = |end: f64| {
        let text = json!({
            "delta": 0.01,
            "robots": [{"name": "G", "parts": [[[-0.3, -0.3], [0.1, -0.3], [0.1, 0.3], [-0.3, 0.3]],
                                             [[0.1, 0.15], [0.6, 0.15], [0.6, 0.25], [0.1, 0.25]],
                                             [[0.1, -0.25], [0.6, -0.25], [0.6, -0.15], [0.1, -0.15]]],
                        "trajectory": [{"t": 0, "x": -1, "y": 0}, {"t": 2, "x": end, "y": 0}]}],
            "obstacles": [{"name": "post", "shape": [[0.95, -0.05], [1.05, -0.05], [1.05, 0.05], [0.95, 0.05]]}]
        });
        parse_scene(&text.to_string(), Path::new("s.json"))
            .unwrap()
            .scene
    };
    // The fingers pass either side of the post: the hull would hit it, the parts do not.
    let free = check(&scene(0.5), &CheckOptions::default());
    assert!(!free.collision && free.certified);
    let hit = check(&scene(1.0), &CheckOptions::default());
    let c = hit.first_contact.unwrap();
    assert_eq!(
        c.parts,
        Some([Some(0), None]),
        "the palm, part 0, meets the post"
    );
    let json = serde_json::to_value(&c).unwrap();
    assert_eq!(json["parts"], json!([0, null]));
}

#[test]
fn cells_take_parts_and_outlines_and_keep_the_hull_as_shape() {
    let cell = |robot: Value| {
        json!({"delta": 0.01, "robots": [robot],
               "obstacles": [{"name": "U", "outline": [[2, -1], [3, -1], [3, 1], [2, 1], [2, 0.8],
                                                       [2.8, 0.8], [2.8, -0.8], [2, -0.8]]}],
               "tasks": [{"name": "t", "at": [2.4, 0], "duration": 1}]})
        .to_string()
    };
    let gripper = json!({"name": "G", "parts": [[[-0.2, -0.3], [0.0, -0.3], [0.0, 0.3], [-0.2, 0.3]],
                                                [[0.0, 0.2], [0.3, 0.2], [0.3, 0.3], [0.0, 0.3]],
                                                [[0.0, -0.3], [0.3, -0.3], [0.3, -0.2], [0.0, -0.2]]],
                         "home": [0, 0], "max_speed": 1, "max_accel": 1, "max_turn_rate": 1});
    let loaded = parse_cell(&cell(gripper), Path::new("c.json"))
        .unwrap()
        .cell;
    let (robot, bay) = (loaded.rigid(0), &loaded.obstacles[0]);
    assert_eq!(robot.pieces().len(), 3);
    assert_eq!(robot.parts.as_ref().unwrap().hull(), &robot.shape);
    // The outline is cut into convex parts; the hull is the bounding square.
    assert!(bay.pieces().len() >= 3);
    assert_eq!(bay.shape.len(), 4);
    // A task inside the bay's hull but outside the bay is taken; one in a wall is not.
    let text = cell(
        json!({"name": "R", "outline": [[0, 0], [0.2, 0], [0.2, 0.2], [0, 0.2]],
                           "home": [0, 0], "max_speed": 1, "max_accel": 1, "max_turn_rate": 1}),
    )
    .replace("[2.4,0]", "[2.9,0]");
    let e = parse_cell(&text, Path::new("c.json")).unwrap_err();
    assert_eq!(
        (e.body.as_deref(), e.field.as_str()),
        (Some("t"), "tasks[0].at")
    );
    assert!(e.reason.contains("inside obstacle \"U\""), "{e}");
    // A home inside the bay's hull, clear of its walls, is taken; one on a wall is not.
    let homed = |home: Value| {
        let mut doc: Value = serde_json::from_str(&cell(json!({"name": "R",
            "shape": [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]],
            "home": home, "max_speed": 1, "max_accel": 1, "max_turn_rate": 1})))
        .unwrap();
        doc["tasks"][0]["at"] = json!([0, 0]);
        parse_cell(&doc.to_string(), Path::new("c.json"))
    };
    assert!(homed(json!([2.4, 0])).is_ok());
    let e = homed(json!([2.9, 0])).unwrap_err();
    assert_eq!(e.field, "robots[0].home", "{e}");
    // A convex outline is one convex shape: no parts kept.
    let square = json!({"name": "R", "outline": [[0, 0], [0.2, 0], [0.2, 0.2], [0, 0.2]],
                        "home": [0, 0], "max_speed": 1, "max_accel": 1, "max_turn_rate": 1});
    let loaded = parse_cell(&cell(square), Path::new("c.json")).unwrap().cell;
    assert!(loaded.rigid(0).parts.is_none());
    // Both `shape` and `parts`: refused by name, as in scenes.
    let both = json!({"name": "R", "shape": [[0, 0], [0.2, 0], [0.2, 0.2]],
                      "parts": [[[0, 0], [0.2, 0], [0.2, 0.2]]],
                      "home": [0, 0], "max_speed": 1, "max_accel": 1, "max_turn_rate": 1});
    let e = parse_cell(&cell(both), Path::new("c.json")).unwrap_err();
    assert_eq!(e.field, "robots[0].parts");
}
