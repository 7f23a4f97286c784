//! The reference geometry the tests and the arms benchmark share: points, the placing of a
//! shape at a pose, pose interpolation, an independent oracle for the distance of two convex
//! polygons, and conservative advancement of one pair. Plain arrays and the `robust` crate
//! only: nothing from the library under test.

use workcell::geometry::Vec2;

// ---------------------------------------------------------------------------------------
// Points
// ---------------------------------------------------------------------------------------

pub type Pt = [f64; 2];

/// A polygon's vertices as the generators make them (counter-clockwise, body frame).
pub type Shape = Vec<Pt>;

/// A point the oracle can read and `place` can write: `[f64; 2]` or `Vec2`.
pub trait Point: Copy {
    fn xy(self) -> Pt;
    fn from_xy(p: Pt) -> Self;
}

impl Point for Pt {
    fn xy(self) -> Pt {
        self
    }
    fn from_xy(p: Pt) -> Self {
        p
    }
}

impl Point for Vec2 {
    fn xy(self) -> Pt {
        [self.x, self.y]
    }
    fn from_xy([x, y]: Pt) -> Self {
        Vec2::new(x, y)
    }
}

pub fn sub(a: Pt, b: Pt) -> Pt {
    [a[0] - b[0], a[1] - b[1]]
}

pub fn dot(a: Pt, b: Pt) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// World vertices: R(theta)·p + (x, y), computed here rather than by `Posed`.
pub fn place<P: Point>(local: &[P], [x, y, theta]: [f64; 3]) -> Vec<P> {
    let (s, c) = theta.sin_cos();
    local
        .iter()
        .map(|p| {
            let [px, py] = p.xy();
            P::from_xy([c * px - s * py + x, s * px + c * py + y])
        })
        .collect()
}

/// The mean of the vertices.
pub fn centroid<P: Point>(poly: &[P]) -> P {
    let [x, y] = poly.iter().fold([0.0, 0.0], |[x, y], p| {
        let [px, py] = p.xy();
        [x + px, y + py]
    });
    P::from_xy([x / poly.len() as f64, y / poly.len() as f64])
}

/// The largest distance from `c` to a vertex.
pub fn radius_about<P: Point>(poly: &[P], c: P) -> f64 {
    poly.iter()
        .map(|p| {
            let [dx, dy] = sub(p.xy(), c.xy());
            dx.hypot(dy)
        })
        .fold(0.0, f64::max)
}

/// The pose of samples `[t, x, y, theta]` by linear interpolation in (x, y, θ), resting at
/// the ends: written here, not taken from the library.
pub fn pose_at(samples: &[[f64; 4]], t: f64) -> [f64; 3] {
    let first = samples[0];
    let last = samples[samples.len() - 1];
    if t <= first[0] {
        return [first[1], first[2], first[3]];
    }
    if t >= last[0] {
        return [last[1], last[2], last[3]];
    }
    let k = samples.iter().rposition(|s| s[0] <= t).unwrap();
    let (p, q) = (samples[k], samples[k + 1]);
    lerp_pose(p, q, (t - p[0]) / (q[0] - p[0]))
}

/// The pose at fraction `u` of the way from sample `p` to sample `q`.
pub fn lerp_pose(p: [f64; 4], q: [f64; 4], u: f64) -> [f64; 3] {
    [1, 2, 3].map(|i| p[i] + (q[i] - p[i]) * u)
}

// ---------------------------------------------------------------------------------------
// Independent oracle
// ---------------------------------------------------------------------------------------

/// Twice the signed area of triangle abc, exact in sign (Shewchuk's adaptive predicate):
/// a plain cross product gives ±4·10⁻¹⁶ for collinear points, and the oracle then took
/// collinear disjoint edges for crossing ones.
pub fn orient(a: Pt, b: Pt, c: Pt) -> f64 {
    let at = |p: Pt| robust::Coord { x: p[0], y: p[1] };
    robust::orient2d(at(a), at(b), at(c))
}

fn point_segment(p: Pt, a: Pt, b: Pt) -> f64 {
    let ab = sub(b, a);
    let len2 = dot(ab, ab);
    let t = if len2 == 0.0 {
        0.0
    } else {
        (dot(sub(p, a), ab) / len2).clamp(0.0, 1.0)
    };
    (a[0] + ab[0] * t - p[0]).hypot(a[1] + ab[1] * t - p[1])
}

/// Edge `j` of `poly`, from vertex `j` to the next.
fn edge<P: Point>(poly: &[P], j: usize) -> (Pt, Pt) {
    (poly[j].xy(), poly[(j + 1) % poly.len()].xy())
}

/// Weakly inside (boundary included), whatever the orientation of `poly`.
fn inside<P: Point>(p: P, poly: &[P]) -> bool {
    let (mut pos, mut neg) = (false, false);
    for i in 0..poly.len() {
        let (a, b) = edge(poly, i);
        let s = orient(a, b, p.xy());
        pos |= s > 0.0;
        neg |= s < 0.0;
    }
    !(pos && neg)
}

fn within_box(p: Pt, a: Pt, b: Pt) -> bool {
    p[0] >= a[0].min(b[0])
        && p[0] <= a[0].max(b[0])
        && p[1] >= a[1].min(b[1])
        && p[1] <= a[1].max(b[1])
}

/// Closed segments p0p1 and q0q1 share a point.
fn segments_meet((p0, p1): (Pt, Pt), (q0, q1): (Pt, Pt)) -> bool {
    let d1 = orient(q0, q1, p0);
    let d2 = orient(q0, q1, p1);
    let d3 = orient(p0, p1, q0);
    let d4 = orient(p0, p1, q1);
    let opposite = |u: f64, v: f64| (u > 0.0 && v < 0.0) || (u < 0.0 && v > 0.0);
    if opposite(d1, d2) && opposite(d3, d4) {
        return true;
    }
    (d1 == 0.0 && within_box(p0, q0, q1))
        || (d2 == 0.0 && within_box(p1, q0, q1))
        || (d3 == 0.0 && within_box(q0, p0, p1))
        || (d4 == 0.0 && within_box(q1, p0, p1))
}

/// The polygons share a point: a vertex of one inside the other, or two edges meeting.
fn overlap<P: Point>(a: &[P], b: &[P]) -> bool {
    a.iter().any(|&p| inside(p, b))
        || b.iter().any(|&p| inside(p, a))
        || (0..a.len()).any(|i| (0..b.len()).any(|j| segments_meet(edge(a, i), edge(b, j))))
}

/// Distance from `p` to the boundary of `poly`.
pub fn boundary_distance<P: Point>(p: P, poly: &[P]) -> f64 {
    (0..poly.len())
        .map(|j| {
            let (a, b) = edge(poly, j);
            point_segment(p.xy(), a, b)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The smallest vertex-edge distance in either direction, whether or not the polygons
/// overlap.
fn boundary_gap<P: Point>(a: &[P], b: &[P]) -> f64 {
    [(a, b), (b, a)]
        .into_iter()
        .flat_map(|(pts, poly)| pts.iter().map(|&p| boundary_distance(p, poly)))
        .fold(f64::INFINITY, f64::min)
}

#[derive(Clone, Copy, Debug)]
pub struct Exact {
    /// 0 on overlap, else the smallest vertex-edge distance.
    pub distance: f64,
    /// The smallest vertex-edge distance, whether or not the polygons overlap.
    pub boundary_gap: f64,
    pub overlap: bool,
}

pub fn exact<P: Point>(a: &[P], b: &[P]) -> Exact {
    let overlap = overlap(a, b);
    let boundary_gap = boundary_gap(a, b);
    Exact {
        distance: if overlap { 0.0 } else { boundary_gap },
        boundary_gap,
        overlap,
    }
}

/// Exact distance of two convex polygons: `exact(a, b).distance`, without the boundary gap
/// when they overlap.
pub fn exact_distance<P: Point>(a: &[P], b: &[P]) -> f64 {
    if overlap(a, b) {
        0.0
    } else {
        boundary_gap(a, b)
    }
}

/// Conservative advancement of one pair, the reference of the property tests: the first time
/// `distance` drops below `delta` over `(h0, h1)`, with the end of the prefix proven δ apart
/// before it; or `None` when it never does. `speed(t)` bounds how fast the pair's gap can
/// close from `t` until the time it also gives (the next sample of either body).
///
/// A step is (d − δ) over that speed. Near a contact such steps shrink without end: under
/// `min_step` the advance goes on by `min_step`, unproven, until δ is crossed (the contact
/// lies in between). `Err` when the pair then moves away again: a graze too close to δ for
/// the reference to decide.
pub fn advance_to_contact(
    distance: impl Fn(f64) -> f64,
    speed: impl Fn(f64) -> (f64, f64),
    (h0, h1): (f64, f64),
    delta: f64,
    min_step: f64,
) -> Result<Option<(f64, f64)>, ()> {
    let mut t = h0;
    // Where unproven steps began.
    let mut unproven_from: Option<f64> = None;
    loop {
        let d = distance(t);
        if d < delta {
            return Ok(Some((unproven_from.unwrap_or(t), t)));
        }
        let (v, until) = speed(t);
        let segment_end = until.min(h1);
        let step = if v > 0.0 {
            (d - delta) / v
        } else {
            f64::INFINITY
        };
        if step >= min_step || t >= h1 {
            if unproven_from.is_some() {
                return Err(());
            }
            if t >= h1 {
                return Ok(None);
            }
            t = if step >= segment_end - t {
                segment_end
            } else {
                t + step
            };
            continue;
        }
        unproven_from.get_or_insert(t);
        t = (t + min_step).min(h1);
    }
}
