//! The search's orders: of the queue (limited discrepancy search, see the module above)
//! and of a node's children.

use std::cmp::{Ordering, Reverse};

/// A total order on f64 keys.
#[derive(Clone, Copy, PartialEq)]
pub(super) struct Ordered(pub(super) f64);

impl Eq for Ordered {}

impl PartialOrd for Ordered {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Ordered {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// Queue order, smallest first: discrepancies, depth of the last one, minus the depth,
/// makespan, and the node's index (older first).
pub(super) type Key = (usize, usize, Reverse<usize>, Ordered, usize);

/// What ranks a node's checked children.
#[derive(Clone, Copy, Debug)]
pub(super) struct Rank {
    pub(super) makespan: f64,
    /// The time of the first collision; none for a schedule without one.
    pub(super) collision: Option<f64>,
    /// The node's index: older first on ties.
    pub(super) id: usize,
}

impl Rank {
    /// Best child first: the smaller makespan; on a tie the one whose first collision comes
    /// later (none at all is latest), since it has cleared more of the schedule; then the
    /// older.
    pub(super) fn cmp_children(&self, other: &Rank) -> Ordering {
        let later = |r: &Rank| r.collision.unwrap_or(f64::INFINITY);
        self.makespan
            .total_cmp(&other.makespan)
            .then(later(other).total_cmp(&later(self)))
            .then(self.id.cmp(&other.id))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rank(makespan: f64, collision: Option<f64>, id: usize) -> Rank {
        Rank {
            makespan,
            collision,
            id,
        }
    }

    #[test]
    fn children_rank_by_makespan_then_the_later_collision_then_age() {
        let mut children = [
            rank(12.0, None, 0),
            rank(10.0, Some(3.0), 1),
            rank(10.0, Some(7.0), 2),
            rank(10.0, None, 3),
            rank(10.0, Some(7.0), 4),
            rank(9.5, Some(1.0), 5),
        ];
        children.sort_by(|a, b| a.cmp_children(b));
        let order: Vec<usize> = children.iter().map(|r| r.id).collect();
        // The shortest first whatever its collision; at 10.0 the free one, then the later
        // collisions (the older of two alike first), the earliest last; the longest last.
        assert_eq!(order, [5, 3, 2, 4, 1, 0]);
    }
}
