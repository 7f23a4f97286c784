//! A bounded, seeded, structure-aware fuzz test of the scene, cell and sequences readers
//! (issue 13, item 19): mutations of the shipped files in `cells/` (wrong types, NaN, ∞,
//! 1e308 and subnormal numbers, arrays for objects, empty and one-vertex shapes, repeated
//! and unsorted times, huge counts, missing fields, cut text), each run through its reader
//! and what follows it. The invariant is in `fuzz_support`: no panic, and either a result
//! or a refusal naming the file and a field.
//!
//! Every input that ever failed, here or under `cargo fuzz` (see `fuzz/`), is kept in
//! `tests/fuzz/<kind>/` and replayed first. A failing case is also written to
//! `target/fuzz-failures/` to be kept there.

mod fuzz_support;

use fuzz_support::{exercise, feedback_cell, mutated, Kind, FEEDBACK_RESULT, SHIPPED};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde_json::Value;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

/// The seed of the mutations: the same cases on every run. `WORKCELL_FUZZ_SEED` sets
/// another for a longer search by hand (with `WORKCELL_FUZZ_CASES`); CI uses this one.
const SEED: u64 = 13;

/// Mutated inputs per shipped file (about 8 s in all, release build).
const CASES_PER_FILE: usize = 400;

fn setting(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Runs one case; on failure, keeps the input under `target/fuzz-failures/` and says where.
/// Panics are caught and reported together, so the default hook's message for each is
/// silenced.
fn run(kind: Kind, text: &str, name: &str) -> Result<(), String> {
    static QUIET: std::sync::Once = std::sync::Once::new();
    QUIET.call_once(|| std::panic::set_hook(Box::new(|_| {})));
    let cells = root().join("cells");
    let feedback = feedback_cell(&cells);
    let file = PathBuf::from(format!("{name}.json"));
    let outcome = catch_unwind(AssertUnwindSafe(|| exercise(kind, text, &file, &feedback)));
    outcome.map_err(|panic| {
        let why = panic
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        let kept = root()
            .join("target/fuzz-failures")
            .join(kind.name())
            .join(format!("{name}.json"));
        std::fs::create_dir_all(kept.parent().unwrap()).unwrap();
        std::fs::write(&kept, text).unwrap();
        format!("{name} ({kind:?}): {why}; input kept as {}", kept.display())
    })
}

/// Fails with every failure, the default panic hook back in place to say so.
fn report(failures: &[String]) {
    if !failures.is_empty() {
        drop(std::panic::take_hook());
        panic!("{} failures:\n{}", failures.len(), failures.join("\n"));
    }
}

#[test]
fn every_kept_regression_input_holds() {
    let mut failures = Vec::new();
    let mut count = 0;
    for kind in [Kind::Scene, Kind::Cell, Kind::Sequences] {
        let folder = root().join("tests/fuzz").join(kind.name());
        let mut files: Vec<PathBuf> = std::fs::read_dir(&folder)
            .unwrap_or_else(|e| panic!("{}: {e}", folder.display()))
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "json"))
            .collect();
        files.sort();
        for path in files {
            let text = std::fs::read_to_string(&path).unwrap();
            let name = path.file_stem().unwrap().to_string_lossy().into_owned();
            count += 1;
            if let Err(e) = run(kind, &text, &name) {
                failures.push(e);
            }
        }
    }
    assert!(count > 0, "no regression inputs found");
    report(&failures);
}

#[test]
fn mutated_shipped_files_are_read_or_refused_cleanly() {
    let seed = setting("WORKCELL_FUZZ_SEED", SEED);
    let cases = setting("WORKCELL_FUZZ_CASES", CASES_PER_FILE as u64) as usize;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut bases: Vec<(String, Kind, Value)> = SHIPPED
        .iter()
        .map(|&(file, kind)| {
            let text = std::fs::read_to_string(root().join("cells").join(file)).unwrap();
            (
                file.trim_end_matches(".json").to_owned(),
                kind,
                serde_json::from_str(&text).unwrap(),
            )
        })
        .collect();
    bases.push((
        "feedback-result".into(),
        Kind::Sequences,
        serde_json::from_str(FEEDBACK_RESULT).unwrap(),
    ));
    bases.push((
        "feedback-sequences".into(),
        Kind::Sequences,
        serde_json::json!({"R1": ["weld-2", "weld-3", "weld-1"], "R2": ["weld-4"]}),
    ));
    let mut failures = Vec::new();
    for (name, kind, base) in &bases {
        for case in 0..cases {
            let text = mutated(base, &mut rng);
            if let Err(e) = run(*kind, &text, &format!("{name}-seed{seed}-case{case}")) {
                failures.push(e);
            }
        }
    }
    report(&failures);
}

/// The narrow-phase disagreements `cargo fuzz run narrow_phase` found (nearly parallel long
/// edges, issue 13, item 1): the walk must agree with the brute force within 10⁻⁹ of the
/// shapes' size.
#[test]
fn kept_narrow_phase_cases_agree_with_brute_force() {
    use workcell::geometry::{brute_force_distance, closest_features, ConvexPolygon, Posed};
    let folder = root().join("tests/fuzz/narrow_phase");
    let mut failures = Vec::new();
    for entry in std::fs::read_dir(&folder).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|x| x != "json") {
            continue;
        }
        let case: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let shape = |key: &str| {
            let points: Vec<[f64; 2]> = serde_json::from_value(case[key].clone()).unwrap();
            ConvexPolygon::new(&points).unwrap().0
        };
        let (a, b) = (shape("a"), shape("b"));
        let pose = |key: &str| -> [f64; 3] { serde_json::from_value(case[key].clone()).unwrap() };
        let ([xa, ya, ta], [xb, yb, tb]) = (pose("pose_a"), pose("pose_b"));
        let (pa, pb) = (Posed::new(&a, xa, ya, ta), Posed::new(&b, xb, yb, tb));
        let exact = brute_force_distance(&pa, &pb).distance;
        let walk = closest_features(&pa, &pb, None, &Default::default()).distance;
        let scale =
            1.0 + a.radius() + b.radius() + xa.abs().max(ya.abs()).max(xb.abs()).max(yb.abs());
        if (walk - exact).abs() > 1e-9 * scale {
            failures.push(format!(
                "{}: walk {walk:e}, exact {exact:e}",
                path.display()
            ));
        }
    }
    report(&failures);
}

/// Seeded hostile names through the reader, the check and both drawings
/// (`fuzz_support::exercise_names`, the `names` target of `fuzz/`).
#[cfg(feature = "cli")]
#[test]
fn hostile_names_are_refused_or_drawn_escaped() {
    use rand::seq::IndexedRandom;
    use rand::Rng;
    let mut rng = ChaCha8Rng::seed_from_u64(setting("WORKCELL_FUZZ_SEED", SEED));
    let name = |rng: &mut ChaCha8Rng| -> String {
        let n = rng.random_range(0..=4);
        let all: Vec<&str> = fuzz_support::NAME_FRAGMENTS
            .iter()
            .chain(&fuzz_support::NAME_CONTROLS)
            .copied()
            .collect();
        (0..n).map(|_| *all.choose(rng).unwrap()).collect()
    };
    for _ in 0..setting("WORKCELL_FUZZ_CASES", 300) {
        let names = [name(&mut rng), name(&mut rng), name(&mut rng)];
        fuzz_support::exercise_names([&names[0], &names[1], &names[2]]);
    }
}
