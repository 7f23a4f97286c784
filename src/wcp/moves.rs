//! Every move a robot may make, planned and then certified obstacle-free by the checker, on
//! demand: [`MoveStore`] plans and certifies each move once, whoever asks first, and keeps it
//! for every later use (the sequencer, the schedules, the feedback loop's remedies).
//! [`bounds`] gives each move's admissible lower bound without planning it.
//!
//! Node indices are those of the sequencer: for each robot, 0 is its home and `1 + t` is
//! task `t`. A move and its reverse visit the same poses (the motion model is symmetric in
//! time), so one plan and one certificate serve both directions.

use super::sequencer::{node_task, task_node};
use super::sequencer::{BoundLimits, Bounds};
use crate::cell::{Cell, CellRobot};
use crate::collision::{check, Body, CheckOptions, Scene, Verdict};
use crate::geometry::{ConvexPolygon, Vec2};
use crate::motion::{Pose, Sample, Trajectory};
use crate::planning::{plan_move, PlanError, PlannedMove, PlannerOptions, RobotLimits};
use rayon::prelude::*;
use std::collections::HashMap;
use std::fmt;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

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
/// assert_eq!(node_pose(&cell, 1, 0), cell.robots[1].home);
/// assert_eq!(node_pose(&cell, 1, 3), cell.tasks[2].at);
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn node_pose(cell: &Cell, r: usize, node: usize) -> Pose {
    match node {
        0 => cell.robots[r].home,
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
pub(crate) fn limits(robot: &CellRobot) -> RobotLimits {
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
    let shapes: Vec<_> = cell.obstacles.iter().map(|o| o.shape.clone()).collect();
    plan_and_certify(cell, r, from, to, planner, &shapes, obstacles)
}

fn plan_and_certify(
    cell: &Cell,
    r: usize,
    from: usize,
    to: usize,
    planner: &PlannerOptions,
    shapes: &[ConvexPolygon],
    obstacles: &[Body],
) -> Result<PlannedMove, MoveFailure> {
    let planned = plan_only(cell, r, from, to, planner, shapes)?;
    certify(cell, r, &planned.samples, obstacles)?;
    Ok(planned)
}

/// The planner's move among `shapes` (every obstacle of the cell, in order), not certified.
fn plan_only(
    cell: &Cell,
    r: usize,
    from: usize,
    to: usize,
    planner: &PlannerOptions,
    shapes: &[ConvexPolygon],
) -> Result<PlannedMove, MoveFailure> {
    let robot = &cell.robots[r];
    let (a, b) = (node_pose(cell, r, from), node_pose(cell, r, to));
    plan_move(
        &robot.shape,
        &limits(robot),
        shapes,
        cell.delta,
        a,
        b,
        planner,
    )
    .map_err(|e| match e {
        PlanError::StartBlocked { obstacle } => MoveFailure::Blocked {
            end: "start",
            obstacle: cell.obstacles[obstacle].name.clone(),
        },
        PlanError::GoalBlocked { obstacle } => MoveFailure::Blocked {
            end: "goal",
            obstacle: cell.obstacles[obstacle].name.clone(),
        },
        other => MoveFailure::Plan(other),
    })
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
    let robot = &cell.robots[r];
    let trajectory = Trajectory::new(samples.to_vec())
        .expect("the planner emits finite samples at increasing times");
    let mut bodies = Vec::with_capacity(obstacles.len() + 1);
    bodies.push(Body::robot(
        robot.name.clone(),
        robot.shape.clone(),
        trajectory,
    ));
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
/// let (lower, store) = (bounds(&cell), MoveStore::new(&cell, &PlannerOptions::default()));
/// // Never longer than the certified move: R2 from home around the fixture to weld-1.
/// assert!(lower.bound(1, 0, 1) <= store.duration(1, 0, 1).unwrap());
/// assert!(lower.bound(1, 0, 1) > 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn bounds(cell: &Cell) -> Bounds {
    let pose = |p: &Pose| (p.pos, p.theta);
    Bounds::new(
        cell.robots
            .iter()
            .map(|r| BoundLimits {
                max_speed: r.max_speed,
                max_accel: r.max_accel,
                max_angular_accel: r.max_accel / r.shape.radius(),
                max_turn_rate: r.max_turn_rate,
            })
            .collect(),
        cell.robots.iter().map(|r| pose(&r.home)).collect(),
        cell.tasks.iter().map(|t| pose(&t.at)).collect(),
    )
}

/// Independent locks over the store, so that planning threads seldom wait for each other.
const SHARDS: usize = 64;

/// A move `(robot, a, b)` with `a <= b`, planned once; its reverse made on first use.
#[derive(Default)]
struct Slot {
    forward: OnceLock<Result<Arc<PlannedMove>, MoveFailure>>,
    backward: OnceLock<Arc<PlannedMove>>,
}

/// One lock's share of the store: `(robot, a, b)` to its slot.
type Shard = HashMap<(usize, usize, usize), Arc<Slot>>;

/// The one store of planned and certified moves of a cell. Thread-safe: any thread may ask
/// for any move; each is planned and certified once (a thread asking for a move being
/// planned waits for it), and a move and its reverse share one plan. The planner is
/// deterministic, so what the store holds never depends on who asked first.
pub struct MoveStore {
    cell: Cell,
    planner: PlannerOptions,
    shapes: Vec<ConvexPolygon>,
    obstacles: Vec<Body>,
    /// Each obstacle's bounding box.
    boxes: Vec<(Vec2, Vec2)>,
    shards: Vec<Mutex<Shard>>,
    planned: AtomicUsize,
}

impl fmt::Debug for MoveStore {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("MoveStore")
            .field("planned", &self.planned())
            .finish_non_exhaustive()
    }
}

impl MoveStore {
    /// An empty store for `cell` (kept as a copy) and these planner settings.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::MoveStore;
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// assert_eq!(store.planned(), 0); // nothing is planned before it is asked for
    /// store.get(0, 0, 1).unwrap();
    /// store.get(0, 1, 0).unwrap(); // the same move backwards: not planned again
    /// assert_eq!(store.planned(), 1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(cell: &Cell, planner: &PlannerOptions) -> Self {
        MoveStore {
            cell: cell.clone(),
            planner: *planner,
            shapes: cell.obstacles.iter().map(|o| o.shape.clone()).collect(),
            obstacles: cell.obstacle_bodies(),
            boxes: cell
                .obstacles
                .iter()
                .map(|o| bounding_box(o.shape.vertices()))
                .collect(),
            shards: (0..SHARDS).map(|_| Mutex::new(HashMap::new())).collect(),
            planned: AtomicUsize::new(0),
        }
    }

    fn slot(&self, r: usize, a: usize, b: usize) -> Arc<Slot> {
        let shard = (r.wrapping_mul(0x9E37_79B9) ^ a.wrapping_mul(0x85EB_CA6B) ^ b) % SHARDS;
        let mut map = self.shards[shard]
            .lock()
            .expect("no thread panics holding it");
        map.entry((r, a, b)).or_default().clone()
    }

    /// Robot `r`'s certified move from node `from` to node `to`, planned on first use.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{node_pose, MoveStore};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let (out, back) = (store.get(0, 0, 2).unwrap(), store.get(0, 2, 0).unwrap());
    /// assert_eq!(out.samples[0].pos, node_pose(&cell, 0, 0).pos);
    /// assert_eq!(back.samples[0].pos, out.samples.last().unwrap().pos);
    /// assert_eq!(back.duration, out.duration);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn get(&self, r: usize, from: usize, to: usize) -> Result<Arc<PlannedMove>, MoveFailure> {
        let (a, b) = (from.min(to), from.max(to));
        let slot = self.slot(r, a, b);
        let planned = slot
            .forward
            .get_or_init(|| {
                self.planned.fetch_add(1, Ordering::Relaxed);
                self.plan(r, a, b).map(Arc::new)
            })
            .clone()?;
        Ok(if from <= to {
            planned
        } else {
            slot.backward
                .get_or_init(|| Arc::new(reversed(&planned)))
                .clone()
        })
    }

    /// Plans and certifies robot `r`'s move from `a` to `b`: the same move as
    /// [`certified_move`] with every obstacle, found faster when few obstacles are near it.
    ///
    /// The planner keeps G out of each obstacle grown by the robot swept over the move's
    /// rotation (within the disc of radius `radius / cos(rotation_step / 2)`) and the
    /// clearance disc (within `δ(1 + clearance_margin) / cos(π/16)`), so an obstacle farther
    /// than their sum from the straight segment can neither block it nor block its ends. If
    /// the obstacles near the segment leave it free, the straight move is the planner's answer
    /// with every obstacle too, bit for bit (the boundary tolerance only grows with more
    /// obstacles, and a free straight move does not depend on it); otherwise the move is
    /// planned again with every obstacle. The checker then sees the obstacles near the
    /// samples: a farther one cannot come within δ.
    fn plan(&self, r: usize, a: usize, b: usize) -> Result<PlannedMove, MoveFailure> {
        let cell = &self.cell;
        let robot = &cell.robots[r];
        let (pa, pb) = (node_pose(cell, r, a).pos, node_pose(cell, r, b).pos);
        let clearance = cell.delta * (1.0 + self.planner.clearance_margin);
        let reach = (robot.shape.radius() / (self.planner.rotation_step / 2.0).cos()
            + 2.0 * clearance)
            * NEAR_SLACK
            + cell.delta;
        let segment = bounding_box(&[pa, pb]);
        let near: Vec<usize> = (0..self.boxes.len())
            .filter(|&k| boxes_within(&self.boxes[k], &segment, reach))
            .collect();
        let planned = if near.len() < self.boxes.len() {
            let shapes: Vec<ConvexPolygon> = near.iter().map(|&k| self.shapes[k].clone()).collect();
            let straight = plan_move(
                &robot.shape,
                &limits(robot),
                &shapes,
                cell.delta,
                node_pose(cell, r, a),
                node_pose(cell, r, b),
                &self.planner,
            )
            .ok()
            .filter(|m| m.path.len() == 2 && m.path[0] == pa && m.path[1] == pb);
            match straight {
                Some(m) => m,
                None => plan_only(cell, r, a, b, &self.planner, &self.shapes)?,
            }
        } else {
            plan_only(cell, r, a, b, &self.planner, &self.shapes)?
        };
        let seen = bounding_box(&planned.samples.iter().map(|s| s.pos).collect::<Vec<_>>());
        let reach = robot.shape.radius() * NEAR_SLACK + 2.0 * cell.delta;
        let bodies: Vec<Body> = (0..self.boxes.len())
            .filter(|&k| boxes_within(&self.boxes[k], &seen, reach))
            .map(|k| self.obstacles[k].clone())
            .collect();
        certify(cell, r, &planned.samples, &bodies)?;
        Ok(planned)
    }

    /// The duration of robot `r`'s move between two nodes (the same both ways), planned on
    /// first use.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::MoveStore;
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// assert_eq!(store.duration(1, 2, 4).unwrap(), store.get(1, 4, 2).unwrap().duration);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn duration(&self, r: usize, from: usize, to: usize) -> Result<f64, MoveFailure> {
        self.get(r, from.min(to), from.max(to)).map(|m| m.duration)
    }

    /// The move's outcome if it was planned already; `None` if not (nothing is planned).
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::MoveStore;
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// assert!(store.known(0, 1, 3).is_none());
    /// let d = store.duration(0, 1, 3).unwrap();
    /// assert_eq!(store.known(0, 3, 1), Some(Ok(d)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn known(&self, r: usize, from: usize, to: usize) -> Option<Result<f64, MoveFailure>> {
        let (a, b) = (from.min(to), from.max(to));
        let shard = (r.wrapping_mul(0x9E37_79B9) ^ a.wrapping_mul(0x85EB_CA6B) ^ b) % SHARDS;
        let map = self.shards[shard]
            .lock()
            .expect("no thread panics holding it");
        let slot = map.get(&(r, a, b))?;
        slot.forward
            .get()
            .map(|m| m.as_ref().map(|m| m.duration).map_err(Clone::clone))
    }

    /// Plans the moves `(robot, a, b)` not planned yet, in parallel; `progress` is called
    /// once per move (from any thread). Returns each move's duration (infinite: no move) in
    /// the order given.
    ///
    /// ```
    /// use std::sync::atomic::{AtomicUsize, Ordering};
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::MoveStore;
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let told = AtomicUsize::new(0);
    /// let times = store.plan_all(&[(0, 0, 1), (1, 0, 4)], &|| { told.fetch_add(1, Ordering::Relaxed); });
    /// assert_eq!((store.planned(), told.into_inner()), (2, 2));
    /// assert_eq!(times, [store.duration(0, 0, 1).unwrap(), store.duration(1, 4, 0).unwrap()]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn plan_all(
        &self,
        moves: &[(usize, usize, usize)],
        progress: &(dyn Fn() + Sync),
    ) -> Vec<f64> {
        moves
            .par_iter()
            .map(|&(r, a, b)| {
                let d = self.duration(r, a, b).unwrap_or(f64::INFINITY);
                progress();
                d
            })
            .collect()
    }

    /// Moves planned so far (one per robot and unordered pair of nodes).
    pub fn planned(&self) -> usize {
        self.planned.load(Ordering::Relaxed)
    }

    /// The cell the store plans for.
    pub fn cell(&self) -> &Cell {
        &self.cell
    }

    /// The cell's obstacles as checker bodies.
    pub fn obstacles(&self) -> &[Body] {
        &self.obstacles
    }

    /// The planner's settings.
    pub fn planner(&self) -> &PlannerOptions {
        &self.planner
    }
}

/// The same move run backwards: the same poses, visited in reverse order.
fn reversed(m: &PlannedMove) -> PlannedMove {
    let samples = m
        .samples
        .iter()
        .rev()
        .map(|s| Sample {
            t: m.duration - s.t,
            vel: -s.vel,
            omega: -s.omega,
            ..*s
        })
        .collect();
    PlannedMove {
        duration: m.duration,
        path: m.path.iter().rev().copied().collect(),
        samples,
        primitives: m.primitives.iter().rev().map(|p| p.reversed()).collect(),
    }
}
