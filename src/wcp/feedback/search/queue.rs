//! The queue: each node's place in it (limited discrepancy search, see the module above),
//! and a node's checked children ranked and queued.

use super::order::{Key, Ordered, Rank};
use super::Search;
use std::cmp::Reverse;

impl Search<'_> {
    /// The node's place in the queue.
    fn key(&self, id: usize) -> Key {
        let n = &self.nodes[id];
        (
            n.discrepancies,
            n.deviated_at,
            Reverse(n.depth),
            Ordered(n.makespan),
            id,
        )
    }

    pub(super) fn enqueue(&mut self, id: usize) {
        let key = self.key(id);
        self.queue.push(Reverse(key));
    }

    /// Ranks checked children, best first: the best continues the parent's line, every other
    /// one is a discrepancy; the colliding ones are queued.
    pub(super) fn rank_and_queue(&mut self, made: Vec<usize>, depth: usize) {
        let rank = |k: usize| Rank {
            makespan: self.nodes[k].makespan,
            collision: self.collision(k).map(|c| c.time),
            id: k,
        };
        let mut ranked: Vec<usize> = made;
        ranked.sort_by(|&a, &b| rank(a).cmp_children(&rank(b)));
        for &k in ranked.iter().skip(1) {
            self.nodes[k].discrepancies += 1;
            self.nodes[k].deviated_at = depth;
        }
        for k in ranked {
            if self.collision(k).is_some() {
                self.enqueue(k);
            }
        }
    }
}
