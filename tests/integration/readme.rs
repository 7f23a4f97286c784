//! The README and `docs/` hold: every `--example X` and `--bench X` they name is a file of
//! the repository, every file path they name in backticks under `src/`, `benches/`,
//! `examples/`, `tests/`, `cells/`, `docs/` or `benchmarks/` is there, every relative link
//! resolves (file and heading), the README stays a front page (at most 250 lines, no commit
//! hashes outside the changelog and the measurements), its short cell is the shipped file, and
//! its quick start's commands run with the exit status it gives. A figure comes from a command
//! anyone can run; a command whose target was removed cannot.

use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn readme() -> String {
    read(&root().join("README.md"))
}

/// The README, `CHANGELOG.md` and every page of `docs/`, with their paths.
fn pages() -> Vec<(PathBuf, String)> {
    let mut files = vec![root().join("README.md"), root().join("CHANGELOG.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    files.extend(docs);
    files.into_iter().map(|p| (p.clone(), read(&p))).collect()
}

/// The words that follow `flag` in `text`.
fn after<'t>(text: &'t str, flag: &str) -> Vec<&'t str> {
    text.match_indices(flag)
        .filter_map(|(i, _)| text[i + flag.len()..].split_whitespace().next())
        .map(|w| w.trim_end_matches(['`', ',', ')', ';', ':']))
        .collect()
}

#[test]
fn the_docs_name_targets_that_exist() {
    let mut missing = Vec::new();
    let mut examples = 0;
    for (page, text) in pages() {
        for (flag, dir) in [("--example ", "examples"), ("--bench ", "benches")] {
            for name in after(&text, flag) {
                examples += usize::from(flag == "--example ");
                if !root().join(dir).join(format!("{name}.rs")).is_file() {
                    missing.push(format!("{}: {flag}{name}", page.display()));
                }
            }
        }
    }
    assert!(missing.is_empty(), "missing targets: {missing:?}");
    assert!(examples >= 3, "the test shows little");
}

#[test]
fn the_docs_name_files_that_exist() {
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
    for (page, text) in pages() {
        for quoted in text.split('`').skip(1).step_by(2) {
            let path = quoted.split_whitespace().next().unwrap_or("");
            let file_like = [".rs", ".json", ".svg", ".py", ".md", ".png"]
                .iter()
                .any(|e| path.ends_with(e));
            if !dirs.iter().any(|d| path.starts_with(d)) || !file_like || path.contains('*') {
                continue;
            }
            seen += 1;
            if !root().join(path).is_file() {
                missing.push(format!("{}: {path}", page.display()));
            }
        }
    }
    missing.dedup();
    assert!(missing.is_empty(), "missing files: {missing:?}");
    assert!(seen >= 10, "only {seen} paths: the test shows little");
}

/// GitHub's anchor of a heading: lower case, punctuation but `-` and `_` dropped, spaces to
/// hyphens.
fn slug(heading: &str) -> String {
    let kept: String = heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | ' '))
        .collect();
    kept.replace(' ', "-")
}

/// The anchors of a Markdown page's headings (outside code blocks).
fn anchors(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
        } else if !fenced && line.starts_with('#') {
            out.push(slug(line.trim_start_matches('#')));
        }
    }
    out
}

/// The targets of the Markdown links and images of `text`, `[label](target)`.
fn links(text: &str) -> Vec<&str> {
    text.match_indices("](")
        .filter_map(|(i, _)| {
            let rest = &text[i + 2..];
            rest.find(')').map(|end| &rest[..end])
        })
        .collect()
}

#[test]
fn every_relative_link_resolves_to_a_file_and_heading() {
    let mut broken = Vec::new();
    let mut checked = 0;
    for (page, text) in pages() {
        for target in links(&text) {
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            checked += 1;
            let (file, anchor) = target.split_once('#').unwrap_or((target, ""));
            let path = match file {
                "" => page.clone(),
                f => page.parent().unwrap().join(f),
            };
            if !path.exists() {
                broken.push(format!("{}: {target} (no such file)", page.display()));
                continue;
            }
            if !anchor.is_empty() && !anchors(&read(&path)).iter().any(|a| a == anchor) {
                broken.push(format!("{}: {target} (no such heading)", page.display()));
            }
        }
    }
    assert!(broken.is_empty(), "broken links: {broken:#?}");
    assert!(checked >= 30, "only {checked} links: the test shows little");
}

#[test]
fn the_readme_is_a_front_page() {
    let text = readme();
    let lines = text.lines().count();
    assert!(
        lines <= 250,
        "README.md has {lines} lines; move detail to docs/"
    );
    // No commit hashes outside the changelog and the measurements (docs/benchmarks.md,
    // docs/parts.md): a word of 7 to 40 hex digits with a digit and a letter.
    for (page, text) in pages() {
        let name = page.file_name().unwrap().to_string_lossy().into_owned();
        if ["CHANGELOG.md", "benchmarks.md", "parts.md"].contains(&name.as_str()) {
            continue;
        }
        let hashes: Vec<&str> = text
            .split(|c: char| !c.is_ascii_alphanumeric())
            .filter(|w| (7..=40).contains(&w.len()))
            .filter(|w| {
                w.chars()
                    .all(|c| c.is_ascii_hexdigit() && !c.is_ascii_uppercase())
            })
            .filter(|w| w.chars().any(|c| c.is_ascii_digit()) && w.chars().any(char::is_alphabetic))
            .collect();
        assert!(hashes.is_empty(), "{name} names commits {hashes:?}");
    }
    for file in ["LICENSE-MIT", "LICENSE-APACHE", "CHANGELOG.md"] {
        assert!(root().join(file).is_file(), "{file} missing");
    }
}

/// The fenced blocks of `text` in the language `lang` (`""`: none given), in order.
fn blocks<'t>(text: &'t str, lang: &str) -> Vec<&'t str> {
    let mut out = Vec::new();
    let mut open: Option<(bool, usize)> = None;
    let mut at = 0;
    for line in text.split_inclusive('\n') {
        if let Some(info) = line.trim_end().strip_prefix("```") {
            open = match open {
                None => Some((info == lang, at + line.len())),
                Some((wanted, from)) => {
                    if wanted {
                        out.push(&text[from..at]);
                    }
                    None
                }
            };
        }
        at += line.len();
    }
    out
}

#[test]
fn the_readme_cell_is_the_shipped_file() {
    let text = readme();
    let cell = blocks(&text, "json");
    let shipped = read(&root().join("cells/two-robots-cell.json"));
    assert_eq!(cell.first().copied(), Some(shipped.as_str()));
}

#[cfg(feature = "cli")]
#[test]
fn the_quick_start_commands_run_as_documented() {
    let text = readme();
    let start = text.find("## Quick start").expect("a quick start");
    let end = text[start..]
        .find("\n## ")
        .map_or(text.len(), |e| start + e);
    let quick = &text[start..end];
    let dir = crate::common::temp_dir_made("readme", "quick-start");
    let mut ran = 0;
    for block in blocks(quick, "sh") {
        for line in block.lines() {
            let (command, comment) = line.split_once('#').unwrap_or((line, ""));
            // The test suite itself is not run again from within it.
            let Some(args) = command.trim().strip_prefix("cargo run --release -- ") else {
                continue;
            };
            let expected = match comment.split("exit ").nth(1) {
                Some(code) => code.trim().parse::<i32>().expect("an exit status"),
                None => 0,
            };
            // Inputs from the checkout, outputs in a folder of the test's own.
            let args: Vec<String> = args
                .split_whitespace()
                .map(|a| match a.starts_with("cells/") {
                    true => root().join(a).to_string_lossy().into_owned(),
                    false => a.to_owned(),
                })
                .collect();
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_workcell"))
                .args(&args)
                .current_dir(&dir)
                .output()
                .unwrap();
            assert_eq!(out.status.code(), Some(expected), "{line}: {out:?}");
            ran += 1;
        }
    }
    assert!(ran >= 3, "only {ran} commands");
    // The first command's output is the one shown, but for the stage times.
    let shown = blocks(quick, "")
        .into_iter()
        .next()
        .expect("the expected output");
    let out = crate::common::workcell(&["solve", &crate::common::shipped("paper-cell.json")]);
    let printed =
        String::from_utf8_lossy(&out.stdout).replace(&root().to_string_lossy().into_owned(), "");
    let printed = printed.replace("/cells/", "cells/");
    for line in shown.lines() {
        assert!(
            printed.lines().any(|l| l == line),
            "not printed: {line}\n{printed}"
        );
    }
}
