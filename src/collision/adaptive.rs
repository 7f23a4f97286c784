//! Table 1 of Feyeux & Landry on one merged interval: certify or bisect.

use super::eta::Eta;
use super::span::{PairSettings, Probe, Span, Stop};
use super::Stats;
use crate::motion::BoundKind;

/// A lower bound of the distance over [l, r] from its convexity (second certificate).
///
/// Under the relative translation w of the interval, the disc gap |G_b − G_a| − Ra − Rb is
/// convex in time whatever the bodies' rotations, and so is the exact distance of the two
/// bodies frozen in their orientation at either end. A convex function lies above its
/// tangents; the tangent's slope is the separation direction times w. Rotation moves no
/// point farther than ρ = Ra·|Δθa| + Rb·|Δθb| over the interval, which tilts the exact
/// tangents by ρ. This certifies in one step bodies that glide past each other close to δ,
/// or spin far from everything, where the first-order condition needs ever finer splits.
fn convexity_bound(l: &Probe, r: &Probe, radii: (f64, f64), feature_tol: f64) -> f64 {
    let w = (r.pose_b.pos - l.pose_b.pos) - (r.pose_a.pos - l.pose_a.pos);
    let (f0, n0, f1, n1, rho) = if l.exact && r.exact {
        let rho = radii.0 * (r.pose_a.theta - l.pose_a.theta).abs()
            + radii.1 * (r.pose_b.theta - l.pose_b.theta).abs();
        (l.eta, l.normal, r.eta, r.normal, rho)
    } else {
        let disc = |p: &Probe| {
            let c = p.pose_b.pos - p.pose_a.pos;
            (c.norm() - radii.0 - radii.1, c / c.norm())
        };
        let ((f0, n0), (f1, n1)) = (disc(l), disc(r));
        (f0, n0, f1, n1, 0.0)
    };
    let (s0, s1) = (n0.dot(&w) - rho, n1.dot(&w) + rho);
    let above_tangents = |u: f64| (f0 + s0 * u).max(f1 - s1 * (1.0 - u));
    let mut low = above_tangents(0.0).min(above_tangents(1.0));
    let crossing = (f1 - s1 - f0) / (s0 - s1);
    if (0.0..=1.0).contains(&crossing) {
        low = low.min(above_tangents(crossing));
    }
    // The walk's separation direction is exact to its Voronoi slack (an angle).
    low - 10.0 * feature_tol * w.norm()
}

/// How much finer than the time tolerance the grazes met just before a contact are searched
/// again: a pair closing in on a contact cannot be proven δ apart on the last intervals
/// before it at the time tolerance, but can at a finer one.
const GRAZE_REFINEMENT: f64 = 1024.0;

/// Table 1 on one merged interval, both ends evaluated and the left one known free.
///
/// Depth-first, left half first, so the first witness (η < δ, an exact distance) found
/// after the certified prefix is the earliest contact up to `time_tol`. Returns the witness
/// and the end of the certified prefix, or `Ok` when the whole interval is certified.
///
/// A graze (no proof of δ, no witness, on an interval shorter than the time tolerance) is
/// accepted only once no contact follows it within the interval. A pair closing in on a
/// contact grazes just before it: a witness within a time tolerance of the first such graze
/// is reported with the prefix before the graze, which is proven, and the contact is still
/// within the time tolerance of the true first one; a witness farther away has the grazes
/// before it searched again [`GRAZE_REFINEMENT`] times finer, which proves them or finds an
/// earlier contact in them.
pub(super) fn search(
    eta: &mut Eta,
    span: &Span,
    ends: (Probe, Probe),
    bound: BoundKind,
    s: &PairSettings,
    stack: &mut Vec<(Probe, Probe)>,
    stats: &mut Stats,
) -> Result<(), Stop> {
    search_with(eta, span, ends, bound, s, stack, stats, Grazes::Refine)
}

/// What a search does with the grazes it meets.
enum Grazes<'g> {
    /// Before a contact, searches them again finer ([`PendingGrazes::refine`]).
    Refine,
    /// Hands them over when no contact follows in the interval: a refining search decides.
    Collect(&'g mut Vec<f64>),
}

/// [`search`], refining the grazes before a contact or collecting them, as `mode` says.
///
/// One loop over the stack of intervals, read top to bottom as the paper's cases of an
/// interval (out of work, no geometry, contact, certified, graze, unresolved, bisect): kept
/// whole so that each case's `continue` or return stays in sight of the others.
#[allow(clippy::too_many_arguments)]
fn search_with(
    eta: &mut Eta,
    span: &Span,
    ends: (Probe, Probe),
    bound: BoundKind,
    s: &PairSettings,
    stack: &mut Vec<(Probe, Probe)>,
    stats: &mut Stats,
    mut mode: Grazes,
) -> Result<(), Stop> {
    let (a, b) = (eta.a, eta.b);
    let duration = span.t1 - span.t0;
    let radii = (a.shape.radius(), b.shape.radius());
    stack.clear();
    // The whole interval first, without a trip through the stack (two probes are large).
    let mut whole = Some(ends);
    let mut grazes = PendingGrazes::default();
    while let Some((l, r)) = whole.take().or_else(|| stack.pop()) {
        if s.out_of_work(stats) {
            // Everything before `l` is proven (grazes aside).
            grazes.accept(stats);
            return Err(Stop::OutOfWork(span.time_before(l.u)));
        }
        let mid = 0.5 * (l.u + r.u);
        let resolved = !(l.u < mid && mid < r.u);
        if l.eta.is_nan() || r.eta.is_nan() {
            // No finite geometry to reason about; the CLI turns this into an input error.
            stats.unresolved += 1;
            continue;
        }
        if r.eta < s.delta {
            if let Some(start) = grazes.within(span.time_after(r.u), s.time_tol) {
                return Err(Stop::Contact(r, start));
            }
            // A contact lies in (l, r]: bisect until the interval is within tolerance.
            if (r.u - l.u) * duration <= s.time_tol || resolved {
                let refined = match mode {
                    Grazes::Refine => grazes.refine(eta, span, bound, s, stats, r.u)?,
                    // A contact inside a graze being refined: those before it stay grazes.
                    Grazes::Collect(_) => {
                        grazes.accept(stats);
                        None
                    }
                };
                return Err(Stop::Contact(r, refined.unwrap_or(span.time_before(l.u))));
            }
        } else {
            // Schwarzer-Saha-Latombe: for s in [0, 1], d(l + s·h) ≥ max(η(l) − sλ, η(r) − (1 − s)λ)
            // ≥ (η(l) + η(r) − λ) / 2, so λ1 + λ2 < η(l) + η(r) − 2δ keeps the pair δ apart.
            let lam = eta.lambda(bound, span, &l, &r);
            let first_order = (l.eta + r.eta - lam) / 2.0;
            if first_order >= s.delta {
                continue;
            }
            // The paper's method has only the first-order certificate. A link's frame does
            // not move linearly: it is held to the linear motion between its ends, less
            // how far its origin may stray from the chord.
            let low = match bound {
                BoundKind::Rigorous if !span.has_links() => {
                    first_order.max(convexity_bound(&l, &r, radii, s.walk.feature_tol))
                }
                BoundKind::Rigorous => {
                    let linear = convexity_bound(&l, &r, radii, s.walk.feature_tol);
                    first_order.max(linear - span.chord_error(l.u, r.u))
                }
                BoundKind::Paper => first_order,
            };
            if low >= s.delta {
                stats.convexity_certificates += 1;
                continue;
            }
            if (r.u - l.u) * duration <= s.time_tol && low >= s.delta - s.grazing_tol {
                // Within the time tolerance and within the allowance of δ, with no witness:
                // a graze. Splitting on would cost ever more where a body turns at exactly δ.
                grazes.add((l, r), span.time_before(l.u));
                continue;
            }
            if resolved {
                // One step of f64 moves a body farther than the allowance: coordinates far too
                // large for δ, which `cell::check_precision` refuses.
                stats.unresolved += 1;
                continue;
            }
        }
        stats.bisections += 1;
        let m = eta.at(span.time(mid), span.poses(mid), stats);
        stack.push((Probe { u: mid, ..m }, r));
        stack.push((l, Probe { u: mid, ..m }));
    }
    match &mut mode {
        Grazes::Refine => grazes.accept(stats),
        Grazes::Collect(out) => grazes.hand_over(span, out),
    }
    Ok(())
}

/// The grazes met since the last proof, in time order, not yet accepted.
#[derive(Default)]
struct PendingGrazes {
    /// Where the first of them starts.
    start: f64,
    intervals: Vec<(Probe, Probe)>,
}

impl PendingGrazes {
    /// A graze on `interval`, which starts at time `t`.
    fn add(&mut self, interval: (Probe, Probe), t: f64) {
        if self.intervals.is_empty() {
            self.start = t;
        }
        self.intervals.push(interval);
    }

    /// The start of the pending grazes, when a witness at `t` is within `time_tol` of it:
    /// they are then part of the contact, not grazes.
    fn within(&mut self, t: f64, time_tol: f64) -> Option<f64> {
        if self.intervals.is_empty() || t - self.start > time_tol {
            return None;
        }
        self.intervals.clear();
        Some(self.start)
    }

    /// No contact follows: the pending grazes are accepted.
    fn accept(&mut self, stats: &mut Stats) {
        stats.grazing += self.intervals.len() as u64;
        self.intervals.clear();
    }

    /// Where each pending graze starts, handed over to a refining search (see [`Grazes`]).
    fn hand_over(&mut self, span: &Span, out: &mut Vec<f64>) {
        out.extend(self.intervals.drain(..).map(|(l, _)| span.time_before(l.u)));
    }

    /// A contact follows, its witness at `witness` of the span, farther than a time tolerance from the
    /// first graze: searches each graze again at a finer time tolerance. A witness in one of
    /// them is an earlier contact. The finer grazes that start within a time tolerance of
    /// the witness are part of its contact, as in [`PendingGrazes::within`]: the first of
    /// them, if any, is returned as the end of the proven prefix; the others are accepted.
    fn refine(
        &mut self,
        eta: &mut Eta,
        span: &Span,
        bound: BoundKind,
        s: &PairSettings,
        stats: &mut Stats,
        witness: f64,
    ) -> Result<Option<f64>, Stop> {
        let witness = span.time_after(witness);
        let fine = PairSettings {
            time_tol: s.time_tol / GRAZE_REFINEMENT,
            ..*s
        };
        let (mut stack, mut finer) = (Vec::new(), Vec::new());
        for interval in std::mem::take(&mut self.intervals) {
            let collect = Grazes::Collect(&mut finer);
            search_with(
                eta, span, interval, bound, &fine, &mut stack, stats, collect,
            )?;
        }
        // `finer` is in time order: the grazes are searched in order, each left first.
        let near = finer.iter().position(|&g| witness - g <= s.time_tol);
        stats.grazing += near.unwrap_or(finer.len()) as u64;
        Ok(near.map(|k| finer[k]))
    }
}
