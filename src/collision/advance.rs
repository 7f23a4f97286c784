//! Conservative advancement on one merged interval (the time of impact of Box2D and FCL).

use super::eta::{Eta, Probe};
use super::pair::{PairSettings, Span};
use super::Stats;
use crate::motion::BoundKind;

/// From the free left end, steps forward by (η − δ) / λ', λ' bounding how far the pair can
/// close in per unit of the interval: the pose is linear on it, so over a fraction u of the
/// interval no point moves farther than u·λ (rigorous λ). The first look closer than δ is
/// the contact. Returns the witness and the time of the last free look.
pub(super) fn search(
    eta: &mut Eta,
    span: &Span,
    (left, right): (Probe, Probe),
    s: &PairSettings,
    stats: &mut Stats,
) -> Result<(), (Probe, f64)> {
    let closing = eta.lambda(BoundKind::Rigorous, &left, &right);
    // Box2D's target slop, as a time: no step is shorter than the time tolerance, or a pair
    // gliding at δ would be advanced forever.
    let min_step = s.time_tol / (span.t1 - span.t0);
    let mut at = left;
    loop {
        if at.eta.is_nan() || right.eta.is_nan() {
            stats.unresolved += 1;
            return Ok(());
        }
        let mut step = (at.eta - s.delta) / closing;
        if step < min_step {
            // Within the slop of δ: a step of the tolerance may pass a contact; a graze.
            step = min_step;
            stats.grazing += 1;
        }
        let u = (at.u + step).max(at.u.next_up());
        if u >= 1.0 {
            return if right.eta < s.delta {
                Err((right, span.time_before(at.u)))
            } else {
                Ok(())
            };
        }
        stats.looks += 1;
        let p = Probe {
            u,
            ..eta.at(span.time(u), span.poses(u), stats)
        };
        if p.eta < s.delta {
            return Err((p, span.time_before(at.u)));
        }
        at = p;
    }
}
