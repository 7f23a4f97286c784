//! [`Arm`]: an articulated robot built in code (contract section 6), as checker bodies.

use super::Body;
use crate::geometry::{ConvexPolygon, Parts};
use crate::motion::{ArmError, ArmMotion, JointSample, Pose};

/// A planar arm of revolute joints, built link by link and sample by sample; [`Arm::bodies`]
/// gives its links as checker bodies. Link bodies are given in their own frame: origin at
/// the link's joint, x along the link.
///
/// ```
/// use workcell::collision::{check, Arm, Body, CheckOptions, Scene};
/// use workcell::geometry::ConvexPolygon;
/// use workcell::motion::Pose;
/// let bar = |l: f64| ConvexPolygon::from_vertices(&[[-0.1, -0.1], [l + 0.1, -0.1], [l + 0.1, 0.1], [-0.1, 0.1]]);
/// // A SCARA arm folding its elbow back over the table, past a post at (0.4, 0.9).
/// let arm = Arm::new("A1", Pose::new(0.0, 0.0, 0.0))
///     .link(0.8, bar(0.8)?)
///     .link(0.6, bar(0.6)?)
///     .sample(0.0, &[0.0, 0.0])
///     .sample(2.0, &[0.8, 2.2]);
/// let post = ConvexPolygon::from_vertices(&[[0.3, 0.8], [0.5, 0.8], [0.5, 1.0], [0.3, 1.0]])?;
/// let mut bodies = arm.bodies()?;
/// bodies.push(Body::obstacle("post", &post));
/// let report = check(&Scene::with_bodies(0.01, bodies)?, &CheckOptions::default());
/// let contact = report.verdict().contact().cloned().expect("the forearm meets the post");
/// assert_eq!((contact.bodies[0].as_str(), contact.links), ("A1", Some([Some(1), None])));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Arm {
    name: String,
    base: Pose,
    links: Vec<(f64, Parts)>,
    samples: Vec<JointSample>,
}

impl Arm {
    /// An arm named `name` with its base at `base`, no links and no samples yet.
    pub fn new(name: impl Into<String>, base: Pose) -> Arm {
        Arm {
            name: name.into(),
            base,
            links: Vec::new(),
            samples: Vec::new(),
        }
    }

    /// Adds a link of `length` whose body is one convex polygon.
    pub fn link(self, length: f64, body: ConvexPolygon) -> Arm {
        let parts = Parts::new(vec![body]).expect("one valid polygon is a body");
        self.link_of_parts(length, parts)
    }

    /// Adds a link of `length` whose body is the union of convex parts.
    pub fn link_of_parts(mut self, length: f64, body: Parts) -> Arm {
        self.links.push((length, body));
        self
    }

    /// Adds a sample: joint angles `q` (one per link) at time `t`; the rates are derived.
    pub fn sample(mut self, t: f64, q: &[f64]) -> Arm {
        self.samples.push(JointSample {
            t,
            q: q.to_vec(),
            qd: Vec::new(),
        });
        self
    }

    /// Adds a sample with its joint rates `qd` (used only by the paper's velocity bound and
    /// the pictures; the checker's bound comes from the angles).
    pub fn sample_with_rates(mut self, t: f64, q: &[f64], qd: &[f64]) -> Arm {
        self.samples.push(JointSample {
            t,
            q: q.to_vec(),
            qd: qd.to_vec(),
        });
        self
    }

    /// The links as checker bodies, all moved by the arm; refuses what
    /// [`ArmMotion::new`] refuses (no link, no sample, angles of the wrong count, times not
    /// increasing, a negative length).
    pub fn bodies(self) -> Result<Vec<Body>, ArmError> {
        let lengths = self.links.iter().map(|l| l.0).collect();
        let reach = self.links.iter().map(|l| l.1.hull().radius()).collect();
        let motion = ArmMotion::new(self.base, lengths, reach, self.samples)?;
        let bodies = self.links.into_iter().map(|l| l.1).collect();
        Ok(Body::arm(self.name, motion, bodies))
    }
}
