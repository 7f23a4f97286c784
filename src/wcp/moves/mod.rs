//! Every move a robot may make, planned and then certified obstacle-free by the checker, on
//! demand: [`MoveStore`] plans and certifies each move once, whoever asks first, and keeps it
//! for every later use (the sequencer, the schedules, the feedback loop's remedies).
//! [`bounds`] gives each move's admissible lower bound without planning it.
//!
//! Node indices are those of the sequencer: for each robot, 0 is its home and `1 + t` is
//! task `t`. A move and its reverse visit the same poses (the motion model is symmetric in
//! time), so one plan and one certificate serve both directions.

use super::configurations::Assignment;
use super::sequencer::{node_task, task_node};
use super::sequencer::{BoundLimits, Bounds, JointNodes};
use crate::cell::{Cell, RigidRobot, RobotKind};
use crate::collision::{check, Body, CheckOptions, Scene, Verdict};
use crate::geometry::{closest_features, ConvexPolygon, Posed, Vec2, WalkTolerances};
use crate::motion::{tool_pose, Pose, Sample, Trajectory};
use crate::planning::{plan_move, PlanError, PlannedMove, PlannerOptions, RobotLimits};
use std::fmt;
use std::sync::Arc;

mod store;
pub use store::MoveStore;

/// Why a robot has no move between two nodes.
#[derive(Clone, Debug, PartialEq)]
pub enum MoveFailure {
    /// The planner found no obstacle-free path.
    Plan(PlanError),
    /// An end of the move is too close to an obstacle for the planner's clearance, swept
    /// over the move's rotation, and turning apart found no way either.
    Blocked {
        /// `"start"` or `"goal"`.
        end: &'static str,
        /// The obstacle.
        obstacle: String,
    },
    /// The checker found the planned move within δ of an obstacle (a planner defect, kept
    /// out of every schedule).
    Collides {
        /// Time into the move of the first contact.
        time: f64,
        /// The obstacle touched.
        obstacle: String,
    },
    /// The checker could neither certify nor refute the move (it grazes δ).
    NotCertified,
    /// At one end the robot's body itself, at that pose, comes within δ of an obstacle: no
    /// move starts or ends there, however it turns.
    Overlaps {
        /// `"start"` or `"goal"`.
        end: &'static str,
        /// The obstacle.
        obstacle: String,
        /// The distance between the body and the obstacle there (0 where they overlap).
        distance: f64,
    },
    /// An arm has no configuration at one of the move's ends.
    NoConfiguration,
    /// An arm's straight joint-space move hits a fixture and no path around it was found.
    NoJointPath,
}

impl fmt::Display for MoveFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MoveFailure::Plan(e) => write!(f, "{e}"),
            MoveFailure::Blocked { end, obstacle } => write!(
                f,
                "at the {end} pose the robot cannot turn as the move requires without coming \
                 closer than the planning clearance (delta + 2%) to obstacle \"{obstacle}\", \
                 and no turning point nearby helps"
            ),
            MoveFailure::Collides { time, obstacle } => write!(
                f,
                "the planned move comes within delta of obstacle \"{obstacle}\" at t = {time:.6} \
                 (refused by the checker)"
            ),
            MoveFailure::Overlaps {
                end,
                obstacle,
                distance,
            } => {
                let how = match *distance > 0.0 {
                    true => format!(
                        "comes within delta of obstacle \"{obstacle}\" ({distance:.3e} apart)"
                    ),
                    false => format!("overlaps obstacle \"{obstacle}\""),
                };
                write!(
                    f,
                    "at the {end} pose the robot's body {how}: no move starts or ends there; \
                     move the pose or the obstacle"
                )
            }
            MoveFailure::NoConfiguration => write!(
                f,
                "the arm has no joint angles that put its tool at the task clear of the fixtures"
            ),
            MoveFailure::NoJointPath => write!(
                f,
                "the arm's straight joint-space move hits a fixture and no joint-space path \
                 around it was found"
            ),
            MoveFailure::NotCertified => {
                write!(
                    f,
                    "the checker cannot certify the planned move: it grazes delta"
                )
            }
        }
    }
}

/// The pose of node `node` for robot `r`: its home for 0, task `node - 1` otherwise.
///
/// ```
/// use workcell::wcp::node_pose;
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// assert_eq!(node_pose(&cell, 1, 0), cell.rigid(1).home);
/// assert_eq!(node_pose(&cell, 1, 3), cell.tasks[2].at);
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn node_pose(cell: &Cell, r: usize, node: usize) -> Pose {
    match node {
        0 => cell.rigid(r).home,
        n => cell.tasks[node_task(n)].at,
    }
}

/// The name of node `node` for robot `r`: the robot's name for its home, else the task's.
///
/// ```
/// use workcell::wcp::node_name;
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// assert_eq!((node_name(&cell, 1, 0), node_name(&cell, 1, 3)), ("R2", "weld-3"));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn node_name(cell: &Cell, r: usize, node: usize) -> &str {
    match node {
        0 => &cell.robots[r].name,
        n => &cell.tasks[node_task(n)].name,
    }
}

/// The nodes robot `r` may visit: its home, then its allowed tasks in file order.
///
/// ```
/// use workcell::cell::parse_cell;
/// use workcell::wcp::robot_nodes;
/// let text = r#"{"delta": 0.01,
///   "robots": [{"name": "R1", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
///               "home": [0, 0, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1},
///              {"name": "R2", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
///               "home": [9, 0, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1}],
///   "tasks": [{"name": "a", "at": [3, 0, 0], "duration": 1, "robots": ["R1"]},
///             {"name": "b", "at": [6, 0, 0], "duration": 1}]}"#;
/// let cell = parse_cell(text, "c.json".as_ref())?.cell;
/// assert_eq!(robot_nodes(&cell, 0), [0, 1, 2]); // home, a, b
/// assert_eq!(robot_nodes(&cell, 1), [0, 2]); // R2 may not do a
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn robot_nodes(cell: &Cell, r: usize) -> Vec<usize> {
    let tasks = cell.tasks.iter().enumerate();
    std::iter::once(0)
        .chain(
            tasks
                .filter(|(_, t)| t.robots.contains(&r))
                .map(|(k, _)| task_node(k)),
        )
        .collect()
}

/// The planner's limits of a robot of the cell.
pub(crate) fn limits(robot: &RigidRobot) -> RobotLimits {
    RobotLimits {
        max_speed: robot.max_speed,
        max_accel: robot.max_accel,
        max_turn_rate: robot.max_turn_rate,
    }
}

/// Plans robot `r`'s move between two nodes and has the checker certify it against every
/// obstacle. The planner is deterministic: planning the same move again gives the same one.
///
/// ```
/// use workcell::planning::PlannerOptions;
/// use workcell::wcp::{certified_move, node_pose};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// // R1 from its home (node 0) to weld-1 (node 1), certified clear of the fixture.
/// let m = certified_move(&cell, 0, 0, 1, &PlannerOptions::default(), &cell.obstacle_bodies()).unwrap();
/// assert_eq!(m.samples.last().unwrap().pos, node_pose(&cell, 0, 1).pos);
/// assert!(m.duration > 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn certified_move(
    cell: &Cell,
    r: usize,
    from: usize,
    to: usize,
    planner: &PlannerOptions,
    obstacles: &[Body],
) -> Result<PlannedMove, MoveFailure> {
    let fixtures = Fixtures::of(cell);
    let planned = plan_only(cell, r, from, to, planner, &fixtures)?;
    certify(cell, r, &planned.samples, obstacles)?;
    Ok(planned)
}

/// The cell's obstacles as the planner takes them: every convex piece (an obstacle of parts
/// gives each part), with the obstacle each belongs to.
#[derive(Clone)]
pub(crate) struct Fixtures {
    pub pieces: Vec<ConvexPolygon>,
    pub owner: Vec<usize>,
}

impl Fixtures {
    pub fn of(cell: &Cell) -> Fixtures {
        let (mut pieces, mut owner) = (Vec::new(), Vec::new());
        for (k, o) in cell.obstacles.iter().enumerate() {
            pieces.extend_from_slice(o.pieces());
            owner.extend(std::iter::repeat_n(k, o.pieces().len()));
        }
        Fixtures { pieces, owner }
    }
}

/// The planner's move among every piece of every obstacle of the cell, not certified.
fn plan_only(
    cell: &Cell,
    r: usize,
    from: usize,
    to: usize,
    planner: &PlannerOptions,
    fixtures: &Fixtures,
) -> Result<PlannedMove, MoveFailure> {
    let robot = cell.rigid(r);
    let (a, b) = (node_pose(cell, r, from), node_pose(cell, r, to));
    let name = |piece: usize| cell.obstacles[fixtures.owner[piece]].name.clone();
    plan_move(
        robot.pieces(),
        &limits(robot),
        &fixtures.pieces,
        cell.delta,
        a,
        b,
        planner,
    )
    .map_err(|e| {
        let (end, pose, piece) = match e {
            PlanError::StartBlocked { obstacle } => ("start", a, obstacle),
            PlanError::GoalBlocked { obstacle } => ("goal", b, obstacle),
            other => return MoveFailure::Plan(other),
        };
        // Blocked for the move's rotation, or already at the pose itself: the second is
        // the cause to tell.
        let distance = body_distance(robot.pieces(), pose, &fixtures.pieces[piece]);
        match distance < cell.delta {
            true => MoveFailure::Overlaps {
                end,
                obstacle: name(piece),
                distance,
            },
            false => MoveFailure::Blocked {
                end,
                obstacle: name(piece),
            },
        }
    })
}

/// The distance between a body's pieces placed at `pose` and a fixed convex piece (0 where
/// they overlap).
fn body_distance(pieces: &[ConvexPolygon], pose: Pose, fixed: &ConvexPolygon) -> f64 {
    let tol = WalkTolerances::default();
    let fixed = Posed::new(fixed, 0.0, 0.0, 0.0);
    pieces
        .iter()
        .map(|p| {
            let placed = Posed::new(p, pose.pos.x, pose.pos.y, pose.theta);
            closest_features(&placed, &fixed, None, &tol).distance
        })
        .fold(f64::INFINITY, f64::min)
}

/// Relative slack on the distances within which an obstacle counts as near a move.
const NEAR_SLACK: f64 = 1.05;

/// The smallest box holding the points.
fn bounding_box(points: &[Vec2]) -> (Vec2, Vec2) {
    points.iter().fold(
        (Vec2::repeat(f64::INFINITY), Vec2::repeat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.inf(p), hi.sup(p)),
    )
}

/// Whether two boxes come within `reach` of each other (on each axis).
fn boxes_within(a: &(Vec2, Vec2), b: &(Vec2, Vec2), reach: f64) -> bool {
    a.0.x <= b.1.x + reach
        && b.0.x <= a.1.x + reach
        && a.0.y <= b.1.y + reach
        && b.0.y <= a.1.y + reach
}

/// The checker's verdict on one robot's samples against the obstacles.
pub(crate) fn certify(
    cell: &Cell,
    r: usize,
    samples: &[Sample],
    obstacles: &[Body],
) -> Result<(), MoveFailure> {
    if obstacles.is_empty() {
        return Ok(());
    }
    let robot = cell.rigid(r);
    let trajectory = Trajectory::new(samples.to_vec())
        .expect("the planner emits finite samples at increasing times");
    let mut bodies = Vec::with_capacity(obstacles.len() + 1);
    bodies.push(robot.body(&cell.robots[r].name, trajectory));
    bodies.extend_from_slice(obstacles);
    let report = check(
        &Scene {
            delta: cell.delta,
            bodies,
        },
        &CheckOptions::default(),
    );
    match report.verdict() {
        Verdict::Contact { contact: c, .. } => Err(MoveFailure::Collides {
            time: c.time,
            obstacle: c.bodies[1].clone(),
        }),
        verdict if verdict.is_certified_free() => Ok(()),
        _ => Err(MoveFailure::NotCertified),
    }
}

/// The admissible lower bound of every move of the cell (see [`Bounds`]).
///
/// ```
/// use workcell::planning::PlannerOptions;
/// use workcell::wcp::{bounds, MoveStore};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let store = MoveStore::new(&cell, &PlannerOptions::default());
/// let lower = bounds(&cell, store.assignment());
/// // Never longer than the certified move: R2 from home around the fixture to weld-1.
/// assert!(lower.bound(1, 0, 1) <= store.duration(1, 0, 1).unwrap());
/// assert!(lower.bound(1, 0, 1) > 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn bounds(cell: &Cell, assignment: &Assignment) -> Bounds {
    let pose = |p: &Pose| (p.pos, p.theta);
    let rigid = |r: usize| cell.robots[r].as_rigid();
    // An arm's limits and home here only place it among the tasks: its own bounds are in
    // joint space.
    let limits = (0..cell.robots.len()).map(|r| match rigid(r) {
        Some(r) => BoundLimits {
            max_speed: r.max_speed,
            max_accel: r.max_accel,
            max_angular_accel: r.max_accel / r.shape.radius(),
            max_turn_rate: r.max_turn_rate,
        },
        None => BoundLimits {
            max_speed: 1.0,
            max_accel: 1.0,
            max_angular_accel: 1.0,
            max_turn_rate: 1.0,
        },
    });
    let homes = (0..cell.robots.len()).map(|r| match &cell.robots[r].kind {
        RobotKind::Rigid(b) => pose(&b.home),
        RobotKind::Arm(a) => {
            let lengths: Vec<f64> = a.links.iter().map(|l| l.0).collect();
            pose(&tool_pose(a.base, &lengths, &a.home))
        }
    });
    let mut bounds = Bounds::new(
        limits.collect(),
        homes.collect(),
        cell.tasks.iter().map(|t| pose(&t.at)).collect(),
    );
    for (r, robot) in cell.robots.iter().enumerate() {
        let Some(arm) = robot.as_arm() else { continue };
        let nodes = (0..=cell.tasks.len())
            .map(|n| assignment.joints(cell, r, n).map(Arc::from))
            .collect();
        let limits = arm.limits.clone();
        bounds = bounds.with_joints(r, JointNodes { nodes, limits });
    }
    bounds
}
