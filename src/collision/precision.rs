//! Refusing scenes that f64 cannot check at their δ and time tolerance.

use super::{Body, Scene};
use crate::error::InputError;
use crate::motion::Motion;
use std::path::Path;

/// Largest |coordinate| / δ accepted: 2³⁸. Rounding a coordinate then costs at most
/// 2³⁸·2⁻⁵² ≈ 6·10⁻⁵ δ, below the checker's default grazing allowance (10⁻⁴ δ), and a
/// bisection can always split an interval finer than that allowance.
pub const MAX_COORDINATE_OVER_DELTA: f64 = (1u64 << 38) as f64;

/// Largest boundary shift accepted from the removal of repeated and collinear vertices, as a
/// fraction of δ: 10⁻⁶. The shape tolerance that judges them is relative to the shape's
/// size, so on shapes 10¹¹·δ long a removal can move the boundary by δ; a shift this small
/// stays far below the grazing allowance (10⁻⁴ δ) once rounding (6·10⁻⁵ δ) is counted.
pub const MAX_REPAIR_SHIFT_OVER_DELTA: f64 = 1e-6;

/// Fewest time tolerances per unit in the last place of the latest time stamp: 16. A time
/// is reported to the nearest f64, so at 10¹⁵ (a unit of 0.125) a contact would be reported
/// up to 0.06 early or late: coarser than a time tolerance of 10⁻³, and at the reported
/// time the bodies need not be within δ.
pub const MIN_TIME_TOL_OVER_ULP: f64 = 16.0;

/// Where a body's fields start in the scene file: `robots[k]` or `obstacles[k]`.
fn field_of(scene: &Scene, k: usize) -> String {
    scene.field_of(k)
}

/// Refuses a shape whose clean-up (repeated and collinear vertices removed) moved its
/// boundary by more than [`MAX_REPAIR_SHIFT_OVER_DELTA`]·δ: for a body of parts, each part
/// and their hull (a hull cleaned up could leave a part's corner out of it).
fn check_repairs(body: &Body, at: &str, delta: f64, file: &Path) -> Result<(), InputError> {
    let Some(parts) = &body.parts else {
        return check_shape_repairs(&body.shape, &body.name, &format!("{at}.shape"), delta, file);
    };
    let outline = parts.outline().is_some();
    let field = |i: usize| match outline {
        true => format!("{at}.outline"),
        false => format!("{at}.parts[{i}]"),
    };
    for (i, part) in parts.parts().iter().enumerate() {
        check_shape_repairs(part, &body.name, &field(i), delta, file)?;
    }
    let whole = if outline {
        field(0)
    } else {
        format!("{at}.parts")
    };
    check_shape_repairs(&body.shape, &body.name, &whole, delta, file)
}

/// As [`check_repairs`], for a polygon of the body `name` at field `at` (`robots[2].shape`)
/// of any file (scenes and cells alike).
pub(crate) fn check_shape_repairs(
    shape: &crate::geometry::ConvexPolygon,
    name: &str,
    at: &str,
    delta: f64,
    file: &Path,
) -> Result<(), InputError> {
    let limit = MAX_REPAIR_SHIFT_OVER_DELTA * delta;
    match shape.repair_shift() {
        Some(shift) if shift.distance > limit => Err(InputError::new(
            file,
            Some(name),
            format!("{at}[{}]", shift.vertex),
            format!(
                "this vertex lies {:e} from the rest of the shape, which the shape tolerance \
                 (relative to the shape's size) took for a repeated or collinear vertex; \
                 removing it would move the boundary by more than {limit:e} \
                 ({MAX_REPAIR_SHIFT_OVER_DELTA:e} x delta): leave it out of the file, or \
                 move it off its neighbours",
                shift.distance
            ),
        )),
        _ => Ok(()),
    }
}

/// Refuses a scene whose time stamps f64 spaces more coarsely than the time tolerance
/// `time_tol` allows ([`MIN_TIME_TOL_OVER_ULP`]): the reported times could not be trusted
/// to it. The message names the latest time stamp (in magnitude).
///
/// ```
/// use workcell::cell::check_time_resolution;
/// use workcell::collision::{Body, Scene};
/// use workcell::geometry::ConvexPolygon;
/// use workcell::motion::{Pose, Trajectory};
/// let at = |t: f64| -> Result<Scene, Box<dyn std::error::Error>> {
///     let path = Trajectory::from_poses([(t, Pose::new(0.0, 0.0, 0.0)), (t + 1.0, Pose::new(1.0, 0.0, 0.0))])?;
///     let mut scene = Scene::new(0.01)?;
///     scene.add(Body::robot("R1", ConvexPolygon::rectangle(1.0, 1.0)?, path))?;
///     Ok(scene)
/// };
/// let file = "scene.json".as_ref();
/// assert!(check_time_resolution(&at(0.0)?, 1e-9, file).is_ok());
/// // At 10¹⁵ s, f64 spaces times 0.125 apart: far coarser than 10⁻⁹.
/// let e = check_time_resolution(&at(1e15)?, 1e-9, file).unwrap_err();
/// assert_eq!(e.body.as_deref(), Some("R1"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn check_time_resolution(scene: &Scene, time_tol: f64, file: &Path) -> Result<(), InputError> {
    let (start, end) = scene.horizon();
    if end == start {
        return Ok(()); // no time to search
    }
    let latest = scene
        .bodies
        .iter()
        .enumerate()
        .flat_map(|(k, b)| b.motion.times().enumerate().map(move |(i, t)| (k, i, t)))
        .max_by(|x, y| x.2.abs().total_cmp(&y.2.abs()));
    let Some((k, i, t)) = latest else {
        return Ok(());
    };
    // One unit in the last place of t is at most ε·|t|.
    let spacing = f64::EPSILON * t.abs();
    if spacing * MIN_TIME_TOL_OVER_ULP <= time_tol {
        return Ok(());
    }
    let body = &scene.bodies[k];
    Err(InputError::new(
        file,
        Some(&body.name),
        format!("{}.trajectory[{i}].t", field_of(scene, k)),
        format!(
            "time stamps of about {t:e} are {spacing:.1e} apart in f64, too coarse for the \
             time tolerance {time_tol:e} (it must be at least {MIN_TIME_TOL_OVER_ULP} times \
             that spacing): count time from the start of the horizon, or raise --time-tol"
        ),
    ))
}

/// Refuses a scene whose coordinates are too large for δ to be resolved in f64, whose
/// shapes were cleaned up by more than a sliver of δ ([`MAX_REPAIR_SHIFT_OVER_DELTA`]), or
/// whose horizon is longer than f64 holds, and a δ that is not a positive number. Fields are
/// named as in the scene file (robots first, then obstacles, in file order).
///
/// ```
/// use workcell::cell::check_precision;
/// use workcell::collision::{Body, Scene};
/// use workcell::geometry::ConvexPolygon;
/// let far = |x: f64| -> Result<Scene, Box<dyn std::error::Error>> {
///     let wall = ConvexPolygon::from_vertices(&[[x, 0.0], [x + 1.0, 0.0], [x + 1.0, 1.0], [x, 1.0]])?;
///     let mut scene = Scene::new(0.01)?;
///     scene.add(Body::obstacle("wall", &wall))?;
///     Ok(scene)
/// };
/// let file = "scene.json".as_ref();
/// assert!(check_precision(&far(1e6)?, 0.01, file).is_ok());
/// // 10¹² is more than 2³⁸ δ: f64 could not resolve δ there.
/// let e = check_precision(&far(1e12)?, 0.01, file).unwrap_err();
/// assert_eq!(e.body.as_deref(), Some("wall"));
/// assert!(check_precision(&far(0.0)?, f64::NAN, file).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn check_precision(scene: &Scene, delta: f64, file: &Path) -> Result<(), InputError> {
    crate::collision::check_delta(delta).map_err(|e| e.in_file(file))?;
    let limit = MAX_COORDINATE_OVER_DELTA * delta;
    let too_large = |value: f64, what: &str| {
        format!(
            "{what} {value:e} is too large for delta = {delta:e}: f64 resolves such a scene only \
             to within {:.1e} (limit |value| <= {limit:e}); move the origin or raise delta",
            value.abs() * f64::EPSILON
        )
    };
    let robots = scene.bodies.iter().filter(|b| b.is_robot()).count();
    let (horizon_start, horizon_end) = scene.horizon();
    for (k, body) in scene.bodies.iter().enumerate() {
        check_repairs(body, &field_of(scene, k), delta, file)?;
        let r = body.shape.radius();
        match &body.motion {
            Motion::Sampled(tr) => {
                let at = field_of(scene, k);
                if r > limit {
                    let reason = too_large(r, "the shape's radius");
                    return Err(InputError::new(
                        file,
                        Some(&body.name),
                        format!("{at}.shape"),
                        reason,
                    ));
                }
                for (i, s) in tr.samples().iter().enumerate() {
                    let checks = [
                        ("x", s.pos.x, "coordinate"),
                        ("y", s.pos.y, "coordinate"),
                        ("theta", r * s.theta, "arc length radius x theta"),
                    ];
                    if let Some((field, v, what)) =
                        checks.into_iter().find(|(_, v, _)| v.abs() > limit)
                    {
                        let field = format!("{at}.trajectory[{i}].{field}");
                        return Err(InputError::new(
                            file,
                            Some(&body.name),
                            field,
                            too_large(v, what),
                        ));
                    }
                }
            }
            Motion::Link(l) => {
                let at = field_of(scene, k);
                let robot = at.split(".links").next().unwrap_or(&at).to_owned();
                let refuse = |field: String, v: f64, what: &str| {
                    Err(InputError::new(
                        file,
                        Some(&body.name),
                        field,
                        too_large(v, what),
                    ))
                };
                let (base, reach) = (l.arm.base(), l.arm.lever(0, l.link));
                if base.pos.amax() + reach > limit {
                    return refuse(
                        format!("{robot}.base"),
                        base.pos.amax() + reach,
                        "coordinate",
                    );
                }
                // An angle is resolved to within ulp(q); at the link's far end that is a length.
                for (i, sample) in l.arm.samples().iter().enumerate() {
                    for j in 0..=l.link {
                        let arc = l.arm.lever(j, l.link) * sample.q[j];
                        if arc.abs() > limit {
                            let field = format!("{robot}.trajectory[{i}].q[{j}]");
                            return refuse(field, arc, "arc length lever x q");
                        }
                    }
                }
            }
            Motion::Fixed(pose) => {
                let extent = pose.pos.amax() + r;
                if extent > limit {
                    let field = format!("obstacles[{}].shape", k - robots);
                    return Err(InputError::new(
                        file,
                        Some(&body.name),
                        field,
                        too_large(extent, "coordinate"),
                    ));
                }
            }
        }
    }
    if !(horizon_end - horizon_start).is_finite() {
        let reason =
            format!("the horizon [{horizon_start:e}, {horizon_end:e}] is longer than f64 holds");
        return Err(InputError::new(
            file,
            None,
            "robots[].trajectory[].t",
            reason,
        ));
    }
    Ok(())
}
