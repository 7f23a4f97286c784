//! The pictures as files: the still picture's labels never overprint or cross a line, the
//! Gantt chart shows what the result says (lanes, makespan, each round's collision on both
//! robots' lanes, the remedies' colours), and the animated page fetches nothing.

use crate::common::{shipped, temp_dir_made};
use serde_json::Value;
use std::process::Command;
use workcell::view::{text_width, KINDS};

fn workcell(args: &[&str]) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_workcell"))
        .args(args)
        .output()
        .expect("the binary runs");
    assert!(
        out.status.code().is_some_and(|c| c <= 1),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap_or(Value::Null)
}

/// An attribute's value in one element's text.
fn attr<'a>(element: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let at = element.find(&key)? + key.len();
    element[at..].split('"').next()
}

/// Every `<text>` element: its attributes' text and its content.
fn texts(svg: &str) -> Vec<(&str, &str)> {
    svg.split("<text")
        .skip(1)
        .map(|piece| {
            let open = piece.find('>').unwrap();
            let close = piece.find("</text>").unwrap();
            (&piece[..open], piece[open + 1..close].trim())
        })
        .collect()
}

/// The labels of homes, tasks and obstacles in a still picture, as the placer estimated their
/// boxes, with their texts.
fn label_boxes(svg: &str) -> Vec<([f64; 4], &str)> {
    texts(svg)
        .into_iter()
        .filter(|(a, _)| attr(a, "class") == Some("label"))
        .map(|(a, content)| {
            let num = |name: &str| -> f64 { attr(a, name).unwrap().parse().unwrap() };
            let (x, y, size) = (num("x"), num("y"), num("font-size"));
            let width = text_width(content, size);
            ([x, y - 0.8 * size, x + width, y + 0.2 * size], content)
        })
        .collect()
}

/// Every side of every polygon (bodies, obstacles, arrowheads) and every piece of every
/// polyline (paths) in an SVG text, as `[x0, y0, x1, y1]`.
fn drawn_lines(svg: &str) -> Vec<[f64; 4]> {
    let mut lines = Vec::new();
    for (tag, closed) in [("<polygon", true), ("<polyline", false)] {
        for piece in svg.split(tag).skip(1) {
            let element = &piece[..piece.find('>').unwrap()];
            let points: Vec<[f64; 2]> = attr(element, "points")
                .unwrap()
                .split_whitespace()
                .map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    [x.parse().unwrap(), y.parse().unwrap()]
                })
                .collect();
            let n = points.len();
            let sides = if closed { n } else { n.saturating_sub(1) };
            for i in 0..sides {
                let (a, b) = (points[i], points[(i + 1) % n]);
                lines.push([a[0], a[1], b[0], b[1]]);
            }
        }
    }
    lines
}

/// Whether the segment meets the box (sampled finely: an independent check of the placer's
/// clipping).
fn meets(r: &[f64; 4], s: &[f64; 4]) -> bool {
    let steps = 400;
    (0..=steps).any(|k| {
        let f = k as f64 / steps as f64;
        let (x, y) = (s[0] + f * (s[2] - s[0]), s[1] + f * (s[3] - s[1]));
        r[0] <= x && x <= r[2] && r[1] <= y && y <= r[3]
    })
}

/// No label overprints another, and none is crossed by a path, a body's outline, an
/// obstacle's side or an arrowhead: on the dense hall cell, on cells with rounds and
/// obstacles, and on an arm cell.
#[test]
fn labels_never_overprint_or_cross_a_line() {
    for (cell, least_tasks) in [
        ("hall-cell.json", 95),
        ("feedback-cell.json", 4),
        ("paper-cell.json", 4),
        ("scara-cell.json", 4),
    ] {
        let svg = temp_dir_made("view", "lines").join(format!("{cell}.svg"));
        workcell(&[
            "solve",
            &shipped(cell),
            "--json",
            "--svg",
            svg.to_str().unwrap(),
        ]);
        let svg = std::fs::read_to_string(svg).unwrap();
        let boxes = label_boxes(&svg);
        let tasks = boxes.iter().filter(|b| b.1.contains(". ")).count();
        assert!(
            tasks >= least_tasks,
            "{cell}: only {tasks} task labels drawn"
        );
        for (i, (a, name)) in boxes.iter().enumerate() {
            for (b, other) in &boxes[..i] {
                let overlap = a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
                assert!(!overlap, "{cell}: {name} overprints {other}");
            }
        }
        let lines = drawn_lines(&svg);
        assert!(lines.len() > 20, "{cell}: {} lines", lines.len());
        for (r, name) in &boxes {
            if let Some(s) = lines.iter().find(|s| meets(r, s)) {
                panic!("{cell}: the label {name} at {r:?} is crossed by the line {s:?}");
            }
        }
        // Every task label says the task's place in its robot's route.
        assert!(boxes
            .iter()
            .filter(|b| b.1.contains("task-"))
            .all(|b| b.1.split(". ").count() == 2));
    }
}

#[test]
fn the_gantt_chart_shows_the_result() {
    let (gantt, html) = (
        temp_dir_made("view", "").join("feedback-gantt.svg"),
        temp_dir_made("view", "").join("feedback.html"),
    );
    let result = workcell(&[
        "solve",
        &shipped("feedback-cell.json"),
        "--json",
        "--gantt",
        gantt.to_str().unwrap(),
        "--html",
        html.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&gantt).unwrap();
    let all_texts: Vec<&str> = texts(&svg).into_iter().map(|t| t.1).collect();
    let makespan = result["makespan"].as_f64().unwrap();
    assert!(all_texts.contains(&format!("makespan {makespan:.3}").as_str()));
    for robot in result["sequences"].as_object().unwrap().keys() {
        assert!(all_texts.contains(&robot.as_str()), "no lane for {robot}");
    }
    // A bar per activity, in its kind's colour; the pause of the final schedule among them.
    let colour = |kind: &str| KINDS.iter().find(|k| k.0 == kind).unwrap().1;
    let bars = svg.matches(&format!("fill=\"{}\"", colour("task"))).count();
    let tasks: usize = result["schedule"]
        .as_object()
        .unwrap()
        .values()
        .map(|s| {
            s.as_array()
                .unwrap()
                .iter()
                .filter(|a| a["activity"] == "task")
                .count()
        })
        .sum();
    assert_eq!(bars, tasks + 1, "a bar per task and the legend's swatch");
    assert!(svg.contains(colour("pause")) && all_texts.contains(&"pause on a move"));
    // Each round's collision: a diamond in the strip of rejected rounds under the lanes, at
    // its time, its number above; none on the lanes of the certified schedule drawn.
    let collisions: Vec<&Value> = result["feedback"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| !r["collision"].is_null())
        .collect();
    assert!(!collisions.is_empty());
    assert!(!svg.contains("contact-marks"));
    let strip = svg
        .split("id=\"rejected-strip\"")
        .nth(1)
        .expect("the strip");
    let strip_top: f64 = attr(strip, "y").unwrap().parse().unwrap();
    let diamonds = svg.split("id=\"round-marks\"").nth(1).unwrap();
    let diamonds = &diamonds[..diamonds.find("</g>").unwrap()];
    let tops: Vec<f64> = diamonds
        .split("<polygon")
        .skip(1)
        .map(|p| {
            let first = attr(p, "points").unwrap().split(' ').next().unwrap();
            first.split(',').nth(1).unwrap().parse().unwrap()
        })
        .collect();
    assert_eq!(tops.len(), collisions.len());
    assert!(
        tops.iter().all(|&y| y > strip_top),
        "{tops:?} above {strip_top}"
    );
    for r in &collisions {
        let when = r["collision"]["time"].as_f64().unwrap();
        assert!(
            diamonds.contains(&format!("collided at t = {when:.3}")),
            "{r}"
        );
    }
    let red: Vec<&str> = texts(&svg)
        .into_iter()
        .filter(|(a, _)| attr(a, "fill") == Some("#d50000"))
        .map(|t| t.1)
        .collect();
    for r in &collisions {
        let n = r["iteration"].to_string();
        let numbers = red.iter().filter(|t| **t == n).count();
        assert_eq!(numbers, 1, "round {n}: {red:?}");
    }
    assert!(all_texts.contains(&"rejected") && all_texts.contains(&"rounds"));
    // The page is whole: nothing to fetch, no script or style from elsewhere.
    let page = std::fs::read_to_string(&html).unwrap();
    let outside = page
        .replace("http://www.w3.org/2000/svg", "")
        .matches("http")
        .count();
    assert_eq!(outside, 0);
    assert!(!page.contains("src=") && page.contains("<script>") && page.contains("<style>"));
}

#[test]
fn evaluate_draws_the_collision_of_the_sequences_given() {
    let (solved, gantt, html) = (
        temp_dir_made("view", "").join("solved.json"),
        temp_dir_made("view", "").join("blind-gantt.svg"),
        temp_dir_made("view", "").join("blind.html"),
    );
    let result = workcell(&["solve", &shipped("feedback-cell.json"), "--json"]);
    // The blind sequences collide (round 1 of the solve).
    let blind = serde_json::to_string(&result["blind_sequences"]).unwrap();
    std::fs::write(&solved, blind).unwrap();
    let evaluated = workcell(&[
        "evaluate",
        &shipped("feedback-cell.json"),
        solved.to_str().unwrap(),
        "--json",
        "--gantt",
        gantt.to_str().unwrap(),
        "--html",
        html.to_str().unwrap(),
    ]);
    let contact = &evaluated["first_collision"];
    assert!(contact.is_object());
    let svg = std::fs::read_to_string(&gantt).unwrap();
    let all: Vec<&str> = texts(&svg).into_iter().map(|t| t.1).collect();
    // The collision is in the schedule drawn: on both robots' lanes, no strip of rounds.
    assert!(all.contains(&"the collision"));
    let lanes = svg.split("id=\"contact-marks\"").nth(1).expect("the marks");
    let lanes = &lanes[..lanes.find("</g>").unwrap()];
    assert_eq!(lanes.matches("<polygon").count(), 2);
    assert!(!svg.contains("rejected-strip"));
    assert!(all
        .iter()
        .any(|t| t.contains("COLLISION between R1 and R2")));
    let page = std::fs::read_to_string(&html).unwrap();
    assert!(page.contains("\"contact\":{\"round\":null"));
}

/// The still picture names every obstacle and has a scale bar of a round length; a scene's
/// time line ends at its horizon, a cell's at its makespan.
#[test]
fn obstacles_are_named_a_scale_is_drawn_and_a_scene_has_a_horizon() {
    let dir = temp_dir_made("view", "named");
    let (svg, gantt) = (dir.join("paper.svg"), dir.join("paper-gantt.svg"));
    let cell = shipped("paper-cell.json");
    workcell(&[
        "solve",
        &cell,
        "--svg",
        svg.to_str().unwrap(),
        "--gantt",
        gantt.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&svg).unwrap();
    let contents: Vec<&str> = texts(&svg).into_iter().map(|(_, c)| c).collect();
    for name in ["fixture-sw", "fixture-se", "fixture-nw", "fixture-ne"] {
        assert!(contents.contains(&name), "{name} not named: {contents:?}");
    }
    assert!(svg.contains("id=\"scale\""));
    // Its label is a round length: 1, 2 or 5 times a power of ten.
    let round = |s: &&str| {
        s.parse::<f64>().is_ok_and(|v| {
            let m = v / 10f64.powf(v.log10().floor());
            [1.0, 2.0, 5.0].iter().any(|k| (m - k).abs() < 1e-9)
        })
    };
    assert!(contents.iter().any(round), "no scale label: {contents:?}");
    let gantt = std::fs::read_to_string(&gantt).unwrap();
    assert!(texts(&gantt).iter().any(|(_, c)| *c == "makespan 36.165"));
    let scene_page = dir.join("scene.svg");
    let scene = shipped("paper-fig12b.json");
    let html = dir.join("scene.html");
    workcell(&[
        "check",
        &scene,
        "--svg",
        scene_page.to_str().unwrap(),
        "--html",
        html.to_str().unwrap(),
    ]);
    let page = std::fs::read_to_string(&html).unwrap();
    let contents: Vec<&str> = texts(&page).into_iter().map(|(_, c)| c).collect();
    assert!(
        contents.iter().any(|c| c.starts_with("horizon ")),
        "{contents:?}"
    );
    assert!(
        !contents.iter().any(|c| c.starts_with("makespan")),
        "{contents:?}"
    );
}

/// A solve that ends without a free schedule draws its last schedule: that schedule's
/// collision sits on its robots' lanes, and only the rounds before it, whose schedules were
/// rejected, go in the strip.
#[test]
fn a_failed_solve_draws_its_collision_on_the_lanes_and_earlier_rounds_in_the_strip() {
    let gantt = temp_dir_made("view", "failed").join("failed-gantt.svg");
    let result = workcell(&[
        "solve",
        &shipped("feedback-cell.json"),
        "--feedback",
        "greedy",
        "--max-iterations",
        "2",
        "--json",
        "--gantt",
        gantt.to_str().unwrap(),
    ]);
    assert_eq!(result["collision_free"], false);
    let svg = std::fs::read_to_string(&gantt).unwrap();
    let group = |id: &str| {
        let g = svg.split(&format!("id=\"{id}\"")).nth(1).expect(id);
        g[..g.find("</g>").unwrap()].to_owned()
    };
    assert_eq!(group("contact-marks").matches("<polygon").count(), 2);
    let strip = group("round-marks");
    assert_eq!(strip.matches("<polygon").count(), 1, "{strip}");
    assert!(strip.contains("round 1:"), "{strip}");
}
