//! The geometry of a cell read from its file: coordinates f64 resolves at δ, shape clean-ups
//! that keep the boundary, homes clear of obstacles and of each other, tasks outside obstacles.

use super::time_axis::check_time_axis;
use super::{Cell, CellObstacle, CellRobot, InputError, MAX_COORDINATE_OVER_DELTA};
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
        check_shape_repairs(&r.shape, &r.name, &format!("{at}.shape"), delta, file)?;
        let radius = r.shape.radius();
        if radius > limit {
            return Err(err("shape", too_large(radius, delta)));
        }
        if r.home.pos.amax() > limit {
            return Err(err("home", too_large(r.home.pos.amax(), delta)));
        }
        if (radius * r.home.theta).abs() > limit {
            return Err(err("home", angle_too_large(r.home.theta, radius, delta)));
        }
    }
    for (k, o) in cell.obstacles.iter().enumerate() {
        let at = format!("obstacles[{k}]");
        check_shape_repairs(&o.shape, &o.name, &format!("{at}.shape"), delta, file)?;
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
        if let Some((o, d)) = nearest_obstacle(&r.shape, r.home, &cell.obstacles, delta) {
            let reason = format!(
                "the robot at its home is {d:.3e} from obstacle \"{}\", closer than delta = {delta}",
                cell.obstacles[o].name
            );
            return Err(cell.error(Some(&r.name), format!("robots[{k}].home"), reason));
        }
    }
    for (k, r) in cell.robots.iter().enumerate() {
        for other in &cell.robots[..k] {
            let d = closest_features(&placed(r), &placed(other), None, &WalkTolerances::default())
                .distance;
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

fn placed(r: &CellRobot) -> Posed<'_> {
    Posed::new(&r.shape, r.home.pos.x, r.home.pos.y, r.home.theta)
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
            .find(|o| contains(&o.shape, &pose.pos))
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
            .map(|&r| cell.robots[r].shape.radius())
            .fold(0.0, f64::max);
        if (rim * pose.theta).abs() > limit {
            return Err(err(angle_too_large(pose.theta, rim, delta)));
        }
    }
    Ok(())
}

fn too_large(value: f64, delta: f64) -> String {
    format!(
        "coordinate {value:e} is too large for delta = {delta:e} (limit {:e}): f64 cannot \
         resolve delta there; move the origin or raise delta",
        MAX_COORDINATE_OVER_DELTA * delta
    )
}

fn angle_too_large(theta: f64, radius: f64, delta: f64) -> String {
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

/// The first obstacle closer than δ to the robot placed at `pose`, with its distance.
fn nearest_obstacle(
    shape: &ConvexPolygon,
    pose: Pose,
    obstacles: &[CellObstacle],
    delta: f64,
) -> Option<(usize, f64)> {
    let robot = Posed::new(shape, pose.pos.x, pose.pos.y, pose.theta);
    obstacles.iter().enumerate().find_map(|(k, o)| {
        let obstacle = Posed::new(&o.shape, 0.0, 0.0, 0.0);
        let d = closest_features(&robot, &obstacle, None, &WalkTolerances::default()).distance;
        (d < delta).then_some((k, d))
    })
}
