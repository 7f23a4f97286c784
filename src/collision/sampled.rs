//! The sampled method on one merged interval: look at fixed times, prove nothing between.

use super::eta::Eta;
use super::span::{PairSettings, Probe, Span, Stop};
use super::Stats;

/// Most looks per pair over the horizon, horizon / step: at about 0.1 µs a look, 10⁸ take
/// some 10 s per pair. A finer step is refused rather than left to run for hours.
pub const MAX_SAMPLED_LOOKS: f64 = 1e8;

/// Why `sampled:step` cannot be run on the horizon `(t0, t1)`, if it cannot: the step is not
/// a positive number, the looks would exceed [`MAX_SAMPLED_LOOKS`], or the step is finer
/// than f64 resolves the horizon's times (the looks would fall on the same instants).
pub(super) fn step_problem(step: f64, (t0, t1): (f64, f64)) -> Option<String> {
    if !(step.is_finite() && step > 0.0) {
        return Some(format!(
            "the step of sampled:{step} must be a positive number of time units"
        ));
    }
    let looks = (t1 - t0) / step;
    if looks > MAX_SAMPLED_LOOKS {
        return Some(format!(
            "sampled:{step:e} takes horizon / step = {looks:.3e} looks per pair over the horizon \
             [{t0}, {t1}], more than the limit {MAX_SAMPLED_LOOKS:e}: take a step of at least {:e}",
            (t1 - t0) / MAX_SAMPLED_LOOKS
        ));
    }
    let resolution = t0.abs().max(t1.abs()) * f64::EPSILON;
    if step < resolution {
        return Some(format!(
            "sampled:{step:e} is finer than f64 resolves the times of the horizon [{t0}, {t1}] \
             ({resolution:.3e}): the looks would fall on the same instants"
        ));
    }
    None
}

/// Looks at every time start + k·`step` inside the interval, then at its right end; the
/// first look closer than δ is the contact. Returns the witness and the time of the previous
/// look.
pub(super) fn search(
    eta: &mut Eta,
    span: &Span,
    (left, right): (Probe, Probe),
    step: f64,
    s: &PairSettings,
    stats: &mut Stats,
) -> Result<(), Stop> {
    let duration = span.t1 - span.t0;
    let mut last = left.u;
    // The first multiple of `step` after t0; counting in k keeps the looks on one global
    // grid. k is an integer and runs over a range fixed in advance: an f64 counter stops
    // advancing past 2⁵³, and the loop with it.
    let first = (((span.t0 - s.start) / step).floor() + 1.0).max(0.0) as u64;
    let end = (((span.t1 - s.start) / step).ceil()).max(0.0) as u64;
    for k in first..=end.saturating_add(1) {
        let t = s.start + k as f64 * step;
        if t >= span.t1 {
            break;
        }
        if t <= span.t0 {
            continue;
        }
        stats.looks += 1;
        let u = (t - span.t0) / duration;
        let p = Probe {
            u,
            ..eta.at(t, span.poses(u), stats)
        };
        if p.eta < s.delta {
            return Err(Stop::Contact(p, span.time_before(last)));
        }
        last = u;
    }
    if right.eta < s.delta {
        return Err(Stop::Contact(right, span.time_before(last)));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_that_cannot_finish_are_refused() {
        let horizon = (0.0, 18.0);
        assert_eq!(step_problem(0.001, horizon), None);
        assert_eq!(step_problem(18.0 / MAX_SAMPLED_LOOKS, horizon), None);
        for step in [1e-300, 5e-324, 0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(step_problem(step, horizon).is_some(), "{step}");
        }
        // 10⁶ looks, but each step is below one unit in the last place of the times.
        assert!(step_problem(1e-6, (1e15, 1e15 + 1.0)).is_some());
    }
}
