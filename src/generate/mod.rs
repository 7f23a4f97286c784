//! Deterministic generators: scenes for the checker ([`generate_scene`]), cells for the
//! solver at the size of a real line ([`generate_cell`]) and cells whose robots get in each
//! other's way, for the feedback loop ([`generate_conflict_cell`]). The same arguments always
//! give the same document (a ChaCha8 stream per document, seeded from kind, seed and index;
//! no clock, no hashing).

mod arm_scenes;
mod cells;
mod conflict;
mod parts_scenes;
mod scara;
mod scenes;
mod smooth;

pub use cells::{cell_file_name, generate_cell, CellRequest, TASK_CLEARANCE};
pub use conflict::{conflict_file_name, generate_conflict_cell, ConflictKind};
pub use scara::{generate_scara_cell, scara_file_name, ScaraRequest, MAX_SCARA_TASKS, SCARA_ARMS};
pub use scenes::{generate_scene, scene_file_name, Kind};

/// SplitMix64's finaliser: spreads (seed, kind, index) over the whole seed space.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}
