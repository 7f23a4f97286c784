//! The feedback loop: the search over remedies on the conflict cells (no divergence, every
//! cell solved, the limits kept), each remedy where it is needed, the shipped cells'
//! documented results, the greedy loop's documented choices, and determinism.

use crate::common::{shipped_cell, solve_with};
use std::path::{Path, PathBuf};
use workcell::cell::{parse_cell, parse_scene, scene_document, Cell};
use workcell::collision::{check, CheckOptions};
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
    assert!(solved.collision_free, "{:?}", solved.failure);
    let text = serde_json::to_string(&scene_document(&solved.schedule.scene(cell))).unwrap();
    let scene = parse_scene(&text, Path::new("exported.json"))
        .unwrap()
        .scene;
    let report = check(&scene, &CheckOptions::default());
    assert!(
        !report.collision && report.certified,
        "{:?}",
        report.first_contact
    );
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

#[test]
fn every_conflict_family_is_solved_without_divergence() {
    // Rings need a group to move at once: see `a_ring_is_solved_or_its_blockers_named`.
    for kind in ConflictKind::ALL
        .into_iter()
        .filter(|k| *k != ConflictKind::Ring)
    {
        // Cell 0 of the workpiece family has a collision-free blind plan (since the
        // sequencer exchanges route ends, 2-opt*): cell 1 exercises the feedback.
        let index = if kind == ConflictKind::Workpiece {
            1
        } else {
            0
        };
        let cell = conflict_cell(kind, index);
        let solved = solve(&cell);
        // The issue's targets, where it sets one: a narrow swap within 35 %, the junction
        // within 40 % (the README's table gives every cell).
        let target = match kind {
            ConflictKind::CorridorNarrow => 0.35,
            ConflictKind::Junction => 0.40,
            _ => f64::INFINITY,
        };
        // And no longer than the search's answer when this test was last tuned (ceilings,
        // not pins: a better search passes; a worse ranking of children fails at the
        // junction). The aisles' 60.778 was 59.399 before the second pass had a share of the
        // budget: the first pass found that schedule after 4,747 checks, when it now stops
        // at 3,500; the junction's was 36.765, the doorway's 30.988.
        let ceiling = match kind {
            ConflictKind::CorridorNarrow => 42.812,
            ConflictKind::CorridorWide => 31.035,
            ConflictKind::Junction => 36.165,
            ConflictKind::Doorway => 30.873,
            ConflictKind::HomeInWay => 21.286,
            ConflictKind::Workpiece => 22.435,
            ConflictKind::Aisles => 60.778,
            ConflictKind::Ring => unreachable!("rings are left out"),
        };
        assert!(
            solved.schedule.makespan <= ceiling + 1e-3,
            "{}: {:.3} above {ceiling}",
            kind.name(),
            solved.schedule.makespan
        );
        assert!(
            overhead(&solved) <= target,
            "{}: {:.3}",
            kind.name(),
            overhead(&solved)
        );
        assert!(
            solved.iterations[0].collision.is_some(),
            "{}: the blind schedule collides",
            kind.name()
        );
        assert_certified_within_limits(&cell, &solved);
        // The answer's branch is a few rounds per conflict, far from the depth limit.
        assert!(
            solved.iterations.len() < SolveOptions::default().max_iterations / 2,
            "{}: {} rounds",
            kind.name(),
            solved.iterations.len()
        );
    }
}

#[test]
fn the_search_beats_the_greedy_loop_where_that_one_diverges() {
    // The junction of the issue: the greedy loop piles up waits at homes that are in the
    // other robots' way and ends without a schedule.
    let cell = conflict_cell(ConflictKind::Junction, 0);
    let greedy = solve_with(
        &cell,
        &SolveOptions {
            feedback: Feedback::Greedy,
            ..SolveOptions::default()
        },
    );
    assert!(!greedy.collision_free);
    let searched = solve(&cell);
    assert_certified_within_limits(&cell, &searched);
    // Not a budget's luck: the first certified schedule is found in a few dozen checks.
    let mut few = SolveOptions::default();
    few.search.max_nodes = 200;
    assert!(solve_with(&cell, &few).collision_free);
}

#[test]
fn stepping_aside_is_the_only_way_out_of_a_home_in_the_way() {
    // R2 has no task and its home lies in the dead-end corridor R1 must enter and leave.
    let cell = conflict_cell(ConflictKind::HomeInWay, 0);
    assert!(cell.tasks.iter().all(|t| t.robots == [0]));
    let solved = solve(&cell);
    assert_certified_within_limits(&cell, &solved);
    assert!(remedies(&solved)
        .iter()
        .any(|r| matches!(r.kind, RemedyKind::StepAside { .. })
            && r.on.is_some_and(|l| l.robot == 1)));
    // R1 is delayed by nothing: R2 makes way.
    assert_eq!(solved.schedule.makespan, solved.blind_makespan);
    let without = solve_with(&cell, &all_but("step-aside"));
    assert!(!without.collision_free);
    assert!(without.failure.unwrap().contains("R2"));
}

/// R2 welds for 100 s right on R1's straight way to its task and back.
const WORKING_IN_THE_WAY: &str = r#"{"delta": 0.01, "robots": [
  {"name": "R1", "shape": [[-0.35,-0.35],[0.35,-0.35],[0.35,0.35],[-0.35,0.35]],
   "home": [0, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1.5},
  {"name": "R2", "shape": [[-0.35,-0.35],[0.35,-0.35],[0.35,0.35],[-0.35,0.35]],
   "home": [5, 3], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1.5}],
 "tasks": [{"name": "far", "at": [10, 0], "duration": 1, "robots": ["R1"]},
           {"name": "long-weld", "at": [5, 0], "duration": 100, "robots": ["R2"]}]}"#;

#[test]
fn a_detour_goes_round_a_robot_that_is_working() {
    let cell = parse_cell(WORKING_IN_THE_WAY, Path::new("working.json"))
        .unwrap()
        .cell;
    let solved = solve(&cell);
    assert_certified_within_limits(&cell, &solved);
    let detours: Vec<_> = remedies(&solved)
        .into_iter()
        .filter(|r| {
            matches!(r.kind, RemedyKind::Detour { around: 1, .. })
                && r.on.is_some_and(|l| l.robot == 0)
        })
        .collect();
    // There and back.
    assert_eq!(detours.len(), 2, "{:?}", remedies(&solved));
    assert!(solved.schedule.makespan <= solved.blind_makespan * 1.001);
    // Without going round (nor pulling in beside its way, from where it may go round too),
    // one waits for the other: R2 starts its weld after R1 has passed (15 s later), or,
    // let through, R1 waits at its far task until the weld is done (7 s later).
    let without = solve_with(&cell, &none_of(&["detour", "pass-aside"]));
    assert!(without.collision_free);
    assert!(without.schedule.makespan > solved.schedule.makespan + 5.0);
}

#[test]
fn a_corridor_crossing_with_two_tasks_each_costs_at_most_a_quarter() {
    let cell = conflict_cell(ConflictKind::CorridorNarrow, 1);
    assert_eq!(cell.tasks.len(), 4);
    let solved = solve(&cell);
    assert_certified_within_limits(&cell, &solved);
    assert!(overhead(&solved) <= 0.25, "{:.3}", overhead(&solved));
}

#[test]
fn robots_pass_side_by_side_in_a_wide_corridor() {
    // Two tasks each on the far side of a corridor 2.4 wide: they swap there and back.
    let cell = conflict_cell(ConflictKind::CorridorWide, 1);
    let solved = solve(&cell);
    assert_certified_within_limits(&cell, &solved);
    assert!(remedies(&solved)
        .iter()
        .any(|r| matches!(r.kind, RemedyKind::Detour { .. })));
    assert!(solved.schedule.makespan <= solved.blind_makespan * 1.01);
    // One at a time, as in a narrow corridor, costs far more (pulling in at a passing
    // place beside the way lets them pass side by side too).
    let without = solve_with(&cell, &none_of(&["detour", "pass-aside"]));
    assert!(without.schedule.makespan > solved.schedule.makespan * 1.02);
}

#[test]
fn a_pause_on_the_way_or_a_slower_move_each_separate_a_crossing() {
    let cell = conflict_cell(ConflictKind::CorridorWide, 2);
    let paused = solve_with(&cell, &only(&["pause"]));
    assert_certified_within_limits(&cell, &paused);
    assert!(remedies(&paused)
        .iter()
        .all(|r| matches!(r.kind, RemedyKind::Pause { .. })));
    assert!(!remedies(&paused).is_empty());
    let slowed = solve_with(&cell, &only(&["slow"]));
    assert_certified_within_limits(&cell, &slowed);
    assert!(remedies(&slowed)
        .iter()
        .all(|r| matches!(r.kind, RemedyKind::Slow { factor } if factor > 1.0)));
    assert!(!remedies(&slowed).is_empty());
}

#[test]
fn the_feedback_cell_keeps_its_documented_results() {
    let cell = shipped_cell("feedback-cell.json");
    // The search: re-sequenced, then R1 pauses on its way to weld 2 (15.711), a pause
    // then shortened as far as R2 allows.
    let solved = solve(&cell);
    assert_certified_within_limits(&cell, &solved);
    assert_eq!(format!("{:.3}", solved.blind_makespan), "15.415");
    assert_eq!(format!("{:.3}", solved.schedule.makespan), "15.710");
    assert_eq!(solved.iterations.len(), 4);
    assert_eq!(format!("{:.3}", solved.iterations[2].makespan), "15.711");
    let taken = remedies(&solved);
    assert!(
        matches!(
            &taken[..],
            [first, Remedy { on: Some(leg), kind: RemedyKind::Pause { .. } },
             Remedy { kind: RemedyKind::Tighten { shortened }, .. }]
                if **first == Remedy::RESEQUENCE && leg.robot == 0
                    && shortened.len() == 1 && shortened[0].after < shortened[0].before
        ),
        "{taken:?}"
    );
    // The greedy loop: re-sequencing wins ties (rounds 1 and 2), then the shortest wait
    // that clears (an eighth of waiting until R1 has left: 1.0 s, not 8).
    let greedy = solve_with(
        &cell,
        &SolveOptions {
            feedback: Feedback::Greedy,
            ..SolveOptions::default()
        },
    );
    assert_certified_within_limits(&cell, &greedy);
    assert_eq!(format!("{:.3}", greedy.schedule.makespan), "15.937");
    assert_eq!(greedy.iterations.len(), 4);
    let taken = remedies(&greedy);
    assert!(
        matches!(taken[..], [a, b, Remedy { on: Some(leg), kind: RemedyKind::Wait { duration } }]
            if *a == Remedy::RESEQUENCE && *b == Remedy::RESEQUENCE
                && leg.robot == 1 && (duration - 1.000).abs() < 5e-4),
        "{taken:?}"
    );
    // Re-sequencing alone also separates them, at a higher cost.
    let resequenced = solve_with(&cell, &only(&["resequence"]));
    assert_certified_within_limits(&cell, &resequenced);
    assert_eq!(format!("{:.3}", resequenced.schedule.makespan), "17.307");
}

#[test]
fn shipped_cells_without_conflicts_keep_their_makespans() {
    for (name, makespan) in [
        ("paper-cell.json", "36.165"),
        ("four-robots-cell.json", "32.475"),
    ] {
        let cell = shipped_cell(name);
        let solved = solve(&cell);
        assert_eq!(solved.iterations.len(), 1, "{name}");
        assert_eq!(
            format!("{:.3}", solved.schedule.makespan),
            makespan,
            "{name}"
        );
    }
}

#[test]
fn the_search_is_the_same_on_one_two_and_four_threads() {
    let cell = conflict_cell(ConflictKind::Doorway, 1);
    let mut opts = SolveOptions::default();
    // A node budget, not a time limit: the result depends on nothing else.
    opts.search.max_nodes = 400;
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let solved = solve_with(&cell, &opts);
            let legs = wcp::remedy_json::legs_json(&cell, &solved.routes, &solved.legs);
            (
                solved.schedule.makespan.to_bits(),
                solved.routes.clone(),
                serde_json::to_string(&legs).unwrap(),
                solved.nodes,
                solved.iterations.len(),
            )
        })
    };
    let one = run(1);
    assert!(one.3 > 1, "the search branches");
    assert_eq!(one, run(2));
    assert_eq!(one, run(4));
    assert_eq!(one, run(2), "and again");
}

/// On a cell of 100 to 199 tasks a re-sequencing is a local repair (`search/pending.rs`,
/// `LOCAL_RESEQUENCE_FROM_TASKS`), and a repair makes no route-end exchanges
/// (`SequencerOptions::route_exchanges`): from its blind plan (21.50) `workpiece-3` (10
/// robots, 100 tasks) is certified at 21.78 by such repairs alone, after 99 schedules. The
/// search's second pass, once nothing is left, asks the re-sequencings that led there
/// again with exchanges (`Search::widen_repairs`) and certifies the blind plan's 21.50
/// (pinned), as the search did before the sequencer exchanged route ends; the schedules
/// checked are a ceiling, not a pin.
#[test]
fn a_resequencing_on_a_hundred_task_cell_is_a_local_repair() {
    let solved = solve(&conflict_cell(ConflictKind::Workpiece, 3));
    assert!(solved.collision_free);
    assert!(
        (solved.schedule.makespan - 21.50).abs() < 5e-3,
        "{}",
        solved.schedule.makespan
    );
    assert!(solved.nodes <= 112, "{} schedules checked", solved.nodes);
}

/// A repair makes no route-end exchanges (`SequencerOptions::route_exchanges`): they move
/// whole route ends between robots, whose schedules must then be checked again.
/// `workpiece-4` (12 robots, 120 tasks) is certified at its collision-blind makespan within
/// 600 schedules (581 today; 605 with exchanges in repairs, at local optima as the default
/// solve makes them, and 1,628 with exchanges in every round of a repair).
#[test]
fn a_repair_keeps_the_route_ends() {
    let solved = solve(&conflict_cell(ConflictKind::Workpiece, 4));
    assert!(solved.collision_free);
    assert!(solved.schedule.makespan <= solved.blind_makespan * (1.0 + 1e-9));
    assert!(solved.nodes <= 600, "{} schedules checked", solved.nodes);
}

/// The answer's waits and holds are shortened as far as the other robots allow
/// (`search/tighten.rs`), and so are those of every schedule that was the best when found:
/// on the junction of seed 1, cell 3 comes down from 50.405 to 49.049 (the answer's wait
/// before R1's way home, 2.24 s, shortened to 0.73), and cell 4 from 42.745 to 42.665, the
/// shortened form of a schedule found earlier, which was longer (42.75 or more) but
/// shortens further (the answer was found when that schedule was, after 3,711 checks, not
/// 4,144); the doorway of seven robots (cell 3) from 39.988 to 39.416, in several passes
/// over the robots (39.85 in one). Each with the whole budget to the first pass, where
/// those schedules were found.
#[test]
fn the_answer_holds_no_longer_than_the_other_robots_allow() {
    let shortened = |solved: &Solved| {
        let n = solved.iterations.len();
        let before = &solved.iterations[n - 2];
        assert!(
            before.collision.is_none(),
            "a certified schedule, shortened"
        );
        let remedy = before.remedy.as_ref().expect("shortened");
        assert!(
            matches!(remedy.kind, RemedyKind::Tighten { .. }),
            "{remedy:?}"
        );
        before.makespan
    };
    // Cell, the makespan shortened, and the one it was shortened from.
    for (kind, k, makespan, from) in [
        (ConflictKind::Junction, 3, 49.05, 50.4),
        (ConflictKind::Junction, 4, 42.67, 42.75),
        (ConflictKind::Doorway, 3, 39.42, 39.9),
    ] {
        let cell = conflict_cell(kind, k);
        let solved = solve_with(&cell, &first_pass_only());
        assert_certified_within_limits(&cell, &solved);
        let got = solved.schedule.makespan;
        assert!(got < makespan, "{}-{k}: {got}", kind.name());
        assert!(shortened(&solved) > from, "{}-{k}", kind.name());
        if (kind, k) == (ConflictKind::Junction, 4) {
            assert!(
                solved.found_after.is_some_and(|n| n < 4000),
                "{:?}",
                solved.found_after
            );
        }
    }
}

/// `patience` ends the search once it stops paying, and only ends it sooner: the answer is
/// the one a budget of that many schedules gives (the whole budget to the first pass, so
/// that a smaller one does not move the second pass sooner). An answer found late earns as
/// long a search again: on the junction, with a patience of 400, the answer found after 940
/// checks ends the search after 1,881, 941 checks later, not 400.
#[test]
fn patience_ends_the_search_once_it_stops_paying() {
    let cell = conflict_cell(ConflictKind::Junction, 0);
    let mut opts = first_pass_only();
    opts.search.patience = Some(400);
    let patient = solve_with(&cell, &opts);
    let checked = patient.nodes;
    assert!(patient.collision_free);
    // It stopped once it had checked 400 schedules, and as many as the answer took, since
    // the answer (`found_after`), which took more than 400.
    let found = patient.found_after.expect("an answer");
    assert!(found > 400, "{found}");
    assert!(
        (found.max(400)..found.max(400) + 100).contains(&(checked - found)),
        "{found} of {checked}"
    );
    assert!(checked < opts.search.max_nodes, "{checked}");
    let mut budget = first_pass_only();
    budget.search.max_nodes = checked;
    let same = solve_with(&cell, &budget);
    assert_eq!(same.nodes, checked);
    assert_eq!(same.schedule.makespan, patient.schedule.makespan);
    // Without it, the whole budget is spent, and finds better.
    let whole = solve_with(&cell, &first_pass_only());
    assert!(whole.nodes > checked && whole.schedule.makespan < patient.schedule.makespan);
}

/// By default the first pass ends once it has gone 2,000 schedules (and as many as its
/// answer took) without finding better, and the second pass then has its 30 % share: the
/// ring of seven robots of `generate --kind conflict --seed 1`, certified after 45 checks,
/// is answered after 3,656 instead of the whole budget's 5,000, with the same makespan.
#[test]
fn the_first_pass_ends_once_it_stops_paying() {
    let cell = conflict_cell(ConflictKind::Ring, 9);
    let opts = SolveOptions::default();
    let patient = solve_with(&cell, &opts);
    assert!(patient.collision_free, "{:?}", patient.failure);
    let found = patient.found_after.expect("an answer");
    let patience = opts.search.patience.expect("on by default");
    assert_eq!(patience, 2000);
    // The first pass's patience, then the second's whole share (give or take a batch of
    // children past each).
    let share = (opts.search.second_pass_share * opts.search.max_nodes as f64) as usize;
    let floor = found + patience.max(found) + share;
    assert!(
        (floor..=floor + 200).contains(&patient.nodes),
        "{} not within {floor} + 200",
        patient.nodes
    );
    let mut whole = opts;
    whole.search.patience = None;
    let spent = solve_with(&cell, &whole);
    assert_eq!(spent.nodes, whole.search.max_nodes);
    assert_eq!(spent.schedule.makespan, patient.schedule.makespan);
}

/// Remembering answers (a re-sequencing asked again, the remedies of a collision met again)
/// changes the time, never the search: on a junction, where both are asked again often and
/// their children differ in other robots' legs, and on a ring that a convoy solves (a
/// convoy reads every robot's route), the same nodes, rounds and schedule.
#[test]
fn remembering_changes_nothing_but_the_time() {
    for cell in [
        conflict_cell(ConflictKind::Junction, 0),
        conflict_cell(ConflictKind::Ring, 8),
    ] {
        let mut opts = SolveOptions::default();
        opts.search.max_nodes = 300;
        let remembered = solve_with(&cell, &opts);
        opts.search.remember = false;
        let asked_again = solve_with(&cell, &opts);
        assert_eq!(remembered.nodes, asked_again.nodes);
        assert_eq!(remembered.schedule.makespan, asked_again.schedule.makespan);
        assert_eq!(remedies(&remembered), remedies(&asked_again));
        let legs = |s: &Solved| format!("{:?}", s.legs);
        assert_eq!(legs(&remembered), legs(&asked_again));
    }
}

/// A first schedule the checker can neither prove free nor show colliding (its work budget
/// of one evaluation per pair runs out) is an answer that says so, from either feedback,
/// never a panic.
#[test]
fn a_first_schedule_left_undecided_is_reported_not_a_panic() {
    let cell = shipped_cell("paper-cell.json");
    for feedback in [Feedback::Search, Feedback::Greedy] {
        let mut opts = SolveOptions {
            feedback,
            ..SolveOptions::default()
        };
        opts.check.max_work_per_pair = 1;
        let solved = solve_with(&cell, &opts);
        let failure = solved.failure.as_deref().unwrap_or_default();
        assert!(!solved.collision_free, "{feedback:?}");
        assert!(failure.contains("work budget"), "{feedback:?}: {failure}");
    }
}

/// Two robots that must swap the ends of a closed corridor one robot wide: no schedule
/// exists, and the failure says so plainly, naming the two robots, the walls that hem them
/// in and what was exhausted; so does the greedy loop's at its limit of rounds.
#[test]
fn a_swap_in_a_closed_corridor_names_the_blockers_and_the_place() {
    let text = r#"{
      "delta": 0.01,
      "robots": [
        {"name": "R1", "shape": [[-0.3, -0.3], [0.3, -0.3], [0.3, 0.3], [-0.3, 0.3]],
         "home": [2, 0, 0], "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.0},
        {"name": "R2", "shape": [[-0.3, -0.3], [0.3, -0.3], [0.3, 0.3], [-0.3, 0.3]],
         "home": [8, 0, 0], "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.0}
      ],
      "obstacles": [
        {"name": "wall-south", "shape": [[-1, -1.5], [11, -1.5], [11, -0.5], [-1, -0.5]]},
        {"name": "wall-north", "shape": [[-1, 0.5], [11, 0.5], [11, 1.5], [-1, 1.5]]},
        {"name": "cap-west", "shape": [[-1, -0.5], [0, -0.5], [0, 0.5], [-1, 0.5]]},
        {"name": "cap-east", "shape": [[10, -0.5], [11, -0.5], [11, 0.5], [10, 0.5]]}
      ],
      "tasks": [
        {"name": "east-end", "at": [9.3, 0, 0], "duration": 1, "robots": ["R1"]},
        {"name": "west-end", "at": [0.7, 0, 0], "duration": 1, "robots": ["R2"]}
      ]
    }"#;
    let cell = parse_cell(text, Path::new("swap-cell.json")).unwrap().cell;
    let greedy = SolveOptions {
        feedback: Feedback::Greedy,
        max_iterations: 5,
        ..SolveOptions::default()
    };
    for (opts, exhausted) in [
        (
            SolveOptions::default(),
            "no remedy clears the first schedule's collision",
        ),
        (greedy, "the limit of 5 rounds ran out"),
    ] {
        let solved = solve_with(&cell, &opts);
        assert!(!solved.collision_free && solved.found_after.is_none());
        let failure = solved.failure.unwrap();
        assert!(failure.starts_with(exhausted), "{failure}");
        // The corridor is 1.00 wide, the two squares of 0.6 need 1.22 side by side.
        assert!(
            failure.contains("R1 and R2 block each other at (")
                && failure.contains(
                    "between wall-north and wall-south, 1.00 apart: too narrow for the two \
                     side by side (1.22)"
                ),
            "{failure}"
        );
    }
}

/// A search that fails says which of its budgets ran out, and never a limit it did not
/// reach: the rounds when lines of remedies reached them, the schedules when those ran
/// out first (the junction needs more of both), the first pass's share of them when the
/// second pass then found nothing more to try (with waits and pauses only, 14 of 20).
#[test]
fn a_failed_search_names_the_budget_it_exhausted() {
    let cell = conflict_cell(ConflictKind::Junction, 0);
    let rounds = SolveOptions {
        max_iterations: 3,
        ..SolveOptions::default()
    };
    let mut nodes = SolveOptions::default();
    nodes.search.max_nodes = 10;
    let mut share = only(&["wait", "pause"]);
    share.search.max_nodes = 20;
    for (opts, exhausted) in [
        (rounds, "the limit of 3 rounds cut "),
        (nodes, "the search's budget of 10 schedules ran out;"),
        (
            share,
            "the first pass spent its share of the search's budget (14 of 20 schedules), and \
             the second pass tried every remedy along the way that got furthest (17 schedules \
             checked in all);",
        ),
    ] {
        let solved = solve_with(&cell, &opts);
        let failure = solved.failure.unwrap();
        assert!(failure.starts_with(exhausted), "{failure}");
        assert!(failure.contains(" block each other at ("), "{failure}");
        assert!(!failure.contains("200"), "{failure}");
    }
}

/// The search's budget is a most: a search that spends it has checked exactly that many
/// schedules, not a batch of children more (the junction needs more than 50).
#[test]
fn the_search_checks_no_more_schedules_than_its_budget() {
    let cell = conflict_cell(ConflictKind::Junction, 0);
    for budget in [1, 7, 50] {
        let mut opts = SolveOptions::default();
        opts.search.max_nodes = budget;
        let solved = solve_with(&cell, &opts);
        assert!(!solved.collision_free);
        assert_eq!(solved.nodes, budget);
    }
}

/// Doorways that a worse search leaves without a schedule (children ranked by the earlier
/// collision instead of the later: 3, 4, 7 and 8 unsolved): each is solved, no longer than
/// when this test was written.
#[test]
fn the_doorways_a_weaker_search_loses_are_solved() {
    for (k, ceiling) in [(3, 39.988), (4, 42.125), (7, 36.539), (8, 40.416)] {
        let cell = conflict_cell(ConflictKind::Doorway, k);
        let solved = solve(&cell);
        assert!(solved.collision_free, "doorway {k}: {:?}", solved.failure);
        assert!(
            solved.schedule.makespan <= ceiling + 1e-3,
            "doorway {k}: {:.3} above {ceiling}",
            solved.schedule.makespan
        );
    }
}

/// The second pass's share of the budget (the last 30 %): junctions whose first pass keeps
/// finding better schedules late, or wanders off, are shorter when it stops at 3,500 checks
/// and the second goes back along the way to its best, where robots pull into the side arms
/// of the junction (cell 0: 36.765 with the whole budget to the first pass, 36.165 with the
/// share; cell 8: 42.058 and 41.168, and 42.146 when the first pass's queue is kept on
/// beside the second).
#[test]
fn the_second_pass_shortens_junctions_the_first_leaves_long() {
    for (k, first_only, shared) in [(0, 36.765, 36.165), (8, 42.058, 41.168)] {
        let cell = conflict_cell(ConflictKind::Junction, k);
        let solved = solve(&cell);
        assert!(
            solved.schedule.makespan <= shared + 1e-3,
            "junction {k}: {:.3} above {shared}",
            solved.schedule.makespan
        );
        let first = solve_with(&cell, &first_pass_only());
        assert!(
            first.schedule.makespan > first_only - 1e-3,
            "junction {k}: {:.3}",
            first.schedule.makespan
        );
    }
}

/// Two robots swap the rooms at the ends of a corridor one robot wide with a bay off one
/// side (`cells/passing-bay-cell.json`). The first pass has one robot step aside at home
/// while the other crosses the whole corridor, each way: 50.923. Once its queue is empty,
/// the second pass offers passing places beside the way (`remedies/step_aside.rs`): each
/// time one robot pulls into the bay while the other goes by, 41.834 (pinned), and every
/// parking pose of the answer lies inside the bay. Without `pass-aside`, 50.923 again.
#[test]
fn robots_pass_each_other_at_a_bay_off_the_corridor() {
    let cell = shipped_cell("passing-bay-cell.json");
    let solved = solve(&cell);
    assert!(solved.collision_free, "{:?}", solved.failure);
    let makespan = solved.schedule.makespan;
    assert!((makespan - 41.834).abs() < 2e-3, "{makespan}");
    let parks: Vec<_> = (remedies(&solved).into_iter())
        .filter_map(|r| match &r.kind {
            RemedyKind::StepAside { park, .. } => Some(park.pos),
            _ => None,
        })
        .collect();
    assert_eq!(parks.len(), 2, "{parks:?}");
    let in_bay =
        |p: &workcell::geometry::Vec2| (4.5..5.7).contains(&p.x) && (0.5..1.7).contains(&p.y);
    assert!(parks.iter().all(in_bay), "{parks:?}");
    let without = solve_with(&cell, &all_but("pass-aside"));
    assert!(without.collision_free);
    let makespan = without.schedule.makespan;
    assert!((makespan - 50.923).abs() < 2e-3, "{makespan}");
}

/// `tune` is a last resort, checked only when the search takes it: offered with the other
/// children on every collision, its extra schedule in every expansion cost `doorway-4`
/// (eight robots) its schedule within the 5,000-node budget; as a last resort the cell is
/// solved as without it.
#[test]
fn tuning_as_a_last_resort_keeps_the_doorways_schedule() {
    let solved = solve(&conflict_cell(ConflictKind::Doorway, 4));
    assert!(solved.collision_free, "{:?}", solved.failure);
    assert!(solved.schedule.makespan <= 42.125 + 1e-3);
}

/// A ring corridor one robot wide: robots never pass each other. Each cell of `generate
/// --kind ring` (seed 1, rings of three to seven robots) ends with a certified schedule
/// within the default budgets: never a hang, never a schedule that collides.
#[test]
fn every_ring_is_certified() {
    for k in 0..9 {
        let cell = conflict_cell(ConflictKind::Ring, k);
        let solved = solve(&cell);
        assert!(solved.failure.is_none(), "ring {k}: {:?}", solved.failure);
        assert_certified_within_limits(&cell, &solved);
    }
}

/// Seven robots on a ring whose order round it must turn as a whole: no remedy of one or
/// two robots gets there, and without the convoy the cell is refused with a failure that
/// names the two robots blocking each other between the centre block and a wall and says
/// what was exhausted. With it, all seven go round together, each following the one ahead
/// (`remedies/following.rs`), and `ring-8` is certified at 25.720 (38 % over its blind
/// 18.600: a whole lap, its holds then shortened and robots' ways back to their planned
/// moves, some after a wait); with a following gap of 1.5 radius sums in motion too, 36.174, and as
/// one rigid ring, all stopping while any works, 42.032.
#[test]
fn a_ring_that_must_turn_whole_goes_round_as_a_convoy() {
    let cell = conflict_cell(ConflictKind::Ring, 8);
    let without = solve_with(&cell, &all_but("convoy"));
    let failure = without.failure.expect("refused without the convoy");
    assert!(!without.collision_free);
    assert!(
        failure.contains(" block each other at (")
            && (failure.contains("between centre and wall-") || failure.contains("between wall-")),
        "{failure}"
    );
    assert!(
        ["ran out", "every remedy was tried", "no remedy clears"]
            .iter()
            .any(|what| failure.contains(what)),
        "{failure}"
    );
    let all_seven = |k: &RemedyKind| matches!(k, RemedyKind::Convoy { robots, following: true, .. } if robots.len() == 7);
    assert_ring_solved(8, 25.720, all_seven);
}

/// Six robots on a wider ring, refused after 7 schedules without the convoy (every remedy
/// tried): with it, `ring-3-6` of seed 3 is certified at 23.473, the whole ring going
/// round once, each robot following the one ahead, then repaired by single remedies, their
/// holds shortened and ways back to their planned moves.
#[test]
fn a_ring_where_nothing_else_separates_goes_round_as_a_convoy() {
    let convoy = |k: &RemedyKind| {
        matches!(
            k,
            RemedyKind::Convoy {
                laps: 1,
                following: true,
                ..
            }
        )
    };
    let text = generate_conflict_cell(ConflictKind::Ring, 3, 6).to_string();
    let cell = parse_cell(&text, &PathBuf::from("ring")).unwrap().cell;
    assert!(!solve_with(&cell, &all_but("convoy")).collision_free);
    assert_ring_solved_with((3, 6), &SolveOptions::default(), 23.473, convoy);
}

/// A robot at work on a ring corridor one robot wide, in the way of another coming along
/// it: the one behind cannot pass, the one ahead cannot come back. It makes way: leaves by
/// its way home round the other side, ahead of the other, which waits (`remedies/
/// make_way.rs`, two robots changed at once). `ring-4` (5 robots) is certified at 17.160,
/// 9.4 % over its blind 15.683; without that remedy every other was tried (741 schedules)
/// and the cell was refused.
#[test]
fn a_robot_at_work_makes_way_round_a_ring() {
    assert_ring_solved(4, 17.160, |k| matches!(k, RemedyKind::MakeWay { .. }));
}

/// Robots that meet head-on in a ring corridor: one goes round the other side (a detour
/// around what the other robot sweeps up to the contact, `remedies/detour.rs`, tried when
/// that robot's whole sweep covers the detouring robot's start) and the others follow or
/// wait. `ring-2` (4 robots) is certified at 17.028, 14.2 % over its blind 14.916; without
/// that detour no remedy cleared its collisions (9 schedules checked).
#[test]
fn a_ring_is_solved_the_other_way_round() {
    assert_ring_solved(2, 17.028, |k| matches!(k, RemedyKind::Detour { .. }));
}

/// Robots that meet head-on where the one that would go round leaves from beside the
/// other's start: the region the other sweeps up to the contact covers the detouring
/// robot's goal too, so the way round the other side is planned around the other's pose
/// at the contact alone. `ring-3-2` (seed 3, four robots, all four on their way home the
/// other way round) is certified at 17.147, 17.2 % over its blind 14.627; with the swept
/// region only, every remedy was tried and the cell was refused (144 schedules).
#[test]
fn a_ring_is_solved_the_other_way_round_from_beside_the_other() {
    let detour = |k: &RemedyKind| matches!(k, RemedyKind::Detour { .. });
    assert_ring_solved_with((3, 2), &SolveOptions::default(), 17.147, detour);
}

/// Six robots on a ring, where a pair collides again after its single remedies: `tune`
/// times their two moves together, one robot holding at a waypoint of its move while the
/// other passes (`remedies/tune.rs`), and `ring-6` is certified at 21.108 (27 % over its
/// blind 16.612; 21.611 before slack was shortened, a schedule found earlier now shortening
/// further, and 21.145 before a way could be given back for a wait); without `tune` (and the convoy) it is refused after 335 schedules,
/// naming the two robots that block each other.
#[test]
fn a_ring_of_six_is_solved_with_two_moves_timed_together() {
    let cell = conflict_cell(ConflictKind::Ring, 6);
    // The convoy would certify it too (every robot round the ring).
    let without = solve_with(&cell, &none_of(&["tune", "convoy"]));
    assert!(!without.collision_free);
    assert!(without.failure.unwrap().contains(" block each other at ("));
    assert_ring_solved(6, 21.108, |k| matches!(k, RemedyKind::Tune { .. }));
}

/// Makespans that differ only in their last bits are the same (`SAME_MAKESPAN`): a schedule
/// shorter by so little is no better, so it neither replaces the answer nor earns the
/// search more schedules. `ring-5` of seed 1 is certified at 20.412 after 42 checks and
/// answered after 47 (ceilings below); counting a gain of 4e-15 as better, the answer is
/// one found after 63, the same to the last printed digit.
#[test]
fn a_schedule_shorter_only_in_its_last_bits_is_no_better() {
    let solved = solved_at(ConflictKind::Ring, 5, 20.412);
    let found = solved.found_after.expect("an answer");
    assert!(
        found <= 50 && solved.nodes <= 55,
        "{found} of {}",
        solved.nodes
    );
}

/// Two robots whose paths cross twice (`tests/cells/crossing-twice.json`): the large A goes
/// over a block, the small B under it through a gap too narrow for A, both to tasks on the
/// far side and back. On the way back each must let the other through one crossing: A holds
/// at its task while B passes the first, B holds under the block while A passes the second.
/// A single remedy delays one robot: without `tune` the search builds every chain of them
/// it can (10 schedules, a larger budget changes nothing) and certifies 23.873 at best;
/// with it, 23.523 (blind 22.938), the two moves timed together with a hold of each robot.
#[test]
fn two_robots_crossing_twice_yield_in_turn_when_tuned() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/cells/crossing-twice.json");
    let text = std::fs::read_to_string(&path).unwrap();
    let cell = parse_cell(&text, &path).unwrap().cell;
    let mut untuned = all_but("tune");
    untuned.search.max_nodes = 50_000;
    let without = solve_with(&cell, &untuned);
    assert!(without.collision_free, "{:?}", without.failure);
    assert!(
        without.nodes < 100,
        "{} schedules: the search did not run out of children",
        without.nodes
    );
    let makespan = without.schedule.makespan;
    assert!((makespan - 23.873).abs() < 1e-3, "{makespan}");

    let solved = solve(&cell);
    assert_certified_within_limits(&cell, &solved);
    let makespan = solved.schedule.makespan;
    assert!((makespan - 23.523).abs() < 1e-3, "{makespan}");
    let holds = remedies(&solved)
        .into_iter()
        .find_map(|r| match &r.kind {
            RemedyKind::Tune { holds, .. } => Some(holds.clone()),
            _ => None,
        })
        .expect("two moves timed together");
    // A at its task (the start of its way back), B under the block, short of the crossing
    // on the left, where A passes first.
    let task_a = workcell::geometry::Vec2::new(4.2, -1.5);
    assert!(holds
        .iter()
        .any(|h| h.robot == 0 && (h.at - task_a).norm() < 1e-9));
    assert!(holds
        .iter()
        .any(|h| h.robot == 1 && h.at.y < -1.35 && h.at.x < 0.0));
}

/// Ring `k` of seed 1 certified at `makespan`, with a remedy on the branch of the answer that
/// `used` recognises.
fn assert_ring_solved(k: u64, makespan: f64, used: fn(&RemedyKind) -> bool) {
    assert_ring_solved_with((1, k), &SolveOptions::default(), makespan, used)
}

/// [`assert_ring_solved`] for ring `k` of `seed`, with the options `opts`.
fn assert_ring_solved_with(
    (seed, k): (u64, u64),
    opts: &SolveOptions,
    makespan: f64,
    used: fn(&RemedyKind) -> bool,
) {
    let text = generate_conflict_cell(ConflictKind::Ring, seed, k).to_string();
    let cell = parse_cell(&text, &PathBuf::from("ring")).unwrap().cell;
    let solved = solve_with(&cell, opts);
    assert!(solved.collision_free, "{:?}", solved.failure);
    assert_certified_within_limits(&cell, &solved);
    let got = solved.schedule.makespan;
    assert!((got - makespan).abs() < 1e-3, "{got}");
    let on_branch = solved.iterations.iter().filter_map(|it| it.remedy.as_ref());
    assert!(on_branch.map(|r| &r.kind).any(used));
}

/// The search checks a changed schedule's robots against each other only (every motion it
/// adds is certified clear of the fixtures when made), but an answer it gives, certified or
/// not, carries the report of the whole schedule, fixtures included, as `workcell check`
/// gives it: on a junction between four blocks, both after the search and with no remedy
/// but waiting (no certified schedule).
#[test]
fn an_answer_is_reported_as_the_whole_schedule_is_checked() {
    let cell = conflict_cell(ConflictKind::Junction, 0);
    let mut few = SolveOptions::default();
    few.search.max_nodes = 100;
    let waiting = only(&["wait"]);
    for (opts, free) in [(few, true), (waiting, false)] {
        let solved = solve_with(&cell, &opts);
        assert_eq!(solved.collision_free, free);
        assert!(solved.iterations.len() > 1, "an answer the remedies made");
        let whole = solved
            .schedule
            .check(&solved.schedule.scene(&cell), &CheckOptions::default());
        let robots = cell.robots.len();
        assert_eq!(whole.pairs, solved.report.pairs);
        assert!(
            solved.report.pairs > robots * (robots - 1) / 2,
            "fixtures too"
        );
        assert_eq!(whole.certified, solved.report.certified);
        assert_eq!(whole.stats, solved.report.stats);
        assert_eq!(
            whole.first_contact.map(|c| c.time),
            solved.report.first_contact.map(|c| c.time)
        );
    }
}
