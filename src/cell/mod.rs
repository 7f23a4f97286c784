//! The model's files: reading scenes (the contract's section 1) with errors that name the
//! file, the body and the field.

mod error;
mod scene_file;

pub use error::InputError;
pub use scene_file::{load_scene, parse_scene, LoadedScene};
