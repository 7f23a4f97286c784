//! The children a search node makes only when it is taken ([`super::Pending`]): a
//! re-sequencing, asked of the sequencer (and remembered: `Question`), and a
//! reconfiguration of an arm.

use super::{Node, Pending, Search};
use crate::cell::InputError;
use crate::wcp::feedback::fingerprint::fingerprint;
use crate::wcp::feedback::outcome::build;
use crate::wcp::feedback::reconfigure::{reconfigured, Reconfig};
use crate::wcp::feedback::remedies::View;
use crate::wcp::legs::default_legs;
use crate::wcp::options::SolveOptions;
use crate::wcp::prepare::{Prepared, Progress};
use crate::wcp::schedule::Collision;
use crate::wcp::sequence::sequence_with;
use crate::wcp::sequencer::{self, Conflict};
use std::collections::HashSet;
use std::sync::Arc;
use std::time::Instant;

/// A re-sequencing runs this fraction (its inverse) of the sequencer's local search.
const RESEQUENCE_SHARE: usize = 2;
/// From this many tasks on (up to [`sequencer::GRANULAR_FROM_TASKS`]), a re-sequencing is a
/// local repair: its share of the local search shrinks further to the share of the tasks
/// the two robots of the new conflict do. Each child departs from routes already searched,
/// and only those two robots' routes are wrong; a full-length search per child made
/// 12 robots x 120 tasks spend 19 s of CPU, nearly all sequencing (14.5 s now, same result).
/// Granular cells keep the full share: there the cost of a child lies elsewhere (lazy
/// rounds), and shorter searches only made more children (50 x 1000: 92 s instead of 48).
const LOCAL_RESEQUENCE_FROM_TASKS: usize = 100;
/// The fewest local-search rounds of a local repair.
const LOCAL_RESEQUENCE_MIN_ITERATIONS: usize = 8;

impl Search<'_> {
    /// The settings of a re-sequencing of `routes` forbidding `conflict`: the exact search as
    /// for the blind schedule, and a share of the local search, started from the parent's
    /// routes (a re-sequencing is one of many children; the routes it departs from were
    /// searched in full). On large cells the share scales with the tasks of the conflict's
    /// two robots (see [`LOCAL_RESEQUENCE_FROM_TASKS`]): rounds, not time, so the result
    /// stays deterministic. It aims at the collision-blind makespan
    /// ([`sequencer::SequencerOptions::target`]), which a plan under more conflicts is not
    /// expected to beat: most re-sequencings of arm cells meet it in their first restarts
    /// (4 arms x 40 tasks: 4.6 s of sequencing became 2.0 s, same answer).
    fn resequencer(&self, conflict: &Conflict, routes: &[Vec<usize>]) -> SolveOptions {
        let mut opts = crate::wcp::sequence::repairing(self.opts);
        opts.sequencer.target = Some(self.blind_makespan);
        opts.sequencer.route_exchanges = self.second_pass;
        let share = (opts.sequencer.iterations / RESEQUENCE_SHARE).max(1);
        let tasks = self.cell.tasks.len();
        let local = (LOCAL_RESEQUENCE_FROM_TASKS..sequencer::GRANULAR_FROM_TASKS).contains(&tasks);
        opts.sequencer.iterations = if local {
            let (a, b) = (conflict.a.0, conflict.b.0);
            let touched = routes[a].len() + if a == b { 0 } else { routes[b].len() };
            (share * touched / tasks).clamp(LOCAL_RESEQUENCE_MIN_ITERATIONS.min(share), share)
        } else {
            share
        };
        opts
    }

    /// Runs the re-sequencing that node `id` stands for and checks it, unless the sequencer
    /// cannot avoid every conflict or the schedule is one seen before.
    pub(super) fn cost_resequencing(
        &mut self,
        id: usize,
        conflict: Conflict,
        progress: &dyn Progress,
    ) -> Result<(), InputError> {
        // Kept sorted, so that the same set is the same question however it was reached.
        let mut conflicts = (*self.nodes[id].conflicts).clone();
        if let Err(k) = conflicts.binary_search(&conflict) {
            conflicts.insert(k, conflict);
        }
        if !self.second_pass {
            let node = &self.nodes[id];
            self.repairs.push((
                id,
                Node {
                    routes: node.routes.clone(),
                    conflicts: node.conflicts.clone(),
                    legs: node.legs.clone(),
                    robots: Vec::new(),
                    makespan: node.makespan,
                    parent: node.parent,
                    remedy: node.remedy.clone(),
                    depth: node.depth,
                    discrepancies: node.discrepancies,
                    deviated_at: node.deviated_at,
                    pending: Some(Pending::Resequence(conflict)),
                    outcome: None,
                    prepared: node.prepared.clone(),
                },
            ));
        }
        let clock = Instant::now();
        let routes = &self.nodes[id].routes;
        let asked = self.prepared_of(id) as *const Prepared as usize;
        let opts = self.resequencer(&conflict, routes);
        let iterations = opts.sequencer.iterations;
        let question = (
            routes.clone(),
            conflicts,
            asked,
            iterations,
            self.second_pass,
        );
        let solution = match self.sequenced.get(&question) {
            Some(answer) => answer.clone(),
            None => {
                let answer = sequence_with(
                    self.cell,
                    self.prepared_of(id),
                    &question.1,
                    &opts,
                    Some(routes),
                    &(),
                )?;
                if self.opts.search.remember {
                    self.sequenced.insert(question.clone(), answer.clone());
                }
                answer
            }
        };
        let conflicts = question.1;
        self.times.sequencing += clock.elapsed();
        // Robots whose routes stay keep their legs: their remedies still answer their
        // collisions.
        let mut legs = default_legs(self.cell.robots.len());
        for (r, route) in solution.sequences.iter().enumerate() {
            if *route == self.nodes[id].routes[r] {
                legs[r] = self.nodes[id].legs[r].clone();
            }
        }
        let assignment = self.prepared_of(id).moves.assignment();
        let print = fingerprint(&solution.sequences, &legs, assignment);
        if solution.violations > 0 || !self.seen.insert(print) {
            return Ok(());
        }
        let clock = Instant::now();
        let moves = &self.prepared_of(id).moves;
        let schedule = build(self.cell, &solution.sequences, &legs, moves)?;
        self.times.scheduling += clock.elapsed();
        let node = &mut self.nodes[id];
        node.routes = Arc::new(solution.sequences);
        node.conflicts = Arc::new(conflicts);
        node.legs = legs;
        node.makespan = schedule.makespan;
        node.robots = schedule.robots;
        if self.worth(id) {
            self.check_all(&[id], progress);
            if self.collision(id).is_some() {
                self.enqueue(id);
            }
        }
        Ok(())
    }

    /// Makes the reconfiguration that node `id` stands for and checks it, unless a move
    /// cannot be planned or the schedule is one seen before.
    pub(super) fn cost_reconfiguration(&mut self, id: usize, r: Reconfig, progress: &dyn Progress) {
        let clock = Instant::now();
        let node = &self.nodes[id];
        let view = View {
            routes: &node.routes,
            legs: &node.legs,
            robots: &node.robots,
        };
        let made = reconfigured(self.cell, self.prepared_of(id), &view, r);
        self.times.scheduling += clock.elapsed();
        let Some((child, prepared)) = made else {
            return;
        };
        let print = fingerprint(&node.routes, &child.legs, prepared.moves.assignment());
        if !self.seen.insert(print) {
            return;
        }
        let node = &mut self.nodes[id];
        node.legs = child.legs;
        for (r, s) in child.changed {
            node.robots[r] = s;
        }
        node.makespan = node.robots.iter().map(|s| s.end).fold(0.0, f64::max);
        node.prepared = Some(prepared);
        if self.worth(id) {
            self.check_all(&[id], progress);
            if self.collision(id).is_some() {
                self.enqueue(id);
            }
        }
    }

    /// The search's second pass, once its queue is empty or the first pass has spent its
    /// share of the budget ([`SearchOptions::second_pass_share`]) or stopped paying
    /// ([`SearchOptions::patience`]). On the way to the best
    /// certified schedule (without one, to the schedule whose collision came latest), every
    /// re-sequencing is asked again, this time exchanging route ends (2-opt*,
    /// [`SequencerOptions::route_exchanges`]), and every colliding schedule is expanded
    /// again, this time with passing places (a robot on its way pulls in beside it and lets
    /// the other pass, `remedies/step_aside.rs`); both hold for everything made from then
    /// on. Neither comes sooner: a repair that exchanges route ends spreads over more
    /// robots, whose schedules must all be checked again (4 arms x 40 tasks took 9.3 s
    /// instead of 3.9 when every repair did; asking every repair of the first pass again,
    /// 3.9 s instead of 2.8, for nothing), and passing places offered with the other
    /// remedies spread the budget thinner and cost cells of the conflict table their
    /// answers. After the first pass they only add schedules: its answer stays unless one is
    /// shorter. Whether anything was queued (nothing once the best certified schedule is as
    /// short as every schedule on its way).
    ///
    /// [`SequencerOptions::route_exchanges`]: crate::wcp::sequencer::SequencerOptions::route_exchanges
    /// [`SearchOptions::second_pass_share`]: crate::wcp::SearchOptions::second_pass_share
    /// [`SearchOptions::patience`]: crate::wcp::SearchOptions::patience
    pub(super) fn widen(&mut self) -> bool {
        if self.second_pass {
            return false;
        }
        self.second_pass = true;
        let mut line = HashSet::new();
        let mut up = self.best.or(self.furthest);
        while let Some(id) = up {
            line.insert(id);
            up = self.nodes[id].parent;
        }
        let mut queued = false;
        for (asked, node) in std::mem::take(&mut self.repairs) {
            if !line.contains(&asked) {
                continue;
            }
            let id = self.add(node);
            if self.worth(id) {
                self.enqueue(id);
                queued = true;
            }
        }
        // Without passing places or lanes a colliding schedule has no child it did not have.
        let set = self.opts.search.remedies;
        if !set.pass_aside && !set.lanes {
            return queued;
        }
        let mut again: Vec<usize> = line.into_iter().collect();
        again.sort_unstable();
        for id in again {
            // One at the limit of rounds would only be cut short again.
            let deep = self.nodes[id].depth + 1 >= self.opts.max_iterations;
            if self.collision(id).is_some() && self.worth(id) && !deep {
                self.enqueue(id);
                queued = true;
            }
        }
        queued
    }

    /// Queues `node`, a re-sequencing that forbids collision `c`'s conflict (the sequencer
    /// plans it when it is taken), if the collision is between two robots at known steps.
    pub(super) fn queue_resequencing(&mut self, node: Node, c: &Collision) {
        let (Some(b), Some(sb)) = (c.robots.1, c.segments.1) else {
            return;
        };
        let conflict = Conflict {
            a: (c.robots.0, c.segments.0.activity.step()),
            b: (b, sb.activity.step()),
        };
        let pending = self.add(Node {
            pending: Some(Pending::Resequence(conflict)),
            ..node
        });
        self.enqueue(pending);
    }
}
