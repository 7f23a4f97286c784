//! Velocity tuning of two robots at once: both keep their paths, and their coordination
//! diagram ([`coordinate`]) says where each holds and how long, so that the one that yields
//! stops as late and as close as the other's motion allows, and both may yield in turn
//! (Siméon, Leroy & Laumond 2002, for a pair).
//!
//! The axes are the two legs' motions as scheduled now (earlier pauses and slowings kept),
//! on a grid of a step in which neither body moves more than a quarter of the two radii
//! summed (an eighth cost a fifth more CPU on a junction, for the same answers). A point of
//! the diagram is free when the bodies placed there are farther apart than a margin that
//! covers the steps beside it; the answer is certified by the checker over both legs, and
//! tried again with a wider margin when it is not.
//!
//! A robot holds only where its motion rests anyway (its start node, a waypoint, a piece's
//! end, a pause it already makes), so the hold is a pause that keeps the timing of the
//! rest of the move.

use super::context::{body_radius, leg_nodes, leg_window, pieces_of, Child, Ctx, Side, View};
use super::coordination::{coordinate, Axis};
use super::pause::split_chain;
use crate::geometry::{closest_features, ConvexPolygon, Posed, Vec2, WalkTolerances};
use crate::motion::{Pose, Sample};
use crate::wcp::feedback::clearing::clears;
use crate::wcp::feedback::{Remedy, RemedyKind, RemedyLeg, TunedHold};
use crate::wcp::legs::{leg, with_leg, HoldReason, Leg, Piece};
use crate::wcp::schedule::{Activity, RobotSchedule, Segment};
use std::sync::Arc;

/// How far either body may move in one grid step, in units of the two radii summed.
const TUNE_STEP: f64 = 1.0 / 4.0;
/// The most grid points of a diagram: longer legs get a coarser step.
const TUNE_MAX_POINTS: f64 = 250_000.0;
/// Margins tried beyond 2δ, in units of half of what both bodies move over the grid steps
/// beside a point (the bound of Schwarzer, Saha & Latombe on a step): half of it first,
/// since grid points rarely see the worst case, then wider until the checker agrees.
const TUNE_MARGINS: [f64; 4] = [0.5, 1.0, 2.0, 4.0];

/// One robot of the pair: its leg in play and that leg's motion window in its schedule.
#[derive(Clone, Copy)]
struct Mover {
    r: usize,
    m: usize,
    /// When the leg's motion starts and ends (its wait before, its task after excluded).
    motion: (f64, f64),
}

/// Both robots of collision `side` held where their coordination diagram says.
pub(super) fn tune(ctx: &Ctx, view: &View, side: &Side) -> Option<Child> {
    let (x, y) = (side.x, side.y);
    if ctx.cell.robots[x].as_arm().is_some() || ctx.cell.robots[y].as_arm().is_some() {
        return None;
    }
    let moving = |g: &Segment| {
        matches!(
            g.activity,
            Activity::Move { .. } | Activity::Pause { .. } | Activity::Park { .. }
        )
    };
    if !moving(&side.sx) && !moving(&side.sy) {
        return None;
    }
    let movers = [mover(view, x, &side.sx)?, mover(view, y, &side.sy)?];
    let reach = [body_radius(ctx.cell, x), body_radius(ctx.cell, y)];
    // Fastest a point of each body moves: G's speed and the turn at the body's radius.
    let speed = [x, y].map(|r| {
        let rigid = ctx.cell.rigid(r);
        rigid.max_speed + rigid.max_turn_rate * rigid.shape.radius()
    });
    let lengths = movers.map(|v| v.motion.1 - v.motion.0);
    // Counted in f64: a leg of hours at a step of milliseconds overflows no integer.
    let points = |dt: f64| lengths.map(|l| (l / dt).ceil() + 1.0);
    let mut dt = TUNE_STEP * (reach[0] + reach[1]) / speed[0].max(speed[1]);
    let [n, m] = points(dt);
    if n * m > TUNE_MAX_POINTS {
        dt *= (n * m / TUNE_MAX_POINTS).sqrt();
    }
    let [n, m] = points(dt);
    // A step too small or too large for its times (limits far apart), or a grid rounding
    // past the bound: no diagram.
    if !(dt.is_finite() && dt > 0.0 && n * m <= 1.01 * TUNE_MAX_POINTS) {
        return None;
    }
    let pts = [n as usize, m as usize];
    let poses: [Vec<Pose>; 2] = [0, 1].map(|k| {
        let (s, (t0, t1)) = (&view.robots[movers[k].r], movers[k].motion);
        (0..pts[k])
            .map(|i| s.pose_at((t0 + i as f64 * dt).min(t1)))
            .collect()
    });
    let axes = [0, 1].map(|k| {
        let (s, (t0, _)) = (&view.robots[movers[k].r], movers[k].motion);
        let mut rest = rest_points(s, t0, dt, pts[k]);
        rest[0] = true;
        rest[pts[k] - 1] = true;
        Axis {
            start: t0,
            after: s.end - movers[k].motion.1,
            points: pts[k],
            rest,
        }
    });
    // How far any point of each body moves in the steps beside each grid point.
    let moved: [Vec<f64>; 2] = [0, 1].map(|k| {
        let step =
            |a: &Pose, b: &Pose| (b.pos - a.pos).norm() + reach[k] * (b.theta - a.theta).abs();
        let steps: Vec<f64> = poses[k].windows(2).map(|w| step(&w[0], &w[1])).collect();
        (0..pts[k])
            .map(|i| {
                let before = if i > 0 { steps[i - 1] } else { 0.0 };
                before.max(steps.get(i).copied().unwrap_or(0.0))
            })
            .collect()
    });
    let bodies = [x, y].map(|r| ctx.cell.rigid(r).pieces());
    // The grid rounds each leg's motion up by less than a step, and a hold lengthens the
    // robot's day by its duration: a timing that costs a step beyond the cap ends a held
    // robot at or after it (the search would drop the child). A robot not held ends as
    // now, below the cap in the search.
    let ends = movers.map(|v| view.robots[v.r].end);
    let bound = ctx.cap.max(ends[0]).max(ends[1]) + dt;
    for k in TUNE_MARGINS {
        // Between two grid points the distance falls by at most half of both bodies' moves
        // (Schwarzer, Saha & Latombe's bound on the two ends of a step): a point is free
        // when the bodies are that far apart, and δ more, both ends.
        let free = |i: usize, j: usize| {
            let margin = 2.0 * ctx.cell.delta + k * (moved[0][i] + moved[1][j]) / 2.0;
            let (a, b) = (poses[0][i], poses[1][j]);
            apart((bodies[0], a), (bodies[1], b), reach[0] + reach[1], margin)
        };
        // A wider margin frees no point: once no timing is found, none will be.
        let plan = coordinate(&axes, dt, bound, free)?;
        if let Some(child) = realise(ctx, view, side, &movers, &plan.holds, dt) {
            return Some(child);
        }
    }
    None
}

/// For each of `n` grid points from `t0` in steps of `dt`, whether the robot scheduled `s`
/// rests there, give or take half a step: a sample at rest (a waypoint, a piece's end) that
/// near, or a pause or a parking then.
fn rest_points(s: &RobotSchedule, t0: f64, dt: f64, n: usize) -> Vec<bool> {
    let mut rest = vec![false; n];
    let point = |t: f64| ((t - t0) / dt).round();
    let (lo, hi) = (t0 - dt / 2.0, t0 + (n as f64 - 0.5) * dt);
    let first = s.samples.partition_point(|p| p.t < lo);
    for p in s.samples[first..].iter().take_while(|p| p.t <= hi) {
        if p.vel.norm() == 0.0 && p.omega == 0.0 {
            let i = point(p.t).clamp(0.0, (n - 1) as f64) as usize;
            rest[i] = true;
        }
    }
    let still = |g: &&Segment| matches!(g.activity, Activity::Pause { .. } | Activity::Park { .. });
    for g in s.segments.iter().filter(still) {
        let (a, b) = (point(g.start).max(0.0), point(g.end).min((n - 1) as f64));
        if a <= b {
            rest[a as usize..=b as usize].fill(true);
        }
    }
    rest
}

/// Robot `r`'s leg in play at its segment `g`: the one it moves on or waits before, or
/// the next one when it is at its task; `None` when it is home for good.
fn mover(view: &View, r: usize, g: &Segment) -> Option<Mover> {
    let s = &view.robots[r];
    let m = match g.activity {
        Activity::Work(_) => g.leg? + 1,
        Activity::Done => return None,
        _ => g.leg?,
    };
    let of_leg = s.segments.iter().filter(|g| {
        g.leg == Some(m)
            && matches!(
                g.activity,
                Activity::Move { .. } | Activity::Pause { .. } | Activity::Park { .. }
            )
    });
    let motion = of_leg.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), g| {
        (lo.min(g.start), hi.max(g.end))
    });
    (motion.0 < motion.1).then_some(Mover { r, m, motion })
}

/// Whether bodies `a` and `b` (convex pieces, placed) are farther apart than `margin`;
/// `reach` is the sum of their radii (bounding discs decide the far pairs).
fn apart(
    (a, pa): (&[ConvexPolygon], Pose),
    (b, pb): (&[ConvexPolygon], Pose),
    reach: f64,
    margin: f64,
) -> bool {
    if (pa.pos - pb.pos).norm() > reach + margin {
        return true;
    }
    let tol = WalkTolerances::default();
    a.iter().all(|p| {
        let p = Posed::new(p, pa.pos.x, pa.pos.y, pa.theta);
        b.iter().all(|q| {
            let q = Posed::new(q, pb.pos.x, pb.pos.y, pb.theta);
            closest_features(&p, &q, None, &tol).distance > margin
        })
    })
}

/// The child of the holds `holds` (per robot, grid point and duration), when the checker
/// certifies the two changed legs clear of each other.
fn realise(
    ctx: &Ctx,
    view: &View,
    side: &Side,
    movers: &[Mover; 2],
    holds: &[Vec<(usize, f64)>; 2],
    dt: f64,
) -> Option<Child> {
    let mut legs = view.legs.clone();
    let mut changed: Vec<(usize, Arc<RobotSchedule>)> = Vec::new();
    let mut report = Vec::new();
    for (v, held) in movers.iter().zip(holds) {
        if held.is_empty() {
            continue;
        }
        let s = &view.robots[v.r];
        let timed: Vec<(f64, f64)> = held.iter().map(|&(i, d)| (i as f64 * dt, d)).collect();
        let (new, places) = with_holds(ctx, view, v, &timed, dt / 2.0)?;
        let rebuilt = ctx.rebuild(view, v.r, v.m, &new)?;
        report.extend(held.iter().zip(places).map(|(&(i, d), at)| TunedHold {
            robot: v.r,
            at: at.unwrap_or_else(|| s.pose_at(v.motion.0 + i as f64 * dt).pos),
            duration: d,
        }));
        legs = with_leg(&legs, v.r, v.m, new);
        changed.push((v.r, Arc::new(rebuilt)));
    }
    if changed.is_empty() {
        // The diagram finds the pair free as it is: the grid missed the contact.
        return None;
    }
    let now = |r: usize| {
        (changed.iter())
            .find(|c| c.0 == r)
            .map_or_else(|| view.robots[r].clone(), |c| c.1.clone())
    };
    let (xs, ys) = (now(side.x), now(side.y));
    let other = Side {
        x: side.y,
        y: side.x,
        sx: side.sy,
        sy: side.sx,
        t: side.t,
    };
    let t0 = leg_window(&view.robots[side.x], movers[0].m)
        .0
        .min(leg_window(&view.robots[side.y], movers[1].m).0);
    let t1 = (side.window_end(&xs, movers[0].m)).max(other.window_end(&ys, movers[1].m));
    let ok = clears(
        ctx.cell,
        (side.x, &xs),
        (side.y, &ys),
        (t0, t1),
        &ctx.opts.check,
    );
    if !ok {
        return None;
    }
    let leg_of = |v: &Mover| RemedyLeg {
        robot: v.r,
        leg: v.m,
        nodes: leg_nodes(view, v.r, v.m),
    };
    let (on, with) = (leg_of(&movers[0]), leg_of(&movers[1]));
    let kind = RemedyKind::Tune {
        with,
        holds: report,
    };
    Some(Child {
        legs,
        changed,
        remedy: Remedy::on(on.robot, on.leg, on.nodes, kind),
        // Offered with the others it made the conflict table's doorway-4 lose its schedule
        // within the budget; as a last resort none is lost (docs/benchmarks.md).
        last_resort: true,
    })
}

/// Leg `v.m` of robot `v.r` holding `d` at each `(τ, d)` of `holds` (τ: time into the leg's
/// motion as scheduled now, ascending), each at the point within `snap` of τ where the
/// robot rests (a hold at τ = 0 is a longer wait); with, for each hold made at a waypoint,
/// where that is (`None` where it stands anyway: its start, a pause).
fn with_holds(
    ctx: &Ctx,
    view: &View,
    v: &Mover,
    holds: &[(f64, f64)],
    snap: f64,
) -> Option<(Leg, Vec<Option<Vec2>>)> {
    let old = leg(view.legs, v.r, v.m);
    let mut wait = old.wait;
    let mut pieces = pieces_of(ctx, view, v.r, v.m)?;
    let mut places = vec![None; holds.len()];
    // From the last hold back, so that each cut leaves the earlier pieces' times as they are.
    for (h, &(tau, d)) in holds.iter().enumerate().rev() {
        if tau <= 0.0 {
            wait += d;
            continue;
        }
        let mut begun = 0.0;
        let (k, local) = pieces.iter().enumerate().find_map(|(k, p)| {
            let here = (tau < begun + p.duration()).then_some((k, tau - begun));
            begun += p.duration();
            here
        })?;
        let hold = Piece::Hold {
            duration: d,
            reason: HoldReason::Pause,
        };
        match pieces[k].clone() {
            Piece::Hold { duration, reason } => {
                pieces[k] = Piece::Hold {
                    duration: duration + d,
                    reason,
                }
            }
            Piece::Go { motion, scale } => {
                let u = at_rest_near(&motion.samples, local / scale, snap / scale)?;
                places[h] = motion.samples.iter().find(|p| p.t == u).map(|p| p.pos);
                if u <= 0.0 {
                    pieces.insert(k, hold);
                } else if u >= motion.duration {
                    pieces.insert(k + 1, hold);
                } else {
                    // At a waypoint: the two halves keep the timing of the whole.
                    let (before, after) =
                        split_chain(&motion.primitives, walked(&motion.samples, u))?;
                    let first = ctx.moves.timed(v.r, &before);
                    let second = ctx.moves.timed(v.r, &after);
                    let go = |motion| Piece::Go { motion, scale };
                    pieces.splice(k..=k, [go(first), hold, go(second)]);
                }
            }
        }
    }
    let new = Leg {
        wait,
        pieces: Some(pieces.into()),
    };
    Some((new, places))
}

/// The time of the sample nearest `u` within `snap` at which the robot rests (no speed, no
/// turn: a waypoint, a piece's ends).
fn at_rest_near(samples: &[Sample], u: f64, snap: f64) -> Option<f64> {
    let rest = samples
        .iter()
        .filter(|s| (s.t - u).abs() <= snap && s.vel.norm() == 0.0 && s.omega == 0.0)
        .min_by(|a, b| (a.t - u).abs().total_cmp(&(b.t - u).abs()));
    rest.map(|s| s.t)
}

/// The length of path G has walked by time `u` of a move (its samples lie on the path).
fn walked(samples: &[Sample], u: f64) -> f64 {
    let mut total = 0.0;
    for w in samples.windows(2) {
        if w[1].t <= u {
            total += (w[1].pos - w[0].pos).norm();
        } else {
            if u > w[0].t {
                let f = (u - w[0].t) / (w[1].t - w[0].t);
                total += ((w[1].pos - w[0].pos) * f).norm();
            }
            break;
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::super::context::TestCell;
    use super::*;

    /// Two robots of side 0.7 crossing at the origin at the same time: X from (-5, 0) to its
    /// task at (5, 0), Y from `y_home` to its task at (0, 5), by way of `obstacles`; X's
    /// task takes 9 s, Y's 1 s, so Y yields.
    fn crossing(y_home: (f64, f64), obstacles: &str) -> TestCell {
        let square = "[[-0.35, -0.35], [0.35, -0.35], [0.35, 0.35], [-0.35, 0.35]]";
        let text = format!(
            r#"{{"delta": 0.01, "robots": [
            {{"name": "X", "shape": {square}, "home": [-5, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1}},
            {{"name": "Y", "shape": {square}, "home": [{}, {}], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1}}],
            "obstacles": [{obstacles}],
            "tasks": [{{"name": "x", "at": [5, 0], "duration": 9, "robots": ["X"]}},
                      {{"name": "y", "at": [0, 5], "duration": 1, "robots": ["Y"]}}]}}"#,
            y_home.0, y_home.1
        );
        TestCell::new(&text, vec![vec![0], vec![1]])
    }

    /// The first collision of the test cell's two robots, as the remedies see it.
    fn tuned(test: &TestCell) -> Child {
        let view = test.view();
        let (xs, ys) = (&view.robots[0], &view.robots[1]);
        // Both on their first move; they meet near the middle of it.
        let t = (0..2000)
            .map(|k| k as f64 * 0.01)
            .find(|&t| (xs.pose_at(t).pos - ys.pose_at(t).pos).norm() < 0.7)
            .expect("the two meet");
        let at = |s: &RobotSchedule| {
            *s.segments
                .iter()
                .find(|g| g.start <= t && t < g.end)
                .unwrap()
        };
        let side = Side {
            x: 0,
            y: 1,
            sx: at(xs),
            sy: at(ys),
            t,
        };
        tune(&test.ctx(), &view, &side).expect("a timing of the two")
    }

    /// On straight paths the one that yields can rest only at its start: it waits there,
    /// little more than the least wait that clears (the grid's margin), and the two
    /// changed schedules are certified apart.
    #[test]
    fn on_straight_paths_the_yielding_robot_waits_at_its_start() {
        let test = crossing((0.0, -5.0), "");
        let child = tuned(&test);
        let RemedyKind::Tune { with, holds } = &child.remedy.kind else {
            panic!("a tuning");
        };
        assert_eq!((child.remedy.on.unwrap().robot, with.robot), (0, 1));
        assert_eq!(child.changed.len(), 1);
        assert_eq!(child.changed[0].0, 1, "Y yields: X has more to do");
        assert_eq!(holds.len(), 1);
        assert_eq!(holds[0].at, Vec2::new(0.0, -5.0), "at its home");
        let ys = &child.changed[0].1;
        let opts = &test.ctx().opts.check;
        assert!(clears(
            &test.cell,
            (0, &test.view().robots[0]),
            (1, ys),
            (0.0, 30.0),
            opts
        ));
        // The least wait that clears, to a hundredth: the grid's margin costs little more.
        let least = (1..1000).map(|k| k as f64 * 0.01).find(|&d| {
            let leg = Leg {
                wait: d,
                pieces: None,
            };
            let s = test.ctx().rebuild(&test.view(), 1, 0, &leg).unwrap();
            clears(
                &test.cell,
                (0, &test.view().robots[0]),
                (1, &s),
                (0.0, 30.0),
                opts,
            )
        });
        let (least, d) = (least.unwrap(), holds[0].duration);
        assert!(
            d >= least - 0.01 && d < least + 0.3,
            "waits {d}, least {least}"
        );
    }

    /// Y comes round a block whose corner is a waypoint: it holds there (as late as it can),
    /// not at home, and its move keeps its path.
    #[test]
    fn the_yielding_robot_holds_at_its_last_waypoint_short_of_the_crossing() {
        let block =
            r#"{"name": "b", "shape": [[-1.5, -3.5], [1.5, -3.5], [1.5, -3.0], [-1.5, -3.0]]}"#;
        let test = crossing((0.0, -5.0), block);
        let before = test.view().robots[1].path.clone();
        let child = tuned(&test);
        let RemedyKind::Tune { holds, .. } = &child.remedy.kind else {
            panic!("a tuning");
        };
        assert_eq!(child.changed.len(), 1);
        let (r, ys) = &child.changed[0];
        assert_eq!(*r, 1);
        assert_eq!(holds.len(), 1);
        // Out of home, round the block's corner (a waypoint), then straight to the task.
        let corner = before[1];
        assert!(corner.x > 1.5 && corner.y < -3.5, "{before:?}");
        assert_eq!(holds[0].at, corner, "{holds:?} {before:?}");
        assert_eq!(ys.path, before, "same path");
        let opts = &test.ctx().opts.check;
        assert!(clears(
            &test.cell,
            (0, &test.view().robots[0]),
            (1, ys),
            (0.0, 40.0),
            opts
        ));
    }

    #[test]
    fn the_walked_length_follows_the_samples() {
        let at = |t: f64, x: f64, v: f64| Sample {
            t,
            pos: Vec2::new(x, 0.0),
            vel: Vec2::new(v, 0.0),
            theta: 0.0,
            omega: 0.0,
        };
        let samples = [at(0.0, 0.0, 0.0), at(1.0, 1.0, 1.0), at(2.0, 3.0, 0.0)];
        assert_eq!(walked(&samples, 0.5), 0.5);
        assert_eq!(walked(&samples, 1.5), 2.0);
        assert_eq!(walked(&samples, 9.0), 3.0);
        // Rests near 1.9 within 0.2: the sample at 2; none within 0.05.
        assert_eq!(at_rest_near(&samples, 1.9, 0.2), Some(2.0));
        assert_eq!(at_rest_near(&samples, 1.9, 0.05), None);
        assert_eq!(at_rest_near(&samples, 1.1, 0.2), None); // moving at 1
    }
}
