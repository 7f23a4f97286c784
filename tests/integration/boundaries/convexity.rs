//! The rotation term ρ of the convexity certificate, deterministically (issue 13, item 18).
//!
//! A bar turns about its middle from −α to +α in one merged interval and its end sweeps past
//! a wall at δ/2 when square to it: at both ends of the interval it is 10·δ away, nobody
//! translates, so without ρ the tangents of the frozen-orientation distances are flat and
//! "prove" the interval above 10·δ. With either body's rotation left out of ρ the contact is
//! missed: the bar is checked as the first body of its pair and as the second.

use super::*;

const HALF: f64 = 1.0; // half length of the bar
const THICK: f64 = 1e-3; // half thickness of the bar

/// cos α = 1 − 10.5·δ / `HALF`: the bar's end is 10·δ from the wall at ±α.
fn alpha() -> f64 {
    (1.0 - 10.5 * DELTA / HALF).acos()
}

/// The bar (robot "bar") turning from −α at t = 0 to +α at t = 1, and a wall (robot "wall",
/// resting) δ/2 beyond the bar's reach when square; `bar_first` puts the bar first.
fn sweep(bar_first: bool) -> String {
    let a = alpha();
    let bar = robot(
        "bar",
        rect(HALF, THICK),
        &[[0.0, 0.0, 0.0, -a], [1.0, 0.0, 0.0, a]],
    );
    let face = HALF + 0.5 * DELTA;
    let wall = robot(
        "wall",
        rect_at(face + 0.5, 0.0, 0.5, 5.0),
        &[[0.0, 0.0, 0.0, 0.0]],
    );
    let robots = if bar_first {
        vec![bar, wall]
    } else {
        vec![wall, bar]
    };
    scene(DELTA, robots, vec![])
}

/// Distance of the bar's outer corner from the wall at time t, less δ.
fn gap(t: f64) -> f64 {
    let theta = alpha() * (2.0 * t - 1.0);
    HALF + 0.5 * DELTA - (HALF * theta.cos() + THICK * theta.sin().abs()) - DELTA
}

#[test]
fn a_turn_that_sweeps_into_a_wall_is_not_certified_by_convexity() {
    assert!(gap(0.0) > 9.0 * DELTA && gap(1.0) > 9.0 * DELTA && gap(0.5) < 0.0);
    let t = root(gap, 0.0, 0.5);
    for bar_first in [true, false] {
        let (scene, r) = run(&sweep(bar_first));
        let pair = if bar_first {
            ["bar", "wall"]
        } else {
            ["wall", "bar"]
        };
        assert_contact(&r, pair, t);
        assert!(r.certified, "{r:?}");
        cross_check_with_parry(&scene, &r);
    }
}

#[test]
fn the_same_turn_short_of_the_wall_is_certified() {
    // The wall 2·δ farther: free, and proven, with the first-order condition failing on the
    // whole interval (λ = 2α·`HALF` ≫ 20·δ).
    for bar_first in [true, false] {
        let text = sweep(bar_first).replace(
            &format!("{}", HALF + 0.5 * DELTA),
            &format!("{}", HALF + 2.5 * DELTA),
        );
        let (_, r) = run(&text);
        assert_free(&r, true);
        assert!(r.stats.bisections > 0, "{r:?}");
    }
}
