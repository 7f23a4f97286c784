//! Reading a cell file (contract section 3): robots with their limits, obstacles and tasks.

use super::arm_file::{ArmAt, PerJoint, RawLink};
use super::body_shape::BodyShape;
use super::cell_checks::check_geometry;
use super::model::{ArmRobot, Cell, CellObstacle, CellRobot, RigidRobot, Task};
use super::object_only::object_only;
use super::reading::{delta, document, read_file, Point};
use super::InputError;
use crate::geometry::{ConvexPolygon, Parts, Vec2};
use crate::motion::{JointLimits, Pose};
use serde::Deserialize;
use std::collections::HashMap;
use std::path::Path;

#[derive(Deserialize)]
#[serde(remote = "Self", deny_unknown_fields)]
struct RawCell {
    #[serde(default)]
    delta: Option<f64>,
    robots: Vec<RawRobot>,
    #[serde(default)]
    obstacles: Vec<RawObstacle>,
    tasks: Vec<RawTask>,
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
    home: Vec<f64>,
    // Optional here so that a missing one is named by its field, and an arm (which has none
    // of them) by its own.
    #[serde(default)]
    max_speed: Option<f64>,
    #[serde(default)]
    max_accel: Option<f64>,
    #[serde(default)]
    max_turn_rate: Option<f64>,
    /// An arm's (contract section 7).
    #[serde(default)]
    base: Option<Vec<f64>>,
    #[serde(default)]
    links: Option<Vec<RawLink>>,
    #[serde(default)]
    joint_limits: Option<Vec<Option<[f64; 2]>>>,
    #[serde(default)]
    max_joint_speed: Option<PerJoint>,
    #[serde(default)]
    max_joint_accel: Option<PerJoint>,
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

#[derive(Deserialize)]
#[serde(remote = "Self", deny_unknown_fields)]
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
    "a robot: an object with `name`, `shape`, `home`, `max_speed`, `max_accel` and `max_turn_rate` \
     (or, for an arm, `name`, `base`, `links`, `home`, `max_joint_speed` and `max_joint_accel`)"
);
object_only!(
    RawObstacle,
    "an obstacle: an object with `name` and `shape`"
);
object_only!(
    RawTask,
    "a task: an object with `name`, `at`, `duration` and optional `robots`"
);

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
/// finite; every task allowed to at least one robot; then the geometry: every home clear of
/// the obstacles by δ; no task pose inside an obstacle. A document is read whole before its
/// geometry is checked, so a fault of reading is reported before any geometric one. Whether
/// a robot can *reach* a task is known only after planning (see `wcp::check_reachable`).
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
    let loaded = read_cell(text, file)?;
    check_geometry(&loaded.cell)?;
    Ok(loaded)
}

/// The cell as written, with names, poses, limits and task lists checked: everything but
/// its geometry (see [`check_geometry`]).
fn read_cell(text: &str, file: &Path) -> Result<LoadedCell, InputError> {
    let raw: RawCell =
        document(text, file, "cell").map_err(|e| scene_instead(text, file).unwrap_or(e))?;
    let delta = delta(raw.delta, file)?;
    let mut names = Names::default();
    let mut warnings = Vec::new();
    let robots = raw
        .robots
        .iter()
        .enumerate()
        .map(|(k, r)| read_robot(file, k, r, &mut names, &mut warnings))
        .collect::<Result<Vec<_>, _>>()?;
    if robots.is_empty() {
        let reason = "a cell needs at least one robot";
        return Err(InputError::new(file, None, "robots", reason));
    }
    let obstacles = raw
        .obstacles
        .iter()
        .enumerate()
        .map(|(k, o)| read_obstacle(file, k, o, &mut names, &mut warnings))
        .collect::<Result<Vec<_>, _>>()?;
    let robot_index: HashMap<&str, usize> = robots
        .iter()
        .enumerate()
        .map(|(k, r)| (r.name.as_str(), k))
        .collect();
    let tasks = raw
        .tasks
        .iter()
        .enumerate()
        .map(|(k, t)| read_task(file, k, t, &mut names, &robot_index))
        .collect::<Result<Vec<_>, _>>()?;
    let cell = Cell {
        file: file.to_path_buf(),
        delta,
        robots,
        obstacles,
        tasks,
    };
    Ok(LoadedCell { cell, warnings })
}

fn read_robot(
    file: &Path,
    k: usize,
    r: &RawRobot,
    names: &mut Names,
    warnings: &mut Vec<String>,
) -> Result<CellRobot, InputError> {
    let at = format!("robots[{k}]");
    let err = |field: String, reason: String| InputError::new(file, Some(&r.name), field, reason);
    names.claim(file, &r.name, &at, "robot")?;
    if r.links.is_some() || r.base.is_some() {
        let arm = read_arm(
            ArmAt {
                file,
                name: &r.name,
                at: &at,
            },
            r,
            warnings,
        )?;
        return Ok(CellRobot::arm(r.name.clone(), arm));
    }
    let arm_keys = [
        ("joint_limits", r.joint_limits.is_some()),
        ("max_joint_speed", r.max_joint_speed.is_some()),
        ("max_joint_accel", r.max_joint_accel.is_some()),
    ];
    if let Some((key, _)) = arm_keys.iter().find(|(_, given)| *given) {
        let reason =
            format!("`{key}` belongs to an arm (with `base` and `links`), not to a rigid robot");
        return Err(err(format!("{at}.{key}"), reason));
    }
    let limit = |value: Option<f64>, field: &str| {
        value.ok_or_else(|| err(format!("{at}.{field}"), format!("missing field `{field}`")))
    };
    let (shape, parts) = body_shape(
        file,
        &r.name,
        &at,
        [&r.shape, &r.outline],
        &r.parts,
        warnings,
    )?;
    let home = pose(&r.home).map_err(|reason| err(format!("{at}.home"), reason))?;
    let robot = RigidRobot {
        shape,
        parts,
        home,
        max_speed: limit(r.max_speed, "max_speed")?,
        max_accel: limit(r.max_accel, "max_accel")?,
        max_turn_rate: limit(r.max_turn_rate, "max_turn_rate")?,
    };
    check_limits(file, &at, &r.name, &robot)?;
    Ok(CellRobot::rigid(r.name.clone(), robot))
}

/// An arm of a cell (contract section 7), every fault named by its field.
fn read_arm(
    place: ArmAt,
    r: &RawRobot,
    warnings: &mut Vec<String>,
) -> Result<ArmRobot, InputError> {
    let at = place.at;
    place.refuse_rigid_keys(&[
        ("shape", r.shape.is_some()),
        ("parts", r.parts.is_some()),
        ("outline", r.outline.is_some()),
        ("max_speed", r.max_speed.is_some()),
        ("max_accel", r.max_accel.is_some()),
        ("max_turn_rate", r.max_turn_rate.is_some()),
    ])?;
    let (base, links) = place.frame(r.base.as_deref(), r.links.as_deref(), warnings)?;
    let joints = links.len();
    if r.home.len() != joints {
        let reason = format!(
            "{} home angles for an arm of {joints} links: one angle per joint",
            r.home.len()
        );
        return Err(InputError::new(
            place.file,
            Some(place.name),
            format!("{at}.home"),
            reason,
        ));
    }
    let limits = JointLimits {
        range: place.ranges(r.joint_limits.as_deref(), joints)?,
        max_speed: place.per_joint("max_joint_speed", r.max_joint_speed.as_ref(), joints)?,
        max_accel: place.per_joint("max_joint_accel", r.max_joint_accel.as_ref(), joints)?,
    };
    let arm = ArmRobot {
        base,
        links,
        home: r.home.clone(),
        limits,
    };
    place.check(&arm)?;
    Ok(arm)
}

/// The robot's limits positive and finite: a planner cannot time a move without them.
pub(super) fn check_limits(
    file: &Path,
    at: &str,
    name: &str,
    r: &RigidRobot,
) -> Result<(), InputError> {
    for (field, value) in [
        ("max_speed", r.max_speed),
        ("max_accel", r.max_accel),
        ("max_turn_rate", r.max_turn_rate),
    ] {
        if !(value.is_finite() && value > 0.0) {
            let reason = format!("must be a positive number, got {value}");
            return Err(InputError::new(
                file,
                Some(name),
                format!("{at}.{field}"),
                reason,
            ));
        }
    }
    Ok(())
}

fn read_obstacle(
    file: &Path,
    k: usize,
    o: &RawObstacle,
    names: &mut Names,
    warnings: &mut Vec<String>,
) -> Result<CellObstacle, InputError> {
    let at = format!("obstacles[{k}]");
    names.claim(file, &o.name, &at, "obstacle")?;
    let (shape, parts) = body_shape(
        file,
        &o.name,
        &at,
        [&o.shape, &o.outline],
        &o.parts,
        warnings,
    )?;
    Ok(CellObstacle {
        name: o.name.clone(),
        shape,
        parts,
    })
}

/// A cell body's geometry (contract sections 1 and 5): exactly one of `shape`, `parts` or
/// `outline`; its convex hull, and its parts when it is not convex.
fn body_shape(
    file: &Path,
    body: &str,
    at: &str,
    [shape, outline]: [&Option<Vec<Point>>; 2],
    parts: &Option<Vec<Vec<Point>>>,
    warnings: &mut Vec<String>,
) -> Result<(ConvexPolygon, Option<Parts>), InputError> {
    let given = BodyShape {
        shape: shape.as_deref(),
        parts: parts.as_deref(),
        outline: outline.as_deref(),
    };
    let parts = given.parts(file, body, at, warnings)?;
    let hull = parts.hull().clone();
    Ok((hull, (!parts.is_convex()).then_some(parts)))
}

fn read_task(
    file: &Path,
    k: usize,
    t: &RawTask,
    names: &mut Names,
    robot_index: &HashMap<&str, usize>,
) -> Result<Task, InputError> {
    let at = format!("tasks[{k}]");
    let err = |field: String, reason: String| InputError::new(file, Some(&t.name), field, reason);
    names.claim(file, &t.name, &at, "task")?;
    let pose = pose(&t.at).map_err(|reason| err(format!("{at}.at"), reason))?;
    check_duration(file, &at, &t.name, t.duration)?;
    let allowed = allowed_robots(
        file,
        &at,
        &t.name,
        t.robots.as_deref(),
        robot_index.len(),
        |name| robot_index.get(name).copied(),
    )?;
    Ok(Task {
        name: t.name.clone(),
        at: pose,
        free_angle: t.at.len() == 2,
        duration: t.duration,
        robots: allowed,
    })
}

/// The indices of the robots named in `list` (all `robots` when there is no list),
/// increasing; `index` finds a robot by name.
pub(super) fn allowed_robots<S: AsRef<str>>(
    file: &Path,
    at: &str,
    task: &str,
    list: Option<&[S]>,
    robots: usize,
    index: impl Fn(&str) -> Option<usize>,
) -> Result<Vec<usize>, InputError> {
    let err = |field: String, reason: String| InputError::new(file, Some(task), field, reason);
    let Some(list) = list else {
        return Ok((0..robots).collect());
    };
    let mut allowed = Vec::with_capacity(list.len());
    for (i, name) in list.iter().enumerate() {
        let name = name.as_ref();
        let Some(r) = index(name) else {
            let reason = format!("no robot is named \"{name}\"");
            return Err(err(format!("{at}.robots[{i}]"), reason));
        };
        allowed.push(r);
    }
    allowed.sort_unstable();
    allowed.dedup();
    if allowed.is_empty() {
        let reason = "no robot may do this task: the list is empty";
        return Err(err(format!("{at}.robots"), reason.into()));
    }
    Ok(allowed)
}

/// A task's duration non-negative and finite.
pub(super) fn check_duration(
    file: &Path,
    at: &str,
    name: &str,
    duration: f64,
) -> Result<(), InputError> {
    if duration.is_finite() && duration >= 0.0 {
        return Ok(());
    }
    let reason = format!("must be a non-negative number, got {duration}");
    Err(InputError::new(
        file,
        Some(name),
        format!("{at}.duration"),
        reason,
    ))
}

/// Names already used, to refuse duplicates among robots, obstacles and tasks: homes and
/// tasks share the graph's node names.
#[derive(Default)]
struct Names(HashMap<String, String>);

impl Names {
    fn claim(&mut self, file: &Path, name: &str, at: &str, kind: &str) -> Result<(), InputError> {
        check_name(file, name, at, kind, self.0.get(name).map(String::as_str))?;
        self.0.insert(name.to_owned(), owner(kind, at));
        Ok(())
    }
}

/// How a message names the owner of a name: robot `robots[0]`.
pub(super) fn owner(kind: &str, at: &str) -> String {
    format!("{kind} `{at}`")
}

/// Refuses an empty name, or one that `first` (its owner, as [`owner`] writes it) has.
pub(super) fn check_name(
    file: &Path,
    name: &str,
    at: &str,
    kind: &str,
    first: Option<&str>,
) -> Result<(), InputError> {
    if name.is_empty() {
        let reason = format!("a {kind} needs a non-empty name");
        return Err(InputError::new(file, None, format!("{at}.name"), reason));
    }
    if let Some(reason) = crate::collision::name_fault(name) {
        return Err(InputError::new(file, None, format!("{at}.name"), reason));
    }
    if let Some(first) = first {
        let reason = format!("the name is already used by {first}");
        return Err(InputError::new(
            file,
            Some(name),
            format!("{at}.name"),
            reason,
        ));
    }
    Ok(())
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

/// The error for a scene given where a cell is read: what `check` says of a cell given to
/// it, the other way round (a robot with a `trajectory` and no `tasks`).
fn scene_instead(text: &str, file: &Path) -> Option<InputError> {
    // Maps, not structs: serde would read a struct from an array as well.
    type Keys = HashMap<String, serde_json::Value>;
    let keys: Keys = serde_json::from_str(text).ok()?;
    let robots = keys.get("robots")?.as_array()?;
    let sampled = robots.iter().any(|r| r.get("trajectory").is_some());
    (sampled && !keys.contains_key("tasks")).then_some(())?;
    let reason = "this is a scene (robots with trajectories), not a cell: use `workcell check` \
                  on it; `solve` and `evaluate` read cells (robots with homes and limits, and \
                  tasks)";
    Some(InputError::new(file, None, "robots[0].trajectory", reason))
}
