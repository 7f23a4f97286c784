//! When the search stops (patience, budgets) and what it answers then: the whole
//! schedule's report, a failure that names what was exhausted and who blocks, never a panic.

use super::*;

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
