//! What the property tests share: an independent oracle for the distance of two convex
//! polygons, the placing of a shape at a pose, pose interpolation, generators of convex
//! shapes and a few helpers.
//!
//! The oracle shares no code with the library: it places the vertices itself, takes the
//! smallest vertex-to-edge distance in both directions, and decides overlap by a
//! point-in-polygon test (either way round) and a segment-intersection test over all edge
//! pairs, with orientations exact in sign (the `robust` crate), so that its overlap verdict
//! is exact for the vertices as placed. It computes on plain arrays rather than nalgebra (the test profile is
//! unoptimised, and `checker_props` runs it on thousands of instants per scene), and reads
//! vertices given as `[f64; 2]` or as `Vec2`.

// Each test binary uses only part of this module.
#![allow(dead_code)]

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{FileFailurePersistence, RngSeed, TestRunner};
use std::f64::consts::{PI, TAU};
use std::ops::{Range, RangeInclusive};
use workcell::geometry::ConvexPolygon;

pub mod arm_reference;
mod oracle;
pub use oracle::*;

/// The unit square with its lower left corner at (x, y).
pub fn unit_square(x: f64, y: f64) -> Shape {
    vec![[x, y], [x + 1.0, y], [x + 1.0, y + 1.0], [x, y + 1.0]]
}

// ---------------------------------------------------------------------------------------
// Generators
// ---------------------------------------------------------------------------------------

/// `sides` random angles on an ellipse (counter-clockwise) of radii drawn from `radii`,
/// centred at an offset drawn from `offset` in x and in y: the frame origin (the rotation
/// centre) is not necessarily at the centre, nor even inside.
pub fn ellipse_shape(
    sides: RangeInclusive<usize>,
    radii: Range<f64>,
    offset: Range<f64>,
) -> impl Strategy<Value = Shape> {
    sides
        .prop_flat_map(move |n| {
            (
                prop::collection::vec(0.2f64..1.0, n),
                radii.clone(),
                radii.clone(),
                0.0..TAU,
                offset.clone(),
                offset.clone(),
            )
        })
        .prop_map(|(w, rx, ry, phase, cx, cy)| {
            let total: f64 = w.iter().sum();
            let mut acc = phase;
            w.iter()
                .map(|wi| {
                    let a = acc;
                    acc += wi / total * TAU;
                    [cx + rx * a.cos(), cy + ry * a.sin()]
                })
                .collect()
        })
}

/// Andrew's monotone chain, strictly convex, counter-clockwise.
pub fn hull(mut pts: Vec<Pt>) -> Shape {
    pts.sort_by(|p, q| p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1])));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut h: Shape = Vec::new();
    for pass in 0..2 {
        let start = h.len();
        let iter: Box<dyn Iterator<Item = &Pt>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while h.len() >= start + 2 && orient(h[h.len() - 2], h[h.len() - 1], p) <= 0.0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

/// Convex hull of random points in a square of half side drawn from `scale`, centred at an
/// offset drawn from `offset` in x and in y.
pub fn hull_shape(scale: Range<f64>, offset: Range<f64>) -> impl Strategy<Value = Shape> {
    (
        prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 3..24),
        scale,
        offset.clone(),
        offset,
    )
        .prop_filter_map("degenerate hull", |(pts, s, cx, cy)| {
            let h = hull(pts.iter().map(|&(x, y)| [cx + s * x, cy + s * y]).collect());
            let n = h.len();
            if n < 3 {
                return None;
            }
            let area2: f64 = (0..n)
                .map(|i| {
                    let (p, q) = (h[i], h[(i + 1) % n]);
                    p[0] * q[1] - p[1] * q[0]
                })
                .sum();
            (area2 > 1e-3 * s * s).then_some(h)
        })
}

/// An axis-aligned rectangle of half sides drawn from `half`, centred at an offset drawn
/// from `offset` in x and in y.
pub fn rectangle_shape(half: Range<f64>, offset: Range<f64>) -> impl Strategy<Value = Shape> {
    (half.clone(), half, offset.clone(), offset).prop_map(|(w, h, cx, cy)| {
        vec![
            [cx - w, cy - h],
            [cx + w, cy - h],
            [cx + w, cy + h],
            [cx - w, cy + h],
        ]
    })
}

/// Regular polygon with an even number of vertices, of circumradius drawn from `radius`,
/// centred at an offset drawn from `offset` in x and in y: opposite edges are parallel, and
/// the edge normals are at multiples of 2π/n, so two of them at the same angle share
/// parallel edges.
pub fn regular_shape(radius: Range<f64>, offset: Range<f64>) -> impl Strategy<Value = Shape> {
    (
        prop::sample::select(vec![4usize, 6, 8, 10, 12, 14, 16]),
        radius,
        offset.clone(),
        offset,
    )
        .prop_map(|(n, r, cx, cy)| {
            (0..n)
                .map(|k| {
                    let a = (2 * k + 1) as f64 * PI / n as f64;
                    [cx + r * a.cos(), cy + r * a.sin()]
                })
                .collect()
        })
}

/// The library's polygon of a generated shape, which it must accept.
pub fn polygon(s: &[Pt]) -> ConvexPolygon {
    ConvexPolygon::new(s)
        .unwrap_or_else(|e| panic!("generated polygon refused: {e}: {s:?}"))
        .0
}

/// The configuration of every property test: `cases` cases from a fixed seed, after the
/// failures ever found, which are kept beside the test file (`NAME.proptest-regressions`).
pub fn proptest_config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        rng_seed: RngSeed::Fixed(0x5eed_0013),
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..ProptestConfig::with_cases(cases)
    }
}

/// One value of `strategy`, outside of a property (no shrinking).
pub fn draw<S: Strategy>(strategy: &S, runner: &mut TestRunner) -> S::Value {
    strategy.new_tree(runner).unwrap().current()
}

/// Runs the `workcell` binary with `args`.
pub fn workcell(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_workcell"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// The path of a shipped file under `cells/`.
pub fn shipped(name: &str) -> String {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("cells")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

/// A thin tip of length 1 spinning `turns` times about G, a quarter turn per sample, past
/// a wall δ·(1 + 10⁻⁹) beyond its reach: free, but the first-order condition proves each
/// pass only in about 10⁴ pieces.
pub fn spinning_tip(turns: usize) -> String {
    let samples: Vec<String> = (0..=4 * turns)
        .map(|k| {
            let theta = k as f64 * std::f64::consts::FRAC_PI_2;
            format!(
                r#"{{"t": {}, "x": 0, "y": 0, "theta": {theta}}}"#,
                k as f64 * 0.25
            )
        })
        .collect();
    let g = 1.0 + 0.001 * (1.0 + 1e-9);
    format!(
        r#"{{"delta": 0.001, "robots": [{{"name": "tip", "shape": [[-0.05,-0.01],[1,0],[-0.05,0.01]],
        "trajectory": [{}]}}], "obstacles": [{{"name": "wall", "shape": [[{g},-5],[{},-5],[{},5],[{g},5]]}}]}}"#,
        samples.join(","),
        g + 1.0,
        g + 1.0
    )
}

/// A cell shipped under `cells/`, read.
pub fn shipped_cell(name: &str) -> workcell::cell::Cell {
    workcell::cell::load_cell(shipped(name).as_ref())
        .unwrap()
        .cell
}

/// `prepare` and `solve` with `opts`, on a cell known to be usable.
pub fn solve_with(
    cell: &workcell::cell::Cell,
    opts: &workcell::wcp::SolveOptions,
) -> workcell::wcp::Solved {
    let prepared = workcell::wcp::prepare(cell, opts, &()).expect("a usable cell");
    workcell::wcp::solve(cell, &prepared, opts, &()).expect("a usable cell")
}

/// The solved schedule's exported scene, read back as a user's `check` would read it, is
/// certified collision-free: the scene read.
pub fn assert_export_certified(
    cell: &workcell::cell::Cell,
    solved: &workcell::wcp::Solved,
) -> workcell::collision::Scene {
    use workcell::cell::{parse_scene, scene_document};
    use workcell::collision::{check, CheckOptions};
    assert!(solved.collision_free, "{:?}", solved.failure);
    let text = serde_json::to_string(&scene_document(&solved.schedule.scene(cell))).unwrap();
    let scene = parse_scene(&text, std::path::Path::new("exported.json"))
        .expect("the export is a valid scene")
        .scene;
    let report = check(&scene, &CheckOptions::default());
    assert!(
        !report.collision && report.certified,
        "{:?}",
        report.first_contact
    );
    scene
}

/// `f` run on a pool of `threads` threads (for tests that the thread count changes nothing).
pub fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

/// A folder of this test run for test `test` of module `module`: made, and kept for the
/// run (files in it are written over).
pub fn temp_dir_made(module: &str, test: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("workcell-{module}-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A folder of this test run that does not exist yet (the command under test makes it).
pub fn temp_dir_absent(module: &str, test: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("workcell-{module}-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}
