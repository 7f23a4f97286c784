//! The visibility graph over the grown obstacles and its shortest path (petgraph A*).

use super::grown::Grown;
use crate::geometry::{cross, Vec2};
use petgraph::graph::{NodeIndex, UnGraph};

/// A node: start, goal, or a vertex of a grown obstacle.
struct Node {
    pos: Vec2,
    /// Set for an obstacle vertex.
    corner: Option<Corner>,
}

/// An obstacle vertex, with what the quadratic loop over pairs needs at hand so that it
/// does no index arithmetic.
struct Corner {
    obstacle: usize,
    vertex: usize,
    /// The obstacle's vertex count.
    len: usize,
    /// From the vertex to the previous one.
    before: Vec2,
    /// From the vertex to the next one.
    after: Vec2,
}

/// How the line through a node towards another meets the node's obstacle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Tangency {
    /// It supports the obstacle: no segment along it enters the obstacle.
    Exact,
    /// A neighbour of the vertex is on the wrong side but within the tolerance: nearly
    /// tangent, yet a long segment could still enter the obstacle further on.
    Near,
    /// It cuts through the obstacle at the vertex: no taut path leaves the vertex so.
    None,
}

impl Corner {
    /// Whether the line from the vertex (at `pos`) towards `target` keeps both neighbours
    /// on one side.
    fn tangency(&self, pos: &Vec2, target: &Vec2, tol: f64) -> Tangency {
        let d = target - pos;
        let (before, after) = (cross(&d, &self.before), cross(&d, &self.after));
        if before * after >= 0.0 {
            Tangency::Exact
        } else if before.abs().min(after.abs()).powi(2) <= tol * tol * d.norm_squared() {
            // Squared: this runs for most pairs of the quadratic loop, a root would show.
            Tangency::Near
        } else {
            Tangency::None
        }
    }
}

/// The cheapest path from `start` to `goal` that does not cross the interior of any
/// `obstacles` (up to `tol`), as waypoints including both ends; `None` if there is none.
///
/// `cost` maps a segment's length to its cost. It must be increasing and subadditive
/// (the rest-to-rest time is): then `cost(|v − goal|)` never overestimates the cost from
/// `v`, and A* returns the cheapest path of the graph.
///
/// Only taut paths are searched: an edge leaves or reaches an obstacle vertex along a
/// supporting line of that obstacle (both neighbours on one side). The shortest path
/// is taut, so pruning the other edges never loses connectivity.
pub(crate) fn shortest_path(
    obstacles: &[Grown],
    start: Vec2,
    goal: Vec2,
    tol: f64,
    cost: impl Fn(f64) -> f64,
) -> Option<Vec<Vec2>> {
    let free = |pos| Node { pos, corner: None };
    let mut nodes = vec![free(start), free(goal)];
    for (k, g) in obstacles.iter().enumerate() {
        let vs = g.vertices();
        let len = vs.len();
        for (i, v) in vs.iter().enumerate() {
            // A vertex inside another grown obstacle is not a place G may be.
            let buried = obstacles
                .iter()
                .enumerate()
                .any(|(j, h)| j != k && h.contains(v, tol));
            if !buried {
                nodes.push(Node {
                    pos: *v,
                    corner: Some(Corner {
                        obstacle: k,
                        vertex: i,
                        len,
                        before: vs[(i + len - 1) % len] - v,
                        after: vs[(i + 1) % len] - v,
                    }),
                });
            }
        }
    }
    let mut graph: UnGraph<(), f64> = UnGraph::with_capacity(nodes.len(), 4 * nodes.len());
    for _ in &nodes {
        graph.add_node(());
    }
    for u in 0..nodes.len() {
        for v in u + 1..nodes.len() {
            if let Some(length) = visible(obstacles, &nodes[u], &nodes[v], tol) {
                graph.add_edge(NodeIndex::new(u), NodeIndex::new(v), cost(length));
            }
        }
    }
    let (_, route) = petgraph::algo::astar(
        &graph,
        NodeIndex::new(0),
        |n| n.index() == 1,
        |e| *e.weight(),
        |n| cost((nodes[n.index()].pos - goal).norm()),
    )?;
    let mut path: Vec<Vec2> = route.iter().map(|n| nodes[n.index()].pos).collect();
    // The ends exactly as given, even if a vertex coincides with them.
    path[0] = start;
    *path.last_mut()? = goal;
    // A vertex at the start or goal itself would be a segment of length 0.
    path.dedup();
    Some(path)
}

/// The length of the edge `a`–`b` if it belongs to the graph.
fn visible(obstacles: &[Grown], a: &Node, b: &Node, tol: f64) -> Option<f64> {
    // Two vertices of one convex obstacle see each other only along an edge.
    if let (Some(p), Some(q)) = (&a.corner, &b.corner) {
        let (i, j) = (p.vertex.min(q.vertex), p.vertex.max(q.vertex));
        let adjacent = j == i + 1 || (i == 0 && j + 1 == p.len);
        if p.obstacle == q.obstacle && !adjacent {
            return None;
        }
    }
    // Exactly tangent ends cannot enter their own obstacle; nearly tangent ones are checked.
    let mut skip = [None, None];
    for (slot, (end, other)) in skip.iter_mut().zip([(a, b), (b, a)]) {
        if let Some(c) = &end.corner {
            match c.tangency(&end.pos, &other.pos, tol) {
                Tangency::None => return None,
                Tangency::Exact => *slot = Some(c.obstacle),
                Tangency::Near => {}
            }
        }
    }
    let free = obstacles
        .iter()
        .enumerate()
        .all(|(k, g)| skip.contains(&Some(k)) || !g.blocks(&a.pos, &b.pos, tol));
    free.then(|| (b.pos - a.pos).norm())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Grown {
        Grown::new(vec![
            Vec2::new(x0, y0),
            Vec2::new(x1, y0),
            Vec2::new(x1, y1),
            Vec2::new(x0, y1),
        ])
    }

    #[test]
    fn tangency_at_a_corner() {
        let p = |x, y| Vec2::new(x, y);
        // Corner (2, 0) of the square [0, 2]²: the square spans the directions from 90 to
        // 180 degrees there, and a line supports it if neither direction points inside.
        let c = Corner {
            obstacle: 0,
            vertex: 1,
            len: 4,
            before: p(-2.0, 0.0),
            after: p(0.0, 2.0),
        };
        let at = |x, y| c.tangency(&p(2.0, 0.0), &p(x, y), 1e-9);
        assert_eq!(at(4.0, 2.0), Tangency::Exact);
        assert_eq!(at(0.0, -2.0), Tangency::Exact);
        assert_eq!(at(4.0, 0.0), Tangency::Exact);
        assert_eq!(at(2.0, 2.0), Tangency::Exact);
        // Outwards, but the line's other half enters the square.
        assert_eq!(at(4.0, -1.0), Tangency::None);
        assert_eq!(at(-1.0, 3.0), Tangency::None);
        // A hair inside the edge to the next corner.
        assert_eq!(at(2.0 - 1e-12, 2.0), Tangency::Near);
    }

    #[test]
    fn goes_around_a_wall_by_its_nearer_end() {
        let wall = rect(-0.5, -1.0, 0.5, 3.0);
        let path = shortest_path(
            &[wall],
            Vec2::new(-2.0, 0.0),
            Vec2::new(2.0, 0.0),
            1e-12,
            |l| l,
        )
        .unwrap();
        assert_eq!(
            path,
            vec![
                Vec2::new(-2.0, 0.0),
                Vec2::new(-0.5, -1.0),
                Vec2::new(0.5, -1.0),
                Vec2::new(2.0, 0.0)
            ]
        );
    }

    #[test]
    fn a_closed_ring_has_no_path_out() {
        let ring = [
            rect(-3.0, -3.0, 3.0, -2.0),
            rect(-3.0, 2.0, 3.0, 3.0),
            rect(-3.0, -3.0, -2.0, 3.0),
            rect(2.0, -3.0, 3.0, 3.0),
        ];
        let out = shortest_path(&ring, Vec2::zeros(), Vec2::new(5.0, 0.0), 1e-12, |l| l);
        assert!(out.is_none());
    }

    #[test]
    fn passes_between_touching_obstacles_but_not_overlapping_ones() {
        // Touching grown obstacles leave G exactly the clearance from both along the seam.
        let (from, to) = (Vec2::new(0.0, -2.0), Vec2::new(0.0, 2.0));
        let touching = [rect(-1.0, -1.0, 0.0, 1.0), rect(0.0, -1.0, 1.0, 1.0)];
        let path = shortest_path(&touching, from, to, 1e-12, |l| l).unwrap();
        assert!(path.iter().all(|p| p.x == 0.0), "{path:?}");
        let overlapping = [rect(-1.0, -1.0, 0.1, 1.0), rect(-0.1, -1.0, 1.0, 1.0)];
        let path = shortest_path(&overlapping, from, to, 1e-12, |l| l).unwrap();
        assert_eq!(path.len(), 4);
        assert!(path[1].x.abs() == 1.0 && path[2].x == path[1].x, "{path:?}");
    }
}
