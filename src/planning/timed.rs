//! From a geometric plan to a timed move, and the changes the feedback loop makes to a move
//! while keeping the motion model: stopping at a point of the path, running slower.
//!
//! A move is a chain of [`Primitive`]s. Each is timed by the model of the module
//! documentation (rest to rest along every path segment, one rotation profile over the
//! whole primitive), so timing the same primitives again gives the same samples, bit for
//! bit: `evaluate` replays a solve's changed moves from their primitives alone.

use super::sampling::Timing;
use super::{PlannedMove, RobotLimits};
use crate::geometry::Vec2;
use crate::motion::{rest_to_rest_time, Trapezoid};
use crate::motion::{JointSample, Pose, Sample};

/// One rest-to-rest piece of a move: G along `path`, stopping at every waypoint, while the
/// angle turns from `theta` by `turn` as one profile over the whole piece. A turn in place
/// has a path of one point repeated.
#[derive(Clone, Debug, PartialEq)]
pub struct Primitive {
    /// Waypoints of G, start and goal included (at least two; equal for a turn in place).
    pub path: Vec<Vec2>,
    /// Angle at the start.
    pub theta: f64,
    /// Signed rotation over the piece: it ends at `theta + turn`.
    pub turn: f64,
}

impl Primitive {
    /// Length of the path of G.
    pub fn length(&self) -> f64 {
        self.path.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
    }

    /// The start pose.
    pub fn start(&self) -> Pose {
        Pose {
            pos: self.path[0],
            theta: self.theta,
        }
    }

    /// The end pose.
    pub fn end(&self) -> Pose {
        Pose {
            pos: *self.path.last().expect("a primitive has a path"),
            theta: self.theta + self.turn,
        }
    }

    /// The primitive cut at arc length `s` along its path (0 < s < length): the part before
    /// and the part after, the turn shared in proportion to the length. Both parts follow the
    /// same path at angles within the same range, so they sweep no more than the whole did.
    ///
    /// ```
    /// use workcell::geometry::Vec2;
    /// use workcell::planning::Primitive;
    /// let p = Primitive { path: vec![Vec2::new(0.0, 0.0), Vec2::new(4.0, 0.0)], theta: 0.0, turn: 1.0 };
    /// let (before, after) = p.split_at(1.0).unwrap();
    /// assert_eq!((before.end().pos, before.turn), (Vec2::new(1.0, 0.0), 0.25));
    /// assert_eq!((after.start(), after.end()), (before.end(), p.end()));
    /// assert!(p.split_at(4.0).is_none()); // not inside the path
    /// ```
    pub fn split_at(&self, s: f64) -> Option<(Primitive, Primitive)> {
        let total = self.length();
        if !(s > 0.0 && s < total) {
            return None;
        }
        let mut walked = 0.0;
        for (k, w) in self.path.windows(2).enumerate() {
            let len = (w[1] - w[0]).norm();
            if walked + len >= s && len > 0.0 {
                let u = ((s - walked) / len).clamp(0.0, 1.0);
                let cut = w[0] + (w[1] - w[0]) * u;
                let mut before: Vec<Vec2> = self.path[..=k].to_vec();
                if cut != w[0] {
                    before.push(cut);
                }
                let mut after = vec![cut];
                after.extend(self.path[k + 1..].iter().copied().filter(|&p| p != cut));
                if before.len() < 2 || after.len() < 2 {
                    return None;
                }
                let turn = self.turn * (s / total);
                return Some((
                    Primitive {
                        path: before,
                        theta: self.theta,
                        turn,
                    },
                    Primitive {
                        path: after,
                        theta: self.theta + turn,
                        turn: self.turn - turn,
                    },
                ));
            }
            walked += len;
        }
        None
    }

    /// The same piece run backwards.
    ///
    /// ```
    /// use workcell::geometry::Vec2;
    /// use workcell::planning::Primitive;
    /// let p = Primitive { path: vec![Vec2::new(0.0, 0.0), Vec2::new(4.0, 3.0)], theta: 0.5, turn: 1.0 };
    /// let back = p.reversed();
    /// assert_eq!((back.start(), back.end()), (p.end(), p.start()));
    /// assert_eq!(back.reversed(), p);
    /// ```
    pub fn reversed(&self) -> Primitive {
        Primitive {
            path: self.path.iter().rev().copied().collect(),
            theta: self.theta + self.turn,
            turn: -self.turn,
        }
    }
}

/// Times one primitive by the motion model: each path segment rest to rest at the robot's
/// limits, the rotation as one trapezoid over the whole piece (angular acceleration
/// `max_accel / radius`), sampled `samples_per_phase` times per profile phase.
pub(super) fn time_primitive(
    radius: f64,
    limits: &RobotLimits,
    primitive: &Primitive,
    samples_per_phase: usize,
) -> PlannedMove {
    let path = &primitive.path;
    let segments: Vec<Trapezoid> = path
        .windows(2)
        .map(|w| Trapezoid::fastest((w[1] - w[0]).norm(), limits.max_speed, limits.max_accel))
        .collect();
    // Summed in the order the sampler accumulates segment start times.
    let t_trans = segments.iter().fold(0.0, |t, s| t + s.duration);
    let alpha = limits.max_accel / radius;
    let t_rot = rest_to_rest_time(primitive.turn, limits.max_turn_rate, alpha);
    let duration = t_trans.max(t_rot);
    let timing = Timing {
        path,
        segments: &segments,
        rotation: Trapezoid::with_duration(
            primitive.turn.abs(),
            alpha,
            limits.max_turn_rate,
            duration,
        ),
        turn: primitive.turn,
        from: primitive.start(),
        duration,
    };
    PlannedMove {
        duration,
        path: path.clone(),
        samples: timing.samples(samples_per_phase),
        primitives: vec![primitive.clone()],
        joints: Vec::new(),
    }
}

/// Times a chain of primitives, each starting where the previous one stopped: the move
/// that [`super::plan_move`] returns for them, sample for sample.
///
/// ```
/// use workcell::geometry::Vec2;
/// use workcell::planning::{time_primitives, Primitive, RobotLimits};
/// let limits = RobotLimits { max_speed: 1.0, max_accel: 1.0, max_turn_rate: 1.0 };
/// let straight = Primitive { path: vec![Vec2::zeros(), Vec2::new(4.0, 0.0)], theta: 0.0, turn: 0.0 };
/// let timed = time_primitives(0.5, &limits, &[straight], 4);
/// assert_eq!(timed.duration, 5.0); // 4/1 + 1/1: trapezoid
/// ```
pub fn time_primitives(
    radius: f64,
    limits: &RobotLimits,
    primitives: &[Primitive],
    samples_per_phase: usize,
) -> PlannedMove {
    let legs: Vec<PlannedMove> = primitives
        .iter()
        .map(|p| time_primitive(radius, limits, p, samples_per_phase))
        .collect();
    chain(&legs)
}

/// The moves one after the other, each starting where and when the previous one stops.
pub(super) fn chain(legs: &[PlannedMove]) -> PlannedMove {
    if legs.len() == 1 {
        return legs[0].clone();
    }
    let mut samples = legs[0].samples.clone();
    let mut path = legs[0].path.clone();
    let mut primitives = legs[0].primitives.clone();
    let mut joints = legs[0].joints.clone();
    let mut start = legs[0].duration;
    for leg in &legs[1..] {
        joints.extend(leg.joints.iter().skip(1).map(|s| JointSample {
            t: start + s.t,
            ..s.clone()
        }));
        // A leg's first sample is the previous leg's last: at rest, at the same pose.
        samples.extend(leg.samples[1..].iter().map(|s| Sample {
            t: start + s.t,
            ..*s
        }));
        path.extend(leg.path.iter().skip(1));
        primitives.extend(leg.primitives.iter().cloned());
        start += leg.duration;
    }
    // A turn in place repeats its point.
    path.dedup();
    // The last sample carries the duration exactly, as for a single primitive.
    PlannedMove {
        duration: samples.last().map_or(0.0, |s| s.t),
        path,
        samples,
        primitives,
        joints,
    }
}

impl PlannedMove {
    /// The same move `factor` (≥ 1) times slower: the same poses, every time stamp
    /// stretched, velocities divided by `factor` and accelerations by its square, so every
    /// limit still holds.
    ///
    /// ```
    /// use workcell::geometry::ConvexPolygon;
    /// use workcell::motion::Pose;
    /// use workcell::planning::{plan_move, PlannerOptions, RobotLimits};
    /// let robot = ConvexPolygon::rectangle(1.0, 1.0)?;
    /// let limits = RobotLimits { max_speed: 1.0, max_accel: 2.0, max_turn_rate: 1.0 };
    /// let (from, to) = (Pose::new(0.0, 0.0, 0.0), Pose::new(3.0, 4.0, 1.0));
    /// let fast = plan_move(&[robot], &limits, &[], 0.01, from, to, &PlannerOptions::default())?;
    /// let slow = fast.slowed(2.0);
    /// assert_eq!(slow.duration, 2.0 * fast.duration);
    /// for (s, f) in slow.samples.iter().zip(&fast.samples) {
    ///     assert_eq!((s.t, s.pos, s.theta), (2.0 * f.t, f.pos, f.theta));
    ///     assert_eq!(s.vel, f.vel / 2.0);
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn slowed(&self, factor: f64) -> PlannedMove {
        PlannedMove {
            duration: self.duration * factor,
            path: self.path.clone(),
            samples: self
                .samples
                .iter()
                .map(|s| Sample {
                    t: s.t * factor,
                    vel: s.vel / factor,
                    omega: s.omega / factor,
                    ..*s
                })
                .collect(),
            primitives: self.primitives.clone(),
            joints: (self.joints.iter())
                .map(|s| JointSample {
                    t: s.t * factor,
                    q: s.q.clone(),
                    qd: s.qd.iter().map(|v| v / factor).collect(),
                })
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIMITS: RobotLimits = RobotLimits {
        max_speed: 1.0,
        max_accel: 2.0,
        max_turn_rate: 1.5,
    };

    fn line(turn: f64) -> Primitive {
        Primitive {
            path: vec![Vec2::zeros(), Vec2::new(3.0, 0.0), Vec2::new(3.0, 2.0)],
            theta: 0.2,
            turn,
        }
    }

    #[test]
    fn split_keeps_the_path_and_shares_the_turn() {
        let p = line(1.0);
        let (a, b) = p.split_at(4.0).unwrap();
        assert_eq!(
            a.path,
            vec![Vec2::zeros(), Vec2::new(3.0, 0.0), Vec2::new(3.0, 1.0)]
        );
        assert_eq!(b.path, vec![Vec2::new(3.0, 1.0), Vec2::new(3.0, 2.0)]);
        assert_eq!(a.end(), b.start());
        assert!((a.turn - 0.8).abs() < 1e-15 && (a.turn + b.turn - 1.0).abs() < 1e-15);
        // At a waypoint the cut adds no point.
        let (a, b) = p.split_at(3.0).unwrap();
        assert_eq!(a.path.len() + b.path.len(), 4);
        assert!(p.split_at(0.0).is_none() && p.split_at(5.0).is_none());
    }

    #[test]
    fn a_split_move_stops_where_it_was_cut_and_takes_longer() {
        let whole = time_primitives(0.5, &LIMITS, &[line(1.0)], 4);
        let (a, b) = line(1.0).split_at(1.5).unwrap();
        let parts = time_primitives(0.5, &LIMITS, &[a.clone(), b], 4);
        assert!(parts.duration > whole.duration);
        let stop = parts
            .samples
            .iter()
            .find(|s| s.pos == a.end().pos && s.t > 0.0)
            .unwrap();
        assert_eq!((stop.vel, stop.omega), (Vec2::zeros(), 0.0));
        assert_eq!(parts.primitives.len(), 2);
    }

    #[test]
    fn slowing_down_divides_the_velocities() {
        let m = time_primitives(0.5, &LIMITS, &[line(1.0)], 4);
        let s = m.slowed(2.0);
        assert_eq!(s.duration, 2.0 * m.duration);
        for (x, y) in m.samples.iter().zip(&s.samples) {
            assert_eq!((y.t, y.pos, y.theta), (2.0 * x.t, x.pos, x.theta));
            assert_eq!((y.vel, y.omega), (x.vel / 2.0, x.omega / 2.0));
        }
    }

    #[test]
    fn reversed_primitive_visits_the_same_poses_backwards() {
        let p = line(0.7);
        let r = p.reversed();
        assert_eq!(r.start(), p.end());
        assert_eq!(r.end().pos, p.start().pos);
        assert!((r.end().theta - p.start().theta).abs() < 1e-15);
    }
}
