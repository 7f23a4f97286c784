//! Detours: the leg re-planned with the other robot as an obstacle, its pose if it stands
//! or the region it sweeps over the conflict window if it moves.

use super::context::{
    apart, body_radius, child, detoured, earliest, leg_nodes, leg_window, occupancy, pieces_of,
    same_path, Child, Ctx, Side, View,
};
use crate::wcp::feedback::{Remedy, RemedyKind};
use crate::wcp::moves::node_pose;
use crate::wcp::schedule::Activity;

/// Half-width of the short detour window about the contact, in the time the detouring
/// robot takes at full speed to cover the two robots' radii summed.
const DETOUR_REACH: f64 = 2.0;
/// Re-plan the leg around the other robot.
pub(super) fn detour(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let m = side.sx.leg?;
    if !matches!(side.sx.activity, Activity::Move { .. }) {
        return None;
    }
    let xs = &view.robots[side.x];
    let (t0, t1) = leg_window(xs, m);
    // Where the other robot is to be gone round: all it sweeps while both move (or where it
    // stands); and, when it moves, only where it is about the contact, so that two robots
    // can pass side by side where the first would close a whole corridor.
    let mut windows = vec![match side.sy.activity {
        Activity::Move { .. } => (side.sy.start.max(t0), side.sy.end.min(t1)),
        _ => (t0, t1),
    }];
    if matches!(side.sy.activity, Activity::Move { .. }) {
        let robot = ctx.cell.rigid(side.x);
        let reach = robot.shape.radius() + body_radius(ctx.cell, side.y);
        let tau = DETOUR_REACH * reach / robot.max_speed;
        let (w0, w1) = windows[0];
        let near = ((side.t - tau).max(w0), (side.t + tau).min(w1));
        if near != windows[0] {
            windows.push(near);
        }
    }
    let (from, to) = leg_nodes(view, side.x, m);
    let (a, b) = (
        node_pose(ctx.cell, side.x, from),
        node_pose(ctx.cell, side.x, to),
    );
    let current = pieces_of(ctx, view, side.x, m)?;
    // Whether a way round was found that ends too late for the search (not checked).
    let late = std::cell::Cell::new(false);
    let around = |(w0, w1): (f64, f64)| {
        let region = occupancy(ctx, view, side.y, w0, w1.max(w0));
        let motion = ctx.moves.between(side.x, a, b, &region)?;
        if same_path(&current, &motion) {
            return None;
        }
        let Ok((new, s)) = detoured(ctx, view, side, (m, t0), &motion)? else {
            late.set(true);
            return None;
        };
        Some((s.end, (motion, new, s)))
    };
    // When neither window works because the other robot's sweep covers the detouring
    // robot's own start, the region swept up to the contact only: on a loop, the way round
    // the other side (robots that meet head-on in a ring corridor). Failing that, because
    // the other's sweep also covers the detouring robot's goal (it leaves from beside it),
    // its pose at the contact alone, which still closes the way it was hit. A last resort
    // (`Child::last_resort`), which the search checks only when it gets to it: tried as a
    // window like the others, it cost a doorway cell its schedule within the budget.
    let (w0, w1) = windows[0];
    let before = (w0, side.t.clamp(w0, w1));
    let contact = (before.1, before.1);
    let hemmed = || {
        let region = occupancy(ctx, view, side.y, w0, w1.max(w0));
        !apart(&[(ctx.cell.rigid(side.x).pieces(), a)], &region, 0.0)
    };
    // On ties the first window tried.
    let (found, last_resort) = match earliest(windows.into_iter().filter_map(around)) {
        Some(found) => (found, false),
        // The other side is for robots with no way round at all.
        None if late.get() => return None,
        None => {
            let other_side = hemmed().then(|| around(before).or_else(|| around(contact)));
            (other_side.flatten()?.1, true)
        }
    };
    let (motion, new, s) = found;
    let kind = RemedyKind::Detour {
        around: side.y,
        path: motion.path.clone(),
    };
    let remedy = Remedy::on(side.x, m, (from, to), kind);
    let made = child(view, side.x, m, new, s, remedy);
    Some(Child {
        last_resort,
        ..made
    })
}

#[cfg(test)]
mod tests {
    use super::super::context::TestCell;
    use super::*;
    use crate::geometry::{ConvexPolygon, Vec2};

    /// The region a robot of parts occupies is its parts', not its hull's: between the two
    /// feet of a gantry another robot may pass.
    #[test]
    fn a_robot_of_parts_occupies_its_parts_not_its_hull() {
        let text = r#"{"delta": 0.01, "robots": [
            {"name": "X", "shape": [[-0.2, -0.2], [0.2, -0.2], [0.2, 0.2], [-0.2, 0.2]],
             "home": [0, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1},
            {"name": "gantry", "parts": [[[-0.2, 0.6], [0.2, 0.6], [0.2, 1.0], [-0.2, 1.0]],
                                         [[-0.2, -1.0], [0.2, -1.0], [0.2, -0.6], [-0.2, -0.6]]],
             "home": [3, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1}],
            "tasks": [{"name": "t", "at": [6, 0], "duration": 1, "robots": ["X"]}]}"#;
        let test = TestCell::new(text, vec![vec![0], vec![]]);
        let (cell, moves) = (&test.cell, &test.moves);
        let region = occupancy(&test.ctx(), &test.view(), 1, 0.0, 1.0);
        assert_eq!(region.len(), 2);
        let between = Vec2::new(3.0, 0.0);
        let inside = |p: &ConvexPolygon| {
            (0..p.len()).all(|i| p.normals()[i].dot(&(between - p.vertices()[i])) < 0.0)
        };
        assert!(!region.iter().any(inside));
        // Through the gantry's feet, the detour is the straight move.
        let (a, b) = (node_pose(cell, 0, 0), node_pose(cell, 0, 1));
        let motion = moves.between(0, a, b, &region).expect("a way through");
        assert_eq!(motion.path, [a.pos, b.pos]);
    }
}
