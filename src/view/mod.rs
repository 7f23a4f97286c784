//! Every picture: the still picture of a cell and its schedule (`--svg`), the Gantt chart
//! (`--gantt`), the animated page (`--html`) and `compare`'s chart.
//!
//! Apart from the solver: the pictures of `solve`, `evaluate` and `check` draw a [`Model`],
//! made from the result as its JSON carries it ([`crate::wcp::report::ResultJson`],
//! [`crate::collision::CheckReport`]) and the scene of the trajectories drawn.

mod bars;
mod canvas;
mod chart;
mod gantt;
mod html;
mod labels;
mod legend;
mod model;
mod picture;
mod rings;

pub use bars::{kind_colour, Bar, KINDS};
pub use canvas::Frame;
pub use chart::chart;
pub use gantt::{gantt, gantt_svg, TimeAxis};
pub use html::html;
pub use labels::{text_width, Placer};
pub use model::{pose_at, ArmView, Mark, Model, RobotView, TaskView, COLOURS};
pub use picture::{cell_svg, picture, placed};
