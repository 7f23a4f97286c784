//! Trajectories, their interpolation, and bounds on how far a body can move.
//!
//! * [`Trajectory`]: time-stamped samples with the paper's clamping (eqs. 4-5) and linear
//!   interpolation of the pose between samples.
//! * [`Motion`]: a body's motion, sampled or fixed (obstacles).
//! * [`lambda`]: the motion bound λ of the Schwarzer-Saha-Latombe condition, rigorous or
//!   the paper's velocity-based eq. (12).

mod bounds;
mod profile;
mod trajectory;

pub use bounds::{lambda, BoundKind};
pub use profile::rest_to_rest_time;
pub(crate) use profile::Trapezoid;
pub use trajectory::{Motion, Pose, Sample, Trajectory, TrajectoryError};
