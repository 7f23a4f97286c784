//! `--svg`: the cell and its schedule in the manner of the paper's Figure 12.
//!
//! Obstacles in grey, tasks as crosses with their names, homes as squares, each robot's path
//! in its own colour with its shape drawn at home and at each of its tasks, and the point of
//! each collision fed back (numbered by round) as a red ring.

use super::moves::node_pose;
use super::schedule::{Activity, Collision, Schedule};
use crate::cell::Cell;
use crate::geometry::{ConvexPolygon, Posed, Vec2};
use crate::motion::Pose;
use svg::node::element::{Circle, Group, Line, Polygon, Polyline, Rectangle, Text};
use svg::Document;

/// Robot colours, distinct on white and for the common colour-vision deficiencies first
/// (Okabe-Ito), then more.
const COLOURS: [&str; 12] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#8C564B",
    "#7F7F7F", "#BCBD22", "#17BECF", "#9467BD",
];

/// Width of the picture in pixels; the height follows the cell's aspect ratio.
const WIDTH: f64 = 900.0;

/// The picture as an SVG document. `collisions` are the collisions fed back, in round order.
pub fn picture(cell: &Cell, schedule: &Schedule, collisions: &[&Collision]) -> String {
    let frame = Frame::around(cell, schedule);
    let mut doc = Document::new()
        .set("viewBox", (0.0, 0.0, WIDTH, frame.height))
        .set("width", WIDTH)
        .set("height", frame.height)
        .set("font-family", "sans-serif")
        .add(
            Rectangle::new()
                .set("width", "100%")
                .set("height", "100%")
                .set("fill", "white"),
        );
    for o in &cell.obstacles {
        doc = doc.add(
            frame
                .polygon(o.shape.vertices().iter().copied())
                .set("fill", "#bdbdbd")
                .set("stroke", "#616161"),
        );
    }
    for (r, (robot, plan)) in cell.robots.iter().zip(&schedule.robots).enumerate() {
        let colour = COLOURS[r % COLOURS.len()];
        let mut group = Group::new().set("stroke", colour);
        let points: Vec<String> = plan.path.iter().map(|p| frame.point(*p)).collect();
        group = group.add(
            Polyline::new()
                .set("points", points.join(" "))
                .set("fill", "none")
                .set("stroke-width", 2),
        );
        // The shape where the robot works, like the paper's snapshots, and at home.
        let mut poses = vec![robot.home];
        poses.extend(plan.segments.iter().filter_map(|s| match s.activity {
            Activity::Work(t) => Some(node_pose(cell, r, t + 1)),
            _ => None,
        }));
        for pose in poses {
            group = group.add(
                frame
                    .polygon(world(&robot.shape, pose))
                    .set("fill", colour)
                    .set("fill-opacity", 0.12)
                    .set("stroke-width", 1),
            );
        }
        let (x, y) = frame.xy(robot.home.pos);
        group = group
            .add(
                Rectangle::new()
                    .set("x", x - 5.0)
                    .set("y", y - 5.0)
                    .set("width", 10)
                    .set("height", 10)
                    .set("fill", colour),
            )
            .add(label(&robot.name, x + 8.0, y - 8.0, colour));
        doc = doc.add(group);
    }
    for task in &cell.tasks {
        let (x, y) = frame.xy(task.at.pos);
        let cross = |dx: f64, dy: f64| {
            Line::new()
                .set("x1", x - dx)
                .set("y1", y - dy)
                .set("x2", x + dx)
                .set("y2", y + dy)
        };
        doc = doc
            .add(
                Group::new()
                    .set("stroke", "#212121")
                    .set("stroke-width", 1.5)
                    .add(cross(4.0, 4.0))
                    .add(cross(4.0, -4.0)),
            )
            .add(label(&task.name, x + 5.0, y + 12.0, "#424242").set("font-size", 10));
    }
    for (k, c) in collisions.iter().enumerate() {
        let (x, y) = frame.xy(c.point);
        // Rounds often collide at nearly one place: fan the numbers out around the ring.
        let (dy, dx) = (0.9 * k as f64 - 0.8).sin_cos();
        doc = doc
            .add(
                Circle::new()
                    .set("cx", x)
                    .set("cy", y)
                    .set("r", 9)
                    .set("fill", "none")
                    .set("stroke", "#d50000")
                    .set("stroke-width", 2.5),
            )
            .add(
                label(
                    &format!("{}", k + 1),
                    x + 16.0 * dx - 4.0,
                    y - 16.0 * dy + 4.0,
                    "#d50000",
                )
                .set("font-weight", "bold"),
            );
    }
    doc.to_string()
}

fn label(text: &str, x: f64, y: f64, colour: &str) -> Text {
    Text::new(text)
        .set("x", x)
        .set("y", y)
        .set("fill", colour)
        .set("stroke", "none")
        .set("font-size", 12)
}

fn world(shape: &ConvexPolygon, pose: Pose) -> impl Iterator<Item = Vec2> + '_ {
    let placed = Posed::new(shape, pose.pos.x, pose.pos.y, pose.theta);
    (0..placed.len()).map(move |i| placed.vertex(i))
}

/// World to picture coordinates: uniform scale, y up.
struct Frame {
    min: Vec2,
    max_y: f64,
    scale: f64,
    height: f64,
}

impl Frame {
    const MARGIN: f64 = 30.0;

    fn around(cell: &Cell, schedule: &Schedule) -> Frame {
        let mut points: Vec<Vec2> = cell
            .obstacles
            .iter()
            .flat_map(|o| o.shape.vertices().iter().copied())
            .collect();
        for (robot, plan) in cell.robots.iter().zip(&schedule.robots) {
            let r = robot.shape.radius();
            for p in plan.path.iter().chain([&robot.home.pos]) {
                points.extend([p + Vec2::new(r, r), p - Vec2::new(r, r)]);
            }
        }
        points.extend(cell.tasks.iter().map(|t| t.at.pos));
        let min = points
            .iter()
            .fold(Vec2::repeat(f64::INFINITY), |m, p| m.inf(p));
        let max = points
            .iter()
            .fold(Vec2::repeat(f64::NEG_INFINITY), |m, p| m.sup(p));
        let size = (max - min).map(|v| v.max(1e-9));
        let scale = (WIDTH - 2.0 * Self::MARGIN) / size.x;
        let height = (size.y * scale + 2.0 * Self::MARGIN).clamp(200.0, 4.0 * WIDTH);
        let scale = scale.min((height - 2.0 * Self::MARGIN) / size.y);
        Frame {
            min,
            max_y: max.y,
            scale,
            height,
        }
    }

    fn xy(&self, p: Vec2) -> (f64, f64) {
        (
            Self::MARGIN + (p.x - self.min.x) * self.scale,
            Self::MARGIN + (self.max_y - p.y) * self.scale,
        )
    }

    fn point(&self, p: Vec2) -> String {
        let (x, y) = self.xy(p);
        format!("{x:.2},{y:.2}")
    }

    fn polygon(&self, vertices: impl Iterator<Item = Vec2>) -> Polygon {
        let points: Vec<String> = vertices.map(|v| self.point(v)).collect();
        Polygon::new().set("points", points.join(" "))
    }
}
