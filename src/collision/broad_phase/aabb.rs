//! Axis-aligned boxes of the broad phase, grown by δ/2 and a relative slack.

use crate::geometry::Vec2;

/// Relative slack added to every box: covers the rounding of interpolated poses and of the
/// narrow phase's own arithmetic (a few units in the last place of the coordinates), with
/// orders of magnitude to spare, while staying far below any δ the scene loader accepts.
const SLACK: f64 = 1e-12;

/// An axis-aligned box: NaN once a NaN point was added, infinite once an infinite one was.
#[derive(Clone, Copy, Debug)]
pub(super) struct Aabb {
    pub(super) lo: [f64; 2],
    pub(super) hi: [f64; 2],
}

impl Aabb {
    pub(super) const EMPTY: Aabb = Aabb {
        lo: [f64::INFINITY; 2],
        hi: [f64::NEG_INFINITY; 2],
    };

    pub(super) fn add(&mut self, p: &Vec2) {
        // An infinite point makes the box infinite by itself; NaN would be skipped by the
        // comparisons below, so it sets the box to NaN, where comparisons keep it.
        if p.x.is_nan() || p.y.is_nan() {
            *self = Aabb {
                lo: [f64::NAN; 2],
                hi: [f64::NAN; 2],
            };
        }
        // Plain comparisons: f64::min and max handle NaN, which costs here.
        for (k, x) in [p.x, p.y].into_iter().enumerate() {
            self.lo[k] = if x < self.lo[k] { x } else { self.lo[k] };
            self.hi[k] = if x > self.hi[k] { x } else { self.hi[k] };
        }
    }

    /// Adds the box of the disc of radius `r` about `c`.
    pub(super) fn add_disc(&mut self, c: &Vec2, r: f64) {
        self.add(&Vec2::new(c.x - r, c.y - r));
        self.add(&Vec2::new(c.x + r, c.y + r));
    }

    /// The box common to both, each holding the same body; a box that is not finite is
    /// kept as it is, so that nothing is dropped on such input.
    pub(super) fn intersection(&self, o: &Aabb) -> Aabb {
        if !self.is_finite() {
            return *self;
        }
        if !o.is_finite() {
            return *o;
        }
        Aabb {
            lo: [0, 1].map(|k| self.lo[k].max(o.lo[k])),
            hi: [0, 1].map(|k| self.hi[k].min(o.hi[k])),
        }
    }

    /// The box that holds both.
    pub(super) fn hull(&self, o: &Aabb) -> Aabb {
        let mut h = *self;
        h.add(&crate::geometry::Vec2::new(o.lo[0], o.lo[1]));
        h.add(&crate::geometry::Vec2::new(o.hi[0], o.hi[1]));
        h
    }

    /// Grown by `by` on every side, plus [`SLACK`] relative to `by` and to `scale`, the
    /// magnitude of the coordinates the box was computed from.
    pub(super) fn grown(self, by: f64, scale: f64) -> Aabb {
        let by = by + SLACK * (scale + by);
        Aabb {
            lo: self.lo.map(|x| x - by),
            hi: self.hi.map(|x| x + by),
        }
    }

    pub(super) fn magnitude(&self) -> f64 {
        self.lo
            .iter()
            .chain(&self.hi)
            .fold(0.0, |m, x| m.max(x.abs()))
    }

    pub(super) fn size(&self) -> f64 {
        (self.hi[0] - self.lo[0]).max(self.hi[1] - self.lo[1])
    }

    pub(super) fn is_finite(&self) -> bool {
        self.lo.iter().chain(&self.hi).all(|x| x.is_finite())
    }

    /// Whether the boxes meet, or either is not finite (and so proves nothing).
    pub(super) fn may_meet(&self, o: &Aabb) -> bool {
        !self.is_finite() || !o.is_finite() || self.meets(o)
    }

    pub(super) fn meets(&self, o: &Aabb) -> bool {
        (0..2).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }
}
