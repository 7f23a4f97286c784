//! The remedies of the feedback loop in the result's terms: their names, what each changed
//! (the JSON of a round) and a sentence for the summary.

use super::feedback::{Remedy, RemedyKind, Shortening};
use super::schedule::Activity;
use crate::cell::Cell;
use serde::Serialize;

/// What a round's remedy changed, serialised under the remedy's name.
#[derive(Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ChangeJson {
    /// A wait at a node.
    Delay(DelayJson),
    /// A stop on the way.
    Pause(PauseJson),
    /// A move slowed down.
    Slow(SlowJson),
    /// A move by another way.
    Detour(DetourJson),
    /// A way by a parking pose.
    StepAside(StepAsideJson),
    /// An arm in another configuration at a task.
    Reconfigure(ReconfigureJson),
    /// A robot in another's way leaves ahead of it; the other waits.
    MakeWay(MakeWayJson),
    /// Two robots keep to opposite sides of the line they meet along.
    Lanes(LanesJson),
    /// Two robots' moves timed together.
    Tune(TuneJson),
    /// Every robot of a loop round it together.
    Convoy(ConvoyJson),
    /// A certified schedule's slack shortened.
    Tighten(TightenJson),
}

/// A certified schedule's slack shortened as far as the other robots allow, in the order
/// each was first shortened.
#[derive(Serialize)]
pub struct TightenJson {
    /// Each one shortened.
    pub shortened: Vec<ShortenedJson>,
}

/// A wait, hold or slowed motion shortened.
#[derive(Serialize)]
pub struct ShortenedJson {
    /// The robot.
    pub robot: String,
    /// Its move: the wait before it, or a hold on its way (a pause, a stay at a parking
    /// pose).
    pub on: String,
    /// `wait` (before the move), `pause` (on its way), `park` (at a parking pose on its
    /// way) or `slow` (a motion of it run slower).
    pub kind: &'static str,
    /// How long it was: seconds, or for `slow` how many times slower than planned.
    pub before: f64,
    /// How long it is.
    pub after: f64,
}

/// Every robot of a closed corridor round it together, the same way.
#[derive(Serialize)]
pub struct ConvoyJson {
    /// The robot whose collision it answers.
    pub robot: String,
    /// Its move there.
    pub on: String,
    /// The robots that go round.
    pub robots: Vec<String>,
    /// `counter-clockwise` or `clockwise`, seen from above.
    pub direction: &'static str,
    /// Whole laps of the loop.
    pub laps: usize,
    /// Each robot goes on as far as the one ahead leaves room (else all stop while any
    /// works, as one rigid ring).
    pub following: bool,
    /// The loop, a closed path of G.
    pub path: Vec<[f64; 2]>,
}

/// Two robots' moves timed together: both keep their paths, each holds where listed.
#[derive(Serialize)]
pub struct TuneJson {
    /// The first robot.
    pub robot: String,
    /// Its move.
    pub on: String,
    /// The other robot.
    pub with: String,
    /// The other's move.
    pub with_on: String,
    /// Every stop of the two, robot by robot, in time order.
    pub holds: Vec<TunedHoldJson>,
}

/// A stop of a robot on a move timed with another's.
#[derive(Serialize)]
pub struct TunedHoldJson {
    /// The robot.
    pub robot: String,
    /// Where G stops.
    pub at: [f64; 2],
    /// How long.
    pub duration: f64,
}

/// Two robots that meet while both move keep to opposite sides of the line they meet along.
#[derive(Serialize)]
pub struct LanesJson {
    /// The first robot.
    pub robot: String,
    /// Its move.
    pub on: String,
    /// The other robot.
    pub with: String,
    /// The other's move.
    pub with_on: String,
    /// The first robot's new path of G.
    pub path: Vec<[f64; 2]>,
    /// The other's new path of G.
    pub with_path: Vec<[f64; 2]>,
}

/// A robot standing in another's way leaves by another way, ahead of it; the other waits.
#[derive(Serialize)]
pub struct MakeWayJson {
    /// The robot that makes way.
    pub robot: String,
    /// The move it leaves by.
    pub on: String,
    /// The robot it makes way for.
    pub ahead_of: String,
    /// Its new path of G.
    pub path: Vec<[f64; 2]>,
    /// How long the other robot waits before its move.
    pub wait: f64,
}

/// An arm in another configuration at a task.
#[derive(Serialize)]
pub struct ReconfigureJson {
    /// The arm.
    pub robot: String,
    /// The task.
    pub at: String,
    /// Its joint angles there.
    pub joints: Vec<f64>,
}

/// A wait at a node.
#[derive(Serialize)]
pub struct DelayJson {
    /// The robot that waits.
    pub robot: String,
    /// The move it waits before, e.g. `move weld-1 -> weld-2`.
    pub before: String,
    /// How long.
    pub duration: f64,
}

/// A stop at a point of a move's path.
#[derive(Serialize)]
pub struct PauseJson {
    /// The robot.
    pub robot: String,
    /// The move, e.g. `move home -> weld-2`.
    pub on: String,
    /// Where G stops.
    pub at: [f64; 2],
    /// How long it waits there.
    pub duration: f64,
}

/// A move made slower.
#[derive(Serialize)]
pub struct SlowJson {
    /// The robot.
    pub robot: String,
    /// The move.
    pub on: String,
    /// How many times slower than planned.
    pub factor: f64,
}

/// A move made by another way.
#[derive(Serialize)]
pub struct DetourJson {
    /// The robot.
    pub robot: String,
    /// The move.
    pub on: String,
    /// The robot it goes around.
    pub around: String,
    /// The new path of G.
    pub path: Vec<[f64; 2]>,
}

/// A way by a parking pose.
#[derive(Serialize)]
pub struct StepAsideJson {
    /// The robot.
    pub robot: String,
    /// The move that goes by the parking pose.
    pub on: String,
    /// The parking pose `[x, y, theta]`.
    pub park: [f64; 3],
    /// How long it waits there.
    pub duration: f64,
}

/// The remedy's name in the JSON and on the command line.
///
/// ```
/// use workcell::wcp::{remedy_json::remedy_name, Delay, Remedy};
/// let wait = Delay { robot: 1, before_move: 0, nodes: (0, 4), duration: 1.0 };
/// assert_eq!((remedy_name(&Remedy::RESEQUENCE), remedy_name(&Remedy::wait(wait))), ("resequence", "delay"));
/// ```
pub fn remedy_name(r: &Remedy) -> &'static str {
    match r.kind {
        RemedyKind::Resequence => "resequence",
        RemedyKind::Wait { .. } => "delay",
        RemedyKind::Pause { .. } => "pause",
        RemedyKind::Slow { .. } => "slow",
        RemedyKind::Detour { .. } => "detour",
        RemedyKind::StepAside { .. } => "step-aside",
        RemedyKind::MakeWay { .. } => "make-way",
        RemedyKind::Lanes { .. } => "lanes",
        RemedyKind::Tune { .. } => "tune",
        RemedyKind::Convoy { .. } => "convoy",
        RemedyKind::Reconfigure { .. } => "reconfigure",
        RemedyKind::Tighten { .. } => "tighten",
    }
}

fn names(cell: &Cell, robots: &[usize]) -> Vec<String> {
    robots
        .iter()
        .map(|&r| cell.robots[r].name.clone())
        .collect()
}

fn direction(counter_clockwise: bool) -> &'static str {
    match counter_clockwise {
        true => "counter-clockwise",
        false => "clockwise",
    }
}

pub(super) fn move_name(cell: &Cell, robot: usize, (from, to): (usize, usize)) -> String {
    Activity::Move { from, to }.describe(cell, robot)
}

/// What the remedy changed, or `None` for a re-sequencing (the new sequences say it).
///
/// ```
/// use serde_json::json;
/// use workcell::wcp::{remedy_json::change_json, Delay, Remedy};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// // R2 waits 1 s at home before its move to weld-4 (node 4).
/// let wait = Delay { robot: 1, before_move: 0, nodes: (0, 4), duration: 1.0 };
/// assert!(change_json(&cell, &Remedy::RESEQUENCE).is_none()); // the new sequences say it
/// let out = serde_json::to_value(change_json(&cell, &Remedy::wait(wait)))?;
/// assert_eq!(out, json!({"delay": {"robot": "R2", "before": "move home -> weld-4", "duration": 1.0}}));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn change_json(cell: &Cell, r: &Remedy) -> Option<ChangeJson> {
    let leg = r.on?;
    let robot = cell.robots[leg.robot].name.clone();
    let on = move_name(cell, leg.robot, leg.nodes);
    Some(match &r.kind {
        RemedyKind::Resequence => return None,
        RemedyKind::Wait { duration } => ChangeJson::Delay(DelayJson {
            robot,
            before: on,
            duration: *duration,
        }),
        RemedyKind::Pause { at, duration } => ChangeJson::Pause(PauseJson {
            robot,
            on,
            at: [at.x, at.y],
            duration: *duration,
        }),
        RemedyKind::Slow { factor } => ChangeJson::Slow(SlowJson {
            robot,
            on,
            factor: *factor,
        }),
        RemedyKind::Detour { around, path } => ChangeJson::Detour(DetourJson {
            robot,
            on,
            around: cell.robots[*around].name.clone(),
            path: path.iter().map(|p| [p.x, p.y]).collect(),
        }),
        RemedyKind::StepAside { park, duration } => ChangeJson::StepAside(StepAsideJson {
            robot,
            on,
            park: [park.pos.x, park.pos.y, park.theta],
            duration: *duration,
        }),
        RemedyKind::MakeWay {
            ahead_of,
            path,
            wait,
        } => ChangeJson::MakeWay(MakeWayJson {
            robot,
            on,
            ahead_of: cell.robots[*ahead_of].name.clone(),
            path: path.iter().map(|p| [p.x, p.y]).collect(),
            wait: *wait,
        }),
        RemedyKind::Lanes {
            with,
            path,
            with_path,
        } => ChangeJson::Lanes(LanesJson {
            robot,
            on,
            with: cell.robots[with.robot].name.clone(),
            with_on: move_name(cell, with.robot, with.nodes),
            path: path.iter().map(|p| [p.x, p.y]).collect(),
            with_path: with_path.iter().map(|p| [p.x, p.y]).collect(),
        }),
        RemedyKind::Tune { with, holds } => ChangeJson::Tune(TuneJson {
            robot,
            on,
            with: cell.robots[with.robot].name.clone(),
            with_on: move_name(cell, with.robot, with.nodes),
            holds: (holds.iter())
                .map(|h| TunedHoldJson {
                    robot: cell.robots[h.robot].name.clone(),
                    at: [h.at.x, h.at.y],
                    duration: h.duration,
                })
                .collect(),
        }),
        RemedyKind::Convoy {
            robots,
            counter_clockwise,
            laps,
            following,
            loop_path,
        } => ChangeJson::Convoy(ConvoyJson {
            robot,
            on,
            robots: names(cell, robots),
            direction: direction(*counter_clockwise),
            laps: *laps,
            following: *following,
            path: loop_path.iter().map(|p| [p.x, p.y]).collect(),
        }),
        RemedyKind::Reconfigure { task, joints } => ChangeJson::Reconfigure(ReconfigureJson {
            robot,
            at: cell.tasks[*task].name.clone(),
            joints: joints.clone(),
        }),
        RemedyKind::Tighten { shortened } => ChangeJson::Tighten(TightenJson {
            shortened: (shortened.iter())
                .map(|h| ShortenedJson {
                    robot: cell.robots[h.robot].name.clone(),
                    on: move_name(cell, h.robot, h.nodes),
                    kind: match h.kind {
                        Shortening::Wait => "wait",
                        Shortening::Pause => "pause",
                        Shortening::Park => "park",
                        Shortening::Slow => "slow",
                        Shortening::Straight => "straight",
                    },
                    before: h.before,
                    after: h.after,
                })
                .collect(),
        }),
    })
}

/// The remedy in a sentence, e.g. `R2 waits 1.000 before its move home -> weld-4`.
///
/// ```
/// use workcell::wcp::{remedy_json::remedy_text, Delay, Remedy};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// // R2 waits 1 s at home before its move to weld-4 (node 4).
/// let wait = Delay { robot: 1, before_move: 0, nodes: (0, 4), duration: 1.0 };
/// assert_eq!(remedy_text(&cell, &Remedy::wait(wait)), "R2 waits 1.000 before its move home -> weld-4");
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn remedy_text(cell: &Cell, r: &Remedy) -> String {
    // A duration to three decimals, unless that would read as none.
    let seconds = |d: f64| match d > 0.0 && d < 0.0005 {
        true => format!("{d:.1e}"),
        false => format!("{d:.3}"),
    };
    let Some(leg) = r.on else {
        return "re-sequenced".to_owned();
    };
    let who = cell.robots[leg.robot].name.as_str();
    let on = move_name(cell, leg.robot, leg.nodes);
    match &r.kind {
        RemedyKind::Resequence => "re-sequenced".to_owned(),
        RemedyKind::Wait { duration } => {
            format!("{who} waits {} before its {on}", seconds(*duration))
        }
        RemedyKind::Pause { at, duration } => format!(
            "{who} pauses {} at ({:.3}, {:.3}) on its {on}",
            seconds(*duration),
            at.x,
            at.y
        ),
        RemedyKind::Slow { factor } => format!("{who} makes its {on} {factor:.3} times slower"),
        RemedyKind::Detour { around, path } => format!(
            "{who} goes round {} on its {on} ({} waypoints)",
            cell.robots[*around].name,
            path.len()
        ),
        RemedyKind::StepAside { park, duration } => format!(
            "{who} steps aside to ({:.3}, {:.3}) for {} on its {on}",
            park.pos.x,
            park.pos.y,
            seconds(*duration)
        ),
        RemedyKind::MakeWay {
            ahead_of,
            path,
            wait,
        } => format!(
            "{who} makes way for {} on its {on} ({} waypoints), which waits {}",
            cell.robots[*ahead_of].name,
            path.len(),
            seconds(*wait)
        ),
        RemedyKind::Lanes { with, .. } => format!(
            "{who} and {} keep to opposite sides as they meet ({on}; {})",
            cell.robots[with.robot].name,
            move_name(cell, with.robot, with.nodes)
        ),
        RemedyKind::Tune { with, holds } => {
            let stops: Vec<String> = (holds.iter())
                .map(|h| {
                    let (r, d) = (&cell.robots[h.robot].name, seconds(h.duration));
                    format!("{r} holds {d} at ({:.3}, {:.3})", h.at.x, h.at.y)
                })
                .collect();
            format!(
                "{who} and {} time their moves together ({on}; {}): {}",
                cell.robots[with.robot].name,
                move_name(cell, with.robot, with.nodes),
                stops.join(", ")
            )
        }
        RemedyKind::Convoy {
            robots,
            counter_clockwise,
            laps,
            following,
            ..
        } => {
            let laps = match laps {
                1 => "one lap".to_owned(),
                n => format!("{n} laps"),
            };
            let how = match following {
                true => "each following the one ahead",
                false => "each working at its tasks while the others hold",
            };
            format!(
                "{} go round the loop together, {} ({laps}), {how} (for {who} on its {on})",
                names(cell, robots).join(", "),
                direction(*counter_clockwise)
            )
        }
        RemedyKind::Tighten { shortened } => {
            let each: Vec<String> = (shortened.iter())
                .map(|h| {
                    let (r, on) = (
                        &cell.robots[h.robot].name,
                        move_name(cell, h.robot, h.nodes),
                    );
                    let (after, before) = (seconds(h.after), seconds(h.before));
                    match h.kind {
                        Shortening::Wait => {
                            format!("{r} waits {after} (was {before}) before its {on}")
                        }
                        Shortening::Pause => {
                            format!("{r} pauses {after} (was {before}) on its {on}")
                        }
                        Shortening::Park => {
                            format!("{r} stays aside {after} (was {before}) on its {on}")
                        }
                        Shortening::Slow => format!(
                            "{r} makes its {on} {:.3} times slower (was {:.3})",
                            h.after, h.before
                        ),
                        Shortening::Straight => {
                            format!("{r} takes its planned way on its {on}: {after} (was {before})")
                        }
                    }
                })
                .collect();
            // The JSON lists them all; a sentence, the first few.
            const SAID: usize = 4;
            match each.len() {
                n if n > SAID => format!(
                    "shortened: {}; and {} more",
                    each[..SAID].join("; "),
                    n - SAID
                ),
                _ => format!("shortened: {}", each.join("; ")),
            }
        }
        RemedyKind::Reconfigure { task, joints } => {
            let angles: Vec<String> = joints.iter().map(|a| format!("{a:.3}")).collect();
            let task = &cell.tasks[*task].name;
            format!(
                "{who} takes the configuration [{}] at {task}",
                angles.join(", ")
            )
        }
    }
}
