//! The validated convex polygon.

use super::segment::project_on_segment;
use super::{cross, Vec2};
use std::f64::consts::TAU;

/// Relative tolerance under which two vertices are the same point, or three are collinear
/// (sine of the turning angle). Far below any meaningful geometry, far above rounding.
const SHAPE_TOL: f64 = 1e-12;

/// Why a vertex list is not a usable convex polygon. Indices are those of the input list.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PolygonError {
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
    #[error("a polygon needs at least 3 distinct vertices, found {distinct}")]
    TooFewVertices {
        /// How many distinct vertices there are.
        distinct: usize,
    },
    /// The vertices enclose no area (all collinear).
    #[error("the vertices are collinear: the polygon has zero area")]
    ZeroArea,
    /// The polygon turns the wrong way at a vertex, or winds around more than once.
    #[error("not convex at vertex {vertex}")]
    NotConvex {
        /// Input index of the offending vertex.
        vertex: usize,
    },
}

/// A repair made while validating; the caller reports it (the CLI prints it on stderr).
#[derive(Clone, Debug, PartialEq)]
pub enum PolygonWarning {
    /// The vertices were clockwise and have been reversed.
    Reversed,
    /// A vertex repeating its predecessor was dropped (input index).
    RepeatedVertex(usize),
    /// A vertex on the straight line through its neighbours was dropped (input index).
    CollinearVertex(usize),
}

impl std::fmt::Display for PolygonWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PolygonWarning::Reversed => write!(f, "vertices were clockwise; reversed"),
            PolygonWarning::RepeatedVertex(i) => {
                write!(f, "vertex {i} repeats its predecessor; removed")
            }
            PolygonWarning::CollinearVertex(i) => {
                write!(f, "vertex {i} lies on the edge of its neighbours; removed")
            }
        }
    }
}

/// A strictly convex polygon with counter-clockwise vertices, in its own frame.
///
/// Invariants (established by [`ConvexPolygon::from_vertices`]): at least three vertices,
/// all finite, every turn strictly left, total turning exactly one revolution.
///
/// ```
/// use workcell::geometry::{ConvexPolygon, PolygonWarning};
/// // Clockwise input is accepted and reversed; the repair stays readable on the polygon.
/// let p = ConvexPolygon::from_vertices(&[[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]])?;
/// assert_eq!(p.len(), 4);
/// assert_eq!(p.warnings(), &[PolygonWarning::Reversed]);
/// # Ok::<(), workcell::geometry::PolygonError>(())
/// ```
#[derive(Clone, Debug)]
pub struct ConvexPolygon {
    vertices: Vec<Vec2>,
    normals: Vec<Vec2>,
    radius: f64,
    repair: Option<RepairShift>,
    /// The repairs that built it from its input (not part of equality: two builds of the
    /// same polygon are equal however their input was written).
    warnings: Vec<PolygonWarning>,
}

impl PartialEq for ConvexPolygon {
    fn eq(&self, other: &Self) -> bool {
        self.vertices == other.vertices
            && self.normals == other.normals
            && self.radius == other.radius
            && self.repair == other.repair
    }
}

/// How far the removal of repeated and collinear vertices moved the boundary: the input
/// vertex removed farthest from the polygon kept, and that distance (length units of the
/// shape). The tolerance that judged them is relative to the polygon's size, so on a
/// polygon 10¹¹·δ long it reaches δ: whoever knows δ refuses a shift that matters
/// (`cell::check_precision`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RepairShift {
    /// Input index of the removed vertex.
    pub vertex: usize,
    /// Its distance from the boundary of the polygon kept.
    pub distance: f64,
}

impl ConvexPolygon {
    /// Validates `points` (in order) and builds the polygon, with the repairs made on the
    /// way readable from [`ConvexPolygon::warnings`].
    ///
    /// Repeated and collinear vertices are removed and clockwise input is reversed. Errors
    /// name the offending input vertex.
    ///
    /// ```
    /// use workcell::geometry::{ConvexPolygon, PolygonError, PolygonWarning};
    /// let dart = ConvexPolygon::from_vertices(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [1.0, 0.5], [0.0, 2.0]]);
    /// assert_eq!(dart.unwrap_err(), PolygonError::NotConvex { vertex: 3 });
    /// let p = ConvexPolygon::from_vertices(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [1.0, 1.0]])?;
    /// assert_eq!(p.len(), 3);
    /// assert_eq!(p.warnings(), &[PolygonWarning::CollinearVertex(1)]);
    /// # Ok::<(), PolygonError>(())
    /// ```
    pub fn from_vertices(points: &[[f64; 2]]) -> Result<Self, PolygonError> {
        Self::new(points).map(|(polygon, _)| polygon)
    }

    /// A `width` × `height` rectangle centred on the origin of its frame, sides along the
    /// axes: the usual shape of a robot's footprint.
    ///
    /// ```
    /// use workcell::geometry::ConvexPolygon;
    /// let r = ConvexPolygon::rectangle(2.0, 1.0)?;
    /// assert_eq!(r.len(), 4);
    /// assert!((r.radius() - 1.25f64.sqrt()).abs() < 1e-15);
    /// assert!(ConvexPolygon::rectangle(0.0, 1.0).is_err());
    /// # Ok::<(), workcell::geometry::PolygonError>(())
    /// ```
    pub fn rectangle(width: f64, height: f64) -> Result<Self, PolygonError> {
        let (x, y) = (0.5 * width, 0.5 * height);
        Self::from_vertices(&[[-x, -y], [x, -y], [x, y], [-x, y]])
    }

    /// The repairs [`ConvexPolygon::from_vertices`] made to its input (empty for shapes made
    /// otherwise); the command line prints them as warnings.
    ///
    /// ```
    /// use workcell::geometry::{ConvexPolygon, PolygonWarning};
    /// let p = ConvexPolygon::from_vertices(&[[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 1.0]])?;
    /// assert_eq!(p.warnings(), &[PolygonWarning::RepeatedVertex(2)]);
    /// assert_eq!(p.warnings()[0].to_string(), "vertex 2 repeats its predecessor; removed");
    /// # Ok::<(), workcell::geometry::PolygonError>(())
    /// ```
    pub fn warnings(&self) -> &[PolygonWarning] {
        &self.warnings
    }

    /// [`ConvexPolygon::from_vertices`] with the repairs also returned beside the polygon.
    ///
    /// ```
    /// use workcell::geometry::ConvexPolygon;
    /// let (p, repairs) = ConvexPolygon::new(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])?;
    /// assert!(repairs.is_empty() && p.warnings().is_empty());
    /// let (p, repairs) = ConvexPolygon::new(&[[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]])?;
    /// assert_eq!(repairs, p.warnings());
    /// # Ok::<(), workcell::geometry::PolygonError>(())
    /// ```
    pub fn new(points: &[[f64; 2]]) -> Result<(Self, Vec<PolygonWarning>), PolygonError> {
        let mut warnings = Vec::new();
        let pts = Self::distinct(points, &mut warnings)?;
        let pts = Self::counter_clockwise(pts, &mut warnings)?;
        let pts = Self::without_collinear(pts, &mut warnings)?;
        Self::strictly_convex(&pts)?;
        let vertices: Vec<Vec2> = pts.into_iter().map(|(_, p)| p).collect();
        let mut polygon = Self::from_ccw(vertices);
        polygon.repair = Self::shift_of(&polygon.vertices, points, &warnings);
        polygon.warnings.clone_from(&warnings);
        Ok((polygon, warnings))
    }

    /// The finite points as (input index, point), consecutive repeats removed (cyclically);
    /// at least three.
    fn distinct(
        points: &[[f64; 2]],
        warnings: &mut Vec<PolygonWarning>,
    ) -> Result<Vec<(usize, Vec2)>, PolygonError> {
        for (i, p) in points.iter().enumerate() {
            if !p[0].is_finite() || !p[1].is_finite() {
                return Err(PolygonError::NotFinite {
                    vertex: i,
                    x: p[0],
                    y: p[1],
                });
            }
        }
        // Relative to the polygon's own size, not to its distance from the origin: far from
        // the origin, an absolute-scaled tolerance would merge distinct vertices.
        let first = points.first().map_or([0.0, 0.0], |p| *p);
        let size = points.iter().fold(0.0f64, |m, p| {
            m.max((p[0] - first[0]).abs()).max((p[1] - first[1]).abs())
        });
        let same_tol = SHAPE_TOL * size;
        let mut pts: Vec<(usize, Vec2)> = Vec::with_capacity(points.len());
        for (i, p) in points.iter().enumerate() {
            let v = Vec2::new(p[0], p[1]);
            if pts.last().is_some_and(|(_, q)| (v - q).amax() <= same_tol) {
                warnings.push(PolygonWarning::RepeatedVertex(i));
            } else {
                pts.push((i, v));
            }
        }
        while pts.len() > 1 && (pts[0].1 - pts[pts.len() - 1].1).amax() <= same_tol {
            let (i, _) = pts.pop().unwrap();
            warnings.push(PolygonWarning::RepeatedVertex(i));
        }
        if pts.len() < 3 {
            return Err(PolygonError::TooFewVertices {
                distinct: pts.len(),
            });
        }
        Ok(pts)
    }

    /// The points in counter-clockwise order (reversed if clockwise); a polygon without area
    /// is refused.
    fn counter_clockwise(
        mut pts: Vec<(usize, Vec2)>,
        warnings: &mut Vec<PolygonWarning>,
    ) -> Result<Vec<(usize, Vec2)>, PolygonError> {
        // Work relative to the first vertex so that far-away polygons keep their precision.
        let origin = pts[0].1;
        let area2: f64 = (0..pts.len())
            .map(|k| cross(&(pts[k].1 - origin), &(pts[(k + 1) % pts.len()].1 - origin)))
            .sum();
        let extent = pts
            .iter()
            .fold(0.0f64, |m, (_, p)| m.max((p - origin).norm()));
        if area2.abs() <= SHAPE_TOL * extent * extent {
            return Err(PolygonError::ZeroArea);
        }
        if area2 < 0.0 {
            pts.reverse();
            warnings.push(PolygonWarning::Reversed);
        }
        Ok(pts)
    }

    /// The points without the vertices where the boundary goes straight on, in one pass: a
    /// stack, then the seam between last and first.
    fn without_collinear(
        pts: Vec<(usize, Vec2)>,
        warnings: &mut Vec<PolygonWarning>,
    ) -> Result<Vec<(usize, Vec2)>, PolygonError> {
        let straight = |p: &Vec2, c: &Vec2, q: &Vec2| {
            let (sine, forward) = turn(p, c, q);
            sine.abs() <= SHAPE_TOL && forward
        };
        let mut kept: Vec<(usize, Vec2)> = Vec::with_capacity(pts.len());
        for p in pts {
            while kept.len() >= 2
                && straight(&kept[kept.len() - 2].1, &kept[kept.len() - 1].1, &p.1)
            {
                let (i, _) = kept.pop().unwrap();
                warnings.push(PolygonWarning::CollinearVertex(i));
            }
            kept.push(p);
        }
        loop {
            let n = kept.len();
            if n < 3 {
                return Err(PolygonError::ZeroArea);
            }
            let removed = if straight(&kept[n - 2].1, &kept[n - 1].1, &kept[0].1) {
                kept.pop().unwrap()
            } else if straight(&kept[n - 1].1, &kept[0].1, &kept[1].1) {
                kept.remove(0)
            } else {
                break;
            };
            warnings.push(PolygonWarning::CollinearVertex(removed.0));
        }
        Ok(kept)
    }

    /// Every turn strictly left, winding once: a reflex or cusp vertex, or a star polygon
    /// (which also turns only left but winds several times), is refused.
    fn strictly_convex(pts: &[(usize, Vec2)]) -> Result<(), PolygonError> {
        let n = pts.len();
        for k in 0..n {
            let (sine, _) = turn(&pts[(k + n - 1) % n].1, &pts[k].1, &pts[(k + 1) % n].1);
            if sine <= SHAPE_TOL {
                return Err(PolygonError::NotConvex { vertex: pts[k].0 });
            }
        }
        let turning: f64 = (0..n)
            .map(|k| {
                let e0 = pts[k].1 - pts[(k + n - 1) % n].1;
                let e1 = pts[(k + 1) % n].1 - pts[k].1;
                cross(&e0, &e1).atan2(e0.dot(&e1))
            })
            .sum();
        if turning > TAU * 1.5 {
            return Err(PolygonError::NotConvex { vertex: pts[0].0 });
        }
        Ok(())
    }

    /// The removed vertex farthest from the boundary of `kept`, if any was removed.
    fn shift_of(
        kept: &[Vec2],
        points: &[[f64; 2]],
        warnings: &[PolygonWarning],
    ) -> Option<RepairShift> {
        let n = kept.len();
        let from_boundary = |p: Vec2| {
            (0..n)
                .map(|k| {
                    let (a, b) = (kept[k], kept[(k + 1) % n]);
                    let s = project_on_segment(&p, &a, &b);
                    (a + (b - a) * s - p).norm()
                })
                .fold(f64::INFINITY, f64::min)
        };
        warnings
            .iter()
            .filter_map(|w| match w {
                PolygonWarning::RepeatedVertex(i) | PolygonWarning::CollinearVertex(i) => Some(*i),
                PolygonWarning::Reversed => None,
            })
            .map(|i| RepairShift {
                vertex: i,
                distance: from_boundary(Vec2::new(points[i][0], points[i][1])),
            })
            .max_by(|x, y| x.distance.total_cmp(&y.distance))
    }

    /// How far the repairs of [`ConvexPolygon::new`] moved the boundary, if it removed a
    /// vertex.
    pub fn repair_shift(&self) -> Option<RepairShift> {
        self.repair
    }

    /// Builds from vertices already known to be strictly convex and counter-clockwise.
    fn from_ccw(vertices: Vec<Vec2>) -> Self {
        let n = vertices.len();
        let normals = (0..n)
            .map(|i| {
                let e = vertices[(i + 1) % n] - vertices[i];
                Vec2::new(e.y, -e.x).normalize()
            })
            .collect();
        let radius = vertices.iter().fold(0.0f64, |m, v| m.max(v.norm()));
        ConvexPolygon {
            vertices,
            normals,
            radius,
            repair: None,
            warnings: Vec::new(),
        }
    }

    /// The same polygon with `offset` subtracted from every vertex: its frame origin moves to
    /// `offset`. Obstacles use it to centre their bounding disc on their own centroid.
    ///
    /// ```
    /// use workcell::geometry::{ConvexPolygon, Vec2};
    /// let world = ConvexPolygon::from_vertices(&[[4.0, 2.0], [6.0, 2.0], [6.0, 4.0], [4.0, 4.0]])?;
    /// let centred = world.translated(&world.centroid());
    /// assert_eq!(centred.centroid(), Vec2::new(0.0, 0.0));
    /// assert_eq!(centred.vertices()[0], Vec2::new(-1.0, -1.0));
    /// # Ok::<(), workcell::geometry::PolygonError>(())
    /// ```
    pub fn translated(&self, offset: &Vec2) -> Self {
        Self {
            repair: self.repair,
            warnings: self.warnings.clone(),
            ..Self::from_ccw(self.vertices.iter().map(|v| v - offset).collect())
        }
    }

    /// Area centroid.
    pub fn centroid(&self) -> Vec2 {
        let o = self.vertices[0];
        let (mut a, mut c) = (0.0, Vec2::zeros());
        for i in 1..self.len() - 1 {
            let (p, q) = (self.vertices[i] - o, self.vertices[i + 1] - o);
            let w = cross(&p, &q);
            a += w;
            c += (p + q) * w;
        }
        o + c / (3.0 * a)
    }

    /// Area (positive: the vertices are counter-clockwise).
    ///
    /// ```
    /// use workcell::geometry::ConvexPolygon;
    /// assert_eq!(ConvexPolygon::rectangle(2.0, 3.0)?.area(), 6.0);
    /// # Ok::<(), workcell::geometry::PolygonError>(())
    /// ```
    pub fn area(&self) -> f64 {
        let o = self.vertices[0];
        let twice: f64 = (1..self.len() - 1)
            .map(|i| cross(&(self.vertices[i] - o), &(self.vertices[i + 1] - o)))
            .sum();
        0.5 * twice
    }

    /// Counter-clockwise vertices, in the polygon's frame.
    #[inline]
    pub fn vertices(&self) -> &[Vec2] {
        &self.vertices
    }

    /// Unit outward normal of each edge `i` (vertex `i` to vertex `i + 1`).
    #[inline]
    pub fn normals(&self) -> &[Vec2] {
        &self.normals
    }

    /// Number of vertices.
    #[inline]
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// Always false: a validated polygon has at least three vertices.
    #[inline]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Rmax of the paper's eq. (13): the largest distance from the frame origin to a vertex,
    /// so the disc of this radius about the origin contains the polygon in every rotation.
    #[inline]
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The polygon's least width: the narrowest gap between two parallel lines that hold it
    /// (attained with one line along an edge), the narrowest passage it can slide through.
    ///
    /// ```
    /// use workcell::geometry::ConvexPolygon;
    /// let plank = ConvexPolygon::rectangle(3.0, 0.5)?;
    /// assert!((plank.min_width() - 0.5).abs() < 1e-12);
    /// let triangle = ConvexPolygon::from_vertices(&[[0.0, 0.0], [2.0, 0.0], [0.0, 1.0]])?;
    /// assert!((triangle.min_width() - 2.0 / 5f64.sqrt()).abs() < 1e-12); // to the hypotenuse
    /// # Ok::<(), workcell::geometry::PolygonError>(())
    /// ```
    pub fn min_width(&self) -> f64 {
        let v = &self.vertices;
        (0..v.len())
            .map(|i| {
                let n = &self.normals[i];
                v.iter().map(|p| (v[i] - p).dot(n)).fold(0.0, f64::max)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Distance from point `p` to the polygon in its own frame: 0 inside or on it.
    ///
    /// ```
    /// use workcell::geometry::{ConvexPolygon, Vec2};
    /// let square = ConvexPolygon::rectangle(2.0, 2.0)?; // corners at (±1, ±1)
    /// assert_eq!(square.distance_to(&Vec2::new(0.5, 0.0)), 0.0);
    /// assert!((square.distance_to(&Vec2::new(3.0, 0.0)) - 2.0).abs() < 1e-12);
    /// assert!((square.distance_to(&Vec2::new(4.0, 5.0)) - 5.0).abs() < 1e-12); // to the corner
    /// # Ok::<(), workcell::geometry::PolygonError>(())
    /// ```
    pub fn distance_to(&self, p: &Vec2) -> f64 {
        let v = &self.vertices;
        let n = v.len();
        let mut inside = true;
        let mut best = f64::INFINITY;
        for i in 0..n {
            let (a, b) = (v[i], v[(i + 1) % n]);
            // Counter-clockwise: inside is left of every edge.
            inside &= cross(&(b - a), &(p - a)) >= 0.0;
            let u = project_on_segment(p, &a, &b);
            best = best.min((a + (b - a) * u - p).norm());
        }
        if inside {
            0.0
        } else {
            best
        }
    }
}

/// The turn at `c` between edges `p → c` and `c → q`: its sine (left positive) and whether
/// the edges run forwards (rather than doubling back).
fn turn(p: &Vec2, c: &Vec2, q: &Vec2) -> (f64, bool) {
    let (e0, e1) = (c - p, q - c);
    (cross(&e0, &e1) / (e0.norm() * e1.norm()), e0.dot(&e1) > 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_is_accepted_without_warnings() {
        let (p, w) = ConvexPolygon::new(&[[0., 0.], [1., 0.], [1., 1.], [0., 1.]]).unwrap();
        assert_eq!(p.len(), 4);
        assert!(w.is_empty());
        assert!((p.centroid() - Vec2::new(0.5, 0.5)).norm() < 1e-15);
        assert!((p.radius() - 2f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn clockwise_repeated_and_collinear_are_repaired() {
        let (p, w) =
            ConvexPolygon::new(&[[0., 0.], [0., 1.], [0., 1.], [1., 1.], [1., 0.5], [1., 0.]])
                .unwrap();
        assert_eq!(p.len(), 4);
        assert!(w.contains(&PolygonWarning::Reversed));
        assert!(w.contains(&PolygonWarning::RepeatedVertex(2)));
        assert!(w.contains(&PolygonWarning::CollinearVertex(4)));
    }

    #[test]
    fn bad_polygons_are_refused_with_the_vertex() {
        assert!(matches!(
            ConvexPolygon::new(&[[0., 0.], [f64::NAN, 0.], [0., 1.]]),
            Err(PolygonError::NotFinite { vertex: 1, .. })
        ));
        assert_eq!(
            ConvexPolygon::new(&[[0., 0.], [1., 0.], [1., 0.]]).unwrap_err(),
            PolygonError::TooFewVertices { distinct: 2 }
        );
        assert_eq!(
            ConvexPolygon::new(&[[0., 0.], [1., 0.], [2., 0.]]).unwrap_err(),
            PolygonError::ZeroArea
        );
        assert_eq!(
            ConvexPolygon::new(&[[0., 0.], [2., 0.], [1., 0.5], [2., 2.], [0., 2.]]).unwrap_err(),
            PolygonError::NotConvex { vertex: 2 }
        );
        // A pentagram turns left at every vertex but winds twice.
        let star: Vec<[f64; 2]> = (0..5)
            .map(|k| {
                let a = k as f64 * 4.0 * std::f64::consts::PI / 5.0;
                [a.cos(), a.sin()]
            })
            .collect();
        assert!(matches!(
            ConvexPolygon::new(&star),
            Err(PolygonError::NotConvex { .. })
        ));
    }
}
