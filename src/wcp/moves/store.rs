//! [`MoveStore`]: each move of the cell planned and certified once, whoever asks first; and
//! the motions the feedback loop's remedies ask for between any two poses, planned once too.

use super::{
    bounding_box, boxes_within, certify, limits, node_pose, plan_only, Fixtures, MoveFailure,
    NEAR_SLACK,
};
use crate::cell::Cell;
use crate::collision::Body;
use crate::geometry::{ConvexPolygon, Vec2};
use crate::motion::IkSettings;
use crate::motion::{JointSample, Pose, Sample};
use crate::planning::{plan_move, time_primitives, PlannedMove, PlannerOptions, Primitive};
use crate::planning::{ArmModel, JointPathSettings};
use crate::wcp::configurations::{configurations_found, Assignment, Configurations};
use crate::wcp::sequencer::node_task;
use rayon::prelude::*;
use std::collections::HashMap;
use std::fmt;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

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
    /// Every convex piece of the obstacles, as the planner takes them.
    fixtures: Fixtures,
    /// Each piece's bounding box.
    piece_boxes: Vec<(Vec2, Vec2)>,
    obstacles: Vec<Body>,
    /// Each obstacle's bounding box.
    boxes: Vec<(Vec2, Vec2)>,
    shards: Arc<Vec<Mutex<Shard>>>,
    planned: Arc<AtomicUsize>,
    /// Motions between any two poses around extra obstacles (the remedies' detours and
    /// ways to a parking pose), keyed by robot, end poses and extra obstacles' bits.
    between: Arc<Mutex<Between>>,
    /// Which configuration each arm takes at each task.
    assignment: Arc<Assignment>,
    /// Arms' moves, by robot and both ends' nodes and configurations (shared by the
    /// stores of other assignments).
    arm_moves: Arc<Mutex<HashMap<ArmKey, Arc<Slot>>>>,
}

/// Motions between two poses, by the bits of the robot, poses and extra obstacles.
type Between = HashMap<Vec<u64>, Option<Arc<PlannedMove>>>;

/// An arm's move: robot, then node and configuration index of each end, lower node first.
type ArmKey = (usize, (usize, usize), (usize, usize));

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
        let found = match cell.robots.iter().any(|r| r.as_arm().is_some()) {
            true => configurations_found(cell, &IkSettings::default()),
            false => Configurations::default(),
        };
        MoveStore::with_assignment(
            cell,
            planner,
            Assignment::nearest_home(cell, Arc::new(found)),
        )
    }

    /// An empty store for `cell` with the arms in the configurations of `assignment`.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::motion::IkSettings;
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{task_configurations, Assignment, MoveStore};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let found = Arc::new(task_configurations(&cell, &IkSettings::default())?);
    /// let store = MoveStore::with_assignment(&cell, &PlannerOptions::default(), Assignment::nearest_home(&cell, found));
    /// assert_eq!(store.planned(), 0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_assignment(cell: &Cell, planner: &PlannerOptions, assignment: Assignment) -> Self {
        let fixtures = Fixtures::of(cell);
        let piece_boxes = fixtures
            .pieces
            .iter()
            .map(|p| bounding_box(p.vertices()))
            .collect();
        MoveStore {
            cell: cell.clone(),
            planner: *planner,
            fixtures,
            piece_boxes,
            obstacles: cell.obstacle_bodies(),
            boxes: cell
                .obstacles
                .iter()
                .map(|o| bounding_box(o.shape.vertices()))
                .collect(),
            shards: Arc::new((0..SHARDS).map(|_| Mutex::new(HashMap::new())).collect()),
            planned: Arc::new(AtomicUsize::new(0)),
            between: Arc::new(Mutex::new(HashMap::new())),
            assignment: Arc::new(assignment),
            arm_moves: Arc::new(Mutex::new(HashMap::new())),
        }
    }

    /// The same store (sharing every move planned so far, and those planned from now on)
    /// with the arms in the configurations of `assignment`.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::MoveStore;
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// store.get(0, 0, 1).unwrap();
    /// let same = store.assigned(store.assignment().clone());
    /// assert_eq!(same.known(0, 0, 1), store.known(0, 0, 1)); // planned once, for both
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn assigned(&self, assignment: Assignment) -> MoveStore {
        MoveStore {
            cell: self.cell.clone(),
            planner: self.planner,
            fixtures: self.fixtures.clone(),
            piece_boxes: self.piece_boxes.clone(),
            obstacles: self.obstacles.clone(),
            boxes: self.boxes.clone(),
            shards: self.shards.clone(),
            planned: self.planned.clone(),
            between: self.between.clone(),
            assignment: Arc::new(assignment),
            arm_moves: self.arm_moves.clone(),
        }
    }

    /// Which configuration each arm takes at each task.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::MoveStore;
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// assert_eq!(store.assignment().joints(&cell, 0, 1), None); // no arm here
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn assignment(&self) -> &Assignment {
        &self.assignment
    }

    /// The arm's slot for the move between `a` and `b` (a <= b) in the current assignment.
    fn arm_slot(&self, r: usize, a: usize, b: usize) -> (ArmKey, Arc<Slot>) {
        let index = |n: usize| match n {
            0 => 0,
            n => self.assignment.index(r, node_task(n)),
        };
        self.arm_slot_at((r, (a, index(a)), (b, index(b))))
    }

    fn arm_slot_at(&self, key: ArmKey) -> (ArmKey, Arc<Slot>) {
        let mut map = self.arm_moves.lock().unwrap_or_else(|e| e.into_inner());
        (key, map.entry(key).or_default().clone())
    }

    /// Arm `r`'s joint angles at node `n` in its configuration `k` there (home: 0).
    fn arm_joints(&self, r: usize, (n, k): (usize, usize)) -> Option<&[f64]> {
        let arm = self.cell.robots[r].as_arm()?;
        match n {
            0 => Some(&arm.home),
            n => (self.assignment.configurations().at(r, node_task(n)).get(k)).map(|q| &q[..]),
        }
    }

    /// The duration of arm `r`'s move between node `a` in its configuration `ka` and node
    /// `b` in its configuration `kb`, whatever the assignment (the same both ways), planned
    /// on first use: what choosing configurations weighs.
    pub(crate) fn arm_duration(
        &self,
        r: usize,
        a: (usize, usize),
        b: (usize, usize),
    ) -> Result<f64, MoveFailure> {
        let (a, b) = if a.0 <= b.0 { (a, b) } else { (b, a) };
        let (key, slot) = self.arm_slot_at((r, a, b));
        slot.forward
            .get_or_init(|| {
                self.planned.fetch_add(1, Ordering::Relaxed);
                self.plan_arm(key).map(Arc::new)
            })
            .as_ref()
            .map(|m| m.duration)
            .map_err(Clone::clone)
    }

    /// Plans an arm's move in joint space: the straight move when the checker certifies it
    /// clear of the fixtures, else a path around them.
    fn plan_arm(&self, (r, a, b): ArmKey) -> Result<PlannedMove, MoveFailure> {
        let cell = &self.cell;
        let arm = cell.robots[r].as_arm().expect("an arm");
        let joints = |end| self.arm_joints(r, end).ok_or(MoveFailure::NoConfiguration);
        let (qa, qb) = (joints(a)?, joints(b)?);
        let model = ArmModel::new(&cell.robots[r].name, arm);
        let settings = JointPathSettings {
            samples_per_phase: self.planner.samples_per_phase,
            ..JointPathSettings::default()
        };
        let path = model
            .joint_path(qa, qb, &self.obstacles, cell.delta, &settings)
            .ok_or(MoveFailure::NoJointPath)?;
        Ok(model.planned(&path.motion))
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
        let arm = self.cell.robots[r].as_arm().is_some();
        let (key, slot) = match arm {
            true => self.arm_slot(r, a, b),
            false => ((r, (a, 0), (b, 0)), self.slot(r, a, b)),
        };
        let planned = slot
            .forward
            .get_or_init(|| {
                self.planned.fetch_add(1, Ordering::Relaxed);
                match arm {
                    true => self.plan_arm(key).map(Arc::new),
                    false => self.plan(r, a, b).map(Arc::new),
                }
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
        let robot = cell.rigid(r);
        let (pa, pb) = (node_pose(cell, r, a).pos, node_pose(cell, r, b).pos);
        let clearance = cell.delta * (1.0 + self.planner.clearance_margin);
        let reach = (robot.shape.radius() / (self.planner.rotation_step / 2.0).cos()
            + 2.0 * clearance)
            * NEAR_SLACK
            + cell.delta;
        let segment = bounding_box(&[pa, pb]);
        let boxes = &self.piece_boxes;
        let near: Vec<usize> = (0..boxes.len())
            .filter(|&k| boxes_within(&boxes[k], &segment, reach))
            .collect();
        let planned = if near.len() < boxes.len() {
            let pieces = &self.fixtures.pieces;
            let shapes: Vec<ConvexPolygon> = near.iter().map(|&k| pieces[k].clone()).collect();
            let straight = plan_move(
                robot.pieces(),
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
                None => plan_only(cell, r, a, b, &self.planner, &self.fixtures)?,
            }
        } else {
            plan_only(cell, r, a, b, &self.planner, &self.fixtures)?
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
        if self.cell.robots[r].as_arm().is_some() {
            let (_, slot) = self.arm_slot(r, a, b);
            let outcome = slot.forward.get()?;
            return Some(outcome.as_ref().map(|m| m.duration).map_err(Clone::clone));
        }
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

    /// Robot `r`'s fastest move from pose `from` to pose `to` around the fixtures and
    /// `extra`, certified clear of the fixtures and timed again from its primitives (as
    /// `evaluate` times it); `None` if there is none. Planned once per robot, poses and
    /// extra obstacles, like the moves between nodes.
    pub(crate) fn between(
        &self,
        r: usize,
        from: Pose,
        to: Pose,
        extra: &[ConvexPolygon],
    ) -> Option<Arc<PlannedMove>> {
        let mut key = vec![r as u64];
        for p in [from, to] {
            key.extend([p.pos.x, p.pos.y, p.theta].map(f64::to_bits));
        }
        for o in extra {
            key.push(o.len() as u64);
            key.extend(
                o.vertices()
                    .iter()
                    .flat_map(|v| [v.x.to_bits(), v.y.to_bits()]),
            );
        }
        if let Some(known) = self.lock_between().get(&key) {
            return known.clone();
        }
        let robot = self.cell.rigid(r);
        let mut obstacles = self.fixtures.pieces.clone();
        obstacles.extend_from_slice(extra);
        let planned = plan_move(
            robot.pieces(),
            &limits(robot),
            &obstacles,
            self.cell.delta,
            from,
            to,
            &self.planner,
        )
        .ok()
        .filter(|m| certify(&self.cell, r, &m.samples, &self.obstacles).is_ok())
        .map(|m| self.timed(r, &m.primitives));
        self.lock_between().entry(key).or_insert(planned).clone()
    }

    /// Robot `r` along `primitives` (rest to rest at every waypoint), timed as the planner
    /// times them and certified clear of the fixtures; `None` if it is not clear. Once per
    /// robot and primitives (kept with the moves between poses): a convoy moves the same
    /// stretches of its loop at every collision it answers.
    pub(crate) fn along(&self, r: usize, primitives: &[Primitive]) -> Option<Arc<PlannedMove>> {
        // No robot index is u64::MAX: these keys never meet those of `between`.
        let mut key = vec![u64::MAX, r as u64];
        for p in primitives {
            key.push(p.path.len() as u64);
            key.extend(p.path.iter().flat_map(|v| [v.x.to_bits(), v.y.to_bits()]));
            key.extend([p.theta.to_bits(), p.turn.to_bits()]);
        }
        if let Some(known) = self.lock_between().get(&key) {
            return known.clone();
        }
        let timed = self.timed(r, primitives);
        let clear = certify(&self.cell, r, &timed.samples, &self.obstacles).is_ok();
        let made = clear.then_some(timed);
        self.lock_between().entry(key).or_insert(made).clone()
    }

    fn lock_between(&self) -> std::sync::MutexGuard<'_, Between> {
        self.between.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Times primitives for robot `r` as the planner would.
    pub(crate) fn timed(&self, r: usize, primitives: &[Primitive]) -> Arc<PlannedMove> {
        let robot = self.cell.rigid(r);
        Arc::new(time_primitives(
            robot.shape.radius(),
            &limits(robot),
            primitives,
            self.planner.samples_per_phase,
        ))
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
        joints: (m.joints.iter().rev())
            .map(|s| JointSample {
                t: m.duration - s.t,
                q: s.q.clone(),
                qd: s.qd.iter().map(|v| -v).collect(),
            })
            .collect(),
    }
}
