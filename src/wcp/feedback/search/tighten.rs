//! The answer's slack, shortened as far as the other robots allow.
//!
//! Each remedy makes the least change that clears one collision, given the schedule it
//! answers; changes made later on the same branch move the other robots, so an early wait
//! may no longer need all of its length, and an early detour may no longer be needed at
//! all. Once the search ends, every schedule that was the best when found has its slack
//! shortened: ways that remedies changed (detours, stays at parking poses, pauses, a
//! convoy's lap), waits, holds and motions run slower than planned. Robot by robot (the one
//! that ends last first, since a robot that goes sooner may leave room for it), in passes
//! until none shortens: a robot's first leg in time order whose changed way can give way to
//! its planned move again does so (`straighten.rs`); else its first slack in time order
//! that can be shortened is cut to the least of a few fractions of it, then bisected, after
//! which the checker proves that robot clear of every other from the leg on (`shorten.rs`). A way may
//! also be given back for a longer wait at the leg's start; such a wait holds room that the
//! others' shortening might have used, or leaves them room they need, so each schedule is
//! shortened twice, those waits tried only once nothing else shortens and from the start,
//! and the shorter kept. Once nothing shortens, the robot that ends last may be let through
//! by another that waits longer instead (`give_way.rs`), and the passes go on. The answer is the shortest of all of them, shortened or not: one
//! found earlier may shorten further. A planned move is certified clear of the fixtures
//! when planned, and the other changes keep paths (only when a robot rests where it already
//! rests, and how fast it runs its path, change), so the fixtures need no new check (the
//! result is checked whole anyway).

use super::draft::Draft;
use super::shorten::{kind, with_excess, Slack};
use super::{Node, Outcome, Search, Status};
use crate::wcp::feedback::outcome::{Remedy, RemedyKind, Shortened, Shortening};
use crate::wcp::legs::{with_leg, Legs};
use crate::wcp::prepare::Progress;
use crate::wcp::schedule::{route_nodes, RobotSchedule, Schedule};
use rayon::prelude::*;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Passes over the robots at most: each shortens some slack, or is the last.
const MAX_PASSES: usize = 16;
/// Shortenings at most, in all: each costs a few pair checks of one robot.
const MAX_STEPS: usize = 256;

/// What a shortening did, in order, for the report.
struct Notes<'n> {
    routes: &'n [Vec<usize>],
    shortened: Vec<Shortened>,
    /// The slack each entry of `shortened` changed (none for a way straightened).
    which: Vec<Option<(usize, Slack)>>,
}

impl Notes<'_> {
    /// Robot `r`'s leg `m` changed from `before` to `after` (`kind`, of slack `slack`):
    /// slack changed again is one entry, from its first length to its last.
    fn note(
        &mut self,
        r: usize,
        m: usize,
        slack: Option<Slack>,
        kind: Shortening,
        (before, after): (f64, f64),
    ) {
        let key = slack.map(|s| (r, s));
        if let Some(k) = key.and_then(|key| self.which.iter().position(|&w| w == Some(key))) {
            self.shortened[k].after = after;
            return;
        }
        let nodes = route_nodes(&self.routes[r]);
        self.which.push(key);
        self.shortened.push(Shortened {
            robot: r,
            leg: m,
            nodes: (nodes[m], nodes[(m + 1).min(nodes.len() - 1)]),
            kind,
            before,
            after,
        });
    }

    /// Robot `r`'s `slack` in `legs` cut from `before` to `after` (an excess), reported as
    /// the robot does it: a slowed motion by its factor.
    fn note_slack(&mut self, legs: &Legs, r: usize, slack: Slack, (before, after): (f64, f64)) {
        let kind = kind(legs, r, slack);
        let lengths = match kind {
            Shortening::Slow => (1.0 + before, 1.0 + after),
            _ => (before, after),
        };
        self.note(r, slack.leg, Some(slack), kind, lengths);
    }
}

/// A certified schedule's slack shortened, and the checker's verdict on it.
struct Tightened {
    legs: Legs,
    robots: Vec<Arc<RobotSchedule>>,
    /// What was shortened, in order.
    shortened: Vec<Shortened>,
    outcome: Outcome,
    free: bool,
    /// Time spent checking the result, and in all.
    checking: Duration,
    elapsed: Duration,
}

impl Search<'_> {
    /// Shortens the slack of every schedule that was the best when found: the answer is
    /// the shortest of them all, shortened or not (one found earlier may shorten more).
    pub(super) fn tighten_all(&mut self, progress: &dyn Progress) {
        // Ways given back for a wait late, then early: each order wins on some cells. Every
        // shortening reads only its own schedule, so all are made at once and taken in
        // order, the answer first (under a time limit, the one most likely to give it).
        // Without waits the two orders are one (`tighten`'s `waiting` stays false).
        let orders: &[bool] = match self.opts.search.remedies.wait {
            true => &[false, true],
            false => &[false],
        };
        let jobs: Vec<(usize, usize, bool)> = (self.incumbents.iter().rev())
            .flat_map(|&(id, found_at)| orders.iter().map(move |&early| (id, found_at, early)))
            .collect();
        let deadline = self.prepared.deadline;
        let clock = Instant::now();
        let made: Vec<Option<Tightened>> = jobs
            .par_iter()
            .map(|&(id, _, early)| match deadline {
                Some(d) if Instant::now() >= d => None,
                _ => self.tighten(id, early),
            })
            .collect();
        // The wall time, shared between the stages as the jobs spent theirs.
        let spent = |f: fn(&Tightened) -> Duration| made.iter().flatten().map(f).sum::<Duration>();
        let (checking, all) = (spent(|t| t.checking), spent(|t| t.elapsed));
        let share = checking.as_secs_f64() / all.as_secs_f64().max(f64::MIN_POSITIVE);
        let wall = clock.elapsed();
        self.times.checking += wall.mul_f64(share);
        self.times.scheduling += wall.mul_f64(1.0 - share);
        for ((id, found_at, _), tightened) in jobs.into_iter().zip(made) {
            let Some(child) = tightened.and_then(|t| self.add_tightened(id, t)) else {
                continue;
            };
            let best = self.best.expect("an incumbent is certified");
            let (m, bound) = (self.nodes[child].makespan, self.nodes[best].makespan);
            // Shortened slack brings robots home no later: the answer's own shortening
            // wins a tie. Only a new best is a round heard: the last heard is the answer.
            if m < bound * (1.0 - super::SAME_MAKESPAN) || (id == best && m <= bound) {
                // Found when the schedule it shortens was.
                (self.best, self.best_at) = (Some(child), found_at);
                progress.iteration(self.checked, m, None);
                progress.certified(m);
            }
        }
    }

    /// Node `id`'s schedule shortened as [`Search::tighten`] made it: a child of it, whose
    /// id is given when it is certified.
    fn add_tightened(&mut self, id: usize, t: Tightened) -> Option<usize> {
        let node = &self.nodes[id];
        let first = &t.shortened[0];
        let remedy = Remedy::on(
            first.robot,
            first.leg,
            first.nodes,
            RemedyKind::Tighten {
                shortened: t.shortened,
            },
        );
        let child = Node {
            routes: node.routes.clone(),
            conflicts: node.conflicts.clone(),
            legs: t.legs,
            makespan: t.robots.iter().map(|s| s.end).fold(0.0, f64::max),
            robots: t.robots,
            parent: Some(id),
            remedy: Some(remedy),
            depth: node.depth + 1,
            discrepancies: node.discrepancies,
            deviated_at: node.deviated_at,
            pending: None,
            outcome: Some(t.outcome),
            prepared: node.prepared.clone(),
        };
        let child = self.add(child);
        self.shortenings_refused += usize::from(!t.free);
        t.free.then_some(child)
    }

    /// Shortens the slack of node `id`, a certified schedule, and checks the result as a
    /// changed node is (its robots, then whole); `None` when nothing shortens. `early`: a
    /// changed way may be given back for a wait from the first pass on (else only once
    /// nothing else shortens).
    fn tighten(&self, id: usize, early: bool) -> Option<Tightened> {
        let clock = Instant::now();
        let node = &self.nodes[id];
        let (routes, mut legs, mut robots) = (&node.routes, node.legs.clone(), node.robots.clone());
        let mut notes = Notes {
            routes,
            shortened: Vec::new(),
            which: Vec::new(),
        };
        let mut steps = 0;
        // Passes over the robots, the one that ends last first, until none can shorten its
        // slack: a robot that goes sooner may leave room for the one that ends last.
        let mut changed = true;
        let mut passes = 0;
        // Whether a changed way may take its planned move after a wait (only where the
        // solve may wait): from the first pass when `early`, else once nothing else
        // shortens.
        let may_wait = self.opts.search.remedies.wait;
        let mut waiting = early && may_wait;
        let deadline = self.prepared.deadline;
        while changed && steps < MAX_STEPS && passes < MAX_PASSES {
            // Under a time limit, what was shortened by then.
            if deadline.is_some_and(|d| Instant::now() >= d) {
                break;
            }
            passes += 1;
            changed = false;
            let mut order: Vec<usize> = (0..robots.len()).collect();
            order.sort_by(|&a, &b| robots[b].end.total_cmp(&robots[a].end).then(a.cmp(&b)));
            for r in order {
                if steps >= MAX_STEPS {
                    break;
                }
                let draft = Draft {
                    id,
                    routes,
                    legs: &legs,
                    robots: &robots,
                };
                if let Some((m, before, after, planned, s)) = self.straighten(&draft, r, waiting) {
                    notes.note(r, m, None, Shortening::Straight, (before, after));
                    legs = with_leg(&legs, r, m, planned);
                    robots[r] = Arc::new(s);
                    steps += 1;
                    changed = true;
                    continue;
                }
                let Some((slack, before, after, s)) = self.shorten(&draft, r) else {
                    continue;
                };
                notes.note_slack(&legs, r, slack, (before, after));
                steps += 1;
                legs = with_leg(&legs, r, slack.leg, with_excess(&legs, r, slack, after));
                robots[r] = Arc::new(s);
                changed = true;
            }
            let draft = Draft {
                id,
                routes,
                legs: &legs,
                robots: &robots,
            };
            if !changed && !waiting && may_wait {
                (waiting, changed) = (true, true);
            } else if !changed && may_wait && self.opts.search.give_way {
                // Nothing else shortens: the robot that ends last, let through.
                if let Some(g) = self.give_way(&draft) {
                    notes.note_slack(&legs, g.r, g.slack, g.cut);
                    let wait = Slack {
                        leg: g.m,
                        piece: None,
                    };
                    notes.note(g.y, g.m, Some(wait), Shortening::Wait, g.wait);
                    let cut = with_excess(&legs, g.r, g.slack, g.cut.1);
                    legs = with_leg(&legs, g.r, g.slack.leg, cut);
                    legs = with_leg(&legs, g.y, g.m, g.y_leg);
                    robots[g.r] = Arc::new(g.r_plan);
                    robots[g.y] = Arc::new(g.y_plan);
                    steps += 1;
                    changed = true;
                }
            }
        }
        let shortened = notes.shortened;
        if shortened.is_empty() {
            return None;
        }
        // Not counted among the search's schedules: like a remedy's own checks, it spends
        // none of its budget.
        let checking = Instant::now();
        let schedule = Schedule::of(robots.clone());
        let opts = &self.opts.check;
        let mut outcome = Outcome::of(self.cell, &schedule, opts, false, &[]);
        if outcome.status() == Status::Free {
            outcome = Outcome::of(self.cell, &schedule, opts, true, &[]);
        }
        Some(Tightened {
            free: outcome.status() == Status::Free,
            legs,
            robots,
            shortened,
            outcome,
            checking: checking.elapsed(),
            elapsed: clock.elapsed(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planning::PlannedMove;
    use crate::wcp::feedback::clearing::clears;
    use crate::wcp::legs::default_legs;
    use crate::wcp::legs::{Leg, Piece};
    use crate::wcp::moves::MoveStore;
    use crate::wcp::options::SolveOptions;
    use crate::wcp::prepare::{prepare, StageTimes};

    /// X crosses from (-5, 0) to its task at (5, 0) and back; Y from (0, -5) to its task at
    /// (0, 5), 9 s long, and back: they meet at the origin on the way out.
    const CELL: &str = r#"{
        "delta": 0.01,
        "robots": [
            {"name": "X", "home": [-5, 0, 0], "shape": [[-0.35, -0.35], [0.35, -0.35], [0.35, 0.35], [-0.35, 0.35]],
             "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5},
            {"name": "Y", "home": [0, -5, 0], "shape": [[-0.35, -0.35], [0.35, -0.35], [0.35, 0.35], [-0.35, 0.35]],
             "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5}
        ],
        "tasks": [{"name": "x", "at": [5, 0, 0], "duration": 1.0, "robots": ["X"]},
                  {"name": "y", "at": [0, 5, 0], "duration": 9.0, "robots": ["Y"]}]
    }"#;

    /// What shortening makes of Y's first leg `leg` (certified, Y ending last): the first
    /// entry shortened and all of them, the makespan before and after, Y's leg after, and
    /// whether the checker proves Y with its first leg `leg` clear of X as X was.
    struct YShortened {
        shortened: Shortened,
        all: Vec<Shortened>,
        makespans: (f64, f64),
        leg: Leg,
        clear: Box<dyn Fn(&Leg) -> bool>,
    }

    fn tightened(leg: impl Fn(&MoveStore) -> Leg) -> YShortened {
        // Each kind of slack alone: no way given back for a wait, no robot let through.
        let mut opts = SolveOptions::default();
        opts.search.remedies.wait = false;
        let t = tightened_with(&opts, leg);
        assert_eq!(t.all.len(), 1, "{:?}", t.all);
        t
    }

    /// [`tightened`] under `opts`.
    fn tightened_with(opts: &SolveOptions, leg: impl Fn(&MoveStore) -> Leg) -> YShortened {
        let cell = crate::cell::parse_cell(CELL, "test.json".as_ref())
            .unwrap()
            .cell;
        let opts = opts.clone();
        let prepared = prepare(&cell, &opts, &()).unwrap();
        let mut search = Search::new(&cell, &prepared, &opts, StageTimes::default(), 0.0);
        let routes = vec![vec![0], vec![1]];
        let root = search.add_root(&routes).unwrap().unwrap();
        search.check_all(&[root], &());
        assert!(search.collision(root).is_some(), "they meet at the origin");
        let legs = with_leg(&default_legs(2), 1, 0, leg(&prepared.moves));
        let y = RobotSchedule::build(&cell, 1, &routes[1], &legs[1], &prepared.moves).unwrap();
        let mut robots = search.nodes[root].robots.clone();
        robots[1] = Arc::new(y);
        let makespan = robots[1].end;
        assert!(robots[0].end < makespan, "Y ends last");
        let yields = search.add(Node::by_hand(root, &routes, legs, robots.clone()));
        search.check_all(&[yields], &());
        assert_eq!(search.best, Some(yields));
        search.tighten_all(&());
        let answer = search.best.unwrap();
        assert_ne!(answer, yields, "shortened");
        let node = &search.nodes[answer];
        assert_eq!(node.parent, Some(yields));
        let outcome = node.outcome.as_ref().unwrap();
        assert!(outcome.whole && outcome.status() == Status::Free);
        let Some(RemedyKind::Tighten { shortened }) = node.remedy.as_ref().map(|r| &r.kind) else {
            panic!("{:?}", node.remedy);
        };
        let (after, leg) = (
            node.makespan,
            crate::wcp::legs::leg(&node.legs, 1, 0).clone(),
        );
        let all = shortened.clone();
        let x = robots[0].clone();
        let clear = Box::new(move |leg: &Leg| {
            let legs = with_leg(&default_legs(2), 1, 0, leg.clone());
            let y = RobotSchedule::build(&cell, 1, &[1], &legs[1], &prepared.moves).unwrap();
            clears(&cell, (1, &y), (0, &x), (0.0, 60.0), &opts.check)
        });
        YShortened {
            shortened: all[0],
            all,
            makespans: (makespan, after),
            leg,
            clear,
        }
    }

    /// Under a time limit the search stops a share of it early, so that its answer is
    /// shortened within the limit.
    #[test]
    fn the_search_leaves_time_for_the_shortening() {
        let cell = crate::cell::parse_cell(CELL, "test.json".as_ref())
            .unwrap()
            .cell;
        let opts = SolveOptions {
            time_limit: Some(std::time::Duration::from_secs(2)),
            ..SolveOptions::default()
        };
        let prepared = prepare(&cell, &opts, &()).unwrap();
        let search = Search::new(&cell, &prepared, &opts, StageTimes::default(), 0.0);
        let (end, limit) = (search.deadline().unwrap(), prepared.deadline.unwrap());
        assert_eq!(limit - end, std::time::Duration::from_millis(100));
        let opts = SolveOptions::default();
        let prepared = prepare(&cell, &opts, &()).unwrap();
        let search = Search::new(&cell, &prepared, &opts, StageTimes::default(), 0.0);
        assert_eq!(search.deadline(), None);
    }

    /// Y waiting 6 s at home is certified, but far longer than X's passing needs: the
    /// answer has it wait no less than the least wait that clears and little more, and Y,
    /// which ends last, home that much sooner.
    #[test]
    fn a_wait_longer_than_needed_is_shortened_to_what_clears() {
        let waits = |d: f64| Leg {
            wait: d,
            ..Leg::DEFAULT
        };
        let t = tightened(|_| waits(6.0));
        let s = t.shortened;
        assert_eq!(
            (s.robot, s.leg, s.kind, s.before),
            (1, 0, Shortening::Wait, 6.0)
        );
        assert_eq!(t.leg.wait, s.after);
        // Y, and the makespan, end exactly that much sooner.
        assert!((t.makespans.1 - (t.makespans.0 - (6.0 - s.after))).abs() < 1e-9);
        // The least wait that clears, to a hundredth: the answer waits no less, and the
        // bisections leave little more.
        let least = (0..600)
            .map(|k| k as f64 * 0.01)
            .find(|&d| (t.clear)(&waits(d)));
        let least = least.unwrap();
        assert!(least > 0.5, "X is in the way for a while: {least}");
        assert!(
            s.after >= least - 0.01 && s.after < least + 6.0 * 0.25 / 8.0 + 0.01,
            "waits {}, least {least}",
            s.after
        );
    }

    /// The answer's own shortening wins a tie: with X's task 20 s long, X sets the makespan,
    /// and Y waiting 6 s before its way out (more than X's passing needs) ends before it.
    /// Shortening Y's wait leaves the makespan as it is, and the shortened schedule is the
    /// answer: a robot that does not set the makespan holds no longer than the others
    /// allow either.
    #[test]
    fn the_answers_own_shortening_wins_a_tie() {
        let text = CELL.replace(r#""duration": 1.0"#, r#""duration": 20.0"#);
        let cell = crate::cell::parse_cell(&text, "test.json".as_ref())
            .unwrap()
            .cell;
        let opts = SolveOptions::default();
        let prepared = prepare(&cell, &opts, &()).unwrap();
        let mut search = Search::new(&cell, &prepared, &opts, StageTimes::default(), 0.0);
        let routes = vec![vec![0], vec![1]];
        let root = search.add_root(&routes).unwrap().unwrap();
        search.check_all(&[root], &());
        let waits = Leg {
            wait: 6.0,
            ..Leg::DEFAULT
        };
        let legs = with_leg(&default_legs(2), 1, 0, waits);
        let y = RobotSchedule::build(&cell, 1, &routes[1], &legs[1], &prepared.moves).unwrap();
        let mut robots = search.nodes[root].robots.clone();
        robots[1] = Arc::new(y);
        assert!(robots[1].end < robots[0].end, "X ends last");
        let yields = search.add(Node::by_hand(root, &routes, legs, robots));
        search.check_all(&[yields], &());
        assert_eq!(search.best, Some(yields));
        search.tighten_all(&());
        let answer = search.best.unwrap();
        assert_ne!(answer, yields, "the shortened schedule is the answer");
        let node = &search.nodes[answer];
        assert_eq!(node.makespan, search.nodes[yields].makespan);
        assert!(node.legs[1][0].wait < 6.0);
    }

    /// Y making its way out 1.4 times slower is certified (3 times slower, it would meet X
    /// on its way back), but slower than X's passing needs:
    /// the answer runs it no faster than the fastest that clears, and little slower.
    #[test]
    fn a_motion_slower_than_needed_is_sped_up_to_what_clears() {
        let slowed = |motion: Arc<PlannedMove>, scale: f64| Leg {
            wait: 0.0,
            pieces: Some(vec![Piece::Go { motion, scale }].into()),
        };
        let planned = |moves: &MoveStore| {
            let m = moves.get(1, 0, 2).unwrap();
            moves.timed(1, &m.primitives)
        };
        let t = tightened(|moves| slowed(planned(moves), 1.4));
        let s = t.shortened;
        assert_eq!(
            (s.robot, s.leg, s.kind, s.before),
            (1, 0, Shortening::Slow, 1.4)
        );
        let Some([Piece::Go { scale, motion }]) = t.leg.pieces.as_deref() else {
            panic!("{:?}", t.leg);
        };
        assert_eq!(*scale, s.after);
        assert!((t.makespans.1 - (t.makespans.0 - (1.4 - s.after) * motion.duration)).abs() < 1e-6);
        // The least factor that clears, to a hundredth.
        let least = (100..140)
            .map(|k| k as f64 * 0.01)
            .find(|&k| (t.clear)(&slowed(motion.clone(), k)));
        let least = least.unwrap();
        assert!(least > 1.05, "X is in the way: {least}");
        assert!(
            s.after >= least - 0.01 && s.after < least + 0.4 * 0.25 / 8.0 + 0.01,
            "{} times slower, least {least}",
            s.after
        );
    }

    /// The same slowed way out of Y, where a wait may be taken: Y waits at home, then makes
    /// its planned move at full speed, and ends sooner than running it the least slower
    /// that clears. The leg's time is reported from before the wait to the arrival.
    #[test]
    fn a_slowed_way_gives_way_to_a_wait_and_the_planned_move() {
        let slowed = |moves: &MoveStore| {
            let m = moves.get(1, 0, 2).unwrap();
            Leg {
                wait: 0.0,
                pieces: Some(
                    vec![Piece::Go {
                        motion: moves.timed(1, &m.primitives),
                        scale: 1.4,
                    }]
                    .into(),
                ),
            }
        };
        // No robot let through: X would wait for Y instead (the test below).
        let mut opts = SolveOptions::default();
        opts.search.give_way = false;
        let waits = tightened_with(&opts, slowed);
        assert_eq!(waits.all.len(), 1, "{:?}", waits.all);
        let s = waits.shortened;
        assert_eq!((s.robot, s.leg, s.kind), (1, 0, Shortening::Straight));
        assert!(
            waits.leg.pieces.is_none() && waits.leg.wait > 0.0,
            "{:?}",
            waits.leg
        );
        // Y ends as much sooner as its leg is shorter.
        let gained = waits.makespans.0 - waits.makespans.1;
        assert!((gained - (s.before - s.after)).abs() < 1e-9, "{s:?}");
        assert!((waits.clear)(&waits.leg));
        let sped_up = tightened(slowed);
        assert!(waits.makespans.1 < sped_up.makespans.1 - 0.1);
    }

    /// Y waits at home until X has crossed; X, with a short task, has room. Cutting Y's
    /// wait to what clears X is the most the other shortenings do; letting Y through, X
    /// waits for it instead, and the cell ends sooner.
    #[test]
    fn the_robot_that_ends_last_is_let_through_by_one_with_room() {
        let waited = |_: &MoveStore| Leg {
            wait: 4.0,
            pieces: None,
        };
        let mut alone = SolveOptions::default();
        alone.search.give_way = false;
        let cut = tightened_with(&alone, waited);
        assert_eq!(cut.all.len(), 1, "{:?}", cut.all);
        assert!(cut.leg.wait > 1.0, "{:?}", cut.leg);
        let through = tightened_with(&SolveOptions::default(), waited);
        assert!(through.leg.wait < cut.leg.wait - 1.0, "{:?}", through.leg);
        assert!(through.makespans.1 < cut.makespans.1 - 1.0);
        // X waits longer at home: listed with its wait before and after.
        let x_waits = (through.all.iter())
            .find(|e| e.robot == 0)
            .expect("X waits");
        assert_eq!((x_waits.leg, x_waits.kind), (0, Shortening::Wait));
        assert!(x_waits.after > x_waits.before, "{x_waits:?}");
    }
}
