//! The pairs of boxes that meet, through a uniform grid.

use super::aabb::Aabb;

/// Fewer boxes than this are tested against each other directly: cheaper than a grid.
const GRID_MIN_BOXES: usize = 32;
/// A box covering more grid cells than this is tested against every box of its window
/// directly, so that one long box cannot flood the grid.
const MAX_CELLS: i128 = 64;

/// Appends to `out` the pairs of bodies of `boxes` (body, box) whose boxes meet, each once,
/// and every pair with a box that is not finite.
///
/// From [`GRID_MIN_BOXES`] finite boxes on, a uniform grid with cells the size of the median
/// box: a box enters the cells it covers, and a pair is tested in the cells both enter, but
/// reported only in the first of them (the one at the larger of their lower cell indices),
/// so nothing needs deduplicating.
pub(super) fn meeting(boxes: &[(usize, Aabb)], out: &mut Vec<(usize, usize)>) {
    let (finite, wild): (Vec<_>, Vec<_>) = boxes.iter().partition(|(_, b)| b.is_finite());
    for (k, &&(i, _)) in wild.iter().enumerate() {
        let others = finite.iter().chain(&wild[k + 1..]);
        out.extend(others.map(|&&(j, _)| (i, j)));
    }
    if finite.len() < GRID_MIN_BOXES {
        for (k, &&(i, b)) in finite.iter().enumerate() {
            let meet = finite[k + 1..].iter().filter(|(_, c)| b.meets(c));
            out.extend(meet.map(|&&(j, _)| (i, j)));
        }
        return;
    }
    let mut sizes: Vec<f64> = finite.iter().map(|(_, b)| b.size()).collect();
    let mid = sizes.len() / 2;
    let cell = *sizes.select_nth_unstable_by(mid, f64::total_cmp).1;
    let cell = if cell.is_finite() && cell > 0.0 {
        cell
    } else {
        f64::MAX
    };
    let origin = [0, 1].map(|k| {
        finite
            .iter()
            .fold(f64::INFINITY, |m, (_, b)| m.min(b.lo[k]))
    });
    // Monotone in x (floor, then a saturating cast), so boxes that meet share a cell; no
    // NaN can arise since x ≥ origin and 0 < cell < ∞.
    let index = |x: f64, k: usize| ((x - origin[k]) / cell).floor() as i64;
    let mut lower = Vec::with_capacity(finite.len());
    let mut entries: Vec<(i64, i64, usize)> = Vec::with_capacity(4 * finite.len());
    let mut big = Vec::new();
    for (n, (_, b)) in finite.iter().enumerate() {
        let (x0, x1) = (index(b.lo[0], 0), index(b.hi[0], 0));
        let (y0, y1) = (index(b.lo[1], 1), index(b.hi[1], 1));
        lower.push((x0, y0));
        let cells = (x1 as i128 - x0 as i128 + 1) * (y1 as i128 - y0 as i128 + 1);
        if cells > MAX_CELLS {
            big.push(n);
        } else {
            entries.extend((x0..=x1).flat_map(|x| (y0..=y1).map(move |y| (x, y, n))));
        }
    }
    // Big boxes against all others (against each other once).
    for (k, &n) in big.iter().enumerate() {
        let (i, b) = finite[n];
        for (m, (j, c)) in finite.iter().enumerate() {
            let other_big = big.binary_search(&m).is_ok_and(|l| l <= k);
            if !other_big && b.meets(c) {
                out.push((*i, *j));
            }
        }
    }
    entries.sort_unstable();
    for run in entries.chunk_by(|p, q| (p.0, p.1) == (q.0, q.1)) {
        for (k, &(x, y, n)) in run.iter().enumerate() {
            for &(_, _, m) in &run[k + 1..] {
                let first = (lower[n].0.max(lower[m].0), lower[n].1.max(lower[m].1));
                if first == (x, y) && finite[n].1.meets(&finite[m].1) {
                    out.push((finite[n].0, finite[m].0));
                }
            }
        }
    }
}
