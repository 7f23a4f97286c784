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
//! ([`view`], among them `compare`'s chart, [`view::chart`]); with `default-features = false` none of them is
//! compiled.
//!
//! Build scenes with [`geometry::ConvexPolygon::from_vertices`], [`motion::Trajectory::from_poses`],
//! [`collision::Body::robot`], [`collision::Body::obstacle`] and [`collision::Scene::new`];
//! check them with [`collision::try_check`] and decide on [`collision::CheckReport::verdict`];
//! solve cells read by [`cell::load_cell`] with [`wcp::prepare`] and [`wcp::solve`]
//! (`examples/library.rs` does both).
//!
//! A scene built in code, checked (the README's "Use as a library" example):
//!
//! ```
//! use workcell::collision::{try_check, Body, CheckOptions, Scene, Verdict};
//! use workcell::geometry::ConvexPolygon;
//! use workcell::motion::{Pose, Trajectory};
//!
//! // A 1 × 1 robot slides from x = 0 to x = 10 in one second, through a post at x = 5.
//! let square = ConvexPolygon::rectangle(1.0, 1.0)?;
//! let path = Trajectory::from_poses([
//!     (0.0, Pose::new(0.0, 0.0, 0.0)),
//!     (1.0, Pose::new(10.0, 0.0, 0.0)),
//! ])?;
//! let post = ConvexPolygon::from_vertices(&[[4.5, -0.5], [5.5, -0.5], [5.5, 0.5], [4.5, 0.5]])?;
//! let mut scene = Scene::new(0.01)?; // δ; NaN, 0 and negatives are refused
//! scene.add(Body::robot("R1", square, path))?.add(Body::obstacle("post", &post))?;
//! match try_check(&scene, &CheckOptions::default())?.verdict() {
//!     Verdict::Contact { contact, .. } => {
//!         println!("{} hits {} at t = {}", contact.bodies[0], contact.bodies[1], contact.time);
//!         assert!(contact.time < 0.5);
//!     }
//!     other => panic!("a contact, not {other}"),
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The same from a scene document:
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
//! let verdict = report.verdict();
//! assert!(verdict.contact().unwrap().time < 0.5);
//! ```

#![warn(missing_docs)]

pub mod cell;
pub mod collision;
pub mod compare;
mod error;
pub mod generate;
pub mod geometry;
pub mod motion;
pub mod planning;
#[cfg(feature = "cli")]
pub mod view;
pub mod wcp;
