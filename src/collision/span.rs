//! The vocabulary of searching one merged interval, shared by the pair loop and every method:
//! the interval, a probe of it, the settings, and why a search stopped.

use super::stats::Stats;
use crate::geometry::{Vec2, WalkTolerances};
use crate::motion::{LinkMotion, Pose};

/// Settings of a pair check, in the scene's units.
#[derive(Clone, Copy, Debug)]
pub struct PairSettings {
    /// δ: closer than this is a collision.
    pub delta: f64,
    /// Grazing allowance (length): an interval shorter than `time_tol` that can only be
    /// shown to stay above δ − `grazing_tol` counts as a graze, not a contact.
    pub grazing_tol: f64,
    /// The first contact is reported no later than this after the true one.
    pub time_tol: f64,
    /// Start of the horizon: the sampled method looks at start + k·step.
    pub start: f64,
    /// Narrow-phase tolerances.
    pub walk: WalkTolerances,
    /// Work budget of the pair: evaluations of η (merged interval ends, bisections, looks).
    pub max_work: u64,
    /// Whether every counter must be known through any time (see
    /// [`super::CheckOptions::counters`]), or only grazes and unresolved intervals.
    pub counters: bool,
}

impl PairSettings {
    /// Whether the pair has done all the work it may (see [`PairSettings::max_work`]).
    pub fn out_of_work(&self, stats: &Stats) -> bool {
        stats.intervals + stats.bisections + stats.looks >= self.max_work
    }
}

/// Why a search of a merged interval stopped before its end.
#[derive(Clone, Copy, Debug)]
pub(super) enum Stop {
    /// A witness closer than δ, and the end of the certified prefix before it.
    Contact(Probe, f64),
    /// The work budget ran out; the prefix up to this time is certified.
    OutOfWork(f64),
}

/// A pair probed at one time: both poses and η.
#[derive(Clone, Copy, Debug)]
pub struct Probe {
    pub t: f64,
    /// Position in the merged interval being checked: 0 at its start, 1 at its end.
    pub u: f64,
    pub pose_a: Pose,
    pub pose_b: Pose,
    /// Lower bound of the distance; exact whenever it is below δ.
    pub eta: f64,
    /// Whether `eta` is the exact distance (else the disc gap).
    pub exact: bool,
    /// When `exact`, the unit direction from A's closest point to B's (zero on overlap);
    /// zero otherwise (the disc direction follows from the poses).
    pub normal: Vec2,
}

/// One merged interval: both poses are linear in time between its ends (for a link of an
/// arm, its joint angles are).
///
/// Points inside it are addressed by a parameter u in [0, 1], not by time: the poses
/// are interpolated between the ends directly, so bisection keeps its resolution even where
/// time stamps are huge or an interval is a single unit in the last place long.
pub(super) struct Span<'s, 'l> {
    pub t0: f64,
    pub t1: f64,
    pub a: (Pose, Pose),
    pub b: (Pose, Pose),
    /// For a pair with a link of an arm, each link's joints at the ends (`None` for a pair of
    /// rigid bodies: their path stays as lean as before arms).
    pub links: Option<&'l [Option<LinkEnds<'s>>; 2]>,
}

/// A link over a merged interval: the arm's two samples about it (the joints are linear
/// between them), where the interval's ends lie between those samples, and its motion bound
/// over the interval. Nothing is allocated: a pose is the kinematics of interpolated angles.
pub(super) struct LinkEnds<'s> {
    pub motion: &'s LinkMotion,
    a: &'s [f64],
    b: &'s [f64],
    /// The interval's ends as parameters between `a` (0) and `b` (1).
    s0: f64,
    s1: f64,
    /// λ of the link over the whole interval (Schwarzer, Saha & Latombe 2005).
    pub lambda: f64,
}

impl<'s> LinkEnds<'s> {
    /// The link over `[t0, t1]`, an interval of the merged grid that starts after `after`
    /// of the arm's samples: the joints are linear between sample `after − 1` and `after`.
    pub fn new(motion: &'s LinkMotion, after: usize, t0: f64, t1: f64) -> Self {
        let samples = motion.arm.samples();
        let (a, b) = match after {
            0 => (&samples[0], &samples[0]),
            k if k == samples.len() => (&samples[k - 1], &samples[k - 1]),
            k => (&samples[k - 1], &samples[k]),
        };
        let (s0, s1) = if b.t > a.t {
            ((t0 - a.t) / (b.t - a.t), (t1 - a.t) / (b.t - a.t))
        } else {
            (0.0, 0.0) // at rest outside the samples
        };
        // The joints turn by (b − a)·(s1 − s0) over the interval.
        let lambda = motion.arm.lambda(motion.link, &a.q, &b.q) * (s1 - s0).abs();
        LinkEnds {
            motion,
            a: &a.q,
            b: &b.q,
            s0,
            s1,
            lambda,
        }
    }

    /// How far the link may stray, over `[u0, u1]` of the interval, from the motion that
    /// moves its frame's origin along the chord between its ends while it turns linearly.
    /// Link k's angle is linear in the joints, and so is exactly that motion's; its origin is
    /// a sum of arcs, one per link j < k, of radius L_j through the angle Δθ_j that link j
    /// turns by. An arc's point at parameter u is off its chord's by at most
    /// u(1 − u)/2 · L_j·Δθ_j² ≤ L_j·Δθ_j²/8 (the error of linear interpolation, whose
    /// second derivative is L_j·Δθ_j² in length), which the middle of a small arc reaches.
    pub fn chord_error(&self, u0: f64, u1: f64) -> f64 {
        let arm = &self.motion.arm;
        let ds = (self.s1 - self.s0) * (u1 - u0);
        let mut turn = 0.0;
        let mut error = 0.0;
        for (j, length) in arm.lengths()[..self.motion.link].iter().enumerate() {
            turn += (self.b[j] - self.a[j]) * ds;
            error += length * turn * turn / 8.0;
        }
        error
    }

    /// The link's pose at `u`: its joints interpolated, then forward kinematics.
    fn pose(&self, u: f64) -> Pose {
        let s = self.s0 + (self.s1 - self.s0) * u;
        (self.motion.arm).pose_between(self.a, self.b, s, self.motion.link)
    }
}

impl Span<'_, '_> {
    pub fn time(&self, u: f64) -> f64 {
        if u == 1.0 {
            self.t1
        } else {
            self.t0 + u * (self.t1 - self.t0)
        }
    }

    /// The time at `u` and the error of that f64 against the exact t0 + u·(t1 − t0), by
    /// error-free transformations (TwoSum, FMA): positive when the f64 is early.
    fn time_and_error(&self, u: f64) -> (f64, f64) {
        let two_sum = |x: f64, y: f64| {
            let s = x + y;
            let yy = s - x;
            (s, (x - (s - yy)) + (y - yy))
        };
        let (d, d_err) = two_sum(self.t1, -self.t0);
        let p = u * d;
        let p_err = u.mul_add(d, -p);
        let (t, t_err) = two_sum(self.t0, p);
        (t, t_err + p_err + u * d_err)
    }

    /// The least f64 time not before the instant at `u`: a contact reported there is never
    /// earlier than its witness, even where the time stamps are huge.
    pub fn time_after(&self, u: f64) -> f64 {
        match u {
            0.0 => self.t0,
            1.0 => self.t1,
            _ => match self.time_and_error(u) {
                (t, e) if e > 0.0 => t.next_up(),
                (t, _) => t,
            },
        }
    }

    /// The greatest f64 time not after the instant at `u`: the end of a certified prefix.
    pub fn time_before(&self, u: f64) -> f64 {
        match u {
            0.0 => self.t0,
            1.0 => self.t1,
            _ => match self.time_and_error(u) {
                (t, e) if e < 0.0 => t.next_down(),
                (t, _) => t,
            },
        }
    }

    #[inline]
    pub fn poses(&self, u: f64) -> (Pose, Pose) {
        match &self.links {
            None => (lerp(&self.a, u), lerp(&self.b, u)),
            Some(links) => self.poses_with_links(links, u),
        }
    }

    /// [`Span::poses`] for a pair with a link of an arm, out of the rigid pairs' way.
    #[inline(never)]
    #[cold]
    fn poses_with_links(&self, links: &[Option<LinkEnds>; 2], u: f64) -> (Pose, Pose) {
        let pose = |ends: &(Pose, Pose), link: &Option<LinkEnds>| match link {
            None => lerp(ends, u),
            Some(link) => match u {
                0.0 => ends.0,
                1.0 => ends.1,
                _ => link.pose(u),
            },
        };
        (pose(&self.a, &links[0]), pose(&self.b, &links[1]))
    }

    /// For a pair with links, how far both may stray over `[u0, u1]` from moving their frames
    /// linearly between the ends ([`LinkEnds::chord_error`]); 0 for rigid bodies.
    pub fn chord_error(&self, u0: f64, u1: f64) -> f64 {
        match &self.links {
            None => 0.0,
            Some(links) => links.iter().flatten().map(|l| l.chord_error(u0, u1)).sum(),
        }
    }

    /// Whether either body is a link of an arm (whose pose is not linear in time).
    #[inline]
    pub fn has_links(&self) -> bool {
        self.links.is_some()
    }
}

fn lerp((p, q): &(Pose, Pose), u: f64) -> Pose {
    Pose {
        pos: p.pos + (q.pos - p.pos) * u,
        theta: p.theta + (q.theta - p.theta) * u,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::{ArmMotion, JointSample};
    use std::sync::Arc;

    fn arm(lengths: &[f64], q0: &[f64], q1: &[f64]) -> Arc<ArmMotion> {
        let sample = |t: f64, q: &[f64]| JointSample {
            t,
            q: q.to_vec(),
            qd: Vec::new(),
        };
        let reach = vec![0.1; lengths.len()];
        let samples = vec![sample(0.0, q0), sample(1.0, q1)];
        Arc::new(
            ArmMotion::new(Pose::new(0.3, -0.2, 0.4), lengths.to_vec(), reach, samples).unwrap(),
        )
    }

    /// The largest distance, over [u0, u1] of the interval [t0, t1], between the link's
    /// origin and the point at the same parameter on the chord between its ends.
    fn stray(link: &LinkMotion, (t0, t1): (f64, f64), (u0, u1): (f64, f64)) -> f64 {
        let at = |u: f64| link.arm.pose_at(t0 + (t1 - t0) * u, link.link).pos;
        let (p, q) = (at(u0), at(u1));
        (0..=400)
            .map(|i| {
                let v = i as f64 / 400.0;
                (at(u0 + (u1 - u0) * v) - (p + (q - p) * v)).norm()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn the_chord_error_bounds_how_far_a_link_strays_and_is_tight() {
        // Deterministic joints of 2 to 4 links, some turning several times.
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..200 {
            let n = 2 + case % 3;
            let lengths: Vec<f64> = (0..n).map(|_| 0.2 + next()).collect();
            let range = if case % 4 == 0 { 20.0 } else { 2.0 };
            let q0: Vec<f64> = (0..n).map(|_| (next() - 0.5) * range).collect();
            let q1: Vec<f64> = (0..n).map(|_| (next() - 0.5) * range).collect();
            let arm = arm(&lengths, &q0, &q1);
            let (t0, t1) = (0.2 * next(), 1.0 - 0.2 * next());
            let (u0, u1) = (0.5 * next(), 0.5 + 0.5 * next());
            for k in 0..n {
                let link = LinkMotion::new(arm.clone(), k);
                let ends = LinkEnds::new(&link, 1, t0, t1);
                let bound = ends.chord_error(u0, u1);
                let seen = stray(&link, (t0, t1), (u0, u1));
                assert!(
                    seen <= bound * (1.0 + 1e-9) + 1e-12,
                    "case {case}, link {k}: {seen} > {bound}"
                );
            }
        }
        // One small turn of the base joint: the middle of the arc is off the chord by about
        // L·Δθ²/8, the bound itself.
        let arm = arm(&[2.0, 1.0], &[0.0, 0.3], &[0.01, 0.3]);
        let link = LinkMotion::new(arm, 1);
        let ends = LinkEnds::new(&link, 1, 0.0, 1.0);
        let (bound, seen) = (
            ends.chord_error(0.0, 1.0),
            stray(&link, (0.0, 1.0), (0.0, 1.0)),
        );
        assert!((2.0 * 0.01f64.powi(2) / 8.0 - bound).abs() < 1e-15);
        assert!(seen > 0.99 * bound, "{seen} against {bound}");
    }
}
