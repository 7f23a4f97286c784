//! The counters of the paper's section 6.

use std::ops::AddAssign;

/// Work counters, summed over pairs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Stats {
    /// Merged time intervals examined (the paper's "intervals").
    pub intervals: u64,
    /// Interval bisections (Table 1's splits, including the refinement of the contact time).
    pub bisections: u64,
    /// Exact distance computations (narrow phase), made when the bounding discs are closer
    /// than δ.
    pub narrow_phase_calls: u64,
    /// Feature pairs visited by the closest-feature walk (the paper's "feature tests").
    pub feature_steps: u64,
    /// Walks stopped by the cycling guard and answered by the exact fallback.
    pub walk_fallbacks: u64,
    /// Intervals certified by the convexity of the distance under the relative translation,
    /// where the first-order condition alone would have split them.
    pub convexity_certificates: u64,
    /// Intervals shorter than the time tolerance, with no witness, shown to stay above
    /// δ·(1 − grazing allowance) but not above δ: the pair grazes δ there.
    pub grazing: u64,
    /// Looks inside merged intervals by the sampled and advance methods (η at a time chosen
    /// by the method rather than by bisection).
    pub looks: u64,
    /// Intervals that floating point cannot split further and that are neither certified
    /// nor hold a witness. Only coordinates far too large for δ cause it (the scene loader
    /// refuses them); a report with any is not a proof.
    pub unresolved: u64,
}

impl AddAssign for Stats {
    fn add_assign(&mut self, o: Stats) {
        self.intervals += o.intervals;
        self.bisections += o.bisections;
        self.narrow_phase_calls += o.narrow_phase_calls;
        self.feature_steps += o.feature_steps;
        self.walk_fallbacks += o.walk_fallbacks;
        self.unresolved += o.unresolved;
        self.convexity_certificates += o.convexity_certificates;
        self.grazing += o.grazing;
        self.looks += o.looks;
    }
}
