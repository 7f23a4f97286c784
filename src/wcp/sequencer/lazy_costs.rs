//! Travel costs of instances too large for a matrix (robots × nodes² beyond
//! `DENSE_MAX_ARCS`): lower bounds computed when asked, the exact arcs known so far, and a
//! band of precomputed costs.
//!
//! The nodes are laid out in slots along a Hilbert curve of the task positions
//! ([`hilbert_slots`]): tasks near in space are mostly near in slot. The band holds, per
//! robot and node, the costs to the nodes within [`BAND`] slots of it, and every move from
//! and to home; nearly every cost a granular search asks for is there, in memory linear in
//! robots × nodes × band. The others come from the exact arcs, else from the bounds.

use std::sync::Arc;

use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::bounds::Bounds;
use super::ExactArcs;

/// Slots on either side of a node whose costs the band holds.
pub(super) const BAND: usize = 40;
/// Width of a band row.
const ROW: usize = 2 * BAND + 1;
/// Bits per axis of the grid on which tasks are ordered along a Hilbert curve.
const HILBERT_BITS: u32 = 16;

pub(super) struct LazyCosts {
    n1: usize,
    slot: Vec<usize>,
    bounds: Arc<Bounds>,
    /// The exact arcs keyed `(r · n1 + from) · n1 + to` (penalised).
    exact: FxHashMap<u64, f64>,
    /// `[(r · n1 + slot[a]) · ROW + BAND + slot[b] − slot[a]]`: the cost from a to b.
    band: Vec<f64>,
    /// `[r · n1 + a]`: from home to node a, and back.
    out: Vec<f64>,
    back: Vec<f64>,
}

impl LazyCosts {
    /// Costs of `robots` robots over `n1` nodes laid out in `slot`s; `finite` turns an
    /// infinite exact time into the model's penalty.
    pub fn new(
        robots: usize,
        slot: &[usize],
        bounds: Arc<Bounds>,
        arcs: &ExactArcs,
        finite: &(dyn Fn(f64) -> f64 + Sync),
    ) -> LazyCosts {
        let n1 = slot.len();
        let mut exact = FxHashMap::default();
        for (r, arcs) in arcs.iter().enumerate() {
            for (&(a, b), &v) in arcs {
                if a != b {
                    exact.insert(((r * n1 + a) * n1 + b) as u64, finite(v));
                }
            }
        }
        let mut costs = LazyCosts {
            n1,
            slot: slot.to_vec(),
            bounds,
            exact,
            band: vec![0.0; robots * n1 * ROW],
            out: vec![0.0; robots * n1],
            back: vec![0.0; robots * n1],
        };
        let mut node = vec![0; n1];
        for (v, &k) in slot.iter().enumerate() {
            node[k] = v;
        }
        let mut band = std::mem::take(&mut costs.band);
        band.par_chunks_mut(n1 * ROW)
            .enumerate()
            .for_each(|(r, rows)| {
                for (sa, row) in rows.chunks_mut(ROW).enumerate() {
                    for (k, c) in row.iter_mut().enumerate() {
                        let sb = sa + k;
                        if sb >= BAND && sb - BAND < n1 {
                            *c = costs.far(r, node[sa], node[sb - BAND]);
                        }
                    }
                }
            });
        let mut out = std::mem::take(&mut costs.out);
        let mut back = std::mem::take(&mut costs.back);
        for (k, (o, b)) in out.iter_mut().zip(&mut back).enumerate() {
            let (r, a) = (k / n1, k % n1);
            (*o, *b) = (costs.far(r, 0, a), costs.far(r, a, 0));
        }
        (costs.band, costs.out, costs.back) = (band, out, back);
        costs
    }

    #[inline(always)]
    pub fn get(&self, r: usize, a: usize, b: usize) -> f64 {
        if a == 0 {
            return self.out[r * self.n1 + b];
        }
        if b == 0 {
            return self.back[r * self.n1 + a];
        }
        let (sa, sb) = (self.slot[a], self.slot[b]);
        let k = (sb + BAND).wrapping_sub(sa);
        if k < ROW {
            return self.band[(r * self.n1 + sa) * ROW + k];
        }
        self.far(r, a, b)
    }

    /// The exact arc when known, else the bound.
    #[inline(never)]
    fn far(&self, r: usize, a: usize, b: usize) -> f64 {
        if a == b {
            return 0.0;
        }
        match self.exact.get(&(((r * self.n1 + a) * self.n1 + b) as u64)) {
            Some(&v) => v,
            None => self.bounds.bound(r, a, b),
        }
    }
}

/// Each node's slot when the tasks are sorted along a Hilbert curve over their positions
/// (ties by index); home keeps slot 0.
pub(super) fn hilbert_slots(bounds: &Bounds) -> Vec<usize> {
    let n = bounds.tasks();
    let points: Vec<_> = (0..n).map(|t| bounds.task_position(t)).collect();
    let (lo, hi) = points.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p.x), lo[1].min(p.y)],
                [hi[0].max(p.x), hi[1].max(p.y)],
            )
        },
    );
    let side = (1u64 << HILBERT_BITS) as f64 - 1.0;
    let cell = |v: f64, k: usize| {
        let span = hi[k] - lo[k];
        if span > 0.0 && v.is_finite() {
            (((v - lo[k]) / span) * side).clamp(0.0, side) as u64
        } else {
            0
        }
    };
    let mut order: Vec<(u64, usize)> = points
        .iter()
        .enumerate()
        .map(|(t, p)| (hilbert_index(cell(p.x, 0), cell(p.y, 1)), t))
        .collect();
    order.sort_unstable();
    let mut slot = vec![0; n + 1];
    for (k, &(_, t)) in order.iter().enumerate() {
        slot[t + 1] = k + 1;
    }
    slot
}

/// Position of grid cell `(x, y)` along the Hilbert curve of side 2^[`HILBERT_BITS`].
fn hilbert_index(mut x: u64, mut y: u64) -> u64 {
    let side = 1u64 << HILBERT_BITS;
    let mut d = 0;
    let mut s = side / 2;
    while s > 0 {
        let rx = u64::from(x & s > 0);
        let ry = u64::from(y & s > 0);
        d += s * s * ((3 * rx) ^ ry);
        // Turn the quadrant so that the curve inside it starts where the last one ended
        // (bits above `s` are never read again).
        if ry == 0 {
            if rx == 1 {
                x = side - 1 - x;
                y = side - 1 - y;
            }
            std::mem::swap(&mut x, &mut y);
        }
        s /= 2;
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Consecutive cells of the curve are grid neighbours, and every cell is visited once.
    #[test]
    fn the_hilbert_curve_visits_every_cell_once_by_steps_of_one() {
        let side = 1u64 << HILBERT_BITS;
        let step = side / 8;
        // On the 8 × 8 grid of cells spaced `step` apart: distinct indices, ordered so
        // that consecutive cells touch.
        let mut cells: Vec<(u64, u64, u64)> = (0..8)
            .flat_map(|x| (0..8).map(move |y| (x, y)))
            .map(|(x, y)| (hilbert_index(x * step, y * step) / (step * step), x, y))
            .collect();
        cells.sort_unstable();
        for (k, w) in cells.windows(2).enumerate() {
            assert_eq!(w[0].0, k as u64);
            assert_eq!(
                w[0].1.abs_diff(w[1].1) + w[0].2.abs_diff(w[1].2),
                1,
                "{w:?}"
            );
        }
    }
}
