//! A convoy: the robots of a closed corridor go round it together, all the same way.
//!
//! On a loop one robot wide, robots can never pass each other: their order round it is
//! fixed, so a robot whose task lies past another's home can reach it only if that robot
//! moves on too, and so on round the loop. No remedy of one or two robots does that; the
//! convoy moves them all at once, as one rigid ring of robots (each keeps its distance
//! along the loop to the next, as at home): all go the same way, all stop when one of them
//! reaches its next task and work there, and all are home again after a whole number of
//! laps. Every robot's motion is timed by the planner's model (rest to rest on each
//! stretch, the faster ones slowed to the slowest so that all arrive together) and
//! certified clear of the fixtures; the schedule is then checked whole, as every child is.
//!
//! The loop is the colliding robot's move and the way round the other side (the detour's
//! last resort): the group is every robot whose home and tasks all lie on it.

use super::context::{leg_nodes, occupancy, Child, Ctx, Side, View};
use crate::geometry::Vec2;
use crate::planning::Primitive;
use crate::wcp::feedback::{Remedy, RemedyKind};
use crate::wcp::legs::{HoldReason, Leg, Legs, Piece};
use crate::wcp::moves::node_pose;
use crate::wcp::schedule::{route_nodes, Activity, RobotSchedule};
use std::sync::Arc;

/// How far from the loop a robot's home or task may lie for the robot to ride it, in
/// units of the robot's radius (the planner's paths hug the inside of a corridor's bends).
const ON_LOOP: f64 = 0.5;
/// Offsets along the loop closer than this fraction of its length are one stop.
const SAME_STOP: f64 = 1e-9;

/// A closed polyline with arc length along it.
#[derive(Debug)]
struct Loop {
    /// Its vertices, the closing edge from the last back to the first implied.
    points: Vec<Vec2>,
    /// Arc length at each vertex; one more entry, the whole length, for the closing edge.
    arc: Vec<f64>,
}

impl Loop {
    /// The loop through `points` (consecutive repeats dropped); `None` when it encloses
    /// nothing (fewer than three distinct points).
    fn new(mut points: Vec<Vec2>) -> Option<Loop> {
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

    fn length(&self) -> f64 {
        self.arc[self.points.len()]
    }

    /// The arc length of the point of the loop nearest `p`, and how far `p` is from it.
    fn project(&self, p: Vec2) -> (f64, f64) {
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
    fn at(&self, s: f64) -> Vec2 {
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
    fn way(&self, s0: f64, s1: f64) -> Vec<Vec2> {
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
    fn counter_clockwise(&self) -> bool {
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
fn stops(offsets: &[Vec<(f64, f64)>], len: f64) -> (Vec<Vec<f64>>, f64, Vec<(f64, f64)>) {
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
struct Rider {
    r: usize,
    home: f64,
    nodes: Vec<usize>,
}

/// Every robot whose home and tasks lie on the loop of collision `side` round it together,
/// the way round that ends sooner; `None` when the loop does not hold both robots of the
/// collision, or a motion is not certified clear of the fixtures.
pub(super) fn convoy(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let (x, y) = (side.x, side.y);
    let rigid = |r: usize| ctx.cell.robots[r].as_arm().is_none();
    if !rigid(x) || !rigid(y) || !matches!(side.sx.activity, Activity::Move { .. }) {
        return None;
    }
    let m = side.sx.leg?;
    let (from, to) = leg_nodes(view, x, m);
    let (a, b) = (node_pose(ctx.cell, x, from), node_pose(ctx.cell, x, to));
    // The move as planned (a remedy before may have sent it round already).
    let here = ctx.moves.get(x, from, to).ok()?.path.clone();
    // The way round the other side: around the other robot where they met.
    let blocked = occupancy(ctx, view, y, side.t, side.t);
    let other = ctx.moves.between(x, a, b, &blocked)?;
    let mut points = here;
    points.extend(other.path.iter().rev());
    let ring = Loop::new(points)?;
    let riders: Vec<Rider> = (0..ctx.cell.robots.len())
        .filter(|&r| rigid(r))
        .filter_map(|r| {
            let nodes = route_nodes(&view.routes[r]);
            let reach = ON_LOOP * ctx.cell.rigid(r).shape.radius();
            let on = |n: usize| {
                let (s, gap) = ring.project(node_pose(ctx.cell, r, n).pos);
                (gap <= reach).then_some(s)
            };
            let home = on(0)?;
            nodes
                .iter()
                .all(|&n| on(n).is_some())
                .then_some(Rider { r, home, nodes })
        })
        .collect();
    if !riders.iter().any(|c| c.r == x) || !riders.iter().any(|c| c.r == y) {
        return None;
    }
    let made = [1.0, -1.0]
        .into_iter()
        .filter_map(|way| round(ctx, view, &ring, &riders, way))
        .min_by(|p, q| p.0.total_cmp(&q.0))?;
    let (_, legs, changed, way, laps) = made;
    let kind = RemedyKind::Convoy {
        robots: riders.iter().map(|c| c.r).collect(),
        counter_clockwise: (way > 0.0) == ring.counter_clockwise(),
        laps,
        loop_path: ring.points.clone(),
    };
    Some(Child {
        legs,
        changed,
        remedy: Remedy::on(x, m, (from, to), kind),
        last_resort: true,
    })
}

/// What a convoy makes: the latest end of its robots, the legs, the changed robots'
/// schedules, the way round (±1) and the laps.
type Made = (f64, Legs, Vec<(usize, Arc<RobotSchedule>)>, f64, usize);

/// The riders round the loop the way `way` (+1: as the loop's vertices run).
fn round(ctx: &Ctx, view: &View, ring: &Loop, riders: &[Rider], way: f64) -> Option<Made> {
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
    let stop_times: Vec<f64> = holds.iter().map(|h| h.0).collect();
    // Each stretch between two stops, for every rider: its motion, then all slowed to the
    // slowest so that they arrive together.
    let mut motions: Vec<Vec<Arc<crate::planning::PlannedMove>>> = Vec::new();
    for (c, phis) in riders.iter().zip(&at) {
        let nodes: Vec<f64> = std::iter::once(0.0)
            .chain(phis.iter().copied())
            .chain([end])
            .collect();
        let theta = |n: usize| node_pose(ctx.cell, c.r, n).theta;
        let mut mine = Vec::new();
        for w in stop_times.windows(2) {
            let (p0, p1) = (w[0], w[1]);
            let mut path = ring.way(c.home + way * p0, c.home + way * p1);
            // The ends of a leg are its nodes' poses, exactly.
            let leg_of = |p: f64| nodes.iter().position(|&q| (q - p).abs() <= SAME_STOP * len);
            let (start, stop) = (leg_of(p0), leg_of(p1));
            let node = |k: usize| c.nodes[k];
            if let Some(k) = start {
                path[0] = node_pose(ctx.cell, c.r, node(k)).pos;
            }
            if let Some(k) = stop {
                let last = path.len() - 1;
                path[last] = node_pose(ctx.cell, c.r, node(k)).pos;
            }
            // Turn on the stretch into a node: from the previous node's angle to its own.
            let before = nodes.iter().rposition(|&q| q <= p0 + SAME_STOP * len)?;
            let from_theta = theta(node(before));
            let turn = match stop {
                Some(k) => wrap(theta(node(k)) - from_theta),
                None => 0.0,
            };
            let primitive = Primitive {
                path,
                theta: from_theta,
                turn,
            };
            mine.push(ctx.moves.along(c.r, &[primitive])?);
        }
        motions.push(mine);
    }
    let stretch: Vec<f64> = (0..stop_times.len() - 1)
        .map(|k| motions.iter().map(|m| m[k].duration).fold(0.0, f64::max))
        .collect();
    let mut legs: Legs = view.legs.to_vec();
    let mut changed = Vec::new();
    let mut latest: f64 = 0.0;
    for (i, (c, mine)) in riders.iter().zip(&motions).enumerate() {
        let nodes: Vec<f64> = at[i].iter().copied().chain([end]).collect();
        let mut robot_legs = Vec::new();
        let mut pieces: Vec<Piece> = Vec::new();
        let mut wait = 0.0;
        let mut next = 0;
        for (k, motion) in mine.iter().enumerate() {
            let scale = if motion.duration > 0.0 {
                (stretch[k] / motion.duration).max(1.0)
            } else {
                1.0
            };
            pieces.push(Piece::Go {
                motion: motion.clone(),
                scale,
            });
            let (p1, hold) = holds[k + 1];
            if (nodes[next] - p1).abs() <= SAME_STOP * len {
                // At its node: its task, then what the others still work there.
                robot_legs.push(Leg {
                    wait,
                    pieces: Some(Arc::from(std::mem::take(&mut pieces))),
                });
                let work = offsets[i].get(next).map_or(0.0, |o| o.1);
                wait = (hold - work).max(0.0);
                next += 1;
                if next == nodes.len() {
                    break;
                }
            } else if hold > 0.0 {
                pieces.push(Piece::Hold {
                    duration: hold,
                    reason: HoldReason::Pause,
                });
            }
        }
        let s =
            RobotSchedule::build(ctx.cell, c.r, &view.routes[c.r], &robot_legs, ctx.moves).ok()?;
        latest = latest.max(s.end);
        legs[c.r] = Arc::new(robot_legs);
        changed.push((c.r, Arc::new(s)));
    }
    let laps = (end / len).round() as usize;
    Some((latest, legs, changed, way, laps))
}

/// An angle in (-π, π].
fn wrap(a: f64) -> f64 {
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
