//! Waiting along the way: a pause at a point of the path short of the contact, or the
//! whole leg run slower (time scaling keeps every limit).

use super::context::{
    body_radius, child, earliest, horizons, least_clearing, leg_nodes, leg_window, paused,
    pieces_of, Child, Ctx, Side, View,
};
use crate::geometry::Vec2;
use crate::planning::Primitive;
use crate::wcp::feedback::{Remedy, RemedyKind};
use crate::wcp::legs::{leg, Leg, Piece};
use crate::wcp::moves::certify;
use crate::wcp::schedule::{Activity, Segment};
use std::cell::Cell;

/// Back-off distances of a pause, in units of the two robots' radii summed: how far short
/// of the contact point along its path the robot stops.
const PAUSE_BACKOFF: [f64; 3] = [1.0, 2.0, 4.0];
/// Slowest time scaling tried.
const MAX_SLOW: f64 = 8.0;

/// The piece of leg `m` under way in segment `sx`, counting the leg's wait as no piece.
pub(super) fn piece_index(view: &View, x: usize, m: usize, sx: &Segment) -> Option<usize> {
    let s = &view.robots[x];
    let k = s
        .segments
        .iter()
        .filter(|g| g.leg == Some(m))
        .position(|g| g == sx)?;
    let waited = leg(view.legs, x, m).wait > 0.0;
    k.checked_sub(waited as usize)
}

/// Arc length along `path` of the point of it nearest to `p`.
fn arc_length_at(path: &[Vec2], p: Vec2) -> f64 {
    let mut best = (f64::INFINITY, 0.0);
    let mut walked = 0.0;
    for w in path.windows(2) {
        let d = w[1] - w[0];
        let len = d.norm();
        let u = if len > 0.0 {
            ((p - w[0]).dot(&d) / (len * len)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let gap = (w[0] + d * u - p).norm();
        if gap < best.0 {
            best = (gap, walked + u * len);
        }
        walked += len;
    }
    best.1
}

/// `primitives` cut at arc length `s` of their chained paths.
pub(super) fn split_chain(
    primitives: &[Primitive],
    s: f64,
) -> Option<(Vec<Primitive>, Vec<Primitive>)> {
    let mut walked = 0.0;
    for (k, p) in primitives.iter().enumerate() {
        let len = p.length();
        if s < walked + len {
            let (a, b) = p.split_at(s - walked)?;
            let mut before = primitives[..k].to_vec();
            before.push(a);
            let mut after = vec![b];
            after.extend_from_slice(&primitives[k + 1..]);
            return Some((before, after));
        }
        walked += len;
    }
    None
}

/// Stop short of the contact point, wait, go on.
pub(super) fn pause(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let t = side.t;
    let m = side.sx.leg?;
    if !matches!(side.sx.activity, Activity::Move { .. }) {
        return None;
    }
    let pieces = pieces_of(ctx, view, side.x, m)?;
    let k = piece_index(view, side.x, m, &side.sx)?;
    let Piece::Go { motion, scale } = pieces.get(k)?.clone() else {
        return None;
    };
    let here = view.robots[side.x].pose_at(t).pos;
    let at = arc_length_at(&motion.path, here);
    let reach = ctx.cell.rigid(side.x).shape.radius() + body_radius(ctx.cell, side.y);
    let old = leg(view.legs, side.x, m).clone();
    let t0 = leg_window(&view.robots[side.x], m).0;
    let horizons = horizons(view, side.y, &side.sy, t0);
    // A later stop wins only by ending sooner than the best so far: none is refined past it.
    let bound = Cell::new(ctx.cap);
    let tried = PAUSE_BACKOFF.iter().filter_map(|back| {
        let ctx = ctx.capped(bound.get());
        let (before, after) = split_chain(&motion.primitives, at - back * reach)?;
        let (first, second) = (
            ctx.moves.timed(side.x, &before),
            ctx.moves.timed(side.x, &after),
        );
        let make = |d: f64| Some(paused(&old, &pieces, k, (&first, &second, scale), d));
        // Stopping costs time even without a hold: no certificate for a stop that loses.
        if ctx.cap < f64::INFINITY && ctx.rebuild(view, side.x, m, &make(0.0)?)?.end >= ctx.cap {
            return None;
        }
        let stop = first.path.last().copied()?;
        let (d, new, s) = least_clearing(&ctx, view, side, (m, t0), &horizons, make)?;
        // Certified once it clears: a stop that clears nothing needs no certificate.
        let obstacles = ctx.moves.obstacles();
        for half in [&first, &second] {
            certify(ctx.cell, side.x, &half.samples, obstacles).ok()?;
        }
        bound.set(s.end);
        Some((s.end, (d, stop, new, s)))
    });
    // On ties the stop nearest the contact (tried first).
    let (d, stop, new, s) = earliest(tried)?;
    let kind = RemedyKind::Pause {
        at: stop,
        duration: d,
    };
    let remedy = Remedy::on(side.x, m, leg_nodes(view, side.x, m), kind);
    Some(child(view, side.x, m, new, s, remedy))
}

/// Run the leg's motions slower.
pub(super) fn slow(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let m = side.sx.leg?;
    if matches!(side.sx.activity, Activity::Wait(_) | Activity::Done) {
        return None;
    }
    let pieces = pieces_of(ctx, view, side.x, m)?;
    let moving: f64 = pieces
        .iter()
        .filter(|p| matches!(p, Piece::Go { .. }))
        .map(Piece::duration)
        .sum();
    if moving <= 0.0 {
        return None;
    }
    let old = leg(view.legs, side.x, m).clone();
    let t0 = leg_window(&view.robots[side.x], m).0;
    // Slowing by 1 + D / moving delays the leg's end by D.
    let extras: Vec<f64> = horizons(view, side.y, &side.sy, t0)
        .into_iter()
        .map(|d| (d / moving).min(MAX_SLOW - 1.0))
        .collect();
    let (extra, new, s) = least_clearing(ctx, view, side, (m, t0), &extras, |e| {
        let scaled: Vec<Piece> = pieces
            .iter()
            .map(|p| match p {
                Piece::Go { motion, scale } => Piece::Go {
                    motion: motion.clone(),
                    scale: scale * (1.0 + e),
                },
                hold => hold.clone(),
            })
            .collect();
        Some(Leg {
            pieces: Some(scaled.into()),
            ..old.clone()
        })
    })?;
    let kind = RemedyKind::Slow {
        factor: 1.0 + extra,
    };
    let remedy = Remedy::on(side.x, m, leg_nodes(view, side.x, m), kind);
    Some(child(view, side.x, m, new, s, remedy))
}
