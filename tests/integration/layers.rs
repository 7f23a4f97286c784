//! The house's layers (issue 27): no import cycle between the crate's top-level modules, nor
//! between its files. Read from the sources' own paths, so a new cycle fails here, naming
//! the files and lines that make each arrow.
//!
//! The top-level modules, lowest first: each imports only modules to its left.
//!
//! `geometry` → `motion` → `collision` → `cell` → `planning` → `wcp` → `generate` →
//! `compare` → `view` → `cli` (and `main.rs`). `error` (the input error type) stands below
//! them all.
//!
//! What counts as an import: a path `crate::a::b` (in a `use`, grouped `crate::{a, b::c}`
//! included, or written inline), `super::x`, and `x::` for a module `x` the file declares.
//! A path that names an item a module re-exports (`pub use`) leads to the file that defines
//! it; a re-export is no import of its own. Inside an inline `mod m { … }` write
//! `crate::` paths: this reader takes `super` to be the file's parent module.
//! Comments and doc comments are not read, nor a file's `#[cfg(test)]` module: tests may
//! build their inputs with the generators of a higher layer.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The order of the top-level modules, lowest first (see the module comment).
const LAYERS: [&str; 11] = [
    "error",
    "geometry",
    "motion",
    "collision",
    "cell",
    "planning",
    "wcp",
    "generate",
    "compare",
    "view",
    "cli",
];

/// An import: from which file, at which line, to which file.
#[derive(Clone, Debug)]
struct Arrow {
    from: PathBuf,
    line: usize,
    to: PathBuf,
}

/// The file of module path `parts` under `dir` (`a/b.rs` or `a/b/mod.rs`), following the
/// path as deep as files go, then through the re-exports (`pub use`) of the file reached to
/// the file that defines the item named.
fn resolve(src: &Path, dir: &Path, parts: &[&str], root: &Path) -> Option<PathBuf> {
    let mut found = None;
    let mut at = dir.to_path_buf();
    let mut depth = 0;
    for part in parts {
        let (file, folder) = (at.join(format!("{part}.rs")), at.join(part).join("mod.rs"));
        if file.is_file() {
            found = Some(file);
        } else if folder.is_file() {
            found = Some(folder);
        } else {
            break;
        }
        at = at.join(part);
        depth += 1;
    }
    // An item of the module `dir` itself: its `mod.rs`, or the crate's root file.
    let file = found.or_else(|| match dir == src {
        true => Some(root.to_path_buf()),
        false => Some(dir.join("mod.rs")).filter(|f| f.is_file()),
    })?;
    let Some(item) = parts.get(depth) else {
        return Some(file);
    };
    match reexports(src, &file).get(*item) {
        Some(path) if path.len() > 1 => {
            let (base, rest) = match path[0].as_str() {
                "crate" => (src.to_path_buf(), &path[1..]),
                _ => (children_dir(&file), &path[..]),
            };
            let rest: Vec<&str> = rest.iter().map(String::as_str).collect();
            resolve(src, &base, &rest, root).or(Some(file))
        }
        _ => Some(file),
    }
}

/// The items a file re-exports (`pub use a::b::{C, D}`): name → the path it stands for
/// (starting with `crate` or with a child module of the file).
fn reexports(src: &Path, file: &Path) -> BTreeMap<String, Vec<String>> {
    let _ = src;
    let text = std::fs::read_to_string(file).unwrap_or_default();
    let code: Vec<String> = code_lines(&text).into_iter().map(|(_, l)| l).collect();
    let joined = code.join(" ");
    let mut map = BTreeMap::new();
    for statement in joined.split(';') {
        let s = statement.trim();
        let Some(rest) = ["pub use ", "pub(crate) use ", "pub(super) use "]
            .iter()
            .find_map(|p| s.strip_prefix(p))
        else {
            continue;
        };
        let rest = rest.trim();
        let (base, items): (&str, Vec<&str>) = match rest.find('{') {
            Some(i) => (
                rest[..i].trim_end_matches("::"),
                rest[i + 1..].trim_end_matches('}').split(',').collect(),
            ),
            None => match rest.rfind("::") {
                Some(i) => (&rest[..i], vec![&rest[i + 2..]]),
                None => continue,
            },
        };
        for item in items {
            let item = item.trim();
            if item.is_empty() {
                continue;
            }
            let name = item.rsplit("::").next().unwrap().trim().to_owned();
            let mut path: Vec<String> = base.split("::").map(str::to_owned).collect();
            path.extend(item.split("::").map(|x| x.trim().to_owned()));
            map.insert(name, path);
        }
    }
    map
}

/// The folder that holds a file's child modules: `a/b.rs` and `a/b/mod.rs` both have `a/b`.
fn children_dir(file: &Path) -> PathBuf {
    let parent = file.parent().unwrap().to_path_buf();
    match file.file_name().unwrap().to_str().unwrap() {
        "mod.rs" | "lib.rs" | "main.rs" => parent,
        name => parent.join(name.trim_end_matches(".rs")),
    }
}

/// A test module declared on the first non-blank of `lines` (after its `#[cfg(test)]`).
enum TestModule {
    /// `mod tests { … }`: the rest of the file.
    Inline,
    /// `mod tests;`: a file of its own, by that name.
    File(String),
}

fn test_module(lines: &[&str]) -> Option<TestModule> {
    let line = lines.iter().find(|l| !l.trim().is_empty())?.trim();
    let name = line.strip_prefix("mod ")?;
    Some(match name.strip_suffix(';') {
        Some(file) => TestModule::File(file.trim().to_owned()),
        None => TestModule::Inline,
    })
}

/// The files of `files` that are test modules (`#[cfg(test)] mod tests;`): not read.
fn test_module_files(files: &[PathBuf]) -> Vec<PathBuf> {
    let mut tests = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(file).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        for (k, line) in lines.iter().enumerate() {
            if line.trim_start().starts_with("#[cfg(test)]") {
                if let Some(TestModule::File(name)) = test_module(&lines[k + 1..]) {
                    tests.push(children_dir(file).join(format!("{name}.rs")));
                }
            }
        }
    }
    tests
}

/// The code of a file, line by line, without comments and without its test module.
fn code_lines(text: &str) -> Vec<(usize, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        let trimmed = line.trim_start();
        if trimmed.starts_with("#[cfg(test)]") {
            match test_module(&lines[k + 1..]) {
                // A test module in a file of its own: the rest of this file is still code.
                Some(TestModule::File(_)) => continue,
                Some(TestModule::Inline) => break,
                None => {}
            }
        }
        if k > 0 && lines[k - 1].trim_start().starts_with("#[cfg(test)]") {
            if let Some(TestModule::File(_)) = test_module(&lines[k..]) {
                continue;
            }
        }
        let code = match line.find("//") {
            Some(i) => &line[..i],
            None => line,
        };
        if !code.trim().is_empty() {
            out.push((k + 1, code.to_owned()));
        }
    }
    out
}

/// The module paths a line names after `prefix` (`crate::`, `super::` or a child's `x::`),
/// a group `a::{b::C, d}` giving one path per item, nested groups included.
fn paths_after(code: &str, prefix: &str) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find(prefix) {
        let before = rest[..i].chars().last();
        rest = &rest[i + prefix.len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
            continue; // a longer name that ends with the prefix, or a path inside a path
        }
        paths.extend(expand(rest));
    }
    paths.retain(|p| !p.is_empty());
    paths
}

/// The paths of `a::b::{c::D, e}` (what follows a prefix): one per item of a group.
fn expand(text: &str) -> Vec<Vec<String>> {
    let head = segments(text);
    let consumed: usize = head.iter().map(|s| s.len() + 2).sum();
    let after = text.get(consumed.min(text.len())..).unwrap_or("");
    let group = if head.is_empty() {
        text.strip_prefix('{')
    } else {
        text.get(consumed.saturating_sub(2)..)
            .and_then(|t| t.strip_prefix("::{"))
            .or_else(|| after.strip_prefix('{'))
    };
    let Some(group) = group else {
        return vec![head];
    };
    // Items at the group's own depth.
    let (mut depth, mut start, mut items) = (0, 0, Vec::new());
    for (k, c) in group.char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => {
                items.push(&group[start..k]);
                break;
            }
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&group[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    items
        .into_iter()
        .flat_map(|item| expand(item.trim()))
        .map(|tail| head.iter().cloned().chain(tail).collect())
        .collect()
}

/// The file's code as statements to read: a `use` joined over its lines, with the number of
/// its first line; re-exports (`pub use`) left out, as they only hand names on (the
/// resolution of a path follows them to the file that defines the name).
fn statements(lines: &[(usize, String)]) -> Vec<(usize, String)> {
    let mut out: Vec<(usize, String)> = Vec::new();
    let mut open: Option<(usize, String)> = None;
    for (k, line) in lines {
        let t = line.trim_start();
        match open.as_mut() {
            Some((_, text)) => text.push_str(t),
            None if t.starts_with("use ") || (t.starts_with("pub") && t.contains(" use ")) => {
                open = Some((*k, t.to_owned()))
            }
            None => {
                out.push((*k, line.clone()));
                continue;
            }
        }
        if t.contains(';') {
            let (k, text) = open.take().unwrap();
            if !text.starts_with("pub") {
                out.push((k, text));
            }
        }
    }
    out
}

/// The leading `a::b::c` of a path, as segments.
fn segments(path: &str) -> Vec<String> {
    let end = path
        .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
        .unwrap_or(path.len());
    path[..end]
        .split("::")
        .filter(|s| !s.is_empty())
        .map(str::to_owned)
        .collect()
}

/// Every import arrow between files of `src`.
fn arrows(src: &Path) -> Vec<Arrow> {
    let mut files = Vec::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    files.sort();
    let tests = test_module_files(&files);
    files.retain(|f| !tests.contains(f));
    let mut arrows = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let lines = code_lines(&text);
        let own = children_dir(file);
        // The binary (`main.rs` and the `cli` it declares) is a crate of its own.
        let bin = file.ends_with("main.rs") || file.starts_with(src.join("cli"));
        let root = src.join(if bin { "main.rs" } else { "lib.rs" });
        let children: Vec<String> = lines
            .iter()
            .filter_map(|(_, l)| {
                let l = l
                    .trim()
                    .trim_start_matches("pub ")
                    .trim_start_matches("pub(crate) ");
                let name = l.strip_prefix("mod ")?.strip_suffix(';')?;
                Some(name.trim().to_owned())
            })
            .collect();
        let parent = match file.file_name().unwrap().to_str().unwrap() {
            "mod.rs" => own.parent().map(Path::to_path_buf),
            _ => Some(own.parent().unwrap().to_path_buf()),
        };
        for (line, code) in &statements(&lines) {
            let mut targets = Vec::new();
            for path in paths_after(code, "crate::") {
                let parts: Vec<&str> = path.iter().map(String::as_str).collect();
                targets.extend(resolve(src, src, &parts, &root));
            }
            if let Some(parent) = &parent {
                for path in paths_after(code, "super::") {
                    // `super::super::x`: one folder up per `super`.
                    let ups = path.iter().take_while(|p| *p == "super").count();
                    let mut dir = parent.clone();
                    for _ in 0..ups {
                        dir = dir.parent().unwrap().to_path_buf();
                    }
                    let parts: Vec<&str> = path[ups..].iter().map(String::as_str).collect();
                    targets.extend(resolve(src, &dir, &parts, &root));
                }
            }
            for child in &children {
                for path in paths_after(code, &format!("{child}::")) {
                    let mut parts = vec![child.as_str()];
                    parts.extend(path.iter().map(String::as_str));
                    targets.extend(resolve(src, &own, &parts, &root));
                }
            }
            for to in targets {
                if &to != file {
                    arrows.push(Arrow {
                        from: file.clone(),
                        line: *line,
                        to,
                    });
                }
            }
        }
    }
    arrows
}

/// A cycle of the graph whose arrows go from the key to the values, if there is one.
fn cycle<N: Ord + Clone>(graph: &BTreeMap<N, BTreeSet<N>>) -> Option<Vec<N>> {
    fn visit<N: Ord + Clone>(
        n: &N,
        graph: &BTreeMap<N, BTreeSet<N>>,
        state: &mut BTreeMap<N, bool>,
        path: &mut Vec<N>,
    ) -> Option<Vec<N>> {
        match state.get(n) {
            Some(true) => {
                let from = path.iter().position(|p| p == n).unwrap();
                return Some(path[from..].to_vec());
            }
            Some(false) => return None,
            None => {}
        }
        state.insert(n.clone(), true);
        path.push(n.clone());
        for m in graph.get(n).into_iter().flatten() {
            if let Some(c) = visit(m, graph, state, path) {
                return Some(c);
            }
        }
        path.pop();
        state.insert(n.clone(), false);
        None
    }
    let mut state = BTreeMap::new();
    graph
        .keys()
        .find_map(|n| visit(n, graph, &mut state, &mut Vec::new()))
}

/// The top-level module of a file of `src`: its first folder, or its name.
fn top(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_str()
        .unwrap();
    first.trim_end_matches(".rs").to_owned()
}

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

#[test]
fn top_level_modules_import_only_lower_layers() {
    let src = src();
    let arrows = arrows(&src);
    assert!(
        arrows.len() > 300,
        "{} arrows: the reader lost its way",
        arrows.len()
    );
    let rank = |m: &str| LAYERS.iter().position(|l| *l == m);
    let mut upward = Vec::new();
    for a in &arrows {
        let (from, to) = (top(&src, &a.from), top(&src, &a.to));
        if from == to || ["lib", "main"].contains(&from.as_str()) {
            continue;
        }
        match (rank(&from), rank(&to)) {
            (Some(f), Some(t)) if f > t => {}
            _ => upward.push(format!(
                "  {from} -> {to}: {}:{}",
                a.from.strip_prefix(&src).unwrap().display(),
                a.line
            )),
        }
    }
    assert!(
        upward.is_empty(),
        "imports against the layers {LAYERS:?}:\n{}",
        upward.join("\n")
    );
}

/// The groups of files that import each other in a loop (strongly connected components
/// of more than one file), each in file order.
fn loops(graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>) -> Vec<Vec<PathBuf>> {
    let reach = |from: &PathBuf| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.clone()];
        while let Some(n) = stack.pop() {
            for m in graph.get(&n).into_iter().flatten() {
                if seen.insert(m.clone()) {
                    stack.push(m.clone());
                }
            }
        }
        seen
    };
    let reached: BTreeMap<&PathBuf, BTreeSet<PathBuf>> =
        graph.keys().map(|n| (n, reach(n))).collect();
    let mut groups: BTreeSet<Vec<PathBuf>> = BTreeSet::new();
    for (n, r) in &reached {
        if !r.contains(*n) {
            continue;
        }
        let group: Vec<PathBuf> = r
            .iter()
            .filter(|m| reached.get(m).is_some_and(|back| back.contains(*n)))
            .cloned()
            .collect();
        groups.insert(group);
    }
    groups.into_iter().collect()
}

#[test]
fn no_cycle_between_files() {
    let src = src();
    let arrows = arrows(&src);
    let mut graph: BTreeMap<PathBuf, BTreeSet<PathBuf>> = BTreeMap::new();
    for a in &arrows {
        graph
            .entry(a.from.clone())
            .or_default()
            .insert(a.to.clone());
    }
    let groups = loops(&graph);
    let report: Vec<String> = groups
        .iter()
        .map(|group| {
            let inside = |p: &PathBuf| group.contains(p);
            let mut seen = BTreeSet::new();
            let lines: Vec<String> = arrows
                .iter()
                .filter(|a| inside(&a.from) && inside(&a.to))
                .filter(|a| seen.insert((a.from.clone(), a.to.clone())))
                .map(|a| {
                    let short = |p: &Path| p.strip_prefix(&src).unwrap().display().to_string();
                    format!("  {}:{} -> {}", short(&a.from), a.line, short(&a.to))
                })
                .collect();
            format!("files importing each other:\n{}", lines.join("\n"))
        })
        .collect();
    assert!(report.is_empty(), "{}", report.join("\n"));
    assert_eq!(cycle(&graph), None);
}

/// The detector finds a cycle where there is one, and the reader sees each kind of path.
#[test]
fn the_detector_sees_cycles_and_paths() {
    let mut graph: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    graph.entry("a").or_default().insert("b");
    graph.entry("b").or_default().insert("c");
    assert_eq!(cycle(&graph), None);
    graph.entry("c").or_default().insert("a");
    assert_eq!(cycle(&graph).map(|c| c.len()), Some(3));
    assert_eq!(
        paths_after("use crate::{cell::Cell, wcp::x::Y};", "crate::"),
        [vec!["cell", "Cell"], vec!["wcp", "x", "Y"]]
    );
    assert_eq!(
        paths_after("use crate::wcp::{feedback::{A, b::C}, D};", "crate::"),
        [
            vec!["wcp", "feedback", "A"],
            vec!["wcp", "feedback", "b", "C"],
            vec!["wcp", "D"]
        ]
    );
    assert_eq!(
        paths_after("let s = my_crate::x();", "crate::"),
        Vec::<Vec<String>>::new()
    );
    assert_eq!(
        code_lines(
            "use a;\n/// crate::b\nx(); // crate::c\n#[cfg(test)]\nmod tests {\nuse crate::d;\n}"
        ),
        [(1, "use a;".to_owned()), (3, "x(); ".to_owned())]
    );
    // A test module in a file of its own hides nothing after it.
    assert_eq!(
        code_lines("#[cfg(test)]\nmod tests;\nuse crate::e;"),
        [(3, "use crate::e;".to_owned())]
    );
}
