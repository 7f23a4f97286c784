//! Scenes whose bodies are not convex (contract section 5): grippers, L- and U-shaped
//! fixtures, a bay a robot drives into, combs that interleave, bodies of 10 to 30 parts.
//! Each is built so that the hull of a body tells a different story from its parts.

use super::smooth::{pick, time_grid, Smooth, R};
use crate::collision::Body;
use crate::geometry::{ConvexPolygon, Outline, Parts, Vec2};
use crate::motion::{Sample, Trajectory};
use rand::Rng;
use std::f64::consts::TAU;

/// An axis-aligned box from (x0, y0) to (x1, y1).
fn bar(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<[f64; 2]> {
    vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
}

fn convex(points: &[[f64; 2]]) -> ConvexPolygon {
    ConvexPolygon::from_vertices(points).expect("generated parts are convex")
}

fn parts(list: &[Vec<[f64; 2]>]) -> Parts {
    Parts::new(list.iter().map(|p| convex(p)).collect()).expect("generated parts")
}

fn outline(points: &[[f64; 2]]) -> Parts {
    let outline = Outline::new(points).expect("generated outlines are simple");
    Parts::from_outline(&outline).expect("generated outlines are cut")
}

/// Every point turned by `phi` about the origin, then moved by `at`.
fn placed(points: &[[f64; 2]], phi: f64, at: Vec2) -> Vec<[f64; 2]> {
    let (s, c) = phi.sin_cos();
    points
        .iter()
        .map(|&[x, y]| [at.x + c * x - s * y, at.y + s * x + c * y])
        .collect()
}

fn robot(name: &str, body: Parts, samples: Vec<Sample>) -> Body {
    let trajectory = Trajectory::new(samples).expect("generated times increase");
    Body::robot_of_parts(name, body, trajectory)
}

/// A gripper opening along +x: a palm and two fingers, `reach` long, `gap` apart.
fn gripper(rng: &mut R) -> Parts {
    let (reach, gap, t) = (
        rng.random_range(0.35..0.7),
        rng.random_range(0.2..0.5),
        rng.random_range(0.06..0.12),
    );
    let half = 0.5 * gap + t;
    parts(&[
        bar(-0.35, -half - 0.05, 0.0, half + 0.05),
        bar(0.0, 0.5 * gap, reach, half),
        bar(0.0, -half, reach, -0.5 * gap),
    ])
}

/// A U of outer size `w` × `h` and wall `t`, open towards +x, its bay's mouth at x = 0.
fn u_outline(w: f64, h: f64, t: f64) -> Vec<[f64; 2]> {
    let (x0, y0, y1) = (-w, -0.5 * h, 0.5 * h);
    vec![
        [x0, y0],
        [0.0, y0],
        [0.0, y0 + t],
        [x0 + t, y0 + t],
        [x0 + t, y1 - t],
        [0.0, y1 - t],
        [0.0, y1],
        [x0, y1],
    ]
}

/// An L with legs `a` and `b` and thickness `t`, its corner at the origin.
fn l_outline(a: f64, b: f64, t: f64) -> Vec<[f64; 2]> {
    vec![[0.0, 0.0], [a, 0.0], [a, t], [t, t], [t, b], [0.0, b]]
}

/// The samples of `motion` on a grid of `n` times over [0, 10].
fn sampled(rng: &mut R, motion: &Smooth, n: usize) -> Vec<Sample> {
    time_grid(rng, n, 0.0, 10.0)
        .into_iter()
        .map(|t| motion.sample(t))
        .collect()
}

/// Two grippers wandering around centres 0.6 to 3 apart, turning: fingers meet fingers or
/// slip between them; about half the scenes collide.
pub(super) fn grippers(rng: &mut R) -> Vec<Body> {
    let (dist, dir) = (rng.random_range(0.6..3.0), rng.random_range(0.0..TAU));
    let centres = [[0.0, 0.0], [dist * dir.cos(), dist * dir.sin()]];
    centres
        .iter()
        .enumerate()
        .map(|(k, &centre)| {
            let body = gripper(rng);
            let motion = Smooth::random(rng, centre, 1.0);
            let n = rng.random_range(20..=50usize);
            robot(&format!("G{}", k + 1), body, sampled(rng, &motion, n))
        })
        .collect()
}

/// A gripper and a convex robot wandering either side of the middle, and an L- and a
/// U-shaped fixture (given as outlines) placed 2 to 3.2 from it.
pub(super) fn fixtures(rng: &mut R) -> Vec<Body> {
    let (g, r) = (gripper(rng), parts(&[bar(-0.25, -0.15, 0.25, 0.15)]));
    let (g_motion, r_motion) = (
        Smooth::random(rng, [-0.8, 0.0], 0.8),
        Smooth::random(rng, [0.8, 0.0], 0.8),
    );
    let mut bodies = vec![
        robot("G", g, sampled(rng, &g_motion, 40)),
        robot("R", r, sampled(rng, &r_motion, 30)),
    ];
    let base = rng.random_range(0.0..TAU);
    for (k, name) in ["L", "U"].into_iter().enumerate() {
        let (a, b, t) = (
            rng.random_range(0.8..1.6),
            rng.random_range(0.8..1.6),
            rng.random_range(0.1..0.3),
        );
        let shape = if k == 0 {
            l_outline(a, b, t)
        } else {
            u_outline(a, b, t)
        };
        let dir = base + k as f64 * rng.random_range(2.0..4.0);
        let at = Vec2::new(dir.cos(), dir.sin()) * rng.random_range(2.0..3.2);
        let phi = rng.random_range(0.0..TAU);
        bodies.push(Body::obstacle_of_parts(
            name,
            &outline(&placed(&shape, phi, at)),
        ));
    }
    bodies
}

/// A box drives straight into a U-shaped fixture's bay, stays, and backs out, its sides
/// 2δ to 4δ from the walls: the hulls overlap all along, the parts never meet. Always free.
pub(super) fn bay(rng: &mut R, delta: f64) -> Vec<Body> {
    let (w, h, t) = (
        rng.random_range(1.0..2.0),
        rng.random_range(0.8..1.5),
        rng.random_range(0.1..0.25),
    );
    let bay = h - 2.0 * t;
    let clearance = rng.random_range(2.0..4.0) * delta;
    let (half_x, half_y) = (rng.random_range(0.2..0.4), 0.5 * bay - clearance);
    // In: from its nose 0.5 outside the mouth to its nose `depth` inside, then out again.
    let depth = rng.random_range(0.3..1.0) * (w - t - 2.0 * delta);
    let (outside, inside) = (0.5 + half_x, half_x - depth);
    let phi = rng.random_range(0.0..TAU);
    let (s, c) = phi.sin_cos();
    let origin = Vec2::new(rng.random_range(-5.0..5.0), rng.random_range(-5.0..5.0));
    let at = |x: f64| origin + Vec2::new(c * x, s * x);
    let times = [0.0, 3.0, 5.0, 8.0];
    let xs = [outside, inside, inside, outside];
    let samples = times
        .iter()
        .zip(xs)
        .map(|(&t, x)| Sample {
            t,
            pos: at(x),
            theta: phi,
            vel: Vec2::zeros(),
            omega: 0.0,
        })
        .collect::<Vec<_>>();
    let body = parts(&[bar(-half_x, -half_y, half_x, half_y)]);
    vec![
        robot_derived("box", body, samples),
        Body::obstacle_of_parts("U", &outline(&placed(&u_outline(w, h, t), phi, origin))),
    ]
}

/// Two combs of 3 to 6 teeth, one pointing up, one down, the second lowered between the
/// first's teeth and raised again, 2δ to 4δ from them on each side; both turned by φ.
/// The hulls overlap deeply, the parts never meet. Always free.
pub(super) fn notch_clear(rng: &mut R, delta: f64) -> Vec<Body> {
    let teeth = rng.random_range(3..=6usize);
    let (tooth, clearance) = (
        rng.random_range(0.06..0.15),
        rng.random_range(2.0..4.0) * delta,
    );
    let pitch = 2.0 * (tooth + clearance);
    let length = rng.random_range(0.3..0.6);
    let width = teeth as f64 * pitch;
    let comb = |offset: f64, up: bool| -> Parts {
        // The back below y = 0 and the teeth above it, or the other way round.
        let (back, teeth_span) = if up {
            ((-0.15, 0.0), (0.0, length))
        } else {
            ((0.0, 0.15), (-length, 0.0))
        };
        let mut list = vec![bar(0.0, back.0, width, back.1)];
        for k in 0..teeth {
            let x = offset + k as f64 * pitch;
            list.push(bar(x, teeth_span.0, x + tooth, teeth_span.1));
        }
        parts(&list)
    };
    let lower = comb(0.0, true);
    let upper = comb(tooth + clearance, false);
    // The upper comb's back starts `length` + 0.3 above the lower's and comes down until its
    // teeth reach `depth` below the lower's tips, never nearer than 2δ to the lower's back.
    let depth = rng.random_range(0.2..0.9) * (length - 2.0 * delta);
    let (high, low) = (2.0 * length + 0.3, 2.0 * length - depth);
    let phi = rng.random_range(0.0..TAU);
    let (s, c) = phi.sin_cos();
    let origin = Vec2::new(rng.random_range(-5.0..5.0), rng.random_range(-5.0..5.0));
    let at = |y: f64| origin + Vec2::new(-s * y, c * y);
    let still = [0.0, 8.0].map(|t| Sample {
        t,
        pos: at(0.0),
        theta: phi,
        vel: Vec2::zeros(),
        omega: 0.0,
    });
    let moving = [(0.0, high), (3.0, low), (5.0, low), (8.0, high)].map(|(t, y)| Sample {
        t,
        pos: at(y),
        theta: phi,
        vel: Vec2::zeros(),
        omega: 0.0,
    });
    vec![
        robot("lower", lower, still.to_vec()),
        robot_derived("upper", upper, moving.to_vec()),
    ]
}

/// A robot whose velocities are derived from its positions (piecewise linear motions).
fn robot_derived(name: &str, body: Parts, mut samples: Vec<Sample>) -> Body {
    for s in &mut samples {
        s.vel = Vec2::new(f64::NAN, f64::NAN);
        s.omega = f64::NAN;
    }
    let trajectory =
        Trajectory::with_missing_velocities(samples).expect("generated times increase");
    Body::robot_of_parts(name, body, trajectory)
}

/// A cluster of `n` small convex parts within about 0.8 of the frame's origin, each
/// touching or overlapping the one before (one connected body).
fn cluster(rng: &mut R, n: usize) -> Parts {
    let mut list = Vec::with_capacity(n);
    let mut at = Vec2::zeros();
    for _ in 0..n {
        let (r, m) = (rng.random_range(0.06..0.15), rng.random_range(3..=6usize));
        let phase = rng.random_range(0.0..TAU);
        list.push(
            (0..m)
                .map(|k| {
                    let a = phase + TAU * k as f64 / m as f64;
                    [at.x + r * a.cos(), at.y + r * a.sin()]
                })
                .collect(),
        );
        // The next part's centre within reach of this one, pulled back towards the origin.
        let dir = rng.random_range(0.0..TAU);
        let next = at + Vec2::new(dir.cos(), dir.sin()) * r;
        at = if next.norm() > 0.8 { next * 0.5 } else { next };
    }
    parts(&list)
}

/// Two bodies of 10 to 30 parts each on smooth motions around centres 0.5 to 2.4 apart:
/// about half the scenes collide.
pub(super) fn many_parts(rng: &mut R) -> Vec<Body> {
    let (dist, dir) = (rng.random_range(0.5..2.4), rng.random_range(0.0..TAU));
    let centres = [[0.0, 0.0], [dist * dir.cos(), dist * dir.sin()]];
    centres
        .iter()
        .enumerate()
        .map(|(k, &centre)| {
            let n = rng.random_range(10..=30usize);
            let body = cluster(rng, n);
            let motion = Smooth::random(rng, centre, 1.0);
            let count = pick(rng, [30, 50]);
            let samples = sampled(rng, &motion, count);
            robot(&format!("M{}", k + 1), body, samples)
        })
        .collect()
}
