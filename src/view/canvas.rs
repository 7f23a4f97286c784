//! What every SVG picture shares: the page and its title, the frame from world to picture
//! coordinates, the sizes of the still picture's parts, and the few shapes drawn everywhere.

use super::labels::Placer;
use super::model::Model;
use svg::node::element::{Circle, Line, Polygon, Rectangle, Text};
use svg::Document;

/// Width of the picture in pixels; the height follows the cell's aspect ratio.
pub const WIDTH: f64 = 900.0;
/// Margin round the drawing of the cell.
pub(super) const MARGIN: f64 = 30.0;
/// Room above the cell for the title and the verdict.
pub(super) const HEADER: f64 = 56.0;
/// One row of the legend.
pub(super) const LEGEND_ROW: f64 = 18.0;
/// Robots per legend row.
pub(super) const LEGEND_PER_ROW: usize = 6;
/// Radius of a collision ring.
pub(super) const RING: f64 = 9.0;
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
    pub(super) fn outline(
        &self,
        vertices: impl Iterator<Item = [f64; 2]>,
        placer: &mut Placer,
    ) -> Polygon {
        let points: Vec<(f64, f64)> = vertices.map(|v| self.xy(v[0], v[1])).collect();
        placer.take_outline(&points, true);
        Polygon::new().set("points", points_attr(&points))
    }
}

/// Picture points as an SVG `points` attribute.
pub(super) fn points_attr(points: &[(f64, f64)]) -> String {
    let text: Vec<String> = points
        .iter()
        .map(|(x, y)| format!("{x:.2},{y:.2}"))
        .collect();
    text.join(" ")
}

pub(super) fn circle(x: f64, y: f64, r: f64) -> Circle {
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
