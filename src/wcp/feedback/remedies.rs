//! The ways out of one collision: for each of the two robots, the changes to one of its
//! legs that separate it from the other robot, each the least of its kind that does.
//!
//! * **wait**: wait longer at the start node of the leg (the robot reaches the place later);
//! * **pause**: stop at a point of the path short of the place of contact, wait there, go
//!   on (the move is cut there into two rest-to-rest moves);
//! * **slow**: run the leg's motions slower (time scaling keeps every limit);
//! * **detour**: re-plan the leg with the other robot as an obstacle: its pose if it
//!   stands, the region it sweeps during the conflict if it moves;
//! * **step aside**: a robot standing in the other's way (waiting at a node, or home for
//!   good) goes to a free parking pose nearby, waits there and goes on (or back home); a
//!   robot on its way leaves its start node for a parking pose near it instead, and lets
//!   the other pass.
//!
//! Every candidate is judged by [`clears`] on the window of the changed leg; the search
//! decides among the survivors by makespan. Motions are planned by the planner and
//! certified clear of the fixtures by the checker, so the limits and the clearance hold.

use super::clearing::{clears, least};
use super::{Remedy, SolveOptions};
use crate::cell::Cell;
use crate::collision::Body;
use crate::geometry::{closest_features, ConvexPolygon, Posed, Vec2, WalkTolerances};
use crate::motion::{Motion, Pose};
use crate::planning::{
    convex_hull, plan_move, time_primitives, PlannedMove, Primitive, RobotLimits,
};
use crate::wcp::legs::{leg, with_leg, HoldReason, Leg, Legs, Piece};
use crate::wcp::moves::MoveStore;
use crate::wcp::moves::{certify, node_pose};
use crate::wcp::schedule::{route_nodes, Activity, Collision, RobotSchedule, Segment};
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// Back-off distances of a pause, in units of the two robots' radii summed: how far short
/// of the contact point along its path the robot stops.
const PAUSE_BACKOFF: [f64; 3] = [1.0, 2.0, 4.0];
/// Slowest time scaling tried.
const MAX_SLOW: f64 = 8.0;
/// Parking rings, in the parking robot's radii, and directions per ring.
const PARK_RINGS: [f64; 5] = [2.0, 3.0, 4.5, 6.5, 9.0];
const PARK_DIRECTIONS: usize = 12;
/// Parking poses examined in full (planned, timed, checked) per remedy, nearest first.
const PARK_TRIES: usize = 3;
/// Half-width of the short detour window about the contact, in the time the detouring
/// robot takes at full speed to cover the two robots' radii summed.
const DETOUR_REACH: f64 = 2.0;
/// Samples of a moving robot per convex piece of the region it sweeps (a detour's
/// obstacle).
const SWEEP_CHUNK: usize = 8;

/// What the remedies read: the cell, the moves, the options, and plans made so far.
pub(super) struct Ctx<'a> {
    pub cell: &'a Cell,
    pub moves: &'a MoveStore,
    pub opts: &'a SolveOptions,
    fixtures: Vec<ConvexPolygon>,
    /// Motions planned for remedies, by robot, end poses and extra obstacles: the same
    /// detour or way to a parking pose is planned once for the whole search.
    plans: Mutex<HashMap<Vec<u64>, Option<Arc<PlannedMove>>>>,
}

/// The schedule a remedy changes: routes, legs and every robot's timed plan.
pub(super) struct View<'a> {
    pub routes: &'a [Vec<usize>],
    pub legs: &'a Legs,
    pub robots: &'a [Arc<RobotSchedule>],
}

/// A changed schedule: one robot's legs and timed plan replaced.
pub(super) struct Child {
    pub legs: Legs,
    pub robot: usize,
    pub schedule: Arc<RobotSchedule>,
    pub remedy: Remedy,
}

/// Which remedies the search may use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Remedies {
    /// Re-sequence with the colliding steps forbidden together.
    pub resequence: bool,
    /// Wait at a node.
    pub wait: bool,
    /// Pause at a point of the path.
    pub pause: bool,
    /// Run a move slower.
    pub slow: bool,
    /// Go around the other robot.
    pub detour: bool,
    /// Step aside to a parking pose.
    pub step_aside: bool,
}

impl Remedies {
    /// Every remedy.
    pub const ALL: Remedies = Remedies {
        resequence: true,
        wait: true,
        pause: true,
        slow: true,
        detour: true,
        step_aside: true,
    };

    /// The names of `--remedies`, in this order.
    pub const NAMES: [&'static str; 6] = [
        "resequence",
        "wait",
        "pause",
        "slow",
        "detour",
        "step-aside",
    ];

    /// The set of the names given (each one of [`Remedies::NAMES`]).
    pub fn of_names<'s>(names: impl IntoIterator<Item = &'s str>) -> Result<Remedies, String> {
        let mut set = Remedies {
            resequence: false,
            wait: false,
            pause: false,
            slow: false,
            detour: false,
            step_aside: false,
        };
        for name in names {
            let flag = match name {
                "resequence" => &mut set.resequence,
                "wait" => &mut set.wait,
                "pause" => &mut set.pause,
                "slow" => &mut set.slow,
                "detour" => &mut set.detour,
                "step-aside" => &mut set.step_aside,
                other => {
                    return Err(format!(
                        "unknown remedy `{other}`: expected some of {}",
                        Remedies::NAMES.join(", ")
                    ))
                }
            };
            *flag = true;
        }
        Ok(set)
    }
}

impl Default for Remedies {
    fn default() -> Self {
        Remedies::ALL
    }
}

impl<'a> Ctx<'a> {
    pub fn new(cell: &'a Cell, moves: &'a MoveStore, opts: &'a SolveOptions) -> Self {
        Ctx {
            cell,
            moves,
            opts,
            fixtures: cell.obstacles.iter().map(|o| o.shape.clone()).collect(),
            plans: Mutex::new(HashMap::new()),
        }
    }

    fn limits(&self, r: usize) -> RobotLimits {
        let robot = &self.cell.robots[r];
        RobotLimits {
            max_speed: robot.max_speed,
            max_accel: robot.max_accel,
            max_turn_rate: robot.max_turn_rate,
        }
    }

    /// Times primitives for robot `r` as the planner would.
    fn timed(&self, r: usize, primitives: &[Primitive]) -> Arc<PlannedMove> {
        let radius = self.cell.robots[r].shape.radius();
        let per_phase = self.moves.planner().samples_per_phase;
        Arc::new(time_primitives(
            radius,
            &self.limits(r),
            primitives,
            per_phase,
        ))
    }

    /// Robot `r`'s fastest move from `from` to `to` around the fixtures and `extra`,
    /// certified clear of the fixtures; `None` if there is none.
    fn plan(
        &self,
        r: usize,
        from: Pose,
        to: Pose,
        extra: &[ConvexPolygon],
    ) -> Option<Arc<PlannedMove>> {
        let mut key = vec![r as u64];
        for p in [from, to] {
            key.extend([p.pos.x, p.pos.y, p.theta].map(f64::to_bits));
        }
        for o in extra {
            key.push(o.len() as u64);
            key.extend(
                o.vertices()
                    .iter()
                    .flat_map(|v| [v.x.to_bits(), v.y.to_bits()]),
            );
        }
        if let Some(known) = self.lock().get(&key) {
            return known.clone();
        }
        let robot = &self.cell.robots[r];
        let mut obstacles = self.fixtures.clone();
        obstacles.extend_from_slice(extra);
        let planner = self.moves.planner();
        let planned = plan_move(
            &robot.shape,
            &self.limits(r),
            &obstacles,
            self.cell.delta,
            from,
            to,
            planner,
        )
        .ok()
        .filter(|m| certify(self.cell, r, &m.samples, self.moves.obstacles()).is_ok())
        // Timed again from its primitives, as `evaluate` will time it.
        .map(|m| self.timed(r, &m.primitives));
        self.lock().entry(key).or_insert(planned).clone()
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, HashMap<Vec<u64>, Option<Arc<PlannedMove>>>> {
        self.plans.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Robot `x`'s schedule with leg `m` replaced; `None` if it cannot be timed.
    fn rebuild(&self, view: &View, x: usize, m: usize, new: &Leg) -> Option<RobotSchedule> {
        let mut legs: Vec<Leg> = (*view.legs[x]).clone();
        if legs.len() <= m {
            legs.resize(m + 1, Leg::DEFAULT);
        }
        legs[m] = new.clone();
        RobotSchedule::build(self.cell, x, &view.routes[x], &legs, self.moves).ok()
    }
}

/// The candidates for collision `c`: for each robot of the pair, each remedy allowed that
/// separates it from the other, in a fixed order (first robot first; wait, pause, slow,
/// detour, step aside). Evaluated in parallel, collected in that order.
pub(super) fn candidates(ctx: &Ctx, view: &View, c: &Collision) -> Vec<Child> {
    let (Some(b), Some(sb)) = (c.robots.1, c.segments.1) else {
        return Vec::new();
    };
    let a = c.robots.0;
    let sa = c.segments.0;
    let set = ctx.opts.search.remedies;
    type Job = fn(&Ctx, &View, &Side) -> Option<Child>;
    let kinds: [(bool, Job); 5] = [
        (set.wait, wait),
        (set.pause, pause),
        (set.slow, slow),
        (set.detour, detour),
        (set.step_aside, step_aside),
    ];
    let t = c.time;
    let sides = [
        Side {
            x: a,
            y: b,
            sx: sa,
            sy: sb,
            t,
        },
        Side {
            x: b,
            y: a,
            sx: sb,
            sy: sa,
            t,
        },
    ];
    let jobs: Vec<(&Side, Job)> = sides
        .iter()
        .flat_map(|side| kinds.iter().filter(|k| k.0).map(move |k| (side, k.1)))
        .collect();
    jobs.par_iter()
        .map(|(side, job)| job(ctx, view, side))
        .collect::<Vec<_>>()
        .into_iter()
        .flatten()
        .collect()
}

/// One way round: robot `x` yields to robot `y`; what each was doing at the contact, and
/// when it was.
struct Side {
    x: usize,
    y: usize,
    sx: Segment,
    sy: Segment,
    t: f64,
}

impl Side {
    /// The end of the window over which a change of leg `m` of `x` must clear `y`, given
    /// the changed schedule `s`: the end of the leg (its task included). When nothing comes
    /// after that leg (the robot is then home for good), no earlier than the end of what `y`
    /// was doing at the contact (for a robot itself home for good, the contact's time): a
    /// change that only brings the robot home sooner, still in `y`'s way, clears nothing.
    /// Later legs are the next rounds' business.
    fn window_end(&self, s: &RobotSchedule, m: usize) -> f64 {
        let leg_end = leg_window(s, m).1;
        let last = !s.segments.iter().any(|g| g.leg.is_some_and(|l| l > m));
        if !last {
            return leg_end;
        }
        let theirs = if self.sy.end.is_finite() {
            self.sy.end
        } else {
            self.t
        };
        leg_end.max(theirs)
    }
}

/// Start of leg `m` and end of what it leads to (its task included).
fn leg_window(s: &RobotSchedule, m: usize) -> (f64, f64) {
    let of_leg = s.segments.iter().filter(|g| g.leg == Some(m));
    of_leg.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), g| {
        (lo.min(g.start), hi.max(g.end))
    })
}

/// Waits long enough to try, from `t0`: until `y` has left the place of its segment `sy`,
/// then until it is home for good. Finite and positive only.
fn horizons(view: &View, y: usize, sy: &Segment, t0: f64) -> Vec<f64> {
    let ys = &view.robots[y];
    let gone = match sy.activity {
        Activity::Move { .. } => sy.end,
        Activity::Done => f64::INFINITY,
        // Standing: until the motion that takes it away ends.
        _ => ys
            .segments
            .iter()
            .skip_while(|g| g.start < sy.end)
            .find(|g| matches!(g.activity, Activity::Move { .. }))
            .map_or(f64::INFINITY, |g| g.end),
    };
    let mut out: Vec<f64> = [gone - t0, ys.end - t0]
        .into_iter()
        .filter(|d| d.is_finite() && *d > 0.0)
        .collect();
    out.dedup();
    out
}

/// The least value in `(0, D]`, for the first horizon D that works, for which the leg
/// `make(value)` of robot `x` clears `y` from `t0` (the leg's start) to the leg's end.
fn least_clearing(
    ctx: &Ctx,
    view: &View,
    side: &Side,
    (m, t0): (usize, f64),
    bounds: &[f64],
    make: impl Fn(f64) -> Option<Leg>,
) -> Option<(f64, Leg, RobotSchedule)> {
    let opts = &ctx.opts.check;
    bounds.iter().find_map(|&hi| {
        let (value, (new, schedule)) = least(0.0, hi, |v| {
            let new = make(v)?;
            let s = ctx.rebuild(view, side.x, m, &new)?;
            let t1 = side.window_end(&s, m);
            let ok = clears(
                ctx.cell,
                (side.x, &s),
                (side.y, &view.robots[side.y]),
                (t0, t1),
                opts,
            );
            ok.then_some((new, s))
        })?;
        Some((value, new, schedule))
    })
}

fn child(view: &View, x: usize, m: usize, new: Leg, s: RobotSchedule, remedy: Remedy) -> Child {
    Child {
        legs: with_leg(view.legs, x, m, new),
        robot: x,
        schedule: Arc::new(s),
        remedy,
    }
}

/// The two nodes of leg `m` of robot `x`.
fn leg_nodes(view: &View, x: usize, m: usize) -> (usize, usize) {
    let nodes = route_nodes(&view.routes[x]);
    (nodes[m], nodes[(m + 1).min(nodes.len() - 1)])
}

/// The leg's motion as pieces: its own, or the planned move timed from its primitives.
fn pieces_of(ctx: &Ctx, view: &View, x: usize, m: usize) -> Option<Vec<Piece>> {
    match &leg(view.legs, x, m).pieces {
        Some(p) => Some(p.to_vec()),
        None => {
            let (from, to) = leg_nodes(view, x, m);
            let planned = ctx.moves.get(x, from, to).ok()?;
            Some(vec![Piece::Go {
                motion: ctx.timed(x, &planned.primitives),
                scale: 1.0,
            }])
        }
    }
}

/// Wait longer at the leg's start node.
fn wait(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let m = side.sx.leg?;
    if matches!(side.sx.activity, Activity::Wait(_) | Activity::Done) {
        // Standing where it is hit: waiting longer keeps it there.
        return None;
    }
    let old = leg(view.legs, side.x, m).clone();
    let t0 = leg_window(&view.robots[side.x], m).0;
    let bounds = horizons(view, side.y, &side.sy, t0);
    let (d, new, s) = least_clearing(ctx, view, side, (m, t0), &bounds, |d| {
        Some(Leg {
            wait: old.wait + d,
            ..old.clone()
        })
    })?;
    let nodes = leg_nodes(view, side.x, m);
    let remedy = Remedy::Delay(crate::wcp::schedule::Delay {
        robot: side.x,
        before_move: m,
        nodes,
        duration: d,
    });
    Some(child(view, side.x, m, new, s, remedy))
}

/// The piece of leg `m` under way in segment `sx`, counting the leg's wait as no piece.
fn piece_index(view: &View, x: usize, m: usize, sx: &Segment) -> Option<usize> {
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
fn split_chain(primitives: &[Primitive], s: f64) -> Option<(Vec<Primitive>, Vec<Primitive>)> {
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
fn pause(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
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
    let reach = ctx.cell.robots[side.x].shape.radius() + ctx.cell.robots[side.y].shape.radius();
    let old = leg(view.legs, side.x, m).clone();
    let t0 = leg_window(&view.robots[side.x], m).0;
    let bounds = horizons(view, side.y, &side.sy, t0);
    let tried = PAUSE_BACKOFF.iter().filter_map(|back| {
        let (before, after) = split_chain(&motion.primitives, at - back * reach)?;
        let (first, second) = (ctx.timed(side.x, &before), ctx.timed(side.x, &after));
        let obstacles = ctx.moves.obstacles();
        for half in [&first, &second] {
            certify(ctx.cell, side.x, &half.samples, obstacles).ok()?;
        }
        let stop = first.path.last().copied()?;
        let make = |d: f64| {
            let mut new = pieces.clone();
            new.splice(
                k..=k,
                [
                    Piece::Go {
                        motion: first.clone(),
                        scale,
                    },
                    Piece::Hold {
                        duration: d,
                        reason: HoldReason::Pause,
                    },
                    Piece::Go {
                        motion: second.clone(),
                        scale,
                    },
                ],
            );
            Some(Leg {
                pieces: Some(new.into()),
                ..old.clone()
            })
        };
        let (d, new, s) = least_clearing(ctx, view, side, (m, t0), &bounds, make)?;
        Some((s.end, d, stop, new, s))
    });
    // The earliest end; on ties the stop nearest the contact (tried first).
    let (_, d, stop, new, s) = tried.fold(
        None,
        |best: Option<(f64, f64, Vec2, Leg, RobotSchedule)>, c| match best {
            Some(b) if b.0 <= c.0 => Some(b),
            _ => Some(c),
        },
    )?;
    let remedy = Remedy::Pause {
        robot: side.x,
        leg: m,
        nodes: leg_nodes(view, side.x, m),
        at: stop,
        duration: d,
    };
    Some(child(view, side.x, m, new, s, remedy))
}

/// Run the leg's motions slower.
fn slow(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
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
    let bounds: Vec<f64> = horizons(view, side.y, &side.sy, t0)
        .into_iter()
        .map(|d| (d / moving).min(MAX_SLOW - 1.0))
        .collect();
    let (extra, new, s) = least_clearing(ctx, view, side, (m, t0), &bounds, |e| {
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
    let remedy = Remedy::Slow {
        robot: side.x,
        leg: m,
        nodes: leg_nodes(view, side.x, m),
        factor: 1.0 + extra,
    };
    Some(child(view, side.x, m, new, s, remedy))
}

/// Robot `y`'s body over `[t0, t1]` as convex polygons: where it stands, or the hulls of
/// runs of its samples while it moves.
fn occupancy(ctx: &Ctx, view: &View, y: usize, t0: f64, t1: f64) -> Vec<ConvexPolygon> {
    let ys = &view.robots[y];
    let shape = &ctx.cell.robots[y].shape;
    let placed = |p: Pose| -> Vec<Vec2> {
        let posed = Posed::new(shape, p.pos.x, p.pos.y, p.theta);
        (0..posed.len()).map(|i| posed.vertex(i)).collect()
    };
    let mut poses = vec![ys.pose_at(t0)];
    poses.extend(
        ys.samples
            .iter()
            .filter(|s| s.t > t0 && s.t < t1)
            .map(|s| Pose {
                pos: s.pos,
                theta: s.theta,
            }),
    );
    poses.push(ys.pose_at(t1));
    poses.dedup();
    let mut out = Vec::new();
    let mut start = 0;
    loop {
        let end = (start + SWEEP_CHUNK).min(poses.len() - 1);
        let points: Vec<Vec2> = poses[start..=end].iter().flat_map(|&p| placed(p)).collect();
        let hull = convex_hull(points);
        let pts: Vec<[f64; 2]> = hull.iter().map(|v| [v.x, v.y]).collect();
        if let Ok((polygon, _)) = ConvexPolygon::new(&pts) {
            out.push(polygon);
        }
        if end == poses.len() - 1 {
            return out;
        }
        start = end;
    }
}

/// Re-plan the leg around the other robot.
fn detour(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
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
        let robot = &ctx.cell.robots[side.x];
        let reach = robot.shape.radius() + ctx.cell.robots[side.y].shape.radius();
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
    let old = leg(view.legs, side.x, m).clone();
    let tried = windows.into_iter().filter_map(|(w0, w1)| {
        let region = occupancy(ctx, view, side.y, w0, w1.max(w0));
        let motion = ctx.plan(side.x, a, b, &region)?;
        if matches!(current.as_slice(), [Piece::Go { motion: old, .. }] if old.path == motion.path)
        {
            return None;
        }
        let new = Leg {
            pieces: Some(
                vec![Piece::Go {
                    motion: motion.clone(),
                    scale: 1.0,
                }]
                .into(),
            ),
            ..old.clone()
        };
        let s = ctx.rebuild(view, side.x, m, &new)?;
        let window = (t0, side.window_end(&s, m));
        let ys = &view.robots[side.y];
        clears(
            ctx.cell,
            (side.x, &s),
            (side.y, ys),
            window,
            &ctx.opts.check,
        )
        .then_some((s.end, motion, new, s))
    });
    // The earliest end; on ties the first window tried.
    let (_, motion, new, s) = tried.fold(None, |best: Option<(f64, _, _, _)>, c| match best {
        Some(b) if b.0 <= c.0 => Some(b),
        _ => Some(c),
    })?;
    let remedy = Remedy::Detour {
        robot: side.x,
        leg: m,
        nodes: (from, to),
        around: side.y,
        path: motion.path.clone(),
    };
    Some(child(view, side.x, m, new, s, remedy))
}

/// Parking poses around `q` for robot `x`, nearest first, clear of the fixtures and of the
/// discs robot `y` sweeps over `[t0, t1]`.
fn parking_poses(
    ctx: &Ctx,
    view: &View,
    x: usize,
    y: usize,
    q: Pose,
    (t0, t1): (f64, f64),
) -> Vec<Pose> {
    let cell = ctx.cell;
    let shape = &cell.robots[x].shape;
    let (rx, ry) = (shape.radius(), cell.robots[y].shape.radius());
    let ys = &view.robots[y];
    let passes: Vec<Vec2> = ys
        .samples
        .iter()
        .filter(|s| s.t >= t0 && s.t <= t1)
        .map(|s| s.pos)
        .chain([ys.pose_at(t0).pos, ys.pose_at(t1).pos])
        .collect();
    let obstacles: Vec<Body> = ctx.moves.obstacles().to_vec();
    let tol = WalkTolerances::default();
    let clear_of_fixtures = |p: Pose| {
        let posed = Posed::new(shape, p.pos.x, p.pos.y, p.theta);
        obstacles.iter().all(|o| {
            let Motion::Fixed(at) = &o.motion else {
                return true;
            };
            let other = Posed::new(&o.shape, at.pos.x, at.pos.y, at.theta);
            closest_features(&posed, &other, None, &tol).distance > 2.0 * cell.delta
        })
    };
    let mut out = Vec::new();
    for ring in PARK_RINGS {
        for k in 0..PARK_DIRECTIONS {
            let (s, c) = (k as f64 * std::f64::consts::TAU / PARK_DIRECTIONS as f64).sin_cos();
            let p = Pose {
                pos: q.pos + ring * rx * Vec2::new(c, s),
                theta: q.theta,
            };
            let away = passes
                .iter()
                .all(|g| (g - p.pos).norm() > rx + ry + 2.0 * cell.delta);
            if away && clear_of_fixtures(p) {
                out.push(p);
            }
        }
    }
    out
}

/// A robot standing in the other's way goes to a parking pose nearby, waits there, and goes
/// on to where its leg leads (or back home).
fn step_aside(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let t = side.t;
    let x = side.x;
    let route = &view.routes[x];
    let m = match side.sx.activity {
        // Waiting at the leg's start node, or already on the way: it leaves that node for
        // the parking pose instead, and lets the other pass.
        Activity::Wait(_) | Activity::Move { .. } => side.sx.leg?,
        // Home for good: a robot without tasks makes an excursion from home to home; one
        // with tasks goes home from its last task by way of the parking pose.
        Activity::Done if route.is_empty() => 0,
        Activity::Done => route.len(),
        _ => return None,
    };
    let (from, to) = leg_nodes(view, x, m);
    let xs = &view.robots[x];
    let q = match side.sx.activity {
        Activity::Move { .. } => node_pose(ctx.cell, x, from),
        _ => xs.pose_at(t),
    };
    let t0 = if route.is_empty() {
        0.0
    } else {
        leg_window(xs, m).0
    };
    let bounds = horizons(view, side.y, &side.sy, t0);
    let until = t0 + bounds.last().copied().unwrap_or(0.0);
    let (a, b) = (node_pose(ctx.cell, x, from), node_pose(ctx.cell, x, to));
    let old = leg(view.legs, x, m).clone();
    let keep_wait = matches!(side.sx.activity, Activity::Done);
    let tried = parking_poses(ctx, view, x, side.y, q, (t.min(t0.max(0.0)), until))
        .into_iter()
        .filter_map(|p| {
            let there = ctx.plan(x, a, p, &[])?;
            let back = ctx.plan(x, p, b, &[])?;
            Some((p, there, back))
        })
        .take(PARK_TRIES)
        .filter_map(|(p, there, back)| {
            let make = |d: f64| {
                Some(Leg {
                    wait: if keep_wait { old.wait } else { 0.0 },
                    pieces: Some(
                        vec![
                            Piece::Go {
                                motion: there.clone(),
                                scale: 1.0,
                            },
                            Piece::Hold {
                                duration: d,
                                reason: HoldReason::Park,
                            },
                            Piece::Go {
                                motion: back.clone(),
                                scale: 1.0,
                            },
                        ]
                        .into(),
                    ),
                })
            };
            let (d, new, s) = least_clearing(ctx, view, side, (m, t0), &bounds, make)?;
            Some((s.end, p, d, new, s))
        });
    let (_, park, d, new, s) = tried.fold(
        None,
        |best: Option<(f64, Pose, f64, Leg, RobotSchedule)>, c| match best {
            Some(b) if b.0 <= c.0 => Some(b),
            _ => Some(c),
        },
    )?;
    let remedy = Remedy::StepAside {
        robot: x,
        leg: m,
        nodes: (from, to),
        park,
        duration: d,
    };
    Some(child(view, x, m, new, s, remedy))
}
