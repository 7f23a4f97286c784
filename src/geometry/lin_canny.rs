//! The 2-D Lin-Canny closest-feature walk (Feyeux & Landry 2013, section 5, Tables 2-6).
//!
//! Each step takes the closest points of the current feature pair and tests each against
//! the Voronoi region of the other polygon's feature; a violated constraint names the
//! neighbouring feature to move to. When both points lie in the other's region the two
//! polygons are separated by a slab of exactly that width, so the distance is exact.
//! Lin-Canny may cycle on degenerate input: the walk is cut after a bounded number of
//! steps and the exact [`brute_force_distance`] answers instead (counted in `fell_back`).

use super::segment::{
    closest_ends, crossing, nearly_parallel, project_on_segment, segment_segment,
};
use super::{brute_force_distance, cross, Distance, Feature, FeaturePair, Posed, Vec2};

/// Tolerances and limits of the walk.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WalkTolerances {
    /// δc: how far a point may lie outside a Voronoi region and still count as inside,
    /// relative to its distance from the feature (so an angle, in radians). Stops the walk
    /// from oscillating between features that are equally close. Relative, not absolute:
    /// an absolute slack ε lets a nearly parallel edge hide a contact behind a distance of
    /// about √(ε·edge length).
    pub feature_tol: f64,
    /// Sine of the angle under which two edges count as parallel.
    pub parallel_tol: f64,
    /// Step limit is `max_steps_per_vertex · (n + m) + 8`; beyond it the walk is taken to
    /// cycle and the exact fallback answers.
    pub max_steps_per_vertex: usize,
}

impl Default for WalkTolerances {
    fn default() -> Self {
        WalkTolerances {
            feature_tol: 1e-10,
            parallel_tol: 1e-10,
            max_steps_per_vertex: 2,
        }
    }
}

/// What testing a point of the other polygon against a feature's Voronoi region decides.
enum Step {
    /// The point lies in the region: the feature stays.
    Stay,
    /// A region constraint is violated: move to the feature beyond it.
    MoveTo(Feature),
    /// The point lies inside the polygon: the polygons overlap.
    Overlap,
}

/// Exact distance between two convex polygons by the closest-feature walk.
///
/// `warm` is the feature pair of a previous query on the same two polygons (the walk then
/// typically takes one step); `None` or out-of-range indices start from the support
/// vertices along the line between the centres. The result is exact up to rounding: the
/// walk stops only at a pair certified by the Voronoi test (within `tol.feature_tol`), at an
/// intersection of features (distance 0), or through the exact fallback.
///
/// ```
/// use workcell::geometry::{brute_force_distance, closest_features, ConvexPolygon, Posed, WalkTolerances};
/// let square = ConvexPolygon::rectangle(2.0, 2.0)?;
/// let tol = WalkTolerances::default();
/// let a = Posed::new(&square, 0.0, 0.0, 0.0);
/// let b = Posed::new(&square, 4.0, 3.0, 0.4);
/// let d = closest_features(&a, &b, None, &tol);
/// assert!((d.distance - brute_force_distance(&a, &b).distance).abs() < 1e-12);
/// // Warm-started from its own answer on a slightly moved pair: the walk has little to do.
/// let moved = Posed::new(&square, 4.0, 3.1, 0.41);
/// let again = closest_features(&a, &moved, Some(d.features), &tol);
/// assert!(again.steps <= d.steps);
/// assert!((again.distance - brute_force_distance(&a, &moved).distance).abs() < 1e-12);
/// # Ok::<(), workcell::geometry::PolygonError>(())
/// ```
pub fn closest_features(
    a: &Posed,
    b: &Posed,
    warm: Option<FeaturePair>,
    tol: &WalkTolerances,
) -> Distance {
    let valid = |f: Feature, p: &Posed| match f {
        Feature::Vertex(i) | Feature::Edge(i) => i < p.len(),
    };
    let start = warm
        .filter(|w| valid(w.a, a) && valid(w.b, b))
        .unwrap_or_else(|| cold_start(a, b));
    let (mut fa, mut fb) = (start.a, start.b);
    let max_steps = tol.max_steps_per_vertex * (a.len() + b.len()) + 8;
    let mut steps = 0u32;
    while (steps as usize) < max_steps {
        steps += 1;
        let (pa, pb) = feature_points(a, fa, b, fb, tol.parallel_tol);
        let result = |distance| Distance {
            distance,
            point_a: pa,
            point_b: pb,
            features: FeaturePair { a: fa, b: fb },
            steps,
            fell_back: false,
        };
        if pa == pb {
            return result(0.0); // the features meet: the polygons touch or overlap
        }
        let slack = tol.feature_tol * (pb - pa).norm();
        match step(a, fa, &pb, slack) {
            Step::Stay => {}
            Step::MoveTo(f) => {
                fa = f;
                continue;
            }
            Step::Overlap => return result(0.0),
        }
        match step(b, fb, &pa, slack) {
            Step::Stay => {}
            Step::MoveTo(f) => {
                fb = f;
                continue;
            }
            Step::Overlap => return result(0.0),
        }
        let distance = (pb - pa).norm();
        match settle(a, b, (fa, fb), (pa, pb), distance, tol) {
            Settle::Move(ea, eb) => {
                (fa, fb) = (ea, eb);
                continue;
            }
            Settle::Cross(x) => {
                return Distance {
                    point_a: x,
                    point_b: x,
                    ..result(0.0)
                }
            }
            Settle::Done => {}
        }
        return result(distance);
    }
    Distance {
        steps,
        fell_back: true,
        ..brute_force_distance(a, b)
    }
}

/// What the walk does at a pair of features that passed both Voronoi tests.
enum Settle {
    /// A closer pair takes over.
    Move(Feature, Feature),
    /// Two edges cross at this point: distance 0.
    Cross(Vec2),
    /// The pair is the closest one.
    Done,
}

/// The checks after the Voronoi tests. The slack of a vertex region (and rounding, on long
/// edges) lets through a neighbouring edge that approaches the other feature at an angle too
/// small to see from the closest points; along a long edge that angle is worth more than δ.
/// Such an edge, when closer, takes over; two nearly parallel edges hand over to the pair at
/// an end of their overlap when it is closer, or cross.
#[inline]
fn settle(
    a: &Posed,
    b: &Posed,
    (fa, fb): (Feature, Feature),
    (pa, pb): (Vec2, Vec2),
    distance: f64,
    tol: &WalkTolerances,
) -> Settle {
    let floor = settled_floor(distance, &pa, &pb, tol);
    let closer = |ea: Feature, eb: Feature| {
        let (qa, qb) = feature_points(a, ea, b, eb, tol.parallel_tol);
        (qb - qa).norm() < floor
    };
    match (fa, fb) {
        (Feature::Vertex(v), Feature::Edge(e)) => {
            if let Some(f) = approaching_edges(a, v, b.normal(e)).find(|&f| closer(f, fb)) {
                return Settle::Move(f, fb);
            }
        }
        (Feature::Edge(e), Feature::Vertex(v)) => {
            if let Some(f) = approaching_edges(b, v, a.normal(e)).find(|&f| closer(fa, f)) {
                return Settle::Move(fa, f);
            }
        }
        _ => {}
    }
    if let (Feature::Edge(i), Feature::Edge(j)) = (fa, fb) {
        match overlap_end(a, i, b, j, (distance, floor), tol) {
            OverlapEnd::Cross(x) => return Settle::Cross(x),
            OverlapEnd::Closer(pair) => return Settle::Move(pair.a, pair.b),
            OverlapEnd::Middle => {}
        }
    }
    Settle::Done
}

/// The edges at vertex `v` of `p` whose other end lies nearer than `v` to the line of an
/// edge of outward normal `n` (of the other polygon): where the closest points are a vertex
/// and an edge, only such a neighbouring edge can come closer. Convexity makes them rare
/// (both neighbours recede from a supporting line); they appear with nearly parallel edges.
fn approaching_edges<'p>(p: &'p Posed, v: usize, n: Vec2) -> impl Iterator<Item = Feature> + 'p {
    let at = p.vertex(v);
    [(p.prev(v), p.prev(v)), (p.next(v), v)]
        .into_iter()
        .filter(move |&(w, _)| n.dot(&(p.vertex(w) - at)) < 0.0)
        .map(|(_, e)| Feature::Edge(e))
}

/// Rounding of the points compared, in units of the largest coordinate (a few operations
/// each): differences below it are noise, and chasing them would make the walk cycle.
const ROUNDING: f64 = 8.0 * f64::EPSILON;

/// How close another pair of features must come to take over from a settled pair at
/// `distance`: closer by the Voronoi slack and by rounding.
fn settled_floor(distance: f64, pa: &Vec2, pb: &Vec2, tol: &WalkTolerances) -> f64 {
    let scale = pa.amax().max(pb.amax());
    distance * (1.0 - tol.feature_tol) - ROUNDING * scale
}

/// Where two settled edges are closest, when the walk took the middle of their overlap.
enum OverlapEnd {
    /// Not parallel, or the middle is as close as any point (within the Voronoi slack).
    Middle,
    /// The nearly parallel edges cross: the polygons overlap.
    Cross(Vec2),
    /// An end of the overlap is closer: the walk goes on from that vertex-edge pair.
    Closer(FeaturePair),
}

/// Settled on two nearly parallel edges, the walk measured the middle of their overlap,
/// but along edges at an angle α the distance changes by α·length across the overlap: on
/// edges 2·10¹⁰·δ long an α of 5·10⁻¹¹ hides a contact 0.5·δ deep at one end. The minimum
/// of two segments that do not cross is at an end point of one of them; from there the
/// walk goes on (a neighbouring edge may be closer still, if it turns away from the other
/// polygon by less than α).
fn overlap_end(
    a: &Posed,
    i: usize,
    b: &Posed,
    j: usize,
    (middle, floor): (f64, f64),
    tol: &WalkTolerances,
) -> OverlapEnd {
    let (p0, p1) = (a.vertex(i), a.vertex(a.next(i)));
    let (q0, q1) = (b.vertex(j), b.vertex(b.next(j)));
    // The middle's distance is to the line of edge j; along edge i that changes by at most
    // |cross| / |edge j|. Within the floor (most often: exactly parallel faces) nothing is
    // closer, and no square root is needed to tell.
    let (c, slack) = (cross(&(p1 - p0), &(q1 - q0)), middle - floor);
    if c * c <= slack * slack * (q1 - q0).norm_squared() {
        return OverlapEnd::Middle;
    }
    if !nearly_parallel(&p0, &p1, &q0, &q1, tol.parallel_tol) {
        return OverlapEnd::Middle;
    }
    if let Some(x) = crossing(&p0, &p1, &q0, &q1) {
        return OverlapEnd::Cross(x);
    }
    let (end, pa, pb) = closest_ends(&p0, &p1, &q0, &q1);
    // Exactly parallel edges differ by rounding only: keep the middle, whose features the
    // warm start keeps too.
    if (pb - pa).norm() >= floor {
        return OverlapEnd::Middle;
    }
    let (fa, fb) = match end {
        0 => (Feature::Vertex(i), Feature::Edge(j)),
        1 => (Feature::Vertex(a.next(i)), Feature::Edge(j)),
        2 => (Feature::Edge(i), Feature::Vertex(j)),
        _ => (Feature::Edge(i), Feature::Vertex(b.next(j))),
    };
    OverlapEnd::Closer(FeaturePair { a: fa, b: fb })
}

/// The vertices of A and B that reach furthest towards each other along the centre line.
fn cold_start(a: &Posed, b: &Posed) -> FeaturePair {
    let dir = b.center() - a.center();
    let support = |p: &Posed, d: Vec2| {
        (0..p.len())
            .max_by(|&i, &j| p.vertex(i).dot(&d).total_cmp(&p.vertex(j).dot(&d)))
            .unwrap_or(0)
    };
    FeaturePair {
        a: Feature::Vertex(support(a, dir)),
        b: Feature::Vertex(support(b, -dir)),
    }
}

/// Closest points of two features (Tables 2-4: vertex-vertex, edge-vertex, edge-edge).
fn feature_points(
    a: &Posed,
    fa: Feature,
    b: &Posed,
    fb: Feature,
    parallel_tol: f64,
) -> (Vec2, Vec2) {
    let point_edge = |p: Vec2, poly: &Posed, j: usize| {
        let (q0, q1) = (poly.vertex(j), poly.vertex(poly.next(j)));
        q0 + (q1 - q0) * project_on_segment(&p, &q0, &q1)
    };
    match (fa, fb) {
        (Feature::Vertex(i), Feature::Vertex(j)) => (a.vertex(i), b.vertex(j)),
        (Feature::Vertex(i), Feature::Edge(j)) => {
            let p = a.vertex(i);
            (p, point_edge(p, b, j))
        }
        (Feature::Edge(i), Feature::Vertex(j)) => {
            let q = b.vertex(j);
            (point_edge(q, a, i), q)
        }
        (Feature::Edge(i), Feature::Edge(j)) => segment_segment(
            &a.vertex(i),
            &a.vertex(a.next(i)),
            &b.vertex(j),
            &b.vertex(b.next(j)),
            parallel_tol,
        ),
    }
}

/// Tests `q` against the Voronoi region of feature `f` of `p` (Tables 5-6).
fn step(p: &Posed, f: Feature, q: &Vec2, tol: f64) -> Step {
    match f {
        Feature::Vertex(i) => {
            // The wedge between the normals of the two edges that meet at the vertex.
            let v = p.vertex(i);
            let before = v - p.vertex(p.prev(i));
            let after = p.vertex(p.next(i)) - v;
            let back = -(q - v).dot(&before) / before.norm(); // > 0: beside the previous edge
            let ahead = (q - v).dot(&after) / after.norm(); // > 0: beside the next edge
            if back.max(ahead) <= tol {
                Step::Stay
            } else if back > ahead {
                Step::MoveTo(Feature::Edge(p.prev(i)))
            } else {
                Step::MoveTo(Feature::Edge(i))
            }
        }
        Feature::Edge(i) => {
            // The strip over the edge, on its outer side.
            let v0 = p.vertex(i);
            let e = p.vertex(p.next(i)) - v0;
            let len = e.norm();
            let s = (q - v0).dot(&e) / len;
            if s < -tol {
                Step::MoveTo(Feature::Vertex(i))
            } else if s > len + tol {
                Step::MoveTo(Feature::Vertex(p.next(i)))
            } else if p.normal(i).dot(&(q - v0)) < -tol {
                // Behind the edge's line: inside the polygon, or in the region of a feature
                // the local walk cannot see ("find the closest feature").
                outermost_edge(p, q).map_or(Step::Overlap, |e| Step::MoveTo(Feature::Edge(e)))
            } else {
                Step::Stay
            }
        }
    }
}

/// The edge of `p` whose outer side `q` lies furthest on, or `None` when `q` is inside or
/// on the boundary of `p` (the paper's overlap test, "find the closest feature").
fn outermost_edge(p: &Posed, q: &Vec2) -> Option<usize> {
    let (mut best, mut best_h) = (None, 0.0);
    for i in 0..p.len() {
        let h = p.normal(i).dot(&(q - p.vertex(i)));
        if h > best_h {
            best = Some(i);
            best_h = h;
        }
    }
    best
}
