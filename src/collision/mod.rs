//! The adaptive collision checker of Feyeux & Landry (2013).
//!
//! For every pair of bodies, the two time grids are merged; on each merged interval the
//! Schwarzer-Saha-Latombe condition λ1 + λ2 < η(tl) + η(tu) − 2δ certifies the interval,
//! or the interval is bisected (the paper's Table 1). η is the gap between bounding discs
//! while they are farther apart than δ, the exact polygon distance of the
//! closest-feature walk otherwise. A space-time broad phase first drops the pairs whose swept
//! bounding boxes stay δ apart (so N bodies do not cost N² pair checks); the remaining pairs
//! run in parallel, and the earliest contact wins.

mod adaptive;
mod advance;
mod arm;
mod broad_phase;
mod check;
mod eta;
mod grid;
mod method;
mod pair;
#[cfg(feature = "parry-peer")]
mod peer;
mod precision;
mod run_ahead;
mod sampled;
mod scene;
mod span;
mod stats;
mod verdict;

pub use arm::Arm;
pub use broad_phase::candidate_pairs;
pub use check::{
    check, check_known, try_check, validate, BudgetExhausted, CheckOptions, CheckReport, Contact,
    PairStats, DEFAULT_MAX_WORK_PER_PAIR, DEFAULT_TIME_TOL_OVER_HORIZON,
};
pub use method::Method;
#[cfg(feature = "parry-peer")]
pub use peer::{check_with_parry, PeerReport};
pub(crate) use precision::check_shape_repairs;
pub use precision::{
    check_precision, check_time_resolution, MAX_COORDINATE_OVER_DELTA, MAX_REPAIR_SHIFT_OVER_DELTA,
    MIN_TIME_TOL_OVER_ULP,
};
pub use sampled::MAX_SAMPLED_LOOKS;
pub(crate) use scene::check_delta;
pub use scene::{name_fault, Body, Scene, MAX_NAME_CHARS};
pub use stats::Stats;
pub use verdict::Verdict;
