//! Bodies made of convex parts (contract section 5): the union of the parts, under their
//! convex hull, with a disc around each part.
//!
//! The levels form the small hierarchy of bounding volumes that Feyeux & Landry's
//! conclusion calls for: the body's disc, its hull, each part's disc, the parts. A query
//! goes down a level only where the coarser one cannot answer, so a non-convex body far
//! from everything costs what its hull costs.

use super::{closest_features, convex_hull, ConvexPolygon, FeaturePair, Outline, Posed, Vec2};
use super::{OutlineError, PolygonError, WalkTolerances};

/// A body made of convex parts, in the body frame: their union, with the convex hull of
/// them all as its outer level. One part is a convex body ([`Parts::is_convex`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Parts {
    hull: ConvexPolygon,
    parts: Vec<ConvexPolygon>,
    /// Each part's axis-aligned box in the body frame, for the bounds of a part query.
    boxes: Vec<[f64; 4]>,
    /// The outline the parts were cut from (pictures draw it, not the seams).
    outline: Option<Vec<Vec2>>,
}

impl Parts {
    /// The union of `parts` (each validated; at least one), under their convex hull.
    ///
    /// ```
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// let body = ConvexPolygon::rectangle(1.0, 0.6)?;
    /// let finger = ConvexPolygon::from_vertices(&[[0.5, -0.1], [1.2, -0.1], [1.2, 0.1], [0.5, 0.1]])?;
    /// let gripper = Parts::new(vec![body, finger])?;
    /// assert_eq!((gripper.len(), gripper.hull().len()), (2, 6));
    /// assert!(!gripper.is_convex());
    /// # Ok::<(), workcell::geometry::PolygonError>(())
    /// ```
    pub fn new(parts: Vec<ConvexPolygon>) -> Result<Parts, PolygonError> {
        let hull = match parts.as_slice() {
            [one] => one.clone(),
            _ => hull_of(parts.iter().flat_map(|p| p.vertices().iter().copied()))?,
        };
        let boxes = parts.iter().map(bounding_box).collect();
        Ok(Parts {
            hull,
            parts,
            boxes,
            outline: None,
        })
    }

    /// The region an outline bounds, cut into convex parts.
    ///
    /// ```
    /// use workcell::geometry::{Outline, Parts};
    /// let l = Outline::new(&[[0.0, 0.0], [4.0, 0.0], [4.0, 1.0], [1.0, 1.0], [1.0, 3.0], [0.0, 3.0]])?;
    /// let parts = Parts::from_outline(&l)?;
    /// assert_eq!((parts.len(), parts.outline().map(<[_]>::len)), (2, Some(6)));
    /// # Ok::<(), workcell::geometry::OutlineError>(())
    /// ```
    pub fn from_outline(outline: &Outline) -> Result<Parts, OutlineError> {
        let convex = outline.convex_parts()?;
        let sliver = OutlineError::Sliver { vertex: 0 };
        let parts = Parts::new(convex).map_err(|_| sliver)?;
        Ok(Parts {
            outline: Some(outline.vertices().to_vec()),
            ..parts
        })
    }

    /// The convex hull of the parts: the body's outer level, and the body itself when it is
    /// convex.
    pub fn hull(&self) -> &ConvexPolygon {
        &self.hull
    }

    /// Whether the body is its hull: one part.
    pub fn is_convex(&self) -> bool {
        self.parts.len() == 1
    }

    /// The same body moved by `offset` in its frame (an obstacle's frame is put at its
    /// hull's centroid).
    pub(crate) fn translated(&self, offset: &Vec2) -> Parts {
        Parts {
            hull: self.hull.translated(offset),
            parts: self.parts.iter().map(|p| p.translated(offset)).collect(),
            boxes: self
                .boxes
                .iter()
                .map(|[x0, y0, x1, y1]| {
                    [x0 - offset.x, y0 - offset.y, x1 - offset.x, y1 - offset.y]
                })
                .collect(),
            outline: self
                .outline
                .as_ref()
                .map(|o| o.iter().map(|v| v - offset).collect()),
        }
    }

    /// The convex parts, in the order given.
    pub fn parts(&self) -> &[ConvexPolygon] {
        &self.parts
    }

    /// The outline the parts were cut from, if they were.
    pub fn outline(&self) -> Option<&[Vec2]> {
        self.outline.as_deref()
    }

    /// Number of parts.
    pub fn len(&self) -> usize {
        self.parts.len()
    }

    /// Always false: a body has at least one part.
    pub fn is_empty(&self) -> bool {
        false
    }
}

/// The convex hull of `points` as a polygon.
fn hull_of(points: impl Iterator<Item = Vec2>) -> Result<ConvexPolygon, PolygonError> {
    let corners: Vec<[f64; 2]> = convex_hull(points.collect())
        .iter()
        .map(|v| [v.x, v.y])
        .collect();
    ConvexPolygon::from_vertices(&corners)
}

/// The axis-aligned box of a polygon's vertices in its own frame: `[x0, y0, x1, y1]`.
///
/// ```
/// use workcell::geometry::{bounding_box, ConvexPolygon};
/// let p = ConvexPolygon::from_vertices(&[[0.0, 0.0], [2.0, 1.0], [1.0, 3.0]])?;
/// assert_eq!(bounding_box(&p), [0.0, 0.0, 2.0, 3.0]);
/// # Ok::<(), workcell::geometry::PolygonError>(())
/// ```
pub fn bounding_box(p: &ConvexPolygon) -> [f64; 4] {
    p.vertices().iter().fold(EMPTY_BOX, |[x0, y0, x1, y1], v| {
        [x0.min(v.x), y0.min(v.y), x1.max(v.x), y1.max(v.y)]
    })
}

/// One side of a part query: a body's convex pieces, their boxes in its frame and its pose.
#[derive(Clone, Copy)]
pub struct PartsSide<'a> {
    parts: &'a [ConvexPolygon],
    boxes: &'a [[f64; 4]],
    pos: Vec2,
    theta: f64,
}

impl<'a> PartsSide<'a> {
    /// A body of parts at this pose.
    pub fn of(parts: &'a Parts, pos: Vec2, theta: f64) -> Self {
        PartsSide {
            parts: &parts.parts,
            boxes: &parts.boxes,
            pos,
            theta,
        }
    }

    /// A convex body as one part; `aabb` is its [`bounding_box`].
    pub fn convex(shape: &'a ConvexPolygon, aabb: &'a [f64; 4], pos: Vec2, theta: f64) -> Self {
        PartsSide {
            parts: std::slice::from_ref(shape),
            boxes: std::slice::from_ref(aabb),
            pos,
            theta,
        }
    }
}

/// How exact a part query must be. Below `exact_below` (δ) the least distance is exact, so
/// that a contact is always real. Above it a lower bound will do (η only has to bound the
/// distance from below): the search may stop up to `slack` short of the least distance, never
/// under `exact_below`, which spares the walks of pairs that are all about as near.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartsTolerance {
    /// Exact below this distance (δ).
    pub exact_below: f64,
    /// How far below the least distance the answer may be, above `exact_below`.
    pub slack: f64,
}

/// The least distance between two bodies' parts (a lower bound within the tolerance), and
/// the nearest pair found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartsDistance {
    /// A lower bound of the least distance between the parts, exact below `exact_below`;
    /// 0 when some pair touches.
    pub distance: f64,
    /// The nearest pair walked: the part of A, the part of B.
    pub parts: (usize, usize),
    /// Closest-feature walks run.
    pub walks: u32,
    /// Feature steps those walks took.
    pub steps: u32,
}

/// What a part query keeps between calls on the same pair: the last closest features of
/// every pair of parts (for warm starts), and room for B's boxes and the pairs' bounds.
#[derive(Clone, Debug, Default)]
pub struct PartsCache {
    warm: Vec<Option<FeaturePair>>,
    boxes_b: Vec<[f64; 4]>,
    gaps: Vec<f64>,
}

/// The least distance between two bodies made of parts, nearest first. Every pair of parts
/// gets a lower bound, the distance between their boxes in A's frame (A's boxes are fixed
/// there; B's are its boxes' corners moved in): the pair of least bound is walked first,
/// then every pair whose bound is below the least distance found, less the slack the
/// tolerance allows. Walks are warm-started from the pair's features at the last call.
///
/// ```
/// use workcell::geometry::{bounding_box, parts_distance, ConvexPolygon, Parts, PartsCache, PartsSide, PartsTolerance, Vec2, WalkTolerances};
/// let bar = |x0: f64, y0: f64, x1: f64, y1: f64| ConvexPolygon::from_vertices(&[[x0, y0], [x1, y0], [x1, y1], [x0, y1]]);
/// // A U open upwards, and a peg hanging in its bay: the hulls overlap, the parts do not.
/// let u = Parts::new(vec![bar(-2.0, 0.0, 2.0, 1.0)?, bar(-2.0, 1.0, -1.0, 4.0)?, bar(1.0, 1.0, 2.0, 4.0)?])?;
/// let peg = bar(-0.5, -1.0, 0.5, 1.0)?;
/// let aabb = bounding_box(&peg);
/// let exact = PartsTolerance { exact_below: f64::INFINITY, slack: 0.0 };
/// let d = parts_distance(
///     PartsSide::of(&u, Vec2::zeros(), 0.0),
///     PartsSide::convex(&peg, &aabb, Vec2::new(0.0, 3.0), 0.0),
///     &WalkTolerances::default(),
///     exact,
///     &mut PartsCache::default(),
/// );
/// assert!((d.distance - 0.5).abs() < 1e-12); // 0.5 to each arm of the U, 1 to its floor
/// assert!(d.parts.0 == 1 || d.parts.0 == 2);
/// # Ok::<(), workcell::geometry::PolygonError>(())
/// ```
pub fn parts_distance(
    a: PartsSide,
    b: PartsSide,
    tol: &WalkTolerances,
    exactness: PartsTolerance,
    cache: &mut PartsCache,
) -> PartsDistance {
    let (na, nb) = (a.parts.len(), b.parts.len());
    if cache.warm.len() != na * nb {
        cache.warm = vec![None; na * nb];
    }
    let PartsCache {
        warm,
        boxes_b,
        gaps,
    } = cache;
    boxes_in_frame_of(&a, &b, boxes_b);
    let first = pair_bounds(a.boxes, boxes_b, gaps);
    let mut best = PartsDistance {
        distance: f64::INFINITY,
        parts: (0, 0),
        walks: 0,
        steps: 0,
    };
    let mut walk = |k: usize, best: &mut PartsDistance| {
        let (i, j) = (k / nb, k % nb);
        let pa = Posed::new(&a.parts[i], a.pos.x, a.pos.y, a.theta);
        let pb = Posed::new(&b.parts[j], b.pos.x, b.pos.y, b.theta);
        let d = closest_features(&pa, &pb, warm[k], tol);
        warm[k] = Some(d.features);
        best.walks += 1;
        best.steps += d.steps;
        if d.distance < best.distance {
            best.distance = d.distance;
            best.parts = (i, j);
        }
    };
    walk(first, &mut best);
    // Pairs bounded below `cut` may be nearer than the best found: walk them; the least
    // bound of those skipped above it, if below the best, is the answer.
    let cut = |best: f64| {
        let slack = exactness.slack.min(best - exactness.exact_below).max(0.0);
        best - slack
    };
    let mut skipped = f64::INFINITY;
    for (k, &gap) in gaps.iter().enumerate() {
        if k == first || best.distance == 0.0 {
            continue;
        }
        let c = cut(best.distance);
        if gap < c * c {
            walk(k, &mut best);
        } else if gap < best.distance * best.distance {
            skipped = skipped.min(gap);
        }
    }
    best.distance = best.distance.min(skipped.sqrt());
    best
}

/// B's boxes in A's frame, each the box of its corners moved there:
/// R(−θa)·(R(θb)·corner + pos_b − pos_a).
fn boxes_in_frame_of(a: &PartsSide, b: &PartsSide, out: &mut Vec<[f64; 4]>) {
    let (sa, ca) = a.theta.sin_cos();
    let (sr, cr) = (b.theta - a.theta).sin_cos();
    let d = b.pos - a.pos;
    let shift = Vec2::new(ca * d.x + sa * d.y, -sa * d.x + ca * d.y);
    out.clear();
    out.extend(b.boxes.iter().map(|&[x0, y0, x1, y1]| {
        let corner = |x: f64, y: f64| (cr * x - sr * y + shift.x, sr * x + cr * y + shift.y);
        let corners = [
            corner(x0, y0),
            corner(x1, y0),
            corner(x1, y1),
            corner(x0, y1),
        ];
        corners.iter().fold(EMPTY_BOX, |[a0, b0, a1, b1], &(x, y)| {
            [a0.min(x), b0.min(y), a1.max(x), b1.max(y)]
        })
    }));
}

/// The box of no point: every point widens it.
const EMPTY_BOX: [f64; 4] = [
    f64::INFINITY,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NEG_INFINITY,
];

/// Every pair's bound, the squared distance between its boxes (A's part `i` and B's `j`
/// at `i · |B| + j`), into `gaps`; the pair of the least bound (the first on ties).
fn pair_bounds(boxes_a: &[[f64; 4]], boxes_b: &[[f64; 4]], gaps: &mut Vec<f64>) -> usize {
    gaps.clear();
    let mut first = (f64::INFINITY, 0);
    for ba in boxes_a {
        for bb in boxes_b {
            let gx = (ba[0] - bb[2]).max(bb[0] - ba[2]).max(0.0);
            let gy = (ba[1] - bb[3]).max(bb[1] - ba[3]).max(0.0);
            let g2 = gx * gx + gy * gy;
            if g2 < first.0 {
                first = (g2, gaps.len());
            }
            gaps.push(g2);
        }
    }
    first.1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::brute_force_distance;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn random_part(rng: &mut ChaCha8Rng) -> ConvexPolygon {
        let (cx, cy) = (rng.random_range(-2.0..2.0), rng.random_range(-2.0..2.0));
        let n = rng.random_range(3..8);
        let mut angles: Vec<f64> = (0..n)
            .map(|_| rng.random_range(0.0..std::f64::consts::TAU))
            .collect();
        angles.sort_by(f64::total_cmp);
        let r = rng.random_range(0.1..1.0);
        let pts: Vec<[f64; 2]> = angles
            .iter()
            .map(|a| [cx + r * a.cos(), cy + r * a.sin()])
            .collect();
        ConvexPolygon::from_vertices(&pts)
            .unwrap_or_else(|_| ConvexPolygon::rectangle(r, r).unwrap())
    }

    /// Nearest first with its early exit finds the least distance over every pair of parts,
    /// and a pair that attains it; warm starts carried from pose to pose change nothing;
    /// with slack, a lower bound within it that is exact below its floor.
    #[test]
    fn best_first_agrees_with_every_pair() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let tol = WalkTolerances::default();
        for _ in 0..200 {
            let pa: Vec<ConvexPolygon> = (0..rng.random_range(2..12))
                .map(|_| random_part(&mut rng))
                .collect();
            let pb: Vec<ConvexPolygon> = (0..rng.random_range(2..12))
                .map(|_| random_part(&mut rng))
                .collect();
            let (a, b) = (
                Parts::new(pa.clone()).unwrap(),
                Parts::new(pb.clone()).unwrap(),
            );
            let mut cache = PartsCache::default();
            let (mut pos, mut theta) = (
                Vec2::new(rng.random_range(-8.0..8.0), rng.random_range(-8.0..8.0)),
                0.0,
            );
            for _ in 0..10 {
                pos += Vec2::new(rng.random_range(-0.3..0.3), rng.random_range(-0.3..0.3));
                theta += rng.random_range(-0.5..0.5);
                let ta = rng.random_range(-3.0..3.0);
                let query = |exactness, cache: &mut PartsCache| {
                    parts_distance(
                        PartsSide::of(&a, Vec2::zeros(), ta),
                        PartsSide::of(&b, pos, theta),
                        &tol,
                        exactness,
                        cache,
                    )
                };
                let exact = PartsTolerance {
                    exact_below: f64::INFINITY,
                    slack: 0.0,
                };
                let d = query(exact, &mut cache);
                let pair = |i: usize, j: usize| {
                    brute_force_distance(
                        &Posed::new(&pa[i], 0.0, 0.0, ta),
                        &Posed::new(&pb[j], pos.x, pos.y, theta),
                    )
                    .distance
                };
                let least = (0..pa.len())
                    .flat_map(|i| (0..pb.len()).map(move |j| (i, j)))
                    .map(|(i, j)| pair(i, j))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    (d.distance - least).abs() <= 1e-9,
                    "{} against {least}",
                    d.distance
                );
                assert!((pair(d.parts.0, d.parts.1) - d.distance).abs() <= 1e-9);
                assert!(d.walks as usize <= pa.len() * pb.len());
                // With slack: a lower bound within it, never under the floor, exact below.
                let loose = PartsTolerance {
                    exact_below: rng.random_range(0.0..3.0),
                    slack: 0.5,
                };
                let l = query(loose, &mut cache).distance;
                assert!(
                    l <= least + 1e-9 && l >= least - loose.slack - 1e-9,
                    "{l} for {least}"
                );
                if least < loose.exact_below {
                    assert!((l - least).abs() <= 1e-9, "{l} for {least} below the floor");
                } else {
                    assert!(l >= loose.exact_below - 1e-12, "{l} under the floor");
                }
            }
        }
    }

    #[test]
    fn hull_holds_every_part_and_one_part_is_convex() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let parts: Vec<ConvexPolygon> = (0..6).map(|_| random_part(&mut rng)).collect();
        let body = Parts::new(parts.clone()).unwrap();
        let hull = body.hull();
        let n = hull.len();
        for p in &parts {
            for v in p.vertices() {
                for k in 0..n {
                    let (a, b) = (hull.vertices()[k], hull.vertices()[(k + 1) % n]);
                    assert!(crate::geometry::cross(&(b - a), &(v - a)) >= -1e-12);
                }
            }
        }
        let one = Parts::new(vec![parts[0].clone()]).unwrap();
        assert!(one.is_convex());
        assert_eq!(one.hull(), &parts[0]);
    }
}
