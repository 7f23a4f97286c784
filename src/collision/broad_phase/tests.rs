use super::super::pair::{check_pair, SharedLimit};
use super::super::span::PairSettings;
use super::*;
use crate::collision::Body;
use crate::generate::{generate_scene, Kind};
use crate::geometry::{brute_force_distance, ConvexPolygon};
use crate::motion::{Pose, Trajectory};
use aabb::Aabb;
use grid::meeting;

/// The default settings of a pair of `scene` at `delta`.
fn settings(scene: &Scene, delta: f64) -> PairSettings {
    let (t0, t1) = scene.horizon();
    PairSettings {
        delta,
        grazing_tol: 1e-4 * delta,
        time_tol: 1e-6 * (t1 - t0),
        start: t0,
        walk: Default::default(),
        max_work: crate::collision::DEFAULT_MAX_WORK_PER_PAIR,
        counters: true,
    }
}

/// Candidates come in report order, and every pair left out is δ apart: the adaptive
/// check finds no contact on it, nor does the exact distance at 200 instants.
fn pruning_is_safe(scene: &Scene, delta: f64) -> usize {
    let (candidates, all) = (candidate_pairs(scene, delta), scene.pairs());
    let mut rest = all.iter();
    assert!(
        candidates.iter().all(|c| rest.any(|p| p == c)),
        "not in order"
    );
    let (t0, t1) = scene.horizon();
    let settings = settings(scene, delta);
    let pruned: Vec<_> = all.iter().filter(|p| !candidates.contains(p)).collect();
    for &&(i, j) in &pruned {
        let (a, b) = (&scene.bodies[i], &scene.bodies[j]);
        let outcome = check_pair(
            a,
            b,
            (t0, t1),
            crate::collision::Method::DEFAULT,
            &settings,
            &SharedLimit::new(),
            &mut Default::default(),
            None,
        );
        assert_eq!(outcome.contact, None, "{} - {} pruned", a.name, b.name);
        for k in 0..=200 {
            let t = t0 + (t1 - t0) * k as f64 / 200.0;
            fn posed(body: &Body, t: f64) -> Posed<'_> {
                let p = body.motion.pose_at(t);
                Posed::new(&body.shape, p.pos.x, p.pos.y, p.theta)
            }
            let d = brute_force_distance(&posed(a, t), &posed(b, t)).distance;
            assert!(
                d >= delta,
                "{} - {} pruned, {d} apart at {t}",
                a.name,
                b.name
            );
        }
    }
    pruned.len()
}

#[test]
fn pruned_pairs_never_come_within_delta() {
    let mut pruned = 0;
    for seed in 0..12 {
        // Up to 12 robots the boxes are tested pairwise; 40 robots and 5 obstacles make
        // 45 boxes, which go through the grid.
        let sizes: &[usize] = if seed < 3 {
            &[2, 5, 12, 40]
        } else {
            &[2, 5, 12]
        };
        for &n in sizes {
            let hall = generate_scene(Kind::Hall, seed, 0, n);
            // The scene's δ, and larger ones that bring boxes to the edge of meeting.
            for delta in [hall.delta, 0.3, 1.5] {
                pruned += pruning_is_safe(&hall, delta);
            }
        }
        for kind in Kind::ALL.into_iter().filter(|&k| k != Kind::Hall) {
            let scene = generate_scene(kind, seed, 0, 0);
            for delta in [scene.delta, 0.5, 2.0] {
                pruned += pruning_is_safe(&scene, delta);
            }
        }
    }
    assert!(
        pruned > 500,
        "only {pruned} pairs pruned: the test shows little"
    );
}

/// A 0.8 × 0.8 square moving linearly through `(t, x, y)`.
fn robot(name: &str, samples: &[(f64, f64, f64)]) -> Body {
    let sample = |&(t, x, y): &(f64, f64, f64)| Sample {
        t,
        pos: Vec2::new(x, y),
        theta: 0.0,
        vel: Vec2::zeros(),
        omega: 0.0,
    };
    let square = [[-0.4, -0.4], [0.4, -0.4], [0.4, 0.4], [-0.4, 0.4]];
    Body::robot(
        name,
        ConvexPolygon::new(&square).unwrap().0,
        Trajectory::new(samples.iter().map(sample).collect()).unwrap(),
    )
}

#[test]
fn robots_sweeping_across_a_hall_are_pruned_safely() {
    // Their boxes cover far more grid cells than the hall's: tested against all boxes.
    let mut hall = generate_scene(Kind::Hall, 5, 0, 30);
    hall.bodies
        .push(robot("S1", &[(0.0, -30.0, -30.0), (20.0, 50.0, 50.0)]));
    hall.bodies
        .push(robot("S2", &[(0.0, 50.0, -30.0), (20.0, -30.0, 50.0)]));
    assert!(pruning_is_safe(&hall, hall.delta) > 300);
    assert!(pruning_is_safe(&hall, 0.8) > 200);
}

#[test]
fn a_hall_of_1000_robots_has_few_candidates() {
    let hall = generate_scene(Kind::Hall, 1, 0, 1000);
    let n = candidate_pairs(&hall, hall.delta).len();
    assert!(n < 20 * 1000, "{n} candidates of {}", hall.pair_count());
    let all = candidate_pairs(&hall, f64::INFINITY);
    assert_eq!(all.len(), hall.pair_count(), "an infinite δ keeps all");
}

/// The broad phase keeps a number of pairs linear in the number of robots where the robots'
/// density is bounded, arms included: one entry per arm in the grid, its links only against
/// what its reach meets.
#[test]
fn an_arm_hall_has_candidates_linear_in_its_robots() {
    let mut counts = Vec::new();
    for n in [50, 100, 200, 400] {
        let hall = generate_scene(Kind::ArmHall, 2, 0, n);
        let c = candidate_pairs(&hall, hall.delta).len();
        assert!(c < 2 * n, "{c} candidates for {n} arms and {n} robots");
        assert!(hall.pair_count() > n * n, "all pairs grow as n²");
        counts.push(c);
    }
    assert!(counts[0] > 10, "{counts:?}: the test shows little");
    assert!(counts[3] < 12 * counts[0], "{counts:?}: not linear");
}

/// An arm beside a robot that stands within its reach: the reach disc meets the robot every
/// time, and each link is kept only where its own swept box meets the robot's.
#[test]
fn a_link_is_kept_only_where_its_own_box_meets() {
    use crate::collision::Arm;
    use std::f64::consts::PI;
    let bar = |l: f64| {
        let corners = [
            [-0.05, -0.05],
            [l + 0.05, -0.05],
            [l + 0.05, 0.05],
            [-0.05, 0.05],
        ];
        ConvexPolygon::new(&corners).unwrap().0
    };
    // Links of 2 and 1.5 turning by 0.01 over the horizon: λ at most 0.036.
    let with = |q: [f64; 2]| {
        let mut scene = Scene::new(0.01).unwrap();
        // A 0.8 square resting at (1, 0.7): its disc's box spans x 0.43 to 1.57 and y 0.13
        // to 1.27.
        scene
            .bodies
            .push(robot("R1", &[(0.0, 1.0, 0.7), (1.0, 1.0, 0.7)]));
        let arm = Arm::new("A1", Pose::new(0.0, 0.0, 0.0))
            .link(2.0, bar(2.0))
            .link(1.5, bar(1.5))
            .sample(0.0, &q)
            .sample(1.0, &[q[0] + 0.01, q[1]]);
        scene.bodies.extend(arm.bodies().unwrap());
        candidate_pairs(&scene, scene.delta)
    };
    assert_eq!(with([PI, 0.0]), vec![], "folded away: both links pruned");
    assert_eq!(with([0.3, 0.0]), vec![(0, 1)], "link 0 across the robot");
    assert_eq!(
        with([PI / 2.0, -2.3]),
        vec![(0, 2)],
        "link 1 across the robot"
    );
}

/// An arm folded at both its samples but stretched between them (the elbow turns from -2.8
/// to 2.8 through 0): its reach over the window is the stretched arm's, not the samples'.
#[test]
fn an_arm_stretching_between_its_samples_keeps_its_reach() {
    use crate::collision::Arm;
    let bar = ConvexPolygon::new(&[[-0.05, -0.05], [1.05, -0.05], [1.05, 0.05], [-0.05, 0.05]])
        .unwrap()
        .0;
    let mut scene = Scene::new(0.01).unwrap();
    // Beyond the folded arm's reach (1.05), within the stretched one's (2.05).
    scene
        .bodies
        .push(robot("R1", &[(0.0, 1.8, 0.0), (1.0, 1.8, 0.0)]));
    let arm = Arm::new("A1", Pose::new(0.0, 0.0, 0.0))
        .link(1.0, bar.clone())
        .link(1.0, bar)
        .sample(0.0, &[0.0, -2.8])
        .sample(1.0, &[0.0, 2.8]);
    scene.bodies.extend(arm.bodies().unwrap());
    assert!(candidate_pairs(&scene, scene.delta).contains(&(0, 2)));
    assert!(
        pruning_is_safe(&scene, scene.delta) > 0,
        "link 0 stays away"
    );
}

/// An arm rests at its first pose before its first sample and at its last after its last,
/// as the checker has it: robots that cross it there, in windows outside its samples, keep
/// their pairs.
#[test]
fn an_arm_is_boxed_where_it_rests_outside_its_samples() {
    use crate::collision::Arm;
    let bar = ConvexPolygon::new(&[[-0.05, -0.05], [1.05, -0.05], [1.05, 0.05], [-0.05, 0.05]])
        .unwrap()
        .0;
    let mut scene = Scene::new(0.01).unwrap();
    // Across the arm pointing along +x, before its samples; across it pointing along +y,
    // after them.
    scene.bodies.push(robot(
        "R1",
        &[(0.0, 0.6, -3.0), (1.6, 0.6, 3.0), (5.0, 0.6, 3.0)],
    ));
    scene.bodies.push(robot(
        "R2",
        &[(0.0, -3.0, 3.0), (3.5, -3.0, 0.6), (5.0, 3.0, 0.6)],
    ));
    let arm = Arm::new("A1", Pose::new(0.0, 0.0, 0.0))
        .link(1.0, bar)
        .sample(2.0, &[0.0])
        .sample(3.0, &[std::f64::consts::FRAC_PI_2]);
    scene.bodies.extend(arm.bodies().unwrap());
    let candidates = candidate_pairs(&scene, scene.delta);
    assert!(
        candidates.contains(&(0, 2)) && candidates.contains(&(1, 2)),
        "{candidates:?}"
    );
    pruning_is_safe(&scene, scene.delta);
}

#[test]
fn the_thread_pool_changes_nothing() {
    let pools = [1, 2, 4].map(|n| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
    });
    for (seed, n) in [(1, 70), (2, 300), (3, 1000)] {
        let hall = generate_scene(Kind::Hall, seed, 0, n);
        for delta in [hall.delta, 0.4, 1.5] {
            let serial = candidates(&hall, delta, false);
            assert!(!serial.is_empty());
            for pool in &pools {
                let parallel = pool.install(|| candidates(&hall, delta, true));
                assert_eq!(parallel, serial, "{n} robots, δ {delta}");
            }
        }
    }
}

/// A deterministic box of sides up to `size` with its corner in a square of side 100.
fn random_box(state: &mut u64, size: f64) -> Aabb {
    let mut next = || {
        // SplitMix64 steps, as uniform numbers in [0, 1).
        *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = *state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        (z ^ (z >> 31)) as f64 / 2f64.powi(64)
    };
    let (x, y) = (100.0 * next(), 100.0 * next());
    let (w, h) = (size * next(), size * next());
    Aabb {
        lo: [x, y],
        hi: [x + w, y + h],
    }
}

#[test]
fn the_grid_finds_what_testing_every_pair_finds() {
    let mut state = 7;
    for (n, size) in [(40, 20.0), (300, 8.0), (2000, 3.0)] {
        // Mostly small boxes; one in fifty covers a large part of the square (more than
        // MAX_CELLS grid cells), one in fifty has no width.
        let boxes: Vec<(usize, Aabb)> = (0..n)
            .map(|i| {
                let b = match i % 50 {
                    0 => random_box(&mut state, 80.0),
                    1 => {
                        let b = random_box(&mut state, size);
                        Aabb {
                            hi: [b.lo[0], b.hi[1]],
                            ..b
                        }
                    }
                    _ => random_box(&mut state, size),
                };
                (i, b)
            })
            .collect();
        let mut expected = Vec::new();
        for (k, (i, b)) in boxes.iter().enumerate() {
            for (j, c) in &boxes[k + 1..] {
                if b.meets(c) {
                    expected.push((*i, *j));
                }
            }
        }
        let mut found = Vec::new();
        meeting(&boxes, &mut found);
        let mut found: Vec<_> = found
            .into_iter()
            .map(|(i, j)| (i.min(j), i.max(j)))
            .collect();
        found.sort_unstable();
        let count = found.len();
        found.dedup();
        assert_eq!(found.len(), count, "a pair twice, {n} boxes");
        assert_eq!(found, expected, "{n} boxes");
        assert!(
            expected.len() > n / 4,
            "{n} boxes, few meet: the test shows little"
        );
    }
}

#[test]
fn non_finite_input_keeps_pairs() {
    let mut scene = generate_scene(Kind::Hall, 3, 0, 6);
    assert_eq!(candidate_pairs(&scene, f64::NAN), scene.pairs());
    let first_odd = scene.bodies.len();
    for x in [f64::NAN, f64::INFINITY] {
        let mut obstacle = robot("O", &[(0.0, 0.0, 0.0)]);
        obstacle.motion = Motion::Fixed(Pose {
            pos: Vec2::new(x, 0.0),
            theta: 0.0,
        });
        scene.bodies.push(obstacle);
    }
    // Far from everything, but every interpolated pose overflows.
    let far = [(0.0, -1.5e308, 1e300), (1.0, 1.5e308, 1e300)];
    scene.bodies.push(robot("far", &far));
    let candidates = candidate_pairs(&scene, scene.delta);
    for (i, j) in scene.pairs() {
        if i.max(j) >= first_odd {
            assert!(candidates.contains(&(i, j)), "{i} - {j} dropped");
        }
    }
}

/// A robot checked against an obstacle in its windows only finds what the whole check
/// finds (the same first contact, or none), and is at least δ away at every instant
/// outside them.
fn windows_miss_nothing(scene: &Scene, delta: f64) -> (usize, usize) {
    let pairs: Vec<_> = scene.pairs();
    let windows = pair_windows(scene, &pairs, delta);
    let (t0, t1) = scene.horizon();
    let settings = settings(scene, delta);
    let (mut windowed, mut contacts) = (0, 0);
    for (&(i, j), w) in pairs.iter().zip(windows) {
        let Some(w) = w else { continue };
        windowed += 1;
        let (a, b) = (&scene.bodies[i], &scene.bodies[j]);
        let run = |w: Option<Windows>| {
            let limit = SharedLimit::new();
            let method = crate::collision::Method::DEFAULT;
            check_pair(
                a,
                b,
                (t0, t1),
                method,
                &settings,
                &limit,
                &mut Default::default(),
                w,
            )
        };
        let (whole, inside) = (run(None), run(Some(w.clone())));
        let name = format!("{} - {} at delta {delta}", a.name, b.name);
        match (whole.contact, inside.contact) {
            (None, None) => assert!(!inside.out_of_work, "{name}"),
            (Some(x), Some(y)) => {
                contacts += 1;
                assert!(
                    (x.time - y.time).abs() <= settings.time_tol,
                    "{name}: {x:?} {y:?}"
                );
                assert!(y.distance < delta, "{name}");
            }
            (x, y) => panic!("{name}: whole {x:?}, in windows {y:?} ({w:?})"),
        }
        for k in 0..=400 {
            let t = t0 + (t1 - t0) * k as f64 / 400.0;
            if w.iter().any(|&(s, e)| s <= t && t <= e) {
                continue;
            }
            let posed = |body: &Body| {
                let p = body.motion.pose_at(t);
                (body.shape.clone(), p)
            };
            let ((sa, pa), (sb, pb)) = (posed(a), posed(b));
            let d = brute_force_distance(
                &Posed::new(&sa, pa.pos.x, pa.pos.y, pa.theta),
                &Posed::new(&sb, pb.pos.x, pb.pos.y, pb.theta),
            )
            .distance;
            assert!(d >= delta, "{name}: {d} apart at {t}, outside {w:?}");
        }
    }
    (windowed, contacts)
}

#[test]
fn checking_in_windows_finds_what_the_whole_horizon_shows() {
    // A robot wandering over 400 samples among posts at every distance from its path.
    let path: Vec<(f64, f64, f64)> = (0..400)
        .map(|k| {
            let t = k as f64 * 0.5;
            (t, 0.3 * t, 4.0 * (0.05 * t).sin() + 2.0 * (0.31 * t).cos())
        })
        .collect();
    let mut scene = Scene::new(0.01).unwrap();
    scene.bodies.push(robot("W", &path));
    for k in 0..60 {
        let (x, y) = (k as f64, -7.0 + 0.23 * k as f64);
        let post = ConvexPolygon::rectangle(0.3, 0.2).unwrap();
        let world = post.translated(&Vec2::new(-x, -y));
        scene
            .bodies
            .push(Body::obstacle(format!("post-{k}"), &world));
    }
    let (mut windowed, mut contacts) = (0, 0);
    for delta in [0.01, 0.3, 1.2] {
        let (w, c) = windows_miss_nothing(&scene, delta);
        (windowed, contacts) = (windowed + w, contacts + c);
    }
    // A robot on a line, one sample a second, meeting a post in the first interval of a
    // chunk (the 8 samples before it stay clear): the window must begin with that interval.
    let line: Vec<(f64, f64, f64)> = (0..100).map(|k| (k as f64, k as f64, 0.0)).collect();
    let mut scene = Scene::new(0.01).unwrap();
    scene.bodies.push(robot("L", &line));
    let post = ConvexPolygon::rectangle(1.0, 1.0).unwrap();
    scene.bodies.push(Body::obstacle(
        "post",
        &post.translated(&Vec2::new(-9.5, 0.0)),
    ));
    assert_eq!(windows_miss_nothing(&scene, 0.01), (1, 1));
    for seed in 0..6 {
        for kind in Kind::ALL {
            let scene = generate_scene(kind, seed, 0, 12);
            let (w, c) = windows_miss_nothing(&scene, scene.delta);
            (windowed, contacts) = (windowed + w, contacts + c);
        }
    }
    // Not vacuous: many pairs checked in windows, some of them in contact.
    assert!(
        windowed > 150 && contacts > 10,
        "{windowed} pairs, {contacts} contacts"
    );
}
