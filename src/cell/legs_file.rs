//! The `legs` of a solve result: the moves the feedback loop changed (paused, slowed,
//! detoured, stepped aside), read back so that `evaluate` replays them exactly.
//!
//! ```json
//! "legs": [{"robot": "R2", "move": 0, "on": "move home -> weld-4", "pieces": [
//!   {"go": {"primitives": [{"path": [[1, 3], [2.5, 3]], "theta": 0, "turn": 0}], "scale": 1}},
//!   {"hold": 1.5, "reason": "pause"},
//!   {"go": {"primitives": [{"path": [[2.5, 3], [4, 3]], "theta": 0, "turn": 0}], "scale": 1}}]}]
//! ```
//!
//! Each `go` is a chain of rest-to-rest primitives (G along `path`, the angle turning from
//! `theta` by `turn`), timed by the motion model at the robot's limits and run `scale` (≥ 1)
//! times slower; each `hold` stands still. `on` is for readers and is not checked.

use super::cell_checks::{angle_too_large, too_large};
use super::{Cell, InputError, MAX_COORDINATE_OVER_DELTA};
use serde_json::Value;
use std::path::Path;

/// A changed leg: robot `robot`'s move `leg` (0 out of home, k after its k-th task).
#[derive(Clone, Debug, PartialEq)]
pub struct LegSpec {
    /// The robot.
    pub robot: usize,
    /// The move of its route.
    pub leg: usize,
    /// What it does instead of the planned move, in order.
    pub pieces: Vec<PieceSpec>,
}

/// One piece of a changed leg.
#[derive(Clone, Debug, PartialEq)]
pub enum PieceSpec {
    /// A motion: primitives one after the other (an arm: through joint-space waypoints),
    /// `scale` times slower than timed.
    Go {
        /// The primitives (none for an arm).
        primitives: Vec<PrimitiveSpec>,
        /// An arm's waypoints in joint space, at rest at each, start and end included; none:
        /// the leg's planned move.
        joints: Vec<Vec<f64>>,
        /// Time stretch, at least 1.
        scale: f64,
    },
    /// Standing still.
    Hold {
        /// How long, at least 0.
        duration: f64,
        /// Parked out of the way (`"park"`) rather than paused on the way (`"pause"`).
        park: bool,
    },
}

/// One rest-to-rest primitive as written.
#[derive(Clone, Debug, PartialEq)]
pub struct PrimitiveSpec {
    /// Waypoints of G, at least two.
    pub path: Vec<[f64; 2]>,
    /// Angle at the start.
    pub theta: f64,
    /// Signed rotation over the primitive.
    pub turn: f64,
}

/// Reads the `legs` list of a solve result, for the routes read from the same file.
///
/// ```
/// use workcell::cell::{load_cell, parse_legs, PieceSpec};
/// let cell = load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let routes = [vec![0, 2], vec![3, 1]];
/// // R2 pauses 1.5 on its way out of home (move 0).
/// let legs = serde_json::json!([{"robot": "R2", "move": 0, "pieces": [
///     {"go": {"primitives": [{"path": [[9, 3], [9, 4]], "theta": 0, "turn": 0}], "scale": 1}},
///     {"hold": 1.5, "reason": "pause"}]}]);
/// let specs = parse_legs(&legs, "result.json".as_ref(), &cell, &routes)?;
/// assert_eq!((specs[0].robot, specs[0].leg), (1, 0));
/// assert_eq!(specs[0].pieces[1], PieceSpec::Hold { duration: 1.5, park: false });
/// // R2 has three moves (out, between its tasks, home): no move 3.
/// let bad = serde_json::json!([{"robot": "R2", "move": 3, "pieces": [{"hold": 1}]}]);
/// let e = parse_legs(&bad, "result.json".as_ref(), &cell, &routes).unwrap_err();
/// assert_eq!((e.body.as_deref(), e.field.as_str()), (Some("R2"), "legs[0].move"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn parse_legs(
    list: &Value,
    file: &Path,
    cell: &Cell,
    routes: &[Vec<usize>],
) -> Result<Vec<LegSpec>, InputError> {
    let Value::Array(items) = list else {
        let reason = "expected a list of {\"robot\", \"move\", \"pieces\"}";
        return Err(InputError::new(file, None, "legs", reason));
    };
    let mut out: Vec<LegSpec> = Vec::with_capacity(items.len());
    for (k, item) in items.iter().enumerate() {
        let at = format!("legs[{k}]");
        let name = item.get("robot").and_then(Value::as_str);
        let fail = |field: String, reason: String| InputError::new(file, name, field, reason);
        if let Some((key, reason)) = unknown_in(item, &["robot", "move", "on", "pieces"]) {
            return Err(fail(format!("{at}.{key}"), reason));
        }
        let Some(robot) = name.and_then(|n| cell.robots.iter().position(|r| r.name == n)) else {
            return Err(fail(
                format!("{at}.robot"),
                "must name a robot of the cell".into(),
            ));
        };
        // A robot with no task may have one leg: an excursion from home and back.
        let moves = routes[robot].len() + 1;
        let leg = item.get("move").and_then(Value::as_u64);
        let Some(leg) = leg.filter(|&m| m < moves as u64).map(|m| m as usize) else {
            let reason = format!("must be a move of the robot: 0 to {}", moves - 1);
            return Err(fail(format!("{at}.move"), reason));
        };
        if out.iter().any(|l| l.robot == robot && l.leg == leg) {
            return Err(fail(
                format!("{at}.move"),
                "this move is listed twice".into(),
            ));
        }
        let Some(Value::Array(list)) = item.get("pieces") else {
            return Err(fail(
                format!("{at}.pieces"),
                "expected a list of pieces".into(),
            ));
        };
        if list.is_empty() {
            return Err(fail(
                format!("{at}.pieces"),
                "a leg needs at least one piece".into(),
            ));
        }
        // An arm's motion is in joint space: no primitives.
        let arm = cell.robots[robot].as_arm().is_some();
        let pieces = list
            .iter()
            .enumerate()
            .map(|(j, p)| {
                let at = format!("{at}.pieces[{j}]");
                let p = piece(p, &at, arm).map_err(|(f, r)| fail(f, r))?;
                check_joints(&p, cell, robot).map_err(|(f, r)| fail(format!("{at}.{f}"), r))?;
                check_extents(&p, cell, robot).map_err(|(f, r)| fail(format!("{at}.{f}"), r))?;
                Ok(p)
            })
            .collect::<Result<_, _>>()?;
        out.push(LegSpec { robot, leg, pieces });
    }
    Ok(out)
}

type Failure = (String, String);

fn number(
    v: Option<&Value>,
    field: String,
    ok: impl Fn(f64) -> bool,
    want: &str,
) -> Result<f64, Failure> {
    match v
        .and_then(Value::as_f64)
        .filter(|x| x.is_finite() && ok(*x))
    {
        Some(x) => Ok(x),
        None => Err((field, format!("must be {want}"))),
    }
}

/// The first key of object `v` it may not hold, with the reason (see `object_only`).
fn unknown_in(v: &Value, known: &[&str]) -> Option<(String, String)> {
    let keys = v.as_object()?.keys().map(String::as_str);
    super::object_only::first_unknown(keys, known)
}

fn piece(p: &Value, at: &str, arm: bool) -> Result<PieceSpec, Failure> {
    let known: &[&str] = match p.get("hold") {
        Some(_) => &["hold", "reason"],
        None => &["go"],
    };
    if let Some((key, reason)) = unknown_in(p, known) {
        return Err((format!("{at}.{key}"), reason));
    }
    if let Some((key, reason)) = p
        .get("go")
        .and_then(|go| unknown_in(go, &["primitives", "joints", "scale"]))
    {
        return Err((format!("{at}.go.{key}"), reason));
    }
    if let Some(d) = p.get("hold") {
        let duration = number(
            Some(d),
            format!("{at}.hold"),
            |x| x >= 0.0,
            "a non-negative number",
        )?;
        let park = match p.get("reason").and_then(Value::as_str) {
            Some("park") => true,
            Some("pause") | None => false,
            Some(other) => {
                return Err((
                    format!("{at}.reason"),
                    format!("`{other}` is not `pause` or `park`"),
                ))
            }
        };
        return Ok(PieceSpec::Hold { duration, park });
    }
    let Some(go) = p.get("go") else {
        return Err((
            at.to_owned(),
            "expected {\"go\": ...} or {\"hold\": ...}".into(),
        ));
    };
    let scale = number(
        go.get("scale"),
        format!("{at}.go.scale"),
        |x| x >= 1.0,
        "a number of at least 1 (slower, never faster)",
    )?;
    let Some(Value::Array(list)) = go.get("primitives") else {
        return Err((
            format!("{at}.go.primitives"),
            "expected a list of primitives".into(),
        ));
    };
    if arm != list.is_empty() {
        let reason = match arm {
            true => "an arm moves in joint space along its leg: its motion has no primitives",
            false => "a motion needs at least one primitive",
        };
        return Err((format!("{at}.go.primitives"), reason.into()));
    }
    let primitives = list
        .iter()
        .enumerate()
        .map(|(i, q)| primitive(q, &format!("{at}.go.primitives[{i}]")))
        .collect::<Result<Vec<_>, _>>()?;
    let joints = match go.get("joints") {
        None => Vec::new(),
        Some(_) if !arm => {
            let reason = "`joints` belongs to an arm's motion, not to a rigid robot's";
            return Err((format!("{at}.go.joints"), reason.into()));
        }
        Some(list) => serde_json::from_value::<Vec<Vec<f64>>>(list.clone())
            .ok()
            .filter(|w| w.len() >= 2)
            .ok_or_else(|| {
                let reason = "expected at least two lists of joint angles (start and end)";
                (format!("{at}.go.joints"), reason.to_owned())
            })?,
    };
    Ok(PieceSpec::Go {
        primitives,
        joints,
        scale,
    })
}

/// An arm's waypoints one angle per joint, each within the joint's limits (field relative
/// to the leg).
fn check_joints(p: &PieceSpec, cell: &Cell, robot: usize) -> Result<(), Failure> {
    let (PieceSpec::Go { joints, .. }, Some(arm)) = (p, cell.robots[robot].as_arm()) else {
        return Ok(());
    };
    for (w, q) in joints.iter().enumerate() {
        let at = format!("go.joints[{w}]");
        if q.len() != arm.links.len() || q.iter().any(|a| !a.is_finite()) {
            let reason = format!("expected {} finite angles, one per joint", arm.links.len());
            return Err((at, reason));
        }
        for (j, (&a, range)) in q.iter().zip(&arm.limits.range).enumerate() {
            if let Some([lo, hi]) = range.filter(|[lo, hi]| !(*lo..=*hi).contains(&a)) {
                let reason = format!("joint {j} at {a}, outside its limits [{lo}, {hi}]");
                return Err((at, reason));
            }
        }
    }
    Ok(())
}

/// A motion's coordinates and angles within what f64 resolves at δ, as the cell's own are
/// (see `cell_checks`): an angle beyond it would be rounded to whole turns and silently
/// become the robot's.
fn check_extents(p: &PieceSpec, cell: &Cell, robot: usize) -> Result<(), Failure> {
    let PieceSpec::Go {
        primitives, joints, ..
    } = p
    else {
        return Ok(());
    };
    let (delta, rim) = (cell.delta, cell.robots[robot].rim());
    let limit = MAX_COORDINATE_OVER_DELTA * delta;
    for (i, q) in primitives.iter().enumerate() {
        let at = format!("go.primitives[{i}]");
        for (n, &[x, y]) in q.path.iter().enumerate() {
            let far = x.abs().max(y.abs());
            if far > limit {
                return Err((format!("{at}.path[{n}]"), too_large(far, delta)));
            }
        }
        if (rim * q.theta).abs() > limit {
            return Err((format!("{at}.theta"), angle_too_large(q.theta, rim, delta)));
        }
    }
    for (w, q) in joints.iter().enumerate() {
        if let Some(&a) = q.iter().find(|a| (rim * **a).abs() > limit) {
            return Err((format!("go.joints[{w}]"), angle_too_large(a, rim, delta)));
        }
    }
    Ok(())
}

/// A primitive of a motion: `path` (at least two finite points), `theta`, `turn` (at most π).
fn primitive(q: &Value, at: &str) -> Result<PrimitiveSpec, Failure> {
    if let Some((key, reason)) = unknown_in(q, &["path", "theta", "turn"]) {
        return Err((format!("{at}.{key}"), reason));
    }
    let Some(Value::Array(points)) = q.get("path") else {
        return Err((
            format!("{at}.path"),
            "expected a list of points [x, y]".into(),
        ));
    };
    if points.len() < 2 {
        return Err((
            format!("{at}.path"),
            "a path needs at least two points".into(),
        ));
    }
    let path = points
        .iter()
        .enumerate()
        .map(|(n, pt)| match pt.as_array().map(Vec::as_slice) {
            Some([x, y]) => match (x.as_f64(), y.as_f64()) {
                (Some(x), Some(y)) if x.is_finite() && y.is_finite() => Ok([x, y]),
                _ => Err((
                    format!("{at}.path[{n}]"),
                    "coordinates must be finite numbers".into(),
                )),
            },
            _ => Err((format!("{at}.path[{n}]"), "expected a point [x, y]".into())),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let any = |_: f64| true;
    let theta = number(
        q.get("theta"),
        format!("{at}.theta"),
        any,
        "a finite number",
    )?;
    let turn = number(
        q.get("turn"),
        format!("{at}.turn"),
        |t| t.abs() <= std::f64::consts::PI,
        "a turn of at most π",
    )?;
    Ok(PrimitiveSpec { path, theta, turn })
}
