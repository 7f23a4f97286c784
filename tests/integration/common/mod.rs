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
use workcell::geometry::{ConvexPolygon, Vec2};

// ---------------------------------------------------------------------------------------
// Points
// ---------------------------------------------------------------------------------------

pub type Pt = [f64; 2];

/// A polygon's vertices as the generators make them (counter-clockwise, body frame).
pub type Shape = Vec<Pt>;

/// A point the oracle can read and `place` can write: `[f64; 2]` or `Vec2`.
pub trait Point: Copy {
    fn xy(self) -> Pt;
    fn from_xy(p: Pt) -> Self;
}

impl Point for Pt {
    fn xy(self) -> Pt {
        self
    }
    fn from_xy(p: Pt) -> Self {
        p
    }
}

impl Point for Vec2 {
    fn xy(self) -> Pt {
        [self.x, self.y]
    }
    fn from_xy([x, y]: Pt) -> Self {
        Vec2::new(x, y)
    }
}

pub fn sub(a: Pt, b: Pt) -> Pt {
    [a[0] - b[0], a[1] - b[1]]
}

pub fn dot(a: Pt, b: Pt) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// World vertices: R(theta)·p + (x, y), computed here rather than by `Posed`.
pub fn place<P: Point>(local: &[P], [x, y, theta]: [f64; 3]) -> Vec<P> {
    let (s, c) = theta.sin_cos();
    local
        .iter()
        .map(|p| {
            let [px, py] = p.xy();
            P::from_xy([c * px - s * py + x, s * px + c * py + y])
        })
        .collect()
}

/// The mean of the vertices.
pub fn centroid<P: Point>(poly: &[P]) -> P {
    let [x, y] = poly.iter().fold([0.0, 0.0], |[x, y], p| {
        let [px, py] = p.xy();
        [x + px, y + py]
    });
    P::from_xy([x / poly.len() as f64, y / poly.len() as f64])
}

/// The largest distance from `c` to a vertex.
pub fn radius_about<P: Point>(poly: &[P], c: P) -> f64 {
    poly.iter()
        .map(|p| {
            let [dx, dy] = sub(p.xy(), c.xy());
            dx.hypot(dy)
        })
        .fold(0.0, f64::max)
}

/// The pose of samples `[t, x, y, theta]` by linear interpolation in (x, y, θ), resting at
/// the ends: written here, not taken from the library.
pub fn pose_at(samples: &[[f64; 4]], t: f64) -> [f64; 3] {
    let first = samples[0];
    let last = samples[samples.len() - 1];
    if t <= first[0] {
        return [first[1], first[2], first[3]];
    }
    if t >= last[0] {
        return [last[1], last[2], last[3]];
    }
    let k = samples.iter().rposition(|s| s[0] <= t).unwrap();
    let (p, q) = (samples[k], samples[k + 1]);
    lerp_pose(p, q, (t - p[0]) / (q[0] - p[0]))
}

/// The pose at fraction `u` of the way from sample `p` to sample `q`.
pub fn lerp_pose(p: [f64; 4], q: [f64; 4], u: f64) -> [f64; 3] {
    [1, 2, 3].map(|i| p[i] + (q[i] - p[i]) * u)
}

// ---------------------------------------------------------------------------------------
// Independent oracle
// ---------------------------------------------------------------------------------------

/// Twice the signed area of triangle abc, exact in sign (Shewchuk's adaptive predicate):
/// a plain cross product gives ±4·10⁻¹⁶ for collinear points, and the oracle then took
/// collinear disjoint edges for crossing ones.
fn orient(a: Pt, b: Pt, c: Pt) -> f64 {
    let at = |p: Pt| robust::Coord { x: p[0], y: p[1] };
    robust::orient2d(at(a), at(b), at(c))
}

fn point_segment(p: Pt, a: Pt, b: Pt) -> f64 {
    let ab = sub(b, a);
    let len2 = dot(ab, ab);
    let t = if len2 == 0.0 {
        0.0
    } else {
        (dot(sub(p, a), ab) / len2).clamp(0.0, 1.0)
    };
    (a[0] + ab[0] * t - p[0]).hypot(a[1] + ab[1] * t - p[1])
}

/// Edge `j` of `poly`, from vertex `j` to the next.
fn edge<P: Point>(poly: &[P], j: usize) -> (Pt, Pt) {
    (poly[j].xy(), poly[(j + 1) % poly.len()].xy())
}

/// Weakly inside (boundary included), whatever the orientation of `poly`.
fn inside<P: Point>(p: P, poly: &[P]) -> bool {
    let (mut pos, mut neg) = (false, false);
    for i in 0..poly.len() {
        let (a, b) = edge(poly, i);
        let s = orient(a, b, p.xy());
        pos |= s > 0.0;
        neg |= s < 0.0;
    }
    !(pos && neg)
}

fn within_box(p: Pt, a: Pt, b: Pt) -> bool {
    p[0] >= a[0].min(b[0])
        && p[0] <= a[0].max(b[0])
        && p[1] >= a[1].min(b[1])
        && p[1] <= a[1].max(b[1])
}

/// Closed segments p0p1 and q0q1 share a point.
fn segments_meet((p0, p1): (Pt, Pt), (q0, q1): (Pt, Pt)) -> bool {
    let d1 = orient(q0, q1, p0);
    let d2 = orient(q0, q1, p1);
    let d3 = orient(p0, p1, q0);
    let d4 = orient(p0, p1, q1);
    let opposite = |u: f64, v: f64| (u > 0.0 && v < 0.0) || (u < 0.0 && v > 0.0);
    if opposite(d1, d2) && opposite(d3, d4) {
        return true;
    }
    (d1 == 0.0 && within_box(p0, q0, q1))
        || (d2 == 0.0 && within_box(p1, q0, q1))
        || (d3 == 0.0 && within_box(q0, p0, p1))
        || (d4 == 0.0 && within_box(q1, p0, p1))
}

/// The polygons share a point: a vertex of one inside the other, or two edges meeting.
fn overlap<P: Point>(a: &[P], b: &[P]) -> bool {
    a.iter().any(|&p| inside(p, b))
        || b.iter().any(|&p| inside(p, a))
        || (0..a.len()).any(|i| (0..b.len()).any(|j| segments_meet(edge(a, i), edge(b, j))))
}

/// Distance from `p` to the boundary of `poly`.
pub fn boundary_distance<P: Point>(p: P, poly: &[P]) -> f64 {
    (0..poly.len())
        .map(|j| {
            let (a, b) = edge(poly, j);
            point_segment(p.xy(), a, b)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The smallest vertex-edge distance in either direction, whether or not the polygons
/// overlap.
fn boundary_gap<P: Point>(a: &[P], b: &[P]) -> f64 {
    [(a, b), (b, a)]
        .into_iter()
        .flat_map(|(pts, poly)| pts.iter().map(|&p| boundary_distance(p, poly)))
        .fold(f64::INFINITY, f64::min)
}

#[derive(Clone, Copy, Debug)]
pub struct Exact {
    /// 0 on overlap, else the smallest vertex-edge distance.
    pub distance: f64,
    /// The smallest vertex-edge distance, whether or not the polygons overlap.
    pub boundary_gap: f64,
    pub overlap: bool,
}

pub fn exact<P: Point>(a: &[P], b: &[P]) -> Exact {
    let overlap = overlap(a, b);
    let boundary_gap = boundary_gap(a, b);
    Exact {
        distance: if overlap { 0.0 } else { boundary_gap },
        boundary_gap,
        overlap,
    }
}

/// Exact distance of two convex polygons: `exact(a, b).distance`, without the boundary gap
/// when they overlap.
pub fn exact_distance<P: Point>(a: &[P], b: &[P]) -> f64 {
    if overlap(a, b) {
        0.0
    } else {
        boundary_gap(a, b)
    }
}

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

/// Conservative advancement of one pair, the reference of the property tests: the first time
/// `distance` drops below `delta` over `(h0, h1)`, with the end of the prefix proven δ apart
/// before it; or `None` when it never does. `speed(t)` bounds how fast the pair's gap can
/// close from `t` until the time it also gives (the next sample of either body).
///
/// A step is (d − δ) over that speed. Near a contact such steps shrink without end: under
/// `min_step` the advance goes on by `min_step`, unproven, until δ is crossed (the contact
/// lies in between). `Err` when the pair then moves away again: a graze too close to δ for
/// the reference to decide.
pub fn advance_to_contact(
    distance: impl Fn(f64) -> f64,
    speed: impl Fn(f64) -> (f64, f64),
    (h0, h1): (f64, f64),
    delta: f64,
    min_step: f64,
) -> Result<Option<(f64, f64)>, ()> {
    let mut t = h0;
    // Where unproven steps began.
    let mut unproven_from: Option<f64> = None;
    loop {
        let d = distance(t);
        if d < delta {
            return Ok(Some((unproven_from.unwrap_or(t), t)));
        }
        let (v, until) = speed(t);
        let segment_end = until.min(h1);
        let step = if v > 0.0 {
            (d - delta) / v
        } else {
            f64::INFINITY
        };
        if step >= min_step || t >= h1 {
            if unproven_from.is_some() {
                return Err(());
            }
            if t >= h1 {
                return Ok(None);
            }
            t = if step >= segment_end - t {
                segment_end
            } else {
                t + step
            };
            continue;
        }
        unproven_from.get_or_insert(t);
        t = (t + min_step).min(h1);
    }
}
