//! The timed schedule: every robot's moves, waits and tasks, sampled into trajectories.
//!
//! * `activity.rs`: one robot's plan, what it does when, and reading it back;
//! * `timeline.rs`: building that plan from a route and its legs;
//! * `whole.rs`: every robot's plan together, its scene and where a check's contact falls.

mod activity;
mod timeline;
mod whole;

pub(crate) use activity::{joints_at, PoseCursor};
pub use activity::{route_nodes, Activity, Delay, RobotSchedule, Segment};
pub use timeline::BuildError;
pub use whole::{Collision, Schedule};
