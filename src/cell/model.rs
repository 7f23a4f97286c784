//! The cell as the solver takes it (contract section 3), validated: robots, fixtures and
//! tasks. Read from a file by `cell_file.rs`, built in code by `cell_build.rs`.

use super::InputError;
use crate::collision::Body;
use crate::geometry::{ConvexPolygon, Parts};
use crate::motion::{forward_kinematics, ArmMotion, JointLimits, JointSample, Pose, Trajectory};
use std::path::PathBuf;

/// A robot of the cell: a rigid body that glides (contract section 3) or a planar arm
/// (section 7).
#[derive(Clone, Debug, PartialEq)]
pub struct CellRobot {
    /// Name, unique among robots, obstacles and tasks.
    pub name: String,
    /// What kind of robot, with its shape, home and limits.
    pub kind: RobotKind,
}

/// The two kinds of robot a cell holds.
#[derive(Clone, Debug, PartialEq)]
pub enum RobotKind {
    /// A rigid body whose pose is planned in the plane.
    Rigid(RigidRobot),
    /// A planar arm of revolute joints, planned in its joint space.
    Arm(ArmRobot),
}

/// A rigid robot: its shape, home and limits.
#[derive(Clone, Debug, PartialEq)]
pub struct RigidRobot {
    /// Shape in the body frame (origin: the rotation centre G): the convex hull of `parts`
    /// when the robot is made of parts.
    pub shape: ConvexPolygon,
    /// The convex parts of a robot that is not convex (given as `parts` or `outline`, in the
    /// body frame); `None` for one convex `shape`.
    pub parts: Option<Parts>,
    /// Where the robot starts and ends.
    pub home: Pose,
    /// Largest speed of G.
    pub max_speed: f64,
    /// Largest acceleration of G.
    pub max_accel: f64,
    /// Largest angular speed.
    pub max_turn_rate: f64,
}

/// A planar arm of revolute joints (contract section 7): its base, links, home angles and
/// joint limits.
#[derive(Clone, Debug, PartialEq)]
pub struct ArmRobot {
    /// The pose of the fixed base.
    pub base: Pose,
    /// Each link's length and body, in the link's frame (contract section 6).
    pub links: Vec<(f64, Parts)>,
    /// The joint angles where the arm starts and ends, one per link.
    pub home: Vec<f64>,
    /// Joint ranges, speeds and accelerations, one entry per link.
    pub limits: JointLimits,
}

/// A fixed obstacle in world coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct CellObstacle {
    /// Name, unique among robots, obstacles and tasks.
    pub name: String,
    /// Shape in world coordinates: the convex hull of `parts` when the obstacle is made of
    /// parts.
    pub shape: ConvexPolygon,
    /// The convex parts of an obstacle that is not convex (given as `parts` or `outline`, in
    /// world coordinates); `None` for one convex `shape`.
    pub parts: Option<Parts>,
}

impl CellRobot {
    /// A rigid robot named `name`.
    ///
    /// ```
    /// use workcell::cell::{CellRobot, RigidRobot};
    /// use workcell::geometry::ConvexPolygon;
    /// use workcell::motion::Pose;
    /// let shape = ConvexPolygon::rectangle(1.0, 1.0)?;
    /// let home = Pose::new(0.0, 0.0, 0.0);
    /// let r = CellRobot::rigid("R1", RigidRobot { shape, parts: None, home, max_speed: 1.0, max_accel: 2.0, max_turn_rate: 1.0 });
    /// assert_eq!(r.as_rigid().map(|b| b.home), Some(home));
    /// assert!(r.as_arm().is_none());
    /// # Ok::<(), workcell::geometry::PolygonError>(())
    /// ```
    pub fn rigid(name: impl Into<String>, robot: RigidRobot) -> CellRobot {
        CellRobot {
            name: name.into(),
            kind: RobotKind::Rigid(robot),
        }
    }

    /// An arm named `name`.
    ///
    /// ```
    /// use workcell::cell::{ArmRobot, CellRobot};
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// use workcell::motion::{JointLimits, Pose};
    /// let bar = Parts::new(vec![ConvexPolygon::from_vertices(&[[-0.1, -0.1], [1.1, -0.1], [1.1, 0.1], [-0.1, 0.1]])?])?;
    /// let limits = JointLimits { range: vec![None], max_speed: vec![1.0], max_accel: vec![2.0] };
    /// let a = CellRobot::arm("A1", ArmRobot { base: Pose::new(0.0, 0.0, 0.0), links: vec![(1.0, bar)], home: vec![0.0], limits });
    /// assert_eq!(a.as_arm().map(|arm| arm.home.len()), Some(1));
    /// assert!(a.as_rigid().is_none());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn arm(name: impl Into<String>, arm: ArmRobot) -> CellRobot {
        CellRobot {
            name: name.into(),
            kind: RobotKind::Arm(arm),
        }
    }

    /// The robot's convex pieces placed as at home: its body at its home pose, or each
    /// link of an arm at its home joint angles.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// let r1 = cell.rigid(0);
    /// assert_eq!(cell.robots[0].at_home(), [(r1.pieces(), r1.home)]);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn at_home(&self) -> Vec<(&[ConvexPolygon], Pose)> {
        match &self.kind {
            RobotKind::Rigid(r) => vec![(r.pieces(), r.home)],
            RobotKind::Arm(a) => a.placed(&a.home),
        }
    }

    /// How far a point of the robot's body may lie from a centre it turns about, where an
    /// angle's rounding moves it most: the radius of a rigid robot; for an arm, the sum of
    /// its link lengths and its largest link's radius (a joint turns all links after it).
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// assert_eq!(cell.robots[0].rim(), cell.rigid(0).shape.radius());
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn rim(&self) -> f64 {
        match &self.kind {
            RobotKind::Rigid(r) => r.shape.radius(),
            RobotKind::Arm(a) => {
                let lengths: f64 = a.links.iter().map(|l| l.0).sum();
                let radius =
                    (a.links.iter().map(|(_, body)| body.hull().radius())).fold(0.0, f64::max);
                lengths + radius
            }
        }
    }

    /// The rigid robot, `None` for an arm.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// assert!(cell.robots.iter().all(|r| r.as_rigid().is_some()));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn as_rigid(&self) -> Option<&RigidRobot> {
        match &self.kind {
            RobotKind::Rigid(r) => Some(r),
            RobotKind::Arm(_) => None,
        }
    }

    /// The arm, `None` for a rigid robot.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// assert!(cell.robots.iter().all(|r| r.as_arm().is_none()));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn as_arm(&self) -> Option<&ArmRobot> {
        match &self.kind {
            RobotKind::Arm(a) => Some(a),
            RobotKind::Rigid(_) => None,
        }
    }

    /// How far the robot's body reaches from its reference point: a rigid robot's radius
    /// (the disc about G that holds it in every rotation), an arm's largest link's.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// // A square of side 1: half its diagonal.
    /// assert!((cell.robots[0].body_radius() - 0.5f64.hypot(0.5)).abs() < 1e-12);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn body_radius(&self) -> f64 {
        match &self.kind {
            RobotKind::Rigid(robot) => robot.shape.radius(),
            RobotKind::Arm(arm) => (arm.links.iter())
                .map(|(_, body)| body.hull().radius())
                .fold(0.0, f64::max),
        }
    }
}

impl RigidRobot {
    /// The robot's convex pieces, whose union it is: its parts, or its one shape.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// let r1 = cell.rigid(0);
    /// assert_eq!(r1.pieces(), [r1.shape.clone()]);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn pieces(&self) -> &[ConvexPolygon] {
        pieces(&self.shape, &self.parts)
    }

    /// The robot, named `name`, as a checker body moving along `trajectory` (with its parts).
    ///
    /// ```
    /// use workcell::motion::{Sample, Trajectory};
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// let robot = cell.rigid(0);
    /// let still = Trajectory::new(vec![Sample::at(0.0, robot.home)])?;
    /// let body = robot.body("R1", still);
    /// assert_eq!((body.name.as_str(), &body.shape), ("R1", &robot.shape));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn body(&self, name: &str, trajectory: Trajectory) -> Body {
        match &self.parts {
            Some(parts) => Body::robot_of_parts(name, parts.clone(), trajectory),
            None => Body::robot(name, self.shape.clone(), trajectory),
        }
    }
}

impl ArmRobot {
    /// The link lengths.
    ///
    /// ```
    /// use workcell::cell::ArmRobot;
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// use workcell::motion::{JointLimits, Pose};
    /// let bar = Parts::new(vec![ConvexPolygon::from_vertices(&[[-0.1, -0.1], [1.1, -0.1], [1.1, 0.1], [-0.1, 0.1]])?])?;
    /// let limits = JointLimits { range: vec![None; 2], max_speed: vec![1.0; 2], max_accel: vec![2.0; 2] };
    /// let arm = ArmRobot { base: Pose::new(0.0, 0.0, 0.0), links: vec![(1.0, bar.clone()), (0.5, bar)], home: vec![0.0; 2], limits };
    /// assert_eq!(arm.lengths(), [1.0, 0.5]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn lengths(&self) -> Vec<f64> {
        self.links.iter().map(|l| l.0).collect()
    }

    /// The arm, named `name`, as checker bodies (one per link) moving through `joints`.
    ///
    /// # Panics
    /// When the samples do not make a trajectory of this arm (see [`ArmMotion::new`]): the
    /// caller's samples come from the arm's own planned moves.
    ///
    /// ```
    /// use workcell::cell::ArmRobot;
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// use workcell::motion::{JointLimits, JointSample, Pose};
    /// let bar = Parts::new(vec![ConvexPolygon::from_vertices(&[[-0.1, -0.1], [1.1, -0.1], [1.1, 0.1], [-0.1, 0.1]])?])?;
    /// let limits = JointLimits { range: vec![None; 2], max_speed: vec![1.0; 2], max_accel: vec![2.0; 2] };
    /// let arm = ArmRobot { base: Pose::new(0.0, 0.0, 0.0), links: vec![(1.0, bar.clone()), (1.0, bar)], home: vec![0.0; 2], limits };
    /// let still = [JointSample { t: 0.0, q: vec![0.0, 0.0], qd: vec![0.0, 0.0] }];
    /// let bodies = arm.bodies("A1", still.to_vec());
    /// assert_eq!((bodies.len(), bodies[1].link()), (2, Some(1)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn bodies(&self, name: &str, joints: Vec<JointSample>) -> Vec<Body> {
        let radii = self.links.iter().map(|l| l.1.hull().radius()).collect();
        let motion = ArmMotion::new(self.base, self.lengths(), radii, joints)
            .expect("an arm's planned samples make its trajectory");
        Body::arm(
            name,
            motion,
            self.links.iter().map(|l| l.1.clone()).collect(),
        )
    }

    /// Each link's convex pieces placed at joint angles `q`.
    ///
    /// ```
    /// use workcell::cell::ArmRobot;
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// use workcell::motion::{JointLimits, Pose};
    /// let bar = Parts::new(vec![ConvexPolygon::from_vertices(&[[-0.1, -0.1], [1.1, -0.1], [1.1, 0.1], [-0.1, 0.1]])?])?;
    /// let limits = JointLimits { range: vec![None; 2], max_speed: vec![1.0; 2], max_accel: vec![2.0; 2] };
    /// let arm = ArmRobot { base: Pose::new(0.0, 0.0, 0.0), links: vec![(1.0, bar.clone()), (1.0, bar)], home: vec![0.0; 2], limits };
    /// let placed = arm.placed(&[0.0, 0.0]);
    /// assert_eq!(placed[1].1, Pose::new(1.0, 0.0, 0.0)); // the second link at the elbow
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn placed(&self, q: &[f64]) -> Vec<(&[ConvexPolygon], Pose)> {
        let lengths = self.lengths();
        (self.links.iter().enumerate())
            .map(|(k, (_, body))| (body.parts(), forward_kinematics(self.base, &lengths, q, k)))
            .collect()
    }
}

impl CellObstacle {
    /// The obstacle's convex pieces in world coordinates: its parts, or its one shape.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/bay-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// let (bay, post) = (&cell.obstacles[0], &cell.obstacles[1]);
    /// assert_eq!(bay.pieces().len(), 3); // the U's outline, cut into convex parts
    /// assert_eq!(post.pieces(), [post.shape.clone()]);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn pieces(&self) -> &[ConvexPolygon] {
        pieces(&self.shape, &self.parts)
    }

    /// The obstacle as a checker body (with its parts).
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/bay-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// let bay = cell.obstacles[0].body();
    /// assert!(!bay.is_robot() && bay.parts.is_some());
    /// assert!(cell.obstacles[1].body().parts.is_none());
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn body(&self) -> Body {
        match &self.parts {
            Some(parts) => Body::obstacle_of_parts(self.name.clone(), parts),
            None => Body::obstacle(self.name.clone(), &self.shape),
        }
    }
}

fn pieces<'a>(shape: &'a ConvexPolygon, parts: &'a Option<Parts>) -> &'a [ConvexPolygon] {
    parts
        .as_ref()
        .map_or(std::slice::from_ref(shape), |p| p.parts())
}

/// A task: a pose to hold for a duration, by one of the allowed robots.
#[derive(Clone, Debug, PartialEq)]
pub struct Task {
    /// Name, unique among robots, obstacles and tasks.
    pub name: String,
    /// The pose the robot holds while doing the task (for an arm, the tool's pose).
    pub at: Pose,
    /// The file gave `at` as `[x, y]`: an arm may hold its tool at any angle there (a rigid
    /// robot holds the angle 0).
    pub free_angle: bool,
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
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/hall-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// let bodies = cell.obstacle_bodies();
    /// assert_eq!(bodies.len(), cell.obstacles.len());
    /// assert!(bodies.iter().all(|b| !b.is_robot()));
    /// assert_eq!(bodies[0].name, cell.obstacles[0].name);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn obstacle_bodies(&self) -> Vec<Body> {
        self.obstacles.iter().map(CellObstacle::body).collect()
    }

    /// Robot `r`, which the caller knows to be rigid (the rigid planner and its remedies).
    ///
    /// # Panics
    /// When robot `r` is an arm: a bug of the caller, which must branch on
    /// [`CellRobot::kind`] first.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// assert_eq!(cell.rigid(1).max_speed, cell.robots[1].as_rigid().unwrap().max_speed);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn rigid(&self, r: usize) -> &RigidRobot {
        self.robots[r]
            .as_rigid()
            .unwrap_or_else(|| panic!("robot {} is an arm, not a rigid robot", self.robots[r].name))
    }

    /// An error about this cell's file.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// let e = cell.error(Some("R1"), "robots[0].home", "in the way");
    /// assert_eq!((e.body.as_deref(), e.field.as_str()), (Some("R1"), "robots[0].home"));
    /// assert!(e.to_string().contains("feedback-cell.json"));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn error(
        &self,
        body: Option<&str>,
        field: impl Into<String>,
        reason: impl std::fmt::Display,
    ) -> InputError {
        InputError::new(&self.file, body, field, reason)
    }
}
