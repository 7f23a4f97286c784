//! The checker on bodies made of parts (contract section 5) against an independent
//! reference: conservative advancement over the exact distance of `common` (exact
//! orientation predicates), between every part of one body and every part of the other.
//!
//! Each body is generated with both of its forms: its convex parts and, where it has one,
//! the outline that bounds the same region. The library reads one form or the other; the
//! reference always takes the parts, and shares no code with the library.

use crate::common::{exact_distance, place, proptest_config, Pt, Shape};
use proptest::prelude::*;
use rayon::ThreadPoolBuilder;
use workcell::collision::{check, Body, CheckOptions, CheckReport, Scene};
use workcell::geometry::{ConvexPolygon, Outline, Parts, Vec2};
use workcell::motion::{Motion, Sample, Trajectory};

const DELTA: f64 = 0.01;

/// A body's region: convex parts (counter-clockwise), and the outline of their union when
/// the generator knows it.
#[derive(Clone, Debug)]
struct BodySpec {
    parts: Vec<Shape>,
    outline: Option<Shape>,
}

impl BodySpec {
    /// The library's view of it, from the parts or from the outline.
    fn parts(&self, from_outline: bool) -> Parts {
        match (&self.outline, from_outline) {
            (Some(o), true) => Parts::from_outline(&Outline::new(o).expect("a simple outline"))
                .expect("an outline cut"),
            _ => Parts::new(
                self.parts
                    .iter()
                    .map(|p| ConvexPolygon::from_vertices(p).expect("a convex part"))
                    .collect(),
            )
            .expect("parts"),
        }
    }
}

/// Axis-aligned box from (x0, y0) to (x1, y1), counter-clockwise.
fn bar(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
    vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
}

/// A U opening towards +x, `w` wide and `h` high, arms `t` thick, centred on the origin:
/// a palm and two fingers (a gripper), or a fixture with a bay.
fn u_shape(w: f64, h: f64, t: f64) -> BodySpec {
    let (x0, x1, y0, y1) = (-0.5 * w, 0.5 * w, -0.5 * h, 0.5 * h);
    BodySpec {
        parts: vec![
            bar(x0, y0, x0 + t, y1),
            bar(x0 + t, y0, x1, y0 + t),
            bar(x0 + t, y1 - t, x1, y1),
        ],
        outline: Some(vec![
            [x0, y0],
            [x1, y0],
            [x1, y0 + t],
            [x0 + t, y0 + t],
            [x0 + t, y1 - t],
            [x1, y1 - t],
            [x1, y1],
            [x0, y1],
        ]),
    }
}

/// An L: a foot along +x and a leg along +y, `t` thick, its corner at the origin.
fn l_shape(a: f64, b: f64, t: f64) -> BodySpec {
    BodySpec {
        parts: vec![bar(0.0, 0.0, a, t), bar(0.0, t, t, b)],
        outline: Some(vec![[0.0, 0.0], [a, 0.0], [a, t], [t, t], [t, b], [0.0, b]]),
    }
}

/// A convex part on a circle of radius `r` around `(cx, cy)`, of `n` vertices from `phase`.
fn round_part(cx: f64, cy: f64, r: f64, n: usize, phase: f64) -> Shape {
    (0..n)
        .map(|k| {
            let a = phase + std::f64::consts::TAU * k as f64 / n as f64;
            [cx + r * a.cos(), cy + r * a.sin()]
        })
        .collect()
}

fn body() -> impl Strategy<Value = BodySpec> {
    prop_oneof![
        (0.5f64..1.2, 0.5f64..1.2, 0.08f64..0.2).prop_map(|(w, h, t)| u_shape(w, h, t)),
        (0.4f64..1.0, 0.4f64..1.0, 0.08f64..0.25).prop_map(|(a, b, t)| {
            let mut l = l_shape(a, b, t);
            // Put the frame's origin inside the foot, not at the corner.
            let shift = |p: &mut Pt| {
                p[0] -= 0.3 * a;
                p[1] -= 0.5 * t
            };
            l.parts.iter_mut().flatten().for_each(shift);
            l.outline.iter_mut().flatten().for_each(shift);
            l
        }),
        // Scattered convex parts, overlapping or apart: no outline.
        prop::collection::vec(
            (
                -0.5f64..0.5,
                -0.5f64..0.5,
                0.08f64..0.3,
                3usize..7,
                0.0f64..1.0
            ),
            2..6
        )
        .prop_map(|ps| BodySpec {
            parts: ps
                .iter()
                .map(|&(x, y, r, n, ph)| round_part(x, y, r, n, ph))
                .collect(),
            outline: None,
        }),
    ]
}

#[derive(Clone, Debug)]
struct RobotSpec {
    body: BodySpec,
    /// `[t, x, y, theta]`.
    samples: Vec<[f64; 4]>,
}

/// Samples on a time grid of its own, wandering around (`cx`, 0) and turning
/// up to a turn and a half between samples (spins that a velocity-only bound would miss).
fn robot(cx: f64) -> impl Strategy<Value = RobotSpec> {
    (
        body(),
        prop::collection::vec(
            (0.05f64..0.6, cx - 1.0..cx + 1.0, -1.0f64..1.0, -9.0f64..9.0),
            3..9,
        ),
    )
        .prop_map(|(body, steps)| {
            let mut t = 0.0;
            let samples = steps
                .iter()
                .map(|&(dt, x, y, th)| {
                    t += dt;
                    [t, x, y, th]
                })
                .collect();
            RobotSpec { body, samples }
        })
}

#[derive(Clone, Debug)]
struct SceneSpec {
    robots: [RobotSpec; 2],
    /// In world coordinates.
    obstacle: BodySpec,
    /// Which bodies the library reads from their outline.
    from_outline: [bool; 3],
}

fn scene_spec() -> impl Strategy<Value = SceneSpec> {
    (
        robot(-1.8),
        robot(1.8),
        body(),
        (-3.5f64..3.5, -2.5f64..2.5),
        any::<[bool; 3]>(),
    )
        .prop_map(|(r0, r1, mut obstacle, (ox, oy), from_outline)| {
            for p in obstacle
                .parts
                .iter_mut()
                .chain(obstacle.outline.iter_mut())
                .flatten()
            {
                p[0] += ox;
                p[1] += oy;
            }
            SceneSpec {
                robots: [r0, r1],
                obstacle,
                from_outline,
            }
        })
}

const NAMES: [&str; 3] = ["r0", "r1", "fixture"];

impl SceneSpec {
    fn scene(&self, outline: [bool; 3]) -> Scene {
        let robot = |k: usize| {
            let r = &self.robots[k];
            let samples = r.samples.iter().map(|&[t, x, y, theta]| Sample {
                t,
                pos: Vec2::new(x, y),
                theta,
                vel: Vec2::zeros(),
                omega: 0.0,
            });
            let trajectory = Trajectory::new(samples.collect()).expect("increasing times");
            Body::robot_of_parts(NAMES[k], r.body.parts(outline[k]), trajectory)
        };
        let fixture = Body::obstacle_of_parts(NAMES[2], &self.obstacle.parts(outline[2]));
        Scene::with_bodies(DELTA, [robot(0), robot(1), fixture]).expect("a scene")
    }

    /// The reference's view: the parts as generated (never the library's partition).
    fn reference(&self) -> Reference {
        let robot = |r: &RobotSpec| RefBody {
            parts: r.body.parts.clone(),
            samples: Some(r.samples.clone()),
        };
        Reference {
            bodies: vec![
                robot(&self.robots[0]),
                robot(&self.robots[1]),
                RefBody {
                    parts: self.obstacle.parts.clone(),
                    samples: None,
                },
            ],
            delta: DELTA,
        }
    }
}

/// A body as the reference sees it: convex parts, in its frame for a robot (with samples
/// `[t, x, y, theta]`) and in the world for an obstacle.
struct RefBody {
    parts: Vec<Shape>,
    samples: Option<Vec<[f64; 4]>>,
}

/// Conservative advancement over the exact distance of `common`: the reference.
struct Reference {
    /// Robots first, then obstacles, as a scene orders them.
    bodies: Vec<RefBody>,
    delta: f64,
}

impl Reference {
    /// A library scene's bodies read as data: the parts' vertices (for a body read from an
    /// outline, the library's cut, whose exact cover `geometry::outline` tests) and the
    /// trajectories' samples.
    fn of(scene: &Scene) -> Reference {
        let bodies = scene
            .bodies
            .iter()
            .map(|b| {
                let shapes: Vec<&ConvexPolygon> = match &b.parts {
                    Some(p) => p.parts().iter().collect(),
                    None => vec![&b.shape],
                };
                let vertices = |p: &ConvexPolygon| -> Shape {
                    p.vertices().iter().map(|v| [v.x, v.y]).collect()
                };
                match &b.motion {
                    Motion::Link(_) => unreachable!("these scenes have no arms"),
                    Motion::Sampled(tr) => RefBody {
                        parts: shapes.into_iter().map(vertices).collect(),
                        samples: Some(
                            tr.samples()
                                .iter()
                                .map(|s| [s.t, s.pos.x, s.pos.y, s.theta])
                                .collect(),
                        ),
                    },
                    Motion::Fixed(pose) => RefBody {
                        parts: shapes
                            .into_iter()
                            .map(|p| place(&vertices(p), [pose.pos.x, pose.pos.y, pose.theta]))
                            .collect(),
                        samples: None,
                    },
                }
            })
            .collect();
        Reference {
            bodies,
            delta: scene.delta,
        }
    }

    fn horizon(&self) -> (f64, f64) {
        let ts = self
            .bodies
            .iter()
            .filter_map(|b| b.samples.as_ref())
            .flat_map(|s| s.iter().map(|s| s[0]));
        ts.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
            (lo.min(t), hi.max(t))
        })
    }

    /// The pairs a scene checks: robot-robot, then robot-obstacle.
    fn pairs(&self) -> Vec<(usize, usize)> {
        let n = self.bodies.len();
        let robot = |k: &usize| self.bodies[*k].samples.is_some();
        let mut pairs = Vec::new();
        for i in (0..n).filter(robot) {
            pairs.extend((i + 1..n).filter(robot).map(|j| (i, j)));
        }
        for i in (0..n).filter(robot) {
            pairs.extend((0..n).filter(|j| !robot(j)).map(|j| (i, j)));
        }
        pairs
    }

    /// The parts of body `k` in the world at time `t`.
    fn world(&self, k: usize, t: f64) -> Vec<Shape> {
        let b = &self.bodies[k];
        match &b.samples {
            None => b.parts.clone(),
            Some(s) => {
                let pose = pose_at(s, t);
                b.parts.iter().map(|p| place(p, pose)).collect()
            }
        }
    }

    /// Least exact distance between the parts of bodies `i` and `j` at `t`.
    fn distance(&self, (i, j): (usize, usize), t: f64) -> f64 {
        let (a, b) = (self.world(i, t), self.world(j, t));
        a.iter()
            .flat_map(|p| b.iter().map(move |q| exact_distance(p, q)))
            .fold(f64::INFINITY, f64::min)
    }

    /// How fast the points of body `k` can move between its samples around `t`: on the
    /// segment holding `t`, |Δ(x, y)| + R·|Δθ| over its duration (0 outside the samples);
    /// and when that segment ends.
    fn speed_bound(&self, k: usize, t: f64) -> (f64, f64) {
        let b = &self.bodies[k];
        let Some(s) = &b.samples else {
            return (0.0, f64::INFINITY);
        };
        let Some(i) = s.windows(2).position(|w| w[0][0] <= t && t < w[1][0]) else {
            // At rest, until its first sample or for good.
            return (0.0, if t < s[0][0] { s[0][0] } else { f64::INFINITY });
        };
        let radius = b
            .parts
            .iter()
            .flatten()
            .map(|p| p[0].hypot(p[1]))
            .fold(0.0, f64::max);
        let (p, q) = (s[i], s[i + 1]);
        let travel = (q[1] - p[1]).hypot(q[2] - p[2]) + radius * (q[3] - p[3]).abs();
        (travel / (q[0] - p[0]), q[0])
    }

    /// Conservative advancement of one pair ([`crate::common::advance_to_contact`]): the
    /// first time it comes closer than δ, with the end of the prefix proven before it.
    fn first_contact(&self, pair: (usize, usize), min_step: f64) -> Result<Option<(f64, f64)>, ()> {
        let speed = |t: f64| {
            let ((va, ea), (vb, eb)) = (self.speed_bound(pair.0, t), self.speed_bound(pair.1, t));
            // Until the next sample of either, the points move no faster than va + vb.
            (va + vb, ea.min(eb))
        };
        let distance = |t: f64| self.distance(pair, t);
        crate::common::advance_to_contact(distance, speed, self.horizon(), self.delta, min_step)
    }
}

/// The pose of samples `[t, x, y, theta]` at `t`, at rest before the first and after the last.
fn pose_at(s: &[[f64; 4]], t: f64) -> [f64; 3] {
    crate::common::pose_at(s, t)
}

/// The reference's first contact: the end of the prefix it proves free, the time of its
/// witness, and the pair; `None` when free.
type Truth = Option<(f64, f64, (usize, usize))>;

/// What the reference finds over every pair; `Err` for a graze it cannot decide.
fn reference(r: &Reference, min_step: f64) -> Result<Truth, ()> {
    let mut first: Option<(f64, f64, (usize, usize))> = None;
    for pair in r.pairs() {
        if let Some((proven, hit)) = r.first_contact(pair, min_step)? {
            if first.is_none_or(|(_, h, _)| hit < h) {
                first = Some((proven, hit, pair));
            }
        }
    }
    Ok(first)
}

/// The first contact of a report: its time and the pair, by body index in `scene`.
fn verdict_of(scene: &Scene, report: &CheckReport) -> Option<(f64, (usize, usize))> {
    let c = report.first_contact.as_ref()?;
    let index = |name: &str| scene.bodies.iter().position(|b| b.name == name).unwrap();
    Some((c.time, (index(&c.bodies[0]), index(&c.bodies[1]))))
}

/// The checker against the reference: same verdict, a contact between the reference's
/// proven prefix and its witness (to the time tolerance), and a pair at that time truly
/// closer than δ; the same report on 1, 2 and 4 threads.
fn agrees(spec: &SceneSpec) -> Result<Option<bool>, TestCaseError> {
    agrees_on(&spec.scene(spec.from_outline), &spec.reference())
}

/// [`agrees`] on any scene and its reference.
fn agrees_on(scene: &Scene, r: &Reference) -> Result<Option<bool>, TestCaseError> {
    let opts = CheckOptions::default();
    let report = check(scene, &opts);
    let tol = report.time_tol;
    let Ok(truth) = reference(r, tol / 8.0) else {
        return Ok(None); // a graze the reference cannot decide
    };
    // Uncertified only by a graze of δ (within the grazing allowance), never unresolved.
    prop_assert!(
        report.certified || report.stats.grazing > 0,
        "{:?}",
        report.stats
    );
    prop_assert_eq!(report.stats.unresolved, 0);
    match (truth, verdict_of(scene, &report)) {
        (None, None) => {}
        (Some((_, hit, pair)), None) => {
            prop_assert!(false, "missed: {pair:?} closer than δ at t = {hit}")
        }
        (None, Some((t, pair))) => {
            prop_assert!(
                false,
                "invented: {pair:?} at t = {t}, the reference finds none"
            )
        }
        (Some((proven, hit, _)), Some((t, pair))) => {
            let slack = 1e-12;
            prop_assert!(
                proven - slack <= t && t <= hit + tol + slack,
                "contact at {t}, the reference's first in [{proven}, {hit}] (tol {tol:e})"
            );
            let d = r.distance(pair, t);
            prop_assert!(d < r.delta + 1e-9, "{pair:?} at {t} is {d} apart");
        }
    }
    for threads in [1, 2, 4] {
        let pool = ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        prop_assert_eq!(
            &pool.install(|| check(scene, &opts)),
            &report,
            "{} threads",
            threads
        );
    }
    Ok(Some(report.collision))
}

proptest! {
    #![proptest_config(proptest_config(160))]

    #[test]
    fn parts_checker_agrees_with_conservative_advancement(spec in scene_spec()) {
        agrees(&spec)?;
    }

    /// A body read from its parts or from its outline is one region: the same verdict, the
    /// same pair and the same first contact, to the time tolerance.
    #[test]
    fn parts_and_outline_give_the_same_verdict(spec in scene_spec()) {
        let opts = CheckOptions::default();
        let (parts, outlines) = (spec.scene([false; 3]), spec.scene([true; 3]));
        let (from_parts, from_outline) = (check(&parts, &opts), check(&outlines, &opts));
        let (a, b) = (verdict_of(&parts, &from_parts), verdict_of(&outlines, &from_outline));
        prop_assert_eq!(a.is_some(), b.is_some());
        if let (Some((ta, pa)), Some((tb, pb))) = (a, b) {
            prop_assert!((ta - tb).abs() <= from_parts.time_tol + 1e-12, "{ta} against {tb}");
            prop_assert_eq!(pa, pb);
        }
    }
}

/// The generated scenes are a mix: many collide, many are free, few are undecided.
#[test]
fn parts_scenes_are_mixed() {
    let mut runner = proptest::test_runner::TestRunner::new(proptest_config(120));
    let (mut free, mut hit, mut undecided) = (0, 0, 0);
    for _ in 0..120 {
        let spec = crate::common::draw(&scene_spec(), &mut runner);
        match agrees(&spec).expect("agrees") {
            Some(true) => hit += 1,
            Some(false) => free += 1,
            None => undecided += 1,
        }
    }
    assert!(
        free >= 20 && hit >= 20 && undecided <= 6,
        "{free} free, {hit} hit, {undecided} undecided"
    );
}

/// A peg in a U's bay: the hulls overlap all along, the parts never meet; then the same peg
/// pushed into the U's floor meets part 1, which the report names.
#[test]
fn notch_clear_and_the_part_in_contact() {
    let u = u_shape(1.0, 1.0, 0.2);
    let peg = BodySpec {
        parts: vec![bar(-0.15, -0.15, 0.15, 0.15)],
        outline: None,
    };
    let spec = |x_end: f64| SceneSpec {
        robots: [
            RobotSpec {
                body: peg.clone(),
                samples: vec![[0.0, 0.45, 0.0, 0.0], [1.0, x_end, 0.0, 0.3]],
            },
            RobotSpec {
                body: peg.clone(),
                samples: vec![[0.0, 5.0, 5.0, 0.0], [1.0, 5.0, 5.0, 0.0]],
            },
        ],
        obstacle: u.clone(),
        from_outline: [false; 3],
    };
    let clear = spec(0.0);
    let report = check(&clear.scene([false; 3]), &CheckOptions::default());
    assert!(!report.collision && report.certified, "{report:?}");
    assert!(agrees(&clear).unwrap().is_some());
    let into_wall = spec(-0.4);
    let report = check(&into_wall.scene([false; 3]), &CheckOptions::default());
    let c = report.first_contact.as_ref().expect("a contact");
    assert_eq!(c.bodies, ["r0".to_owned(), "fixture".to_owned()]);
    assert_eq!(
        c.parts,
        Some([None, Some(0)]),
        "the palm of the U, its part 0"
    );
    // Read from the outline, the fixture's parts are the project's own: no index.
    let report = check(
        &into_wall.scene([false, false, true]),
        &CheckOptions::default(),
    );
    assert_eq!(report.first_contact.unwrap().parts, None);
}

/// An H-shaped robot jumps in one sample step from having a post in its upper bay to
/// having it in its lower bay: its crossbar passes through the post between two samples
/// where the hulls overlap and the parts are 0.2 apart. Only bisection finds the contact:
/// the part distance is no convex function of the motion, so no tangent may certify it.
#[test]
fn tunnelling_through_a_crossbar_between_samples() {
    let h = BodySpec {
        parts: vec![
            bar(-0.6, -0.6, -0.4, 0.6),
            bar(0.4, -0.6, 0.6, 0.6),
            bar(-0.4, -0.1, 0.4, 0.1),
        ],
        outline: None,
    };
    let post = BodySpec {
        parts: vec![bar(-0.05, -0.05, 0.05, 0.05)],
        outline: None,
    };
    let spec = SceneSpec {
        robots: [
            RobotSpec {
                body: h,
                samples: vec![[0.0, 0.0, -0.35, 0.0], [1.0, 0.0, 0.35, 0.0]],
            },
            RobotSpec {
                body: post.clone(),
                samples: vec![[0.0, 9.0, 9.0, 0.0], [1.0, 9.0, 9.0, 0.0]],
            },
        ],
        obstacle: post,
        from_outline: [false; 3],
    };
    let report = check(&spec.scene([false; 3]), &CheckOptions::default());
    let c = report
        .first_contact
        .as_ref()
        .expect("the crossbar meets the post");
    assert_eq!(
        (c.bodies[1].as_str(), c.parts),
        ("fixture", Some([Some(2), None]))
    );
    // The crossbar's top, 0.2 below the post at first, closes in at 0.7 per unit of time.
    assert!((c.time - (0.2 - DELTA) / 0.7).abs() < 1e-5, "{}", c.time);
    assert_eq!(agrees(&spec).unwrap(), Some(true));
}

/// Every generated kind of non-convex bodies against the reference, eight scenes of each:
/// 0 missed, 0 invented; the kinds known free are free and certified.
#[test]
fn generated_parts_kinds_agree_with_the_reference() {
    use workcell::generate::{generate_scene, Kind};
    for kind in Kind::PARTS {
        let mut decided = 0;
        for index in 0..8 {
            let scene = generate_scene(kind, 1, index, 0);
            let verdict = agrees_on(&scene, &Reference::of(&scene))
                .unwrap_or_else(|e| panic!("{} {index}: {e}", kind.name()));
            if let Some(collides) = verdict {
                decided += 1;
                if matches!(kind, Kind::Bay | Kind::NotchClear) {
                    assert!(!collides, "{} {index} collides", kind.name());
                }
            }
        }
        assert!(decided >= 7, "{}: {decided} of 8 decided", kind.name());
    }
}
