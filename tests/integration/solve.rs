//! `solve` end to end on the shipped cells: the schedules are checked by the checker, every
//! task is done once by an allowed robot for its duration, and the feedback loop acts.

use crate::common::{assert_export_certified, shipped, solve_with};
use std::path::Path;
use workcell::cell::{load_cell, parse_cell, Cell};
use workcell::collision::{check, CheckOptions};
use workcell::planning::rest_to_rest_time;
use workcell::wcp::{self, Activity, Feedback, Remedy, RemedyKind, SolveOptions, Solved};

fn solve(cell: &Cell, seed: u64) -> Solved {
    let mut opts = SolveOptions::default();
    opts.sequencer.seed = seed;
    solve_with(cell, &opts)
}

/// Every property the issue asks of a shipped cell's solution.
fn assert_valid_solution(cell: &Cell, solved: &Solved) {
    let scene = assert_export_certified(cell, solved);
    // Every task once, by an allowed robot, for its duration, at its pose.
    let mut done = vec![0; cell.tasks.len()];
    for (r, plan) in solved.schedule.robots.iter().enumerate() {
        let trajectory = scene.bodies[r].motion.clone();
        let samples = plan.samples.clone();
        assert_eq!(samples[0].t, 0.0);
        assert_eq!(samples[0].pos, cell.rigid(r).home.pos, "starts at home");
        assert_eq!(
            samples.last().unwrap().pos,
            cell.rigid(r).home.pos,
            "ends at home"
        );
        for seg in &plan.segments {
            if let Activity::Work(t) = seg.activity {
                done[t] += 1;
                assert!(
                    cell.tasks[t].robots.contains(&r),
                    "task {t} by a robot not allowed"
                );
                assert!(
                    (seg.end - seg.start - cell.tasks[t].duration).abs() <= 1e-9 * seg.end.max(1.0)
                );
                for time in [seg.start, (seg.start + seg.end) / 2.0, seg.end] {
                    let pose = trajectory.pose_at(time);
                    assert!(
                        (pose.pos - cell.tasks[t].at.pos).norm() < 1e-9,
                        "robot {r} away from task {t} at {time}"
                    );
                    let turns = (pose.theta - cell.tasks[t].at.theta) / std::f64::consts::TAU;
                    assert!(
                        (turns - turns.round()).abs() < 1e-9,
                        "robot {r} at task {t} with angle {}",
                        pose.theta
                    );
                }
            }
        }
    }
    assert!(done.iter().all(|&n| n == 1), "tasks done {done:?} times");
    // The makespan is the end of the last trajectory.
    let last = scene.horizon().1;
    assert_eq!(solved.schedule.makespan, last);
}

#[test]
fn shipped_cells_get_verified_schedules() {
    for name in [
        "paper-cell.json",
        "feedback-cell.json",
        "four-robots-cell.json",
    ] {
        let cell = load_cell(Path::new(&shipped(name))).unwrap().cell;
        let solved = solve(&cell, 0);
        assert_valid_solution(&cell, &solved);
    }
}

#[test]
fn the_hall_cell_scales() {
    let cell = load_cell(Path::new(&shipped("hall-cell.json")))
        .unwrap()
        .cell;
    assert!(cell.robots.len() >= 12 && cell.tasks.len() >= 120);
    let solved = solve(&cell, 0);
    assert_valid_solution(&cell, &solved);
}

#[test]
fn the_feedback_cell_needs_resequencing_and_ends_collision_free() {
    let cell = load_cell(Path::new(&shipped("feedback-cell.json")))
        .unwrap()
        .cell;
    let solved = solve(&cell, 0);
    let first = &solved.iterations[0];
    assert!(
        first.collision.is_some(),
        "the collision-blind schedule collides"
    );
    assert_eq!(first.makespan, solved.blind_makespan);
    assert!(solved
        .iterations
        .iter()
        .any(|i| i.remedy == Some(Remedy::RESEQUENCE)));
    assert!(solved.collision_free);
    assert!(solved.schedule.makespan >= solved.blind_makespan * (1.0 - 1e-12));
    // Evaluating the blind routes finds the same collision.
    let blind = wcp::solve(
        &cell,
        &wcp::prepare(
            &cell,
            &SolveOptions {
                max_iterations: 1,
                ..Default::default()
            },
            &(),
        )
        .unwrap(),
        &SolveOptions {
            max_iterations: 1,
            ..Default::default()
        },
        &(),
    )
    .unwrap();
    let given = workcell::cell::Sequences {
        routes: blind.routes.clone(),
        ..Default::default()
    };
    let evaluated = wcp::evaluate(
        &cell,
        &given,
        &SolveOptions::default(),
        Path::new("seq.json"),
    )
    .unwrap();
    assert_eq!(
        evaluated.collision.as_ref().map(|c| c.time),
        first.collision.as_ref().map(|c| c.time)
    );
}

#[test]
fn every_planned_move_is_clear_and_no_faster_than_the_straight_line_bound() {
    let cell = load_cell(Path::new(&shipped("four-robots-cell.json")))
        .unwrap()
        .cell;
    let opts = SolveOptions::default();
    let obstacles = cell.obstacle_bodies();
    for r in 0..cell.robots.len() {
        let robot = cell.rigid(r);
        let name = &cell.robots[r].name;
        let nodes = wcp::robot_nodes(&cell, r);
        for &a in &nodes {
            for &b in &nodes {
                if a >= b {
                    continue;
                }
                let m = wcp::certified_move(&cell, r, a, b, &opts.planner, &obstacles)
                    .expect("every move exists here");
                // Checked again here, independently of the table that certified it.
                let mut bodies = vec![workcell::collision::Body::robot(
                    name.clone(),
                    robot.shape.clone(),
                    workcell::motion::Trajectory::new(m.samples.clone()).unwrap(),
                )];
                bodies.extend(obstacles.iter().cloned());
                let report = check(
                    &workcell::collision::Scene {
                        delta: cell.delta,
                        bodies,
                    },
                    &CheckOptions::default(),
                );
                assert!(!report.collision && report.certified);
                let (pa, pb) = (wcp::node_pose(&cell, r, a), wcp::node_pose(&cell, r, b));
                let bound =
                    rest_to_rest_time((pb.pos - pa.pos).norm(), robot.max_speed, robot.max_accel);
                assert!(
                    m.duration >= bound * (1.0 - 1e-12),
                    "{} < {bound}",
                    m.duration
                );
            }
        }
    }
}

#[test]
fn the_same_seed_gives_the_same_schedule() {
    let cell = load_cell(Path::new(&shipped("four-robots-cell.json")))
        .unwrap()
        .cell;
    let (a, b) = (solve(&cell, 7), solve(&cell, 7));
    assert_eq!(a.routes, b.routes);
    assert_eq!(a.schedule.makespan, b.schedule.makespan);
}

#[test]
fn an_enclosed_task_is_an_input_error_naming_it() {
    let wall = |name: &str, x0: f64, y0: f64, x1: f64, y1: f64| {
        format!(
            r#"{{"name": "{name}", "shape": [[{x0},{y0}],[{x1},{y0}],[{x1},{y1}],[{x0},{y1}]]}}"#
        )
    };
    let walls = [
        wall("south", 4.0, 4.0, 8.0, 4.5),
        wall("north", 4.0, 7.5, 8.0, 8.0),
        wall("west", 4.0, 4.5, 4.5, 7.5),
        wall("east", 7.5, 4.5, 8.0, 7.5),
    ]
    .join(",");
    let text = format!(
        r#"{{"delta": 0.01, "robots": [{{"name": "R1", "shape": [[-0.3,-0.3],[0.3,-0.3],[0.3,0.3],[-0.3,0.3]],
            "home": [0, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1.5}}],
            "obstacles": [{walls}],
            "tasks": [{{"name": "free", "at": [2, 2], "duration": 1}}, {{"name": "boxed", "at": [6, 6], "duration": 1}}]}}"#
    );
    let cell = parse_cell(&text, Path::new("boxed.json")).unwrap().cell;
    let e = wcp::prepare(&cell, &SolveOptions::default(), &())
        .err()
        .expect("the boxed task is unreachable");
    assert_eq!(
        (e.field.as_str(), e.body.as_deref()),
        ("tasks[1].at", Some("boxed"))
    );
    assert!(e.reason.contains("R1"), "{e}");
}

#[test]
fn crossing_robots_with_forced_tasks_are_separated_by_a_delay_or_better() {
    // Each robot may do only the task on the other's side: the straight moves cross at the
    // same time, and no re-sequencing can avoid it.
    let robot = |name: &str, x: f64| {
        format!(
            r#"{{"name": "{name}", "shape": [[-0.3,-0.3],[0.3,-0.3],[0.3,0.3],[-0.3,0.3]],
                "home": [{x}, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1.5}}"#
        )
    };
    let text = format!(
        r#"{{"delta": 0.01, "robots": [{}, {}], "tasks": [
            {{"name": "east", "at": [10, 3], "duration": 1, "robots": ["R1"]}},
            {{"name": "west", "at": [0, 3], "duration": 1, "robots": ["R2"]}}]}}"#,
        robot("R1", 0.0),
        robot("R2", 10.0)
    );
    let cell = parse_cell(&text, Path::new("crossing.json")).unwrap().cell;
    let greedy = SolveOptions {
        feedback: Feedback::Greedy,
        ..SolveOptions::default()
    };
    let solved = solve_with(&cell, &greedy);
    assert!(
        solved.iterations[0].collision.is_some(),
        "the blind schedule collides"
    );
    assert!(solved.iterations.iter().any(|i| i
        .remedy
        .as_ref()
        .is_some_and(|r| matches!(r.kind, RemedyKind::Wait { .. }))));
    assert!(solved.schedule.robots.iter().any(|r| r
        .segments
        .iter()
        .any(|s| matches!(s.activity, Activity::Wait(_)))));
    assert_valid_solution(&cell, &solved);
    assert!(solved.schedule.makespan > solved.blind_makespan);
    // The search has the greedy loop's remedies and more: never worse.
    let searched = solve(&cell, 0);
    assert_valid_solution(&cell, &searched);
    assert!(searched.schedule.makespan <= solved.schedule.makespan);
    assert!(searched.schedule.makespan > searched.blind_makespan);
}

/// One or two unit-limit square robots and the given tasks and obstacles (JSON fragments).
fn small_cell(robots: &[(&str, &str)], obstacles: &str, tasks: &str) -> Cell {
    let robots: Vec<String> = robots
        .iter()
        .map(|(name, home)| {
            format!(
                r#"{{"name": "{name}", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
                    "home": {home}, "max_speed": 1, "max_accel": 1, "max_turn_rate": 1}}"#
            )
        })
        .collect();
    let text = format!(
        r#"{{"delta": 0.01, "robots": [{}], "obstacles": [{obstacles}], "tasks": [{tasks}]}}"#,
        robots.join(",")
    );
    parse_cell(&text, Path::new("small.json")).unwrap().cell
}

#[test]
fn task_durations_f64_rounds_away_are_refused_not_dropped() {
    // 2 + 1e-16 rounds to 2: the task would have no length on the time axis, as a 1000 s
    // task after moves of 1e20 s would. The cell shows it: refused when read (issue 13).
    let robot = r#"{"name": "R1", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
                    "home": [0, 0], "max_speed": 1, "max_accel": 1, "max_turn_rate": 1}"#;
    let text = format!(
        r#"{{"robots": [{robot}], "tasks": [{{"name": "t", "at": [1, 0], "duration": 1e-16}}]}}"#
    );
    let e = parse_cell(&text, Path::new("small.json")).expect_err("refused");
    assert_eq!(
        (e.field.as_str(), e.body.as_deref()),
        ("tasks[0].duration", Some("t"))
    );
    // After a task of 1e17 only the schedule shows it: refused like moves that vanish.
    let cell = small_cell(
        &[("R1", "[0, 0]")],
        "",
        r#"{"name": "long", "at": [1, 0], "duration": 1e17},
           {"name": "t", "at": [2, 0], "duration": 1}"#,
    );
    let opts = SolveOptions::default();
    let prepared = wcp::prepare(&cell, &opts, &()).unwrap();
    let e = wcp::solve(&cell, &prepared, &opts, &()).expect_err("refused");
    assert_eq!(e.body.as_deref(), Some("R1"));
    assert!(e.reason.contains("orders of magnitude"), "{e}");
    let zero = small_cell(
        &[("R1", "[0, 0]")],
        "",
        r#"{"name": "t", "at": [1, 0], "duration": 0}"#,
    );
    assert_valid_solution(&zero, &solve(&zero, 0));
}

#[test]
fn time_scales_f64_cannot_hold_together_are_refused_not_dropped() {
    // After a task of 1e17, the way home (seconds) would vanish in rounding.
    let cell = small_cell(
        &[("R1", "[0, 0]")],
        "",
        r#"{"name": "t", "at": [1, 0], "duration": 1e17}"#,
    );
    let opts = SolveOptions::default();
    let prepared = wcp::prepare(&cell, &opts, &()).unwrap();
    let e = wcp::solve(&cell, &prepared, &opts, &()).expect_err("refused");
    assert_eq!(
        (e.field.as_str(), e.body.as_deref()),
        ("robots[0]", Some("R1"))
    );
    assert!(e.reason.contains("orders of magnitude"), "{e}");
}

#[test]
fn a_home_too_close_to_turn_from_is_blamed_not_its_task() {
    // 1.01 delta from the wall: legal, but below the planner's clearance of delta + 2%.
    let wall = r#"{"name": "wall", "shape": [[0.5101,-1],[2,-1],[2,1],[0.5101,1]]}"#;
    let task = r#"{"name": "t1", "at": [-3, 0], "duration": 1, "robots": ["R1"]}"#;
    let cell = small_cell(&[("R1", "[0, 0]"), ("R2", "[0, 5]")], wall, task);
    let e = wcp::prepare(&cell, &SolveOptions::default(), &())
        .err()
        .expect("refused");
    assert_eq!(
        (e.field.as_str(), e.body.as_deref()),
        ("robots[0].home", Some("R1"))
    );
    assert!(e.reason.contains("\"wall\""), "{e}");
    // A robot with no task never leaves such a home, and needs no move.
    let cell = small_cell(
        &[("R1", "[0, 0]"), ("R2", "[0, 5]")],
        wall,
        &task.replace("R1", "R2"),
    );
    assert_valid_solution(&cell, &solve(&cell, 0));
}

#[test]
fn a_shortened_wait_never_parks_a_robot_where_it_is_hit_for_good() {
    // Found by review: half of R0's wait got it home before R1 came by, and a robot back
    // home can no longer be delayed. Waits are only shortened when that cannot happen.
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/cells/parked-after-a-short-wait.json");
    let cell = load_cell(&path).unwrap().cell;
    assert_valid_solution(&cell, &solve(&cell, 0));
}
