//! Exact distance by exhaustion: the walk's fallback and the tests' oracle.

use super::segment::project_on_segment;
use super::{Distance, Feature, FeaturePair, Posed, Vec2};

/// Exact distance between two posed convex polygons in O(n·m).
///
/// Overlap (including touching) is decided by the separating-axis theorem over all edge
/// normals and gives distance 0. Otherwise the distance is the smallest vertex-to-edge
/// distance in either direction, which for disjoint convex polygons is the true distance.
/// `steps` is 0 and `fell_back` false in the result.
///
/// ```
/// use workcell::geometry::{brute_force_distance, ConvexPolygon, Posed, Vec2};
/// let square = ConvexPolygon::rectangle(2.0, 2.0)?;
/// // Centres 5 apart, corners 3 apart along x.
/// let d = brute_force_distance(&Posed::new(&square, 0.0, 0.0, 0.0), &Posed::new(&square, 5.0, 0.0, 0.0));
/// assert_eq!(d.distance, 3.0);
/// assert_eq!((d.point_a.x, d.point_b.x), (1.0, 4.0));
/// let overlap = brute_force_distance(&Posed::new(&square, 0.0, 0.0, 0.0), &Posed::new(&square, 1.0, 1.0, 0.7));
/// assert_eq!(overlap.distance, 0.0);
/// # let _: Vec2 = d.point_a;
/// # Ok::<(), workcell::geometry::PolygonError>(())
/// ```
pub fn brute_force_distance(a: &Posed, b: &Posed) -> Distance {
    let va: Vec<Vec2> = (0..a.len()).map(|i| a.vertex(i)).collect();
    let vb: Vec<Vec2> = (0..b.len()).map(|i| b.vertex(i)).collect();
    let overlap = !(separated_by_an_edge_of(a, &va, &vb) || separated_by_an_edge_of(b, &vb, &va));

    let mut best = Distance {
        distance: f64::INFINITY,
        point_a: va[0],
        point_b: vb[0],
        features: FeaturePair {
            a: Feature::Vertex(0),
            b: Feature::Vertex(0),
        },
        steps: 0,
        fell_back: false,
    };
    for (pts, edges, swapped) in [(&va, &vb, false), (&vb, &va, true)] {
        let n = edges.len();
        for (i, p) in pts.iter().enumerate() {
            for j in 0..n {
                let (q0, q1) = (edges[j], edges[(j + 1) % n]);
                let s = project_on_segment(p, &q0, &q1);
                let q = q0 + (q1 - q0) * s;
                let d = (q - p).norm();
                if d < best.distance {
                    let edge_feature = if s == 0.0 {
                        Feature::Vertex(j)
                    } else if s == 1.0 {
                        Feature::Vertex((j + 1) % n)
                    } else {
                        Feature::Edge(j)
                    };
                    let pair = FeaturePair {
                        a: Feature::Vertex(i),
                        b: edge_feature,
                    };
                    (best.point_a, best.point_b, best.features) = if swapped {
                        (q, *p, pair.swapped())
                    } else {
                        (*p, q, pair)
                    };
                    best.distance = d;
                }
            }
        }
    }
    if overlap {
        best.distance = 0.0;
    }
    best
}

/// True when some edge line of `p` (vertices `vp`) has all of `vq` strictly outside.
fn separated_by_an_edge_of(p: &Posed, vp: &[Vec2], vq: &[Vec2]) -> bool {
    (0..vp.len()).any(|i| {
        let n = p.normal(i);
        vq.iter().all(|q| n.dot(&(q - vp[i])) > 0.0)
    })
}
