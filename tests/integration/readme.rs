//! The README's commands name targets that exist: every `--example X`, `--bench X` and
//! `--test X` is a file of the repository, and every file path it names in backticks under
//! `src/`, `benches/`, `examples/`, `tests/`, `cells/`, `docs/` or `benchmarks/` is there. A
//! figure in the README comes from a command anyone can run; a command whose target was
//! removed cannot.

use std::path::Path;

fn readme() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).unwrap()
}

/// The words that follow `flag` in `text`.
fn after<'t>(text: &'t str, flag: &str) -> Vec<&'t str> {
    text.match_indices(flag)
        .filter_map(|(i, _)| text[i + flag.len()..].split_whitespace().next())
        .map(|w| w.trim_end_matches(['`', ',', ')', ';', ':']))
        .collect()
}

#[test]
fn the_readme_names_targets_that_exist() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = readme();
    let mut missing = Vec::new();
    for (flag, dir) in [("--example ", "examples"), ("--bench ", "benches")] {
        for name in after(&text, flag) {
            if !root.join(dir).join(format!("{name}.rs")).is_file() {
                missing.push(format!("{flag}{name}"));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "README names missing targets: {missing:?}"
    );
    assert!(
        after(&text, "--example ").len() >= 3,
        "the test shows little"
    );
}

#[test]
fn the_readme_names_files_that_exist() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = readme();
    let dirs = [
        "src/",
        "benches/",
        "examples/",
        "tests/",
        "cells/",
        "docs/",
        "benchmarks/",
    ];
    let mut seen = 0;
    let mut missing = Vec::new();
    for quoted in text.split('`').skip(1).step_by(2) {
        let path = quoted.split_whitespace().next().unwrap_or("");
        let file_like = path.ends_with(".rs")
            || path.ends_with(".json")
            || path.ends_with(".svg")
            || path.ends_with(".py")
            || path.ends_with(".md")
            || path.ends_with(".png");
        if !dirs.iter().any(|d| path.starts_with(d)) || !file_like || path.contains('*') {
            continue;
        }
        seen += 1;
        if !root.join(path).is_file() {
            missing.push(path.to_owned());
        }
    }
    missing.dedup();
    assert!(
        missing.is_empty(),
        "README names missing files: {missing:?}"
    );
    assert!(seen >= 10, "only {seen} paths: the test shows little");
}
