//! SCARA cells (issue 22, item 6): 2 to 8 planar arms of 2 or 3 links around a welding table
//! (even indices) or along a conveyor (odd ones), every third cell with a rigid robot too.
//! Each task is reachable by 1 to 3 arms (the nearest ones when more reach it); half the
//! arms have an elbow that bends one way only, so some tasks are only elbow-up or only
//! elbow-down for them. Every document is read back by the cell reader and each task's
//! configurations found before it is returned: what it writes, `solve` takes.

use super::mix;
use crate::cell::parse_cell;
use crate::motion::{inverse_kinematics, IkSettings, Pose, ToolGoal};
use crate::wcp::configurations_found;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::{json, Value};
use std::f64::consts::FRAC_PI_2;
use std::path::Path;

/// Fewest and most arms.
pub const SCARA_ARMS: std::ops::RangeInclusive<usize> = 2..=8;
/// Most tasks.
pub const MAX_SCARA_TASKS: usize = 2_000;
/// Draws per task before the request is judged impossible.
const ATTEMPTS_PER_TASK: usize = 500;
/// Distance between neighbouring bases along a side (length units).
const SPACING: f64 = 2.0;
/// Distance of the bases from the edge of the work area.
const STANDOFF: f64 = 0.9;

/// A SCARA cell's size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ScaraRequest {
    /// Arms, within [`SCARA_ARMS`].
    pub arms: usize,
    /// Tasks, 1 to [`MAX_SCARA_TASKS`].
    pub tasks: usize,
}

/// One arm as drawn.
struct Arm {
    base: Pose,
    lengths: Vec<f64>,
    limits: Vec<[f64; 2]>,
    json: Value,
}

/// The file name of SCARA cell `index` of `seed`: `scara-<arms>x<tasks>-<seed>-<index>.json`.
///
/// ```
/// use workcell::generate::{scara_file_name, ScaraRequest};
/// assert_eq!(scara_file_name(&ScaraRequest { arms: 4, tasks: 40 }, 1, 0), "scara-4x40-1-0.json");
/// ```
pub fn scara_file_name(req: &ScaraRequest, seed: u64, index: u64) -> String {
    format!("scara-{}x{}-{seed}-{index}.json", req.arms, req.tasks)
}

/// SCARA cell `index` of `seed` (see the module's comment), deterministic.
///
/// ```
/// use workcell::generate::{generate_scara_cell, ScaraRequest};
/// let req = ScaraRequest { arms: 2, tasks: 6 };
/// let doc = generate_scara_cell(&req, 1, 0)?;
/// assert_eq!(doc["robots"].as_array().unwrap().len(), 2);
/// assert_eq!(doc["tasks"].as_array().unwrap().len(), 6);
/// assert_eq!(doc, generate_scara_cell(&req, 1, 0)?);
/// assert!(generate_scara_cell(&ScaraRequest { arms: 9, tasks: 6 }, 1, 0).is_err());
/// # Ok::<(), String>(())
/// ```
pub fn generate_scara_cell(req: &ScaraRequest, seed: u64, index: u64) -> Result<Value, String> {
    if !SCARA_ARMS.contains(&req.arms) {
        return Err(format!("a SCARA cell has 2 to 8 arms, not {}", req.arms));
    }
    if !(1..=MAX_SCARA_TASKS).contains(&req.tasks) {
        return Err(format!(
            "a SCARA cell has 1 to {MAX_SCARA_TASKS} tasks, not {}",
            req.tasks
        ));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(mix(mix(mix(seed) ^ 0x5CA4A) ^ index));
    let table = index.is_multiple_of(2);
    let per_side = req.arms.div_ceil(2);
    let width = SPACING * per_side as f64;
    // The work area: a table, or a conveyor's narrow band.
    let half_height = if table { 0.8 } else { 0.35 };
    let arms: Vec<Arm> = (0..req.arms)
        .map(|k| arm(&mut rng, k, width, half_height))
        .collect();
    let mut robots: Vec<Value> = arms.iter().map(|a| a.json.clone()).collect();
    let rigid = index % 3 == 2;
    if rigid {
        robots.push(json!({"name": "R1", "shape": [[-0.25, -0.25], [0.25, -0.25], [0.25, 0.25], [-0.25, 0.25]],
            "home": [width / 2.0 + 2.0, 0.0, 0.0], "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5}));
    }
    let obstacles = fixtures(&mut rng, table, per_side, width);
    // The arms at home clear of each other and of the fixtures, before any task.
    let bare = json!({"delta": 0.01, "robots": robots, "obstacles": obstacles, "tasks": []});
    parse_cell(&bare.to_string(), Path::new("scara.json")).map_err(|e| e.to_string())?;
    let mut tasks: Vec<Value> = Vec::with_capacity(req.tasks);
    let prefix = if table { "weld" } else { "pick" };
    let mut attempts = 0;
    while tasks.len() < req.tasks {
        attempts += 1;
        if attempts > ATTEMPTS_PER_TASK * req.tasks {
            return Err(format!("no room for {} reachable tasks", req.tasks));
        }
        let area = Area {
            width,
            half_height,
            prefix,
            rigid,
        };
        if let Some(task) = draw_task(&mut rng, &arms, &area, (&robots, &obstacles), tasks.len()) {
            tasks.push(task);
        }
    }
    let doc = json!({"delta": 0.01, "robots": robots, "obstacles": obstacles, "tasks": tasks});
    parse_cell(&doc.to_string(), Path::new("scara.json")).map_err(|e| e.to_string())?;
    Ok(doc)
}

/// Clamps on a table, between the arms' reaches; the end stop of a conveyor.
fn fixtures(rng: &mut ChaCha8Rng, table: bool, per_side: usize, width: f64) -> Vec<Value> {
    if table {
        (0..per_side)
            .map(|k| {
                let x = -width / 2.0 + SPACING * (k as f64 + 0.5) + rng.random_range(-0.3..0.3);
                let y = rng.random_range(-0.3..0.3);
                let h = 0.08;
                json!({"name": format!("clamp-{}", k + 1),
                       "shape": [[x - h, y - h], [x + h, y - h], [x + h, y + h], [x - h, y + h]]})
            })
            .collect()
    } else {
        let x = width / 2.0 + 0.4;
        vec![
            json!({"name": "conveyor-end", "shape": [[x, -0.4], [x + 0.3, -0.4], [x + 0.3, 0.4], [x, 0.4]]}),
        ]
    }
}

/// Where the tasks lie and what they are called.
struct Area {
    width: f64,
    half_height: f64,
    prefix: &'static str,
    /// The cell has the rigid robot R1, which may do the tasks near its end.
    rigid: bool,
}

/// Task number `done + 1` drawn in the area, allowed to the (at most 3) nearest arms that
/// reach it within their limits and clear of the fixtures; `None` when none does.
fn draw_task(
    rng: &mut ChaCha8Rng,
    arms: &[Arm],
    area: &Area,
    (robots, obstacles): (&[Value], &[Value]),
    done: usize,
) -> Option<Value> {
    let x = rng.random_range(-area.width / 2.0..area.width / 2.0);
    let y = rng.random_range(-area.half_height..area.half_height);
    let angled = rng.random_bool(0.2);
    let theta = rng.random_range(-std::f64::consts::PI..std::f64::consts::PI);
    let duration = rng.random_range(0.5..2.0);
    let goal = ToolGoal {
        pos: crate::geometry::Vec2::new(x, y),
        theta: angled.then_some(theta),
    };
    let mut reach: Vec<(f64, usize)> = (arms.iter().enumerate())
        .filter(|(_, a)| {
            let limits: Vec<Option<[f64; 2]>> = a.limits.iter().copied().map(Some).collect();
            inverse_kinematics(a.base, &a.lengths, &limits, goal, &IkSettings::default()).is_ok()
        })
        .map(|(k, a)| ((a.base.pos - goal.pos).norm(), k))
        .collect();
    reach.sort_by(|a, b| a.0.total_cmp(&b.0));
    reach.truncate(3);
    let at = if angled {
        json!([round(x), round(y), round(theta)])
    } else {
        json!([round(x), round(y)])
    };
    let task = |names: &[String]| {
        json!({"name": format!("{}-{}", area.prefix, done + 1), "at": at,
               "duration": round(duration), "robots": names})
    };
    let names: Vec<String> = reach.iter().map(|&(_, k)| format!("A{}", k + 1)).collect();
    // Kept for the arms that reach it clear of the fixtures, if any.
    let doc =
        json!({"delta": 0.01, "robots": robots, "obstacles": obstacles, "tasks": [task(&names)]});
    let read = parse_cell(&doc.to_string(), Path::new("scara.json")).ok()?;
    let found = configurations_found(&read.cell, &IkSettings::default());
    let mut able: Vec<String> = (names.iter().zip(&reach))
        .filter(|(_, &(_, k))| !found.at(k, 0).is_empty())
        .map(|(n, _)| n.clone())
        .collect();
    if able.is_empty() {
        return None;
    }
    if area.rigid && x > area.width / 2.0 - 1.0 {
        able.push("R1".into());
    }
    Some(task(&able))
}

/// Arm `k`: bases along the bottom side (even `k`) and the top side (odd), facing the work
/// area; 2 links, or 3 for every third arm; every other arm's elbow bends one way only; at
/// home, folded back away from the work area.
fn arm(rng: &mut ChaCha8Rng, k: usize, width: f64, half_height: f64) -> Arm {
    let top = k % 2 == 1;
    let x = -width / 2.0 + SPACING * ((k / 2) as f64 + 0.5);
    let (y, facing) = if top {
        (half_height + STANDOFF, -FRAC_PI_2)
    } else {
        (-half_height - STANDOFF, FRAC_PI_2)
    };
    let three = k % 3 == 2;
    let mut lengths = vec![
        round(rng.random_range(1.0..1.2)),
        round(rng.random_range(0.8..1.0)),
    ];
    let mut half_widths = vec![0.08, 0.06];
    if three {
        lengths.push(0.25);
        half_widths.push(0.05);
    }
    // Every other arm: an elbow that bends one way only.
    let elbow = match k % 4 {
        1 => [0.15, 2.6],
        3 => [-2.6, -0.15],
        _ => [-2.6, 2.6],
    };
    let mut limits = vec![[-2.5, 2.5], elbow];
    if three {
        limits.push([-3.0, 3.0]);
    }
    // Every arm's first link back and to the same side (neighbours stay parallel), the
    // second folded along it.
    let fold = if elbow[1] > 0.0 { 2.3 } else { -2.3 };
    let mut home = vec![-2.3, fold];
    if three {
        home.push(0.0);
    }
    let links: Vec<Value> = (lengths.iter().zip(&half_widths))
        .map(|(&l, &w)| json!({"length": l, "shape": [[-w, -w], [l + w, -w], [l + w, w], [-w, w]]}))
        .collect();
    let speeds = [1.5, 2.5, 3.0];
    let accels = [3.0, 5.0, 6.0];
    let n = lengths.len();
    Arm {
        base: Pose::new(x, y, facing),
        json: json!({"name": format!("A{}", k + 1), "base": [round(x), round(y), facing],
                     "links": links, "home": home, "joint_limits": limits,
                     "max_joint_speed": speeds[..n], "max_joint_accel": accels[..n]}),
        lengths,
        limits,
    }
}

fn round(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}
