//! The model's files: reading scenes (the contract's section 1) with errors that name the
//! file, the body and the field.

mod error;
mod precision;
mod scene_file;

pub use error::InputError;
pub use precision::{check_precision, MAX_COORDINATE_OVER_DELTA};
pub use scene_file::{load_scene, parse_scene, LoadedScene};
