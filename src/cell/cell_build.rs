//! Building a cell in code: the checks of a cell file, field by field, with the errors
//! naming the field as the file would (`robots[0].max_speed`), and no file.

use super::arm_file::ArmAt;
use super::cell_checks::check_geometry;
use super::cell_file::{allowed_robots, check_duration, check_limits, check_name, owner};
use super::model::{Cell, CellObstacle, CellRobot, RigidRobot, RobotKind, Task};
use super::InputError;
use crate::collision::check_delta;
use crate::geometry::{ConvexPolygon, Parts};
use crate::motion::Pose;
use std::path::PathBuf;

impl Cell {
    /// An empty cell whose bodies collide closer than `delta` (refused unless positive and
    /// finite). Add robots, obstacles and tasks, then [`Cell::validate`] before solving.
    ///
    /// ```
    /// use workcell::cell::{Cell, CellObstacle, CellRobot, RigidRobot};
    /// use workcell::geometry::{ConvexPolygon, Vec2};
    /// use workcell::motion::Pose;
    /// use workcell::wcp::{prepare, solve, SolveOptions};
    ///
    /// let square = ConvexPolygon::rectangle(1.0, 1.0)?;
    /// let mut cell = Cell::new(0.01)?;
    /// cell.add_robot(CellRobot::rigid("R1", RigidRobot {
    ///     shape: square.clone(),
    ///     parts: None,
    ///     home: Pose::new(0.0, 0.0, 0.0),
    ///     max_speed: 1.0,
    ///     max_accel: 2.0,
    ///     max_turn_rate: 1.0,
    /// }))?
    /// .add_obstacle(CellObstacle { name: "post".into(), shape: square.translated(&Vec2::new(3.0, 3.0)), parts: None })?
    /// .add_task("weld", Pose::new(4.0, 0.0, 0.0), 1.5, None)?
    /// .validate()?;
    /// let opts = SolveOptions::default();
    /// let solved = solve(&cell, &prepare(&cell, &opts, &())?, &opts, &())?;
    /// assert_eq!(solved.routes, [vec![0]]);
    /// // There and back, at most 1 m/s, and the task: more than 8 + 1.5 s.
    /// assert!(solved.schedule.makespan > 9.5);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(delta: f64) -> Result<Cell, InputError> {
        check_delta(delta)?;
        Ok(Cell {
            file: PathBuf::new(),
            delta,
            robots: Vec::new(),
            obstacles: Vec::new(),
            tasks: Vec::new(),
        })
    }

    /// Adds a robot: its name new and non-empty, its home finite, its limits positive and
    /// finite. A rigid robot with `parts` gets their convex hull as its `shape` (a convex
    /// union, as its one shape); an arm is checked as a file's arm is (one home angle and
    /// one limit per joint, home within the joint limits).
    ///
    /// ```
    /// use workcell::cell::{Cell, CellRobot, RigidRobot};
    /// use workcell::geometry::ConvexPolygon;
    /// use workcell::motion::Pose;
    ///
    /// let robot = CellRobot::rigid("R1", RigidRobot {
    ///     shape: ConvexPolygon::rectangle(1.0, 1.0)?,
    ///     parts: None,
    ///     home: Pose::new(0.0, 0.0, 0.0),
    ///     max_speed: 1.0,
    ///     max_accel: 0.0,
    ///     max_turn_rate: 1.0,
    /// });
    /// let e = Cell::new(0.01)?.add_robot(robot).unwrap_err();
    /// assert_eq!((e.body.as_deref(), e.field.as_str()), (Some("R1"), "robots[0].max_accel"));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_robot(&mut self, robot: CellRobot) -> Result<&mut Cell, InputError> {
        let at = format!("robots[{}]", self.robots.len());
        self.check_new_name(&robot.name, &at, "robot")?;
        let kind = match robot.kind {
            RobotKind::Rigid(rigid) => {
                self.check_pose(&robot.name, &format!("{at}.home"), &rigid.home)?;
                check_limits(&self.file, &at, &robot.name, &rigid)?;
                let (shape, parts) = hull_and_parts(rigid.shape, rigid.parts);
                RobotKind::Rigid(RigidRobot {
                    shape,
                    parts,
                    ..rigid
                })
            }
            RobotKind::Arm(arm) => {
                let place = ArmAt {
                    file: &self.file,
                    name: &robot.name,
                    at: &at,
                };
                place.check(&arm)?;
                RobotKind::Arm(arm)
            }
        };
        self.robots.push(CellRobot { kind, ..robot });
        Ok(self)
    }

    /// Adds an obstacle (its shape in world coordinates) under a new, non-empty name. An
    /// obstacle with `parts` gets their convex hull as its `shape`.
    ///
    /// ```
    /// use workcell::cell::{Cell, CellObstacle};
    /// use workcell::geometry::ConvexPolygon;
    ///
    /// let post = ConvexPolygon::rectangle(1.0, 1.0)?;
    /// let mut cell = Cell::new(0.01)?;
    /// cell.add_obstacle(CellObstacle { name: "post".into(), shape: post.clone(), parts: None })?;
    /// let e = cell.add_obstacle(CellObstacle { name: "post".into(), shape: post, parts: None }).unwrap_err();
    /// assert_eq!(e.field, "obstacles[1].name");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_obstacle(&mut self, obstacle: CellObstacle) -> Result<&mut Cell, InputError> {
        let at = format!("obstacles[{}]", self.obstacles.len());
        self.check_new_name(&obstacle.name, &at, "obstacle")?;
        let (shape, parts) = hull_and_parts(obstacle.shape, obstacle.parts);
        self.obstacles.push(CellObstacle {
            shape,
            parts,
            ..obstacle
        });
        Ok(self)
    }

    /// Adds a task: hold pose `at` for `duration` (non-negative, finite), by one of the
    /// robots named in `robots` (added before), or by any robot when `robots` is `None`.
    ///
    /// ```
    /// use workcell::cell::Cell;
    /// use workcell::motion::Pose;
    ///
    /// let mut cell = Cell::new(0.01)?;
    /// let e = cell.add_task("weld", Pose::new(1.0, 0.0, 0.0), 2.0, Some(&["R9"])).unwrap_err();
    /// assert_eq!(e.field, "tasks[0].robots[0]");
    /// assert!(e.reason.contains("no robot is named \"R9\""));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_task(
        &mut self,
        name: &str,
        at: Pose,
        duration: f64,
        robots: Option<&[&str]>,
    ) -> Result<&mut Cell, InputError> {
        let field = format!("tasks[{}]", self.tasks.len());
        self.check_new_name(name, &field, "task")?;
        self.check_pose(name, &format!("{field}.at"), &at)?;
        check_duration(&self.file, &field, name, duration)?;
        let robots = allowed_robots(&self.file, &field, name, robots, self.robots.len(), |n| {
            self.robots.iter().position(|r| r.name == n)
        })?;
        self.tasks.push(Task {
            name: name.to_owned(),
            at,
            free_angle: false,
            duration,
            robots,
        });
        Ok(self)
    }

    /// What a cell file's reader checks once the whole cell is known: at least one robot,
    /// then the geometry (coordinates f64 resolves at δ, homes clear of the obstacles and of
    /// each other by δ, no task pose inside an obstacle, a time axis that keeps every task's
    /// length). [`crate::wcp::prepare`] expects a cell that passes.
    ///
    /// ```
    /// use workcell::cell::{Cell, CellObstacle, CellRobot, RigidRobot};
    /// use workcell::geometry::{ConvexPolygon, Vec2};
    /// use workcell::motion::Pose;
    ///
    /// let square = ConvexPolygon::rectangle(1.0, 1.0)?;
    /// let mut cell = Cell::new(0.01)?;
    /// assert_eq!(cell.validate().unwrap_err().field, "robots");
    /// cell.add_robot(CellRobot::rigid("R1", RigidRobot {
    ///     shape: square.clone(),
    ///     parts: None,
    ///     home: Pose::new(0.0, 0.0, 0.0),
    ///     max_speed: 1.0,
    ///     max_accel: 2.0,
    ///     max_turn_rate: 1.0,
    /// }))?;
    /// // A post over R1's home.
    /// cell.add_obstacle(CellObstacle { name: "post".into(), shape: square.translated(&Vec2::new(0.5, 0.0)), parts: None })?;
    /// assert_eq!(cell.validate().unwrap_err().field, "robots[0].home");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn validate(&self) -> Result<(), InputError> {
        if self.robots.is_empty() {
            let reason = "a cell needs at least one robot";
            return Err(self.error(None, "robots", reason));
        }
        check_geometry(self)
    }

    /// Refuses an empty name or one a robot, obstacle or task of the cell already has (homes
    /// and tasks share the graph's node names).
    fn check_new_name(&self, name: &str, at: &str, kind: &str) -> Result<(), InputError> {
        let robots = (self.robots.iter().map(|r| &r.name).enumerate())
            .map(|(k, n)| (n, "robot", "robots", k));
        let obstacles = (self.obstacles.iter().map(|o| &o.name).enumerate())
            .map(|(k, n)| (n, "obstacle", "obstacles", k));
        let tasks =
            (self.tasks.iter().map(|t| &t.name).enumerate()).map(|(k, n)| (n, "task", "tasks", k));
        let first = robots
            .chain(obstacles)
            .chain(tasks)
            .find(|(n, ..)| *n == name)
            .map(|(_, kind, list, k)| owner(kind, &format!("{list}[{k}]")));
        check_name(&self.file, name, at, kind, first.as_deref())
    }

    /// Refuses a pose that is not finite (a file cannot hold one; code can).
    fn check_pose(&self, body: &str, field: &str, pose: &Pose) -> Result<(), InputError> {
        if pose.pos.x.is_finite() && pose.pos.y.is_finite() && pose.theta.is_finite() {
            return Ok(());
        }
        let reason = format!(
            "must be finite, got [{}, {}, {}]",
            pose.pos.x, pose.pos.y, pose.theta
        );
        Err(self.error(Some(body), field, reason))
    }
}

/// A body's shape and parts as the cell keeps them: the hull of parts that are not convex
/// with the parts, else one convex shape.
fn hull_and_parts(shape: ConvexPolygon, parts: Option<Parts>) -> (ConvexPolygon, Option<Parts>) {
    match parts {
        Some(p) if !p.is_convex() => (p.hull().clone(), Some(p)),
        Some(p) => (p.hull().clone(), None),
        None => (shape, None),
    }
}
