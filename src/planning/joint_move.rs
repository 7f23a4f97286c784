//! Joint-space moves of an arm (contract section 7): a synchronised rest-to-rest profile in
//! which every joint starts and stops together, each within its speed and acceleration
//! limits. The slowest joint sets the duration; every other joint follows a trapezoid of
//! that duration (the smaller cruise speed that fits, so its own limits hold too).

use crate::motion::{JointLimits, JointSample, Trapezoid};
use std::f64::consts::{PI, TAU};

/// A move in joint space, rest to rest.
#[derive(Clone, Debug, PartialEq)]
pub struct JointMove {
    /// How long it takes.
    pub duration: f64,
    /// The joints at the profile's phase changes (each phase cut `samples_per_phase` times),
    /// from 0 to `duration`: the checker interpolates linearly between them.
    pub samples: Vec<JointSample>,
}

impl JointMove {
    /// The joint angles where the move ends: `to` for a joint with limits, `to` up to whole
    /// turns for one without (it turns the shorter way).
    ///
    /// ```
    /// use workcell::motion::JointLimits;
    /// use workcell::planning::joint_move;
    /// let limits = JointLimits { range: vec![None], max_speed: vec![1.0], max_accel: vec![1.0] };
    /// let m = joint_move(&[0.0], &[7.0], &limits, 2);
    /// assert!((m.end()[0] - (7.0 - 2.0 * std::f64::consts::PI)).abs() < 1e-12); // one turn less
    /// ```
    pub fn end(&self) -> &[f64] {
        &self.samples.last().expect("a move has samples").q
    }
}

/// Sample times of one move closer than this share of its duration are one time.
const SAME_TIME: f64 = 1e-9;

/// The angle joint `j` turns by from `a` to `b`: `b − a` for a joint with limits (both ends
/// within them, the way between is too); the shorter way round, in (−π, π], for one without.
fn turn(limits: &JointLimits, j: usize, a: f64, b: f64) -> f64 {
    match limits.range.get(j).copied().flatten() {
        Some(_) => b - a,
        None => {
            let w = (b - a).rem_euclid(TAU);
            if w > PI {
                w - TAU
            } else {
                w
            }
        }
    }
}

/// The duration of [`joint_move`] from `from` to `to`, bit for bit, without its samples: the
/// slowest joint's fastest rest-to-rest time. A lower bound of every joint-space path
/// between them (each joint turns at least as far, and the rest-to-rest time is
/// subadditive).
///
/// ```
/// use workcell::motion::JointLimits;
/// use workcell::planning::{joint_move, joint_move_time};
/// let limits = JointLimits { range: vec![None, Some([-2.0, 2.0])], max_speed: vec![1.0, 2.0], max_accel: vec![1.0, 1.0] };
/// let (a, b) = ([0.0, 0.0], [4.0, 1.0]);
/// assert_eq!(joint_move_time(&a, &b, &limits), joint_move(&a, &b, &limits, 4).duration);
/// ```
pub fn joint_move_time(from: &[f64], to: &[f64], limits: &JointLimits) -> f64 {
    (0..from.len())
        .map(|j| {
            let turn = turn(limits, j, from[j], to[j]).abs();
            Trapezoid::fastest(turn, limits.max_speed[j], limits.max_accel[j]).duration
        })
        .fold(0.0, f64::max)
}

/// The synchronised rest-to-rest move from joint angles `from` to `to`.
///
/// ```
/// use workcell::motion::JointLimits;
/// use workcell::planning::joint_move;
/// let limits = JointLimits {
///     range: vec![None, Some([-2.0, 2.0])],
///     max_speed: vec![1.0, 2.0],
///     max_accel: vec![1.0, 1.0],
/// };
/// let m = joint_move(&[0.0, 0.0], &[4.0, 1.0], &limits, 4);
/// // Joint 0 turns the shorter way (4 − 2π ≈ −2.28): 2.28/1 + 1/1 ≈ 3.28.
/// assert!((m.duration - (2.0 * std::f64::consts::PI - 4.0 + 1.0)).abs() < 1e-12);
/// assert!((m.end()[0] - (4.0 - 2.0 * std::f64::consts::PI)).abs() < 1e-12 && m.end()[1] == 1.0);
/// ```
pub fn joint_move(
    from: &[f64],
    to: &[f64],
    limits: &JointLimits,
    samples_per_phase: usize,
) -> JointMove {
    let turns: Vec<f64> = (0..from.len())
        .map(|j| turn(limits, j, from[j], to[j]))
        .collect();
    let duration = joint_move_time(from, to, limits);
    let profiles: Vec<Trapezoid> = (0..from.len())
        .map(|j| {
            let (v, a) = (limits.max_speed[j], limits.max_accel[j]);
            Trapezoid::with_duration(turns[j].abs(), a, v, duration)
        })
        .collect();
    // Every joint's phase changes, each phase cut evenly.
    let mut times: Vec<f64> = (profiles.iter())
        .flat_map(|p| p.boundaries())
        .map(|t| t.clamp(0.0, duration))
        .collect();
    times.sort_by(f64::total_cmp);
    // Phases of different joints that change within rounding of each other change at one
    // time: times a few ulps apart would merge when the move is shifted or reversed.
    times.dedup_by(|b, a| *b - *a <= SAME_TIME * duration);
    let cuts = samples_per_phase.max(1);
    let mut at: Vec<f64> = Vec::new();
    for w in times.windows(2) {
        for k in 0..cuts {
            let t = w[0] + (w[1] - w[0]) * k as f64 / cuts as f64;
            // Strictly increasing, apart by more than rounding, and short of the end.
            let gap = SAME_TIME * duration;
            if at.last().is_none_or(|&last| t - last > gap) && duration - t > gap {
                at.push(t);
            }
        }
    }
    at.push(duration);
    let samples = at
        .into_iter()
        .map(|t| {
            let (q, qd) = (0..from.len())
                .map(|j| {
                    let (s, v) = profiles[j].eval(t);
                    let sign = turns[j].signum();
                    // The end exactly: the joint's own profile ends at its whole turn.
                    let q = if t >= duration {
                        from[j] + turns[j]
                    } else {
                        from[j] + sign * s
                    };
                    (q, sign * v)
                })
                .unzip();
            JointSample { t, q, qd }
        })
        .collect();
    JointMove { duration, samples }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> JointLimits {
        JointLimits {
            range: vec![None, Some([-3.1, 3.1]), None],
            max_speed: vec![1.0, 2.0, 4.0],
            max_accel: vec![2.0, 1.0, 8.0],
        }
    }

    #[test]
    fn joints_start_and_stop_together_within_their_limits() {
        let l = limits();
        let (from, to) = ([0.3, -1.0, 2.0], [-1.2, 2.5, 2.4]);
        let m = joint_move(&from, &to, &l, 4);
        let slowest = (0..3)
            .map(|j| {
                Trapezoid::fastest((to[j] - from[j]).abs(), l.max_speed[j], l.max_accel[j]).duration
            })
            .fold(0.0, f64::max);
        assert_eq!(m.duration, slowest);
        let (first, last) = (&m.samples[0], m.samples.last().unwrap());
        assert_eq!((first.t, last.t), (0.0, m.duration));
        assert_eq!(first.q, from);
        assert_eq!(last.q, to);
        assert!(
            first.qd.iter().chain(&last.qd).all(|v| *v == 0.0),
            "at rest at both ends"
        );
        for w in m.samples.windows(2) {
            assert!(w[1].t > w[0].t);
            for j in 0..3 {
                let speed = (w[1].q[j] - w[0].q[j]).abs() / (w[1].t - w[0].t);
                assert!(
                    speed <= l.max_speed[j] * (1.0 + 1e-9),
                    "joint {j} at {speed}"
                );
                assert!(w[0].qd[j].abs() <= l.max_speed[j] * (1.0 + 1e-9));
            }
        }
    }

    #[test]
    fn free_joints_turn_the_shorter_way_and_limited_ones_never_wrap() {
        let l = limits();
        let m = joint_move(&[3.0, 3.0, 0.0], &[-3.0, -3.0, 0.0], &l, 2);
        let end = m.end();
        // Joint 0 is free: through π, by 2π − 6.
        assert!((end[0] - (3.0 + (TAU - 6.0))).abs() < 1e-12, "{end:?}");
        // Joint 1 has limits: the long way, by −6, staying within them.
        assert_eq!(end[1], -3.0);
        assert!(m.samples.iter().all(|s| (-3.1..=3.1).contains(&s.q[1])));
        // Joint 2 does not move at all.
        assert!(m.samples.iter().all(|s| s.q[2] == 0.0));
    }

    /// Across many moves, some with phases a few ulps long (joints of equal limits turning by
    /// nearly equal angles), the sample times strictly increase and the move ends on time.
    #[test]
    fn sample_times_strictly_increase() {
        let l = JointLimits {
            range: vec![None, None, Some([-10.0, 10.0])],
            max_speed: vec![1.0, 1.0, 1.0],
            max_accel: vec![2.0, 2.0, 2.0],
        };
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..2000 {
            let a = 3.0 * next();
            let to = [a, a * (1.0 + 1e-15 * next()), -a + 1e-13 * next()];
            let m = joint_move(&[0.0; 3], &to, &l, 1 + (next() * 5.0) as usize);
            assert!(m.samples.windows(2).all(|w| w[1].t > w[0].t), "{m:?}");
            assert_eq!(m.samples.last().unwrap().t, m.duration);
        }
    }

    #[test]
    fn no_move_takes_no_time() {
        let m = joint_move(&[1.0, 0.5, -2.0], &[1.0, 0.5, -2.0 + TAU], &limits(), 3);
        assert_eq!(m.duration, 0.0);
        assert_eq!(m.end(), [1.0, 0.5, -2.0]);
    }
}
