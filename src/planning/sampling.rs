//! From the profiles of a move to its time samples.

use crate::geometry::Vec2;
use crate::motion::Trapezoid;
use crate::motion::{Pose, Sample};

/// Times closer than this fraction of the move's duration are one sample.
const MERGE_REL: f64 = 1e-12;

/// The timed motion of one move: G along the path, one segment after the other, each
/// rest to rest; the orientation by one profile over the whole move.
pub(crate) struct Timing<'a> {
    /// Waypoints of G, start and goal included.
    pub path: &'a [Vec2],
    /// One profile per path segment.
    pub segments: &'a [Trapezoid],
    /// The rotation's profile, over the whole duration.
    pub rotation: Trapezoid,
    /// Signed rotation: the orientation ends at `from.theta + turn`.
    pub turn: f64,
    /// Start pose.
    pub from: Pose,
    /// Duration of the move.
    pub duration: f64,
}

impl Timing<'_> {
    /// Start time of each segment, and the end of the translation last.
    fn starts(&self) -> Vec<f64> {
        let mut starts = Vec::with_capacity(self.segments.len() + 1);
        let mut t = 0.0;
        starts.push(t);
        for s in self.segments {
            t += s.duration;
            starts.push(t);
        }
        starts
    }

    /// Sample times: every phase boundary of every profile, `per_phase − 1` evenly spaced
    /// times inside each phase, and both ends; sorted, near-duplicates merged.
    fn times(&self, starts: &[f64], per_phase: usize) -> Vec<f64> {
        let mut times = vec![0.0, self.duration];
        let mut add_phases = |offset: f64, p: &Trapezoid| {
            let b = p.boundaries();
            for (lo, hi) in b.iter().zip(&b[1..]) {
                if hi > lo {
                    let (lo, hi) = (offset + lo, offset + hi);
                    times.push(lo);
                    times.extend(
                        (1..per_phase).map(|k| lo + (hi - lo) * k as f64 / per_phase as f64),
                    );
                    times.push(hi);
                }
            }
        };
        for (p, &t0) in self.segments.iter().zip(starts) {
            add_phases(t0, p);
        }
        if self.rotation.distance > 0.0 {
            add_phases(0.0, &self.rotation);
        }
        times.sort_unstable_by(f64::total_cmp);
        // A merge may drop a waypoint's time for one a hair earlier: the robot is then
        // within ½·a·(10⁻¹² T)² of the waypoint, far below any tolerance, so the
        // interpolated corner stays on the path.
        let gap = MERGE_REL * self.duration;
        let mut merged: Vec<f64> = Vec::with_capacity(times.len());
        for t in times {
            if merged.last().is_none_or(|&last| t - last > gap) {
                merged.push(t);
            }
        }
        // The duration is the largest time; a merge may have kept a neighbour instead.
        if let Some(last) = merged.last_mut() {
            *last = self.duration;
        }
        merged
    }

    /// The samples of the move. Each takes position and velocity from the translation
    /// profile and orientation and angular velocity from the rotation profile, exactly at
    /// its time; the last is the goal at rest.
    pub fn samples(&self, per_phase: usize) -> Vec<Sample> {
        let starts = self.starts();
        let times = self.times(&starts, per_phase);
        let goal = self.path[self.path.len() - 1];
        let sign = self.turn.signum();
        let mut k = 0;
        let mut out: Vec<Sample> = times
            .iter()
            .map(|&t| {
                while k < self.segments.len() && t >= starts[k + 1] {
                    k += 1;
                }
                let (pos, vel) = if k == self.segments.len() {
                    (goal, Vec2::zeros())
                } else if self.segments[k].distance == 0.0 {
                    (self.path[k], Vec2::zeros())
                } else {
                    let (a, b) = (self.path[k], self.path[k + 1]);
                    let p = &self.segments[k];
                    let (s, v) = p.eval(t - starts[k]);
                    let u = s / p.distance;
                    (a + (b - a) * u, (b - a) * (v / p.distance))
                };
                let (angle, rate) = self.rotation.eval(t);
                Sample {
                    t,
                    pos,
                    theta: self.from.theta + sign * angle,
                    vel,
                    omega: sign * rate,
                }
            })
            .collect();
        // The ends exactly as specified, whatever rounding did to the profiles.
        out[0] = Sample {
            t: 0.0,
            pos: self.from.pos,
            theta: self.from.theta,
            vel: Vec2::zeros(),
            omega: 0.0,
        };
        if out.len() > 1 {
            let last = out.len() - 1;
            out[last] = Sample {
                t: self.duration,
                pos: goal,
                theta: self.from.theta + self.turn,
                vel: Vec2::zeros(),
                omega: 0.0,
            };
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_follow_the_profiles_and_end_at_rest() {
        let path = [Vec2::zeros(), Vec2::new(4.0, 0.0), Vec2::new(4.0, 1.0)];
        let segments = [
            Trapezoid::fastest(4.0, 1.0, 1.0),
            Trapezoid::fastest(1.0, 1.0, 1.0),
        ];
        let duration = segments[0].duration + segments[1].duration + 1.0;
        let timing = Timing {
            path: &path,
            segments: &segments,
            rotation: Trapezoid::with_duration(1.0, 1.0, 1.0, duration),
            turn: -1.0,
            from: Pose {
                pos: path[0],
                theta: 0.5,
            },
            duration,
        };
        let s = timing.samples(4);
        assert!(s.windows(2).all(|w| w[1].t > w[0].t));
        // Trapezoid (3 phases) + triangle (2) + rotation (3) phases, 4 samples each, plus
        // the shared boundaries; never fewer than one per phase.
        assert!(s.len() > 3 * 4 + 2 * 4);
        let first_stop = segments[0].duration;
        let at_corner = s.iter().find(|p| p.t == first_stop).unwrap();
        assert_eq!(at_corner.pos, path[1]);
        assert_eq!(at_corner.vel, Vec2::zeros());
        let last = s.last().unwrap();
        assert_eq!((last.t, last.pos, last.theta), (duration, path[2], -0.5));
        assert!(s
            .iter()
            .all(|p| p.omega <= 0.0 && p.theta <= 0.5 && p.theta >= -0.5));
        // Resting at the goal while the rotation finishes.
        assert!(s
            .iter()
            .filter(|p| p.t > duration - 1.0)
            .all(|p| p.pos == path[2]));
    }
}
