//! Sampled trajectories and the motion they define.

use crate::geometry::Vec2;

/// One time sample of a robot's trajectory, as in the scene file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Time stamp.
    pub t: f64,
    /// Position of G, the body origin.
    pub pos: Vec2,
    /// Rotation angle, radians counter-clockwise.
    pub theta: f64,
    /// Velocity of G as given (used only by the paper's bound).
    pub vel: Vec2,
    /// Angular velocity as given (used only by the paper's bound).
    pub omega: f64,
}

/// A rigid pose: position of G and rotation angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Position of G.
    pub pos: Vec2,
    /// Rotation angle, radians counter-clockwise.
    pub theta: f64,
}

impl Pose {
    /// The pose with G at (`x`, `y`) and rotation `theta` (radians, counter-clockwise).
    ///
    /// ```
    /// use workcell::motion::Pose;
    /// let p = Pose::new(1.0, 2.0, 0.5);
    /// assert_eq!((p.pos.x, p.pos.y, p.theta), (1.0, 2.0, 0.5));
    /// ```
    pub fn new(x: f64, y: f64, theta: f64) -> Self {
        Pose {
            pos: Vec2::new(x, y),
            theta,
        }
    }
}

impl Sample {
    /// The sample at time `t` in `pose`, velocities zero: [`Trajectory::from_poses`] derives
    /// them, or set `vel` and `omega` to give them.
    ///
    /// ```
    /// use workcell::motion::{Pose, Sample};
    /// let s = Sample::at(2.0, Pose::new(1.0, 0.0, 0.0));
    /// assert_eq!((s.t, s.vel.x, s.omega), (2.0, 0.0, 0.0));
    /// ```
    pub fn at(t: f64, pose: Pose) -> Self {
        Sample {
            t,
            pos: pose.pos,
            theta: pose.theta,
            vel: Vec2::zeros(),
            omega: 0.0,
        }
    }
}

/// Why a list of samples is not a trajectory. `sample` is the index in the input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TrajectoryError {
    /// No samples at all.
    #[error("a trajectory needs at least one sample")]
    Empty,
    /// A value is NaN or infinite.
    #[error("sample {sample}: `{field}` is not a finite number")]
    NotFinite {
        /// Input index.
        sample: usize,
        /// Field name as in the scene file.
        field: &'static str,
    },
    /// A velocity left out of the file and derived from the positions is not finite: the
    /// positions are too far apart for the time step.
    #[error("sample {sample}: the velocity derived from the positions overflows")]
    DerivedVelocityOverflow {
        /// Input index.
        sample: usize,
    },
    /// Time stamps do not strictly increase.
    #[error("sample {sample}: `t` = {t} does not come after the previous {previous}")]
    NotIncreasing {
        /// Input index.
        sample: usize,
        /// Its time.
        t: f64,
        /// The previous sample's time.
        previous: f64,
    },
}

/// A validated trajectory: at least one sample, finite values, strictly increasing times.
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory {
    samples: Vec<Sample>,
}

impl Trajectory {
    /// The trajectory through `poses` (time, pose), with the velocities the scene file
    /// derives when it gives none ([`Trajectory::derived_velocity`]). Refuses what
    /// [`Trajectory::new`] refuses, and a derived velocity that overflows.
    ///
    /// ```
    /// use workcell::motion::{Pose, Trajectory, TrajectoryError};
    /// let tr = Trajectory::from_poses([
    ///     (0.0, Pose::new(0.0, 0.0, 0.0)),
    ///     (1.0, Pose::new(2.0, 0.0, 0.0)),
    ///     (2.0, Pose::new(6.0, 0.0, 1.0)),
    /// ])?;
    /// let s = tr.samples();
    /// assert_eq!((s[0].vel.x, s[1].vel.x, s[2].vel.x), (2.0, 3.0, 4.0));
    /// assert_eq!((s[1].omega, s[2].omega), (0.5, 1.0));
    /// assert_eq!(tr.pose_at(0.5).pos.x, 1.0);
    ///
    /// let backwards = Trajectory::from_poses([(1.0, Pose::new(0.0, 0.0, 0.0)), (0.0, Pose::new(1.0, 0.0, 0.0))]);
    /// assert!(matches!(backwards, Err(TrajectoryError::NotIncreasing { sample: 1, .. })));
    /// # Ok::<(), TrajectoryError>(())
    /// ```
    pub fn from_poses(
        poses: impl IntoIterator<Item = (f64, Pose)>,
    ) -> Result<Self, TrajectoryError> {
        let unknown = |(t, p)| Sample {
            vel: Vec2::new(f64::NAN, f64::NAN),
            omega: f64::NAN,
            ..Sample::at(t, p)
        };
        Self::with_missing_velocities(poses.into_iter().map(unknown).collect())
    }

    /// The scene file's rule for velocities: a sample whose velocities (vx, vy, omega) are
    /// all given keeps them; any other gets those it lacks, NaN in `samples`, from
    /// [`Trajectory::derived_velocity`], which must then be finite.
    pub(crate) fn with_missing_velocities(
        mut samples: Vec<Sample>,
    ) -> Result<Self, TrajectoryError> {
        // Validate before deriving: derivation divides by time steps.
        Self::check(&samples, false)?;
        for k in 0..samples.len() {
            let given = samples[k];
            if [given.vel.x, given.vel.y, given.omega]
                .iter()
                .any(|v| v.is_nan())
            {
                // From times and poses only: the velocities filled in so far do not count.
                let (v, w) = Trajectory::derived_velocity(&samples, k);
                if !(v.x.is_finite() && v.y.is_finite() && w.is_finite()) {
                    return Err(TrajectoryError::DerivedVelocityOverflow { sample: k });
                }
                let or = |g: f64, derived: f64| if g.is_nan() { derived } else { g };
                samples[k].vel = Vec2::new(or(given.vel.x, v.x), or(given.vel.y, v.y));
                samples[k].omega = or(given.omega, w);
            }
        }
        // Times and poses passed above: only the velocities given are left to check.
        for (k, s) in samples.iter().enumerate() {
            let fields = [("vx", s.vel.x), ("vy", s.vel.y), ("omega", s.omega)];
            if let Some((field, _)) = fields.iter().find(|(_, v)| !v.is_finite()) {
                return Err(TrajectoryError::NotFinite { sample: k, field });
            }
        }
        Ok(Trajectory { samples })
    }

    /// Validates the samples, velocities as given.
    ///
    /// ```
    /// use workcell::motion::{Pose, Sample, Trajectory, TrajectoryError};
    /// let mut s = Sample::at(0.0, Pose::new(0.0, 0.0, 0.0));
    /// s.vel.x = 1.0;
    /// assert_eq!(Trajectory::new(vec![s])?.velocity_at(0.0).0.x, 0.0); // at rest outside
    /// s.omega = f64::NAN;
    /// assert_eq!(
    ///     Trajectory::new(vec![s]).unwrap_err(),
    ///     TrajectoryError::NotFinite { sample: 0, field: "omega" }
    /// );
    /// # Ok::<(), TrajectoryError>(())
    /// ```
    pub fn new(samples: Vec<Sample>) -> Result<Self, TrajectoryError> {
        Self::validate(&samples)?;
        Ok(Trajectory { samples })
    }

    /// A trajectory of samples known to pass [`Trajectory::validate`]: a robot schedule's,
    /// made by its timeline (which refuses times that do not increase) from certified
    /// moves. Skips the check, which the search over remedies otherwise repeated on every
    /// window it judged (a twentieth of its time); debug builds still make it.
    pub(crate) fn trusted(samples: Vec<Sample>) -> Self {
        debug_assert_eq!(Self::validate(&samples), Ok(()));
        Trajectory { samples }
    }

    /// What [`Trajectory::new`] refuses, without taking the samples.
    pub(crate) fn validate(samples: &[Sample]) -> Result<(), TrajectoryError> {
        Self::check(samples, true)
    }

    /// What [`Trajectory::validate`] refuses, the velocities left out unless `velocities`.
    fn check(samples: &[Sample], velocities: bool) -> Result<(), TrajectoryError> {
        if samples.is_empty() {
            return Err(TrajectoryError::Empty);
        }
        for (k, s) in samples.iter().enumerate() {
            let fields = [
                ("t", s.t),
                ("x", s.pos.x),
                ("y", s.pos.y),
                ("theta", s.theta),
                ("vx", s.vel.x),
                ("vy", s.vel.y),
                ("omega", s.omega),
            ];
            let fields = if velocities {
                &fields[..]
            } else {
                &fields[..4]
            };
            if let Some((field, _)) = fields.iter().find(|(_, v)| !v.is_finite()) {
                return Err(TrajectoryError::NotFinite { sample: k, field });
            }
            if k > 0 && s.t <= samples[k - 1].t {
                return Err(TrajectoryError::NotIncreasing {
                    sample: k,
                    t: s.t,
                    previous: samples[k - 1].t,
                });
            }
        }
        Ok(())
    }

    /// The samples, in time order.
    pub fn samples(&self) -> &[Sample] {
        &self.samples
    }

    /// Index `k` of the segment [t_k, t_{k+1}] that holds `t`, or `None` outside the samples.
    #[inline]
    fn segment(&self, t: f64) -> Option<usize> {
        let k = self.samples.partition_point(|s| s.t <= t);
        (k > 0 && k < self.samples.len()).then(|| k - 1)
    }

    /// The pose at time `t`: linear interpolation between samples; before the first sample
    /// the first pose and after the last the last pose (the paper's eqs. 4-5).
    ///
    /// Interpolates by the fraction of the time step, never by a rate Δpos/Δt: a step of
    /// 1e-310 would overflow the rate and turn the poses into NaN.
    ///
    /// ```
    /// use workcell::motion::{Pose, Trajectory};
    /// let path = Trajectory::from_poses([(1.0, Pose::new(0.0, 0.0, 0.0)), (3.0, Pose::new(4.0, 2.0, 1.0))])?;
    /// assert_eq!(path.pose_at(2.0), Pose::new(2.0, 1.0, 0.5));
    /// assert_eq!(path.pose_at(0.0), Pose::new(0.0, 0.0, 0.0)); // before the first sample: the first pose
    /// assert_eq!(path.pose_at(9.0), Pose::new(4.0, 2.0, 1.0));
    /// # Ok::<(), workcell::motion::TrajectoryError>(())
    /// ```
    pub fn pose_at(&self, t: f64) -> Pose {
        self.pose_after(self.samples.partition_point(|s| s.t <= t), t)
    }

    /// [`Trajectory::pose_at`] when the number of samples at or before `t` is known
    /// (`after`): a caller walking forward in time finds it without a search.
    #[inline]
    pub(crate) fn pose_after(&self, after: usize, t: f64) -> Pose {
        let s = &self.samples;
        let (p, q, u) = if after > 0 && after < s.len() {
            let k = after - 1;
            (&s[k], &s[k + 1], (t - s[k].t) / (s[k + 1].t - s[k].t))
        } else if after == 0 && t < s[0].t {
            (&s[0], &s[0], 0.0)
        } else {
            (&s[s.len() - 1], &s[s.len() - 1], 0.0)
        };
        Pose {
            pos: p.pos + (q.pos - p.pos) * u,
            theta: p.theta + (q.theta - p.theta) * u,
        }
    }

    /// The given velocities at `t`, interpolated linearly between samples; zero outside the
    /// samples, where the robot rests. Only the paper's bound uses them.
    ///
    /// ```
    /// use workcell::geometry::Vec2;
    /// use workcell::motion::{Pose, Trajectory};
    /// let path = Trajectory::from_poses([(0.0, Pose::new(0.0, 0.0, 0.0)), (2.0, Pose::new(4.0, 0.0, 1.0))])?;
    /// assert_eq!(path.velocity_at(1.0), (Vec2::new(2.0, 0.0), 0.5));
    /// assert_eq!(path.velocity_at(3.0), (Vec2::zeros(), 0.0)); // at rest after the last sample
    /// # Ok::<(), workcell::motion::TrajectoryError>(())
    /// ```
    pub fn velocity_at(&self, t: f64) -> (Vec2, f64) {
        let s = &self.samples;
        match self.segment(t) {
            Some(k) => {
                let (p, q) = (&s[k], &s[k + 1]);
                let u = (t - p.t) / (q.t - p.t);
                (
                    p.vel + (q.vel - p.vel) * u,
                    p.omega + (q.omega - p.omega) * u,
                )
            }
            None if s.len() == 1 || t < s[0].t || t > s[s.len() - 1].t => (Vec2::zeros(), 0.0),
            None => (s[s.len() - 1].vel, s[s.len() - 1].omega),
        }
    }

    /// Velocity and angular velocity consistent with the interpolated positions: the
    /// average of the slopes of the two segments that meet at each sample. For samples
    /// whose velocities the input left out.
    ///
    /// ```
    /// use workcell::motion::{Pose, Sample, Trajectory};
    /// // Slopes 2 then 4 in x (per time unit) meet at the middle sample: its velocity is 3.
    /// let at = |t, x, theta| Sample::at(t, Pose::new(x, 0.0, theta));
    /// let samples = [at(0.0, 0.0, 0.0), at(1.0, 2.0, 0.0), at(2.0, 6.0, 1.0)];
    /// let (vel, omega) = Trajectory::derived_velocity(&samples, 1);
    /// assert_eq!((vel.x, vel.y, omega), (3.0, 0.0, 0.5));
    /// ```
    pub fn derived_velocity(samples: &[Sample], k: usize) -> (Vec2, f64) {
        let slope = |i: usize| {
            let (p, q) = (&samples[i], &samples[i + 1]);
            let dt = q.t - p.t;
            ((q.pos - p.pos) / dt, (q.theta - p.theta) / dt)
        };
        let n = samples.len();
        match (k > 0, k + 1 < n) {
            (true, true) => {
                let ((v0, w0), (v1, w1)) = (slope(k - 1), slope(k));
                ((v0 + v1) * 0.5, 0.5 * (w0 + w1))
            }
            (true, false) => slope(k - 1),
            (false, true) => slope(k),
            (false, false) => (Vec2::zeros(), 0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(t: f64, x: f64, theta: f64) -> Sample {
        Sample {
            t,
            pos: Vec2::new(x, 0.0),
            theta,
            vel: Vec2::new(1.0, 0.0),
            omega: 0.0,
        }
    }

    #[test]
    fn interpolates_and_clamps() {
        let tr = Trajectory::new(vec![sample(1.0, 0.0, 0.0), sample(3.0, 4.0, 1.0)]).unwrap();
        assert_eq!(tr.pose_at(2.0).pos.x, 2.0);
        assert_eq!(tr.pose_at(2.0).theta, 0.5);
        assert_eq!(tr.pose_at(0.0).pos.x, 0.0);
        assert_eq!(tr.pose_at(9.0).pos.x, 4.0);
        assert_eq!(tr.pose_at(3.0).pos.x, 4.0);
        assert_eq!(tr.velocity_at(0.0).0.x, 0.0);
        assert_eq!(tr.velocity_at(2.0).0.x, 1.0);
    }

    #[test]
    fn refuses_bad_times() {
        let e = Trajectory::new(vec![sample(1.0, 0.0, 0.0), sample(1.0, 4.0, 1.0)]).unwrap_err();
        assert!(matches!(
            e,
            TrajectoryError::NotIncreasing { sample: 1, .. }
        ));
        let e = Trajectory::new(vec![sample(f64::NAN, 0.0, 0.0)]).unwrap_err();
        assert_eq!(
            e,
            TrajectoryError::NotFinite {
                sample: 0,
                field: "t"
            }
        );
        assert_eq!(Trajectory::new(vec![]).unwrap_err(), TrajectoryError::Empty);
    }

    #[test]
    fn derived_velocity_matches_the_slopes() {
        let s = [
            sample(0.0, 0.0, 0.0),
            sample(1.0, 2.0, 0.0),
            sample(2.0, 6.0, 1.0),
        ];
        assert_eq!(Trajectory::derived_velocity(&s, 0).0.x, 2.0);
        assert_eq!(Trajectory::derived_velocity(&s, 1).0.x, 3.0);
        assert_eq!(Trajectory::derived_velocity(&s, 2).1, 1.0);
    }
}
