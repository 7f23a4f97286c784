//! Lazy planning: the lower bounds never exceed the planned times, lazy and full planning find
//! the same makespan where the exact search settles it, every move of a returned plan is
//! planned and certified, a time limit still gives a certified plan, and the result does not
//! depend on the number of threads.

use crate::common::on_threads;
use std::path::Path;
use std::time::Duration;
use workcell::cell::{parse_cell, Cell};
use workcell::generate::{generate_cell, CellRequest};
use workcell::wcp::sequencer::{steps, Solution, Step};
use workcell::wcp::{self, bounds, robot_nodes, Planning, Prepared, SolveOptions};

fn cell(robots: usize, tasks: usize, fixtures: usize, seed: u64) -> Cell {
    let req = CellRequest {
        robots,
        tasks,
        fixtures,
    };
    let doc = generate_cell(&req, seed, 0).expect("a possible request");
    parse_cell(&doc.to_string(), Path::new("generated-cell.json"))
        .expect("generated cells are valid")
        .cell
}

fn opts(planning: Planning) -> SolveOptions {
    SolveOptions {
        planning,
        ..SolveOptions::default()
    }
}

/// Every move of `sol` is planned and certified in the store, and its makespan is the one of
/// those moves.
fn assert_certified(cell: &Cell, prepared: &Prepared, sol: &Solution) {
    let mut makespan: f64 = 0.0;
    for (r, route) in sol.sequences.iter().enumerate() {
        let mut time = 0.0;
        for step in steps(route) {
            match step {
                Step::Move { from, to } => {
                    let known = prepared.moves.known(r, from, to);
                    let Some(Ok(d)) = known else {
                        panic!("robot {r}: move {from} -> {to} is {known:?}");
                    };
                    time += d;
                }
                Step::Stay { node } if node > 0 => time += cell.tasks[node - 1].duration,
                Step::Stay { .. } => {}
            }
        }
        makespan = makespan.max(time);
    }
    assert!(
        (makespan - sol.makespan).abs() <= 1e-9 * makespan.max(1.0),
        "{makespan} vs {}",
        sol.makespan
    );
}

#[test]
fn bounds_never_exceed_the_planned_times() {
    // Random cells of every density of fixtures, every move of every robot (fixed seeds).
    let mut checked = 0;
    for seed in 0..6u64 {
        let cell = cell(3, 10, [0, 2, 4][seed as usize % 3], seed);
        let store = wcp::MoveStore::new(&cell, &Default::default());
        let b = bounds(&cell, store.assignment());
        for r in 0..cell.robots.len() {
            let nodes = robot_nodes(&cell, r);
            for &a in &nodes {
                for &c in nodes.iter().filter(|&&c| c != a) {
                    let bound = b.bound(r, a, c);
                    if let Ok(m) = store.get(r, a, c) {
                        assert!(
                            bound <= m.duration,
                            "seed {seed} robot {r} {a} -> {c}: bound {bound} > {}",
                            m.duration
                        );
                        // Nothing in the way: the bound is the planned time.
                        if cell.obstacles.is_empty() {
                            assert_eq!(bound, m.duration, "seed {seed} robot {r} {a} -> {c}");
                        }
                        checked += 1;
                    }
                }
            }
        }
    }
    assert!(checked > 1000, "{checked} moves checked");
}

#[test]
fn lazy_and_full_planning_give_the_same_makespan_on_small_cells() {
    for seed in 0..5u64 {
        let cell = cell(3, 8, 3, seed);
        let mut makespans = Vec::new();
        for planning in [Planning::Lazy, Planning::All] {
            let opts = opts(planning);
            let prepared = wcp::prepare(&cell, &opts, &()).unwrap();
            let sol = wcp::sequence(&cell, &prepared, &[], &opts).unwrap();
            assert!(sol.optimal, "seed {seed}: the exact search settles 8 tasks");
            assert_certified(&cell, &prepared, &sol);
            makespans.push(sol.makespan);
        }
        assert!(
            (makespans[0] - makespans[1]).abs() <= 1e-9 * makespans[1],
            "seed {seed}: lazy {} vs full {}",
            makespans[0],
            makespans[1]
        );
    }
}

#[test]
fn lazy_plans_fewer_moves_and_certifies_its_plan() {
    let cell = cell(4, 60, 4, 3);
    let lazy = opts(Planning::Lazy);
    let prepared = wcp::prepare(&cell, &lazy, &()).unwrap();
    let sol = wcp::sequence(&cell, &prepared, &[], &lazy).unwrap();
    assert_certified(&cell, &prepared, &sol);
    let full = wcp::prepare(&cell, &opts(Planning::All), &()).unwrap();
    assert!(
        3 * prepared.moves.planned() < full.moves.planned(),
        "lazy {} vs all {}",
        prepared.moves.planned(),
        full.moves.planned()
    );
}

#[test]
fn a_tiny_time_limit_still_returns_a_certified_plan() {
    // Large enough for the granular search and lazy planning.
    let cell = cell(6, 240, 8, 1);
    let opts = SolveOptions {
        time_limit: Some(Duration::from_millis(1)),
        ..opts(Planning::Lazy)
    };
    let prepared = wcp::prepare(&cell, &opts, &()).unwrap();
    let sol = wcp::sequence(&cell, &prepared, &[], &opts).unwrap();
    assert_certified(&cell, &prepared, &sol);
    let mut seen = vec![false; cell.tasks.len()];
    for (r, route) in sol.sequences.iter().enumerate() {
        for &t in route {
            assert!(!seen[t] && cell.tasks[t].robots.contains(&r));
            seen[t] = true;
        }
    }
    assert!(seen.iter().all(|&s| s));
    // The whole solve too: a schedule, collision-free or not.
    let solved = wcp::solve(&cell, &prepared, &opts, &()).unwrap();
    assert!(solved.schedule.makespan.is_finite());
}

#[test]
fn a_time_limit_spent_in_planning_leaves_it_unfinished_and_says_so() {
    let cell = cell(2, 30, 4, 1);
    for planning in [Planning::Lazy, Planning::All] {
        let opts = SolveOptions {
            time_limit: Some(Duration::from_nanos(1)),
            ..opts(planning)
        };
        let prepared = wcp::prepare(&cell, &opts, &()).unwrap();
        let left = prepared.unfinished.expect("no time to plan");
        assert!(left.done < left.total, "{planning:?}: {left:?}");
        assert_eq!(left.tasks, planning == Planning::Lazy);
        // Tasks, or moves between every two nodes of each robot.
        match planning {
            Planning::Lazy => assert_eq!(left.total, 30),
            _ => assert!(left.total > 2 * 30, "{left:?}"),
        }
        assert!(left
            .to_string()
            .contains("time limit ran out while planning"));
        // Without a limit, nothing is left.
        let whole = wcp::prepare(&cell, &self::opts(planning), &()).unwrap();
        assert_eq!(whole.unfinished, None);
    }
}

#[test]
fn lazy_granular_sequencing_is_the_same_on_1_2_and_4_threads() {
    let cell = cell(5, 220, 6, 2);
    let mut opts = opts(Planning::Lazy);
    opts.sequencer.iterations = 20;
    let run = |threads: usize| {
        on_threads(threads, || {
            let prepared = wcp::prepare(&cell, &opts, &()).unwrap();
            wcp::sequence(&cell, &prepared, &[], &opts).unwrap()
        })
    };
    let one = run(1);
    assert_eq!(one, run(2));
    assert_eq!(one, run(4));
}

#[test]
fn the_store_plans_the_same_moves_as_planning_among_every_obstacle() {
    // Many fixtures: most moves see only a few of them.
    let cell = cell(2, 14, 14, 7);
    let store = wcp::MoveStore::new(&cell, &Default::default());
    let obstacles = cell.obstacle_bodies();
    for r in 0..cell.robots.len() {
        let nodes = robot_nodes(&cell, r);
        for (i, &a) in nodes.iter().enumerate() {
            for &b in &nodes[i + 1..] {
                let all = wcp::certified_move(&cell, r, a, b, &Default::default(), &obstacles);
                assert_eq!(
                    store.get(r, a, b).map(|m| (*m).clone()),
                    all,
                    "robot {r} {a} -> {b}"
                );
            }
        }
    }
}

/// Under a time limit, `Auto` plans the moves from home first and every move only when that
/// fits in the limit: all of a small cell's moves under a generous limit (as without a
/// limit), none but the lazy ones beyond `AUTO_ALL_MAX_MOVES`, whatever the limit.
#[test]
fn auto_planning_under_a_time_limit_plans_all_only_when_it_fits() {
    let known_by = |cell: &Cell, planning: Planning, limit: Option<Duration>| {
        let opts = SolveOptions {
            time_limit: limit,
            ..opts(planning)
        };
        let prepared = wcp::prepare(cell, &opts, &()).unwrap();
        assert!(prepared.unfinished.is_none());
        prepared.known.iter().map(|k| k.len()).sum::<usize>()
    };
    let known = |cell: &Cell, limit: Option<Duration>| known_by(cell, Planning::Auto, limit);
    let all_moves = |cell: &Cell| -> usize {
        (0..cell.robots.len())
            .map(|r| robot_nodes(cell, r).len())
            .map(|n| n * (n - 1))
            .sum()
    };
    let small = cell(2, 20, 2, 1);
    let hour = Some(Duration::from_secs(3600));
    assert_eq!(known(&small, hour), all_moves(&small));
    assert_eq!(known(&small, None), all_moves(&small));
    let large = cell(8, 300, 4, 1);
    assert!(all_moves(&large) / 2 > wcp::AUTO_ALL_MAX_MOVES);
    // The moves lazy planning plans: from the nearest home of each task, both ways.
    let lazy = known_by(&large, Planning::Lazy, None);
    assert!(lazy < all_moves(&large) / 10);
    assert_eq!(known(&large, hour), lazy);
}
