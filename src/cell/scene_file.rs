//! Reading a scene file (contract section 1) into a [`Scene`].

use super::object_only::object_only;
use super::reading::{delta, document, polygon, read_file, Point};
use super::InputError;
use crate::collision::{Body, Scene};
use crate::motion::{Motion, Pose, Sample, Trajectory, TrajectoryError};
use serde::Deserialize;
use std::collections::HashSet;
use std::path::Path;

#[derive(Deserialize)]
#[serde(remote = "Self")]
struct RawScene {
    #[serde(default)]
    delta: Option<f64>,
    robots: Vec<RawRobot>,
    #[serde(default)]
    obstacles: Vec<RawObstacle>,
}

#[derive(Deserialize)]
#[serde(remote = "Self")]
struct RawRobot {
    name: String,
    shape: Vec<Point>,
    trajectory: Vec<RawSample>,
}

#[derive(Deserialize)]
#[serde(remote = "Self")]
struct RawSample {
    t: f64,
    x: f64,
    y: f64,
    #[serde(default)]
    vx: Option<f64>,
    #[serde(default)]
    vy: Option<f64>,
    #[serde(default)]
    theta: Option<f64>,
    #[serde(default)]
    omega: Option<f64>,
}

#[derive(Deserialize)]
#[serde(remote = "Self")]
struct RawObstacle {
    name: String,
    shape: Vec<Point>,
}

object_only!(
    RawScene,
    "a scene: an object with `robots` and optional `delta` and `obstacles`"
);
object_only!(
    RawRobot,
    "a robot: an object with `name`, `shape` and `trajectory`"
);
object_only!(
    RawSample,
    "a sample: an object with `t`, `x`, `y` and optional `theta`, `vx`, `vy`, `omega`"
);
object_only!(
    RawObstacle,
    "an obstacle: an object with `name` and `shape`"
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
    let raw: RawScene =
        document(text, file, "scene").map_err(|e| cell_instead(text, file).unwrap_or(e))?;
    let delta = delta(raw.delta, file)?;
    let mut warnings = Vec::new();
    let mut names = HashSet::new();
    let mut bodies = Vec::with_capacity(raw.robots.len() + raw.obstacles.len());
    for (k, r) in raw.robots.iter().enumerate() {
        let at = format!("robots[{k}]");
        check_name(file, &r.name, &at, &mut names)?;
        let shape = polygon(
            file,
            &r.name,
            &format!("{at}.shape"),
            &r.shape,
            &mut warnings,
        )?;
        let trajectory = trajectory(&r.trajectory).map_err(|e| {
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
        bodies.push(Body {
            name: r.name.clone(),
            shape,
            motion: Motion::Sampled(trajectory),
        });
    }
    for (k, o) in raw.obstacles.iter().enumerate() {
        let at = format!("obstacles[{k}]");
        check_name(file, &o.name, &at, &mut names)?;
        let shape = polygon(
            file,
            &o.name,
            &format!("{at}.shape"),
            &o.shape,
            &mut warnings,
        )?;
        bodies.push(Body::obstacle(o.name.clone(), &shape));
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

/// Samples with defaults filled in: theta 0, velocities derived from the positions.
fn trajectory(raw: &[RawSample]) -> Result<Trajectory, TrajectoryError> {
    let samples = raw
        .iter()
        .map(|s| Sample::at(s.t, Pose::new(s.x, s.y, s.theta.unwrap_or(0.0))))
        .collect();
    Trajectory::with_given_velocities(samples, |k| [raw[k].vx, raw[k].vy, raw[k].omega])
}
