//! When the search and its passes stop: the budgets of schedules and time, the share of
//! the schedules kept for the second pass, and the first pass's patience.

use super::Search;
use std::time::Instant;

/// The share of the solve's time limit left, after the search, for shortening the answers'
/// slack: about 0.1 s at most on the conflict cells, a few milliseconds on most.
const TIGHTEN_SHARE: f64 = 0.05;

impl Search<'_> {
    /// The budget that has run out, if one has: schedules checked, the solve's time limit
    /// or the search's own (counted from `started`).
    pub(super) fn budget_spent(&self, started: Instant) -> Option<String> {
        let max_nodes = self.opts.search.max_nodes;
        if self.checked >= max_nodes {
            return Some(format!(
                "the search's budget of {} schedule{}",
                max_nodes,
                if max_nodes == 1 { "" } else { "s" }
            ));
        }
        if self.deadline().is_some_and(|d| Instant::now() >= d) {
            return Some("the solve's time limit".to_owned());
        }
        if started.elapsed() >= self.opts.search.time_limit {
            return Some(format!(
                "the search's time limit of {:.0} s",
                self.opts.search.time_limit.as_secs_f64()
            ));
        }
        None
    }

    /// When the search stops under the solve's time limit: a share of the limit before it,
    /// left for shortening the answers' slack (`tighten.rs`).
    pub(super) fn deadline(&self) -> Option<Instant> {
        let reserve = self
            .opts
            .time_limit
            .unwrap_or_default()
            .mul_f64(TIGHTEN_SHARE);
        self.prepared
            .deadline
            .map(|d| d.checked_sub(reserve).unwrap_or(d))
    }

    /// Whether the first pass has checked its share of the budget of schedules (all but
    /// [`SearchOptions::second_pass_share`] of it).
    ///
    /// [`SearchOptions::second_pass_share`]: crate::wcp::SearchOptions::second_pass_share
    pub(super) fn first_pass_spent(&self) -> bool {
        !self.second_pass && self.checked >= self.first_pass_budget()
    }

    /// The schedules the first pass may check, a share of them kept for the second (all of
    /// them with no share: the budget stops the search first).
    pub(super) fn first_pass_budget(&self) -> usize {
        let search = &self.opts.search;
        ((1.0 - search.second_pass_share) * search.max_nodes as f64).ceil() as usize
    }

    /// Whether the second pass, after a first pass that was cut, has checked its share.
    pub(super) fn second_pass_spent(&self) -> bool {
        self.second_pass_end.is_some_and(|end| self.checked >= end)
    }

    /// The schedules the second pass may check after a first pass that was cut.
    pub(super) fn second_pass_budget(&self) -> usize {
        self.opts.search.max_nodes - self.first_pass_budget()
    }

    /// Whether the first pass has stopped paying (see [`SearchOptions::patience`]): a node
    /// found late earns as long a search again.
    ///
    /// [`SearchOptions::patience`]: crate::wcp::SearchOptions::patience
    pub(super) fn stalled(&self) -> bool {
        let Some(patience) = self.opts.search.patience else {
            return false;
        };
        !self.second_pass
            && self.best.is_some()
            && self.checked - self.best_at >= patience.max(self.best_at)
    }
}
