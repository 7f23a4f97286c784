//! The adaptive check of one pair of bodies (Feyeux & Landry, Table 1).

use super::eta::{Eta, Probe};
use super::{Body, Stats};
use crate::geometry::WalkTolerances;
use crate::motion::{lambda, BoundKind, Pose};
use std::sync::atomic::{AtomicU64, Ordering};

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
    /// Which λ.
    pub bound: BoundKind,
    /// Narrow-phase tolerances.
    pub walk: WalkTolerances,
}

/// A contact found on one pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairContact {
    /// A time at which the exact distance is below δ, at most `time_tol` after the first.
    pub time: f64,
    /// The exact distance at `time`.
    pub distance: f64,
    /// 1-based index of the merged interval that holds `time`.
    pub interval: usize,
}

/// What the check of one pair found.
#[derive(Clone, Debug)]
pub struct PairOutcome {
    /// The pair's first contact, if it has one before the shared limit.
    pub contact: Option<PairContact>,
    /// End of the prefix certified free of contact.
    pub safe_until: f64,
    /// Number of merged intervals of the pair over the whole horizon.
    pub merged_intervals: usize,
    /// `(start of merged interval, counters before it)`, for every interval examined.
    log: Vec<(f64, Stats)>,
    /// All the work done.
    total: Stats,
}

impl PairOutcome {
    /// The work done on the merged intervals that start at or before `t`. When `t` is the
    /// scene's first contact, this does not depend on how the pairs were scheduled on
    /// threads: every pair examines those intervals whatever the others found.
    pub fn stats_through(&self, t: f64) -> Stats {
        match self.log.iter().find(|(start, _)| *start > t) {
            Some((_, before)) => *before,
            None => self.total,
        }
    }
}

/// The earliest contact time found so far by any pair, shared between threads: once a
/// contact at t is known, no pair needs to look past t.
pub struct SharedLimit(AtomicU64);

impl SharedLimit {
    pub fn new() -> Self {
        SharedLimit(AtomicU64::new(f64::INFINITY.to_bits()))
    }

    pub fn get(&self) -> f64 {
        f64::from_bits(self.0.load(Ordering::Relaxed))
    }

    pub fn lower_to(&self, t: f64) {
        let _ = self
            .0
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |bits| {
                (t < f64::from_bits(bits)).then_some(t.to_bits())
            });
    }
}

/// Union of both bodies' sample times within the horizon, with the horizon's ends: on each
/// interval between consecutive grid times both poses are linear in time.
fn merged_grid(a: &Body, b: &Body, (t0, t1): (f64, f64)) -> Vec<f64> {
    let mut grid: Vec<f64> = a
        .motion
        .times()
        .chain(b.motion.times())
        .filter(|&t| t > t0 && t < t1)
        .chain([t0, t1])
        .collect();
    grid.sort_by(f64::total_cmp);
    grid.dedup();
    grid
}

/// One merged interval: both poses are linear in time between its ends.
///
/// Points inside it are addressed by a parameter u in [0, 1], not by time: the poses
/// are interpolated between the ends directly, so bisection keeps its resolution even where
/// time stamps are huge or an interval is a single unit in the last place long.
struct Span {
    t0: f64,
    t1: f64,
    a: (Pose, Pose),
    b: (Pose, Pose),
}

impl Span {
    fn time(&self, u: f64) -> f64 {
        if u == 1.0 {
            self.t1
        } else {
            self.t0 + u * (self.t1 - self.t0)
        }
    }

    fn poses(&self, u: f64) -> (Pose, Pose) {
        (lerp(&self.a, u), lerp(&self.b, u))
    }
}

fn lerp((p, q): &(Pose, Pose), u: f64) -> Pose {
    Pose {
        pos: p.pos + (q.pos - p.pos) * u,
        theta: p.theta + (q.theta - p.theta) * u,
    }
}

/// Checks one pair over the horizon, merged interval by merged interval, stopping at its
/// first contact or at the first interval that starts after `limit`.
pub fn check_pair(
    a: &Body,
    b: &Body,
    horizon: (f64, f64),
    s: &PairSettings,
    limit: &SharedLimit,
) -> PairOutcome {
    let grid = merged_grid(a, b, horizon);
    let mut eta = Eta::new(a, b, s.delta, s.walk);
    let mut stats = Stats::default();
    let mut log = Vec::with_capacity(grid.len());
    // Bisection stack, reused by every merged interval of the pair.
    let mut stack = Vec::new();
    let poses_at = |t: f64| (a.motion.pose_at(t), b.motion.pose_at(t));
    let mut left = eta.at(grid[0], poses_at(grid[0]), &mut stats);
    let merged_intervals = grid.len() - 1;
    let outcome = |contact: Option<PairContact>, safe_until: f64, log, total| PairOutcome {
        contact,
        safe_until,
        merged_intervals,
        log,
        total,
    };
    let contact = |p: &Probe, interval| {
        limit.lower_to(p.t);
        Some(PairContact {
            time: p.t,
            distance: p.eta,
            interval,
        })
    };
    if left.eta < s.delta {
        return outcome(contact(&left, 1), left.t, log, stats);
    }
    for (k, &t) in grid.iter().enumerate().skip(1) {
        if left.t > limit.get() {
            return outcome(None, left.t, log, stats);
        }
        log.push((left.t, stats));
        stats.intervals += 1;
        let right = eta.at(t, poses_at(t), &mut stats);
        let span = Span {
            t0: left.t,
            t1: t,
            a: (left.pose_a, right.pose_a),
            b: (left.pose_b, right.pose_b),
        };
        let ends = (Probe { u: 0.0, ..left }, Probe { u: 1.0, ..right });
        if let Err((witness, safe_until)) =
            adaptive(&mut eta, &span, ends, s, &mut stack, &mut stats)
        {
            return outcome(contact(&witness, k), safe_until, log, stats);
        }
        left = right;
    }
    outcome(None, left.t, log, stats)
}

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

/// Table 1 on one merged interval, both ends evaluated and the left one known free.
///
/// Depth-first, left half first, so the first witness (η < δ, an exact distance) found
/// after the certified prefix is the earliest contact up to `time_tol`. Returns the witness
/// and the end of the certified prefix, or `Ok` when the whole interval is certified.
fn adaptive(
    eta: &mut Eta,
    span: &Span,
    ends: (Probe, Probe),
    s: &PairSettings,
    stack: &mut Vec<(Probe, Probe)>,
    stats: &mut Stats,
) -> Result<(), (Probe, f64)> {
    let (a, b) = (eta.a, eta.b);
    let duration = span.t1 - span.t0;
    let radii = (a.shape.radius(), b.shape.radius());
    stack.clear();
    stack.push(ends);
    while let Some((l, r)) = stack.pop() {
        let mid = 0.5 * (l.u + r.u);
        let resolved = !(l.u < mid && mid < r.u);
        if l.eta.is_nan() || r.eta.is_nan() {
            // No finite geometry to reason about; the CLI turns this into an input error.
            stats.unresolved += 1;
            continue;
        }
        if r.eta < s.delta {
            // A contact lies in (l, r]: bisect until the interval is within tolerance.
            if (r.u - l.u) * duration <= s.time_tol || resolved {
                return Err((r, l.t));
            }
        } else {
            // Schwarzer-Saha-Latombe: for s in [0, 1], d(l + s·h) ≥ max(η(l) − sλ, η(r) − (1 − s)λ)
            // ≥ (η(l) + η(r) − λ) / 2, so λ1 + λ2 < η(l) + η(r) − 2δ keeps the pair δ apart.
            let lam = lambda(
                s.bound,
                &a.motion,
                a.shape.radius(),
                (l.t, &l.pose_a),
                (r.t, &r.pose_a),
            ) + lambda(
                s.bound,
                &b.motion,
                b.shape.radius(),
                (l.t, &l.pose_b),
                (r.t, &r.pose_b),
            );
            let first_order = (l.eta + r.eta - lam) / 2.0;
            if first_order >= s.delta {
                continue;
            }
            // The paper's method has only the first-order certificate.
            let low = match s.bound {
                BoundKind::Rigorous => {
                    first_order.max(convexity_bound(&l, &r, radii, s.walk.feature_tol))
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
                stats.grazing += 1;
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
    Ok(())
}
