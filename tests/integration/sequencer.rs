//! The sequencer against an independent exhaustive search, and its contract:
//! valid plans, honest costs, determinism, conflicts avoided.

use crate::common::on_threads;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use workcell::wcp::sequencer::{
    count_violations, solve, solve_from, steps, Conflict, Instance, SequencerError,
    SequencerOptions, Solution, Step,
};

/// Random instance: points in a 10 × 10 square, one home per robot, travel
/// = distance / robot speed, slower uphill (asymmetric); each task allowed
/// to each robot with probability `p_allowed` (at least one); `infinite`
/// random arcs removed.
fn random_instance(
    seed: u64,
    robots: usize,
    tasks: usize,
    p_allowed: f64,
    infinite: usize,
) -> Instance {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut point = || (rng.random_range(0.0..10.0), rng.random_range(0.0..10.0));
    let homes: Vec<(f64, f64)> = (0..robots).map(|_| point()).collect();
    let spots: Vec<(f64, f64)> = (0..tasks).map(|_| point()).collect();
    let speed: Vec<f64> = (0..robots).map(|_| rng.random_range(0.5..2.0)).collect();
    let duration: Vec<f64> = (0..tasks).map(|_| rng.random_range(0.0..3.0)).collect();
    let mut allowed = vec![vec![false; tasks]; robots];
    for t in 0..tasks {
        for row in allowed.iter_mut() {
            row[t] = rng.random_bool(p_allowed);
        }
        allowed[rng.random_range(0..robots)][t] = true;
    }
    let cut: Vec<(usize, usize, usize)> = (0..infinite)
        .map(|_| {
            let r = rng.random_range(0..robots);
            (r, rng.random_range(0..=tasks), rng.random_range(0..=tasks))
        })
        .collect();
    Instance::from_fn(duration, allowed, |r, a, b| {
        if cut.contains(&(r, a, b)) {
            return f64::INFINITY;
        }
        let at = |v: usize| if v == 0 { homes[r] } else { spots[v - 1] };
        let (p, q) = (at(a), at(b));
        let dist = ((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt();
        dist / speed[r] * (1.0 + 0.02 * (q.1 - p.1))
    })
    .unwrap()
}

/// Route time, computed here without the crate.
fn route_cost(inst: &Instance, r: usize, seq: &[usize]) -> f64 {
    if seq.is_empty() {
        return 0.0;
    }
    let mut nodes = vec![0];
    nodes.extend(seq.iter().map(|t| t + 1));
    nodes.push(0);
    let travel: f64 = nodes.windows(2).map(|w| inst.travel(r, w[0], w[1])).sum();
    travel + seq.iter().map(|&t| inst.duration[t]).sum::<f64>()
}

/// Smallest makespan over every assignment and every order: task `t` goes
/// to every allowed robot at every position of its route so far.
fn exhaustive(inst: &Instance) -> f64 {
    fn go(inst: &Instance, t: usize, routes: &mut Vec<Vec<usize>>, best: &mut f64) {
        if t == inst.tasks {
            let mk = (0..inst.robots)
                .map(|r| route_cost(inst, r, &routes[r]))
                .fold(0.0, f64::max);
            *best = best.min(mk);
            return;
        }
        for r in 0..inst.robots {
            if !inst.allowed[r][t] {
                continue;
            }
            for k in 0..=routes[r].len() {
                routes[r].insert(k, t);
                go(inst, t + 1, routes, best);
                routes[r].remove(k);
            }
        }
    }
    let mut best = f64::INFINITY;
    go(inst, 0, &mut vec![Vec::new(); inst.robots], &mut best);
    best
}

/// Each task once, by an allowed robot; the reported costs are the plan's.
fn assert_valid(inst: &Instance, conflicts: &[Conflict], sol: &Solution) {
    assert_eq!(sol.sequences.len(), inst.robots);
    let mut seen = vec![0; inst.tasks];
    for (r, seq) in sol.sequences.iter().enumerate() {
        for &t in seq {
            assert!(inst.allowed[r][t], "robot {r} may not do task {t}");
            seen[t] += 1;
        }
    }
    assert!(seen.iter().all(|&k| k == 1), "tasks done {seen:?} times");
    assert_eq!(sol.makespan, inst.makespan(&sol.sequences));
    assert!(sol.makespan.is_finite());
    let total: f64 = (0..inst.robots)
        .map(|r| route_cost(inst, r, &sol.sequences[r]))
        .sum();
    assert!((sol.total - total).abs() <= 1e-9 * total.max(1.0));
    assert_eq!(sol.violations, count_violations(conflicts, &sol.sequences));
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

/// Seeds and sizes of the small instances compared with the exhaustive search.
fn small_cases() -> Vec<(u64, usize, usize, f64, usize)> {
    (0..36u64)
        .map(|s| {
            let robots = 1 + (s % 3) as usize;
            let tasks = 3 + (s % 6) as usize;
            let p = [1.0, 0.7, 0.5][(s / 3 % 3) as usize];
            let infinite = [0, 2, 6][(s / 9 % 3) as usize];
            (1000 + s, robots, tasks, p, infinite)
        })
        .chain((0..6).map(|s| (2000 + s, 3, 8, 0.8, 3)))
        .collect()
}

#[test]
fn exact_matches_exhaustive_search() {
    for (seed, robots, tasks, p, infinite) in small_cases() {
        let inst = random_instance(seed, robots, tasks, p, infinite);
        let best = exhaustive(&inst);
        match solve(&inst, &[], &SequencerOptions::default()) {
            Ok(sol) => {
                assert_valid(&inst, &[], &sol);
                assert!(sol.optimal, "seed {seed}");
                assert!(
                    close(sol.makespan, best),
                    "seed {seed}: {} vs {best}",
                    sol.makespan
                );
            }
            Err(e) => {
                assert!(best.is_infinite(), "seed {seed}: {e} but {best} exists");
                assert!(matches!(
                    e,
                    SequencerError::TaskUnassignable { .. } | SequencerError::Infeasible
                ));
            }
        }
    }
}

#[test]
fn heuristic_reaches_the_optimum_and_never_undercuts_it() {
    let opts = SequencerOptions {
        exact_limit: 0,
        ..SequencerOptions::default()
    };
    let mut missed = Vec::new();
    for (seed, robots, tasks, p, infinite) in small_cases() {
        let inst = random_instance(seed, robots, tasks, p, infinite);
        let best = exhaustive(&inst);
        let Ok(sol) = solve(&inst, &[], &opts) else {
            assert!(best.is_infinite(), "seed {seed}");
            continue;
        };
        assert_valid(&inst, &[], &sol);
        assert!(!sol.optimal);
        assert!(
            sol.makespan >= best * (1.0 - 1e-9),
            "seed {seed}: below the optimum"
        );
        if !close(sol.makespan, best) {
            missed.push((seed, sol.makespan / best));
        }
    }
    println!("heuristic misses: {missed:?}");
    assert!(missed.is_empty(), "heuristic missed {missed:?}");
}

#[test]
fn steps_of_routes() {
    assert_eq!(steps(&[]), vec![Step::Stay { node: 0 }]);
    assert_eq!(
        steps(&[2, 0]),
        vec![
            Step::Stay { node: 0 },
            Step::Move { from: 0, to: 3 },
            Step::Stay { node: 3 },
            Step::Move { from: 3, to: 1 },
            Step::Stay { node: 1 },
            Step::Move { from: 1, to: 0 },
        ]
    );
}

#[test]
fn same_seed_same_solution_whatever_the_threads() {
    let inst = random_instance(7, 6, 40, 0.5, 10);
    let opts = SequencerOptions {
        seed: 42,
        iterations: 50,
        ..SequencerOptions::default()
    };
    let a = solve(&inst, &[], &opts).unwrap();
    let b = solve(&inst, &[], &opts).unwrap();
    let c = on_threads(1, || solve(&inst, &[], &opts)).unwrap();
    assert_eq!(a, b);
    assert_eq!(a, c);
    assert_valid(&inst, &[], &a);
}

/// Conflicts between the first two busy robots of the blind optimum.
/// A target (a repair's aim) missed changes nothing; met, it ends the search: the first
/// wave of restarts stops at its first plan, and the others never run.
#[test]
fn a_target_ends_the_search_once_met_and_changes_nothing_when_missed() {
    use std::sync::atomic::{AtomicUsize, Ordering};
    let inst = random_instance(7, 6, 40, 0.5, 10);
    let opts = SequencerOptions {
        seed: 42,
        iterations: 50,
        exact_limit: 0,
        ..SequencerOptions::default()
    };
    let heard = AtomicUsize::new(0);
    let count = |_: f64| {
        heard.fetch_add(1, Ordering::Relaxed);
    };
    let free = solve_from(&inst, &[], &opts, None, &count).unwrap();
    let untargeted = heard.swap(0, Ordering::Relaxed);
    let aim = |target: f64| SequencerOptions {
        target: Some(target),
        ..opts.clone()
    };
    assert_eq!(solve(&inst, &[], &aim(0.5 * free.makespan)).unwrap(), free);
    let met = solve_from(&inst, &[], &aim(f64::INFINITY), None, &count).unwrap();
    assert_valid(&inst, &[], &met);
    assert_eq!(
        heard.load(Ordering::Relaxed),
        2,
        "one plan per restart of the first wave"
    );
    assert!(
        untargeted > 4,
        "every restart improves at least once: {untargeted}"
    );
    // Met at the free search's makespan: no longer than it, found as soon as it is.
    let exact = solve(&inst, &[], &aim(free.makespan)).unwrap();
    assert!(exact.makespan <= free.makespan * (1.0 + 1e-9));
    assert_eq!(
        on_threads(1, || solve(&inst, &[], &aim(free.makespan))).unwrap(),
        exact
    );
    // One chain, aimed at a makespan it passes on the way: it stops at the first plan that
    // meets the aim.
    let heard = std::sync::Mutex::new(Vec::new());
    let record = |m: f64| heard.lock().unwrap().push(m);
    let one = SequencerOptions {
        restarts: 1,
        iterations: 400,
        ..opts.clone()
    };
    solve_from(&inst, &[], &one, None, &record).unwrap();
    let bests = std::mem::take(&mut *heard.lock().unwrap());
    assert!(bests.len() > 2, "the chain improves: {bests:?}");
    let target = bests[bests.len() / 2];
    let aimed = SequencerOptions {
        target: Some(target),
        ..one
    };
    let sol = solve_from(&inst, &[], &aimed, None, &record).unwrap();
    let stopped = heard.into_inner().unwrap();
    let met = bests.iter().position(|&m| m <= target).unwrap();
    assert_eq!(stopped, bests[..=met], "stops where it meets {target}");
    assert!(sol.makespan <= target * (1.0 + 1e-9));
}

fn conflicts_against(sol: &Solution) -> Vec<Conflict> {
    let busy: Vec<usize> = (0..sol.sequences.len())
        .filter(|&r| !sol.sequences[r].is_empty())
        .collect();
    assert!(busy.len() >= 2, "the test needs two busy robots");
    let (r, q) = (busy[0], busy[1]);
    let (t, u) = (sol.sequences[r][0], sol.sequences[q][0]);
    vec![
        Conflict {
            a: (r, Step::Stay { node: t + 1 }),
            b: (q, Step::Stay { node: u + 1 }),
        },
        Conflict {
            a: (q, Step::Move { from: 0, to: u + 1 }),
            b: (r, Step::Stay { node: 0 }),
        },
    ]
}

#[test]
fn avoidable_conflicts_are_avoided() {
    for (seed, exact_limit) in [(11, 0), (11, u64::MAX), (12, 0), (12, u64::MAX)] {
        let inst = random_instance(seed, 3, 7, 1.0, 0);
        let opts = SequencerOptions {
            exact_limit,
            ..SequencerOptions::default()
        };
        let blind = solve(&inst, &[], &SequencerOptions::default()).unwrap();
        let conflicts = conflicts_against(&blind);
        assert_eq!(count_violations(&conflicts, &blind.sequences), 2);
        let sol = solve(&inst, &conflicts, &opts).unwrap();
        assert_valid(&inst, &conflicts, &sol);
        assert_eq!(sol.violations, 0, "seed {seed}");
        assert!(sol.makespan >= blind.makespan * (1.0 - 1e-12));
        assert!(!sol.optimal);
        let again = solve(&inst, &conflicts, &opts).unwrap();
        assert_eq!(sol, again);
    }
}

#[test]
fn conflicts_the_optimum_misses_keep_it_optimal() {
    let inst = random_instance(13, 3, 6, 1.0, 0);
    let blind = solve(&inst, &[], &SequencerOptions::default()).unwrap();
    // A robot staying at a task it does not do is never chosen.
    let (r, t) = (0..3)
        .flat_map(|r| (0..6).map(move |t| (r, t)))
        .find(|&(r, t)| !blind.sequences[r].contains(&t))
        .unwrap();
    let conflicts = [Conflict {
        a: (r, Step::Stay { node: t + 1 }),
        b: (r, Step::Stay { node: 0 }),
    }];
    let sol = solve(&inst, &conflicts, &SequencerOptions::default()).unwrap();
    assert_eq!(sol, blind);
}

#[test]
fn unavoidable_conflicts_are_counted() {
    let inst = random_instance(14, 2, 5, 1.0, 0);
    let home = (0, Step::Stay { node: 0 });
    let conflicts = [Conflict {
        a: home,
        b: (1, Step::Stay { node: 0 }),
    }];
    let sol = solve(&inst, &conflicts, &SequencerOptions::default()).unwrap();
    assert_valid(&inst, &conflicts, &sol);
    assert_eq!(sol.violations, 1);
    let blind = solve(&inst, &[], &SequencerOptions::default()).unwrap();
    assert!(close(sol.makespan, blind.makespan));
}

#[test]
fn errors() {
    let inf = f64::INFINITY;
    // Task 1 is only allowed to robot 0, which cannot get there.
    let travel = vec![0.0, 1.0, inf, 1.0, 0.0, inf, inf, inf, 0.0];
    let inst = Instance::new(vec![1.0, 1.0], vec![vec![true, true]], vec![travel]).unwrap();
    let err = solve(&inst, &[], &SequencerOptions::default()).unwrap_err();
    assert_eq!(err, SequencerError::TaskUnassignable { task: 1 });
    // Both tasks reachable, but not one from the other: one robot cannot do both.
    let travel = vec![0.0, 1.0, 1.0, 1.0, 0.0, inf, 1.0, inf, 0.0];
    let inst = Instance::new(vec![1.0, 1.0], vec![vec![true, true]], vec![travel]).unwrap();
    for exact_limit in [0, u64::MAX] {
        let opts = SequencerOptions {
            exact_limit,
            ..SequencerOptions::default()
        };
        assert_eq!(
            solve(&inst, &[], &opts).unwrap_err(),
            SequencerError::Infeasible
        );
    }
    let bad = [Conflict {
        a: (1, Step::Stay { node: 0 }),
        b: (0, Step::Stay { node: 0 }),
    }];
    let err = solve(&inst, &bad, &SequencerOptions::default()).unwrap_err();
    assert!(matches!(err, SequencerError::BadConflict { index: 0, .. }));
}

#[test]
fn no_tasks() {
    let inst = Instance::new(vec![], vec![vec![]; 2], vec![vec![0.0]; 2]).unwrap();
    for exact_limit in [0, u64::MAX] {
        let opts = SequencerOptions {
            exact_limit,
            ..SequencerOptions::default()
        };
        let sol = solve(&inst, &[], &opts).unwrap();
        assert_eq!(sol.sequences, vec![Vec::<usize>::new(); 2]);
        assert_eq!(sol.makespan, 0.0);
    }
}

#[test]
fn many_conflicts_on_a_larger_instance() {
    let inst = random_instance(15, 8, 60, 0.4, 0);
    let opts = SequencerOptions::default();
    let blind = solve(&inst, &[], &opts).unwrap();
    // Forbid random pairs of steps the blind plan makes with two robots.
    let mut rng = ChaCha8Rng::seed_from_u64(15);
    let made: Vec<(usize, Step)> = (0..inst.robots)
        .flat_map(|r| {
            steps(&blind.sequences[r])
                .into_iter()
                .skip(1)
                .map(move |s| (r, s))
        })
        .collect();
    let mut conflicts = Vec::new();
    while conflicts.len() < 60 {
        let (a, b) = (
            made[rng.random_range(0..made.len())],
            made[rng.random_range(0..made.len())],
        );
        if a.0 != b.0 {
            conflicts.push(Conflict { a, b });
        }
    }
    assert_eq!(count_violations(&conflicts, &blind.sequences), 60);
    let sol = solve(&inst, &conflicts, &opts).unwrap();
    assert_valid(&inst, &conflicts, &sol);
    assert_eq!(sol.violations, 0);
}

/// Instances from 3 x 8 up to 12 x 120 all get valid plans with honest costs (their times
/// are measured by `cargo bench --bench solve`, not here).
#[test]
fn valid_plans_from_small_to_hall_sized_instances() {
    let cases = [
        (3, 8, 1.0, 21),
        (4, 12, 1.0, 22),
        (4, 20, 1.0, 23),
        (12, 120, 0.33, 24),
    ];
    for (robots, tasks, p, seed) in cases {
        let inst = random_instance(seed, robots, tasks, p, 0);
        let sol = solve(&inst, &[], &SequencerOptions::default()).unwrap();
        assert_valid(&inst, &[], &sol);
    }
}

/// A deadline already past: the granular search builds its first plan with near insertions
/// and stops its descents at once, and still returns a valid plan of every task. With only
/// the search's deadline past, the first plan is the full cheapest-insertion construction,
/// valid too.
#[test]
fn a_past_deadline_still_gives_a_whole_valid_plan() {
    use std::time::Instant;
    use workcell::wcp::sequencer::GRANULAR_FROM_TASKS;
    let inst = random_instance(7, 3, GRANULAR_FROM_TASKS + 50, 0.6, 0);
    let free = SequencerOptions {
        iterations: 5,
        restarts: 1,
        ..SequencerOptions::default()
    };
    let unhurried = solve(&inst, &[], &free).unwrap();
    assert_valid(&inst, &[], &unhurried);
    let past = Some(Instant::now());
    let hurried = SequencerOptions {
        deadline: past,
        construction_deadline: past,
        ..free.clone()
    };
    let sol = solve(&inst, &[], &hurried).unwrap();
    assert_valid(&inst, &[], &sol);
    // Hurried, it is worse here: it neither inserted where it costs least nor descended.
    assert!(
        sol.makespan > unhurried.makespan,
        "{} vs {}",
        sol.makespan,
        unhurried.makespan
    );
    // Only the search stopped (the construction's own deadline far off): the first plan is
    // the full construction, not descended.
    let built = SequencerOptions {
        deadline: past,
        construction_deadline: Some(Instant::now() + std::time::Duration::from_secs(3600)),
        ..free.clone()
    };
    let sol_built = solve(&inst, &[], &built).unwrap();
    assert_valid(&inst, &[], &sol_built);
    assert!(sol_built.makespan >= unhurried.makespan);
    // The construction in full beats the hurried one: the two deadlines are apart.
    assert!(
        sol_built.makespan < sol.makespan,
        "{} vs {}",
        sol_built.makespan,
        sol.makespan
    );
}
