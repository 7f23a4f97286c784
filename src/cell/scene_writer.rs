//! Writing a scene in the contract's format (section 1), readable by `workcell check`.

use crate::collision::Scene;
use crate::geometry::{Posed, Vec2};
use crate::motion::Motion;
use serde_json::{json, Value};

/// The scene as a JSON document: robots with their body-frame shapes and full samples
/// (`t`, `x`, `y`, `vx`, `vy`, `theta`, `omega`), obstacles in world coordinates.
///
/// ```
/// use workcell::cell::{load_scene, parse_scene, scene_document};
/// let scene = load_scene(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/near-miss.json").as_ref())?.scene;
/// let doc = scene_document(&scene);
/// assert_eq!(doc["robots"][0]["trajectory"][0].as_object().unwrap().len(), 7); // t, x, y, vx, vy, theta, omega
/// // Written and read back: the same scene.
/// assert_eq!(parse_scene(&doc.to_string(), "copy.json".as_ref())?.scene, scene);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn scene_document(scene: &Scene) -> Value {
    let mut robots = Vec::new();
    let mut obstacles = Vec::new();
    for body in &scene.bodies {
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
                    json!({"name": body.name, "shape": points(body.shape.vertices()), "trajectory": samples}),
                );
            }
            Motion::Fixed(pose) => {
                let placed = Posed::new(&body.shape, pose.pos.x, pose.pos.y, pose.theta);
                let world: Vec<Vec2> = (0..placed.len()).map(|i| placed.vertex(i)).collect();
                obstacles.push(json!({"name": body.name, "shape": points(&world)}));
            }
        }
    }
    json!({"delta": scene.delta, "robots": robots, "obstacles": obstacles})
}

fn points(vertices: &[Vec2]) -> Vec<[f64; 2]> {
    vertices.iter().map(|v| [v.x, v.y]).collect()
}
