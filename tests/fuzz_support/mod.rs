//! What every input must satisfy, and the mutations that make inputs from the shipped files.
//! Shared by the seeded fuzz test (`tests/fuzz_inputs.rs`) and the `cargo fuzz` targets
//! (`fuzz/`), which include this file by path.
//!
//! The invariant: no panic, and either a result or a clean refusal that names the file given
//! and a field of the document (empty only for what concerns the whole document: syntax, its
//! type, a missing top-level field), with the body that field belongs to.

#![allow(dead_code)]

use rand::{Rng, RngCore};
use serde_json::Value;
use std::path::Path;
use workcell::cell::{parse_cell, parse_scene, parse_sequences, Cell, InputError, Sequences};
use workcell::collision::{try_check, CheckOptions};
use workcell::wcp::{self, SolveOptions};

/// Which reader an input is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A scene (`workcell check`).
    Scene,
    /// A cell (`workcell solve`).
    Cell,
    /// Sequences for the feedback cell (`workcell evaluate`).
    Sequences,
}

impl Kind {
    /// The folder name of its regression files.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Scene => "scene",
            Kind::Cell => "cell",
            Kind::Sequences => "sequences",
        }
    }
}

/// The shipped inputs that mutations start from, with their kind.
pub const SHIPPED: [(&str, Kind); 10] = [
    ("paper-fig12a.json", Kind::Scene),
    ("paper-fig12b.json", Kind::Scene),
    ("tunnelling.json", Kind::Scene),
    ("spin-hit.json", Kind::Scene),
    ("near-miss.json", Kind::Scene),
    ("bad-velocities.json", Kind::Scene),
    ("feedback-cell.json", Kind::Cell),
    ("paper-cell.json", Kind::Cell),
    ("four-robots-cell.json", Kind::Cell),
    ("hall-cell.json", Kind::Cell),
];

/// The feedback cell's solve result (sequences and a wait), the start of sequences inputs.
pub const FEEDBACK_RESULT: &str = r#"{"makespan": 15.93711717077279, "collision_free": true,
  "sequences": {"R1": ["weld-2", "weld-3", "weld-1"], "R2": ["weld-4"]}, "iterations": 4,
  "waits": [{"robot": "R2", "before_move": 0, "before": "move home -> weld-4",
             "duration": 1.0002561096933777}]}"#;

/// Cells larger than this are only read: solving them costs too much for a fuzz case.
const SOLVED_TASKS: usize = 20;

/// Scenes with more samples than this are only read and precision-checked.
const CHECKED_SAMPLES: usize = 20_000;

/// The feedback cell, which sequences inputs are read against.
pub fn feedback_cell(cells: &Path) -> Cell {
    let path = cells.join("feedback-cell.json");
    let text = std::fs::read_to_string(&path).expect("the shipped cell");
    parse_cell(&text, &path)
        .expect("the shipped cell is valid")
        .cell
}

/// Runs the reader for `kind` on `text` (named `file`) and, when it accepts, what follows it:
/// the checker for a scene, planning and a short solve for a small cell, evaluate for
/// sequences. Panics, with the reason, when the invariant does not hold; a panic of the code
/// under test propagates as one.
pub fn exercise(kind: Kind, text: &str, file: &Path, feedback: &Cell) {
    let doc: Option<Value> = serde_json::from_str(text).ok();
    // Errors about another file (the feedback cell, the sequences made up below) are checked
    // for their file only.
    let refused = |e: InputError, files: &[&Path]| {
        let doc = doc.as_ref().filter(|_| e.file == file);
        assert_clean(&e, files, doc, kind)
    };
    let accepted = || {
        if let Some(doc) = &doc {
            assert!(
                records_are_objects(kind, doc),
                "accepted a record that is not a JSON object"
            );
        }
    };
    match kind {
        Kind::Scene => match parse_scene(text, file) {
            Err(e) => refused(e, &[file]),
            Ok(loaded) => {
                accepted();
                let samples: usize = loaded
                    .scene
                    .bodies
                    .iter()
                    .map(|b| b.motion.times().count())
                    .sum();
                if samples > CHECKED_SAMPLES {
                    return;
                }
                match try_check(&loaded.scene, &CheckOptions::default()) {
                    Err(e) => refused(e.in_file(file), &[file]),
                    Ok(report) => {
                        assert_eq!(report.collision, report.first_contact.is_some());
                        assert!(report.safe_until <= report.horizon[1], "{report:?}");
                    }
                }
            }
        },
        Kind::Cell => match parse_cell(text, file) {
            Err(e) => refused(e, &[file]),
            Ok(loaded) => {
                accepted();
                let cell = loaded.cell;
                if cell.tasks.len() > SOLVED_TASKS || cell.robots.len() > 4 {
                    return;
                }
                let opts = SolveOptions {
                    max_iterations: 3,
                    ..SolveOptions::default()
                };
                match wcp::prepare(&cell, &opts, &()) {
                    Err(e) => refused(e, &[file]),
                    Ok(prepared) => match wcp::solve(&cell, &prepared, &opts, &()) {
                        Err(e) => refused(e, &[file]),
                        Ok(solved) => assert!(solved.schedule.makespan.is_finite()),
                    },
                }
                // Given sequences too, which need no planning first: each task by the first
                // robot allowed to do it, in file order.
                let mut routes = vec![Vec::new(); cell.robots.len()];
                for (t, task) in cell.tasks.iter().enumerate() {
                    routes[task.robots[0]].push(t);
                }
                let given = Sequences {
                    routes,
                    ..Sequences::default()
                };
                let made_up = Path::new("made-up-sequences.json");
                match wcp::evaluate(&cell, &given, &opts, made_up) {
                    Err(e) => refused(e, &[file, made_up]),
                    Ok(evaluated) => assert!(evaluated.schedule.makespan.is_finite()),
                }
            }
        },
        Kind::Sequences => match parse_sequences(text, file, feedback) {
            Err(e) => refused(e, &[file]),
            Ok(sequences) => {
                accepted();
                match wcp::evaluate(feedback, &sequences, &SolveOptions::default(), file) {
                    Err(e) => refused(e, &[file, &feedback.file]),
                    Ok(evaluated) => assert!(evaluated.schedule.makespan.is_finite()),
                }
            }
        },
    }
}

/// Whether every record that the formats document as an object is one: serde would read
/// an array of field values positionally (a sample `[t, x, y, theta]` as t, x, y, vx).
fn records_are_objects(kind: Kind, doc: &Value) -> bool {
    let all_objects = |v: &Value| {
        v.as_array()
            .is_none_or(|items| items.iter().all(Value::is_object))
    };
    let lists: &[&str] = match kind {
        Kind::Scene => &["robots", "obstacles"],
        Kind::Cell => &["robots", "obstacles", "tasks"],
        Kind::Sequences => &["waits"],
    };
    doc.is_object()
        && lists.iter().all(|l| all_objects(&doc[*l]))
        && (kind != Kind::Scene
            || doc["robots"]
                .as_array()
                .is_none_or(|robots| robots.iter().all(|r| all_objects(&r["trajectory"]))))
}

/// A refusal names one of `files`, a field (or says why the whole document is refused),
/// and, where the field points into a list of named records, that record's name.
fn assert_clean(e: &InputError, files: &[&Path], doc: Option<&Value>, kind: Kind) {
    assert!(files.contains(&e.file.as_path()), "names another file: {e}");
    assert!(!e.reason.is_empty(), "says nothing: {e:?}");
    if e.field.is_empty() {
        // serde's errors say where in the text; the rest are about the document as a whole.
        let whole = ["line", "not valid JSON", "an object mapping", "after the"];
        assert!(
            whole.iter().any(|w| e.reason.contains(w)),
            "names no field: {e}"
        );
        return;
    }
    let (Some(doc), true) = (doc, kind != Kind::Sequences) else {
        return;
    };
    let root = e.field.split(['[', '.']).next().unwrap_or("");
    assert!(
        doc.get(root).is_some() || root == "delta" || e.reason.contains("missing field"),
        "field `{}` is not in the document: {e}",
        e.field
    );
    // `robots[3]...`: the body is that robot, when the document names it.
    let (Some(body), Some(rest)) = (&e.body, e.field.strip_prefix(root)) else {
        return;
    };
    let index = rest
        .strip_prefix('[')
        .and_then(|r| r.split_once(']'))
        .and_then(|(k, _)| k.parse::<usize>().ok());
    if let Some(name) = index
        .and_then(|k| doc[root].get(k))
        .and_then(|r| r["name"].as_str())
    {
        assert_eq!(
            name, body,
            "field `{}` belongs to another body: {e}",
            e.field
        );
    }
}

/// Number literals that JSON may spell but f64 handles badly, and two that JSON may not.
const SPECIAL_NUMBERS: [&str; 18] = [
    "1e999",
    "-1e999",
    "1e308",
    "-1e308",
    "5e-324",
    "-5e-324",
    "1e-310",
    "2.2250738585072014e-308",
    "0",
    "-0",
    "-1",
    "1e15",
    "9007199254740993",
    "1e-300",
    "1e300",
    "1e-16",
    "NaN",
    "Infinity",
];

/// Marks a value to be replaced by a literal after serialisation.
const LITERAL: &str = "@@workcell-literal@@";

/// `base` (a shipped document) after 1 to 3 structure-aware mutations, as text; now and then
/// the text itself is cut or loses a character.
pub fn mutated(base: &Value, rng: &mut impl RngCore) -> String {
    let mut doc = base.clone();
    let mut literals = Vec::new();
    for _ in 0..rng.random_range(1..=3) {
        mutate_once(&mut doc, rng, &mut literals);
    }
    let mut text = doc.to_string();
    for (k, literal) in literals.iter().enumerate() {
        text = text.replace(&format!("\"{LITERAL}{k}\""), literal);
    }
    match rng.random_range(0..20) {
        0 => {
            let cut = rng.random_range(0..text.len().max(1));
            text.truncate(floor_char_boundary(&text, cut));
        }
        1 if !text.is_empty() => {
            let at = floor_char_boundary(&text, rng.random_range(0..text.len()));
            text.remove(at);
        }
        _ => {}
    }
    text
}

fn floor_char_boundary(text: &str, mut at: usize) -> usize {
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// A path into a document: keys and indices.
#[derive(Clone, Debug)]
enum Step {
    Key(String),
    Index(usize),
}

fn paths(v: &Value, here: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    out.push(here.clone());
    match v {
        Value::Object(map) => {
            for (k, child) in map {
                here.push(Step::Key(k.clone()));
                paths(child, here, out);
                here.pop();
            }
        }
        Value::Array(items) => {
            for (k, child) in items.iter().enumerate() {
                here.push(Step::Index(k));
                paths(child, here, out);
                here.pop();
            }
        }
        _ => {}
    }
}

fn at<'v>(v: &'v mut Value, path: &[Step]) -> &'v mut Value {
    path.iter().fold(v, |v, step| match step {
        Step::Key(k) => &mut v[k.as_str()],
        Step::Index(i) => &mut v[*i],
    })
}

fn mutate_once(doc: &mut Value, rng: &mut impl RngCore, literals: &mut Vec<String>) {
    let mut all = Vec::new();
    paths(doc, &mut Vec::new(), &mut all);
    let path = &all[rng.random_range(0..all.len())];
    let node = at(doc, path);
    let mut literal = |text: String| {
        literals.push(text);
        Value::String(format!("{LITERAL}{}", literals.len() - 1))
    };
    let wrong_types = [
        Value::String("x".into()),
        Value::Bool(true),
        Value::Null,
        Value::Object(Default::default()),
        Value::Array(Vec::new()),
        Value::from(0.5),
    ];
    match (node.clone(), rng.random_range(0..10)) {
        (Value::Number(n), 0..=4) => {
            let special = SPECIAL_NUMBERS[rng.random_range(0..SPECIAL_NUMBERS.len())];
            *node = literal(special.to_owned());
            let _ = n;
        }
        (Value::Number(n), 5..=7) => {
            // Scaled by a power of ten, or negated.
            let x = n.as_f64().unwrap_or(1.0);
            let scaled = if rng.random_bool(0.3) {
                -x
            } else {
                x * 10f64.powi(rng.random_range(-320..=320))
            };
            *node = literal(format!("{scaled:e}"));
        }
        (Value::Object(map), 0..=3) => {
            // An object written as an array of its values.
            *node = Value::Array(map.into_iter().map(|(_, v)| v).collect());
        }
        (Value::Object(mut map), 4..=5) if !map.is_empty() => {
            let key = map
                .keys()
                .nth(rng.random_range(0..map.len()))
                .cloned()
                .unwrap();
            map.remove(&key);
            *node = Value::Object(map);
        }
        (Value::Array(items), k) if k <= 7 => *node = Value::Array(reshaped(items, rng)),
        (Value::String(_), 0..=4) => {
            let names = ["", "R1", "R2", "weld-1", "home", "\u{1F916}"];
            *node = Value::String(names[rng.random_range(0..names.len())].into());
        }
        _ => *node = wrong_types[rng.random_range(0..wrong_types.len())].clone(),
    }
}

/// Empty, one item, repeated items (up to 2000 copies: huge counts), reversed or swapped
/// (unsorted times), or an item left out.
fn reshaped(mut items: Vec<Value>, rng: &mut impl RngCore) -> Vec<Value> {
    if items.is_empty() {
        return vec![Value::from(0.0)];
    }
    let k = rng.random_range(0..items.len());
    match rng.random_range(0..7) {
        0 => Vec::new(),
        1 => vec![items.swap_remove(k)],
        2 => {
            let copies = [2, 10, 2000][rng.random_range(0..3)];
            let item = items[k].clone();
            items.splice(k..k, std::iter::repeat_n(item, copies));
            items
        }
        3 => {
            items.reverse();
            items
        }
        4 => {
            let j = rng.random_range(0..items.len());
            items.swap(k, j);
            items
        }
        5 => {
            items.remove(k);
            items
        }
        _ => {
            let item = items[k].clone();
            items.insert(k, item);
            items
        }
    }
}

/// The markers a name could forge in a picture or a page.
#[cfg(feature = "cli")]
pub fn markers(text: &str) -> [usize; 4] {
    ["<script", "</script", "<!--", "]]>"].map(|m| text.matches(m).count())
}

/// A scene of two robots crossing past an obstacle, its three bodies named `names` (cycled),
/// as a file's text.
#[cfg(feature = "cli")]
fn named_scene(names: [&str; 3]) -> String {
    let square = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]];
    let doc = serde_json::json!({
        "delta": 0.01,
        "robots": [
            {"name": names[0], "shape": square,
             "trajectory": [{"t": 0, "x": 0, "y": 0}, {"t": 2, "x": 4, "y": 0}]},
            {"name": names[1], "shape": square,
             "trajectory": [{"t": 0, "x": 2, "y": -2}, {"t": 2, "x": 2, "y": 2}]},
        ],
        "obstacles": [{"name": names[2], "shape": [[5, 2], [6, 2], [6, 3], [5, 3]]}],
    });
    doc.to_string()
}

/// Names as a user could write them, read, checked, and drawn into the still picture and
/// the page: either refused naming the body's field (control characters, empty, too long,
/// repeated), or drawn with no name raw in the picture (`<` and `&` escaped) or the page's
/// data (`<` escaped), no markup forged (the markers of a page with plain names), and no
/// control character anywhere.
#[cfg(feature = "cli")]
pub fn exercise_names(names: [&str; 3]) {
    use workcell::{collision::check, view};
    let file = Path::new("names.json");
    let draw = |text: &str| -> Result<[String; 2], InputError> {
        let loaded = parse_scene(text, file)?;
        let report = check(&loaded.scene, &CheckOptions::default());
        let model = view::Model::of_check(file, &loaded.scene, &report);
        Ok([view::picture(&model), view::html(&model)])
    };
    let plain = draw(&named_scene(["A", "B", "C"])).expect("plain names");
    let fields = ["robots[0].name", "robots[1].name", "obstacles[0].name"];
    match draw(&named_scene(names)) {
        Err(e) => {
            assert_eq!(e.file, file, "{e}");
            assert!(
                fields.contains(&e.field.as_str()),
                "names no name field: {e}"
            );
        }
        Ok(drawn) => {
            for (k, (text, plain)) in drawn.iter().zip(&plain).enumerate() {
                assert_eq!(
                    markers(text),
                    markers(plain),
                    "a name forged markup: {names:?}"
                );
                assert!(
                    !text
                        .chars()
                        .any(|c| c.is_control() && !matches!(c, '\n' | '\t' | '\r')),
                    "a control character in an output: {names:?}"
                );
                // Escapes (`&lt;`) read as nothing; a name whose raw text a plain drawing
                // holds anyway (`<`, `</`) proves nothing.
                let (text, plain) = (without_entities(text), without_entities(plain));
                let raw: &[char] = if k == 0 { &['<', '&'] } else { &['<'] };
                let telling = |n: &&&str| n.contains(raw) && !plain.contains(**n);
                for name in names.iter().filter(telling) {
                    assert!(!text.contains(name), "{name:?} raw in an output");
                }
            }
        }
    }
}

/// `text` with its character and entity references (`&amp;`, `&#60;`) taken out.
#[cfg(feature = "cli")]
fn without_entities(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find('&') {
        out.push_str(&rest[..at]);
        let after = &rest[at + 1..];
        let len = after
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '#'))
            .unwrap_or(after.len());
        match after[len..].starts_with(';') && len > 0 {
            true => rest = &after[len + 1..],
            false => {
                out.push('&');
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// Fragments of names that break SVG, HTML, the JSON a page embeds, terminals or
/// bidirectional text.
pub const NAME_FRAGMENTS: [&str; 22] = [
    "<!--",
    "-->",
    "<script>",
    "</script>",
    "]]>",
    "\"",
    "'",
    "&",
    "&amp;",
    "<",
    ">",
    "\u{202E}",
    "\u{200B}",
    "é",
    "\u{1F916}",
    "x",
    " ",
    "\\",
    "/",
    "`",
    "${",
    "\u{FEFF}",
];

/// Characters no output may carry: a name holding one is refused.
pub const NAME_CONTROLS: [&str; 5] = ["\u{0}", "\u{1}", "\u{1B}", "\u{7F}", "\u{FFFE}"];
