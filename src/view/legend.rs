//! The legend under the picture: the robots in their colours, then the symbols the
//! picture shows and what each means.

use super::canvas::{circle, line, text, LEGEND_PER_ROW, LEGEND_ROW, MARGIN, WIDTH};
use super::labels::text_width;
use super::model::{Model, RobotView};
use svg::node::element::{Group, Rectangle};
use svg::Document;

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
pub(super) fn legend_robots(m: &Model) -> Vec<&RobotView> {
    let mut named: Vec<&RobotView> = Vec::new();
    for robot in &m.robots {
        if named.last().is_none_or(|last| last.name != robot.name) {
            named.push(robot);
        }
    }
    named
}

pub(super) fn legend(
    mut doc: Document,
    m: &Model,
    top: f64,
    left_out: usize,
    rings: bool,
) -> Document {
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
