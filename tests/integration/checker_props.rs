//! Property tests of the whole checker on random two-robot scenes (some with an obstacle),
//! against the independent oracle of `common`: the pose interpolated by hand at thousands of
//! instants (all sample times included) and the exact polygon distance by brute force.
//!
//! Dense sampling can miss a short contact but never invents one, so each property below is
//! one the checker must satisfy whatever the sampling missed.

use crate::common::{
    centroid, dot, draw, ellipse_shape, exact_distance, lerp_pose, place, polygon, pose_at,
    proptest_config, radius_about, sub, unit_square, Shape,
};
use proptest::prelude::*;
use proptest::test_runner::TestRunner;
use rayon::{ThreadPool, ThreadPoolBuilder};
use std::f64::consts::PI;
use std::sync::OnceLock;
use workcell::collision::{check, check_known, Body, CheckOptions, CheckReport, Contact, Scene};
use workcell::geometry::Vec2;
use workcell::motion::{Sample, Trajectory};

const DELTA: f64 = 0.01;
/// Instants of the dense sampling, on top of every sample time.
const DENSE: usize = 8000;
/// Rounding allowance on distances (coordinates are of order 1).
const EPS: f64 = 1e-9;

#[test]
fn oracle_sanity() {
    let sq = unit_square;
    assert!((exact_distance(&sq(0.0, 0.0), &sq(2.0, 0.0)) - 1.0).abs() < 1e-15);
    assert!((exact_distance(&sq(0.0, 0.0), &sq(2.0, 2.0)) - 2f64.sqrt()).abs() < 1e-15);
    assert_eq!(exact_distance(&sq(0.0, 0.0), &sq(1.0, 1.0)), 0.0);
    assert_eq!(exact_distance(&sq(0.0, 0.0), &sq(0.2, 0.3)), 0.0);
    let r = RobotSpec {
        shape: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        samples: vec![[1.0, 0.0, 0.0, 0.0], [3.0, 4.0, 2.0, 1.0]],
    };
    assert_eq!(pose_at(&r.samples, 0.0), [0.0, 0.0, 0.0]);
    assert_eq!(pose_at(&r.samples, 2.0), [2.0, 1.0, 0.5]);
    assert_eq!(pose_at(&r.samples, 5.0), [4.0, 2.0, 1.0]);
}

// ---------------------------------------------------------------------------------------
// Scenes
// ---------------------------------------------------------------------------------------

#[derive(Clone, Debug)]
struct RobotSpec {
    /// Counter-clockwise, in the body frame.
    shape: Shape,
    /// `[t, x, y, theta]`, times increasing.
    samples: Vec<[f64; 4]>,
}

#[derive(Clone, Debug)]
struct SceneSpec {
    robots: [RobotSpec; 2],
    /// In world coordinates.
    obstacle: Option<Shape>,
}

const NAMES: [&str; 3] = ["r0", "r1", "obs"];

impl SceneSpec {
    fn scene(&self) -> Scene {
        let mut bodies: Vec<Body> = self
            .robots
            .iter()
            .zip(NAMES)
            .map(|(r, name)| {
                let samples = r
                    .samples
                    .iter()
                    .map(|&[t, x, y, theta]| Sample {
                        t,
                        pos: Vec2::new(x, y),
                        theta,
                        vel: Vec2::zeros(),
                        omega: 0.0,
                    })
                    .collect();
                Body::robot(
                    name.to_owned(),
                    polygon(&r.shape),
                    Trajectory::new(samples).expect("valid trajectory"),
                )
            })
            .collect();
        if let Some(o) = &self.obstacle {
            bodies.push(Body::obstacle(NAMES[2].to_owned(), &polygon(o)));
        }
        Scene {
            delta: DELTA,
            bodies,
        }
    }

    /// Every sample time of the robots.
    fn sample_times(&self) -> impl Iterator<Item = f64> + '_ {
        self.robots
            .iter()
            .flat_map(|r| r.samples.iter().map(|s| s[0]))
    }

    fn horizon(&self) -> (f64, f64) {
        self.sample_times()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
                (lo.min(t), hi.max(t))
            })
    }

    /// The pairs checked, by body index: robot-robot, then robot-obstacle.
    fn pairs(&self) -> Vec<(usize, usize)> {
        let mut pairs = vec![(0, 1)];
        if self.obstacle.is_some() {
            pairs.extend([(0, 2), (1, 2)]);
        }
        pairs
    }

    /// The poses of the robots at time `t`.
    fn poses(&self, t: f64) -> [[f64; 3]; 2] {
        [0, 1].map(|k| pose_at(&self.robots[k].samples, t))
    }

    /// Exact distance of bodies `i` and `j`, the robots at `poses`.
    fn pair_distance(&self, (i, j): (usize, usize), poses: &[[f64; 3]; 2]) -> f64 {
        let world = |k: usize| match k {
            0 | 1 => place(&self.robots[k].shape, poses[k]),
            _ => self.obstacle.clone().unwrap(),
        };
        exact_distance(&world(i), &world(j))
    }

    /// Exact distance of bodies `i` and `j` at time `t`.
    fn distance(&self, pair: (usize, usize), t: f64) -> f64 {
        self.pair_distance(pair, &self.poses(t))
    }

    /// Smallest distance over all pairs at `t` when it is below δ, else `None`; skips
    /// pairs whose bounding discs are δ apart.
    fn close_at(&self, t: f64) -> Option<f64> {
        let poses = self.poses(t);
        let disc = |k: usize| match k {
            0 | 1 => (
                [poses[k][0], poses[k][1]],
                radius_about(&self.robots[k].shape, [0.0; 2]),
            ),
            _ => {
                let o = self.obstacle.as_ref().unwrap();
                let c = centroid(o);
                (c, radius_about(o, c))
            }
        };
        self.pairs()
            .into_iter()
            .filter(|&(i, j)| {
                let ((ci, ri), (cj, rj)) = (disc(i), disc(j));
                let c = sub(ci, cj);
                dot(c, c).sqrt() - ri - rj < 2.0 * DELTA
            })
            .map(|pair| self.pair_distance(pair, &poses))
            .filter(|&d| d < DELTA)
            .reduce(f64::min)
    }

    /// The dense sample of instants: a uniform grid over the horizon and every sample time.
    fn instants(&self) -> Vec<f64> {
        let (h0, h1) = self.horizon();
        let mut ts: Vec<f64> = (0..=DENSE)
            .map(|k| h0 + (h1 - h0) * k as f64 / DENSE as f64)
            .chain(self.sample_times())
            .collect();
        ts.sort_by(f64::total_cmp);
        ts.dedup();
        ts
    }
}

// ---------------------------------------------------------------------------------------
// Generators
// ---------------------------------------------------------------------------------------

/// A convex shape of size about 0.2 to 1: random angles on an ellipse, the body origin
/// (the rotation centre) not necessarily at its centre, nor even inside it.
fn shape() -> impl Strategy<Value = Shape> {
    ellipse_shape(3..=12, 0.1..0.5, -0.25..0.25)
}

/// Turn between consecutive samples: none, moderate, or a fast spin.
fn turn() -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(0.0),
        3 => -0.7f64..0.7,
        1 => -25.0f64..25.0,
    ]
}

/// 2 to 12 samples on a random time grid (its own start, its own steps), the positions
/// scattered about a home position.
fn robot() -> impl Strategy<Value = RobotSpec> {
    (
        shape(),
        2usize..=12,
        -1.8f64..1.8,
        -1.8f64..1.8,
        prop_oneof![1 => 0.0f64..0.5, 3 => 0.5f64..2.5],
    )
        .prop_flat_map(|(shape, n, hx, hy, spread)| {
            (
                Just(shape),
                0.0f64..2.0,
                prop::collection::vec(prop_oneof![3 => 0.05f64..1.5, 1 => 1e-3f64..0.05], n - 1),
                prop::collection::vec(
                    (
                        prop_oneof![5 => Just(false), 1 => Just(true)],
                        (hx - spread)..(hx + spread + 1e-9),
                        (hy - spread)..(hy + spread + 1e-9),
                    ),
                    n,
                ),
                -PI..PI,
                prop::collection::vec(turn(), n - 1),
            )
        })
        .prop_map(|(shape, t0, steps, places, theta0, turns)| {
            let mut samples: Vec<[f64; 4]> = Vec::with_capacity(places.len());
            let (mut t, mut theta) = (t0, theta0);
            for (k, &(rest, x, y)) in places.iter().enumerate() {
                if k > 0 {
                    t += steps[k - 1];
                    theta += turns[k - 1];
                }
                // A resting robot repeats its previous position.
                let (x, y) = match samples.last() {
                    Some(&[_, px, py, _]) if rest => (px, py),
                    _ => (x, y),
                };
                samples.push([t, x, y, theta]);
            }
            RobotSpec { shape, samples }
        })
}

fn obstacle() -> impl Strategy<Value = Shape> {
    (shape(), -2.0f64..2.0, -2.0f64..2.0)
        .prop_map(|(s, x, y)| s.iter().map(|p| [p[0] + x, p[1] + y]).collect())
}

fn scene_spec() -> impl Strategy<Value = SceneSpec> {
    (robot(), robot(), prop::option::weighted(0.4, obstacle())).prop_map(|(a, b, obstacle)| {
        SceneSpec {
            robots: [a, b],
            obstacle,
        }
    })
}

/// A near miss whose smallest distance is known exactly: robot 0 slides without turning
/// along a straight line past body B (a resting robot 1, or an obstacle with robot 1 far
/// away), from well before to well after it, at an irregular speed.
///
/// The distance between A + s·u and B over all s is the distance from the line s·u to the
/// Minkowski difference B − A, which is the gap of their projections on the normal n of u:
/// min over B of n·b − max over A of n·a. The line is offset along n to make that gap
/// δ·(1 + k).
#[derive(Clone, Debug)]
struct NearMiss {
    spec: SceneSpec,
    /// The exact smallest distance over the whole motion.
    gap: f64,
}

fn near_miss() -> impl Strategy<Value = NearMiss> {
    let relative = prop_oneof![
        Just(-0.5),
        Just(-1e-3),
        Just(-1e-5),
        Just(-3e-6),
        Just(-1e-7),
        Just(0.0),
        Just(1e-7),
        Just(1e-5),
        Just(1e-3),
        Just(0.5),
    ];
    (
        (shape(), shape(), -PI..PI, -PI..PI, -PI..PI, relative),
        (
            prop::collection::vec(-3.5f64..3.5, 0..6),
            prop::collection::vec(0.01f64..1.0, 7),
            0.0f64..1.0,
            prop::collection::vec(0.1f64..2.0, 1..4),
            0.0f64..1.0,
            any::<bool>(),
        ),
    )
        .prop_map(
            |((a, b, theta_a, theta_b, phi, k), (mids, steps_a, t0_a, steps_b, t0_b, obstacle))| {
                let u = [phi.cos(), phi.sin()];
                let n = [-u[1], u[0]];
                let top_a = place(&a, [0.0, 0.0, theta_a])
                    .into_iter()
                    .map(|p| dot(n, p))
                    .fold(f64::NEG_INFINITY, f64::max);
                let bottom_b = place(&b, [0.0, 0.0, theta_b])
                    .into_iter()
                    .map(|p| dot(n, p))
                    .fold(f64::INFINITY, f64::min);
                let gap = DELTA * (1.0 + k);
                let w = bottom_b - top_a - gap;
                // Positions along the line: -4, the sorted intermediate points, +4.
                let mut along = vec![-4.0];
                along.extend(mids.iter().copied());
                along.push(4.0);
                along.sort_by(f64::total_cmp);
                let mut t = t0_a;
                let samples_a = along
                    .iter()
                    .zip(&steps_a)
                    .map(|(&s, &dt)| {
                        t += dt;
                        [t, s * u[0] + w * n[0], s * u[1] + w * n[1], theta_a]
                    })
                    .collect();
                let (home, obstacle) = if obstacle {
                    ([50.0, 50.0], Some(place(&b, [0.0, 0.0, theta_b])))
                } else {
                    ([0.0, 0.0], None)
                };
                let mut t = t0_b;
                let mut samples_b = vec![[t, home[0], home[1], theta_b]];
                for dt in &steps_b {
                    t += dt;
                    samples_b.push([t, home[0], home[1], theta_b]);
                }
                NearMiss {
                    spec: SceneSpec {
                        robots: [
                            RobotSpec {
                                shape: a,
                                samples: samples_a,
                            },
                            RobotSpec {
                                shape: b.clone(),
                                samples: samples_b,
                            },
                        ],
                        obstacle,
                    },
                    gap,
                }
            },
        )
}

// ---------------------------------------------------------------------------------------
// Properties
// ---------------------------------------------------------------------------------------

fn pools() -> &'static (ThreadPool, ThreadPool) {
    static POOLS: OnceLock<(ThreadPool, ThreadPool)> = OnceLock::new();
    POOLS.get_or_init(|| {
        let pool = |n| ThreadPoolBuilder::new().num_threads(n).build().unwrap();
        (pool(1), pool(4))
    })
}

fn check_scene(spec: &SceneSpec) -> Result<(), TestCaseError> {
    let scene = spec.scene();
    let opts = CheckOptions::default();
    let report = check(&scene, &opts);
    let (h0, h1) = spec.horizon();
    // Certificates prove a distance of at least δ(1 − grazing_tol): closer than that (with
    // rounding to spare) at a sampled instant is a contact the checker must report.
    let must_report = DELTA * (1.0 - opts.grazing_tol) - EPS;

    prop_assert_eq!(report.horizon, [h0, h1]);
    prop_assert_eq!(report.delta, DELTA);
    prop_assert_eq!(report.pairs + report.pairs_pruned, spec.pairs().len());

    // The oracle: the sampled instants closer than δ, in time order, up to the first one
    // closer than δ(1 − grazing_tol); no property needs the instants after it.
    let mut close: Vec<(f64, f64)> = Vec::new();
    for t in spec.instants() {
        if let Some(d) = spec.close_at(t) {
            close.push((t, d));
            if d < must_report {
                break;
            }
        }
    }
    let first_sampled = close.last().copied().filter(|&(_, d)| d < must_report);

    // (a) A sampled contact is reported.
    if let Some((t, d)) = first_sampled {
        prop_assert!(
            report.collision,
            "no collision reported, but the distance is {d:e} < δ at t = {t}"
        );
    }

    match &report.first_contact {
        None => {
            prop_assert!(!report.collision);
            prop_assert_eq!(report.safe_until, h1, "free scene not certified to the end");
        }
        Some(c) => contact_holds(spec, &report, c, first_sampled)?,
    }
    // (e) Nothing sampled before safe_until is closer than δ(1 − grazing_tol).
    if let Some(&(t, d)) = close
        .iter()
        .find(|&&(t, d)| t < report.safe_until && d < must_report)
    {
        prop_assert!(
            false,
            "certified free until {} but the distance is {d:e} at t = {t}",
            report.safe_until
        );
    }

    // (f) What an earlier check proved is not searched again: known δ apart up to its
    // certified prefix, or half of it, the scene has the same verdict and first contact.
    // A graze proves less than δ: nothing is known then.
    for share in [0.5, 1.0]
        .into_iter()
        .filter(|_| report.proven_until().is_some())
    {
        let known = h0 + share * (report.proven_until().unwrap() - h0);
        let again = check_known(&scene, &opts, &vec![known; scene.bodies.len()]);
        prop_assert_eq!(
            &again.first_contact,
            &report.first_contact,
            "known to {}",
            known
        );
        prop_assert_eq!(again.safe_until, report.safe_until, "known to {}", known);
        prop_assert_eq!(again.verdict(), report.verdict(), "known to {}", known);
        prop_assert!(again.stats.intervals <= report.stats.intervals);
    }

    // (g) Without every counter, the same verdict and first contact, and the same grazes
    // and unresolved intervals through it (which certify the report).
    let lean = check(
        &scene,
        &CheckOptions {
            counters: false,
            ..opts
        },
    );
    prop_assert_eq!(&lean.first_contact, &report.first_contact);
    prop_assert_eq!(
        (lean.safe_until, lean.certified),
        (report.safe_until, report.certified)
    );
    prop_assert_eq!(
        (lean.stats.grazing, lean.stats.unresolved),
        (report.stats.grazing, report.stats.unresolved)
    );

    // (d) The report does not depend on the number of threads.
    same_on_any_threads(&scene, &opts, &report)
}

/// (b) At the reported time, the named pair is closer than δ; (c) not later than the earliest
/// sampled contact, up to the time tolerance; the certified prefix ends within the time
/// tolerance before the contact.
fn contact_holds(
    spec: &SceneSpec,
    report: &CheckReport,
    c: &Contact,
    first_sampled: Option<(f64, f64)>,
) -> Result<(), TestCaseError> {
    let (h0, h1) = spec.horizon();
    // Slack for the time comparisons: a few rounding errors of the horizon's end.
    let slack = 1e-12 * (1.0 + h1.abs());
    prop_assert!(report.collision);
    prop_assert!(
        (h0..=h1).contains(&c.time),
        "contact time {} outside the horizon [{h0}, {h1}]",
        c.time
    );
    // (b) At the reported time, the named pair is closer than δ.
    let index = |name: &str| NAMES.iter().position(|n| *n == name).unwrap();
    let pair = (index(&c.bodies[0]), index(&c.bodies[1]));
    prop_assert!(
        spec.pairs().contains(&pair),
        "reported pair {:?} is not one of the scene's pairs in report order",
        c.bodies
    );
    let d = spec.distance(pair, c.time);
    prop_assert!(
        d < DELTA + EPS,
        "contact reported at t = {} but the distance there is {d:e} >= δ",
        c.time
    );
    prop_assert!(
        (d - c.distance).abs() <= EPS,
        "reported distance {:e}, exact {d:e}",
        c.distance
    );
    // (c) Not later than the earliest sampled contact, up to the time tolerance.
    if let Some((t, d)) = first_sampled {
        prop_assert!(
            c.time <= t + report.time_tol + slack,
            "first contact reported at {}, but distance {d:e} at t = {t} (tol {:e})",
            c.time,
            report.time_tol
        );
    }
    // The certified prefix ends within the time tolerance before the contact.
    prop_assert!(
        report.safe_until <= c.time && c.time - report.safe_until <= report.time_tol + slack,
        "safe_until {} vs contact time {} (tol {:e})",
        report.safe_until,
        c.time,
        report.time_tol
    );
    Ok(())
}

/// The same report on one thread and, three times, on four.
fn same_on_any_threads(
    scene: &Scene,
    opts: &CheckOptions,
    report: &CheckReport,
) -> Result<(), TestCaseError> {
    let (one, four) = pools();
    let serial = one.install(|| check(scene, opts));
    prop_assert_eq!(&serial, report, "1 thread vs the global pool");
    for _ in 0..3 {
        let parallel: CheckReport = four.install(|| check(scene, opts));
        prop_assert_eq!(&parallel, &serial, "4 threads vs 1 thread");
    }
    Ok(())
}

proptest! {
    #![proptest_config(proptest_config(128))]

    #[test]
    fn checker_agrees_with_dense_sampling(spec in scene_spec()) {
        check_scene(&spec)?;
    }
}

proptest! {
    #![proptest_config(proptest_config(64))]

    /// Near misses, decided both ways: closer than δ(1 − grazing_tol) is a collision, δ or
    /// farther is not (in between, either answer is allowed).
    #[test]
    fn near_misses_are_decided_exactly(m in near_miss()) {
        let opts = CheckOptions::default();
        let report = check(&m.spec.scene(), &opts);
        if m.gap < DELTA * (1.0 - opts.grazing_tol) - EPS {
            prop_assert!(report.collision, "missed a pass at {:e} (δ = {DELTA})", m.gap);
        }
        if m.gap > DELTA + EPS {
            prop_assert!(
                !report.collision,
                "collision reported for a pass at {:e} (δ = {DELTA}): {:?}",
                m.gap,
                report.first_contact
            );
        }
        check_scene(&m.spec)?;
    }
}

/// The scenes generated are a mix of free and colliding ones, with contacts after the start
/// of the horizon, so that every property above is exercised.
#[test]
fn scenes_are_mixed() {
    let mut runner = TestRunner::deterministic();
    let (mut free, mut at_start, mut later) = (0, 0, 0);
    for _ in 0..200 {
        let spec = draw(&scene_spec(), &mut runner);
        let report = check(&spec.scene(), &CheckOptions::default());
        match report.first_contact {
            None => free += 1,
            Some(c) if c.time == report.horizon[0] => at_start += 1,
            Some(_) => later += 1,
        }
    }
    eprintln!("scenes: {free} free, {at_start} colliding at the start, {later} later");
    assert!(free >= 40, "only {free}/200 free scenes");
    assert!(
        later >= 40,
        "only {later}/200 scenes with a contact after the start"
    );
}

/// The near misses are built right: the smallest distance along robot 0's line (a convex
/// function of the position on the line, minimised by golden-section search) is the gap.
#[test]
fn near_miss_construction_is_right() {
    let mut runner = TestRunner::deterministic();
    for _ in 0..100 {
        let m = draw(&near_miss(), &mut runner);
        let a = &m.spec.robots[0];
        let (first, last) = (a.samples[0], a.samples[a.samples.len() - 1]);
        let b = match &m.spec.obstacle {
            Some(o) => o.clone(),
            None => {
                let r = &m.spec.robots[1];
                place(&r.shape, pose_at(&r.samples, r.samples[0][0]))
            }
        };
        let d = |u: f64| exact_distance(&place(&a.shape, lerp_pose(first, last, u)), &b);
        let (mut lo, mut hi) = (0.0, 1.0);
        let g = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..200 {
            let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if d(x1) < d(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        let min = d(0.5 * (lo + hi));
        assert!(
            (min - m.gap).abs() <= 1e-12,
            "near miss built at {:e}, smallest distance {min:e}",
            m.gap
        );
    }
}

/// The narrow-phase bug of `narrow_phase_props::touching_wedge_is_at_distance_zero`, seen
/// from the checker: two resting robots overlap (a vertex of B is 7e-4 deep inside A, with
/// δ = 0.001), but the walk reports them 9.5e-3 apart and the scene is certified free.
#[test]
fn overlapping_resting_robots_collide() {
    let p = 5e-4;
    let spec = SceneSpec {
        robots: [
            RobotSpec {
                shape: vec![[0.0, 0.0], [1000.0, 0.0], [1000.0, 1000.0], [0.0, 1000.0]],
                samples: vec![[0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]],
            },
            RobotSpec {
                shape: vec![
                    [1000.0 - p, 1000.0 - p],
                    [1000.015 - p, -500.0 - p],
                    [3000.0 - p, 250.0 - p],
                ],
                samples: vec![[0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]],
            },
        ],
        obstacle: None,
    };
    assert_eq!(spec.distance((0, 1), 0.0), 0.0);
    let scene = Scene {
        delta: 0.001,
        bodies: spec.scene().bodies,
    };
    let report = check(&scene, &CheckOptions::default());
    assert!(report.collision, "overlapping robots certified free");
}
