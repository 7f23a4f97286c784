//! Whether a changed robot schedule clears another robot, and the least change that does.
//!
//! A remedy changes one leg of one robot, from the leg's start on; before that start both
//! robots move as in the schedule the checker just examined, which it certified free up to
//! the collision. So a candidate is judged on a window: from the changed leg's start to its
//! end (the task it leads to included), with both trajectories cut to that window, and the
//! checker must prove the pair at least δ apart throughout. What happens after the window is
//! the next round's business. The shortening of an answer (`search/tighten.rs`) asks the
//! same of longer windows, from the changed leg's start to the later of the two robots'
//! ends, and checks its result whole.

use crate::cell::{Cell, RobotKind};
use crate::collision::{check, Body, CheckOptions, Scene, Verdict};
use crate::geometry::{closest_features, Posed, WalkTolerances};
use crate::motion::{Sample, Trajectory};
use crate::wcp::schedule::{PoseCursor, RobotSchedule};

/// Values of [`least`]'s first scan, evenly spaced over the bracket: clearing need not be
/// monotone (a robot may pass before the other arrives, or only after it has gone), so the
/// scan finds the first value that clears before bisection refines it.
const SCAN: usize = 12;
/// Closer than this share of δ at an instant of the window's samples: a contact the checker
/// cannot miss (it evaluates every sample instant of both robots), so the candidate does
/// not clear, found without the check. Half of δ, so that the checker's own rounding could
/// not judge that instant clear.
const SURE_CONTACT: f64 = 0.5;
/// Bisection steps of [`least`] after the scan: the answer is within 2⁻⁸ of a scan step
/// above the least value that clears.
const BISECTIONS: usize = 8;

/// True when the checker proves robots `x` and `y`, as scheduled, at least δ apart over
/// `[t0, t1]`.
pub(super) fn clears(
    cell: &Cell,
    (x, sx): (usize, &RobotSchedule),
    (y, sy): (usize, &RobotSchedule),
    (t0, t1): (f64, f64),
    opts: &CheckOptions,
) -> bool {
    // Most candidates fail, most of them where a sample instant already shows the contact.
    !sure_contact(cell, (x, sx), (y, sy), (t0, t1))
        && checked_clear(cell, (x, sx), (y, sy), (t0, t1), opts)
}

/// Whether a sample instant shows robots `x` and `y` in contact over `[t0, t1]`, as the
/// checker would find it (so [`clears`] is false): one of `x`'s (from the sample before
/// `t0`, where the checker's window starts), or one of `y`'s within the window (where both
/// robots are posed between samples of their own).
pub(super) fn sure_contact(
    cell: &Cell,
    (x, sx): (usize, &RobotSchedule),
    (y, sy): (usize, &RobotSchedule),
    (t0, t1): (f64, f64),
) -> bool {
    contact_at_a_sample(cell, (x, sx), (y, sy), (t0, t1), f64::NEG_INFINITY)
        || contact_at_a_sample(cell, (y, sy), (x, sx), (t0, t1), t0)
}

/// [`clears`] by the checker alone.
fn checked_clear(
    cell: &Cell,
    (x, sx): (usize, &RobotSchedule),
    (y, sy): (usize, &RobotSchedule),
    (t0, t1): (f64, f64),
    opts: &CheckOptions,
) -> bool {
    let bodies = |r: usize, s: &RobotSchedule| -> Option<Vec<Body>> {
        let name = &cell.robots[r].name;
        let (first, last) = window(&s.samples, t0, t1);
        match &cell.robots[r].kind {
            RobotKind::Rigid(rigid) => {
                // A window of a schedule's samples: valid as the whole is.
                let trajectory = Trajectory::trusted(s.samples[first..=last].to_vec());
                Some(vec![rigid.body(name, trajectory)])
            }
            // An arm's joint samples share the tool's times.
            RobotKind::Arm(arm) => Some(arm.bodies(name, s.joints[first..=last].to_vec())),
        }
    };
    let (Some(mut a), Some(b)) = (bodies(x, sx), bodies(y, sy)) else {
        return false;
    };
    a.extend(b);
    // Only the verdict counts: no counters through the first event.
    let opts = CheckOptions {
        counters: false,
        ..*opts
    };
    let report = check(
        &Scene {
            delta: cell.delta,
            bodies: a,
        },
        &opts,
    );
    match report.verdict() {
        // The cut trajectories reach one sample beyond t1: a contact there is not ours.
        Verdict::Contact { contact, .. } => contact.time > t1,
        verdict => verdict.is_certified_free(),
    }
}

/// Whether rigid robots `x` and `y` come closer than [`SURE_CONTACT`] δ at an instant of
/// `x`'s samples over `[t0, t1]` (from the sample before `t0`, none before `from`), posed
/// as the checker poses them: the checker evaluates every sample instant of both robots, so
/// it would report a contact at that instant or before it. Arms are left to the checker.
fn contact_at_a_sample(
    cell: &Cell,
    (x, sx): (usize, &RobotSchedule),
    (y, sy): (usize, &RobotSchedule),
    (t0, t1): (f64, f64),
    from: f64,
) -> bool {
    let (Some(rx), Some(ry)) = (cell.robots[x].as_rigid(), cell.robots[y].as_rigid()) else {
        return false;
    };
    let near = SURE_CONTACT * cell.delta;
    let reach = rx.shape.radius() + ry.shape.radius() + near;
    let tol = WalkTolerances::default();
    let (first, last) = window(&sx.samples, t0, t1);
    let mut instants = (sx.samples[first..=last].iter())
        .skip_while(|s| s.t < from)
        .take_while(|s| s.t <= t1)
        .peekable();
    let Some(start) = instants.peek().map(|s| s.t) else {
        return false;
    };
    let mut y_at = PoseCursor::new(sy, start);
    instants.any(|s| {
        // In a frame centred on x, as the checker works.
        let q = y_at.at(s.t);
        let rel = q.pos - s.pos;
        if rel.norm() >= reach {
            return false;
        }
        rx.pieces().iter().any(|a| {
            let a = Posed::new(a, 0.0, 0.0, s.theta);
            ry.pieces().iter().any(|b| {
                let b = Posed::new(b, rel.x, rel.y, q.theta);
                closest_features(&a, &b, None, &tol).distance < near
            })
        })
    })
}

/// The first and last indices of the samples that pose the robot over `[t0, t1]`: from the
/// last at or before `t0` to the first at or after `t1`. Between them the pose is
/// interpolated exactly as in the whole.
fn window(samples: &[Sample], t0: f64, t1: f64) -> (usize, usize) {
    let first = samples.partition_point(|s| s.t <= t0).saturating_sub(1);
    let last = samples.partition_point(|s| s.t < t1).min(samples.len() - 1);
    (first, last)
}

/// The least `p` in `(lo, hi]` for which `f(p)` succeeds, to within the resolution of a scan
/// of [`SCAN`] values refined by [`BISECTIONS`] bisections, with what `f` gave there. Only
/// values that are `viable` are wanted, and `viable` holds for the values below some bound
/// (a robot's end grows with its wait): once the answer must lie above a value that is not
/// viable, the search gives up without calling `f` again (`None`, as when no scanned value
/// succeeds). Where it does not, it finds what it would find with every value viable.
pub(super) fn least<T>(
    lo: f64,
    hi: f64,
    f: impl Fn(f64) -> Option<T>,
    viable: impl Fn(f64) -> bool,
) -> Option<(f64, T)> {
    let step = (hi - lo) / SCAN as f64;
    let mut scan = (1..=SCAN).map(|k| if k == SCAN { hi } else { lo + step * k as f64 });
    // The answer of a scanned value p lies in (p - step, p]: none is viable once p - step
    // is not.
    let (mut below, mut best) = loop {
        let p = scan.next()?;
        if !viable(p - step) {
            return None;
        }
        if let Some(t) = f(p) {
            break (p - step, (p, t));
        }
    };
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (below + best.0);
        if !(mid > below && mid < best.0) {
            break;
        }
        match f(mid) {
            Some(t) => best = (mid, t),
            None if viable(mid) => below = mid,
            None => return None,
        }
    }
    Some(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn least_finds_the_threshold_from_above() {
        let all = |_: f64| true;
        let (p, v) = least(0.0, 12.0, |p| (p >= 3.3).then_some(p * 2.0), all).unwrap();
        assert!((3.3..3.3 + 1.0 / 256.0 + 1e-12).contains(&p), "{p}");
        assert_eq!(v, 2.0 * p);
        assert!(least(0.0, 10.0, |p| (p > 11.0).then_some(()), all).is_none());
        // Not monotone: clears early (before the other robot arrives) and late; the scan
        // finds the early window, not the threshold of the late one.
        let early = |p: f64| ((1.5..2.5).contains(&p) || p > 9.0).then_some(());
        let (p, _) = least(0.0, 12.0, early, all).unwrap();
        assert!((1.5..1.5 + 1.0 / 256.0 + 1e-12).contains(&p), "{p}");
    }

    /// Values past the viable ones are not tried, and the answer is the same wherever it is
    /// viable, even just above the last scanned value below it.
    #[test]
    fn least_gives_up_past_the_viable_values_only() {
        let tries = std::cell::Cell::new(0);
        let f = |p: f64| {
            tries.set(tries.get() + 1);
            (p >= 3.3).then_some(())
        };
        // Scanned by steps of 1: 3.3 lies above 3, the last value that fails.
        let (p, _) = least(0.0, 12.0, f, |v| v < 3.31).unwrap();
        assert!((3.3..3.3 + 1.0 / 256.0 + 1e-12).contains(&p), "{p}");
        let all = tries.replace(0);
        assert!(least(0.0, 12.0, f, |v| v < 3.29).is_none());
        assert!(tries.get() < all, "{} tries of {all}", tries.get());
        // None viable past 2: the values from 3 on are never tried.
        tries.set(0);
        assert!(least(0.0, 12.0, f, |v| v < 2.0).is_none());
        assert_eq!(tries.get(), 2);
    }

    /// Robot X drives along y = 0 from x = -3 to 3 in 6 s, sampled every 0.5 s; Y stands at
    /// (0, `off`). Both are the same 0.7 square: they are `off` - 0.7 apart as X passes.
    fn passing(off: f64) -> (Cell, RobotSchedule, RobotSchedule) {
        let text = r#"{"delta": 0.01, "obstacles": [],
            "robots": [
                {"name": "X", "home": [-3, 0, 0], "shape": [[-0.35, -0.35], [0.35, -0.35], [0.35, 0.35], [-0.35, 0.35]],
                 "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5},
                {"name": "Y", "home": [0, 2, 0], "shape": [[-0.35, -0.35], [0.35, -0.35], [0.35, 0.35], [-0.35, 0.35]],
                 "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5}],
            "tasks": []}"#;
        let cell = crate::cell::parse_cell(text, "test.json".as_ref())
            .unwrap()
            .cell;
        let at = |t: f64, x: f64, y: f64, vx: f64| Sample {
            t,
            pos: crate::geometry::Vec2::new(x, y),
            theta: 0.0,
            vel: crate::geometry::Vec2::new(vx, 0.0),
            omega: 0.0,
        };
        let schedule = |samples: Vec<Sample>| RobotSchedule {
            route: Vec::new(),
            segments: Vec::new(),
            end: samples.last().unwrap().t,
            samples,
            joints: Vec::new(),
            path: Vec::new(),
        };
        let drives = (0..=12).map(|k| at(0.5 * k as f64, -3.0 + 0.5 * k as f64, 0.0, 1.0));
        let x = schedule(drives.collect());
        let y = schedule(vec![at(0.0, 0.0, off, 0.0), at(6.0, 0.0, off, 0.0)]);
        (cell, x, y)
    }

    /// The sample instants say "contact" only where the checker finds one: through, just
    /// within and just outside δ, and clear. Closer than half of δ at a sample, they say it
    /// without the checker, at the moving robot's instants whichever robot [`clears`] asks
    /// about (the standing robot's two samples show no contact).
    #[test]
    fn a_contact_at_a_sample_is_one_the_checker_finds() {
        let opts = CheckOptions::default();
        let window = (0.0, 6.0);
        let all = f64::NEG_INFINITY;
        for (off, sure, clear) in [
            (0.3, true, false),
            (0.7 + 0.004, true, false),
            (0.7 + 0.008, false, false),
            (0.7 + 0.012, false, true),
            (1.5, false, true),
        ] {
            let (cell, x, y) = passing(off);
            let got = contact_at_a_sample(&cell, (0, &x), (1, &y), window, all);
            assert_eq!(got, sure, "{off}");
            assert!(!contact_at_a_sample(&cell, (1, &y), (0, &x), window, all));
            // X passes Y at t = 3: no instant from 4.5 on shows the contact.
            assert!(!contact_at_a_sample(&cell, (0, &x), (1, &y), window, 4.5));
            assert_eq!(
                clears(&cell, (1, &y), (0, &x), window, &opts),
                clear,
                "{off}"
            );
            assert_eq!(
                checked_clear(&cell, (0, &x), (1, &y), window, &opts),
                clear,
                "{off}"
            );
            assert_eq!(
                clears(&cell, (0, &x), (1, &y), window, &opts),
                clear,
                "{off}"
            );
            // X comes within δ of Y from t = 2.29 on, at the latest, after the window
            // (0, 2.2), whose last sample (2.5) is past its end: not a contact of the window.
            let early = (0.0, 2.2);
            assert!(!contact_at_a_sample(&cell, (0, &x), (1, &y), early, all));
            assert!(clears(&cell, (0, &x), (1, &y), early, &opts));
        }
    }

    #[test]
    fn window_keeps_the_samples_around_it() {
        let s = |t: f64| Sample {
            t,
            pos: crate::geometry::Vec2::new(t, 0.0),
            theta: 0.0,
            vel: crate::geometry::Vec2::zeros(),
            omega: 0.0,
        };
        let samples: Vec<Sample> = [0.0, 1.0, 2.0, 3.0, 4.0].map(s).to_vec();
        let ts = |(a, b): (usize, usize)| samples[a..=b].iter().map(|s| s.t).collect::<Vec<_>>();
        assert_eq!(ts(window(&samples, 1.5, 2.5)), vec![1.0, 2.0, 3.0]);
        assert_eq!(ts(window(&samples, 1.0, 2.0)), vec![1.0, 2.0]);
        assert_eq!(
            ts(window(&samples, -1.0, 9.0)),
            vec![0.0, 1.0, 2.0, 3.0, 4.0]
        );
    }
}
