//! The coordination diagram of two robots on fixed paths (O'Donnell & Lozano-Pérez, ICRA
//! 1989; Siméon, Leroy & Laumond, IEEE T-RA 18(1), 2002): each robot's progress along its
//! own timed motion is an axis, the pairs of progresses at which the two bodies come closer
//! than a margin are forbidden, and a timing of the pair is a monotone path from the start
//! corner to the end corner.
//!
//! Here the axes are each motion's own time on a grid of one step `dt` for both, so that a
//! diagonal step (both robots go on as planned) takes `dt` as either axis step does. A robot
//! may hold only at the points where its motion rests anyway (its start, its waypoints),
//! so that holding keeps the motion model and the timing of the rest of the move. Moves
//! only go up and right, so one sweep in grid order gives the earliest arrival at every
//! point (where a pair that must wait for a robot's start cannot hold, a later arrival
//! could have gone on: the sweep keeps the earliest, a small loss). The answer minimises the later of the two robots'
//! finishes, each counted with what the robot still has to do after this motion, then the
//! earlier sum of the two. A robot holds as late and as close as the other's motion allows:
//! among equal arrivals at a point, the way that got further sooner (the larger sum of
//! progress over its points) is kept.

/// One robot's axis: its motion's grid points, where it may hold, and when it may start.
#[derive(Clone, Debug)]
pub(super) struct Axis {
    /// Wall time before which the robot stays at grid point 0 (when its motion starts).
    pub start: f64,
    /// What the robot still does after this motion: its finish is counted with it.
    pub after: f64,
    /// Grid points, at least 2: point `k` at `k·dt` of motion time, the last at the end.
    pub points: usize,
    /// Whether the robot may hold at each point (it rests there anyway); point 0 and the
    /// last always.
    pub rest: Vec<bool>,
}

/// A timing of the pair: for each robot, where it holds (grid point) and how long.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Coordinated {
    /// `holds[r]`: robot `r`'s holds in grid order, each `(grid point, duration)`; a hold at
    /// point 0 is a later start. Holds at a robot's last point (done) are not listed.
    pub holds: [Vec<(usize, f64)>; 2],
    /// When each robot reaches its last point.
    pub finish: [f64; 2],
}

/// A way to the end: its cost (the later finish with what follows, in millionths of a
/// step), the sum of the two finishes, where the first robot done is done, and the finishes.
#[derive(Clone, Copy)]
struct End {
    cost: i64,
    sum: f64,
    at: (usize, usize),
    finish: [f64; 2],
}

/// A step of the diagram: which robots advance one grid point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Step {
    Both,
    First,
    Second,
}

impl Step {
    fn moves(self) -> [bool; 2] {
        match self {
            Step::Both => [true, true],
            Step::First => [true, false],
            Step::Second => [false, true],
        }
    }
}

/// The best timing of the pair through the diagram of `axes` with grid step `dt`, where
/// `free(i, j)` tells whether the first robot at point `i` and the second at point `j` are
/// apart by the margin; `None` when every monotone path is blocked, or costs `bound` or
/// more (the later finish with what follows): a point from which neither robot can end
/// sooner is not walked on, nor its freedom asked.
pub(super) fn coordinate(
    axes: &[Axis; 2],
    dt: f64,
    bound: f64,
    free: impl Fn(usize, usize) -> bool,
) -> Option<Coordinated> {
    let (n, m) = (axes[0].points, axes[1].points);
    debug_assert!(n >= 2 && m >= 2 && dt > 0.0);
    let at = |i: usize, j: usize| i * m + j;
    // Each point's freedom, asked once, only where a path could get to.
    let mut known: Vec<Option<bool>> = vec![None; n * m];
    let mut is_free = |i: usize, j: usize| *known[at(i, j)].get_or_insert_with(|| free(i, j));
    let start = axes[0].start.min(axes[1].start);
    // The least cost of a way through (i, j) reached at t: each robot's steps left, then
    // what follows its leg.
    let late = |t: f64, i: usize, j: usize| {
        let left = |k: usize, p: usize| t + (axes[k].points - 1 - p) as f64 * dt + axes[k].after;
        left(0, i).max(left(1, j)) >= bound
    };
    if late(start, 0, 0) || !is_free(0, 0) {
        return None;
    }
    // Earliest arrival at each point, the progress made on the way, and the last step.
    let mut arrival = vec![f64::INFINITY; n * m];
    let mut progress = vec![0usize; n * m];
    let mut came: Vec<Option<Step>> = vec![None; n * m];
    arrival[0] = start;
    // Leaving (i, j) by `step` no earlier than the arrival there nor the movers' starts.
    // `None` when a robot that does not move cannot hold, or the pair cannot wait for a
    // start.
    let depart = |arrival: &[f64], (i, j): (usize, usize), step: Step| -> Option<f64> {
        let [mx, my] = step.moves();
        let (rx, ry) = (axes[0].rest[i], axes[1].rest[j]);
        if (!mx && !rx) || (!my && !ry) {
            return None;
        }
        let a = arrival[at(i, j)];
        let mut t = a;
        if mx && i == 0 {
            t = t.max(axes[0].start);
        }
        if my && j == 0 {
            t = t.max(axes[1].start);
        }
        (t == a || (rx && ry)).then_some(t)
    };
    // The last column and row are entered, not walked: a robot done holds, and the other's
    // way to its end is the tail counted below.
    for i in 0..n {
        for j in 0..m {
            if (i, j) == (0, 0) {
                continue;
            }
            let last = (i == n - 1, j == m - 1);
            let mut best: Option<(f64, usize, Step)> = None;
            let steps = [
                (
                    Step::Both,
                    i > 0 && j > 0,
                    (i.wrapping_sub(1), j.wrapping_sub(1)),
                ),
                (Step::First, i > 0 && !last.1, (i.wrapping_sub(1), j)),
                (Step::Second, j > 0 && !last.0, (i, j.wrapping_sub(1))),
            ];
            for (step, ok, from) in steps {
                if !ok || !arrival[at(from.0, from.1)].is_finite() {
                    continue;
                }
                let Some(t) = depart(&arrival, from, step) else {
                    continue;
                };
                let t = t + dt;
                let made = progress[at(from.0, from.1)] + i + j;
                if best.is_none_or(|(b, p, _)| t < b || (t == b && made > p)) {
                    best = Some((t, made, step));
                }
            }
            if let Some((t, made, step)) = best {
                if !late(t, i, j) && is_free(i, j) {
                    arrival[at(i, j)] = t;
                    progress[at(i, j)] = made;
                    came[at(i, j)] = Some(step);
                }
            }
        }
    }
    // The ends: one robot done first (the other then goes on alone), or both at once.
    // Costs summed along different ways differ in their last bits: they are compared in
    // millionths of a step.
    let tie = 1e-6 * dt;
    let mut ends: Vec<End> = Vec::new();
    let mut consider = |at: (usize, usize), finish: [f64; 2]| {
        let cost = (finish[0] + axes[0].after).max(finish[1] + axes[1].after);
        ends.push(End {
            cost: (cost / tie).round() as i64,
            sum: finish[0] + finish[1],
            at,
            finish,
        });
    };
    let corner = arrival[at(n - 1, m - 1)];
    if corner.is_finite() {
        consider((n - 1, m - 1), [corner, corner]);
    }
    for j in 0..m - 1 {
        let fx = arrival[at(n - 1, j)];
        if fx.is_finite() && (j + 1..m).all(|k| is_free(n - 1, k)) {
            let go = if j == 0 { fx.max(axes[1].start) } else { fx };
            consider((n - 1, j), [fx, go + (m - 1 - j) as f64 * dt]);
        }
    }
    for i in 0..n - 1 {
        let fy = arrival[at(i, m - 1)];
        if fy.is_finite() && (i + 1..n).all(|k| is_free(k, m - 1)) {
            let go = if i == 0 { fy.max(axes[0].start) } else { fy };
            consider((i, m - 1), [go + (n - 1 - i) as f64 * dt, fy]);
        }
    }
    let &End {
        at: end, finish, ..
    } = (ends.iter()).min_by(|a, b| a.cost.cmp(&b.cost).then(a.sum.total_cmp(&b.sum)))?;
    let cost = (finish[0] + axes[0].after).max(finish[1] + axes[1].after);
    if cost >= bound {
        return None;
    }
    // Back from the end to the start, then forward to time the holds.
    let mut steps = Vec::new();
    let (mut i, mut j) = end;
    while (i, j) != (0, 0) {
        let step = came[at(i, j)].expect("a reached point has a step");
        steps.push(step);
        let [mx, my] = step.moves();
        (i, j) = (i - mx as usize, j - my as usize);
    }
    steps.reverse();
    // The tail: the robot not done goes on alone.
    let tail = if end.0 == n - 1 {
        (Step::Second, m - 1 - end.1)
    } else {
        (Step::First, n - 1 - end.0)
    };
    steps.extend(std::iter::repeat_n(tail.0, tail.1));
    let mut holds: [Vec<(usize, f64)>; 2] = [Vec::new(), Vec::new()];
    // Where each robot is, and since when it could have gone on.
    let mut point = [0usize, 0usize];
    let mut since = [axes[0].start, axes[1].start];
    let mut t = start;
    for step in steps {
        let mv = step.moves();
        let mut leave = t;
        for r in 0..2 {
            if mv[r] && point[r] == 0 {
                leave = leave.max(axes[r].start);
            }
        }
        for r in 0..2 {
            if mv[r] {
                let held = leave - since[r];
                if held > 1e-12 {
                    holds[r].push((point[r], held));
                }
                point[r] += 1;
                since[r] = leave + dt;
            }
        }
        t = leave + dt;
    }
    debug_assert_eq!(point, [n - 1, m - 1]);
    Some(Coordinated { holds, finish })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An axis that may hold anywhere.
    fn axis(start: f64, points: usize) -> Axis {
        Axis {
            start,
            after: 0.0,
            points,
            rest: vec![true; points],
        }
    }

    /// Nothing in the way: both go as planned, no hold.
    #[test]
    fn a_free_diagram_is_crossed_on_the_diagonal() {
        let c = coordinate(
            &[axis(0.0, 11), axis(2.0, 6)],
            1.0,
            f64::INFINITY,
            |_, _| true,
        )
        .unwrap();
        assert_eq!(c.holds, [vec![], vec![]]);
        assert_eq!(c.finish, [10.0, 7.0]);
    }

    /// Two robots crossing the same point: its cell is forbidden; the one whose delay costs
    /// less holds, as late as it can (just before the forbidden cells), as long as needed.
    #[test]
    fn a_crossing_is_passed_by_the_cheaper_hold_as_late_as_allowed() {
        // Both pass point 5 of their axes at once.
        let blocked = |i: usize, j: usize| (4..=6).contains(&i) && (4..=6).contains(&j);
        let mut axes = [axis(0.0, 11), axis(0.0, 11)];
        axes[0].after = 5.0; // the first has more to do afterwards: the second yields
        let c = coordinate(&axes, 1.0, f64::INFINITY, |i, j| !blocked(i, j)).unwrap();
        // The second goes on to point 3 (the last free before the first reaches 4) and
        // leaves it as the first leaves 6 (the steps' end points decide; the margin of
        // `free` covers what lies between).
        assert_eq!(c.holds[0], vec![]);
        assert_eq!(c.holds[1], vec![(3, 3.0)]);
        assert_eq!(c.finish, [10.0, 13.0]);
        // The other way round when the second has more to do.
        axes[0].after = 0.0;
        axes[1].after = 5.0;
        let c = coordinate(&axes, 1.0, f64::INFINITY, |i, j| !blocked(i, j)).unwrap();
        assert_eq!(
            (c.holds[0].clone(), c.holds[1].clone()),
            (vec![(3, 3.0)], vec![])
        );
    }

    /// A bound drops only the timings that cost it or more, and spares the freedom of the
    /// points past which neither robot can end sooner.
    #[test]
    fn a_bound_drops_only_the_timings_that_reach_it() {
        let blocked = |i: usize, j: usize| (4..=6).contains(&i) && (4..=6).contains(&j);
        let mut axes = [axis(0.0, 11), axis(0.0, 11)];
        axes[0].after = 5.0;
        let asked = std::cell::Cell::new(0);
        let free = |i: usize, j: usize| {
            asked.set(asked.get() + 1);
            !blocked(i, j)
        };
        let open = coordinate(&axes, 1.0, f64::INFINITY, free).unwrap();
        let all = asked.replace(0);
        // It costs 15: the first ends at 10 with 5 to do, the second at 13.
        let near = coordinate(&axes, 1.0, 15.0 + 1e-9, free).unwrap();
        assert_eq!(near, open);
        assert!(asked.replace(0) < all);
        assert!(coordinate(&axes, 1.0, 15.0, free).is_none());
        assert!(asked.get() < all);
    }

    /// A robot that starts later is no hold of its own; the other holds only where it must.
    #[test]
    fn a_later_start_is_waited_for_only_where_it_matters() {
        let axes = [axis(0.0, 6), axis(5.0, 6)];
        // The first's point 3 meets the second's way from its point 3 on: the first passes
        // it while the second has not started.
        let c = coordinate(&axes, 1.0, f64::INFINITY, |i, j| !(i == 3 && j >= 3)).unwrap();
        assert_eq!(c.holds, [vec![], vec![]]);
        assert_eq!(c.finish, [5.0, 10.0]);
        // It meets the second's way up to point 2: the first holds at 2 until the second,
        // starting at 5, has passed (point 3 at 8).
        let c = coordinate(&axes, 1.0, f64::INFINITY, |i, j| !(i == 3 && j <= 2)).unwrap();
        assert_eq!(c.holds, [vec![(2, 5.0)], vec![]]);
        assert_eq!(c.finish, [10.0, 10.0]);
    }

    /// A robot holds only where it rests: the nearest such point short of the crossing.
    #[test]
    fn a_robot_holds_only_where_it_rests() {
        let blocked = |i: usize, j: usize| (4..=6).contains(&i) && (4..=6).contains(&j);
        let mut axes = [axis(0.0, 11), axis(0.0, 11)];
        axes[0].after = 5.0;
        axes[1].rest = (0..11).map(|j| j % 2 == 0 && j != 2).collect(); // 0, 4, 6, 8, 10
        let c = coordinate(&axes, 1.0, f64::INFINITY, |i, j| !blocked(i, j)).unwrap();
        // Not at 3 (moving there) nor 2: from its start, as late as it can still go on
        // without stopping short of the crossing.
        assert_eq!(c.holds, [vec![], vec![(0, 3.0)]]);
        assert_eq!(c.finish, [10.0, 13.0]);
        // With more to do afterwards, the second goes first; the first holds at its last
        // rest short of the crossing (3), not at its start.
        (axes[0].after, axes[1].after) = (0.0, 5.0);
        axes[0].rest = (0..11).map(|i| i == 0 || i == 3 || i == 10).collect();
        let c = coordinate(&axes, 1.0, f64::INFINITY, |i, j| !blocked(i, j)).unwrap();
        assert_eq!(c.holds, [vec![(3, 3.0)], vec![]]);
    }

    /// A robot blocked at its start by the other's end forever: no timing.
    #[test]
    fn a_blocked_end_has_no_timing() {
        // The first's end pose meets the second's whole way: the second can never finish
        // after it, and cannot finish before it either (its end meets the first's way).
        let c = coordinate(&[axis(0.0, 5), axis(0.0, 5)], 1.0, f64::INFINITY, |i, j| {
            i != 4 && j != 4
        });
        assert!(c.is_none());
        let c = coordinate(&[axis(0.0, 5), axis(0.0, 5)], 1.0, f64::INFINITY, |i, j| {
            (i, j) != (0, 0)
        });
        assert!(c.is_none());
    }
}
