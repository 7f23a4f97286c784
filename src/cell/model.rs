//! The cell as the solver takes it (contract section 3), validated: robots, fixtures and
//! tasks. Read from a file by `cell_file.rs`, built in code by `cell_build.rs`.

use super::InputError;
use crate::collision::Body;
use crate::geometry::ConvexPolygon;
use crate::motion::Pose;
use std::path::PathBuf;

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
        self.obstacles
            .iter()
            .map(|o| Body::obstacle(o.name.clone(), &o.shape))
            .collect()
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
