//! The loop a convoy goes round: a closed path with arc length along it, where each robot
//! stops on it (the convoy's plan), and a robot's motion along a stretch of it.

use crate::geometry::Vec2;
use crate::planning::{PlannedMove, Primitive};
use crate::wcp::feedback::remedies::context::{Ctx, View};
use crate::wcp::legs::{Leg, Legs};
use crate::wcp::moves::node_pose;
use crate::wcp::schedule::RobotSchedule;
use std::sync::Arc;

/// How far from the loop a robot's home or task may lie for the robot to ride it, in
/// units of the robot's radius (the planner's paths hug the inside of a corridor's bends).
pub(super) const ON_LOOP: f64 = 0.5;
/// Offsets along the loop closer than this fraction of its length are one stop.
pub(super) const SAME_STOP: f64 = 1e-9;

/// A closed polyline with arc length along it.
#[derive(Debug)]
pub(super) struct Loop {
    /// Its vertices, the closing edge from the last back to the first implied.
    pub(super) points: Vec<Vec2>,
    /// Arc length at each vertex; one more entry, the whole length, for the closing edge.
    arc: Vec<f64>,
}

impl Loop {
    /// The loop through `points` (consecutive repeats dropped); `None` when it encloses
    /// nothing (fewer than three distinct points).
    pub(super) fn new(mut points: Vec<Vec2>) -> Option<Loop> {
        points.dedup_by(|a, b| (*a - *b).norm() < 1e-12);
        while points.len() > 1 && (points[0] - points[points.len() - 1]).norm() < 1e-12 {
            points.pop();
        }
        if points.len() < 3 {
            return None;
        }
        let mut arc = vec![0.0];
        for k in 0..points.len() {
            let next = points[(k + 1) % points.len()];
            arc.push(arc[k] + (next - points[k]).norm());
        }
        Some(Loop { points, arc })
    }

    pub(super) fn length(&self) -> f64 {
        self.arc[self.points.len()]
    }

    /// The arc length of the point of the loop nearest `p`, and how far `p` is from it.
    pub(super) fn project(&self, p: Vec2) -> (f64, f64) {
        let n = self.points.len();
        let mut best = (0.0, f64::INFINITY);
        for k in 0..n {
            let (a, b) = (self.points[k], self.points[(k + 1) % n]);
            let d = b - a;
            let len2 = d.norm_squared();
            let u = if len2 > 0.0 {
                ((p - a).dot(&d) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let gap = (a + d * u - p).norm();
            if gap < best.1 {
                best = (self.arc[k] + u * (self.arc[k + 1] - self.arc[k]), gap);
            }
        }
        best
    }

    /// The point at arc length `s` (any real: taken round the loop).
    pub(super) fn at(&self, s: f64) -> Vec2 {
        let len = self.length();
        let s = s.rem_euclid(len);
        let n = self.points.len();
        let k = self.arc[1..].partition_point(|&a| a <= s).min(n - 1);
        let (a, b) = (self.points[k], self.points[(k + 1) % n]);
        let span = self.arc[k + 1] - self.arc[k];
        let u = if span > 0.0 {
            (s - self.arc[k]) / span
        } else {
            0.0
        };
        a + (b - a) * u
    }

    /// The way along the loop from arc length `s0` to `s1` (unwrapped: `s1 < s0` goes the
    /// other way round): its two ends and every vertex strictly between, in order.
    pub(super) fn way(&self, s0: f64, s1: f64) -> Vec<Vec2> {
        let (len, n) = (self.length(), self.points.len());
        let (lo, hi) = (s0.min(s1), s0.max(s1));
        let mut inside = Vec::new();
        let first_lap = (lo / len).floor() as i64;
        let last_lap = (hi / len).floor() as i64;
        for lap in first_lap..=last_lap {
            for k in 0..n {
                let s = lap as f64 * len + self.arc[k];
                if s > lo && s < hi {
                    inside.push(self.points[k]);
                }
            }
        }
        if s1 < s0 {
            inside.reverse();
        }
        let mut way = vec![self.at(s0)];
        way.extend(inside);
        way.push(self.at(s1));
        way
    }

    /// True when the vertices run counter-clockwise (positive area).
    pub(super) fn counter_clockwise(&self) -> bool {
        let n = self.points.len();
        let twice_area: f64 = (0..n)
            .map(|k| {
                let (a, b) = (self.points[k], self.points[(k + 1) % n]);
                a.x * b.y - b.x * a.y
            })
            .sum();
        twice_area > 0.0
    }
}

/// The convoy's stops: for each robot, how far (along the loop, the convoy's way) each node
/// of its route lies from its home, the next after the previous; `None` for a robot with
/// nowhere to go. Returns the stops of every robot and the end (the whole laps after the
/// last task), and each shared stop with how long the convoy holds there (the longest task
/// of the robots working at it).
pub(super) fn stops(
    offsets: &[Vec<(f64, f64)>],
    len: f64,
) -> (Vec<Vec<f64>>, f64, Vec<(f64, f64)>) {
    let mut at: Vec<Vec<f64>> = Vec::new();
    let mut last: f64 = 0.0;
    for nodes in offsets {
        let mut phi = 0.0;
        let mut mine = Vec::new();
        for &(d, _) in nodes {
            // The first time the convoy, turning on from phi, brings this robot to d.
            let ahead = (d - phi).rem_euclid(len);
            phi += if ahead > len * (1.0 - SAME_STOP) {
                0.0
            } else {
                ahead
            };
            mine.push(phi);
        }
        last = last.max(phi);
        at.push(mine);
    }
    let laps = (last / len * (1.0 - SAME_STOP)).ceil().max(1.0);
    let end = laps * len;
    let mut holds: Vec<(f64, f64)> = vec![(0.0, 0.0), (end, 0.0)];
    for (mine, nodes) in at.iter().zip(offsets) {
        for (&phi, &(_, work)) in mine.iter().zip(nodes) {
            match (holds.iter_mut()).find(|(s, _)| (s - phi).abs() <= SAME_STOP * len) {
                Some(stop) => stop.1 = stop.1.max(work),
                None => holds.push((phi, work)),
            }
        }
    }
    holds.sort_by(|a, b| a.0.total_cmp(&b.0));
    (at, end, holds)
}

/// The robots of the loop, each with its home's arc length and its route's nodes.
pub(super) struct Rider {
    pub(super) r: usize,
    pub(super) home: f64,
    pub(super) nodes: Vec<usize>,
}

/// What a convoy makes: the latest end of its robots, the legs, the changed robots'
/// schedules, the way round (±1) and the laps.
pub(super) type Made = (f64, Legs, Vec<(usize, Arc<RobotSchedule>)>, f64, usize);

/// The convoy made: each rider's new legs (by robot) timed into its schedule, with the
/// latest end, the way round and the laps (`turns`, a whole number up to rounding).
pub(super) fn made(
    ctx: &Ctx,
    view: &View,
    ridden: Vec<(usize, Vec<Leg>)>,
    way: f64,
    turns: f64,
) -> Option<Made> {
    let mut legs: Legs = view.legs.to_vec();
    let mut changed = Vec::new();
    let mut latest: f64 = 0.0;
    for (r, robot_legs) in ridden {
        let s = RobotSchedule::build(ctx.cell, r, &view.routes[r], &robot_legs, ctx.moves).ok()?;
        latest = latest.max(s.end);
        legs[r] = Arc::new(robot_legs);
        changed.push((r, Arc::new(s)));
    }
    Some((latest, legs, changed, way, turns.round() as usize))
}

/// Where a convoy the way `way` (+1: as the loop's vertices run) stops each rider: every
/// rider's tasks as (offset from its home along the loop, duration), the convoy's turn at
/// each of its nodes, its end (whole laps) and each shared stop with its hold
/// ([`stops`]); `None` when a task lies where its robot already is.
pub(super) struct Plan {
    pub(super) offsets: Vec<Vec<(f64, f64)>>,
    pub(super) at: Vec<Vec<f64>>,
    pub(super) end: f64,
    pub(super) holds: Vec<(f64, f64)>,
}

pub(super) fn plan(ctx: &Ctx, ring: &Loop, riders: &[Rider], way: f64) -> Option<Plan> {
    let len = ring.length();
    let offsets: Vec<Vec<(f64, f64)>> = riders
        .iter()
        .map(|c| {
            let tasks = &c.nodes[1..c.nodes.len() - 1];
            tasks
                .iter()
                .map(|&n| {
                    let s = ring.project(node_pose(ctx.cell, c.r, n).pos).0;
                    let work = ctx.cell.tasks[n - 1].duration;
                    ((way * (s - c.home)).rem_euclid(len), work)
                })
                .collect()
        })
        .collect();
    let (at, end, holds) = stops(&offsets, len);
    // A task where the robot already is (at home, or at its previous task) would make a
    // leg of no motion: not a convoy's business.
    let still = |mine: &Vec<f64>| {
        let mut prev = 0.0;
        mine.iter().any(|&phi| {
            let same = phi - prev <= SAME_STOP * len;
            prev = phi;
            same
        })
    };
    if at.iter().any(still) {
        return None;
    }
    Some(Plan {
        offsets,
        at,
        end,
        holds,
    })
}

/// Rider `c`'s motion along the loop the way `way`, from `p0` to `p1` on from its home,
/// certified clear of the fixtures. `nodes` is where the convoy has turned at each node of
/// its route (home first and last): at a node the motion starts or ends at the node's pose
/// exactly, and on a stretch into a node it turns from the angle of the node before to its
/// own.
pub(super) fn stretch_motion(
    ctx: &Ctx,
    ring: &Loop,
    c: &Rider,
    nodes: &[f64],
    way: f64,
    (p0, p1): (f64, f64),
) -> Option<Arc<PlannedMove>> {
    let near = SAME_STOP * ring.length();
    let mut path = ring.way(c.home + way * p0, c.home + way * p1);
    let leg_of = |p: f64| nodes.iter().position(|&q| (q - p).abs() <= near);
    let (start, stop) = (leg_of(p0), leg_of(p1));
    let pose = |k: usize| node_pose(ctx.cell, c.r, c.nodes[k]);
    if let Some(k) = start {
        path[0] = pose(k).pos;
    }
    if let Some(k) = stop {
        let last = path.len() - 1;
        path[last] = pose(k).pos;
    }
    let before = nodes.iter().rposition(|&q| q <= p0 + near)?;
    let theta = pose(before).theta;
    let turn = stop.map_or(0.0, |k| wrap(pose(k).theta - theta));
    let primitive = Primitive { path, theta, turn };
    ctx.moves.along(c.r, &[primitive])
}

/// An angle in (-π, π].
pub(super) fn wrap(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    let a = a.rem_euclid(t);
    if a > std::f64::consts::PI {
        a - t
    } else {
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Loop {
        let corners = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)];
        Loop::new(corners.map(|(x, y)| Vec2::new(x, y)).to_vec()).unwrap()
    }

    /// Arc length round a square of side 4: projection, points past a whole lap, and the
    /// way along it either way with the corners between.
    #[test]
    fn a_loop_measures_and_walks_its_way_round() {
        let ring = square();
        assert_eq!(ring.length(), 16.0);
        assert!(ring.counter_clockwise());
        let (s, gap) = ring.project(Vec2::new(4.2, 1.0));
        assert!((s - 5.0).abs() < 1e-12 && (gap - 0.2).abs() < 1e-12);
        assert_eq!(ring.at(5.0), Vec2::new(4.0, 1.0));
        assert_eq!(ring.at(5.0 + 16.0), ring.at(5.0));
        assert_eq!(ring.at(-1.0), Vec2::new(0.0, 1.0));
        let v = |x: f64, y: f64| Vec2::new(x, y);
        assert_eq!(
            ring.way(2.0, 9.0),
            [v(2., 0.), v(4., 0.), v(4., 4.), v(3., 4.)]
        );
        // Back the other way, through the start of the loop.
        assert_eq!(ring.way(2.0, -2.0), [v(2., 0.), v(0., 0.), v(0., 2.)]);
        // A whole lap passes every corner once.
        assert_eq!(ring.way(1.0, 17.0).len(), 6);
        let reversed = Loop::new(ring.points.iter().rev().copied().collect()).unwrap();
        assert!(!reversed.counter_clockwise());
        // Two points and a repeat enclose nothing.
        assert!(Loop::new(vec![v(0., 0.), v(1., 0.), v(1., 0.), v(0., 0.)]).is_none());
    }

    /// The convoy stops where any robot reaches its next task, holds there for the longest
    /// task of those working there, and ends home after whole laps: a robot whose second
    /// task lies behind its first goes round again, and so do all.
    #[test]
    fn the_convoy_stops_at_every_task_and_ends_after_whole_laps() {
        let offsets = vec![vec![(3.0, 1.0)], vec![(8.0, 2.0)], vec![(3.0, 0.5)]];
        let (at, end, holds) = stops(&offsets, 10.0);
        assert_eq!(at, [vec![3.0], vec![8.0], vec![3.0]]);
        assert_eq!(end, 10.0);
        assert_eq!(holds, [(0.0, 0.0), (3.0, 1.0), (8.0, 2.0), (10.0, 0.0)]);
        let (at, end, _) = stops(&[vec![(6.0, 1.0), (2.0, 1.0)], vec![]], 10.0);
        assert_eq!(at, [vec![6.0, 12.0], vec![]]);
        assert_eq!(end, 20.0);
        // A task a rounding error short of a whole lap is where the robot is (the convoy
        // refuses such a leg of no motion), and the convoy still ends after one lap.
        let (at, end, _) = stops(&[vec![(10.0 - 1e-12, 1.0)]], 10.0);
        assert_eq!((at, end), (vec![vec![0.0]], 10.0));
    }
}
