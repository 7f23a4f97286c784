//! Scenes with arms (contract section 6): two SCARA arms sharing a table, an arm sweeping
//! past a fixture just over δ away, joints of several turns that meet a post only between
//! samples, an arm against a rigid robot crossing its reach, long links with a fast tip, a
//! contact in the last 1 % of the horizon, and a hall of arms and rigid robots.

use super::smooth::{time_grid, Smooth, R};
use crate::collision::Body;
use crate::geometry::{ConvexPolygon, Parts, Vec2};
use crate::motion::{ArmMotion, JointSample, Pose, Sample, Trajectory};
use rand::Rng;
use std::f64::consts::{PI, TAU};

/// A link `length` long and `2·half` wide along its frame's x axis, with rounded-off ends of
/// `half` beyond its joints.
fn link(length: f64, half: f64) -> Parts {
    let bar = [
        [-half, -half],
        [length + half, -half],
        [length + half, half],
        [-half, half],
    ];
    let polygon = ConvexPolygon::from_vertices(&bar).expect("a link is a rectangle");
    Parts::new(vec![polygon]).expect("one convex part")
}

/// An arm's bodies: links of these lengths and half-widths, moved through `samples`.
fn arm(name: &str, base: Pose, links: &[(f64, f64)], samples: Vec<JointSample>) -> Vec<Body> {
    let bodies: Vec<Parts> = links.iter().map(|&(l, h)| link(l, h)).collect();
    let reach = bodies.iter().map(|p| p.hull().radius()).collect();
    let lengths = links.iter().map(|l| l.0).collect();
    let motion = ArmMotion::new(base, lengths, reach, samples).expect("generated arms are valid");
    Body::arm(name, motion, bodies)
}

/// Smooth joint angles: each joint a sum of two sines about `centre`, of amplitude up to
/// `swing`, sampled at `n` times over [0, `horizon`].
fn joint_samples(
    rng: &mut R,
    centre: &[f64],
    swing: f64,
    n: usize,
    horizon: f64,
) -> Vec<JointSample> {
    let waves: Vec<[(f64, f64, f64); 2]> = centre
        .iter()
        .map(|_| {
            let mut wave = || {
                (
                    rng.random_range(0.2..1.0) * swing / 2.0,
                    rng.random_range(0.1..0.8),
                    rng.random_range(0.0..TAU),
                )
            };
            [wave(), wave()]
        })
        .collect();
    time_grid(rng, n, 0.0, horizon)
        .into_iter()
        .map(|t| JointSample {
            t,
            q: centre
                .iter()
                .zip(&waves)
                .map(|(c, w)| c + w.iter().map(|(a, f, p)| a * (f * t + p).sin()).sum::<f64>())
                .collect(),
            qd: Vec::new(),
        })
        .collect()
}

/// Two 2-link SCARA arms whose bases stand 1.4 to 2.6 apart, each reaching about 1.3 over
/// the table between them, on smooth joint motions of 100 samples; about half collide.
pub(super) fn arms(rng: &mut R) -> Vec<Body> {
    let gap = rng.random_range(1.4..2.6);
    let mut bodies = Vec::new();
    // Folded to either side of the table's middle line at rest: the arms meet only when
    // their motions bring them across it.
    for (k, (x, facing, fold)) in [(0.0, 0.0, 1.0), (gap, PI, -1.0)].into_iter().enumerate() {
        let links = [
            (rng.random_range(0.6..0.8), 0.08),
            (rng.random_range(0.4..0.6), 0.06),
        ];
        let swing = rng.random_range(0.8..2.0);
        let samples = joint_samples(rng, &[0.7 * fold, -1.4 * fold], swing, 100, 10.0);
        let base = Pose::new(x, 0.0, facing);
        bodies.extend(arm(&format!("A{}", k + 1), base, &links, samples));
    }
    bodies
}

/// One arm sweeping its straight 2 links about its base past a box whose near face is 1.1δ
/// to 1.5δ beyond the farthest corner's circle, where the sweep passes: always free.
pub(super) fn arm_sweep(rng: &mut R, delta: f64) -> Vec<Body> {
    let links = [
        (rng.random_range(0.5..0.9), 0.07),
        (rng.random_range(0.3..0.6), 0.05),
    ];
    let gap = rng.random_range(1.1..1.5) * delta;
    let (fixture, mid) = box_past(rng, links, gap);
    // Turning by 2·span at a constant rate, 2 to 12 samples, past the box at a time drawn
    // in [2, 8], not on any regular grid of looks.
    let (span, pass) = (rng.random_range(0.6..2.5), rng.random_range(2.0..8.0));
    let n = rng.random_range(2..=12usize);
    let samples = time_grid(rng, n, 0.0, 10.0)
        .into_iter()
        .map(|t| base_joint(t, mid + 2.0 * span * (t - pass) / 10.0))
        .collect();
    let mut bodies = arm("A1", Pose::new(0.0, 0.0, 0.0), &links, samples);
    bodies.push(Body::obstacle("F1", &fixture));
    bodies
}

/// Long links (3 to 5, then 1 to 2) that swing fast past a box: 0.3 to 0.6 rad each side of
/// it within 0.02 to 0.05 s (the tip at 25 to 200 units a second), slowly before and after.
/// Half the scenes graze the box, its near face δ·(1 − 0.02 to 0.1) beyond the tip's
/// circle, for 0.5 to 7 ms; the others miss it by 0.05δ to 0.2δ. Fast enough that a graze
/// crosses δ steeply: no time tolerance of the checker holds the distance within its
/// grazing allowance of δ.
pub(super) fn arm_long(rng: &mut R, delta: f64) -> Vec<Body> {
    let links = [
        (rng.random_range(3.0..5.0), 0.05),
        (rng.random_range(1.0..2.0), 0.04),
    ];
    let gap = if rng.random_bool(0.5) {
        delta * (1.0 - 10f64.powf(rng.random_range(-1.7..-1.0)))
    } else {
        delta * (1.0 + rng.random_range(0.05..0.2))
    };
    let (fixture, mid) = box_past(rng, links, gap);
    let (pass, half) = (rng.random_range(2.0..8.0), rng.random_range(0.02..0.05));
    let (swing, slow) = (rng.random_range(0.3..0.6), rng.random_range(0.1..0.5));
    let samples = [
        (0.0, -swing - slow),
        (pass - half, -swing),
        (pass + half, swing),
        (10.0, swing + slow),
    ];
    let samples = samples.map(|(t, q)| base_joint(t, mid + q)).to_vec();
    let mut bodies = arm("A1", Pose::new(0.0, 0.0, 0.0), &links, samples);
    bodies.push(Body::obstacle("F1", &fixture));
    bodies
}

/// A sample of a straight 2-link arm: the base joint at `q0`, the elbow straight.
fn base_joint(t: f64, q0: f64) -> JointSample {
    JointSample {
        t,
        q: vec![q0, 0.0],
        qd: Vec::new(),
    }
}

/// A box for a straight arm of two `links` based at the origin, in a direction drawn at
/// random, whose near face is `gap` beyond the circle of the arm's farthest corner; and the
/// base joint's angle at which that corner points at the box.
fn box_past(rng: &mut R, links: [(f64, f64); 2], gap: f64) -> (ConvexPolygon, f64) {
    // Straight: the farthest point is the last link's outer corner.
    let far = Vec2::new(links[0].0 + links[1].0 + links[1].1, links[1].1).norm();
    let phi = rng.random_range(0.0..TAU);
    let (dir, side) = (
        Vec2::new(phi.cos(), phi.sin()),
        Vec2::new(-phi.sin(), phi.cos()),
    );
    let near = (far + gap) * dir;
    let corners = [
        near - 0.2 * side,
        near + 0.2 * side,
        near + 0.2 * side + 0.3 * dir,
        near - 0.2 * side + 0.3 * dir,
    ];
    let points: Vec<[f64; 2]> = corners.iter().map(|p| [p.x, p.y]).collect();
    let fixture = ConvexPolygon::from_vertices(&points).expect("a box");
    // The corner's own angle off the link.
    let corner = (links[1].1).atan2(links[0].0 + links[1].0 + links[1].1);
    (fixture, phi - corner)
}

/// A straight 2-link arm turning its base joint at a constant rate over [0, 10] towards a
/// post beside link 0: the post's corner nearest the arm lies at radius ρ on a ray at angle β,
/// the post itself beyond that ray. Link 0's leading edge (half-width h) is then
/// ρ·sin(β − α) − h from the corner while the arm points at α < β, so it comes within δ
/// exactly when α reaches β − asin((h + δ)/ρ): placed at a time in the last 1 % of the
/// horizon, or 1.1δ to 1.5δ beyond the arm's last angle.
pub(super) fn arm_late(rng: &mut R, delta: f64) -> Vec<Body> {
    let (l0, h) = (rng.random_range(0.8..1.2), 0.06);
    let links = [(l0, h), (rng.random_range(0.3..0.6), 0.05)];
    let (alpha0, turn) = (rng.random_range(0.0..TAU), rng.random_range(0.5..2.0));
    let alpha = |t: f64| alpha0 + turn * t / 10.0;
    let rho = rng.random_range(0.3..0.5) * l0;
    let beta = if rng.random_bool(0.5) {
        let t = 10.0 * (1.0 - rng.random_range(0.001..0.01));
        alpha(t) + ((h + delta) / rho).asin()
    } else {
        alpha(10.0) + ((h + rng.random_range(1.1..1.5) * delta) / rho).asin()
    };
    let (ray, across) = (
        Vec2::new(beta.cos(), beta.sin()),
        Vec2::new(-beta.sin(), beta.cos()),
    );
    // The post: ρ to ρ + 0.2 along the ray, 0.15 across it, away from the arm.
    let corners = [
        rho * ray,
        (rho + 0.2) * ray,
        (rho + 0.2) * ray + 0.15 * across,
        rho * ray + 0.15 * across,
    ];
    let points: Vec<[f64; 2]> = corners.iter().map(|p| [p.x, p.y]).collect();
    let post = ConvexPolygon::from_vertices(&points).expect("a box");
    let n = rng.random_range(2..=10usize);
    let samples = time_grid(rng, n, 0.0, 10.0)
        .into_iter()
        .map(|t| JointSample {
            t,
            q: vec![alpha(t), 0.0],
            qd: Vec::new(),
        })
        .collect();
    let mut bodies = arm("A1", Pose::new(0.0, 0.0, 0.0), &links, samples);
    bodies.push(Body::obstacle("post", &post));
    bodies
}

/// A 2-link arm of an [`super::Kind::ArmHall`] based at `centre`, free to turn: it reaches at
/// most 1.3, within its cell.
pub(super) fn cell_arm(rng: &mut R, name: &str, centre: Vec2) -> Vec<Body> {
    let links = [
        (rng.random_range(0.55..0.7), 0.07),
        (rng.random_range(0.4..0.5), 0.05),
    ];
    let start = [rng.random_range(-PI..PI), rng.random_range(-2.5..2.5)];
    let samples = joint_samples(rng, &start, 3.0, 100, 20.0);
    arm(name, Pose::new(centre.x, centre.y, 0.0), &links, samples)
}

/// A 2-link arm whose base joint turns 2 to 4 times between each pair of its few samples, past a
/// post inside its reach: the samples all miss the post; the sweep between them does not.
/// Always collides.
pub(super) fn arm_spin(rng: &mut R) -> Vec<Body> {
    let links = [(0.7, 0.06), (0.5, 0.05)];
    let n = rng.random_range(2..=4usize);
    // Straight at every sample, pointing away from the post (at angle π): the post stands
    // 0.9 from the base, within the straight arm's reach.
    let times = time_grid(rng, n, 0.0, 10.0);
    let mut q = 0.0;
    let mut samples = Vec::with_capacity(n);
    for &t in &times {
        samples.push(JointSample {
            t,
            q: vec![q, 0.0],
            qd: Vec::new(),
        });
        q += TAU * rng.random_range(2..=4) as f64;
    }
    let mut bodies = arm("A1", Pose::new(0.0, 0.0, 0.0), &links, samples);
    let post =
        ConvexPolygon::from_vertices(&[[-1.0, -0.1], [-0.8, -0.1], [-0.8, 0.1], [-1.0, 0.1]])
            .expect("a box");
    bodies.push(Body::obstacle("post", &post));
    bodies
}

/// A 2-link arm on smooth joint motions and a rigid robot wandering across its reach;
/// about half collide.
pub(super) fn arm_robot(rng: &mut R) -> Vec<Body> {
    let links = [
        (rng.random_range(0.6..0.9), 0.08),
        (rng.random_range(0.4..0.6), 0.06),
    ];
    let swing = rng.random_range(1.0..2.5);
    let samples = joint_samples(rng, &[0.0, 0.0], swing, 60, 10.0);
    let mut bodies = arm("A1", Pose::new(0.0, 0.0, 0.0), &links, samples);
    let reach = links[0].0 + links[1].0;
    let (r, dir) = (
        rng.random_range(0.8..1.6) * reach,
        rng.random_range(0.0..TAU),
    );
    let motion = Smooth::random(rng, [r * dir.cos(), r * dir.sin()], 0.8);
    let samples: Vec<Sample> = time_grid(rng, 40, 0.0, 10.0)
        .into_iter()
        .map(|t| motion.sample(t))
        .collect();
    let square =
        ConvexPolygon::from_vertices(&[[-0.2, -0.2], [0.2, -0.2], [0.2, 0.2], [-0.2, 0.2]])
            .expect("a square");
    let trajectory = Trajectory::new(samples).expect("generated times increase");
    bodies.push(Body::robot("R1", square, trajectory));
    bodies
}
