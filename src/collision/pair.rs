//! The adaptive check of one pair of bodies (Feyeux & Landry, Table 1).

use super::eta::{Eta, Instant};
use super::{Body, Stats};
use crate::geometry::WalkTolerances;
use crate::motion::{lambda, BoundKind, Piece};
use std::sync::atomic::{AtomicU64, Ordering};

/// Settings of a pair check, in the scene's units.
#[derive(Clone, Copy, Debug)]
pub struct PairSettings {
    /// δ: closer than this is a collision.
    pub delta: f64,
    /// Grazing allowance: certificates prove distance ≥ δ − `dist_tol`.
    pub dist_tol: f64,
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
    let pieces_at = |t: f64| (a.motion.piece_at(t), b.motion.piece_at(t));
    let mut left = eta.at(grid[0], &pieces_at(grid[0]), &mut stats);
    let merged_intervals = grid.len() - 1;
    let outcome = |contact: Option<PairContact>, safe_until: f64, log, total| PairOutcome {
        contact,
        safe_until,
        merged_intervals,
        log,
        total,
    };
    if left.eta < s.delta {
        limit.lower_to(left.t);
        let contact = PairContact {
            time: left.t,
            distance: left.eta,
            interval: 1,
        };
        return outcome(Some(contact), left.t, log, stats);
    }
    for (k, &t) in grid.iter().enumerate().skip(1) {
        if left.t > limit.get() {
            return outcome(None, left.t, log, stats);
        }
        log.push((left.t, stats));
        stats.intervals += 1;
        // Both motions are linear on the merged interval: one piece each serves all of it.
        let pieces = pieces_at(0.5 * (left.t + t));
        let right = eta.at(t, &pieces, &mut stats);
        if let Err((witness, safe_until)) = adaptive(&mut eta, &pieces, left, right, s, &mut stats)
        {
            limit.lower_to(witness.t);
            let contact = PairContact {
                time: witness.t,
                distance: witness.eta,
                interval: k,
            };
            return outcome(Some(contact), safe_until, log, stats);
        }
        left = right;
    }
    outcome(None, left.t, log, stats)
}

/// Table 1 on one merged interval [l, r], both ends evaluated and l known free.
///
/// Depth-first, left half first, so the first witness (η < δ, an exact distance) found
/// after the certified prefix is the earliest contact up to `time_tol`. Returns the witness
/// and the end of the certified prefix, or `Ok` when the whole interval is certified.
fn adaptive(
    eta: &mut Eta,
    pieces: &(Piece, Piece),
    l: Instant,
    r: Instant,
    s: &PairSettings,
    stats: &mut Stats,
) -> Result<(), (Instant, f64)> {
    let (a, b) = (eta.a, eta.b);
    let mut stack = vec![(l, r)];
    while let Some((l, r)) = stack.pop() {
        let mid = 0.5 * (l.t + r.t);
        let resolved = !(l.t < mid && mid < r.t);
        if r.eta < s.delta {
            // A contact lies in (l.t, r.t]: bisect until the interval is within tolerance.
            if r.t - l.t <= s.time_tol || resolved {
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
            if lam < l.eta + r.eta - 2.0 * (s.delta - s.dist_tol) {
                continue;
            }
            if resolved {
                stats.grazing += 1;
                continue;
            }
        }
        stats.bisections += 1;
        let m = eta.at(mid, pieces, stats);
        stack.push((m, r));
        stack.push((l, m));
    }
    Ok(())
}
