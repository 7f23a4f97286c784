//! What a solve gives back: the remedies applied, the rounds, the final schedule and its
//! report ([`Solved`]); and the words for a collision or an uncertified schedule.

use crate::cell::{Cell, CellObstacle, InputError, RobotKind};
use crate::collision::{CheckReport, Verdict};
use crate::geometry::Vec2;
use crate::geometry::{closest_features, ConvexPolygon, Posed, WalkTolerances};
use crate::motion::Pose;
use crate::wcp::configurations::Assignment;
use crate::wcp::legs::Legs;
use crate::wcp::moves::MoveStore;
use crate::wcp::prepare::StageTimes;
use crate::wcp::schedule::{Activity, BuildError, Collision, Delay, Schedule};
use crate::wcp::time_axis::culprit;

/// How one round's collision was removed: what was done, and for every kind but a
/// re-sequencing, to which leg of which robot.
#[derive(Clone, Debug, PartialEq)]
pub struct Remedy {
    /// The leg changed; `None` for a re-sequencing, which changes the sequences instead.
    pub on: Option<RemedyLeg>,
    /// What was done.
    pub kind: RemedyKind,
}

/// The leg a remedy changes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RemedyLeg {
    /// The robot.
    pub robot: usize,
    /// The leg (move of its route, 0 out of home).
    pub leg: usize,
    /// The leg's nodes.
    pub nodes: (usize, usize),
}

/// What a remedy does.
#[derive(Clone, Debug, PartialEq)]
pub enum RemedyKind {
    /// The sequencer re-planned with the colliding pair of steps forbidden.
    Resequence,
    /// The robot waits at the leg's start node before its move.
    Wait {
        /// How long.
        duration: f64,
    },
    /// The robot stops at a point of the leg's path and waits there.
    Pause {
        /// Where it stops.
        at: Vec2,
        /// How long it waits there.
        duration: f64,
    },
    /// The robot makes the leg's move slower.
    Slow {
        /// How many times slower than planned.
        factor: f64,
    },
    /// The robot makes the leg's move by another way, around another robot.
    Detour {
        /// The robot gone around.
        around: usize,
        /// The new path of G.
        path: Vec<Vec2>,
    },
    /// An arm takes another of its configurations at a task (the legs into and out of it
    /// as planned for it).
    Reconfigure {
        /// The task.
        task: usize,
        /// The arm's joint angles there.
        joints: Vec<f64>,
    },
    /// The robot steps aside to a parking pose, waits there and goes on.
    StepAside {
        /// The parking pose.
        park: Pose,
        /// How long it waits there.
        duration: f64,
    },
    /// The robot, standing in another's way, leaves by another way, ahead of the other,
    /// which waits (a remedy of the two at once).
    MakeWay {
        /// The robot it makes way for.
        ahead_of: usize,
        /// Its new path of G.
        path: Vec<Vec2>,
        /// How long the other waits before its move.
        wait: f64,
    },
    /// Two robots that meet while both move keep to opposite sides of the line they meet
    /// along, each on a new path (a remedy of the two at once).
    Lanes {
        /// The other robot's move.
        with: RemedyLeg,
        /// This robot's new path of G.
        path: Vec<Vec2>,
        /// The other's new path of G.
        with_path: Vec<Vec2>,
    },
    /// Two robots' moves timed together (velocity tuning in their coordination diagram):
    /// both keep their paths; each holds where its [`TunedHold`]s say.
    Tune {
        /// The other robot's move timed with this one.
        with: RemedyLeg,
        /// Where each robot of the two holds and how long, robot by robot, in time order.
        holds: Vec<TunedHold>,
    },
    /// Every robot of a closed corridor goes round it together, the same way, each
    /// stopping at its tasks while the others hold, until all are home again (robots on a
    /// loop one robot wide, which cannot pass each other).
    Convoy {
        /// The robots that go round, in cell order.
        robots: Vec<usize>,
        /// The way round, seen from above.
        counter_clockwise: bool,
        /// Whole laps of the loop.
        laps: usize,
        /// Each robot goes on as far as the one ahead leaves room (else all stop while
        /// any works, as one rigid ring).
        following: bool,
        /// The loop, a closed path of G.
        loop_path: Vec<Vec2>,
    },
    /// A certified schedule's slack (waits, holds, slowed motions) shortened as far as the
    /// other robots allow (no collision answered: the last round but one).
    Tighten {
        /// Each one shortened, in the order it first was.
        shortened: Vec<Shortened>,
    },
}

/// A wait, hold or slowed motion of the answer shortened ([`RemedyKind::Tighten`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shortened {
    /// The robot.
    pub robot: usize,
    /// The leg (move of its route, 0 out of home).
    pub leg: usize,
    /// The leg's nodes.
    pub nodes: (usize, usize),
    /// What was shortened.
    pub kind: Shortening,
    /// How long it was: seconds, or for [`Shortening::Slow`] how many times slower.
    pub before: f64,
    /// How long it is.
    pub after: f64,
}

/// What a [`Shortened`] shortened.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shortening {
    /// The wait at the leg's start.
    Wait,
    /// A pause on the leg's way.
    Pause,
    /// A stay at a parking pose on the leg's way.
    Park,
    /// A motion of the leg run slower than planned.
    Slow,
    /// The leg's way, changed by a remedy, back to its planned move: `before` and `after`
    /// are the leg's time (wait, way and stops) in seconds.
    Straight,
}

/// A stop of a robot on a move timed with another's ([`RemedyKind::Tune`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TunedHold {
    /// The robot.
    pub robot: usize,
    /// Where G stops (its start node for a longer wait there).
    pub at: Vec2,
    /// How long.
    pub duration: f64,
}

impl Remedy {
    /// A re-sequencing.
    pub const RESEQUENCE: Remedy = Remedy {
        on: None,
        kind: RemedyKind::Resequence,
    };

    /// A remedy of `kind` on leg `leg` of `robot`, between `nodes`.
    ///
    /// ```
    /// use workcell::wcp::{Delay, Remedy, RemedyKind};
    /// let pause = Remedy::on(1, 0, (0, 4), RemedyKind::Slow { factor: 2.0 });
    /// assert_eq!(pause.on.map(|l| l.robot), Some(1));
    /// let wait = Delay { robot: 1, before_move: 0, nodes: (0, 4), duration: 1.0 };
    /// assert_eq!(Remedy::wait(wait), Remedy::on(1, 0, (0, 4), RemedyKind::Wait { duration: 1.0 }));
    /// ```
    pub fn on(robot: usize, leg: usize, nodes: (usize, usize), kind: RemedyKind) -> Remedy {
        Remedy {
            on: Some(RemedyLeg { robot, leg, nodes }),
            kind,
        }
    }

    /// A wait at a node as a remedy.
    ///
    /// ```
    /// use workcell::wcp::{remedy_json::remedy_name, Delay, Remedy};
    /// let wait = Remedy::wait(Delay { robot: 0, before_move: 2, nodes: (3, 1), duration: 0.5 });
    /// assert_eq!((remedy_name(&wait), wait.on.unwrap().leg), ("delay", 2));
    /// ```
    pub fn wait(d: Delay) -> Remedy {
        Remedy::on(
            d.robot,
            d.before_move,
            d.nodes,
            RemedyKind::Wait {
                duration: d.duration,
            },
        )
    }
}

/// One round of the loop.
#[derive(Clone, Debug)]
pub struct Iteration {
    /// Makespan of the schedule checked in this round.
    pub makespan: f64,
    /// Its first collision, if any.
    pub collision: Option<Collision>,
    /// What was done about it (`None` in the last round).
    pub remedy: Option<Remedy>,
}

/// A solve's result.
#[derive(Clone, Debug)]
pub struct Solved {
    /// Each robot's tasks in order.
    pub routes: Vec<Vec<usize>>,
    /// Every robot's legs as the loop changed them (waits, pauses, detours, parking).
    pub legs: Legs,
    /// The final schedule.
    pub schedule: Schedule,
    /// The checker's report on the final schedule.
    pub report: CheckReport,
    /// True when the final schedule is certified collision-free.
    pub collision_free: bool,
    /// Every round, in order; the last one checked the final schedule.
    pub iterations: Vec<Iteration>,
    /// The collision-blind best sequences (the first round's).
    pub blind_routes: Vec<Vec<usize>>,
    /// Makespan of the collision-blind best schedule.
    pub blind_makespan: f64,
    /// Whether the sequencer proved that one optimal.
    pub blind_optimal: bool,
    /// Why the loop stopped without a collision-free schedule.
    pub failure: Option<String>,
    /// Which configuration each arm takes at each task (see [`Assignment`]).
    pub assignment: Assignment,
    /// Schedules checked: the rounds for the greedy loop, the search nodes for the search.
    pub nodes: usize,
    /// Schedules checked when the answer was found (of [`Solved::nodes`]): the last for the
    /// greedy loop; for the search, when its best certified schedule came (for a shortened
    /// one, the schedule it shortens; the rest was spent looking for a better one); none when
    /// there is no certified answer.
    pub found_after: Option<usize>,
    /// Wall time per stage.
    pub times: StageTimes,
    /// Shortened answers (`tighten.rs`) that the check of the whole schedule refused. Each
    /// step of a shortening proves its own changes clear, so none should be; a window that
    /// started too late would show here, as a shortening silently lost.
    pub shortenings_refused: usize,
}

impl Solved {
    /// The waits at nodes of the final schedule.
    ///
    /// ```
    /// use workcell::wcp::{prepare, solve, Feedback, SolveOptions};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// // The greedy loop ends by making R2 wait at home (docs/solver.md, "feedback cell").
    /// let opts = SolveOptions { feedback: Feedback::Greedy, ..SolveOptions::default() };
    /// let solved = solve(&cell, &prepare(&cell, &opts, &())?, &opts, &())?;
    /// let delays = solved.delays();
    /// assert_eq!((delays.len(), delays[0].robot, delays[0].before_move), (1, 1, 0));
    /// assert!(solved.collision_free && delays[0].duration > 0.0);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn delays(&self) -> Vec<Delay> {
        Delay::of_legs(&self.routes, &self.legs)
    }
}

/// The schedule of `routes` with `legs`; a failure is an error in the cell's terms.
pub(super) fn build(
    cell: &Cell,
    routes: &[Vec<usize>],
    legs: &Legs,
    moves: &MoveStore,
) -> Result<Schedule, InputError> {
    Schedule::build(cell, routes, legs, moves)
        .map_err(|e| build_error(cell, routes, legs, moves, e))
}

fn build_error(
    cell: &Cell,
    routes: &[Vec<usize>],
    legs: &Legs,
    moves: &MoveStore,
    e: BuildError,
) -> InputError {
    let robot = &cell.robots[e.robot()].name;
    match e {
        // The table certified every move the sequencer may choose: a failure here means
        // the planner is not deterministic, a defect to report rather than hide.
        BuildError::Move { .. } => cell.error(
            Some(robot),
            "",
            format!(
                "internal error: a move certified before fails now: {}",
                e.reason(cell)
            ),
        ),
        // Blame the task whose duration stretched the axis, as `evaluate` does, and the
        // robot's limits otherwise (its waits are the solver's, never the user's).
        BuildError::Precision { robot: r, time } => {
            let delays = Delay::of_legs(routes, legs);
            let blamed = culprit(cell, r, &routes[r], &delays, moves, time).map(|m| m.blamed);
            match blamed.map(|b| b.activity) {
                Some(Activity::Work(k)) => cell.error(
                    Some(&cell.tasks[k].name),
                    format!("tasks[{k}].duration"),
                    format!(
                        "this duration of {:e} stretches the time axis: {}",
                        cell.tasks[k].duration,
                        e.reason(cell)
                    ),
                ),
                _ => cell.error(Some(robot), format!("robots[{r}]"), e.reason(cell)),
            }
        }
        // Remedies are made to start where the robot is: a jump is a defect of ours.
        BuildError::Discontinuous { .. } => cell.error(
            Some(robot),
            "",
            format!("internal error: {}", e.reason(cell)),
        ),
    }
}

/// Why the checker did not certify a schedule in which it found no collision: its work
/// budget ran out on a pair, or two bodies graze δ too closely to prove either way.
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::wcp::uncertified;
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/near-miss.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// // One evaluation per pair is not enough to prove the near miss free.
/// let report = check(&scene, &CheckOptions { max_work_per_pair: 1, ..CheckOptions::default() });
/// assert!(uncertified(&report).starts_with("the checker spent its work budget"));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn uncertified(report: &CheckReport) -> String {
    match report.verdict() {
        Verdict::Unresolved { budget: b } => format!(
            "the checker spent its work budget ({} evaluations) on {} and {} after t = {:.6} \
             without a proof or a witness",
            b.work, b.bodies[0], b.bodies[1], b.time
        ),
        _ => "the checker cannot certify the schedule: two bodies graze delta".to_owned(),
    }
}

/// Where a collision between two robots happens, for a reader who must change the cell:
/// its point, and the fixtures that hem it in (those within [`HEMMED_IN`] times the two
/// robots' radii of it, nearest first, at most two), with the passage between two of them
/// against two rigid robots side by side (their least widths and 2δ): `at (2.10, 3.00),
/// between block-1 and block-2, 1.00 apart: too narrow for the two side by side (1.42)`.
/// An obstacle collision is placed by its point only.
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::planning::PlannerOptions;
/// use workcell::wcp::{place, legs::default_legs, MoveStore, Schedule};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let store = MoveStore::new(&cell, &PlannerOptions::default());
/// let schedule = Schedule::build(&cell, &[vec![1, 0, 2], vec![3]], &default_legs(2), &store).unwrap();
/// let report = check(&schedule.scene(&cell), &CheckOptions::default());
/// let c = schedule.collision(&cell, &report).expect("a collision");
/// let place = place(&cell, &c); // at the weld next to the fixture
/// assert!(place.starts_with("at (") && place.ends_with("), beside fixture"), "{place}");
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn place<'a>(cell: &'a Cell, c: &Collision) -> String {
    let at = format!("at ({:.2}, {:.2})", c.point.x, c.point.y);
    let Some(b) = c.robots.1 else {
        return at;
    };
    let reach = HEMMED_IN * (cell.robots[c.robots.0].body_radius() + cell.robots[b].body_radius());
    let pieces = |o: &'a CellObstacle| -> &'a [ConvexPolygon] {
        o.parts
            .as_ref()
            .map_or(std::slice::from_ref(&o.shape), |p| p.parts())
    };
    let mut near: Vec<(f64, &CellObstacle)> = cell
        .obstacles
        .iter()
        .map(|o| {
            let d = (pieces(o).iter())
                .map(|p| p.distance_to(&c.point))
                .fold(f64::INFINITY, f64::min);
            (d, o)
        })
        .filter(|(d, _)| *d <= reach)
        .collect();
    near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.name.cmp(&b.1.name)));
    let (one, two) = match near.as_slice() {
        [] => return at,
        [(_, one)] => return format!("{at}, beside {}", one.name),
        [(_, one), (_, two), ..] => (one, two),
    };
    // How wide the passage between them is, against the two robots side by side.
    let tol = WalkTolerances::default();
    let gap = (pieces(one).iter())
        .flat_map(|p| pieces(two).iter().map(move |q| (p, q)))
        .map(|(p, q)| {
            let (p, q) = (Posed::new(p, 0.0, 0.0, 0.0), Posed::new(q, 0.0, 0.0, 0.0));
            closest_features(&p, &q, None, &tol).distance
        })
        .fold(f64::INFINITY, f64::min);
    let side_by_side = match (&cell.robots[c.robots.0].kind, &cell.robots[b].kind) {
        (RobotKind::Rigid(p), RobotKind::Rigid(q)) => {
            Some(p.shape.min_width() + q.shape.min_width() + 2.0 * cell.delta)
        }
        _ => None,
    };
    let between = format!(
        "{at}, between {} and {}, {gap:.2} apart",
        one.name, two.name
    );
    match side_by_side {
        Some(w) if gap < w => format!("{between}: too narrow for the two side by side ({w:.2})"),
        _ => between,
    }
}

/// Who blocks whom, and where: `R1 and R2 block each other at (5.00, 0.30), between
/// wall-north and wall-south`, or `R1 hits pillar at (…)`.
pub(super) fn blockers(cell: &Cell, c: &Collision) -> String {
    let [a, b] = &c.bodies;
    match c.robots.1 {
        Some(_) => format!("{a} and {b} block each other {}", place(cell, c)),
        None => format!("{a} hits {b} {}", place(cell, c)),
    }
}

/// Fixtures this many times the two robots' radii from a collision hem it in.
pub const HEMMED_IN: f64 = 1.0;

/// Why a schedule in which no collision was named is not certified: [`uncertified`], or a
/// contact the checker reports between bodies the schedule does not know (a defect of ours).
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::wcp::{unresolved, uncertified};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/near-miss.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// let report = check(&scene, &CheckOptions { max_work_per_pair: 1, ..CheckOptions::default() });
/// assert_eq!(unresolved(&report), uncertified(&report));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn unresolved(report: &CheckReport) -> String {
    match report.verdict() {
        Verdict::Contact { .. } => {
            "internal error: the checker's first contact names no body of the cell".to_owned()
        }
        _ => uncertified(report),
    }
}

/// One line about a collision: `R1 (move weld-1 -> weld-2) and R2 (task weld-5) at t = 3.2`.
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::planning::PlannerOptions;
/// use workcell::wcp::{describe, legs::default_legs, MoveStore, Schedule};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let store = MoveStore::new(&cell, &PlannerOptions::default());
/// let schedule = Schedule::build(&cell, &[vec![1, 0, 2], vec![3]], &default_legs(2), &store).unwrap();
/// let report = check(&schedule.scene(&cell), &CheckOptions::default());
/// let line = describe(&cell, &schedule.collision(&cell, &report).expect("a collision"));
/// assert!(line.starts_with("R1 (") && line.contains(") and R2 (") && line.contains(" at t = "), "{line}");
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn describe(cell: &Cell, c: &Collision) -> String {
    let a = format!(
        "{} ({})",
        c.bodies[0],
        c.segments.0.activity.describe(cell, c.robots.0)
    );
    let b = match (c.robots.1, c.segments.1) {
        (Some(b), Some(s)) => format!("{} ({})", c.bodies[1], s.activity.describe(cell, b)),
        _ => format!("obstacle {}", c.bodies[1]),
    };
    format!("{a} and {b} at t = {:.6}", c.time)
}
