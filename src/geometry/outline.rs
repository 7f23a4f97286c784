//! A simple polygon, convex or not, validated with exact predicates and cut into convex
//! parts (Hertel & Mehlhorn 1983: an ear-clipping triangulation, then every diagonal removed
//! whose removal leaves both sides convex: at most four times the fewest convex parts).
//!
//! Exactness matters twice here: whether the outline is simple (two edges that cross make
//! the region ambiguous), and whether the parts cover exactly its region (a sliver lost or
//! invented is a contact missed or invented). Both rest on Shewchuk's exact orientation
//! predicate (`robust::orient2d`), never on a tolerance.

use super::{ConvexPolygon, PolygonWarning, Vec2};
use std::collections::HashMap;
#[cfg(test)]
use std::f64::consts::TAU;

/// Why a vertex list is not a usable outline. Indices are those of the input list; edge `k`
/// runs from vertex `k` to the next kept vertex.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum OutlineError {
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate ({x}, {y})")]
    NotFinite {
        /// Input index.
        vertex: usize,
        /// Its x.
        x: f64,
        /// Its y.
        y: f64,
    },
    /// Fewer than three distinct vertices remain.
    #[error("an outline needs at least 3 distinct vertices, found {distinct}")]
    TooFewVertices {
        /// How many distinct vertices there are.
        distinct: usize,
    },
    /// The outline encloses no area.
    #[error("the outline encloses no area")]
    ZeroArea,
    /// The outline doubles back on itself at a vertex (a needle of zero width).
    #[error("the outline doubles back at vertex {vertex} (collinear with its neighbours, not between them)")]
    DoublesBack {
        /// Input index of the vertex.
        vertex: usize,
    },
    /// Two edges that are not neighbours meet (cross, touch or overlap), or a vertex
    /// repeats a vertex that is not its neighbour: the outline is not simple.
    #[error("edges {first} and {second} cross (edge k runs from vertex k to the next): the outline must not touch itself")]
    Crossing {
        /// The edge that comes first.
        first: usize,
        /// The other edge.
        second: usize,
    },
    /// A convex part cut from the outline is too thin to be a polygon (its area vanishes
    /// against its size in f64): the outline has a sliver there.
    #[error(
        "the outline is too thin near vertex {vertex} to be cut into convex parts of positive area"
    )]
    Sliver {
        /// Input index of a vertex of the thin part.
        vertex: usize,
    },
}

/// A validated simple polygon, counter-clockwise, with no repeated or straight vertices.
#[derive(Clone, Debug, PartialEq)]
pub struct Outline {
    vertices: Vec<Vec2>,
    /// The input index of each vertex kept.
    input: Vec<usize>,
    /// The repairs that built it (as for a convex shape: reversed, repeated and straight
    /// vertices dropped), reported by the caller.
    warnings: Vec<PolygonWarning>,
}

fn orient(a: &Vec2, b: &Vec2, c: &Vec2) -> f64 {
    let at = |p: &Vec2| robust::Coord { x: p.x, y: p.y };
    robust::orient2d(at(a), at(b), at(c))
}

/// Whether `p`, known collinear with segment `ab`, lies within its bounding box.
fn within(a: &Vec2, b: &Vec2, p: &Vec2) -> bool {
    a.x.min(b.x) <= p.x && p.x <= a.x.max(b.x) && a.y.min(b.y) <= p.y && p.y <= a.y.max(b.y)
}

/// Whether the closed segments `ab` and `cd` share a point (exactly).
fn segments_meet(a: &Vec2, b: &Vec2, c: &Vec2, d: &Vec2) -> bool {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return true;
    }
    (o1 == 0.0 && within(a, b, c))
        || (o2 == 0.0 && within(a, b, d))
        || (o3 == 0.0 && within(c, d, a))
        || (o4 == 0.0 && within(c, d, b))
}

impl Outline {
    /// Validates `points` as a simple polygon. Exactly repeated consecutive vertices and
    /// vertices on the straight line between their neighbours are dropped, clockwise input
    /// is reversed (each a warning, as for a convex shape); a vertex where the outline
    /// doubles back, edges that meet other than at a shared vertex, and no area are errors.
    ///
    /// ```
    /// use workcell::geometry::{Outline, OutlineError};
    /// let l = Outline::new(&[[0.0, 0.0], [4.0, 0.0], [4.0, 1.0], [1.0, 1.0], [1.0, 3.0], [0.0, 3.0]])?;
    /// assert_eq!(l.len(), 6);
    /// let bow_tie = Outline::new(&[[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]]);
    /// assert_eq!(bow_tie.unwrap_err(), OutlineError::Crossing { first: 0, second: 2 });
    /// # Ok::<(), OutlineError>(())
    /// ```
    pub fn new(points: &[[f64; 2]]) -> Result<Self, OutlineError> {
        for (i, p) in points.iter().enumerate() {
            if !p[0].is_finite() || !p[1].is_finite() {
                return Err(OutlineError::NotFinite {
                    vertex: i,
                    x: p[0],
                    y: p[1],
                });
            }
        }
        let mut warnings = Vec::new();
        let mut pts: Vec<(usize, Vec2)> = Vec::with_capacity(points.len());
        for (i, p) in points.iter().enumerate() {
            let v = Vec2::new(p[0], p[1]);
            if pts.last().is_some_and(|(_, q)| *q == v) {
                warnings.push(PolygonWarning::RepeatedVertex(i));
            } else {
                pts.push((i, v));
            }
        }
        while pts.len() > 1 && pts[0].1 == pts[pts.len() - 1].1 {
            let (i, _) = pts.pop().expect("more than one");
            warnings.push(PolygonWarning::RepeatedVertex(i));
        }
        if pts.len() < 3 {
            return Err(OutlineError::TooFewVertices {
                distinct: pts.len(),
            });
        }
        drop_straight(&mut pts, &mut warnings)?;
        check_simple(&pts)?;
        // Twice the signed area, relative to the first vertex (exact sign is not needed:
        // a simple polygon's area is far from zero unless it has none, refused above).
        let o = pts[0].1;
        let n = pts.len();
        let area2: f64 = (0..n)
            .map(|k| super::cross(&(pts[k].1 - o), &(pts[(k + 1) % n].1 - o)))
            .sum();
        if area2 == 0.0 {
            return Err(OutlineError::ZeroArea);
        }
        if area2 < 0.0 {
            pts.reverse();
            warnings.push(PolygonWarning::Reversed);
        }
        Ok(Outline {
            vertices: pts.iter().map(|(_, v)| *v).collect(),
            input: pts.iter().map(|(i, _)| *i).collect(),
            warnings,
        })
    }

    /// The vertices, counter-clockwise.
    pub fn vertices(&self) -> &[Vec2] {
        &self.vertices
    }

    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// Always false: an outline has at least three vertices.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The repairs made to the input.
    pub fn warnings(&self) -> &[PolygonWarning] {
        &self.warnings
    }

    /// Twice the enclosed area.
    pub fn area2(&self) -> f64 {
        let v = &self.vertices;
        let n = v.len();
        (0..n)
            .map(|k| super::cross(&(v[k] - v[0]), &(v[(k + 1) % n] - v[0])))
            .sum()
    }

    /// The outline cut into convex parts whose union is exactly its region, parts meeting
    /// only along shared diagonals (Hertel–Mehlhorn). One part when it is convex.
    ///
    /// ```
    /// use workcell::geometry::Outline;
    /// let u = Outline::new(&[[0.0, 0.0], [3.0, 0.0], [3.0, 3.0], [2.0, 3.0], [2.0, 1.0], [1.0, 1.0], [1.0, 3.0], [0.0, 3.0]])?;
    /// let parts = u.convex_parts()?;
    /// assert_eq!(parts.len(), 3);
    /// let area: f64 = parts.iter().map(|p| p.area()).sum();
    /// assert_eq!(area, 7.0);
    /// # Ok::<(), workcell::geometry::OutlineError>(())
    /// ```
    pub fn convex_parts(&self) -> Result<Vec<ConvexPolygon>, OutlineError> {
        let v = &self.vertices;
        let (triangles, diagonals) = ear_clip(v);
        let mut parts: Vec<Option<Vec<usize>>> = triangles.into_iter().map(Some).collect();
        // Which part each triangle now belongs to (a merge points the absorbed part here).
        let mut owner: Vec<usize> = (0..parts.len()).collect();
        fn find(owner: &mut [usize], mut k: usize) -> usize {
            while owner[k] != k {
                owner[k] = owner[owner[k]];
                k = owner[k];
            }
            k
        }
        for (a, b, left, right) in diagonals {
            let (p, q) = (find(&mut owner, left), find(&mut owner, right));
            if let Some(merged) = merge_if_convex(v, parts[p].as_ref(), parts[q].as_ref(), a, b) {
                parts[p] = Some(merged);
                parts[q] = None;
                owner[q] = p;
            }
        }
        let parts: Vec<ConvexPolygon> = parts
            .into_iter()
            .flatten()
            .map(|ids| {
                convex_part(v, &ids).ok_or(OutlineError::Sliver {
                    vertex: self.input[ids[0]],
                })
            })
            .collect::<Result<_, _>>()?;
        // The parts tile the region: their areas add up to its own. A shortfall would be a
        // triangulation that stopped early (unreachable under exact predicates).
        let (whole, sum) = (
            self.area2(),
            parts.iter().map(|p| 2.0 * p.area()).sum::<f64>(),
        );
        if (whole - sum).abs() > 1e-9 * whole {
            return Err(OutlineError::Sliver {
                vertex: self.input[0],
            });
        }
        Ok(parts)
    }
}

/// Drops the vertices on the straight line between their neighbours (a warning each); a
/// vertex collinear with its neighbours but not between them is a needle: an error.
fn drop_straight(
    pts: &mut Vec<(usize, Vec2)>,
    warnings: &mut Vec<PolygonWarning>,
) -> Result<(), OutlineError> {
    let (a, b) = (pts[0].1, pts[1].1);
    if pts.iter().all(|(_, p)| orient(&a, &b, p) == 0.0) {
        return Err(OutlineError::ZeroArea);
    }
    let mut k = 0;
    let mut unchanged = 0;
    // Cyclic: a removal can make the previous vertex straight; stop after a full lap
    // without one.
    while unchanged < pts.len() {
        if pts.len() < 3 {
            return Err(OutlineError::ZeroArea);
        }
        let n = pts.len();
        k %= n;
        let (p, c, q) = (pts[(k + n - 1) % n].1, pts[k].1, pts[(k + 1) % n].1);
        if orient(&p, &c, &q) == 0.0 {
            if (c - p).dot(&(q - c)) > 0.0 {
                warnings.push(PolygonWarning::CollinearVertex(pts[k].0));
                pts.remove(k);
                k = (k + n - 2) % (n - 1);
                unchanged = 0;
                continue;
            }
            return Err(OutlineError::DoublesBack { vertex: pts[k].0 });
        }
        k += 1;
        unchanged += 1;
    }
    Ok(())
}

/// Every two edges that are not neighbours are disjoint (exactly), and no vertex repeats.
fn check_simple(pts: &[(usize, Vec2)]) -> Result<(), OutlineError> {
    let n = pts.len();
    let edge = |k: usize| (pts[k].1, pts[(k + 1) % n].1);
    // Bounding boxes first: O(n²) box tests, exact predicates only where boxes meet.
    let boxes: Vec<[f64; 4]> = (0..n)
        .map(|k| {
            let (a, b) = edge(k);
            [a.x.min(b.x), a.y.min(b.y), a.x.max(b.x), a.y.max(b.y)]
        })
        .collect();
    for i in 0..n {
        for j in i + 1..n {
            let neighbours = j == i + 1 || (i == 0 && j == n - 1);
            let (bi, bj) = (boxes[i], boxes[j]);
            if neighbours || bi[0] > bj[2] || bj[0] > bi[2] || bi[1] > bj[3] || bj[1] > bi[3] {
                continue;
            }
            let ((a, b), (c, d)) = (edge(i), edge(j));
            if segments_meet(&a, &b, &c, &d) {
                return Err(OutlineError::Crossing {
                    first: pts[i].0,
                    second: pts[j].0,
                });
            }
        }
    }
    // Neighbouring edges meet only at their shared vertex: they could overlap only by
    // doubling back, refused by `drop_straight`; the closing vertex of a triangle repeated
    // is caught as two edges meeting.
    Ok(())
}

/// A diagonal `(a, b)` of a triangulation and the triangle on each side of it.
type Diagonal = (usize, usize, usize, usize);

/// An ear-clipping triangulation of the simple counter-clockwise polygon `v`: triangles as
/// vertex indices (counter-clockwise) and the diagonals `(a, b, one triangle, the other)`.
///
/// An ear is a convex vertex whose triangle holds no other vertex of the remaining polygon,
/// on its boundary included; a vertex exactly straight between its neighbours in the
/// remaining polygon is cut away with no triangle (it lies on the new edge, which loses no
/// area). By the two-ears theorem and exact predicates an ear always exists.
fn ear_clip(v: &[Vec2]) -> (Vec<Vec<usize>>, Vec<Diagonal>) {
    let mut ring: Vec<usize> = (0..v.len()).collect();
    let mut triangles: Vec<Vec<usize>> = Vec::new();
    let mut diagonals = Vec::new();
    // A diagonal made by an ear, waiting for the triangle on its other side.
    let mut open: HashMap<(usize, usize), usize> = HashMap::new();
    let key = |a: usize, b: usize| (a.min(b), a.max(b));
    let mut k = 0;
    let mut misses = 0;
    while ring.len() > 3 {
        let n = ring.len();
        let (ip, ic, iq) = (ring[(k + n - 1) % n], ring[k % n], ring[(k + 1) % n]);
        let turn = orient(&v[ip], &v[ic], &v[iq]);
        let straight = turn == 0.0;
        let ear = turn > 0.0
            && ring.iter().all(|&j| {
                j == ip || j == ic || j == iq || {
                    let p = &v[j];
                    // Inside or on the triangle: never an ear.
                    !(orient(&v[ip], &v[ic], p) >= 0.0
                        && orient(&v[ic], &v[iq], p) >= 0.0
                        && orient(&v[iq], &v[ip], p) >= 0.0)
                }
            });
        if ear {
            let t = triangles.len();
            triangles.push(vec![ip, ic, iq]);
            for (a, b) in [(ip, ic), (ic, iq)] {
                if let Some(other) = open.remove(&key(a, b)) {
                    diagonals.push((a, b, other, t));
                }
            }
            open.insert(key(ip, iq), t);
        } else if straight && misses >= n {
            // No ear in a whole lap (never seen: the two-ears theorem promises one), but a
            // vertex straight between its neighbours: cutting it away loses no area. The
            // diagonals on its sides stay unmerged.
            open.remove(&key(ip, ic));
            open.remove(&key(ic, iq));
        } else {
            k = (k + 1) % n;
            misses += 1;
            if misses > 2 * n {
                // Unreachable for a simple polygon under exact predicates; the caller
                // refuses a partition whose area falls short rather than panicking here.
                break;
            }
            continue;
        }
        ring.remove(k % n);
        k = (k % n + n - 2) % (n - 1);
        misses = 0;
    }
    let t = triangles.len();
    let (a, b, c) = (ring[0], ring[1], ring[2]);
    if ring.len() == 3 && orient(&v[a], &v[b], &v[c]) > 0.0 {
        triangles.push(vec![a, b, c]);
        for (x, y) in [(a, b), (b, c), (c, a)] {
            if let Some(other) = open.remove(&key(x, y)) {
                diagonals.push((x, y, other, t));
            }
        }
    }
    (triangles, diagonals)
}

/// The union of convex parts `p` and `q` that share the diagonal `(a, b)`, when it is
/// convex at both ends of the diagonal (elsewhere it is convex already).
fn merge_if_convex(
    v: &[Vec2],
    p: Option<&Vec<usize>>,
    q: Option<&Vec<usize>>,
    a: usize,
    b: usize,
) -> Option<Vec<usize>> {
    let (p, q) = (p?, q?);
    // Rotate each so that the shared edge comes last: p ends … u, v and q ends … v, u.
    let rotated = |poly: &Vec<usize>, from: usize, to: usize| -> Option<Vec<usize>> {
        let n = poly.len();
        let i = (0..n).find(|&i| poly[i] == from && poly[(i + 1) % n] == to)?;
        Some((0..n).map(|k| poly[(i + 2 + k) % n]).collect())
    };
    let (p, q) = match (rotated(p, a, b), rotated(q, b, a)) {
        (Some(p), Some(q)) => (p, q),
        _ => (rotated(p, b, a)?, rotated(q, a, b)?),
    };
    // p = [x0 … u, v] with the edge u → v; q = [y0 … v, u] with v → u.
    let (u, w) = (p[p.len() - 2], p[p.len() - 1]);
    let merged: Vec<usize> = p[..p.len() - 1]
        .iter()
        .chain(&q[..q.len() - 1])
        .copied()
        .collect();
    let n = merged.len();
    let convex_at = |x: usize| {
        let i = merged
            .iter()
            .position(|&m| m == x)
            .expect("an end of the diagonal");
        orient(&v[merged[(i + n - 1) % n]], &v[x], &v[merged[(i + 1) % n]]) >= 0.0
    };
    (convex_at(u) && convex_at(w)).then_some(merged)
}

/// A part's polygon, with the vertices exactly straight between their neighbours left out
/// (a merge across a diagonal can leave one); `None` for a sliver that is no polygon in f64.
fn convex_part(v: &[Vec2], ids: &[usize]) -> Option<ConvexPolygon> {
    let n = ids.len();
    let corners: Vec<[f64; 2]> = (0..n)
        .filter(|&k| orient(&v[ids[(k + n - 1) % n]], &v[ids[k]], &v[ids[(k + 1) % n]]) != 0.0)
        .map(|k| [v[ids[k]].x, v[ids[k]].y])
        .collect();
    ConvexPolygon::from_vertices(&corners).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Even-odd rule with exact orientations: whether `p` is inside the outline `v`.
    fn inside_outline(v: &[Vec2], p: &Vec2) -> bool {
        let n = v.len();
        let mut inside = false;
        for k in 0..n {
            let (a, b) = (v[k], v[(k + 1) % n]);
            if (a.y > p.y) != (b.y > p.y) {
                // The edge crosses the horizontal line through p: left of it when the
                // orientation has the edge's upward sign.
                let o = orient(&a, &b, p);
                if (o > 0.0) == (b.y > a.y) {
                    inside = !inside;
                }
            }
        }
        inside
    }

    fn inside_part(part: &ConvexPolygon, p: &Vec2) -> bool {
        let v = part.vertices();
        (0..v.len()).all(|k| orient(&v[k], &v[(k + 1) % v.len()], p) >= 0.0)
    }

    /// The parts cover the outline's region exactly: same area, and every sampled point is
    /// in the outline exactly when it is in some part; parts overlap nowhere but along
    /// their edges.
    fn assert_exact_cover(points: &[[f64; 2]], seed: u64) -> usize {
        let outline = Outline::new(points).expect("a valid outline");
        let parts = outline.convex_parts().expect("a partition");
        let area: f64 = parts.iter().map(|p| p.area()).sum();
        let whole = 0.5 * outline.area2();
        assert!(
            (area - whole).abs() <= 1e-12 * whole,
            "area {area} against {whole}"
        );
        let v = outline.vertices();
        let (lo, hi) = v.iter().fold(
            (Vec2::repeat(f64::INFINITY), Vec2::repeat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.inf(p), hi.sup(p)),
        );
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for _ in 0..4000 {
            let p = Vec2::new(rng.random_range(lo.x..hi.x), rng.random_range(lo.y..hi.y));
            let holders = parts.iter().filter(|q| inside_part(q, &p)).count();
            assert_eq!(inside_outline(v, &p), holders > 0, "at {p:?}");
            assert!(holders <= 1, "{p:?} in {holders} parts");
        }
        parts.len()
    }

    #[test]
    fn l_and_u_shapes_are_cut_exactly() {
        let l = [
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 1.0],
            [1.0, 1.0],
            [1.0, 3.0],
            [0.0, 3.0],
        ];
        assert_eq!(assert_exact_cover(&l, 1), 2);
        let u = [
            [0.0, 0.0],
            [3.0, 0.0],
            [3.0, 3.0],
            [2.0, 3.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 3.0],
            [0.0, 3.0],
        ];
        assert_eq!(assert_exact_cover(&u, 2), 3);
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(assert_exact_cover(&square, 3), 1);
    }

    /// Star-shaped outlines (simple by construction) of 5 to 60 vertices, spiky or round,
    /// some far from the origin: exact cover, and Hertel–Mehlhorn's bound of at most four
    /// times the fewest parts, which is at least ⌈reflex/2⌉ + 1 … checked as parts ≤ n − 2.
    #[test]
    fn random_star_outlines_are_cut_exactly() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for case in 0..300 {
            let n = rng.random_range(5..60);
            let offset = if case % 3 == 0 { 1e5 } else { 0.0 };
            let mut angles: Vec<f64> = (0..n).map(|_| rng.random_range(0.0..TAU)).collect();
            angles.sort_by(f64::total_cmp);
            angles.dedup();
            let points: Vec<[f64; 2]> = angles
                .iter()
                .map(|&a| {
                    let r = rng.random_range(0.2..2.0);
                    [offset + r * a.cos(), offset + r * a.sin()]
                })
                .collect();
            let Ok(outline) = Outline::new(&points) else {
                continue; // a rare star whose three vertices line up
            };
            let parts = assert_exact_cover(&points, case);
            let reflex = (0..outline.len())
                .filter(|&k| {
                    let v = outline.vertices();
                    let n = v.len();
                    orient(&v[(k + n - 1) % n], &v[k], &v[(k + 1) % n]) < 0.0
                })
                .count();
            // Hertel–Mehlhorn keeps at most 2r + 1 parts for r reflex vertices.
            assert!(
                parts <= 2 * reflex + 1,
                "{parts} parts for {reflex} reflex vertices"
            );
        }
    }

    /// A comb: many teeth, every notch a reflex pair.
    #[test]
    fn combs_are_cut_exactly() {
        let mut points = vec![[0.0, 0.0], [20.0, 0.0], [20.0, 2.0]];
        for k in (0..10).rev() {
            let x = 2.0 * k as f64;
            points.extend([
                [x + 1.5, 2.0],
                [x + 1.5, 5.0],
                [x + 0.5, 5.0],
                [x + 0.5, 2.0],
            ]);
        }
        points.push([0.0, 2.0]);
        let parts = assert_exact_cover(&points, 11);
        assert!(parts <= 21, "{parts}");
    }

    #[test]
    fn clockwise_repeated_and_straight_vertices_are_repaired() {
        let o = Outline::new(&[
            [0.0, 0.0],
            [0.0, 3.0],
            [1.0, 3.0],
            [1.0, 1.0],
            [1.0, 1.0],
            [2.0, 1.0],
            [4.0, 1.0],
            [4.0, 0.0],
        ])
        .unwrap();
        assert_eq!(o.len(), 6);
        assert_eq!(
            o.warnings(),
            &[
                PolygonWarning::RepeatedVertex(4),
                PolygonWarning::CollinearVertex(5),
                PolygonWarning::Reversed
            ]
        );
    }

    #[test]
    fn bad_outlines_are_refused_naming_what() {
        let err = |pts: &[[f64; 2]]| Outline::new(pts).unwrap_err();
        // Vertex 3 lies on edge 0: edges 0 and 2 (which ends there) meet at (1, 0).
        let touching = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [1.0, 0.0], [0.0, 2.0]];
        assert_eq!(
            err(&touching),
            OutlineError::Crossing {
                first: 0,
                second: 2
            }
        );
        // The same point twice, not consecutively: a figure eight.
        let eight = [
            [0.0, 0.0],
            [1.0, 1.0],
            [2.0, 0.0],
            [2.0, 2.0],
            [1.0, 1.0],
            [0.0, 2.0],
        ];
        assert!(matches!(err(&eight), OutlineError::Crossing { .. }));
        let needle = [
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [3.0, 1.0],
            [2.0, 1.0],
            [0.0, 1.0],
        ];
        assert!(matches!(err(&needle), OutlineError::DoublesBack { .. }));
        assert_eq!(
            err(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]),
            OutlineError::ZeroArea
        );
        assert_eq!(
            err(&[[0.0, 0.0], [1.0, 1.0], [1.0, 1.0]]),
            OutlineError::TooFewVertices { distinct: 2 }
        );
        assert!(matches!(
            err(&[[0.0, 0.0], [f64::NAN, 1.0], [1.0, 0.0]]),
            OutlineError::NotFinite { vertex: 1, .. }
        ));
        assert_eq!(
            err(&[[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]]).to_string(),
            "edges 0 and 2 cross (edge k runs from vertex k to the next): the outline must not touch itself"
        );
    }
}
