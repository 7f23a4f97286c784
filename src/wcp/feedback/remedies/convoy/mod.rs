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
//! Beside it the search is offered the same convoy as traffic ([`following`]): each
//! robot goes on as far as the one ahead leaves room, which ends sooner on every ring
//! measured (docs/solver.md); the rigid ring is the fallback where no robot has room.
//!
//! The loop is the colliding robot's move and the way round the other side (the detour's
//! last resort): the group is every robot whose home and tasks all lie on it.

use super::context::{leg_nodes, occupancy, Child, Ctx, Side, View};
use crate::planning::PlannedMove;
use crate::wcp::feedback::{Remedy, RemedyKind};
use crate::wcp::legs::{HoldReason, Leg, Piece};
use crate::wcp::moves::node_pose;
use crate::wcp::schedule::{route_nodes, Activity};
use following::traffic;
use ring::{made, plan, stretch_motion, Loop, Made, Plan, Rider, ON_LOOP, SAME_STOP};
use std::sync::Arc;

mod following;
mod ring;

/// Every robot whose home and tasks lie on the loop of collision `side` round it together:
/// following each other, and as one rigid ring, each the way round that ends sooner (none
/// of a kind whose motions are not certified clear of the fixtures); `None` when the loop
/// does not hold both robots of the collision.
pub(super) fn convoy(ctx: &Ctx, view: &View, side: &Side) -> Option<Vec<Child>> {
    let (ring, riders) = gather(ctx, view, side)?;
    let x = side.x;
    let m = side.sx.leg?;
    let (from, to) = leg_nodes(view, x, m);
    // As traffic (each robot behind the one ahead) and as one rigid ring, each the way
    // round that ends sooner: the first is shorter, the second holds every gap as at home
    // when the first cannot be made or is refused by the checker.
    type Make = fn(&Ctx, &View, &Loop, &[Rider], f64) -> Option<Made>;
    let ways: [(bool, Make); 2] = [(true, traffic), (false, round)];
    let children = ways.into_iter().filter_map(|(following, make)| {
        let made = [1.0, -1.0]
            .into_iter()
            .filter_map(|way| make(ctx, view, &ring, &riders, way))
            .min_by(|p, q| p.0.total_cmp(&q.0))?;
        let (_, legs, changed, way, laps) = made;
        let kind = RemedyKind::Convoy {
            robots: riders.iter().map(|c| c.r).collect(),
            counter_clockwise: (way > 0.0) == ring.counter_clockwise(),
            laps,
            following,
            loop_path: ring.points.clone(),
        };
        Some(Child {
            legs,
            changed,
            remedy: Remedy::on(x, m, (from, to), kind),
            last_resort: true,
        })
    });
    Some(children.collect())
}

/// The loop of collision `side` and the robots on it: the colliding robot's planned move
/// and its way round the other side (around the other robot where they met), and every
/// rigid robot whose home and tasks lie within [`ON_LOOP`] of its radius of that loop;
/// `None` when the loop does not hold both robots of the collision.
fn gather(ctx: &Ctx, view: &View, side: &Side) -> Option<(Loop, Vec<Rider>)> {
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
    let on_it = |r: usize| riders.iter().any(|c| c.r == r);
    (on_it(x) && on_it(y)).then_some((ring, riders))
}

/// The riders round the loop the way `way`, as one rigid ring.
fn round(ctx: &Ctx, view: &View, ring: &Loop, riders: &[Rider], way: f64) -> Option<Made> {
    let len = ring.length();
    let Plan {
        offsets,
        at,
        end,
        holds,
    } = plan(ctx, ring, riders, way)?;
    let stop_times: Vec<f64> = holds.iter().map(|h| h.0).collect();
    // Each stretch between two stops, for every rider: its motion, then all slowed to the
    // slowest so that they arrive together.
    let mut motions: Vec<Vec<Arc<PlannedMove>>> = Vec::new();
    for (c, phis) in riders.iter().zip(&at) {
        let nodes: Vec<f64> = std::iter::once(0.0)
            .chain(phis.iter().copied())
            .chain([end])
            .collect();
        let mine = (stop_times.windows(2))
            .map(|w| stretch_motion(ctx, ring, c, &nodes, way, (w[0], w[1])))
            .collect::<Option<Vec<_>>>()?;
        motions.push(mine);
    }
    let stretch: Vec<f64> = (0..stop_times.len() - 1)
        .map(|k| motions.iter().map(|m| m[k].duration).fold(0.0, f64::max))
        .collect();
    let mut ridden = Vec::new();
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
        ridden.push((c.r, robot_legs));
    }
    made(ctx, view, ridden, way, end / len)
}

#[cfg(test)]
mod tests {
    use super::super::context::TestCell;
    use super::*;
    use crate::generate::{generate_conflict_cell, ConflictKind};
    use crate::wcp::schedule::Schedule;

    /// The convoy goes the way round that ends sooner: on a ring of seven robots where R1
    /// has a second task, the way on which R1 meets its tasks in its route's order takes
    /// one lap and the other two. With R1's tasks in either order, the convoy (following)
    /// takes the one-lap way; in one of the two orders that is the loop's way -1.
    #[test]
    fn the_convoy_goes_the_way_round_that_ends_sooner() {
        let mut cell = generate_conflict_cell(ConflictKind::Ring, 1, 8);
        let second = serde_json::json!({
            "name": "R1-weld-2", "at": [0.5, 2.275, 0.0], "duration": 1.0, "robots": ["R1"]
        });
        cell["tasks"].as_array_mut().unwrap().push(second);
        let text = cell.to_string();
        let mut one_lap_ways = Vec::new();
        for first in [vec![0, 7], vec![7, 0]] {
            let routes: Vec<Vec<usize>> = std::iter::once(first)
                .chain((1..7).map(|k| vec![k]))
                .collect();
            let t = TestCell::new(&text, routes);
            let (ctx, view) = (t.ctx(), t.view());
            let schedule = Schedule::of(view.robots.to_vec());
            let report = schedule.check(&schedule.scene(&t.cell), &ctx.opts.check);
            let c = schedule.collision(&t.cell, &report).expect("a collision");
            let (a, b) = (c.robots.0, c.robots.1.unwrap());
            let (sa, sb) = (c.segments.0, c.segments.1.unwrap());
            let side = [(a, b, sa, sb), (b, a, sb, sa)]
                .map(|(x, y, sx, sy)| Side {
                    x,
                    y,
                    sx,
                    sy,
                    t: c.time,
                })
                .into_iter()
                .find(|side| gather(&ctx, &view, side).is_some())
                .expect("a loop holding both");
            let (ring, riders) = gather(&ctx, &view, &side).unwrap();
            let laps = |way: f64| traffic(&ctx, &view, &ring, &riders, way).unwrap().4;
            let one_lap = match (laps(1.0), laps(-1.0)) {
                (1, 2) => 1.0,
                (2, 1) => -1.0,
                other => panic!("laps both ways {other:?}"),
            };
            let children = convoy(&ctx, &view, &side).expect("a convoy");
            let chosen = (children.iter())
                .find_map(|child| match &child.remedy.kind {
                    RemedyKind::Convoy {
                        following: true,
                        counter_clockwise,
                        laps,
                        ..
                    } => Some((*counter_clockwise, *laps)),
                    _ => None,
                })
                .expect("a following convoy");
            let counter_clockwise = (one_lap > 0.0) == ring.counter_clockwise();
            assert_eq!(chosen, (counter_clockwise, 1));
            one_lap_ways.push(one_lap);
        }
        assert!(one_lap_ways.contains(&-1.0), "{one_lap_ways:?}");
    }
}
