//! What f64 cannot hold, refused rather than answered wrongly (issue 13, items 2 and 3):
//! a shape clean-up that moves the boundary, and time stamps too coarse for the tolerance.

use super::*;
use workcell::cell::{check_time_resolution, MAX_REPAIR_SHIFT_OVER_DELTA};

/// A triangle 2.5·10⁸ long (2.5·10¹¹·δ) with a bump at its corner: vertex 1 lies `bump`
/// below the bottom edge, within the shape tolerance (10⁻¹² of the size, 2.5·10⁻⁴) of
/// vertex 0, so the clean-up takes it for a repeat. A robot sits 0.9·δ below the bump.
fn bumped_triangle(bump: f64) -> String {
    let size = 2.5e8;
    scene(
        DELTA,
        vec![robot(
            "R",
            square(),
            &[[0.0, bump, -bump - 0.5 - 0.9 * DELTA, 0.0]],
        )],
        vec![obstacle(
            "big",
            json!([[0.0, 0.0], [bump, -bump], [size, 0.0], [0.0, size]]),
        )],
    )
}

#[test]
fn a_clean_up_that_moves_the_boundary_is_refused_naming_the_vertex() {
    // Before: the bump was dropped with a warning, the robot (0.9·δ from it) came out
    // 1.15·δ from what was kept, and the scene was certified free.
    let text = bumped_triangle(2.4e-4);
    let path = Path::new("bump.json");
    let loaded = parse_scene(&text, path).unwrap();
    assert!(
        !loaded.warnings.is_empty(),
        "the bump is removed as a repeat"
    );
    let e = check_precision(&loaded.scene, DELTA, path).unwrap_err();
    assert_eq!(e.body.as_deref(), Some("big"));
    assert_eq!(e.field, "obstacles[0].shape[1]");
    assert!(e.reason.contains("repeated or collinear"), "{e}");
    // The same removal is harmless for a δ so large that the shift is below the limit.
    let shift = 2.4e-4;
    assert!(check_precision(
        &loaded.scene,
        2.0 * shift / MAX_REPAIR_SHIFT_OVER_DELTA,
        path
    )
    .is_ok());
}

#[test]
fn an_ordinary_repair_is_still_accepted() {
    // A repeated vertex and a collinear one on a unit square: the boundary does not move.
    let text = scene(
        DELTA,
        vec![robot(
            "R",
            json!([
                [0.0, 0.0],
                [0.5, 0.0],
                [1.0, 0.0],
                [1.0, 1.0],
                [1.0, 1.0],
                [0.0, 1.0]
            ]),
            &[[0.0, 0.0, 0.0, 0.0]],
        )],
        vec![],
    );
    let loaded = parse_scene(&text, Path::new("square.json")).unwrap();
    assert_eq!(loaded.warnings.len(), 2, "{:?}", loaded.warnings);
    assert!(check_precision(&loaded.scene, 1e-9, Path::new("square.json")).is_ok());
}

/// Square A crosses the wall at the origin along x from −1000 to 1000 over [T, T + `span`]:
/// with a span of 1000 it first comes within δ of it at T + 499.2495 (not an f64 near 10¹²).
fn late_pass(t: f64, span: f64) -> String {
    scene(
        DELTA,
        vec![robot(
            "A",
            square(),
            &[[t, -1000.0, 0.0, 0.0], [t + span, 1000.0, 0.0, 0.0]],
        )],
        vec![obstacle("wall", rect(1.0, 5.0))],
    )
}

#[test]
fn time_stamps_too_coarse_for_the_time_tolerance_are_refused() {
    let path = Path::new("late.json");
    let scene = load(&late_pass(1e14, 1000.0));
    let opts = CheckOptions::default();
    // f64 spaces times near 10¹⁴ by 0.016; the default tolerance is 10⁻³.
    let e = check_time_resolution(&scene, opts.time_tol_for(scene.horizon()), path).unwrap_err();
    assert_eq!(e.body.as_deref(), Some("A"));
    assert_eq!(e.field, "robots[0].trajectory[1].t");
    assert!(e.reason.contains("--time-tol"), "{e}");
    assert!(check_time_resolution(&scene, 0.5, path).is_ok());
    // Seconds since 1970 with a minute of motion are fine.
    let epoch = load(&late_pass(1.7e9, 60.0));
    let tol = opts.time_tol_for(epoch.horizon());
    assert!(check_time_resolution(&epoch, tol, path).is_ok());
}

#[test]
fn a_contact_at_a_huge_time_is_never_reported_before_it_happens() {
    // Below the resolution of f64 (the library does not refuse): the reported contact is
    // the first f64 at or after its witness, and `safe_until` the last at or before a
    // proven instant. Before, `safe_until` came out 1.2·10⁻⁵ (at 10¹²) to 5·10⁻⁴ (at 10¹⁴
    // and beyond) after the true first contact.
    let first = 499.2495; // after T; differences to T below are exact in f64
    for t in [1e12, 3e12, 1e13, 1e14, 1e15] {
        let opts = CheckOptions {
            time_tol: Some(1e-3),
            ..CheckOptions::default()
        };
        let (_, r) = run_with(&late_pass(t, 1000.0), &opts);
        let c = r.first_contact.as_ref().expect("a contact");
        assert!(
            c.time - t >= first - 1e-9,
            "at {t}: contact at T + {}",
            c.time - t
        );
        assert!(
            r.safe_until - t <= first + 1e-9,
            "at {t}: certified free until T + {}",
            r.safe_until - t
        );
    }
}
