//! # workcell
//!
//! Schedules robots in a work-cell and certifies that their motions never collide.
//!
//! The pipeline, one module per stage:
//! * [`geometry`]: convex polygons and their exact distance (2-D Lin-Canny walk);
//! * [`motion`]: trajectories, interpolation and motion bounds λ;
//! * [`collision`]: the adaptive checker of Feyeux & Landry (2013);
//! * [`cell`]: the model's files and their validation;
//! * [`planning`]: point-to-point moves around the obstacles;
//! * [`wcp`]: the work-cell graph, the sequencer and the collision feedback loop;
//! * [`generate`]: deterministic scenes and cells for tests and benchmarks;
//! * [`compare`]: the checking methods against each other and the parry peer.
//!
//! The feature `cli` (on by default) adds the command line's crates and the SVG pictures
//! (`wcp::picture`, `compare::chart`); with `default-features = false` none of them is
//! compiled.
//!
//! ```
//! use workcell::{cell, collision};
//! let text = r#"{"delta": 0.01, "robots": [
//!   {"name": "A", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
//!    "trajectory": [{"t": 0, "x": 0, "y": 0}, {"t": 1, "x": 10, "y": 0}]},
//!   {"name": "B", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
//!    "trajectory": [{"t": 0, "x": 5, "y": 0}, {"t": 1, "x": 5, "y": 0}]}]}"#;
//! let loaded = cell::parse_scene(text, "inline.json".as_ref()).unwrap();
//! let report = collision::check(&loaded.scene, &collision::CheckOptions::default());
//! // A passes through B between the two samples: a check at the samples alone misses it.
//! assert!(report.collision);
//! assert!(report.first_contact.unwrap().time < 0.5);
//! ```

#![warn(missing_docs)]

pub mod cell;
pub mod collision;
pub mod compare;
pub mod generate;
pub mod geometry;
pub mod motion;
pub mod planning;
pub mod wcp;
