//! Lanes, a remedy of two robots at once: two robots that meet while both move, head-on or
//! nearly, keep to opposite sides of the line along which they meet, as traffic keeps to
//! its lane. Each leg is planned again with the other side of that line
//! as an obstacle; where the way is wide enough for both, they pass side by side without
//! either waiting.
//!
//! A detour of one robot around the other's sweep closes the whole way where the other
//! crosses it diagonally (a corridor two robots wide, both going from one side to the
//! other): one of the two then waits. With lanes both change at once, so the remedy is one
//! child, and like every child it clears the collision it answers.

use super::context::{
    body_radius, by_motion, earliest, leg_nodes, leg_window, pieces_of, same_path, Child, Ctx,
    FixtureDiscs, Side, View,
};
use crate::geometry::{convex_hull, ConvexPolygon, Vec2};
use crate::wcp::feedback::clearing::clears;
use crate::wcp::feedback::{Remedy, RemedyKind, RemedyLeg};
use crate::wcp::legs::{leg, with_leg, Leg};
use crate::wcp::moves::node_pose;
use crate::wcp::schedule::{Activity, RobotSchedule, Segment};
use std::sync::Arc;

/// How far along the line, each way from where the robots meet, the other side is closed,
/// in the two robots' radii summed: long enough for both to be in their lanes as they pass,
/// and no longer (closed as far as each leg allowed, the ways back across the wide corridor
/// of the conflict table ended later than one robot's wait did).
const LANE_REACH: f64 = 2.0;
/// Robots meet head-on when their headings are more than 120° apart (the cosine below).
const HEAD_ON_COS: f64 = -0.5;
/// How far apart, in their radii from the line, two robots that fit side by side there
/// are in the open.
const OPEN: f64 = 3.0;
/// Half the span, in seconds, over which each robot's velocity at the contact is read.
const VELOCITY_SPAN: f64 = 0.05;

/// Two robots moving at a contact keep to opposite sides of the line along which they meet
/// (both ways round tried; the one whose later changed leg ends sooner).
pub(super) fn lanes(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let (x, y) = (side.x, side.y);
    if ctx.cell.robots[x].as_arm().is_some() || ctx.cell.robots[y].as_arm().is_some() {
        return None;
    }
    let moving = |g: &Segment| matches!(g.activity, Activity::Move { .. });
    if !moving(&side.sx) || !moving(&side.sy) {
        return None;
    }
    let (mx, my) = (side.sx.leg?, side.sy.leg?);
    let (xs, ys) = (&view.robots[x], &view.robots[y]);
    // The line they meet along: through the midpoint of the two at the contact, along
    // their relative motion (for two robots crossing a corridor diagonally, its axis).
    let (vx, vy) = (
        velocity(xs, &side.sx, side.t),
        velocity(ys, &side.sy, side.t),
    );
    // Only robots heading against each other: crossing ways have no side to keep.
    if vx.dot(&vy) >= HEAD_ON_COS * vx.norm() * vy.norm() {
        return None;
    }
    let rel = vx - vy;
    let along = rel / rel.norm();
    let across = Vec2::new(-along.y, along.x);
    let centre = 0.5 * (xs.pose_at(side.t).pos + ys.pose_at(side.t).pos);
    let width = body_radius(ctx.cell, x) + body_radius(ctx.cell, y);
    // Only where both fit side by side across the line at the contact, `k` times their
    // radii from it, `s` the side x keeps to: most ways one robot wide are told so without
    // a plan. And only where they would not fit farther apart: in the open a detour of one
    // suffices, and lanes there only add plans.
    let fixtures = FixtureDiscs::of(ctx);
    let beside = |s: f64, k: f64| {
        let margin = 2.0 * ctx.cell.delta;
        let at = |r: usize, sign: f64| {
            let pose = view.robots[r].pose_at(side.t);
            let off = sign * s * k * (body_radius(ctx.cell, r) + margin);
            crate::motion::Pose {
                pos: centre + across * off,
                ..pose
            }
        };
        fixtures.clear(ctx.cell, x, at(x, 1.0), margin)
            && fixtures.clear(ctx.cell, y, at(y, -1.0), margin)
    };
    let fits = beside(1.0, 1.0) || beside(-1.0, 1.0);
    if !fits || beside(1.0, OPEN) && beside(-1.0, OPEN) {
        return None;
    }
    let ways = [1.0, -1.0].map(|s| {
        // x keeps to the side `s` of the line, y to the other.
        let line = Line {
            centre,
            along,
            across: across * s,
            width,
        };
        let new_x = replanned(ctx, view, x, mx, &line)?;
        let new_y = replanned(ctx, view, y, my, &line.flipped())?;
        let xs = ctx.rebuild(view, x, mx, &new_x.0)?;
        let ys = ctx.rebuild(view, y, my, &new_y.0)?;
        if xs.end >= ctx.cap || ys.end >= ctx.cap {
            return None;
        }
        let (wx, wy) = (leg_window(&xs, mx), leg_window(&ys, my));
        let window = (wx.0.min(wy.0), wx.1.max(wy.1));
        let apart = clears(ctx.cell, (x, &xs), (y, &ys), window, &ctx.opts.check);
        apart.then_some((window.1, (new_x, xs, new_y, ys)))
    });
    let ((new_x, path), xs, (new_y, with_path), ys) = earliest(ways.into_iter().flatten())?;
    let legs = with_leg(&with_leg(view.legs, x, mx, new_x), y, my, new_y);
    let with = RemedyLeg {
        robot: y,
        leg: my,
        nodes: leg_nodes(view, y, my),
    };
    let kind = RemedyKind::Lanes {
        with,
        path,
        with_path,
    };
    Some(Child {
        legs,
        changed: vec![(x, Arc::new(xs)), (y, Arc::new(ys))],
        remedy: Remedy::on(x, mx, leg_nodes(view, x, mx), kind),
        last_resort: false,
    })
}

/// A line two robots meet along, and the side of it one of them keeps to.
struct Line {
    centre: Vec2,
    along: Vec2,
    /// Unit normal towards the side kept.
    across: Vec2,
    /// How far the other side is closed, from the line; along it, twice as far each way
    /// from the centre (less where the leg ends).
    width: f64,
}

impl Line {
    /// The same line, the other side kept.
    fn flipped(&self) -> Line {
        Line {
            across: -self.across,
            ..*self
        }
    }
}

/// Robot `r`'s leg `m` planned again with the other side of `line` closed, as far along it
/// as leaves the leg's start and goal free; `None` if that is no change or no way.
fn replanned(ctx: &Ctx, view: &View, r: usize, m: usize, line: &Line) -> Option<(Leg, Vec<Vec2>)> {
    let (from, to) = leg_nodes(view, r, m);
    let (a, b) = (node_pose(ctx.cell, r, from), node_pose(ctx.cell, r, to));
    // The closed side, grown as the planner grows it, ends short of every end of the leg
    // that lies on that side (the robot crosses the line there) or near the line.
    let grown = body_radius(ctx.cell, r) + 1.05 * ctx.cell.delta;
    let reach = [a.pos, b.pos]
        .iter()
        .filter(|p| (*p - line.centre).dot(&line.across) < grown)
        .map(|p| (p - line.centre).dot(&line.along).abs() - grown)
        .fold(f64::INFINITY, f64::min)
        .min(LANE_REACH * line.width);
    if reach <= line.width {
        return None;
    }
    let (c, u, n) = (line.centre, line.along * reach, line.across * line.width);
    let corners = vec![c - u, c + u, c + u - n, c - u - n];
    let pts: Vec<[f64; 2]> = convex_hull(corners).iter().map(|v| [v.x, v.y]).collect();
    let closed = ConvexPolygon::new(&pts).ok()?.0;
    let motion = ctx.moves.between(r, a, b, &[closed])?;
    let current = pieces_of(ctx, view, r, m)?;
    if same_path(&current, &motion) {
        return None;
    }
    Some((
        by_motion(leg(view.legs, r, m), &motion),
        motion.path.clone(),
    ))
}

/// Robot `s`'s velocity at `t`, from its poses a moment before and after, within segment
/// `g`.
fn velocity(s: &RobotSchedule, g: &Segment, t: f64) -> Vec2 {
    let (t0, t1) = (
        (t - VELOCITY_SPAN).max(g.start),
        (t + VELOCITY_SPAN).min(g.end),
    );
    if t1 <= t0 {
        return Vec2::zeros();
    }
    (s.pose_at(t1).pos - s.pose_at(t0).pos) / (t1 - t0)
}

#[cfg(test)]
mod tests {
    use super::super::context::TestCell;
    use super::*;
    use crate::collision::check;
    use crate::wcp::schedule::Schedule;

    /// Two robots of side 0.7 in a corridor of half-width `half` (none if 0) between walls
    /// from x = -3 to 3: X from its upper left end to its lower right, Y from the upper
    /// right to the lower left.
    fn corridor(half: f64) -> String {
        let walls = if half > 0.0 {
            format!(
                r#"{{"name": "north", "shape": [[-3, {half}], [3, {half}], [3, 7], [-3, 7]]}},
                   {{"name": "south", "shape": [[-3, -7], [3, -7], [3, -{half}], [-3, -{half}]]}}"#
            )
        } else {
            String::new()
        };
        two(
            &walls,
            [(-5.5, 1.5), (5.5, -1.5)],
            [(5.5, 1.5), (-5.5, -1.5)],
        )
    }

    /// Two corridors 2.4 wide crossing at right angles between four blocks: X from west
    /// to east, Y from south to north, at the crossing together.
    fn crossing() -> String {
        let block = |name: &str, x: [f64; 2], y: [f64; 2]| {
            format!(
                r#"{{"name": "{name}", "shape": [[{}, {}], [{}, {}], [{}, {}], [{}, {}]]}}"#,
                x[0], y[0], x[1], y[0], x[1], y[1], x[0], y[1]
            )
        };
        let (near, far) = ([1.2, 7.0], [-7.0, -1.2]);
        let blocks = [
            block("ne", near, near),
            block("nw", far, near),
            block("sw", far, far),
            block("se", near, far),
        ];
        two(
            &blocks.join(", "),
            [(-8.0, 0.0), (8.0, 0.0)],
            [(0.0, -8.0), (0.0, 8.0)],
        )
    }

    /// A cell of robots X and Y of side 0.7, each from its home to its task (1 s).
    fn two(obstacles: &str, [xh, xt]: [(f64, f64); 2], [yh, yt]: [(f64, f64); 2]) -> String {
        let robot = |name: &str, (x, y): (f64, f64)| {
            format!(
                r#"{{"name": "{name}", "shape": [[-0.35, -0.35], [0.35, -0.35], [0.35, 0.35], [-0.35, 0.35]],
                 "home": [{x}, {y}], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1}}"#
            )
        };
        let task = |name: &str, robot: &str, (x, y): (f64, f64)| {
            format!(
                r#"{{"name": "{name}", "at": [{x}, {y}], "duration": 1, "robots": ["{robot}"]}}"#
            )
        };
        format!(
            r#"{{"delta": 0.01, "robots": [{}, {}], "obstacles": [{obstacles}], "tasks": [{}, {}]}}"#,
            robot("X", xh),
            robot("Y", yh),
            task("x", "X", xt),
            task("y", "Y", yt)
        )
    }

    /// The lanes child for the first collision of the two robots' plain schedules, and
    /// the test cell.
    fn lanes_of(text: &str) -> (TestCell, Option<Child>) {
        let test = TestCell::new(text, vec![vec![0], vec![1]]);
        let view = test.view();
        let schedule = Schedule::of(view.robots.to_vec());
        let report = check(&schedule.scene(&test.cell), &Default::default());
        let c = schedule.collision(&test.cell, &report).expect("they meet");
        let side = Side {
            x: c.robots.0,
            y: c.robots.1.expect("two robots"),
            sx: c.segments.0,
            sy: c.segments.1.expect("two robots"),
            t: c.time,
        };
        let child = lanes(&test.ctx(), &view, &side);
        (test, child)
    }

    /// In a corridor wide enough for two (2.4, robots of 0.7), the robots that cross it
    /// diagonally keep to opposite sides: both change, they are proven apart, neither
    /// waits, and each ends within a second of its plain plan.
    #[test]
    fn robots_crossing_a_wide_corridor_keep_to_their_sides() {
        let (test, child) = lanes_of(&corridor(1.2));
        let child = child.expect("lanes in a corridor two robots wide");
        assert_eq!(child.changed.len(), 2);
        assert!(matches!(child.remedy.kind, RemedyKind::Lanes { .. }));
        let mut robots = test.view().robots.to_vec();
        for (r, s) in &child.changed {
            assert!(
                s.end < robots[*r].end + 1.0,
                "{} against {}",
                s.end,
                robots[*r].end
            );
            robots[*r] = s.clone();
        }
        // Apart until both are at their tasks (they meet again on their ways home).
        let there = robots
            .iter()
            .map(|s| s.segments[1].start)
            .fold(0.0, f64::max);
        let report = check(
            &Schedule::of(robots.clone()).scene(&test.cell),
            &Default::default(),
        );
        let first = report.first_contact.map_or(f64::INFINITY, |c| c.time);
        assert!(first > there, "{first} before {there}");
        // In the middle of the corridor, on the way out, each on its own side of the axis.
        let sides: Vec<f64> = (robots.iter())
            .map(|s| {
                let out = s.segments[1].start;
                let within = (s.samples.iter()).filter(|p| p.t < out && p.pos.x.abs() < 2.0);
                let ys: Vec<f64> = within.map(|p| p.pos.y).collect();
                assert!(ys.iter().all(|y| y.signum() == ys[0].signum()), "{ys:?}");
                ys[0].signum()
            })
            .collect();
        assert_eq!(sides[0], -sides[1]);
    }

    /// No lanes where they do not fit side by side (a corridor one robot wide), in the open
    /// (a detour of one does), or for ways that cross at right angles.
    #[test]
    fn no_lanes_in_a_narrow_way_in_the_open_or_across() {
        for (text, why) in [
            (corridor(0.6), "one robot wide"),
            (corridor(0.0), "in the open"),
            (crossing(), "crossing at right angles"),
        ] {
            assert!(lanes_of(&text).1.is_none(), "{why}");
        }
    }
}
