//! `workcell generate`: deterministic files in the scene format, and the kinds whose verdict
//! is known by construction checked against the checker and an independent dense sampling.

use crate::common::{exact_distance, place, pose_at, Pt};
#[cfg(feature = "cli")]
use crate::common::{temp_dir_absent, workcell};
use serde_json::Value;
use std::path::Path;
use workcell::cell::{check_precision, parse_scene, scene_document};
use workcell::collision::{check, CheckOptions, CheckReport};
use workcell::generate::{generate_scene, Kind};

/// Scene `k` as the command writes it.
fn text(kind: Kind, seed: u64, k: u64, robots: usize) -> String {
    let scene = generate_scene(kind, seed, k, robots);
    serde_json::to_string_pretty(&scene_document(&scene)).unwrap() + "\n"
}

/// Parses, checks the precision limit, and checks.
fn parse_and_check(text: &str, name: &str) -> CheckReport {
    let path = Path::new(name);
    let loaded = parse_scene(text, path).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(loaded.warnings.is_empty(), "{name}: {:?}", loaded.warnings);
    check_precision(&loaded.scene, loaded.scene.delta, path)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    check(&loaded.scene, &CheckOptions::default())
}

/// The two robots of a file, read straight from the JSON: (body-frame shape, samples
/// `[t, x, y, theta]`).
fn robots(text: &str) -> Vec<(Vec<Pt>, Vec<[f64; 4]>)> {
    let doc: Value = serde_json::from_str(text).unwrap();
    let num = |v: &Value, f: &str| v[f].as_f64().unwrap();
    doc["robots"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            let shape = r["shape"].as_array().unwrap().iter();
            let shape = shape.map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()]);
            let samples = r["trajectory"].as_array().unwrap().iter();
            let samples = samples.map(|s| [num(s, "t"), num(s, "x"), num(s, "y"), num(s, "theta")]);
            (shape.collect(), samples.collect())
        })
        .collect()
}

/// The distance of the two robots at time t.
fn distance_at(robots: &[(Vec<Pt>, Vec<[f64; 4]>)], t: f64) -> f64 {
    let [a, b] = [0, 1].map(|i| place(&robots[i].0, pose_at(&robots[i].1, t)));
    exact_distance(&a, &b)
}

#[cfg(feature = "cli")]
#[test]
fn same_arguments_give_the_same_bytes_and_seeds_differ() {
    for kind in Kind::ALL {
        for k in 0..3 {
            assert_eq!(text(kind, 7, k, 5), text(kind, 7, k, 5), "{}", kind.name());
            assert_ne!(text(kind, 7, k, 5), text(kind, 8, k, 5), "{}", kind.name());
            assert_ne!(
                text(kind, 7, k, 5),
                text(kind, 7, k + 1, 5),
                "{}",
                kind.name()
            );
        }
    }
    let (a, b) = (
        temp_dir_absent("gen", "same-a"),
        temp_dir_absent("gen", "same-b"),
    );
    for dir in [&a, &b] {
        let out = workcell(
            &["generate", "--kind", "pairs", "--seed", "3", "--count", "4"]
                .into_iter()
                .chain(["--out", dir.to_str().unwrap()])
                .collect::<Vec<_>>(),
        );
        assert_eq!(out.status.code(), Some(0));
    }
    for k in 0..4 {
        let name = format!("pairs-3-{k}.json");
        let (x, y) = (std::fs::read(a.join(&name)), std::fs::read(b.join(&name)));
        assert_eq!(x.unwrap(), y.unwrap(), "{name}");
    }
}

#[test]
fn every_kind_parses_and_checks() {
    for kind in Kind::ALL {
        let mut collisions = 0;
        for k in 0..10 {
            let name = format!("{}-11-{k}.json", kind.name());
            let report = parse_and_check(&text(kind, 11, k, 10), &name);
            assert_eq!(report.delta, kind.delta(), "{name}");
            collisions += usize::from(report.collision);
        }
        eprintln!("{}: {collisions}/10 collide", kind.name());
    }
}

#[test]
fn pairs_use_different_time_grids_and_4_to_8_vertices() {
    for k in 0..10 {
        let t = text(Kind::Pairs, 5, k, 0);
        let r = robots(&t);
        assert_eq!(r.len(), 2);
        assert_ne!(r[0].1.len(), r[1].1.len());
        for (shape, _) in &r {
            assert!((4..=8).contains(&shape.len()));
        }
    }
}

#[test]
fn tunnelling_always_collides_and_no_sample_shows_it() {
    for k in 0..30 {
        let name = format!("tunnelling-{k}");
        let t = text(Kind::Tunnelling, 1, k, 0);
        let report = parse_and_check(&t, &name);
        assert!(report.collision, "{name}");
        let r = robots(&t);
        let delta = Kind::Tunnelling.delta();
        for time in r.iter().flat_map(|(_, s)| s.iter().map(|s| s[0])) {
            assert!(
                distance_at(&r, time) >= delta,
                "{name}: contact at sample {time}"
            );
        }
    }
}

#[test]
fn near_miss_is_certified_free_and_its_closest_approach_is_between_samples() {
    let delta = Kind::NearMiss.delta();
    for k in 0..30 {
        let name = format!("near-miss-{k}");
        let t = text(Kind::NearMiss, 1, k, 0);
        let report = parse_and_check(&t, &name);
        assert!(!report.collision && report.certified, "{name}: {report:?}");
        let r = robots(&t);
        let (t0, t1) = (r[0].1[0][0], r[0].1[r[0].1.len() - 1][0]);
        let dense = (0..=20_000)
            .map(|i| distance_at(&r, t0 + (t1 - t0) * i as f64 / 20_000.0))
            .fold(f64::INFINITY, f64::min);
        assert!(
            (1.5 * delta..=5.0 * delta).contains(&dense),
            "{name}: closest approach {dense}"
        );
        let at_samples = r
            .iter()
            .flat_map(|(_, s)| s.iter().map(|s| distance_at(&r, s[0])))
            .fold(f64::INFINITY, f64::min);
        assert!(
            at_samples > dense + delta,
            "{name}: {at_samples} at a sample"
        );
    }
}

#[test]
fn hall_has_the_requested_robots_with_100_samples() {
    let t = text(Kind::Hall, 2, 0, 50);
    let doc: Value = serde_json::from_str(&t).unwrap();
    let robots = doc["robots"].as_array().unwrap();
    assert_eq!(robots.len(), 50);
    for r in robots {
        assert_eq!(r["trajectory"].as_array().unwrap().len(), 100);
    }
    assert!(!doc["obstacles"].as_array().unwrap().is_empty());
    parse_and_check(&t, "hall-2-0.json");
}

#[cfg(feature = "cli")]
#[test]
fn cli_writes_files_and_prints_them() {
    let dir = temp_dir_absent("gen", "cli").join("nested");
    let out = workcell(&[
        "generate",
        "--kind",
        "hall",
        "--seed",
        "9",
        "--robots",
        "12",
        "--count",
        "3",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 3);
    for k in 0..3 {
        let file = dir.join(format!("hall-9-{k}.json"));
        assert!(stdout.contains(file.to_str().unwrap()));
        assert_eq!(
            std::fs::read_to_string(&file).unwrap(),
            text(Kind::Hall, 9, k, 12)
        );
    }
    // Default count: 10.
    let dir = temp_dir_absent("gen", "cli-default");
    let out = workcell(
        &["generate", "--kind", "near-miss", "--seed", "1", "--out"]
            .into_iter()
            .chain([dir.to_str().unwrap()])
            .collect::<Vec<_>>(),
    );
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 10);
    // `all`: every kind, with --robots for the halls.
    let dir = temp_dir_absent("gen", "cli-all");
    let out = workcell(&[
        "generate",
        "--kind",
        "all",
        "--seed",
        "4",
        "--count",
        "2",
        "--robots",
        "5",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        2 * Kind::ALL.len()
    );
    for kind in Kind::ALL {
        let file = dir.join(format!("{}-4-1.json", kind.name()));
        assert_eq!(std::fs::read_to_string(&file).unwrap(), text(kind, 4, 1, 5));
    }
}

#[cfg(feature = "cli")]
#[test]
fn cli_errors_exit_2_and_name_the_path() {
    let out = workcell(&["generate", "--kind", "nope", "--seed", "1", "--out", "x"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("nope"));
    // A folder under a regular file cannot be created, even by root.
    let dir = temp_dir_absent("gen", "unwritable");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("file"), "").unwrap();
    let bad = dir.join("file").join("out");
    let out = workcell(
        &["generate", "--kind", "pairs", "--seed", "1"]
            .into_iter()
            .chain(["--out", bad.to_str().unwrap()])
            .collect::<Vec<_>>(),
    );
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains(bad.to_str().unwrap()), "{stderr}");
    // --robots belongs to hall alone.
    let out = workcell(
        &[
            "generate", "--kind", "pairs", "--seed", "1", "--robots", "3",
        ]
        .into_iter()
        .chain(["--out", dir.to_str().unwrap()])
        .collect::<Vec<_>>(),
    );
    assert_eq!(out.status.code(), Some(2));
}

#[cfg(feature = "cli")]
#[test]
fn cli_writes_conflict_cells_of_every_family() {
    let dir = temp_dir_absent("gen", "cli-conflict");
    let args = |d: &std::path::Path| {
        workcell(&[
            "generate",
            "--kind",
            "conflict",
            "--seed",
            "3",
            "--count",
            "2",
            "--out",
            d.to_str().unwrap(),
        ])
    };
    let out = args(&dir);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    let families = workcell::generate::ConflictKind::ALL.len();
    assert_eq!(stdout.lines().count(), 2 * families);
    let again = temp_dir_absent("gen", "cli-conflict-again");
    assert_eq!(args(&again).status.code(), Some(0));
    for family in workcell::generate::ConflictKind::ALL {
        for k in 0..2 {
            let name = format!("{}-3-{k}-cell.json", family.name());
            let text = std::fs::read_to_string(dir.join(&name)).unwrap();
            assert_eq!(text, std::fs::read_to_string(again.join(&name)).unwrap());
            let loaded = workcell::cell::parse_cell(&text, std::path::Path::new(&name));
            assert!(loaded.is_ok(), "{name}: {:?}", loaded.err());
        }
    }
    // A cell file is not a scene: `compare` skips `*-cell.json` in folders.
    let one = temp_dir_absent("gen", "cli-conflict-one");
    let out = workcell(&[
        "generate",
        "--kind",
        "doorway",
        "--seed",
        "3",
        "--count",
        "1",
        "--out",
        one.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0));
    assert!(one.join("doorway-3-0-cell.json").exists());
}
