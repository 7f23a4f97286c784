//! Making way, a remedy of two robots at once: a robot standing in another's way (at its
//! task, or waiting at a node) leaves by a way round where the other comes from, ahead of
//! it, and the other waits the least that lets it go first.
//!
//! Neither robot alone can do this when the one standing would otherwise leave towards the
//! other, as on a ring corridor one robot wide: the robot behind cannot pass, and the one
//! ahead cannot come back. Its next leg is planned around a short stretch of the other's
//! sweep just short of the contact (where the other comes from), so on a loop it goes on
//! round the other side.

use super::context::{
    body_radius, by_motion, horizons, least_clearing, leg_nodes, leg_window, occupancy, pieces_of,
    same_path, Child, Ctx, Side, View,
};
use crate::wcp::feedback::{Remedy, RemedyKind};
use crate::wcp::legs::{leg, with_leg, Leg};
use crate::wcp::moves::node_pose;
use crate::wcp::schedule::Activity;
use std::sync::Arc;

/// How far short of the contact y's sweep ends, in the time y takes at full speed to
/// cover the two robots' radii summed: tried in turn until x can leave around it.
const MAKE_WAY_BACKOFF: [f64; 4] = [0.5, 1.0, 2.0, 4.0];

/// How much of y's way towards x is gone round, in the same unit.
const MAKE_WAY_REACH: f64 = 1.0;

/// Robot `side.x`, standing in the way of `side.y`, leaves ahead of it; `side.y` waits.
pub(super) fn make_way(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let (x, y) = (side.x, side.y);
    if ctx.cell.robots[x].as_arm().is_some() || ctx.cell.robots[y].as_arm().is_some() {
        return None;
    }
    // The leg by which x leaves: the next one after its task, or the one it waits before.
    let m = match side.sx.activity {
        Activity::Work(_) => side.sx.leg? + 1,
        Activity::Wait(_) => side.sx.leg?,
        _ => return None,
    };
    let my = side.sy.leg?;
    if !matches!(side.sy.activity, Activity::Move { .. })
        || !view.robots[x].segments.iter().any(|g| g.leg == Some(m))
    {
        return None;
    }
    // Round where y comes from: its sweep over a stretch ending a little before the contact
    // (at the contact it touches x, whose start would be blocked), the nearest such that
    // lets x leave.
    let (from, to) = leg_nodes(view, x, m);
    let (a, b) = (node_pose(ctx.cell, x, from), node_pose(ctx.cell, x, to));
    let rigid = ctx.cell.rigid(y);
    let tau = (rigid.shape.radius() + body_radius(ctx.cell, x)) / rigid.max_speed;
    let start = side.sy.start;
    let motion = MAKE_WAY_BACKOFF.iter().find_map(|k| {
        let until = side.t - k * tau;
        if until <= start {
            return None;
        }
        // Only where y comes from near x: its sweep long before is no obstacle now.
        let since = (until - MAKE_WAY_REACH * tau).max(start);
        let region = occupancy(ctx, view, y, since, until);
        ctx.moves.between(x, a, b, &region)
    })?;
    let current = pieces_of(ctx, view, x, m)?;
    if same_path(&current, &motion) {
        return None;
    }
    let ahead = by_motion(leg(view.legs, x, m), &motion);
    let xs = Arc::new(ctx.rebuild(view, x, m, &ahead)?);
    // Then y waits the least that clears x as it now goes.
    let legs = with_leg(view.legs, x, m, ahead);
    let mut robots = view.robots.to_vec();
    robots[x] = xs.clone();
    let after = View {
        routes: view.routes,
        legs: &legs,
        robots: &robots,
    };
    let waits = Side {
        x: y,
        y: x,
        sx: side.sy,
        sy: side.sx,
        t: side.t,
    };
    let old = leg(&legs, y, my).clone();
    let t0 = leg_window(&robots[y], my).0;
    let horizons = horizons(&after, x, &side.sx, t0);
    let (d, new, ys) = least_clearing(ctx, &after, &waits, (my, t0), &horizons, |d| {
        Some(Leg {
            wait: old.wait + d,
            ..old.clone()
        })
    })?;
    let kind = RemedyKind::MakeWay {
        ahead_of: y,
        path: motion.path.clone(),
        wait: d,
    };
    Some(Child {
        legs: with_leg(&legs, y, my, new),
        changed: vec![(x, xs), (y, Arc::new(ys))],
        remedy: Remedy::on(x, m, (from, to), kind),
        // Offered on every robot standing in another's way, it would widen every search;
        // as a last resort it costs nothing until the search gets to it.
        last_resort: true,
    })
}
