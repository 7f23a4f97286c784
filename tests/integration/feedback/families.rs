//! Every conflict family solved, the search against the greedy loop, the shipped cells'
//! documented results, repairs that stay near their routes, and determinism.

use super::*;

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
        // The targets, where it sets one: a narrow swap within 35 %, the junction
        // within 40 % (the README's table gives every cell).
        let target = match kind {
            ConflictKind::CorridorNarrow => 0.35,
            ConflictKind::Junction => 0.40,
            _ => f64::INFINITY,
        };
        // And no longer than the search's answer when this test was last tuned (ceilings,
        // not pins: a better search passes; a worse ranking of children fails at the
        // junction; without lanes the wide corridor's was 31.033). The aisles' 60.778 was
        // 59.399 before the second pass had a share of the budget: the first pass found that
        // schedule after 4,747 checks, when it now stops at 3,500; the junction's was
        // 36.765, the doorway's 30.988.
        let ceiling = match kind {
            ConflictKind::CorridorNarrow => 42.812,
            ConflictKind::CorridorWide => 29.006,
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
        // Every step of the answer's shortening proved its own changes clear.
        assert_eq!(solved.shortenings_refused, 0, "{}", kind.name());
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
        on_threads(threads, || {
            let solved = solve_with(&cell, &opts);
            let legs = wcp::legs_json::legs_json(&cell, &solved.routes, &solved.legs);
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

/// The hand-made schedule of `benchmarks/junction-centre/` (every robot of `junction-4`
/// crosses at the centre, both ways) is what its README claims: certified collision-free at
/// 42.493, more than 20 % over the blind plan.
#[test]
fn the_junctions_schedule_through_the_centre_is_what_it_claims() {
    use crate::common::{temp_dir_absent, workcell};
    let dir = temp_dir_absent("families", "centre");
    std::fs::create_dir_all(&dir).unwrap();
    let cell = dir.join("junction-1-4-cell.json");
    let text = generate_conflict_cell(ConflictKind::Junction, 1, 4).to_string();
    std::fs::write(&cell, text).unwrap();
    let schedule = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("benchmarks/junction-centre/junction-4-centre.json");
    let out = workcell(&[
        "evaluate",
        "--json",
        cell.to_str().unwrap(),
        schedule.to_str().unwrap(),
    ]);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let makespan = doc["makespan"].as_f64().unwrap();
    assert!((makespan - 42.493).abs() < 5e-4, "{makespan}");
    assert!(makespan > 1.2 * 32.827, "{makespan}");
}
