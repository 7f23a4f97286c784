//! `--svg`: the cell and its schedule in the manner of the paper's Figure 12, with a title,
//! a legend, the visiting order and collision rings set apart.
//!
//! Obstacles in grey, tasks as crosses labelled with their place in their robot's route,
//! homes as squares, each robot's path in its own colour with arrowheads along it and its
//! shape at home and at each of its tasks, and the point of each collision fed back as a red
//! ring numbered by round.

use super::canvas::{
    line, page, points_attr, text, titled, Frame, HEADER, LEGEND_PER_ROW, LEGEND_ROW, MARGIN, WIDTH,
};
use super::labels::{text_width, Placer};
use super::legend::{legend, legend_robots};
use super::model::{pose_at, ArmView, Mark, Model, RobotView};
use super::rings::{numbered_rings, ring_places, rings_of};
use crate::motion::{forward_kinematics, Pose};
use svg::node::element::{Circle, Group, Polygon, Polyline, Rectangle};
use svg::Document;

/// Font sizes of the labels of tasks and homes.
const TASK_FONT: f64 = 10.0;
const HOME_FONT: f64 = 12.0;

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
