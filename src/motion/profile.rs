//! Rest-to-rest trapezoidal velocity profiles along one coordinate (a distance or an angle).

/// Duration of the fastest rest-to-rest motion over `|distance|` under a speed limit and an
/// acceleration limit: a trapezoid (accelerate at `max_accel`, cruise at `max_speed`,
/// decelerate), or a triangle when the distance is too short to reach `max_speed`
/// (`|distance| < max_speed² / max_accel`).
///
/// The two formulas, `2·√(d/a)` and `d/v + v/a`, meet at the switch point, so the time is
/// continuous and increasing in the distance. An infinite `max_speed` gives the triangle.
///
/// ```
/// use workcell::planning::rest_to_rest_time;
/// assert_eq!(rest_to_rest_time(1.0, 10.0, 1.0), 2.0); // triangle: 2·√(1/1)
/// assert_eq!(rest_to_rest_time(10.0, 1.0, 1.0), 11.0); // trapezoid: 10/1 + 1/1
/// ```
pub fn rest_to_rest_time(distance: f64, max_speed: f64, max_accel: f64) -> f64 {
    Trapezoid::fastest(distance.abs(), max_speed, max_accel).duration
}

/// A rest-to-rest motion over `distance`: accelerate at `accel` for `t_accel`, cruise at
/// `speed` for `t_cruise`, decelerate at `accel` for `t_accel`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Trapezoid {
    /// Distance covered (non-negative).
    pub distance: f64,
    /// Acceleration and deceleration magnitude.
    pub accel: f64,
    /// Cruise (peak) speed.
    pub speed: f64,
    /// Duration of the acceleration phase (equal to the deceleration phase).
    pub t_accel: f64,
    /// Duration of the cruise phase (0 for a triangle).
    pub t_cruise: f64,
    /// Total duration.
    pub duration: f64,
}

impl Trapezoid {
    /// No motion at all, lasting `duration`.
    pub fn rest(duration: f64) -> Self {
        Trapezoid {
            distance: 0.0,
            accel: 0.0,
            speed: 0.0,
            t_accel: 0.0,
            t_cruise: duration,
            duration,
        }
    }

    /// The fastest motion over `distance` (≥ 0) under the limits.
    pub fn fastest(distance: f64, max_speed: f64, max_accel: f64) -> Self {
        if distance <= 0.0 {
            return Self::rest(0.0);
        }
        // Written as a quotient, not `max_speed² / max_accel`: that overflows for large speeds.
        if distance <= max_speed * (max_speed / max_accel) {
            let t_accel = (distance / max_accel).sqrt();
            Trapezoid {
                distance,
                accel: max_accel,
                speed: max_accel * t_accel,
                t_accel,
                t_cruise: 0.0,
                duration: 2.0 * t_accel,
            }
        } else {
            let t_accel = max_speed / max_accel;
            let t_cruise = distance / max_speed - t_accel;
            Trapezoid {
                distance,
                accel: max_accel,
                speed: max_speed,
                t_accel,
                t_cruise,
                duration: distance / max_speed + t_accel,
            }
        }
    }

    /// The motion over `distance` that takes exactly `duration`, which must be at least the
    /// fastest time under `accel` (any speed limit is then respected by the smaller root).
    ///
    /// The cruise speed `w` solves `duration = distance/w + w/accel`; the smaller root keeps
    /// the peak speed lowest and the acceleration phases shortest.
    pub fn with_duration(distance: f64, accel: f64, max_speed: f64, duration: f64) -> Self {
        if distance <= 0.0 {
            return Self::rest(duration);
        }
        // Smaller root of w² − a·T·w + a·d = 0, in the form that neither cancels nor
        // squares the acceleration (which may be large).
        let disc = (duration * duration - 4.0 * distance / accel).max(0.0);
        let speed = (2.0 * distance / (duration + disc.sqrt())).min(max_speed);
        let t_accel = (speed / accel).min(0.5 * duration);
        Trapezoid {
            distance,
            accel,
            speed,
            t_accel,
            t_cruise: (duration - 2.0 * t_accel).max(0.0),
            duration,
        }
    }

    /// Distance covered and speed at time `t` (clamped to the motion).
    ///
    /// Each phase has its own closed form; the deceleration phase counts back from the end
    /// so that the distance at `duration` is exactly `distance`.
    pub fn eval(&self, t: f64) -> (f64, f64) {
        if t <= 0.0 {
            (0.0, 0.0)
        } else if t >= self.duration {
            (self.distance, 0.0)
        } else if t < self.t_accel {
            (0.5 * self.accel * t * t, self.accel * t)
        } else if t <= self.t_accel + self.t_cruise {
            let s = 0.5 * self.accel * self.t_accel * self.t_accel;
            (s + self.speed * (t - self.t_accel), self.speed)
        } else {
            let r = self.duration - t;
            (self.distance - 0.5 * self.accel * r * r, self.accel * r)
        }
    }

    /// Times at which the phase changes, from 0 to the duration (repeats for empty phases).
    pub fn boundaries(&self) -> [f64; 4] {
        let cruise_end = self.t_accel + self.t_cruise;
        [0.0, self.t_accel, cruise_end, self.duration]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()))
    }

    #[test]
    fn triangle_and_trapezoid() {
        // v²/a = 4: below it a triangle, above a trapezoid.
        assert!(close(rest_to_rest_time(1.0, 2.0, 1.0), 2.0));
        assert!(close(rest_to_rest_time(9.0, 2.0, 1.0), 9.0 / 2.0 + 2.0));
        assert!(close(rest_to_rest_time(-9.0, 2.0, 1.0), 6.5));
        assert_eq!(rest_to_rest_time(0.0, 2.0, 1.0), 0.0);
        assert!(close(rest_to_rest_time(4.0, f64::INFINITY, 1.0), 4.0));
    }

    #[test]
    fn continuous_and_increasing_at_the_switch() {
        let (v, a) = (1.5, 0.7);
        let d = v * v / a;
        let below = rest_to_rest_time(d * (1.0 - 1e-12), v, a);
        let at = rest_to_rest_time(d, v, a);
        let above = rest_to_rest_time(d * (1.0 + 1e-12), v, a);
        assert!(close(at, 2.0 * v / a));
        assert!(below <= at && at <= above);
        assert!(above - below < 1e-9);
    }

    #[test]
    fn eval_is_continuous_and_ends_exactly() {
        for p in [
            Trapezoid::fastest(9.0, 2.0, 1.0),
            Trapezoid::fastest(1.0, 2.0, 1.0),
            Trapezoid::with_duration(2.0, 1.0, 5.0, 7.0),
            Trapezoid::with_duration(1.0, 1.0, 5.0, 2.0),
        ] {
            for b in p.boundaries() {
                let (lo, hi) = (p.eval(b * (1.0 - 1e-13)), p.eval(b * (1.0 + 1e-13)));
                assert!((lo.0 - hi.0).abs() < 1e-9 && (lo.1 - hi.1).abs() < 1e-9);
            }
            assert_eq!(p.eval(p.duration), (p.distance, 0.0));
            assert_eq!(p.eval(0.0), (0.0, 0.0));
            let (s, v) = p.eval(0.5 * p.duration);
            assert!(close(s, 0.5 * p.distance) && v <= p.speed);
        }
    }

    #[test]
    fn fixed_duration_meets_the_time_and_the_limit() {
        // Fastest over 10 with v = 2, a = 1 takes 7; stretching to 7 gives back v = 2.
        let p = Trapezoid::with_duration(10.0, 1.0, 2.0, 7.0);
        assert!(close(p.speed, 2.0) && close(p.t_cruise, 3.0));
        let q = Trapezoid::with_duration(10.0, 1.0, 2.0, 20.0);
        assert!(q.speed < 2.0);
        assert!(close(q.distance / q.speed + q.speed / q.accel, 20.0));
        // The shortest time at unlimited speed gives the triangle.
        let r = Trapezoid::with_duration(4.0, 1.0, 10.0, 4.0);
        assert!(close(r.t_accel, 2.0) && r.t_cruise < 1e-7);
        // A huge acceleration: nearly all cruise, nothing overflows.
        let h = Trapezoid::with_duration(1.0, 1e300, 10.0, 2.0);
        assert!(close(h.speed, 0.5) && close(h.eval(1.0).0, 0.5));
    }
}
