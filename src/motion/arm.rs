//! Planar arms of revolute joints (contract section 6): forward kinematics, joint
//! trajectories interpolated linearly per joint, and the motion bound of Schwarzer, Saha and
//! Latombe (IEEE T-RO 2005) for a link: every point of link k moves by at most
//! λ_k = Σ_{j ≤ k} |Δq_j| · r_{j,k} while each joint turns linearly, where r_{j,k} bounds the
//! distance from joint j's axis to the points of link k.

use super::{Pose, Sample};
use crate::geometry::Vec2;
use std::fmt;
use std::sync::Arc;

/// One sample of an arm's trajectory: a time and one angle per joint (radians), with the
/// joint velocities given (or derived from the angles).
#[derive(Clone, Debug, PartialEq)]
pub struct JointSample {
    /// Time.
    pub t: f64,
    /// Joint angles, one per link.
    pub q: Vec<f64>,
    /// Joint velocities, one per link.
    pub qd: Vec<f64>,
}

/// An arm's joint limits and dynamics, one entry per joint.
#[derive(Clone, Debug, PartialEq)]
pub struct JointLimits {
    /// `[min, max]` of each joint, `None` for a joint that turns freely.
    pub range: Vec<Option<[f64; 2]>>,
    /// Largest speed of each joint (rad per time unit), positive.
    pub max_speed: Vec<f64>,
    /// Largest acceleration of each joint, positive.
    pub max_accel: Vec<f64>,
}

/// Why joint samples cannot make an arm's trajectory; each names the sample.
#[derive(Clone, Debug, PartialEq)]
pub enum ArmError {
    /// No sample at all.
    Empty,
    /// A link count of zero.
    NoLinks,
    /// A link length that is negative or not finite.
    Length {
        /// The link.
        link: usize,
        /// Its length as given.
        length: f64,
    },
    /// A base pose that is not finite.
    Base,
    /// `q` or `qd` of the wrong length.
    Joints {
        /// The sample.
        sample: usize,
        /// `q` or `qd`.
        field: &'static str,
        /// Angles given.
        got: usize,
        /// Links of the arm.
        links: usize,
    },
    /// A time, angle or velocity that is not finite.
    NotFinite {
        /// The sample.
        sample: usize,
        /// `t`, `q` or `qd`.
        field: &'static str,
    },
    /// Times not strictly increasing.
    NotIncreasing {
        /// The sample whose time is not after the previous one's.
        sample: usize,
    },
    /// A link's radius about its joint missing, negative or not finite.
    Reach {
        /// The link.
        link: usize,
    },
}

impl fmt::Display for ArmError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ArmError::Empty => write!(f, "an arm's trajectory needs at least one sample"),
            ArmError::NoLinks => write!(f, "an arm needs at least one link"),
            ArmError::Length { length, .. } => {
                write!(
                    f,
                    "a link's length must be a finite number >= 0, got {length}"
                )
            }
            ArmError::Base => write!(f, "the base must be three finite numbers [x, y, theta]"),
            ArmError::Joints {
                field, got, links, ..
            } => write!(
                f,
                "`{field}` has {got} angles for an arm of {links} links: one per link"
            ),
            ArmError::NotFinite { field, .. } => write!(f, "`{field}` must be finite"),
            ArmError::NotIncreasing { .. } => {
                write!(f, "sample times must strictly increase")
            }
            ArmError::Reach { .. } => write!(
                f,
                "each link needs the radius of its body about its joint, a finite number >= 0"
            ),
        }
    }
}

impl std::error::Error for ArmError {}

/// An arm's base, link lengths and joint trajectory: what moves its links. Each link's body
/// is kept by the checker beside it (one body per link).
#[derive(Clone, Debug, PartialEq)]
pub struct ArmMotion {
    base: Pose,
    lengths: Vec<f64>,
    samples: Vec<JointSample>,
    /// `reach[k]`: the radius of link k's body about its own joint (the farthest vertex).
    reach: Vec<f64>,
    /// r_{j,k} at `levers[j * links + k]` for j ≤ k: the motion bound reads them for every
    /// interval of the checker.
    levers: Vec<f64>,
}

impl ArmMotion {
    /// An arm with its base pose, link lengths, the radius of each link's body about its
    /// joint, and its samples (`qd` empty in a sample where the file gives none: derived from
    /// the angles, as for rigid robots).
    ///
    /// ```
    /// use workcell::motion::{ArmMotion, JointSample, Pose};
    /// let s = |t: f64, q: [f64; 2]| JointSample { t, q: q.to_vec(), qd: Vec::new() };
    /// let arm = ArmMotion::new(Pose::new(0.0, 0.0, 0.0), vec![1.0, 0.5], vec![1.1, 0.6],
    ///                          vec![s(0.0, [0.0, 0.0]), s(2.0, [1.0, -1.0])])?;
    /// assert_eq!(arm.q_at(1.0), [0.5, -0.5]);
    /// assert_eq!(arm.samples()[0].qd, [0.5, -0.5]); // derived: the first segment's rate
    /// # Ok::<(), workcell::motion::ArmError>(())
    /// ```
    pub fn new(
        base: Pose,
        lengths: Vec<f64>,
        reach: Vec<f64>,
        mut samples: Vec<JointSample>,
    ) -> Result<ArmMotion, ArmError> {
        let links = lengths.len();
        if links == 0 {
            return Err(ArmError::NoLinks);
        }
        if !(base.pos.x.is_finite() && base.pos.y.is_finite() && base.theta.is_finite()) {
            return Err(ArmError::Base);
        }
        if let Some(link) = lengths.iter().position(|l| !(l.is_finite() && *l >= 0.0)) {
            return Err(ArmError::Length {
                link,
                length: lengths[link],
            });
        }
        if let Some(link) =
            (0..links).find(|&k| !reach.get(k).is_some_and(|r| *r >= 0.0 && r.is_finite()))
        {
            return Err(ArmError::Reach { link });
        }
        if samples.is_empty() {
            return Err(ArmError::Empty);
        }
        for (k, s) in samples.iter().enumerate() {
            for (field, v, allow_empty) in [("q", &s.q, false), ("qd", &s.qd, true)] {
                if v.len() != links && !(allow_empty && v.is_empty()) {
                    let got = v.len();
                    return Err(ArmError::Joints {
                        sample: k,
                        field,
                        got,
                        links,
                    });
                }
                if v.iter().any(|x| !x.is_finite()) {
                    return Err(ArmError::NotFinite { sample: k, field });
                }
            }
            if !s.t.is_finite() {
                return Err(ArmError::NotFinite {
                    sample: k,
                    field: "t",
                });
            }
            if k > 0 && s.t <= samples[k - 1].t {
                return Err(ArmError::NotIncreasing { sample: k });
            }
        }
        for k in 0..samples.len() {
            if samples[k].qd.is_empty() {
                samples[k].qd = derived_rates(&samples, k);
            }
        }
        Ok(ArmMotion {
            base,
            lengths,
            samples,
            reach,
            levers: Vec::new(),
        }
        .with_levers())
    }

    /// The arm with each link's radius about its joint raised to at least `radii[k]`: the
    /// bodies the checker moves decide how far their points lie from the joints, whatever
    /// radius the arm was given.
    pub(crate) fn covering(mut self, radii: &[f64]) -> ArmMotion {
        for (r, &body) in self.reach.iter_mut().zip(radii) {
            *r = r.max(body);
        }
        self.with_levers()
    }

    /// The arm with its table of r_{j,k} computed from its lengths and reaches.
    fn with_levers(mut self) -> ArmMotion {
        let n = self.links();
        self.levers = (0..n * n)
            .map(|i| {
                let (j, k) = (i / n, i % n);
                if j <= k {
                    self.lengths[j..k].iter().sum::<f64>() + self.reach[k]
                } else {
                    0.0
                }
            })
            .collect();
        self
    }

    /// The base pose.
    pub fn base(&self) -> Pose {
        self.base
    }

    /// The link lengths.
    pub fn lengths(&self) -> &[f64] {
        &self.lengths
    }

    /// The samples, with their velocities.
    pub fn samples(&self) -> &[JointSample] {
        &self.samples
    }

    /// The number of links.
    pub fn links(&self) -> usize {
        self.lengths.len()
    }

    /// The joint angles at `t`: linear per joint between samples, held before the first and
    /// after the last.
    ///
    /// ```
    /// use workcell::motion::{ArmMotion, JointSample, Pose};
    /// let s = |t: f64, q: [f64; 2]| JointSample { t, q: q.to_vec(), qd: Vec::new() };
    /// let arm = ArmMotion::new(Pose::new(0.0, 0.0, 0.0), vec![1.0, 0.5], vec![1.1, 0.6],
    ///                          vec![s(0.0, [0.0, 0.0]), s(2.0, [1.0, -1.0])])?;
    /// assert_eq!(arm.q_at(-1.0), [0.0, 0.0]); // at rest before the first sample
    /// assert_eq!(arm.q_at(0.5), [0.25, -0.25]);
    /// # Ok::<(), workcell::motion::ArmError>(())
    /// ```
    pub fn q_at(&self, t: f64) -> Vec<f64> {
        let (a, b, u) = self.segment(t);
        (0..self.links()).map(|j| lerp(a[j], b[j], u)).collect()
    }

    /// Link `link`'s pose at `t`, given `after`, the number of samples at or before `t` (as
    /// a walk through the samples knows it): bit for bit [`ArmMotion::pose_at`], without its
    /// search.
    pub(crate) fn pose_after(&self, after: usize, t: f64, link: usize) -> Pose {
        let s = &self.samples;
        if after == 0 || after == s.len() {
            let at = &s[after.saturating_sub(1)].q;
            return self.pose_between(at, at, 0.0, link);
        }
        let (a, b) = (&s[after - 1], &s[after]);
        self.pose_between(&a.q, &b.q, (t - a.t) / (b.t - a.t), link)
    }

    /// The samples' angles about `t` and where `t` lies between them: `q(t)` is
    /// `a + (b − a)·u` per joint (the same sample twice, u = 0, outside the samples).
    fn segment(&self, t: f64) -> (&[f64], &[f64], f64) {
        let s = &self.samples;
        let k = s.partition_point(|x| x.t <= t);
        if k == 0 || k == s.len() {
            let at = &s[k.saturating_sub(1)].q;
            return (at, at, 0.0);
        }
        let (a, b) = (&s[k - 1], &s[k]);
        (&a.q, &b.q, (t - a.t) / (b.t - a.t))
    }

    /// The given joint velocities at `t`: those of the segment about it (zero outside the
    /// samples).
    ///
    /// ```
    /// use workcell::motion::{ArmMotion, JointSample, Pose};
    /// let s = |t: f64, q: [f64; 2]| JointSample { t, q: q.to_vec(), qd: Vec::new() };
    /// let arm = ArmMotion::new(Pose::new(0.0, 0.0, 0.0), vec![1.0, 0.5], vec![1.1, 0.6],
    ///                          vec![s(0.0, [0.0, 0.0]), s(2.0, [1.0, -1.0])])?;
    /// assert_eq!(arm.qd_at(1.0), [0.5, -0.5]);
    /// assert_eq!(arm.qd_at(3.0), [0.0, 0.0]); // at rest after the last sample
    /// # Ok::<(), workcell::motion::ArmError>(())
    /// ```
    pub fn qd_at(&self, t: f64) -> Vec<f64> {
        let s = &self.samples;
        let k = s.partition_point(|x| x.t <= t);
        if k == 0 || k == s.len() {
            return vec![0.0; self.links()];
        }
        s[k - 1].qd.clone()
    }

    /// The pose of link `link`'s frame for joint angles `q` (at least `link + 1` of them).
    ///
    /// ```
    /// use workcell::motion::{ArmMotion, JointSample, Pose};
    /// let s = |t: f64, q: [f64; 2]| JointSample { t, q: q.to_vec(), qd: Vec::new() };
    /// let arm = ArmMotion::new(Pose::new(0.0, 0.0, 0.0), vec![1.0, 0.5], vec![1.1, 0.6],
    ///                          vec![s(0.0, [0.0, 0.0]), s(2.0, [1.0, -1.0])])?;
    /// let elbow = arm.link_pose(&[std::f64::consts::FRAC_PI_2, 0.0], 1);
    /// assert!((elbow.pos.x).abs() < 1e-15 && elbow.pos.y == 1.0); // link 0 points up
    /// # Ok::<(), workcell::motion::ArmError>(())
    /// ```
    pub fn link_pose(&self, q: &[f64], link: usize) -> Pose {
        forward_kinematics(self.base, &self.lengths, q, link)
    }

    /// Link `link`'s pose at time `t`.
    ///
    /// ```
    /// use workcell::motion::{ArmMotion, JointSample, Pose};
    /// let s = |t: f64, q: [f64; 2]| JointSample { t, q: q.to_vec(), qd: Vec::new() };
    /// let arm = ArmMotion::new(Pose::new(0.0, 0.0, 0.0), vec![1.0, 0.5], vec![1.1, 0.6],
    ///                          vec![s(0.0, [0.0, 0.0]), s(2.0, [1.0, -1.0])])?;
    /// assert_eq!(arm.pose_at(2.0, 1), arm.link_pose(&[1.0, -1.0], 1));
    /// # Ok::<(), workcell::motion::ArmError>(())
    /// ```
    pub fn pose_at(&self, t: f64, link: usize) -> Pose {
        let (a, b, u) = self.segment(t);
        self.pose_between(a, b, u, link)
    }

    /// Link `link`'s pose at joint angles `a + (b − a)·u`, without gathering them.
    pub(crate) fn pose_between(&self, a: &[f64], b: &[f64], u: f64, link: usize) -> Pose {
        let q = |j: usize| lerp(a[j], b[j], u);
        let mut pos = self.base.pos;
        let mut theta = self.base.theta + q(0);
        for k in 1..=link {
            pos += self.lengths[k - 1] * Vec2::new(theta.cos(), theta.sin());
            theta += q(k);
        }
        Pose { pos, theta }
    }

    /// r_{j,k}: a bound of the distance from joint j's axis to every point of link k, for
    /// j ≤ k: the lengths of the links between them plus link k's reach about its joint.
    ///
    /// ```
    /// use workcell::motion::{ArmMotion, JointSample, Pose};
    /// let s = |t: f64, q: [f64; 2]| JointSample { t, q: q.to_vec(), qd: Vec::new() };
    /// let arm = ArmMotion::new(Pose::new(0.0, 0.0, 0.0), vec![1.0, 0.5], vec![1.1, 0.6],
    ///                          vec![s(0.0, [0.0, 0.0]), s(2.0, [1.0, -1.0])])?;
    /// assert_eq!(arm.lever(0, 1), 1.0 + 0.6); // link 0's length, then link 1's reach
    /// assert_eq!(arm.lever(1, 1), 0.6);
    /// # Ok::<(), workcell::motion::ArmError>(())
    /// ```
    pub fn lever(&self, j: usize, k: usize) -> f64 {
        assert!(j <= k, "r_(j,k) is for joints j <= k");
        self.levers[j * self.links() + k]
    }

    /// The motion bound of link `link` while the joints turn linearly from `q0` to `q1`:
    /// Σ_{j ≤ link} |q1_j − q0_j| · r_{j,link} (Schwarzer, Saha & Latombe 2005, eq. 5). A
    /// chord is never longer than its arc, and the joints' contributions add up along the
    /// chain.
    ///
    /// ```
    /// use workcell::motion::{ArmMotion, JointSample, Pose};
    /// let s = |t: f64, q: [f64; 2]| JointSample { t, q: q.to_vec(), qd: Vec::new() };
    /// let arm = ArmMotion::new(Pose::new(0.0, 0.0, 0.0), vec![1.0, 0.5], vec![1.1, 0.6],
    ///                          vec![s(0.0, [0.0, 0.0]), s(2.0, [1.0, -1.0])])?;
    /// // Joint 0 turns by 1 (lever 1.6), joint 1 by 1 (lever 0.6).
    /// assert!((arm.lambda(1, &[0.0, 0.0], &[1.0, -1.0]) - 2.2).abs() < 1e-12);
    /// # Ok::<(), workcell::motion::ArmError>(())
    /// ```
    pub fn lambda(&self, link: usize, q0: &[f64], q1: &[f64]) -> f64 {
        let n = self.links();
        (0..=link)
            .map(|j| (q1[j] - q0[j]).abs() * self.levers[j * n + link])
            .sum()
    }

    /// The sample times.
    pub fn times(&self) -> impl Iterator<Item = f64> + '_ {
        self.samples.iter().map(|s| s.t)
    }
}

/// Link `link` of an arm; the links of one arm share its [`ArmMotion`].
#[derive(Clone, Debug)]
pub struct LinkMotion {
    /// The arm's base, lengths and joint trajectory.
    pub arm: Arc<ArmMotion>,
    /// Which link (0 at the base).
    pub link: usize,
    /// The link frame at each of the arm's sample times, with its velocity: where the
    /// checker's time grid, the broad phase and the pictures read the link's samples.
    /// Between them the link follows its joints ([`ArmMotion::pose_at`]), not these.
    frames: Vec<Sample>,
}

impl PartialEq for LinkMotion {
    fn eq(&self, other: &Self) -> bool {
        self.link == other.link && (Arc::ptr_eq(&self.arm, &other.arm) || self.arm == other.arm)
    }
}

impl LinkMotion {
    /// Link `link` of `arm`.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::motion::{ArmMotion, JointSample, LinkMotion, Pose};
    /// let s = |t: f64, q: [f64; 2]| JointSample { t, q: q.to_vec(), qd: Vec::new() };
    /// let arm = ArmMotion::new(Pose::new(0.0, 0.0, 0.0), vec![2.0, 0.5], vec![2.1, 0.6],
    ///                          vec![s(0.0, [0.0, 0.0]), s(1.0, [1.0, 0.0])])?;
    /// let elbow = LinkMotion::new(Arc::new(arm), 1);
    /// assert_eq!(elbow.frames()[0].pos.x, 2.0);
    /// # Ok::<(), workcell::motion::ArmError>(())
    /// ```
    pub fn new(arm: Arc<ArmMotion>, link: usize) -> LinkMotion {
        let mut motion = LinkMotion {
            arm,
            link,
            frames: Vec::new(),
        };
        motion.frames = (motion.arm.samples().iter())
            .map(|s| {
                let pose = motion.arm.link_pose(&s.q, link);
                let (vel, omega) = motion.velocity_with(&s.q, &s.qd);
                Sample {
                    t: s.t,
                    pos: pose.pos,
                    theta: pose.theta,
                    vel,
                    omega,
                }
            })
            .collect();
        motion
    }

    /// The link frame at each of the arm's sample times (see the field).
    pub fn frames(&self) -> &[Sample] {
        &self.frames
    }

    /// Whether `other` is a link of the same arm (the same shared motion).
    pub fn same_arm(&self, other: &LinkMotion) -> bool {
        Arc::ptr_eq(&self.arm, &other.arm)
    }

    /// The link frame's velocity and angular velocity at `t`, from the given joint rates.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::motion::{ArmMotion, JointSample, LinkMotion, Pose};
    /// let s = |t: f64, q: [f64; 2]| JointSample { t, q: q.to_vec(), qd: Vec::new() };
    /// let arm = ArmMotion::new(Pose::new(0.0, 0.0, 0.0), vec![2.0, 0.5], vec![2.1, 0.6],
    ///                          vec![s(0.0, [0.0, 0.0]), s(1.0, [1.0, 0.0])])?;
    /// // The elbow, 2 from the base turning at 1 rad/s: speed 2, straight up.
    /// let (v, omega) = LinkMotion::new(Arc::new(arm), 1).velocity_at(0.0);
    /// assert!((v.x.abs(), v.y, omega) == (0.0, 2.0, 1.0));
    /// # Ok::<(), workcell::motion::ArmError>(())
    /// ```
    pub fn velocity_at(&self, t: f64) -> (Vec2, f64) {
        self.velocity_with(&self.arm.q_at(t), &self.arm.qd_at(t))
    }

    /// The link frame's velocity and angular velocity at joint angles `q` and rates `qd`.
    fn velocity_with(&self, q: &[f64], qd: &[f64]) -> (Vec2, f64) {
        let origin = self.arm.link_pose(q, self.link).pos;
        let mut v = Vec2::zeros();
        let mut omega = 0.0;
        for (j, &rate) in qd.iter().enumerate().take(self.link + 1) {
            let axis = self.arm.link_pose(q, j).pos;
            let r = origin - axis;
            v += rate * Vec2::new(-r.y, r.x);
            omega += rate;
        }
        (v, omega)
    }
}

/// The pose of link `link`'s frame (contract section 6): link 0 at the base's position with
/// angle `base.theta + q[0]`; link k at the point (`lengths[k-1]`, 0) of link k−1's frame,
/// with angle (link k−1's angle) + `q[k]`.
///
/// ```
/// use workcell::motion::{forward_kinematics, Pose};
/// let base = Pose::new(1.0, 2.0, 0.0);
/// // Two links of lengths 1 and 0.5: the elbow turned a quarter turn.
/// let p = forward_kinematics(base, &[1.0, 0.5], &[0.0, std::f64::consts::FRAC_PI_2], 1);
/// assert_eq!((p.pos.x, p.pos.y), (2.0, 2.0));
/// assert_eq!(p.theta, std::f64::consts::FRAC_PI_2);
/// ```
pub fn forward_kinematics(base: Pose, lengths: &[f64], q: &[f64], link: usize) -> Pose {
    let mut pos = base.pos;
    let mut theta = base.theta + q[0];
    for k in 1..=link {
        pos += lengths[k - 1] * Vec2::new(theta.cos(), theta.sin());
        theta += q[k];
    }
    Pose { pos, theta }
}

/// `a + (b − a)·u`, exactly `a` at u = 0 (the angles of a sample as given).
#[inline]
fn lerp(a: f64, b: f64, u: f64) -> f64 {
    if u == 0.0 {
        a
    } else {
        a + (b - a) * u
    }
}

/// The joint rates derived from the angles at sample `k`: the segment after it, or the one
/// before it at the last sample (zero for a single sample).
fn derived_rates(s: &[JointSample], k: usize) -> Vec<f64> {
    let (a, b) = match (k.checked_sub(1), s.get(k + 1)) {
        (_, Some(next)) => (&s[k], next),
        (Some(prev), None) => (&s[prev], &s[k]),
        (None, None) => return vec![0.0; s[k].q.len()],
    };
    let dt = b.t - a.t;
    a.q.iter()
        .zip(&b.q)
        .map(|(p, q)| {
            let r = (q - p) / dt;
            if r.is_finite() {
                r
            } else {
                0.0
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI, TAU};

    fn close(p: Pose, x: f64, y: f64, theta: f64) {
        let tol = 1e-12;
        assert!(
            (p.pos.x - x).abs() < tol && (p.pos.y - y).abs() < tol && (p.theta - theta).abs() < tol,
            "{p:?} vs ({x}, {y}, {theta})"
        );
    }

    /// Hand-computed poses of a three-link arm on a turned base.
    #[test]
    fn forward_kinematics_by_hand() {
        let base = Pose::new(1.0, -1.0, FRAC_PI_2);
        let lengths = [2.0, 1.0, 0.5];
        // Straight up from the base (base turned a quarter), elbow back down, wrist level.
        let q = [0.0, PI, -FRAC_PI_2];
        close(
            forward_kinematics(base, &lengths, &q, 0),
            1.0,
            -1.0,
            FRAC_PI_2,
        );
        close(
            forward_kinematics(base, &lengths, &q, 1),
            1.0,
            1.0,
            1.5 * PI,
        );
        close(forward_kinematics(base, &lengths, &q, 2), 1.0, 0.0, PI);
        // The tool point: (0.5, 0) in the last frame, pointing along −x.
        let last = forward_kinematics(base, &lengths, &q, 2);
        let tool = last.pos + 0.5 * Vec2::new(last.theta.cos(), last.theta.sin());
        assert!((tool - Vec2::new(0.5, 0.0)).norm() < 1e-12);
    }

    /// Angles of several turns are not wrapped: the pose is the same, the angle carries the
    /// turns.
    #[test]
    fn several_turns() {
        let base = Pose::new(0.0, 0.0, 0.0);
        let lengths = [1.0, 1.0];
        let q = [3.0 * TAU + FRAC_PI_2, -2.0 * TAU];
        let p = forward_kinematics(base, &lengths, &q, 1);
        close(p, 0.0, 1.0, 3.0 * TAU + FRAC_PI_2 - 2.0 * TAU);
    }

    #[test]
    fn interpolation_and_bound() {
        let s = |t: f64, q: Vec<f64>| JointSample {
            t,
            q,
            qd: Vec::new(),
        };
        let arm = ArmMotion::new(
            Pose::new(0.0, 0.0, 0.0),
            vec![1.0, 0.5],
            vec![1.2, 0.7],
            vec![s(0.0, vec![0.0, 0.0]), s(1.0, vec![TAU, -TAU])],
        )
        .unwrap();
        assert_eq!(arm.q_at(-1.0), [0.0, 0.0]);
        assert_eq!(arm.q_at(0.5), [PI, -PI]);
        assert_eq!(arm.q_at(7.0), [TAU, -TAU]);
        // Link 1: joint 0 at lever 1 + 0.7, joint 1 at lever 0.7.
        let lam = arm.lambda(1, &[0.0, 0.0], &[1.0, -2.0]);
        assert!((lam - (1.7 + 2.0 * 0.7)).abs() < 1e-12);
        // The bound holds for every point of the link on a dense grid of the motion.
        let q0 = [0.3, -1.0];
        let q1 = [2.0, 1.5];
        let tip = |q: &[f64]| {
            let p = arm.link_pose(q, 1);
            p.pos + 0.7 * Vec2::new(p.theta.cos(), p.theta.sin())
        };
        let lam = arm.lambda(1, &q0, &q1);
        let start = tip(&q0);
        for i in 0..=1000 {
            let u = i as f64 / 1000.0;
            let q: Vec<f64> = q0.iter().zip(&q1).map(|(a, b)| a + (b - a) * u).collect();
            assert!((tip(&q) - start).norm() <= lam * u + 1e-12);
        }
    }

    /// The walk's pose (by sample count) is the searched one, bit for bit, at and between
    /// samples and outside them.
    #[test]
    fn pose_after_is_pose_at() {
        let s = |t: f64, q: Vec<f64>| JointSample {
            t,
            q,
            qd: Vec::new(),
        };
        let samples = vec![
            s(0.5, vec![0.1, 2.0]),
            s(1.0, vec![7.0, -1.0]),
            s(3.0, vec![-2.0, 0.3]),
        ];
        let arm = ArmMotion::new(
            Pose::new(1.0, 2.0, 0.3),
            vec![0.7, 0.4],
            vec![0.8, 0.5],
            samples,
        )
        .unwrap();
        for t in [0.0, 0.5, 0.7, 1.0, 1.3, 2.999, 3.0, 9.0] {
            let after = arm.samples().partition_point(|x| x.t <= t);
            for link in 0..2 {
                assert_eq!(
                    arm.pose_after(after, t, link),
                    arm.pose_at(t, link),
                    "t = {t}"
                );
            }
        }
    }

    #[test]
    fn bad_input_is_named() {
        let s = |t: f64, q: Vec<f64>| JointSample {
            t,
            q,
            qd: Vec::new(),
        };
        let base = Pose::new(0.0, 0.0, 0.0);
        let new = |lengths: Vec<f64>, samples| {
            let reach = vec![1.0; lengths.len()];
            ArmMotion::new(base, lengths, reach, samples)
        };
        assert_eq!(
            new(vec![1.0, 1.0], vec![s(0.0, vec![0.0])]).unwrap_err(),
            ArmError::Joints {
                sample: 0,
                field: "q",
                got: 1,
                links: 2
            }
        );
        assert_eq!(
            new(vec![1.0, -1.0], vec![s(0.0, vec![0.0, 0.0])]).unwrap_err(),
            ArmError::Length {
                link: 1,
                length: -1.0
            }
        );
        assert_eq!(
            new(vec![1.0], vec![s(0.0, vec![0.0]), s(0.0, vec![1.0])]).unwrap_err(),
            ArmError::NotIncreasing { sample: 1 }
        );
        let mut bad = s(0.0, vec![0.0]);
        bad.qd = vec![1.0, 2.0];
        assert_eq!(
            new(vec![1.0], vec![bad]).unwrap_err(),
            ArmError::Joints {
                sample: 0,
                field: "qd",
                got: 2,
                links: 1
            }
        );
        assert_eq!(new(vec![], vec![]).unwrap_err(), ArmError::NoLinks);
    }
}
