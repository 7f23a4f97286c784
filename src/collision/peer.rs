//! The peer: parry2d-f64's nonlinear shape cast, applied the way a parry user would.
//!
//! Compiled only with the feature `parry-peer`, for `workcell compare` and the benchmarks:
//! it is what our checker is measured against, never a part of it. On each merged interval
//! of each pair both poses are linear in time, which is exactly parry's
//! `NonlinearRigidMotion` (constant linear and angular velocity about G). One body is
//! rounded by δ, so that a time of impact is the first time the distance falls to δ; a
//! body of parts is parry's `Compound` of them (each part rounded).

use super::pair::{merged_grid, SharedLimit};
use super::{Body, Scene};
use crate::geometry::ConvexPolygon;
use parry2d_f64::math::{Pose, Vector};
use parry2d_f64::query::{cast_shapes_nonlinear, NonlinearRigidMotion};
use parry2d_f64::shape::SharedShape;
use rayon::prelude::*;

/// What the peer found on a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct PeerReport {
    /// The earliest time of impact at δ, and the pair.
    pub first_contact: Option<(f64, [String; 2])>,
    /// Pairs parry could not handle (a shape it refuses, or a query it does not support).
    pub unsupported: Vec<[String; 2]>,
    /// Shape casts made (one per merged interval examined).
    pub casts: u64,
}

/// Checks `pairs` of `scene` at `delta` with `cast_shapes_nonlinear`, in parallel, each pair
/// stopping at its first impact and no pair looking past the earliest impact found.
///
/// ```
/// use workcell::collision::{check, check_with_parry, CheckOptions};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/tunnelling.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// let peer = check_with_parry(&scene, &scene.pairs(), scene.delta);
/// let ours = check(&scene, &CheckOptions::default());
/// // Both find the needle passing through the block, at about the same time.
/// let (time, bodies) = peer.first_contact.expect("a contact");
/// let verdict = ours.verdict();
/// let contact = verdict.contact().expect("a contact");
/// assert_eq!(bodies, contact.bodies);
/// assert!((time - contact.time).abs() < 1e-3);
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn check_with_parry(scene: &Scene, pairs: &[(usize, usize)], delta: f64) -> PeerReport {
    let horizon = scene.horizon();
    let limit = SharedLimit::new();
    let outcomes: Vec<_> = pairs
        .par_iter()
        .map(|&(i, j)| cast_pair(&scene.bodies[i], &scene.bodies[j], horizon, delta, &limit))
        .collect();
    let names =
        |(i, j): (usize, usize)| [scene.bodies[i].name.clone(), scene.bodies[j].name.clone()];
    let mut report = PeerReport {
        first_contact: None,
        unsupported: Vec::new(),
        casts: 0,
    };
    for (o, &p) in outcomes.iter().zip(pairs) {
        match o {
            Err(()) => report.unsupported.push(names(p)),
            Ok((hit, casts)) => {
                report.casts += casts;
                if let Some(t) = *hit {
                    if report
                        .first_contact
                        .as_ref()
                        .is_none_or(|(first, _)| t < *first)
                    {
                        report.first_contact = Some((t, names(p)));
                    }
                }
            }
        }
    }
    report
}

fn points(p: &ConvexPolygon) -> Vec<Vector> {
    p.vertices().iter().map(|v| Vector::new(v.x, v.y)).collect()
}

/// A body as a parry user would give it: a convex polygon, or a `Compound` of its parts
/// (parry's bounding-volume hierarchy over them); rounded by `border` when it is not 0.
fn parry_shape(body: &Body, border: f64) -> Option<SharedShape> {
    let one = |p: &ConvexPolygon| match border {
        0.0 => SharedShape::convex_polyline(points(p)),
        _ => SharedShape::round_convex_polyline(points(p), border),
    };
    match &body.parts {
        None => one(&body.shape),
        Some(parts) => {
            let shapes = parts
                .parts()
                .iter()
                .map(|p| Some((Pose::IDENTITY, one(p)?)));
            Some(SharedShape::compound(shapes.collect::<Option<Vec<_>>>()?))
        }
    }
}

/// The first time of impact of one pair and the number of casts made; `Err` when parry
/// cannot handle the pair.
fn cast_pair(
    a: &Body,
    b: &Body,
    horizon: (f64, f64),
    delta: f64,
    limit: &SharedLimit,
) -> Result<(Option<f64>, u64), ()> {
    // parry's motions are rigid; a link's pose is not linear between its samples.
    if a.link().is_some() || b.link().is_some() {
        return Err(());
    }
    let shape_a = parry_shape(a, delta).ok_or(())?;
    let shape_b = parry_shape(b, 0.0).ok_or(())?;
    let grid = merged_grid(a, b, horizon);
    let mut casts = 0;
    for w in grid.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        if t0 > limit.get() {
            break;
        }
        let (a0, a1) = (a.motion.pose_at(t0), a.motion.pose_at(t1));
        let (b0, b1) = (b.motion.pose_at(t0), b.motion.pose_at(t1));
        // Times from t0 and positions from A's start keep the digits that matter.
        let (h, origin) = (t1 - t0, a0.pos);
        let motion = |p0: &crate::motion::Pose, p1: &crate::motion::Pose| {
            let start = p0.pos - origin;
            NonlinearRigidMotion::new(
                Pose::new(Vector::new(start.x, start.y), p0.theta),
                Vector::ZERO,
                Vector::new((p1.pos.x - p0.pos.x) / h, (p1.pos.y - p0.pos.y) / h),
                (p1.theta - p0.theta) / h,
            )
        };
        casts += 1;
        let hit = cast_shapes_nonlinear(
            &motion(&a0, &a1),
            &*shape_a,
            &motion(&b0, &b1),
            &*shape_b,
            0.0,
            h,
            true,
        )
        .map_err(|_| ())?;
        if let Some(hit) = hit {
            let t = t0 + hit.time_of_impact;
            limit.lower_to(t);
            return Ok((Some(t), casts));
        }
    }
    Ok((None, casts))
}
