//! What the search answers with: the best certified node, or else the one that got
//! furthest with what was exhausted and who blocks whom; and the result made of it.

use super::{Outcome, Search};
use crate::wcp::feedback::outcome::{Iteration, Solved};
use crate::wcp::schedule::Schedule;
use crate::wcp::sequencer;

impl Search<'_> {
    /// The node the search answers with, and why it is not collision-free if it is not: the
    /// best certified node, or else the one that got furthest, with what was exhausted
    /// (`stop`: the budget that ended the search, none when it ran out of nodes), the robots
    /// that block each other and where.
    pub(super) fn outcome(&self, stop: Option<String>) -> (usize, Option<String>) {
        if let Some(id) = self.best {
            return (id, None);
        }
        // No node collides and none is certified: the first schedule itself could be
        // neither proven free nor shown to collide.
        let Some(id) = self.furthest else {
            let report = &self.nodes[0].outcome.as_ref().expect("checked").report;
            return (0, Some(crate::wcp::feedback::unresolved(report)));
        };
        let c = self.collision(id).expect("a colliding node");
        let max_iterations = self.opts.max_iterations;
        let deepest = (self.nodes.iter())
            .filter(|n| n.outcome.is_some())
            .map(|n| n.depth)
            .max()
            .unwrap_or(0);
        let exhausted = match stop {
            Some(budget) => format!("{budget} ran out"),
            None if self.second_pass_end.is_some() => format!(
                "the first pass spent its share of the search's budget ({} of {} schedules), \
                 and the second pass tried every remedy along the way that got furthest ({} \
                 schedules checked in all)",
                self.first_pass_budget(),
                self.opts.search.max_nodes,
                self.checked
            ),
            None if self.capped > 0 => format!(
                "the limit of {max_iterations} round{} cut {} line{} of remedies short, and \
                 every other remedy was tried",
                if max_iterations == 1 { "" } else { "s" },
                self.capped,
                if self.capped == 1 { "" } else { "s" }
            ),
            None if deepest == 0 => "no remedy clears the first schedule's collision".to_owned(),
            None => format!(
                "every remedy was tried ({} schedules checked, over up to {deepest} round{})",
                self.checked,
                if deepest == 1 { "" } else { "s" }
            ),
        };
        let failure = format!(
            "{exhausted}; {}; the schedule that got furthest collides: {}",
            crate::wcp::feedback::outcome::blockers(self.cell, c),
            crate::wcp::feedback::describe(self.cell, c)
        );
        (id, Some(failure))
    }

    /// The result for node `id`: its schedule, and the rounds from the root to it.
    pub(super) fn finish(
        self,
        id: usize,
        failure: Option<String>,
        blind: &sequencer::Solution,
    ) -> Solved {
        let mut path = vec![id];
        while let Some(p) = self.nodes[*path.last().unwrap()].parent {
            path.push(p);
        }
        path.reverse();
        let iterations = path
            .iter()
            .enumerate()
            .map(|(k, &n)| Iteration {
                makespan: self.nodes[n].makespan,
                collision: self.collision(n).cloned(),
                remedy: path
                    .get(k + 1)
                    .and_then(|&next| self.nodes[next].remedy.clone()),
            })
            .collect();
        let node = &self.nodes[id];
        let outcome = node.outcome.as_ref().expect("checked");
        let schedule = Schedule::of(node.robots.clone());
        // An answer that is not free was checked for its robots only: its report is that of
        // the whole schedule, as the user checks it.
        let report = match outcome.whole {
            true => outcome.report.clone(),
            false => Outcome::of(self.cell, &schedule, &self.opts.check, true, &[]).report,
        };
        Solved {
            routes: (*node.routes).clone(),
            legs: node.legs.clone(),
            schedule,
            collision_free: failure.is_none(),
            report,
            iterations,
            blind_routes: blind.sequences.clone(),
            blind_makespan: blind.makespan,
            blind_optimal: blind.optimal,
            failure,
            assignment: self.prepared_of(id).moves.assignment().clone(),
            times: self.times,
            nodes: self.checked,
            found_after: self.best.map(|_| self.best_at),
            shortenings_refused: self.shortenings_refused,
        }
    }
}
