//! The roots of the search: the collision-blind plan, and its anytime refinements. With time
//! left under a time limit once the search has run out of nodes, the sequencer searches on
//! from the collision-blind plan, and a shorter plan becomes a new root of the search
//! (checked, and searched when it collides). When asked, plans with one robot fewer are
//! roots too, from the start (`idle.rs`).

use super::{Node, Search};
use crate::cell::InputError;
use crate::wcp::feedback::fingerprint::fingerprint;
use crate::wcp::feedback::outcome::build;
use crate::wcp::legs::default_legs;
use crate::wcp::prepare::Progress;
use crate::wcp::sequence::sequence_with;
use crate::wcp::sequencer::Solution;
use std::sync::Arc;
use std::time::Instant;

impl Search<'_> {
    /// Adds a root: `sequences` with every robot on its default legs, timed, not checked yet;
    /// none when that schedule was seen before.
    pub(super) fn add_root(
        &mut self,
        sequences: &[Vec<usize>],
    ) -> Result<Option<usize>, InputError> {
        let legs = default_legs(self.cell.robots.len());
        let moves = &self.prepared.moves;
        if !self
            .seen
            .insert(fingerprint(sequences, &legs, moves.assignment()))
        {
            return Ok(None);
        }
        let timed = build(self.cell, sequences, &legs, moves)?;
        Ok(Some(self.add(Node {
            routes: Arc::new(sequences.to_vec()),
            conflicts: Arc::new(Vec::new()),
            legs,
            makespan: timed.makespan,
            robots: timed.robots,
            parent: None,
            remedy: None,
            depth: 0,
            discrepancies: 0,
            deviated_at: 0,
            pending: None,
            outcome: None,
            prepared: None,
        })))
    }

    /// Refines the collision-blind plan until the time limit (the first sequencing got only
    /// a share of it, see [`sequence_blind`](crate::wcp::sequence::sequence_blind)), when the
    /// sequencer may search beyond one epoch, the limit leaves time and the search has not
    /// stopped for want of progress. A shorter plan, unlike any before, becomes `blind` and
    /// a new root: checked now, and queued when it collides and may still beat the best
    /// certified schedule. Whether there is such a root to search.
    pub(super) fn refine(
        &mut self,
        blind: &mut Solution,
        progress: &dyn Progress,
    ) -> Result<bool, InputError> {
        let Some(deadline) = self.deadline() else {
            return Ok(false);
        };
        if self.opts.sequencer.effort <= 1 || self.stalled() || Instant::now() >= deadline {
            return Ok(false);
        }
        let clock = Instant::now();
        let refined = sequence_with(
            self.cell,
            self.prepared,
            &[],
            self.opts,
            Some(&blind.sequences),
            progress,
        )?;
        self.times.sequencing += clock.elapsed();
        if refined.makespan >= blind.makespan || refined.sequences == blind.sequences {
            return Ok(false);
        }
        *blind = refined;
        let Some(id) = self.add_root(&blind.sequences)? else {
            return Ok(false);
        };
        self.check_all(&[id], progress);
        let searched = self.collision(id).is_some() && self.worth(id);
        if searched {
            self.enqueue(id);
        }
        Ok(searched)
    }
}
