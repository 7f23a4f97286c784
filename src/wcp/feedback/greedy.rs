//! The greedy loop: each round, the first collision is removed by the better of two
//! remedies, re-sequencing with the colliding steps forbidden or one robot waiting at a
//! node, and the choice is never revisited. Kept as `--feedback greedy`, to compare the
//! search against.

use super::outcome::{blockers, describe};
use super::outcome::{build, Iteration, Remedy, Solved};
use crate::cell::{Cell, InputError};
use crate::collision::{CheckReport, Verdict};
use crate::wcp::legs::Legs;
use crate::wcp::moves::MoveStore;
use crate::wcp::options::SolveOptions;
use crate::wcp::prepare::{Prepared, Progress, StageTimes};
use crate::wcp::schedule::{Activity, Collision, Delay, Schedule, Segment};
use crate::wcp::sequence::{repairing, sequence_blind, sequence_with};
use crate::wcp::sequencer::{Conflict, Solution};
use std::time::Instant;

/// Solves the cell: the loop of the module's documentation, at most
/// `opts.max_iterations` rounds.
pub fn solve(
    cell: &Cell,
    prepared: &Prepared,
    opts: &SolveOptions,
    progress: &dyn Progress,
) -> Result<Solved, InputError> {
    let clock = Instant::now();
    let blind = sequence_blind(cell, prepared, opts, progress)?;
    let mut times = prepared.times;
    times.sequencing += clock.elapsed();
    let mut greedy = Greedy {
        cell,
        prepared,
        opts,
        progress,
        times,
        routes: blind.sequences.clone(),
        delays: Vec::new(),
        conflicts: Vec::new(),
        iterations: Vec::new(),
    };
    loop {
        let round = greedy.check_round()?;
        let Some(c) = round.collision.clone() else {
            let failure = (!round.report.verdict().is_certified_free())
                .then(|| super::unresolved(&round.report));
            return Ok(greedy.finish(round, None, failure, &blind));
        };
        if greedy.iterations.len() + 1 >= opts.max_iterations {
            let failure = format!(
                "the limit of {} round{} ran out; {}; the last schedule collides: {}",
                opts.max_iterations,
                if opts.max_iterations == 1 { "" } else { "s" },
                blockers(cell, &c),
                describe(cell, &c)
            );
            return Ok(greedy.finish(round, None, Some(failure), &blind));
        }
        let Some(next) = greedy.best_remedy(&c, &round.schedule)? else {
            let failure = format!(
                "no remedy clears the collision; {}; the last schedule collides: {}",
                blockers(cell, &c),
                describe(cell, &c)
            );
            return Ok(greedy.finish(round, None, Some(failure), &blind));
        };
        greedy.iterations.push(Iteration {
            makespan: round.schedule.makespan,
            collision: Some(c),
            remedy: Some(next.remedy),
        });
        greedy.routes = next.routes;
        greedy.delays = next.delays;
    }
}

/// The loop's state: the routes and waits of the current schedule, the conflicts forbidden
/// so far and the rounds run.
struct Greedy<'a> {
    cell: &'a Cell,
    prepared: &'a Prepared,
    opts: &'a SolveOptions,
    progress: &'a dyn Progress,
    times: StageTimes,
    routes: Vec<Vec<usize>>,
    delays: Vec<Delay>,
    conflicts: Vec<Conflict>,
    iterations: Vec<Iteration>,
}

/// One round's schedule, the checker's report on it and its first collision.
struct Round {
    schedule: Schedule,
    report: CheckReport,
    collision: Option<Collision>,
}

impl Greedy<'_> {
    fn legs(&self, delays: &[Delay]) -> Legs {
        Delay::legs(self.cell.robots.len(), delays)
    }

    /// Builds and checks the current schedule.
    fn check_round(&mut self) -> Result<Round, InputError> {
        let clock = Instant::now();
        let legs = self.legs(&self.delays);
        let schedule = build(self.cell, &self.routes, &legs, &self.prepared.moves)?;
        self.times.scheduling += clock.elapsed();
        let clock = Instant::now();
        let report = schedule.check(&schedule.scene(self.cell), &self.opts.check);
        self.times.checking += clock.elapsed();
        let collision = schedule.collision(self.cell, &report);
        self.progress.iteration(
            self.iterations.len() + 1,
            schedule.makespan,
            collision.as_ref(),
        );
        if collision.is_none() && report.verdict().is_certified_free() {
            self.progress.certified(schedule.makespan);
        }
        Ok(Round {
            schedule,
            report,
            collision,
        })
    }

    /// Candidates: re-sequencing with the colliding steps forbidden together, or one of the
    /// two robots waiting until the other's activity is over. The smaller makespan wins;
    /// re-sequencing wins ties, since it removes the conflict rather than timing around it.
    /// None when the collision is with an obstacle or no candidate clears it.
    fn best_remedy(
        &mut self,
        c: &Collision,
        schedule: &Schedule,
    ) -> Result<Option<Candidate>, InputError> {
        let (Some(b), Some(seg_b)) = (c.robots.1, c.segments.1) else {
            return Ok(None);
        };
        let (cell, moves) = (self.cell, &self.prepared.moves);
        let a = c.robots.0;
        let mut best: Option<Candidate> = None;
        self.conflicts.push(Conflict {
            a: (a, c.segments.0.activity.step()),
            b: (b, seg_b.activity.step()),
        });
        let clock = Instant::now();
        let resequenced = sequence_with(
            cell,
            self.prepared,
            &self.conflicts,
            &repairing(self.opts),
            None,
            self.progress,
        )?;
        self.times.sequencing += clock.elapsed();
        if resequenced.violations == 0 {
            best = Some(Candidate {
                makespan: resequenced.makespan,
                remedy: Remedy::RESEQUENCE,
                routes: resequenced.sequences,
                delays: Vec::new(),
            });
        }
        let clock = Instant::now();
        for (x, seg_x, seg_y) in [(a, c.segments.0, seg_b), (b, seg_b, c.segments.0)] {
            let y = if x == a { b } else { a };
            let Some(full) = delay_until(
                &schedule.robots[x].segments,
                x,
                seg_x.leg,
                schedule.robots[y].left(&seg_y),
            ) else {
                continue;
            };
            let delay = shortest_delay(
                cell,
                &self.routes,
                &self.delays,
                moves,
                full,
                y,
                seg_x.end,
                self.opts,
            )?;
            let mut candidate = self.delays.clone();
            candidate.push(delay);
            let makespan = build(cell, &self.routes, &self.legs(&candidate), moves)?.makespan;
            if best.as_ref().is_none_or(|b| makespan < b.makespan) {
                best = Some(Candidate {
                    makespan,
                    remedy: Remedy::wait(delay),
                    routes: self.routes.clone(),
                    delays: candidate,
                });
            }
        }
        self.times.scheduling += clock.elapsed();
        Ok(best)
    }

    /// The result: `round` is the last round, recorded with `remedy` (none: the loop ends on
    /// it), and `failure` says why it is not collision-free, if it is not.
    fn finish(
        mut self,
        round: Round,
        remedy: Option<Remedy>,
        failure: Option<String>,
        blind: &Solution,
    ) -> Solved {
        self.iterations.push(Iteration {
            makespan: round.schedule.makespan,
            collision: round.collision,
            remedy,
        });
        Solved {
            nodes: self.iterations.len(),
            found_after: failure.is_none().then_some(self.iterations.len()),
            collision_free: failure.is_none(),
            legs: self.legs(&self.delays),
            routes: self.routes,
            schedule: round.schedule,
            report: round.report,
            iterations: self.iterations,
            blind_routes: blind.sequences.clone(),
            blind_makespan: blind.makespan,
            blind_optimal: blind.optimal,
            failure,
            assignment: self.prepared.moves.assignment().clone(),
            times: self.times,
            shortenings_refused: 0,
        }
    }
}

/// A way out of a collision, and the makespan it leads to.
struct Candidate {
    makespan: f64,
    remedy: Remedy,
    routes: Vec<Vec<usize>>,
    delays: Vec<Delay>,
}

/// Fractions of the full delay tried before it, shortest first. Waiting until the other
/// robot's activity is over clears this conflict, but often by far more than needed.
const DELAY_FRACTIONS: [f64; 3] = [0.125, 0.25, 0.5];

/// The shortest of the tried fractions of `full` after which the two robots no longer meet
/// while the delayed robot's conflicting activity (`segment_end`, shifted by the wait) lasts,
/// nor meet later with one of them back home; `full` if none of them does.
#[allow(clippy::too_many_arguments)]
fn shortest_delay(
    cell: &Cell,
    routes: &[Vec<usize>],
    delays: &[Delay],
    moves: &MoveStore,
    full: Delay,
    other: usize,
    segment_end: f64,
    opts: &SolveOptions,
) -> Result<Delay, InputError> {
    for fraction in DELAY_FRACTIONS {
        let delay = Delay {
            duration: fraction * full.duration,
            ..full
        };
        let mut trial = delays.to_vec();
        trial.push(delay);
        let schedule = build(cell, routes, &Delay::legs(cell.robots.len(), &trial), moves)?;
        let report = schedule.check(&schedule.pair_scene(cell, full.robot, other), &opts.check);
        // The pair must not meet while the conflicting activity lasts, nor later with one of
        // them already home for good: no wait could separate them then.
        let cleared = match report.verdict() {
            Verdict::Contact { contact: c, .. } => {
                let done =
                    |r: usize| schedule.robots[r].segment_at(c.time).activity == Activity::Done;
                c.time >= segment_end + delay.duration && !done(full.robot) && !done(other)
            }
            verdict => verdict.is_certified_free(),
        };
        if cleared {
            return Ok(delay);
        }
    }
    Ok(full)
}

/// A wait that makes robot `x` start move `m` when the other robot's activity ends.
fn delay_until(segments: &[Segment], x: usize, m: Option<usize>, other_end: f64) -> Option<Delay> {
    let m = m?;
    let (start, nodes) = segments.iter().find_map(|s| match s.activity {
        Activity::Move { from, to } if s.leg == Some(m) => Some((s.start, (from, to))),
        _ => None,
    })?;
    let duration = other_end - start;
    (duration.is_finite() && duration > 0.0).then_some(Delay {
        robot: x,
        before_move: m,
        nodes,
        duration,
    })
}
