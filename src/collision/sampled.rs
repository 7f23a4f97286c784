//! The sampled method on one merged interval: look at fixed times, prove nothing between.

use super::eta::{Eta, Probe};
use super::pair::{PairSettings, Span, Stop};
use super::Stats;

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
    // The first multiple of `step` after t0; counting in k keeps the looks on one global grid.
    let mut k = ((span.t0 - s.start) / step).floor() + 1.0;
    loop {
        let t = s.start + k * step;
        if t >= span.t1 {
            break;
        }
        k += 1.0;
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
