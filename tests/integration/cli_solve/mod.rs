//! `workcell solve` and `workcell evaluate` as a user meets them: exit statuses, the
//! contract's JSON, the exports, and errors that name the file, the body and the field. The
//! helpers shared by its modules are here.

mod refusals;
mod results;

use crate::common::{shipped, temp_dir_made, workcell};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn json(o: &Output) -> Value {
    serde_json::from_slice(&o.stdout).expect("stdout is JSON")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Cell `k` of `workcell generate --kind <kind> --seed 1`, written into a folder of the
/// test `tag`: its path.
fn generated(tag: &str, kind: &str, k: usize) -> String {
    let dir = temp_dir_made("solve", tag).join("cells");
    let count = (k + 1).to_string();
    let out = workcell(&[
        "generate",
        "--kind",
        kind,
        "--seed",
        "1",
        "--count",
        &count,
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let cell = dir.join(format!("{kind}-1-{k}-cell.json"));
    cell.to_str().unwrap().to_owned()
}

/// `evaluate` replays a solve's result document (its changed moves and holds), then its own
/// output, each time giving what the solve gave under `keys`.
fn replays_to_the_same(cell: &str, solved: &Output, tag: &str, keys: &[&str]) {
    let result = json(solved);
    let mut document = temp_dir_made("solve", tag).join("result.json");
    std::fs::write(&document, &solved.stdout).unwrap();
    for round in 0..2 {
        let out = workcell(&["evaluate", cell, document.to_str().unwrap(), "--json"]);
        let how = format!("round {round}: {}", text(&out.stdout));
        assert_eq!(out.status.code(), Some(0), "{how}");
        for key in keys {
            assert_eq!(json(&out)[key], result[key], "{key}, {how}");
        }
        document = temp_dir_made("solve", tag).join(format!("evaluated-{round}.json"));
        std::fs::write(&document, &out.stdout).unwrap();
    }
}

/// The feedback cell with `edit` applied, written to a per-test file.
fn edited_cell(test: &str, edit: impl FnOnce(&mut Value)) -> PathBuf {
    let text = std::fs::read_to_string(shipped("feedback-cell.json")).unwrap();
    let mut cell: Value = serde_json::from_str(&text).unwrap();
    edit(&mut cell);
    let path = temp_dir_made("solve", test).join("cell.json");
    std::fs::write(&path, cell.to_string()).unwrap();
    path
}

/// Writes a sequences document to a per-test file.
fn sequences_file(test: &str, doc: &Value) -> PathBuf {
    let path = temp_dir_made("solve", test).join("sequences.json");
    std::fs::write(&path, doc.to_string()).unwrap();
    path
}

/// Asserts exit status 2 and that stderr names `file` and every one of `needles`.
fn refused_naming(out: &Output, file: &Path, needles: &[&str]) {
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}{}", text(&out.stdout));
    assert!(
        err.contains(&format!("error: {}: ", file.display())),
        "not about {}: {err}",
        file.display()
    );
    for n in needles {
        assert!(err.contains(n), "`{n}` missing from {err}");
    }
}

/// All four tasks done by R1, in file order.
fn r1_does_everything() -> Value {
    serde_json::json!({"R1": ["weld-1", "weld-2", "weld-3", "weld-4"]})
}

fn text_of_first_line(o: &Output) -> String {
    text(&o.stdout)
        .lines()
        .next()
        .unwrap_or_default()
        .to_owned()
}

/// `evaluate` on `result` with each case's value put at its JSON pointer: exit 2, naming the
/// file written and the case's field, saying the case's words and every one of `also`.
fn evaluate_refuses_each(
    cell: &str,
    result: &Value,
    dir: &Path,
    cases: &[(String, f64, String, &str)],
    also: &[&str],
) {
    for (n, (pointer, value, field, says)) in cases.iter().enumerate() {
        let mut bad = result.clone();
        *bad.pointer_mut(pointer).unwrap() = serde_json::json!(value);
        let file = dir.join(format!("bad-{n}.json"));
        std::fs::write(&file, bad.to_string()).unwrap();
        let o = workcell(&["evaluate", cell, file.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "{pointer} = {value}");
        let err = text(&o.stderr);
        assert!(
            err.contains(file.to_str().unwrap()) && err.contains(&format!("`{field}`")),
            "{err}"
        );
        assert!(err.contains(says), "{err}");
        assert!(also.iter().all(|w| err.contains(w)), "{err}");
    }
}
