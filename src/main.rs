//! `workcell`: the command-line tool. Thin: parses arguments, calls the library, prints.
//!
//! Exit status, every command: 2 when the input cannot be used (the message on stderr names
//! the file, the body and the field) or an output file cannot be written.
//! * `check`: 0 collision-free, 1 collision found, 3 unresolved within the work budget.
//! * `solve`: 0 a collision-free schedule found, 1 none found within the limits.
//! * `evaluate`: 0 the schedule is collision-free, 1 it collides.
//! * `generate`: 0 all scenes or cells written.
//! * `compare`: 0 compared.

mod cli;

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;
use workcell::collision::{CheckOptions, Method};
use workcell::compare::{default_contenders, Contender};
use workcell::generate::{CellRequest, ConflictKind, Kind, ScaraRequest};

#[derive(Parser)]
#[command(
    name = "workcell",
    version,
    about = "Schedules robots in a work-cell and certifies that their motions never collide."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Certify a scene collision-free, or find its first contact (Feyeux & Landry 2013).
    ///
    /// Exit status: 0 collision-free, 1 collision found, 2 unusable input, 3 unresolved
    /// (a pair used its work budget with neither a proof nor a collision).
    Check {
        /// Scene file (JSON, see docs/formats.md: "Scene file").
        scene: PathBuf,
        /// Print the result as JSON on stdout.
        #[arg(long)]
        json: bool,
        /// Safety margin δ, replacing the scene's (length units of the scene).
        #[arg(long, value_parser = cli::positive, allow_negative_numbers = true)]
        delta: Option<f64>,
        /// How each merged interval is searched: `adaptive` (the paper's bisection with a
        /// motion bound true for any input), `adaptive-paper` (with the paper's eq. 12, from
        /// the given velocities: can miss collisions when they disagree with the positions),
        /// `sampled:STEP` (the distance at the samples and every STEP time units only; proves
        /// nothing) or `advance` (conservative advancement).
        #[arg(long, default_value = "adaptive")]
        method: Method,
        /// Time tolerance of the first contact (time units; default 1e-6 of the horizon).
        #[arg(long, value_parser = cli::positive, allow_negative_numbers = true)]
        time_tol: Option<f64>,
        /// Also give each pair's counters (`pair_stats` in the JSON).
        #[arg(long)]
        per_pair: bool,
        /// Work budget of each pair, in evaluations of the distance (default 1000000).
        #[arg(long, value_parser = cli::at_least_one, allow_negative_numbers = true)]
        max_work: Option<u64>,
        /// Write a self-contained HTML page that animates the scene, its first contact
        /// highlighted and the certified-free prefix shown on the time slider.
        #[arg(long)]
        html: Option<PathBuf>,
        /// Write the still picture of the scene (SVG): each robot's path, each arm where it
        /// starts (links in its colour, joints as dots, the base as a square), the first
        /// contact ringed.
        #[arg(long)]
        svg: Option<PathBuf>,
    },
    /// Schedule a cell: plan every move, sequence the tasks, check the schedule and re-plan
    /// around collisions until it is collision-free.
    ///
    /// Exit status: 0 collision-free schedule found, 1 none found, 2 unusable input.
    Solve {
        /// Cell file (JSON, see docs/formats.md: "Cell file").
        cell: PathBuf,
        #[command(flatten)]
        out: cli::solve::Outputs,
        /// Seed of the sequencer's search: the same seed gives the same schedule.
        #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
        seed: u64,
        /// Rounds of sequencing, checking and feedback before giving up (for the search:
        /// along one branch).
        #[arg(long, default_value_t = 200, value_parser = cli::at_least_one, allow_negative_numbers = true)]
        max_iterations: u64,
        #[command(flatten)]
        feedback: cli::solve::FeedbackArgs,
        /// Write the work-cell graph (nodes and each robot's travel times) to this file, once
        /// solved: each arc says whether its time is exact (planned and certified) or a
        /// lower bound.
        #[arg(long)]
        export_graph: Option<PathBuf>,
        /// Spend this many seconds (whole solve) improving the schedule, and answer with the
        /// best certified one: the sequencer searches on until half the time left, then the
        /// search over remedies (or, on a collision-free plan, the sequencer again) takes the
        /// rest. Without it the result depends only on the cell, the seed and the effort.
        #[arg(long, value_parser = cli::positive, allow_negative_numbers = true)]
        time_limit: Option<f64>,
        /// Work of the sequencer's search, deterministic: epochs of its iterated local search
        /// (each kicks every chain and searches again); the same cell, seed and effort give
        /// the same schedule on any machine and number of threads [default: 1; with
        /// --time-limit, until the time is spent].
        #[arg(long, value_parser = cli::at_least_one, allow_negative_numbers = true)]
        effort: Option<u64>,
        /// Write the anytime curve as CSV: one line per better schedule found (seconds since
        /// the start, stage, makespan, whether it is certified, a lower bound of the
        /// collision-blind makespan).
        #[arg(long)]
        trace: Option<PathBuf>,
        /// Print a plain progress line on stderr every second (stage, best makespan, elapsed
        /// time) instead of the progress bar.
        #[arg(long)]
        progress: bool,
        /// Which moves are planned and certified before sequencing: `all` (every move of every
        /// robot), `lazy` (those between homes and tasks; the sequencer works on lower bounds
        /// of the others and plans those its plans use) or `auto` (`all` for cells of at most
        /// 100,000 moves, else `lazy`).
        #[arg(long, default_value = "auto", value_parser = ["auto", "lazy", "all"])]
        planning: String,
    },
    /// Time and check given sequences (the `sequences` object of a solve result).
    ///
    /// Exit status: 0 collision-free, 1 the schedule collides, 2 unusable input.
    // `--svg` is shared with `solve`, whose picture marks every feedback round's collision.
    #[command(mut_arg("svg", |a| a.help(
        "Draw the cell, the paths and the schedule's first collision, if any, as an SVG picture"
    )))]
    Evaluate {
        /// Cell file (JSON, see docs/formats.md: "Cell file").
        cell: PathBuf,
        /// Sequences file: `{"R1": ["weld-3", "weld-1"], ...}` or a whole solve result.
        sequences: PathBuf,
        /// Evaluate the collision-blind sequences of a whole solve result (its
        /// `blind_sequences`, without waits or changed legs) instead of its final ones.
        #[arg(long)]
        blind: bool,
        #[command(flatten)]
        out: cli::solve::Outputs,
    },
    /// Run every checking method on every scene and compare time per check, collisions
    /// missed and invented, and the first contact time against a tight reference.
    ///
    /// Exit status: 0 compared, 2 unusable input or an output that cannot be written.
    Compare {
        /// Scene files, or folders whose `*.json` scene files are all read (`*-cell.json` aside).
        #[arg(required = true)]
        inputs: Vec<PathBuf>,
        /// Write the chart (time per check against collisions missed) to this SVG file.
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Print the comparison as JSON on stdout instead of a table.
        #[arg(long)]
        json: bool,
        /// Methods to compare, comma-separated (`parry` needs the feature parry-peer).
        /// Default: adaptive, adaptive-paper, advance, sampled:1, sampled:0.1, sampled:0.01,
        /// sampled:0.001, and parry when built in.
        #[arg(long, value_delimiter = ',')]
        methods: Option<Vec<Contender>>,
    },
    /// Write deterministic random scenes or cells (same arguments, same bytes) as
    /// `OUT/<kind>-<seed>-<k>.json` for k in 0..count; conflict cells as
    /// `OUT/<kind>-<seed>-<k>-cell.json`, cells for `solve` (`--kind cell`) as
    /// `OUT/cell-<R>r-<N>t-<F>f-<seed>-<k>-cell.json`.
    ///
    /// Exit status: 0 written, 2 an impossible request, or the folder or a file cannot be
    /// written.
    Generate {
        /// Family of scenes or cells (see docs/cli.md: "`workcell generate`"): `all` for every
        /// family of scenes, `conflict` for every family of conflict cells, `cell` for a cell
        /// at the size of a line, `scara` for a cell of SCARA arms.
        #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(cli::generate::kind_names()))]
        kind: String,
        /// Seed: the same seed gives the same scenes.
        #[arg(long, allow_negative_numbers = true)]
        seed: u64,
        /// Number of robots (`hall`: default 10; `cell`: required, at most 1,000; `scara`:
        /// arms, 2 to 8, default 4).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..=100_000), allow_negative_numbers = true)]
        robots: Option<u64>,
        /// Number of tasks of a cell (`cell`: required; `scara`: default 40).
        #[arg(long, allow_negative_numbers = true)]
        tasks: Option<u64>,
        /// Number of fixtures of a cell (`cell` only; default 3 per 50 tasks).
        #[arg(long, allow_negative_numbers = true)]
        fixtures: Option<u64>,
        /// Number of scenes or cells (default 10 scenes, 1 cell).
        #[arg(long, allow_negative_numbers = true)]
        count: Option<u64>,
        /// Output folder, created if missing.
        #[arg(long)]
        out: PathBuf,
    },
}

/// `workcell generate`: scenes of one kind or all, or cells.
fn generate(
    kind: &str,
    seed: u64,
    robots: Option<u64>,
    tasks: Option<u64>,
    fixtures: Option<u64>,
    count: Option<u64>,
    out: &std::path::Path,
) -> Result<ExitCode, workcell::cell::InputError> {
    use cli::generate::{run_generate, What};
    let refuse = |reason: &str| workcell::cell::InputError {
        file: out.to_path_buf(),
        body: None,
        field: String::new(),
        reason: reason.to_owned(),
    };
    if kind == "cell" {
        let (Some(robots), Some(tasks)) = (robots, tasks) else {
            return Err(refuse("--kind cell needs --robots and --tasks"));
        };
        let tasks = tasks as usize;
        let req = CellRequest {
            robots: robots as usize,
            tasks,
            fixtures: fixtures.map_or(CellRequest::default_fixtures(tasks), |f| f as usize),
        };
        req.check().map_err(|e| refuse(&e))?;
        return run_generate(&What::Cells(req), seed, count.unwrap_or(1), out);
    }
    if kind == "scara" {
        if fixtures.is_some() {
            return Err(refuse("--fixtures applies only to --kind cell"));
        }
        let req = ScaraRequest {
            arms: robots.map_or(4, |r| r as usize),
            tasks: tasks.map_or(40, |t| t as usize),
        };
        return run_generate(&What::Scara(req), seed, count.unwrap_or(1), out);
    }
    if tasks.is_some() || fixtures.is_some() {
        return Err(refuse(
            "--tasks and --fixtures apply only to --kind cell and scara",
        ));
    }
    let conflicts = match kind {
        "conflict" => Some(ConflictKind::ALL.to_vec()),
        other => ConflictKind::from_name(other).map(|k| vec![k]),
    };
    if let Some(kinds) = conflicts {
        if robots.is_some() {
            return Err(refuse(&format!(
                "--robots applies only to --kind hall, arm-hall and cell, not to {kind}"
            )));
        }
        return run_generate(&What::Conflicts(&kinds), seed, count.unwrap_or(10), out);
    }
    let kinds = Kind::from_name(kind);
    let what = What::Scenes {
        kinds: kinds.as_ref().map_or(&Kind::ALL[..], std::slice::from_ref),
        robots: robots.map(|r| r as usize),
    };
    run_generate(&what, seed, count.unwrap_or(10), out)
}

/// `--planning`'s value (clap has checked it is one of these).
fn planning_of(value: &str) -> workcell::wcp::Planning {
    match value {
        "all" => workcell::wcp::Planning::All,
        "lazy" => workcell::wcp::Planning::Lazy,
        _ => workcell::wcp::Planning::Auto,
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Check {
            scene,
            json,
            delta,
            method,
            time_tol,
            per_pair,
            max_work,
            html,
            svg,
        } => {
            let defaults = CheckOptions::default();
            let max_work_per_pair = max_work.unwrap_or(defaults.max_work_per_pair);
            let opts = CheckOptions {
                delta,
                time_tol,
                per_pair,
                method,
                max_work_per_pair,
                ..defaults
            };
            cli::check::run_check(&scene, json, &opts, (html.as_deref(), svg.as_deref()))
        }
        Command::Solve {
            cell,
            out,
            seed,
            max_iterations,
            feedback,
            export_graph,
            time_limit,
            effort,
            trace,
            progress,
            planning,
        } => cli::solve::run_solve(
            &cell,
            &out,
            &cli::solve::SolveArgs {
                seed,
                max_iterations: max_iterations as usize,
                feedback: &feedback,
                export_graph: export_graph.as_deref(),
                // Beyond what a Duration holds, no limit at all.
                time_limit: time_limit.and_then(|t| std::time::Duration::try_from_secs_f64(t).ok()),
                effort: effort.map(|e| e as usize),
                trace: trace.as_deref(),
                progress,
                planning: planning_of(&planning),
            },
        ),
        Command::Evaluate {
            cell,
            sequences,
            blind,
            out,
        } => cli::solve::run_evaluate(&cell, &sequences, blind, &out),
        Command::Generate {
            kind,
            seed,
            robots,
            tasks,
            fixtures,
            count,
            out,
        } => generate(&kind, seed, robots, tasks, fixtures, count, &out),
        Command::Compare {
            inputs,
            svg,
            json,
            methods,
        } => cli::compare::run_compare(
            &inputs,
            &methods.unwrap_or_else(default_contenders),
            svg.as_deref(),
            json,
        ),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
