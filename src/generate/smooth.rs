//! What the scene generators share: the random stream, strictly increasing time grids and
//! smooth random motions with their exact derivatives.

use crate::geometry::Vec2;
use crate::motion::Sample;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{PI, TAU};

/// The generators' random stream.
pub(super) type R = ChaCha8Rng;

/// One of two values, evenly.
pub(super) fn pick<T: Copy>(rng: &mut R, of: [T; 2]) -> T {
    of[rng.random_range(0..2usize)]
}

/// `n` strictly increasing times from `t0` to `t1`, with steps between 0.3 and 1.7 times
/// the mean step.
pub(super) fn time_grid(rng: &mut R, n: usize, t0: f64, t1: f64) -> Vec<f64> {
    let steps: Vec<f64> = (1..n).map(|_| rng.random_range(0.3..1.7)).collect();
    let total: f64 = steps.iter().sum();
    let mut t = vec![t0];
    let mut acc = 0.0;
    for s in &steps[..n - 2] {
        acc += s;
        t.push(t0 + (t1 - t0) * acc / total);
    }
    t.push(t1);
    t
}

/// A smooth motion in (x, y, θ): for each coordinate a base value, a drift rate and a sum of
/// sinusoids `(amplitude, angular frequency, phase)`.
pub(super) struct Smooth {
    pub(super) coords: [(f64, f64, Vec<[f64; 3]>); 3],
}

impl Smooth {
    /// Wanders around `centre` by up to about `reach` (three sinusoids each in x and y) and
    /// turns (a drift and two sinusoids in θ).
    pub(super) fn random(rng: &mut R, centre: [f64; 2], reach: f64) -> Smooth {
        let mut waves = |n: usize, amp: f64| -> Vec<[f64; 3]> {
            (0..n)
                .map(|_| {
                    [
                        amp * rng.random_range(0.2..1.0),
                        rng.random_range(0.2..1.5),
                        rng.random_range(0.0..TAU),
                    ]
                })
                .collect()
        };
        let (wx, wy, wt) = (waves(3, reach / 3.0), waves(3, reach / 3.0), waves(2, 1.0));
        let theta0 = rng.random_range(-PI..PI);
        let drift = rng.random_range(-0.5..0.5);
        Smooth {
            coords: [
                (centre[0], 0.0, wx),
                (centre[1], 0.0, wy),
                (theta0, drift, wt),
            ],
        }
    }

    /// The sample at time `t`, with the exact derivatives as velocities.
    pub(super) fn sample(&self, t: f64) -> Sample {
        let [x, y, th] = self.coords.each_ref().map(|(base, drift, waves)| {
            waves
                .iter()
                .fold((base + drift * t, *drift), |(v, d), [a, w, p]| {
                    (v + a * (w * t + p).sin(), d + a * w * (w * t + p).cos())
                })
        });
        Sample {
            t,
            pos: Vec2::new(x.0, y.0),
            theta: th.0,
            vel: Vec2::new(x.1, y.1),
            omega: th.1,
        }
    }
}
