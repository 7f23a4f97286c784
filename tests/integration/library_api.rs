//! The constructors and the verdict of the library API (issue 14, item 2): a scene built in
//! code is the scene its file describes, and the verdict says what the report's fields say.

use std::path::Path;
use workcell::cell::{load_cell, parse_scene, Cell};
use workcell::collision::{check, Body, CheckOptions, Method, Scene, Verdict};
use workcell::geometry::{ConvexPolygon, PolygonWarning};
use workcell::motion::{Pose, Trajectory};
use workcell::wcp::{prepare, solve, SolveOptions};

const SCENE: &str = r#"{"delta": 0.02, "robots": [
  {"name": "A", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
   "trajectory": [{"t": 0, "x": 0, "y": 0}, {"t": 1, "x": 3, "y": 1, "theta": 0.5},
                  {"t": 2.5, "x": 4, "y": 4, "theta": -1}]},
  {"name": "B", "shape": [[0,0],[0,1],[1,1],[1,0]],
   "trajectory": [{"t": 0.5, "x": 5, "y": 0}]}],
  "obstacles": [{"name": "wall", "shape": [[7,-1],[8,-1],[8,6],[7,6]]}]}"#;

fn built() -> Scene {
    let square = ConvexPolygon::rectangle(1.0, 1.0).unwrap();
    let a = Trajectory::from_poses([
        (0.0, Pose::new(0.0, 0.0, 0.0)),
        (1.0, Pose::new(3.0, 1.0, 0.5)),
        (2.5, Pose::new(4.0, 4.0, -1.0)),
    ])
    .unwrap();
    // Clockwise, as in the file: reversed with a warning.
    let b_shape =
        ConvexPolygon::from_vertices(&[[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]).unwrap();
    assert_eq!(b_shape.warnings(), &[PolygonWarning::Reversed]);
    let b = Trajectory::from_poses([(0.5, Pose::new(5.0, 0.0, 0.0))]).unwrap();
    let wall =
        ConvexPolygon::from_vertices(&[[7.0, -1.0], [8.0, -1.0], [8.0, 6.0], [7.0, 6.0]]).unwrap();
    let mut scene = Scene::new(0.02).unwrap();
    // Added out of order: robots still come first.
    scene
        .add(Body::robot("A", square, a))
        .unwrap()
        .add(Body::obstacle("wall", &wall))
        .unwrap()
        .add(Body::robot("B", b_shape, b))
        .unwrap();
    scene
}

#[test]
fn a_scene_built_in_code_is_the_scene_its_file_describes() {
    let loaded = parse_scene(SCENE, Path::new("scene.json")).unwrap();
    let scene = built();
    // Velocities included: the builder derives them by the file's rule.
    assert_eq!(scene, loaded.scene);
    let names: Vec<&str> = scene.bodies.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["A", "B", "wall"]);
    // The file reader reports the same repair the polygon carries.
    assert_eq!(loaded.warnings.len(), 1);
    assert!(loaded.warnings[0].contains(&PolygonWarning::Reversed.to_string()));
    let from_list = Scene::with_bodies(0.02, scene.bodies.iter().rev().cloned()).unwrap();
    let names: Vec<&str> = from_list.bodies.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["B", "A", "wall"]);
}

#[test]
fn derived_velocities_match_the_file_when_it_leaves_them_out() {
    let loaded = parse_scene(SCENE, Path::new("scene.json")).unwrap();
    let workcell::motion::Motion::Sampled(tr) = &loaded.scene.bodies[0].motion else {
        panic!("A is a robot");
    };
    let s = tr.samples();
    // Average of the slopes either side: (3, 1) and (4 - 3, 4 - 1) / 1.5.
    assert_eq!(s[1].vel.x, 0.5 * (3.0 + 1.0 / 1.5));
    assert_eq!(s[2].omega, -1.5 / 1.5);
    // A single sample rests.
    let workcell::motion::Motion::Sampled(tr) = &loaded.scene.bodies[1].motion else {
        panic!("B is a robot");
    };
    assert_eq!(
        (tr.samples()[0].vel.norm(), tr.samples()[0].omega),
        (0.0, 0.0)
    );
}

#[test]
fn names_must_be_unique_and_non_empty() {
    let mut scene = built();
    let square = ConvexPolygon::rectangle(1.0, 1.0).unwrap();
    let e = scene.add(Body::obstacle("A", &square)).unwrap_err();
    assert_eq!(e.body.as_deref(), Some("A"));
    assert_eq!(e.field, "bodies[3].name");
    assert_eq!(e.reason, "another body has the same name");
    let e = scene.add(Body::obstacle("", &square)).unwrap_err();
    assert_eq!(
        (e.body, e.reason.as_str()),
        (None, "a body needs a non-empty name")
    );
    assert_eq!(scene.bodies.len(), 3, "a refused body is not added");
    let twice = [Body::obstacle("p", &square), Body::obstacle("p", &square)];
    assert_eq!(
        Scene::with_bodies(1.0, twice).unwrap_err().field,
        "bodies[1].name"
    );
    for delta in [0.0, -0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(Scene::new(delta).unwrap_err().field, "delta", "{delta}");
        assert!(Scene::with_bodies(delta, []).is_err(), "{delta}");
    }
}

#[test]
fn warnings_stay_on_the_polygon_and_out_of_its_equality() {
    let messy = [[0.0, 0.0], [0.0, 0.0], [1.0, 1.0], [1.0, 0.0]];
    let (p, tuple) = ConvexPolygon::new(&messy).unwrap();
    let q = ConvexPolygon::from_vertices(&messy).unwrap();
    assert_eq!(q.warnings(), tuple.as_slice());
    assert_eq!(p.warnings(), tuple.as_slice());
    assert!(tuple.contains(&PolygonWarning::Reversed));
    assert!(tuple.contains(&PolygonWarning::RepeatedVertex(1)));
    // Moving the frame keeps them (an obstacle's shape is moved to its centroid).
    let o = Body::obstacle("o", &q);
    assert_eq!(o.shape.warnings(), tuple.as_slice());
    // The same polygon written counter-clockwise, from where the repaired one starts: no
    // warnings, and equal (warnings are not part of equality).
    let cw = ConvexPolygon::from_vertices(&[[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]]).unwrap();
    assert_eq!(cw.warnings(), &[PolygonWarning::Reversed]);
    let ccw: Vec<[f64; 2]> = cw.vertices().iter().map(|v| [v.x, v.y]).collect();
    let ccw = ConvexPolygon::from_vertices(&ccw).unwrap();
    assert!(ccw.warnings().is_empty());
    assert_eq!(ccw, cw);
}

/// Each verdict against the report's fields it sums up.
fn agrees(report: &workcell::collision::CheckReport) -> Verdict {
    let v = report.verdict();
    match &v {
        Verdict::Free { certified } => {
            assert!(!report.collision && report.budget_exhausted.is_none());
            assert_eq!(*certified, report.certified);
        }
        Verdict::Contact { contact, certified } => {
            assert!(report.collision);
            assert_eq!(Some(contact), report.first_contact.as_ref());
            assert_eq!(*certified, report.certified);
        }
        Verdict::Unresolved { budget } => {
            assert!(!report.collision && !report.certified);
            assert_eq!(Some(budget), report.budget_exhausted.as_ref());
        }
    }
    v
}

#[test]
fn the_verdict_sums_up_the_report() {
    let scene = built();
    let free = check(&scene, &CheckOptions::default());
    assert!(agrees(&free).is_certified_free(), "{}", free.verdict());

    // A's path passes through B's square at x = 5 when B sits at y = 0.5.
    let mut hit = built();
    let b = Trajectory::from_poses([(0.0, Pose::new(3.6, 2.0, 0.0))]).unwrap();
    hit.bodies[1].motion = workcell::motion::Motion::Sampled(b);
    let report = check(&hit, &CheckOptions::default());
    let v = agrees(&report);
    let c = v.contact().expect("a contact");
    assert_eq!(c.bodies, ["A".to_owned(), "B".to_owned()]);
    assert!(c.distance < 0.02 && c.time > 1.0 && c.time < 2.5, "{v}");
    assert!(v.to_string().starts_with("contact between A and B at t = "));

    let sampled = CheckOptions {
        method: Method::Sampled { step: 0.1 },
        ..CheckOptions::default()
    };
    let report = check(&scene, &sampled);
    assert_eq!(agrees(&report), Verdict::Free { certified: false });
    assert_eq!(report.verdict().to_string(), "free (not certified)");

    let starved = CheckOptions {
        max_work_per_pair: 3,
        ..CheckOptions::default()
    };
    let report = check(&hit, &starved);
    let v = agrees(&report);
    assert!(matches!(v, Verdict::Unresolved { .. }), "{v}");
    assert!(!v.is_certified_free() && v.contact().is_none());
}

/// `cell` rebuilt through `Cell::new` and the `add_*` methods, task robots by name.
fn rebuilt(cell: &Cell) -> Cell {
    let mut built = Cell::new(cell.delta).unwrap();
    for r in &cell.robots {
        built.add_robot(r.clone()).unwrap();
    }
    for o in &cell.obstacles {
        built.add_obstacle(o.clone()).unwrap();
    }
    for t in &cell.tasks {
        let names: Vec<&str> = t
            .robots
            .iter()
            .map(|&r| cell.robots[r].name.as_str())
            .collect();
        // The file's rule: a task that any robot may do lists none.
        let list = (names.len() < cell.robots.len()).then_some(names.as_slice());
        built.add_task(&t.name, t.at, t.duration, list).unwrap();
    }
    built.validate().unwrap();
    built
}

#[test]
fn a_cell_built_in_code_is_the_cell_its_file_describes_and_solves_the_same() {
    for name in ["feedback-cell.json", "four-robots-cell.json"] {
        let loaded = load_cell(Path::new(&crate::common::shipped(name)))
            .unwrap()
            .cell;
        let built = rebuilt(&loaded);
        assert_eq!(
            Cell {
                file: loaded.file.clone(),
                ..built.clone()
            },
            loaded,
            "{name}"
        );
        let opts = SolveOptions::default();
        let solve = |c: &Cell| solve(c, &prepare(c, &opts, &()).unwrap(), &opts, &()).unwrap();
        let (a, b) = (solve(&loaded), solve(&built));
        assert_eq!(
            (a.routes, a.schedule.makespan),
            (b.routes, b.schedule.makespan)
        );
    }
}

#[test]
fn a_cell_built_in_code_is_refused_where_its_file_would_be() {
    let loaded = load_cell(Path::new(&crate::common::shipped("feedback-cell.json")))
        .unwrap()
        .cell;
    let robot = loaded.robots[0].clone();
    let home = loaded.rigid(0).home;
    // The same messages as the file reader's, for the same faults.
    let mut cell = Cell::new(loaded.delta).unwrap();
    cell.add_robot(robot.clone()).unwrap();
    let e = cell.add_task(&robot.name, home, 1.0, None).unwrap_err();
    assert_eq!(e.field, "tasks[0].name");
    assert_eq!(e.reason, "the name is already used by robot `robots[0]`");
    let e = cell.add_task("t", home, -1.0, None).unwrap_err();
    assert_eq!(
        (e.field.as_str(), e.reason.as_str()),
        ("tasks[0].duration", "must be a non-negative number, got -1")
    );
    let e = cell.add_task("t", home, 1.0, Some(&[])).unwrap_err();
    assert_eq!(e.field, "tasks[0].robots");
    // What a file cannot hold and code can: a NaN pose.
    let mut bad = robot.clone();
    bad.name = "R9".into();
    if let workcell::cell::RobotKind::Rigid(rigid) = &mut bad.kind {
        rigid.home.theta = f64::NAN;
    }
    let e = cell.add_robot(bad).unwrap_err();
    assert_eq!(
        (e.body.as_deref(), e.field.as_str()),
        (Some("R9"), "robots[1].home")
    );
    let e = cell
        .add_task("t", Pose::new(f64::INFINITY, 0.0, 0.0), 1.0, None)
        .unwrap_err();
    assert_eq!(e.field, "tasks[0].at");
    for delta in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(Cell::new(delta).unwrap_err().field, "delta");
    }
    // Refused additions leave the cell as it was.
    assert_eq!((cell.robots.len(), cell.tasks.len()), (1, 0));
    // A second robot at the first one's home: found by `validate`, as by the file reader.
    let mut twin = robot.clone();
    twin.name = "R9".into();
    cell.add_robot(twin).unwrap();
    let e = cell.validate().unwrap_err();
    assert_eq!(e.field, "robots[1].home");
}
