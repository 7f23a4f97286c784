//! The exact reference for arms, shared by the tests (`arms.rs`) and the arms benchmark
//! (`benches/arms.rs`): a scene read back into plain arrays, forward kinematics of its own,
//! and conservative advancement on the link polygons with the independent oracle's exact
//! distance and the joint-rate speed bound of each link on each segment of its samples.

use super::{exact_distance, pose_at, Shape};
use workcell::collision::Scene;

/// An arm as the test draws it: base, link lengths, each link's polygon in its frame, and
/// samples `(t, q)`.
#[derive(Clone, Debug)]
pub struct ArmSpec {
    pub name: String,
    pub base: [f64; 3],
    pub lengths: Vec<f64>,
    pub links: Vec<Shape>,
    pub samples: Vec<(f64, Vec<f64>)>,
}

/// A rigid robot: a polygon and samples `[t, x, y, θ]`.
#[derive(Clone, Debug)]
pub struct RigidSpec {
    pub shape: Shape,
    pub samples: Vec<[f64; 4]>,
}

#[derive(Clone, Debug)]
pub struct SceneSpec {
    pub arms: Vec<ArmSpec>,
    pub rigid: Vec<RigidSpec>,
    pub fixtures: Vec<Shape>,
}

impl SceneSpec {
    /// A generated scene as the reference reads it: each arm's base, lengths, link polygons
    /// and joint samples; each rigid robot's polygon and poses; each obstacle in the world.
    pub fn of_scene(scene: &Scene) -> SceneSpec {
        use workcell::motion::Motion;
        let vertices = |p: &workcell::geometry::ConvexPolygon| -> Shape {
            p.vertices().iter().map(|v| [v.x, v.y]).collect()
        };
        let mut spec = SceneSpec {
            arms: Vec::new(),
            rigid: Vec::new(),
            fixtures: Vec::new(),
        };
        for (k, b) in scene.bodies.iter().enumerate() {
            assert!(b.parts.is_none(), "generated arm scenes are convex");
            match &b.motion {
                Motion::Link(l) => {
                    if k > 0 && scene.bodies[k - 1].same_arm(b) {
                        spec.arms.last_mut().unwrap().links.push(vertices(&b.shape));
                        continue;
                    }
                    let base = l.arm.base();
                    spec.arms.push(ArmSpec {
                        name: b.name.clone(),
                        base: [base.pos.x, base.pos.y, base.theta],
                        lengths: l.arm.lengths().to_vec(),
                        links: vec![vertices(&b.shape)],
                        samples: l.arm.samples().iter().map(|s| (s.t, s.q.clone())).collect(),
                    });
                }
                Motion::Sampled(tr) => spec.rigid.push(RigidSpec {
                    shape: vertices(&b.shape),
                    samples: tr
                        .samples()
                        .iter()
                        .map(|s| [s.t, s.pos.x, s.pos.y, s.theta])
                        .collect(),
                }),
                Motion::Fixed(p) => spec.fixtures.push(super::place(
                    &vertices(&b.shape),
                    [p.pos.x, p.pos.y, p.theta],
                )),
            }
        }
        spec
    }

    /// The reference's bodies in the scene's order: each link of each arm, the rigid robot,
    /// the fixture.
    pub fn bodies(&self) -> Vec<RefBody<'_>> {
        let mut out: Vec<RefBody> = Vec::new();
        for a in &self.arms {
            out.extend((0..a.links.len()).map(|k| RefBody::Link(a, k)));
        }
        out.extend(self.rigid.iter().map(RefBody::Rigid));
        out.extend(self.fixtures.iter().map(RefBody::Fixed));
        out
    }

    pub fn horizon(&self) -> (f64, f64) {
        let mut ts: Vec<f64> = self
            .arms
            .iter()
            .flat_map(|a| a.samples.iter().map(|s| s.0))
            .collect();
        for r in &self.rigid {
            ts.extend(r.samples.iter().map(|s| s[0]));
        }
        ts.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
                (lo.min(t), hi.max(t))
            })
    }
}

#[derive(Clone, Copy)]
pub enum RefBody<'s> {
    Link(&'s ArmSpec, usize),
    Rigid(&'s RigidSpec),
    Fixed(&'s Shape),
}

/// The joint angles of `a` at `t`: linear per joint, held outside the samples.
fn q_at(a: &ArmSpec, t: f64) -> Vec<f64> {
    let s = &a.samples;
    if t <= s[0].0 {
        return s[0].1.clone();
    }
    let last = &s[s.len() - 1];
    if t >= last.0 {
        return last.1.clone();
    }
    let k = s.iter().rposition(|x| x.0 <= t).unwrap();
    let (p, q) = (&s[k], &s[k + 1]);
    let u = (t - p.0) / (q.0 - p.0);
    p.1.iter().zip(&q.1).map(|(a, b)| a + (b - a) * u).collect()
}

/// The test's own forward kinematics (contract section 6).
fn link_pose(a: &ArmSpec, q: &[f64], link: usize) -> [f64; 3] {
    let (mut x, mut y) = (a.base[0], a.base[1]);
    let mut th = a.base[2] + q[0];
    for (length, turn) in a.lengths[..link].iter().zip(&q[1..=link]) {
        x += length * th.cos();
        y += length * th.sin();
        th += turn;
    }
    [x, y, th]
}

fn radius(shape: &Shape) -> f64 {
    shape.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max)
}

impl RefBody<'_> {
    pub fn robot(&self) -> bool {
        !matches!(self, RefBody::Fixed(_))
    }

    pub fn world(&self, t: f64) -> Shape {
        match *self {
            RefBody::Link(a, k) => {
                let pose = link_pose(a, &q_at(a, t), k);
                super::place(&a.links[k], pose)
            }
            RefBody::Rigid(r) => super::place(&r.shape, pose_at(&r.samples, t)),
            RefBody::Fixed(s) => s.clone(),
        }
    }

    /// How fast any point can move on the segment holding `t`, and when that segment ends.
    pub fn speed_bound(&self, t: f64) -> (f64, f64) {
        let segment = |times: &[f64]| {
            times
                .windows(2)
                .position(|w| w[0] <= t && t < w[1])
                .ok_or(if t < times[0] {
                    times[0]
                } else {
                    f64::INFINITY
                })
        };
        match *self {
            RefBody::Fixed(_) => (0.0, f64::INFINITY),
            RefBody::Rigid(r) => {
                let times: Vec<f64> = r.samples.iter().map(|s| s[0]).collect();
                match segment(&times) {
                    Err(end) => (0.0, end),
                    Ok(i) => {
                        let (p, q) = (r.samples[i], r.samples[i + 1]);
                        let travel = (q[1] - p[1]).hypot(q[2] - p[2])
                            + radius(&r.shape) * (q[3] - p[3]).abs();
                        (travel / (q[0] - p[0]), q[0])
                    }
                }
            }
            RefBody::Link(a, k) => {
                let times: Vec<f64> = a.samples.iter().map(|s| s.0).collect();
                match segment(&times) {
                    Err(end) => (0.0, end),
                    Ok(i) => {
                        let (p, q) = (&a.samples[i], &a.samples[i + 1]);
                        let dt = q.0 - p.0;
                        let lever =
                            |j: usize| a.lengths[j..k].iter().sum::<f64>() + radius(&a.links[k]);
                        let v: f64 = (0..=k)
                            .map(|j| (q.1[j] - p.1[j]).abs() / dt * lever(j))
                            .sum();
                        (v, q.0)
                    }
                }
            }
        }
    }
}

/// Conservative advancement of one pair (the reference of `parts_checker` too).
pub fn first_contact(
    a: RefBody,
    b: RefBody,
    horizon: (f64, f64),
    delta: f64,
    min_step: f64,
) -> Result<Option<(f64, f64)>, ()> {
    let distance = |t: f64| exact_distance(&a.world(t), &b.world(t));
    let speed = |t: f64| {
        let ((va, ea), (vb, eb)) = (a.speed_bound(t), b.speed_bound(t));
        (va + vb, ea.min(eb))
    };
    super::advance_to_contact(distance, speed, horizon, delta, min_step)
}

/// Every pair the scene checks, in its order: robots against robots (never two links of one
/// arm), then robots against the fixture.
pub fn pairs(bodies: &[RefBody]) -> Vec<(usize, usize)> {
    let same_arm = |i: usize, j: usize| match (bodies[i], bodies[j]) {
        (RefBody::Link(a, _), RefBody::Link(b, _)) => std::ptr::eq(a, b),
        _ => false,
    };
    let n = bodies.len();
    let robot = |k: &usize| bodies[*k].robot();
    let mut out = Vec::new();
    for i in (0..n).filter(robot) {
        out.extend(
            (i + 1..n)
                .filter(|j| robot(j) && !same_arm(i, *j))
                .map(|j| (i, j)),
        );
    }
    for i in (0..n).filter(robot) {
        out.extend((0..n).filter(|j| !robot(j)).map(|j| (i, j)));
    }
    out
}

/// The proven prefix's end, the first time found closer than δ, and the pair.
pub type SceneContact = (f64, f64, (usize, usize));

/// The reference's first contact of the whole scene: `(proven, hit, pair)`, the prefix it
/// proves δ apart and the first time it finds closer than δ, on the pair that comes first;
/// `Ok(None)` when no pair comes within δ; `Err` for a graze it cannot decide.
pub fn scene_first_contact(
    spec: &SceneSpec,
    delta: f64,
    min_step: f64,
) -> Result<Option<SceneContact>, ()> {
    let bodies = spec.bodies();
    let mut truth: Option<SceneContact> = None;
    for (i, j) in pairs(&bodies) {
        if let Some((proven, hit)) =
            first_contact(bodies[i], bodies[j], spec.horizon(), delta, min_step)?
        {
            if truth.is_none_or(|(_, h, _)| hit < h) {
                truth = Some((proven, hit, (i, j)));
            }
        }
    }
    Ok(truth)
}
