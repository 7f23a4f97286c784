//! The checker's input: bodies with their shapes and motions.

use crate::geometry::ConvexPolygon;
use crate::motion::{Motion, Pose};

/// A robot or an obstacle.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// Name, unique in the scene.
    pub name: String,
    /// Shape in the body frame, whose origin is the rotation centre G.
    pub shape: ConvexPolygon,
    /// How the body moves.
    pub motion: Motion,
}

impl Body {
    /// A fixed obstacle given in world coordinates. Its frame is moved to its centroid so
    /// that its bounding disc (eq. 13) is tight.
    pub fn obstacle(name: String, world_shape: &ConvexPolygon) -> Self {
        let c = world_shape.centroid();
        Body {
            name,
            shape: world_shape.translated(&c),
            motion: Motion::Fixed(Pose { pos: c, theta: 0.0 }),
        }
    }

    /// True for a body that moves along a trajectory.
    pub fn is_robot(&self) -> bool {
        matches!(self.motion, Motion::Sampled(_))
    }
}

/// Robots with trajectories and fixed obstacles, and the safety margin.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// δ: bodies closer than this collide. Length units of the scene.
    pub delta: f64,
    /// Robots first, then obstacles.
    pub bodies: Vec<Body>,
}

impl Scene {
    /// Earliest and latest sample time of any robot; `(0, 0)` without robots.
    pub fn horizon(&self) -> (f64, f64) {
        let times = || self.bodies.iter().flat_map(|b| b.motion.times());
        match times().next() {
            None => (0.0, 0.0),
            Some(t0) => times().fold((t0, t0), |(lo, hi), t| (lo.min(t), hi.max(t))),
        }
    }

    /// The pairs to check, in report order: robot-robot pairs, then robot-obstacle pairs.
    /// Obstacle pairs never change and are not checked.
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        let robots: Vec<usize> = (0..self.bodies.len())
            .filter(|&i| self.bodies[i].is_robot())
            .collect();
        let obstacles: Vec<usize> = (0..self.bodies.len())
            .filter(|&i| !self.bodies[i].is_robot())
            .collect();
        let mut pairs = Vec::new();
        for (k, &i) in robots.iter().enumerate() {
            pairs.extend(robots[k + 1..].iter().map(|&j| (i, j)));
        }
        for &i in &robots {
            pairs.extend(obstacles.iter().map(|&j| (i, j)));
        }
        pairs
    }

    /// The number of robots (bodies that move).
    pub fn robot_count(&self) -> usize {
        self.bodies.iter().filter(|b| b.is_robot()).count()
    }

    /// The number of pairs [`Scene::pairs`] gives, without listing them.
    pub fn pair_count(&self) -> usize {
        let robots = self.robot_count();
        let obstacles = self.bodies.len() - robots;
        robots * robots.saturating_sub(1) / 2 + robots * obstacles
    }
}
