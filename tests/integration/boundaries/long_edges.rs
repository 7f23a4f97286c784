//! Nearly parallel long edges (issue 13, item 1): the distance of two edges at an angle α
//! changes by α·length across their overlap, so on edges 2·10¹⁰·δ long an α below the
//! walk's parallel tolerance (10⁻¹⁰) hides a contact 0.5·δ deep at one end of it.
//! parry2d-f64 answers with the middle of the overlap here too, so the distances are
//! checked against the slab's geometry instead of against parry.

use super::*;

/// Half length of the slabs: 10⁷ = 10¹⁰·δ, within the coordinate limit 2³⁸·δ.
const HALF: f64 = 1e7;

/// A slab 2·`HALF` long and 1 thick, resting on its bottom face (the body origin at its
/// middle) turned by `angle`, beside the top face of a wall 2·`HALF` long; the robot's
/// middle is at `x` along the wall, `lift(t)` above it.
fn slab_over_wall(x: f64, angle: f64, lift: &[(f64, f64)]) -> String {
    let samples: Vec<[f64; 4]> = lift.iter().map(|&(t, y)| [t, x, y, angle]).collect();
    scene(
        DELTA,
        vec![robot("R", rect_at(0.0, 0.5, HALF, 0.5), &samples)],
        vec![obstacle("wall", rect_at(HALF, -0.5, HALF, 0.5))],
    )
}

/// The smallest distance between the slab and the wall: at an end of their overlap.
fn slab_gap(x: f64, angle: f64, y: f64) -> f64 {
    let (lo, hi) = ((x - HALF).max(0.0), (x + HALF).min(2.0 * HALF));
    [lo, hi]
        .map(|end| y + (end - x) * angle.tan())
        .into_iter()
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn nearly_parallel_long_edges_hide_no_contact() {
    // Offsets along the wall and angles on both sides of zero, below the parallel
    // tolerance: at every one the slab's middle is δ·(1 + 1/4) above the wall and one end
    // of the overlap is 0.75·δ or 0.55·δ above it.
    for x in [HALF, 1.5 * HALF, 0.5 * HALF, 2.0 * HALF] {
        for angle in [5e-11f64, -5e-11, 9e-11, -9e-11] {
            let drop = angle.abs() * HALF;
            let y = DELTA + 0.25 * drop;
            let gap = slab_gap(x, angle, y);
            let (_, r) = run(&slab_over_wall(x, angle, &[(0.0, y), (1.0, y)]));
            if gap < DELTA {
                assert_contact(&r, ["R", "wall"], 0.0);
                let c = r.first_contact.as_ref().unwrap();
                assert!(
                    (c.distance - gap).abs() < 1e-9 * DELTA,
                    "x {x}, angle {angle}: distance {} instead of {gap}",
                    c.distance
                );
            } else {
                assert_free(&r, true);
            }
        }
    }
}

#[test]
fn a_nearly_parallel_long_edge_comes_into_contact_on_time() {
    // The slab comes down onto the wall: the end of the overlap reaches δ at exactly t = 1
    // and the wall at t = 2. Before the fix, t = 1.75 was reported (when the middle of the
    // overlap reached δ), 375 000 times the time tolerance late.
    let (x, angle) = (1.5 * HALF, 5e-11);
    let end = angle * HALF; // how much lower the slab's left end is than its middle
    let lift = [(0.0, 1.0 + DELTA + end), (1.0, DELTA + end), (2.0, end)];
    for method in [Method::DEFAULT, Method::Advance] {
        let opts = CheckOptions {
            method,
            ..CheckOptions::default()
        };
        let (_, r) = run_with(&slab_over_wall(x, angle, &lift), &opts);
        if method == Method::DEFAULT {
            assert_contact(&r, ["R", "wall"], 1.0);
        } else {
            // `advance` reports its last free look as `safe_until`, not a tight prefix.
            let c = r.first_contact.as_ref().expect("a contact");
            assert!(
                (c.time - 1.0).abs() <= r.time_tol && c.distance < DELTA,
                "{r:?}"
            );
        }
    }
}
