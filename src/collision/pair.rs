//! The check of one pair of bodies: its merged intervals in time order, each searched by the
//! method (Feyeux & Landry, Table 1, by default).

use super::broad_phase::Windows;
use super::eta::Eta;
use super::grid::MergedGrid;
use super::method::{Method, Scratch};
use super::run_ahead::RunAhead;
use super::span::{LinkEnds, PairSettings, Probe, Span, Stop};
use super::{Body, Stats};
use crate::motion::Motion;
use std::sync::atomic::{AtomicU64, Ordering};

/// A contact found on one pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairContact {
    /// A time at which the exact distance is below δ, at most `time_tol` after the first.
    pub time: f64,
    /// The exact distance at `time`.
    pub distance: f64,
    /// 1-based index of the merged interval that holds `time`.
    pub interval: usize,
    /// For bodies made of parts, the part of each nearest the other at `time` (a convex
    /// body is its part 0); `None` for two convex bodies.
    pub parts: Option<(usize, usize)>,
}

/// What the check of one pair found.
#[derive(Clone, Copy, Debug)]
pub struct PairOutcome {
    /// The pair's first contact, if it has one before the shared limit.
    pub contact: Option<PairContact>,
    /// End of the prefix certified free of contact.
    pub safe_until: f64,
    /// Whether the work budget ran out at `safe_until`, neither proof nor witness beyond.
    pub out_of_work: bool,
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
#[cfg(feature = "parry-peer")]
pub(super) fn merged_grid(a: &Body, b: &Body, horizon: (f64, f64)) -> Vec<f64> {
    MergedGrid::new(a, b, horizon).map(|(t, _)| t).collect()
}

/// Checks one pair over the horizon (in its `windows` only, when given), merged interval by
/// merged interval, stopping at its first contact or at the first interval that starts
/// after `limit`.
#[cfg(test)]
#[allow(clippy::too_many_arguments)]
pub fn check_pair(
    a: &Body,
    b: &Body,
    horizon: (f64, f64),
    method: Method,
    s: &PairSettings,
    limit: &SharedLimit,
    scratch: &mut Scratch,
    windows: Option<Windows>,
) -> PairOutcome {
    PairCheck::start(a, b, horizon, s, limit, windows).finish(method, s, limit, scratch)
}

/// One pair's check: evaluated at the horizon's start by [`PairCheck::start`], run on by
/// [`PairCheck::finish`], and asked for its counters once the scene's first event is known.
/// A scene starts every pair before it runs any, so that a contact at the start stops all of
/// them there; each pair's state stays in place from its start to the report.
pub struct PairCheck<'a> {
    grid: MergedGrid<'a>,
    eta: Eta<'a>,
    /// All the work done so far.
    stats: Stats,
    /// The left end of the next merged interval, free.
    left: Probe,
    /// Merged intervals whose right end the grid has given.
    reached: usize,
    /// `(start of merged interval, counters before it)` for every interval examined but the
    /// first: that one starts at the horizon's start, at or before any time asked about.
    /// Without every counter ([`PairSettings::counters`]), only for those after which the
    /// grazes or unresolved intervals changed, and the last.
    log: Vec<(f64, Stats)>,
    /// What the check found, once it is over.
    found: Option<PairOutcome>,
    /// Where the pair may come within δ (`None`: anywhere); merged intervals outside are
    /// proven free by the broad phase's boxes and skipped.
    windows: Option<Windows>,
    /// The first window that has not ended before the interval being examined.
    window: usize,
}

fn contact(limit: &SharedLimit, eta: &mut Eta, p: &Probe, interval: usize) -> Option<PairContact> {
    limit.lower_to(p.t);
    Some(PairContact {
        time: p.t,
        distance: p.eta,
        interval,
        parts: eta.closest_parts((p.pose_a, p.pose_b)),
    })
}

/// The outcome of a pair whose check stopped in its `interval`-th merged interval.
fn stopped(limit: &SharedLimit, eta: &mut Eta, stop: Stop, interval: usize) -> PairOutcome {
    match stop {
        Stop::Contact(witness, safe_until) => PairOutcome {
            contact: contact(limit, eta, &witness, interval),
            safe_until,
            out_of_work: false,
        },
        Stop::OutOfWork(safe_until) => {
            // Nothing after this can be the scene's first event: no pair need look on.
            limit.lower_to(safe_until);
            PairOutcome {
                contact: None,
                safe_until,
                out_of_work: true,
            }
        }
    }
}

impl<'a> PairCheck<'a> {
    /// Evaluates the pair at the horizon's start; the check is over when it is in contact
    /// there.
    pub fn start(
        a: &'a Body,
        b: &'a Body,
        horizon: (f64, f64),
        s: &PairSettings,
        limit: &SharedLimit,
        windows: Option<Windows>,
    ) -> Self {
        let mut grid = MergedGrid::new(a, b, horizon);
        let mut eta = Eta::new(a, b, s.delta, s.walk);
        let mut stats = Stats::default();
        let (t, poses) = grid.next().expect("a grid holds the horizon's start");
        let left = eta.at(t, poses, &mut stats);
        let found = (left.eta < s.delta).then(|| PairOutcome {
            contact: contact(limit, &mut eta, &left, 1),
            safe_until: left.t,
            out_of_work: false,
        });
        PairCheck {
            grid,
            eta,
            stats,
            left,
            reached: 0,
            log: Vec::new(),
            found,
            windows,
            window: 0,
        }
    }

    /// The rest of the check, from the horizon's start, each merged interval searched by
    /// `method`; what it found.
    pub fn finish(
        &mut self,
        method: Method,
        s: &PairSettings,
        limit: &SharedLimit,
        scratch: &mut Scratch,
    ) -> PairOutcome {
        if self.found.is_none() {
            // Links, checked by the default method, run ahead of their probes; the loop is
            // compiled apart for them, so that rigid pairs carry none of it.
            let links = self.eta.a.link().is_some() || self.eta.b.link().is_some();
            self.found = Some(match method == Method::DEFAULT && links {
                true => self.run::<true>(method, s, limit, scratch),
                false => self.run::<false>(method, s, limit, scratch),
            });
        }
        self.found.expect("set above")
    }

    fn run<const AHEAD: bool>(
        &mut self,
        method: Method,
        s: &PairSettings,
        limit: &SharedLimit,
        scratch: &mut Scratch,
    ) -> PairOutcome {
        let PairCheck {
            grid,
            eta,
            stats,
            left,
            reached,
            log,
            windows,
            window,
            ..
        } = self;
        let free = |safe_until| PairOutcome {
            contact: None,
            safe_until,
            out_of_work: false,
        };
        let mut ahead = AHEAD.then(RunAhead::default);
        // Whether `left` holds only its time: the intervals before were skipped.
        let mut stale = false;
        loop {
            let afters = grid.afters();
            let Some(t) = grid.next_time() else {
                break;
            };
            *reached += 1;
            let from = ahead.as_ref().map_or(left.t, |a| a.from(left));
            if from > limit.get() {
                return free(from);
            }
            if let Some(w) = windows.as_deref() {
                if !examines(w, window, left.t, t) {
                    left.t = t;
                    stale = true;
                    continue;
                }
            }
            let k = *reached;
            if k > 1 {
                record(log, (from, *stats), s.counters);
            }
            stats.intervals += 1;
            if std::mem::take(&mut stale) {
                // The skipped stretch ends here, proven free by the boxes: the interval
                // starts from a fresh evaluation.
                let fresh = eta.at(left.t, grid.poses_with(afters, left.t), stats);
                if fresh.eta < s.delta {
                    return stopped(limit, eta, Stop::Contact(fresh, fresh.t), k);
                }
                *left = fresh;
            }
            if let Some(ahead) = &mut ahead {
                match ahead.step(eta, grid, left, (afters, t), s, stats) {
                    Ok(true) => continue,
                    Ok(false) => {}
                    Err(stop) => return stopped(limit, eta, stop, k),
                }
            }
            let poses = grid.poses(t);
            let right = eta.at(t, poses, stats);
            let links = links_of(eta.a, eta.b, afters, left.t, t);
            let span = Span {
                t0: left.t,
                t1: t,
                a: (left.pose_a, right.pose_a),
                b: (left.pose_b, right.pose_b),
                links: links.as_ref(),
            };
            let ends = (Probe { u: 0.0, ..*left }, Probe { u: 1.0, ..right });
            match method.search(eta, &span, ends, s, scratch, stats) {
                Ok(()) => {}
                Err(Stop::Contact(witness, safe_until)) => {
                    // Never report a contact before its witness.
                    let t = span.time_after(witness.u);
                    let stop = Stop::Contact(Probe { t, ..witness }, safe_until);
                    return stopped(limit, eta, stop, k);
                }
                Err(stop) => return stopped(limit, eta, stop, k),
            }
            *left = right;
        }
        free(ahead.as_ref().map_or(left.t, |a| a.from(left)))
    }

    /// What the check found, once [`PairCheck::finish`] ran or the start was a contact.
    pub fn outcome(&self) -> PairOutcome {
        self.found.expect("a pair check over")
    }

    /// The work done on the merged intervals that start at or before `t`, a time at or after
    /// the horizon's start. When `t` is the scene's first event, this does not depend on how
    /// the pairs were scheduled on threads: every pair examines those intervals whatever the
    /// others found. Without every counter ([`PairSettings::counters`]), only the grazes
    /// and unresolved intervals are those through `t`; the rest may count later work.
    pub fn stats_through(&self, t: f64) -> Stats {
        through(&self.log, self.stats, t)
    }

    /// Number of merged intervals of the pair over the whole horizon. Counting those not
    /// examined walks the rest of the grid, without poses: only reports that list pairs ask.
    pub fn merged_intervals(&self) -> usize {
        self.reached + self.grid.clone().count_rest()
    }
}

/// Records `entry`, the start of a merged interval and the counters before it, in `log`.
/// With every counter, each; else only grazes and unresolved intervals are asked for through
/// a time, and a record after which neither changed is replaced.
fn record(log: &mut Vec<(f64, Stats)>, entry: (f64, Stats), counters: bool) {
    let now = &entry.1;
    let changed = |(_, before): &(f64, Stats)| {
        (before.grazing, before.unresolved) != (now.grazing, now.unresolved)
    };
    match log.last_mut() {
        Some(last) if !counters && !changed(last) => *last = entry,
        _ => log.push(entry),
    }
}

/// The counters through time `t` from `log` (see [`record`]): those before the first
/// interval that starts after `t`, else all of them (`total`).
fn through(log: &[(f64, Stats)], total: Stats, t: f64) -> Stats {
    match log.iter().find(|(start, _)| *start > t) {
        Some((_, before)) => *before,
        None => total,
    }
}

/// Whether the merged interval `[t0, t1]` overlaps a window of `w` by more than a point:
/// else it lies in chunks proven δ apart, its ends included. `next` is the first window
/// that has not ended at `t0`, moved on as time goes forward.
#[inline]
fn examines(w: &[(f64, f64)], next: &mut usize, t0: f64, t1: f64) -> bool {
    while w.get(*next).is_some_and(|&(_, end)| end <= t0) {
        *next += 1;
    }
    w.get(*next).is_some_and(|&(start, _)| start < t1)
}

/// The joints at both ends of `[t0, t1]` of each body that is a link of an arm, given how
/// many samples of each body lie at or before `t0`; `None` for a pair of rigid bodies.
#[inline]
fn links_of<'s>(
    a: &'s Body,
    b: &'s Body,
    afters: (usize, usize),
    t0: f64,
    t1: f64,
) -> Option<[Option<LinkEnds<'s>>; 2]> {
    match (&a.motion, &b.motion) {
        (Motion::Link(_), _) | (_, Motion::Link(_)) => Some(links_of_arms(a, b, afters, t0, t1)),
        _ => None,
    }
}

#[inline(never)]
#[cold]
fn links_of_arms<'s>(
    a: &'s Body,
    b: &'s Body,
    (after_a, after_b): (usize, usize),
    t0: f64,
    t1: f64,
) -> [Option<LinkEnds<'s>>; 2] {
    let link = |body: &'s Body, after: usize| match &body.motion {
        Motion::Link(l) => Some(LinkEnds::new(l, after, t0, t1)),
        _ => None,
    };
    [link(a, after_a), link(b, after_b)]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Without every counter, the log is short and still says how many grazes and unresolved
    /// intervals came through any time, as the full log does.
    #[test]
    fn a_lean_log_keeps_the_grazes_through_any_time() {
        // Intervals 2..=9 start at t = 1, 2, ...; interval k does k bisections, a graze in
        // intervals 3 and 6, an unresolved one in 8.
        let (mut full, mut lean) = (Vec::new(), Vec::new());
        let mut stats = Stats::default();
        for k in 2..=9u64 {
            let entry = ((k - 1) as f64, stats);
            record(&mut full, entry, true);
            record(&mut lean, entry, false);
            stats.intervals += 1;
            stats.bisections += k;
            stats.grazing += u64::from(k == 3 || k == 6);
            stats.unresolved += u64::from(k == 8);
        }
        assert_eq!(full.len(), 8);
        assert!(lean.len() < 5, "{}", lean.len());
        for t in (0..20).map(|k| 0.5 * k as f64) {
            let (a, b) = (through(&full, stats, t), through(&lean, stats, t));
            assert_eq!(
                (a.grazing, a.unresolved),
                (b.grazing, b.unresolved),
                "t = {t}"
            );
        }
        // The full log has every counter through a time: interval 2's 2 bisections.
        assert_eq!(through(&full, stats, 1.5).bisections, 2);
    }
}
