//! The model's files: reading scenes (the contract's section 1) and cells (section 3) with errors that name the
//! file, the body and the field.

mod arm_file;
mod body_shape;
mod cell_build;
mod cell_checks;
mod cell_file;
mod json_cursor;
mod legs_file;
mod model;
mod object_only;
mod reading;
mod scene_file;
mod scene_writer;
mod sequences_file;
mod time_axis;

pub use crate::error::InputError;
pub use cell_file::{load_cell, parse_cell, LoadedCell};
pub use legs_file::{parse_legs, LegSpec, PieceSpec, PrimitiveSpec};
pub use model::{ArmRobot, Cell, CellObstacle, CellRobot, RigidRobot, RobotKind, Task};
// Whether f64 can check a scene is the checker's to say; the readers ask it, and these
// paths stay where a user of the files finds them.
pub use crate::collision::{
    check_precision, check_time_resolution, MAX_COORDINATE_OVER_DELTA, MAX_REPAIR_SHIFT_OVER_DELTA,
    MIN_TIME_TOL_OVER_ULP,
};
pub use scene_file::{load_scene, parse_scene, LoadedScene};
pub use scene_writer::scene_document;
pub use sequences_file::{
    load_blind_sequences, load_sequences, parse_blind_sequences, parse_sequences, Sequences, Wait,
};
pub(crate) use time_axis::number;
pub use time_axis::{keeps_length, TASK_LENGTH_TOL};
