//! Arms in cell files (contract section 7): read with their joints' limits, every fault named
//! by file, body and field, and each task's configurations found or refused with each arm's
//! reason.

use serde_json::{json, Value};
use std::path::Path;
use workcell::cell::{parse_cell, Cell, InputError};
use workcell::motion::{tool_pose, IkSettings};
use workcell::wcp::task_configurations;

/// A SCARA-like arm of two links of 1 m with its base at `x`.
fn arm(name: &str, x: f64) -> Value {
    let bar = json!([[-0.1, -0.1], [1.1, -0.1], [1.1, 0.1], [-0.1, 0.1]]);
    json!({"name": name, "base": [x, 0.0],
           "links": [{"length": 1.0, "shape": bar}, {"length": 1.0, "shape": bar}],
           "home": [1.2, 1.0], "joint_limits": [[-2.6, 2.6], [-2.4, 2.4]],
           "max_joint_speed": [2.0, 3.0], "max_joint_accel": 4.0})
}

fn cell_of(robots: Vec<Value>, obstacles: Value, tasks: Value) -> String {
    json!({"delta": 0.01, "robots": robots, "obstacles": obstacles, "tasks": tasks}).to_string()
}

/// One arm (changed by `edit`) and a task in its reach.
fn one_arm(edit: impl FnOnce(&mut Value)) -> String {
    let mut a = arm("A1", 0.0);
    edit(&mut a);
    cell_of(
        vec![a],
        json!([]),
        json!([{"name": "t", "at": [1.2, 0.8], "duration": 1}]),
    )
}

fn read(text: &str) -> Result<Cell, InputError> {
    parse_cell(text, Path::new("arms.json")).map(|l| l.cell)
}

fn refused(text: &str, body: &str, field: &str, says: &str) {
    let e = read(text).expect_err("the cell must be refused");
    assert_eq!(
        (e.body.as_deref(), e.field.as_str()),
        (Some(body), field),
        "{e}"
    );
    assert!(e.reason.contains(says), "{e}");
    assert!(e.to_string().starts_with("arms.json: "), "{e}");
}

#[test]
fn an_arm_is_read_with_its_joints() {
    let cell = read(&one_arm(|_| {})).unwrap();
    let a = cell.robots[0].as_arm().expect("an arm");
    assert_eq!(a.base.theta, 0.0); // `[x, y]`: angle 0
    assert_eq!(a.links.len(), 2);
    assert_eq!(a.home, [1.2, 1.0]);
    assert_eq!(a.limits.range, [Some([-2.6, 2.6]), Some([-2.4, 2.4])]);
    assert_eq!(a.limits.max_speed, [2.0, 3.0]);
    assert_eq!(a.limits.max_accel, [4.0, 4.0]); // one number for every joint
    assert!(cell.tasks[0].free_angle); // `[x, y]`: the tool's angle is free
                                       // No `joint_limits`, or `null` for one joint: that joint turns freely.
    let free = read(&one_arm(|a| {
        a.as_object_mut().unwrap().remove("joint_limits");
    }))
    .unwrap();
    assert_eq!(free.robots[0].as_arm().unwrap().limits.range, [None, None]);
    let one = read(&one_arm(|a| a["joint_limits"] = json!([null, [-2.0, 2.0]]))).unwrap();
    assert_eq!(
        one.robots[0].as_arm().unwrap().limits.range,
        [None, Some([-2.0, 2.0])]
    );
}

/// A change to an arm's JSON.
type Edit = Box<dyn FnOnce(&mut Value)>;

/// Issue 22, item 7: each fault of an arm named by file, body and field.
#[test]
fn bad_arms_are_named() {
    let cases: Vec<(Edit, &str, &str)> = vec![
        (
            Box::new(|a| a["home"] = json!([2.9, 0.0])),
            "robots[0].home[0]",
            "outside its joint limits",
        ),
        (
            Box::new(|a| a["home"] = json!([0.0])),
            "robots[0].home",
            "one angle per joint",
        ),
        (
            Box::new(|a| a["joint_limits"] = json!([[-1, 1]])),
            "robots[0].joint_limits",
            "one [min, max] per joint",
        ),
        (
            Box::new(|a| a["joint_limits"] = json!([[1, -1], [-2, 2]])),
            "robots[0].joint_limits[0]",
            "min < max",
        ),
        (
            Box::new(|a| a["max_joint_speed"] = json!([2.0, 0.0])),
            "robots[0].max_joint_speed[1]",
            "positive",
        ),
        (
            Box::new(|a| a["max_joint_speed"] = json!(-1.0)),
            "robots[0].max_joint_speed[0]",
            "positive",
        ),
        (
            Box::new(|a| a["max_joint_accel"] = json!([1.0, 2.0, 3.0])),
            "robots[0].max_joint_accel",
            "3 values for 2 joints",
        ),
        (
            Box::new(|a| {
                a.as_object_mut().unwrap().remove("max_joint_accel");
            }),
            "robots[0].max_joint_accel",
            "missing field",
        ),
        (
            Box::new(|a| a["shape"] = json!([[0, 0], [1, 0], [1, 1]])),
            "robots[0].shape",
            "not `shape`",
        ),
        (
            Box::new(|a| a["max_speed"] = json!(1.0)),
            "robots[0].max_speed",
            "not `max_speed`",
        ),
        (
            Box::new(|a| a["links"][1]["length"] = json!(-1.0)),
            "robots[0].links[1].length",
            ">= 0",
        ),
        (
            Box::new(|a| a["base"] = json!([0])),
            "robots[0].base",
            "[x, y, theta]",
        ),
    ];
    for (edit, field, says) in cases {
        refused(&one_arm(edit), "A1", field, says);
    }
    // A rigid robot with an arm's key.
    let rigid = json!({"name": "R1", "shape": [[-0.3, -0.3], [0.3, -0.3], [0.3, 0.3]], "home": [5, 5],
                       "max_speed": 1, "max_accel": 1, "max_turn_rate": 1, "max_joint_speed": 1});
    let text = cell_of(vec![rigid], json!([]), json!([]));
    refused(
        &text,
        "R1",
        "robots[0].max_joint_speed",
        "belongs to an arm",
    );
}

#[test]
fn an_arm_at_home_clear_of_fixtures_and_other_arms() {
    // A post on link 1 at home (the arm's home angles point it up and to the left).
    let (c, s) = (1.2f64.cos(), 1.2f64.sin());
    let (x, y) = (0.5 * c, 0.5 * s);
    let post = json!([{"name": "post", "shape": [[x - 0.1, y - 0.1], [x + 0.1, y - 0.1], [x + 0.1, y + 0.1], [x - 0.1, y + 0.1]]}]);
    let text = cell_of(vec![arm("A1", 0.0)], post, json!([]));
    refused(&text, "A1", "robots[0].home", "from obstacle \"post\"");
    // Two arms whose homes overlap: the second is named.
    let text = cell_of(vec![arm("A1", 0.0), arm("A2", 0.3)], json!([]), json!([]));
    refused(&text, "A2", "robots[1].home", "from robot \"A1\"");
    // Far enough apart: read.
    let text = cell_of(vec![arm("A1", 0.0), arm("A2", 5.0)], json!([]), json!([]));
    assert!(read(&text).is_ok());
}

/// Issue 22, item 1: every configuration that puts the tool on the task, or each arm's reason.
#[test]
fn task_configurations_or_each_arms_reason() {
    let tasks = json!([{"name": "both", "at": [1.2, 0.8], "duration": 1}]);
    let text = cell_of(vec![arm("A1", 0.0)], json!([]), tasks);
    let cell = read(&text).unwrap();
    let found = task_configurations(&cell, &IkSettings::default()).unwrap();
    let a = cell.robots[0].as_arm().unwrap();
    let lengths: Vec<f64> = a.links.iter().map(|l| l.0).collect();
    // Two links and a point: elbow up and elbow down, each on the task.
    assert_eq!(found.at(0, 0).len(), 2);
    assert_ne!(found.at(0, 0)[0], found.at(0, 0)[1]);
    for q in found.at(0, 0) {
        let tool = tool_pose(a.base, &lengths, q);
        assert!((tool.pos - cell.tasks[0].at.pos).norm() < 1e-9);
    }
    let refuse = |tasks: Value, obstacles: Value, says: &str| {
        let text = cell_of(vec![arm("A1", 0.0), arm("A2", 6.0)], obstacles, tasks);
        let cell = read(&text).unwrap();
        let e = task_configurations(&cell, &IkSettings::default()).unwrap_err();
        assert_eq!(
            (e.body.as_deref(), e.field.as_str()),
            (Some("t"), "tasks[0].at"),
            "{e}"
        );
        assert!(e.reason.contains(says), "{e}");
        e
    };
    // Out of both arms' reach: each arm named with its reason.
    let e = refuse(
        json!([{"name": "t", "at": [3.0, 3.0], "duration": 1}]),
        json!([]),
        "\"A1\": out of reach",
    );
    assert!(e.reason.contains("\"A2\": out of reach"), "{e}");
    // Two links cannot also choose the tool's angle there.
    refuse(
        json!([{"name": "t", "at": [1.2, 0.8, 0.3], "duration": 1}]),
        json!([]),
        "\"A1\": out of reach",
    );
    // Behind A1 (x < 0 needs the first joint past its limits), A2 only.
    let e = refuse(
        json!([{"name": "t", "at": [-1.9, 0.0], "duration": 1, "robots": ["A1"]}]),
        json!([]),
        "reachable only outside its joint limits",
    );
    assert!(!e.reason.contains("A2"), "A2 may not do the task: {e}");
    // A post at each elbow (elbow up and elbow down): every configuration puts a link in one.
    let (phi, alpha) = (0.8f64.atan2(1.2), (1.2f64.hypot(0.8) / 2.0).acos());
    let post = |name: &str, angle: f64| {
        let (x, y) = (angle.cos(), angle.sin());
        let h = 0.04;
        json!({"name": name, "shape": [[x - h, y - h], [x + h, y - h], [x + h, y + h], [x - h, y + h]]})
    };
    let mut a1 = arm("A1", 0.0);
    a1["home"] = json!([-1.0, 0.5]); // clear of both posts
    let text = cell_of(
        vec![a1],
        json!([post("up", phi + alpha), post("down", phi - alpha)]),
        json!([{"name": "t", "at": [1.2, 0.8], "duration": 1}]),
    );
    let cell = read(&text).unwrap();
    let e = task_configurations(&cell, &IkSettings::default()).unwrap_err();
    assert_eq!(e.field, "tasks[0].at", "{e}");
    assert!(
        e.reason
            .contains("\"A1\": reachable only with a link inside a fixture"),
        "{e}"
    );
}

/// The command line states a bad arm, and an unreachable task, with exit 2.
#[cfg(feature = "cli")]
#[test]
fn solve_names_a_bad_arm_with_exit_2() {
    use crate::common::{temp_dir_made, workcell};
    let dir = temp_dir_made("arm-cells", "cli");
    let run = |name: &str, text: String| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let o = workcell(&["solve", path.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let err = run("home.json", one_arm(|a| a["home"] = json!([2.9, 0.0])));
    assert!(
        err.contains("home.json") && err.contains("\"A1\"") && err.contains("robots[0].home[0]"),
        "{err}"
    );
    let far = cell_of(
        vec![arm("A1", 0.0)],
        json!([]),
        json!([{"name": "far", "at": [5.0, 0.0], "duration": 1}]),
    );
    let err = run("far.json", far);
    assert!(
        err.contains("tasks[0].at") && err.contains("out of reach"),
        "{err}"
    );
}
