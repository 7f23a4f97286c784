//! workcell as a library, as the README's "Use as a library" section shows it:
//!
//! ```sh
//! cargo run --release --example library [-- CELL.json]
//! ```
//!
//! 1. Builds a scene in code (two square robots whose paths cross, and a post), checks it and
//!    prints the verdict: a contact. Starts the second robot 3 s later and checks again:
//!    free, certified.
//! 2. Loads a cell (default `cells/feedback-cell.json`), solves it and prints the schedule
//!    and the checker's verdict on it.

use std::error::Error;
use std::path::PathBuf;
use workcell::cell::load_cell;
use workcell::collision::{try_check, Body, CheckOptions, Scene, Verdict};
use workcell::geometry::ConvexPolygon;
use workcell::motion::{Pose, Trajectory};
use workcell::wcp::{self, SolveOptions};

/// R1 goes along y = 0 from x = 0 to 10 in 10 s, turning a quarter turn on the way; R2 goes
/// up x = 5 from y = -5 to 5 in 10 s, leaving at `r2_start` (> 0).
fn crossing(r2_start: f64) -> Result<Scene, Box<dyn Error>> {
    let square = ConvexPolygon::rectangle(1.0, 1.0)?;
    let r1 = Trajectory::from_poses([
        (0.0, Pose::new(0.0, 0.0, 0.0)),
        (10.0, Pose::new(10.0, 0.0, std::f64::consts::FRAC_PI_2)),
    ])?;
    // Velocities are derived from the poses, as a scene file without `vx`, `vy`, `omega`.
    let r2 = Trajectory::from_poses([
        (0.0, Pose::new(5.0, -5.0, 0.0)),
        (r2_start, Pose::new(5.0, -5.0, 0.0)),
        (r2_start + 10.0, Pose::new(5.0, 5.0, 0.0)),
    ])?;
    let post = ConvexPolygon::from_vertices(&[[8.0, 3.0], [9.0, 3.0], [9.0, 4.0], [8.0, 4.0]])?;
    let mut scene = Scene::new(0.01)?;
    scene
        .add(Body::robot("R1", square.clone(), r1))?
        .add(Body::robot("R2", square, r2))?
        .add(Body::obstacle("post", &post))?;
    Ok(scene)
}

fn main() -> Result<(), Box<dyn Error>> {
    for start in [1.0, 4.0] {
        let scene = crossing(start)?;
        // `try_check` refuses what the command line refuses (δ, tolerances, f64 precision).
        let report = try_check(&scene, &CheckOptions::default())?;
        println!("R2 leaving at t = {start}: {}", report.verdict());
        match report.verdict() {
            Verdict::Contact { contact, .. } => println!(
                "  {} and {} are {:.3e} apart at t = {:.6}",
                contact.bodies[0], contact.bodies[1], contact.distance, contact.time
            ),
            Verdict::Free { certified } => println!(
                "  free over [{}, {}], certified: {certified}",
                report.horizon[0], report.horizon[1]
            ),
            Verdict::Unresolved { budget } => println!("  unknown after t = {}", budget.time),
        }
    }

    let path = std::env::args().nth(1).map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cells/feedback-cell.json"),
        PathBuf::from,
    );
    let loaded = load_cell(&path)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let cell = &loaded.cell;
    let opts = SolveOptions::default();
    // `()` reports no progress; a type implementing `wcp::Progress` would.
    let prepared = wcp::prepare(cell, &opts, &())?;
    let solved = wcp::solve(cell, &prepared, &opts, &())?;
    println!(
        "{}: makespan {:.3} after {} rounds ({} schedules checked): {}",
        path.display(),
        solved.schedule.makespan,
        solved.iterations.len(),
        solved.nodes,
        solved.report.verdict()
    );
    for (robot, route) in cell.robots.iter().zip(&solved.routes) {
        let tasks: Vec<&str> = route.iter().map(|&k| cell.tasks[k].name.as_str()).collect();
        println!("  {}: {}", robot.name, tasks.join(" -> "));
    }
    if let Some(why) = &solved.failure {
        println!("  no collision-free schedule: {why}");
    }
    Ok(())
}
