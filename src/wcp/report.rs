//! What `solve` and `evaluate` print: the contract's JSON (section 4, with optional fields
//! added) and the human summary.

use super::configurations::Assignment;
use super::feedback::{describe, Iteration};
use super::legs_json::LegJson;
use super::moves::node_name;
use super::prepare::StageTimes;
use super::remedy_json::{change_json, remedy_name, remedy_text, ChangeJson};
use super::schedule::{Activity, Collision, Delay, Schedule};
use super::sequencer::task_node;
use crate::cell::Cell;
use crate::collision::Stats;
use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;
use std::fmt::Write;

/// The JSON of `solve --json` and `evaluate --json`.
#[derive(Serialize)]
pub struct ResultJson<'a> {
    /// When the last robot is back home.
    pub makespan: f64,
    /// The final schedule is certified collision-free.
    pub collision_free: bool,
    /// Each robot's tasks in order, robots in the cell's order.
    #[serde(serialize_with = "ordered_map")]
    pub sequences: Vec<(&'a str, Vec<&'a str>)>,
    /// Each arm's joint angles at each of its tasks, in the order of `sequences` (contract
    /// section 7: the configuration the solver chose); arms only.
    #[serde(serialize_with = "ordered_map", skip_serializing_if = "Vec::is_empty")]
    pub configurations: Vec<(&'a str, Vec<Vec<f64>>)>,
    /// Rounds of sequencing, checking and feedback (1 for `evaluate`): for the search, the
    /// rounds on the branch of the answer.
    pub iterations: usize,
    /// Schedules the checker examined (solve only): the rounds for the greedy loop, every
    /// node checked for the search.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub schedules_checked: Option<usize>,
    /// Schedules checked when the answer was found (solve, when it found one): the rest of
    /// `schedules_checked` was spent looking for a better one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub found_after: Option<usize>,
    /// Waits of the final schedule, which `evaluate` applies when given this document.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub waits: Vec<WaitJson>,
    /// Moves changed by the loop (pauses, slower moves, detours, parking), which `evaluate`
    /// replays when given this document.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub legs: Vec<LegJson>,
    /// The collision-blind best sequences, before any feedback (solve only).
    #[serde(
        serialize_with = "ordered_optional_map",
        skip_serializing_if = "Option::is_none"
    )]
    pub blind_sequences: Option<Vec<(&'a str, Vec<&'a str>)>>,
    /// Makespan of the collision-blind best schedule (solve only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub blind_makespan: Option<f64>,
    /// The sequencer proved the collision-blind schedule optimal (solve only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub blind_optimal: Option<bool>,
    /// The first collision of the final schedule, when there is one.
    pub first_collision: Option<CollisionJson>,
    /// Every round: its makespan, collision and remedy (solve only).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub feedback: Vec<RoundJson>,
    /// Why no collision-free schedule was found, if so.
    pub failure: Option<String>,
    /// Each robot's activities with their times.
    #[serde(serialize_with = "ordered_map")]
    pub schedule: Vec<(&'a str, Vec<SegmentJson<'a>>)>,
    /// The checker's counters on the final schedule.
    pub check_stats: Stats,
    /// Wall time per stage, in milliseconds.
    pub stages_ms: StagesJson,
}

/// A collision in the JSON.
#[derive(Serialize)]
pub struct CollisionJson {
    /// Time of the first contact.
    pub time: f64,
    /// The two bodies, robot first.
    pub bodies: [String; 2],
    /// What each was doing, e.g. `move weld-1 -> weld-2`, `task weld-3`, `obstacle`.
    pub activities: [String; 2],
    /// Midpoint of the closest points.
    pub point: [f64; 2],
}

/// One round of the loop in the JSON.
#[derive(Serialize)]
pub struct RoundJson {
    /// Round number, from 1.
    pub iteration: usize,
    /// Makespan of the schedule checked.
    pub makespan: f64,
    /// Its first collision.
    pub collision: Option<CollisionJson>,
    /// `"resequence"`, `"delay"`, `"pause"`, `"slow"`, `"detour"`, `"step-aside"` or null.
    pub remedy: Option<&'static str>,
    /// What the remedy changed, under its own name (`"delay": {...}`, `"pause": {...}`, ...).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub change: Option<ChangeJson>,
}

/// A wait of the final schedule in the JSON.
#[derive(Serialize)]
pub struct WaitJson {
    /// The robot that waits.
    pub robot: String,
    /// Index of the move it waits before (0: out of home).
    pub before_move: usize,
    /// That move, e.g. `move weld-1 -> weld-2`.
    pub before: String,
    /// How long.
    pub duration: f64,
}

/// The waits of a schedule in the JSON's terms.
///
/// ```
/// use serde_json::json;
/// use workcell::wcp::{report::waits_json, Delay};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// // R2 waits 1 s at home before its move to weld-4 (node 4).
/// let wait = Delay { robot: 1, before_move: 0, nodes: (0, 4), duration: 1.0 };
/// let out = serde_json::to_value(waits_json(&cell, &[wait]))?;
/// assert_eq!(out, json!([{"robot": "R2", "before_move": 0, "before": "move home -> weld-4", "duration": 1.0}]));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn waits_json(cell: &Cell, delays: &[Delay]) -> Vec<WaitJson> {
    delays
        .iter()
        .map(|d| WaitJson {
            robot: cell.robots[d.robot].name.clone(),
            before_move: d.before_move,
            before: Activity::Move {
                from: d.nodes.0,
                to: d.nodes.1,
            }
            .describe(cell, d.robot),
            duration: d.duration,
        })
        .collect()
}

/// One activity in the JSON.
#[derive(Serialize)]
pub struct SegmentJson<'a> {
    /// `move`, `task` or `wait`.
    pub activity: &'static str,
    /// Source node of a move, the node of a task or wait.
    pub at: &'a str,
    /// Target node of a move.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub to: Option<&'a str>,
    /// Start time.
    pub start: f64,
    /// End time.
    pub end: f64,
}

/// Stage times in milliseconds.
#[derive(Serialize)]
pub struct StagesJson {
    planning: f64,
    graph: f64,
    sequencing: f64,
    scheduling: f64,
    checking: f64,
}

impl From<StageTimes> for StagesJson {
    fn from(t: StageTimes) -> Self {
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        StagesJson {
            planning: ms(t.planning),
            graph: ms(t.graph),
            sequencing: ms(t.sequencing),
            scheduling: ms(t.scheduling),
            checking: ms(t.checking),
        }
    }
}

/// Each arm's joint angles at the tasks of its route, in order (see
/// [`ResultJson::configurations`]); rigid robots are left out.
///
/// ```
/// use workcell::wcp::{prepare, report::configurations_json, solve, SolveOptions};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/scara-cell.json").as_ref())?.cell;
/// let opts = SolveOptions::default();
/// let solved = solve(&cell, &prepare(&cell, &opts, &())?, &opts, &())?;
/// let chosen = configurations_json(&cell, &solved.routes, &solved.assignment);
/// assert_eq!(chosen[0].0, "A1");
/// assert_eq!(chosen[0].1.len(), solved.routes[0].len());
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn configurations_json<'a>(
    cell: &'a Cell,
    routes: &[Vec<usize>],
    assignment: &Assignment,
) -> Vec<(&'a str, Vec<Vec<f64>>)> {
    (routes.iter().enumerate())
        .filter(|&(r, _)| cell.robots[r].as_arm().is_some())
        .map(|(r, route)| {
            let joints = route
                .iter()
                .filter_map(|&t| {
                    assignment
                        .joints(cell, r, task_node(t))
                        .map(<[f64]>::to_vec)
                })
                .collect();
            (cell.robots[r].name.as_str(), joints)
        })
        .collect()
}

fn ordered_map<S: Serializer, V: Serialize>(pairs: &[(&str, V)], s: S) -> Result<S::Ok, S::Error> {
    let mut map = s.serialize_map(Some(pairs.len()))?;
    for (k, v) in pairs {
        map.serialize_entry(k, v)?;
    }
    map.end()
}

fn ordered_optional_map<S: Serializer, V: Serialize>(
    pairs: &Option<Vec<(&str, V)>>,
    s: S,
) -> Result<S::Ok, S::Error> {
    match pairs {
        Some(pairs) => ordered_map(pairs, s),
        None => s.serialize_none(),
    }
}

/// Each robot's task names, robots in the cell's order.
///
/// ```
/// use workcell::wcp::report::sequences_json;
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let named = sequences_json(&cell, &[vec![2, 0], vec![]]);
/// assert_eq!(named, [("R1", vec!["weld-3", "weld-1"]), ("R2", vec![])]);
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn sequences_json<'a>(cell: &'a Cell, routes: &[Vec<usize>]) -> Vec<(&'a str, Vec<&'a str>)> {
    cell.robots
        .iter()
        .zip(routes)
        .map(|(r, route)| {
            let names = route.iter().map(|&t| cell.tasks[t].name.as_str()).collect();
            (r.name.as_str(), names)
        })
        .collect()
}

/// A collision in the JSON's terms.
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::planning::PlannerOptions;
/// use workcell::wcp::{legs::default_legs, report::collision_json, MoveStore, Schedule};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let store = MoveStore::new(&cell, &PlannerOptions::default());
/// let schedule = Schedule::build(&cell, &[vec![1, 0, 2], vec![3]], &default_legs(2), &store).unwrap();
/// let report = check(&schedule.scene(&cell), &CheckOptions::default());
/// let c = schedule.collision(&cell, &report).expect("a collision");
/// let out = collision_json(&cell, &c);
/// assert_eq!((out.time, out.bodies.clone()), (c.time, ["R1".to_owned(), "R2".to_owned()]));
/// assert!(out.activities[1].starts_with("move ") || out.activities[1].starts_with("task "));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn collision_json(cell: &Cell, c: &Collision) -> CollisionJson {
    let b = match (c.robots.1, c.segments.1) {
        (Some(b), Some(s)) => s.activity.describe(cell, b),
        _ => "obstacle".to_owned(),
    };
    CollisionJson {
        time: c.time,
        bodies: c.bodies.clone(),
        activities: [c.segments.0.activity.describe(cell, c.robots.0), b],
        point: [c.point.x, c.point.y],
    }
}

/// The rounds of a solve in the JSON's terms.
///
/// ```
/// use workcell::wcp::{report::rounds_json, Delay, Iteration, Remedy};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// // R2 waits 1 s at home before its move to weld-4 (node 4).
/// let wait = Delay { robot: 1, before_move: 0, nodes: (0, 4), duration: 1.0 };
/// let rounds = [
///     Iteration { makespan: 15.4, collision: None, remedy: Some(Remedy::wait(wait)) },
///     Iteration { makespan: 15.9, collision: None, remedy: None },
/// ];
/// let out = rounds_json(&cell, &rounds);
/// assert_eq!((out[0].iteration, out[0].remedy, out[1].iteration, out[1].remedy), (1, Some("delay"), 2, None));
/// assert!(out[0].change.is_some() && out[1].change.is_none());
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn rounds_json(cell: &Cell, iterations: &[Iteration]) -> Vec<RoundJson> {
    iterations
        .iter()
        .enumerate()
        .map(|(k, it)| RoundJson {
            iteration: k + 1,
            makespan: it.makespan,
            collision: it.collision.as_ref().map(|c| collision_json(cell, c)),
            remedy: it.remedy.as_ref().map(remedy_name),
            change: it.remedy.as_ref().and_then(|r| change_json(cell, r)),
        })
        .collect()
}

/// Sequences and schedule of `schedule` in the JSON's terms.
///
/// ```
/// use workcell::planning::PlannerOptions;
/// use workcell::wcp::{legs::default_legs, report::schedule_json, MoveStore, Schedule};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let store = MoveStore::new(&cell, &PlannerOptions::default());
/// let schedule = Schedule::build(&cell, &[vec![0], vec![]], &default_legs(2), &store).unwrap();
/// let (sequences, timeline) = schedule_json(&cell, &schedule);
/// assert_eq!(sequences, [("R1", vec!["weld-1"]), ("R2", vec![])]);
/// let r1: Vec<(&str, &str)> = timeline[0].1.iter().map(|s| (s.activity, s.at)).collect();
/// assert_eq!(r1, [("move", "R1"), ("task", "weld-1"), ("move", "weld-1")]); // homes are named after their robot
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
#[allow(clippy::type_complexity)]
pub fn schedule_json<'a>(
    cell: &'a Cell,
    schedule: &Schedule,
) -> (
    Vec<(&'a str, Vec<&'a str>)>,
    Vec<(&'a str, Vec<SegmentJson<'a>>)>,
) {
    let routes: Vec<Vec<usize>> = schedule.robots.iter().map(|s| s.route.clone()).collect();
    let sequences = sequences_json(cell, &routes);
    let timeline = schedule
        .robots
        .iter()
        .enumerate()
        .map(|(r, s)| {
            let segments = s
                .segments
                .iter()
                .filter_map(|seg| {
                    let (activity, at, to) = match seg.activity {
                        Activity::Move { from, to } => (
                            "move",
                            node_name(cell, r, from),
                            Some(node_name(cell, r, to)),
                        ),
                        Activity::Work(t) => ("task", cell.tasks[t].name.as_str(), None),
                        Activity::Wait(node) => ("wait", node_name(cell, r, node), None),
                        Activity::Pause { from, to } => (
                            "pause",
                            node_name(cell, r, from),
                            Some(node_name(cell, r, to)),
                        ),
                        Activity::Park { from, to } => (
                            "park",
                            node_name(cell, r, from),
                            Some(node_name(cell, r, to)),
                        ),
                        Activity::Done => return None,
                    };
                    Some(SegmentJson {
                        activity,
                        at,
                        to,
                        start: seg.start,
                        end: seg.end,
                    })
                })
                .collect();
            (cell.robots[r].name.as_str(), segments)
        })
        .collect();
    (sequences, timeline)
}

/// An interval of the schedule as the summary prints it: `[2.44-4.44]`, or the start and the
/// duration when both ends print alike (`[7.81, 0.002 s]`, `[7.81, 0 s]`).
fn span(start: f64, end: f64) -> String {
    let (a, b) = (format!("{start:.2}"), format!("{end:.2}"));
    if a != b {
        return format!("[{a}-{b}]");
    }
    match end - start {
        d if d <= 0.0 => format!("[{a}, 0 s]"),
        d if d < 0.0005 => format!("[{a}, {d:.1e} s]"),
        d => format!("[{a}, {d:.3} s]"),
    }
}

/// The human summary: makespan, each robot's sequence with times, the rounds of the loop and
/// the time per stage.
///
/// ```
/// use workcell::planning::PlannerOptions;
/// use workcell::wcp::{legs::default_legs, report::summary, MoveStore, Schedule, StageTimes};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let store = MoveStore::new(&cell, &PlannerOptions::default());
/// let schedule = Schedule::build(&cell, &[vec![0, 1, 2, 3], vec![]], &default_legs(2), &store).unwrap();
/// let text = summary(&cell, &schedule, &[], None, StageTimes::default());
/// assert!(text.starts_with(&format!("makespan {:.3}\n", schedule.makespan)), "{text}");
/// assert!(text.contains("R2 stays home"), "{text}");
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn summary(
    cell: &Cell,
    schedule: &Schedule,
    rounds: &[Iteration],
    final_collision: Option<&Collision>,
    times: StageTimes,
) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "makespan {:.3}", schedule.makespan);
    for (r, s) in schedule.robots.iter().enumerate() {
        let _ = write!(out, "  {} ", cell.robots[r].name);
        if s.route.is_empty() && s.segments.len() == 1 {
            let _ = writeln!(out, "stays home");
            continue;
        }
        let mut steps = Vec::new();
        for seg in &s.segments {
            let what = match seg.activity {
                Activity::Work(t) => cell.tasks[t].name.clone(),
                Activity::Wait(_) | Activity::Pause { .. } | Activity::Park { .. } => {
                    seg.activity.describe(cell, r)
                }
                _ => continue,
            };
            steps.push(format!("{what} {}", span(seg.start, seg.end)));
        }
        let _ = writeln!(out, "{} -> home at {:.2}", steps.join(" -> "), s.end);
    }
    let lines: Vec<String> = rounds
        .iter()
        .map(|it| {
            let what = match (&it.collision, &it.remedy) {
                (None, None) => "collision-free".to_owned(),
                (None, Some(r)) => format!("collision-free; {}", remedy_text(cell, r)),
                (Some(c), Some(r)) => {
                    format!("{}; {}", describe(cell, c), remedy_text(cell, r))
                }
                (Some(c), None) => format!("{}; not fixed", describe(cell, c)),
            };
            format!("makespan {:.3}, {what}", it.makespan)
        })
        .collect();
    // Rounds that read alike (the same collision met again and the same remedy applied on
    // top, as a wait added to a wait) are one line.
    // A round like an earlier one, further back, says so: the later remedies brought the
    // same collision back.
    let mut k = 0;
    while k < lines.len() {
        let same = lines[k..].iter().take_while(|l| **l == lines[k]).count();
        let seen = lines[..k].iter().position(|l| *l == lines[k]);
        let again = seen.map_or(String::new(), |e| {
            format!(" (again, as in round {})", e + 1)
        });
        let _ = match same {
            1 => writeln!(out, "round {}: {}{again}", k + 1, lines[k]),
            n => writeln!(
                out,
                "rounds {}-{}: {}{again} ({n} rounds alike: the remedy applied again each time)",
                k + 1,
                k + n,
                lines[k]
            ),
        };
        k += same;
    }
    if rounds.is_empty() {
        let verdict = final_collision.map_or_else(
            || "collision-free".to_owned(),
            |c| format!("COLLISION: {}", describe(cell, c)),
        );
        let _ = writeln!(out, "{verdict}");
    }
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    let _ = writeln!(
        out,
        "time: planning {:.1} ms, graph {:.1} ms, sequencing {:.1} ms, scheduling {:.1} ms, checking {:.1} ms",
        ms(times.planning),
        ms(times.graph),
        ms(times.sequencing),
        ms(times.scheduling),
        ms(times.checking)
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planning::PlannerOptions;
    use crate::wcp::{legs::default_legs, MoveStore};

    #[test]
    fn intervals_too_short_to_print_give_their_duration() {
        assert_eq!(span(2.44, 4.44), "[2.44-4.44]");
        assert_eq!(span(7.81, 7.81), "[7.81, 0 s]");
        assert_eq!(span(7.811, 7.813), "[7.81, 0.002 s]");
        assert_eq!(span(7.8111, 7.81112), "[7.81, 2.0e-5 s]");
        // Ends that print apart keep the plain form, however short.
        assert_eq!(span(7.814, 7.816), "[7.81-7.82]");
    }

    #[test]
    fn rounds_that_read_alike_are_one_line_and_repeats_say_so() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
        let cell = crate::cell::load_cell(path.as_ref()).unwrap().cell;
        let store = MoveStore::new(&cell, &PlannerOptions::default());
        let schedule =
            Schedule::build(&cell, &[vec![0, 1], vec![2, 3]], &default_legs(2), &store).unwrap();
        let round = |makespan: f64| Iteration {
            makespan,
            collision: None,
            remedy: None,
        };
        let rounds = [round(2.0), round(2.0), round(2.0), round(3.0), round(2.0)];
        let text = summary(&cell, &schedule, &rounds, None, StageTimes::default());
        let lines: Vec<&str> = text.lines().filter(|l| l.starts_with("round")).collect();
        assert_eq!(
            lines,
            [
                "rounds 1-3: makespan 2.000, collision-free (3 rounds alike: the remedy applied again each time)",
                "round 4: makespan 3.000, collision-free",
                "round 5: makespan 2.000, collision-free (again, as in round 1)",
            ]
        );
    }
}
