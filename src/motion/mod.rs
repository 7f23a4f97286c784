//! Trajectories, their interpolation, and bounds on how far a body can move.
//!
//! * [`Trajectory`]: time-stamped samples with the paper's clamping (eqs. 4-5) and linear
//!   interpolation of the pose between samples.
//! * [`Motion`]: a body's motion, sampled or fixed (obstacles).
//! * [`inverse_kinematics`]: every joint configuration of an arm that puts its tool at a pose.
//! * [`lambda`]: the motion bound λ of the Schwarzer-Saha-Latombe condition, rigorous or
//!   the paper's velocity-based eq. (12).

mod arm;
mod bounds;
mod ik;
mod motion_kind;
mod profile;
mod trajectory;

pub use arm::{forward_kinematics, ArmError, ArmMotion, JointLimits, JointSample, LinkMotion};
pub use bounds::{lambda, BoundKind};
pub use ik::{inverse_kinematics, tool_pose, IkSettings, ToolGoal, Unreachable};
pub use motion_kind::Motion;
pub use profile::rest_to_rest_time;
pub(crate) use profile::Trapezoid;
pub use trajectory::{Pose, Sample, Trajectory, TrajectoryError};
