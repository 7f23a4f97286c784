//! Feedback as a search over remedies, in the manner of conflict-based search (Sharon et
//! al., "Conflict-based search for optimal multi-agent pathfinding", 2015).
//!
//! A search node is a schedule: routes, the conflicts the sequencer must avoid, and every
//! robot's legs. Every node is checked when it is made (`verdict.rs`: a root whole; any
//! other node's robots against each other, as every motion it adds is certified clear of the
//! fixtures when made, from where its parent's check left off, and whole once found free).
//! A node whose schedule collides branches into its children, one per way out of that
//! collision: either robot yielding by each remedy of `remedies/` (each the least of its
//! kind that clears the pair), or the sequencer re-planning with the two colliding steps
//! forbidden together. A re-sequencing
//! child is costed lazily: it waits in the queue, and the sequencer runs only when it comes
//! out. A remedy's last resort (a detour round the other side of a loop, a robot making way
//! ahead of another) is made at once but checked only when it comes out. A reconfiguration
//! (when asked) is costed lazily too: an arm of the pair in another configuration at a task
//! (`reconfigure.rs`); the node then carries the preparation of its configurations, which
//! its own children inherit.
//!
//! The order is that of limited discrepancy search (Harvey & Ginsberg, 1995), with the
//! makespan as the heuristic: a node's children are ranked by makespan (then by how late
//! their first collision comes), and a child other than the first is a *discrepancy*. Nodes
//! with fewer discrepancies go first; among equals, those whose last discrepancy is nearest
//! the root, then the deepest (depth first), then the smallest makespan. So the search first
//! dives along the best child at every step to a certified schedule, after about as many
//! rounds as there are conflicts, never a growing pile of waits (every child clears the
//! collision it answers); then it dives again from each other choice, the choices near the
//! root first, where a poor choice costs most. Nodes that cannot beat the best certified
//! makespan are dropped. When none is left, or once the first pass has checked its share
//! of the budget (all but [`SearchOptions::second_pass_share`] of it) or stopped paying
//! ([`SearchOptions::patience`]; either way the rest of its queue is dropped), a second
//! pass goes back along the way to the best: its re-sequencings are asked again with
//! route-end exchanges, and its colliding schedules expanded again with passing places
//! (`pending.rs`); it ends when its share of the budget is spent, or when nothing is left,
//! and then the answer is the best the remedies can give.
//! When the search ends, every schedule that was the best when found has its slack (waits,
//! holds, slowed motions) shortened as far as the other robots allow (`tighten.rs`), and the
//! answer is the shortest of them. Ties go to the node made first, so that the result is
//! the same on every run and on any number of threads: children are made and checked in
//! parallel and collected in a fixed order.
//!
//! The budgets are a number of schedules checked and a time limit (a safety stop: a run
//! that reaches it may differ from run to run). Without any certified schedule, the search
//! reports the schedule whose first collision came latest, and that collision.
//!
//! [`SearchOptions::second_pass_share`]: crate::wcp::SearchOptions::second_pass_share
//! [`SearchOptions::patience`]: crate::wcp::SearchOptions::patience

mod answer;
mod budget;
mod draft;
mod give_way;
mod idle;
mod order;
mod pending;
mod queue;
mod roots;
mod shorten;
mod straighten;
mod tighten;
mod verdict;

use super::fingerprint::{fingerprint, pair_fingerprint};
use super::outcome::{Remedy, Solved};
use super::reconfigure::{self, reconfigurations, Reconfig};
use super::remedies::{candidates, Child, Ctx, View};
use crate::cell::{Cell, InputError};
use crate::collision::CheckReport;
use crate::wcp::legs::{default_legs, Legs};
use crate::wcp::options::SolveOptions;
use crate::wcp::prepare::{Prepared, Progress, StageTimes};
use crate::wcp::schedule::{Collision, RobotSchedule};
use crate::wcp::sequence::sequence_blind;
use crate::wcp::sequencer::{self, Conflict};
use order::Key;
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap, HashSet};
use std::sync::Arc;
use std::time::Instant;

/// One schedule of the search.
struct Node {
    routes: Arc<Vec<Vec<usize>>>,
    conflicts: Arc<Vec<Conflict>>,
    legs: Legs,
    /// The timed robots; empty while a re-sequencing child waits to be costed.
    robots: Vec<Arc<RobotSchedule>>,
    /// The schedule's makespan; for a re-sequencing not yet run, a lower bound of it.
    makespan: f64,
    parent: Option<usize>,
    /// How the parent became this node.
    remedy: Option<Remedy>,
    depth: usize,
    /// Choices other than the best child on the way from the root.
    discrepancies: usize,
    /// Depth of the last of them (0 for none).
    deviated_at: usize,
    /// What the node stands for, not made yet: a re-sequencing or a reconfiguration.
    pending: Option<Pending>,
    /// The checker's verdict, once checked.
    outcome: Option<Outcome>,
    /// The preparation whose arm configurations the node takes, when an arm was
    /// reconfigured on the way from the root (else the search's).
    prepared: Option<Arc<Prepared>>,
}

#[cfg(test)]
impl Node {
    /// A child of `parent` with the routes, legs and timed robots given, made by hand (no
    /// remedy, no discrepancy): what the unit tests check and shorten.
    fn by_hand(
        parent: usize,
        routes: &[Vec<usize>],
        legs: Legs,
        robots: Vec<Arc<RobotSchedule>>,
    ) -> Node {
        Node {
            routes: Arc::new(routes.to_vec()),
            conflicts: Arc::new(Vec::new()),
            legs,
            makespan: robots.iter().map(|s| s.end).fold(0.0, f64::max),
            robots,
            parent: Some(parent),
            remedy: None,
            depth: 1,
            discrepancies: 0,
            deviated_at: 0,
            pending: None,
            outcome: None,
            prepared: None,
        }
    }
}

/// A child made only when the search takes it.
enum Pending {
    /// The parent re-sequenced with this conflict added.
    Resequence(Conflict),
    /// The parent with an arm reconfigured.
    Reconfigure(Reconfig),
    /// A last resort of the remedies ([`Child::last_resort`]), made but checked only when
    /// taken: a discrepancy that spends none of the budget unless the search gets to it.
    Check,
}

/// The checker's verdict on a node.
struct Outcome {
    report: CheckReport,
    collision: Option<Collision>,
    /// Whether the fixtures were in the check (see [`Search::check_all`]).
    whole: bool,
}

/// What a node's schedule is, by the checker.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Status {
    /// Certified collision-free: a candidate answer.
    Free,
    /// Two bodies collide: the node is expanded.
    Collides,
    /// Neither proven free nor shown to collide (a graze of δ, the checker's work budget):
    /// a dead end, reported as the greedy loop reports it when nothing better is found.
    Undecided,
}

/// Two makespans closer than this (relative) are the same: a node must beat the bound by
/// more to be worth checking.
const SAME_MAKESPAN: f64 = 1e-9;

/// What a re-sequencing asks the sequencer, which answers it deterministically: the routes
/// it departs from, the conflicts to avoid (sorted), the preparation whose configurations
/// it plans with (its address: every preparation lives as long as the search, held by the
/// nodes), the rounds of local search it is given and whether it exchanges route ends (see
/// [`Search::resequencer`]). Parents whose routes agree and whose legs differ ask the same
/// question: a third of the re-sequencings of a 4-arm cell of 40 tasks.
type Question = (Arc<Vec<Vec<usize>>>, Vec<Conflict>, usize, usize, bool);

/// A collision as the remedies see it: a digest of every route and of the two robots' legs
/// (in the pair's order), the preparation's address, the contact's time, and whether the
/// pair met before on the branch. The remedies read only the routes and the two robots'
/// legs and schedules (a robot's schedule follows from its route and legs), so nodes that
/// differ in a third robot, or that reached the same two robots' legs by different
/// branches, and then meet the same collision get the same children: 45 % of the
/// expansions of a junction of 4 robots and 8 tasks (28 % when schedules were known by
/// address only). A convoy reads the other robots' routes too, and replaces their legs
/// whole.
type Met = (u128, usize, u64, bool, bool);

struct Search<'a> {
    cell: &'a Cell,
    prepared: &'a Prepared,
    opts: &'a SolveOptions,
    nodes: Vec<Node>,
    queue: BinaryHeap<Reverse<Key>>,
    seen: HashSet<u128>,
    /// The sequencer's answers by question, for re-sequencings asked again.
    sequenced: HashMap<Question, sequencer::Solution>,
    /// The remedies' children by collision, for a collision met again (see [`Met`]).
    remedied: HashMap<Met, Vec<Child>>,
    times: StageTimes,
    checked: usize,
    /// The collision-blind plan's makespan: what a re-sequencing waits in the queue at.
    blind_makespan: f64,
    /// The certified node of least makespan so far.
    best: Option<usize>,
    /// Schedules checked when it was found.
    best_at: usize,
    /// Every node that was the best certified one when found, in order, with the schedules
    /// checked by then.
    incumbents: Vec<(usize, usize)>,
    /// The colliding node whose first collision came latest.
    furthest: Option<usize>,
    /// Colliding nodes left unexpanded at the limit of rounds.
    capped: usize,
    /// The re-sequencings costed so far, each by the node it became and as it was queued:
    /// asked again with route-end exchanges once the queue is empty
    /// ([`Search::widen`]).
    repairs: Vec<(usize, Node)>,
    /// Whether the search is in its second pass ([`Search::widen`]): re-sequencings
    /// exchange route ends, and a robot on its way may pull in at a passing place.
    second_pass: bool,
    /// The schedules checked by which the second pass ends, once the first pass was cut
    /// with nodes still queued (its share of the budget spent, or its patience): the
    /// second's share after that.
    second_pass_end: Option<usize>,
    /// Shortened answers the whole check refused (see [`Solved::shortenings_refused`]).
    shortenings_refused: usize,
}

/// Solves the cell by searching over remedies (see the module documentation).
pub(super) fn solve(
    cell: &Cell,
    prepared: &Prepared,
    opts: &SolveOptions,
    progress: &dyn Progress,
) -> Result<Solved, InputError> {
    let mut times = prepared.times;
    let clock = Instant::now();
    let mut blind = sequence_blind(cell, prepared, opts, progress)?;
    times.sequencing += clock.elapsed();
    let mut search = Search::new(cell, prepared, opts, times, blind.makespan);
    let root = search.add_root(&blind.sequences)?.expect("the first node");
    search.check_all(&[root], progress);
    if search.collision(root).is_some() {
        search.enqueue(root);
        search.add_idle_roots(&blind, progress)?;
    }
    let started = Instant::now();
    let mut stop = search.run(started, progress)?;
    // With time left under a time limit: a refined plan, searched in turn; once nothing is
    // left, the second pass along the way to the best.
    while stop.is_none() && (search.refine(&mut blind, progress)? || search.widen()) {
        stop = search.run(started, progress)?;
    }
    search.tighten_all(progress);
    let (id, failure) = search.outcome(stop);
    Ok(search.finish(id, failure, &blind))
}

impl<'a> Search<'a> {
    /// A search with no node yet, `times` spent before it.
    fn new(
        cell: &'a Cell,
        prepared: &'a Prepared,
        opts: &'a SolveOptions,
        times: StageTimes,
        blind_makespan: f64,
    ) -> Self {
        Search {
            cell,
            prepared,
            opts,
            nodes: Vec::new(),
            queue: BinaryHeap::new(),
            seen: HashSet::new(),
            sequenced: HashMap::new(),
            remedied: HashMap::new(),
            times,
            checked: 0,
            blind_makespan,
            best: None,
            best_at: 0,
            incumbents: Vec::new(),
            furthest: None,
            capped: 0,
            repairs: Vec::new(),
            second_pass: false,
            second_pass_end: None,
            shortenings_refused: 0,
        }
    }
}

impl Search<'_> {
    /// Takes nodes from the queue until it is empty or a budget is spent (which one, then).
    fn run(
        &mut self,
        started: Instant,
        progress: &dyn Progress,
    ) -> Result<Option<String>, InputError> {
        while let Some(Reverse((.., id))) = self.queue.pop() {
            let stop = self.budget_spent(started);
            if stop.is_some() || self.second_pass_spent() {
                return Ok(stop);
            }
            if self.first_pass_spent() || self.stalled() {
                // The second pass's share of the budget from here: what the first pass
                // left queued waits no longer.
                self.second_pass_end = Some(self.checked + self.second_pass_budget());
                self.queue.clear();
                return Ok(None);
            }
            if !self.worth(id) {
                continue;
            }
            match self.nodes[id].pending.take() {
                // Costed and checked now; queued again to be expanded if it collides.
                Some(Pending::Resequence(conflict)) => {
                    self.cost_resequencing(id, conflict, progress)?;
                    continue;
                }
                Some(Pending::Reconfigure(r)) => {
                    self.cost_reconfiguration(id, r, progress);
                    continue;
                }
                Some(Pending::Check) => {
                    self.check_all(&[id], progress);
                    if self.collision(id).is_some() {
                        self.enqueue(id);
                    }
                    continue;
                }
                None => {}
            }
            if self.nodes[id].depth + 1 < self.opts.max_iterations {
                self.expand(id, progress);
            } else {
                self.capped += 1;
            }
        }
        Ok(None)
    }

    /// The preparation node `id` works with.
    fn prepared_of(&self, id: usize) -> &Prepared {
        self.nodes[id].prepared.as_deref().unwrap_or(self.prepared)
    }

    fn add(&mut self, node: Node) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    fn collision(&self, id: usize) -> Option<&Collision> {
        self.nodes[id].outcome.as_ref()?.collision.as_ref()
    }

    /// Whether node `id` may still beat the best certified schedule.
    fn worth(&self, id: usize) -> bool {
        self.best.is_none_or(|b| {
            let bound = self.nodes[b].makespan;
            self.nodes[id].makespan < bound * (1.0 - SAME_MAKESPAN)
        })
    }

    /// Whether the two robots of collision `c` of node `id` collided in an ancestor of it
    /// too: a pair whose remedies did not keep it apart.
    fn met_before(&self, id: usize, c: &Collision) -> bool {
        let pair = |c: &Collision| {
            let (a, b) = (c.robots.0, c.robots.1?);
            Some((a.min(b), a.max(b)))
        };
        let Some(this) = pair(c) else {
            return false;
        };
        let mut up = self.nodes[id].parent;
        while let Some(p) = up {
            let theirs = self.collision(p).and_then(pair);
            if theirs == Some(this) {
                return true;
            }
            up = self.nodes[p].parent;
        }
        false
    }

    /// Makes, checks and queues the children of colliding node `id`.
    fn expand(&mut self, id: usize, progress: &dyn Progress) {
        let clock = Instant::now();
        let node = &self.nodes[id];
        let c = node
            .outcome
            .as_ref()
            .and_then(|o| o.collision.clone())
            .expect("only colliding nodes are queued");
        let view = View {
            routes: &node.routes,
            legs: &node.legs,
            robots: &node.robots,
        };
        let own = node.prepared.clone();
        let prepared = self.prepared_of(id);
        // A child that cannot beat the best is dropped: its remedy need not refine it.
        let cap = self.best.map_or(f64::INFINITY, |b| {
            self.nodes[b].makespan * (1.0 - SAME_MAKESPAN)
        });
        let ctx = (Ctx::new(self.cell, &prepared.moves, self.opts))
            .capped(cap)
            .passing(self.second_pass);
        let again = self.met_before(id, &c);
        let met = c.robots.1.filter(|_| self.opts.search.remember).map(|b| {
            let assignment = prepared.moves.assignment();
            let digest = pair_fingerprint(view.routes, view.legs, assignment, (c.robots.0, b));
            let prepared_at = prepared as *const Prepared as usize;
            (
                digest,
                prepared_at,
                c.time.to_bits(),
                again,
                self.second_pass,
            )
        });
        let known = met.as_ref().and_then(|key| self.remedied.get(key));
        let mut learnt = None;
        let children = match known {
            // The same children, each in this node's legs.
            Some(children) => (children.iter())
                .map(|child| {
                    let mut legs = view.legs.clone();
                    for (r, _) in &child.changed {
                        legs[*r] = child.legs[*r].clone();
                    }
                    Child {
                        legs,
                        ..child.clone()
                    }
                })
                .collect(),
            None => {
                let children = candidates(&ctx, &view, &c, again);
                learnt = met.map(|key| (key, children.clone()));
                children
            }
        };
        let reconfigs: Vec<(Reconfig, Remedy)> = match self.opts.search.remedies.reconfigure {
            true => reconfigurations(self.cell, (self.prepared, prepared), &node.routes, &c)
                .into_iter()
                .map(|r| (r, reconfigure::remedy(&node.routes, prepared, r)))
                .collect(),
            false => Vec::new(),
        };
        if let Some((key, value)) = learnt {
            self.remedied.insert(key, value);
        }
        self.times.scheduling += clock.elapsed();
        let node = &self.nodes[id];
        let (routes, conflicts, robots, depth) = (
            node.routes.clone(),
            node.conflicts.clone(),
            node.robots.clone(),
            node.depth + 1,
        );
        // No re-sequencing is expected to beat the collision-blind plan.
        let blind_makespan = self.blind_makespan;
        let (discrepancies, deviated_at) = (node.discrepancies, node.deviated_at);
        let parent_makespan = node.makespan;
        let legs = node.legs.clone();
        let mut made = Vec::new();
        for child in children {
            let assignment = self.prepared_of(id).moves.assignment();
            if !self
                .seen
                .insert(fingerprint(&routes, &child.legs, assignment))
            {
                continue;
            }
            let mut timed = robots.clone();
            for (r, s) in child.changed {
                timed[r] = s;
            }
            let makespan = timed.iter().map(|s| s.end).fold(0.0, f64::max);
            let last_resort = child.last_resort;
            let child = self.add(Node {
                routes: routes.clone(),
                conflicts: conflicts.clone(),
                legs: child.legs,
                robots: timed,
                makespan,
                parent: Some(id),
                remedy: Some(child.remedy),
                depth,
                discrepancies,
                deviated_at,
                pending: None,
                outcome: None,
                prepared: own.clone(),
            });
            if !self.worth(child) {
                continue;
            }
            if last_resort {
                let node = &mut self.nodes[child];
                node.pending = Some(Pending::Check);
                (node.discrepancies, node.deviated_at) = (discrepancies + 1, depth);
                self.enqueue(child);
            } else {
                made.push(child);
            }
        }
        // No more than the budget: children beyond it are left unchecked (the search ends).
        made.truncate(self.opts.search.max_nodes.saturating_sub(self.checked));
        self.check_all(&made, progress);
        self.rank_and_queue(made, depth);
        // A reconfiguration departs from the configurations chosen with the routes: a
        // discrepancy, as a re-sequencing is, made and checked when it is taken.
        for (r, remedy) in reconfigs {
            let pending = self.add(Node {
                routes: routes.clone(),
                conflicts: conflicts.clone(),
                legs: legs.clone(),
                robots: robots.clone(),
                makespan: parent_makespan,
                parent: Some(id),
                remedy: Some(remedy),
                depth,
                discrepancies: discrepancies + 1,
                deviated_at: depth,
                pending: Some(Pending::Reconfigure(r)),
                outcome: None,
                prepared: own.clone(),
            });
            self.enqueue(pending);
        }
        if self.opts.search.remedies.resequence {
            let parent = Node {
                routes,
                conflicts,
                legs: default_legs(self.cell.robots.len()),
                robots: Vec::new(),
                makespan: blind_makespan,
                parent: Some(id),
                remedy: Some(Remedy::RESEQUENCE),
                depth,
                discrepancies: discrepancies + 1,
                deviated_at: depth,
                pending: None,
                outcome: None,
                prepared: own,
            };
            self.queue_resequencing(parent, &c);
        }
    }
}
