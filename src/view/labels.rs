//! Labels that never overprint: each is tried at a few places round its anchor, then
//! farther away with a leader line, and left out when nothing is free.

/// A box `[x0, y0, x1, y1]` in picture pixels.
pub type Rect = [f64; 4];

/// Width of one character, generous for sans-serif (average glyphs are about 0.55 em).
pub const CHAR_EM: f64 = 0.62;

/// Estimated width of `text` at `size` pixels.
pub fn text_width(text: &str, size: f64) -> f64 {
    CHAR_EM * size * text.chars().count() as f64
}

/// Gap kept between a label and anything else, so that neighbours never read as one word.
const GAP: f64 = 2.0;

/// Distances from the anchor tried: beside it, then led away.
const RINGS: [f64; 3] = [8.0, 18.0, 32.0];

/// Where a label went.
pub struct Placed {
    /// Left end of the text.
    pub x: f64,
    /// Baseline.
    pub y: f64,
    /// Whether it is away from its anchor and needs a leader line.
    pub led: bool,
}

/// The boxes taken so far and the area labels must stay in.
pub struct Placer {
    taken: Vec<Rect>,
    bounds: Rect,
    /// Labels that found no place.
    pub left_out: usize,
}

fn overlaps(a: &Rect, b: &Rect) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

impl Placer {
    /// Labels stay inside `bounds`.
    pub fn new(bounds: Rect) -> Placer {
        Placer {
            taken: Vec::new(),
            bounds,
            left_out: 0,
        }
    }

    /// Marks a box as taken (a symbol, a title).
    pub fn take(&mut self, r: Rect) {
        self.taken.push(r);
    }

    /// Whether a box is free and inside the bounds.
    pub fn free(&self, r: &Rect) -> bool {
        let b = &self.bounds;
        r[0] >= b[0]
            && r[1] >= b[1]
            && r[2] <= b[2]
            && r[3] <= b[3]
            && !self.taken.iter().any(|t| overlaps(t, r))
    }

    /// Places a label of `width` × `size` near `(ax, ay)`: right, left, above, below and the
    /// diagonals, nearest first; `None` (and counted as left out) when all are taken.
    pub fn place(&mut self, ax: f64, ay: f64, width: f64, size: f64) -> Option<Placed> {
        for (ring, d) in RINGS.iter().enumerate() {
            // Offsets of the box's left-top corner for each direction.
            let h = size;
            let candidates = [
                (ax + d, ay - h / 2.0),
                (ax - d - width, ay - h / 2.0),
                (ax - width / 2.0, ay - d - h),
                (ax - width / 2.0, ay + d),
                (ax + d, ay - d - h),
                (ax - d - width, ay - d - h),
                (ax + d, ay + d),
                (ax - d - width, ay + d),
            ];
            for (x0, y0) in candidates {
                let r = [x0 - GAP, y0 - GAP, x0 + width + GAP, y0 + h + GAP];
                if self.free(&r) {
                    self.taken.push(r);
                    return Some(Placed {
                        x: x0,
                        // The baseline sits about a fifth of the size above the box's bottom.
                        y: y0 + 0.8 * h,
                        led: ring > 0,
                    });
                }
            }
        }
        self.left_out += 1;
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_at_one_anchor_never_overlap_and_the_rest_are_left_out() {
        let mut p = Placer::new([0.0, 0.0, 200.0, 200.0]);
        let mut boxes: Vec<Rect> = Vec::new();
        for _ in 0..40 {
            if let Some(l) = p.place(100.0, 100.0, 40.0, 10.0) {
                let r = [l.x, l.y - 8.0, l.x + 40.0, l.y + 2.0];
                assert!(boxes.iter().all(|b| !overlaps(b, &r)));
                boxes.push(r);
            }
        }
        assert!(boxes.len() >= 8 && p.left_out > 0);
        assert_eq!(boxes.len() + p.left_out, 40);
    }
}
