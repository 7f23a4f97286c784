//! Property tests of the closest-feature walk (`closest_features`) against an independent
//! brute-force distance written here, and against the library's `brute_force_distance`.
//!
//! The oracle below shares no code with the library: it places the vertices itself, takes
//! the smallest vertex-to-edge distance in both directions, and decides overlap by a
//! point-in-polygon test (either way round) and a segment-intersection test over all edge
//! pairs.

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;
use std::f64::consts::{PI, TAU};
use workcell::geometry::{
    brute_force_distance, closest_features, ConvexPolygon, Distance, Feature, FeaturePair, Posed,
    Vec2, WalkTolerances,
};

// ---------------------------------------------------------------------------------------
// Independent oracle
// ---------------------------------------------------------------------------------------

fn cross(a: Vec2, b: Vec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// World vertices: R(theta)·p + (x, y), computed here rather than by `Posed`.
fn place(local: &[Vec2], [x, y, theta]: [f64; 3]) -> Vec<Vec2> {
    let (s, c) = theta.sin_cos();
    local
        .iter()
        .map(|p| Vec2::new(c * p.x - s * p.y + x, s * p.x + c * p.y + y))
        .collect()
}

fn point_segment(p: Vec2, a: Vec2, b: Vec2) -> f64 {
    let ab = b - a;
    let len2 = ab.norm_squared();
    let t = if len2 == 0.0 {
        0.0
    } else {
        ((p - a).dot(&ab) / len2).clamp(0.0, 1.0)
    };
    (a + ab * t - p).norm()
}

fn orient(a: Vec2, b: Vec2, c: Vec2) -> f64 {
    cross(b - a, c - a)
}

/// Weakly inside (boundary included), whatever the orientation of `poly`.
fn inside(p: Vec2, poly: &[Vec2]) -> bool {
    let n = poly.len();
    let signs: Vec<f64> = (0..n)
        .map(|i| orient(poly[i], poly[(i + 1) % n], p))
        .collect();
    signs.iter().all(|&s| s >= 0.0) || signs.iter().all(|&s| s <= 0.0)
}

fn within_box(p: Vec2, a: Vec2, b: Vec2) -> bool {
    p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
}

/// Closed segments p0p1 and q0q1 share a point.
fn segments_meet(p0: Vec2, p1: Vec2, q0: Vec2, q1: Vec2) -> bool {
    let d1 = orient(q0, q1, p0);
    let d2 = orient(q0, q1, p1);
    let d3 = orient(p0, p1, q0);
    let d4 = orient(p0, p1, q1);
    let opposite = |u: f64, v: f64| (u > 0.0 && v < 0.0) || (u < 0.0 && v > 0.0);
    if opposite(d1, d2) && opposite(d3, d4) {
        return true;
    }
    (d1 == 0.0 && within_box(p0, q0, q1))
        || (d2 == 0.0 && within_box(p1, q0, q1))
        || (d3 == 0.0 && within_box(q0, p0, p1))
        || (d4 == 0.0 && within_box(q1, p0, p1))
}

#[derive(Clone, Copy, Debug)]
struct Exact {
    /// 0 on overlap, else the smallest vertex-edge distance.
    distance: f64,
    /// The smallest vertex-edge distance, whether or not the polygons overlap.
    boundary_gap: f64,
    overlap: bool,
}

fn exact(a: &[Vec2], b: &[Vec2]) -> Exact {
    let mut gap = f64::INFINITY;
    for (pts, poly) in [(a, b), (b, a)] {
        let n = poly.len();
        for &p in pts {
            for j in 0..n {
                gap = gap.min(point_segment(p, poly[j], poly[(j + 1) % n]));
            }
        }
    }
    let overlap = a.iter().any(|&p| inside(p, b))
        || b.iter().any(|&p| inside(p, a))
        || (0..a.len()).any(|i| {
            (0..b.len())
                .any(|j| segments_meet(a[i], a[(i + 1) % a.len()], b[j], b[(j + 1) % b.len()]))
        });
    Exact {
        distance: if overlap { 0.0 } else { gap },
        boundary_gap: gap,
        overlap,
    }
}

/// Distance from `p` to the boundary of `poly`.
fn boundary_distance(p: Vec2, poly: &[Vec2]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|j| point_segment(p, poly[j], poly[(j + 1) % n]))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn oracle_sanity() {
    let sq = |x: f64, y: f64| {
        vec![
            Vec2::new(x, y),
            Vec2::new(x + 1.0, y),
            Vec2::new(x + 1.0, y + 1.0),
            Vec2::new(x, y + 1.0),
        ]
    };
    let e = exact(&sq(0.0, 0.0), &sq(2.0, 0.0));
    assert!(!e.overlap && (e.distance - 1.0).abs() < 1e-15);
    let e = exact(&sq(0.0, 0.0), &sq(2.0, 2.0));
    assert!(!e.overlap && (e.distance - 2f64.sqrt()).abs() < 1e-15);
    assert!(exact(&sq(0.0, 0.0), &sq(1.0, 0.5)).overlap); // touching edges
    assert!(exact(&sq(0.0, 0.0), &sq(1.0, 1.0)).overlap); // touching corners
    assert!(exact(&sq(0.0, 0.0), &sq(0.5, 0.5)).overlap); // overlap
                                                          // A cross: no vertex of either is inside the other, but the edges cross.
    let wide = [[-2.0, -0.5], [2.0, -0.5], [2.0, 0.5], [-2.0, 0.5]].map(|[x, y]| Vec2::new(x, y));
    let tall = wide.map(|v| Vec2::new(v.y, v.x));
    assert!(exact(&wide, &tall).overlap);
    // Containment: no edges meet.
    let big = sq(0.0, 0.0).iter().map(|v| v * 10.0).collect::<Vec<_>>();
    assert!(exact(&big, &sq(4.0, 4.0)).overlap);
    assert!(exact(&sq(4.0, 4.0), &big).overlap);
}

// ---------------------------------------------------------------------------------------
// Generators
// ---------------------------------------------------------------------------------------

type Shape = Vec<[f64; 2]>;

/// Random angles on an ellipse (counter-clockwise), frame origin anywhere near it.
fn ellipse_shape() -> impl Strategy<Value = Shape> {
    (3usize..=16)
        .prop_flat_map(|n| {
            (
                prop::collection::vec(0.2f64..1.0, n),
                0.05f64..2.0,
                0.05f64..2.0,
                0.0..TAU,
                -0.5f64..0.5,
                -0.5f64..0.5,
            )
        })
        .prop_map(|(w, rx, ry, phase, cx, cy)| {
            let total: f64 = w.iter().sum();
            let mut acc = phase;
            w.iter()
                .map(|wi| {
                    let a = acc;
                    acc += wi / total * TAU;
                    [cx + rx * a.cos(), cy + ry * a.sin()]
                })
                .collect()
        })
}

/// Andrew's monotone chain, strictly convex, counter-clockwise.
fn hull(mut pts: Vec<[f64; 2]>) -> Shape {
    pts.sort_by(|p, q| p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1])));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let turn = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut h: Shape = Vec::new();
    for pass in 0..2 {
        let start = h.len();
        let iter: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while h.len() >= start + 2 && turn(h[h.len() - 2], h[h.len() - 1], p) <= 0.0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

/// Convex hull of random points.
fn hull_shape() -> impl Strategy<Value = Shape> {
    (
        prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 3..24),
        0.05f64..2.0,
        -0.5f64..0.5,
        -0.5f64..0.5,
    )
        .prop_filter_map("degenerate hull", |(pts, s, cx, cy)| {
            let h = hull(pts.iter().map(|&(x, y)| [cx + s * x, cy + s * y]).collect());
            let n = h.len();
            if n < 3 {
                return None;
            }
            let area2: f64 = (0..n)
                .map(|i| {
                    let (p, q) = (h[i], h[(i + 1) % n]);
                    p[0] * q[1] - p[1] * q[0]
                })
                .sum();
            (area2 > 1e-3 * s * s).then_some(h)
        })
}

fn rectangle_shape() -> impl Strategy<Value = Shape> {
    (0.05f64..2.0, 0.05f64..2.0, -0.5f64..0.5, -0.5f64..0.5).prop_map(|(w, h, cx, cy)| {
        vec![
            [cx - w, cy - h],
            [cx + w, cy - h],
            [cx + w, cy + h],
            [cx - w, cy + h],
        ]
    })
}

/// Regular polygon with an even number of vertices: opposite edges are parallel, and the
/// edge normals are at multiples of 2π/n, so two of them at the same angle share parallel
/// edges.
fn regular_shape() -> impl Strategy<Value = Shape> {
    (
        prop::sample::select(vec![4usize, 6, 8, 10, 12, 14, 16]),
        0.05f64..2.0,
        -0.5f64..0.5,
        -0.5f64..0.5,
    )
        .prop_map(|(n, r, cx, cy)| {
            (0..n)
                .map(|k| {
                    let a = (2 * k + 1) as f64 * PI / n as f64;
                    [cx + r * a.cos(), cy + r * a.sin()]
                })
                .collect()
        })
}

fn any_shape() -> impl Strategy<Value = Shape> {
    prop_oneof![
        3 => ellipse_shape(),
        3 => hull_shape(),
        1 => rectangle_shape(),
        2 => regular_shape(),
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

fn polygon(s: &Shape) -> ConvexPolygon {
    ConvexPolygon::new(s)
        .unwrap_or_else(|e| panic!("generated polygon refused: {e}: {s:?}"))
        .0
}

fn local_vertices(s: &Shape) -> Vec<Vec2> {
    polygon(s).vertices().to_vec()
}

/// Outward unit normal of edge `i` of counter-clockwise `v`.
fn normal(v: &[Vec2], i: usize) -> Vec2 {
    let e = v[(i + 1) % v.len()] - v[i];
    Vec2::new(e.y, -e.x).normalize()
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
            let wa = place(&local_vertices(&a), pose_a);
            let i = i % wa.len();
            let na = normal(&wa, i);
            let lb = local_vertices(&b);
            let j = j % lb.len();
            let nb = normal(&lb, j);
            let theta_b = (-na.y).atan2(-na.x) - nb.y.atan2(nb.x);
            let wb = place(&lb, [0.0, 0.0, theta_b]);
            let mid_b = (wb[j] + wb[(j + 1) % wb.len()]) * 0.5;
            let target = wa[i] + (wa[(i + 1) % wa.len()] - wa[i]) * s + na * g;
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
            let wa = place(&local_vertices(&a), pose_a);
            let i = i % wa.len();
            let na = normal(&wa, i);
            let wb = place(&local_vertices(&b), [0.0, 0.0, theta_b]);
            let support = wb
                .iter()
                .copied()
                .min_by(|p, q| p.dot(&na).total_cmp(&q.dot(&na)))
                .unwrap();
            let target = wa[i] + (wa[(i + 1) % wa.len()] - wa[i]) * s + na * g;
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
            let c = wbig.iter().sum::<Vec2>() / wbig.len() as f64;
            let inradius = (0..wbig.len())
                .map(|i| normal(&wbig, i).dot(&(wbig[i] - c)))
                .fold(f64::INFINITY, f64::min);
            let ls = local_vertices(&small);
            let cs = ls.iter().sum::<Vec2>() / ls.len() as f64;
            let rs = ls.iter().map(|v| (v - cs).norm()).fold(0.0, f64::max);
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
    let n = w.nudge;
    let near_a = [c.pose_a[0] + n[0], c.pose_a[1] + n[1], c.pose_a[2] + n[2]];
    let near_b = [c.pose_b[0] + n[3], c.pose_b[1] + n[4], c.pose_b[2] + n[5]];
    let before = closest_features(&posed(&s.pa, near_a), &posed(&s.pb, near_b), None, &tolw);
    let warmed = closest_features(&a, &b, Some(before.features), &tolw);
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
    #![proptest_config(ProptestConfig::with_cases(256))]

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
    let mut draw = |s: &dyn Fn(&mut TestRunner) -> PairCase, n: usize| -> Vec<Setting> {
        (0..n).map(|_| setting(&s(&mut runner))).collect()
    };
    let touching = draw(&|r| touching_case().new_tree(r).unwrap().current(), 400);
    let exactly = touching
        .iter()
        .filter(|s| s.oracle.boundary_gap <= s.tol)
        .count();
    assert!(exactly > 100, "only {exactly}/400 touching cases touch");
    let contained = draw(&|r| containment_case().new_tree(r).unwrap().current(), 100);
    assert!(contained
        .iter()
        .all(|s| s.oracle.overlap && s.oracle.boundary_gap > 0.0));
    let random = draw(&|r| random_case().new_tree(r).unwrap().current(), 400);
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
        let c = pair_case().new_tree(&mut runner).unwrap().current();
        let w = warm().new_tree(&mut runner).unwrap().current();
        let s = setting(&c);
        let (a, b) = (posed(&s.pa, c.pose_a), posed(&s.pb, c.pose_b));
        let cold = closest_features(&a, &b, None, &tolw);
        let n = w.nudge;
        let near_a = [c.pose_a[0] + n[0], c.pose_a[1] + n[1], c.pose_a[2] + n[2]];
        let near_b = [c.pose_b[0] + n[3], c.pose_b[1] + n[4], c.pose_b[2] + n[5]];
        let before = closest_features(&posed(&s.pa, near_a), &posed(&s.pb, near_b), None, &tolw);
        let warmed = closest_features(&a, &b, Some(before.features), &tolw);
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
    let a = polygon(&vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    let b = polygon(&vec![[1.0, 1.0], [1.0 + 1.5e-5, -0.5], [3.0, 0.25]]);
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
