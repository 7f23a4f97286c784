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
use cli::generate::Family;
use std::path::PathBuf;
use std::process::ExitCode;
use workcell::collision::{CheckOptions, Method};
use workcell::compare::{default_contenders, Contender};

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
        /// Scene file (JSON, see README: "Scene file").
        scene: PathBuf,
        /// Print the result as JSON on stdout.
        #[arg(long)]
        json: bool,
        /// Safety margin δ, replacing the scene's (length units of the scene).
        #[arg(long, value_parser = positive)]
        delta: Option<f64>,
        /// How each merged interval is searched: `adaptive` (the paper's bisection with a
        /// motion bound true for any input), `adaptive-paper` (with the paper's eq. 12, from
        /// the given velocities: can miss collisions when they disagree with the positions),
        /// `sampled:STEP` (the distance at the samples and every STEP time units only; proves
        /// nothing) or `advance` (conservative advancement).
        #[arg(long, default_value = "adaptive")]
        method: Method,
        /// Time tolerance of the first contact (time units; default 1e-6 of the horizon).
        #[arg(long, value_parser = positive)]
        time_tol: Option<f64>,
        /// Also give each pair's counters (`pair_stats` in the JSON).
        #[arg(long)]
        per_pair: bool,
        /// Work budget of each pair, in evaluations of the distance (default 1000000).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
        max_work: Option<u64>,
    },
    /// Schedule a cell: plan every move, sequence the tasks, check the schedule and re-plan
    /// around collisions until it is collision-free.
    ///
    /// Exit status: 0 collision-free schedule found, 1 none found, 2 unusable input.
    Solve {
        /// Cell file (JSON, see README: "Cell file").
        cell: PathBuf,
        #[command(flatten)]
        out: cli::solve::Outputs,
        /// Seed of the sequencer's search: the same seed gives the same schedule.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Rounds of sequencing, checking and feedback before giving up.
        #[arg(long, default_value_t = 50, value_parser = clap::value_parser!(u64).range(1..))]
        max_iterations: u64,
        /// Write the work-cell graph (nodes and each robot's travel times) to this file.
        #[arg(long)]
        export_graph: Option<PathBuf>,
    },
    /// Time and check given sequences (the `sequences` object of a solve result).
    ///
    /// Exit status: 0 collision-free, 1 the schedule collides, 2 unusable input.
    Evaluate {
        /// Cell file (JSON, see README: "Cell file").
        cell: PathBuf,
        /// Sequences file: `{"R1": ["weld-3", "weld-1"], ...}` or a whole solve result.
        sequences: PathBuf,
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
    /// Write deterministic random scenes or conflict cells (same arguments, same bytes) as
    /// `OUT/<kind>-<seed>-<k>.json` (cells: `...-cell.json`) for k in 0..count.
    ///
    /// Exit status: 0 written, 2 the folder or a file cannot be written.
    Generate {
        /// Family of scenes or cells (see README: "`workcell generate`"); `all` for every
        /// family of scenes, `conflict` for every family of conflict cells.
        #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(Family::names()))]
        kind: String,
        /// Seed: the same seed gives the same scenes.
        #[arg(long)]
        seed: u64,
        /// Number of robots (`hall` only; default 10).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..=100_000))]
        robots: Option<u64>,
        /// Number of scenes.
        #[arg(long, default_value_t = 10)]
        count: u64,
        /// Output folder, created if missing.
        #[arg(long)]
        out: PathBuf,
    },
}

fn positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("expected a positive number, got `{s}`")),
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
        } => {
            let defaults = CheckOptions::default();
            let opts = CheckOptions {
                delta,
                time_tol,
                per_pair,
                method,
                max_work_per_pair: max_work.unwrap_or(defaults.max_work_per_pair),
                ..defaults
            };
            cli::check::run_check(&scene, json, &opts)
        }
        Command::Solve {
            cell,
            out,
            seed,
            max_iterations,
            export_graph,
        } => cli::solve::run_solve(
            &cell,
            &out,
            seed,
            max_iterations as usize,
            export_graph.as_deref(),
        ),
        Command::Evaluate {
            cell,
            sequences,
            out,
        } => cli::solve::run_evaluate(&cell, &sequences, &out),
        Command::Generate {
            kind,
            seed,
            robots,
            count,
            out,
        } => cli::generate::run_generate(
            &Family::parse(&kind).expect("clap accepts only the names of families"),
            seed,
            robots.map(|r| r as usize),
            count,
            &out,
        ),
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
