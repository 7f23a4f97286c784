//! The motion bound λ of the Schwarzer-Saha-Latombe condition.

use super::{Motion, Pose};

/// Which motion bound λ the checker uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BoundKind {
    /// A true upper bound of the motion actually checked, for any input:
    /// λ = |ΔG| + Rmax·|Δθ| over an interval on which the pose is linear in time.
    #[default]
    Rigorous,
    /// The paper's eq. (12): λ = (max|v| + Rmax·max|ω|)·(tb − ta) with the velocities given
    /// at the interval's ends. Not a bound when the given velocities disagree with the
    /// positions; kept to show that failure.
    Paper,
}

/// λ for one body on [ta, tb], an interval on which its pose is linear in time.
///
/// With [`BoundKind::Rigorous`], no point of the body moves farther than λ during
/// [ta, tb], and over a sub-interval of relative length s no farther than s·λ (the motion is
/// linear, so the bound is additive). Length units are the scene's; `radius` is Rmax.
///
/// ```
/// use workcell::motion::{lambda, BoundKind, Motion, Pose, Trajectory};
/// let path = Trajectory::from_poses([(0.0, Pose::new(0.0, 0.0, 0.0)), (2.0, Pose::new(3.0, 4.0, 0.5))])?;
/// let motion = Motion::Sampled(path);
/// let (a, b) = (motion.pose_at(0.0), motion.pose_at(2.0));
/// // A body of radius 2: G moves 5, its farthest point 2·0.5 more by the turn.
/// assert_eq!(lambda(BoundKind::Rigorous, &motion, 2.0, (0.0, &a), (2.0, &b)), 6.0);
/// let fixed = Motion::Fixed(Pose::new(1.0, 1.0, 0.0));
/// assert_eq!(lambda(BoundKind::Rigorous, &fixed, 2.0, (0.0, &a), (2.0, &b)), 0.0);
/// # Ok::<(), workcell::motion::TrajectoryError>(())
/// ```
#[inline]
pub fn lambda(
    kind: BoundKind,
    motion: &Motion,
    radius: f64,
    ta: (f64, &Pose),
    tb: (f64, &Pose),
) -> f64 {
    if let Motion::Fixed(_) = motion {
        return 0.0;
    }
    match kind {
        // A chord is never longer than its arc: |R(θb)P − R(θa)P| ≤ |P|·|θb − θa|.
        BoundKind::Rigorous => {
            (tb.1.pos - ta.1.pos).norm() + radius * (tb.1.theta - ta.1.theta).abs()
        }
        BoundKind::Paper => {
            let (va, wa) = motion.velocity_at(ta.0);
            let (vb, wb) = motion.velocity_at(tb.0);
            (va.norm().max(vb.norm()) + radius * wa.abs().max(wb.abs())) * (tb.0 - ta.0)
        }
    }
}
