//! Reading a scene file (contract section 1) into a [`Scene`].

use super::arm_file::{ArmAt, RawLink};
use super::body_shape::BodyShape;
use super::object_only::object_only;
use super::reading::{delta, document, read_file, Point};
use super::InputError;
use crate::collision::{Body, Scene};
use crate::geometry::{Parts, Vec2};
use crate::motion::{ArmError, ArmMotion, JointSample, Sample, Trajectory, TrajectoryError};
use serde::Deserialize;
use std::collections::HashSet;
use std::path::Path;

#[derive(Deserialize)]
#[serde(remote = "Self", deny_unknown_fields)]
struct RawScene {
    #[serde(default)]
    delta: Option<f64>,
    robots: Vec<RawRobot>,
    #[serde(default)]
    obstacles: Vec<RawObstacle>,
}

#[derive(Deserialize)]
#[serde(remote = "Self", deny_unknown_fields)]
struct RawRobot {
    name: String,
    #[serde(default)]
    shape: Option<Vec<Point>>,
    #[serde(default)]
    parts: Option<Vec<Vec<Point>>>,
    #[serde(default)]
    outline: Option<Vec<Point>>,
    /// An arm's base pose (contract section 6).
    #[serde(default)]
    base: Option<Vec<f64>>,
    /// An arm's links.
    #[serde(default)]
    links: Option<Vec<RawLink>>,
    trajectory: Samples,
}

#[derive(Deserialize)]
#[serde(remote = "Self", deny_unknown_fields)]
struct RawSample {
    t: f64,
    #[serde(default)]
    x: Option<f64>,
    #[serde(default)]
    y: Option<f64>,
    #[serde(default)]
    vx: Option<f64>,
    #[serde(default)]
    vy: Option<f64>,
    #[serde(default)]
    theta: Option<f64>,
    #[serde(default)]
    omega: Option<f64>,
    /// An arm's joint angles (contract section 6).
    #[serde(default)]
    q: Option<Vec<f64>>,
    /// An arm's joint velocities.
    #[serde(default)]
    qd: Option<Vec<f64>>,
}

impl RawSample {
    /// A rigid robot's sample as [`Samples`] holds it (`x` and `y` checked given).
    fn sample(&self, x: f64, y: f64) -> Sample {
        let missing = f64::NAN;
        Sample {
            t: self.t,
            pos: Vec2::new(x, y),
            theta: self.theta.unwrap_or(0.0),
            vel: Vec2::new(self.vx.unwrap_or(missing), self.vy.unwrap_or(missing)),
            omega: self.omega.unwrap_or(missing),
        }
    }
}

/// A robot's samples as written. A rigid robot's in the trajectory's own form and vector: θ
/// 0 where the file gives none, velocities NaN where it gives none (JSON cannot hold NaN), for
/// [`Trajectory::with_missing_velocities`] to derive; an arm's with its joint angles (`qd`
/// empty where the file gives none).
enum Samples {
    Rigid(Vec<Sample>),
    Joints(Vec<JointSample>),
}

/// One sample, of either kind: decided by its keys, refused by name when they are mixed.
enum AnySample {
    Rigid(Sample),
    Joints(JointSample),
}

impl<'de> Deserialize<'de> for AnySample {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        // The trait's, which refuses a record written as an array (`object_only!`).
        let raw = <RawSample as Deserialize>::deserialize(d)?;
        let Some(q) = raw.q.clone() else {
            if raw.qd.is_some() {
                return Err(D::Error::custom("`qd` is given without `q`"));
            }
            let x = raw.x.ok_or_else(|| D::Error::missing_field("x"))?;
            let y = raw.y.ok_or_else(|| D::Error::missing_field("y"))?;
            return Ok(AnySample::Rigid(raw.sample(x, y)));
        };
        let rigid = [
            ("x", raw.x.is_some()),
            ("y", raw.y.is_some()),
            ("theta", raw.theta.is_some()),
            ("vx", raw.vx.is_some()),
            ("vy", raw.vy.is_some()),
            ("omega", raw.omega.is_some()),
        ];
        if let Some((key, _)) = rigid.iter().find(|(_, given)| *given) {
            let reason = format!(
                "a sample gives joint angles `q` or a pose (`x`, `y`, ...), not both: `{key}` \
                 beside `q`"
            );
            return Err(D::Error::custom(reason));
        }
        Ok(AnySample::Joints(JointSample {
            t: raw.t,
            q,
            qd: raw.qd.unwrap_or_default(),
        }))
    }
}

impl<'de> Deserialize<'de> for Samples {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let raw = Vec::<AnySample>::deserialize(d)?;
        let joints = matches!(raw.first(), Some(AnySample::Joints(_)));
        let mut rigid = Vec::new();
        let mut arm = Vec::new();
        for (k, sample) in raw.into_iter().enumerate() {
            match (sample, joints) {
                (AnySample::Rigid(s), false) => rigid.push(s),
                (AnySample::Joints(s), true) => arm.push(s),
                _ => {
                    return Err(D::Error::custom(format!(
                        "sample {k} is not of the first sample's kind: a trajectory gives \
                         joint angles `q` in every sample (an arm) or poses in every sample"
                    )))
                }
            }
        }
        Ok(if joints {
            Samples::Joints(arm)
        } else {
            Samples::Rigid(rigid)
        })
    }
}

#[derive(Deserialize)]
#[serde(remote = "Self", deny_unknown_fields)]
struct RawObstacle {
    name: String,
    #[serde(default)]
    shape: Option<Vec<Point>>,
    #[serde(default)]
    parts: Option<Vec<Vec<Point>>>,
    #[serde(default)]
    outline: Option<Vec<Point>>,
}

object_only!(
    RawScene,
    "a scene: an object with `robots` and optional `delta` and `obstacles`"
);
object_only!(
    RawRobot,
    "a robot: an object with `name`, `trajectory` and one of `shape`, `parts`, `outline`"
);
object_only!(
    RawSample,
    "a sample: an object with `t`, `x`, `y` and optional `theta`, `vx`, `vy`, `omega`"
);
object_only!(
    RawObstacle,
    "an obstacle: an object with `name` and one of `shape`, `parts`, `outline`"
);

/// A scene read from a file, with the repairs made on the way (one line each).
#[derive(Clone, Debug)]
pub struct LoadedScene {
    /// The scene.
    pub scene: Scene,
    /// Warnings for stderr: clockwise shapes reversed, vertices removed.
    pub warnings: Vec<String>,
}

/// Reads and validates the scene file at `path`. Whether f64 can check it depends on the
/// δ finally used: see [`super::check_precision`].
///
/// ```
/// use workcell::cell::load_scene;
/// use workcell::collision::{check, CheckOptions};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/paper-fig12b.json");
/// let loaded = load_scene(path.as_ref())?;
/// let verdict = check(&loaded.scene, &CheckOptions::default()).verdict();
/// assert!(verdict.contact().is_some(), "the paper's colliding example: {verdict}");
/// let e = load_scene("no-such-file.json".as_ref()).unwrap_err();
/// assert!(e.to_string().starts_with("no-such-file.json: cannot read the file"));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn load_scene(path: &Path) -> Result<LoadedScene, InputError> {
    parse_scene(&read_file(path)?, path)
}

/// Parses and validates a scene document; `file` is only used to name it in messages.
///
/// ```
/// use workcell::cell::parse_scene;
/// let text = r#"{"robots": [{"name": "A", "shape": [[0,0],[1,0],[1,1]],
///                "trajectory": [{"t": 0, "x": 0, "y": 0}, {"t": 1, "x": "far"}]}]}"#;
/// let e = parse_scene(text, "s.json".as_ref()).unwrap_err();
/// assert_eq!((e.body.as_deref(), e.field.as_str()), (Some("A"), "robots[0].trajectory[1].x"));
/// ```
pub fn parse_scene(text: &str, file: &Path) -> Result<LoadedScene, InputError> {
    // The one-pass reader takes what scene files usually hold; serde reads the rest, and
    // names what is wrong.
    let raw = match fast::scene(text) {
        Some(raw) => raw,
        None => document(text, file, "scene").map_err(|e| cell_instead(text, file).unwrap_or(e))?,
    };
    build(raw, file)
}

/// The scene of a document read, validated.
fn build(raw: RawScene, file: &Path) -> Result<LoadedScene, InputError> {
    let delta = delta(raw.delta, file)?;
    let mut warnings = Vec::new();
    let mut names = HashSet::new();
    let mut bodies = Vec::with_capacity(raw.robots.len() + raw.obstacles.len());
    for (k, r) in raw.robots.into_iter().enumerate() {
        let at = format!("robots[{k}]");
        check_name(file, &r.name, &at, &mut names)?;
        if r.links.is_some() || r.base.is_some() {
            bodies.extend(arm(file, &at, r, &mut warnings)?);
            continue;
        }
        let shape = BodyShape {
            shape: r.shape.as_deref(),
            parts: r.parts.as_deref(),
            outline: r.outline.as_deref(),
        };
        let parts = shape.parts(file, &r.name, &at, &mut warnings)?;
        let Samples::Rigid(samples) = r.trajectory else {
            let reason = "joint angles `q` belong to an arm: give `base` and `links`";
            let field = format!("{at}.trajectory[0].q");
            return Err(InputError::new(file, Some(&r.name), field, reason));
        };
        let trajectory = Trajectory::with_missing_velocities(samples).map_err(|e| {
            let field = match &e {
                TrajectoryError::Empty => format!("{at}.trajectory"),
                TrajectoryError::NotFinite { sample, field } => {
                    format!("{at}.trajectory[{sample}].{field}")
                }
                TrajectoryError::DerivedVelocityOverflow { sample } => {
                    format!("{at}.trajectory[{sample}]")
                }
                TrajectoryError::NotIncreasing { sample, .. } => {
                    format!("{at}.trajectory[{sample}].t")
                }
            };
            InputError::new(file, Some(&r.name), field, e)
        })?;
        bodies.push(Body::robot_of_parts(r.name, parts, trajectory));
    }
    for (k, o) in raw.obstacles.into_iter().enumerate() {
        let at = format!("obstacles[{k}]");
        check_name(file, &o.name, &at, &mut names)?;
        let shape = BodyShape {
            shape: o.shape.as_deref(),
            parts: o.parts.as_deref(),
            outline: o.outline.as_deref(),
        };
        let parts = shape.parts(file, &o.name, &at, &mut warnings)?;
        bodies.push(Body::obstacle_of_parts(o.name, &parts));
    }
    Ok(LoadedScene {
        scene: Scene { delta, bodies },
        warnings,
    })
}

/// A scene that does not parse but has the `tasks` of a cell is most likely a cell given
/// where a scene was expected: say so rather than which scene field is missing.
fn cell_instead(text: &str, file: &Path) -> Option<InputError> {
    // A map, not a struct: serde would read a struct from an array as well.
    let keys: std::collections::HashMap<String, serde::de::IgnoredAny> =
        serde_json::from_str(text).ok()?;
    keys.contains_key("tasks").then_some(())?;
    let reason = "this is a cell, not a scene: use `workcell solve` on it, or \
                  `workcell solve --export-scene` to get the scene of its schedule";
    Some(InputError::new(file, None, "tasks", reason))
}

fn check_name(
    file: &Path,
    name: &str,
    at: &str,
    seen: &mut HashSet<String>,
) -> Result<(), InputError> {
    if name.is_empty() {
        return Err(InputError::new(
            file,
            None,
            format!("{at}.name"),
            "a body needs a non-empty name",
        ));
    }
    if let Some(reason) = crate::collision::name_fault(name) {
        return Err(InputError::new(file, None, format!("{at}.name"), reason));
    }
    if !seen.insert(name.to_owned()) {
        return Err(InputError::new(
            file,
            Some(name),
            format!("{at}.name"),
            "another body has the same name",
        ));
    }
    Ok(())
}

/// An arm's links as checker bodies (contract section 6), every fault named by its field.
fn arm(
    file: &Path,
    at: &str,
    r: RawRobot,
    warnings: &mut Vec<String>,
) -> Result<Vec<Body>, InputError> {
    let name = r.name.as_str();
    let err = |field: String, reason: String| InputError::new(file, Some(name), field, reason);
    let place = ArmAt { file, name, at };
    place.refuse_rigid_keys(&[
        ("shape", r.shape.is_some()),
        ("parts", r.parts.is_some()),
        ("outline", r.outline.is_some()),
    ])?;
    let (base, links) = place.frame(r.base.as_deref(), r.links.as_deref(), warnings)?;
    let (lengths, bodies): (Vec<f64>, Vec<Parts>) = links.into_iter().unzip();
    let Samples::Joints(samples) = r.trajectory else {
        let reason = "an arm's samples give its joint angles `q` (and optional `qd`), not a pose";
        return Err(err(format!("{at}.trajectory[0]"), reason.into()));
    };
    let reach = bodies.iter().map(|p| p.hull().radius()).collect();
    let motion = ArmMotion::new(base, lengths, reach, samples).map_err(|e| {
        let field = match &e {
            ArmError::Empty => format!("{at}.trajectory"),
            ArmError::NoLinks => format!("{at}.links"),
            ArmError::Length { link, .. } => format!("{at}.links[{link}].length"),
            ArmError::Base => format!("{at}.base"),
            ArmError::Joints { sample, field, .. } | ArmError::NotFinite { sample, field } => {
                format!("{at}.trajectory[{sample}].{field}")
            }
            ArmError::NotIncreasing { sample } => format!("{at}.trajectory[{sample}].t"),
            ArmError::Reach { link } => format!("{at}.links[{link}]"),
        };
        err(field, e.to_string())
    })?;
    Ok(Body::arm(r.name, motion, bodies))
}

/// The scene document read in one pass by [`Cursor`], into the records serde would make of
/// it: comments (keys beginning with `_`) skipped; an unknown key, a key given twice or
/// anything the cursor leaves to serde (`None`) read again by serde, which refuses or
/// reads it.
mod fast {
    use super::{RawObstacle, RawRobot, RawSample, RawScene, Samples};
    use crate::cell::json_cursor::{once, Cursor};
    use crate::cell::reading::Point;
    use crate::motion::Sample;

    pub(super) fn scene(text: &str) -> Option<RawScene> {
        let mut c = Cursor::new(text);
        let (mut delta, mut robots, mut obstacles) = (None, None, None);
        c.object(|c, key| match key {
            "delta" => once(&mut delta, c.number()),
            "robots" => once(&mut robots, list(c, robot)),
            "obstacles" => once(&mut obstacles, list(c, obstacle)),
            _ => comment(c, key),
        })?;
        c.end()?;
        Some(RawScene {
            delta,
            robots: robots?,
            obstacles: obstacles.unwrap_or_default(),
        })
    }

    /// Skips a comment's value; any other unknown key is left to serde (`None`).
    fn comment(c: &mut Cursor, key: &str) -> Option<()> {
        match key.starts_with('_') {
            true => c.skip(),
            false => None,
        }
    }

    fn list<'a, T>(c: &mut Cursor<'a>, item: fn(&mut Cursor<'a>) -> Option<T>) -> Option<Vec<T>> {
        // No room reserved from a guess: a robot's count of samples says nothing of the
        // next one's, and a reserve too large for many robots would multiply memory.
        let mut items = Vec::new();
        c.array(|c| {
            items.push(item(c)?);
            Some(())
        })?;
        Some(items)
    }

    fn robot(c: &mut Cursor) -> Option<RawRobot> {
        let (mut name, mut trajectory) = (None, None);
        let (mut shape, mut parts, mut outline) = (None, None, None);
        c.object(|c, key| match key {
            "name" => once(&mut name, c.string().map(str::to_owned)),
            "shape" => once(&mut shape, list(c, vertex)),
            "parts" => once(&mut parts, list(c, polygon)),
            "outline" => once(&mut outline, list(c, vertex)),
            "trajectory" => once(&mut trajectory, list(c, sample).map(Samples::Rigid)),
            // Arms are read by serde.
            "base" | "links" => None,
            _ => comment(c, key),
        })?;
        Some(RawRobot {
            name: name?,
            shape,
            parts,
            outline,
            base: None,
            links: None,
            trajectory: trajectory?,
        })
    }

    fn obstacle(c: &mut Cursor) -> Option<RawObstacle> {
        let mut name = None;
        let (mut shape, mut parts, mut outline) = (None, None, None);
        c.object(|c, key| match key {
            "name" => once(&mut name, c.string().map(str::to_owned)),
            "shape" => once(&mut shape, list(c, vertex)),
            "parts" => once(&mut parts, list(c, polygon)),
            "outline" => once(&mut outline, list(c, vertex)),
            _ => comment(c, key),
        })?;
        Some(RawObstacle {
            name: name?,
            shape,
            parts,
            outline,
        })
    }

    fn polygon(c: &mut Cursor) -> Option<Vec<Point>> {
        list(c, vertex)
    }

    fn vertex(c: &mut Cursor) -> Option<Point> {
        let mut p = Point::empty();
        c.array(|c| {
            p.push(c.number()?);
            Some(())
        })?;
        Some(p)
    }

    fn sample(c: &mut Cursor) -> Option<Sample> {
        let [mut t, mut x, mut y, mut vx, mut vy, mut theta, mut omega] = [None; 7];
        c.object(|c, key| {
            let slot = match key {
                "t" => &mut t,
                "x" => &mut x,
                "y" => &mut y,
                "vx" => &mut vx,
                "vy" => &mut vy,
                "theta" => &mut theta,
                "omega" => &mut omega,
                // An arm's sample: read by serde.
                "q" | "qd" => return None,
                _ => return comment(c, key),
            };
            once(slot, c.number())
        })?;
        let raw = RawSample {
            t: t?,
            x,
            y,
            vx,
            vy,
            theta,
            omega,
            q: None,
            qd: None,
        };
        Some(raw.sample(x?, y?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::{json, Value};

    /// The scene the one-pass reader reads (when it does), and serde's, as text: Debug
    /// prints each f64 by its shortest round-trip digits, so bits must agree.
    fn both(text: &str) -> (Option<String>, String) {
        let file = Path::new("s.json");
        let shown = |r: Result<LoadedScene, InputError>| match r {
            Ok(loaded) => format!("{:?}", loaded.scene),
            Err(e) => e.to_string(),
        };
        let fast = fast::scene(text).map(|raw| shown(build(raw, file)));
        let serde = shown(document(text, file, "scene").and_then(|raw| build(raw, file)));
        (fast, serde)
    }

    fn scene_files() -> Vec<String> {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut texts = Vec::new();
        for dir in ["tests/corpus", "cells"] {
            for entry in std::fs::read_dir(root.join(dir)).unwrap() {
                let path = entry.unwrap().path();
                let text = std::fs::read_to_string(&path).unwrap_or_default();
                if path.extension().is_some_and(|e| e == "json") && text.contains("trajectory") {
                    texts.push(text);
                }
            }
        }
        texts
    }

    /// Every shipped and corpus scene, and each rewritten with its keys in another order,
    /// pretty-printed, with keys the format does not know and with `null` velocities: the
    /// one-pass reader reads the same scene as serde, bit for bit, or leaves it to serde.
    #[test]
    fn the_one_pass_reader_reads_what_serde_reads() {
        let texts = scene_files();
        assert!(texts.len() >= 50, "{} scenes", texts.len());
        let mut read_fast = 0;
        for text in &texts {
            let doc: Value = serde_json::from_str(text).unwrap();
            let mut extra = doc.clone();
            extra["_note"] = json!({"a": [1, "x", {"b": [], "c": -2.5e-3}]});
            for robot in extra["robots"].as_array_mut().unwrap() {
                robot["_colour"] = json!("red");
                robot["trajectory"][0]["_tag"] = json!([[0]]);
            }
            let mut unknown = doc.clone();
            unknown["robots"][0]["trajectory"][0]["tag"] = json!(1);
            let mut nulls = doc.clone();
            nulls["robots"][0]["trajectory"][0]["vx"] = Value::Null;
            let variants = [
                text.clone(),
                doc.to_string(), // keys sorted
                serde_json::to_string_pretty(&doc).unwrap(),
                extra.to_string(),
                nulls.to_string(),
                unknown.to_string(),
            ];
            for (k, v) in variants.iter().enumerate() {
                let (fast, serde) = both(v);
                match fast {
                    Some(fast) => {
                        assert_eq!(fast, serde, "variant {k}");
                        read_fast += 1;
                    }
                    None if k == 5 => assert!(serde.contains("unknown key `tag`"), "{serde}"),
                    None => assert_eq!(k, 4, "only `null` and `tag` are left to serde:\n{v}"),
                }
            }
        }
        assert_eq!(read_fast, 4 * texts.len());
    }

    /// A sample keeps the velocities it gives only when it gives all three; the others, and
    /// any left out, come from the positions (the average of the slopes either side).
    #[test]
    fn velocities_given_or_derived() {
        let text = r#"{"robots": [{"name": "A", "shape": [[0,0],[1,0],[1,1]], "trajectory": [
            {"t": 0, "x": 0, "y": 0},
            {"t": 1, "x": 2, "y": 4, "vx": 7, "theta": 1},
            {"t": 2, "x": 6, "y": 4, "vx": 5, "vy": 6, "omega": 7}]}]}"#;
        let loaded = parse_scene(text, Path::new("s.json")).unwrap();
        let crate::motion::Motion::Sampled(tr) = &loaded.scene.bodies[0].motion else {
            panic!("a robot");
        };
        let at = |k: usize| {
            let s = tr.samples()[k];
            (s.vel.x, s.vel.y, s.omega)
        };
        assert_eq!(at(0), (2.0, 4.0, 1.0), "slope of the first segment");
        assert_eq!(at(1), (7.0, 2.0, 0.0), "vx given, vy and omega derived");
        assert_eq!(at(2), (5.0, 6.0, 7.0), "all three given");
    }

    /// What the one-pass reader leaves to serde, or refuses, reads as before.
    #[test]
    fn anything_else_is_left_to_serde() {
        let ok = r#"{"robots": [{"name": "A", "shape": [[0,0],[1,0],[1,1]],
                     "trajectory": [{"t": 0, "x": 0, "y": 0}, {"t": 1, "x": 1, "y": 0}]}]}"#;
        assert!(fast::scene(ok).is_some());
        for (from, to) in [
            ("\"A\"", "\"\\u0041\""),                      // an escape
            ("\"t\": 1", "\"t\": 1, \"t\": 2"),            // a key twice
            ("\"t\": 1", "\"t\": \"1\""),                  // a string for a number
            ("\"y\": 0}]", "\"y\": 1e999}]"),              // beyond f64
            ("[[0,0],", "[[0,0,0],"),                      // three numbers
            ("[{\"name\"", "[{\"x\": true, \"name\""),     // a literal
            ("\"robots\"", "\"delta\": null, \"robots\""), // null
        ] {
            let text = ok.replacen(from, to, 1);
            assert_ne!(text, ok);
            let (fast, serde) = both(&text);
            assert_eq!(fast.as_ref().filter(|f| *f != &serde), None, "{text}");
            if fast.is_some() {
                // A vertex of three numbers is read as serde reads it, then refused alike.
                assert!(serde.contains("shape[0]"), "{serde}");
            }
        }
    }
}
