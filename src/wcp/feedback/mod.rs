//! The loop of the Work-Cell Problem: sequence, schedule, check, feed the first collision
//! back, until the schedule is collision-free.
//!
//! Two ways to feed a collision back: [`Feedback::Search`] (the default) searches over
//! remedies best-first on makespan, in the manner of conflict-based search (see
//! `search/`); [`Feedback::Greedy`] takes the best of two remedies each round and never
//! looks back (see `greedy.rs`), kept to compare against.

mod clearing;
mod fingerprint;
mod greedy;
mod outcome;
mod reconfigure;
mod remedies;
mod search;

pub use outcome::{
    describe, place, uncertified, unresolved, Iteration, Remedy, RemedyKind, RemedyLeg, Shortened,
    Shortening, Solved, TunedHold, HEMMED_IN,
};

use super::choose::choose_configurations;
use super::options::{Feedback, SolveOptions};
use super::prepare::{Prepared, Progress};
use crate::cell::{Cell, InputError};
use std::time::Instant;

/// Solves the cell: sequences it collision-blind, then feeds collisions back as
/// `opts.feedback` says, until the checker certifies a schedule or the limits are reached.
///
/// ```
/// use workcell::wcp::{prepare, solve, SolveOptions};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
/// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
/// let opts = SolveOptions::default();
/// let solved = solve(&cell, &prepare(&cell, &opts, &())?, &opts, &())?;
/// assert!(solved.collision_free && solved.report.verdict().is_certified_free());
/// // Collisions cost time: the final makespan is no shorter than the collision-blind one.
/// assert!(solved.schedule.makespan >= solved.blind_makespan);
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn solve(
    cell: &Cell,
    prepared: &Prepared,
    opts: &SolveOptions,
    progress: &dyn Progress,
) -> Result<Solved, InputError> {
    let clock = Instant::now();
    let chosen = choose_configurations(cell, prepared, opts, progress)?;
    let choosing = clock.elapsed();
    let prepared = chosen.as_ref().unwrap_or(prepared);
    let mut solved = match opts.feedback {
        Feedback::Greedy => greedy::solve(cell, prepared, opts, progress),
        Feedback::Search => search::solve(cell, prepared, opts, progress),
    }?;
    // Choosing configurations is sequencing, with the moves it plans.
    solved.times.sequencing += choosing;
    // The sequencer proves routes optimal for the configurations it is given, not the
    // choice of configurations.
    let found = prepared.moves.assignment().configurations();
    let choice =
        (0..cell.robots.len()).any(|r| (0..cell.tasks.len()).any(|t| found.at(r, t).len() > 1));
    solved.blind_optimal &= !choice;
    Ok(solved)
}
