//! Cells whose robots get in each other's way, for the feedback loop and its benchmark.
//!
//! Eight families, each built so that the collision-blind best schedule collides (a ring of
//! three robots may not): corridor
//! swaps (narrow: one robot at a time; wide: room to pass side by side), a four-arm junction
//! whose robots work beside each other's homes, a doorway into a closed room that several
//! robots must pass, a home that lies in another robot's only way (a dead-end corridor), a
//! workpiece whose welds neighbouring robots share, closed ring corridors one robot wide
//! (robots that can never pass each other, only move round together) and a grid of aisles
//! that robots cross to far tasks. Every family but the rings is solved by one robot
//! yielding to another; the rings ask for a group to move at once (a convoy). Robots are
//! squares of side 0.7 with the limits of the shipped cells; δ = 0.01. Every document is a
//! cell in the contract's format (section 3), deterministic in (family, seed, index).

use super::mix;
use rand::seq::SliceRandom;
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
    /// 3 + (k / 2) mod 6 robots (3 to 8) on a closed ring corridor 1.05 wide round a central
    /// block, square for even k, a long oval (a long rectangle) for odd k; each robot's one
    /// task lies past the next one or two robots' homes, clockwise for some robots and
    /// counter-clockwise for others. Robots on a ring never pass each other.
    Ring,
    /// 6 + k mod 3 robots at the mouths of the aisles of a 3 × 3 grid of blocks, aisles 1.3
    /// wide (one robot at a time); each robot has a task past the far mouth of its aisle and
    /// one at the middle of a crossing aisle.
    Aisles,
}

impl ConflictKind {
    /// Every family, in documentation order.
    pub const ALL: [ConflictKind; 8] = [
        ConflictKind::CorridorNarrow,
        ConflictKind::CorridorWide,
        ConflictKind::Junction,
        ConflictKind::Doorway,
        ConflictKind::HomeInWay,
        ConflictKind::Workpiece,
        ConflictKind::Ring,
        ConflictKind::Aisles,
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
            ConflictKind::Ring => "ring",
            ConflictKind::Aisles => "aisles",
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
        ConflictKind::Ring => ring(&mut cell, &mut rng, 3 + (k / 2) % 6, k % 2 == 1),
        ConflictKind::Aisles => aisles(&mut cell, &mut rng, 6 + k % 3),
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

/// Width of a ring's corridor: one robot (0.7) with room to move, never two.
const RING_WIDTH: f64 = 1.05;
// Two robots side by side, each δ = 0.01 clear, would need 4 HALF + 2 δ.
const _: () = assert!(RING_WIDTH > 2.0 * HALF && RING_WIDTH < 4.0 * HALF + 0.02);
/// Arc length between two robots' homes along a ring's centre line.
const RING_SPACING: f64 = 2.6;

/// The point at arc length `s` along the centre line of a rectangular ring of half sizes
/// (a, b), counter-clockwise from its bottom right corner.
fn along_ring(a: f64, b: f64, s: f64) -> (f64, f64) {
    let s = s.rem_euclid(4.0 * (a + b));
    let sides = [
        (2.0 * b, (a, -b), (0.0, 1.0)),
        (2.0 * a, (a, b), (-1.0, 0.0)),
        (2.0 * b, (-a, b), (0.0, -1.0)),
        (2.0 * a, (-a, -b), (1.0, 0.0)),
    ];
    let mut left = s;
    for (length, (x, y), (dx, dy)) in sides {
        if left <= length {
            return (x + dx * left, y + dy * left);
        }
        left -= length;
    }
    (a, -b)
}

/// A closed ring corridor round a central block, `robots` on its centre line; an oval ring
/// is a long thin rectangle, a square one a square.
fn ring(cell: &mut CellDoc, rng: &mut ChaCha8Rng, robots: usize, oval: bool) {
    let perimeter = RING_SPACING * robots as f64;
    // Half sizes of the centre line: perimeter 4 (a + b).
    let (a, b) = if oval {
        let b = 1.2;
        ((perimeter / 4.0 - b).max(3.0), b)
    } else {
        let a = (perimeter / 8.0).max(1.6);
        (a, a)
    };
    let (h, wall) = (RING_WIDTH / 2.0, 1.0);
    cell.block("centre", -(a - h), -(b - h), a - h, b - h);
    cell.block(
        "wall-north",
        -(a + h + wall),
        b + h,
        a + h + wall,
        b + h + wall,
    );
    cell.block(
        "wall-south",
        -(a + h + wall),
        -(b + h),
        a + h + wall,
        -(b + h + wall),
    );
    cell.block("wall-east", a + h, -(b + h), a + h + wall, b + h);
    cell.block("wall-west", -(a + h), -(b + h), -(a + h + wall), b + h);
    let spacing = 4.0 * (a + b) / robots as f64;
    let offset = rng.random_range(0.0..spacing);
    let homes: Vec<f64> = (0..robots).map(|i| offset + spacing * i as f64).collect();
    let names: Vec<String> = (homes.iter())
        .map(|&s| {
            let (x, y) = along_ring(a, b, s);
            cell.robot(x, y)
        })
        .collect();
    let mut used = vec![0; robots];
    for (i, owner) in names.iter().enumerate() {
        // Mixed directions: the first robot counter-clockwise, the second clockwise.
        let dir = match i {
            0 => 1.0,
            1 => -1.0,
            _ if rng.random_bool(0.5) => 1.0,
            _ => -1.0,
        };
        let past: usize = if robots >= 4 {
            rng.random_range(1..=2)
        } else {
            1
        };
        // In the gap between two homes past which it lies (gaps numbered by the home that
        // starts them counter-clockwise); a gap's first task a third of the way along it,
        // its second two thirds, so that no two tasks meet.
        let gap = |past: usize| {
            let ahead = if dir > 0.0 {
                i + past
            } else {
                i + robots - past - 1
            };
            ahead % robots
        };
        let g = [past, 3 - past]
            .into_iter()
            .filter(|&p| p <= robots - 2)
            .map(gap)
            .find(|&g| used[g] < 2)
            .unwrap_or(gap(past));
        let fraction = [1.0 / 3.0, 2.0 / 3.0][used[g].min(1)];
        used[g] += 1;
        let (x, y) = along_ring(a, b, homes[g] + spacing * fraction);
        let d = duration(rng);
        cell.task(format!("{owner}-weld-1"), x, y, d, &[owner]);
    }
}

/// Blocks in a 3 × 3 grid with aisles 1.3 wide between them; the robots wait at aisle
/// mouths outside the grid.
fn aisles(cell: &mut CellDoc, rng: &mut ChaCha8Rng, robots: usize) {
    let (aisle, size) = (1.3, rng.random_range(3.0..4.0f64).round());
    let pitch = size + aisle;
    for i in -1..=1 {
        for j in -1..=1 {
            let (cx, cy) = (pitch * i as f64, pitch * j as f64);
            let name = format!("block-{}-{}", i + 2, j + 2);
            let s = size / 2.0;
            cell.block(&name, cx - s, cy - s, cx + s, cy + s);
        }
    }
    // The four inner aisles, each with a mouth at both ends: (mouth, unit way in).
    let (c, out) = (pitch / 2.0, 1.5 * pitch + 1.0);
    let mut mouths: Vec<((f64, f64), (f64, f64))> = Vec::new();
    for lane in [-c, c] {
        mouths.push(((-out, lane), (1.0, 0.0)));
        mouths.push(((out, lane), (-1.0, 0.0)));
        mouths.push(((lane, -out), (0.0, 1.0)));
        mouths.push(((lane, out), (0.0, -1.0)));
    }
    mouths.shuffle(rng);
    for &((x, y), (ux, uy)) in mouths.iter().take(robots) {
        let owner = cell.robot(x, y);
        // Past the far mouth, beside where a robot may wait there.
        let (fx, fy) = (x + ux * (2.0 * out + 1.2), y + uy * (2.0 * out + 1.2));
        let d = duration(rng);
        cell.task(
            format!("{owner}-weld-1"),
            fx + uy * 1.0,
            fy - ux * 1.0,
            d,
            &[&owner],
        );
        // In a crossing aisle, beside the centre block (between it and a side block).
        let side = if rng.random_bool(0.5) { c } else { -c };
        let shift = (rng.random_range(-8..=8) as f64) / 10.0;
        let (tx, ty) = if ux != 0.0 {
            (side, shift)
        } else {
            (shift, side)
        };
        let d = duration(rng);
        cell.task(format!("{owner}-weld-2"), tx, ty, d, &[&owner]);
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
        assert_eq!(count(ConflictKind::Ring, 0), (3, 3));
        assert_eq!(count(ConflictKind::Ring, 11), (8, 8));
        assert_eq!(count(ConflictKind::Aisles, 2), (8, 16));
    }

    /// A ring's corridor takes one robot and never two side by side, every robot and task
    /// sits on its centre line, each task lies past at least one other robot's home (in
    /// both directions among the robots), and no two tasks meet.
    #[test]
    fn ring_robots_cannot_pass_and_their_tasks_lie_past_other_homes() {
        let xy = |v: &Value| (v[0].as_f64().unwrap(), v[1].as_f64().unwrap());
        for k in 0..12 {
            let doc = generate_conflict_cell(ConflictKind::Ring, 1, k);
            let centre = doc["obstacles"][0]["shape"].as_array().unwrap();
            let (a, b) = (
                centre[2][0].as_f64().unwrap() + RING_WIDTH / 2.0,
                centre[2][1].as_f64().unwrap() + RING_WIDTH / 2.0,
            );
            let on_line = |(x, y): (f64, f64)| {
                let near = |p: f64, q: f64| (p - q).abs() < 1e-9;
                (near(x.abs(), a) && y.abs() <= b + 1e-9)
                    || (near(y.abs(), b) && x.abs() <= a + 1e-9)
            };
            let homes: Vec<(f64, f64)> = (doc["robots"].as_array().unwrap().iter())
                .map(|r| xy(&r["home"]))
                .collect();
            let tasks: Vec<(f64, f64)> = (doc["tasks"].as_array().unwrap().iter())
                .map(|t| xy(&t["at"]))
                .collect();
            assert!(homes.iter().chain(&tasks).all(|&p| on_line(p)), "ring {k}");
            // Arc length along the centre line, as `along_ring` walks it.
            let arc = |(x, y): (f64, f64)| -> f64 {
                let sides = [
                    ((x - a).abs() < 1e-9, y + b),
                    ((y - b).abs() < 1e-9, 2.0 * b + (a - x)),
                    ((x + a).abs() < 1e-9, 2.0 * b + 2.0 * a + (b - y)),
                    (true, 4.0 * b + 2.0 * a + (x + a)),
                ];
                sides.into_iter().find(|s| s.0).unwrap().1
            };
            let perimeter = 4.0 * (a + b);
            let spacing = perimeter / homes.len() as f64;
            for (home, task) in homes.iter().zip(&tasks) {
                let d = (arc(*task) - arc(*home)).rem_euclid(perimeter);
                // Past the next home either way: beyond one spacing from its own.
                assert!(
                    d.min(perimeter - d) > spacing,
                    "ring {k}: {home:?} {task:?}"
                );
            }
            for (i, t) in tasks.iter().enumerate() {
                for u in &tasks[..i] {
                    assert!((t.0 - u.0).hypot(t.1 - u.1) > HALF, "ring {k}");
                }
            }
        }
    }
}
