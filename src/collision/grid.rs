//! The merged time grid of a pair, walked forward with one cursor per body.
//!
//! Both grids are sorted already (a trajectory's times strictly increase), so their union is
//! a merge: no sort, no allocation, and each pose comes from the segment the cursor is on
//! instead of a binary search per time.

use super::Body;
use crate::motion::{Motion, Pose};

/// One body's place in its own grid: the number of its samples at or before the time last
/// yielded.
#[derive(Clone)]
struct Cursor<'a> {
    motion: &'a Motion,
    times: &'a [crate::motion::Sample],
    after: usize,
}

impl<'a> Cursor<'a> {
    fn new(body: &'a Body) -> Self {
        let times = match &body.motion {
            Motion::Sampled(tr) => tr.samples(),
            Motion::Link(l) => l.frames(),
            Motion::Fixed(_) => &[],
        };
        Cursor {
            motion: &body.motion,
            times,
            after: 0,
        }
    }

    /// The next sample time strictly inside (.., `end`), if any.
    fn head(&self, end: f64) -> Option<f64> {
        self.times.get(self.after).map(|s| s.t).filter(|&t| t < end)
    }

    /// Moves past every sample at or before `t`.
    fn pass(&mut self, t: f64) {
        while self.times.get(self.after).is_some_and(|s| s.t <= t) {
            self.after += 1;
        }
    }

    /// The pose at the time last passed: bit for bit [`Motion::pose_at`].
    fn pose(&self, t: f64) -> Pose {
        self.pose_with(self.after, t)
    }

    /// The pose at `t`, a time with `after` samples at or before it.
    fn pose_with(&self, after: usize, t: f64) -> Pose {
        match self.motion {
            Motion::Sampled(tr) => tr.pose_after(after, t),
            // At the arm's own sample time the frame is already known (the same bits).
            Motion::Link(l) => match after.checked_sub(1).map(|k| &self.times[k]) {
                Some(f) if f.t == t => Pose {
                    pos: f.pos,
                    theta: f.theta,
                },
                _ => l.arm.pose_after(after, t, l.link),
            },
            Motion::Fixed(p) => *p,
        }
    }
}

/// The union of both bodies' sample times strictly inside the horizon, with the horizon's
/// ends, in increasing order and without repeats; each time with both poses. On each
/// interval between consecutive times both poses are linear in time.
#[derive(Clone)]
pub(super) struct MergedGrid<'a> {
    a: Cursor<'a>,
    b: Cursor<'a>,
    horizon: (f64, f64),
    /// The last time yielded; `None` before the first.
    last: Option<f64>,
}

impl<'a> MergedGrid<'a> {
    pub fn new(a: &'a Body, b: &'a Body, horizon: (f64, f64)) -> Self {
        MergedGrid {
            a: Cursor::new(a),
            b: Cursor::new(b),
            horizon,
            last: None,
        }
    }

    /// The next time, without the poses ([`MergedGrid::poses`] gives them).
    pub fn next_time(&mut self) -> Option<f64> {
        let (t0, t1) = self.horizon;
        let t = match self.last {
            None => t0,
            Some(last) if last >= t1 => return None,
            Some(_) => match (self.a.head(t1), self.b.head(t1)) {
                // The lesser in total order: a sort by `total_cmp` then `dedup` keeps it.
                (Some(x), Some(y)) => x.min_total(y),
                (Some(x), None) | (None, Some(x)) => x,
                (None, None) => t1,
            },
        };
        self.a.pass(t);
        self.b.pass(t);
        self.last = Some(t);
        Some(t)
    }

    /// For each body, the number of its samples at or before the time last yielded: a link's
    /// segment over the interval that starts there.
    pub fn afters(&self) -> (usize, usize) {
        (self.a.after, self.b.after)
    }

    /// Both poses at `t`, the time last yielded.
    pub fn poses(&self, t: f64) -> (Pose, Pose) {
        (self.a.pose(t), self.b.pose(t))
    }

    /// Both poses at `t`, a time with `afters` samples of each body at or before it (as
    /// [`MergedGrid::afters`] gave them when `t` was the time last yielded).
    pub fn poses_with(&self, (after_a, after_b): (usize, usize), t: f64) -> (Pose, Pose) {
        (self.a.pose_with(after_a, t), self.b.pose_with(after_b, t))
    }

    /// Body B's pose (A's when `b` is false) at `t`, a time with `after` of its samples at
    /// or before it.
    pub fn pose_of(&self, b: bool, after: usize, t: f64) -> Pose {
        match b {
            false => self.a.pose_with(after, t),
            true => self.b.pose_with(after, t),
        }
    }

    /// The number of times not yielded yet.
    pub fn count_rest(mut self) -> usize {
        std::iter::from_fn(|| self.next_time()).count()
    }
}

impl Iterator for MergedGrid<'_> {
    /// A time and both poses at it.
    type Item = (f64, (Pose, Pose));

    fn next(&mut self) -> Option<Self::Item> {
        let t = self.next_time()?;
        Some((t, self.poses(t)))
    }
}

trait MinTotal {
    fn min_total(self, other: Self) -> Self;
}

impl MinTotal for f64 {
    fn min_total(self, other: f64) -> f64 {
        if other.total_cmp(&self).is_lt() {
            other
        } else {
            self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::ConvexPolygon;
    use crate::motion::Trajectory;
    use proptest::prelude::*;

    /// The former construction: every time, sorted, repeats removed.
    fn sorted_grid(a: &Body, b: &Body, (t0, t1): (f64, f64)) -> Vec<f64> {
        let mut grid: Vec<f64> = a
            .motion
            .times()
            .chain(b.motion.times())
            .filter(|&t| t > t0 && t < t1)
            .chain([t0, t1])
            .collect();
        grid.sort_by(f64::total_cmp);
        grid.dedup();
        grid
    }

    fn body(name: &str, times: &[f64]) -> Body {
        let square = ConvexPolygon::rectangle(1.0, 1.0).unwrap();
        if times.is_empty() {
            return Body::obstacle(name, &square);
        }
        let poses = times.iter().enumerate().map(|(k, &t)| {
            let k = k as f64;
            (t, Pose::new(k.sin() * 3.0, k * 0.5, k * 0.1))
        });
        Body::robot(name, square, Trajectory::from_poses(poses).unwrap())
    }

    fn increasing(max: usize) -> impl Strategy<Value = Vec<f64>> {
        // Small integers and halves make shared times and times at the horizon's ends common.
        proptest::collection::btree_set(-8i32..40, 0..max)
            .prop_map(|s| s.into_iter().map(|k| f64::from(k) * 0.5).collect())
    }

    proptest! {
        #[test]
        fn merge_is_the_sorted_union_with_the_same_poses(
            ta in increasing(30),
            tb in increasing(30),
            ends in (-6i32..10, 0i32..30),
        ) {
            let (a, b) = (body("a", &ta), body("b", &tb));
            let horizon = (f64::from(ends.0), f64::from(ends.0 + ends.1));
            let expected = sorted_grid(&a, &b, horizon);
            let merged: Vec<_> = MergedGrid::new(&a, &b, horizon).collect();
            let times: Vec<f64> = merged.iter().map(|m| m.0).collect();
            prop_assert_eq!(times.iter().map(|t| t.to_bits()).collect::<Vec<_>>(),
                expected.iter().map(|t| t.to_bits()).collect::<Vec<_>>());
            for (t, (pa, pb)) in merged {
                prop_assert_eq!(pa, a.motion.pose_at(t));
                prop_assert_eq!(pb, b.motion.pose_at(t));
            }
            for skip in 0..expected.len() {
                let mut g = MergedGrid::new(&a, &b, horizon);
                g.by_ref().take(skip).for_each(drop);
                prop_assert_eq!(g.count_rest(), expected.len() - skip);
            }
        }
    }
}
