//! Seeded fuzzing of what `solve` writes (issue 26): output paths of every kind a shell can
//! name (plain files new and old, symbolic links live and dangling, hard links, FIFOs with
//! and without a reader, devices, folders, missing folders, the input itself, one path
//! twice), and names built from the fragments that break pictures and pages. The invariants:
//! the exit status says what happened (0, or 2 naming the path or field), nothing hangs,
//! nothing is left half-written or replaced that should not be, and no name reaches an
//! output raw.

use crate::common::{shipped, temp_dir_made};
use fuzz_support::{markers, NAME_CONTROLS, NAME_FRAGMENTS};
use rand::seq::IndexedRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

#[path = "../fuzz_support/mod.rs"]
mod fuzz_support;

/// The seed of the cases: the same on every run.
const SEED: u64 = 26;

/// Runs `workcell args`, killed (and the test failed) if it has not ended in `limit`.
fn run_bounded(args: &[String], limit: Duration) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_workcell"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("workcell {args:?} hung for {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// The kinds of output path.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    New,
    Old,
    Link,
    Dangling,
    HardLinked,
    FifoRead,
    FifoUnread,
    DevNull,
    Folder,
    MissingFolder,
    Input,
}

const KINDS: [Kind; 11] = [
    Kind::New,
    Kind::Old,
    Kind::Link,
    Kind::Dangling,
    Kind::HardLinked,
    Kind::FifoRead,
    Kind::FifoUnread,
    Kind::DevNull,
    Kind::Folder,
    Kind::MissingFolder,
    Kind::Input,
];

impl Kind {
    /// Refused before any work: nothing at all is written.
    fn refused_first(self) -> bool {
        matches!(
            self,
            Kind::Dangling | Kind::Folder | Kind::MissingFolder | Kind::Input
        )
    }
}

/// A FIFO's reader: a thread reading what comes until the writer closes, or until told the
/// writer has gone without writing.
type Reader = (std::thread::JoinHandle<Vec<u8>>, Arc<AtomicBool>);

/// One output's path, made of its kind in `dir`, and what to look at afterwards: the file
/// holding its content, or a FIFO's reader.
struct Target {
    kind: Kind,
    path: PathBuf,
    content: Option<PathBuf>,
    reader: Option<Reader>,
}

/// Opens `fifo` for reading at once (without waiting for a writer: a writer then finds a
/// reader) and reads it on a thread.
fn read_fifo(fifo: &Path) -> Reader {
    use std::io::Read;
    use std::os::unix::fs::OpenOptionsExt;
    let mut file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(fifo)
        .unwrap();
    let over = Arc::new(AtomicBool::new(false));
    let told = over.clone();
    let thread = std::thread::spawn(move || {
        let (mut got, mut buf) = (Vec::new(), [0u8; 65536]);
        loop {
            match file.read(&mut buf) {
                // No writer: none yet, or it has closed.
                Ok(0) if !got.is_empty() || told.load(Ordering::SeqCst) => return got,
                Ok(n) => got.extend_from_slice(&buf[..n]),
                Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {}
                Err(e) => panic!("reading the FIFO: {e}"),
            }
            std::thread::sleep(Duration::from_millis(1));
        }
    });
    (thread, over)
}

fn make(kind: Kind, dir: &Path, k: usize, input: &Path) -> Target {
    let path = dir.join(format!("out-{k}"));
    let old = |p: &Path| std::fs::write(p, "old").unwrap();
    let mut content = Some(path.clone());
    let mut reader = None;
    match kind {
        Kind::New => {}
        Kind::Old => old(&path),
        Kind::Link => {
            let target = dir.join(format!("target-{k}"));
            old(&target);
            std::os::unix::fs::symlink(&target, &path).unwrap();
            content = Some(target);
        }
        Kind::Dangling => {
            std::os::unix::fs::symlink(dir.join("nowhere/x"), &path).unwrap();
            content = None;
        }
        Kind::HardLinked => {
            let other = dir.join(format!("other-{k}"));
            old(&other);
            std::fs::hard_link(&other, &path).unwrap();
            content = Some(other);
        }
        Kind::FifoRead | Kind::FifoUnread => {
            let status = Command::new("mkfifo").arg(&path).status().unwrap();
            assert!(status.success());
            content = None;
            if kind == Kind::FifoRead {
                reader = Some(read_fifo(&path));
            }
        }
        Kind::DevNull => {
            return Target {
                kind,
                path: PathBuf::from("/dev/null"),
                content: None,
                reader: None,
            }
        }
        Kind::Folder => {
            std::fs::create_dir(&path).unwrap();
            content = None;
        }
        Kind::MissingFolder => {
            return Target {
                kind,
                path: dir.join(format!("missing-{k}/x.svg")),
                content: None,
                reader: None,
            }
        }
        Kind::Input => {
            return Target {
                kind,
                path: input.to_path_buf(),
                content: None,
                reader: None,
            }
        }
    }
    Target {
        kind,
        path,
        content,
        reader,
    }
}

#[cfg(target_os = "linux")]
#[test]
fn outputs_of_every_kind_are_written_or_refused_cleanly() {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let options = [
        "--svg",
        "--gantt",
        "--html",
        "--export-scene",
        "--export-graph",
    ];
    let (mut drawn, mut twins, mut exits) = (Vec::new(), 0, [0; 3]);
    for case in 0..40 {
        let dir = temp_dir_made("fuzz-outputs", &format!("case-{case}"));
        let input = dir.join("feedback-cell.json");
        std::fs::copy(shipped("feedback-cell.json"), &input).unwrap();
        let count = rng.random_range(1..=3);
        let mut chosen: Vec<&str> = options.choose_multiple(&mut rng, count).copied().collect();
        chosen.sort();
        let mut targets: Vec<(&str, Target)> = chosen
            .iter()
            .enumerate()
            .map(|(k, &option)| {
                let kind = *KINDS.choose(&mut rng).unwrap();
                (option, make(kind, &dir, k, &input))
            })
            .collect();
        // Now and then two options name one file.
        let plain = [Kind::New, Kind::Old, Kind::Link, Kind::HardLinked];
        if targets.len() > 1 && plain.contains(&targets[0].1.kind) && rng.random_bool(0.3) {
            let twin = targets[0].1.path.clone();
            let replaced = std::mem::replace(
                &mut targets[1].1,
                Target {
                    kind: Kind::Input,
                    path: twin,
                    content: None,
                    reader: None,
                },
            );
            if let Some((thread, over)) = replaced.reader {
                over.store(true, Ordering::SeqCst);
                thread.join().unwrap();
            }
            twins += 1;
        }
        let input_before = std::fs::read(&input).unwrap();
        let mut args = vec!["solve".to_owned(), input.to_string_lossy().into_owned()];
        for (option, t) in &targets {
            args.push(option.to_string());
            args.push(t.path.to_string_lossy().into_owned());
        }
        let out = run_bounded(&args, Duration::from_secs(60));
        let kinds: Vec<Kind> = targets.iter().map(|(_, t)| t.kind).collect();
        drawn.extend(kinds.iter().copied());
        if let Some(code @ 0..=2) = out.status.code() {
            exits[code as usize] += 1;
        }
        let name = format!("case {case}: {kinds:?}");
        let refused_first = kinds.iter().any(|k| k.refused_first());
        let refused = refused_first || kinds.contains(&Kind::FifoUnread);
        let stderr = String::from_utf8_lossy(&out.stderr);
        match refused {
            true => {
                assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
                assert!(stderr.starts_with("error: "), "{name}: {stderr}");
            }
            false => assert_eq!(out.status.code(), Some(0), "{name}: {stderr}"),
        }
        // The input is never touched.
        assert_eq!(std::fs::read(&input).unwrap(), input_before, "{name}");
        for (option, t) in &mut targets {
            let text = match (t.reader.take(), &t.content) {
                (Some((thread, over)), _) => {
                    over.store(true, Ordering::SeqCst);
                    String::from_utf8(thread.join().unwrap()).unwrap()
                }
                (None, Some(content)) => std::fs::read_to_string(content).unwrap_or_default(),
                (None, None) => continue,
            };
            let written = text != "old" && !text.is_empty();
            if refused_first {
                assert!(!written, "{name}: {option} written");
                continue;
            }
            if !refused {
                assert!(written, "{name}: {option} ({:?}) not written", t.kind);
            }
            // Written whole or not at all.
            if written {
                let whole = match *option {
                    "--svg" | "--gantt" => text.trim_end().ends_with("</svg>"),
                    "--html" => text.trim_end().ends_with("</html>"),
                    _ => serde_json::from_str::<serde_json::Value>(&text).is_ok(),
                };
                assert!(whole, "{name}: {option} half-written");
            }
            match t.kind {
                Kind::Link => assert!(t.path.is_symlink(), "{name}: the link was replaced"),
                Kind::HardLinked => assert_eq!(
                    std::fs::read_to_string(&t.path).unwrap(),
                    text,
                    "{name}: the hard link was split"
                ),
                _ => {}
            }
        }
        // No temporary file is left behind.
        let left: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with(".workcell-"))
            .collect();
        assert!(left.is_empty(), "{name}: left {left:?}");
    }
    // Not vacuous: every kind drawn, both outcomes seen, two options on one file.
    assert!(KINDS.iter().all(|k| drawn.contains(k)), "{drawn:?}");
    assert!(
        exits[0] >= 8 && exits[2] >= 8 && twins >= 1,
        "{exits:?}, {twins} twins"
    );
}

fn hostile_name(rng: &mut ChaCha8Rng, k: usize) -> String {
    let mut name: String = (0..rng.random_range(1..=5))
        .map(|_| *NAME_FRAGMENTS.choose(rng).unwrap())
        .collect();
    // Unique, whatever the fragments drawn.
    name.push_str(&format!("#{k}"));
    name
}

#[test]
fn hostile_names_never_break_an_output() {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let base: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(shipped("feedback-cell.json")).unwrap())
            .unwrap();
    let dir = temp_dir_made("fuzz-outputs", "names");
    let outputs = |dir: &Path, cell: &Path| -> (Output, [String; 3]) {
        let files = ["p.svg", "g.svg", "v.html"].map(|f| dir.join(f));
        for f in &files {
            let _ = std::fs::remove_file(f);
        }
        let mut args = vec!["solve".to_owned(), cell.to_string_lossy().into_owned()];
        for (option, f) in ["--svg", "--gantt", "--html"].iter().zip(&files) {
            args.push(option.to_string());
            args.push(f.to_string_lossy().into_owned());
        }
        let out = run_bounded(&args, Duration::from_secs(60));
        let texts = files.map(|f| std::fs::read_to_string(f).unwrap_or_default());
        (out, texts)
    };
    // The pages of the cell as shipped: the markers a page has of its own.
    let plain = dir.join("plain.json");
    std::fs::write(&plain, base.to_string()).unwrap();
    let (out, texts) = outputs(&dir, &plain);
    assert_eq!(out.status.code(), Some(0));
    let own = texts.each_ref().map(|t| markers(t));
    let (mut accepted, mut refused) = (0, 0);
    for case in 0..16 {
        let mut doc = base.clone();
        let mut names = Vec::new();
        let mut control = None;
        let mut k = 0;
        for list in ["robots", "obstacles", "tasks"] {
            let n = doc[list].as_array().unwrap().len();
            for i in 0..n {
                let mut name = hostile_name(&mut rng, k);
                k += 1;
                if control.is_none() && rng.random_bool(0.03) {
                    name.insert_str(0, NAME_CONTROLS.choose(&mut rng).unwrap());
                    control = Some(format!("{list}[{i}].name"));
                }
                doc[list][i]["name"] = serde_json::Value::String(name.clone());
                names.push(name);
            }
        }
        // Tasks name their robots: keep those names in step.
        let robot_names: Vec<String> = doc["robots"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r["name"].as_str().unwrap().to_owned())
            .collect();
        for task in doc["tasks"].as_array_mut().unwrap() {
            if let Some(list) = task.get_mut("robots").and_then(|r| r.as_array_mut()) {
                for r in list.iter_mut() {
                    let old = base["robots"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .position(|b| b["name"] == *r)
                        .unwrap();
                    *r = serde_json::Value::String(robot_names[old].clone());
                }
            }
        }
        let cell = dir.join(format!("case-{case}.json"));
        std::fs::write(&cell, doc.to_string()).unwrap();
        let (out, texts) = outputs(&dir, &cell);
        let stderr = String::from_utf8_lossy(&out.stderr);
        if let Some(field) = control {
            assert_eq!(out.status.code(), Some(2), "case {case}: {stderr}");
            assert!(
                stderr.contains(&field),
                "case {case}: {stderr} should name {field}"
            );
            assert!(texts.iter().all(String::is_empty), "case {case}: written");
            refused += 1;
            continue;
        }
        assert_eq!(out.status.code(), Some(0), "case {case}: {stderr}");
        accepted += 1;
        for (file, (text, own)) in texts.iter().zip(&own).enumerate() {
            assert_eq!(&markers(text), own, "case {case}: a name forged markup");
            assert!(
                !text
                    .chars()
                    .any(|c| c.is_control() && !matches!(c, '\n' | '\t' | '\r')),
                "case {case}: a control character in an output"
            );
            // In a page's script data `&` is plain text; in SVG it starts an entity.
            let raw: &[char] = if file < 2 { &['<', '&'] } else { &['<'] };
            for name in &names {
                if name.contains(raw) {
                    assert!(!text.contains(name.as_str()), "case {case}: {name:?} raw");
                }
            }
        }
    }
    assert!(
        accepted >= 8 && refused >= 1,
        "{accepted} accepted, {refused} refused"
    );
}
