//! Inverse kinematics of a planar arm (contract sections 6 and 7): every joint configuration
//! that puts the tool at a task's pose, within the joint limits.
//!
//! Two links reach a point in closed form, elbow up and elbow down (the law of cosines);
//! three links with the tool's angle given reduce to two once the wrist (the last link's
//! joint) is placed back from the tool. Every other case has free angles: the absolute angles
//! of the links past the first two (all of them when the tool's angle is free, all but the
//! last when it is given) are sampled on a deterministic grid, and each sample is solved in
//! closed form with both branches kept. A joint with limits takes every whole-turn shift of
//! an angle that fits them; a joint without limits takes the angle in (−π, π].

use super::arm::forward_kinematics;
use super::Pose;
use crate::geometry::Vec2;
use std::f64::consts::{PI, TAU};

/// Where an arm's tool must be: its position, and its angle when the task gives one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolGoal {
    /// The tool point in the world.
    pub pos: Vec2,
    /// The tool's angle (the last link's), or `None` when the task leaves it free.
    pub theta: Option<f64>,
}

/// How the free angles are sampled and how close a solution must come.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IkSettings {
    /// Samples of each free angle over a whole turn.
    pub samples_per_turn: usize,
    /// At most this many combinations of free angles are tried (the samples per angle are
    /// thinned to fit, for arms of many links).
    pub max_combinations: usize,
    /// A solution's tool lies within this distance of the goal (length units).
    pub position_tol: f64,
    /// And, when the goal gives an angle, within this angle of it (radians).
    pub angle_tol: f64,
}

impl Default for IkSettings {
    fn default() -> Self {
        IkSettings {
            samples_per_turn: 16,
            max_combinations: 4096,
            position_tol: 1e-9,
            angle_tol: 1e-9,
        }
    }
}

/// Why no configuration puts the tool at a goal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unreachable {
    /// No joint angles at all reach it.
    OutOfReach,
    /// Some do, but none within the joint limits.
    OutsideLimits,
}

/// The tool's pose for joint angles `q` (contract section 6): the point (`length`, 0) of the
/// last link's frame, with that link's angle.
///
/// ```
/// use workcell::motion::{tool_pose, Pose};
/// let tool = tool_pose(Pose::new(1.0, 0.0, 0.0), &[1.0, 0.5], &[0.0, std::f64::consts::FRAC_PI_2]);
/// assert!((tool.pos.x - 2.0).abs() < 1e-15 && (tool.pos.y - 0.5).abs() < 1e-15);
/// ```
pub fn tool_pose(base: Pose, lengths: &[f64], q: &[f64]) -> Pose {
    let last = lengths.len() - 1;
    let frame = forward_kinematics(base, lengths, q, last);
    Pose {
        pos: frame.pos + lengths[last] * Vec2::new(frame.theta.cos(), frame.theta.sin()),
        theta: frame.theta,
    }
}

/// Every joint configuration within `limits` (`[min, max]` per joint, or `None`) that puts
/// the tool of the arm with `base` and link `lengths` at `goal`, each to the settings'
/// tolerances; in a deterministic order.
///
/// ```
/// use workcell::geometry::Vec2;
/// use workcell::motion::{inverse_kinematics, tool_pose, IkSettings, Pose, ToolGoal, Unreachable};
/// let (base, lengths) = (Pose::new(0.0, 0.0, 0.0), [1.0, 1.0]);
/// let goal = ToolGoal { pos: Vec2::new(1.0, 1.0), theta: None };
/// let found = inverse_kinematics(base, &lengths, &[None, None], goal, &IkSettings::default())?;
/// assert_eq!(found.len(), 2); // elbow up and elbow down
/// for q in &found {
///     assert!((tool_pose(base, &lengths, q).pos - goal.pos).norm() < 1e-9);
/// }
/// let far = ToolGoal { pos: Vec2::new(3.0, 0.0), theta: None };
/// assert_eq!(inverse_kinematics(base, &lengths, &[None, None], far, &IkSettings::default()),
///            Err(Unreachable::OutOfReach));
/// # Ok::<(), Unreachable>(())
/// ```
pub fn inverse_kinematics(
    base: Pose,
    lengths: &[f64],
    limits: &[Option<[f64; 2]>],
    goal: ToolGoal,
    settings: &IkSettings,
) -> Result<Vec<Vec<f64>>, Unreachable> {
    let n = lengths.len();
    let raw = raw_solutions(base, lengths, goal, settings);
    // Keep what reaches the goal to the tolerances (the closed forms lose digits near the
    // edges of the reach), once.
    let mut reached: Vec<Vec<f64>> = Vec::new();
    for q in raw {
        let tool = tool_pose(base, lengths, &q);
        let angle_off = goal.theta.map_or(0.0, |t| wrap(tool.theta - t).abs());
        let near = (tool.pos - goal.pos).norm() <= settings.position_tol;
        let duplicate = reached.iter().any(|r| same_angles(r, &q));
        if near && angle_off <= settings.angle_tol && !duplicate {
            reached.push(q);
        }
    }
    if reached.is_empty() {
        return Err(Unreachable::OutOfReach);
    }
    let mut within = Vec::new();
    for q in &reached {
        within.extend(shifts_within(q, &limits[..n.min(limits.len())], n));
    }
    if within.is_empty() {
        return Err(Unreachable::OutsideLimits);
    }
    Ok(within)
}

/// Candidate angles in (−π, π], not yet checked against the goal.
fn raw_solutions(base: Pose, lengths: &[f64], goal: ToolGoal, s: &IkSettings) -> Vec<Vec<f64>> {
    let n = lengths.len();
    // The goal in the base's frame.
    let (sb, cb) = base.theta.sin_cos();
    let d = goal.pos - base.pos;
    let local = Vec2::new(cb * d.x + sb * d.y, -sb * d.x + cb * d.y);
    let theta = goal.theta.map(|t| t - base.theta);
    if n == 1 {
        return vec![vec![wrap(local.y.atan2(local.x))]];
    }
    // The absolute angles (in the base's frame) of links 2.. that are not solved in closed
    // form: all of them when the tool's angle is free, all but the last when it is given. A
    // two-link arm with a given angle is solved for its position and kept where the angle
    // agrees.
    let given = theta.is_some() && n >= 3;
    let free = n - 2 - usize::from(given);
    let per_angle = samples_per_angle(free, s);
    let mut out = Vec::new();
    let mut combination = vec![0usize; free];
    loop {
        // Absolute angles of links 2..n−1, the given tool angle last.
        let mut absolute: Vec<f64> = (combination.iter())
            .map(|&k| -PI + TAU * k as f64 / per_angle as f64)
            .collect();
        if given {
            absolute.push(theta.expect("given"));
        }
        // Walk back from the tool to link 2's joint: the wrist the first two links reach.
        let mut wrist = local;
        for (k, &a) in absolute.iter().enumerate().rev() {
            wrist -= lengths[k + 2] * Vec2::new(a.cos(), a.sin());
        }
        for (a0, a1) in two_links(lengths[0], lengths[1], wrist) {
            // Absolute angles to joint angles: each relative to the link before.
            let angles: Vec<f64> = [a0, a1]
                .into_iter()
                .chain(absolute.iter().copied())
                .collect();
            let q = (0..n)
                .map(|k| {
                    wrap(if k == 0 {
                        angles[0]
                    } else {
                        angles[k] - angles[k - 1]
                    })
                })
                .collect();
            out.push(q);
        }
        if !next_combination(&mut combination, per_angle) {
            break;
        }
    }
    out
}

/// The absolute angles of two links of lengths `l0`, `l1` from a common base whose far end
/// reaches `p`: elbow one way and the other (one pair where they coincide, none out of reach).
fn two_links(l0: f64, l1: f64, p: Vec2) -> Vec<(f64, f64)> {
    let r2 = p.norm_squared();
    if l0 == 0.0 || l1 == 0.0 {
        // One link does the reaching; the other's angle is that link's (any would do).
        let a = p.y.atan2(p.x);
        return vec![(a, a)];
    }
    let c = (r2 - l0 * l0 - l1 * l1) / (2.0 * l0 * l1);
    // Just outside [−1, 1] by rounding at the edge of the reach: the straight or folded arm,
    // which the tolerance check above then judges.
    if !(-1.0 - 1e-12..=1.0 + 1e-12).contains(&c) {
        return Vec::new();
    }
    let elbow = c.clamp(-1.0, 1.0).acos();
    [elbow, -elbow]
        .into_iter()
        .map(|e| {
            let a0 = p.y.atan2(p.x) - (l1 * e.sin()).atan2(l0 + l1 * e.cos());
            (a0, a0 + e)
        })
        .collect()
}

/// Samples per free angle: the settings' per turn, thinned so that all combinations fit.
fn samples_per_angle(free: usize, s: &IkSettings) -> usize {
    let mut per = s.samples_per_turn.max(1);
    while free > 0
        && per > 1
        && per
            .checked_pow(free as u32)
            .is_none_or(|c| c > s.max_combinations)
    {
        per -= 1;
    }
    per
}

/// The next combination of `per`-valued digits; false after the last.
fn next_combination(digits: &mut [usize], per: usize) -> bool {
    for d in digits.iter_mut() {
        *d += 1;
        if *d < per {
            return true;
        }
        *d = 0;
    }
    false
}

/// Every configuration `q + 2π·k` (per joint) within `limits`: for a joint with limits every
/// whole-turn shift that fits them, for one without its angle as it is.
fn shifts_within(q: &[f64], limits: &[Option<[f64; 2]>], n: usize) -> Vec<Vec<f64>> {
    let mut out = vec![Vec::with_capacity(n)];
    for (j, &angle) in q.iter().enumerate() {
        let options: Vec<f64> = match limits.get(j).copied().flatten() {
            None => vec![angle],
            Some([lo, hi]) => {
                let first = ((lo - angle) / TAU).ceil() as i64;
                let last = ((hi - angle) / TAU).floor() as i64;
                (first..=last).map(|k| angle + TAU * k as f64).collect()
            }
        };
        out = out
            .into_iter()
            .flat_map(|prefix| {
                options.iter().map(move |&a| {
                    let mut q = prefix.clone();
                    q.push(a);
                    q
                })
            })
            .collect();
    }
    out
}

/// An angle in (−π, π].
fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI {
        w - TAU
    } else {
        w
    }
}

fn same_angles(a: &[f64], b: &[f64]) -> bool {
    a.iter().zip(b).all(|(x, y)| wrap(x - y).abs() <= 1e-12)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn goal(x: f64, y: f64, theta: Option<f64>) -> ToolGoal {
        ToolGoal {
            pos: Vec2::new(x, y),
            theta,
        }
    }

    /// Every solution puts the tool at the goal.
    fn all_reach(base: Pose, lengths: &[f64], g: ToolGoal, found: &[Vec<f64>]) {
        for q in found {
            let tool = tool_pose(base, lengths, q);
            assert!(
                (tool.pos - g.pos).norm() < 1e-9,
                "{q:?} puts the tool at {:?}",
                tool.pos
            );
            if let Some(t) = g.theta {
                assert!(
                    wrap(tool.theta - t).abs() < 1e-9,
                    "{q:?}: tool angle {}",
                    tool.theta
                );
            }
        }
    }

    #[test]
    fn two_links_elbow_up_and_down_and_out_of_reach() {
        let base = Pose::new(0.5, -0.2, 0.7);
        let lengths = [1.0, 0.6];
        let s = IkSettings::default();
        // Points across the annulus of reach [0.4, 1.6] about the base.
        for k in 0..50 {
            let (r, a) = (0.41 + 1.18 * k as f64 / 49.0, 0.37 * k as f64);
            let g = goal(0.5 + r * a.cos(), -0.2 + r * a.sin(), None);
            let found = inverse_kinematics(base, &lengths, &[None, None], g, &s).unwrap();
            assert_eq!(found.len(), 2, "r = {r}");
            assert!(
                found[0][1] * found[1][1] < 0.0,
                "one elbow each way: {found:?}"
            );
            all_reach(base, &lengths, g, &found);
        }
        for r in [0.3, 1.7] {
            let g = goal(0.5 + r, -0.2, None);
            let e = inverse_kinematics(base, &lengths, &[None, None], g, &s);
            assert_eq!(e, Err(Unreachable::OutOfReach), "r = {r}");
        }
        // At full reach: the straight arm, once.
        let g = goal(0.5 + 1.6 * 0.7f64.cos(), -0.2 + 1.6 * 0.7f64.sin(), None);
        let found = inverse_kinematics(base, &lengths, &[None, None], g, &s).unwrap();
        assert_eq!(found.len(), 1);
        assert!(
            found[0][0].abs() < 1e-6 && found[0][1].abs() < 1e-6,
            "{found:?}"
        );
    }

    /// A link of length 0 (a turntable under the arm) leaves the other to do the reaching.
    #[test]
    fn a_link_of_length_zero_reaches_with_the_other() {
        let base = Pose::new(0.0, 0.0, 0.0);
        let lengths = [0.0, 1.0];
        let g = goal(0.6, 0.8, None);
        let found = inverse_kinematics(base, &lengths, &[None, None], g, &IkSettings::default());
        let found = found.expect("the tool's circle holds the goal");
        assert!(!found.is_empty());
        all_reach(base, &lengths, g, &found);
    }

    #[test]
    fn limits_keep_branches_and_turns_that_fit() {
        let base = Pose::new(0.0, 0.0, 0.0);
        let lengths = [1.0, 1.0];
        let s = IkSettings::default();
        let g = goal(1.0, 1.0, None);
        // The elbow only bends one way: one branch left.
        let one_way = [None, Some([0.0, PI])];
        let found = inverse_kinematics(base, &lengths, &one_way, g, &s).unwrap();
        assert_eq!(found.len(), 1);
        assert!(found[0][1] > 0.0);
        // A base joint of three turns: each branch at every whole turn that fits.
        let turns = [Some([-3.0 * PI, 3.0 * PI]), None];
        let found = inverse_kinematics(base, &lengths, &turns, g, &s).unwrap();
        assert_eq!(found.len(), 6, "{found:?}");
        all_reach(base, &lengths, g, &found);
        assert!(found.iter().all(|q| q[0] >= -3.0 * PI && q[0] <= 3.0 * PI));
        // Both branches outside the elbow's limits.
        let tight = [None, Some([-0.1, 0.1])];
        let e = inverse_kinematics(base, &lengths, &tight, g, &s);
        assert_eq!(e, Err(Unreachable::OutsideLimits));
    }

    #[test]
    fn three_links_with_and_without_the_tool_angle() {
        let base = Pose::new(0.2, 0.1, -0.4);
        let lengths = [0.8, 0.6, 0.3];
        let s = IkSettings::default();
        let none = [None, None, None];
        let g = goal(0.9, 0.8, Some(1.2));
        let found = inverse_kinematics(base, &lengths, &none, g, &s).unwrap();
        assert_eq!(found.len(), 2, "elbow up and down: {found:?}");
        all_reach(base, &lengths, g, &found);
        // The tool's angle free: every sampled angle that can be reached, both branches.
        let free = goal(0.9, 0.8, None);
        let found = inverse_kinematics(base, &lengths, &none, free, &s).unwrap();
        assert!(found.len() > 16, "{}", found.len());
        all_reach(base, &lengths, free, &found);
        // Given an angle the wrist cannot take from there.
        let g = goal(0.2 + 1.65, 0.1, Some(PI));
        assert_eq!(
            inverse_kinematics(base, &lengths, &none, g, &s),
            Err(Unreachable::OutOfReach)
        );
    }

    #[test]
    fn two_links_with_an_angle_keep_the_branch_that_has_it() {
        let base = Pose::new(0.0, 0.0, 0.0);
        let lengths = [1.0, 1.0];
        let s = IkSettings::default();
        let q = [0.3, 1.1];
        let tool = tool_pose(base, &lengths, &q);
        let g = goal(tool.pos.x, tool.pos.y, Some(tool.theta));
        let found = inverse_kinematics(base, &lengths, &[None, None], g, &s).unwrap();
        assert_eq!(found.len(), 1);
        assert!(same_angles(&found[0], &q), "{found:?}");
        let wrong = goal(tool.pos.x, tool.pos.y, Some(tool.theta + 0.5));
        assert_eq!(
            inverse_kinematics(base, &lengths, &[None, None], wrong, &s),
            Err(Unreachable::OutOfReach)
        );
    }

    #[test]
    fn many_links_are_sampled_and_every_sample_reaches() {
        let base = Pose::new(0.0, 0.0, 0.0);
        let lengths = [0.7, 0.6, 0.5, 0.4, 0.2];
        let s = IkSettings {
            samples_per_turn: 12,
            max_combinations: 100,
            ..IkSettings::default()
        };
        let g = goal(1.0, 0.9, Some(0.4));
        let found = inverse_kinematics(base, &lengths, &[None; 5], g, &s).unwrap();
        // Two free angles, thinned from 12 samples each to 10 (10² ≤ 100 < 11²), two branches.
        assert!(
            found.len() > 10 && found.len() <= 2 * 10 * 10,
            "{}",
            found.len()
        );
        all_reach(base, &lengths, g, &found);
        let again = inverse_kinematics(base, &lengths, &[None; 5], g, &s).unwrap();
        assert_eq!(found, again, "deterministic");
    }
}
