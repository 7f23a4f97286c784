//! A convex polygon placed in the plane by a rotation and a translation.

use super::{ConvexPolygon, Vec2};
use nalgebra::{Isometry2, Point2};

/// A polygon in world position: world vertex = R(θ)·P + G (the paper's eq. 2).
///
/// Vertices and normals are transformed on demand, so a closest-feature walk that visits
/// k features costs O(k), not O(n).
#[derive(Clone, Copy, Debug)]
pub struct Posed<'a> {
    /// The polygon in its body frame.
    pub shape: &'a ConvexPolygon,
    /// Body frame to world frame.
    pub iso: Isometry2<f64>,
}

impl<'a> Posed<'a> {
    /// Places `shape` with its body origin at `(x, y)`, rotated by `theta` radians.
    ///
    /// ```
    /// use workcell::geometry::{ConvexPolygon, Posed, Vec2};
    /// let bar = ConvexPolygon::from_vertices(&[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]])?;
    /// let placed = Posed::new(&bar, 10.0, 0.0, std::f64::consts::FRAC_PI_2); // a quarter turn
    /// assert_eq!(placed.center(), Vec2::new(10.0, 0.0));
    /// assert!((placed.vertex(1) - Vec2::new(10.0, 2.0)).norm() < 1e-12); // (2, 0) turned to (0, 2)
    /// # Ok::<(), workcell::geometry::PolygonError>(())
    /// ```
    pub fn new(shape: &'a ConvexPolygon, x: f64, y: f64, theta: f64) -> Self {
        Posed {
            shape,
            iso: Isometry2::new(Vec2::new(x, y), theta),
        }
    }

    /// Number of vertices (and of edges).
    #[inline]
    pub fn len(&self) -> usize {
        self.shape.len()
    }

    /// Always false: a validated polygon has at least three vertices.
    #[inline]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Index of the vertex after `i`.
    #[inline]
    pub fn next(&self, i: usize) -> usize {
        if i + 1 == self.len() {
            0
        } else {
            i + 1
        }
    }

    /// Index of the vertex before `i`.
    #[inline]
    pub fn prev(&self, i: usize) -> usize {
        if i == 0 {
            self.len() - 1
        } else {
            i - 1
        }
    }

    /// Vertex `i` in the world frame.
    #[inline]
    pub fn vertex(&self, i: usize) -> Vec2 {
        (self.iso * Point2::from(self.shape.vertices()[i])).coords
    }

    /// Unit outward normal of edge `i` in the world frame.
    #[inline]
    pub fn normal(&self, i: usize) -> Vec2 {
        self.iso.rotation * self.shape.normals()[i]
    }

    /// Centre of the bounding disc (the body origin) in the world frame.
    #[inline]
    pub fn center(&self) -> Vec2 {
        self.iso.translation.vector
    }
}
