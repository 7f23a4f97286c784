//! `--gantt`: one lane per robot, its moves, tasks, waits and remedies as coloured bars over
//! a time axis; the makespan marked, a collision of the schedule drawn on its robots' lanes,
//! and the collisions of the feedback rounds' rejected schedules in a strip of their own
//! under the lanes (they are not in the schedule drawn).

use super::bars::{kind_colour, KINDS};
use super::canvas::{line, page, text, titled};
use super::labels::{text_width, Placer};
use super::model::{Mark, Model, RobotView};
use svg::node::element::{Group, Polygon, Rectangle, Title};
use svg::Document;

/// Width of the chart.
pub const WIDTH: f64 = 1000.0;
/// Left of the time axis: room for the robots' names.
const LEFT: f64 = 90.0;
/// Right margin.
const RIGHT: f64 = 40.0;
/// Room for the title and the verdict, and the makespan's label below them.
const HEADER: f64 = 74.0;
/// Height of a lane and of a bar in it.
const LANE: f64 = 34.0;
const BAR: f64 = 16.0;
/// Height of the strip of the rejected rounds' collisions.
const STRIP: f64 = 30.0;
/// The time axis under the lanes, and a legend row.
const AXIS: f64 = 36.0;
const LEGEND_ROW: f64 = 18.0;
const KINDS_PER_ROW: usize = 5;
/// Font size of the task names in their bars.
const BAR_FONT: f64 = 10.0;
/// Narrowest bar of a wait, pause or other remedy, in pixels.
const MIN_REMEDY_WIDTH: f64 = 3.0;
/// About this many ticks on the time axis.
const TICKS: f64 = 10.0;

/// Time to chart coordinates, which the animated page's cursor reads back.
#[derive(Clone, Copy, Debug)]
pub struct TimeAxis {
    /// Time at the left end of the axis.
    pub t0: f64,
    /// Pixels per time unit.
    pub scale: f64,
    /// The chart x of `t0`.
    pub left: f64,
}

impl TimeAxis {
    /// The chart x of time `t`.
    pub fn x(&self, t: f64) -> f64 {
        self.left + (t - self.t0) * self.scale
    }
}

/// The chart as an SVG document.
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::view::{gantt, Model};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/tunnelling.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// let model = Model::of_check(path.as_ref(), &scene, &check(&scene, &CheckOptions::default()));
/// let svg = gantt(&model);
/// assert!(svg.starts_with("<svg") && svg.contains("needle") && !svg.contains("cursor"));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn gantt(m: &Model) -> String {
    gantt_svg(m, WIDTH, false).0.to_string()
}

/// The chart `width` pixels wide and its time axis; with a cursor (a line `#cursor`) for the
/// animated page.
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::view::{gantt_svg, Model};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/tunnelling.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// let model = Model::of_check(path.as_ref(), &scene, &check(&scene, &CheckOptions::default()));
/// let (doc, axis) = gantt_svg(&model, 800.0, true);
/// assert!(doc.to_string().contains(r#"id="cursor""#));
/// assert!(axis.x(model.start()) < axis.x(model.end) && axis.x(model.end) <= 800.0);
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn gantt_svg(m: &Model, width: f64, cursor: bool) -> (Document, TimeAxis) {
    let (t0, t1) = (m.start(), m.end.max(m.start() + 1e-9));
    let axis = TimeAxis {
        t0,
        scale: (width - LEFT - RIGHT) / (t1 - t0),
        left: LEFT,
    };
    // One lane per robot (an arm's links share its first link's), and the rounds' strip.
    let lanes_end = HEADER + LANE * m.robots.iter().filter(|r| r.leads()).count() as f64;
    let strip = if rejected(m).next().is_none() {
        0.0
    } else {
        STRIP
    };
    let lanes_bottom = lanes_end + strip;
    let kinds: Vec<_> = KINDS
        .iter()
        .filter(|k| {
            m.robots
                .iter()
                .any(|r| r.bars.iter().any(|b| b.kind == k.0))
        })
        .collect();
    // The kinds five to a row, then a row for the collision marks.
    let marked = m.contact.is_some() || rejected(m).next().is_some();
    let legend_rows = kinds.len().div_ceil(KINDS_PER_ROW) + usize::from(marked);
    let height = lanes_bottom + AXIS + LEGEND_ROW * legend_rows as f64 + 8.0;
    let chart = Chart {
        m,
        width,
        axis,
        t1,
        lanes_end,
        lanes_bottom,
    };
    let mut doc = chart.header(height);
    doc = chart.ticks(doc);
    let mut placer = Placer::new([LEFT, 48.0, width, lanes_bottom]);
    for (r, robot) in m.robots.iter().filter(|r| r.leads()).enumerate() {
        doc = chart.lane(doc, r, robot, &mut placer);
    }
    doc = chart.makespan(doc, &mut placer);
    doc = chart.rejected_rounds(doc, &mut placer);
    doc = chart.contact(doc, &mut placer);
    if cursor {
        doc = doc.add(
            line(LEFT, HEADER - 4.0, LEFT, lanes_bottom + 4.0)
                .set("id", "cursor")
                .set("stroke", "#d50000")
                .set("stroke-width", 2),
        );
    }
    (chart.legend(doc, &kinds), axis)
}

/// What every part of the chart is drawn from.
struct Chart<'a> {
    m: &'a Model,
    width: f64,
    axis: TimeAxis,
    /// The end of the time axis.
    t1: f64,
    /// The bottom of the last robot's lane.
    lanes_end: f64,
    /// The bottom of the rounds' strip (of the lanes when there is none): the time axis.
    lanes_bottom: f64,
}

impl Chart<'_> {
    /// A white page with the title and the verdict.
    fn header(&self, height: f64) -> Document {
        let title = format!("{}: schedule", self.m.title);
        titled(
            page(self.width, height),
            self.width,
            &title,
            &self.m.verdict,
        )
    }

    /// The time axis under the lanes, with grid lines and labels at 1, 2 or 5 times a power
    /// of ten.
    fn ticks(&self, doc: Document) -> Document {
        let (axis, t1, lanes_bottom) = (self.axis, self.t1, self.lanes_bottom);
        let raw = (t1 - axis.t0) / TICKS;
        let p = 10f64.powf(raw.log10().floor());
        let step = [1.0, 2.0, 5.0, 10.0]
            .into_iter()
            .map(|f| f * p)
            .find(|s| *s >= raw)
            .unwrap_or(10.0 * p);
        let mut t = (axis.t0 / step).ceil() * step;
        let mut ticks = Group::new().set("stroke", "#e0e0e0");
        let mut tick_labels = Group::new();
        while t <= t1 + 1e-9 * step {
            let x = axis.x(t);
            ticks = ticks
                .add(line(x, HEADER, x, lanes_bottom))
                .add(line(x, lanes_bottom, x, lanes_bottom + 5.0).set("stroke", "#424242"));
            let label = format!("{}", (t / step).round() * step);
            let label = if label.len() > 8 {
                format!("{t:.3e}")
            } else {
                label
            };
            tick_labels = tick_labels.add(
                text(x, lanes_bottom + 18.0, &label, 11.0, "#424242").set("text-anchor", "middle"),
            );
            t += step;
        }
        doc.add(ticks)
            .add(tick_labels)
            .add(line(LEFT, lanes_bottom, axis.x(t1), lanes_bottom).set("stroke", "#424242"))
            .add(
                text(
                    self.width - RIGHT,
                    lanes_bottom + 32.0,
                    "time",
                    11.0,
                    "#424242",
                )
                .set("text-anchor", "end"),
            )
    }

    /// Robot `r`'s name and lane of bars, task names in the bars they fit.
    fn lane(&self, doc: Document, r: usize, robot: &RobotView, placer: &mut Placer) -> Document {
        let (axis, t1) = (self.axis, self.t1);
        // The collision on this lane: a task's name is left out of a bar that it would cover.
        let marks_here: Vec<f64> = self
            .m
            .contact
            .iter()
            .filter(|mark| mark.bodies.contains(&robot.name))
            .map(|mark| axis.x(mark.time))
            .collect();
        let y = HEADER + LANE * r as f64 + (LANE - BAR) / 2.0;
        let doc = doc.add(
            text(LEFT - 8.0, y + BAR * 0.75, &robot.name, 12.0, robot.colour)
                .set("text-anchor", "end")
                .set("font-weight", "bold"),
        );
        let mut lane = Group::new();
        // Remedies over the moves round them, which would hide a short one.
        let plain = |kind: &str| matches!(kind, "move" | "task" | "still");
        let order = robot
            .bars
            .iter()
            .filter(|b| plain(b.kind))
            .chain(robot.bars.iter().filter(|b| !plain(b.kind)));
        for bar in order {
            let (x0, x1) = (axis.x(bar.start), axis.x(bar.end.min(t1)));
            // A remedy stays visible however short: a pause of 9 ms is what made it work.
            let least = if plain(bar.kind) {
                0.5
            } else {
                MIN_REMEDY_WIDTH
            };
            let w = (x1 - x0).max(least);
            lane = lane.add(
                Rectangle::new()
                    .set("x", x0)
                    .set("y", y)
                    .set("width", w)
                    .set("height", BAR)
                    .set("fill", kind_colour(bar.kind))
                    .set("stroke", "white")
                    .set("stroke-width", 0.5)
                    .add(Title::new(format!(
                        "{}: {} [{:.3}-{:.3}]",
                        robot.name, bar.label, bar.start, bar.end
                    ))),
            );
            placer.take([x0, y, x0 + w, y + BAR]);
            let half = text_width(&bar.short, BAR_FONT) / 2.0 + 6.0;
            let mid = (x0 + x1) / 2.0;
            let covered = marks_here.iter().any(|&x| (x - mid).abs() < half);
            if !bar.short.is_empty() && 2.0 * half - 8.0 < w && !covered {
                lane = lane.add(
                    text(
                        (x0 + x1) / 2.0,
                        y + BAR * 0.72,
                        &bar.short,
                        BAR_FONT,
                        "white",
                    )
                    .set("text-anchor", "middle"),
                );
            }
        }
        doc.add(lane)
    }

    /// The makespan (a scene's horizon), a dashed line from the header to the axis, and its
    /// label.
    fn makespan(&self, doc: Document, placer: &mut Placer) -> Document {
        let m = self.m;
        let xm = self.axis.x(m.end);
        // A scene's trajectories end where they end: its horizon, not a makespan.
        let scene = m.tasks.is_empty() && m.robots.iter().all(|r| r.home.is_none());
        let what = if scene { "horizon" } else { "makespan" };
        let label = format!("{what} {:.3}", m.end);
        placer.take([xm - 8.0 - text_width(&label, 11.0), 52.0, xm + 2.0, 68.0]);
        doc.add(
            line(xm, 52.0, xm, self.lanes_bottom)
                .set("id", "makespan")
                .set("stroke", "#212121")
                .set("stroke-width", 1.5)
                .set("stroke-dasharray", "5 3"),
        )
        .add(text(xm - 4.0, 64.0, &label, 11.0, "#212121").set("text-anchor", "end"))
    }

    /// The collision of the schedule drawn (a check's contact, or the last schedule of a solve
    /// that found none free) as a diamond on the lanes of both its robots.
    fn contact(&self, doc: Document, placer: &mut Placer) -> Document {
        let m = self.m;
        let Some(mark) = &m.contact else {
            return doc;
        };
        let lanes = || m.robots.iter().filter(|r| r.leads());
        let x = self.axis.x(mark.time);
        let mut diamonds = Group::new()
            .set("id", "contact-marks")
            .set("fill", "#d50000")
            .set("stroke", "white");
        for lane in mark
            .bodies
            .iter()
            .filter_map(|b| lanes().position(|r| &r.name == b))
        {
            let y = HEADER + LANE * lane as f64 + LANE / 2.0;
            diamonds = diamonds.add(diamond(x, y).add(Title::new(format!(
                "{} and {} collide at t = {:.3}",
                mark.bodies[0], mark.bodies[1], mark.time
            ))));
            placer.take([x - 5.0, y - 7.0, x + 5.0, y + 7.0]);
        }
        doc.add(diamonds)
    }

    /// The strip under the lanes: each feedback round's collision, in the schedule that round
    /// checked and rejected, as a diamond at its time numbered with its round (a number sits
    /// above its diamond or as near beside it as is free).
    fn rejected_rounds(&self, mut doc: Document, placer: &mut Placer) -> Document {
        let m = self.m;
        if rejected(m).next().is_none() {
            return doc;
        }
        let (top, bottom) = (self.lanes_end, self.lanes_bottom);
        let y = bottom - 9.0;
        doc = doc
            .add(
                Rectangle::new()
                    .set("id", "rejected-strip")
                    .set("x", LEFT)
                    .set("y", top + 2.0)
                    .set("width", self.axis.x(self.t1) - LEFT)
                    .set("height", bottom - top - 2.0)
                    .set("fill", "#d50000")
                    .set("fill-opacity", 0.07),
            )
            .add(
                text(LEFT - 8.0, top + 13.0, "rejected", 10.0, "#b71c1c")
                    .set("text-anchor", "end")
                    .set("font-style", "italic"),
            )
            .add(
                text(LEFT - 8.0, top + 25.0, "rounds", 10.0, "#b71c1c")
                    .set("text-anchor", "end")
                    .set("font-style", "italic"),
            );
        let mut diamonds = Group::new()
            .set("id", "round-marks")
            .set("fill", "#d50000")
            .set("stroke", "white");
        let mut numbers = Vec::new();
        for mark in rejected(m) {
            let x = self.axis.x(mark.time);
            let round = mark.round.map_or("?".to_owned(), |r| r.to_string());
            diamonds = diamonds.add(diamond(x, y).add(Title::new(format!(
                "round {round}: {} and {} collided at t = {:.3} in the schedule that round \
                 checked (not the one drawn)",
                mark.bodies[0], mark.bodies[1], mark.time
            ))));
            placer.take([x - 5.0, y - 7.0, x + 5.0, y + 7.0]);
            numbers.push((x, round));
        }
        doc = doc.add(diamonds);
        for (x, label) in numbers {
            let w = text_width(&label, 10.0);
            let base = y - 9.0;
            let spot = [0.0, 1.0, -1.0, 2.0, -2.0, 3.0, -3.0]
                .into_iter()
                .map(|k| x - w / 2.0 + k * (w + 3.0))
                .find(|&x0| placer.free(&[x0 - 1.0, base - 9.0, x0 + w + 1.0, base + 1.0]));
            if let Some(x0) = spot {
                placer.take([x0 - 1.0, base - 9.0, x0 + w + 1.0, base + 1.0]);
                doc = doc.add(
                    text(x0, base, &label, 10.0, "#d50000")
                        .set("font-weight", "bold")
                        .set("paint-order", "stroke")
                        .set("stroke", "white")
                        .set("stroke-width", 3),
                );
            }
        }
        doc
    }

    /// The legend: the kinds present, the collision marks and the makespan.
    fn legend(&self, mut doc: Document, kinds: &[&(&str, &str, &str)]) -> Document {
        let (m, width) = (self.m, self.width);
        let mut x = LEFT;
        let mut y = self.lanes_bottom + AXIS + LEGEND_ROW - 4.0;
        let slot = (width - LEFT - RIGHT) / KINDS_PER_ROW as f64;
        for (n, k) in kinds.iter().enumerate() {
            if n > 0 && n.is_multiple_of(KINDS_PER_ROW) {
                x = LEFT;
                y += LEGEND_ROW;
            }
            doc = doc
                .add(
                    Rectangle::new()
                        .set("x", x)
                        .set("y", y - 10.0)
                        .set("width", 16)
                        .set("height", 10)
                        .set("fill", k.1),
                )
                .add(text(x + 20.0, y, k.2, 11.0, "#212121"));
            x += slot;
        }
        (x, y) = (LEFT, y + LEGEND_ROW);
        let marks = [
            (m.contact.is_some(), "the collision"),
            (
                rejected(m).next().is_some(),
                "n: the collision that rejected round n's schedule",
            ),
        ];
        for (_, what) in marks.into_iter().filter(|(shown, _)| *shown) {
            doc = doc
                .add(diamond(x + 6.0, y - 5.0).set("fill", "#d50000"))
                .add(text(x + 20.0, y, what, 11.0, "#212121"));
            x += slot.max(20.0 + text_width(what, 11.0) + 12.0);
        }
        doc
    }
}

/// The rounds whose schedules were rejected: every round's collision but the one of the
/// schedule drawn (the last round of a solve that found no free schedule), which is on the
/// lanes.
fn rejected(m: &Model) -> impl Iterator<Item = &Mark> {
    let drawn = |mark: &Mark| {
        m.contact
            .as_ref()
            .is_some_and(|c| c.time == mark.time && c.bodies == mark.bodies)
    };
    m.rounds.iter().filter(move |mark| !drawn(mark))
}

/// A collision's mark: a diamond 10 pixels wide and 14 high centred on `(x, y)`.
fn diamond(x: f64, y: f64) -> Polygon {
    Polygon::new().set(
        "points",
        format!(
            "{:.2},{:.2} {:.2},{:.2} {:.2},{:.2} {:.2},{:.2}",
            x,
            y - 7.0,
            x + 5.0,
            y,
            x,
            y + 7.0,
            x - 5.0,
            y
        ),
    )
}
