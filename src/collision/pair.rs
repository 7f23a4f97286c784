//! The adaptive check of one pair of bodies (Feyeux & Landry, Table 1).

use super::eta::{Eta, Probe};
use super::grid::MergedGrid;
use super::{adaptive, advance, sampled, Method};
use super::{Body, Stats};
use crate::geometry::WalkTolerances;
use crate::motion::Pose;
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
    /// How each merged interval is searched.
    pub method: Method,
    /// Start of the horizon: the sampled method looks at start + k·step.
    pub start: f64,
    /// Narrow-phase tolerances.
    pub walk: WalkTolerances,
    /// Work budget of the pair: evaluations of η (merged interval ends, bisections, looks).
    pub max_work: u64,
}

impl PairSettings {
    /// Whether the pair has done all the work it may (see [`PairSettings::max_work`]).
    pub fn out_of_work(&self, stats: &Stats) -> bool {
        stats.intervals + stats.bisections + stats.looks >= self.max_work
    }
}

/// Why a search of a merged interval stopped before its end.
#[derive(Clone, Copy, Debug)]
pub(super) enum Stop {
    /// A witness closer than δ, and the end of the certified prefix before it.
    Contact(Probe, f64),
    /// The work budget ran out; the prefix up to this time is certified.
    OutOfWork(f64),
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
    /// Whether the work budget ran out at `safe_until`, neither proof nor witness beyond.
    pub out_of_work: bool,
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
#[cfg(feature = "parry-peer")]
pub(super) fn merged_grid(a: &Body, b: &Body, horizon: (f64, f64)) -> Vec<f64> {
    MergedGrid::new(a, b, horizon).map(|(t, _)| t).collect()
}

/// What one thread reuses from pair to pair.
#[derive(Default)]
pub struct Scratch {
    /// The bisection stack of the adaptive method.
    stack: Vec<(Probe, Probe)>,
}

/// One merged interval: both poses are linear in time between its ends.
///
/// Points inside it are addressed by a parameter u in [0, 1], not by time: the poses
/// are interpolated between the ends directly, so bisection keeps its resolution even where
/// time stamps are huge or an interval is a single unit in the last place long.
pub(super) struct Span {
    pub t0: f64,
    pub t1: f64,
    pub a: (Pose, Pose),
    pub b: (Pose, Pose),
}

impl Span {
    pub fn time(&self, u: f64) -> f64 {
        if u == 1.0 {
            self.t1
        } else {
            self.t0 + u * (self.t1 - self.t0)
        }
    }

    /// The time at `u` and the error of that f64 against the exact t0 + u·(t1 − t0), by
    /// error-free transformations (TwoSum, FMA): positive when the f64 is early.
    fn time_and_error(&self, u: f64) -> (f64, f64) {
        let two_sum = |x: f64, y: f64| {
            let s = x + y;
            let yy = s - x;
            (s, (x - (s - yy)) + (y - yy))
        };
        let (d, d_err) = two_sum(self.t1, -self.t0);
        let p = u * d;
        let p_err = u.mul_add(d, -p);
        let (t, t_err) = two_sum(self.t0, p);
        (t, t_err + p_err + u * d_err)
    }

    /// The least f64 time not before the instant at `u`: a contact reported there is never
    /// earlier than its witness, even where the time stamps are huge.
    pub fn time_after(&self, u: f64) -> f64 {
        match u {
            0.0 => self.t0,
            1.0 => self.t1,
            _ => match self.time_and_error(u) {
                (t, e) if e > 0.0 => t.next_up(),
                (t, _) => t,
            },
        }
    }

    /// The greatest f64 time not after the instant at `u`: the end of a certified prefix.
    pub fn time_before(&self, u: f64) -> f64 {
        match u {
            0.0 => self.t0,
            1.0 => self.t1,
            _ => match self.time_and_error(u) {
                (t, e) if e < 0.0 => t.next_down(),
                (t, _) => t,
            },
        }
    }

    pub fn poses(&self, u: f64) -> (Pose, Pose) {
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
#[cfg(test)]
pub fn check_pair(
    a: &Body,
    b: &Body,
    horizon: (f64, f64),
    s: &PairSettings,
    limit: &SharedLimit,
    scratch: &mut Scratch,
) -> PairOutcome {
    match PairCheck::start(a, b, horizon, s, limit) {
        Started::Running(pair) => pair.finish(s, limit, scratch),
        Started::Done(done) => done,
    }
}

/// A pair check evaluated at the horizon's start and not yet further: a scene starts every
/// pair before it runs any, so that a contact at the start stops all of them there.
pub struct PairCheck<'a> {
    grid: MergedGrid<'a>,
    eta: Eta<'a>,
    stats: Stats,
    left: Probe,
}

/// A pair after [`PairCheck::start`].
pub enum Started<'a> {
    /// Free at the start: the check goes on.
    Running(PairCheck<'a>),
    /// In contact at the start: its outcome.
    Done(PairOutcome),
}

fn outcome(
    contact: Option<PairContact>,
    safe_until: f64,
    log: Vec<(f64, Stats)>,
    total: Stats,
    reached: usize,
    rest: MergedGrid,
) -> PairOutcome {
    PairOutcome {
        contact,
        safe_until,
        out_of_work: false,
        // Counting the intervals not examined walks the rest of the grid, without poses.
        merged_intervals: reached + rest.count_rest(),
        log,
        total,
    }
}

fn contact(limit: &SharedLimit, p: &Probe, interval: usize) -> Option<PairContact> {
    limit.lower_to(p.t);
    Some(PairContact {
        time: p.t,
        distance: p.eta,
        interval,
    })
}

impl<'a> PairCheck<'a> {
    /// Evaluates the pair at the horizon's start; its outcome when it is in contact there.
    pub fn start(
        a: &'a Body,
        b: &'a Body,
        horizon: (f64, f64),
        s: &PairSettings,
        limit: &SharedLimit,
    ) -> Started<'a> {
        let mut grid = MergedGrid::new(a, b, horizon);
        let mut eta = Eta::new(a, b, s.delta, s.walk);
        let mut stats = Stats::default();
        let (t, poses) = grid.next().expect("a grid holds the horizon's start");
        let left = eta.at(t, poses, &mut stats);
        if left.eta < s.delta {
            return Started::Done(outcome(
                contact(limit, &left, 1),
                left.t,
                Vec::new(),
                stats,
                0,
                grid,
            ));
        }
        Started::Running(PairCheck {
            grid,
            eta,
            stats,
            left,
        })
    }

    /// The rest of the check, from the horizon's start.
    pub fn finish(
        self,
        s: &PairSettings,
        limit: &SharedLimit,
        scratch: &mut Scratch,
    ) -> PairOutcome {
        let PairCheck {
            mut grid,
            mut eta,
            mut stats,
            mut left,
        } = self;
        // Pairs that stop at an early contact log a few intervals: grow as needed.
        let mut log = Vec::new();
        // Merged intervals whose right end the grid has given.
        let mut reached = 0;
        while let Some((t, poses)) = grid.next() {
            reached += 1;
            if left.t > limit.get() {
                return outcome(None, left.t, log, stats, reached, grid);
            }
            let k = reached;
            log.push((left.t, stats));
            stats.intervals += 1;
            let right = eta.at(t, poses, &mut stats);
            let span = Span {
                t0: left.t,
                t1: t,
                a: (left.pose_a, right.pose_a),
                b: (left.pose_b, right.pose_b),
            };
            let ends = (Probe { u: 0.0, ..left }, Probe { u: 1.0, ..right });
            let searched = match s.method {
                Method::Adaptive(bound) => {
                    let stack = &mut scratch.stack;
                    adaptive::search(&mut eta, &span, ends, bound, s, stack, &mut stats)
                }
                Method::Sampled { step } => {
                    sampled::search(&mut eta, &span, ends, step, s, &mut stats)
                }
                Method::Advance => advance::search(&mut eta, &span, ends, s, &mut stats),
            };
            match searched {
                Ok(()) => {}
                Err(Stop::Contact(witness, safe_until)) => {
                    // Never report a contact before its witness.
                    let witness = Probe {
                        t: span.time_after(witness.u),
                        ..witness
                    };
                    let found = contact(limit, &witness, k);
                    return outcome(found, safe_until, log, stats, k, grid);
                }
                Err(Stop::OutOfWork(safe_until)) => {
                    // Nothing after this can be the scene's first event: no pair need look on.
                    limit.lower_to(safe_until);
                    return PairOutcome {
                        out_of_work: true,
                        ..outcome(None, safe_until, log, stats, k, grid)
                    };
                }
            }
            left = right;
        }
        outcome(None, left.t, log, stats, reached, grid)
    }
}
