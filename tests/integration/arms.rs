//! Arms in `check` (contract section 6) against an exact reference: conservative
//! advancement on the link polygons, placed by its own forward kinematics, with the
//! independent oracle's exact distance, and the joint-rate speed bound of each link on each
//! segment of its samples.

use crate::common::{exact_distance, pose_at, proptest_config, Shape};
use proptest::prelude::*;
use rayon::ThreadPoolBuilder;
use serde_json::{json, Value};
use std::f64::consts::TAU;
use std::path::Path;
use workcell::cell::parse_scene;
use workcell::collision::{check, CheckOptions, CheckReport, Scene};

const DELTA: f64 = 0.01;

impl SceneSpec {
    /// A generated scene as the reference reads it: each arm's base, lengths, link polygons
    /// and joint samples; each rigid robot's polygon and poses; each obstacle in the world.
    fn of_scene(scene: &Scene) -> SceneSpec {
        use workcell::motion::Motion;
        let vertices = |p: &workcell::geometry::ConvexPolygon| -> Shape {
            p.vertices().iter().map(|v| [v.x, v.y]).collect()
        };
        let mut spec = SceneSpec {
            arms: Vec::new(),
            rigid: Vec::new(),
            fixtures: Vec::new(),
        };
        for (k, b) in scene.bodies.iter().enumerate() {
            assert!(b.parts.is_none(), "generated arm scenes are convex");
            match &b.motion {
                Motion::Link(l) => {
                    if k > 0 && scene.bodies[k - 1].same_arm(b) {
                        spec.arms.last_mut().unwrap().links.push(vertices(&b.shape));
                        continue;
                    }
                    let base = l.arm.base();
                    spec.arms.push(ArmSpec {
                        name: b.name.clone(),
                        base: [base.pos.x, base.pos.y, base.theta],
                        lengths: l.arm.lengths().to_vec(),
                        links: vec![vertices(&b.shape)],
                        samples: l.arm.samples().iter().map(|s| (s.t, s.q.clone())).collect(),
                    });
                }
                Motion::Sampled(tr) => spec.rigid.push(RigidSpec {
                    shape: vertices(&b.shape),
                    samples: tr
                        .samples()
                        .iter()
                        .map(|s| [s.t, s.pos.x, s.pos.y, s.theta])
                        .collect(),
                }),
                Motion::Fixed(p) => spec.fixtures.push(crate::common::place(
                    &vertices(&b.shape),
                    [p.pos.x, p.pos.y, p.theta],
                )),
            }
        }
        spec
    }
}

/// An arm as the test draws it: base, link lengths, each link's polygon in its frame, and
/// samples `(t, q)`.
#[derive(Clone, Debug)]
struct ArmSpec {
    name: String,
    base: [f64; 3],
    lengths: Vec<f64>,
    links: Vec<Shape>,
    samples: Vec<(f64, Vec<f64>)>,
}

/// A rigid robot: a polygon and samples `[t, x, y, θ]`.
#[derive(Clone, Debug)]
struct RigidSpec {
    shape: Shape,
    samples: Vec<[f64; 4]>,
}

#[derive(Clone, Debug)]
struct SceneSpec {
    arms: Vec<ArmSpec>,
    rigid: Vec<RigidSpec>,
    fixtures: Vec<Shape>,
}

fn bar(length: f64, w: f64) -> Shape {
    vec![[-w, -w], [length + w, -w], [length + w, w], [-w, w]]
}

fn arm(name: &'static str, base: [f64; 3]) -> impl Strategy<Value = ArmSpec> {
    let links = prop::collection::vec((0.3..0.9f64, 0.04..0.12f64), 2..=3);
    (links, 2..=6usize, 0.05..2.0f64, any::<u64>()).prop_map(move |(links, n, dt, seed)| {
        // Angles from a small deterministic generator: some joints turn several times.
        let mut state = seed | 1;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let spin = next() < 0.3;
        let mut t = 0.0;
        let samples = (0..n)
            .map(|_| {
                let q: Vec<f64> = links
                    .iter()
                    .map(|_| {
                        let range = if spin { 3.0 * TAU } else { 2.0 };
                        (next() - 0.5) * 2.0 * range
                    })
                    .collect();
                let sample = (t, q);
                t += dt * (0.2 + next());
                sample
            })
            .collect();
        ArmSpec {
            name: name.into(),
            base,
            lengths: links.iter().map(|l| l.0).collect(),
            links: links.iter().map(|&(l, w)| bar(l, w)).collect(),
            samples,
        }
    })
}

fn scene_spec() -> impl Strategy<Value = SceneSpec> {
    let a = arm("A1", [0.0, 0.0, 0.0]);
    let b =
        (1.4..4.2f64, -0.6..0.6f64, -3.0..3.0f64).prop_flat_map(|(x, y, th)| arm("A2", [x, y, th]));
    let rigid = prop::option::of(
        prop::collection::vec((-1.0..3.0f64, -1.5..1.5f64, -2.0..2.0f64), 2..=4).prop_map(
            |points| RigidSpec {
                shape: bar(0.2, 0.1),
                samples: points
                    .iter()
                    .enumerate()
                    .map(|(k, &(x, y, th))| [k as f64 * 0.7, x, y, th])
                    .collect(),
            },
        ),
    );
    let fixture = (-1.0..3.0f64, -1.8..1.8f64)
        .prop_map(|(x, y)| vec![[x, y], [x + 0.3, y], [x + 0.3, y + 0.2], [x, y + 0.2]]);
    (a, b, rigid, fixture).prop_map(|(a, b, rigid, fixture)| SceneSpec {
        arms: vec![a, b],
        rigid: rigid.into_iter().collect(),
        fixtures: vec![fixture],
    })
}

impl SceneSpec {
    fn document(&self) -> Value {
        let mut robots: Vec<Value> = self
            .arms
            .iter()
            .map(|a| {
                let links: Vec<Value> = a
                    .lengths
                    .iter()
                    .zip(&a.links)
                    .map(|(l, s)| json!({"length": l, "shape": s}))
                    .collect();
                let samples: Vec<Value> = a
                    .samples
                    .iter()
                    .map(|(t, q)| json!({"t": t, "q": q}))
                    .collect();
                json!({"name": a.name, "base": a.base, "links": links, "trajectory": samples})
            })
            .collect();
        for (k, r) in self.rigid.iter().enumerate() {
            let samples: Vec<Value> = r
                .samples
                .iter()
                .map(|s| json!({"t": s[0], "x": s[1], "y": s[2], "theta": s[3]}))
                .collect();
            robots.push(json!({"name": format!("R{k}"), "shape": r.shape, "trajectory": samples}));
        }
        let obstacles: Vec<Value> = (self.fixtures.iter().enumerate())
            .map(|(k, f)| json!({"name": format!("F{k}"), "shape": f}))
            .collect();
        json!({"delta": DELTA, "robots": robots, "obstacles": obstacles})
    }

    fn scene(&self) -> Scene {
        parse_scene(&self.document().to_string(), Path::new("arms.json"))
            .unwrap()
            .scene
    }

    /// The reference's bodies in the scene's order: each link of each arm, the rigid robot,
    /// the fixture.
    fn bodies(&self) -> Vec<RefBody<'_>> {
        let mut out: Vec<RefBody> = Vec::new();
        for a in &self.arms {
            out.extend((0..a.links.len()).map(|k| RefBody::Link(a, k)));
        }
        out.extend(self.rigid.iter().map(RefBody::Rigid));
        out.extend(self.fixtures.iter().map(RefBody::Fixed));
        out
    }

    fn horizon(&self) -> (f64, f64) {
        let mut ts: Vec<f64> = self
            .arms
            .iter()
            .flat_map(|a| a.samples.iter().map(|s| s.0))
            .collect();
        for r in &self.rigid {
            ts.extend(r.samples.iter().map(|s| s[0]));
        }
        ts.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
                (lo.min(t), hi.max(t))
            })
    }
}

#[derive(Clone, Copy)]
enum RefBody<'s> {
    Link(&'s ArmSpec, usize),
    Rigid(&'s RigidSpec),
    Fixed(&'s Shape),
}

/// The joint angles of `a` at `t`: linear per joint, held outside the samples.
fn q_at(a: &ArmSpec, t: f64) -> Vec<f64> {
    let s = &a.samples;
    if t <= s[0].0 {
        return s[0].1.clone();
    }
    let last = &s[s.len() - 1];
    if t >= last.0 {
        return last.1.clone();
    }
    let k = s.iter().rposition(|x| x.0 <= t).unwrap();
    let (p, q) = (&s[k], &s[k + 1]);
    let u = (t - p.0) / (q.0 - p.0);
    p.1.iter().zip(&q.1).map(|(a, b)| a + (b - a) * u).collect()
}

/// The test's own forward kinematics (contract section 6).
fn link_pose(a: &ArmSpec, q: &[f64], link: usize) -> [f64; 3] {
    let (mut x, mut y) = (a.base[0], a.base[1]);
    let mut th = a.base[2] + q[0];
    for (length, turn) in a.lengths[..link].iter().zip(&q[1..=link]) {
        x += length * th.cos();
        y += length * th.sin();
        th += turn;
    }
    [x, y, th]
}

fn radius(shape: &Shape) -> f64 {
    shape.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max)
}

impl RefBody<'_> {
    fn robot(&self) -> bool {
        !matches!(self, RefBody::Fixed(_))
    }

    fn world(&self, t: f64) -> Shape {
        match *self {
            RefBody::Link(a, k) => {
                let pose = link_pose(a, &q_at(a, t), k);
                crate::common::place(&a.links[k], pose)
            }
            RefBody::Rigid(r) => crate::common::place(&r.shape, pose_at(&r.samples, t)),
            RefBody::Fixed(s) => s.clone(),
        }
    }

    /// How fast any point can move on the segment holding `t`, and when that segment ends.
    fn speed_bound(&self, t: f64) -> (f64, f64) {
        let segment = |times: &[f64]| {
            times
                .windows(2)
                .position(|w| w[0] <= t && t < w[1])
                .ok_or(if t < times[0] {
                    times[0]
                } else {
                    f64::INFINITY
                })
        };
        match *self {
            RefBody::Fixed(_) => (0.0, f64::INFINITY),
            RefBody::Rigid(r) => {
                let times: Vec<f64> = r.samples.iter().map(|s| s[0]).collect();
                match segment(&times) {
                    Err(end) => (0.0, end),
                    Ok(i) => {
                        let (p, q) = (r.samples[i], r.samples[i + 1]);
                        let travel = (q[1] - p[1]).hypot(q[2] - p[2])
                            + radius(&r.shape) * (q[3] - p[3]).abs();
                        (travel / (q[0] - p[0]), q[0])
                    }
                }
            }
            RefBody::Link(a, k) => {
                let times: Vec<f64> = a.samples.iter().map(|s| s.0).collect();
                match segment(&times) {
                    Err(end) => (0.0, end),
                    Ok(i) => {
                        let (p, q) = (&a.samples[i], &a.samples[i + 1]);
                        let dt = q.0 - p.0;
                        let lever =
                            |j: usize| a.lengths[j..k].iter().sum::<f64>() + radius(&a.links[k]);
                        let v: f64 = (0..=k)
                            .map(|j| (q.1[j] - p.1[j]).abs() / dt * lever(j))
                            .sum();
                        (v, q.0)
                    }
                }
            }
        }
    }
}

/// Conservative advancement of one pair (the reference of `parts_checker` too).
fn first_contact(
    a: RefBody,
    b: RefBody,
    horizon: (f64, f64),
    min_step: f64,
) -> Result<Option<(f64, f64)>, ()> {
    let distance = |t: f64| exact_distance(&a.world(t), &b.world(t));
    let speed = |t: f64| {
        let ((va, ea), (vb, eb)) = (a.speed_bound(t), b.speed_bound(t));
        (va + vb, ea.min(eb))
    };
    crate::common::advance_to_contact(distance, speed, horizon, DELTA, min_step)
}

/// Every pair the scene checks, in its order: robots against robots (never two links of one
/// arm), then robots against the fixture.
fn pairs(bodies: &[RefBody]) -> Vec<(usize, usize)> {
    let same_arm = |i: usize, j: usize| match (bodies[i], bodies[j]) {
        (RefBody::Link(a, _), RefBody::Link(b, _)) => std::ptr::eq(a, b),
        _ => false,
    };
    let n = bodies.len();
    let robot = |k: &usize| bodies[*k].robot();
    let mut out = Vec::new();
    for i in (0..n).filter(robot) {
        out.extend(
            (i + 1..n)
                .filter(|j| robot(j) && !same_arm(i, *j))
                .map(|j| (i, j)),
        );
    }
    for i in (0..n).filter(robot) {
        out.extend((0..n).filter(|j| !robot(j)).map(|j| (i, j)));
    }
    out
}

fn agrees(spec: &SceneSpec) -> Result<Option<bool>, TestCaseError> {
    agrees_on(&spec.scene(), spec)
}

/// [`agrees`] on a scene and the reference's reading of it.
fn agrees_on(scene: &Scene, spec: &SceneSpec) -> Result<Option<bool>, TestCaseError> {
    let opts = CheckOptions::default();
    let report = check(scene, &opts);
    let tol = report.time_tol;
    let bodies = spec.bodies();
    prop_assert_eq!(bodies.len(), scene.bodies.len());
    let mut truth: Option<(f64, f64, (usize, usize))> = None;
    for (i, j) in pairs(&bodies) {
        let Ok(found) = first_contact(bodies[i], bodies[j], spec.horizon(), tol / 8.0) else {
            return Ok(None); // a graze the reference cannot decide
        };
        if let Some((proven, hit)) = found {
            if truth.is_none_or(|(_, h, _)| hit < h) {
                truth = Some((proven, hit, (i, j)));
            }
        }
    }
    prop_assert!(
        report.certified || report.stats.grazing > 0,
        "{:?}",
        report.stats
    );
    prop_assert_eq!(report.stats.unresolved, 0);
    match (truth, &report.first_contact) {
        (None, None) => {}
        (Some((_, hit, pair)), None) => prop_assert!(false, "missed: {pair:?} at t = {hit}"),
        (None, Some(c)) => prop_assert!(false, "invented: {c:?}"),
        (Some((proven, hit, _)), Some(c)) => {
            let slack = 1e-12;
            prop_assert!(
                proven - slack <= c.time && c.time <= hit + tol + slack,
                "contact at {}, the reference's first in [{proven}, {hit}]",
                c.time
            );
            // The pair named, by name and link, is closer than δ at the time reported.
            let index = |name: &str, link: Option<usize>| {
                scene
                    .bodies
                    .iter()
                    .position(|b| b.name == name && b.link() == link)
                    .unwrap()
            };
            let links = c.links.unwrap_or([None, None]);
            let (i, j) = (index(&c.bodies[0], links[0]), index(&c.bodies[1], links[1]));
            let d = exact_distance(&bodies[i].world(c.time), &bodies[j].world(c.time));
            prop_assert!(d < DELTA + 1e-9, "({i}, {j}) at {} is {d} apart", c.time);
        }
    }
    for threads in [1, 2, 4] {
        let pool = ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let again: CheckReport = pool.install(|| check(scene, &opts));
        prop_assert_eq!(&again, &report, "{} threads", threads);
    }
    Ok(Some(report.collision))
}

proptest! {
    #![proptest_config(proptest_config(96))]

    #[test]
    fn arms_agree_with_conservative_advancement(spec in scene_spec()) {
        agrees(&spec)?;
    }
}

/// The drawn scenes are of every kind the property needs: free, colliding at the start,
/// colliding later (mid-interval, after a certified prefix); few left undecided.
#[test]
fn arm_scenes_are_mixed() {
    let mut runner = proptest::test_runner::TestRunner::new(proptest_config(120));
    let (mut free, mut at_start, mut later, mut undecided) = (0, 0, 0, 0);
    for _ in 0..120 {
        let spec = crate::common::draw(&scene_spec(), &mut runner);
        match agrees(&spec).expect("agrees") {
            None => undecided += 1,
            Some(false) => free += 1,
            Some(true) => {
                let report = check(&spec.scene(), &CheckOptions::default());
                match report.first_contact {
                    Some(c) if c.time > spec.horizon().0 => later += 1,
                    _ => at_start += 1,
                }
            }
        }
    }
    assert!(
        free >= 15 && later >= 15 && undecided <= 6,
        "{free} free, {at_start} at the start, {later} later, {undecided} undecided"
    );
}

/// Every generated arm kind agrees with the reference: the free sweeps 1.1δ to 1.5δ past a
/// fixture, the spins that meet a post only between samples, two arms on a table, an arm and
/// a rigid robot, long links with a fast tip, contacts in the last 1 % of the horizon, halls
/// of arms and rigid robots.
#[test]
fn generated_arm_kinds_agree_with_the_reference() {
    use workcell::generate::{generate_scene, Kind};
    for kind in Kind::ARMS {
        let (mut hit, mut free) = (0, 0);
        for seed in 1..=2 {
            for k in 0..8 {
                // Halls of 4 arms and 4 rigid robots.
                let scene = generate_scene(kind, seed, k, 4);
                let spec = SceneSpec::of_scene(&scene);
                match agrees_on(&scene, &spec) {
                    Ok(Some(true)) => hit += 1,
                    Ok(Some(false)) => free += 1,
                    Ok(None) => panic!("{}-{seed}-{k}: undecided by the reference", kind.name()),
                    Err(e) => panic!("{}-{seed}-{k}: {e}", kind.name()),
                }
            }
        }
        match kind {
            Kind::ArmSweep => assert_eq!(hit, 0, "sweeps are free"),
            Kind::ArmSpin => assert_eq!(free, 0, "spins collide"),
            _ => assert!(
                hit > 0 && free > 0,
                "{}: {hit} hit, {free} free",
                kind.name()
            ),
        }
    }
}

/// The late contacts of `generate --kind arm-late` are found where the geometry puts them:
/// link 0's leading edge, h from the link's axis, is ρ·sin(β − α) − h from the post's corner
/// at (ρ, β) while the arm points at α < β, so the first contact is at the time the base
/// joint reaches β − asin((h + δ)/ρ), when that falls within the horizon. The report is never
/// before it and at most the time tolerance after it.
#[test]
fn late_contacts_come_exactly_where_the_geometry_puts_them() {
    use workcell::generate::{generate_scene, Kind};
    use workcell::motion::Motion;
    let (mut late, mut short) = (0, 0);
    for k in 0..20 {
        let scene = generate_scene(Kind::ArmLate, 3, k, 0);
        let Motion::Link(link) = &scene.bodies[0].motion else {
            panic!("link 0 first")
        };
        let samples = link.arm.samples();
        let (first, last) = (&samples[0], &samples[samples.len() - 1]);
        let rate = (last.q[0] - first.q[0]) / (last.t - first.t);
        let h = (scene.bodies[0].shape.vertices().iter()).fold(0.0f64, |m, v| m.max(v.y.abs()));
        let post = scene.bodies.iter().find(|b| b.name == "post").unwrap();
        let corner = (post.shape.vertices().iter())
            .map(|v| post.motion.pose_at(0.0).pos + v)
            .min_by(|a, b| a.norm().total_cmp(&b.norm()))
            .unwrap();
        let (rho, beta) = (corner.norm(), corner.y.atan2(corner.x));
        // β is only known up to turns: the one just ahead of the arm's start.
        let ahead = (beta - first.q[0]).rem_euclid(TAU);
        let reach = first.q[0] + ahead - ((h + scene.delta) / rho).asin();
        let t = first.t + (reach - first.q[0]) / rate;
        let opts = CheckOptions::default();
        let report = check(&scene, &opts);
        let tol = opts.time_tol_for(scene.horizon());
        match report.first_contact {
            Some(c) => {
                late += 1;
                assert!(t > 9.9 && t < 10.0, "scene {k}: contact expected at {t}");
                let slack = 1e-9;
                assert!(
                    c.time >= t - slack && c.time <= t + tol + slack,
                    "scene {k}: reported at {}, expected {t} (tolerance {tol})",
                    c.time
                );
            }
            None => {
                short += 1;
                assert!(t > last.t, "scene {k}: contact at {t} missed");
            }
        }
    }
    assert!(late >= 5 && short >= 5, "{late} late, {short} short");
}
