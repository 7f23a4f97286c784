//! The robot that ends last, let through: a wait, hold or slowed motion of it that one
//! other robot alone keeps it from dropping is dropped, and that robot waits longer at the
//! start of one of its legs instead, where it still ends sooner than the makespan
//! (`tighten.rs` tries it once nothing else shortens).

use super::draft::Draft;
use super::shorten::{excess, slacks, with_excess, Slack};
use super::Search;
use crate::wcp::feedback::clearing::{clears, sure_contact};
use crate::wcp::legs::{leg, Leg};
use crate::wcp::schedule::RobotSchedule;

/// Shares of its room (up to the makespan) tried as the other robot's longer wait, least
/// first; then bisected [`BISECTIONS`] times.
const WAITS: [f64; 4] = [0.25, 0.5, 0.75, 0.97];
// A wait shifts the rest of the robot's plan by as much: under 1 of its room, it still ends
// before the makespan.
const _: () = {
    let mut k = 0;
    while k < WAITS.len() {
        assert!(WAITS[k] > 0.0 && WAITS[k] < 1.0);
        k += 1;
    }
};
/// Bisections between the wait kept and the share below it.
const BISECTIONS: usize = 3;

/// Robot `r` let through by robot `y`: `r`'s slack cut, `y`'s leg `m` waited longer.
pub(super) struct GiveWay {
    pub(super) r: usize,
    pub(super) slack: Slack,
    /// `r`'s slack before and after (none).
    pub(super) cut: (f64, f64),
    pub(super) r_plan: RobotSchedule,
    pub(super) y: usize,
    pub(super) m: usize,
    /// `y`'s wait at the start of leg `m`, before and after.
    pub(super) wait: (f64, f64),
    pub(super) y_leg: Leg,
    pub(super) y_plan: RobotSchedule,
}

impl Search<'_> {
    /// The robot that ends last let through by another (see the module documentation).
    pub(super) fn give_way(&self, draft: &Draft) -> Option<GiveWay> {
        let robots = draft.robots;
        let makespan = robots.iter().map(|s| s.end).fold(0.0, f64::max);
        let r = (0..robots.len()).find(|&r| robots[r].end == makespan)?;
        let (cell, opts) = (self.cell, &self.opts.check);
        for slack in slacks(draft.legs, r) {
            let before = excess(draft.legs, r, slack);
            let Some(t0) = (robots[r].segments.iter())
                .find(|g| g.leg == Some(slack.leg))
                .map(|g| g.start)
            else {
                continue;
            };
            let leg = with_excess(draft.legs, r, slack, 0.0);
            let Some(s) = self.rebuilt(draft, r, slack.leg, leg) else {
                continue;
            };
            let window = |y: usize| (t0, s.end.max(robots[y].end));
            let others = || (0..robots.len()).filter(|&y| y != r);
            // Only where one robot alone is in the way: it alone must wait. Two seen in the
            // way at a sample instant settle it without a check.
            let mut sure =
                others().filter(|&y| sure_contact(cell, (r, &s), (y, &robots[y]), window(y)));
            if let (Some(_), Some(_)) = (sure.next(), sure.next()) {
                continue;
            }
            let mut blockers =
                others().filter(|&y| !clears(cell, (r, &s), (y, &robots[y]), window(y), opts));
            let (Some(y), None) = (blockers.next(), blockers.next()) else {
                continue;
            };
            if let Some((m, wait, y_leg, y_plan)) = self.waited(draft, (r, &s, t0), y, makespan) {
                return Some(GiveWay {
                    r,
                    slack,
                    cut: (before, 0.0),
                    r_plan: s,
                    y,
                    m,
                    wait,
                    y_leg,
                    y_plan,
                });
            }
        }
        None
    }

    /// The least longer wait of robot `y` at the start of one of its legs under way while
    /// robot `r`'s new plan `s` runs (from `t0`) that clears `y` of `s` and of every other
    /// robot from that leg on, and ends `y` before `makespan`: the leg, its wait before and
    /// after, the new leg and `y`'s new plan.
    fn waited(
        &self,
        draft: &Draft,
        (r, s, t0): (usize, &RobotSchedule, f64),
        y: usize,
        makespan: f64,
    ) -> Option<(usize, (f64, f64), Leg, RobotSchedule)> {
        let robots = draft.robots;
        let room = makespan - robots[y].end;
        if room <= 0.0 {
            return None;
        }
        let (cell, opts) = (self.cell, &self.opts.check);
        let legs_of_y = (robots[y].segments.iter())
            .filter(|g| g.end > t0 && g.start < s.end)
            .filter_map(|g| g.leg);
        let mut tried = Vec::new();
        for m in legs_of_y {
            if tried.contains(&m) {
                continue;
            }
            tried.push(m);
            let old = leg(draft.legs, y, m).clone();
            let Some(t0y) = (robots[y].segments.iter())
                .find(|g| g.leg == Some(m))
                .map(|g| g.start)
            else {
                continue;
            };
            let attempt = |w: f64| -> Option<(Leg, RobotSchedule)> {
                let new = Leg {
                    wait: old.wait + w,
                    ..old.clone()
                };
                // Later by `w`, so still before the makespan.
                let p = self.rebuilt(draft, y, m, new.clone())?;
                let from = t0.min(t0y);
                let apart = clears(cell, (y, &p), (r, s), (from, p.end.max(s.end)), opts);
                let others = (0..robots.len()).filter(|&z| z != y && z != r).all(|z| {
                    clears(
                        cell,
                        (y, &p),
                        (z, &robots[z]),
                        (t0y, p.end.max(robots[z].end)),
                        opts,
                    )
                });
                (apart && others).then_some((new, p))
            };
            let Some((k, mut kept)) =
                (WAITS.iter().enumerate()).find_map(|(k, f)| Some((k, attempt(f * room)?)))
            else {
                continue;
            };
            let mut below = k.checked_sub(1).map_or(0.0, |j| WAITS[j] * room);
            let mut w = WAITS[k] * room;
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (below + w);
                match attempt(mid) {
                    Some(got) => (w, kept) = (mid, got),
                    None => below = mid,
                }
            }
            let (new, p) = kept;
            return Some((m, (old.wait, new.wait), new, p));
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wcp::legs::{default_legs, with_leg};
    use crate::wcp::options::SolveOptions;
    use crate::wcp::prepare::{prepare, StageTimes};
    use std::sync::Arc;

    /// Every robot's body and limits: a square of 0.7.
    const SQUARE: &str = r#""shape": [[-0.35, -0.35], [0.35, -0.35], [0.35, 0.35], [-0.35, 0.35]],
             "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5"#;

    /// X crosses from (-5, 0) to its task at (5, 0) and back; Y goes from (0, -5) to its
    /// task at (0, 5), 9 s long, after a wait of 4 s at home that lets X by; Z, when given,
    /// goes from its home to its task and back.
    fn cell(z: Option<([f64; 2], [f64; 2])>) -> String {
        let mut robots = vec![
            format!(r#"{{"name": "X", "home": [-5, 0, 0], {SQUARE}}}"#),
            format!(r#"{{"name": "Y", "home": [0, -5, 0], {SQUARE}}}"#),
        ];
        let mut tasks = vec![
            r#"{"name": "x", "at": [5, 0, 0], "duration": 1.0, "robots": ["X"]}"#.to_owned(),
            r#"{"name": "y", "at": [0, 5, 0], "duration": 9.0, "robots": ["Y"]}"#.to_owned(),
        ];
        if let Some((home, at)) = z {
            let [(hx, hy), (ax, ay)] = [home, at].map(|p| (p[0], p[1]));
            robots.push(format!(
                r#"{{"name": "Z", "home": [{hx}, {hy}, 0], {SQUARE}}}"#
            ));
            tasks.push(format!(
                r#"{{"name": "z", "at": [{ax}, {ay}, 0], "duration": 1.0, "robots": ["Z"]}}"#
            ));
        }
        format!(
            r#"{{"delta": 0.01, "robots": [{}], "tasks": [{}]}}"#,
            robots.join(", "),
            tasks.join(", ")
        )
    }

    /// What [`Search::give_way`] makes of the certified schedule of `cell(z)`, and whether
    /// what it gives keeps every pair of robots apart (each robot on its new plan).
    fn given_way(z: Option<([f64; 2], [f64; 2])>) -> (Option<GiveWay>, bool) {
        let n = if z.is_some() { 3 } else { 2 };
        given_way_in(&cell(z), (0..n).map(|r| vec![r]).collect(), (1, 0, 4.0))
    }

    /// The same for the schedule of the cell `json` where robot `r` does the tasks
    /// `routes[r]` (indices in the file) and `waiter` waits `wait` before its leg `leg`.
    fn given_way_in(
        json: &str,
        routes: Vec<Vec<usize>>,
        (waiter, leg, wait): (usize, usize, f64),
    ) -> (Option<GiveWay>, bool) {
        let cell = crate::cell::parse_cell(json, "test.json".as_ref())
            .unwrap()
            .cell;
        let opts = SolveOptions::default();
        let prepared = prepare(&cell, &opts, &()).unwrap();
        let mut search = Search::new(&cell, &prepared, &opts, StageTimes::default(), 0.0);
        let n = cell.robots.len();
        let wait = Leg { wait, pieces: None };
        let legs = with_leg(&default_legs(n), waiter, leg, wait);
        let build =
            |r: usize| RobotSchedule::build(&cell, r, &routes[r], &legs[r], &prepared.moves);
        let robots: Vec<Arc<RobotSchedule>> = (0..n).map(|r| Arc::new(build(r).unwrap())).collect();
        let root = search.add_root(&routes).unwrap().unwrap();
        let node = super::super::Node::by_hand(root, &routes, legs.clone(), robots.clone());
        let waits = search.add(node);
        search.check_all(&[waits], &());
        assert_eq!(search.best, Some(waits), "the wait lets the others by");
        let draft = Draft {
            id: waits,
            routes: &routes,
            legs: &legs,
            robots: &robots,
        };
        let Some(g) = search.give_way(&draft) else {
            return (None, true);
        };
        let mut now: Vec<&RobotSchedule> = robots.iter().map(|s| &**s).collect();
        (now[g.r], now[g.y]) = (&g.r_plan, &g.y_plan);
        let apart = (0..n).all(|a| {
            (a + 1..n).all(|b| clears(&cell, (a, now[a]), (b, now[b]), (0.0, 60.0), &opts.check))
        });
        (Some(g), apart)
    }

    /// Y, last, is let through by X alone: its wait cut, X's longer, X still ending sooner.
    #[test]
    fn one_robot_in_the_way_waits_for_the_last() {
        let (g, apart) = given_way(None);
        let g = g.expect("X lets Y through");
        assert!(apart);
        assert_eq!((g.r, g.y, g.m), (1, 0, 0));
        assert!(
            g.cut.1 < g.cut.0 && g.wait.1 > g.wait.0,
            "{:?} {:?}",
            g.cut,
            g.wait
        );
        assert!(g.y_plan.end < g.r_plan.end + g.cut.0 - g.cut.1);
    }

    /// With Z, both X and Z are in Y's way when Y does not wait at all: neither is asked
    /// to let Y through alone (Y would still meet the other); a shorter wait that clears
    /// both is the other shortenings' business. Z crosses Y's way while Y is at a sample
    /// (settled without a check), or, a metre to the west, only between samples.
    #[test]
    fn a_robot_is_let_through_only_where_one_alone_is_in_its_way() {
        for z in [([-3.0, -2.0], [3.0, -2.0]), ([-4.0, -2.0], [2.0, -2.0])] {
            let (g, apart) = given_way(Some(z));
            assert!(apart, "{z:?}");
            assert!(g.is_none(), "{z:?}: {:?}", g.map(|g| (g.cut, g.y, g.wait)));
        }
    }

    /// Z crosses X's home twice, on its way to and from its task beside it: X let through
    /// by waiting longer at home only where Z does not run into it there.
    #[test]
    fn the_robot_that_waits_stays_clear_of_the_others() {
        let (_, apart) = given_way(Some(([-5.0, -1.5], [-5.0, 1.5])));
        assert!(apart);
    }

    /// X (from (-5, 0) to (5, 0) and back) crosses Y's way home from its first task, and Y
    /// waits 2 s there; Z passes over X's task place 1.3-2.8 s after X left it, before Y's
    /// wait starts. Without Z, X waits at its task for Y instead; with Z it cannot (Z would
    /// run into it), and the check of X against Z must start where X's wait does, not
    /// where Y's slack does.
    #[test]
    fn the_robot_that_waits_is_checked_from_its_own_wait() {
        let json = |with_z: bool| {
            let mut robots = vec![
                format!(r#"{{"name": "X", "home": [-5, 0, 0], {SQUARE}}}"#),
                format!(r#"{{"name": "Y", "home": [0, 1.5, 0], {SQUARE}}}"#),
            ];
            let mut tasks = vec![
                r#"{"name": "x", "at": [5, 0, 0], "duration": 1.0, "robots": ["X"]}"#,
                r#"{"name": "y1", "at": [0, -1.2, 0], "duration": 12.0, "robots": ["Y"]}"#,
                r#"{"name": "y2", "at": [0, 8, 0], "duration": 1.0, "robots": ["Y"]}"#,
            ];
            if with_z {
                robots.push(format!(
                    r#"{{"name": "Z", "home": [5, -13.3, 0], {SQUARE}}}"#
                ));
                tasks.push(r#"{"name": "z", "at": [5, 1.5, 0], "duration": 1.0, "robots": ["Z"]}"#);
            }
            format!(
                r#"{{"delta": 0.01, "robots": [{}], "tasks": [{}]}}"#,
                robots.join(", "),
                tasks.join(", ")
            )
        };
        let routes = |with_z: bool| {
            let mut r = vec![vec![0], vec![1, 2]];
            if with_z {
                r.push(vec![3]);
            }
            r
        };
        let (g, apart) = given_way_in(&json(false), routes(false), (1, 1, 2.0));
        let g = g.expect("without Z, X lets Y through");
        assert!(apart);
        assert_eq!((g.r, g.y, g.m), (1, 0, 1));
        let (g, apart) = given_way_in(&json(true), routes(true), (1, 1, 2.0));
        assert!(apart, "X and Z kept apart");
        assert!(g.is_none(), "{:?}", g.map(|g| (g.y, g.m, g.wait)));
    }
}
