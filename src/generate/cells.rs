//! Deterministic random cells for `workcell solve` (`workcell generate --kind cell`): a hall
//! with robots at homes along its walls, rectangular fixtures inside, and tasks spread between
//! the fixtures. The same request always gives the same document (one ChaCha8 stream per
//! cell, no clock, no hashing).
//!
//! Every cell is solvable: every task pose keeps the bounding disc of every robot clear of
//! the fixtures by [`TASK_CLEARANCE`], so each robot may turn in place at every task; homes lie
//! between the walls and the band that holds fixtures; the hall grows with the number of
//! tasks, fixtures and robots so that everything fits.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::{json, Value};
use std::f64::consts::PI;

/// Hall floor per task (m²): about ten times the disc a task keeps free of other tasks.
const AREA_PER_TASK: f64 = 10.0;
/// Hall floor per fixture (m²).
const AREA_PER_FIXTURE: f64 = 40.0;
/// Wall length per robot home (m), so that homes are at least this far apart along the walls.
const WALL_PER_ROBOT: f64 = 3.0;
/// Smallest hall (m).
const MIN_WIDTH: f64 = 16.0;
/// Homes sit this far inside the walls (m).
const HOME_INSET: f64 = 1.0;
/// Fixture centres keep this far from the walls (m): a fixture reaches at most 1.5 further.
const FIXTURE_INSET: f64 = 4.0;
/// Fixture centres are farther than this from every other fixture (m).
const FIXTURE_SPACING: f64 = 2.5;
/// Task positions keep this far from the walls (m).
const TASK_INSET: f64 = 2.0;
/// Tasks are at least this far apart (m).
const TASK_SPACING: f64 = 1.0;
/// Gap between a robot's bounding disc at a task and any fixture (m).
pub const TASK_CLEARANCE: f64 = 0.15;
/// One task in this many is restricted to the robots with the nearest homes.
const RESTRICTED_EVERY: usize = 3;
/// How many robots (nearest homes) a restricted task allows.
const RESTRICTED_ROBOTS: usize = 3;
/// Random draws per fixture or task before the request is judged impossible.
const ATTEMPTS_PER_ITEM: usize = 2_000;
/// Largest requests: beyond them the cell would not fit in memory when solved.
pub const MAX_ROBOTS: usize = 1_000;
/// See [`MAX_ROBOTS`].
pub const MAX_TASKS: usize = 100_000;
/// See [`MAX_ROBOTS`].
pub const MAX_FIXTURES: usize = 10_000;

/// What to generate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellRequest {
    /// Robots (1 to `MAX_ROBOTS`).
    pub robots: usize,
    /// Tasks (0 to `MAX_TASKS`).
    pub tasks: usize,
    /// Fixtures (0 to `MAX_FIXTURES`).
    pub fixtures: usize,
}

impl CellRequest {
    /// The default number of fixtures for `tasks` tasks: 3 per 50 tasks (30 for 500, 120
    /// for 2,000), as in the issue's cells.
    ///
    /// ```
    /// use workcell::generate::CellRequest;
    /// assert_eq!(CellRequest::default_fixtures(500), 30);
    /// assert_eq!(CellRequest::default_fixtures(10), 0);
    /// ```
    pub fn default_fixtures(tasks: usize) -> usize {
        tasks * 3 / 50
    }

    /// Refuses sizes out of range, with the flag to blame.
    ///
    /// ```
    /// use workcell::generate::CellRequest;
    /// assert!(CellRequest { robots: 2, tasks: 10, fixtures: 1 }.check().is_ok());
    /// let e = CellRequest { robots: 0, tasks: 10, fixtures: 1 }.check().unwrap_err();
    /// assert!(e.starts_with("--robots"), "{e}");
    /// ```
    pub fn check(&self) -> Result<(), String> {
        if !(1..=MAX_ROBOTS).contains(&self.robots) {
            return Err(format!(
                "--robots must be 1 to {MAX_ROBOTS} for a cell, got {}",
                self.robots
            ));
        }
        if self.tasks > MAX_TASKS {
            return Err(format!(
                "--tasks must be at most {MAX_TASKS}, got {}",
                self.tasks
            ));
        }
        if self.fixtures > MAX_FIXTURES {
            return Err(format!(
                "--fixtures must be at most {MAX_FIXTURES}, got {}",
                self.fixtures
            ));
        }
        Ok(())
    }
}

/// The file name of cell `index` of a run: `cell-<R>r-<N>t-<F>f-<seed>-<index>-cell.json`
/// (the `-cell.json` ending keeps it out of `compare`'s folders of scenes).
///
/// ```
/// use workcell::generate::{cell_file_name, CellRequest};
/// let req = CellRequest { robots: 3, tasks: 40, fixtures: 2 };
/// assert_eq!(cell_file_name(&req, 0, 5), "cell-3r-40t-2f-0-5-cell.json");
/// ```
pub fn cell_file_name(req: &CellRequest, seed: u64, index: u64) -> String {
    format!(
        "cell-{}r-{}t-{}f-{seed}-{index}-cell.json",
        req.robots, req.tasks, req.fixtures
    )
}

/// Cell `index` of a run with `seed`, as a cell document (contract section 3), or why the
/// request cannot be met.
///
/// ```
/// use workcell::cell::parse_cell;
/// use workcell::generate::{generate_cell, CellRequest};
/// let req = CellRequest { robots: 3, tasks: 12, fixtures: 2 };
/// let doc = generate_cell(&req, 0, 0)?;
/// // A valid cell document of the requested size.
/// let cell = parse_cell(&doc.to_string(), "generated.json".as_ref())?.cell;
/// assert_eq!((cell.robots.len(), cell.tasks.len(), cell.obstacles.len()), (3, 12, 2));
/// assert_eq!(doc, generate_cell(&req, 0, 0)?);
/// assert!(generate_cell(&CellRequest { robots: 0, ..req }, 0, 0).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn generate_cell(req: &CellRequest, seed: u64, index: u64) -> Result<Value, String> {
    req.check()?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index);
    let (width, height) = hall_size(req);
    let robots = robots(&mut rng, req.robots, width, height);
    let fixtures = fixtures(&mut rng, req.fixtures, width, height)?;
    let margin = robots.iter().map(|r| r.radius).fold(0.0, f64::max) + TASK_CLEARANCE;
    let tasks = tasks(&mut rng, req, &robots, &fixtures, margin, width, height)?;
    Ok(json!({
        "delta": 0.01,
        "robots": robots.iter().map(|r| r.json.clone()).collect::<Vec<_>>(),
        "obstacles": fixtures
            .iter()
            .enumerate()
            .map(|(k, f)| json!({"name": format!("fixture-{}", k + 1), "shape": f}))
            .collect::<Vec<_>>(),
        "tasks": tasks,
    }))
}

/// Width and height (4 : 3) with room for the floor the tasks and fixtures need and the wall
/// length the homes need.
fn hall_size(req: &CellRequest) -> (f64, f64) {
    let area = AREA_PER_TASK * req.tasks as f64 + AREA_PER_FIXTURE * req.fixtures as f64;
    let by_area = (area * 4.0 / 3.0).sqrt();
    // Homes run along a loop 2·(w + h) − 8·inset long, with h = 3w/4.
    let by_wall = (WALL_PER_ROBOT * req.robots as f64 + 8.0 * HOME_INSET) / 3.5;
    let width = by_area.max(by_wall).max(MIN_WIDTH).ceil();
    (width, (0.75 * width).ceil())
}

struct Robot {
    home: [f64; 2],
    radius: f64,
    json: Value,
}

fn round(x: f64, digits: i32) -> f64 {
    let s = 10f64.powi(digits);
    (x * s).round() / s
}

/// Robots spread evenly along the walls, one metre in; three shapes and three speeds in turn.
fn robots(rng: &mut ChaCha8Rng, n: usize, width: f64, height: f64) -> Vec<Robot> {
    let hexagon: Vec<[f64; 2]> = (0..6)
        .map(|k| {
            let a = k as f64 * PI / 3.0;
            [round(0.35 * a.cos(), 4), round(0.35 * a.sin(), 4)]
        })
        .collect();
    let shapes = [
        vec![[-0.3, -0.3], [0.3, -0.3], [0.3, 0.3], [-0.3, 0.3]],
        vec![[-0.4, -0.25], [0.4, -0.25], [0.4, 0.25], [-0.4, 0.25]],
        hexagon,
    ];
    let (w, h) = (width - 2.0 * HOME_INSET, height - 2.0 * HOME_INSET);
    (0..n)
        .map(|k| {
            let s = (k as f64 + 0.5) / n as f64 * 2.0 * (w + h);
            let (x, y) = if s < w {
                (HOME_INSET + s, HOME_INSET)
            } else if s < w + h {
                (width - HOME_INSET, HOME_INSET + s - w)
            } else if s < 2.0 * w + h {
                (width - HOME_INSET - (s - w - h), height - HOME_INSET)
            } else {
                (HOME_INSET, height - HOME_INSET - (s - 2.0 * w - h))
            };
            let shape = &shapes[k % 3];
            let radius = shape.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max);
            let speed = [0.8, 1.0, 1.2][rng.random_range(0..3usize)];
            let home = [round(x, 3), round(y, 3)];
            Robot {
                home,
                radius,
                json: json!({
                    "name": format!("R{}", k + 1),
                    "shape": shape,
                    "home": [home[0], home[1], 0.0],
                    "max_speed": speed,
                    "max_accel": 2.0,
                    "max_turn_rate": 1.5,
                }),
            }
        })
        .collect()
}

/// Turned rectangles (half-sides 0.5–1.5 by 0.3–1.0), centres apart.
fn fixtures(
    rng: &mut ChaCha8Rng,
    n: usize,
    width: f64,
    height: f64,
) -> Result<Vec<Vec<[f64; 2]>>, String> {
    let mut out: Vec<Vec<[f64; 2]>> = Vec::with_capacity(n);
    let mut attempts = 0;
    while out.len() < n {
        attempts += 1;
        if attempts > ATTEMPTS_PER_ITEM * n {
            return Err(format!(
                "cannot place {n} fixtures in a hall of {width} x {height} m"
            ));
        }
        let c = [
            rng.random_range(FIXTURE_INSET..width - FIXTURE_INSET),
            rng.random_range(FIXTURE_INSET..height - FIXTURE_INSET),
        ];
        let (hx, hy) = (rng.random_range(0.5..1.5), rng.random_range(0.3..1.0));
        let (s, co) = rng.random_range(0.0..PI).sin_cos();
        let shape: Vec<[f64; 2]> = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]
            .iter()
            .map(|&(x, y)| {
                [
                    round(c[0] + co * x - s * y, 4),
                    round(c[1] + s * x + co * y, 4),
                ]
            })
            .collect();
        if out
            .iter()
            .all(|o| point_polygon_distance(c, o) > FIXTURE_SPACING)
        {
            out.push(shape);
        }
    }
    Ok(out)
}

/// Tasks clear of the fixtures by `margin`, apart from each other; one in
/// [`RESTRICTED_EVERY`] allowed only to the robots whose homes are nearest.
fn tasks(
    rng: &mut ChaCha8Rng,
    req: &CellRequest,
    robots: &[Robot],
    fixtures: &[Vec<[f64; 2]>],
    margin: f64,
    width: f64,
    height: f64,
) -> Result<Vec<Value>, String> {
    let n = req.tasks;
    // A grid of TASK_SPACING-wide buckets finds the tasks near a new one in O(1).
    let cols = (width / TASK_SPACING).ceil() as usize + 1;
    let rows = (height / TASK_SPACING).ceil() as usize + 1;
    let mut grid: Vec<Vec<[f64; 2]>> = vec![Vec::new(); cols * rows];
    let bucket = |p: [f64; 2]| {
        (
            (p[0] / TASK_SPACING) as usize,
            (p[1] / TASK_SPACING) as usize,
        )
    };
    let mut out = Vec::with_capacity(n);
    let mut attempts = 0;
    while out.len() < n {
        attempts += 1;
        if attempts > ATTEMPTS_PER_ITEM * n {
            return Err(format!(
                "cannot place {n} tasks clear of {} fixtures in a hall of {width} x {height} m",
                req.fixtures
            ));
        }
        let p = [
            round(rng.random_range(TASK_INSET..width - TASK_INSET), 3),
            round(rng.random_range(TASK_INSET..height - TASK_INSET), 3),
        ];
        let theta = round(rng.random_range(-PI..PI), 3);
        let duration = round(rng.random_range(1.0..4.0), 1);
        if fixtures
            .iter()
            .any(|f| point_polygon_distance(p, f) < margin)
        {
            continue;
        }
        let (bx, by) = bucket(p);
        let near = (bx.saturating_sub(1)..=(bx + 1).min(cols - 1))
            .flat_map(|x| (by.saturating_sub(1)..=(by + 1).min(rows - 1)).map(move |y| (x, y)))
            .any(|(x, y)| {
                grid[y * cols + x]
                    .iter()
                    .any(|q| (q[0] - p[0]).hypot(q[1] - p[1]) < TASK_SPACING)
            });
        if near {
            continue;
        }
        grid[by * cols + bx].push(p);
        let k = out.len();
        let mut task = json!({
            "name": format!("task-{}", k + 1),
            "at": [p[0], p[1], theta],
            "duration": duration,
        });
        if k % RESTRICTED_EVERY == RESTRICTED_EVERY - 1 && robots.len() > RESTRICTED_ROBOTS {
            let mut order: Vec<usize> = (0..robots.len()).collect();
            let d = |r: usize| (robots[r].home[0] - p[0]).hypot(robots[r].home[1] - p[1]);
            order.sort_by(|&a, &b| d(a).total_cmp(&d(b)).then(a.cmp(&b)));
            order.truncate(RESTRICTED_ROBOTS);
            order.sort_unstable();
            task["robots"] = json!(order
                .iter()
                .map(|&r| format!("R{}", r + 1))
                .collect::<Vec<_>>());
        }
        out.push(task);
    }
    Ok(out)
}

/// Distance from a point to a convex polygon (counter-clockwise or not; 0 inside).
fn point_polygon_distance(p: [f64; 2], poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    let mut best = f64::INFINITY;
    let (mut left, mut right) = (true, true);
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let e = [b[0] - a[0], b[1] - a[1]];
        let cross = e[0] * (p[1] - a[1]) - e[1] * (p[0] - a[0]);
        left &= cross >= 0.0;
        right &= cross <= 0.0;
        let t = ((p[0] - a[0]) * e[0] + (p[1] - a[1]) * e[1]) / (e[0] * e[0] + e[1] * e[1]);
        let t = t.clamp(0.0, 1.0);
        best = best.min((p[0] - a[0] - t * e[0]).hypot(p[1] - a[1] - t * e[1]));
    }
    if left || right {
        0.0
    } else {
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_polygon_distance_is_zero_inside_and_euclidean_outside() {
        let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(point_polygon_distance([0.5, 0.5], &sq), 0.0);
        assert_eq!(point_polygon_distance([2.0, 0.5], &sq), 1.0);
        assert!((point_polygon_distance([2.0, 2.0], &sq) - 2f64.sqrt()).abs() < 1e-15);
    }
}
