//! `workcell solve` and `workcell evaluate`: schedules, their checks and their exports.

use super::trace::Trace;
use clap::builder::PossibleValuesParser;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use workcell::cell::{
    load_blind_sequences, load_cell, load_sequences, scene_document, Cell, InputError,
};
use workcell::view;
use workcell::wcp::legs_json::legs_json;
use workcell::wcp::report::{
    collision_json, configurations_json, rounds_json, schedule_json, sequences_json, summary,
    waits_json, ResultJson, StagesJson,
};
use workcell::wcp::{
    self, Collision, Feedback, Iteration, Progress, Remedies, Schedule, SearchOptions,
    SolveOptions, WcpGraph,
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
    /// Draw the schedule as a Gantt chart (SVG): one lane per robot.
    #[arg(long)]
    gantt: Option<PathBuf>,
    /// Write a self-contained HTML page that animates the schedule.
    #[arg(long)]
    html: Option<PathBuf>,
}

/// How `solve` feeds collisions back.
#[derive(clap::Args)]
pub struct FeedbackArgs {
    /// `search`: best-first search over remedies; `greedy`: each round the better of
    /// re-sequencing and one wait at a node, never revisited (to compare against).
    #[arg(long, default_value = "search", value_parser = ["search", "greedy"])]
    feedback: String,
    /// The search's budget: most schedules checked [default: 5000; with --time-limit, no
    /// budget but the time].
    #[arg(long, value_parser = super::at_least_one, allow_negative_numbers = true)]
    search_nodes: Option<u64>,
    /// The search's time limit, in seconds, a safety stop (the result is deterministic when
    /// it is not reached) [default: 60; with --time-limit, that limit's].
    #[arg(long, value_parser = positive_seconds, allow_negative_numbers = true)]
    search_time: Option<f64>,
    /// End the search's first pass when it stops paying: once it has checked this many
    /// schedules, and at least as many as it took to find it, since its best certified
    /// schedule; the second pass then has its share of the budget, and the search ends (0:
    /// the first pass runs until its share is spent or no node is left).
    #[arg(long, default_value_t = 2000)]
    search_patience: u64,
    /// The share of the search's budget of schedules kept for its second pass along the way
    /// to the best schedule (passing places, route-end exchanges), from 0 (the second pass
    /// only once no node is left) to 1.
    #[arg(long, default_value_t = 0.3, value_parser = share, allow_negative_numbers = true)]
    second_pass_share: f64,
    /// Also search from plans with one robot fewer, at home throughout: this many, of the
    /// robots whose tasks others may all do, those whose plans without them are shortest
    /// (robots that share a door may finish sooner with one of them at home; they share
    /// the search's budget).
    #[arg(long, default_value_t = 0)]
    idle_roots: usize,
    /// The remedies the search may use, comma-separated: resequence, wait, pause, slow,
    /// detour (with it make-way: a robot in another's way leaves ahead of it, the other
    /// waits), step-aside, pass-aside (a robot on its way pulls in at a passing place beside
    /// it, in the search's second pass), lanes (two robots that meet moving keep to opposite
    /// sides where both fit side by side, in the second pass), tune (two robots' moves timed
    /// together, for a pair that collides again), convoy (every robot of a closed corridor
    /// round it together), reconfigure (an arm's; default: all but reconfigure).
    #[arg(long, value_delimiter = ',', value_parser = PossibleValuesParser::new(Remedies::NAMES))]
    remedies: Option<Vec<String>>,
}

/// A share, from 0 to 1.
fn share(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("expected a share from 0 to 1, got `{s}`")),
    }
}

/// A positive, finite number of seconds; one beyond what a `Duration` holds is no limit.
fn positive_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("expected a positive number of seconds, got `{s}`")),
    }
}

impl FeedbackArgs {
    /// Sets the feedback's options; under a time limit (`opts.time_limit`) the search's own
    /// budgets default to none: the solve's limit is the one the user gave.
    fn apply(&self, opts: &mut SolveOptions) {
        opts.feedback = match self.feedback.as_str() {
            "greedy" => Feedback::Greedy,
            _ => Feedback::Search,
        };
        let limited = opts.time_limit.is_some();
        opts.search.max_nodes = match (self.search_nodes, limited) {
            (Some(n), _) => n as usize,
            (None, true) => usize::MAX,
            (None, false) => SearchOptions::default().max_nodes,
        };
        opts.search.patience = (self.search_patience > 0).then_some(self.search_patience as usize);
        opts.search.second_pass_share = self.second_pass_share;
        opts.search.idle_roots = self.idle_roots;
        opts.search.time_limit = match (self.search_time, limited) {
            (Some(s), _) => Duration::try_from_secs_f64(s).unwrap_or(Duration::MAX),
            (None, true) => Duration::MAX,
            (None, false) => SearchOptions::default().time_limit,
        };
        if let Some(names) = &self.remedies {
            opts.search.remedies = Remedies::of_names(names.iter().map(String::as_str))
                .expect("clap accepts only the remedies' names");
        }
    }
}

/// How often `--progress` prints a line.
const PROGRESS_PERIOD: Duration = Duration::from_secs(1);

/// A progress bar on stderr, shown only on a terminal and without `--json` or `--progress`;
/// with `--progress`, a plain line every [`PROGRESS_PERIOD`] instead.
struct Bar {
    bar: ProgressBar,
    lines: Option<Arc<Lines>>,
    /// `--trace`.
    trace: Option<Trace>,
    printer: Option<std::thread::JoinHandle<()>>,
}

/// What the `--progress` lines say, shared with the thread that prints them.
struct Lines {
    start: Instant,
    stage: Mutex<String>,
    planned: AtomicUsize,
    to_plan: AtomicUsize,
    /// Best makespan the sequencer found, as f64 bits (infinity: none yet).
    best: AtomicU64,
    /// Best makespan of a schedule checked collision-free, as f64 bits (infinity: none
    /// yet).
    certified: AtomicU64,
    /// A lower bound of the makespan, as f64 bits (infinity: not known yet).
    lower_bound: AtomicU64,
    done: AtomicBool,
}

impl Lines {
    fn line(&self) -> String {
        let stage = self.stage.lock().expect("no panic while held").clone();
        let stage = if stage == "planning" {
            let (k, n) = (
                self.planned.load(Ordering::Relaxed),
                self.to_plan.load(Ordering::Relaxed),
            );
            format!("planning moves {k}/{n}")
        } else {
            stage
        };
        let best = f64::from_bits(self.best.load(Ordering::Relaxed));
        let certified = f64::from_bits(self.certified.load(Ordering::Relaxed));
        // Once a schedule is collision-free, that is the best there is; before, the
        // sequencer's plans on the times it knows (unchecked).
        let best = if certified.is_finite() {
            format!("best makespan {certified:.3}, collision-free")
        } else if best.is_finite() {
            format!("best makespan {best:.3}, the sequencer's estimate (not checked)")
        } else {
            "best makespan -".to_owned()
        };
        let bound = f64::from_bits(self.lower_bound.load(Ordering::Relaxed));
        let bound = match bound.is_finite() {
            true => format!(", lower bound {bound:.3}"),
            false => String::new(),
        };
        format!(
            "progress: {:.1} s, {stage}, {best}{bound}",
            self.start.elapsed().as_secs_f64()
        )
    }
}

impl Bar {
    fn new(json: bool, lines: bool, trace: bool) -> Bar {
        let bar = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr());
        if json || lines || !std::io::stderr().is_terminal() {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        }
        let lines = lines.then(|| {
            Arc::new(Lines {
                start: Instant::now(),
                stage: Mutex::new("reading".to_owned()),
                planned: AtomicUsize::new(0),
                to_plan: AtomicUsize::new(0),
                best: AtomicU64::new(f64::INFINITY.to_bits()),
                certified: AtomicU64::new(f64::INFINITY.to_bits()),
                lower_bound: AtomicU64::new(f64::INFINITY.to_bits()),
                done: AtomicBool::new(false),
            })
        });
        let printer = lines.clone().map(|lines| {
            std::thread::spawn(move || {
                let mut next = lines.start + PROGRESS_PERIOD;
                while !lines.done.load(Ordering::Relaxed) {
                    // Short naps, so that the end of the solve is not held up by a second.
                    std::thread::sleep(Duration::from_millis(20));
                    if Instant::now() >= next {
                        eprintln!("{}", lines.line());
                        next += PROGRESS_PERIOD;
                    }
                }
            })
        });
        Bar {
            bar,
            trace: trace.then(|| Trace::new(Instant::now())),
            lines,
            printer,
        }
    }

    fn stage(&self, stage: String) {
        if let Some(lines) = &self.lines {
            *lines.stage.lock().expect("no panic while held") = stage;
        }
    }

    /// Clears the bar, stops the lines (a last one says where the solve ended).
    fn finish(&mut self) {
        self.bar.finish_and_clear();
        if let (Some(lines), Some(printer)) = (&self.lines, self.printer.take()) {
            lines.done.store(true, Ordering::Relaxed);
            let _ = printer.join();
            eprintln!("{}", lines.line());
        }
    }
}

impl Progress for Bar {
    fn planning(&self, total: usize) {
        self.bar.set_style(
            ProgressStyle::with_template("planning moves {bar:40} {pos}/{len} {elapsed}")
                .expect("a valid template"),
        );
        self.bar.set_length(total as u64);
        if let Some(lines) = &self.lines {
            lines.to_plan.store(total, Ordering::Relaxed);
        }
        self.stage("planning".to_owned());
    }

    fn move_planned(&self) {
        self.bar.inc(1);
        if let Some(lines) = &self.lines {
            lines.planned.fetch_add(1, Ordering::Relaxed);
        }
    }

    fn sequencing(&self, round: usize) {
        self.bar.set_style(
            ProgressStyle::with_template("{spinner} {msg} {elapsed}").expect("a valid template"),
        );
        self.bar.set_message(format!("sequencing, round {round}"));
        self.bar.tick();
        self.stage(format!("sequencing round {round}"));
    }

    fn best(&self, makespan: f64) {
        if let Some(lines) = &self.lines {
            // Smallest wins; f64 bits of positive numbers order as the numbers.
            lines.best.fetch_min(makespan.to_bits(), Ordering::Relaxed);
        }
        if let Some(trace) = &self.trace {
            trace.found(makespan, false);
        }
    }

    fn certified(&self, makespan: f64) {
        if let Some(lines) = &self.lines {
            lines
                .certified
                .fetch_min(makespan.to_bits(), Ordering::Relaxed);
        }
        if let Some(trace) = &self.trace {
            trace.found(makespan, true);
        }
    }

    fn iteration(&self, k: usize, makespan: f64, collision: Option<&Collision>) {
        self.bar.set_style(
            ProgressStyle::with_template("{spinner} round {msg} {elapsed}")
                .expect("a valid template"),
        );
        let verdict = if collision.is_some() {
            "collides, re-planning"
        } else {
            "collision-free"
        };
        self.bar
            .set_message(format!("{k}: makespan {makespan:.3}, {verdict}"));
        self.bar.tick();
        self.stage(format!(
            "checked round {k} (makespan {makespan:.3}, {verdict})"
        ));
    }
}

/// Settings of `workcell solve` beyond the outputs.
pub struct SolveArgs<'a> {
    /// Seed of the sequencer.
    pub seed: u64,
    /// Rounds of the feedback loop.
    pub max_iterations: usize,
    /// How collisions are fed back.
    pub feedback: &'a FeedbackArgs,
    /// `--export-graph`.
    pub export_graph: Option<&'a Path>,
    /// `--time-limit`.
    pub time_limit: Option<Duration>,
    /// `--effort`.
    pub effort: Option<usize>,
    /// `--trace`.
    pub trace: Option<&'a Path>,
    /// `--progress`.
    pub progress: bool,
    /// `--planning`.
    pub planning: wcp::Planning,
}

/// Solves the cell; exit status 0 collision-free, 1 none found.
pub fn run_solve(path: &Path, out: &Outputs, args: &SolveArgs) -> Result<ExitCode, InputError> {
    let extra = [
        ("--export-graph", args.export_graph),
        ("--trace", args.trace),
    ];
    check_paths(&[path], out, &extra)?;
    let mut bar = Bar::new(out.json, args.progress, args.trace.is_some());
    let cell = load(path).inspect_err(|_| bar.finish())?;
    let mut opts = SolveOptions {
        max_iterations: args.max_iterations,
        time_limit: args.time_limit,
        planning: args.planning,
        ..SolveOptions::default()
    };
    args.feedback.apply(&mut opts);
    opts.sequencer.seed = args.seed;
    // A time limit is a budget to use: epochs until it is spent, unless an effort is given.
    opts.sequencer.effort = match (args.effort, args.time_limit) {
        (Some(effort), _) => effort,
        (None, Some(_)) => usize::MAX,
        (None, None) => 1,
    };
    // An error leaves no half-drawn bar above its message.
    let prepared = wcp::prepare(&cell, &opts, &bar).inspect_err(|_| bar.finish())?;
    if let Some(unfinished) = prepared.unfinished {
        bar.finish();
        return Ok(out_of_time(path, out.json, &unfinished, &prepared));
    }
    let bound = prepared.makespan_lower_bound(&cell);
    if let Some(trace) = &bar.trace {
        trace.lower_bound(bound);
    }
    if let Some(lines) = &bar.lines {
        lines.lower_bound.store(bound.to_bits(), Ordering::Relaxed);
    }
    let solved = wcp::solve(&cell, &prepared, &opts, &bar).inspect_err(|_| bar.finish())?;
    bar.finish();
    let mut written = Ok(());
    if let (Some(file), Some(trace)) = (args.trace, &bar.trace) {
        written = written.and(write(file, &trace.csv()));
    }
    if let Some(file) = args.export_graph {
        // After the solve: every move it planned is exact there.
        // The configurations the solve chose.
        let moves = prepared.moves.assigned(solved.assignment.clone());
        let graph = WcpGraph::new(&cell, &moves, &wcp::bounds(&cell, moves.assignment()));
        let doc = serde_json::to_string_pretty(&graph.export(&cell)).expect("a graph serialises");
        written = written.and(write(file, &doc));
    }
    let final_collision = solved.iterations.last().and_then(|i| i.collision.as_ref());
    let (sequences, schedule) = schedule_json(&cell, &solved.schedule);
    let json = ResultJson {
        makespan: solved.schedule.makespan,
        collision_free: solved.collision_free,
        sequences,
        configurations: configurations_json(&cell, &solved.routes, &solved.assignment),
        iterations: solved.iterations.len(),
        schedules_checked: Some(solved.nodes),
        found_after: solved.found_after,
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
    let written = written.and(exports(&cell, &solved.schedule, &json, out));
    let text = if out.json {
        serde_json::to_string_pretty(&json).expect("a result serialises") + "\n"
    } else {
        let mut text = format!("{}: ", path.display());
        text += &match &solved.failure {
            None => "collision-free schedule".to_owned(),
            Some(why) => format!("NO collision-free schedule: {why}"),
        };
        let plural = |n: usize| if n == 1 { "" } else { "s" };
        // δ is what "collision-free" means here: the clearance certified.
        text += &format!(
            " (delta {}; {} round{}, {} schedule{} checked; collision-blind makespan {:.3}{})\n",
            cell.delta,
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

/// Reports a solve whose time limit ran out before a first schedule could be built: exit
/// status 1, as for any solve that finds no collision-free schedule within its limits. No
/// output file is written (there is no schedule to draw); the files there are kept.
fn out_of_time(
    path: &Path,
    json: bool,
    unfinished: &wcp::Unfinished,
    prepared: &wcp::Prepared,
) -> ExitCode {
    let text = match json {
        true => {
            let doc = serde_json::json!({
                "collision_free": false,
                "failure": unfinished.to_string(),
                "stages_ms": StagesJson::from(prepared.times),
            });
            serde_json::to_string_pretty(&doc).expect("a result serialises") + "\n"
        }
        false => format!("{}: NO schedule: {unfinished}\n", path.display()),
    };
    let _ = std::io::stdout().write_all(text.as_bytes());
    ExitCode::from(1)
}

/// Evaluates given sequences; exit status 0 collision-free, 1 the schedule collides.
/// With `blind`, the sequences are a solve result's collision-blind ones.
pub fn run_evaluate(
    path: &Path,
    sequences: &Path,
    blind: bool,
    out: &Outputs,
) -> Result<ExitCode, InputError> {
    check_paths(&[path, sequences], out, &[])?;
    let cell = load(path)?;
    let given = if blind {
        load_blind_sequences(sequences, &cell)?
    } else {
        load_sequences(sequences, &cell)?
    };
    let opts = SolveOptions::default();
    let evaluated = wcp::evaluate(&cell, &given, &opts, sequences)?;
    let failure = match &evaluated.collision {
        Some(c) => Some(format!(
            "the schedule collides: {}",
            wcp::describe(&cell, c)
        )),
        None if evaluated.collision_free => None,
        None => Some(wcp::uncertified(&evaluated.report)),
    };
    let (sequence_names, schedule) = schedule_json(&cell, &evaluated.schedule);
    let json = ResultJson {
        makespan: evaluated.schedule.makespan,
        collision_free: evaluated.collision_free,
        sequences: sequence_names,
        configurations: Vec::new(),
        iterations: 1,
        schedules_checked: None,
        found_after: None,
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
    let written = exports(&cell, &evaluated.schedule, &json, out);
    let text = if out.json {
        serde_json::to_string_pretty(&json).expect("a result serialises") + "\n"
    } else {
        let verdict = failure.as_deref().map_or_else(
            || format!("collision-free (delta {})", cell.delta),
            |f| format!("REJECTED: {f}"),
        );
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

/// Writes `--export-scene` and the pictures, drawn from the result document; every file is
/// attempted before an error is returned.
fn exports(
    cell: &Cell,
    schedule: &Schedule,
    json: &ResultJson,
    out: &Outputs,
) -> Result<(), InputError> {
    let mut result = Ok(());
    let scene = schedule.scene(cell);
    if let Some(file) = &out.export_scene {
        let doc = scene_document(&scene);
        result = result.and(write(
            file,
            &serde_json::to_string_pretty(&doc).expect("a scene serialises"),
        ));
    }
    if out.svg.is_none() && out.gantt.is_none() && out.html.is_none() {
        return result;
    }
    let model = view::Model::of_result(cell, &scene, json);
    if let Some(file) = &out.svg {
        result = result.and(write(file, &view::picture(&model)));
    }
    if let Some(file) = &out.gantt {
        result = result.and(write(file, &view::gantt(&model)));
    }
    if let Some(file) = &out.html {
        result = result.and(write(file, &view::html(&model)));
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
    extra: &[(&str, Option<&Path>)],
) -> Result<(), InputError> {
    let outputs: Vec<(&str, &Path)> = [
        ("--export-scene", out.export_scene.as_deref()),
        ("--svg", out.svg.as_deref()),
        ("--gantt", out.gantt.as_deref()),
        ("--html", out.html.as_deref()),
    ]
    .into_iter()
    .chain(extra.iter().copied())
    .filter_map(|(option, path)| Some((option, path?)))
    .collect();
    super::output::check_outputs(inputs, &outputs)
}
