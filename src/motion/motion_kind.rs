//! How a body moves: [`Motion`], the one type the checker asks for poses and sample times.

use super::{LinkMotion, Pose, Trajectory};
use crate::geometry::Vec2;

/// How a body moves: along a sampled trajectory (robots), as a link of an arm, or not at
/// all (obstacles).
#[derive(Clone, Debug, PartialEq)]
pub enum Motion {
    /// A robot's sampled trajectory.
    Sampled(Trajectory),
    /// A link of an arm: its frame follows the arm's joints (contract section 6).
    Link(LinkMotion),
    /// A body that never moves.
    Fixed(Pose),
}

impl Motion {
    /// Pose at time `t`.
    ///
    /// ```
    /// use workcell::motion::{Motion, Pose, Trajectory};
    /// let robot = Motion::Sampled(Trajectory::from_poses([(0.0, Pose::new(0.0, 0.0, 0.0)), (1.0, Pose::new(2.0, 0.0, 0.0))])?);
    /// assert_eq!(robot.pose_at(0.5), Pose::new(1.0, 0.0, 0.0));
    /// let post = Motion::Fixed(Pose::new(5.0, 5.0, 0.0));
    /// assert_eq!(post.pose_at(1e6), Pose::new(5.0, 5.0, 0.0));
    /// # Ok::<(), workcell::motion::TrajectoryError>(())
    /// ```
    #[inline]
    pub fn pose_at(&self, t: f64) -> Pose {
        match self {
            Motion::Sampled(tr) => tr.pose_at(t),
            Motion::Link(l) => l.arm.pose_at(t, l.link),
            Motion::Fixed(p) => *p,
        }
    }

    /// Given velocity and angular velocity at `t` (zero for a fixed body).
    #[inline]
    pub fn velocity_at(&self, t: f64) -> (Vec2, f64) {
        match self {
            Motion::Sampled(tr) => tr.velocity_at(t),
            Motion::Link(l) => l.velocity_at(t),
            Motion::Fixed(_) => (Vec2::zeros(), 0.0),
        }
    }

    /// Sample times: the ends of the pieces on which the pose (for a link: each joint angle)
    /// is linear in time.
    pub fn times(&self) -> Box<dyn Iterator<Item = f64> + '_> {
        match self {
            Motion::Sampled(tr) => Box::new(tr.samples().iter().map(|s| s.t)),
            Motion::Link(l) => Box::new(l.arm.times()),
            Motion::Fixed(_) => Box::new(std::iter::empty()),
        }
    }

    /// The first and last sample times of a moving body; `None` for a fixed one.
    ///
    /// ```
    /// use workcell::motion::{Motion, Pose, Trajectory};
    /// let path = Trajectory::from_poses([(1.0, Pose::new(0.0, 0.0, 0.0)), (4.0, Pose::new(1.0, 0.0, 0.0))])?;
    /// assert_eq!(Motion::Sampled(path).span(), Some((1.0, 4.0)));
    /// assert_eq!(Motion::Fixed(Pose::new(0.0, 0.0, 0.0)).span(), None);
    /// # Ok::<(), workcell::motion::TrajectoryError>(())
    /// ```
    pub fn span(&self) -> Option<(f64, f64)> {
        match self {
            Motion::Sampled(tr) => Some((tr.samples().first()?.t, tr.samples().last()?.t)),
            Motion::Link(l) => Some((l.arm.samples().first()?.t, l.arm.samples().last()?.t)),
            Motion::Fixed(_) => None,
        }
    }
}
