//! An arm as a file gives it (contract sections 6 and 7): `base` and `links`, each link its
//! length and body; in a cell also its home angles and joint limits. Scenes and cells read
//! the same way, every fault named by its field.

use super::body_shape::BodyShape;
use super::model::ArmRobot;
use super::object_only::object_only;
use super::reading::Point;
use super::InputError;
use crate::geometry::Parts;
use crate::motion::{JointLimits, Pose};
use serde::Deserialize;
use std::path::Path;

/// A link of an arm as written: its length and body in its own frame.
#[derive(Deserialize)]
#[serde(remote = "Self", deny_unknown_fields)]
pub(super) struct RawLink {
    length: f64,
    #[serde(default)]
    shape: Option<Vec<Point>>,
    #[serde(default)]
    parts: Option<Vec<Vec<Point>>>,
    #[serde(default)]
    outline: Option<Vec<Point>>,
}

object_only!(
    RawLink,
    "a link: an object with `length` and one of `shape`, `parts`, `outline`"
);

/// A joint limit given for every joint (one number) or joint by joint (a list).
#[derive(Deserialize)]
#[serde(untagged)]
pub(super) enum PerJoint {
    One(f64),
    Each(Vec<f64>),
}

/// Where an arm is read from: the file, its name and its field path (`robots[2]`).
pub(super) struct ArmAt<'a> {
    pub file: &'a Path,
    pub name: &'a str,
    pub at: &'a str,
}

impl ArmAt<'_> {
    fn err(&self, field: &str, reason: impl Into<String>) -> InputError {
        InputError::new(
            self.file,
            Some(self.name),
            format!("{}.{field}", self.at),
            reason.into(),
        )
    }

    /// Refuses the keys of a rigid body given to an arm (`given`: each key and whether it
    /// is there).
    pub fn refuse_rigid_keys(&self, given: &[(&str, bool)]) -> Result<(), InputError> {
        match given.iter().find(|(_, there)| *there) {
            Some((key, _)) => Err(self.err(
                key,
                format!(
                    "an arm takes `base` and `links` (each link with its own body), not `{key}`"
                ),
            )),
            None => Ok(()),
        }
    }

    /// The base pose (`[x, y, theta]`, or `[x, y]` at angle 0) and the links.
    pub fn frame(
        &self,
        base: Option<&[f64]>,
        links: Option<&[RawLink]>,
        warnings: &mut Vec<String>,
    ) -> Result<(Pose, Vec<(f64, Parts)>), InputError> {
        let Some(links) = links else {
            return Err(self.err("links", "an arm needs `links` beside `base`"));
        };
        let base = match base {
            Some(&[x, y]) => Pose::new(x, y, 0.0),
            Some(&[x, y, theta]) => Pose::new(x, y, theta),
            Some(_) => {
                return Err(self.err(
                    "base",
                    "expected the base pose [x, y, theta] (or [x, y] at angle 0)",
                ))
            }
            None => return Err(self.err("base", "an arm needs `base`")),
        };
        if links.is_empty() {
            return Err(self.err("links", "an arm needs at least one link"));
        }
        let mut out = Vec::with_capacity(links.len());
        for (k, link) in links.iter().enumerate() {
            let at = format!("{}.links[{k}]", self.at);
            if !(link.length.is_finite() && link.length >= 0.0) {
                let reason = format!("must be finite and >= 0, got {}", link.length);
                return Err(self.err(&format!("links[{k}].length"), reason));
            }
            let shape = BodyShape {
                shape: link.shape.as_deref(),
                parts: link.parts.as_deref(),
                outline: link.outline.as_deref(),
            };
            out.push((
                link.length,
                shape.parts(self.file, self.name, &at, warnings)?,
            ));
        }
        Ok((base, out))
    }

    /// One value per joint from a number for all or a list of `joints` numbers, each
    /// positive and finite.
    pub fn per_joint(
        &self,
        field: &str,
        given: Option<&PerJoint>,
        joints: usize,
    ) -> Result<Vec<f64>, InputError> {
        let values = match given {
            None => return Err(self.err(field, format!("missing field `{field}`"))),
            Some(PerJoint::One(v)) => vec![*v; joints],
            Some(PerJoint::Each(list)) if list.len() == joints => list.clone(),
            Some(PerJoint::Each(list)) => {
                let reason = format!(
                    "{} values for {joints} joints: give one per joint, or one number for all",
                    list.len()
                );
                return Err(self.err(field, reason));
            }
        };
        Ok(values)
    }

    /// `joint_limits` as read: absent (no limits) or one `[min, max]` (or `null`, no limit)
    /// per joint.
    pub fn ranges(
        &self,
        given: Option<&[Option<[f64; 2]>]>,
        joints: usize,
    ) -> Result<Vec<Option<[f64; 2]>>, InputError> {
        match given {
            None => Ok(vec![None; joints]),
            Some(list) if list.len() == joints => Ok(list.to_vec()),
            Some(list) => Err(self.err(
                "joint_limits",
                format!(
                    "{} ranges for {joints} joints: give one [min, max] per joint",
                    list.len()
                ),
            )),
        }
    }

    /// What an arm of a cell must be, wherever it comes from (a file or code): a finite base,
    /// links of finite non-negative length, one home angle and one limit per joint, ranges
    /// `min < max` that hold the home angles, speeds and accelerations positive and finite.
    pub fn check(&self, arm: &ArmRobot) -> Result<(), InputError> {
        let joints = arm.links.len();
        if joints == 0 {
            return Err(self.err("links", "an arm needs at least one link"));
        }
        let b = arm.base;
        if !(b.pos.x.is_finite() && b.pos.y.is_finite() && b.theta.is_finite()) {
            return Err(self.err("base", "must be finite"));
        }
        if let Some(k) = (arm.links.iter()).position(|l| !(l.0.is_finite() && l.0 >= 0.0)) {
            let reason = format!("must be finite and >= 0, got {}", arm.links[k].0);
            return Err(self.err(&format!("links[{k}].length"), reason));
        }
        let counts = [
            ("home", arm.home.len()),
            ("joint_limits", arm.limits.range.len()),
            ("max_joint_speed", arm.limits.max_speed.len()),
            ("max_joint_accel", arm.limits.max_accel.len()),
        ];
        if let Some((field, n)) = counts.iter().find(|(_, n)| *n != joints) {
            let reason = format!("{n} values for an arm of {joints} links: one per joint");
            return Err(self.err(field, reason));
        }
        self.check_rates(&arm.limits)?;
        for (j, &q) in arm.home.iter().enumerate() {
            if !q.is_finite() {
                return Err(self.err(&format!("home[{j}]"), format!("must be finite, got {q}")));
            }
            let Some([lo, hi]) = arm.limits.range[j] else {
                continue;
            };
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                let reason =
                    format!("expected [min, max] with min < max, both finite, got [{lo}, {hi}]");
                return Err(self.err(&format!("joint_limits[{j}]"), reason));
            }
            if !(lo..=hi).contains(&q) {
                let reason = format!(
                    "the home angle {q} of joint {j} is outside its joint limits [{lo}, {hi}]"
                );
                return Err(self.err(&format!("home[{j}]"), reason));
            }
        }
        Ok(())
    }

    fn check_rates(&self, limits: &JointLimits) -> Result<(), InputError> {
        let fields = [
            ("max_joint_speed", &limits.max_speed),
            ("max_joint_accel", &limits.max_accel),
        ];
        for (field, values) in fields {
            if let Some(j) = values.iter().position(|v| !(v.is_finite() && *v > 0.0)) {
                let reason = format!("must be a positive number, got {}", values[j]);
                return Err(self.err(&format!("{field}[{j}]"), reason));
            }
        }
        Ok(())
    }
}
