//! The animated page (`--html`) in a real browser: headless Chromium (Debian's `chromium` and
//! `chromium-driver`) opens the pages of `solve` and `check`, sets the time with the slider,
//! and the robots drawn must be where the checker's interpolation of the trajectories
//! (`Motion::pose_at`) puts them, within a pixel; play and pause must run and stop the
//! clock, the Gantt cursor follow it, a click on a robot say what it is doing, and the console
//! stay free of errors.
//!
//! Skipped, with a message, when the browser is missing, unless `WORKCELL_BROWSER_TEST` is set
//! (`.ci/run` sets it, after installing the packages): then a missing browser fails.
//! `WORKCELL_SCREENSHOT=docs/feedback-cell-view.png` also saves the README's screenshot.

mod webdriver;

use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;
use webdriver::{binaries, Browser};
use workcell::cell::load_scene;
use workcell::collision::Scene;
use workcell::geometry::Vec2;

/// How far a drawn vertex may be from where the trajectory puts it, in pixels.
const PIXEL: f64 = 1.0;
/// The browser window of most checks (the page fits any landscape window).
const WINDOW: (u32, u32) = (1820, 760);

fn workcell(args: &[&str]) -> std::process::Output {
    let out = Command::new(env!("CARGO_BIN_EXE_workcell"))
        .args(args)
        .output()
        .expect("the binary runs");
    assert!(
        out.status.code().is_some_and(|c| c <= 1),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn temp_dir() -> PathBuf {
    std::env::temp_dir().join(format!("workcell-browser-{}", std::process::id()))
}

fn temp(name: &str) -> PathBuf {
    std::fs::create_dir_all(temp_dir()).unwrap();
    temp_dir().join(name)
}

fn shipped(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("cells")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

fn browser() -> Option<Browser> {
    match binaries() {
        Some((chromium, driver)) => Some(Browser::start(&chromium, &driver, WINDOW.0, WINDOW.1)),
        None if std::env::var_os("WORKCELL_BROWSER_TEST").is_some() => panic!(
            "WORKCELL_BROWSER_TEST is set but chromium or chromedriver is missing \
             (apt-get install chromium chromium-driver)"
        ),
        None => {
            eprintln!(
                "SKIPPED: the browser test needs chromium and chromedriver \
                 (apt-get install chromium chromium-driver); .ci/run installs them"
            );
            None
        }
    }
}

/// Common screens, landscape: the page must fit each without scrolling.
const SCREENS: [(u32, u32); 2] = [(1366, 768), (1920, 1080)];

/// At each of the [`SCREENS`], the open page fits the window: nothing to scroll, the cell, the
/// controls, the whole Gantt chart and the rounds' buttons inside the window, the Gantt chart
/// at least 60 % of its natural size (its text stays readable) and the cell drawn large
/// (at least half the window's height or 40 % of its width). The window is restored after.
fn fits_the_window(b: &Browser, what: &str) {
    for (w, h) in SCREENS {
        let [iw, ih] = b.viewport(w, h);
        assert!(
            (iw - f64::from(w)).abs() <= 1.0 && (ih - f64::from(h)).abs() <= 1.0,
            "{what}: a {w}x{h} window has a {iw}x{ih} viewport"
        );
        let boxes = b.run(
            "const box = e => { const r = e.getBoundingClientRect(); \
               return [r.left, r.top, r.right, r.bottom]; }; \
             const g = document.querySelector('#gantt svg'); \
             return { \
               page: [document.documentElement.scrollWidth, document.documentElement.scrollHeight], \
               stage: box(document.getElementById('stage-svg')), \
               gantt: box(g), ganttNatural: g.viewBox.baseVal.width, \
               controls: box(document.getElementById('controls')), \
               buttons: Array.from(document.querySelectorAll('#marks button')).map(box) };",
            json!([]),
        );
        let rect = |v: &Value| -> [f64; 4] { serde_json::from_value(v.clone()).unwrap() };
        let inside =
            |r: [f64; 4]| r[0] >= -0.5 && r[1] >= -0.5 && r[2] <= iw + 0.5 && r[3] <= ih + 0.5;
        let page: [f64; 2] = serde_json::from_value(boxes["page"].clone()).unwrap();
        assert!(
            page[0] <= iw && page[1] <= ih,
            "{what} at {w}x{h}: the page is {page:?}, it scrolls"
        );
        for part in ["stage", "gantt", "controls"] {
            let r = rect(&boxes[part]);
            assert!(
                inside(r),
                "{what} at {w}x{h}: the {part} at {r:?} is outside the window"
            );
        }
        for button in boxes["buttons"].as_array().unwrap() {
            let r = rect(button);
            assert!(
                inside(r),
                "{what} at {w}x{h}: a round's button at {r:?} is outside the window"
            );
        }
        let gantt = rect(&boxes["gantt"]);
        let natural = boxes["ganttNatural"].as_f64().unwrap();
        assert!(
            gantt[2] - gantt[0] >= 0.6 * natural.min(iw / 2.0),
            "{what} at {w}x{h}: the Gantt chart is squeezed to {gantt:?}"
        );
        let stage = rect(&boxes["stage"]);
        assert!(
            stage[3] - stage[1] >= 0.5 * ih || stage[2] - stage[0] >= 0.4 * iw,
            "{what} at {w}x{h}: the cell is drawn small, {stage:?}"
        );
    }
    b.viewport(WINDOW.0, WINDOW.1);
}

/// Sets the time with the slider as a user drags it; the time the page then shows.
fn set_time(b: &Browser, t: f64) -> f64 {
    let shown = b.run(
        "const s = document.getElementById('slider'); s.value = arguments[0]; \
         s.dispatchEvent(new Event('input')); return window.workcellView.time();",
        json!([t]),
    );
    shown.as_f64().expect("a time")
}

fn time(b: &Browser) -> f64 {
    b.run("return window.workcellView.time();", json!([]))
        .as_f64()
        .expect("a time")
}

/// The page's polygons matching `css`, as their points in the stage's pixels.
fn polygons(b: &Browser, css: &str) -> Vec<Vec<[f64; 2]>> {
    let v = b.run(
        "return Array.from(document.querySelectorAll(arguments[0])).map(p => \
         Array.from(p.points).map(q => [q.x, q.y]));",
        json!([css]),
    );
    serde_json::from_value(v).expect("points")
}

/// World to stage pixels, as the page says; checked against the obstacles drawn.
struct Frame {
    ox: f64,
    oy: f64,
    scale: f64,
}

impl Frame {
    fn read(b: &Browser) -> Frame {
        let f = b.run(
            "return JSON.parse(document.getElementById('model').textContent).frame;",
            json!([]),
        );
        Frame {
            ox: f["ox"].as_f64().unwrap(),
            oy: f["oy"].as_f64().unwrap(),
            scale: f["scale"].as_f64().unwrap(),
        }
    }

    fn px(&self, x: f64, y: f64) -> [f64; 2] {
        [self.ox + x * self.scale, self.oy - y * self.scale]
    }
}

/// Vertices of every body matching `robots` (robots or obstacles) at `t`, in pixels: a
/// polygon per convex body, its outline for a body given by one, each part for a body given
/// by parts.
fn expected(scene: &Scene, frame: &Frame, t: f64, robots: bool) -> Vec<Vec<[f64; 2]>> {
    let mut drawn = Vec::new();
    for body in scene.bodies.iter().filter(|body| body.is_robot() == robots) {
        let p = body.motion.pose_at(t);
        let place = |local: &[Vec2]| -> Vec<[f64; 2]> {
            let (s, c) = p.theta.sin_cos();
            local
                .iter()
                .map(|v| frame.px(p.pos.x + c * v.x - s * v.y, p.pos.y + s * v.x + c * v.y))
                .collect()
        };
        match &body.parts {
            None => drawn.push(place(body.shape.vertices())),
            Some(parts) => match parts.outline() {
                Some(outline) => drawn.push(place(outline)),
                None => drawn.extend(parts.parts().iter().map(|q| place(q.vertices()))),
            },
        }
    }
    drawn
}

/// Each vertex drawn within a pixel of the screen (`scale` pixels per stage unit) of where
/// the trajectory puts it.
fn assert_near(drawn: &[Vec<[f64; 2]>], want: &[Vec<[f64; 2]>], scale: f64, what: &str) {
    assert_eq!(drawn.len(), want.len(), "{what}: number of bodies");
    for (k, (d, w)) in drawn.iter().zip(want).enumerate() {
        assert_eq!(d.len(), w.len(), "{what}: body {k}'s vertices");
        for (p, q) in d.iter().zip(w) {
            let off = scale * (p[0] - q[0]).hypot(p[1] - q[1]);
            assert!(
                off <= PIXEL,
                "{what}: body {k} drawn at {p:?}, trajectory at {q:?}"
            );
        }
    }
}

/// The robots drawn at a few times, set with the slider, against the trajectories.
fn robots_follow_the_trajectories(b: &Browser, scene: &Scene, times: &[f64], what: &str) {
    // The stage is scaled to the window, alike in x and y, unrotated: `scale` pixels a unit.
    let ctm = b.run(
        "const m = document.getElementById('stage-svg').getScreenCTM(); return [m.a, m.b, m.c, m.d];",
        json!([]),
    );
    let ctm: Vec<f64> = serde_json::from_value(ctm).unwrap();
    let scale = ctm[0];
    assert!(
        scale > 0.0 && ctm[3] == scale && ctm[1] == 0.0 && ctm[2] == 0.0,
        "{what}: stage transformed by {ctm:?}"
    );
    let frame = Frame::read(b);
    // The frame is the still drawing's: the obstacles it drew are where the scene has them.
    let obstacles = polygons(b, "#stage-svg > polygon[fill='#bdbdbd']");
    assert_near(
        &obstacles,
        &expected(scene, &frame, 0.0, false),
        scale,
        what,
    );
    let (t0, t1) = scene.horizon();
    let mut cursor = Vec::new();
    for &t in times {
        let shown = set_time(b, t);
        assert!((shown - t.clamp(t0.min(0.0), t1)).abs() <= 1e-9 * t1.abs().max(1.0));
        // The bodies' polygons (the seams of an outline have no fill).
        let drawn = polygons(b, "#robots polygon[fill-opacity]");
        assert_near(
            &drawn,
            &expected(scene, &frame, shown, true),
            scale,
            &format!("{what} at t = {shown}"),
        );
        let x = b.run(
            "return +document.getElementById('cursor').getAttribute('x1');",
            json!([]),
        );
        cursor.push((shown, x.as_f64().unwrap()));
    }
    cursor.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert!(
        cursor
            .windows(2)
            .all(|w| w[0].0 == w[1].0 || w[0].1 < w[1].1),
        "{what}: the Gantt cursor does not follow the time: {cursor:?}"
    );
}

/// Play runs the clock, pause stops it.
fn play_and_pause(b: &Browser) {
    let start = set_time(b, 0.0);
    b.click("#play");
    std::thread::sleep(Duration::from_millis(600));
    let running = time(b);
    assert!(running > start, "play: the time stays at {start}");
    assert_eq!(
        b.run(
            "return document.getElementById('play').textContent;",
            json!([])
        ),
        "Pause"
    );
    b.click("#play");
    let stopped = time(b);
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(time(b), stopped, "pause: the time runs on");
    assert_eq!(
        b.run("return window.workcellView.playing();", json!([])),
        false
    );
}

fn no_console_errors(b: &Browser, what: &str) {
    let errors: Vec<Value> = b
        .console()
        .into_iter()
        .filter(|e| e["level"] == "SEVERE")
        .collect();
    assert!(errors.is_empty(), "{what}: the console logged {errors:?}");
}

/// One browser for every page (starting one costs more than the pages).
#[test]
fn animated_pages_in_headless_chromium() {
    let Some(b) = browser() else { return };
    solve_page(&b);
    check_page(&b);
    parts_page(&b);
    arms_page(&b);
    scara_page(&b);
    many_robots_page(&b);
    hostile_names_page(&b);
    let _ = std::fs::remove_dir_all(temp_dir());
}

/// `solve`'s page: robots where the trajectories put them, the cursor, play and pause, and
/// a click on a robot that says what it does.
fn solve_page(b: &Browser) {
    let (page, scene_file) = (temp("feedback.html"), temp("feedback-scene.json"));
    let out = workcell(&[
        "solve",
        &shipped("feedback-cell.json"),
        "--json",
        "--html",
        page.to_str().unwrap(),
        "--export-scene",
        scene_file.to_str().unwrap(),
    ]);
    let result: Value = serde_json::from_slice(&out.stdout).unwrap();
    let scene = load_scene(&scene_file).unwrap().scene;
    let makespan = result["makespan"].as_f64().unwrap();
    b.open(&format!("file://{}", page.display()));
    let times = [
        -1.0,
        0.37 * makespan,
        0.5 * makespan + 0.123,
        0.91 * makespan,
        makespan,
        makespan + 5.0,
    ];
    fits_the_window(b, "solve page");
    robots_follow_the_trajectories(b, &scene, &times, "solve page");
    // At the end, the cursor sits on the makespan's line.
    set_time(b, makespan);
    let xs = b.run(
        "return [+document.getElementById('cursor').getAttribute('x1'), \
         +document.getElementById('makespan').getAttribute('x1')];",
        json!([]),
    );
    assert!(
        (xs[0].as_f64().unwrap() - xs[1].as_f64().unwrap()).abs() < 0.5,
        "{xs}"
    );
    play_and_pause(b);
    // A click on the first robot says what it does then, as the result's schedule has it.
    let t = set_time(b, 0.45 * makespan);
    let robot = result["sequences"]
        .as_object()
        .unwrap()
        .keys()
        .next()
        .unwrap()
        .clone();
    let segment = result["schedule"][&robot]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["start"].as_f64().unwrap() <= t && t < s["end"].as_f64().unwrap())
        .expect("a segment at that time")
        .clone();
    b.run(
        "document.getElementById('robot-0').dispatchEvent(new MouseEvent('click'));",
        json!([]),
    );
    let info = b.run(
        "return document.getElementById('info').textContent;",
        json!([]),
    );
    let info = info.as_str().unwrap();
    let start = format!("{:.3}", segment["start"].as_f64().unwrap());
    assert!(
        info.starts_with(&robot) && info.contains(&start),
        "{info} for {segment}"
    );
    no_console_errors(b, "solve page");
    if let Some(png) = std::env::var_os("WORKCELL_SCREENSHOT") {
        // The README's picture: on a laptop's screen, the first round's collision shown, the
        // first robot clicked.
        b.viewport(SCREENS[0].0, SCREENS[0].1);
        b.click("#marks button");
        b.run(
            "document.getElementById('robot-0').dispatchEvent(new MouseEvent('click'));",
            json!([]),
        );
        std::fs::write(&png, b.screenshot()).expect("the screenshot is written");
        b.viewport(WINDOW.0, WINDOW.1);
    }
}

/// `check`'s page: the first contact highlighted at its time, the safe prefix on the track.
fn check_page(b: &Browser) {
    let scene_file = shipped("paper-fig12b.json");
    let page = temp("fig12b.html");
    let out = workcell(&[
        "check",
        &scene_file,
        "--json",
        "--html",
        page.to_str().unwrap(),
    ]);
    let report: Value = serde_json::from_slice(&out.stdout).unwrap();
    let contact = report["first_contact"]["time"]
        .as_f64()
        .expect("fig12b collides");
    let scene = load_scene(Path::new(&scene_file)).unwrap().scene;
    b.open(&format!("file://{}", page.display()));
    let (t0, t1) = scene.horizon();
    fits_the_window(b, "check page");
    robots_follow_the_trajectories(
        b,
        &scene,
        &[t0, 0.3 * t1, contact, 0.8 * t1, t1],
        "check page",
    );
    let shown = |t: f64| {
        set_time(b, t);
        b.run(
            "return document.getElementById('contact').getAttribute('visibility');",
            json!([]),
        )
    };
    assert_eq!(shown(contact), "visible");
    let strokes = b.run(
        "return Array.from(document.querySelectorAll('#robots polygon')).map(p => p.getAttribute('stroke'));",
        json!([]),
    );
    let names: Vec<&str> = scene
        .bodies
        .iter()
        .filter(|x| x.is_robot())
        .map(|x| x.name.as_str())
        .collect();
    for (name, stroke) in names.iter().zip(strokes.as_array().unwrap()) {
        let hit = report["first_contact"]["bodies"]
            .as_array()
            .unwrap()
            .iter()
            .any(|n| n == name);
        assert_eq!(stroke == "#d50000", hit, "{name}: {stroke}");
    }
    assert_eq!(shown(t0), "hidden");
    let ticks = b.run(
        "return document.querySelectorAll('#track .tick').length;",
        json!([]),
    );
    assert_eq!(ticks, 1);
    play_and_pause(b);
    no_console_errors(b, "check page");
}

/// Writes `text` to `scene_file`, checks it with `--html` beside it and opens the page; the
/// scene as the checker read it.
fn open_checked(b: &Browser, scene_file: &Path, text: &Value) -> Scene {
    std::fs::write(scene_file, text.to_string()).unwrap();
    let page = scene_file.with_extension("html");
    let out = workcell(&[
        "check",
        scene_file.to_str().unwrap(),
        "--html",
        page.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    b.open(&format!("file://{}", page.display()));
    load_scene(scene_file).unwrap().scene
}

/// Bodies of parts: drawn part by part, an outline as itself, its seams on hover only.
fn parts_page(b: &Browser) {
    let scene_file = temp("parts.json");
    let text = json!({
        "delta": 0.01,
        "robots": [
            {"name": "gripper", "parts": [[[-0.3, -0.3], [0.1, -0.3], [0.1, 0.3], [-0.3, 0.3]],
                                        [[0.1, 0.15], [0.6, 0.15], [0.6, 0.25], [0.1, 0.25]],
                                        [[0.1, -0.25], [0.6, -0.25], [0.6, -0.15], [0.1, -0.15]]],
             "trajectory": [{"t": 0, "x": -1, "y": 0}, {"t": 2, "x": 1, "y": 0.2, "theta": 0.7}]},
            {"name": "L", "outline": [[0, 0], [0.8, 0], [0.8, 0.2], [0.2, 0.2], [0.2, 0.6], [0, 0.6]],
             "trajectory": [{"t": 0, "x": 1, "y": -1.5}, {"t": 2, "x": -1, "y": -1.2, "theta": -2}]}
        ],
        "obstacles": [{"name": "U", "outline": [[2, -1], [3, -1], [3, 1], [2, 1], [2, 0.8],
                                                [2.8, 0.8], [2.8, -0.8], [2, -0.8]]}]
    });
    let scene = open_checked(b, &scene_file, &text);
    robots_follow_the_trajectories(b, &scene, &[0.0, 0.7, 1.3, 2.0], "parts page");
    let seams =
        "return Array.from(document.querySelectorAll('#robot-1 polygon:not([fill-opacity])'))\
                 .map(p => p.getAttribute('visibility'));";
    let hidden = b.run(seams, json!([]));
    assert_eq!(
        hidden,
        json!(["hidden", "hidden"]),
        "the L's two parts, hidden"
    );
    b.run(
        "document.getElementById('robot-1').dispatchEvent(new MouseEvent('mouseenter'));",
        json!([]),
    );
    assert_eq!(b.run(seams, json!([])), json!(["visible", "visible"]));
    no_console_errors(b, "parts page");
}

/// Arms: each link where forward kinematics of the interpolated joints puts it, between the
/// samples too (not the link's pose interpolated); the base a square, each joint past it a
/// dot at its link's origin; one row and one Gantt lane for the arm.
fn arms_page(b: &Browser) {
    let scene_file = temp("arms.json");
    let bar = |l: f64, w: f64| json!([[-w, -w], [l + w, -w], [l + w, w], [-w, w]]);
    let text = json!({
        "delta": 0.01,
        "robots": [
            {"name": "A1", "base": [0, 0, 0.3],
             "links": [{"length": 1.0, "shape": bar(1.0, 0.08)}, {"length": 0.7, "shape": bar(0.7, 0.06)}],
             "trajectory": [{"t": 0, "q": [0, 0.4]}, {"t": 1, "q": [2.5, -2.0]}, {"t": 2, "q": [-1, 3.5]}]},
            {"name": "R1", "shape": [[-0.2, -0.2], [0.2, -0.2], [0.2, 0.2], [-0.2, 0.2]],
             "trajectory": [{"t": 0, "x": 2.5, "y": 1}, {"t": 2, "x": 2.5, "y": -1}]}
        ],
        "obstacles": [{"name": "post", "shape": [[-2.5, -0.2], [-2.2, -0.2], [-2.2, 0.2], [-2.5, 0.2]]}]
    });
    let scene = open_checked(b, &scene_file, &text);
    // Mid-segment the joints' interpolation and the links' poses' differ by far more than
    // a pixel: the times between samples tell them apart.
    let times = [0.0, 0.3, 0.5, 0.77, 1.0, 1.4, 2.0];
    robots_follow_the_trajectories(b, &scene, &times, "arms page");
    let frame = Frame::read(b);
    let base = b.run(
        "const r = document.querySelector('#robots rect.base'); \
         return [+r.getAttribute('x') + 5, +r.getAttribute('y') + 5];",
        json!([]),
    );
    let base: [f64; 2] = serde_json::from_value(base).unwrap();
    let want = frame.px(0.0, 0.0);
    assert!(
        (base[0] - want[0]).hypot(base[1] - want[1]) <= PIXEL,
        "base at {base:?}"
    );
    for t in [0.25, 1.6] {
        let shown = set_time(b, t);
        let dots = b.run(
            "return Array.from(document.querySelectorAll('#robots circle.joint'))\
                    .map(c => [+c.getAttribute('cx'), +c.getAttribute('cy')]);",
            json!([]),
        );
        let dots: Vec<[f64; 2]> = serde_json::from_value(dots).unwrap();
        let elbow = scene.bodies[1].motion.pose_at(shown).pos;
        let want = frame.px(elbow.x, elbow.y);
        assert_eq!(dots.len(), 1, "one joint past the base");
        let off = (dots[0][0] - want[0]).hypot(dots[0][1] - want[1]);
        assert!(
            off <= PIXEL,
            "elbow drawn at {:?}, at {want:?} by the kinematics",
            dots[0]
        );
    }
    let rows = b.run(
        "return document.querySelectorAll('#status tr').length;",
        json!([]),
    );
    assert_eq!(rows, json!(2), "one row for the arm, one for R1");
    no_console_errors(b, "arms page");
}

/// The page of a generated cell of thirty robots: their Gantt chart, taller than the window
/// at its natural size, still fits.
fn many_robots_page(b: &Browser) {
    let dir = temp_dir().join("thirty");
    let out = dir.to_str().unwrap();
    #[rustfmt::skip]
    workcell(&["generate", "--kind", "cell", "--robots", "30", "--tasks", "60", "--seed", "3", "--out", out]);
    let cell = dir.join("cell-30r-60t-3f-3-0-cell.json");
    let page = temp("thirty.html");
    workcell(&[
        "solve",
        cell.to_str().unwrap(),
        "--html",
        page.to_str().unwrap(),
    ]);
    b.open(&format!("file://{}", page.display()));
    fits_the_window(b, "thirty robots' page");
    no_console_errors(b, "thirty robots' page");
}

/// `solve`'s page of an arm cell (issue 22, item 5): each link where the exported scene's
/// joints put it, between samples too, one status row per arm.
fn scara_page(b: &Browser) {
    let (page, scene_file) = (temp("scara.html"), temp("scara-scene.json"));
    let out = workcell(&[
        "solve",
        &shipped("scara-cell.json"),
        "--json",
        "--html",
        page.to_str().unwrap(),
        "--export-scene",
        scene_file.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let result: Value = serde_json::from_slice(&out.stdout).unwrap();
    let scene = load_scene(&scene_file).unwrap().scene;
    let makespan = result["makespan"].as_f64().unwrap();
    b.open(&format!("file://{}", page.display()));
    let times = [
        0.0,
        0.13 * makespan,
        0.377 * makespan,
        0.6 * makespan + 0.01,
        makespan,
    ];
    fits_the_window(b, "scara page");
    robots_follow_the_trajectories(b, &scene, &times, "scara page");
    let rows = b.run(
        "return document.querySelectorAll('#status tr').length;",
        json!([]),
    );
    assert_eq!(rows, json!(2), "one row per arm");
    play_and_pause(b);
    no_console_errors(b, "scara page");
}

/// Names made to break out of the page's data or markup: the page still draws every robot
/// under its name as written, and no script from the data runs.
fn hostile_names_page(b: &Browser) {
    let names = [
        "<!--<script>",
        "</script><script>window.pwned = 1</script>",
        "\"><img src=x onerror=\"window.pwned = 2\">",
        "]]> & &amp; <b>",
    ];
    let square = json!([[-0.2, -0.2], [0.2, -0.2], [0.2, 0.2], [-0.2, 0.2]]);
    let robots: Vec<Value> = (names.iter().enumerate())
        .map(|(k, name)| {
            let y = k as f64;
            json!({"name": name, "shape": square,
                   "trajectory": [{"t": 0, "x": 0, "y": y}, {"t": 1, "x": 1, "y": y}]})
        })
        .collect();
    let text = json!({"delta": 0.01, "robots": robots});
    let scene = open_checked(b, &temp("hostile.json"), &text);
    robots_follow_the_trajectories(b, &scene, &[0.0, 0.5, 1.0], "hostile names page");
    let pwned = b.run(
        "return window.pwned === undefined ? null : window.pwned;",
        json!([]),
    );
    assert_eq!(pwned, Value::Null, "a script from the data ran");
    let shown = b.run(
        "return Array.from(document.querySelectorAll('#status tr td:first-child'))\
                .map(td => td.textContent);",
        json!([]),
    );
    assert_eq!(shown, json!(names), "the names as written");
    no_console_errors(b, "hostile names page");
}
