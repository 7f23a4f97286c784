//! The feedback loop: the search over remedies on the conflict cells (no divergence, every
//! cell solved, the limits kept), each remedy where it is needed, the shipped cells'
//! documented results, the greedy loop's documented choices, and determinism. The helpers
//! shared by its modules are here.

mod families;
mod limits;
mod remedies;
mod rings;

use crate::common::{assert_export_certified, on_threads, shipped_cell, solve_with};
use std::path::{Path, PathBuf};
use workcell::cell::{parse_cell, Cell};
use workcell::collision::CheckOptions;
use workcell::generate::{generate_conflict_cell, ConflictKind};
use workcell::wcp::{self, Feedback, Remedies, Remedy, RemedyKind, SolveOptions, Solved};

fn conflict_cell(kind: ConflictKind, k: u64) -> Cell {
    let text = generate_conflict_cell(kind, 1, k).to_string();
    parse_cell(&text, &PathBuf::from(kind.name())).unwrap().cell
}

fn solve(cell: &Cell) -> Solved {
    solve_with(cell, &SolveOptions::default())
}

/// Options with only the remedies named.
fn only(names: &[&str]) -> SolveOptions {
    let mut opts = SolveOptions::default();
    opts.search.remedies = Remedies::of_names(names.iter().copied()).unwrap();
    opts
}

/// Every remedy but the one named.
fn all_but(name: &str) -> SolveOptions {
    none_of(&[name])
}

/// Default options but the whole budget of schedules to the search's first pass (the
/// second only once no node is left), however long since it last found better.
fn first_pass_only() -> SolveOptions {
    let mut opts = SolveOptions::default();
    opts.search.second_pass_share = 0.0;
    opts.search.patience = None;
    opts
}

/// Options with every remedy but those named.
fn none_of(names: &[&str]) -> SolveOptions {
    let rest: Vec<&str> = (Remedies::NAMES.into_iter())
        .filter(|n| !names.contains(n))
        .collect();
    only(&rest)
}

/// Cell `k` of `kind` (seed 1) solved with the default options, certified at `makespan`.
fn solved_at(kind: ConflictKind, k: u64, makespan: f64) -> Solved {
    let solved = solve(&conflict_cell(kind, k));
    assert!(solved.collision_free, "{:?}", solved.failure);
    let got = solved.schedule.makespan;
    assert!((got - makespan).abs() < 1e-3, "{}-{k}: {got}", kind.name());
    solved
}

fn remedies(solved: &Solved) -> Vec<&Remedy> {
    solved
        .iterations
        .iter()
        .filter_map(|i| i.remedy.as_ref())
        .collect()
}

/// The schedule is certified by a fresh check of its exported scene, and every robot keeps
/// its limits: speed, turn rate, and the accelerations between samples (each motion is
/// rest to rest on trapezoids sampled at their phase boundaries, so the slope of the
/// sampled velocity is the acceleration).
fn assert_certified_within_limits(cell: &Cell, solved: &Solved) {
    assert_export_certified(cell, solved);
    let slack = 1.0 + 1e-6;
    for (r, plan) in solved.schedule.robots.iter().enumerate() {
        let robot = cell.rigid(r);
        let name = &cell.robots[r].name;
        let alpha = robot.max_accel / robot.shape.radius();
        for s in &plan.samples {
            assert!(
                s.vel.norm() <= robot.max_speed * slack,
                "{}: speed {}",
                name,
                s.vel.norm()
            );
            assert!(
                s.omega.abs() <= robot.max_turn_rate * slack,
                "{}: turn rate {}",
                name,
                s.omega
            );
        }
        for w in plan.samples.windows(2) {
            let dt = w[1].t - w[0].t;
            let accel = (w[1].vel - w[0].vel).norm() / dt;
            let spin = (w[1].omega - w[0].omega).abs() / dt;
            assert!(
                accel <= robot.max_accel * slack + 1e-9,
                "{}: accel {accel} at {}",
                name,
                w[0].t
            );
            assert!(
                spin <= alpha * slack + 1e-9,
                "{}: angular accel {spin} at {}",
                name,
                w[0].t
            );
        }
    }
}

/// The overhead of a solve over its collision-blind makespan.
fn overhead(solved: &Solved) -> f64 {
    solved.schedule.makespan / solved.blind_makespan - 1.0
}
