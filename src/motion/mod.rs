//! Trajectories, their interpolation, and bounds on how far a body can move.
//!
//! * [`Trajectory`]: time-stamped samples with the paper's clamping (eqs. 4-5) and linear
//!   interpolation of the pose between samples.
//! * [`Motion`]: a body's motion, sampled or fixed (obstacles).
//! * [`lambda`]: the motion bound λ of the Schwarzer-Saha-Latombe condition, rigorous or
//!   the paper's velocity-based eq. (12).

mod arm;
mod bounds;
mod motion_kind;
mod profile;
mod trajectory;

pub use arm::{forward_kinematics, ArmError, ArmMotion, JointSample, LinkMotion};
pub use bounds::{lambda, BoundKind};
pub use motion_kind::Motion;
pub use profile::rest_to_rest_time;
pub(crate) use profile::Trapezoid;
pub use trajectory::{Pose, Sample, Trajectory, TrajectoryError};
