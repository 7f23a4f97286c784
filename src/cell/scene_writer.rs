//! Writing a scene in the contract's format (section 1), readable by `workcell check`.

use crate::collision::Scene;
use crate::geometry::Vec2;
use crate::motion::Motion;
use serde_json::{json, Value};

/// The scene as a JSON document: robots with their body-frame shapes and full samples
/// (`t`, `x`, `y`, `vx`, `vy`, `theta`, `omega`), obstacles in world coordinates.
pub fn scene_document(scene: &Scene) -> Value {
    let mut robots = Vec::new();
    let mut obstacles = Vec::new();
    for body in &scene.bodies {
        let vertices = |f: &dyn Fn(&Vec2) -> Vec2| -> Vec<[f64; 2]> {
            body.shape
                .vertices()
                .iter()
                .map(f)
                .map(|v| [v.x, v.y])
                .collect()
        };
        match &body.motion {
            Motion::Sampled(trajectory) => {
                let samples: Vec<Value> = trajectory
                    .samples()
                    .iter()
                    .map(|s| {
                        json!({"t": s.t, "x": s.pos.x, "y": s.pos.y, "vx": s.vel.x, "vy": s.vel.y,
                               "theta": s.theta, "omega": s.omega})
                    })
                    .collect();
                robots.push(
                    json!({"name": body.name, "shape": vertices(&|v| *v), "trajectory": samples}),
                );
            }
            Motion::Fixed(pose) => {
                let (s, c) = pose.theta.sin_cos();
                let place = |v: &Vec2| pose.pos + Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y);
                obstacles.push(json!({"name": body.name, "shape": vertices(&place)}));
            }
        }
    }
    json!({"delta": scene.delta, "robots": robots, "obstacles": obstacles})
}
