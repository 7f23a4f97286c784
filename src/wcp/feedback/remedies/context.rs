//! What every remedy works with: the cell, the store of moves and the settings ([`Ctx`]),
//! the schedule being changed ([`View`]), which robot yields to which ([`Side`]), and the
//! helpers that find a leg's window, its nodes and pieces, and make the changed schedule.

use crate::cell::Cell;
use crate::geometry::{closest_features, convex_hull, ConvexPolygon, Posed, Vec2, WalkTolerances};
use crate::planning::PlannedMove;
use crate::wcp::feedback::clearing::{clears, least};
use crate::wcp::feedback::Remedy;
use crate::wcp::legs::{leg, with_leg, HoldReason, Leg, Legs, Piece};
use crate::wcp::moves::MoveStore;
use crate::wcp::options::SolveOptions;
use crate::wcp::schedule::{route_nodes, RobotSchedule, Segment};
use std::sync::Arc;

/// What the remedies read: the cell, the moves, the options, and plans made so far.
#[derive(Clone, Copy)]
pub(crate) struct Ctx<'a> {
    pub cell: &'a Cell,
    pub moves: &'a MoveStore,
    pub opts: &'a SolveOptions,
    /// A changed robot that ends at or after this makes a child the search drops (it
    /// cannot beat the best certified schedule): the remedies stop refining it.
    pub cap: f64,
    /// Whether a robot on its way may pull in at a passing place, and two robots that meet
    /// keep to lanes (the search's second pass, see `step_aside::pass_aside` and `lanes`).
    pub passing: bool,
}

/// The schedule a remedy changes: routes, legs and every robot's timed plan.
pub(crate) struct View<'a> {
    pub routes: &'a [Vec<usize>],
    pub legs: &'a Legs,
    pub robots: &'a [Arc<RobotSchedule>],
}

/// A changed schedule: one robot's legs and timed plan replaced (two robots' for a robot
/// that makes way for another).
#[derive(Clone)]
pub(crate) struct Child {
    pub legs: Legs,
    /// The robots changed, with their new timed plans.
    pub changed: Vec<(usize, Arc<RobotSchedule>)>,
    pub remedy: Remedy,
    /// A way out offered only when the usual ones fail, or one that would widen every
    /// search (a detour round the other side of a loop, a robot making way ahead of
    /// another): the search makes it a discrepancy, checked only when taken.
    pub last_resort: bool,
}

impl<'a> Ctx<'a> {
    pub fn new(cell: &'a Cell, moves: &'a MoveStore, opts: &'a SolveOptions) -> Self {
        Ctx {
            cell,
            moves,
            opts,
            cap: f64::INFINITY,
            passing: false,
        }
    }

    /// This context with children capped at `cap` (see [`Ctx::cap`]).
    pub fn capped(self, cap: f64) -> Self {
        Ctx { cap, ..self }
    }

    /// This context with passing places and lanes offered or not (see [`Ctx::passing`]).
    pub fn passing(self, passing: bool) -> Self {
        Ctx { passing, ..self }
    }

    /// Robot `x`'s schedule with leg `m` replaced; `None` if it cannot be timed.
    pub(super) fn rebuild(
        &self,
        view: &View,
        x: usize,
        m: usize,
        new: &Leg,
    ) -> Option<RobotSchedule> {
        let mut legs: Vec<Leg> = (*view.legs[x]).clone();
        if legs.len() <= m {
            legs.resize(m + 1, Leg::DEFAULT);
        }
        legs[m] = new.clone();
        RobotSchedule::build(self.cell, x, &view.routes[x], &legs, self.moves).ok()
    }
}

/// One way round: robot `x` yields to robot `y`; what each was doing at the contact, and
/// when it was.
pub(super) struct Side {
    pub(super) x: usize,
    pub(super) y: usize,
    pub(super) sx: Segment,
    pub(super) sy: Segment,
    pub(super) t: f64,
}

impl Side {
    /// The end of the window over which a change of leg `m` of `x` must clear `y`, given
    /// the changed schedule `s`: the end of the leg (its task included). When nothing comes
    /// after that leg (the robot is then home for good), no earlier than the end of what `y`
    /// was doing at the contact (for a robot itself home for good, the contact's time): a
    /// change that only brings the robot home sooner, still in `y`'s way, clears nothing.
    /// Later legs are the next rounds' business.
    pub(super) fn window_end(&self, s: &RobotSchedule, m: usize) -> f64 {
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
pub(super) fn leg_window(s: &RobotSchedule, m: usize) -> (f64, f64) {
    let of_leg = s.segments.iter().filter(|g| g.leg == Some(m));
    of_leg.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), g| {
        (lo.min(g.start), hi.max(g.end))
    })
}

/// Waits long enough to try, from `t0`: until `y` has left the place of its segment `sy`,
/// then until it is home for good. Finite and positive only.
pub(super) fn horizons(view: &View, y: usize, sy: &Segment, t0: f64) -> Vec<f64> {
    let ys = &view.robots[y];
    let mut out: Vec<f64> = [ys.left(sy) - t0, ys.end - t0]
        .into_iter()
        .filter(|d| d.is_finite() && *d > 0.0)
        .collect();
    out.dedup();
    out
}

/// The least value in `(0, D]`, for the first horizon D that works, for which the leg
/// `make(value)` of robot `x` clears `y` from `t0` (the leg's start) to the leg's end. A
/// horizon is given up once what is left of it would end the robot at or after
/// [`Ctx::cap`] (the search would drop that child), as one where nothing clears: the next
/// may still hold a value that clears sooner, between the first one's steps.
pub(super) fn least_clearing(
    ctx: &Ctx,
    view: &View,
    side: &Side,
    (m, t0): (usize, f64),
    horizons: &[f64],
    make: impl Fn(f64) -> Option<Leg>,
) -> Option<(f64, Leg, RobotSchedule)> {
    let opts = &ctx.opts.check;
    // The end of the robot at the value last made: the scan asks next whether the value
    // just below its next one (mostly the one it made) is viable.
    let made = std::cell::Cell::new((f64::NAN, f64::NAN));
    let make_at = |v: f64| {
        let new = make(v)?;
        let s = ctx.rebuild(view, side.x, m, &new)?;
        made.set((v, s.end));
        Some((new, s))
    };
    // A longer wait, pause or slowing never ends the robot sooner.
    let viable = |v: f64| {
        if ctx.cap == f64::INFINITY {
            return true;
        }
        let end = match made.get() {
            (at, end) if at == v => Some(end),
            _ => make_at(v).map(|(_, s)| s.end),
        };
        end.is_none_or(|end| end < ctx.cap)
    };
    horizons.iter().find_map(|&hi| {
        let clearing = |v: f64| {
            let (new, s) = make_at(v)?;
            let t1 = side.window_end(&s, m);
            let ok = clears(
                ctx.cell,
                (side.x, &s),
                (side.y, &view.robots[side.y]),
                (t0, t1),
                opts,
            );
            ok.then_some((new, s))
        };
        let (value, (new, schedule)) = least(0.0, hi, clearing, viable)?;
        Some((value, new, schedule))
    })
}

pub(super) fn child(
    view: &View,
    x: usize,
    m: usize,
    new: Leg,
    s: RobotSchedule,
    remedy: Remedy,
) -> Child {
    Child {
        legs: with_leg(view.legs, x, m, new),
        changed: vec![(x, Arc::new(s))],
        remedy,
        last_resort: false,
    }
}

/// The two nodes of leg `m` of robot `x`.
pub(super) fn leg_nodes(view: &View, x: usize, m: usize) -> (usize, usize) {
    let nodes = route_nodes(&view.routes[x]);
    (nodes[m], nodes[(m + 1).min(nodes.len() - 1)])
}

/// The leg's motion as pieces: its own, or the planned move timed from its primitives (as
/// `evaluate` times it; an arm's joint-space move as planned).
pub(super) fn pieces_of(ctx: &Ctx, view: &View, x: usize, m: usize) -> Option<Vec<Piece>> {
    match &leg(view.legs, x, m).pieces {
        Some(p) => Some(p.to_vec()),
        None => {
            let (from, to) = leg_nodes(view, x, m);
            let planned = ctx.moves.get(x, from, to).ok()?;
            let motion = match ctx.cell.robots[x].as_arm() {
                Some(_) => planned,
                None => ctx.moves.timed(x, &planned.primitives),
            };
            Some(vec![Piece::Go { motion, scale: 1.0 }])
        }
    }
}

/// Samples of a moving robot per convex piece of the region it sweeps (a detour's
/// obstacle, what a parked robot keeps clear of).
const SWEEP_CHUNK: usize = 8;

/// The region robot `y` occupies over `[t0, t1]`: for each of its convex pieces (each part
/// of each link of an arm), the hulls of short runs of its placements; where it stands,
/// the pieces themselves.
pub(super) fn occupancy(ctx: &Ctx, view: &View, y: usize, t0: f64, t1: f64) -> Vec<ConvexPolygon> {
    let ys = &view.robots[y];
    let robot = &ctx.cell.robots[y];
    let mut times = vec![t0];
    times.extend(ys.samples.iter().map(|s| s.t).filter(|&t| t > t0 && t < t1));
    times.push(t1);
    let mut placements: Vec<Vec<Vec<Vec2>>> = times
        .iter()
        .map(|&t| {
            (ys.placed(robot, t).into_iter())
                .flat_map(|(pieces, at)| pieces.iter().map(move |p| placed(p, at)))
                .collect()
        })
        .collect();
    placements.dedup();
    // Piece by piece: a robot of parts leaves free what lies between its parts (a gripper's
    // opening), which the hull of the whole robot would close.
    let mut out = Vec::new();
    for piece in 0..placements[0].len() {
        let mut start = 0;
        loop {
            let end = (start + SWEEP_CHUNK).min(placements.len() - 1);
            let points: Vec<Vec2> = (placements[start..=end].iter())
                .flat_map(|p| p[piece].iter().copied())
                .collect();
            let pts: Vec<[f64; 2]> = convex_hull(points).iter().map(|v| [v.x, v.y]).collect();
            if let Ok((polygon, _)) = ConvexPolygon::new(&pts) {
                out.push(polygon);
            }
            if end == placements.len() - 1 {
                break;
            }
            start = end;
        }
    }
    out
}

/// The vertices of `piece` placed at `at`.
fn placed(piece: &ConvexPolygon, at: crate::motion::Pose) -> Vec<Vec2> {
    let posed = Posed::new(piece, at.pos.x, at.pos.y, at.theta);
    (0..posed.len()).map(|i| posed.vertex(i)).collect()
}

/// Whether every piece of `pieces` placed lies farther than `margin` from every polygon of
/// `region` (in world coordinates).
pub(super) fn apart(
    pieces: &[(&[ConvexPolygon], crate::motion::Pose)],
    region: &[ConvexPolygon],
    margin: f64,
) -> bool {
    let tol = WalkTolerances::default();
    // Bounding discs first: most pairs are far apart.
    let discs: Vec<(Vec2, f64)> = (region.iter())
        .map(|o| {
            let c = o.centroid();
            let r = o
                .vertices()
                .iter()
                .fold(0.0, |m: f64, v| m.max((v - c).norm()));
            (c, r)
        })
        .collect();
    pieces.iter().all(|(parts, at)| {
        parts.iter().all(|p| {
            let posed = Posed::new(p, at.pos.x, at.pos.y, at.theta);
            region.iter().zip(&discs).all(|(o, (c, r))| {
                if (posed.center() - c).norm() > p.radius() + r + margin {
                    return true;
                }
                let other = Posed::new(o, 0.0, 0.0, 0.0);
                closest_features(&posed, &other, None, &tol).distance > margin
            })
        })
    })
}

/// Every fixture part where it stands, with a disc about its vertices: a pose farther from
/// a part than its disc and the robot's radius needs no closest features. Built once for a
/// remedy that tries many poses.
pub(super) struct FixtureDiscs<'a> {
    parts: Vec<(Posed<'a>, Vec2, f64)>,
}

impl<'a> FixtureDiscs<'a> {
    /// The cell's fixed obstacles, from `ctx`'s store of moves.
    pub(super) fn of(ctx: &Ctx<'a>) -> Self {
        let parts = (ctx.moves.obstacles().iter())
            .filter_map(|o| match &o.motion {
                crate::motion::Motion::Fixed(at) => Some((o, *at)),
                _ => None,
            })
            .flat_map(|(o, at)| {
                let parts =
                    (o.parts.as_ref()).map_or(std::slice::from_ref(&o.shape), |p| p.parts());
                parts.iter().map(move |q| {
                    let posed = Posed::new(q, at.pos.x, at.pos.y, at.theta);
                    let corners: Vec<Vec2> = (0..posed.len()).map(|k| posed.vertex(k)).collect();
                    let centre = corners.iter().sum::<Vec2>() / corners.len() as f64;
                    let reach = (corners.iter())
                        .map(|c| (c - centre).norm())
                        .fold(0.0, f64::max);
                    (posed, centre, reach)
                })
            })
            .collect();
        FixtureDiscs { parts }
    }

    /// Whether rigid robot `x` of `cell` at `pose` keeps more than `margin` from every
    /// fixture, part by part (a robot of parts may stand in a bay its hull would not fit).
    pub(super) fn clear(
        &self,
        cell: &Cell,
        x: usize,
        pose: crate::motion::Pose,
        margin: f64,
    ) -> bool {
        let tol = WalkTolerances::default();
        let reach = cell.rigid(x).shape.radius() + margin;
        cell.rigid(x).pieces().iter().all(|piece| {
            let posed = Posed::new(piece, pose.pos.x, pose.pos.y, pose.theta);
            (self.parts.iter()).all(|(other, centre, disc)| {
                (pose.pos - centre).norm() > disc + reach
                    || closest_features(&posed, other, None, &tol).distance > margin
            })
        })
    }
}

/// How far a robot's body reaches from the point it is placed by: a rigid robot's radius;
/// an arm's largest link radius (about its joint).
pub(super) fn body_radius(cell: &Cell, r: usize) -> f64 {
    cell.robots[r].body_radius()
}

/// Leg `old` with its piece `k` cut into `first`, a pause of `d`, and `second`, both at
/// `scale` (a pause's leg).
pub(super) fn paused(
    old: &Leg,
    pieces: &[Piece],
    k: usize,
    (first, second, scale): (&Arc<PlannedMove>, &Arc<PlannedMove>, f64),
    d: f64,
) -> Leg {
    let mut new = pieces.to_vec();
    let go = |motion: &Arc<PlannedMove>| Piece::Go {
        motion: motion.clone(),
        scale,
    };
    let hold = Piece::Hold {
        duration: d,
        reason: HoldReason::Pause,
    };
    new.splice(k..=k, [go(first), hold, go(second)]);
    Leg {
        pieces: Some(new.into()),
        ..old.clone()
    }
}

/// The leg of a step aside: after `wait`, `there` (to the parking place), `d` parked, and
/// `back` (on to the leg's end).
pub(super) fn by_parking(
    wait: f64,
    (there, back): (&Arc<PlannedMove>, &Arc<PlannedMove>),
    d: f64,
) -> Leg {
    let go = |motion: &Arc<PlannedMove>| Piece::Go {
        motion: motion.clone(),
        scale: 1.0,
    };
    let hold = Piece::Hold {
        duration: d,
        reason: HoldReason::Park,
    };
    Leg {
        wait,
        pieces: Some(vec![go(there), hold, go(back)].into()),
    }
}

/// Leg `old` (its wait kept) made by the one motion `motion`, as planned.
pub(super) fn by_motion(old: &Leg, motion: &Arc<PlannedMove>) -> Leg {
    let go = Piece::Go {
        motion: motion.clone(),
        scale: 1.0,
    };
    Leg {
        pieces: Some(vec![go].into()),
        ..old.clone()
    }
}

/// Whether `pieces` are already the one motion along `motion`'s path: a new plan that
/// changes nothing.
pub(super) fn same_path(pieces: &[Piece], motion: &PlannedMove) -> bool {
    matches!(pieces, [Piece::Go { motion: old, .. }] if old.path == motion.path)
}

/// A detour that ends its robot at or after [`Ctx::cap`]: the search would drop it, so it
/// is not checked.
pub(super) struct Late;

/// Leg `m` of `side.x` as the one motion `motion` (a detour's leg), and the schedule it
/// makes, when that clears `side.y` from `t0` (the leg's start) to the window's end.
pub(super) fn detoured(
    ctx: &Ctx,
    view: &View,
    side: &Side,
    (m, t0): (usize, f64),
    motion: &Arc<PlannedMove>,
) -> Option<Result<(Leg, RobotSchedule), Late>> {
    let new = by_motion(leg(view.legs, side.x, m), motion);
    let s = ctx.rebuild(view, side.x, m, &new)?;
    if s.end >= ctx.cap {
        return Some(Err(Late));
    }
    let window = (t0, side.window_end(&s, m));
    let ys = &view.robots[side.y];
    let ok = clears(
        ctx.cell,
        (side.x, &s),
        (side.y, ys),
        window,
        &ctx.opts.check,
    );
    ok.then_some(Ok((new, s)))
}

/// Of the candidates tried, `(end of the changed leg, candidate)`, the one that ends
/// earliest; on ties the one tried first (each remedy tries its best guess first).
pub(super) fn earliest<T>(tried: impl Iterator<Item = (f64, T)>) -> Option<T> {
    tried
        .fold(None, |best: Option<(f64, T)>, c| match best {
            Some(b) if b.0 <= c.0 => Some(b),
            _ => Some(c),
        })
        .map(|(_, candidate)| candidate)
}

/// A cell read from `text` with every robot's schedule on `routes` (default legs), and the
/// context and view a remedy works with: for the remedies' unit tests.
#[cfg(test)]
pub(super) struct TestCell {
    pub cell: Cell,
    opts: SolveOptions,
    pub moves: MoveStore,
    routes: Vec<Vec<usize>>,
    legs: Legs,
    robots: Vec<Arc<RobotSchedule>>,
}

#[cfg(test)]
impl TestCell {
    pub fn new(text: &str, routes: Vec<Vec<usize>>) -> TestCell {
        let cell = crate::cell::parse_cell(text, "test.json".as_ref())
            .unwrap()
            .cell;
        let moves = MoveStore::new(&cell, &crate::planning::PlannerOptions::default());
        let legs = crate::wcp::legs::default_legs(cell.robots.len());
        let schedule = crate::wcp::schedule::Schedule::build(&cell, &routes, &legs, &moves);
        let robots = schedule.unwrap().robots;
        TestCell {
            cell,
            opts: SolveOptions::default(),
            moves,
            routes,
            legs,
            robots,
        }
    }

    pub fn ctx(&self) -> Ctx<'_> {
        Ctx::new(&self.cell, &self.moves, &self.opts)
    }

    pub fn view(&self) -> View<'_> {
        View {
            routes: &self.routes,
            legs: &self.legs,
            robots: &self.robots,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::Pose;

    /// `apart` measures the pieces placed against the region, by `margin`: its bounding-disc
    /// shortcut decides only pairs that are far apart.
    #[test]
    fn apart_is_the_distance_beyond_a_margin() {
        let square = ConvexPolygon::rectangle(1.0, 1.0).unwrap(); // about its centre
        let region = [
            ConvexPolygon::new(&[[2.0, -0.5], [3.0, -0.5], [3.0, 0.5], [2.0, 0.5]])
                .unwrap()
                .0,
        ];
        let at = |x: f64| [(std::slice::from_ref(&square), Pose::new(x, 0.0, 0.0))];
        // The square's right edge at x + 0.5; the region's left edge at 2.
        assert!(apart(&at(1.4), &region, 0.05)); // 0.1 apart
        assert!(!apart(&at(1.4), &region, 0.15)); // within the margin
        assert!(!apart(&at(1.6), &region, 0.0)); // overlapping
        assert!(apart(&at(-50.0), &region, 1.0)); // far: the discs decide
                                                  // A long thin piece whose centre is far but whose end reaches the region.
        let bar = ConvexPolygon::new(&[[-4.0, -0.1], [4.0, -0.1], [4.0, 0.1], [-4.0, 0.1]])
            .unwrap()
            .0;
        let reach = [(std::slice::from_ref(&bar), Pose::new(-2.0, 0.0, 0.0))];
        assert!(!apart(&reach, &region, 0.0));
    }
}
