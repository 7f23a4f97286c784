//! δ down to 10⁻⁹.

use super::*;

// ---------------------------------------------------------------------------------------
// 1. δ = 10⁻⁹
// ---------------------------------------------------------------------------------------

const TINY: f64 = 1e-9;

/// Square B comes from x = 3 to rest at a face gap `gap` from square A (at the origin) at
/// t = 1, and stays there until t = 2.
fn approach(gap: f64) -> String {
    let end = 1.0 + gap;
    scene(
        TINY,
        vec![
            robot("A", square(), &[[0.0, 0.0, 0.0, 0.0]]),
            robot(
                "B",
                square(),
                &[
                    [0.0, 3.0, 0.0, 0.0],
                    [1.0, end, 0.0, 0.0],
                    [2.0, end, 0.0, 0.0],
                ],
            ),
        ],
        vec![],
    )
}

#[test]
fn delta_1e_9_approach_to_twice_delta_is_free_and_certified() {
    let (_, r) = run(&approach(2e-9));
    assert_eq!(r.delta, TINY);
    assert_free(&r, true);
}

#[test]
fn delta_1e_9_approach_to_half_delta_collides_when_the_gap_is_delta() {
    // A tolerance far below the default (2·10⁻⁶ here) tells the contact, 2.5·10⁻¹⁰ before
    // B stops, from the stop itself.
    let opts = CheckOptions {
        time_tol: Some(1e-13),
        ..CheckOptions::default()
    };
    let (scene, r) = run_with(&approach(0.5e-9), &opts);
    // gap(t) = 2 − (2 − g)·t reaches δ at t = (2 − δ) / (2 − g), with g as rounded.
    let g = (1.0 + 0.5e-9) - 1.0;
    let t = (2.0 - TINY) / (2.0 - g);
    assert!(t < 1.0 - 2e-10);
    assert_contact(&r, ["A", "B"], t);
    assert_eq!(r.time_tol, 1e-13);
    cross_check_with_parry(&scene, &r);
}

/// Square B flies past square A at 2·10⁵ units per time unit, its bottom face `gap` above
/// A's top face: from x = −100 to 100 in 10⁻³.
fn fast_pass(gap: f64) -> String {
    let y = 1.0 + gap;
    scene(
        TINY,
        vec![
            robot("A", square(), &[[0.0, 0.0, 0.0, 0.0]]),
            robot(
                "B",
                square(),
                &[[0.0, -100.0, y, 0.0], [1e-3, 100.0, y, 0.0]],
            ),
        ],
        vec![],
    )
}

#[test]
fn delta_1e_9_fast_pass_at_three_delta_is_free_and_certified() {
    let (_, r) = run(&fast_pass(3e-9));
    assert_free(&r, true);
}

#[test]
fn delta_1e_9_fast_pass_at_half_delta_collides_at_the_corner() {
    let (scene, r) = run(&fast_pass(0.5e-9));
    // Corner to corner: B's lower right corner is h left of and g above A's upper left
    // one; the distance √(h² + g²) reaches δ at h = √(δ² − g²), when x_B = −1 − h.
    let g = (1.0 + 0.5e-9) - 1.0;
    let h = (TINY * TINY - g * g).sqrt();
    let t = (99.0 - h) / 2e5;
    assert_contact(&r, ["A", "B"], t);
    cross_check_with_parry(&scene, &r);
}

#[test]
fn delta_1e_9_spinning_corner_dipping_to_half_delta_collides() {
    // A unit square turns a quarter turn about G, √½ + δ/2 above a wall's top face: its
    // lowest corner, √½·cos(θ − π/4) below G, comes within δ/2 of the wall at θ = π/4. The
    // rotation spoils the convexity certificate: only bisection resolves it.
    let yc = 0.5f64.sqrt() + 0.5 * TINY;
    let quarter = std::f64::consts::FRAC_PI_2;
    let text = scene(
        TINY,
        vec![robot(
            "R",
            square(),
            &[[0.0, 0.0, yc, 0.0], [1.0, 0.0, yc, quarter]],
        )],
        vec![obstacle("wall", rect_at(0.0, -0.5, 3.0, 0.5))],
    );
    let (_, r) = run(&text);
    let gap = |t: f64| {
        let th = quarter * t;
        yc - 0.5 * (th.sin() + th.cos()) - TINY
    };
    let t = root(gap, 0.0, 0.5);
    assert!(t > 0.4999 && t < 0.5, "{t}");
    assert_contact(&r, ["R", "wall"], t);
    // Not cross-checked with parry: its GJK reports separations of a few 10⁻⁹ between
    // unit bodies as intersections (distance 0), here from t ≈ 0.4999.
}
