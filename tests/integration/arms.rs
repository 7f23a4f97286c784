//! Arms in `check` (contract section 6) against an exact reference: conservative
//! advancement on the link polygons, placed by its own forward kinematics, with the
//! independent oracle's exact distance, and the joint-rate speed bound of each link on each
//! segment of its samples.

use crate::common::arm_reference::{scene_first_contact, ArmSpec, RigidSpec, SceneSpec};
use crate::common::{exact_distance, proptest_config, Shape};
use proptest::prelude::*;
use rayon::ThreadPoolBuilder;
use serde_json::{json, Value};
use std::f64::consts::TAU;
use std::path::Path;
use workcell::cell::parse_scene;
use workcell::collision::{check, CheckOptions, CheckReport, Scene};

const DELTA: f64 = 0.01;

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
    let Ok(truth) = scene_first_contact(spec, DELTA, tol / 8.0) else {
        return Ok(None); // a graze the reference cannot decide
    };
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

/// The work budget keeps its meaning for arms, whether a pair runs ahead of its probes or
/// searches: a budget too small for a colliding scene stops the check with no verdict, its
/// proven prefix before the contact and never shrinking as the budget grows; enough budget
/// finds the contact. The same on 1, 2 and 4 threads.
#[test]
fn the_work_budget_holds_for_arms() {
    use workcell::generate::{generate_scene, Kind};
    let pools = [1, 2, 4].map(|n| ThreadPoolBuilder::new().num_threads(n).build().unwrap());
    let mut stopped = 0;
    for k in 0..6 {
        let scene = generate_scene(Kind::Arms, 1, k, 0);
        let full = check(&scene, &CheckOptions::default());
        let Some(contact) = &full.first_contact else {
            continue;
        };
        if contact.time == full.horizon[0] {
            continue; // in contact at the start: no budget is spent before
        }
        let mut last = f64::NEG_INFINITY;
        for budget in [1, 2, 5, 20, 100, 1000] {
            let opts = CheckOptions {
                max_work_per_pair: budget,
                ..CheckOptions::default()
            };
            let r = check(&scene, &opts);
            // No pair works past its budget, the intervals it runs ahead over included.
            let work = r.stats.intervals + r.stats.bisections + r.stats.looks;
            assert!(
                work <= budget * r.pairs as u64,
                "scene {k}: {work} for {budget}"
            );
            for pool in &pools {
                let again = pool.install(|| check(&scene, &opts));
                assert_eq!(
                    serde_json::to_value(&again).unwrap()["stats"],
                    serde_json::to_value(&r).unwrap()["stats"]
                );
                assert_eq!(
                    (again.safe_until, again.collision),
                    (r.safe_until, r.collision)
                );
            }
            match &r.budget_exhausted {
                Some(b) => {
                    stopped += 1;
                    assert!(!r.collision && !r.certified, "scene {k}, budget {budget}");
                    assert!(
                        b.time <= contact.time && r.safe_until <= b.time,
                        "scene {k}: {b:?}"
                    );
                    assert!(
                        r.safe_until >= last,
                        "scene {k}: the prefix shrank at {budget}"
                    );
                    last = r.safe_until;
                }
                None => {
                    let c = r
                        .first_contact
                        .as_ref()
                        .expect("the contact, with enough budget");
                    assert_eq!(c.time, contact.time, "scene {k}, budget {budget}");
                }
            }
        }
    }
    assert!(
        stopped >= 6,
        "only {stopped} checks ran out of budget: the test shows little"
    );
}
