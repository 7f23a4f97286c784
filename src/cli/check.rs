//! `workcell check`: certify a scene or find its first contact.

use std::io::Write;
use std::path::Path;
use std::process::ExitCode;
use std::time::{Duration, Instant};
use workcell::cell::{check_precision, check_time_resolution, load_scene, InputError};
use workcell::collision::{check, validate, CheckOptions, CheckReport, Verdict};

/// Exit status when a pair spent its work budget before a proof or a witness.
const EXIT_UNRESOLVED: u8 = 3;

/// Runs the check; the exit status is 0 collision-free, 1 collision, 3 unresolved within
/// the work budget. `html` and `svg`: the animated page and the still picture of the scene,
/// written after the check.
pub fn run_check(
    path: &Path,
    json: bool,
    opts: &CheckOptions,
    (html, svg): (Option<&Path>, Option<&Path>),
) -> Result<ExitCode, InputError> {
    let outputs: Vec<(&str, &Path)> = [("--html", html), ("--svg", svg)]
        .into_iter()
        .filter_map(|(option, file)| Some((option, file?)))
        .collect();
    super::output::check_outputs(&[path], &outputs)?;
    let loaded = load_scene(path)?;
    check_precision(
        &loaded.scene,
        opts.delta.unwrap_or(loaded.scene.delta),
        path,
    )?;
    validate(&loaded.scene, opts).map_err(|e| e.in_file(path))?;
    let time_tol = opts.time_tol_for(loaded.scene.horizon());
    check_time_resolution(&loaded.scene, time_tol, path)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    // Start the thread pool before the clock: the run time is the check's alone.
    let threads = rayon::current_num_threads();
    let start = Instant::now();
    let report = check(&loaded.scene, opts);
    let elapsed = start.elapsed();
    let text = if json {
        serde_json::to_string_pretty(&report).expect("a report always serialises") + "\n"
    } else {
        summary(path, &report, opts, elapsed, threads)
    };
    // A closed pipe (`| head`) is the reader's choice, not an error of ours.
    let _ = std::io::stdout().write_all(text.as_bytes());
    if !outputs.is_empty() {
        let model = workcell::view::Model::of_check(path, &loaded.scene, &report);
        if let Some(file) = html {
            super::output::write_file(file, workcell::view::html(&model).as_bytes())?;
        }
        if let Some(file) = svg {
            super::output::write_file(file, workcell::view::picture(&model).as_bytes())?;
        }
    }
    if report.stats.unresolved > 0 {
        return Err(InputError {
            file: path.to_path_buf(),
            body: None,
            field: String::new(),
            reason: format!(
                "{} could not be resolved in f64 at these coordinates: no proof",
                super::counted(report.stats.unresolved, "interval")
            ),
        });
    }
    Ok(ExitCode::from(match report.verdict() {
        Verdict::Free { .. } => 0,
        Verdict::Contact { .. } => 1,
        Verdict::Unresolved { .. } => EXIT_UNRESOLVED,
    }))
}

fn summary(
    path: &Path,
    r: &CheckReport,
    opts: &CheckOptions,
    elapsed: Duration,
    threads: usize,
) -> String {
    let mut out = String::new();
    let mut line = |l: String| {
        out.push_str(&l);
        out.push('\n');
    };
    let proof = proof(r, opts);
    verdict_lines(path, r, opts, &proof, &mut line);
    let s = &r.stats;
    line(format!(
        "intervals {}, bisections {}, narrow-phase calls {}, feature steps {}, walk fallbacks {}, convexity certificates {}",
        s.intervals, s.bisections, s.narrow_phase_calls, s.feature_steps, s.walk_fallbacks, s.convexity_certificates
    ));
    for p in r.pair_stats.iter().flatten() {
        let s = &p.stats;
        line(format!(
            "  {} - {}: {} of {} merged intervals, bisections {}, narrow-phase calls {}, feature steps {}",
            p.bodies[0], p.bodies[1], s.intervals, p.merged_intervals, s.bisections, s.narrow_phase_calls, s.feature_steps
        ));
    }
    if s.grazing > 0 {
        line(format!(
            "NOT CERTIFIED: {} (each shorter than the time tolerance) graze delta: proven only to stay above delta*(1 - {:e})",
            super::counted(s.grazing, "interval"), opts.grazing_tol
        ));
    }
    line(format!(
        "{} checked ({} more pruned by the broad phase) in {:.3} ms on {}",
        super::counted(r.pairs as u64, "pair"),
        r.pairs_pruned,
        elapsed.as_secs_f64() * 1e3,
        super::counted(threads as u64, "thread")
    ));
    out
}

/// What a verdict of free rests on: a proof, a proof up to grazes, or nothing at all.
fn proof(r: &CheckReport, opts: &CheckOptions) -> String {
    let method = opts.method;
    if !method.proves_free() {
        format!("not certified: `{method}` certifies nothing")
    } else if r.stats.unresolved > 0 {
        format!(
            "not certified: {} unresolved in f64",
            super::counted(r.stats.unresolved, "interval")
        )
    } else if r.stats.grazing > 0 {
        "NOT CERTIFIED: within the grazing allowance".to_owned()
    } else {
        "certified".to_owned()
    }
}

/// The verdict's lines: the collision, or what is proven free and until when.
fn verdict_lines(
    path: &Path,
    r: &CheckReport,
    opts: &CheckOptions,
    proof: &str,
    line: &mut impl FnMut(String),
) {
    let method = opts.method;
    match r.verdict() {
        Verdict::Unresolved { budget: b } => {
            line(format!(
                "{}: UNRESOLVED: {} and {} used their work budget ({} evaluations of the distance) at t = {} with neither a proof nor a collision",
                path.display(),
                b.bodies[0],
                b.bodies[1],
                b.work,
                time(b.time)
            ));
            line(format!(
                "collision-free until t = {} ({}), unknown after it; --max-work raises the budget",
                time(r.safe_until),
                if proof == "certified" {
                    "certified"
                } else {
                    &proof
                }
            ));
        }
        Verdict::Free { .. } if method.proves_free() => line(format!(
            "{}: collision-free over [{}, {}] (delta {}; {proof})",
            path.display(),
            r.horizon[0],
            r.horizon[1],
            r.delta
        )),
        Verdict::Free { .. } => line(format!(
            "{}: no collision found over [{}, {}] (delta {}; {proof})",
            path.display(),
            r.horizon[0],
            r.horizon[1],
            r.delta
        )),
        Verdict::Contact { contact: c, .. } => {
            line(format!(
                "{}: COLLISION between {} and {} at t = {} (merged interval {}, distance {:.6e} < delta {})",
                path.display(),
                c.bodies[0],
                c.bodies[1],
                time(c.time),
                c.interval,
                c.distance,
                r.delta
            ));
            let before = if method.proves_free() {
                "collision-free until"
            } else {
                "no collision found before"
            };
            line(format!(
                "{before} t = {} ({proof}; time tolerance {:.3e})",
                time(r.safe_until),
                r.time_tol
            ));
        }
    }
}

/// A time for people: nine decimals, or every digit f64 holds when it is huge (nine
/// significant digits would hide the time of day in a time stamp of 10¹⁴).
pub fn time(t: f64) -> String {
    if t.abs() < 1e9 {
        format!("{t:.9}")
    } else {
        format!("{t:e}")
    }
}
