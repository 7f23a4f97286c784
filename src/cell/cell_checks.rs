//! The geometry of a cell read from its file: coordinates f64 resolves at δ, shape clean-ups
//! that keep the boundary, homes clear of obstacles and of each other, tasks outside obstacles.

use super::time_axis::check_time_axis;
use super::{Cell, CellObstacle, InputError, RobotKind, MAX_COORDINATE_OVER_DELTA};
use crate::collision::check_shape_repairs;
use crate::geometry::{closest_features, ConvexPolygon, Posed, Vec2, WalkTolerances};
use crate::motion::Pose;

/// Refuses a cell whose geometry cannot be scheduled or checked at its δ; the first fault
/// found is reported, robots, obstacles, homes, tasks, then the time axis.
pub(super) fn check_geometry(cell: &Cell) -> Result<(), InputError> {
    check_extents(cell)?;
    check_homes(cell)?;
    check_tasks(cell)?;
    check_time_axis(&cell.file, &cell.robots, &cell.tasks)
}

/// Coordinates, radii and angles within what f64 resolves at δ; shape repairs within a
/// sliver of δ.
fn check_extents(cell: &Cell) -> Result<(), InputError> {
    let (file, delta) = (cell.file.as_path(), cell.delta);
    let limit = MAX_COORDINATE_OVER_DELTA * delta;
    for (k, r) in cell.robots.iter().enumerate() {
        let at = format!("robots[{k}]");
        let err = |field: &str, reason: String| {
            cell.error(Some(&r.name), format!("{at}.{field}"), reason)
        };
        match &r.kind {
            RobotKind::Rigid(rigid) => {
                for (field, piece) in piece_fields(&at, rigid.pieces(), rigid.parts.is_some()) {
                    check_shape_repairs(piece, &r.name, &field, delta, file)?;
                }
                let radius = rigid.shape.radius();
                if radius > limit {
                    return Err(err("shape", too_large(radius, delta)));
                }
                let home = rigid.home;
                if home.pos.amax() > limit {
                    return Err(err("home", too_large(home.pos.amax(), delta)));
                }
                if (radius * home.theta).abs() > limit {
                    return Err(err("home", angle_too_large(home.theta, radius, delta)));
                }
            }
            RobotKind::Arm(arm) => {
                for (i, (_, body)) in arm.links.iter().enumerate() {
                    let link = format!("{at}.links[{i}]");
                    for (field, piece) in piece_fields(&link, body.parts(), body.len() > 1) {
                        check_shape_repairs(piece, &r.name, &field, delta, file)?;
                    }
                }
                let rim = r.rim();
                if arm.base.pos.amax() + rim > limit {
                    return Err(err("base", too_large(arm.base.pos.amax() + rim, delta)));
                }
                let angles = std::iter::once(("base", arm.base.theta))
                    .chain(arm.home.iter().map(|&q| ("home", q)));
                for (field, angle) in angles {
                    if (rim * angle).abs() > limit {
                        return Err(err(field, angle_too_large(angle, rim, delta)));
                    }
                }
            }
        }
    }
    for (k, o) in cell.obstacles.iter().enumerate() {
        let at = format!("obstacles[{k}]");
        for (field, piece) in piece_fields(&at, o.pieces(), o.parts.is_some()) {
            check_shape_repairs(piece, &o.name, &field, delta, file)?;
        }
        let extent = o
            .shape
            .vertices()
            .iter()
            .map(|v| v.amax())
            .fold(0.0, f64::max);
        if extent > limit {
            let reason = too_large(extent, delta);
            return Err(cell.error(Some(&o.name), format!("{at}.shape"), reason));
        }
    }
    Ok(())
}

/// Every home clear of the obstacles and of the other homes by δ: bodies closer at home
/// collide before anything is scheduled, and no sequence or wait can separate them.
fn check_homes(cell: &Cell) -> Result<(), InputError> {
    let delta = cell.delta;
    for (k, r) in cell.robots.iter().enumerate() {
        if let Some((o, d)) = nearest_obstacle(&r.at_home(), &cell.obstacles, delta) {
            let reason = format!(
                "the robot at its home is {d:.3e} from obstacle \"{}\", closer than delta = {delta}",
                cell.obstacles[o].name
            );
            return Err(cell.error(Some(&r.name), format!("robots[{k}].home"), reason));
        }
    }
    for (k, r) in cell.robots.iter().enumerate() {
        for other in &cell.robots[..k] {
            let d = placed_distance(&r.at_home(), &other.at_home());
            if d < delta {
                let reason = format!(
                    "at home the robot is {d:.3e} from robot \"{}\" at its home, closer than delta = {delta}",
                    other.name
                );
                return Err(cell.error(Some(&r.name), format!("robots[{k}].home"), reason));
            }
        }
    }
    Ok(())
}

/// The distance between two bodies, each convex pieces placed at poses (an arm's links
/// each at its own): the least over pairs of pieces.
fn placed_distance(a: &[(&[ConvexPolygon], Pose)], b: &[(&[ConvexPolygon], Pose)]) -> f64 {
    let mut least = f64::INFINITY;
    for &x in a {
        for &y in b {
            least = least.min(pieces_distance(x, y));
        }
    }
    least
}

/// Each convex piece of a body with the field that names it: `shape`, or `parts[i]`.
fn piece_fields<'a>(
    at: &'a str,
    pieces: &'a [ConvexPolygon],
    of_parts: bool,
) -> impl Iterator<Item = (String, &'a ConvexPolygon)> + 'a {
    pieces.iter().enumerate().map(move |(i, p)| {
        let field = if of_parts {
            format!("{at}.parts[{i}]")
        } else {
            format!("{at}.shape")
        };
        (field, p)
    })
}

/// The distance between two bodies of convex pieces placed at their poses: the least over
/// pairs of pieces (0 where they overlap).
fn pieces_distance((a, pa): (&[ConvexPolygon], Pose), (b, pb): (&[ConvexPolygon], Pose)) -> f64 {
    let tol = WalkTolerances::default();
    let mut least = f64::INFINITY;
    for x in a {
        let px = Posed::new(x, pa.pos.x, pa.pos.y, pa.theta);
        for y in b {
            let py = Posed::new(y, pb.pos.x, pb.pos.y, pb.theta);
            least = least.min(closest_features(&px, &py, None, &tol).distance);
        }
    }
    least
}

/// Task poses within what f64 resolves at δ (the angle at the rim of the largest allowed
/// robot) and outside every obstacle.
fn check_tasks(cell: &Cell) -> Result<(), InputError> {
    let delta = cell.delta;
    let limit = MAX_COORDINATE_OVER_DELTA * delta;
    for (k, t) in cell.tasks.iter().enumerate() {
        let err = |reason: String| cell.error(Some(&t.name), format!("tasks[{k}].at"), reason);
        let pose = t.at;
        if pose.pos.amax() > limit {
            return Err(err(too_large(pose.pos.amax(), delta)));
        }
        if let Some(o) = cell
            .obstacles
            .iter()
            .find(|o| o.pieces().iter().any(|p| contains(p, &pose.pos)))
        {
            return Err(err(format!(
                "the task pose is inside obstacle \"{}\"",
                o.name
            )));
        }
        // The angle is resolved to within ulp(θ); at the robot's rim that is a length.
        let rim = t
            .robots
            .iter()
            .map(|&r| cell.robots[r].rim())
            .fold(0.0, f64::max);
        if (rim * pose.theta).abs() > limit {
            return Err(err(angle_too_large(pose.theta, rim, delta)));
        }
    }
    Ok(())
}

pub(super) fn too_large(value: f64, delta: f64) -> String {
    format!(
        "coordinate {value:e} is too large for delta = {delta:e} (limit {:e}): f64 cannot \
         resolve delta there; move the origin or raise delta",
        MAX_COORDINATE_OVER_DELTA * delta
    )
}

pub(super) fn angle_too_large(theta: f64, radius: f64, delta: f64) -> String {
    format!(
        "angle {theta:e} is too large for delta = {delta:e}: f64 resolves it only to {:.1e} \
         rad, {:.1e} at the robot's rim (limit |radius x theta| <= {:e}); reduce it modulo 2 pi",
        theta.abs() * f64::EPSILON,
        (radius * theta).abs() * f64::EPSILON,
        MAX_COORDINATE_OVER_DELTA * delta
    )
}

fn contains(shape: &ConvexPolygon, p: &Vec2) -> bool {
    let n = shape.vertices().len();
    (0..n).all(|i| shape.normals()[i].dot(&(p - shape.vertices()[i])) < 0.0)
}

/// The first obstacle closer than δ to the robot's pieces placed as given, with its
/// distance.
fn nearest_obstacle(
    placed: &[(&[ConvexPolygon], Pose)],
    obstacles: &[CellObstacle],
    delta: f64,
) -> Option<(usize, f64)> {
    let origin = Pose::new(0.0, 0.0, 0.0);
    obstacles.iter().enumerate().find_map(|(k, o)| {
        let d = placed_distance(placed, &[(o.pieces(), origin)]);
        (d < delta).then_some((k, d))
    })
}
