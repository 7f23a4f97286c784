//! Solving cells whose robots and fixtures are made of parts (issue 20, item 3): the planner
//! grows each part, homes and task poses are checked part by part, and the feedback loop's
//! checks see the parts. Each schedule is checked again here with the independent oracle,
//! part against part, at dense instants.

use crate::common::{exact_distance, place, shipped, shipped_cell, solve_with};
use serde_json::json;
use std::path::Path;
use workcell::cell::{parse_cell, Cell};
use workcell::geometry::Vec2;
use workcell::wcp::{SolveOptions, Solved};

/// The least oracle distance, over `instants` evenly spread instants of the schedule and
/// every pair of parts, between each robot and every obstacle and other robot; with its time.
fn least_gap(cell: &Cell, solved: &Solved, instants: usize) -> (f64, f64) {
    let end = solved.schedule.makespan;
    let mut least = (f64::INFINITY, 0.0);
    for k in 0..=instants {
        let t = end * k as f64 / instants as f64;
        let robot_parts = |r: usize| -> Vec<Vec<Vec2>> {
            let p = solved.schedule.robots[r].pose_at(t);
            cell.rigid(r)
                .pieces()
                .iter()
                .map(|q| place(q.vertices(), [p.pos.x, p.pos.y, p.theta]))
                .collect()
        };
        let placed: Vec<_> = (0..cell.robots.len()).map(robot_parts).collect();
        let mut gap = |a: &[Vec2], b: &[Vec2]| {
            let d = exact_distance(a, b);
            if d < least.0 {
                least = (d, t);
            }
        };
        for (r, parts) in placed.iter().enumerate() {
            for part in parts {
                for o in &cell.obstacles {
                    for q in o.pieces() {
                        gap(part, q.vertices());
                    }
                }
                for other in &placed[r + 1..] {
                    for q in other {
                        gap(part, q);
                    }
                }
            }
        }
    }
    least
}

/// Certified free, and no instant the oracle samples closer than δ within the grazing
/// allowance.
fn assert_free(cell: &Cell, solved: &Solved, opts: &SolveOptions) {
    assert!(solved.collision_free, "{:?}", solved.failure);
    let (gap, t) = least_gap(cell, solved, 4000);
    let floor = cell.delta * (1.0 - opts.check.grazing_tol);
    assert!(
        gap >= floor,
        "parts {gap:e} apart at t = {t}, under {floor:e}"
    );
}

#[test]
fn the_bay_cell_is_solved_where_hulls_would_block_it() {
    let cell = shipped_cell("bay-cell.json");
    let opts = SolveOptions::default();
    let solved = solve_with(&cell, &opts);
    assert_free(&cell, &solved, &opts);
    let task = |name: &str| cell.tasks.iter().position(|t| t.name == name).unwrap();
    assert!(solved.routes[0].contains(&task("inside")));
    assert!(solved.routes[1].contains(&task("grip")));
    // R1 works inside the bay's hull; G holds the post inside its own hull, between its
    // fingers.
    let (bay, post) = (&cell.obstacles[0], &cell.obstacles[1]);
    let inside = cell.tasks[task("inside")].at;
    let r1 = place(
        cell.rigid(0).shape.vertices(),
        [inside.pos.x, inside.pos.y, 0.0],
    );
    assert_eq!(exact_distance(&r1, bay.shape.vertices()), 0.0);
    let grip = cell.tasks[task("grip")].at;
    let g_hull = place(
        cell.rigid(1).shape.vertices(),
        [grip.pos.x, grip.pos.y, 0.0],
    );
    assert_eq!(exact_distance(&g_hull, post.shape.vertices()), 0.0);

    // The same cell with the bay or the gripper given as its hull is refused, naming why.
    let text = std::fs::read_to_string(shipped("bay-cell.json")).unwrap();
    let mut doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    doc["obstacles"][0] = json!({"name": "bay", "shape": [[2, -2], [6, -2], [6, 2], [2, 2]]});
    let e = parse_cell(&doc.to_string(), Path::new("bay-hull.json")).unwrap_err();
    assert_eq!(
        (e.body.as_deref(), e.field.as_str()),
        (Some("inside"), "tasks[0].at")
    );
    let mut doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    doc["robots"][1].as_object_mut().unwrap().remove("parts");
    doc["robots"][1]["shape"] = json!([[-0.4, -0.5], [0.8, -0.5], [0.8, 0.5], [-0.4, 0.5]]);
    let hull = parse_cell(&doc.to_string(), Path::new("g-hull.json"))
        .unwrap()
        .cell;
    let e = workcell::wcp::prepare(&hull, &opts, &())
        .err()
        .expect("refused");
    assert_eq!(
        (e.body.as_deref(), e.field.as_str()),
        (Some("grip"), "tasks[2].at")
    );
    assert!(e.reason.contains("\"post\""), "{e}");
}

/// Two grippers, fingers forward, swap ends of a hall head on: the blind plan has them meet,
/// the feedback loop separates them, part by part.
#[test]
fn grippers_that_meet_head_on_are_separated_by_the_feedback() {
    let gripper = |name: &str, home: [f64; 3]| {
        json!({"name": name,
               "parts": [[[-0.3, -0.4], [0.0, -0.4], [0.0, 0.4], [-0.3, 0.4]],
                         [[0.0, 0.25], [0.6, 0.25], [0.6, 0.4], [0.0, 0.4]],
                         [[0.0, -0.4], [0.6, -0.4], [0.6, -0.25], [0.0, -0.25]]],
               "home": home, "max_speed": 1, "max_accel": 2, "max_turn_rate": 1.5})
    };
    let text = json!({
        "delta": 0.01,
        "robots": [gripper("G1", [0.0, 0.0, 0.0]), gripper("G2", [8.0, 0.2, std::f64::consts::PI])],
        "obstacles": [{"name": "wall", "outline": [[-2, 1.5], [10, 1.5], [10, 2], [-2, 2]]}],
        "tasks": [{"name": "east", "at": [7.0, 0.2, 0.0], "duration": 1, "robots": ["G1"]},
                  {"name": "west", "at": [1.0, 0.0, std::f64::consts::PI], "duration": 1, "robots": ["G2"]}]
    })
    .to_string();
    let cell = parse_cell(&text, Path::new("head-on.json")).unwrap().cell;
    let opts = SolveOptions::default();
    let solved = solve_with(&cell, &opts);
    assert!(
        solved.iterations.len() >= 2 && solved.iterations[0].collision.is_some(),
        "the blind plan should collide: {:?}",
        solved.iterations
    );
    assert_free(&cell, &solved, &opts);
}
