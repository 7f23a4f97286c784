//! Deterministic generators: scenes for the checker (`scenes`) and, later, cells for the
//! solver. The same arguments always give the same document (ChaCha8 streams, no clock).

mod scenes;

pub use scenes::{generate_scene, scene_file_name, Kind};
