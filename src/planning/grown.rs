//! A grown obstacle: the region of the plane G must not enter, with fast queries.

use crate::geometry::Vec2;

/// A convex counter-clockwise polygon with unit outward edge normals and a bounding box.
///
/// Half-plane offsets are taken relative to the first vertex, so that queries far from the
/// world origin keep the precision of the polygon's own size.
#[derive(Clone, Debug)]
pub(crate) struct Grown {
    vertices: Vec<Vec2>,
    /// Unit outward normal of edge `i` (vertex `i` to `i + 1`).
    normals: Vec<Vec2>,
    /// `normals[i] · (vertices[i] − vertices[0])`.
    offsets: Vec<f64>,
    min: Vec2,
    max: Vec2,
}

impl Grown {
    /// Wraps a convex counter-clockwise polygon with at least three vertices.
    pub fn new(vertices: Vec<Vec2>) -> Self {
        let n = vertices.len();
        let o = vertices[0];
        let mut normals = Vec::with_capacity(n);
        let mut offsets = Vec::with_capacity(n);
        let (mut min, mut max) = (o, o);
        for i in 0..n {
            let (a, b) = (vertices[i], vertices[(i + 1) % n]);
            // A difference of two floats is correct to half an ulp of itself, so even a
            // short edge's normal is accurate.
            let e = b - a;
            let normal = Vec2::new(e.y, -e.x) / e.norm();
            normals.push(normal);
            offsets.push(normal.dot(&(a - o)));
            min = min.inf(&a);
            max = max.sup(&a);
        }
        Grown {
            vertices,
            normals,
            offsets,
            min,
            max,
        }
    }

    /// Counter-clockwise vertices.
    pub fn vertices(&self) -> &[Vec2] {
        &self.vertices
    }

    /// Largest absolute coordinate of a vertex.
    pub fn extent(&self) -> f64 {
        self.min.amax().max(self.max.amax())
    }

    /// Whether `p` lies inside the polygon deeper than `tol` from every edge.
    pub fn contains(&self, p: &Vec2, tol: f64) -> bool {
        if p.x <= self.min.x + tol
            || p.y <= self.min.y + tol
            || p.x >= self.max.x - tol
            || p.y >= self.max.y - tol
        {
            return false;
        }
        let q = p - self.vertices[0];
        self.normals
            .iter()
            .zip(&self.offsets)
            .all(|(n, c)| n.dot(&q) < c - tol)
    }

    /// Whether the segment `a`–`b` passes through the polygon shrunk by `tol`: it crosses
    /// the interior, rather than touching the boundary or running along it.
    ///
    /// Cyrus-Beck clipping of the segment by the shrunk half-planes.
    pub fn blocks(&self, a: &Vec2, b: &Vec2, tol: f64) -> bool {
        let (lo, hi) = (a.inf(b), a.sup(b));
        if hi.x <= self.min.x + tol
            || hi.y <= self.min.y + tol
            || lo.x >= self.max.x - tol
            || lo.y >= self.max.y - tol
        {
            return false;
        }
        let qa = a - self.vertices[0];
        let d = b - a;
        let (mut enter, mut exit) = (0.0f64, 1.0f64);
        for (n, c) in self.normals.iter().zip(&self.offsets) {
            // Inside this half-plane where n·(qa + t·d) < c − tol.
            let room = c - tol - n.dot(&qa);
            let rate = n.dot(&d);
            if rate > 0.0 {
                exit = exit.min(room / rate);
            } else if rate < 0.0 {
                enter = enter.max(room / rate);
            } else if room <= 0.0 {
                return false;
            }
            if enter >= exit {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Grown {
        Grown::new(vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(2.0, 2.0),
            Vec2::new(0.0, 2.0),
        ])
    }

    #[test]
    fn containment_excludes_the_boundary_band() {
        let s = square();
        assert!(s.contains(&Vec2::new(1.0, 1.0), 1e-9));
        assert!(!s.contains(&Vec2::new(0.0, 1.0), 1e-9));
        assert!(!s.contains(&Vec2::new(1e-10, 1.0), 1e-9));
        assert!(s.contains(&Vec2::new(1e-8, 1.0), 1e-9));
        assert!(!s.contains(&Vec2::new(3.0, 1.0), 1e-9));
    }

    #[test]
    fn segments_crossing_touching_and_along() {
        let s = square();
        let p = |x, y| Vec2::new(x, y);
        assert!(s.blocks(&p(-1.0, 1.0), &p(3.0, 1.0), 1e-9));
        assert!(s.blocks(&p(-1.0, -1.0), &p(3.0, 3.0), 1e-9));
        assert!(s.blocks(&p(1.0, 1.0), &p(1.5, 1.0), 1e-9));
        // Along an edge, through a corner only, or outside.
        assert!(!s.blocks(&p(-1.0, 0.0), &p(3.0, 0.0), 1e-9));
        assert!(!s.blocks(&p(0.0, 0.0), &p(2.0, 0.0), 1e-9));
        assert!(!s.blocks(&p(-1.0, 1.0), &p(1.0, -1.0), 1e-9));
        assert!(!s.blocks(&p(-1.0, 3.0), &p(3.0, 3.0), 1e-9));
        assert!(s.blocks(&p(2.0, 0.0), &p(0.0, 2.0), 1e-9));
    }
}
