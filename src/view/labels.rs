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
const RINGS: [f64; 5] = [8.0, 18.0, 32.0, 48.0, 64.0];

/// Directions tried between the eight main ones when a label is led away.
const LED_ANGLES: usize = 16;

/// Where a label went.
pub struct Placed {
    /// Left end of the text.
    pub x: f64,
    /// Baseline.
    pub y: f64,
    /// The leader line from the anchor to the label's nearer end, when it is away from its
    /// anchor.
    pub leader: Option<Segment>,
}

/// A line segment `[x0, y0, x1, y1]` in picture pixels: a piece of a path or an outline.
pub type Segment = [f64; 4];

/// The boxes and lines taken so far and the area labels must stay in.
pub struct Placer {
    taken: Vec<Rect>,
    /// The labels' boxes among `taken`: no leader line may cross them.
    labels: Vec<Rect>,
    /// Lines no label may cross (paths, outlines, leader lines), with their bounding boxes
    /// for a quick rejection.
    lines: Vec<(Rect, Segment)>,
    bounds: Rect,
    /// Labels that found no place.
    pub left_out: usize,
}

fn overlaps(a: &Rect, b: &Rect) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// [`overlaps`] for closed boxes: a horizontal or vertical line's box has no width.
fn overlaps_or_touches(a: &Rect, b: &Rect) -> bool {
    a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3]
}

/// Whether segment `s` has a point inside box `r` (Liang-Barsky clipping: the parameter
/// interval of the segment left inside all four half-planes is not empty).
pub fn crosses(r: &Rect, s: &Segment) -> bool {
    let (dx, dy) = (s[2] - s[0], s[3] - s[1]);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, s[0] - r[0]),
        (dx, r[2] - s[0]),
        (-dy, s[1] - r[1]),
        (dy, r[3] - s[1]),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false; // parallel to this side and outside it
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return false;
            }
        }
    }
    true
}

impl Placer {
    /// Labels stay inside `bounds`.
    pub fn new(bounds: Rect) -> Placer {
        Placer {
            taken: Vec::new(),
            labels: Vec::new(),
            lines: Vec::new(),
            bounds,
            left_out: 0,
        }
    }

    /// Marks a box as taken (a symbol, a title).
    pub fn take(&mut self, r: Rect) {
        self.taken.push(r);
    }

    /// Marks a line as taken: no label will cross it.
    ///
    /// ```
    /// use workcell::view::Placer;
    /// let mut p = Placer::new([0.0, 0.0, 100.0, 100.0]);
    /// p.take_line([0.0, 50.0, 100.0, 50.0]);
    /// assert!(!p.free(&[10.0, 45.0, 30.0, 55.0]) && p.free(&[10.0, 30.0, 30.0, 45.0]));
    /// ```
    pub fn take_line(&mut self, s: Segment) {
        let bounds = [
            s[0].min(s[2]),
            s[1].min(s[3]),
            s[0].max(s[2]),
            s[1].max(s[3]),
        ];
        self.lines.push((bounds, s));
    }

    /// Marks the sides of a polygon (closed) or the pieces of a polyline as taken.
    ///
    /// ```
    /// use workcell::view::Placer;
    /// let square = [(10.0, 10.0), (50.0, 10.0), (50.0, 50.0), (10.0, 50.0)];
    /// let mut open = Placer::new([0.0, 0.0, 100.0, 100.0]);
    /// open.take_outline(&square, false);
    /// let mut closed = Placer::new([0.0, 0.0, 100.0, 100.0]);
    /// closed.take_outline(&square, true);
    /// let on_the_left_side = [5.0, 20.0, 15.0, 30.0];
    /// assert!(open.free(&on_the_left_side) && !closed.free(&on_the_left_side));
    /// assert!(closed.free(&[20.0, 20.0, 40.0, 30.0])); // inside crosses no side
    /// ```
    pub fn take_outline(&mut self, points: &[(f64, f64)], closed: bool) {
        let wrap = closed.then(|| (points.last(), points.first()));
        let pieces = points.windows(2).map(|w| (&w[0], &w[1]));
        for (a, b) in pieces.chain(wrap.and_then(|(a, b)| a.zip(b))) {
            self.take_line([a.0, a.1, b.0, b.1]);
        }
    }

    /// Whether a box is free (of boxes and lines) and inside the bounds.
    pub fn free(&self, r: &Rect) -> bool {
        let b = &self.bounds;
        r[0] >= b[0]
            && r[1] >= b[1]
            && r[2] <= b[2]
            && r[3] <= b[3]
            && !self.taken.iter().any(|t| overlaps(t, r))
            && !self
                .lines
                .iter()
                .any(|(bounds, s)| overlaps_or_touches(bounds, r) && crosses(r, s))
    }

    /// Places a label of `width` × `size` near `(ax, ay)`: right, left, above, below and the
    /// diagonals, nearest first; farther away with a leader line that crosses no other label;
    /// `None` (and counted as left out) when all are taken.
    pub fn place(&mut self, ax: f64, ay: f64, width: f64, size: f64) -> Option<Placed> {
        for (ring, d) in RINGS.iter().enumerate() {
            // Offsets of the box's left-top corner for each direction.
            let h = size;
            let beside = [
                (ax + d, ay - h / 2.0),
                (ax - d - width, ay - h / 2.0),
                (ax - width / 2.0, ay - d - h),
                (ax - width / 2.0, ay + d),
                (ax + d, ay - d - h),
                (ax - d - width, ay - d - h),
                (ax + d, ay + d),
                (ax - d - width, ay + d),
            ];
            // Led away, also at the angles between: a dense picture has gaps there.
            let between = (ring > 0).then(|| {
                (0..LED_ANGLES).map(move |k| {
                    let a = std::f64::consts::TAU * (k as f64 + 0.5) / LED_ANGLES as f64;
                    let (cx, cy) = (ax + d * a.cos(), ay - d * a.sin());
                    let x0 = if a.cos() >= 0.0 { cx } else { cx - width };
                    (x0, cy - h / 2.0)
                })
            });
            for (x0, y0) in beside.into_iter().chain(between.into_iter().flatten()) {
                let r = [x0 - GAP, y0 - GAP, x0 + width + GAP, y0 + h + GAP];
                // To the nearer end of the label, at its middle height.
                let lx = if x0 >= ax { x0 } else { x0 + width };
                let leader = (ring > 0).then_some([ax, ay, lx, y0 + 0.45 * h]);
                let leader_clear =
                    leader.is_none_or(|s| !self.labels.iter().any(|l| crosses(l, &s)));
                if leader_clear && self.free(&r) {
                    self.taken.push(r);
                    self.labels.push(r);
                    if let Some(s) = leader {
                        self.take_line(s);
                    }
                    return Some(Placed {
                        x: x0,
                        // The baseline sits about a fifth of the size above the box's bottom.
                        y: y0 + 0.8 * h,
                        leader,
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
    fn a_segment_crosses_a_box_when_a_piece_of_it_is_inside() {
        let r = [0.0, 0.0, 10.0, 4.0];
        assert!(crosses(&r, &[-5.0, 2.0, 15.0, 2.0])); // through
        assert!(crosses(&r, &[5.0, 2.0, 50.0, 90.0])); // from inside
        assert!(crosses(&r, &[-1.0, -1.0, 11.0, 5.0])); // the diagonal
        assert!(crosses(&r, &[0.0, -3.0, 0.0, 9.0])); // along a side
        assert!(!crosses(&r, &[-5.0, 5.0, 15.0, 5.0])); // above
        assert!(!crosses(&r, &[11.0, -9.0, 11.0, 9.0])); // beside, vertical
        assert!(!crosses(&r, &[9.0, 6.0, 14.0, 1.0])); // past the corner
        assert!(crosses(&r, &[8.0, 6.0, 13.0, 1.0])); // touching the corner
        assert!(!crosses(&r, &[20.0, 2.0, 30.0, 2.0])); // on the line, past the box
    }

    #[test]
    fn labels_keep_off_the_lines_taken() {
        let mut p = Placer::new([0.0, 0.0, 200.0, 200.0]);
        // A path through the anchor, left to right, and one going up from it.
        p.take_outline(&[(0.0, 100.0), (100.0, 100.0), (200.0, 100.0)], false);
        p.take_line([100.0, 100.0, 100.0, 0.0]);
        let l = p.place(100.0, 100.0, 40.0, 10.0).expect("below is free");
        assert!(l.y - 8.0 > 100.0, "the label goes below the path: {}", l.y);
        let r = [l.x, l.y - 8.0, l.x + 40.0, l.y + 2.0];
        assert!(!crosses(&r, &[0.0, 100.0, 200.0, 100.0]));
    }

    #[test]
    fn labels_at_one_anchor_never_overlap_and_the_rest_are_left_out() {
        let mut p = Placer::new([0.0, 0.0, 200.0, 200.0]);
        let placed = place_all(&mut p, &[(100.0, 100.0); 40]);
        // Round the anchor, a few fit; then a leader from it would cross one of them.
        assert!(
            placed.len() >= 6 && p.left_out > 0,
            "{} placed",
            placed.len()
        );
        leaders_are_clear(&placed);
    }

    #[test]
    fn leaders_reach_their_label_and_cross_no_other() {
        // Symbols on a grid 16 pixels apart: most labels must be led away.
        let anchors: Vec<(f64, f64)> = (0..30)
            .map(|k| (200.0 + 16.0 * (k % 6) as f64, 150.0 + 16.0 * (k / 6) as f64))
            .collect();
        let mut p = Placer::new([0.0, 0.0, 500.0, 400.0]);
        for &(x, y) in &anchors {
            p.take([x - 5.0, y - 5.0, x + 5.0, y + 5.0]);
        }
        let placed = place_all(&mut p, &anchors);
        let led = placed.iter().filter(|(_, l)| l.is_some()).count();
        assert!(
            led >= 5 && placed.len() >= 10,
            "{} placed, {led} led",
            placed.len()
        );
        leaders_are_clear(&placed);
    }

    /// Each leader reaches its own label and crosses no other.
    fn leaders_are_clear(placed: &[(Rect, Option<Segment>)]) {
        for (k, (r, leader)) in placed.iter().enumerate() {
            let Some(s) = leader else { continue };
            assert!(crosses(r, s), "leader {k} misses its label");
            for (j, (other, _)) in placed.iter().enumerate() {
                assert!(j == k || !crosses(other, s), "leader {k} crosses label {j}");
            }
        }
    }

    /// Places a label 40 × 10 at each anchor; the boxes of those placed (without the gap)
    /// and their leaders, checked never to overlap one another.
    fn place_all(p: &mut Placer, anchors: &[(f64, f64)]) -> Vec<(Rect, Option<Segment>)> {
        let mut placed: Vec<(Rect, Option<Segment>)> = Vec::new();
        for &(x, y) in anchors {
            if let Some(l) = p.place(x, y, 40.0, 10.0) {
                let r = [l.x, l.y - 8.0, l.x + 40.0, l.y + 2.0];
                assert!(placed.iter().all(|(b, _)| !overlaps(b, &r)));
                placed.push((r, l.leader));
            }
        }
        assert_eq!(placed.len() + p.left_out, anchors.len());
        placed
    }
}
