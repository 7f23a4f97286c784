//! Arms in the broad phase, two levels per time window: the arm's reach disc about its base
//! (the grid's one entry for the arm), then each link's swept box, computed and tested only
//! against the bodies that the reach disc meets. An arm that meets nothing in a window costs
//! its reach alone there.
//!
//! Both levels come from the joint samples: over a segment of the arm's trajectory, every
//! point of link k stays within λ_k of where it was at the segment's start (Schwarzer, Saha
//! & Latombe 2005, eq. 5). So link k stays within r_{k,k} + λ_k of its joint's position at
//! the segment's start (the reach), and within its hull there grown by λ_k (the swept box);
//! and no point of link k is ever farther from the base than r_{0,k}.

use super::aabb::Aabb;
use crate::collision::Body;
use crate::geometry::Posed;
use crate::motion::{ArmMotion, LinkMotion, Motion};
use std::collections::HashMap;
use std::sync::Arc;

/// One arm in the broad phase: its reach in every window, and what its links' swept boxes
/// are computed from when a window asks for them.
pub(super) struct ArmBoxes<'s> {
    arm: Arc<ArmMotion>,
    /// The bodies of its links, in link order, with their motions.
    pub links: Vec<(usize, &'s LinkMotion)>,
    /// Per window, the box of its reach disc.
    pub reach: Vec<Aabb>,
    /// Per window, the pieces of the trajectory that meet it.
    pieces: Vec<Pieces>,
    grow: f64,
    scale: f64,
}

/// The pieces of an arm's trajectory that meet a window: the segments `segments.start` to
/// `segments.end` (segment i from sample i to i + 1), and the rest before the first sample
/// or after the last, where the arm holds its first or last pose.
#[derive(Clone, Debug)]
struct Pieces {
    before: bool,
    segments: std::ops::Range<usize>,
    after: bool,
}

impl Pieces {
    /// Each piece as (its start sample, its end sample): the same sample twice for a rest.
    fn iter(&self, last: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
        let before = self.before.then_some((0, 0));
        let after = self.after.then_some((last, last));
        before
            .into_iter()
            .chain(self.segments.clone().map(|i| (i, i + 1)))
            .chain(after)
    }
}

/// The arms of `bodies`, each with the bodies of its links (in the order their first link
/// appears).
pub(super) fn arms_of(bodies: &[Body]) -> Vec<(Arc<ArmMotion>, Vec<usize>)> {
    let mut arms: Vec<(Arc<ArmMotion>, Vec<usize>)> = Vec::new();
    let mut by_arm = HashMap::new();
    for (i, b) in bodies.iter().enumerate() {
        if let Motion::Link(l) = &b.motion {
            let k = *by_arm.entry(Arc::as_ptr(&l.arm)).or_insert_with(|| {
                arms.push((l.arm.clone(), Vec::new()));
                arms.len() - 1
            });
            arms[k].1.push(i);
        }
    }
    arms
}

impl<'s> ArmBoxes<'s> {
    /// The arm whose links are the bodies `links`, its reach in the windows between
    /// consecutive `ends`; every box grown by `grow`.
    pub fn new(
        arm: Arc<ArmMotion>,
        links: &[usize],
        bodies: &'s [Body],
        ends: &[f64],
        grow: f64,
    ) -> Self {
        let links: Vec<(usize, &LinkMotion)> = (links.iter())
            .map(|&i| match &bodies[i].motion {
                Motion::Link(l) => (i, l),
                _ => unreachable!("the bodies of an arm's links"),
            })
            .collect();
        let base = arm.base().pos;
        let scale = base.amax() + arm.lever(0, arm.links() - 1);
        let pieces = pieces_of(&arm, ends);
        let last = arm.samples().len() - 1;
        let samples = arm.samples();
        let reach = (pieces.iter())
            .map(|pieces| {
                let mut far = 0.0f64;
                for &(i, l) in &links {
                    let own = bodies[i].shape.radius();
                    let mut link_far = 0.0f64;
                    for (a, b) in pieces.iter(last) {
                        let lambda = arm.lambda(l.link, &samples[a].q, &samples[b].q);
                        let joint = l.frames()[a].pos;
                        link_far = link_far.max((joint - base).norm() + own + lambda);
                    }
                    far = far.max(link_far.min(arm.lever(0, l.link)));
                }
                let mut disc = Aabb::EMPTY;
                disc.add_disc(&base, far);
                disc.grown(grow, scale)
            })
            .collect();
        ArmBoxes {
            arm,
            links,
            reach,
            pieces,
            grow,
            scale,
        }
    }

    /// Each link's swept box in window `w`, in link order.
    pub fn link_boxes(&self, w: usize, bodies: &[Body]) -> Vec<Aabb> {
        let (arm, samples) = (&self.arm, self.arm.samples());
        let base = arm.base().pos;
        let pieces = self.pieces[w].iter(samples.len() - 1);
        let pieces: Vec<(usize, usize)> = pieces.collect();
        (self.links.iter())
            .map(|&(i, l)| {
                let mut swept = Aabb::EMPTY;
                for &(a, b) in &pieces {
                    let lambda = arm.lambda(l.link, &samples[a].q, &samples[b].q);
                    let f = &l.frames()[a];
                    let posed = Posed::new(&bodies[i].shape, f.pos.x, f.pos.y, f.theta);
                    (0..posed.len()).for_each(|k| swept.add_disc(&posed.vertex(k), lambda));
                }
                // The lever bound is the finer one where the arm turns fast.
                let mut around = Aabb::EMPTY;
                around.add_disc(&base, arm.lever(0, l.link));
                swept.intersection(&around).grown(self.grow, self.scale)
            })
            .collect()
    }
}

/// For each window between consecutive `ends`, the pieces of the arm's trajectory that meet
/// it. Windows go forward in time: the samples are scanned once in all (a segment that spans
/// several windows counts in each).
fn pieces_of(arm: &ArmMotion, ends: &[f64]) -> Vec<Pieces> {
    let samples = arm.samples();
    let last = samples.len() - 1;
    let mut first = 0;
    (ends.windows(2))
        .map(|span| {
            let (a, b) = (span[0], span[1]);
            while first < last && samples[first + 1].t < a {
                first += 1;
            }
            let mut end = first;
            while end < last && samples[end].t <= b {
                end += 1;
            }
            Pieces {
                before: a < samples[0].t || last == 0,
                segments: first..end,
                after: b > samples[last].t,
            }
        })
        .collect()
}
