//! η(t): a lower bound of the distance between two bodies at time t.

use super::span::{LinkEnds, Probe, Span};
use super::{Body, Stats};
use crate::geometry::{
    bounding_box, closest_features, parts_distance, FeaturePair, PartsCache, PartsDistance,
    PartsSide, PartsTolerance, Posed, Vec2, WalkTolerances,
};
use crate::motion::{lambda, BoundKind, Pose};

/// Evaluates η for one pair, keeping the last closest features for the next warm start.
pub struct Eta<'s> {
    pub a: &'s Body,
    pub b: &'s Body,
    delta: f64,
    walk: WalkTolerances,
    warm: Option<FeaturePair>,
    /// The parts' warm starts, for a pair where either body has parts.
    parts: Option<Box<PartsCache>>,
    /// The boxes of A and B as one part each (used for a convex body of such a pair).
    boxes: [[f64; 4]; 2],
}

/// How far short of the least part distance η may stop, above δ, relative to δ: far below
/// what any certificate notices, and enough to skip pairs of parts that are as near as the
/// nearest up to rounding (parallel teeth of two combs).
const PARTS_SLACK: f64 = 1e-3;

impl<'s> Eta<'s> {
    pub fn new(a: &'s Body, b: &'s Body, delta: f64, walk: WalkTolerances) -> Self {
        let has_parts = a.parts.is_some() || b.parts.is_some();
        Eta {
            a,
            b,
            delta,
            walk,
            warm: None,
            parts: has_parts.then(Box::default),
            boxes: match has_parts {
                true => [bounding_box(&a.shape), bounding_box(&b.shape)],
                false => [[0.0; 4]; 2],
            },
        }
    }

    /// Sum of the two bounding-disc radii (eq. 13).
    pub fn radii(&self) -> f64 {
        self.a.shape.radius() + self.b.shape.radius()
    }

    /// λ1 + λ2 from probe `l` to probe `r` of `span`, between which both poses are linear
    /// in time (a link's joints are: its λ is the joint-rate bound, for either kind).
    #[inline]
    pub(super) fn lambda(&self, bound: BoundKind, span: &Span, l: &Probe, r: &Probe) -> f64 {
        match &span.links {
            None => {
                self.rigid_lambda(bound, self.a, l, r, true)
                    + self.rigid_lambda(bound, self.b, l, r, false)
            }
            Some(links) => self.lambda_with_links(bound, links, l, r),
        }
    }

    #[inline]
    fn rigid_lambda(&self, bound: BoundKind, body: &Body, l: &Probe, r: &Probe, a: bool) -> f64 {
        let (p, q) = if a {
            (&l.pose_a, &r.pose_a)
        } else {
            (&l.pose_b, &r.pose_b)
        };
        lambda(bound, &body.motion, body.shape.radius(), (l.t, p), (r.t, q))
    }

    /// [`Eta::lambda`] for a pair with a link of an arm, out of the rigid pairs' way.
    #[inline(never)]
    #[cold]
    fn lambda_with_links(
        &self,
        bound: BoundKind,
        links: &[Option<LinkEnds>; 2],
        l: &Probe,
        r: &Probe,
    ) -> f64 {
        let one = |body: &Body, link: &Option<LinkEnds>, a: bool| match link {
            Some(link) => link.lambda * (r.u - l.u),
            None => self.rigid_lambda(bound, body, l, r, a),
        };
        one(self.a, &links[0], true) + one(self.b, &links[1], false)
    }

    /// η(t): the gap between the bounding discs (eq. 13) while it is at least δ, else the
    /// exact distance from the closest-feature walk, warm-started from the previous call.
    /// For bodies made of parts the walk runs on their hulls, and only where the hulls come
    /// closer than δ does η become the least distance between the parts.
    /// `poses` are A's and B's poses at time `t`.
    pub fn at(&mut self, t: f64, (pose_a, pose_b): (Pose, Pose), stats: &mut Stats) -> Probe {
        // Work in a frame centred on A: far from the origin, positions lose digits but
        // their difference does not.
        let rel = pose_b.pos - pose_a.pos;
        let disc_gap = rel.norm() - self.radii();
        let (eta, exact, normal) = if disc_gap >= self.delta {
            (disc_gap, false, Vec2::zeros())
        } else {
            stats.narrow_phase_calls += 1;
            let pa = Posed::new(&self.a.shape, 0.0, 0.0, pose_a.theta);
            let pb = Posed::new(&self.b.shape, rel.x, rel.y, pose_b.theta);
            let d = closest_features(&pa, &pb, self.warm, &self.walk);
            stats.feature_steps += u64::from(d.steps);
            stats.walk_fallbacks += u64::from(d.fell_back);
            self.warm = Some(d.features);
            if d.distance < self.delta && self.parts.is_some() {
                // The hulls are within δ: the parts decide. Their least distance is no convex
                // function of the motion, so the probe gives no tangent (`exact` false: the
                // convexity certificate falls back to the discs, which bound it from below).
                let p = self.parts_at(pose_a, rel, pose_b.theta);
                stats.narrow_phase_calls += u64::from(p.walks);
                stats.feature_steps += u64::from(p.steps);
                (p.distance, false, Vec2::zeros())
            } else {
                // The hull distance of a body of parts is a convex lower bound of its own.
                let normal = if d.distance > 0.0 {
                    (d.point_b - d.point_a) / d.distance
                } else {
                    Vec2::zeros()
                };
                (d.distance, true, normal)
            }
        };
        Probe {
            t,
            u: 0.0,
            pose_a,
            pose_b,
            eta,
            exact,
            normal,
        }
    }

    /// The least distance between the two bodies' parts, A at the origin of the frame and B
    /// at `rel` (a convex body counts as one part).
    fn parts_at(&mut self, pose_a: Pose, rel: Vec2, theta_b: f64) -> PartsDistance {
        fn side<'b>(body: &'b Body, aabb: &'b [f64; 4], pos: Vec2, theta: f64) -> PartsSide<'b> {
            match &body.parts {
                Some(parts) => PartsSide::of(parts, pos, theta),
                None => PartsSide::convex(&body.shape, aabb, pos, theta),
            }
        }
        let exactness = PartsTolerance {
            exact_below: self.delta,
            slack: PARTS_SLACK * self.delta,
        };
        let cache = self.parts.get_or_insert_with(Box::default);
        parts_distance(
            side(self.a, &self.boxes[0], Vec2::zeros(), pose_a.theta),
            side(self.b, &self.boxes[1], rel, theta_b),
            &self.walk,
            exactness,
            cache,
        )
    }

    /// Which part of each body is nearest the other at these poses: for the report of a
    /// contact (`None` for a pair of convex bodies).
    pub fn closest_parts(&mut self, (pose_a, pose_b): (Pose, Pose)) -> Option<(usize, usize)> {
        self.parts.as_ref()?;
        let p = self.parts_at(pose_a, pose_b.pos - pose_a.pos, pose_b.theta);
        Some(p.parts)
    }
}
