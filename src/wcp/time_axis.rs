//! Where a schedule leaves f64's time axis, and why.
//!
//! The cell's own check ([`crate::cell::keeps_length`] at the earliest start of each task)
//! refuses limits and durations that can never share one time axis; the schedule refuses a
//! move, task or wait that rounds away where it falls. When that happens, [`culprit`] tells
//! which of the robot's activities stretched the axis so far, so that the error can name it.

use super::moves::MoveStore;
use super::schedule::{route_nodes, Activity, Delay, RobotSchedule};
use super::sequencer::node_task;
use crate::cell::Cell;

/// The time of the first sample or segment end of a robot's schedule that is not finite (a
/// move whose time overflowed f64), if there is one: such a schedule cannot be checked.
pub(super) fn first_infinite_time(schedule: &RobotSchedule) -> Option<f64> {
    let mut last = 0.0;
    for s in &schedule.samples {
        if !s.t.is_finite() {
            return Some(last);
        }
        last = s.t;
    }
    schedule
        .segments
        .iter()
        .find(|seg| {
            !seg.start.is_finite() || !(seg.end.is_finite() || seg.activity == Activity::Done)
        })
        .map(|seg| seg.start)
}

/// One activity of a robot's route with the length it adds to the time axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stretch {
    /// What the robot does.
    pub activity: Activity,
    /// When it starts, summed as the schedule sums it.
    pub start: f64,
    /// How long it lasts: the wait, the planned move's duration or the task's.
    pub length: f64,
    /// The move it belongs to: waits before it, the move, the task it leads to (0 is the
    /// move out of home).
    pub step: usize,
}

/// Why a robot's schedule cannot be placed on f64's time axis (see [`culprit`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Misplaced {
    /// The activity that lost its length: the shortest move or task under way at the time
    /// (waits may shrink: they only delay).
    pub lost: Stretch,
    /// The longest activity that starts no later, which stretched the axis so far.
    pub longest: Stretch,
    /// The one of the two that is out of scale: `longest` when it is farther above the
    /// cell's median task duration than `lost` is below it (or when nothing is known of
    /// the cell's scale, or a time is not finite), else `lost`.
    pub blamed: Stretch,
}

/// Why robot `r`'s schedule cannot be placed on f64's time axis at `time`. The route is
/// replayed as the schedule times it (waits, each planned move, each task); a move that
/// cannot be planned ends the replay (legs changed by the feedback loop are not replayed:
/// `evaluate` builds default legs). `None` when nothing starts by `time`.
///
/// ```
/// use workcell::cell::parse_cell;
/// use workcell::planning::PlannerOptions;
/// use workcell::wcp::{culprit, Activity, MoveStore};
/// // Tasks of 1 s, and one of 10¹⁷ s: f64 rounds away what follows it.
/// let text = r#"{"delta": 0.01,
///   "robots": [{"name": "R1", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
///               "home": [0, 0, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1}],
///   "tasks": [{"name": "long", "at": [3, 0, 0], "duration": 1e17},
///             {"name": "short", "at": [5, 0, 0], "duration": 1},
///             {"name": "first", "at": [1, 2, 0], "duration": 1}]}"#;
/// let cell = parse_cell(text, "c.json".as_ref())?.cell;
/// let store = MoveStore::new(&cell, &PlannerOptions::default());
/// let route = [2, 0, 1];
/// let m = culprit(&cell, 0, &route, &[], &store, 1e17).expect("the axis is stretched");
/// // The long task is out of scale (the median task lasts 1 s): it is blamed.
/// assert_eq!((m.longest.activity, m.blamed), (Activity::Work(0), m.longest));
/// assert!(culprit(&cell, 0, &route, &[], &store, -1.0).is_none()); // nothing started yet
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn culprit(
    cell: &Cell,
    r: usize,
    route: &[usize],
    delays: &[Delay],
    moves: &MoveStore,
    time: f64,
) -> Option<Misplaced> {
    let stretches = replay(cell, r, route, delays, moves);
    let before = stretches.iter().filter(|s| s.start <= time);
    let longest = *before
        .clone()
        .reduce(|a, b| if b.length > a.length { b } else { a })?;
    let lost = before
        .filter(|s| !matches!(s.activity, Activity::Wait(_)) && s.start + s.length >= time)
        .reduce(|a, b| if b.length < a.length { b } else { a })
        .copied()
        .unwrap_or(longest);
    // The user's time unit shows in the task durations: what is out of scale with them.
    let mut durations: Vec<f64> = cell
        .tasks
        .iter()
        .map(|t| t.duration)
        .filter(|&d| d > 0.0)
        .collect();
    durations.sort_by(f64::total_cmp);
    let blamed = match durations.get(durations.len() / 2) {
        Some(&scale) if longest.length.is_finite() && lost.length > 0.0 => {
            if scale / lost.length > longest.length / scale {
                lost
            } else {
                longest
            }
        }
        _ => longest,
    };
    Some(Misplaced {
        lost,
        longest,
        blamed,
    })
}

fn replay(
    cell: &Cell,
    r: usize,
    route: &[usize],
    delays: &[Delay],
    moves: &MoveStore,
) -> Vec<Stretch> {
    let mut out = Vec::new();
    if route.is_empty() {
        return out;
    }
    let nodes = route_nodes(route);
    let mut now = 0.0;
    for (m, pair) in nodes.windows(2).enumerate() {
        let (from, to) = (pair[0], pair[1]);
        let wait: f64 = delays
            .iter()
            .filter(|d| d.robot == r && d.before_move == m)
            .map(|d| d.duration)
            .sum();
        let mut push = |activity, length: f64, now: &mut f64| {
            out.push(Stretch {
                activity,
                start: *now,
                length,
                step: m,
            });
            *now += length;
        };
        if wait > 0.0 {
            push(Activity::Wait(from), wait, &mut now);
        }
        let Ok(planned) = moves.get(r, from, to) else {
            break;
        };
        push(Activity::Move { from, to }, planned.duration, &mut now);
        if to != 0 {
            push(
                Activity::Work(node_task(to)),
                cell.tasks[node_task(to)].duration,
                &mut now,
            );
        }
    }
    out
}
