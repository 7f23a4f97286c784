//! The settings of a solve: how collisions are fed back, the search's budgets and
//! remedies, which moves are planned up front, and the settings of every stage below.

use crate::collision::CheckOptions;
use crate::motion::IkSettings;
use crate::planning::PlannerOptions;
use crate::wcp::sequencer::SequencerOptions;
use std::time::Duration;

/// How collisions are fed back.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Feedback {
    /// Best-first search over remedies (`search.rs`).
    #[default]
    Search,
    /// Each round, the better of re-sequencing and one wait at a node (`greedy.rs`).
    Greedy,
}

/// Settings of a solve.
#[derive(Clone, Debug)]
pub struct SolveOptions {
    /// Rounds of sequencing, checking and feedback before giving up (for the search: along
    /// one branch).
    pub max_iterations: usize,
    /// How collisions are fed back.
    pub feedback: Feedback,
    /// The search's budgets and remedies (for [`Feedback::Search`]).
    pub search: SearchOptions,
    /// The sequencer's settings, its seed among them.
    pub sequencer: SequencerOptions,
    /// The planner's settings.
    pub planner: PlannerOptions,
    /// The checker's settings for the schedules.
    pub check: CheckOptions,
    /// Wall time for the whole solve, from [`prepare`](crate::wcp::prepare) on: the sequencer then returns the
    /// best certified plan found so far, and the search its best certified schedule. `None`:
    /// no limit, and the result depends only on the input and the seed.
    pub time_limit: Option<Duration>,
    /// Under a time limit, with an effort beyond one epoch (`sequencer.effort`): the share of
    /// the time left after planning that the collision-blind sequencing may take (0.5; clamped
    /// to 0..=1, NaN as 0). The search over remedies, or the refinement of a collision-free plan, gets
    /// the rest.
    pub blind_share: f64,
    /// Which moves are planned before sequencing.
    pub planning: Planning,
    /// How arms' configurations at the tasks are found (inverse kinematics).
    pub ik: IkSettings,
    /// Which configuration each arm takes at each task.
    pub configurations: ConfigurationChoice,
}
/// How each arm's configuration at each task is decided.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ConfigurationChoice {
    /// Chosen with the routes (`choose.rs`), from the ones reached soonest from home.
    #[default]
    Chosen,
    /// The one each arm reaches soonest from home, kept.
    NearestHome,
    /// The first inverse-kinematics solution (for two links, the elbow-up one where the
    /// limits allow it), kept: a fixed choice to compare against.
    First,
}

/// Which moves [`prepare`](crate::wcp::prepare) plans and certifies.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Planning {
    /// [`Planning::All`] for cells of at most [`AUTO_ALL_MAX_MOVES`] moves, else
    /// [`Planning::Lazy`]; under a time limit, lazy first, then all only when that fits
    /// (see [`AUTO_ALL_LIMIT_SHARE`]).
    #[default]
    Auto,
    /// For each task, the move from the home of its nearest allowed robot that can reach it;
    /// the sequencer works on lower bounds of the others and plans those its plans use.
    Lazy,
    /// Every move of every robot between every two of its nodes (robots × nodes² / 2).
    All,
}

/// Cells with at most this many moves (robots × unordered pairs of their nodes) are planned
/// whole under [`Planning::Auto`]: a second or two of planning, and the sequencer then
/// searches on exact times from the start.
pub const AUTO_ALL_MAX_MOVES: usize = 100_000;

/// Under a time limit, [`Planning::Auto`] plans every move only when that is expected to take
/// at most this share of the limit, at the pace of the moves from home (planned first, as
/// under [`Planning::Lazy`]); else it stays lazy.
pub const AUTO_ALL_LIMIT_SHARE: f64 = 0.25;

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            max_iterations: 200,
            feedback: Feedback::default(),
            search: SearchOptions::default(),
            sequencer: SequencerOptions::default(),
            planner: PlannerOptions::default(),
            check: CheckOptions::default(),
            time_limit: None,
            blind_share: 0.5,
            planning: Planning::Auto,
            ik: IkSettings::default(),
            configurations: ConfigurationChoice::Chosen,
        }
    }
}

/// Budgets and remedies of the search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SearchOptions {
    /// Most schedules checked.
    pub max_nodes: usize,
    /// Most wall time spent searching (after the collision-blind sequencing).
    pub time_limit: Duration,
    /// The remedies the search may use.
    pub remedies: Remedies,
    /// When the first pass stops paying: it ends once it has checked this many schedules,
    /// and at least as many as it took to find it, since its best certified schedule; the
    /// second pass then has its share of the budget ([`SearchOptions::second_pass_share`]),
    /// and the search ends. `None`: the first pass runs until its share is spent or no
    /// node is left. The default, 2,000, changed no answer of the conflict cells of
    /// docs/solver.md but one, shorter, and spared a ninth of their checks; 1,500 made two
    /// longer and two shorter. Counted in schedules, not seconds, so that the result does
    /// not depend on the machine.
    pub patience: Option<usize>,
    /// The share of `max_nodes` kept for the second pass, along the way to the best
    /// certified schedule (passing places, route-end exchanges): the first pass ends once
    /// it has checked the rest, or sooner when no node is left. 0: the second pass only
    /// then. Under a time limit without a node budget, the second pass comes when no node
    /// is left. The default, 0.3, answered better than 0.2 and 0.4 on the conflict cells of
    /// docs/solver.md.
    pub second_pass_share: f64,
    /// Whether a question asked again is answered from memory: a re-sequencing of the same
    /// routes and conflicts, the remedies of a collision between the same two schedules.
    /// On by default; off only to check that remembering changes nothing but the time.
    pub remember: bool,
    /// Plans with one robot fewer searched beside the collision-blind plan: as many as
    /// this, of the robots whose tasks others may all do, those whose plans without them
    /// are shortest by makespan plus mean route time (`search/idle.rs`). Robots that share
    /// a bottleneck (a door) can finish sooner with one of them at home: the doorways of
    /// docs/benchmarks.md. 0, the default: none, since they share the budget with the
    /// collision-blind plan. A re-sequencing: none without [`Remedies::resequence`].
    pub idle_roots: usize,
    /// Whether shortening the answer may let the robot that ends last through: a wait or
    /// hold of it that one other robot alone keeps it from dropping is dropped, and that robot
    /// waits longer instead, where it still ends sooner (`search/give_way.rs`; only where
    /// [`Remedies::wait`] allows waits). On by default; off to see the other shortenings
    /// alone.
    pub give_way: bool,
}

impl Default for SearchOptions {
    fn default() -> Self {
        SearchOptions {
            max_nodes: 5000,
            time_limit: Duration::from_secs(60),
            remedies: Remedies::default(),
            patience: Some(2000),
            second_pass_share: 0.3,
            remember: true,
            idle_roots: 0,
            give_way: true,
        }
    }
}

/// Which remedies the search may use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Remedies {
    /// Re-sequence with the colliding steps forbidden together.
    pub resequence: bool,
    /// Wait at a node.
    pub wait: bool,
    /// Pause at a point of the path.
    pub pause: bool,
    /// Run a move slower.
    pub slow: bool,
    /// Go around the other robot.
    pub detour: bool,
    /// Step aside to a parking pose.
    pub step_aside: bool,
    /// Pull in at a passing place beside the way (a bay off a corridor) and let the other
    /// pass: in the search's second pass only, once its queue is empty.
    pub pass_aside: bool,
    /// Two robots that meet while both move, where both fit side by side, keep to opposite
    /// sides of the line they meet along: in the search's second pass only.
    pub lanes: bool,
    /// Time two robots' moves together in their coordination diagram, for a pair that
    /// collides again on the search's branch.
    pub tune: bool,
    /// Every robot of a closed corridor goes round it together, when a pair meets on it
    /// again or no other remedy separates them.
    pub convoy: bool,
    /// An arm takes another of its configurations at the task of a collision (off by
    /// default: up to six more children per collision with an arm widen the search more
    /// than they pay; see docs/benchmarks.md).
    pub reconfigure: bool,
}

impl Remedies {
    /// Every remedy.
    pub const ALL: Remedies = Remedies {
        resequence: true,
        wait: true,
        pause: true,
        slow: true,
        detour: true,
        step_aside: true,
        pass_aside: true,
        lanes: true,
        tune: true,
        convoy: true,
        reconfigure: true,
    };

    /// The names of `--remedies`, in this order.
    pub const NAMES: [&'static str; 11] = [
        "resequence",
        "wait",
        "pause",
        "slow",
        "detour",
        "step-aside",
        "pass-aside",
        "lanes",
        "tune",
        "convoy",
        "reconfigure",
    ];

    /// The set of the names given (each one of [`Remedies::NAMES`]).
    ///
    /// ```
    /// use workcell::wcp::Remedies;
    /// let some = Remedies::of_names(["resequence", "pause"])?;
    /// assert!(some.resequence && some.pause && !some.wait && !some.step_aside);
    /// assert_eq!(Remedies::of_names(Remedies::NAMES)?, Remedies::ALL);
    /// assert!(Remedies::of_names(["teleport"]).unwrap_err().contains("unknown remedy"));
    /// # Ok::<(), String>(())
    /// ```
    pub fn of_names<'s>(names: impl IntoIterator<Item = &'s str>) -> Result<Remedies, String> {
        let mut set = Remedies {
            resequence: false,
            wait: false,
            pause: false,
            slow: false,
            detour: false,
            step_aside: false,
            pass_aside: false,
            lanes: false,
            tune: false,
            convoy: false,
            reconfigure: false,
        };
        for name in names {
            let flag = match name {
                "resequence" => &mut set.resequence,
                "wait" => &mut set.wait,
                "pause" => &mut set.pause,
                "slow" => &mut set.slow,
                "detour" => &mut set.detour,
                "step-aside" => &mut set.step_aside,
                "pass-aside" => &mut set.pass_aside,
                "lanes" => &mut set.lanes,
                "tune" => &mut set.tune,
                "convoy" => &mut set.convoy,
                "reconfigure" => &mut set.reconfigure,
                other => {
                    return Err(format!(
                        "unknown remedy `{other}`: expected some of {}",
                        Remedies::NAMES.join(", ")
                    ))
                }
            };
            *flag = true;
        }
        Ok(set)
    }
}

impl Default for Remedies {
    /// Every remedy but `reconfigure`.
    fn default() -> Self {
        Remedies {
            reconfigure: false,
            ..Remedies::ALL
        }
    }
}
