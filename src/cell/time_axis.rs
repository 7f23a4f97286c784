//! Refusing cells whose limits and task durations f64 cannot place on one time axis.
//!
//! A schedule puts every move and task of a robot end to end on one f64 time axis. Near
//! time t, f64 spaces times t·2⁻⁵² apart: a task of 1000 s that starts at 2·10²⁰ (a robot
//! with `max_speed` 10⁻²⁰) would occupy [2·10²⁰, 2·10²⁰], and a subnormal limit makes the
//! move times infinite. What can be told from the cell alone is refused here, when it is
//! read: the schedule itself is checked again when it is built (`wcp`).

use super::{CellRobot, InputError, RigidRobot, RobotKind, Task};
use crate::motion::{rest_to_rest_time, JointLimits};
use std::f64::consts::{PI, TAU};
use std::path::Path;

/// Largest relative change of a task's duration that placing it on the schedule's time
/// axis may cause (dimensionless): a task keeps its length to six digits, or is refused.
pub const TASK_LENGTH_TOL: f64 = 1e-6;

/// Whether a span of `length` that starts at `start` (or earlier) keeps its length on the
/// f64 time axis to within [`TASK_LENGTH_TOL`]: rounding its end moves it by at most half
/// a unit in the last place of `start + length`. A zero length is an instant and is kept.
///
/// ```
/// use workcell::cell::keeps_length;
/// assert!(keeps_length(100.0, 1.5));
/// assert!(keeps_length(1e17, 0.0)); // an instant
/// // At 10¹⁷ s, f64 spaces times 16 s apart: a 1.5 s task cannot keep its length.
/// assert!(!keeps_length(1e17, 1.5));
/// ```
pub fn keeps_length(start: f64, length: f64) -> bool {
    length == 0.0 || 0.5 * (start + length) * f64::EPSILON <= TASK_LENGTH_TOL * length
}

/// Refuses limits that are subnormal or whose ratios are not normal numbers, a robot whose
/// fastest move to one of its tasks takes
/// longer than f64 holds, and a task whose duration would not keep its length
/// ([`keeps_length`]) at the earliest time one of its robots could start it. Fields are
/// named as in the cell file.
pub(super) fn check_time_axis(
    file: &Path,
    robots: &[CellRobot],
    tasks: &[Task],
) -> Result<(), InputError> {
    for (k, r) in robots.iter().enumerate() {
        for (field, value) in limits(r) {
            if value < f64::MIN_POSITIVE {
                let reason = format!(
                    "{value:e} is subnormal (below {:.1e}, the smallest normal f64): f64 holds it \
                     to fewer digits, and the move times computed from it overflow",
                    f64::MIN_POSITIVE
                );
                return Err(InputError::new(
                    file,
                    Some(&r.name),
                    format!("robots[{k}].{field}"),
                    reason,
                ));
            }
        }
    }
    for (k, r) in robots.iter().enumerate() {
        let out = match &r.kind {
            RobotKind::Rigid(b) => profile_out_of_range(b).map(|(f, why)| (f.to_owned(), why)),
            RobotKind::Arm(a) => joints_out_of_range(&a.limits),
        };
        if let Some((field, reason)) = out {
            let field = format!("robots[{k}].{field}");
            return Err(InputError::new(file, Some(&r.name), field, reason));
        }
    }
    for (k, task) in tasks.iter().enumerate() {
        for &ri in &task.robots {
            let r = &robots[ri];
            // An arm's configuration at the task is the solver's choice: no bound here.
            let Some(rigid) = r.as_rigid() else { continue };
            let (arrival, slowest) = fastest_arrival(rigid, task);
            if !arrival.is_finite() {
                let reason = format!(
                    "the robot's fastest move from home to task \"{}\" takes longer than f64 \
                     holds at these limits ({})",
                    task.name,
                    describe_limits(r)
                );
                return Err(InputError::new(
                    file,
                    Some(&r.name),
                    format!("robots[{ri}].{slowest}"),
                    reason,
                ));
            }
            if !keeps_length(arrival, task.duration) {
                let reason = format!(
                    "robot \"{}\" cannot start this task before t = {arrival:.3e} (its fastest \
                     move from home at {}), where f64 spaces times {:.1e} apart: a duration of \
                     {} would not keep its length to {TASK_LENGTH_TOL:e}; rescale the time \
                     unit or the limits, or give 0 for an instant",
                    r.name,
                    describe_limits(r),
                    (arrival + task.duration) * f64::EPSILON,
                    number(task.duration)
                );
                return Err(InputError::new(
                    file,
                    Some(&task.name),
                    format!("tasks[{k}].duration"),
                    reason,
                ));
            }
        }
    }
    Ok(())
}

/// The motion model's derived quantities that f64 must hold as normal numbers: the angular
/// acceleration `max_accel / radius` and the two acceleration phases, `max_speed /
/// max_accel` and `max_turn_rate` over the angular acceleration. Beyond, the planner's
/// profiles overflow or vanish (an infinite angular acceleration gave NaN angles). Returns
/// the limit to blame, the more extreme of the two in a ratio, and why.
fn profile_out_of_range(r: &RigidRobot) -> Option<(&'static str, String)> {
    let normal = |q: f64| (f64::MIN_POSITIVE..f64::INFINITY).contains(&q);
    let alpha = r.max_accel / r.shape.radius();
    let extreme = |(fa, a): (&'static str, f64), (fb, b): (&'static str, f64)| {
        if a.log10().abs() >= b.log10().abs() {
            fa
        } else {
            fb
        }
    };
    let checks = [
        (
            "max_accel / radius (the angular acceleration)",
            alpha,
            "max_accel",
        ),
        (
            "max_speed / max_accel (the time to reach max_speed)",
            r.max_speed / r.max_accel,
            extreme(("max_speed", r.max_speed), ("max_accel", r.max_accel)),
        ),
        (
            "max_turn_rate over the angular acceleration (the time to reach it)",
            r.max_turn_rate / alpha,
            extreme(
                ("max_turn_rate", r.max_turn_rate),
                ("max_accel", r.max_accel),
            ),
        ),
    ];
    checks
        .into_iter()
        .find(|&(_, q, _)| !normal(q))
        .map(|(what, q, field)| (field, not_normal(what, q)))
}

/// As [`profile_out_of_range`] for an arm: each joint's time to reach its speed,
/// `max_joint_speed / max_joint_accel`, a normal number.
fn joints_out_of_range(limits: &JointLimits) -> Option<(String, String)> {
    let normal = |q: f64| (f64::MIN_POSITIVE..f64::INFINITY).contains(&q);
    (limits.max_speed.iter().zip(&limits.max_accel).enumerate()).find_map(|(j, (&v, &a))| {
        let field = if v.log10().abs() >= a.log10().abs() {
            format!("max_joint_speed[{j}]")
        } else {
            format!("max_joint_accel[{j}]")
        };
        let what = "max_joint_speed / max_joint_accel (the time to reach the joint's speed)";
        (!normal(v / a)).then(|| (field, not_normal(what, v / a)))
    })
}

fn not_normal(what: &str, q: f64) -> String {
    format!(
        "{what} is {q:e}, out of the range of normal f64 numbers [{:.1e}, {:.1e}]: the motion \
         profiles would overflow or vanish; bring the limits closer together",
        f64::MIN_POSITIVE,
        f64::MAX
    )
}

/// The robot's limits with the fields that name them.
fn limits(r: &CellRobot) -> Vec<(String, f64)> {
    match &r.kind {
        RobotKind::Rigid(b) => vec![
            ("max_speed".into(), b.max_speed),
            ("max_accel".into(), b.max_accel),
            ("max_turn_rate".into(), b.max_turn_rate),
        ],
        RobotKind::Arm(a) => {
            let speeds = (a.limits.max_speed.iter().enumerate())
                .map(|(j, &v)| (format!("max_joint_speed[{j}]"), v));
            let accels = (a.limits.max_accel.iter().enumerate())
                .map(|(j, &v)| (format!("max_joint_accel[{j}]"), v));
            speeds.chain(accels).collect()
        }
    }
}

fn describe_limits(r: &CellRobot) -> String {
    limits(r)
        .iter()
        .map(|(field, value)| format!("{field} {}", number(*value)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A number for people, to four significant digits: plain when moderate, else in exponent
/// form (`1e-20`, not twenty zeros).
pub(crate) fn number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    if (1e-3..1e6).contains(&v.abs()) {
        let digits = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        let text = format!("{v:.digits$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            text
        }
    } else {
        let text = format!("{v:.3e}");
        let (mantissa, exponent) = text.split_once('e').expect("exponent form");
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        format!("{mantissa}e{exponent}")
    }
}

/// A lower bound of the time robot `r` needs from home to the task's pose, and the limit
/// that bounds it most. Any planned path is at least the straight line, and a rest-to-rest
/// time only grows when a distance is split into stops; the turn is at least the shortest
/// way to the task's angle, at the angular acceleration `max_accel / radius` of the model.
fn fastest_arrival(r: &RigidRobot, task: &Task) -> (f64, &'static str) {
    let distance = (task.at.pos - r.home.pos).norm();
    let translation = rest_to_rest_time(distance, r.max_speed, r.max_accel);
    let turn = ((task.at.theta - r.home.theta + PI).rem_euclid(TAU) - PI).abs();
    let alpha = r.max_accel / r.shape.radius();
    let rotation = rest_to_rest_time(turn, r.max_turn_rate, alpha);
    if translation >= rotation {
        let slowest = if (distance / r.max_speed).is_finite() {
            "max_accel"
        } else {
            "max_speed"
        };
        (translation, slowest)
    } else {
        let slowest = if (turn / r.max_turn_rate).is_finite() {
            "max_accel"
        } else {
            "max_turn_rate"
        };
        (rotation, slowest)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_length_is_kept_while_rounding_its_end_changes_it_little() {
        assert!(keeps_length(0.0, 1e-300));
        assert!(keeps_length(1e3, 1.0));
        assert!(keeps_length(2e20, 0.0), "an instant");
        assert!(
            !keeps_length(2e20, 1000.0),
            "the vanishing task of issue 13"
        );
        assert!(!keeps_length(2.0, 1e-16));
        // A 1 s task at t = 5e9 may move by 5e9·2⁻⁵³ = 5.6e-7 < 1e-6; at 1e10, by 1.1e-6.
        assert!(keeps_length(5e9, 1.0));
        assert!(!keeps_length(1e10, 1.0));
    }

    #[test]
    fn numbers_for_people() {
        for (v, text) in [
            (1000.0, "1000"),
            (1.2, "1.2"),
            (2.8153614603062423e-150, "2.815e-150"),
            (1e300, "1e300"),
            (1e-20, "1e-20"),
            (0.5, "0.5"),
            (123456.0, "123456"),
            (0.0, "0"),
        ] {
            assert_eq!(number(v), text);
        }
    }
}
