//! Coordinates of 10⁶ and 10⁴ samples per trajectory.

use super::contact_shapes::{diamonds, diamonds_contact, turn_parallel};
use super::*;

// ---------------------------------------------------------------------------------------
// 7. Coordinates of 10⁶
// ---------------------------------------------------------------------------------------

#[test]
fn a_scene_shifted_by_1e6_keeps_its_verdict_and_contact_time() {
    let dy = 0.3 * DELTA;
    let near = diamonds(dy, 0.0, 0.0);
    let far = diamonds(dy, 1e6, 1e6);
    // 10⁶ is within 2³⁸·δ for δ = 10⁻³, not for δ = 10⁻⁶.
    let path = Path::new("far.json");
    let far_scene = load(&far);
    assert!(check_precision(&far_scene, DELTA, path).is_ok());
    assert!(check_precision(&far_scene, 1e-6, path).is_err());
    let (_, r0) = run(&near);
    let (far_scene, r1) = run(&far);
    let t = diamonds_contact(dy);
    assert_contact(&r0, ["A", "B"], t);
    assert_contact(&r1, ["A", "B"], t);
    let (c0, c1) = (
        r0.first_contact.unwrap(),
        r1.first_contact.as_ref().unwrap(),
    );
    assert!((c0.time - c1.time).abs() <= r1.time_tol);
    cross_check_with_parry(&far_scene, &r1);
}

#[test]
fn a_free_scene_shifted_by_1e6_stays_free() {
    // The slide at 1.5 δ of the parallel faces, 10⁶ away from the origin.
    let shift = |text: &str| {
        let mut v: Value = serde_json::from_str(text).unwrap();
        for r in v["robots"].as_array_mut().unwrap() {
            for s in r["trajectory"].as_array_mut().unwrap() {
                s["x"] = json!(s["x"].as_f64().unwrap() + 1e6);
                s["y"] = json!(s["y"].as_f64().unwrap() + 1e6);
            }
        }
        v.to_string()
    };
    let text = turn_parallel(1.0 + 1.5 * DELTA, 1.5, true);
    let (_, r0) = run(&text);
    let (_, r1) = run(&shift(&text));
    assert_free(&r0, true);
    assert_free(&r1, true);
}

// ---------------------------------------------------------------------------------------
// 8. 10⁴ samples per trajectory
// ---------------------------------------------------------------------------------------

const SAMPLES: usize = 10_000;
const BOWL: f64 = 0.1;

/// A goes right along y = 0 (x = t − 5), sampled at 0.0002 + 0.0009999·k; B goes left
/// (x = 5 − t) along the parabola y = 1 + `low` + 0.1·(t − 5)², sampled at k / 1000: the two
/// grids differ. While the squares overlap along x (t in (4.5, 5.5)) their distance is
/// B's height less 1, on the chords between B's samples; the lowest, `low`, at t = 5.
fn long_run(low: f64) -> (String, Vec<[f64; 4]>) {
    let a: Vec<[f64; 4]> = (0..SAMPLES)
        .map(|k| {
            let t = 0.0002 + 0.0009999 * k as f64;
            [t, t - 5.0, 0.0, 0.0]
        })
        .collect();
    let b: Vec<[f64; 4]> = (0..SAMPLES)
        .map(|k| {
            let t = k as f64 / 1000.0;
            [t, 5.0 - t, 1.0 + low + BOWL * (t - 5.0) * (t - 5.0), 0.0]
        })
        .collect();
    let text = scene(
        DELTA,
        vec![robot("A", square(), &a), robot("B", square(), &b)],
        vec![],
    );
    (text, b)
}

#[test]
fn ten_thousand_samples_closest_at_three_delta_are_free_and_certified() {
    let (text, b) = long_run(3.0 * DELTA);
    assert_eq!((b[5000][0], b[5000][2]), (5.0, 1.0 + 3.0 * DELTA));
    let (scene, r) = run(&text);
    assert_free(&r, true);
    // From B's first sample to B's last; A rests before its first and after its last.
    assert_eq!(r.horizon, [0.0, 9.999]);
    // About 2·10⁴ merged intervals.
    assert!(r.stats.intervals >= 19_000, "{:?}", r.stats);
    let pair = ["A".to_owned(), "B".to_owned()];
    let d = parry_distance(&scene, &pair, 5.0);
    assert!((d - 3.0 * DELTA).abs() < 1e-12, "{d}");
}

#[test]
fn ten_thousand_samples_dipping_to_half_delta_collide_on_the_right_chord() {
    let (text, b) = long_run(0.5 * DELTA);
    let (scene, r) = run(&text);
    // First chord of B's path whose end is below 1 + δ; the gap falls to δ on it.
    let k = b.iter().position(|s| s[2] - 1.0 < DELTA).unwrap() - 1;
    let (p, q) = (b[k], b[k + 1]);
    let u = ((p[2] - 1.0) - DELTA) / (p[2] - q[2]);
    let t = p[0] + u * (q[0] - p[0]);
    // About 5 − √(0.5·δ / 0.1) ≈ 4.929: the squares overlap along x.
    assert!(
        (t - (5.0 - (0.5 * DELTA / BOWL).sqrt())).abs() < 1e-4,
        "{t}"
    );
    assert_contact(&r, ["A", "B"], t);
    cross_check_with_parry(&scene, &r);
}
