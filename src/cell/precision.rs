//! Refusing scenes that f64 cannot check at their δ.

use super::InputError;
use crate::collision::Scene;
use crate::motion::Motion;
use std::path::Path;

/// Largest |coordinate| / δ accepted: 2³⁸. Rounding a coordinate then costs at most
/// 2³⁸·2⁻⁵² ≈ 6·10⁻⁵ δ, below the checker's default grazing allowance (10⁻⁴ δ), and a
/// bisection can always split an interval finer than that allowance.
pub const MAX_COORDINATE_OVER_DELTA: f64 = (1u64 << 38) as f64;

/// Refuses a scene whose coordinates are too large for δ to be resolved in f64, or whose
/// horizon is longer than f64 holds, and a δ that is not a positive number. Fields are named
/// as in the scene file (robots first, then obstacles, in file order).
pub fn check_precision(scene: &Scene, delta: f64, file: &Path) -> Result<(), InputError> {
    if !(delta.is_finite() && delta > 0.0) {
        let reason = format!("must be a positive number, got {delta}");
        return Err(InputError::new(file, None, "delta", reason));
    }
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
        let r = body.shape.radius();
        match &body.motion {
            Motion::Sampled(tr) => {
                let at = format!("robots[{k}]");
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
