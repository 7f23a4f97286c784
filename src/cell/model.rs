//! The cell as the solver takes it (contract section 3), validated: robots, fixtures and
//! tasks. Read from a file by `cell_file.rs`, built in code by `cell_build.rs`.

use super::InputError;
use crate::collision::Body;
use crate::geometry::{ConvexPolygon, Parts};
use crate::motion::{Pose, Trajectory};
use std::path::PathBuf;

/// A robot of the cell: its shape, home and limits.
#[derive(Clone, Debug, PartialEq)]
pub struct CellRobot {
    /// Name, unique among robots, obstacles and tasks.
    pub name: String,
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
    /// The robot's convex pieces, whose union it is: its parts, or its one shape.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    /// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
    /// assert_eq!(cell.robots[0].pieces(), [cell.robots[0].shape.clone()]);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn pieces(&self) -> &[ConvexPolygon] {
        pieces(&self.shape, &self.parts)
    }

    /// The robot as a checker body moving along `trajectory` (with its parts).
    ///
    /// ```
    /// use workcell::motion::{Sample, Trajectory};
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
    /// let robot = &workcell::cell::load_cell(path.as_ref())?.cell.robots[0];
    /// let still = Trajectory::new(vec![Sample::at(0.0, robot.home)])?;
    /// let body = robot.body(still);
    /// assert_eq!((body.name.as_str(), &body.shape), (robot.name.as_str(), &robot.shape));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn body(&self, trajectory: Trajectory) -> Body {
        match &self.parts {
            Some(parts) => Body::robot_of_parts(self.name.clone(), parts.clone(), trajectory),
            None => Body::robot(self.name.clone(), self.shape.clone(), trajectory),
        }
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
