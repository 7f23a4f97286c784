//! `--html`: one self-contained page (styles and script inline, nothing fetched) that shows
//! the cell and plays its schedule: play, pause, speed, a time slider, the Gantt chart with a
//! cursor, and what each robot is doing.

use super::canvas::Frame;
use super::gantt::gantt_svg;
use super::model::Model;
use super::picture::cell_svg;
use serde::Serialize;
use svg::node::element::Group;

/// Width of the Gantt chart on the page.
const GANTT_WIDTH: f64 = 860.0;
/// Offered playback speeds, time units per second.
const SPEEDS: [f64; 12] = [
    0.1, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0,
];

/// What the page's script reads: the model and how to place it.
#[derive(Serialize)]
struct PageData<'a> {
    model: &'a Model,
    /// World to stage pixels, as [`Frame`].
    frame: FrameJson,
    /// Time to Gantt pixels.
    axis: AxisJson,
    t0: f64,
    t1: f64,
}

#[derive(Serialize)]
struct FrameJson {
    ox: f64,
    oy: f64,
    scale: f64,
}

#[derive(Serialize)]
struct AxisJson {
    t0: f64,
    scale: f64,
    left: f64,
}

/// The page as one HTML document.
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::view::{html, Model};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/tunnelling.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// let model = Model::of_check(path.as_ref(), &scene, &check(&scene, &CheckOptions::default()));
/// let page = html(&model);
/// assert!(page.starts_with("<!DOCTYPE html>") && page.contains("needle") && page.contains("<svg"));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn html(m: &Model) -> String {
    let frame = Frame::of(m);
    let stage = cell_svg(m, true)
        .set("id", "stage-svg")
        .add(Group::new().set("id", "robots"))
        .add(Group::new().set("id", "overlay"));
    let (gantt, axis) = gantt_svg(m, GANTT_WIDTH, true);
    let data = PageData {
        model: m,
        frame: FrameJson {
            ox: frame.ox,
            oy: frame.oy,
            scale: frame.scale,
        },
        axis: AxisJson {
            t0: axis.t0,
            scale: axis.scale,
            left: axis.left,
        },
        t0: m.start(),
        t1: m.end.max(m.start()),
    };
    // Nothing in the data can end the script or open a comment in it (`</script>`, `<!--`):
    // `<`, `>` and `&` occur only inside JSON strings, where `\u003c` and the like read the same.
    let json = serde_json::to_string(&data)
        .expect("a model serialises")
        .replace('<', "\\u003c")
        .replace('>', "\\u003e")
        .replace('&', "\\u0026");
    let speeds: String = SPEEDS
        .iter()
        .map(|s| format!("<option value=\"{s}\">{s}×</option>"))
        .collect();
    let (t0, t1) = (data.t0, data.t1);
    format!(
        r#"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>{title} — workcell</title>
<link rel="icon" href="data:,">
<style>
{css}</style>
</head>
<body>
<header><h1>{title}</h1><p id="verdict">{verdict}</p></header>
<div id="controls">
<button id="play" type="button">Play</button>
<label>speed <select id="speed">{speeds}</select></label>
<div id="timeline"><div id="track"></div><input id="slider" type="range" min="{t0}" max="{t1}" step="any" value="{t0}"></div>
<span id="clock"></span>
</div>
<div id="panes">
<div id="stage">{stage}</div>
<div id="side">
<div id="gantt">{gantt}</div>
<div id="marks"></div>
<div id="info">Hover over or click a robot to see what it is doing.</div>
<table id="status"></table>
</div>
</div>
<script type="application/json" id="model">{json}</script>
<script>
{js}</script>
</body>
</html>
"#,
        title = escape(&m.title),
        verdict = escape(&m.verdict),
        css = include_str!("view.css"),
        js = include_str!("view.js"),
    )
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
