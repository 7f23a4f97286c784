//! `--svg`: the cell and its schedule in the manner of the paper's Figure 12, with a title,
//! a legend, the visiting order and collision rings set apart.
//!
//! Obstacles in grey, tasks as crosses labelled with their place in their robot's route,
//! homes as squares, each robot's path in its own colour with arrowheads along it and its
//! shape at home and at each of its tasks, and the point of each collision fed back as a red
//! ring numbered by round.

use super::labels::{text_width, Placer, Rect};
use super::model::{pose_at, ArmView, Mark, Model, RobotView};
use crate::motion::{forward_kinematics, Pose};
use svg::node::element::{Circle, Group, Line, Polygon, Polyline, Rectangle, Text};
use svg::Document;

/// Width of the picture in pixels; the height follows the cell's aspect ratio.
pub const WIDTH: f64 = 900.0;
/// Margin round the drawing of the cell.
const MARGIN: f64 = 30.0;
/// Room above the cell for the title and the verdict.
const HEADER: f64 = 56.0;
/// One row of the legend.
const LEGEND_ROW: f64 = 18.0;
/// Robots per legend row.
const LEGEND_PER_ROW: usize = 6;
/// Radius of a collision ring.
const RING: f64 = 9.0;
/// Font sizes of the labels of tasks and homes.
const TASK_FONT: f64 = 10.0;
const HOME_FONT: f64 = 12.0;

/// World to picture coordinates: uniform scale, y up. The browser test reads poses through
/// it.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// Picture x of world x = 0.
    pub ox: f64,
    /// Picture y of world y = 0.
    pub oy: f64,
    /// Pixels per length unit.
    pub scale: f64,
    /// Height of the cell's drawing area, header included.
    pub height: f64,
}

impl Frame {
    /// The frame of the model's picture.
    pub fn of(m: &Model) -> Frame {
        let mut points: Vec<[f64; 2]> = m.obstacles.iter().flatten().copied().collect();
        for robot in &m.robots {
            let r = robot
                .shape
                .iter()
                .map(|v| v[0].hypot(v[1]))
                .fold(0.0, f64::max);
            let home = robot.home.map(|h| [0.0, h[0], h[1], 0.0]);
            for s in robot.samples.iter().chain(home.iter()) {
                points.extend([[s[1] - r, s[2] - r], [s[1] + r, s[2] + r]]);
            }
        }
        points.extend(m.tasks.iter().map(|t| [t.pose[0], t.pose[1]]));
        let (mut min, mut max) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &points {
            for i in 0..2 {
                min[i] = min[i].min(p[i]);
                max[i] = max[i].max(p[i]);
            }
        }
        if !min[0].is_finite() {
            (min, max) = ([0.0; 2], [1.0; 2]);
        }
        let size = [(max[0] - min[0]).max(1e-9), (max[1] - min[1]).max(1e-9)];
        let scale = (WIDTH - 2.0 * MARGIN) / size[0];
        let plot = (size[1] * scale + 2.0 * MARGIN).clamp(200.0, 4.0 * WIDTH);
        let scale = scale.min((plot - 2.0 * MARGIN) / size[1]);
        Frame {
            ox: MARGIN - min[0] * scale,
            oy: HEADER + MARGIN + max[1] * scale,
            scale,
            height: HEADER + plot,
        }
    }

    /// Picture coordinates of a world point.
    pub fn xy(&self, x: f64, y: f64) -> (f64, f64) {
        (self.ox + x * self.scale, self.oy - y * self.scale)
    }

    /// A polygon of world vertices, its sides taken in `placer`: no label will cross them.
    fn outline(&self, vertices: impl Iterator<Item = [f64; 2]>, placer: &mut Placer) -> Polygon {
        let points: Vec<(f64, f64)> = vertices.map(|v| self.xy(v[0], v[1])).collect();
        placer.take_outline(&points, true);
        Polygon::new().set("points", points_attr(&points))
    }
}

/// Picture points as an SVG `points` attribute.
fn points_attr(points: &[(f64, f64)]) -> String {
    let text: Vec<String> = points
        .iter()
        .map(|(x, y)| format!("{x:.2},{y:.2}"))
        .collect();
    text.join(" ")
}

/// The still picture as an SVG document.
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::view::{picture, Model};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/tunnelling.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// let model = Model::of_check(path.as_ref(), &scene, &check(&scene, &CheckOptions::default()));
/// let svg = picture(&model);
/// assert!(svg.starts_with("<svg") && svg.contains("needle") && svg.contains("block"));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn picture(m: &Model) -> String {
    cell_svg(m, false).to_string()
}

/// A polygon of the robot's frame at a pose, in world coordinates.
pub fn placed(polygon: &[[f64; 2]], pose: [f64; 3]) -> impl Iterator<Item = [f64; 2]> + '_ {
    let (s, c) = pose[2].sin_cos();
    polygon
        .iter()
        .map(move |v| [pose[0] + c * v[0] - s * v[1], pose[1] + s * v[0] + c * v[1]])
}

/// The cell as an SVG document: still, or as the animated page's stage (no snapshots of the
/// robots, which the page draws moving, and no legend, which the page has beside it).
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::view::{cell_svg, picture, Model};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/tunnelling.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// let model = Model::of_check(path.as_ref(), &scene, &check(&scene, &CheckOptions::default()));
/// let still = cell_svg(&model, false).to_string();
/// let stage = cell_svg(&model, true).to_string();
/// assert_eq!(still, picture(&model));
/// assert!(stage.len() < still.len()); // no snapshots, no legend
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn cell_svg(m: &Model, animated: bool) -> Document {
    let frame = Frame::of(m);
    let legend_rows = if animated {
        0
    } else {
        // Robots, symbols (which may wrap once) and the note of labels left out.
        legend_robots(m).len().div_ceil(LEGEND_PER_ROW) + 3
    };
    // Whole pixels: a page lays the picture out on them, and one unit stays one pixel.
    let height = (frame.height + legend_rows as f64 * LEGEND_ROW + 8.0).ceil();
    let mut doc = page(WIDTH, height);
    if !animated {
        doc = titled(doc, WIDTH, &m.title, &m.verdict);
    }
    let mut placer = Placer::new([0.0, HEADER, WIDTH, frame.height]);
    for o in &m.obstacles {
        doc = doc.add(
            frame
                .outline(o.iter().copied(), &mut placer)
                .set("fill", "#bdbdbd")
                .set("stroke", "#616161"),
        );
    }
    for robot in &m.robots {
        doc = doc.add(robot_layer(m, robot, &frame, animated, &mut placer));
    }
    // Symbols first, so that labels keep clear of them.
    // The page shows the rings itself, at their times.
    let marks: Vec<&Mark> = if animated {
        Vec::new()
    } else if m.rounds.is_empty() {
        m.contact.iter().collect()
    } else {
        m.rounds.iter().collect()
    };
    let rings = rings_of(&marks, &frame);
    let places = ring_places(&rings, &frame, &mut placer);
    doc = scale_bar(doc, &frame, &mut placer);
    doc = homes_and_tasks(doc, m, &frame, &mut placer);
    // Obstacles' names last: a name left out costs less than a task's.
    for (name, at) in &m.obstacle_names {
        let (x, y) = frame.xy(at[0], at[1]);
        doc = add_label(doc, &mut placer, (x, y), name, TASK_FONT, "#616161");
    }
    doc = numbered_rings(doc, &rings, &places, &frame);
    if !animated {
        doc = legend(
            doc,
            m,
            frame.height + 4.0,
            placer.left_out,
            !marks.is_empty(),
        );
    }
    doc
}

/// A bar of a round length (1, 2 or 5 times a power of ten) near a sixth of the drawing's
/// width, at its bottom left, labelled with that length in the file's unit.
fn scale_bar(doc: Document, frame: &Frame, placer: &mut Placer) -> Document {
    let wanted = (WIDTH - 2.0 * MARGIN) / frame.scale / 6.0;
    if !(wanted.is_finite() && wanted > 0.0) {
        return doc;
    }
    let power = 10f64.powf(wanted.log10().floor());
    let length = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|k| k * power)
        .min_by(|a, b| (a / wanted).ln().abs().total_cmp(&(b / wanted).ln().abs()))
        .expect("four lengths");
    let (x0, y) = (MARGIN, frame.height - 10.0);
    let x1 = x0 + length * frame.scale;
    let label = format!("{length}");
    placer.take([
        x0 - 2.0,
        y - 16.0,
        x1 + 4.0 + text_width(&label, 10.0),
        y + 4.0,
    ]);
    let tick = |x: f64| line(x, y - 4.0, x, y + 4.0);
    doc.add(
        Group::new()
            .set("id", "scale")
            .set("stroke", "#212121")
            .set("stroke-width", 1.5)
            .add(line(x0, y, x1, y))
            .add(tick(x0))
            .add(tick(x1)),
    )
    .add(text(x1 + 4.0, y + 3.5, &label, 10.0, "#212121"))
}

/// The robots' names at their homes and the tasks' crosses with their labels ("n. task" in
/// the colour of the robot that does it). Every home and task is taken first, so that no
/// label covers one.
fn homes_and_tasks(mut doc: Document, m: &Model, frame: &Frame, placer: &mut Placer) -> Document {
    for robot in &m.robots {
        if let Some(h) = robot.home {
            let (x, y) = frame.xy(h[0], h[1]);
            placer.take([x - 6.0, y - 6.0, x + 6.0, y + 6.0]);
        }
    }
    for t in &m.tasks {
        let (x, y) = frame.xy(t.pose[0], t.pose[1]);
        placer.take([x - 5.0, y - 5.0, x + 5.0, y + 5.0]);
    }
    for robot in &m.robots {
        if let Some(h) = robot.home {
            let (x, y) = frame.xy(h[0], h[1]);
            doc = add_label(doc, placer, (x, y), &robot.name, HOME_FONT, robot.colour);
        }
    }
    for (k, t) in m.tasks.iter().enumerate() {
        let (x, y) = frame.xy(t.pose[0], t.pose[1]);
        let cross = |dx: f64, dy: f64| line(x - dx, y - dy, x + dx, y + dy);
        doc = doc.add(
            Group::new()
                .set("stroke", "#212121")
                .set("stroke-width", 1.5)
                .add(cross(4.0, 4.0))
                .add(cross(4.0, -4.0)),
        );
        let visit = m
            .robots
            .iter()
            .find_map(|r| Some((r, r.order.iter().position(|&i| i == k)?)));
        let (label, colour) = match visit {
            Some((r, n)) => (format!("{}. {}", n + 1, t.name), r.colour),
            None => (t.name.clone(), "#424242"),
        };
        doc = add_label(doc, placer, (x, y), &label, TASK_FONT, colour);
    }
    doc
}

/// Collisions this close on the picture (pixels) are one place: one ring for them all.
const SAME_PLACE: f64 = 2.0;

/// One ring: the collisions of one place, with their rounds' numbers ("!" for a check's
/// contact) in round order, and its half width (a ring widens into a pill for a list).
struct Ring<'m> {
    at: &'m Mark,
    numbers: String,
    font: f64,
    half_width: f64,
}

/// The rings of `marks`: marks at one place (within [`SAME_PLACE`]) share one, numbered
/// with every round that collided there (a search that met the same collision again).
fn rings_of<'m>(marks: &[&'m Mark], frame: &Frame) -> Vec<Ring<'m>> {
    let mut groups: Vec<(&Mark, Vec<String>)> = Vec::new();
    for mark in marks {
        let number = mark.round.map_or("!".to_owned(), |r| r.to_string());
        let (x, y) = frame.xy(mark.point[0], mark.point[1]);
        let same = groups.iter_mut().find(|(first, _)| {
            let (fx, fy) = frame.xy(first.point[0], first.point[1]);
            (fx - x).hypot(fy - y) <= SAME_PLACE
        });
        match same {
            Some((_, numbers)) => numbers.push(number),
            None => groups.push((mark, vec![number])),
        }
    }
    groups
        .into_iter()
        .map(|(at, numbers)| {
            let numbers = numbers.join(", ");
            let font = if numbers.len() > 2 { 8.0 } else { 11.0 };
            let half_width = RING.max(0.5 * text_width(&numbers, font) + 5.0);
            Ring {
                at,
                numbers,
                font,
                half_width,
            }
        })
        .collect()
}

/// Each ring with its numbers at the place [`ring_places`] chose, led back to the contact
/// point when moved. Leaders go under every ring, so that no leader crosses another
/// round's number.
fn numbered_rings(
    mut doc: Document,
    rings: &[Ring],
    places: &[(f64, f64)],
    frame: &Frame,
) -> Document {
    for (ring, &(cx, cy)) in rings.iter().zip(places) {
        let (x, y) = frame.xy(ring.at.point[0], ring.at.point[1]);
        if (cx - x).hypot(cy - y) > 0.5 {
            doc = doc
                .add(
                    line(x, y, cx, cy)
                        .set("stroke", "#d50000")
                        .set("stroke-width", 0.8),
                )
                .add(circle(x, y, 2.0).set("fill", "#d50000"));
        }
    }
    for (ring, &(cx, cy)) in rings.iter().zip(places) {
        let hw = ring.half_width;
        let outline = Group::new()
            .set("fill", "white")
            .set("fill-opacity", 0.85)
            .set("stroke", "#d50000")
            .set("stroke-width", 2.5);
        let outline = match hw > RING {
            false => outline.add(circle(cx, cy, RING)),
            true => outline.add(
                Rectangle::new()
                    .set("x", cx - hw)
                    .set("y", cy - RING)
                    .set("width", 2.0 * hw)
                    .set("height", 2.0 * RING)
                    .set("rx", RING),
            ),
        };
        doc = doc.add(outline).add(
            text(
                cx,
                cy + ring.font * 0.36,
                &ring.numbers,
                ring.font,
                "#d50000",
            )
            .set("text-anchor", "middle")
            .set("font-weight", "bold"),
        );
    }
    doc
}

/// A robot's path with arrows, and in the still picture its body where it works; every line
/// taken in `placer`.
fn robot_layer(
    m: &Model,
    robot: &RobotView,
    frame: &Frame,
    animated: bool,
    placer: &mut Placer,
) -> Group {
    let colour = robot.colour;
    let mut group = Group::new().set("stroke", colour);
    let path: Vec<(f64, f64)> = robot.samples.iter().map(|s| frame.xy(s[1], s[2])).collect();
    placer.take_outline(&path, false);
    group = group.add(
        Polyline::new()
            .set("points", points_attr(&path))
            .set("fill", "none")
            .set("stroke-width", 2),
    );
    let moving = ["move", "slow", "detour", "aside"];
    for bar in robot.bars.iter().filter(|b| moving.contains(&b.kind)) {
        let mid = 0.5 * (bar.start + bar.end);
        let eps = 0.02 * (bar.end - bar.start);
        let (a, b) = (
            pose_at(&robot.samples, mid - eps),
            pose_at(&robot.samples, mid + eps),
        );
        let (ax, ay) = frame.xy(a[0], a[1]);
        let (bx, by) = frame.xy(b[0], b[1]);
        let len = (bx - ax).hypot(by - ay);
        if len < 1e-3 {
            continue; // a turn in place
        }
        let (ux, uy) = ((bx - ax) / len, (by - ay) / len);
        let (cx, cy) = ((ax + bx) / 2.0, (ay + by) / 2.0);
        let tip = (cx + 5.0 * ux, cy + 5.0 * uy);
        let back = |side: f64| {
            (
                cx - 4.0 * ux - side * 4.0 * uy,
                cy - 4.0 * uy + side * 4.0 * ux,
            )
        };
        let (l, r) = (back(1.0), back(-1.0));
        placer.take_outline(&[tip, l, r], true);
        group = group.add(
            Polygon::new()
                .set(
                    "points",
                    format!(
                        "{:.2},{:.2} {:.2},{:.2} {:.2},{:.2}",
                        tip.0, tip.1, l.0, l.1, r.0, r.1
                    ),
                )
                .set("fill", colour)
                .set("stroke", "none"),
        );
    }
    if !animated {
        // The shape where the robot works, like the paper's snapshots, and at home.
        let poses = robot
            .home
            .into_iter()
            .chain(robot.order.iter().map(|&k| m.tasks[k].pose));
        for pose in poses {
            for polygon in robot.drawn() {
                group = group.add(
                    frame
                        .outline(placed(polygon, pose), placer)
                        .set("fill", colour)
                        .set("fill-opacity", 0.12)
                        .set("stroke-width", 1),
                );
            }
        }
    }
    if let Some(arm) = &robot.arm {
        group = group.add(arm_marks(arm, robot, frame, animated, placer));
    }
    if let Some(h) = robot.home {
        let (x, y) = frame.xy(h[0], h[1]);
        group = group.add(
            Rectangle::new()
                .set("x", x - 5.0)
                .set("y", y - 5.0)
                .set("width", 10)
                .set("height", 10)
                .set("fill", colour),
        );
    }
    group
}

/// A link of an arm: the base as a square (link 0), and in the still picture the link where
/// the arm starts, with its joint as a dot (links past the base); the page draws them moving.
fn arm_marks(
    arm: &ArmView,
    robot: &RobotView,
    frame: &Frame,
    animated: bool,
    placer: &mut Placer,
) -> Group {
    let mut group = Group::new();
    if arm.link == 0 {
        let (x, y) = frame.xy(arm.base[0], arm.base[1]);
        group = group.add(
            Rectangle::new()
                .set("class", "base")
                .set("x", x - 5.0)
                .set("y", y - 5.0)
                .set("width", 10)
                .set("height", 10)
                .set("fill", robot.colour),
        );
    }
    if animated {
        return group;
    }
    let Some(first) = arm.joints.first() else {
        return group;
    };
    let base = Pose::new(arm.base[0], arm.base[1], arm.base[2]);
    let p = forward_kinematics(base, &arm.lengths, &first[1..], arm.link);
    for polygon in robot.drawn() {
        group = group.add(
            frame
                .outline(placed(polygon, [p.pos.x, p.pos.y, p.theta]), placer)
                .set("fill", robot.colour)
                .set("fill-opacity", 0.3)
                .set("stroke-width", 1),
        );
    }
    if arm.link > 0 {
        let (x, y) = frame.xy(p.pos.x, p.pos.y);
        group = group.add(
            Circle::new()
                .set("class", "joint")
                .set("cx", x)
                .set("cy", y)
                .set("r", 3.5)
                .set("fill", robot.colour)
                .set("stroke", "white"),
        );
    }
    group
}

/// Where each ring goes: on its point when free, else on rings round it, away from the
/// rings already placed (rounds often collide at nearly one place).
fn ring_places(rings: &[Ring], frame: &Frame, placer: &mut Placer) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for ring in rings {
        let (x, y) = frame.xy(ring.at.point[0], ring.at.point[1]);
        let (hw, r) = (ring.half_width + 2.0, RING + 2.0);
        let boxed = |cx: f64, cy: f64| -> Rect { [cx - hw, cy - r, cx + hw, cy + r] };
        let spots = std::iter::once((x, y)).chain((1..=4).flat_map(|step| {
            let d = step as f64 * (2.0 * hw.max(r) + 4.0);
            let n = 6 * step;
            (0..n).map(move |k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64 - std::f64::consts::FRAC_PI_4;
                (x + d * a.cos(), y - d * a.sin())
            })
        }));
        let mut chosen = (x, y);
        for (cx, cy) in spots {
            if placer.free(&boxed(cx, cy)) {
                chosen = (cx, cy);
                break;
            }
        }
        placer.take(boxed(chosen.0, chosen.1));
        out.push(chosen);
    }
    out
}

fn add_label(
    doc: Document,
    placer: &mut Placer,
    (x, y): (f64, f64),
    label: &str,
    size: f64,
    colour: &str,
) -> Document {
    let width = text_width(label, size);
    let Some(p) = placer.place(x, y, width, size) else {
        return doc;
    };
    let mut doc = doc;
    if let Some([x0, y0, x1, y1]) = p.leader {
        doc = doc.add(
            line(x0, y0, x1, y1)
                .set("stroke", colour)
                .set("stroke-width", 0.6),
        );
    }
    doc.add(text(p.x, p.y, label, size, colour).set("class", "label"))
}

/// A symbol drawn with its baseline's left end at (x, y).
type Symbol = fn(f64, f64) -> Box<dyn svg::Node>;

/// The legend's symbols and what each means: only those the picture shows.
fn legend_entries(m: &Model, rings: bool) -> Vec<(Symbol, &'static str)> {
    let mut entries: Vec<(Symbol, &'static str)> = vec![(
        |x, y| {
            Box::new(
                Rectangle::new()
                    .set("x", x)
                    .set("y", y - 10.0)
                    .set("width", 12)
                    .set("height", 10)
                    .set("fill", "#bdbdbd")
                    .set("stroke", "#616161"),
            )
        },
        "obstacle",
    )];
    if m.robots.iter().any(|r| r.home.is_some()) {
        entries.push((
            |x, y| {
                Box::new(
                    Rectangle::new()
                        .set("x", x + 1.0)
                        .set("y", y - 9.0)
                        .set("width", 9)
                        .set("height", 9)
                        .set("fill", "#424242"),
                )
            },
            "home",
        ));
    }
    if !m.tasks.is_empty() {
        entries.push((
            |x, y| {
                Box::new(
                    Group::new()
                        .set("stroke", "#212121")
                        .set("stroke-width", 1.5)
                        .add(line(x + 2.0, y - 9.0, x + 10.0, y - 1.0))
                        .add(line(x + 2.0, y - 1.0, x + 10.0, y - 9.0)),
                )
            },
            "n. task: the robot's n-th task (in its colour); arrows: direction of travel",
        ));
    }
    if rings {
        entries.push((
            |x, y| {
                Box::new(
                    circle(x + 6.0, y - 5.0, 6.0)
                        .set("fill", "none")
                        .set("stroke", "#d50000")
                        .set("stroke-width", 2),
                )
            },
            if m.rounds.is_empty() {
                "the collision"
            } else {
                "n: where round n's schedule collided (that schedule was rejected)"
            },
        ));
    }
    entries
}

/// The robots the legend names: an arm once, though each of its links is drawn as a body.
fn legend_robots(m: &Model) -> Vec<&RobotView> {
    let mut named: Vec<&RobotView> = Vec::new();
    for robot in &m.robots {
        if named.last().is_none_or(|last| last.name != robot.name) {
            named.push(robot);
        }
    }
    named
}

fn legend(mut doc: Document, m: &Model, top: f64, left_out: usize, rings: bool) -> Document {
    let mut y = top + LEGEND_ROW - 4.0;
    for row in legend_robots(m).chunks(LEGEND_PER_ROW) {
        let mut x = MARGIN;
        for robot in row {
            doc = doc
                .add(
                    line(x, y - 4.0, x + 18.0, y - 4.0)
                        .set("stroke", robot.colour)
                        .set("stroke-width", 3),
                )
                .add(text(x + 22.0, y, &robot.name, 12.0, "#212121"));
            x += (WIDTH - 2.0 * MARGIN) / LEGEND_PER_ROW as f64;
        }
        y += LEGEND_ROW;
    }
    let entries = legend_entries(m, rings);
    let mut x = MARGIN;
    for (symbol, what) in entries {
        if x + 18.0 + text_width(what, 12.0) > WIDTH - MARGIN {
            x = MARGIN;
            y += LEGEND_ROW;
        }
        doc = doc
            .add(symbol(x, y))
            .add(text(x + 18.0, y, what, 12.0, "#212121"));
        x += 18.0 + text_width(what, 12.0) + 14.0;
    }
    if left_out > 0 {
        y += LEGEND_ROW;
        doc = doc.add(text(
            MARGIN,
            y,
            &format!("{left_out} labels left out where they would overprint or cross a line"),
            11.0,
            "#616161",
        ));
    }
    doc
}

fn circle(x: f64, y: f64, r: f64) -> Circle {
    Circle::new().set("cx", x).set("cy", y).set("r", r)
}

/// A white page `width` × `height` pixels, one unit a pixel.
pub(super) fn page(width: f64, height: f64) -> Document {
    Document::new()
        .set("viewBox", (0.0, 0.0, width, height))
        .set("width", width)
        .set("height", height)
        .set("font-family", "sans-serif")
        .add(
            Rectangle::new()
                .set("width", "100%")
                .set("height", "100%")
                .set("fill", "white"),
        )
}

/// The title in bold and the verdict under it, centred at the top of a page `width` wide.
pub(super) fn titled(doc: Document, width: f64, title: &str, verdict: &str) -> Document {
    doc.add(
        text(width / 2.0, 24.0, title, 18.0, "#212121")
            .set("text-anchor", "middle")
            .set("font-weight", "bold"),
    )
    .add(text(width / 2.0, 44.0, verdict, 13.0, "#424242").set("text-anchor", "middle"))
}

pub(super) fn line(x1: f64, y1: f64, x2: f64, y2: f64) -> Line {
    Line::new()
        .set("x1", x1)
        .set("y1", y1)
        .set("x2", x2)
        .set("y2", y2)
}

pub(super) fn text(x: f64, y: f64, content: &str, size: f64, colour: &str) -> Text {
    Text::new(content)
        .set("x", x)
        .set("y", y)
        .set("fill", colour)
        .set("stroke", "none")
        .set("font-size", size)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rounds that collided at one place share one ring, numbered with each of them;
    /// a collision elsewhere keeps its own.
    #[test]
    fn rings_of_one_place_are_merged_with_their_rounds() {
        let mark = |round: usize, point: [f64; 2]| Mark {
            round: Some(round),
            time: round as f64,
            bodies: ["R1".into(), "R2".into()],
            point,
        };
        let square = vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
        let model = Model {
            title: "rings".into(),
            verdict: String::new(),
            end: 1.0,
            delta: 0.01,
            robots: Vec::new(),
            obstacles: vec![square],
            obstacle_names: Vec::new(),
            tasks: Vec::new(),
            rounds: vec![
                mark(1, [2.0, 2.0]),
                mark(2, [8.0, 8.0]),
                mark(3, [2.0, 2.0 + 1e-6]),
                mark(4, [2.0, 2.0]),
            ],
            contact: None,
            safe_until: None,
        };
        let frame = Frame::of(&model);
        let marks: Vec<&Mark> = model.rounds.iter().collect();
        let rings = rings_of(&marks, &frame);
        let numbers: Vec<&str> = rings.iter().map(|r| r.numbers.as_str()).collect();
        assert_eq!(numbers, ["1, 3, 4", "2"]);
        assert!(rings[0].half_width > RING && rings[1].half_width == RING);
        let svg = picture(&model);
        assert!(svg.contains("1, 3, 4") && svg.contains(">\n2\n<"), "{svg}");
    }
}
