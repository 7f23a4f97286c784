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
    // The arms meet over the table: the blind schedule collides and feedback separates them.
    assert!(s.iterations.len() > 1, "the arms meet");
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
