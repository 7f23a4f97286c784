//! Where an arm can work and how it moves there (contract section 7): the configurations
//! that put its tool at a task's pose clear of the fixtures, and whether a joint-space move
//! stays clear of them, both proven by the checker.

use super::joint_move::JointMove;
use super::PlannedMove;
use crate::cell::ArmRobot;
use crate::collision::{check, Arm, Body, CheckOptions, Scene};
use crate::geometry::Parts;
use crate::geometry::Vec2;
use crate::motion::{
    inverse_kinematics, tool_pose, IkSettings, JointLimits, JointSample, Pose, Sample, ToolGoal,
    Unreachable,
};

/// An arm as the planner takes it: where it stands, its links and its joints' limits.
#[derive(Clone, Debug)]
pub struct ArmModel {
    /// Its name (the checker names its links by it).
    pub name: String,
    /// The base pose.
    pub base: Pose,
    /// Each link's length and body, in its frame (contract section 6).
    pub links: Vec<(f64, Parts)>,
    /// Joint ranges, speeds and accelerations.
    pub limits: JointLimits,
}

/// Why an arm cannot work at a pose.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refusal {
    /// No joint angles put the tool there.
    OutOfReach,
    /// Some do, but none within the joint limits.
    OutsideLimits,
    /// Some within the limits do, but each brings a link within δ of a fixture.
    InsideFixture,
}

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Refusal::OutOfReach => "out of reach",
            Refusal::OutsideLimits => "reachable only outside its joint limits",
            Refusal::InsideFixture => "reachable only with a link inside a fixture",
        })
    }
}

impl ArmModel {
    /// The arm `name` of a cell, for planning.
    ///
    /// ```
    /// use workcell::cell::ArmRobot;
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// use workcell::motion::{JointLimits, Pose};
    /// use workcell::planning::ArmModel;
    /// let bar = Parts::new(vec![ConvexPolygon::from_vertices(&[[-0.1, -0.1], [1.1, -0.1], [1.1, 0.1], [-0.1, 0.1]])?])?;
    /// let limits = JointLimits { range: vec![None], max_speed: vec![1.0], max_accel: vec![2.0] };
    /// let arm = ArmRobot { base: Pose::new(1.0, 0.0, 0.0), links: vec![(1.0, bar)], home: vec![0.0], limits };
    /// let model = ArmModel::new("A1", &arm);
    /// assert_eq!((model.name.as_str(), model.base, &model.limits), ("A1", arm.base, &arm.limits));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(name: &str, arm: &ArmRobot) -> ArmModel {
        ArmModel {
            name: name.to_owned(),
            base: arm.base,
            links: arm.links.clone(),
            limits: arm.limits.clone(),
        }
    }

    fn lengths(&self) -> Vec<f64> {
        self.links.iter().map(|l| l.0).collect()
    }

    /// The arm's bodies moving through `samples`, for the checker.
    fn bodies(&self, samples: &[JointSample]) -> Vec<Body> {
        let mut arm = Arm::new(self.name.clone(), self.base);
        for (length, body) in &self.links {
            arm = arm.link_of_parts(*length, body.clone());
        }
        for s in samples {
            arm = arm.sample_with_rates(s.t, &s.q, &s.qd);
        }
        arm.bodies().expect("a planned arm's samples are valid")
    }

    /// Whether the arm, moving through `samples`, stays δ clear of every fixture: the checker
    /// certifies it.
    fn clear_of(&self, samples: &[JointSample], fixtures: &[Body], delta: f64) -> bool {
        let mut bodies = self.bodies(samples);
        bodies.extend(fixtures.iter().cloned());
        let Ok(scene) = Scene::with_bodies(delta, bodies) else {
            return false;
        };
        let report = check(&scene, &CheckOptions::default());
        !report.collision && report.certified
    }

    /// Every configuration within the limits that puts the tool at `goal` with every link
    /// at least δ from every fixture, in the order of [`inverse_kinematics`]; or why there
    /// is none.
    ///
    /// ```
    /// use workcell::collision::Body;
    /// use workcell::geometry::{ConvexPolygon, Parts, Vec2};
    /// use workcell::motion::{IkSettings, Pose, ToolGoal};
    /// use workcell::motion::JointLimits;
    /// use workcell::planning::{ArmModel, Refusal};
    /// let bar = |l: f64| Parts::new(vec![ConvexPolygon::from_vertices(&[[-0.05, -0.05], [l + 0.05, -0.05], [l + 0.05, 0.05], [-0.05, 0.05]])?]);
    /// let arm = ArmModel {
    ///     name: "A1".into(),
    ///     base: Pose::new(0.0, 0.0, 0.0),
    ///     links: vec![(1.0, bar(1.0)?), (1.0, bar(1.0)?)],
    ///     limits: JointLimits { range: vec![None, None], max_speed: vec![1.0, 1.0], max_accel: vec![1.0, 1.0] },
    /// };
    /// // A post where the elbow-down solution's elbow would be: only elbow up is left.
    /// let post = Body::obstacle("post", &ConvexPolygon::from_vertices(&[[0.9, -0.1], [1.1, -0.1], [1.1, 0.1], [0.9, 0.1]])?);
    /// let goal = ToolGoal { pos: Vec2::new(1.0, 1.0), theta: None };
    /// let found = arm.configurations(goal, &[post.clone()], 0.01, &IkSettings::default());
    /// assert_eq!(found.map(|q| q.len()), Ok(1));
    /// let far = ToolGoal { pos: Vec2::new(3.0, 0.0), theta: None };
    /// assert_eq!(arm.configurations(far, &[post], 0.01, &IkSettings::default()), Err(Refusal::OutOfReach));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn configurations(
        &self,
        goal: ToolGoal,
        fixtures: &[Body],
        delta: f64,
        settings: &IkSettings,
    ) -> Result<Vec<Vec<f64>>, Refusal> {
        let found = inverse_kinematics(
            self.base,
            &self.lengths(),
            &self.limits.range,
            goal,
            settings,
        )
        .map_err(|e| match e {
            Unreachable::OutOfReach => Refusal::OutOfReach,
            Unreachable::OutsideLimits => Refusal::OutsideLimits,
        })?;
        let at_rest = |q: &Vec<f64>| {
            let rest = JointSample {
                t: 0.0,
                q: q.clone(),
                qd: vec![0.0; q.len()],
            };
            self.clear_of(&[rest], fixtures, delta)
        };
        let clear: Vec<Vec<f64>> = found.into_iter().filter(at_rest).collect();
        if clear.is_empty() {
            return Err(Refusal::InsideFixture);
        }
        Ok(clear)
    }

    /// The joint-space move as a planned move (see [`PlannedMove::joints`]): its joints,
    /// and the tool's pose and velocity at the same times, and the tool's path.
    ///
    /// ```
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// use workcell::motion::{JointLimits, Pose};
    /// use workcell::planning::{joint_move, ArmModel};
    /// let bar = Parts::new(vec![ConvexPolygon::from_vertices(&[[-0.05, -0.05], [1.05, -0.05], [1.05, 0.05], [-0.05, 0.05]])?])?;
    /// let limits = JointLimits { range: vec![None], max_speed: vec![1.0], max_accel: vec![1.0] };
    /// let arm = ArmModel { name: "A1".into(), base: Pose::new(0.0, 0.0, 0.0), links: vec![(1.0, bar)], limits };
    /// let quarter = arm.planned(&joint_move(&[0.0], &[1.0], &arm.limits, 4));
    /// assert_eq!(quarter.samples.len(), quarter.joints.len());
    /// let end = quarter.samples.last().unwrap();
    /// assert!((end.pos.x - 1f64.cos()).abs() < 1e-12 && (end.theta - 1.0).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn planned(&self, motion: &JointMove) -> PlannedMove {
        let lengths = self.lengths();
        let samples: Vec<Sample> = (motion.samples.iter())
            .map(|s| {
                let tool = tool_pose(self.base, &lengths, &s.q);
                // d/dt of the tool point: each link turns at the sum of the rates before it.
                let (mut angle, mut rate) = (self.base.theta, 0.0);
                let mut vel = Vec2::zeros();
                for (k, &l) in lengths.iter().enumerate() {
                    angle += s.q[k];
                    rate += s.qd[k];
                    vel += Vec2::new(-angle.sin(), angle.cos()) * (l * rate);
                }
                Sample {
                    t: s.t,
                    pos: tool.pos,
                    theta: tool.theta,
                    vel,
                    omega: rate,
                }
            })
            .collect();
        let mut path: Vec<Vec2> = samples.iter().map(|s| s.pos).collect();
        path.dedup();
        PlannedMove {
            duration: motion.duration,
            path,
            samples,
            primitives: Vec::new(),
            joints: motion.samples.clone(),
        }
    }

    /// Whether the joint-space move keeps every link δ clear of every fixture (certified by
    /// the checker).
    ///
    /// ```
    /// use workcell::collision::Body;
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// use workcell::motion::Pose;
    /// use workcell::motion::JointLimits;
    /// use workcell::planning::{joint_move, ArmModel};
    /// let bar = Parts::new(vec![ConvexPolygon::from_vertices(&[[-0.05, -0.05], [1.05, -0.05], [1.05, 0.05], [-0.05, 0.05]])?])?;
    /// let limits = JointLimits { range: vec![None], max_speed: vec![1.0], max_accel: vec![1.0] };
    /// let arm = ArmModel { name: "A1".into(), base: Pose::new(0.0, 0.0, 0.0), links: vec![(1.0, bar)], limits };
    /// let quarter = joint_move(&[0.0], &[1.57], &arm.limits, 4);
    /// let post = |x: f64, y: f64| Body::obstacle("post", &ConvexPolygon::from_vertices(&[[x, y], [x + 0.2, y], [x + 0.2, y + 0.2], [x, y + 0.2]]).unwrap());
    /// assert!(!arm.move_is_clear(&quarter, &[post(0.5, 0.5)], 0.01)); // in the swept quarter
    /// assert!(arm.move_is_clear(&quarter, &[post(-0.8, -0.8)], 0.01)); // behind the base
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn move_is_clear(&self, mv: &JointMove, fixtures: &[Body], delta: f64) -> bool {
        self.clear_of(&mv.samples, fixtures, delta)
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::geometry::{ConvexPolygon, Vec2};
    use crate::planning::joint_move;

    /// A link `l` long and 0.1 wide, its ends rounded off 0.05 beyond its joints.
    pub(in crate::planning) fn bar(l: f64) -> Parts {
        let corners = [
            [-0.05, -0.05],
            [l + 0.05, -0.05],
            [l + 0.05, 0.05],
            [-0.05, 0.05],
        ];
        Parts::new(vec![ConvexPolygon::from_vertices(&corners).unwrap()]).unwrap()
    }

    fn arm(range: Vec<Option<[f64; 2]>>) -> ArmModel {
        ArmModel {
            name: "A1".into(),
            base: Pose::new(0.0, 0.0, 0.0),
            links: vec![(1.0, bar(1.0)), (1.0, bar(1.0))],
            limits: JointLimits {
                range,
                max_speed: vec![1.0, 1.0],
                max_accel: vec![2.0, 2.0],
            },
        }
    }

    fn square(x: f64, y: f64, half: f64) -> Body {
        let corners = [
            [x - half, y - half],
            [x + half, y - half],
            [x + half, y + half],
            [x - half, y + half],
        ];
        Body::obstacle("post", &ConvexPolygon::from_vertices(&corners).unwrap())
    }

    #[test]
    fn each_refusal_names_its_reason() {
        let s = IkSettings::default();
        let goal = ToolGoal {
            pos: Vec2::new(1.0, 1.0),
            theta: None,
        };
        let free = arm(vec![None, None]);
        assert_eq!(
            free.configurations(goal, &[], 0.01, &s).map(|q| q.len()),
            Ok(2)
        );
        let stiff = arm(vec![None, Some([-0.1, 0.1])]);
        assert_eq!(
            stiff.configurations(goal, &[], 0.01, &s),
            Err(Refusal::OutsideLimits)
        );
        // A post on the tool's point: every configuration puts the last link in it.
        let on_tool = square(1.0, 1.0, 0.05);
        assert_eq!(
            free.configurations(goal, &[on_tool], 0.01, &s),
            Err(Refusal::InsideFixture)
        );
    }

    #[test]
    fn a_move_through_a_post_is_not_clear_and_one_past_it_is() {
        let free = arm(vec![None, None]);
        let l = &free.limits;
        // Straight, from pointing along +x to pointing along +y: it sweeps the quarter
        // between, where the post stands.
        let sweep = joint_move(&[0.0, 0.0], &[std::f64::consts::FRAC_PI_2, 0.0], l, 4);
        let post = square(1.2, 1.2, 0.1);
        assert!(!free.move_is_clear(&sweep, std::slice::from_ref(&post), 0.01));
        // The same turn with the elbow folded back keeps inside the post's circle.
        let folded = joint_move(&[0.0, 2.8], &[std::f64::consts::FRAC_PI_2, 2.8], l, 4);
        assert!(free.move_is_clear(&folded, &[post], 0.01));
    }
}
