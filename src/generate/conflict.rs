//! Cells whose robots get in each other's way, for the feedback loop and its benchmark.
//!
//! Six families, each built so that the collision-blind best schedule collides and some
//! remedy separates the robots: corridor swaps (narrow: one robot at a time; wide: room to
//! pass side by side), a four-arm junction whose robots work beside each other's homes, a
//! doorway into a closed room that several robots must pass, a home that lies in another
//! robot's only way (a dead-end corridor), and a workpiece whose welds neighbouring robots
//! share. Robots are squares of side 0.7 with the limits of the shipped cells; δ = 0.01.
//! Every document is a cell in the contract's format (section 3), deterministic in
//! (family, seed, index).

use super::mix;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::{json, Value};
use std::f64::consts::FRAC_PI_2;

/// The families of conflict cells.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConflictKind {
    /// Two robots swap sides through a corridor 1.0 wide: one at a time. Index k gives each
    /// robot 1 + k mod 2 tasks on the far side.
    CorridorNarrow,
    /// The same swap through a corridor 2.4 wide: room to pass side by side.
    CorridorWide,
    /// Four robots at the ends of a plus-shaped crossing between four blocks, each working at
    /// the far end of the opposite arm, 1.6 beside that arm's robot's home (1 + k mod 2
    /// tasks each); the space outside the blocks is open.
    Junction,
    /// 4 + k mod 5 robots outside a closed room with one door 1.2 wide; each has two tasks
    /// inside, which it or its neighbour may do.
    Doorway,
    /// A dead-end corridor 1.2 wide holds one robot's tasks; another robot's home lies in it,
    /// near its mouth. That robot has k mod 3 tasks outside (none: it must step aside).
    HomeInWay,
    /// 4 + 2·(k mod 5) robots (up to 12) along both long sides of a workpiece, ten welds per
    /// robot along its sides (up to 120), each weld allowed to the two nearest robots of its
    /// side: neighbours working near their common border collide.
    Workpiece,
}

impl ConflictKind {
    /// Every family, in documentation order.
    pub const ALL: [ConflictKind; 6] = [
        ConflictKind::CorridorNarrow,
        ConflictKind::CorridorWide,
        ConflictKind::Junction,
        ConflictKind::Doorway,
        ConflictKind::HomeInWay,
        ConflictKind::Workpiece,
    ];

    /// The name on the command line and in file names, e.g. `corridor-narrow`.
    pub fn name(self) -> &'static str {
        match self {
            ConflictKind::CorridorNarrow => "corridor-narrow",
            ConflictKind::CorridorWide => "corridor-wide",
            ConflictKind::Junction => "junction",
            ConflictKind::Doorway => "doorway",
            ConflictKind::HomeInWay => "home-in-way",
            ConflictKind::Workpiece => "workpiece",
        }
    }

    /// The family of a name, if it is one.
    ///
    /// ```
    /// use workcell::generate::ConflictKind;
    /// assert_eq!(ConflictKind::from_name("doorway"), Some(ConflictKind::Doorway));
    /// assert_eq!(ConflictKind::from_name("door"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<ConflictKind> {
        ConflictKind::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// The file name of cell `index` of a run: `<family>-<seed>-<index>-cell.json` (the
/// `-cell.json` ending keeps it out of `compare`'s folders of scenes).
///
/// ```
/// use workcell::generate::{conflict_file_name, ConflictKind};
/// assert_eq!(conflict_file_name(ConflictKind::HomeInWay, 2, 0), "home-in-way-2-0-cell.json");
/// ```
pub fn conflict_file_name(kind: ConflictKind, seed: u64, index: u64) -> String {
    format!("{}-{seed}-{index}-cell.json", kind.name())
}

/// Cell `index` of family `kind` for `seed`, as a JSON document in the cell format.
///
/// ```
/// use workcell::cell::parse_cell;
/// use workcell::generate::{generate_conflict_cell, ConflictKind};
/// let doc = generate_conflict_cell(ConflictKind::Doorway, 0, 1);
/// let cell = parse_cell(&doc.to_string(), "doorway.json".as_ref())?.cell;
/// // 4 + k mod 5 robots, two tasks inside the room each.
/// assert_eq!((cell.robots.len(), cell.tasks.len()), (5, 10));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn generate_conflict_cell(kind: ConflictKind, seed: u64, index: u64) -> Value {
    let kind_no = ConflictKind::ALL.iter().position(|k| *k == kind).unwrap() as u64;
    // Offset from the scene kinds' numbers, so that no scene and cell share a stream.
    let mut rng = ChaCha8Rng::seed_from_u64(mix(mix(mix(seed) ^ (100 + kind_no)) ^ index));
    let mut cell = CellDoc::default();
    let k = index as usize;
    match kind {
        ConflictKind::CorridorNarrow => corridor(&mut cell, &mut rng, 1.0, 1 + k % 2),
        ConflictKind::CorridorWide => corridor(&mut cell, &mut rng, 2.4, 1 + k % 2),
        ConflictKind::Junction => junction(&mut cell, &mut rng, 1 + k % 2),
        ConflictKind::Doorway => doorway(&mut cell, &mut rng, 4 + k % 5),
        ConflictKind::HomeInWay => home_in_way(&mut cell, &mut rng, k % 3),
        ConflictKind::Workpiece => workpiece(&mut cell, &mut rng, 4 + 2 * (k % 5)),
    }
    cell.document()
}

/// Half the side of every robot's square.
const HALF: f64 = 0.35;

/// A cell document under construction.
#[derive(Default)]
struct CellDoc {
    robots: Vec<Value>,
    obstacles: Vec<Value>,
    tasks: Vec<Value>,
}

impl CellDoc {
    /// A square robot `R<n>` at `home` (θ = 0); returns its name.
    fn robot(&mut self, x: f64, y: f64) -> String {
        let name = format!("R{}", self.robots.len() + 1);
        self.robots.push(json!({
            "name": name,
            "shape": [[-HALF, -HALF], [HALF, -HALF], [HALF, HALF], [-HALF, HALF]],
            "home": [x, y, 0.0],
            "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5,
        }));
        name
    }

    /// An axis-aligned block from (x0, y0) to (x1, y1).
    fn block(&mut self, name: &str, x0: f64, y0: f64, x1: f64, y1: f64) {
        let (x0, x1, y0, y1) = (x0.min(x1), x0.max(x1), y0.min(y1), y0.max(y1));
        self.obstacles.push(json!({
            "name": name,
            "shape": [[x0, y0], [x1, y0], [x1, y1], [x0, y1]],
        }));
    }

    /// A task at (x, y), θ = 0, for the robots named.
    fn task(&mut self, name: String, x: f64, y: f64, duration: f64, robots: &[&str]) {
        self.tasks.push(json!({
            "name": name, "at": [x, y, 0.0], "duration": duration, "robots": robots,
        }));
    }

    fn document(self) -> Value {
        json!({
            "delta": 0.01,
            "robots": self.robots,
            "obstacles": self.obstacles,
            "tasks": self.tasks,
        })
    }
}

/// Task durations: 1 to 3 time units, rounded to a tenth.
fn duration(rng: &mut ChaCha8Rng) -> f64 {
    (rng.random_range(10..=30) as f64) / 10.0
}

/// Two robots swap sides through a corridor of `width` between two blocks reaching 6 above
/// and below it (going round them is far longer than waiting).
fn corridor(cell: &mut CellDoc, rng: &mut ChaCha8Rng, width: f64, tasks: usize) {
    let length = rng.random_range(6.0..9.0f64).round();
    let (h, l) = (width / 2.0, length / 2.0);
    cell.block("wall-north", -l, h, l, h + 6.0);
    cell.block("wall-south", -l, -h - 6.0, l, -h);
    let a = cell.robot(-l - 2.5, 1.5);
    let b = cell.robot(l + 2.5, 1.5);
    // Each robot's tasks lie on the other side, below the other's home.
    for (owner, side) in [(&a, 1.0), (&b, -1.0)] {
        let spots = [(l + 2.5, -1.5), (l + 4.0, 0.3)];
        for (j, &(x, y)) in spots.iter().take(tasks).enumerate() {
            let name = format!("{owner}-weld-{}", j + 1);
            let d = duration(rng);
            cell.task(name, side * x, y, d, &[owner]);
        }
    }
}

/// Four blocks leave a plus-shaped crossing with arms 1.2 wide.
fn junction(cell: &mut CellDoc, rng: &mut ChaCha8Rng, tasks: usize) {
    let arm = 0.6;
    let size = rng.random_range(4.0..5.0f64).round();
    for (k, (sx, sy)) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
        .into_iter()
        .enumerate()
    {
        let name = format!("block-{}", k + 1);
        cell.block(
            &name,
            sx * arm,
            sy * arm,
            sx * (arm + size),
            sy * (arm + size),
        );
    }
    let reach = arm + size + 1.0;
    let dir = |i: usize| {
        let (s, c) = (i as f64 * FRAC_PI_2).sin_cos();
        (c, s)
    };
    let names: Vec<String> = (0..4)
        .map(|i| {
            let (c, s) = dir(i);
            cell.robot(reach * c, reach * s)
        })
        .collect();
    for (i, owner) in names.iter().enumerate() {
        // At the opposite arm's end, beside its robot's home (to the left of the way there).
        let (c, s) = dir(i);
        let (u, v) = ((-c, -s), (s, -c));
        let spots = [(reach, 1.6), (reach + 1.5, -1.4)];
        for (j, &(along, aside)) in spots.iter().take(tasks).enumerate() {
            let (x, y) = (u.0 * along + v.0 * aside, u.1 * along + v.1 * aside);
            let d = duration(rng);
            cell.task(format!("{owner}-weld-{}", j + 1), x, y, d, &[owner]);
        }
    }
}

/// A closed room right of x = 0 with one door 1.2 wide in its left wall; the robots wait
/// outside on the left.
fn doorway(cell: &mut CellDoc, rng: &mut ChaCha8Rng, robots: usize) {
    let h = (0.75 * robots as f64).max(3.0);
    let (door, wall, depth) = (0.6, 0.3, 8.0);
    cell.block("wall-left-low", 0.0, -h - wall, wall, -door);
    cell.block("wall-left-high", 0.0, door, wall, h + wall);
    cell.block("wall-top", wall, h, depth + wall, h + wall);
    cell.block("wall-bottom", wall, -h - wall, depth + wall, -h);
    cell.block("wall-right", depth, -h, depth + wall, h);
    let step = (2.0 * h - 1.6) / (robots - 1) as f64;
    let names: Vec<String> = (0..robots)
        .map(|i| cell.robot(-3.5, -h + 0.8 + step * i as f64))
        .collect();
    // Task spots on a grid inside the room, 1.5 apart, drawn without repetition.
    let mut spots: Vec<(f64, f64)> = Vec::new();
    let rows = ((2.0 * h - 2.0) / 1.5).floor() as usize + 1;
    for col in 0..5 {
        for row in 0..rows {
            spots.push((1.5 + 1.5 * col as f64, -h + 1.0 + 1.5 * row as f64));
        }
    }
    for (i, owner) in names.iter().enumerate() {
        let neighbour = &names[(i + 1) % robots];
        for j in 0..2 {
            let (x, y) = spots.swap_remove(rng.random_range(0..spots.len()));
            let d = duration(rng);
            cell.task(
                format!("{owner}-weld-{}", j + 1),
                x,
                y,
                d,
                &[owner, neighbour],
            );
        }
    }
}

/// A dead-end corridor along +x from x = 0, 1.2 wide; R1's tasks are at its end, R2's home
/// just inside its mouth.
fn home_in_way(cell: &mut CellDoc, rng: &mut ChaCha8Rng, outside: usize) {
    let length = rng.random_range(5.0..7.0f64).round();
    let h = 0.6;
    cell.block("wall-north", 0.0, h, length, h + 3.0);
    cell.block("wall-south", 0.0, -h - 3.0, length, -h);
    cell.block("wall-end", length, -h - 3.0, length + 0.5, h + 3.0);
    let a = cell.robot(-3.0, -1.5);
    let b = cell.robot(1.2, 0.0);
    for (j, x) in [length - 0.8, length - 2.5].into_iter().enumerate() {
        let d = duration(rng);
        cell.task(format!("{a}-weld-{}", j + 1), x, 0.0, d, &[&a]);
    }
    for (j, &(x, y)) in [(-3.0, 2.0), (-5.0, 0.5)].iter().take(outside).enumerate() {
        let d = duration(rng);
        cell.task(format!("{b}-weld-{}", j + 1), x, y, d, &[&b]);
    }
}

/// A workpiece 2 high with `robots / 2` robots along each long side, 2.5 away, and ten
/// welds per robot 0.5 off its sides.
fn workpiece(cell: &mut CellDoc, rng: &mut ChaCha8Rng, robots: usize) {
    let per_side = robots / 2;
    let length = 1.6 * per_side as f64 + 2.0;
    let (l, h) = (length / 2.0, 1.0);
    cell.block("workpiece", -l, -h, l, h);
    let pitch = length / per_side as f64;
    let mut sides: Vec<Vec<(f64, String)>> = Vec::new();
    for sign in [1.0, -1.0] {
        let side = (0..per_side)
            .map(|j| {
                let x = -l + (j as f64 + 0.5) * pitch;
                (x, cell.robot(x, sign * (h + 2.5)))
            })
            .collect();
        sides.push(side);
    }
    let welds = 10 * per_side;
    for (side, sign) in sides.iter().zip([1.0, -1.0]) {
        for w in 0..welds {
            let x = -l + (w as f64 + 0.5) * length / welds as f64;
            // The two robots of this side whose homes are nearest (ties: lower index).
            let mut near: Vec<&(f64, String)> = side.iter().collect();
            near.sort_by(|a, b| (a.0 - x).abs().total_cmp(&(b.0 - x).abs()));
            let allowed: Vec<&str> = near.iter().take(2).map(|(_, n)| n.as_str()).collect();
            let d = (rng.random_range(5..=15) as f64) / 10.0;
            let name = format!(
                "{}-weld-{}",
                if sign > 0.0 { "top" } else { "bottom" },
                w + 1
            );
            cell.task(name, x, sign * (h + 0.5), d, &allowed);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::parse_cell;

    #[test]
    fn every_family_parses_and_is_deterministic() {
        for kind in ConflictKind::ALL {
            for k in 0..5 {
                let doc = generate_conflict_cell(kind, 1, k);
                assert_eq!(doc, generate_conflict_cell(kind, 1, k));
                let text = doc.to_string();
                let loaded = parse_cell(&text, "generated.json".as_ref())
                    .unwrap_or_else(|e| panic!("{} {k}: {e}", kind.name()));
                assert!(
                    loaded.warnings.is_empty(),
                    "{}: {:?}",
                    kind.name(),
                    loaded.warnings
                );
            }
        }
    }

    #[test]
    fn sizes_span_four_to_twelve_robots_and_up_to_120_tasks() {
        let count = |kind, k| {
            let doc = generate_conflict_cell(kind, 1, k);
            (
                doc["robots"].as_array().unwrap().len(),
                doc["tasks"].as_array().unwrap().len(),
            )
        };
        assert_eq!(count(ConflictKind::Workpiece, 4), (12, 120));
        assert_eq!(count(ConflictKind::Workpiece, 0), (4, 40));
        assert_eq!(count(ConflictKind::Doorway, 4), (8, 16));
        assert_eq!(count(ConflictKind::Junction, 1), (4, 8));
        assert_eq!(count(ConflictKind::HomeInWay, 0).1, 2);
    }
}
