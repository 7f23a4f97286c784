//! The Work-Cell Problem: from a cell to a collision-free schedule with a small makespan.
//!
//! 1. [`MoveTable`]: every robot's fastest move between every two of its nodes (home,
//!    allowed tasks), planned by [`crate::planning`] and certified by the checker.
//! 2. [`WcpGraph`]: the petgraph graph of those travel times.
//! 3. [`sequencer`]: assigns and orders the tasks to minimise the makespan.
//! 4. [`solve`]: the loop. Each round times the sequences into a [`Schedule`], checks every
//!    pair with [`crate::collision::check`] and feeds the first collision back: either the
//!    sequencer re-plans with the two colliding steps forbidden together, or one robot waits
//!    until the other's activity is over, whichever gives the smaller makespan.
//! 5. [`evaluate`]: the same schedule and check for sequences given by the user.

mod evaluate;
mod feedback;
mod graph;
pub mod legs;
mod moves;
mod picture;
pub mod report;
mod schedule;
pub mod sequencer;
mod time_axis;

pub use evaluate::{evaluate, Evaluated};
pub use feedback::{
    describe, prepare, sequencer_error, solve, Feedback, Iteration, Prepared, Progress, Remedy,
    SolveOptions, Solved, StageTimes,
};
pub use graph::{
    check_reachable, GraphFile, GraphFileArc, GraphFileNode, NodeKind, TravelArc, WcpGraph,
};
pub use moves::{certified_move, node_name, node_pose, robot_nodes, MoveFailure, MoveTable};
pub use picture::picture;
pub use schedule::{
    route_nodes, Activity, BuildError, Collision, Delay, MoveCache, RobotSchedule, Schedule,
    Segment,
};
pub use time_axis::{culprit, Misplaced, Stretch};
