//! Rings one robot wide: every one certified, by convoys, by a robot making way, and by
//! two moves timed together.

use super::*;

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
        assert_eq!(solved.shortenings_refused, 0, "ring {k}");
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
