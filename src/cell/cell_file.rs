//! Reading a cell file (contract section 3): robots with their limits, obstacles and tasks.

use super::object_only::object_only;
use super::precision::check_shape_repairs;
use super::scene_file::{document, polygon, read_file, Point, DEFAULT_DELTA};
use super::{InputError, MAX_COORDINATE_OVER_DELTA};
use crate::collision::Body;
use crate::geometry::{closest_features, ConvexPolygon, Posed, Vec2, WalkTolerances};
use crate::motion::Pose;
use serde::Deserialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

#[derive(Deserialize)]
#[serde(remote = "Self")]
struct RawCell {
    #[serde(default)]
    delta: Option<f64>,
    robots: Vec<RawRobot>,
    #[serde(default)]
    obstacles: Vec<RawObstacle>,
    tasks: Vec<RawTask>,
}

#[derive(Deserialize)]
#[serde(remote = "Self")]
struct RawRobot {
    name: String,
    shape: Vec<Point>,
    home: Vec<f64>,
    max_speed: f64,
    max_accel: f64,
    max_turn_rate: f64,
}

#[derive(Deserialize)]
#[serde(remote = "Self")]
struct RawObstacle {
    name: String,
    shape: Vec<Point>,
}

#[derive(Deserialize)]
#[serde(remote = "Self")]
struct RawTask {
    name: String,
    at: Vec<f64>,
    duration: f64,
    #[serde(default)]
    robots: Option<Vec<String>>,
}

object_only!(
    RawCell,
    "a cell: an object with `robots`, `tasks` and optional `delta` and `obstacles`"
);
object_only!(
    RawRobot,
    "a robot: an object with `name`, `shape`, `home`, `max_speed`, `max_accel` and `max_turn_rate`"
);
object_only!(
    RawObstacle,
    "an obstacle: an object with `name` and `shape`"
);
object_only!(
    RawTask,
    "a task: an object with `name`, `at`, `duration` and optional `robots`"
);

/// A robot of the cell: its shape, home and limits.
#[derive(Clone, Debug, PartialEq)]
pub struct CellRobot {
    /// Name, unique among robots, obstacles and tasks.
    pub name: String,
    /// Shape in the body frame (origin: the rotation centre G).
    pub shape: ConvexPolygon,
    /// Where the robot starts and ends.
    pub home: Pose,
    /// Largest speed of G.
    pub max_speed: f64,
    /// Largest acceleration of G.
    pub max_accel: f64,
    /// Largest angular speed.
    pub max_turn_rate: f64,
}

/// A fixed obstacle in world coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct CellObstacle {
    /// Name, unique among robots, obstacles and tasks.
    pub name: String,
    /// Shape in world coordinates.
    pub shape: ConvexPolygon,
}

/// A task: a pose to hold for a duration, by one of the allowed robots.
#[derive(Clone, Debug, PartialEq)]
pub struct Task {
    /// Name, unique among robots, obstacles and tasks.
    pub name: String,
    /// The pose the robot holds while doing the task.
    pub at: Pose,
    /// How long the robot stays at `at`.
    pub duration: f64,
    /// Indices (into [`Cell::robots`]) of the robots allowed to do it, increasing.
    pub robots: Vec<usize>,
}

/// A work-cell to schedule (contract section 3), validated.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// The file it was read from, to name it in later messages.
    pub file: PathBuf,
    /// δ: bodies closer than this collide.
    pub delta: f64,
    /// The robots, in file order.
    pub robots: Vec<CellRobot>,
    /// The obstacles, in file order.
    pub obstacles: Vec<CellObstacle>,
    /// The tasks, in file order.
    pub tasks: Vec<Task>,
}

impl Cell {
    /// The obstacles as checker bodies.
    pub fn obstacle_bodies(&self) -> Vec<Body> {
        self.obstacles
            .iter()
            .map(|o| Body::obstacle(o.name.clone(), &o.shape))
            .collect()
    }

    /// An error about this cell's file.
    pub fn error(
        &self,
        body: Option<&str>,
        field: impl Into<String>,
        reason: impl std::fmt::Display,
    ) -> InputError {
        InputError::new(&self.file, body, field, reason)
    }
}

/// A cell read from a file, with the repairs made on the way (one line each).
#[derive(Clone, Debug)]
pub struct LoadedCell {
    /// The cell.
    pub cell: Cell,
    /// Warnings for stderr: clockwise shapes reversed, vertices removed.
    pub warnings: Vec<String>,
}

/// Reads and validates the cell file at `path`.
///
/// ```
/// use workcell::cell::load_cell;
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
/// let cell = load_cell(path.as_ref())?.cell;
/// assert_eq!((cell.robots.len(), cell.tasks.len(), cell.delta), (2, 4, 0.01));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn load_cell(path: &Path) -> Result<LoadedCell, InputError> {
    parse_cell(&read_file(path)?, path)
}

/// Parses and validates a cell document; `file` names it in messages and in [`Cell::file`].
///
/// Beyond the syntax: names unique among robots, obstacles and tasks; limits positive and
/// finite; every home clear of the obstacles by δ; no task pose inside an obstacle; every task
/// allowed to at least one robot. Whether a robot can *reach* a task is known only after
/// planning (see `wcp::check_reachable`).
///
/// ```
/// use workcell::cell::parse_cell;
/// let text = r#"{"delta": 0.01,
///   "robots": [{"name": "R1", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
///               "home": [0, 0, 0], "max_speed": 1, "max_accel": 0, "max_turn_rate": 1}],
///   "tasks": [{"name": "weld", "at": [3, 0, 0], "duration": 1}]}"#;
/// let e = parse_cell(text, "c.json".as_ref()).unwrap_err();
/// assert_eq!((e.body.as_deref(), e.field.as_str()), (Some("R1"), "robots[0].max_accel"));
/// let ok = parse_cell(&text.replace(r#""max_accel": 0"#, r#""max_accel": 2"#), "c.json".as_ref())?;
/// assert_eq!(ok.cell.tasks[0].robots, [0]); // no `robots` list: any robot
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn parse_cell(text: &str, file: &Path) -> Result<LoadedCell, InputError> {
    let raw: RawCell = document(text, file, "cell")?;
    let delta = raw.delta.unwrap_or(DEFAULT_DELTA);
    if !(delta.is_finite() && delta > 0.0) {
        let reason = format!("must be a positive number, got {delta}");
        return Err(InputError::new(file, None, "delta", reason));
    }
    let mut names = Names::default();
    let mut warnings = Vec::new();
    let limit = MAX_COORDINATE_OVER_DELTA * delta;
    let err = |body: &str, field: String, reason: String| {
        InputError::new(file, Some(body), field, reason)
    };

    let mut robots = Vec::with_capacity(raw.robots.len());
    for (k, r) in raw.robots.iter().enumerate() {
        let at = format!("robots[{k}]");
        names.claim(file, &r.name, &at, "robot")?;
        let shape = polygon(
            file,
            &r.name,
            &format!("{at}.shape"),
            &r.shape,
            &mut warnings,
        )?;
        check_shape_repairs(&shape, &r.name, &at, delta, file)?;
        if shape.radius() > limit {
            return Err(err(
                &r.name,
                format!("{at}.shape"),
                too_large(shape.radius(), delta),
            ));
        }
        let home = pose(&r.home).map_err(|reason| err(&r.name, format!("{at}.home"), reason))?;
        if home.pos.amax() > limit {
            let reason = too_large(home.pos.amax(), delta);
            return Err(err(&r.name, format!("{at}.home"), reason));
        }
        if (shape.radius() * home.theta).abs() > limit {
            let reason = angle_too_large(home.theta, shape.radius(), delta);
            return Err(err(&r.name, format!("{at}.home"), reason));
        }
        for (field, value) in [
            ("max_speed", r.max_speed),
            ("max_accel", r.max_accel),
            ("max_turn_rate", r.max_turn_rate),
        ] {
            if !(value.is_finite() && value > 0.0) {
                let reason = format!("must be a positive number, got {value}");
                return Err(err(&r.name, format!("{at}.{field}"), reason));
            }
        }
        robots.push(CellRobot {
            name: r.name.clone(),
            shape,
            home,
            max_speed: r.max_speed,
            max_accel: r.max_accel,
            max_turn_rate: r.max_turn_rate,
        });
    }
    if robots.is_empty() {
        return Err(InputError::new(
            file,
            None,
            "robots",
            "a cell needs at least one robot",
        ));
    }

    let mut obstacles = Vec::with_capacity(raw.obstacles.len());
    for (k, o) in raw.obstacles.iter().enumerate() {
        let at = format!("obstacles[{k}]");
        names.claim(file, &o.name, &at, "obstacle")?;
        let shape = polygon(
            file,
            &o.name,
            &format!("{at}.shape"),
            &o.shape,
            &mut warnings,
        )?;
        check_shape_repairs(&shape, &o.name, &at, delta, file)?;
        let extent = shape
            .vertices()
            .iter()
            .map(|v| v.amax())
            .fold(0.0, f64::max);
        if extent > limit {
            return Err(err(
                &o.name,
                format!("{at}.shape"),
                too_large(extent, delta),
            ));
        }
        obstacles.push(CellObstacle {
            name: o.name.clone(),
            shape,
        });
    }

    // A home too close to an obstacle leaves the robot in collision before it moves.
    for (k, r) in robots.iter().enumerate() {
        if let Some((o, d)) = nearest_obstacle(&r.shape, r.home, &obstacles, delta) {
            let reason = format!(
                "the robot at its home is {d:.3e} from obstacle \"{}\", closer than delta = {delta}",
                obstacles[o].name
            );
            return Err(err(&r.name, format!("robots[{k}].home"), reason));
        }
    }

    // Two robots touching at home collide before anything is scheduled: no sequence or
    // wait can separate them.
    for (k, r) in robots.iter().enumerate() {
        let placed = Posed::new(&r.shape, r.home.pos.x, r.home.pos.y, r.home.theta);
        for other in &robots[..k] {
            let o = Posed::new(
                &other.shape,
                other.home.pos.x,
                other.home.pos.y,
                other.home.theta,
            );
            let d = closest_features(&placed, &o, None, &WalkTolerances::default()).distance;
            if d < delta {
                let reason = format!(
                    "at home the robot is {d:.3e} from robot \"{}\" at its home, closer than delta = {delta}",
                    other.name
                );
                return Err(err(&r.name, format!("robots[{k}].home"), reason));
            }
        }
    }

    let robot_index: HashMap<&str, usize> = robots
        .iter()
        .enumerate()
        .map(|(k, r)| (r.name.as_str(), k))
        .collect();
    let mut tasks = Vec::with_capacity(raw.tasks.len());
    for (k, t) in raw.tasks.iter().enumerate() {
        let at = format!("tasks[{k}]");
        names.claim(file, &t.name, &at, "task")?;
        let pose = pose(&t.at).map_err(|reason| err(&t.name, format!("{at}.at"), reason))?;
        if pose.pos.amax() > limit {
            return Err(err(
                &t.name,
                format!("{at}.at"),
                too_large(pose.pos.amax(), delta),
            ));
        }
        if !(t.duration.is_finite() && t.duration >= 0.0) {
            let reason = format!("must be a non-negative number, got {}", t.duration);
            return Err(err(&t.name, format!("{at}.duration"), reason));
        }
        if let Some(o) = obstacles.iter().find(|o| contains(&o.shape, &pose.pos)) {
            let reason = format!("the task pose is inside obstacle \"{}\"", o.name);
            return Err(err(&t.name, format!("{at}.at"), reason));
        }
        let allowed = match &t.robots {
            None => (0..robots.len()).collect(),
            Some(list) => {
                let mut allowed = Vec::with_capacity(list.len());
                for (i, name) in list.iter().enumerate() {
                    let Some(&r) = robot_index.get(name.as_str()) else {
                        let reason = format!("no robot is named \"{name}\"");
                        return Err(err(&t.name, format!("{at}.robots[{i}]"), reason));
                    };
                    allowed.push(r);
                }
                allowed.sort_unstable();
                allowed.dedup();
                allowed
            }
        };
        if allowed.is_empty() {
            let reason = "no robot may do this task: the list is empty";
            return Err(err(&t.name, format!("{at}.robots"), reason.into()));
        }
        // The angle is resolved to within ulp(θ); at the robot's rim that is a length.
        let rim = allowed
            .iter()
            .map(|&r| robots[r].shape.radius())
            .fold(0.0, f64::max);
        if (rim * pose.theta).abs() > limit {
            let reason = angle_too_large(pose.theta, rim, delta);
            return Err(err(&t.name, format!("{at}.at"), reason));
        }
        tasks.push(Task {
            name: t.name.clone(),
            at: pose,
            duration: t.duration,
            robots: allowed,
        });
    }

    super::time_axis::check_time_axis(file, &robots, &tasks)?;
    let cell = Cell {
        file: file.to_path_buf(),
        delta,
        robots,
        obstacles,
        tasks,
    };
    Ok(LoadedCell { cell, warnings })
}

/// Names already used, to refuse duplicates among robots, obstacles and tasks: homes and
/// tasks share the graph's node names.
#[derive(Default)]
struct Names(HashMap<String, String>);

impl Names {
    fn claim(&mut self, file: &Path, name: &str, at: &str, kind: &str) -> Result<(), InputError> {
        if name.is_empty() {
            let reason = format!("a {kind} needs a non-empty name");
            return Err(InputError::new(file, None, format!("{at}.name"), reason));
        }
        if let Some(first) = self.0.get(name) {
            let reason = format!("the name is already used by {first}");
            return Err(InputError::new(
                file,
                Some(name),
                format!("{at}.name"),
                reason,
            ));
        }
        self.0.insert(name.to_owned(), format!("{kind} `{at}`"));
        Ok(())
    }
}

/// `[x, y]` or `[x, y, theta]`.
fn pose(values: &[f64]) -> Result<Pose, String> {
    let (x, y, theta) = match *values {
        [x, y] => (x, y, 0.0),
        [x, y, theta] => (x, y, theta),
        _ => {
            return Err(format!(
                "a pose is [x, y] or [x, y, theta], found {} numbers",
                values.len()
            ))
        }
    };
    Ok(Pose {
        pos: Vec2::new(x, y),
        theta,
    })
}

fn too_large(value: f64, delta: f64) -> String {
    format!(
        "coordinate {value:e} is too large for delta = {delta:e} (limit {:e}): f64 cannot \
         resolve delta there; move the origin or raise delta",
        MAX_COORDINATE_OVER_DELTA * delta
    )
}

fn angle_too_large(theta: f64, radius: f64, delta: f64) -> String {
    format!(
        "angle {theta:e} is too large for delta = {delta:e}: f64 resolves it only to {:.1e} \
         rad, {:.1e} at the robot's rim (limit |radius x theta| <= {:e}); reduce it modulo 2 pi",
        theta.abs() * f64::EPSILON,
        (radius * theta).abs() * f64::EPSILON,
        MAX_COORDINATE_OVER_DELTA * delta
    )
}

fn contains(shape: &ConvexPolygon, p: &Vec2) -> bool {
    let n = shape.vertices().len();
    (0..n).all(|i| shape.normals()[i].dot(&(p - shape.vertices()[i])) < 0.0)
}

/// The first obstacle closer than δ to the robot placed at `pose`, with its distance.
pub(crate) fn nearest_obstacle(
    shape: &ConvexPolygon,
    pose: Pose,
    obstacles: &[CellObstacle],
    delta: f64,
) -> Option<(usize, f64)> {
    let robot = Posed::new(shape, pose.pos.x, pose.pos.y, pose.theta);
    obstacles.iter().enumerate().find_map(|(k, o)| {
        let obstacle = Posed::new(&o.shape, 0.0, 0.0, 0.0);
        let d = closest_features(&robot, &obstacle, None, &WalkTolerances::default()).distance;
        (d < delta).then_some((k, d))
    })
}
