//! The Work-Cell Problem: from a cell to a collision-free schedule with a small makespan.
//!
//! 1. [`MoveStore`]: every robot's fastest move between two of its nodes (home, allowed
//!    tasks), planned by [`crate::planning`] and certified by the checker when first needed,
//!    then kept; [`bounds`] bounds every move from below without planning it.
//! 2. [`sequence`]: the [`sequencer`] assigns and orders the tasks to minimise the makespan,
//!    on the bounds and the moves known so far; the moves of its plan are then planned, and
//!    it runs again until every move of its plan is exact.
//! 3. [`WcpGraph`]: the petgraph graph of the travel times, exact or bounds, for export.
//! 4. [`solve`]: the feedback loop. Each schedule (routes and their [`legs`]) is timed into a
//!    [`Schedule`] and checked pair by pair with [`crate::collision::check`]; a collision
//!    branches a search over remedies (re-sequencing, waits, pauses, slower moves, detours,
//!    stepping aside) until the checker certifies a schedule; `--feedback greedy` keeps the
//!    former loop (re-sequence or wait, the better each round).
//! 5. [`evaluate`]: the same schedule and check for sequences given by the user.

mod choose;
mod configurations;
mod evaluate;
mod feedback;
mod graph;
pub mod legs;
mod moves;
mod options;
mod prepare;

pub mod legs_json;
pub mod remedy_json;
pub mod report;
mod schedule;
mod sequence;
pub mod sequencer;
mod time_axis;

pub use choose::choose_configurations;
pub(crate) use configurations::configurations_found;
pub use configurations::{task_configurations, Assignment, Configuration, Configurations};
pub use evaluate::{evaluate, Evaluated};
pub use feedback::{
    describe, place, solve, uncertified, unresolved, Iteration, Remedy, RemedyKind, RemedyLeg,
    Shortened, Shortening, Solved, TunedHold, HEMMED_IN,
};
pub use graph::{
    check_reachable, GraphFile, GraphFileArc, GraphFileNode, NodeKind, TravelArc, WcpGraph,
};
pub use moves::{
    bounds, certified_move, node_name, node_pose, robot_nodes, MoveFailure, MoveStore,
};
pub use options::{
    ConfigurationChoice, Feedback, Planning, Remedies, SearchOptions, SolveOptions,
    AUTO_ALL_LIMIT_SHARE, AUTO_ALL_MAX_MOVES,
};
pub use prepare::{prepare, sequencer_error, Prepared, Progress, StageTimes, Unfinished};

pub use schedule::{
    route_nodes, Activity, BuildError, Collision, Delay, RobotSchedule, Schedule, Segment,
};
pub use sequence::{sequence, sequence_with};
pub use time_axis::{culprit, Misplaced, Stretch};
