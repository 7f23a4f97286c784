//! Ways that remedies changed, back to their planned moves once the other robots have moved
//! (`search/tighten.rs`): a detour, a stay aside or a convoy's lap that a later remedy made
//! needless is dropped from the answer, where that clears every other robot and ends the
//! robot no later.

use crate::common::solve_with;
use std::path::PathBuf;
use workcell::cell::parse_cell;
use workcell::generate::{generate_conflict_cell, ConflictKind};
use workcell::wcp::remedy_json::remedy_text;
use workcell::wcp::{Remedy, RemedyKind, Shortened, Shortening, SolveOptions, Solved};

/// The shortening on the answer's branch, and what it shortened.
fn shortening(solved: &Solved) -> (&Remedy, &[Shortened]) {
    let tighten = (solved.iterations.iter())
        .filter_map(|it| it.remedy.as_ref())
        .find(|r| matches!(r.kind, RemedyKind::Tighten { .. }))
        .expect("the answer shortened");
    let RemedyKind::Tighten { shortened } = &tighten.kind else {
        unreachable!()
    };
    (tighten, shortened)
}

/// Five robots on the ring of seed 3, cell 4: the answer's schedule is a convoy repaired by
/// pauses; once its pauses are shortened, R5's way out and R1's way home need no lap of the
/// convoy, and the answer is 19.702 (18.3 % over its blind 16.655) instead of 20.206 with
/// those ways kept; then, once nothing else shortens, R4 and R3 take their planned ways out
/// after a wait. The straightened legs are the planned moves (no pieces of their own).
#[test]
fn a_convoys_lap_made_needless_gives_way_to_the_planned_move() {
    let text = generate_conflict_cell(ConflictKind::Ring, 3, 4).to_string();
    let cell = parse_cell(&text, &PathBuf::from("ring-3-4")).unwrap().cell;
    let solved = solve_with(&cell, &SolveOptions::default());
    assert!(solved.collision_free, "{:?}", solved.failure);
    let got = solved.schedule.makespan;
    assert!((got - 19.702).abs() < 1e-3, "{got}");
    let (tighten, shortened) = shortening(&solved);
    let straight: Vec<_> = (shortened.iter())
        .filter(|s| s.kind == Shortening::Straight)
        .map(|s| (cell.robots[s.robot].name.as_str(), s.leg))
        .collect();
    assert_eq!(straight, [("R1", 1), ("R5", 0), ("R4", 0), ("R3", 0)]);
    for (robot, leg) in [(0, 1), (4, 0), (3, 0), (2, 0)] {
        // A leg left as planned may not be listed at all.
        let kept = solved.legs[robot].get(leg);
        assert!(kept.is_none_or(|l| l.pieces.is_none()), "R{}", robot + 1);
    }
    // Said as the robot does it: its way and the time the leg takes, before and after.
    let said = remedy_text(&cell, tighten);
    assert!(
        said.contains("R1 takes its planned way on its move R1-weld-1 -> home: 4.167 (was 4.168)"),
        "{said}"
    );
}

/// On the junction of seed 1, cell 1, the best schedule found (43.574) has R1 pull in at a
/// passing place on its way out; once the others are shortened, R1 can take its planned way
/// after a wait at home instead, and ends 0.89 s sooner. Then R2, last, is let through by
/// R3, which waits 0.37 s longer before its second move (its pause on the way home cut),
/// and takes its planned way home too: the answer is 42.685 (19.9 % over the blind 35.61;
/// 42.954 without letting R2 through).
#[test]
fn a_way_given_back_for_a_wait_ends_the_robot_sooner() {
    let text = generate_conflict_cell(ConflictKind::Junction, 1, 1).to_string();
    let cell = parse_cell(&text, &PathBuf::from("junction-1"))
        .unwrap()
        .cell;
    let solved = solve_with(&cell, &SolveOptions::default());
    assert!(solved.collision_free, "{:?}", solved.failure);
    let got = solved.schedule.makespan;
    assert!((got - 42.685).abs() < 1e-3, "{got}");
    let (_, shortened) = shortening(&solved);
    let s = shortened[0];
    assert_eq!((s.robot, s.leg, s.kind), (0, 0, Shortening::Straight));
    assert!((s.before - s.after - 0.888).abs() < 1e-3, "{s:?}");
    // R3 waits longer for R2, which then takes its planned way home.
    let r3 = (shortened.iter())
        .find(|e| e.robot == 2)
        .expect("R3 lets R2 through");
    assert_eq!((r3.leg, r3.kind), (1, Shortening::Wait));
    assert!(r3.after > r3.before, "{r3:?}");
    let r2 = shortened.last().unwrap();
    assert_eq!((r2.robot, r2.leg, r2.kind), (1, 2, Shortening::Straight));
    let mut alone = SolveOptions::default();
    alone.search.give_way = false;
    let without = solve_with(&cell, &alone).schedule.makespan;
    assert!((without - 42.954).abs() < 1e-3, "{without}");
    // Its planned move, after a wait at home.
    let leg = &solved.legs[0][0];
    assert!(leg.pieces.is_none() && leg.wait > 0.0, "{leg:?}");
}
