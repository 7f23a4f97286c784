//! The trade-off at a glance: time per check (log) against collisions missed, one point per
//! method and sampling step.

use crate::compare::Comparison;
use svg::node::element::{Circle, Group, Line, Polyline, Rectangle, Text};
use svg::Document;

const WIDTH: f64 = 760.0;
const HEIGHT: f64 = 520.0;
/// Plot area inside the margins.
const LEFT: f64 = 70.0;
const RIGHT: f64 = 680.0;
const TOP: f64 = 110.0;
const BOTTOM: f64 = 460.0;
/// The title's baseline.
const TITLE_Y: f64 = 24.0;
/// A label's line height and a generous width per character at font size 12, for placing
/// labels clear of each other.
const LABEL_HEIGHT: f64 = 15.0;
const LABEL_CHAR_WIDTH: f64 = 7.0;

/// The chart as an SVG document.
///
/// ```
/// use workcell::compare::{compare, NamedScene};
/// use workcell::view::chart;
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/tunnelling.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// let scenes = [NamedScene { name: "tunnelling.json".into(), scene }];
/// let result = compare(&scenes, &["adaptive".parse()?, "sampled:1".parse()?], |_| ());
/// let svg = chart(&result);
/// assert!(svg.starts_with("<svg") && svg.contains("adaptive") && svg.contains("sampled:1"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn chart(c: &Comparison) -> String {
    let points: Vec<Point> = c
        .methods
        .iter()
        .filter(|m| m.median_us.is_finite() && m.median_us > 0.0)
        .map(|m| (m.method.as_str(), m.median_us, m.missed, m.invented))
        .collect();
    let scale = Scale::of(&points);
    let title = format!(
        "{} scenes ({} colliding): time per check against collisions missed",
        c.scenes, c.colliding
    );
    let mut doc = frame(&scale, &title);
    // The sampling steps as one curve: finer steps cost more and miss less.
    let sampled: Vec<String> = points
        .iter()
        .filter(|p| p.0.starts_with("sampled:"))
        .map(|p| format!("{},{}", scale.x(p.1), scale.y(p.2 as f64)))
        .collect();
    if sampled.len() > 1 {
        doc = doc.add(
            Polyline::new()
                .set("points", sampled.join(" "))
                .set("fill", "none")
                .set("stroke", colour("sampled"))
                .set("stroke-dasharray", "4 3"),
        );
    }
    labelled_points(doc, &points, &scale, &title).to_string()
}

/// A method's point: its name, median time per check (µs), scenes missed and invented.
type Point<'a> = (&'a str, f64, usize, usize);

/// The axes' ranges: whole decades of µs around the times, missed from 0 to at least 1.
struct Scale {
    lo: f64,
    hi: f64,
    top_missed: f64,
}

impl Scale {
    fn of(points: &[Point]) -> Scale {
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.1.log10()), hi.max(p.1.log10()))
            });
        let (lo, hi) = if lo.is_finite() {
            (lo.floor(), hi.ceil().max(lo.floor() + 1.0))
        } else {
            (0.0, 1.0)
        };
        let top_missed = points.iter().map(|p| p.2).max().unwrap_or(0).max(1) as f64;
        Scale { lo, hi, top_missed }
    }

    fn x(&self, us: f64) -> f64 {
        LEFT + (us.log10() - self.lo) / (self.hi - self.lo) * (RIGHT - LEFT)
    }

    fn y(&self, missed: f64) -> f64 {
        BOTTOM - missed / self.top_missed * (BOTTOM - TOP)
    }
}

/// The page: background, title, axes, grid lines with their values, and axis titles.
fn frame(scale: &Scale, title: &str) -> Document {
    let mut doc = Document::new()
        .set("viewBox", (0.0, 0.0, WIDTH, HEIGHT))
        .set("width", WIDTH)
        .set("height", HEIGHT)
        .set("font-family", "sans-serif")
        .set("font-size", 12)
        .add(
            Rectangle::new()
                .set("width", "100%")
                .set("height", "100%")
                .set("fill", "white"),
        )
        .add(text(WIDTH / 2.0, TITLE_Y, title, "middle"));
    let mut axes = Group::new().set("stroke", "#444").set("stroke-width", 1);
    axes = axes
        .add(line(LEFT, BOTTOM, RIGHT, BOTTOM))
        .add(line(LEFT, TOP, LEFT, BOTTOM));
    doc = doc.add(axes);
    for decade in scale.lo as i32..=scale.hi as i32 {
        let px = scale.x(10f64.powi(decade));
        doc = doc
            .add(line(px, BOTTOM, px, TOP).set("stroke", "#e0e0e0"))
            .add(text(px, BOTTOM + 18.0, &decade_label(decade), "middle"));
    }
    let step = (scale.top_missed / 5.0).ceil().max(1.0);
    let mut m = 0.0;
    while m <= scale.top_missed {
        let y = scale.y(m);
        doc = doc
            .add(line(LEFT, y, RIGHT, y).set("stroke", "#e0e0e0"))
            .add(text(LEFT - 8.0, y + 4.0, &format!("{m}"), "end"));
        m += step;
    }
    doc.add(text(
        (LEFT + RIGHT) / 2.0,
        BOTTOM + 40.0,
        "median time per whole-scene check (µs, log scale)",
        "middle",
    ))
    .add(text(0.0, 0.0, "collisions missed (scenes)", "middle").set(
        "transform",
        format!("translate(20 {}) rotate(-90)", (TOP + BOTTOM) / 2.0),
    ))
}

/// Each method's point and label, in order of time. Labels read horizontally, just above and
/// right of their point (left of it near the right edge). One that would overlap a label
/// already placed, a point or the title moves up a line at a time, with a leader line back to
/// its point.
fn labelled_points(mut doc: Document, points: &[Point], scale: &Scale, title: &str) -> Document {
    let title_half = LABEL_CHAR_WIDTH * title.chars().count() as f64 / 2.0;
    let mut taken: Vec<[f64; 4]> = points
        .iter()
        .map(|p| {
            let (px, py) = (scale.x(p.1), scale.y(p.2 as f64));
            [px - 5.0, py - 5.0, px + 5.0, py + 5.0]
        })
        .chain([[
            WIDTH / 2.0 - title_half,
            TITLE_Y - LABEL_HEIGHT,
            WIDTH / 2.0 + title_half,
            TITLE_Y + 4.0,
        ]])
        .collect();
    let mut by_x: Vec<_> = points.iter().collect();
    by_x.sort_by(|a, b| a.1.total_cmp(&b.1));
    for &&(name, us, missed, invented) in &by_x {
        let (px, py) = (scale.x(us), scale.y(missed as f64));
        let label = if invented > 0 {
            format!("{name} ({invented} invented)")
        } else {
            name.to_string()
        };
        let width = LABEL_CHAR_WIDTH * label.chars().count() as f64;
        // Inside the plot: left of the point when the right would run past the axis's end,
        // and against the axis's start when neither side has room.
        let left = px + 8.0 + width > RIGHT;
        let (x0, anchor) = if !left {
            (px + 8.0, "start")
        } else if px - 8.0 - width >= LEFT {
            (px - 8.0 - width, "end")
        } else {
            (LEFT + 2.0, "start")
        };
        let mut base = py - 8.0;
        let overlaps = |base: f64, r: &[f64; 4]| {
            // A space's width apart, so that neighbours do not read as one word.
            let b = [
                x0 - 6.0,
                base - LABEL_HEIGHT + 2.0,
                x0 + width + 6.0,
                base + 2.0,
            ];
            b[0] < r[2] && r[0] < b[2] && b[1] < r[3] && r[1] < b[3]
        };
        while base > LABEL_HEIGHT && taken.iter().any(|r| overlaps(base, r)) {
            base -= LABEL_HEIGHT;
        }
        taken.push([x0, base - LABEL_HEIGHT + 2.0, x0 + width, base + 2.0]);
        let lx = if anchor == "end" { x0 + width } else { x0 };
        if base < py - 8.0 - 1.0 {
            doc = doc.add(
                line(px, py - 5.0, lx, base - 4.0)
                    .set("stroke", colour(name))
                    .set("stroke-width", 0.6),
            );
        }
        doc = doc
            .add(
                Circle::new()
                    .set("cx", px)
                    .set("cy", py)
                    .set("r", 5)
                    .set("fill", colour(name))
                    .set("stroke", if invented > 0 { "#d00" } else { "none" })
                    .set("stroke-width", 2),
            )
            .add(text(lx, base, &label, anchor).set("fill", colour(name)));
    }
    doc
}

fn colour(method: &str) -> &'static str {
    match method {
        "adaptive" => "#0072B2",
        "adaptive-paper" => "#56B4E9",
        "advance" => "#009E73",
        "parry" => "#000000",
        _ => "#D55E00",
    }
}

fn decade_label(decade: i32) -> String {
    if (0..=6).contains(&decade) {
        format!("{}", 10u64.pow(decade as u32))
    } else {
        format!("1e{decade}")
    }
}

fn line(x1: f64, y1: f64, x2: f64, y2: f64) -> Line {
    Line::new()
        .set("x1", x1)
        .set("y1", y1)
        .set("x2", x2)
        .set("y2", y2)
}

fn text(x: f64, y: f64, content: &str, anchor: &str) -> Text {
    Text::new(content)
        .set("x", x)
        .set("y", y)
        .set("text-anchor", anchor)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compare::MethodSummary;

    fn method(name: &str, median_us: f64, missed: usize) -> MethodSummary {
        MethodSummary {
            method: name.to_owned(),
            median_us,
            missed,
            invented: 0,
            max_time_error: None,
            unsupported: 0,
        }
    }

    /// Every label's estimated box ends inside the plot, even next to the last decade.
    #[test]
    fn labels_stay_inside_the_plot() {
        let c = Comparison {
            scenes: 10,
            colliding: 5,
            methods: vec![
                method("adaptive", 10.0, 0),
                method("a-rather-long-method-name:0.0001", 999.0, 3),
                method("sampled:0.001", 1000.0, 0),
                method("sampled:1", 1.0, 3),
            ],
            disagreements: Vec::new(),
            threads: 2,
        };
        let svg = chart(&c);
        let mut checked = 0;
        for piece in svg.split("<text").skip(1) {
            let tag = &piece[..piece.find('>').unwrap()];
            let attr = |name: &str| -> Option<f64> {
                let at = tag.find(&format!(" {name}=\""))? + name.len() + 3;
                tag[at..].split('"').next()?.parse().ok()
            };
            let content = &piece[piece.find('>').unwrap() + 1..piece.find("</text>").unwrap()];
            let width = LABEL_CHAR_WIDTH * content.chars().count() as f64;
            let x = attr("x").unwrap();
            if !tag.contains("fill=") {
                continue; // the axes' own labels
            }
            let (x0, x1) = if tag.contains("text-anchor=\"end\"") {
                (x - width, x)
            } else {
                (x, x + width)
            };
            assert!(x0 >= LEFT && x1 <= RIGHT, "{content} at [{x0}, {x1}]");
            checked += 1;
        }
        assert_eq!(checked, 4);
    }
}
