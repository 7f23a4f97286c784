//! What every picture draws, gathered from a result as its JSON carries it ([`ResultJson`],
//! [`CheckReport`]) and from the scene of its trajectories: never from the solver's internals.

use super::bars::{bar_of, still_and_moving, Bar};
use crate::cell::Cell;
use crate::collision::{CheckReport, Scene, Verdict};
use crate::geometry::{closest_features, Posed, Vec2, WalkTolerances};
use crate::motion::Motion;
use crate::wcp::remedy_json::ChangeJson;
use crate::wcp::report::ResultJson;
use serde::Serialize;

/// Robot colours, distinct on white and for the common colour-vision deficiencies first
/// (Okabe-Ito), then more.
pub const COLOURS: [&str; 12] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#8C564B",
    "#7F7F7F", "#BCBD22", "#17BECF", "#9467BD",
];

/// A cell or scene with its schedule, ready to draw.
#[derive(Clone, Debug, Serialize)]
pub struct Model {
    /// The cell's or scene's name (its file name without `.json`).
    pub title: String,
    /// One line under the title: makespan and verdict.
    pub verdict: String,
    /// The end of the time axis: the makespan, or the scene's last sample.
    pub end: f64,
    /// The safety margin δ.
    pub delta: f64,
    /// The robots, in the cell's order.
    pub robots: Vec<RobotView>,
    /// The fixed obstacles, in world coordinates.
    pub obstacles: Vec<Vec<[f64; 2]>>,
    /// Each obstacle's name and the world point its label belongs to (the middle of its
    /// box), in the scene's order.
    pub obstacle_names: Vec<(String, [f64; 2])>,
    /// The tasks (none for a scene).
    pub tasks: Vec<TaskView>,
    /// The collision of each feedback round, in round order (solve only).
    pub rounds: Vec<Mark>,
    /// The first collision of the schedule or scene drawn, if any.
    pub contact: Option<Mark>,
    /// End of the prefix certified collision-free (check only).
    pub safe_until: Option<f64>,
}

/// One robot: shape, trajectory and what it does when.
#[derive(Clone, Debug, Serialize)]
pub struct RobotView {
    /// Its name.
    pub name: String,
    /// Its colour in every picture.
    pub colour: &'static str,
    /// Its shape in its own frame (G at the origin): the body, its outline, or for a body
    /// given by parts the hull of them (not drawn).
    pub shape: Vec<[f64; 2]>,
    /// The convex parts of a body that has them, in its frame: drawn as the body when it was
    /// given by parts; the seams of its outline, shown faintly on hover, when `outlined`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub parts: Vec<Vec<[f64; 2]>>,
    /// Whether the body was given by an outline (`shape` holds it).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub outlined: bool,
    /// Its samples `[t, x, y, θ]`: the checker interpolates linearly between them. For a
    /// link of an arm, its frame at the arm's sample times (`arm` places it between them).
    pub samples: Vec<[f64; 4]>,
    /// For a link of an arm: what places it at every time, as the checker does.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub arm: Option<ArmView>,
    /// Its home pose `[x, y, θ]` (cells only).
    pub home: Option<[f64; 3]>,
    /// Indices into [`Model::tasks`] in visiting order.
    pub order: Vec<usize>,
    /// Its activities, in time order.
    pub bars: Vec<Bar>,
}

/// A link of an arm as the page places it: forward kinematics (contract section 6) of the
/// joint angles, each linear between samples ([`crate::motion::ArmMotion::pose_at`]).
#[derive(Clone, Debug, Serialize)]
pub struct ArmView {
    /// The base pose `[x, y, θ]`.
    pub base: [f64; 3],
    /// The link lengths.
    pub lengths: Vec<f64>,
    /// Which link this is (0 at the base).
    pub link: usize,
    /// The samples `[t, q_0, q_1, ...]`.
    pub joints: Vec<Vec<f64>>,
}

impl RobotView {
    /// Whether this robot has a lane, a row and a name of its own: every robot but the links
    /// of an arm after its first, which belong to the arm's.
    ///
    /// ```
    /// use workcell::collision::{check, Arm, CheckOptions, Scene};
    /// use workcell::geometry::ConvexPolygon;
    /// use workcell::motion::Pose;
    /// use workcell::view::Model;
    /// let bar = ConvexPolygon::from_vertices(&[[-0.1, -0.1], [1.1, -0.1], [1.1, 0.1], [-0.1, 0.1]])?;
    /// let arm = Arm::new("A1", Pose::new(0.0, 0.0, 0.0)).link(1.0, bar.clone()).link(1.0, bar)
    ///     .sample(0.0, &[0.0, 0.0]).sample(1.0, &[1.0, -1.0]).bodies()?;
    /// let scene = Scene::with_bodies(0.01, arm)?;
    /// let model = Model::of_check("arm.json".as_ref(), &scene, &check(&scene, &CheckOptions::default()));
    /// let leads: Vec<bool> = model.robots.iter().map(|r| r.leads()).collect();
    /// assert_eq!(leads, [true, false]); // one lane for the arm, its link 0's
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn leads(&self) -> bool {
        self.arm.as_ref().is_none_or(|a| a.link == 0)
    }

    /// The polygons that draw the body: its parts when it was given by parts, else its one
    /// shape (convex, or its outline).
    ///
    /// ```
    /// use workcell::collision::{check, CheckOptions};
    /// use workcell::view::Model;
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/grippers-interleave.json");
    /// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
    /// let model = Model::of_check(path.as_ref(), &scene, &check(&scene, &CheckOptions::default()));
    /// // G1 is given by parts (a palm and two fingers); G2 by an outline, drawn as itself.
    /// assert_eq!((model.robots[0].drawn().len(), model.robots[1].drawn().len()), (3, 1));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn drawn(&self) -> Vec<&[[f64; 2]]> {
        if self.parts.is_empty() || self.outlined {
            vec![&self.shape]
        } else {
            self.parts.iter().map(Vec::as_slice).collect()
        }
    }
}

/// A task pose.
#[derive(Clone, Debug, Serialize)]
pub struct TaskView {
    /// Its name.
    pub name: String,
    /// `[x, y, θ]`.
    pub pose: [f64; 3],
}

/// A collision: where and when, between whom.
#[derive(Clone, Debug, Serialize)]
pub struct Mark {
    /// The feedback round (from 1) whose schedule collided here; none for the drawn schedule.
    pub round: Option<usize>,
    /// Time of the contact.
    pub time: f64,
    /// The two bodies, robot first.
    pub bodies: [String; 2],
    /// A point between the two bodies at that time.
    pub point: [f64; 2],
}

fn robots_of(scene: &Scene) -> Vec<RobotView> {
    // One colour per robot: the links of an arm share theirs.
    let mut robot = 0;
    let colours: Vec<&'static str> = (scene.bodies.iter().enumerate())
        .filter(|(_, b)| b.is_robot())
        .map(|(k, b)| {
            if k > 0 && scene.bodies[k - 1].same_arm(b) {
                robot -= 1;
            }
            robot += 1;
            COLOURS[(robot - 1) % COLOURS.len()]
        })
        .collect();
    scene
        .bodies
        .iter()
        .filter(|b| b.is_robot())
        .zip(colours)
        .map(|(b, colour)| RobotView {
            name: b.name.clone(),
            colour,
            shape: match b.parts.as_ref().and_then(|p| p.outline()) {
                Some(outline) => points(outline),
                None => points(b.shape.vertices()),
            },
            parts: b
                .parts
                .iter()
                .flat_map(|p| p.parts())
                .map(|p| points(p.vertices()))
                .collect(),
            outlined: b.parts.as_ref().is_some_and(|p| p.outline().is_some()),
            samples: match &b.motion {
                Motion::Sampled(tr) => tr
                    .samples()
                    .iter()
                    .map(|s| [s.t, s.pos.x, s.pos.y, s.theta])
                    .collect(),
                Motion::Link(l) => l
                    .frames()
                    .iter()
                    .map(|s| [s.t, s.pos.x, s.pos.y, s.theta])
                    .collect(),
                Motion::Fixed(p) => vec![[0.0, p.pos.x, p.pos.y, p.theta]],
            },
            arm: match &b.motion {
                Motion::Link(l) => Some(ArmView {
                    base: [l.arm.base().pos.x, l.arm.base().pos.y, l.arm.base().theta],
                    lengths: l.arm.lengths().to_vec(),
                    link: l.link,
                    joints: (l.arm.samples().iter())
                        .map(|s| std::iter::once(s.t).chain(s.q.iter().copied()).collect())
                        .collect(),
                }),
                _ => None,
            },
            home: None,
            order: Vec::new(),
            bars: Vec::new(),
        })
        .collect()
}

/// Each obstacle's name, at the middle of its box in the world.
fn obstacle_names(scene: &Scene) -> Vec<(String, [f64; 2])> {
    let names = scene.bodies.iter().filter_map(|b| {
        let Motion::Fixed(p) = b.motion else {
            return None;
        };
        let iso = nalgebra::Isometry2::new(p.pos, p.theta);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for v in b.shape.vertices() {
            let w = iso * nalgebra::Point2::from(*v);
            for (i, c) in [w.x, w.y].into_iter().enumerate() {
                lo[i] = lo[i].min(c);
                hi[i] = hi[i].max(c);
            }
        }
        let middle = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
        Some((b.name.clone(), middle))
    });
    names.collect()
}

/// The obstacles' polygons in the world: one per convex obstacle, its outline for one given
/// by an outline, each part for one given by parts.
fn obstacles_of(scene: &Scene) -> Vec<Vec<[f64; 2]>> {
    let mut polygons = Vec::new();
    for b in &scene.bodies {
        let Motion::Fixed(p) = b.motion else {
            continue;
        };
        let world = |v: &[Vec2]| -> Vec<[f64; 2]> {
            let iso = nalgebra::Isometry2::new(p.pos, p.theta);
            v.iter()
                .map(|v| {
                    let w = iso * nalgebra::Point2::from(*v);
                    [w.x, w.y]
                })
                .collect()
        };
        match &b.parts {
            None => polygons.push(world(b.shape.vertices())),
            Some(parts) => match parts.outline() {
                Some(outline) => polygons.push(world(outline)),
                None => polygons.extend(parts.parts().iter().map(|q| world(q.vertices()))),
            },
        }
    }
    polygons
}

fn points(vertices: &[Vec2]) -> Vec<[f64; 2]> {
    vertices.iter().map(|v| [v.x, v.y]).collect()
}

fn file_title(path: &std::path::Path) -> String {
    path.file_stem().map_or_else(
        || path.display().to_string(),
        |s| s.to_string_lossy().into(),
    )
}

impl Model {
    /// The model of `solve` or `evaluate`: the cell, the scene of the final schedule
    /// (`Schedule::scene`, as `--export-scene` writes it) and the result document.
    ///
    /// ```
    /// use workcell::cell::{load_cell, parse_sequences};
    /// use workcell::view::Model;
    /// use workcell::wcp::report::{collision_json, schedule_json, ResultJson};
    /// use workcell::wcp::{evaluate, SolveOptions};
    /// let cell = load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let sequences = r#"{"R1": ["weld-2", "weld-1", "weld-3"], "R2": ["weld-4"]}"#;
    /// let file = "seq.json".as_ref();
    /// let e = evaluate(&cell, &parse_sequences(sequences, file, &cell)?, &SolveOptions::default(), file)?;
    /// let (sequences, schedule) = schedule_json(&cell, &e.schedule);
    /// // The result document, as `workcell evaluate --json` writes it.
    /// let result = ResultJson {
    ///     makespan: e.schedule.makespan, collision_free: e.collision_free, sequences, schedule,
    ///     configurations: vec![],
    ///     first_collision: e.collision.as_ref().map(|c| collision_json(&cell, c)),
    ///     iterations: 1, schedules_checked: None, found_after: None, waits: vec![], legs: vec![], blind_sequences: None,
    ///     blind_makespan: None, blind_optimal: None, feedback: vec![], failure: None,
    ///     check_stats: e.report.stats, stages_ms: e.times.into(),
    /// };
    /// let model = Model::of_result(&cell, &e.schedule.scene(&cell), &result);
    /// assert_eq!((model.robots.len(), model.tasks.len(), model.end), (2, 4, e.schedule.makespan));
    /// assert_eq!(model.contact.expect("the collision").bodies, ["R1", "R2"]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn of_result(cell: &Cell, scene: &Scene, result: &ResultJson) -> Model {
        let mut robots = robots_of(scene);
        let task_index = |name: &str| cell.tasks.iter().position(|t| t.name == name);
        let changes: Vec<&ChangeJson> = result
            .feedback
            .iter()
            .filter_map(|r| r.change.as_ref())
            .collect();
        // One lane per robot of the cell: an arm's on its first link.
        for (r, robot) in robots.iter_mut().filter(|v| v.leads()).enumerate() {
            // An arm's base marks where it stands; its home is its joints'.
            robot.home =
                (cell.robots[r].as_rigid()).map(|b| [b.home.pos.x, b.home.pos.y, b.home.theta]);
            if let Some((_, tasks)) = result.sequences.get(r) {
                robot.order = tasks.iter().filter_map(|t| task_index(t)).collect();
            }
            let Some((_, segments)) = result.schedule.get(r) else {
                continue;
            };
            let bars: Vec<Bar> = segments
                .iter()
                .map(|seg| bar_of(&robot.name, seg, result, &changes))
                .collect();
            robot.bars.extend(bars);
        }
        let mark = |round, c: &crate::wcp::report::CollisionJson| Mark {
            round,
            time: c.time,
            bodies: c.bodies.clone(),
            point: c.point,
        };
        let verdict = verdict_of(result);
        Model {
            title: file_title(&cell.file),
            verdict,
            end: result.makespan,
            delta: cell.delta,
            robots,
            obstacles: obstacles_of(scene),
            obstacle_names: obstacle_names(scene),
            tasks: cell
                .tasks
                .iter()
                .map(|t| TaskView {
                    name: t.name.clone(),
                    pose: [t.at.pos.x, t.at.pos.y, t.at.theta],
                })
                .collect(),
            rounds: result
                .feedback
                .iter()
                .filter_map(|r| Some(mark(Some(r.iteration), r.collision.as_ref()?)))
                .collect(),
            contact: result.first_collision.as_ref().map(|c| mark(None, c)),
            safe_until: None,
        }
    }

    /// The model of `check`: the scene and its report.
    ///
    /// ```
    /// use workcell::collision::{check, CheckOptions};
    /// use workcell::view::Model;
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/tunnelling.json");
    /// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
    /// let model = Model::of_check(path.as_ref(), &scene, &check(&scene, &CheckOptions::default()));
    /// let names: Vec<&str> = model.robots.iter().map(|r| r.name.as_str()).collect();
    /// assert_eq!(names, ["needle", "block"]);
    /// let contact = model.contact.expect("the needle hits the block");
    /// assert_eq!(contact.bodies, ["needle", "block"]);
    /// assert!(model.safe_until.unwrap() <= contact.time);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn of_check(file: &std::path::Path, scene: &Scene, report: &CheckReport) -> Model {
        let mut robots = robots_of(scene);
        for robot in &mut robots {
            // An arm moves while any joint turns.
            robot.bars = match &robot.arm {
                Some(arm) => still_and_moving(&arm.joints),
                None => still_and_moving(&robot.samples),
            };
        }
        let contact = report.first_contact.as_ref().map(|c| {
            let body = |name: &str| scene.bodies.iter().find(|b| b.name == name);
            let point = match (body(&c.bodies[0]), body(&c.bodies[1])) {
                (Some(a), Some(b)) => {
                    fn posed(b: &crate::collision::Body, t: f64) -> Posed<'_> {
                        let p = b.motion.pose_at(t);
                        Posed::new(&b.shape, p.pos.x, p.pos.y, p.theta)
                    }
                    let d = closest_features(
                        &posed(a, c.time),
                        &posed(b, c.time),
                        None,
                        &WalkTolerances::default(),
                    );
                    let m = (d.point_a + d.point_b) / 2.0;
                    [m.x, m.y]
                }
                _ => [0.0, 0.0],
            };
            Mark {
                round: None,
                time: c.time,
                bodies: c.bodies.clone(),
                point,
            }
        });
        let verdict = match report.verdict() {
            Verdict::Contact { contact: c, .. } => format!(
                "COLLISION between {} and {} at t = {:.6}; collision-free until t = {:.6}",
                c.bodies[0], c.bodies[1], c.time, report.safe_until
            ),
            Verdict::Free { certified: true } => format!(
                "collision-free over [{}, {}] (certified)",
                report.horizon[0], report.horizon[1]
            ),
            Verdict::Free { certified: false } | Verdict::Unresolved { .. } => format!(
                "no collision found; NOT certified after t = {:.6}",
                report.safe_until
            ),
        };
        Model {
            title: file_title(std::path::Path::new(file)),
            verdict,
            end: report.horizon[1],
            delta: report.delta,
            robots,
            obstacles: obstacles_of(scene),
            obstacle_names: obstacle_names(scene),
            tasks: Vec::new(),
            rounds: Vec::new(),
            contact,
            safe_until: Some(report.safe_until),
        }
    }

    /// Start of the time axis: 0, or a scene's first sample when earlier.
    pub fn start(&self) -> f64 {
        self.robots
            .iter()
            .filter_map(|r| r.samples.first())
            .map(|s| s[0])
            .fold(0.0, f64::min)
    }
}

/// The pose of a robot at `t` exactly as the checker interpolates: linear in x, y and θ
/// between samples, the first pose before them and the last after them.
///
/// ```
/// use workcell::view::pose_at;
/// let samples = [[0.0, 0.0, 0.0, 0.0], [2.0, 4.0, 2.0, 1.0]]; // [t, x, y, theta]
/// assert_eq!(pose_at(&samples, 1.0), [2.0, 1.0, 0.5]);
/// assert_eq!(pose_at(&samples, 5.0), [4.0, 2.0, 1.0]); // after the last: the last pose
/// ```
pub fn pose_at(samples: &[[f64; 4]], t: f64) -> [f64; 3] {
    let k = samples.partition_point(|s| s[0] <= t);
    let (p, q, u) = if k == 0 {
        (&samples[0], &samples[0], 0.0)
    } else if k == samples.len() {
        (&samples[k - 1], &samples[k - 1], 0.0)
    } else {
        let (p, q) = (&samples[k - 1], &samples[k]);
        (p, q, (t - p[0]) / (q[0] - p[0]))
    };
    [
        p[1] + (q[1] - p[1]) * u,
        p[2] + (q[2] - p[2]) * u,
        p[3] + (q[3] - p[3]) * u,
    ]
}

/// A solve result's headline: makespan, the collision or whether it is certified, rounds.
fn verdict_of(result: &ResultJson) -> String {
    format!(
        "makespan {:.3}, {}{}",
        result.makespan,
        match (&result.first_collision, result.collision_free) {
            (Some(c), _) => format!(
                "COLLISION between {} and {} at t = {:.3}",
                c.bodies[0], c.bodies[1], c.time
            ),
            (None, true) => "collision-free (certified)".to_owned(),
            (None, false) => "NOT certified".to_owned(),
        },
        match result.feedback.len() {
            0 => String::new(),
            1 => ", 1 round".to_owned(),
            n => format!(", {n} rounds"),
        }
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poses_interpolate_linearly_and_hold_outside_the_samples() {
        let s = [[1.0, 0.0, 0.0, 0.0], [3.0, 2.0, 4.0, 1.0]];
        assert_eq!(pose_at(&s, 0.0), [0.0, 0.0, 0.0]);
        assert_eq!(pose_at(&s, 2.0), [1.0, 2.0, 0.5]);
        assert_eq!(pose_at(&s, 9.0), [2.0, 4.0, 1.0]);
    }

    /// Bit for bit the checker's interpolation, at sample times, between them and outside.
    #[test]
    fn poses_are_the_checkers() {
        use crate::geometry::Vec2;
        use crate::motion::{Sample, Trajectory};
        let raw = [
            [0.1, 1.0, -2.0, 0.3],
            [0.7, 1.5, 2.0, -3.0],
            [2.9, -4.0, 0.25, 6.0],
        ];
        let tr = Trajectory::new(
            raw.iter()
                .map(|s| Sample {
                    t: s[0],
                    pos: Vec2::new(s[1], s[2]),
                    theta: s[3],
                    vel: Vec2::zeros(),
                    omega: 0.0,
                })
                .collect(),
        )
        .unwrap();
        for k in 0..=70 {
            let t = -0.3 + 0.05 * k as f64;
            let p = tr.pose_at(t);
            assert_eq!(pose_at(&raw, t), [p.pos.x, p.pos.y, p.theta], "t = {t}");
        }
    }
}
