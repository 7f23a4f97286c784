//! `workcell solve` and `workcell evaluate`: schedules, their checks and their exports.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use workcell::cell::{load_cell, load_sequences, scene_document, Cell, InputError};
use workcell::wcp::report::{
    collision_json, rounds_json, schedule_json, sequences_json, summary, waits_json, ResultJson,
};
use workcell::wcp::{self, Collision, Iteration, Progress, Schedule, SolveOptions};

/// Output options shared by `solve` and `evaluate`.
#[derive(clap::Args)]
pub struct Outputs {
    /// Print the result as JSON on stdout (no progress bar).
    #[arg(long)]
    json: bool,
    /// Write the schedule's trajectories as a scene, readable by `workcell check`.
    #[arg(long)]
    export_scene: Option<PathBuf>,
    /// Draw the cell, the paths and the collisions fed back as an SVG picture.
    #[arg(long)]
    svg: Option<PathBuf>,
}

/// A progress bar on stderr, shown only on a terminal and without `--json`.
struct Bar(ProgressBar);

impl Bar {
    fn new(json: bool) -> Bar {
        let bar = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr());
        if json || !std::io::stderr().is_terminal() {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        }
        Bar(bar)
    }
}

impl Progress for Bar {
    fn planning(&self, total: usize) {
        self.0.set_style(
            ProgressStyle::with_template("planning moves {bar:40} {pos}/{len} {elapsed}")
                .expect("a valid template"),
        );
        self.0.set_length(total as u64);
    }

    fn move_planned(&self) {
        self.0.inc(1);
    }

    fn iteration(&self, k: usize, makespan: f64, collision: Option<&Collision>) {
        if k == 1 {
            self.0.set_style(
                ProgressStyle::with_template("{spinner} round {msg} {elapsed}")
                    .expect("a valid template"),
            );
        }
        let verdict = if collision.is_some() {
            "collides, re-planning"
        } else {
            "collision-free"
        };
        self.0
            .set_message(format!("{k}: makespan {makespan:.3}, {verdict}"));
        self.0.tick();
    }
}

/// Solves the cell; exit status 0 collision-free, 1 none found.
pub fn run_solve(
    path: &Path,
    out: &Outputs,
    seed: u64,
    max_iterations: usize,
    export_graph: Option<&Path>,
) -> Result<ExitCode, InputError> {
    check_paths(&[path], out, export_graph)?;
    let cell = load(path)?;
    let mut opts = SolveOptions {
        max_iterations,
        ..SolveOptions::default()
    };
    opts.sequencer.seed = seed;
    let bar = Bar::new(out.json);
    // An error leaves no half-drawn bar above its message.
    let prepared = wcp::prepare(&cell, &opts, &bar).inspect_err(|_| bar.0.finish_and_clear())?;
    let mut written = Ok(());
    if let Some(file) = export_graph {
        let doc = serde_json::to_string_pretty(&prepared.graph.export(&cell))
            .expect("a graph serialises");
        written = written.and(write(file, &doc));
    }
    let solved =
        wcp::solve(&cell, &prepared, &opts, &bar).inspect_err(|_| bar.0.finish_and_clear())?;
    bar.0.finish_and_clear();
    let collisions: Vec<&Collision> = solved
        .iterations
        .iter()
        .filter_map(|i| i.collision.as_ref())
        .collect();
    let written = written.and(exports(&cell, &solved.schedule, &collisions, out));
    let final_collision = solved.iterations.last().and_then(|i| i.collision.as_ref());
    let text = if out.json {
        let (sequences, schedule) = schedule_json(&cell, &solved.schedule);
        let json = ResultJson {
            makespan: solved.schedule.makespan,
            collision_free: solved.collision_free,
            sequences,
            iterations: solved.iterations.len(),
            waits: waits_json(&cell, &solved.delays()),
            blind_sequences: Some(sequences_json(&cell, &solved.blind_routes)),
            blind_makespan: Some(solved.blind_makespan),
            blind_optimal: Some(solved.blind_optimal),
            first_collision: final_collision.map(|c| collision_json(&cell, c)),
            feedback: rounds_json(&cell, &solved.iterations),
            failure: solved.failure.clone(),
            schedule,
            check_stats: solved.report.stats,
            stages_ms: solved.times.into(),
        };
        serde_json::to_string_pretty(&json).expect("a result serialises") + "\n"
    } else {
        let mut text = format!("{}: ", path.display());
        text += &match &solved.failure {
            None => "collision-free schedule".to_owned(),
            Some(why) => format!("NO collision-free schedule: {why}"),
        };
        text += &format!(
            " ({} round{}; collision-blind makespan {:.3}{})\n",
            solved.iterations.len(),
            if solved.iterations.len() == 1 {
                ""
            } else {
                "s"
            },
            solved.blind_makespan,
            if solved.blind_optimal {
                ", proven optimal"
            } else {
                ""
            }
        );
        text + &summary(
            &cell,
            &solved.schedule,
            &solved.iterations,
            final_collision,
            solved.times,
        )
    };
    let _ = std::io::stdout().write_all(text.as_bytes());
    written?;
    Ok(ExitCode::from(u8::from(!solved.collision_free)))
}

/// Evaluates given sequences; exit status 0 collision-free, 1 the schedule collides.
pub fn run_evaluate(path: &Path, sequences: &Path, out: &Outputs) -> Result<ExitCode, InputError> {
    check_paths(&[path, sequences], out, None)?;
    let cell = load(path)?;
    let given = load_sequences(sequences, &cell)?;
    let opts = SolveOptions::default();
    let evaluated = wcp::evaluate(&cell, &given, &opts, sequences)?;
    let collisions: Vec<&Collision> = evaluated.collision.iter().collect();
    let written = exports(&cell, &evaluated.schedule, &collisions, out);
    let failure = match (&evaluated.collision, evaluated.report.certified) {
        (Some(c), _) => Some(format!(
            "the schedule collides: {}",
            wcp::describe(&cell, c)
        )),
        (None, false) => {
            Some("the checker cannot certify the schedule: two bodies graze delta".to_owned())
        }
        (None, true) => None,
    };
    let text = if out.json {
        let (sequences, schedule) = schedule_json(&cell, &evaluated.schedule);
        let json = ResultJson {
            makespan: evaluated.schedule.makespan,
            collision_free: evaluated.collision_free,
            sequences,
            iterations: 1,
            waits: waits_json(&cell, &evaluated.delays),
            blind_sequences: None,
            blind_makespan: None,
            blind_optimal: None,
            first_collision: evaluated
                .collision
                .as_ref()
                .map(|c| collision_json(&cell, c)),
            feedback: Vec::new(),
            failure: failure.clone(),
            schedule,
            check_stats: evaluated.report.stats,
            stages_ms: evaluated.times.into(),
        };
        serde_json::to_string_pretty(&json).expect("a result serialises") + "\n"
    } else {
        let verdict = failure
            .as_deref()
            .map_or("collision-free".to_owned(), |f| format!("REJECTED: {f}"));
        let rounds: [Iteration; 0] = [];
        format!("{}: {verdict}\n", sequences.display())
            + &summary(
                &cell,
                &evaluated.schedule,
                &rounds,
                evaluated.collision.as_ref(),
                evaluated.times,
            )
    };
    let _ = std::io::stdout().write_all(text.as_bytes());
    written?;
    Ok(ExitCode::from(u8::from(!evaluated.collision_free)))
}

fn load(path: &Path) -> Result<Cell, InputError> {
    let loaded = load_cell(path)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    Ok(loaded.cell)
}

/// Writes `--export-scene` and `--svg`; every file is attempted before an error is returned.
fn exports(
    cell: &Cell,
    schedule: &Schedule,
    collisions: &[&Collision],
    out: &Outputs,
) -> Result<(), InputError> {
    let mut result = Ok(());
    if let Some(file) = &out.export_scene {
        let doc = scene_document(&schedule.scene(cell));
        result = result.and(write(
            file,
            &serde_json::to_string_pretty(&doc).expect("a scene serialises"),
        ));
    }
    if let Some(file) = &out.svg {
        result = result.and(write(file, &wcp::picture(cell, schedule, collisions)));
    }
    result
}

fn write(file: &Path, text: &str) -> Result<(), InputError> {
    super::output::write_file(file, text.as_bytes())
}

/// Refuses outputs that would replace an input or each other, before any work is done.
fn check_paths(
    inputs: &[&Path],
    out: &Outputs,
    export_graph: Option<&Path>,
) -> Result<(), InputError> {
    let outputs: Vec<(&str, &Path)> = [
        ("--export-scene", out.export_scene.as_deref()),
        ("--svg", out.svg.as_deref()),
        ("--export-graph", export_graph),
    ]
    .into_iter()
    .filter_map(|(option, path)| Some((option, path?)))
    .collect();
    super::output::check_outputs(inputs, &outputs)
}
