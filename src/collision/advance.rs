//! Conservative advancement on one merged interval (the time of impact of Box2D and FCL).

use super::eta::Eta;
use super::span::{PairSettings, Probe, Span, Stop};
use super::{adaptive, Stats};
use crate::motion::BoundKind;

/// From the free left end, steps forward by (η − δ) / λ', λ' bounding how far the pair can
/// close in per unit of the interval: the pose is linear on it, so over a fraction u of the
/// interval no point moves farther than u·λ (rigorous λ). The first look closer than δ is
/// the contact. Returns the witness and the time of the last free look.
///
/// No step is shorter than the time tolerance (Box2D's target slop, as a time), or a pair
/// gliding at δ would be advanced forever. Such a step proves nothing by itself: Table 1
/// (`adaptive`) searches it, which proves it, finds the contact in it, or accepts it as a
/// graze on its own terms (distance provably above δ·(1 − grazing allowance)).
pub(super) fn search(
    eta: &mut Eta,
    span: &Span,
    (left, right): (Probe, Probe),
    s: &PairSettings,
    stats: &mut Stats,
) -> Result<(), Stop> {
    let closing = eta.lambda(BoundKind::Rigorous, span, &left, &right);
    let min_step = s.time_tol / (span.t1 - span.t0);
    let mut stack = Vec::new();
    let mut at = left;
    loop {
        if at.eta.is_nan() || right.eta.is_nan() {
            stats.unresolved += 1;
            return Ok(());
        }
        if s.out_of_work(stats) {
            return Err(Stop::OutOfWork(span.time_before(at.u)));
        }
        let step = (at.eta - s.delta) / closing;
        let slop = step < min_step;
        let u = (at.u + step.max(min_step)).max(at.u.next_up());
        let next = if u >= 1.0 {
            right
        } else {
            stats.looks += 1;
            Probe {
                u,
                ..eta.at(span.time(u), span.poses(u), stats)
            }
        };
        if slop {
            adaptive::search(
                eta,
                span,
                (at, next),
                BoundKind::Rigorous,
                s,
                &mut stack,
                stats,
            )?;
        } else if next.eta < s.delta {
            return Err(Stop::Contact(next, span.time_before(at.u)));
        }
        if u >= 1.0 {
            return Ok(());
        }
        at = next;
    }
}
