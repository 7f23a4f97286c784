//! What the targets share: the invariant and mutations of `tests/fuzz_support`, and the
//! feedback cell that sequences are read against.

// Each target uses part of this.
#![allow(dead_code)]

#[path = "../../tests/fuzz_support/mod.rs"]
pub mod support;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use workcell::cell::Cell;

/// The repository's `cells/` folder.
pub fn cells() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../cells")
}

/// The feedback cell, read once.
pub fn feedback() -> &'static Cell {
    static CELL: OnceLock<Cell> = OnceLock::new();
    CELL.get_or_init(|| support::feedback_cell(&cells()))
}

/// Runs the reader of `kind` and what follows on `data`, when it is text.
pub fn exercise_bytes(kind: support::Kind, data: &[u8]) {
    if let Ok(text) = std::str::from_utf8(data) {
        support::exercise(kind, text, Path::new("fuzz.json"), feedback());
    }
}
