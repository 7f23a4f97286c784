//! Deterministic random scenes for `workcell generate`: the same kind, seed and index always
//! give the same [`Scene`] (a ChaCha8 stream per scene, no clock, no hashing).

use super::smooth::{pick, time_grid, Smooth, R};
use super::{arm_scenes, mix, parts_scenes};
use crate::collision::{Body, Scene};
use crate::geometry::{ConvexPolygon, Vec2};
use crate::motion::{Motion, Sample, Trajectory};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{PI, TAU};

/// The families of scenes, each with its own δ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Two robots with random convex shapes (4 to 8 vertices) on smooth random motions in
    /// x, y and θ, sampled on different non-uniform time grids; velocities are the exact
    /// derivatives. About half the scenes collide. δ = 0.01.
    Pairs,
    /// A thin fast bar passes right through another robot between two of its samples: only a
    /// continuous check sees the collision. Always collides. δ = 0.001.
    Tunnelling,
    /// Two squares on parallel lines at constant velocity (θ = 0, ω = 0) whose closest
    /// approach, a gap drawn in [2δ, 4.5δ], falls strictly between samples. Always free.
    /// δ = 0.01.
    NearMiss,
    /// A bar of aspect ratio 10 to 20 turning π/8 to 3π/4 per sample step next to another
    /// robot; collides or not at random. δ = 0.001.
    Spinning,
    /// As [`Kind::Pairs`], but each robot's velocities are scaled by 0.1 or negated while the
    /// positions stay right. δ = 0.01.
    BadVelocities,
    /// As [`Kind::Pairs`], moved by 10⁵ to 10⁶ in x and y. δ = 0.001 (the coordinates stay
    /// below 2³⁸·δ).
    LargeCoordinates,
    /// N robots, each going back and forth along its own lane about a cell of a square grid
    /// (100 samples each; one lane in five crosses into the next cell, the others stay in
    /// their own), and a few static obstacles in spare cells; the hall grows with N. Nothing
    /// touches at t = 0; contacts come from the crossing lanes. δ = 0.01.
    Hall,
    /// Two grippers (a palm and two fingers each) on smooth motions like [`Kind::Pairs`]:
    /// fingers meet fingers or slip between them. About half the scenes collide. δ = 0.01.
    Grippers,
    /// A gripper and a convex robot wandering among an L- and a U-shaped fixture given as
    /// outlines. δ = 0.01.
    Fixtures,
    /// A box driving into a U-shaped fixture's bay and out again, 2δ to 4δ from its walls:
    /// the hulls overlap, the parts never meet. Always free. δ = 0.01.
    Bay,
    /// Two combs of 3 to 6 teeth, one lowered between the other's teeth 2δ to 4δ from them
    /// and raised again. Always free. δ = 0.01.
    NotchClear,
    /// Two bodies of 10 to 30 convex parts on smooth motions; about half collide. δ = 0.01.
    ManyParts,
    /// Two 2-link SCARA arms sharing a table, on smooth joint motions of 100 samples; about
    /// half collide. δ = 0.01.
    Arms,
    /// An arm sweeping past a fixture 1.1δ to 1.5δ beyond its reach where the sweep passes.
    /// Always free. δ = 0.01.
    ArmSweep,
    /// An arm whose joints turn several times between samples, past a post that no sample
    /// meets. Always collides. δ = 0.01.
    ArmSpin,
    /// An arm and a rigid robot wandering across its reach; about half collide. δ = 0.01.
    ArmRobot,
    /// An arm of long links (3 to 5, then 1 to 2) that swings fast past a box, its tip at 25
    /// to 200 units a second: a graze of a few milliseconds (half the scenes) or a near miss
    /// by 0.05δ to 0.2δ. δ = 0.01.
    ArmLong,
    /// An arm turning at constant rate towards a post that it reaches within the last 1 % of
    /// the horizon (half the scenes), or stops 1.1δ to 1.5δ short of (the others). δ = 0.01.
    ArmLate,
    /// N 2-link arms and N rigid robots, each in its own cell of a hall like [`Kind::Hall`]'s
    /// (the arms reach 1.05 to 1.3 from a base at the cell's centre, turning freely); N/4
    /// obstacles in spare cells. Contacts come from the rigid robots' crossing lanes. δ = 0.01.
    ArmHall,
}

impl Kind {
    /// Every kind, in documentation order.
    pub const ALL: [Kind; 19] = [
        Kind::Pairs,
        Kind::Tunnelling,
        Kind::NearMiss,
        Kind::Spinning,
        Kind::BadVelocities,
        Kind::LargeCoordinates,
        Kind::Hall,
        Kind::Grippers,
        Kind::Fixtures,
        Kind::Bay,
        Kind::NotchClear,
        Kind::ManyParts,
        Kind::Arms,
        Kind::ArmSweep,
        Kind::ArmSpin,
        Kind::ArmRobot,
        Kind::ArmLong,
        Kind::ArmLate,
        Kind::ArmHall,
    ];

    /// The kinds with arms (contract section 6).
    pub const ARMS: [Kind; 7] = [
        Kind::Arms,
        Kind::ArmSweep,
        Kind::ArmSpin,
        Kind::ArmRobot,
        Kind::ArmLong,
        Kind::ArmLate,
        Kind::ArmHall,
    ];

    /// The kinds whose bodies are not convex (contract section 5).
    pub const PARTS: [Kind; 5] = [
        Kind::Grippers,
        Kind::Fixtures,
        Kind::Bay,
        Kind::NotchClear,
        Kind::ManyParts,
    ];

    /// The name on the command line and in file names, e.g. `near-miss`.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Pairs => "pairs",
            Kind::Tunnelling => "tunnelling",
            Kind::NearMiss => "near-miss",
            Kind::Spinning => "spinning",
            Kind::BadVelocities => "bad-velocities",
            Kind::LargeCoordinates => "large-coordinates",
            Kind::Hall => "hall",
            Kind::Grippers => "grippers",
            Kind::Fixtures => "fixtures",
            Kind::Bay => "bay",
            Kind::NotchClear => "notch-clear",
            Kind::ManyParts => "many-parts",
            Kind::Arms => "arms",
            Kind::ArmSweep => "arm-sweep",
            Kind::ArmSpin => "arm-spin",
            Kind::ArmRobot => "arm-robot",
            Kind::ArmLong => "arm-long",
            Kind::ArmLate => "arm-late",
            Kind::ArmHall => "arm-hall",
        }
    }

    /// The kind of a name, if it is one.
    ///
    /// ```
    /// use workcell::generate::Kind;
    /// assert_eq!(Kind::from_name("near-miss"), Some(Kind::NearMiss));
    /// assert_eq!(Kind::from_name("near_miss"), None);
    /// assert!(Kind::ALL.iter().all(|&k| Kind::from_name(k.name()) == Some(k)));
    /// ```
    pub fn from_name(name: &str) -> Option<Kind> {
        Kind::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The safety margin δ of this kind's scenes.
    pub fn delta(self) -> f64 {
        match self {
            Kind::Tunnelling | Kind::Spinning | Kind::LargeCoordinates => 0.001,
            _ => 0.01,
        }
    }
}

/// The file name of scene `index` of a run: `<kind>-<seed>-<index>.json`.
///
/// ```
/// use workcell::generate::{scene_file_name, Kind};
/// assert_eq!(scene_file_name(Kind::Tunnelling, 7, 3), "tunnelling-7-3.json");
/// ```
pub fn scene_file_name(kind: Kind, seed: u64, index: u64) -> String {
    format!("{}-{seed}-{index}.json", kind.name())
}

/// Scene `index` of kind `kind` for `seed`. `robots` is the number of robots of a
/// [`Kind::Hall`] scene (at least 1) and is ignored by the other kinds.
///
/// ```
/// use workcell::collision::{check, CheckOptions};
/// use workcell::generate::{generate_scene, Kind};
/// let scene = generate_scene(Kind::Hall, 1, 0, 4);
/// assert_eq!(scene.robot_count(), 4);
/// assert_eq!(scene.delta, Kind::Hall.delta());
/// // Deterministic: the same arguments give the same scene, another index another one.
/// assert_eq!(scene, generate_scene(Kind::Hall, 1, 0, 4));
/// assert_ne!(scene, generate_scene(Kind::Hall, 1, 1, 4));
/// // Kinds with a known verdict: a tunnelling scene always collides, a near miss never.
/// let opts = CheckOptions::default();
/// assert!(check(&generate_scene(Kind::Tunnelling, 1, 0, 0), &opts).verdict().contact().is_some());
/// assert!(check(&generate_scene(Kind::NearMiss, 1, 0, 0), &opts).verdict().is_certified_free());
/// ```
pub fn generate_scene(kind: Kind, seed: u64, index: u64, robots: usize) -> Scene {
    let kind_no = Kind::ALL.iter().position(|k| *k == kind).unwrap() as u64;
    let mut rng = ChaCha8Rng::seed_from_u64(mix(mix(mix(seed) ^ kind_no) ^ index));
    let rng = &mut rng;
    let bodies = match kind {
        Kind::Pairs => pairs(rng),
        Kind::Tunnelling => tunnelling(rng),
        Kind::NearMiss => near_miss(rng),
        Kind::Spinning => spinning(rng),
        Kind::BadVelocities => bad_velocities(rng),
        Kind::LargeCoordinates => large_coordinates(rng),
        Kind::Hall => hall(rng, robots.max(1)),
        Kind::Grippers => parts_scenes::grippers(rng),
        Kind::Fixtures => parts_scenes::fixtures(rng),
        Kind::Bay => parts_scenes::bay(rng, kind.delta()),
        Kind::NotchClear => parts_scenes::notch_clear(rng, kind.delta()),
        Kind::ManyParts => parts_scenes::many_parts(rng),
        Kind::Arms => arm_scenes::arms(rng),
        Kind::ArmSweep => arm_scenes::arm_sweep(rng, kind.delta()),
        Kind::ArmSpin => arm_scenes::arm_spin(rng),
        Kind::ArmRobot => arm_scenes::arm_robot(rng),
        Kind::ArmLong => arm_scenes::arm_long(rng, kind.delta()),
        Kind::ArmLate => arm_scenes::arm_late(rng, kind.delta()),
        Kind::ArmHall => arm_hall(rng, robots.max(1)),
    };
    Scene {
        delta: kind.delta(),
        bodies,
    }
}

fn polygon(points: &[[f64; 2]]) -> ConvexPolygon {
    ConvexPolygon::new(points)
        .expect("generated shapes are strictly convex")
        .0
}

/// A convex polygon of 4 to 8 vertices: points in order on a circle of radius drawn in
/// `radius` (angles jittered by less than half a step, so strictly convex), squeezed along
/// y, turned, and centred on their mean.
fn random_shape(rng: &mut R, radius: std::ops::Range<f64>) -> Vec<[f64; 2]> {
    let r = rng.random_range(radius);
    let n = rng.random_range(4..=8usize);
    let step = TAU / n as f64;
    let squeeze = rng.random_range(0.5..1.0);
    let (s, c) = rng.random_range(0.0..TAU).sin_cos();
    let pts: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let a = step * (i as f64 + rng.random_range(-0.35..0.35));
            let (x, y) = (r * a.cos(), r * squeeze * a.sin());
            [c * x - s * y, s * x + c * y]
        })
        .collect();
    let m = pts
        .iter()
        .fold([0.0, 0.0], |m, p| [m[0] + p[0], m[1] + p[1]]);
    let m = [m[0] / n as f64, m[1] / n as f64];
    pts.iter().map(|p| [p[0] - m[0], p[1] - m[1]]).collect()
}

/// An axis-aligned rectangle of half sides `a`, `b`, turned by `phi`.
fn rectangle(a: f64, b: f64, phi: f64) -> Vec<[f64; 2]> {
    let (s, c) = phi.sin_cos();
    [[-a, -b], [a, -b], [a, b], [-a, b]]
        .map(|[x, y]| [c * x - s * y, s * x + c * y])
        .to_vec()
}

fn robot(name: String, shape: &[[f64; 2]], samples: Vec<Sample>) -> Body {
    Body::robot(
        name,
        polygon(shape),
        Trajectory::new(samples).expect("generated times increase"),
    )
}

/// A sample of a motion at constant velocity `vel`, `omega` through `(pos0, theta0)` at t = 0.
fn linear(t: f64, pos0: Vec2, vel: Vec2, theta0: f64, omega: f64) -> Sample {
    Sample {
        t,
        pos: pos0 + vel * t,
        theta: theta0 + omega * t,
        vel,
        omega,
    }
}

/// Two robots wandering around centres 0 to 3.2 apart (the reach of each is about 1.3):
/// about half the scenes collide. Horizon [0, 10], 20 to 60 samples each, never the same
/// number.
fn pairs(rng: &mut R) -> Vec<Body> {
    let n1 = rng.random_range(20..=60usize);
    let n2 = loop {
        let n = rng.random_range(20..=60usize);
        if n != n1 {
            break n;
        }
    };
    let (dist, dir) = (rng.random_range(0.0..3.2), rng.random_range(0.0..TAU));
    let centres = [[0.0, 0.0], [dist * f64::cos(dir), dist * f64::sin(dir)]];
    [n1, n2]
        .into_iter()
        .zip(centres)
        .enumerate()
        .map(|(i, (n, centre))| {
            let shape = random_shape(rng, 0.4..0.9);
            let motion = Smooth::random(rng, centre, 1.3);
            let samples = time_grid(rng, n, 0.0, 10.0)
                .into_iter()
                .map(|t| motion.sample(t))
                .collect();
            robot(format!("R{}", i + 1), &shape, samples)
        })
        .collect()
}

/// Replaces each robot's samples by `f` of them.
fn map_samples(mut bodies: Vec<Body>, f: impl Fn(&Sample) -> Sample) -> Vec<Body> {
    for body in &mut bodies {
        if let Motion::Sampled(tr) = &body.motion {
            let samples = tr.samples().iter().map(&f).collect();
            body.motion = Motion::Sampled(Trajectory::new(samples).expect("same times"));
        }
    }
    bodies
}

/// [`pairs`] with both robots' velocities (linear and angular) scaled by 0.1 or negated.
fn bad_velocities(rng: &mut R) -> Vec<Body> {
    let factor = pick(rng, [0.1, -1.0]);
    map_samples(pairs(rng), |s| Sample {
        vel: s.vel * factor,
        omega: s.omega * factor,
        ..*s
    })
}

/// [`pairs`] moved by 10⁵ to 10⁶ in x and in y.
fn large_coordinates(rng: &mut R) -> Vec<Body> {
    let offset = Vec2::new(rng.random_range(1e5..1e6), rng.random_range(1e5..1e6));
    map_samples(pairs(rng), |s| Sample {
        pos: s.pos + offset,
        ..*s
    })
}

/// A target robot that stays put while turning slowly, and a thin bar crossing it at
/// constant velocity along a line through its centre: at the crossing time both centres
/// (inside both shapes) coincide, so they overlap. The bar's samples all lie farther than
/// the sum of the radii from the target, so no sample time shows the contact.
fn tunnelling(rng: &mut R) -> Vec<Body> {
    let target_shape = random_shape(rng, 0.4..1.0);
    let target_r = polygon(&target_shape).radius();
    let (len, width) = (rng.random_range(0.5..1.5), rng.random_range(0.02..0.05));
    let bar = rectangle(len / 2.0, width / 2.0, rng.random_range(0.0..PI));
    let bar_r = polygon(&bar).radius();
    let centre = Vec2::new(rng.random_range(-5.0..5.0), rng.random_range(-5.0..5.0));
    let (omega, theta0) = (rng.random_range(-0.3..0.3), rng.random_range(-PI..PI));
    let target = [0.0, 10.0].map(|t| linear(t, centre, Vec2::zeros(), theta0, omega));
    // The bar crosses the centre at t_c, speed v; its samples keep clear by `gap` at least.
    let (t_c, speed) = (rng.random_range(3.0..7.0), rng.random_range(20.0..60.0));
    let dir = rng.random_range(0.0..TAU);
    let vel = Vec2::new(dir.cos(), dir.sin()) * speed;
    let gap = (target_r + bar_r) * rng.random_range(1.2..2.0);
    let (before, after) = (
        t_c - gap / speed,
        t_c + gap / speed * rng.random_range(1.0..2.0),
    );
    let times = [0.0, rng.random_range(0.5..before), before, after, 10.0];
    let bar_samples = times.map(|t| linear(t, centre - vel * t_c, vel, 0.0, 0.0));
    vec![
        robot("target".into(), &target_shape, target.to_vec()),
        robot("bar".into(), &bar, bar_samples.to_vec()),
    ]
}

/// Squares of half sides `a`, `b`: A on the line y = 0, B on y = a + b + gap, moving along
/// x at different constant velocities, lined up at t*; the whole drawn turned by φ. Their
/// distance is the gap exactly while their x-extents overlap (|t − t*| ≤ w) and more
/// otherwise; no sample falls within w + 0.1 of t*.
fn near_miss(rng: &mut R) -> Vec<Body> {
    let delta = Kind::NearMiss.delta();
    let (a, b) = (rng.random_range(0.2..0.5), rng.random_range(0.2..0.5));
    let gap = rng.random_range(2.0..4.5) * delta;
    let va: f64 = rng.random_range(1.0..3.0) * pick(rng, [1.0, -1.0]);
    let vb = va - rng.random_range(0.5..2.0) * va.signum();
    let t_star = rng.random_range(4.0..6.0);
    let w = (a + b) / (va - vb).abs() + 0.1;
    let phi = rng.random_range(0.0..TAU);
    let (s, c) = phi.sin_cos();
    let turn = |x: f64, y: f64| Vec2::new(c * x - s * y, s * x + c * y);
    let origin = Vec2::new(rng.random_range(-5.0..5.0), rng.random_range(-5.0..5.0));
    let mut bodies = Vec::new();
    for (name, half, y, v) in [("A", a, 0.0, va), ("B", b, a + b + gap, vb)] {
        let mut times = vec![0.0, 10.0];
        for _ in 0..rng.random_range(0..4) {
            let t = if rng.random_bool(0.5) {
                rng.random_range(0.2..t_star - w)
            } else {
                rng.random_range(t_star + w..9.8)
            };
            times.push(t);
        }
        times.sort_by(f64::total_cmp);
        times.dedup();
        let samples = times
            .iter()
            .map(|&t| linear(t, origin + turn(-v * t_star, y), turn(v, 0.0), 0.0, 0.0))
            .collect();
        bodies.push(robot(name.into(), &rectangle(half, half, phi), samples));
    }
    bodies
}

/// A bar of length 2 to 3 and aspect ratio 10 to 20 turning at a constant rate of π/8 to
/// 3π/4 per sample step about its fixed centre, and a robot wandering a little at 0.6 to 1.4
/// times the distance at which the bar's tip would reach it.
fn spinning(rng: &mut R) -> Vec<Body> {
    let len = rng.random_range(2.0..3.0);
    let bar = rectangle(len / 2.0, len / rng.random_range(10.0..20.0) / 2.0, 0.0);
    let n = rng.random_range(8..=20usize);
    let dt = 4.0 / (n - 1) as f64;
    let turn = rng.random_range(PI / 8.0..0.75 * PI) * pick(rng, [1.0, -1.0]);
    let (centre, theta0) = (
        Vec2::new(rng.random_range(-5.0..5.0), 0.0),
        rng.random_range(-PI..PI),
    );
    let bar_samples = (0..n)
        .map(|k| linear(k as f64 * dt, centre, Vec2::zeros(), theta0, turn / dt))
        .collect();
    let other = random_shape(rng, 0.3..0.6);
    let reach = len / 2.0 + polygon(&other).radius();
    let (d, dir) = (
        reach * rng.random_range(0.6..1.4),
        rng.random_range(0.0..TAU),
    );
    let at = centre + Vec2::new(dir.cos(), dir.sin()) * d;
    let motion = Smooth::random(rng, [at.x, at.y], 0.1);
    let m = rng.random_range(10..=40usize);
    let other_samples = time_grid(rng, m, 0.0, 4.0)
        .into_iter()
        .map(|t| motion.sample(t))
        .collect();
    vec![
        robot("bar".into(), &bar, bar_samples),
        robot("other".into(), &other, other_samples),
    ]
}

/// `n` robots and `max(1, n / 8)` obstacles shuffled over the cells of a near-square grid
/// of pitch [`HALL_PITCH`] (so the area grows as n); horizon [0, 20], 100 evenly spaced
/// samples per robot. Each robot swings along x or y about its cell's centre and sways in θ.
///
/// What is known by construction: an obstacle, and a robot on a short lane (amplitude 0.5 to
/// 0.9, less if its shape is large), stay inside their own cell's square shrunk by
/// [`HALL_MARGIN`], so two of them never meet. One robot in five has a crossing lane
/// (amplitude 2 to 3) that reaches into the next cell; it starts at its cell's centre, so no
/// robot touches anything at t = 0, and every contact is a crossing robot meeting a
/// neighbour or an obstacle while out of its cell.
fn hall(rng: &mut R, n: usize) -> Vec<Body> {
    let inside = HALL_PITCH / 2.0 - HALL_MARGIN;
    let obstacles = (n / 8).max(1);
    let cells = n + obstacles;
    let cols = (cells as f64).sqrt().ceil() as usize;
    let mut order: Vec<usize> = (0..cols * cells.div_ceil(cols)).collect();
    order.shuffle(rng);
    let cell = |k: usize| {
        Vec2::new(
            (k % cols) as f64 * HALL_PITCH,
            (k / cols) as f64 * HALL_PITCH,
        )
    };
    let mut bodies = Vec::with_capacity(cells);
    for (i, &k) in order[..n].iter().enumerate() {
        let shape = random_shape(rng, 0.3..0.5);
        let radius = polygon(&shape).radius();
        let crossing = rng.random_bool(0.2);
        let amp = if crossing {
            rng.random_range(2.0..3.0)
        } else {
            rng.random_range(0.5..0.9f64).min(inside - radius)
        };
        // Phase 0 or π: at its centre at t = 0, heading either way.
        let (w, phase) = (rng.random_range(0.3..0.8), pick(rng, [0.0, PI]));
        let [ax, ay] = pick(rng, [[amp, 0.0], [0.0, amp]]);
        let sway = [0.0..0.5, 0.2..1.0, 0.0..TAU].map(|r| rng.random_range(r));
        let theta0 = rng.random_range(-PI..PI);
        let motion = Smooth {
            coords: [
                (cell(k).x, 0.0, vec![[ax, w, phase]]),
                (cell(k).y, 0.0, vec![[ay, w, phase]]),
                (theta0, 0.0, vec![sway]),
            ],
        };
        let samples = (0..100).map(|j| motion.sample(20.0 * j as f64 / 99.0));
        let samples = samples.collect();
        bodies.push(robot(format!("R{}", i + 1), &shape, samples));
    }
    for (i, &k) in order[n..n + obstacles].iter().enumerate() {
        let (c, shape) = (cell(k), random_shape(rng, 0.5..1.0));
        let shrink = (inside / polygon(&shape).radius()).min(1.0);
        let world: Vec<[f64; 2]> = shape
            .iter()
            .map(|p| [p[0] * shrink + c.x, p[1] * shrink + c.y])
            .collect();
        bodies.push(Body::obstacle(format!("O{}", i + 1), &polygon(&world)));
    }
    bodies
}

/// [`hall`] of 2n robots whose first n become 2-link arms based at their cells' centres
/// (where each robot starts), free to turn: their reach stays inside their cell, so only
/// the crossing lanes of the rigid robots meet them. The rigid robots are renamed R1 to Rn.
fn arm_hall(rng: &mut R, n: usize) -> Vec<Body> {
    let hall = hall(rng, 2 * n);
    let mut bodies = Vec::with_capacity(hall.len() + n);
    for (i, mut body) in hall.into_iter().enumerate() {
        match (body.is_robot(), i < n) {
            (true, true) => {
                let centre = body.motion.pose_at(0.0).pos;
                bodies.extend(arm_scenes::cell_arm(rng, &format!("A{}", i + 1), centre));
            }
            (true, false) => {
                body.name = format!("R{}", i - n + 1);
                bodies.push(body);
            }
            (false, _) => bodies.push(body),
        }
    }
    bodies
}

/// The distance between the centres of neighbouring cells of a [`Kind::Hall`].
const HALL_PITCH: f64 = 3.0;
/// How far inside its cell's square an obstacle, or a robot on a short lane, stays: the gap
/// between two such neighbours is at least twice this, far above the hall's δ.
const HALL_MARGIN: f64 = 0.05;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_velocities_are_the_derivatives() {
        let mut rng = R::seed_from_u64(1);
        let m = Smooth::random(&mut rng, [1.0, 2.0], 1.3);
        for t in [0.0, 1.7, 6.2, 9.9] {
            let (s, a, b) = (m.sample(t), m.sample(t - 1e-6), m.sample(t + 1e-6));
            let fd = |p: f64, q: f64| (q - p) / 2e-6;
            assert!((s.vel.x - fd(a.pos.x, b.pos.x)).abs() < 1e-6);
            assert!((s.vel.y - fd(a.pos.y, b.pos.y)).abs() < 1e-6);
            assert!((s.omega - fd(a.theta, b.theta)).abs() < 1e-6);
        }
    }

    /// The vertices of `b` at each of its samples (an obstacle: once), relative to `c`.
    fn offsets(b: &Body, c: Vec2) -> Vec<Vec<Vec2>> {
        let poses = match &b.motion {
            Motion::Sampled(tr) => tr.samples().iter().map(|s| (s.pos, s.theta)).collect(),
            Motion::Link(_) => unreachable!("the generated rigid scenes have no arms"),
            Motion::Fixed(p) => vec![(p.pos, p.theta)],
        };
        poses
            .into_iter()
            .map(|(pos, theta)| {
                let posed = crate::geometry::Posed::new(&b.shape, pos.x, pos.y, theta);
                (0..posed.len()).map(|k| posed.vertex(k) - c).collect()
            })
            .collect()
    }

    #[test]
    fn hall_bodies_stay_in_their_cells_but_the_crossing_lanes() {
        let inside = HALL_PITCH / 2.0 - HALL_MARGIN;
        let within = |vs: &[Vec2]| vs.iter().all(|v| v.amax() <= inside);
        for (seed, n) in [(1, 10), (2, 100), (3, 300)] {
            let bodies = hall(&mut R::seed_from_u64(seed), n);
            let mut centres = Vec::new();
            let mut crossing = 0;
            for b in &bodies {
                let Motion::Sampled(tr) = &b.motion else {
                    // Obstacles: the cell is the one of the mean of their vertices.
                    let vs = &offsets(b, Vec2::zeros())[0];
                    let mean = vs.iter().fold(Vec2::zeros(), |m, v| m + v) / vs.len() as f64;
                    let c = (mean / HALL_PITCH).map(f64::round) * HALL_PITCH;
                    assert!(within(&offsets(b, c)[0]), "{}", b.name);
                    centres.push(c);
                    continue;
                };
                // Robots start at their cell's centre, inside it.
                let s = tr.samples();
                let c = (s[0].pos / HALL_PITCH).map(f64::round) * HALL_PITCH;
                assert!((s[0].pos - c).amax() < 1e-12, "{}", b.name);
                let at = offsets(b, c);
                assert!(within(&at[0]), "{} at t = 0", b.name);
                // A crossing lane swings G by 2 to 3, a short one by at most 0.9 and stays in.
                let swing = s.iter().fold(0.0f64, |m, s| m.max((s.pos - c).amax()));
                if swing > 1.9 {
                    crossing += 1;
                } else {
                    assert!(swing <= 0.9, "{}: G swings by {swing}", b.name);
                    assert!(at.iter().all(|vs| within(vs)), "{} leaves its cell", b.name);
                }
                centres.push(c);
            }
            // One cell each, and about one lane in five crosses.
            centres.sort_by(|p, q| p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y)));
            centres.dedup();
            assert_eq!(centres.len(), bodies.len());
            let share = crossing as f64 / n as f64;
            assert!((0.05..0.4).contains(&share), "{crossing} of {n} cross");
        }
    }

    #[test]
    fn bad_velocities_keep_the_positions_of_pairs() {
        for seed in 0..20 {
            let mut rng = R::seed_from_u64(seed);
            let mut twin = rng.clone();
            let factor = [0.1, -1.0][twin.random_range(0..2usize)];
            let (bad, good) = (bad_velocities(&mut rng), pairs(&mut twin));
            for (b, g) in bad.iter().zip(&good) {
                let (Motion::Sampled(b), Motion::Sampled(g)) = (&b.motion, &g.motion) else {
                    panic!("robots")
                };
                for (b, g) in b.samples().iter().zip(g.samples()) {
                    assert_eq!((b.t, b.pos, b.theta), (g.t, g.pos, g.theta));
                    assert_eq!((b.vel, b.omega), (g.vel * factor, g.omega * factor));
                }
            }
        }
    }
}
