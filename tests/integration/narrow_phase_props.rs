//! Property tests of the closest-feature walk (`closest_features`) against the independent
//! brute-force distance of `common` (which shares no code with the library), and against
//! the library's `brute_force_distance`.

use crate::common::{
    boundary_distance, centroid, draw, ellipse_shape, exact, hull_shape, place, polygon,
    proptest_config, radius_about, rectangle_shape, regular_shape, Exact, Shape,
};
use proptest::prelude::*;
use proptest::test_runner::TestRunner;
use std::f64::consts::{PI, TAU};
use workcell::geometry::{
    brute_force_distance, closest_features, ConvexPolygon, Distance, Feature, FeaturePair, Posed,
    Vec2, WalkTolerances,
};

// ---------------------------------------------------------------------------------------
// Generators
// ---------------------------------------------------------------------------------------

/// A convex shape of size about 0.05 to 2, the frame origin anywhere near it.
fn any_shape() -> impl Strategy<Value = Shape> {
    let (size, offset) = (0.05..2.0, -0.5..0.5);
    prop_oneof![
        3 => ellipse_shape(3..=16, size.clone(), offset.clone()),
        3 => hull_shape(size.clone(), offset.clone()),
        1 => rectangle_shape(size.clone(), offset.clone()),
        2 => regular_shape(size, offset),
    ]
}

fn angle() -> impl Strategy<Value = f64> {
    prop_oneof![4 => -PI..PI, 1 => -100.0f64..100.0]
}

fn pose() -> impl Strategy<Value = [f64; 3]> {
    (-3.0f64..3.0, -3.0f64..3.0, angle()).prop_map(|(x, y, t)| [x, y, t])
}

/// A gap between two polygons placed face to face: touching, within rounding of touching,
/// barely separated or overlapping, or clearly apart.
fn gap() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => Just(0.0),
        1 => Just(1e-15),
        1 => Just(-1e-15),
        1 => Just(1e-12),
        1 => Just(1e-9),
        1 => Just(1e-6),
        1 => Just(-1e-6),
        3 => 1e-3f64..0.5,
        1 => -0.1f64..0.0,
    ]
}

/// Where along an edge (0 and 1: its end vertices; outside [0, 1]: beyond them).
fn along() -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(0.0),
        1 => Just(1.0),
        1 => Just(0.5),
        4 => -0.3f64..1.3,
    ]
}

#[derive(Clone, Debug)]
#[allow(dead_code)] // `kind` names the generator in failure reports
struct PairCase {
    kind: &'static str,
    a: Shape,
    pose_a: [f64; 3],
    b: Shape,
    pose_b: [f64; 3],
}

fn local_vertices(s: &Shape) -> Vec<Vec2> {
    polygon(s).vertices().to_vec()
}

/// Outward unit normal of edge `i` of counter-clockwise `v`.
fn normal(v: &[Vec2], i: usize) -> Vec2 {
    let e = v[(i + 1) % v.len()] - v[i];
    Vec2::new(e.y, -e.x).normalize()
}

/// Edge `i` (taken modulo) of `shape` at `pose`: its outward unit normal, and the point at
/// parameter `s` along it pushed out by `g` along that normal.
fn edge_point(shape: &Shape, pose: [f64; 3], i: usize, s: f64, g: f64) -> (Vec2, Vec2) {
    let w = place(&local_vertices(shape), pose);
    let i = i % w.len();
    let n = normal(&w, i);
    (n, w[i] + (w[(i + 1) % w.len()] - w[i]) * s + n * g)
}

fn random_case() -> impl Strategy<Value = PairCase> {
    (any_shape(), pose(), any_shape(), pose()).prop_map(|(a, pose_a, b, pose_b)| PairCase {
        kind: "random",
        a,
        pose_a,
        b,
        pose_b,
    })
}

/// Edge `j` of B turned to face edge `i` of A exactly (antiparallel normals), then moved so
/// that the two edges lie `gap` apart with B's edge centred at parameter `s` of A's edge.
fn parallel_case() -> impl Strategy<Value = PairCase> {
    (
        any_shape(),
        pose(),
        any_shape(),
        any::<usize>(),
        any::<usize>(),
        along(),
        gap(),
    )
        .prop_map(|(a, pose_a, b, i, j, s, g)| {
            let (na, target) = edge_point(&a, pose_a, i, s, g);
            let lb = local_vertices(&b);
            let j = j % lb.len();
            let nb = normal(&lb, j);
            let theta_b = (-na.y).atan2(-na.x) - nb.y.atan2(nb.x);
            let wb = place(&lb, [0.0, 0.0, theta_b]);
            let mid_b = (wb[j] + wb[(j + 1) % wb.len()]) * 0.5;
            let t = target - mid_b;
            PairCase {
                kind: "parallel",
                a,
                pose_a,
                b,
                pose_b: [t.x, t.y, theta_b],
            }
        })
}

/// B's extreme vertex towards A's edge `i` put at parameter `s` of that edge, pushed out
/// along the edge normal by `gap`: with gap 0 the polygons touch.
fn touching_case() -> impl Strategy<Value = PairCase> {
    (
        any_shape(),
        pose(),
        any_shape(),
        angle(),
        any::<usize>(),
        along(),
        gap(),
    )
        .prop_map(|(a, pose_a, b, theta_b, i, s, g)| {
            let (na, target) = edge_point(&a, pose_a, i, s, g);
            let wb = place(&local_vertices(&b), [0.0, 0.0, theta_b]);
            let support = wb
                .iter()
                .copied()
                .min_by(|p, q| p.dot(&na).total_cmp(&q.dot(&na)))
                .unwrap();
            let t = target - support;
            PairCase {
                kind: "touching",
                a,
                pose_a,
                b,
                pose_b: [t.x, t.y, theta_b],
            }
        })
}

/// A small polygon strictly inside a big one, in either order.
fn containment_case() -> impl Strategy<Value = PairCase> {
    (
        any_shape(),
        pose(),
        any_shape(),
        angle(),
        0.05f64..0.9,
        0.0f64..0.95,
        0.0..TAU,
        any::<bool>(),
    )
        .prop_map(|(big, pose_big, small, theta_s, f, reach, dir, swap)| {
            let wbig = place(&local_vertices(&big), pose_big);
            let c = centroid(&wbig);
            let inradius = (0..wbig.len())
                .map(|i| normal(&wbig, i).dot(&(wbig[i] - c)))
                .fold(f64::INFINITY, f64::min);
            let ls = local_vertices(&small);
            let cs = centroid(&ls);
            let rs = radius_about(&ls, cs);
            let k = f * inradius / rs;
            let small: Shape = ls.iter().map(|v| [v.x * k, v.y * k]).collect();
            let room = (inradius - f * inradius) * reach;
            let target = c + Vec2::new(dir.cos(), dir.sin()) * room;
            let rot = place(&[cs * k], [0.0, 0.0, theta_s])[0];
            let t = target - rot;
            let pose_small = [t.x, t.y, theta_s];
            if swap {
                PairCase {
                    kind: "contained-a",
                    a: small,
                    pose_a: pose_small,
                    b: big,
                    pose_b: pose_big,
                }
            } else {
                PairCase {
                    kind: "contained-b",
                    a: big,
                    pose_a: pose_big,
                    b: small,
                    pose_b: pose_small,
                }
            }
        })
}

fn identical_case() -> impl Strategy<Value = PairCase> {
    (any_shape(), pose()).prop_map(|(a, pose_a)| PairCase {
        kind: "identical",
        b: a.clone(),
        pose_b: pose_a,
        a,
        pose_a,
    })
}

/// Any case, shifted as a whole: most near the origin, some far from it.
fn pair_case() -> impl Strategy<Value = PairCase> {
    let case = prop_oneof![
        4 => random_case(),
        3 => parallel_case(),
        3 => touching_case(),
        1 => containment_case(),
        1 => identical_case(),
    ];
    let offset = prop_oneof![
        4 => Just([0.0, 0.0]),
        1 => (-1e3f64..1e3, -1e3f64..1e3).prop_map(|(x, y)| [x, y]),
    ];
    (case, offset).prop_map(|(mut c, [ox, oy])| {
        c.pose_a[0] += ox;
        c.pose_a[1] += oy;
        c.pose_b[0] += ox;
        c.pose_b[1] += oy;
        c
    })
}

fn feature(vertex: bool, i: usize) -> Feature {
    if vertex {
        Feature::Vertex(i)
    } else {
        Feature::Edge(i)
    }
}

// ---------------------------------------------------------------------------------------
// Properties
// ---------------------------------------------------------------------------------------

/// The world-frame setting of a case and its tolerance.
struct Setting {
    pa: ConvexPolygon,
    pb: ConvexPolygon,
    wa: Vec<Vec2>,
    wb: Vec<Vec2>,
    scale: f64,
    tol: f64,
    oracle: Exact,
}

fn setting(c: &PairCase) -> Setting {
    let pa = polygon(&c.a);
    let pb = polygon(&c.b);
    let wa = place(pa.vertices(), c.pose_a);
    let wb = place(pb.vertices(), c.pose_b);
    let scale = wa
        .iter()
        .chain(&wb)
        .map(|v| v.amax())
        .fold(pa.radius().max(pb.radius()), f64::max);
    let tol = (1e-9 * scale).max(1e-12);
    let oracle = exact(&wa, &wb);
    Setting {
        pa,
        pb,
        wa,
        wb,
        scale,
        tol,
        oracle,
    }
}

fn posed<'a>(shape: &'a ConvexPolygon, p: [f64; 3]) -> Posed<'a> {
    Posed::new(shape, p[0], p[1], p[2])
}

/// Checks one answer of the library against the oracle.
fn agrees(s: &Setting, d: &Distance, what: &str) -> Result<(), TestCaseError> {
    let (o, tol) = (s.oracle, s.tol);
    prop_assert!(
        d.distance.is_finite() && d.distance >= 0.0,
        "{what}: distance {} is not a finite non-negative number",
        d.distance
    );
    prop_assert!(
        (d.distance - o.distance).abs() <= tol,
        "{what}: distance {:e}, oracle {:e} (overlap {}), tol {:e}",
        d.distance,
        o.distance,
        o.overlap,
        tol
    );
    // Zero exactly when the oracle says overlap (both within the tolerance).
    if o.overlap {
        prop_assert!(
            d.distance <= tol,
            "{what}: oracle says overlap, distance {:e}",
            d.distance
        );
    } else if o.distance > tol {
        prop_assert!(
            d.distance > 0.0,
            "{what}: oracle says apart by {:e}, distance 0",
            o.distance
        );
    }
    if d.distance == 0.0 {
        prop_assert!(
            o.overlap || o.distance <= tol,
            "{what}: distance 0 but the oracle says {:e} apart",
            o.distance
        );
    }
    if d.distance > tol {
        // Separated: the points are on their polygons and realise the distance.
        let on_a = boundary_distance(d.point_a, &s.wa);
        let on_b = boundary_distance(d.point_b, &s.wb);
        prop_assert!(on_a <= tol, "{what}: point_a is {on_a:e} off polygon A");
        prop_assert!(on_b <= tol, "{what}: point_b is {on_b:e} off polygon B");
        let between = (d.point_b - d.point_a).norm();
        prop_assert!(
            (between - d.distance).abs() <= tol,
            "{what}: |point_b - point_a| = {between:e}, distance {:e}",
            d.distance
        );
    }
    Ok(())
}

#[derive(Clone, Debug)]
struct Warm {
    /// Pose perturbation of the previous query: dx, dy, dθ for A and for B.
    nudge: [f64; 6],
    /// An arbitrary starting pair.
    any_pair: (bool, usize, bool, usize),
}

fn warm() -> impl Strategy<Value = Warm> {
    let small = || prop_oneof![Just(0.0), -1e-3f64..1e-3, -0.1f64..0.1];
    (
        [small(), small(), small(), small(), small(), small()],
        (any::<bool>(), any::<usize>(), any::<bool>(), any::<usize>()),
    )
        .prop_map(|(nudge, any_pair)| Warm { nudge, any_pair })
}

/// The walk at the case's poses, warm-started from the features of a query at the poses
/// nudged by `w`.
fn warm_walk(s: &Setting, c: &PairCase, w: &Warm, tolw: &WalkTolerances) -> Distance {
    let n = w.nudge;
    let near_a = [c.pose_a[0] + n[0], c.pose_a[1] + n[1], c.pose_a[2] + n[2]];
    let near_b = [c.pose_b[0] + n[3], c.pose_b[1] + n[4], c.pose_b[2] + n[5]];
    let before = closest_features(&posed(&s.pa, near_a), &posed(&s.pb, near_b), None, tolw);
    let (a, b) = (posed(&s.pa, c.pose_a), posed(&s.pb, c.pose_b));
    closest_features(&a, &b, Some(before.features), tolw)
}

fn check_case(c: &PairCase, w: &Warm) -> Result<(), TestCaseError> {
    let s = setting(c);
    let tolw = WalkTolerances::default();
    let (a, b) = (posed(&s.pa, c.pose_a), posed(&s.pb, c.pose_b));

    // Cold query.
    let cold = closest_features(&a, &b, None, &tolw);
    agrees(&s, &cold, "cold")?;
    prop_assert!(
        !(cold.fell_back && s.oracle.distance > 1e-6 * s.scale),
        "cold walk fell back on clearly separated polygons ({:e} apart)",
        s.oracle.distance
    );
    let in_range = |f: Feature, n: usize| match f {
        Feature::Vertex(i) | Feature::Edge(i) => i < n,
    };
    prop_assert!(
        in_range(cold.features.a, s.pa.len()) && in_range(cold.features.b, s.pb.len()),
        "feature index out of range: {:?}",
        cold.features
    );

    // The library's own oracle.
    let bf = brute_force_distance(&a, &b);
    agrees(&s, &bf, "brute_force_distance")?;

    // Swapped arguments give the same distance.
    let swapped = closest_features(&b, &a, None, &tolw);
    prop_assert!(
        (swapped.distance - cold.distance).abs() <= s.tol,
        "swapped: {:e} vs {:e}",
        swapped.distance,
        cold.distance
    );

    // Warm start from the features of a query at a nearby pose.
    let warmed = warm_walk(&s, c, w, &tolw);
    agrees(&s, &warmed, "warm (nearby pose)")?;
    prop_assert!(
        (warmed.distance - cold.distance).abs() <= s.tol,
        "warm {:e} vs cold {:e}",
        warmed.distance,
        cold.distance
    );
    prop_assert!(
        !(warmed.fell_back && s.oracle.distance > 1e-6 * s.scale),
        "warm walk fell back on clearly separated polygons"
    );

    // Warm start from the answer itself: certified at the first step.
    let again = closest_features(&a, &b, Some(cold.features), &tolw);
    agrees(&s, &again, "warm (same pose)")?;
    if !cold.fell_back {
        prop_assert_eq!(
            again.steps,
            1,
            "restarting from the answer took several steps"
        );
    }

    // Warm start from an arbitrary pair of features: still exact.
    let (va, ia, vb, ib) = w.any_pair;
    let pair = FeaturePair {
        a: feature(va, ia % s.pa.len()),
        b: feature(vb, ib % s.pb.len()),
    };
    let arbitrary = closest_features(&a, &b, Some(pair), &tolw);
    agrees(&s, &arbitrary, "warm (arbitrary pair)")?;

    // Out-of-range warm indices fall back to a cold start.
    let bogus = FeaturePair {
        a: feature(va, s.pa.len() + ia % 7),
        b: feature(vb, ib % s.pb.len()),
    };
    let out_of_range = closest_features(&a, &b, Some(bogus), &tolw);
    agrees(&s, &out_of_range, "warm (out of range)")?;
    Ok(())
}

proptest! {
    #![proptest_config(proptest_config(256))]

    #[test]
    fn walk_matches_oracle(c in pair_case(), w in warm()) {
        check_case(&c, &w)?;
    }

    #[test]
    fn walk_matches_oracle_face_to_face(c in parallel_case(), w in warm()) {
        check_case(&c, &w)?;
    }

    #[test]
    fn walk_matches_oracle_touching(c in touching_case(), w in warm()) {
        check_case(&c, &w)?;
    }
}

/// The generators really produce the situations they are named for, so that the
/// properties above are exercised on them.
#[test]
fn generators_cover_the_special_cases() {
    let mut runner = TestRunner::deterministic();
    let mut settings = |s: &dyn Fn(&mut TestRunner) -> PairCase, n: usize| -> Vec<Setting> {
        (0..n).map(|_| setting(&s(&mut runner))).collect()
    };
    let touching = settings(&|r| draw(&touching_case(), r), 400);
    let exactly = touching
        .iter()
        .filter(|s| s.oracle.boundary_gap <= s.tol)
        .count();
    assert!(exactly > 100, "only {exactly}/400 touching cases touch");
    let contained = settings(&|r| draw(&containment_case(), r), 100);
    assert!(contained
        .iter()
        .all(|s| s.oracle.overlap && s.oracle.boundary_gap > 0.0));
    let random = settings(&|r| draw(&random_case(), r), 400);
    let overlapping = random.iter().filter(|s| s.oracle.overlap).count();
    assert!(
        (40..=360).contains(&overlapping),
        "{overlapping}/400 random cases overlap"
    );
}

/// The cycling guard is not the normal path: over a fixed sample of cases, cold and warm
/// walks fall back rarely.
#[test]
fn fallback_is_rare() {
    let mut runner = TestRunner::deterministic();
    let tolw = WalkTolerances::default();
    let (mut walks, mut fallbacks) = (0usize, 0usize);
    for _ in 0..2000 {
        let c = draw(&pair_case(), &mut runner);
        let w = draw(&warm(), &mut runner);
        let s = setting(&c);
        let (a, b) = (posed(&s.pa, c.pose_a), posed(&s.pb, c.pose_b));
        let cold = closest_features(&a, &b, None, &tolw);
        let warmed = warm_walk(&s, &c, &w, &tolw);
        walks += 2;
        fallbacks += usize::from(cold.fell_back) + usize::from(warmed.fell_back);
    }
    eprintln!("fallbacks: {fallbacks} of {walks} walks");
    assert!(
        fallbacks * 100 <= walks,
        "the walk fell back {fallbacks} times in {walks} walks"
    );
}

/// Library bug found by `walk_matches_oracle_touching` (reduced by hand): two polygons that
/// touch at a vertex, with edges leaving it at an angle of 1e-5 rad, are reported 1e-5
/// apart. The walk certifies (vertex 1 of A, edge 0 of B): the projection of B's point on
/// A's edge 1 is about 1e-10, inside the Voronoi tolerance `feature_tol · Rmax` (3e-10), but
/// along nearly parallel edges that slack is worth a distance of about
/// sqrt(feature_tol · Rmax · edge length). Ignored until the walk is fixed.
#[test]
fn touching_wedge_is_at_distance_zero() {
    let a = polygon(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    let b = polygon(&[[1.0, 1.0], [1.0 + 1.5e-5, -0.5], [3.0, 0.25]]);
    let (pa, pb) = (posed(&a, [0.0; 3]), posed(&b, [0.0; 3]));
    assert_eq!(brute_force_distance(&pa, &pb).distance, 0.0);
    let d = closest_features(&pa, &pb, None, &WalkTolerances::default());
    assert!(
        d.distance <= 1e-12,
        "touching polygons reported {:e} apart, features {:?}",
        d.distance,
        d.features
    );
}

proptest! {
    #![proptest_config(proptest_config(512))]

    /// Slabs up to 10⁷ long whose long faces are at an angle below the walk's parallel
    /// tolerance (10⁻¹⁰), one slid along the other and lifted by up to its drop: the true
    /// minimum is at an end of the overlap, up to 5·10⁻⁴ below its middle. The walk gives
    /// it to rounding, far tighter than the 10⁻⁹·size of the other properties.
    #[test]
    fn walk_is_exact_on_long_nearly_parallel_edges(
        len in prop_oneof![Just(1e7), 1e3f64..1e7],
        angle in prop_oneof![Just(5e-11), Just(-9e-11), -1.5e-10f64..1.5e-10],
        slide in -0.9f64..0.9,
        lift in -0.5f64..2.0,
        turn in 0.0..TAU,
        w in warm(),
    ) {
        let half = 0.5 * len;
        let slab = vec![[-half, 0.0], [half, 0.0], [half, 1.0], [-half, 1.0]];
        let wall = vec![[-half, -1.0], [half, -1.0], [half, 0.0], [-half, 0.0]];
        // The slab's face lies `lift`·(its drop over the half length) above the wall's, at
        // its middle, `slide`·len along it; both turned by `turn` about the origin.
        let drop = angle.abs() * half;
        let (s, c) = turn.sin_cos();
        let (x, y) = (slide * len, 1e-3 + lift * drop);
        let case = PairCase {
            kind: "long-parallel",
            a: slab,
            pose_a: [c * x - s * y, s * x + c * y, turn + angle],
            b: wall,
            pose_b: [0.0, 0.0, turn],
        };
        let st = Setting { tol: 1e-14 * len, ..setting(&case) };
        let (a, b) = (posed(&st.pa, case.pose_a), posed(&st.pb, case.pose_b));
        let tolw = WalkTolerances::default();
        agrees(&st, &closest_features(&a, &b, None, &tolw), "cold")?;
        let swapped = closest_features(&b, &a, None, &tolw).distance;
        prop_assert!((swapped - st.oracle.distance).abs() <= st.tol, "swapped: {swapped:e}");
        agrees(&st, &warm_walk(&st, &case, &w, &tolw), "warm")?;
    }
}
