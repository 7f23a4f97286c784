//! Arms in `solve` (issue 22): schedules of SCARA cells checked here independently of the
//! solver, against the contract: the checker certifies the exported scene, every joint stays
//! within its limits and speed, every task is done once with the tool on its pose.

use std::path::Path;
use workcell::cell::{load_cell, Cell};
use workcell::collision::{check, CheckOptions};
use workcell::motion::tool_pose;
use workcell::wcp::{prepare, solve, Activity, SolveOptions, Solved};

fn scara() -> Cell {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/scara-cell.json");
    load_cell(Path::new(path)).unwrap().cell
}

fn solved(cell: &Cell, opts: &SolveOptions) -> Solved {
    solve(cell, &prepare(cell, opts, &()).unwrap(), opts, &()).unwrap()
}

/// What every schedule of arms must be, checked from its samples alone.
fn assert_valid(cell: &Cell, s: &Solved) {
    // The scene `--export-scene` writes, checked again: certified free.
    let report = check(&s.schedule.scene(cell), &CheckOptions::default());
    assert!(
        report.verdict().is_certified_free(),
        "{:?}",
        report.verdict()
    );
    let mut done = vec![0; cell.tasks.len()];
    for (r, plan) in s.schedule.robots.iter().enumerate() {
        let Some(arm) = cell.robots[r].as_arm() else {
            for seg in &plan.segments {
                if let Activity::Work(t) = seg.activity {
                    done[t] += 1;
                }
            }
            continue;
        };
        let lengths = arm.lengths();
        let joints = &plan.joints;
        assert_eq!(joints.len(), plan.samples.len());
        assert_eq!(joints[0].q, arm.home, "starts at home");
        for (j, range) in arm.limits.range.iter().enumerate() {
            for w in joints.windows(2) {
                // The motion between samples is linear: its speed is the chord's.
                let speed = (w[1].q[j] - w[0].q[j]).abs() / (w[1].t - w[0].t);
                let max = arm.limits.max_speed[j];
                assert!(
                    speed <= max * (1.0 + 1e-9),
                    "{}: joint {j} at {speed} > {max}",
                    cell.robots[r].name
                );
            }
            if let Some([lo, hi]) = range {
                assert!(
                    joints.iter().all(|s| (*lo..=*hi).contains(&s.q[j])),
                    "joint {j} off its limits"
                );
            }
        }
        let last = joints.last().unwrap();
        for (j, (&q, &home)) in last.q.iter().zip(&arm.home).enumerate() {
            let whole = ((q - home) / std::f64::consts::TAU).round();
            assert!(
                (q - home - whole * std::f64::consts::TAU).abs() < 1e-9
                    && (whole == 0.0 || arm.limits.range[j].is_none()),
                "ends at home"
            );
        }
        for seg in &plan.segments {
            if let Activity::Work(t) = seg.activity {
                done[t] += 1;
                for at in [seg.start, (seg.start + seg.end) / 2.0, seg.end] {
                    let tool = tool_pose(arm.base, &lengths, &plan.q_at(at));
                    let task = &cell.tasks[t];
                    assert!(
                        (tool.pos - task.at.pos).norm() < 1e-9,
                        "the tool on {}",
                        task.name
                    );
                }
            }
        }
    }
    assert!(done.iter().all(|&n| n == 1), "every task once: {done:?}");
}

#[test]
fn the_shipped_scara_cell_is_solved_and_certified() {
    let cell = scara();
    let s = solved(&cell, &SolveOptions::default());
    assert_valid(&cell, &s);
    // The arms meet over the table: the blind schedule collides and feedback separates them
    // (the figures of the README's table of shipped cells).
    assert!(s.iterations.len() > 1, "the arms meet");
    assert_eq!(format!("{:.3}", s.blind_makespan), "10.211");
    assert_eq!(format!("{:.3}", s.schedule.makespan), "10.211");
}

#[test]
fn arm_solves_are_deterministic() {
    let cell = scara();
    let (a, b) = (
        solved(&cell, &SolveOptions::default()),
        solved(&cell, &SolveOptions::default()),
    );
    assert_eq!(a.routes, b.routes);
    assert_eq!(a.schedule.makespan, b.schedule.makespan);
}

/// Issue 22, item 6: `generate --kind scara` writes cells that read, whose every task 1 to 3
/// arms may do, some arms bending their elbow one way only, some cells with a rigid robot
/// too; each solves to a certified schedule.
#[test]
fn generated_scara_cells_solve_and_certify() {
    use workcell::generate::{generate_scara_cell, ScaraRequest};
    let req = ScaraRequest { arms: 3, tasks: 8 };
    let mut one_way = 0;
    for k in 0..3 {
        let doc = generate_scara_cell(&req, 7, k).unwrap();
        assert_eq!(
            doc,
            generate_scara_cell(&req, 7, k).unwrap(),
            "deterministic"
        );
        let cell = workcell::cell::parse_cell(&doc.to_string(), Path::new("g.json"))
            .unwrap()
            .cell;
        let arms = cell.robots.iter().filter(|r| r.as_arm().is_some()).count();
        assert_eq!(arms, 3);
        assert_eq!(
            cell.robots.len() > arms,
            k == 2,
            "a rigid robot in every third cell"
        );
        for t in &cell.tasks {
            let by_arms = t
                .robots
                .iter()
                .filter(|&&r| cell.robots[r].as_arm().is_some())
                .count();
            assert!((1..=3).contains(&by_arms), "{}: {by_arms} arms", t.name);
        }
        one_way += (cell.robots.iter().filter_map(|r| r.as_arm()))
            .filter(|a| a.limits.range[1].is_some_and(|[lo, hi]| lo > 0.0 || hi < 0.0))
            .count();
        let s = solved(&cell, &SolveOptions::default());
        assert!(s.collision_free, "{:?}", s.failure);
        assert_valid(&cell, &s);
    }
    assert!(one_way > 0, "some elbows bend one way only");
}

/// Issue 22, item 3: the configurations chosen with the routes are never worse, collision
/// blind, than the fixed choices they start from.
#[test]
fn chosen_configurations_beat_fixed_ones() {
    use workcell::generate::{generate_scara_cell, ScaraRequest};
    use workcell::wcp::{choose_configurations, sequence, ConfigurationChoice};
    let doc = generate_scara_cell(&ScaraRequest { arms: 4, tasks: 16 }, 1, 0).unwrap();
    let cell = workcell::cell::parse_cell(&doc.to_string(), Path::new("g.json"))
        .unwrap()
        .cell;
    let blind = |configurations| {
        let opts = SolveOptions {
            configurations,
            ..SolveOptions::default()
        };
        let prepared = prepare(&cell, &opts, &()).unwrap();
        let prepared = choose_configurations(&cell, &prepared, &opts, &())
            .unwrap()
            .unwrap_or(prepared);
        sequence(&cell, &prepared, &[], &opts).unwrap().makespan
    };
    let chosen = blind(ConfigurationChoice::Chosen);
    assert!(chosen <= blind(ConfigurationChoice::First));
    assert!(chosen <= blind(ConfigurationChoice::NearestHome));
}

/// `workcell generate --kind scara` writes cells `solve` takes; a bad size is exit 2.
#[cfg(feature = "cli")]
#[test]
fn generate_scara_from_the_command_line() {
    use crate::common::{temp_dir_made, workcell};
    let dir = temp_dir_made("arm-solve", "generate");
    let out = dir.to_str().unwrap();
    let o = workcell(&[
        "generate", "--kind", "scara", "--seed", "3", "--robots", "2", "--tasks", "5", "--out", out,
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let file = dir.join("scara-2x5-3-0.json");
    let o = workcell(&["solve", file.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    for bad in [vec!["--robots", "9"], vec!["--fixtures", "2"]] {
        let mut args = vec!["generate", "--kind", "scara", "--seed", "3", "--out", out];
        args.extend(bad);
        let o = workcell(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
    }
}

/// Issue 22, item 4: `evaluate` replays an arm cell's result (its configurations, waits and
/// slower legs) to the same makespan, certified; without the waits it finds the collision;
/// joint angles that are not a configuration at the task are refused by field.
#[cfg(feature = "cli")]
#[test]
fn evaluate_replays_arm_results() {
    use crate::common::{temp_dir_made, workcell};
    use serde_json::Value;
    use workcell::generate::{generate_scara_cell, ScaraRequest};
    let dir = temp_dir_made("arm-solve", "evaluate");
    let generated = dir.join("scara-6x12-1-1.json");
    let doc = generate_scara_cell(&ScaraRequest { arms: 6, tasks: 12 }, 1, 1).unwrap();
    std::fs::write(&generated, doc.to_string()).unwrap();
    let scara = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/scara-cell.json");
    let json = |o: &std::process::Output| -> Value {
        serde_json::from_slice(&o.stdout)
            .unwrap_or_else(|_| panic!("{}", String::from_utf8_lossy(&o.stderr)))
    };
    let mut slowed = None;
    for cell in [scara, generated.to_str().unwrap()] {
        // A node budget, not a time limit: the same answer on any machine.
        let solved = json(&workcell(&[
            "solve",
            cell,
            "--json",
            "--search-nodes",
            "200",
        ]));
        assert_eq!(solved["collision_free"], true);
        if solved["legs"].as_array().is_some_and(|l| !l.is_empty()) {
            slowed = Some((cell, solved.clone()));
        }
        let result = dir.join("result.json");
        std::fs::write(&result, solved.to_string()).unwrap();
        let o = workcell(&["evaluate", cell, result.to_str().unwrap(), "--json"]);
        assert_eq!(o.status.code(), Some(0));
        let replayed = json(&o);
        assert_eq!(replayed["makespan"], solved["makespan"], "{cell}");
        assert_eq!(replayed["collision_free"], true);
    }
    let (cell, solved) = slowed.expect("a slower arm leg replayed");
    // An arm's changed leg gives its joint-space waypoints; bad ones are refused by field.
    let go = &solved["legs"][0]["pieces"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p.get("go").is_some())
        .expect("a motion")["go"];
    let joints = go["joints"].as_array().expect("an arm's waypoints");
    assert!(joints.len() >= 2 && go["primitives"].as_array().unwrap().is_empty());
    let at = |s: &Value| -> String {
        let legs = s["legs"][0]["pieces"].as_array().unwrap();
        let j = legs.iter().position(|p| p.get("go").is_some()).unwrap();
        format!("legs[0].pieces[{j}].go.joints")
    };
    let field = at(&solved);
    let tampered = |edit: &dyn Fn(&mut Value)| -> (Option<i32>, String) {
        let mut s = solved.clone();
        let pieces = s["legs"][0]["pieces"].as_array_mut().unwrap();
        let go = pieces.iter_mut().find(|p| p.get("go").is_some()).unwrap();
        edit(&mut go["go"]["joints"]);
        let result = dir.join("tampered.json");
        std::fs::write(&result, s.to_string()).unwrap();
        let o = workcell(&["evaluate", cell, result.to_str().unwrap()]);
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stderr).into_owned(),
        )
    };
    // One angle too many.
    let (code, err) = tampered(&|j| j[0].as_array_mut().unwrap().push(0.0.into()));
    assert!(
        code == Some(2) && err.contains(&format!("{field}[0]")),
        "{err}"
    );
    // Far outside any joint's limits (the generated arms' joints all have limits).
    let (code, err) = tampered(&|j| j[1][1] = 40.0.into());
    assert!(
        code == Some(2) && err.contains(&format!("{field}[1]")),
        "{err}"
    );
    // Starting elsewhere than the arm stands: a jump, named by its leg.
    let (code, err) = tampered(&|j| {
        let a = j[0][0].as_f64().unwrap();
        j[0][0] = (a + 0.01).into();
    });
    assert!(code == Some(2) && err.contains("legs[0]"), "{err}");
    // The shipped cell's arms collide without their wait.
    let mut solved = json(&workcell(&["solve", scara, "--json"]));
    solved.as_object_mut().unwrap().remove("waits");
    let result = dir.join("no-wait.json");
    std::fs::write(&result, solved.to_string()).unwrap();
    let o = workcell(&["evaluate", scara, result.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    // A configuration off the task.
    solved["configurations"]["A1"][0][0] = serde_json::json!(0.123);
    std::fs::write(&result, solved.to_string()).unwrap();
    let o = workcell(&["evaluate", scara, result.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("configurations.A1[0]") && err.contains("not a configuration"),
        "{err}"
    );
}

/// Issue 22, item 4: an arm detours in joint space round an idle arm in its way, or the idle
/// arm draws in while the other passes; `evaluate` replays either (its joint-space
/// waypoints) to the same makespan, certified. Time alone cannot help: the idle arm never
/// leaves.
#[cfg(feature = "cli")]
#[test]
fn arms_detour_and_step_aside_in_joint_space() {
    use crate::common::{temp_dir_made, workcell};
    use serde_json::Value;
    let cell = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/cells/arm-crossing.json");
    let dir = temp_dir_made("arm-solve", "crossing");
    for remedy in ["detour", "step-aside"] {
        let o = workcell(&["solve", cell, "--json", "--remedies", remedy]);
        assert_eq!(o.status.code(), Some(0), "{remedy}");
        let solved: Value = serde_json::from_slice(&o.stdout).unwrap();
        let used: Vec<&str> = (solved["feedback"].as_array().unwrap().iter())
            .filter_map(|r| r["remedy"].as_str())
            .collect();
        assert!(
            !used.is_empty() && used.iter().all(|r| *r == remedy),
            "{used:?}"
        );
        let result = dir.join(format!("{remedy}.json"));
        std::fs::write(&result, solved.to_string()).unwrap();
        let o = workcell(&["evaluate", cell, result.to_str().unwrap(), "--json"]);
        assert_eq!(o.status.code(), Some(0), "{remedy}");
        let replayed: Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(replayed["makespan"], solved["makespan"], "{remedy}");
        assert_eq!(replayed["collision_free"], true);
    }
    for remedy in ["wait", "pause", "slow"] {
        let o = workcell(&["solve", cell, "--remedies", remedy]);
        assert_eq!(o.status.code(), Some(1), "{remedy}");
    }
    // A pause splits an arm's move at a configuration on its way: replayed the same.
    let doc = workcell::generate::generate_scara_cell(
        &workcell::generate::ScaraRequest { arms: 6, tasks: 24 },
        1,
        0,
    )
    .unwrap();
    let generated = dir.join("scara-6x24-1-0.json");
    std::fs::write(&generated, doc.to_string()).unwrap();
    let cell = generated.to_str().unwrap();
    let o = workcell(&[
        "solve",
        cell,
        "--json",
        "--remedies",
        "pause",
        "--search-nodes",
        "100",
    ]);
    assert_eq!(o.status.code(), Some(0));
    let solved: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(solved["feedback"][0]["remedy"], "pause");
    let result = dir.join("pause.json");
    std::fs::write(&result, solved.to_string()).unwrap();
    let o = workcell(&["evaluate", cell, result.to_str().unwrap(), "--json"]);
    let replayed: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(replayed["makespan"], solved["makespan"]);
    assert_eq!(replayed["collision_free"], true);
}

/// Issue 22, item 4: with `reconfigure`, the search may switch an arm's configuration at the
/// task of a collision; the result records the new one (in `configurations` and in the
/// round), and `evaluate` replays it to the same makespan. Without it, that configuration
/// is not the one taken there.
#[cfg(feature = "cli")]
#[test]
fn the_search_may_switch_an_arms_configuration() {
    use crate::common::{temp_dir_made, workcell};
    use serde_json::Value;
    use workcell::generate::{generate_scara_cell, ScaraRequest};
    let dir = temp_dir_made("arm-solve", "reconfigure");
    let doc = generate_scara_cell(&ScaraRequest { arms: 6, tasks: 24 }, 2, 0).unwrap();
    let cell = dir.join("scara-6x24-2-0.json");
    std::fs::write(&cell, doc.to_string()).unwrap();
    let cell = cell.to_str().unwrap();
    let all = "resequence,wait,pause,slow,detour,step-aside,reconfigure";
    let run = |remedies: &str| -> Value {
        let o = workcell(&[
            "solve",
            cell,
            "--json",
            "--search-nodes",
            "200",
            // All of them to the first pass, where reconfigurations are offered.
            "--second-pass-share",
            "0",
            "--remedies",
            remedies,
        ]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let solved = run(all);
    let rounds = solved["feedback"].as_array().unwrap();
    let at = (rounds.iter())
        .position(|r| r["remedy"] == "reconfigure")
        .expect("a reconfiguration on the answer's branch");
    let change = &rounds[at]["reconfigure"];
    let (arm, task) = (
        change["robot"].as_str().unwrap(),
        change["at"].as_str().unwrap(),
    );
    // Where the arm still does that task, the result gives the new configuration; only a
    // later re-sequencing may have given the task to another robot.
    let done = (solved["sequences"][arm].as_array().unwrap().iter()).position(|t| t == task);
    match done {
        Some(k) => assert_eq!(solved["configurations"][arm][k], change["joints"]),
        None => assert!(
            rounds[at..].iter().any(|r| r["remedy"] == "resequence"),
            "{arm} no longer does {task}, yet nothing re-sequenced it"
        ),
    }
    let result = dir.join("result.json");
    std::fs::write(&result, solved.to_string()).unwrap();
    let o = workcell(&["evaluate", cell, result.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(0));
    let replayed: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(replayed["makespan"], solved["makespan"]);
    assert_eq!(replayed["collision_free"], true);
    // By default the search keeps the configurations chosen with the routes.
    let default = run("resequence,wait,pause,slow,detour,step-aside");
    let used =
        (default["feedback"].as_array().unwrap().iter()).any(|r| r["remedy"] == "reconfigure");
    assert!(!used);
}
