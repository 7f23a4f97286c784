//! Writing a scene in the contract's format (section 1), readable by `workcell check`.

use crate::collision::{Body, Scene};
use crate::geometry::Vec2;
use crate::motion::Motion;
use nalgebra::{Isometry2, Point2};
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
    for (k, body) in scene.bodies.iter().enumerate() {
        match &body.motion {
            // The first link of an arm writes the whole arm (contract section 6).
            Motion::Link(l) => {
                if k > 0 && scene.bodies[k - 1].same_arm(body) {
                    continue;
                }
                let arm = &l.arm;
                let links: Vec<Value> = scene.bodies[k..k + arm.links()]
                    .iter()
                    .zip(arm.lengths())
                    .map(|(link, length)| {
                        let (key, value) = geometry(link, |v| v);
                        json!({"length": length, key: value})
                    })
                    .collect();
                let samples: Vec<Value> = arm
                    .samples()
                    .iter()
                    .map(|s| json!({"t": s.t, "q": s.q, "qd": s.qd}))
                    .collect();
                let b = arm.base();
                robots.push(
                    json!({"name": body.name, "base": [b.pos.x, b.pos.y, b.theta],
                                   "links": links, "trajectory": samples}),
                );
            }
            Motion::Sampled(trajectory) => {
                let samples: Vec<Value> = trajectory
                    .samples()
                    .iter()
                    .map(|s| {
                        json!({"t": s.t, "x": s.pos.x, "y": s.pos.y, "vx": s.vel.x, "vy": s.vel.y,
                               "theta": s.theta, "omega": s.omega})
                    })
                    .collect();
                let (key, value) = geometry(body, |v| v);
                robots.push(json!({"name": body.name, key: value, "trajectory": samples}));
            }
            Motion::Fixed(pose) => {
                let iso = Isometry2::new(pose.pos, pose.theta);
                let (key, value) = geometry(body, |v| (iso * Point2::from(v)).coords);
                obstacles.push(json!({"name": body.name, key: value}));
            }
        }
    }
    json!({"delta": scene.delta, "robots": robots, "obstacles": obstacles})
}

/// The body's geometry as the file gives it (`shape`, `parts` or `outline`), each vertex
/// placed by `place`.
fn geometry(body: &Body, place: impl Fn(Vec2) -> Vec2) -> (&'static str, Value) {
    let points = |vertices: &[Vec2]| -> Value {
        json!(vertices
            .iter()
            .map(|v| {
                let p = place(*v);
                [p.x, p.y]
            })
            .collect::<Vec<_>>())
    };
    match &body.parts {
        None => ("shape", points(body.shape.vertices())),
        Some(parts) => match parts.outline() {
            Some(outline) => ("outline", points(outline)),
            None => (
                "parts",
                Value::Array(parts.parts().iter().map(|p| points(p.vertices())).collect()),
            ),
        },
    }
}
