//! The report does not depend on the number of threads, on scenes crowded enough that the
//! checker takes its parallel paths: 10 robots and 3 obstacles (75 pairs) go through the
//! space-time broad phase, and the pairs it keeps are checked on the thread pool, where a
//! pair's contact stops the others at different places from run to run.
//!
//! The two-robot scenes of `checker_props` (at most 3 pairs) run neither path, so their
//! comparison of thread counts could not fail.

use crate::common::{draw, ellipse_shape, polygon};
use proptest::prelude::*;
use proptest::test_runner::TestRunner;
use rayon::ThreadPoolBuilder;
use workcell::collision::{check, Body, CheckOptions, CheckReport, Scene};
use workcell::geometry::Vec2;
use workcell::motion::{Sample, Trajectory};

const ROBOTS: usize = 10;
const OBSTACLES: usize = 3;
/// Pitch of the grid of home cells: neighbours reach into each other's cell.
const PITCH: f64 = 2.5;
/// Crowds checked.
const SCENES: usize = 200;

/// A robot about the centre of its cell `k`: 4 to 14 samples on its own time grid within
/// [0, 10], wandering up to 1 from the centre and turning up to 1 rad per sample.
fn robot(k: usize) -> impl Strategy<Value = Body> {
    let home = Vec2::new(PITCH * (k % 4) as f64, PITCH * (k / 4) as f64);
    (
        ellipse_shape(3..=8, 0.1..0.4, -0.1..0.1),
        prop::collection::vec(
            (0.05f64..1.5, -1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0),
            4..=14,
        ),
        0.0f64..1.0,
    )
        .prop_map(move |(shape, steps, t0)| {
            let (mut t, mut theta) = (t0, 0.0);
            let samples = steps
                .iter()
                .map(|&(dt, x, y, turn)| {
                    t += dt;
                    theta += turn;
                    Sample {
                        t,
                        pos: home + Vec2::new(x, y),
                        theta,
                        vel: Vec2::zeros(),
                        omega: 0.0,
                    }
                })
                .collect();
            Body::robot(
                format!("r{k}"),
                polygon(&shape),
                Trajectory::new(samples).unwrap(),
            )
        })
}

/// An obstacle in one of the two spare cells of the grid's last row, or between cells.
fn obstacle(k: usize) -> impl Strategy<Value = Body> {
    (
        ellipse_shape(3..=6, 0.2..0.6, 0.0..0.01),
        0.0f64..4.0 * PITCH,
        0.0f64..3.0 * PITCH,
    )
        .prop_map(move |(shape, x, y)| {
            let world: Vec<[f64; 2]> = shape.iter().map(|p| [p[0] + x, p[1] + y]).collect();
            Body::obstacle(format!("o{k}"), &polygon(&world))
        })
}

fn crowd(runner: &mut TestRunner) -> Scene {
    let mut bodies: Vec<Body> = (0..ROBOTS).map(|k| draw(&robot(k), runner)).collect();
    bodies.extend((0..OBSTACLES).map(|k| draw(&obstacle(k), runner)));
    Scene {
        delta: 0.01,
        bodies,
    }
}

#[test]
fn crowded_scenes_give_the_same_report_on_1_2_and_4_threads() {
    let mut runner = TestRunner::deterministic();
    let pools: Vec<_> = [1, 2, 4]
        .iter()
        .map(|&n| ThreadPoolBuilder::new().num_threads(n).build().unwrap())
        .collect();
    let opts = CheckOptions {
        per_pair: true,
        ..CheckOptions::default()
    };
    let (mut free, mut later, mut pruned, mut parallel) = (0, 0, 0, 0);
    for k in 0..SCENES {
        let scene = crowd(&mut runner);
        let outside: CheckReport = check(&scene, &opts);
        // The parallel paths are taken: the broad phase (from 16 pairs) and the pool (from 4).
        assert_eq!(outside.pairs + outside.pairs_pruned, 75);
        parallel += usize::from(outside.pairs >= 4);
        pruned += usize::from(outside.pairs_pruned > 0);
        match &outside.first_contact {
            None => free += 1,
            Some(c) if c.time > outside.horizon[0] => later += 1,
            Some(_) => {}
        }
        for (pool, n) in pools.iter().zip([1, 2, 4]) {
            for _ in 0..3 {
                let inside = pool.install(|| check(&scene, &opts));
                assert_eq!(inside, outside, "scene {k} on {n} threads");
            }
        }
    }
    let counts = format!(
        "{free} free, {later} colliding after the start, {pruned} pruned, {parallel} on the pool"
    );
    eprintln!("{SCENES} crowds: {counts}");
    // Both kinds of verdict, contacts that stop other pairs part of the way, both paths.
    assert!(
        free >= 20 && later >= 80 && pruned >= 180 && parallel >= 100,
        "{counts}"
    );
}
