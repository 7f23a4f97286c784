//! Convex polygons and the exact distance between two of them.
//!
//! * [`ConvexPolygon`]: a validated, counter-clockwise, strictly convex polygon.
//! * [`Posed`]: a polygon placed in the world by a rigid transform, evaluated lazily so
//!   that a closest-feature walk touches only the vertices it visits.
//! * [`closest_features`]: the 2-D Lin-Canny closest-feature walk of Feyeux & Landry
//!   (2013, section 5), warm-started and guarded against cycling.
//! * [`brute_force_distance`]: the exact O(n·m) reference, used as the walk's fallback
//!   and as the oracle of the tests.

mod brute_force;
mod feature;
mod hull;
mod lin_canny;
mod outline;
mod parts;
mod polygon;
mod posed;
mod segment;

pub use brute_force::brute_force_distance;
pub use feature::{Distance, Feature, FeaturePair};
pub(crate) use hull::convex_hull;
pub use lin_canny::{closest_features, WalkTolerances};
pub use outline::{Outline, OutlineError};
pub use parts::{
    bounding_box, parts_distance, Parts, PartsCache, PartsDistance, PartsSide, PartsTolerance,
};
pub use polygon::{ConvexPolygon, PolygonError, PolygonWarning, RepairShift};
pub use posed::Posed;

/// A point or vector of the plane.
pub type Vec2 = nalgebra::Vector2<f64>;

/// The z component of the cross product of two plane vectors.
///
/// ```
/// use workcell::geometry::{cross, Vec2};
/// let (x, y) = (Vec2::new(1.0, 0.0), Vec2::new(0.0, 2.0));
/// assert_eq!((cross(&x, &y), cross(&y, &x)), (2.0, -2.0)); // positive: y lies counter-clockwise of x
/// ```
#[inline]
pub fn cross(a: &Vec2, b: &Vec2) -> f64 {
    a.x * b.y - a.y * b.x
}
