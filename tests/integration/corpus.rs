//! The checker agrees with every scene of the independently computed corpus: same verdict,
//! same pair, first contact within 1e-6 of the horizon's length.
//!
//! The corpus is vendored in tests/corpus; when the shared corpus sits beside the
//! repository (../shared/corpus-sample, as in CI), it is checked too.

use serde::Deserialize;
use std::path::{Path, PathBuf};
use workcell::cell::load_scene;
use workcell::collision::{check, CheckOptions, CheckReport, Method};

#[derive(Deserialize)]
struct Truth {
    file: String,
    category: String,
    collision: bool,
    first_contact_time: Option<f64>,
    bodies: Option<[String; 2]>,
    horizon: [f64; 2],
}

fn corpora() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut dirs = vec![root.join("tests/corpus")];
    let shared = root.join("../shared/corpus-sample");
    if shared.join("truth.jsonl").is_file() {
        dirs.push(shared);
    }
    dirs
}

fn truths(dir: &Path) -> Vec<Truth> {
    let text = std::fs::read_to_string(dir.join("truth.jsonl")).unwrap();
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

fn run(dir: &Path, t: &Truth, method: Method) -> CheckReport {
    let loaded = load_scene(&dir.join(&t.file)).unwrap_or_else(|e| panic!("{e}"));
    check(
        &loaded.scene,
        &CheckOptions {
            method,
            ..CheckOptions::default()
        },
    )
}

/// Why `r` disagrees with `t`, if it does.
fn disagreement(t: &Truth, r: &CheckReport) -> Option<String> {
    if r.collision != t.collision {
        return Some(format!(
            "verdict {} instead of {}",
            r.collision, t.collision
        ));
    }
    let (Some(c), Some(time), Some(bodies)) = (&r.first_contact, t.first_contact_time, &t.bodies)
    else {
        return None;
    };
    let tol = 1e-6 * (t.horizon[1] - t.horizon[0]);
    if (c.time - time).abs() > tol {
        return Some(format!(
            "first contact at {} instead of {time} (tolerance {tol})",
            c.time
        ));
    }
    // Two robots may come in either order; a robot and an obstacle name the robot first.
    let swapped = [bodies[1].clone(), bodies[0].clone()];
    let same = c.bodies == *bodies || (!bodies[1].starts_with("obstacle") && c.bodies == swapped);
    (!same).then(|| format!("pair {:?} instead of {bodies:?}", c.bodies))
}

#[test]
fn agrees_with_every_corpus_scene() {
    let mut checked = 0;
    let mut failures = Vec::new();
    for dir in corpora() {
        for t in truths(&dir) {
            let r = run(&dir, &t, Method::DEFAULT);
            if let Some(why) = disagreement(&t, &r) {
                failures.push(format!(
                    "{}: {} ({}): {why}",
                    dir.display(),
                    t.file,
                    t.category
                ));
            }
            if let Some(c) = &r.first_contact {
                assert!(
                    r.safe_until <= c.time && c.time - r.safe_until <= r.time_tol,
                    "{}: safe_until {} vs contact {}",
                    t.file,
                    r.safe_until,
                    c.time
                );
                assert!(
                    c.distance < r.delta,
                    "{}: contact without a witness",
                    t.file
                );
            } else {
                // The whole horizon: the scene's own (its largest `t`, exactly), which the
                // truth file states to within rounding of its generator.
                assert_eq!(r.safe_until, r.horizon[1], "{}", t.file);
                let ulps =
                    (r.horizon[1] - t.horizon[1]).abs() / (f64::EPSILON * t.horizon[1].abs());
                assert!(
                    ulps <= 2.0,
                    "{}: horizon {} vs {}",
                    t.file,
                    r.horizon[1],
                    t.horizon[1]
                );
            }
            if !r.certified {
                failures.push(format!(
                    "{}: {}: not certified: {:?}",
                    dir.display(),
                    t.file,
                    r.stats
                ));
            }
            checked += 1;
        }
    }
    assert!(checked >= 48, "only {checked} corpus scenes found");
    assert!(
        failures.is_empty(),
        "{} disagreements:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn the_papers_velocity_bound_misses_an_inconsistent_velocity_collision() {
    // The point of the rigorous bound: with velocities that disagree with the positions,
    // eq. (12) underestimates the motion and certifies a colliding interval.
    let dir = &corpora()[0];
    let missed: Vec<String> = truths(dir)
        .iter()
        .filter(|t| t.collision && t.category == "g-bad-velocities")
        .filter(|t| !run(dir, t, Method::Adaptive(workcell::motion::BoundKind::Paper)).collision)
        .map(|t| t.file.clone())
        .collect();
    assert!(
        !missed.is_empty(),
        "the paper's bound found every collision of the corpus"
    );
}

#[test]
fn result_does_not_depend_on_the_number_of_threads() {
    let dir = &corpora()[0];
    for t in truths(dir)
        .iter()
        .filter(|t| t.category == "e-multi-obstacles")
    {
        let reports: Vec<CheckReport> = [1, 2, 4]
            .iter()
            .map(|&n| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .unwrap()
                    .install(|| run(dir, t, Method::DEFAULT))
            })
            .collect();
        assert_eq!(reports[0], reports[1], "{}", t.file);
        assert_eq!(reports[0], reports[2], "{}", t.file);
    }
}

/// Halls large enough for the parallel broad phase, free and colliding: the same report on
/// 1, 2 and 4 threads, and from a thread outside any pool.
#[test]
fn halls_do_not_depend_on_the_number_of_threads() {
    use workcell::generate::{generate_scene, Kind};
    for (seed, n) in [(1, 100), (2, 400)] {
        let mut hall = generate_scene(Kind::Hall, seed, 0, n);
        let opts = CheckOptions {
            per_pair: true,
            ..CheckOptions::default()
        };
        let colliding = check(&hall, &opts);
        let contact = colliding
            .first_contact
            .clone()
            .expect("halls this size collide");
        // Without the robot of the first contact, another contact or none.
        hall.bodies.retain(|b| b.name != contact.bodies[0]);
        for scene in [generate_scene(Kind::Hall, seed, 0, n), hall] {
            let outside = check(&scene, &opts);
            assert!(outside.pairs_pruned > 0);
            for threads in [1, 2, 4] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let inside = pool.install(|| check(&scene, &opts));
                assert_eq!(inside, outside, "{n} robots on {threads} threads");
            }
        }
    }
}

/// Every kind of `workcell generate` ends certified, colliding or not: none is built to
/// graze δ. Before grazes were searched again when a contact followed them, 14 of the 300
/// pairs, bad-velocities and large-coordinates scenes of seeds 2 and 3 were not certified:
/// the pair grazed just before its contact. The README's table of how often each kind ends
/// certified is printed by
/// `cargo test --release --test integration corpus::every_generated_kind_ends_certified -- --nocapture`.
#[test]
fn every_generated_kind_ends_certified() {
    use workcell::generate::{generate_scene, Kind};
    const SEEDS: [u64; 3] = [1, 2, 3];
    const COUNT: u64 = 30;
    let mut failures = Vec::new();
    eprintln!("| kind | scenes | colliding | certified |");
    eprintln!("| --- | ---: | ---: | ---: |");
    for kind in Kind::ALL {
        let (mut colliding, mut certified) = (0, 0);
        for seed in SEEDS {
            for k in 0..COUNT {
                let r = check(&generate_scene(kind, seed, k, 10), &CheckOptions::default());
                colliding += usize::from(r.collision);
                // The proven prefix ends within the time tolerance before the contact.
                if let Some(c) = &r.first_contact {
                    let gap = c.time - r.safe_until;
                    if !(0.0..=r.time_tol * (1.0 + 1e-9)).contains(&gap) {
                        failures.push(format!(
                            "{}-{seed}-{k}: safe_until {gap} before",
                            kind.name()
                        ));
                    }
                }
                certified += usize::from(r.certified);
                if !r.certified {
                    failures.push(format!("{}-{seed}-{k}: {:?}", kind.name(), r.stats));
                }
            }
        }
        let scenes = SEEDS.len() * COUNT as usize;
        eprintln!(
            "| `{}` | {scenes} | {colliding} | {certified} |",
            kind.name()
        );
    }
    assert!(
        failures.is_empty(),
        "not certified:\n{}",
        failures.join("\n")
    );
}
