//! The integration tests, one module per former test file, in one test binary: each test
//! binary links the whole library and its dependencies, so 23 of them took most of a cold
//! `cargo test --release` (issue 14, item 5). Kept apart: `tests/sequences_memory.rs`
//! (a counting global allocator, which other tests would disturb) and
//! `tests/fuzz_inputs.rs` (replaces the panic hook while it runs), and `tests/browser.rs`
//! (drives a browser, and its own WebDriver client module).
//!
//! The modules that run the binary or draw pictures need the `cli` feature (on by default);
//! `cargo test --no-default-features` runs the others on the bare library.

mod anytime;
mod arm_cells;
mod arm_files;
mod arm_solve;
mod arms;
mod boundaries;
mod cell_file;
mod checker_props;
mod checker_threads;
#[cfg(feature = "cli")]
mod cli;
#[cfg(feature = "cli")]
mod cli_messages;
#[cfg(feature = "cli")]
mod cli_scale;
#[cfg(feature = "cli")]
mod cli_solve;
#[cfg(feature = "cli")]
mod cli_verdicts;
mod common;
mod compare;
mod corpus;
mod feedback;
#[cfg(all(feature = "cli", unix))]
mod fuzz_outputs;
mod generate;
mod idle;
mod layers;
mod lazy;
mod library_api;
mod library_inputs;
mod narrow_phase_props;
mod oracle;
mod parts_checker;
mod parts_files;
mod parts_solve;
mod planning;
mod readme;
mod sequencer;
mod solve;
mod stability;
mod straight;
#[cfg(feature = "cli")]
mod view;
