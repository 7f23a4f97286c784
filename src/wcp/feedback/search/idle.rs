//! Roots with one robot fewer ([`SearchOptions::idle_roots`]): robots that share a
//! bottleneck (a door, one corridor) wait for each other at it, and a robot whose tasks the
//! others can take may cost the cell more by going than by staying home. The sequencer
//! plans without it (each of its tasks forbidden to it, as a conflict of the step with
//! itself, so that every re-sequencing below keeps it home), and the plan becomes a root of
//! the search beside the collision-blind one.
//!
//! Which robots: of those whose tasks others may all do, the plans of least makespan plus
//! mean route time. The makespan alone prefers a robot whose tasks fill the others' slack;
//! the mean route time measures the traffic the plan puts through the cell, which is what
//! a robot fewer should lessen (on the doorways of `generate --kind conflict --seed 1`, the
//! robot at the end of the row of homes, whose way to the door passes its neighbour's
//! home).
//!
//! [`SearchOptions::idle_roots`]: crate::wcp::SearchOptions::idle_roots

use super::Search;
use crate::cell::{Cell, InputError};
use crate::wcp::prepare::Progress;
use crate::wcp::sequence::{repairing, sequence_with};
use crate::wcp::sequencer::{task_node, Conflict, Solution, Step};
use rayon::prelude::*;
use std::sync::Arc;
use std::time::Instant;

/// A plan with robot `robot` at home throughout.
struct Idle {
    robot: usize,
    /// Makespan plus mean route time (s).
    score: f64,
    sequences: Vec<Vec<usize>>,
    /// The robot's tasks forbidden to it, sorted.
    bans: Vec<Conflict>,
}

/// Each task robot `r` may do, forbidden to it: a conflict of its stay there with itself.
fn bans(cell: &Cell, r: usize) -> Vec<Conflict> {
    let mut out: Vec<Conflict> = (0..cell.tasks.len())
        .filter(|&t| cell.tasks[t].robots.contains(&r))
        .map(|t| {
            let stay = (r, Step::Stay { node: task_node(t) });
            Conflict { a: stay, b: stay }
        })
        .collect();
    out.sort_unstable();
    out
}

impl Search<'_> {
    /// Adds the roots with one robot fewer that the options ask for, each checked and
    /// queued when it collides. `blind` is the collision-blind plan, where each sequencing
    /// starts.
    pub(super) fn add_idle_roots(
        &mut self,
        blind: &Solution,
        progress: &dyn Progress,
    ) -> Result<(), InputError> {
        let wanted = self.opts.search.idle_roots;
        if wanted == 0 || !self.opts.search.remedies.resequence {
            return Ok(());
        }
        let clock = Instant::now();
        let cell = self.cell;
        let spare = |r: usize| {
            !blind.sequences[r].is_empty()
                && (cell.tasks.iter())
                    .filter(|t| t.robots.contains(&r))
                    .all(|t| t.robots.len() > 1)
        };
        let candidates: Vec<usize> = (0..cell.robots.len()).filter(|&r| spare(r)).collect();
        // A repair's settings: the plan departs from the collision-blind one.
        let opts = repairing(self.opts);
        let prepared = self.prepared;
        let planned: Vec<Option<Idle>> = candidates
            .par_iter()
            .map(|&r| -> Result<Option<Idle>, InputError> {
                let bans = bans(cell, r);
                let start = Some(&blind.sequences[..]);
                let plan = sequence_with(cell, prepared, &bans, &opts, start, &())?;
                if plan.violations > 0 {
                    return Ok(None);
                }
                let mean = plan.total / cell.robots.len() as f64;
                Ok(Some(Idle {
                    robot: r,
                    score: plan.makespan + mean,
                    sequences: plan.sequences,
                    bans,
                }))
            })
            .collect::<Result<_, _>>()?;
        let mut idle: Vec<Idle> = planned.into_iter().flatten().collect();
        idle.sort_by(|a, b| a.score.total_cmp(&b.score).then(a.robot.cmp(&b.robot)));
        self.times.sequencing += clock.elapsed();
        for plan in idle.into_iter().take(wanted) {
            let Some(id) = self.add_root(&plan.sequences)? else {
                continue;
            };
            self.nodes[id].conflicts = Arc::new(plan.bans);
            self.check_all(&[id], progress);
            if self.collision(id).is_some() && self.worth(id) {
                self.enqueue(id);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::parse_cell;
    use crate::generate::{generate_conflict_cell, ConflictKind};
    use crate::wcp::{prepare, SolveOptions};

    /// A robot's tasks forbidden to it leave it at home, and the others do them all.
    #[test]
    fn a_robot_whose_tasks_are_forbidden_stays_home() {
        let text = generate_conflict_cell(ConflictKind::Doorway, 1, 0).to_string();
        let cell = parse_cell(&text, "doorway-0".as_ref()).unwrap().cell;
        let opts = SolveOptions::default();
        let prepared = prepare(&cell, &opts, &()).unwrap();
        let all = sequence_with(&cell, &prepared, &[], &opts, None, &()).unwrap();
        assert!(all.sequences.iter().all(|s| !s.is_empty()));
        let bans = bans(&cell, 0);
        assert_eq!(
            bans.len(),
            4,
            "R1 may do its own two tasks and the last robot's two"
        );
        let plan =
            sequence_with(&cell, &prepared, &bans, &opts, Some(&all.sequences), &()).unwrap();
        assert_eq!(plan.violations, 0);
        assert!(plan.sequences[0].is_empty());
        let mut done = plan.sequences.concat();
        done.sort_unstable();
        assert_eq!(done, (0..cell.tasks.len()).collect::<Vec<_>>());
    }
}
