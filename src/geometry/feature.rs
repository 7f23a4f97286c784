//! Features of a convex polygon: its vertices and its edges.

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
