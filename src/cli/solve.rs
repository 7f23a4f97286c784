//! `workcell solve` and `workcell evaluate`: schedules, their checks and their exports.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use workcell::cell::{load_cell, load_sequences, scene_document, Cell, InputError};
use workcell::wcp::remedy_json::legs_json;
use workcell::wcp::report::{
    collision_json, rounds_json, schedule_json, sequences_json, summary, waits_json, ResultJson,
};
use workcell::wcp::{
    self, Collision, Feedback, Iteration, Progress, Remedies, Schedule, SolveOptions,
};

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

/// How `solve` feeds collisions back.
#[derive(clap::Args)]
pub struct FeedbackArgs {
    /// `search`: best-first search over remedies; `greedy`: each round the better of
    /// re-sequencing and one wait at a node, never revisited (to compare against).
    #[arg(long, default_value = "search", value_parser = ["search", "greedy"])]
    feedback: String,
    /// The search's budget: most schedules checked.
    #[arg(long, default_value_t = 5000, value_parser = clap::value_parser!(u64).range(1..))]
    search_nodes: u64,
    /// The search's time limit, in seconds (a safety stop; the result is deterministic
    /// when it is not reached).
    #[arg(long, default_value_t = 60.0, value_parser = positive_seconds)]
    search_time: f64,
    /// The remedies the search may use, comma-separated: resequence, wait, pause, slow,
    /// detour, step-aside (default: all).
    #[arg(long, value_delimiter = ',', value_parser = ["resequence", "wait", "pause", "slow", "detour", "step-aside"])]
    remedies: Option<Vec<String>>,
}

fn positive_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v < 1e9 => Ok(v),
        _ => Err(format!("expected a positive number of seconds, got `{s}`")),
    }
}

impl FeedbackArgs {
    fn apply(&self, opts: &mut SolveOptions) {
        opts.feedback = match self.feedback.as_str() {
            "greedy" => Feedback::Greedy,
            _ => Feedback::Search,
        };
        opts.search.max_nodes = self.search_nodes as usize;
        opts.search.time_limit = std::time::Duration::from_secs_f64(self.search_time);
        if let Some(names) = &self.remedies {
            opts.search.remedies = Remedies::of_names(names.iter().map(String::as_str))
                .expect("clap accepts only the remedies' names");
        }
    }
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
    feedback: &FeedbackArgs,
    export_graph: Option<&Path>,
) -> Result<ExitCode, InputError> {
    let cell = load(path)?;
    let mut opts = SolveOptions {
        max_iterations,
        ..SolveOptions::default()
    };
    feedback.apply(&mut opts);
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
            legs: legs_json(&cell, &solved.routes, &solved.legs),
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
        let plural = |n: usize| if n == 1 { "" } else { "s" };
        text += &format!(
            " ({} round{}, {} schedule{} checked; collision-blind makespan {:.3}{})\n",
            solved.iterations.len(),
            plural(solved.iterations.len()),
            solved.nodes,
            plural(solved.nodes),
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
            legs: legs_json(&cell, &evaluated.routes, &evaluated.legs),
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
    std::fs::write(file, text).map_err(|e| InputError {
        file: file.to_path_buf(),
        body: None,
        field: String::new(),
        reason: format!("cannot write the file: {e}"),
    })
}
