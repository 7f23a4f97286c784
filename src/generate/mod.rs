//! Deterministic generators: scenes for the checker (`scenes`) and cells for the solver
//! (`cells`). The same arguments always give the same document (ChaCha8 streams, no clock).

mod cells;
mod scenes;

pub use cells::{cell_file_name, generate_cell, CellRequest, TASK_CLEARANCE};
pub use scenes::{generate_scene, scene_file_name, Kind};
