//! Failure boundaries of the checker, each verdict and contact time known by construction:
//! δ = 10⁻⁹, a vertex grazing δ at one instant, faces turning parallel into contact,
//! identical and tip-to-tip bodies, 10⁴:1 slivers, coordinates of 10⁶, 10⁴ samples per
//! trajectory, a start in contact, bad time stamps and velocities that lie.
//!
//! Complements tests/integration/stability.rs (gliding at δ, a teleport within one ulp, huge time
//! stamps, coordinates too large for δ). Where a contact exists, the distance at the
//! reported time and at `safe_until` is re-computed with parry2d-f64, an independent
//! implementation (GJK), as a cross-check of the witness.

mod contact_shapes;
mod convexity;
mod input;
mod long_edges;
mod precision;
mod scale;
mod tiny_delta;

use parry2d_f64::math::{Pose as ParryPose, Vector as ParryVector};
use parry2d_f64::shape::ConvexPolygon as ParryPolygon;
use serde_json::{json, Value};
use std::f64::consts::FRAC_PI_4;
use std::path::Path;
use workcell::cell::{check_precision, parse_scene};
use workcell::collision::Method;
use workcell::collision::{check, Body, CheckOptions, CheckReport, Scene};
use workcell::motion::BoundKind;

const DELTA: f64 = 1e-3;

// ---------------------------------------------------------------------------------------
// Scenes as JSON text, as a user would write them
// ---------------------------------------------------------------------------------------

/// Axis-aligned rectangle of half-sides `hx`, `hy` about `(cx, cy)`, counter-clockwise.
fn rect_at(cx: f64, cy: f64, hx: f64, hy: f64) -> Value {
    json!([
        [cx - hx, cy - hy],
        [cx + hx, cy - hy],
        [cx + hx, cy + hy],
        [cx - hx, cy + hy]
    ])
}

fn rect(hx: f64, hy: f64) -> Value {
    rect_at(0.0, 0.0, hx, hy)
}

/// The unit square.
fn square() -> Value {
    rect(0.5, 0.5)
}

/// A robot from `[t, x, y, theta]` samples (velocities derived from the positions).
fn robot(name: &str, shape: Value, samples: &[[f64; 4]]) -> Value {
    let trajectory: Vec<Value> = samples
        .iter()
        .map(|&[t, x, y, theta]| json!({"t": t, "x": x, "y": y, "theta": theta}))
        .collect();
    json!({"name": name, "shape": shape, "trajectory": trajectory})
}

fn obstacle(name: &str, shape: Value) -> Value {
    json!({"name": name, "shape": shape})
}

fn scene(delta: f64, robots: Vec<Value>, obstacles: Vec<Value>) -> String {
    json!({"delta": delta, "robots": robots, "obstacles": obstacles}).to_string()
}

fn load(text: &str) -> Scene {
    let path = Path::new("boundaries.json");
    let loaded = parse_scene(text, path).unwrap_or_else(|e| panic!("{e}"));
    // Every scene here is inside the domain of the checker's guarantee.
    check_precision(&loaded.scene, loaded.scene.delta, path).unwrap_or_else(|e| panic!("{e}"));
    loaded.scene
}

fn run_with(text: &str, opts: &CheckOptions) -> (Scene, CheckReport) {
    let scene = load(text);
    let report = check(&scene, opts);
    (scene, report)
}

fn run(text: &str) -> (Scene, CheckReport) {
    run_with(text, &CheckOptions::default())
}

// ---------------------------------------------------------------------------------------
// Verdicts
// ---------------------------------------------------------------------------------------

/// Free over the whole horizon; `certified` as expected.
#[track_caller]
fn assert_free(r: &CheckReport, certified: bool) {
    assert!(!r.collision && r.first_contact.is_none(), "{r:?}");
    assert_eq!(r.certified, certified, "{r:?}");
    assert_eq!(r.safe_until, r.horizon[1], "{r:?}");
    assert_eq!(r.stats.unresolved, 0, "{r:?}");
}

/// A contact between `bodies` reported within the time tolerance of `t`, the true first
/// contact: never before it (beyond rounding: the witness is an exact distance), at most
/// `time_tol` after it, with a certified prefix up to `safe_until` just before it.
#[track_caller]
fn assert_contact(r: &CheckReport, bodies: [&str; 2], t: f64) {
    assert!(r.collision, "no contact, expected one at {t}: {r:?}");
    let c = r.first_contact.as_ref().unwrap();
    assert_eq!(c.bodies, bodies, "{r:?}");
    assert!(
        (c.time - t).abs() <= r.time_tol,
        "contact at {} instead of {t} (tolerance {}): {r:?}",
        c.time,
        r.time_tol
    );
    assert!(
        c.time >= t - 1e-2 * r.time_tol,
        "contact at {} before the true one at {t}: {r:?}",
        c.time
    );
    assert!(c.distance < r.delta, "{r:?}");
    assert!(
        r.safe_until <= c.time && c.time - r.safe_until <= r.time_tol,
        "{r:?}"
    );
    assert_eq!(r.stats.unresolved, 0, "{r:?}");
}

// ---------------------------------------------------------------------------------------
// The independent cross-check: parry2d-f64's distance (GJK)
// ---------------------------------------------------------------------------------------

/// Exact distance between the bodies named `pair` at time `t`, by parry2d-f64.
fn parry_distance(scene: &Scene, pair: &[String; 2], t: f64) -> f64 {
    let placed = |name: &str| {
        let body: &Body = scene.bodies.iter().find(|b| b.name == name).unwrap();
        let points = body
            .shape
            .vertices()
            .iter()
            .map(|v| ParryVector::new(v.x, v.y))
            .collect();
        let shape = ParryPolygon::from_convex_polyline(points).expect("a convex polygon");
        let pose = body.motion.pose_at(t);
        let pose = ParryPose::new(ParryVector::new(pose.pos.x, pose.pos.y), pose.theta);
        (pose, shape)
    };
    let (pa, sa) = placed(&pair[0]);
    let (pb, sb) = placed(&pair[1]);
    parry2d_f64::query::distance(&pa, &sa, &pb, &sb)
        .unwrap()
        .distance
}

/// parry agrees with the reported witness distance, and finds the pair at least δ apart at
/// `safe_until` (when the contact is not at the start).
///
/// parry's GJK stops within a relative 5·10⁻⁸ and takes separations below about that much
/// of the bodies' size for contact (distance 0): the δ = 10⁻⁹ scenes cross-checked here are
/// of axis-aligned faces and corners, where it is exact.
#[track_caller]
fn cross_check_with_parry(scene: &Scene, r: &CheckReport) {
    let c = r.first_contact.as_ref().expect("a contact");
    let scale = scene
        .bodies
        .iter()
        .filter(|b| c.bodies.contains(&b.name))
        .map(|b| b.motion.pose_at(c.time).pos.amax() + b.shape.radius())
        .fold(1.0, f64::max);
    // GJK stops within a relative 5·10⁻⁸ of the distance; poses are rounded at `scale`.
    let tol = |d: f64| 1e-12 + 1e-7 * d + 1e-15 * scale;
    let d = parry_distance(scene, &c.bodies, c.time);
    assert!(
        (d - c.distance).abs() <= tol(d),
        "at {}: parry {d}, workcell {}",
        c.time,
        c.distance
    );
    if r.safe_until < c.time {
        let d = parry_distance(scene, &c.bodies, r.safe_until);
        assert!(
            d >= r.delta - tol(d),
            "parry finds {d} < δ = {} at safe_until {}",
            r.delta,
            r.safe_until
        );
    }
}

/// The root of a decreasing `f` on `[lo, hi]`, by bisection to the last bit.
fn root(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    assert!(f(lo) > 0.0 && f(hi) < 0.0);
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return mid;
        }
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
}
