//! Following: a convoy's robots round their loop as traffic, each behind the one ahead.
//!
//! The rigid convoy ([`super`]) stops every robot while any one works. Here each
//! robot goes on to its next stop as soon as, and as far as, the robot ahead of it leaves
//! room: it stops [`FOLLOW_GAP`] behind where the one ahead stands or will stop, and leaves
//! when the leader's timed move keeps it at least [`PASSING_GAP`] ahead along the loop at
//! every sample of both moves (all robots only move on). A robot that cannot reach its
//! stop moves up behind the one ahead when that gains at least [`MIN_HOP`], and waits
//! otherwise: its stopping point moves with its leader, as in coordination_oru (Pecora,
//! Andreasson, Mansouri & Petkov, ICAPS 2018). The result is one more child, checked
//! whole like every other: the gaps are along the loop, and the checker has the last word
//! where it bends.

use super::ring::{made, plan, stretch_motion, Loop, Made, Plan, Rider};
use crate::planning::PlannedMove;
use crate::wcp::feedback::remedies::context::{Ctx, View};
use crate::wcp::legs::{HoldReason, Leg, Piece};
use std::sync::Arc;

/// Where a robot stops behind the robot ahead, along the loop, in units of the two robots'
/// radii summed (plus 2δ): the chord of a right-angled bend is 1/√2 of its arc, so two
/// robots at rest stay a radius sum apart round such a bend.
const FOLLOW_GAP: f64 = 1.5;
/// The least distance along the loop while both move, in the same unit: 1.5 here too made
/// the rings of seeds 1 to 3 that need a convoy a third longer (`ring-1-8` 36.17 instead of
/// 27.52).
const PASSING_GAP: f64 = 1.0;
/// The shortest move up behind the robot ahead, in the same unit: each move is rest to
/// rest, and shorter ones cost more time than they gain.
const MIN_HOP: f64 = 1.0;
/// A bound on the events of one simulation (each ends a move or a task).
const MAX_EVENTS: usize = 100_000;

#[derive(Clone)]
enum State {
    Rest,
    /// On its way from `from` to `to`: when it leaves, and how far it has gone since at
    /// each sample of its motion (arc length along the loop, from the samples).
    Moving {
        from: f64,
        to: f64,
        leaves: f64,
        until: f64,
        gone: Arc<[(f64, f64)]>,
    },
    Working {
        until: f64,
    },
    Done,
}

/// How far along its path the motion has gone at each sample: (time, distance).
fn progress(motion: &PlannedMove) -> Arc<[(f64, f64)]> {
    let mut gone = 0.0;
    let mut out = Vec::with_capacity(motion.samples.len());
    let mut last = motion.samples.first().map(|s| s.pos);
    for s in &motion.samples {
        if let Some(p) = last {
            gone += (s.pos - p).norm();
        }
        last = Some(s.pos);
        out.push((s.t, gone));
    }
    out.into()
}

/// One robot of the traffic: how far it has gone from home, what it does, its next stop.
struct Car {
    phi: f64,
    state: State,
    next: usize,
    /// Its moves: when each starts, the motion, and whether it ends at a node.
    moves: Vec<(f64, Arc<PlannedMove>, bool)>,
}

/// The riders round the loop the way `way` as traffic; `None` when they would block each
/// other for good (a loop too full for the gaps) or a motion is not certified.
pub(super) fn traffic(
    ctx: &Ctx,
    view: &View,
    ring: &Loop,
    riders: &[Rider],
    way: f64,
) -> Option<Made> {
    let len = ring.length();
    let Plan {
        offsets, at, end, ..
    } = plan(ctx, ring, riders, way)?;
    let n = riders.len();
    let radius = |k: usize| ctx.cell.rigid(riders[k].r).shape.radius();
    // Where each home lies along the loop the way round, from the first rider's.
    let base: Vec<f64> = (riders.iter())
        .map(|c| (way * (c.home - riders[0].home)).rem_euclid(len))
        .collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| base[i].total_cmp(&base[j]));
    // The rider ahead of each, and how much farther round its home lies.
    let mut ahead = vec![(0, 0.0); n];
    for (k, &i) in order.iter().enumerate() {
        let j = order[(k + 1) % n];
        let lap = if k + 1 == n { len } else { 0.0 };
        ahead[i] = (j, base[j] + lap - base[i]);
    }
    // Each rider's distance to the one ahead at `factor` times their radii summed, plus 2δ,
    // no more than they stand apart at home.
    let spacing = |factor: f64| -> Vec<f64> {
        (0..n)
            .map(|i| {
                let (j, apart) = ahead[i];
                let wanted = factor * (radius(i) + radius(j)) + 2.0 * ctx.cell.delta;
                wanted.min(apart)
            })
            .collect()
    };
    let (gap, passing) = (spacing(FOLLOW_GAP), spacing(PASSING_GAP));
    let targets: Vec<Vec<f64>> = (at.iter())
        .map(|mine| mine.iter().copied().chain([end]).collect())
        .collect();
    let nodes: Vec<Vec<f64>> = (at.iter())
        .map(|mine| {
            std::iter::once(0.0)
                .chain(mine.iter().copied())
                .chain([end])
                .collect()
        })
        .collect();
    let mut cars: Vec<Car> = (0..n)
        .map(|_| Car {
            phi: 0.0,
            state: State::Rest,
            next: 0,
            moves: Vec::new(),
        })
        .collect();
    let mut now = 0.0;
    for _ in 0..MAX_EVENTS {
        // Every robot at rest moves on, as far as the one ahead leaves room.
        let mut moved = true;
        while moved {
            moved = false;
            for i in 0..n {
                if !matches!(cars[i].state, State::Rest) {
                    continue;
                }
                let (j, apart) = ahead[i];
                let leader = match &cars[j].state {
                    State::Moving { to, .. } => *to,
                    _ => cars[j].phi,
                };
                let room = leader + apart - gap[i];
                let target = targets[i][cars[i].next];
                let to = target.min(room);
                let hop = MIN_HOP * (radius(i) + radius(j));
                let reaches = to >= target;
                if to <= cars[i].phi || (!reaches && to - cars[i].phi < hop) {
                    continue;
                }
                let motion =
                    stretch_motion(ctx, ring, &riders[i], &nodes[i], way, (cars[i].phi, to))?;
                // Leave when the leader's move keeps it the gap ahead all the way.
                let gone = progress(&motion);
                let leaves = match &cars[j].state {
                    State::Moving {
                        from: lead_from,
                        leaves: lead_leaves,
                        gone: lead_gone,
                        ..
                    } => (gone.iter())
                        .map(|&(t, d)| {
                            let needed = cars[i].phi + d + passing[i] - apart - lead_from;
                            let k = lead_gone.partition_point(|&(_, ld)| ld < needed);
                            let when = lead_gone.get(k).map_or(f64::INFINITY, |&(lt, _)| lt);
                            lead_leaves + when - t
                        })
                        .fold(now, f64::max),
                    _ => now,
                };
                if !leaves.is_finite() {
                    continue;
                }
                let until = leaves + motion.duration;
                cars[i].moves.push((leaves, motion, reaches));
                cars[i].state = State::Moving {
                    from: cars[i].phi,
                    to,
                    leaves,
                    until,
                    gone,
                };
                moved = true;
            }
        }
        // The next event: a move or a task ends.
        let next = (cars.iter())
            .filter_map(|c| match c.state {
                State::Moving { until, .. } | State::Working { until } => Some(until),
                _ => None,
            })
            .fold(f64::INFINITY, f64::min);
        if !next.is_finite() {
            break;
        }
        now = next;
        for (i, car) in cars.iter_mut().enumerate() {
            match car.state.clone() {
                State::Moving { until, to, .. } if until <= now => {
                    car.phi = to;
                    car.state = State::Rest;
                    if to >= targets[i][car.next] {
                        car.state = match offsets[i].get(car.next) {
                            Some(&(_, work)) => State::Working { until: now + work },
                            None => State::Done,
                        };
                        car.next += 1;
                    }
                }
                State::Working { until } if until <= now => car.state = State::Rest,
                _ => {}
            }
        }
    }
    if !cars.iter().all(|c| matches!(c.state, State::Done)) {
        return None;
    }
    let mut ridden = Vec::new();
    for (i, (c, car)) in riders.iter().zip(&cars).enumerate() {
        let mut robot_legs = Vec::new();
        let mut pieces: Vec<Piece> = Vec::new();
        // When the robot was free to leave where it stands, and whether that is a node.
        let (mut free, mut at_node) = (0.0, true);
        let mut done_tasks = 0;
        for (start, motion, ends_at_node) in &car.moves {
            let idle = (start - free).max(0.0);
            let wait = if at_node {
                idle
            } else {
                if idle > 0.0 {
                    pieces.push(Piece::Hold {
                        duration: idle,
                        reason: HoldReason::Pause,
                    });
                }
                0.0
            };
            if at_node {
                robot_legs.push(Leg { wait, pieces: None });
            }
            pieces.push(Piece::Go {
                motion: motion.clone(),
                scale: 1.0,
            });
            free = start + motion.duration;
            at_node = *ends_at_node;
            if at_node {
                let last = robot_legs.last_mut()?;
                last.pieces = Some(Arc::from(std::mem::take(&mut pieces)));
                free += offsets[i].get(done_tasks).map_or(0.0, |o| o.1);
                done_tasks += 1;
            }
        }
        ridden.push((c.r, robot_legs));
    }
    made(ctx, view, ridden, way, end / len)
}
