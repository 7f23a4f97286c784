//! Features of a convex polygon (its vertices and its edges), and what a distance query
//! between two polygons answers: the distance, the closest points and features.

use super::Vec2;

/// A feature of a convex polygon with `n` vertices.
///
/// `Edge(i)` runs from vertex `i` to vertex `(i + 1) % n`, counter-clockwise.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Feature {
    /// The vertex of that index.
    Vertex(usize),
    /// The edge from that vertex to the next one.
    Edge(usize),
}

/// The closest features of polygons A and B: what the walk returns and is warm-started from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FeaturePair {
    /// Feature of the first polygon.
    pub a: Feature,
    /// Feature of the second polygon.
    pub b: Feature,
}

impl FeaturePair {
    /// The same pair seen from the other polygon.
    pub fn swapped(self) -> Self {
        FeaturePair {
            a: self.b,
            b: self.a,
        }
    }
}

/// Result of a distance query between polygons A and B.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Distance {
    /// Euclidean distance; 0 when the polygons touch or overlap.
    pub distance: f64,
    /// Closest point on A (world frame); on overlap, a point near the contact.
    pub point_a: Vec2,
    /// Closest point on B (world frame); on overlap, a point near the contact.
    pub point_b: Vec2,
    /// The closest features, for the next warm start.
    pub features: FeaturePair,
    /// Feature pairs visited by the walk.
    pub steps: u32,
    /// Whether the cycling guard fired and the exact fallback gave the answer.
    pub fell_back: bool,
}
