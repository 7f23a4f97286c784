//! The checker's verdict on a node: a root checked whole, robots and fixtures; any other node
//! for its robots against each other, from where its parent's check proved nothing, and
//! whole once found free.

use super::{Outcome, Search, Status};
use crate::cell::Cell;
use crate::collision::CheckOptions;
use crate::wcp::prepare::Progress;
use crate::wcp::schedule::{RobotSchedule, Schedule};
use rayon::prelude::*;
use std::sync::Arc;
use std::time::Instant;

impl Outcome {
    /// The checker's verdict on `schedule`: with the fixtures when `whole`, else of its
    /// robots against each other.
    pub(super) fn of(
        cell: &Cell,
        schedule: &Schedule,
        opts: &CheckOptions,
        whole: bool,
        known: &[f64],
    ) -> Outcome {
        let scene = match whole {
            true => schedule.scene(cell),
            false => schedule.robots_scene(cell),
        };
        // By body: an arm is a body per link.
        let known: Vec<f64> = match known.is_empty() {
            true => Vec::new(),
            false => (schedule.body_robots(cell).into_iter())
                .map(|r| known[r])
                .collect(),
        };
        // The counters of a check of robots only are read by no one.
        let opts = CheckOptions {
            counters: whole && opts.counters,
            ..*opts
        };
        let report = schedule.check_known(&scene, &opts, &known);
        let collision = schedule.collision(cell, &report);
        Outcome {
            report,
            collision,
            whole,
        }
    }

    pub(super) fn status(&self) -> Status {
        match (&self.collision, self.report.verdict().is_certified_free()) {
            (Some(_), _) => Status::Collides,
            (None, true) => Status::Free,
            (None, false) => Status::Undecided,
        }
    }
}

impl Search<'_> {
    /// Checks the nodes given (in parallel, results in order) and records the verdicts.
    ///
    /// A root is checked whole, robots and fixtures. Every motion a node adds to its root's
    /// is certified clear of the fixtures when it is made (planned moves by the store, the
    /// remedies' by the checker, holds where such a motion rests, slower runs of the same
    /// path), so any other node is checked for its robots against each other only (solves
    /// of the aisle grids of 7 and 8 robots 15-20 % faster), and only from where its
    /// parent's check left off ([`Search::known_apart`]): a child shares its parent's
    /// motions up to the change it makes, and the pairs the parent proved apart up to its
    /// first contact need no second proof there (the children's checks of the doorway and
    /// aisle cells about a third shorter, every verdict the same). One found free is then
    /// checked whole, from the start, and only that verdict makes it a candidate answer.
    pub(super) fn check_all(&mut self, ids: &[usize], progress: &dyn Progress) {
        let clock = Instant::now();
        let (cell, check_opts) = (self.cell, &self.opts.check);
        let outcomes: Vec<Outcome> = ids
            .par_iter()
            .map(|&id| {
                let node = &self.nodes[id];
                let schedule = Schedule::of(node.robots.clone());
                if let Some(p) = node.parent {
                    let known = self.known_apart(p, &node.robots);
                    let robots = Outcome::of(cell, &schedule, check_opts, false, &known);
                    if robots.status() != Status::Free {
                        return robots;
                    }
                }
                Outcome::of(cell, &schedule, check_opts, true, &[])
            })
            .collect();
        self.times.checking += clock.elapsed();
        for (&id, outcome) in ids.iter().zip(outcomes) {
            self.checked += 1;
            progress.iteration(
                self.checked,
                self.nodes[id].makespan,
                outcome.collision.as_ref(),
            );
            let status = outcome.status();
            self.nodes[id].outcome = Some(outcome);
            match status {
                Status::Free if self.worth(id) => {
                    self.best = Some(id);
                    self.best_at = self.checked;
                    self.incumbents.push((id, self.checked));
                    progress.certified(self.nodes[id].makespan);
                }
                Status::Free | Status::Undecided => {}
                Status::Collides => {
                    let t = self.collision(id).map(|c| c.time);
                    let later = self
                        .furthest
                        .and_then(|f| self.collision(f).map(|c| c.time))
                        .is_none_or(|best| t.is_some_and(|t| t > best));
                    if later {
                        self.furthest = Some(id);
                    }
                }
            }
        }
    }

    /// Up to when each robot of a child of node `parent` is known δ apart from every other,
    /// from the parent's check: every pair of the parent up to where that check proved them
    /// apart ([`CheckReport::proven_until`]), a robot the child moved only up to its last
    /// sample the parent shares. Empty when nothing is known.
    ///
    /// [`CheckReport::proven_until`]: crate::collision::CheckReport::proven_until
    fn known_apart(&self, parent: usize, robots: &[Arc<RobotSchedule>]) -> Vec<f64> {
        let node = &self.nodes[parent];
        let until = node.outcome.as_ref().and_then(|o| o.report.proven_until());
        let Some(until) = until.filter(|_| node.robots.len() == robots.len()) else {
            return Vec::new();
        };
        (robots.iter().zip(&node.robots))
            .map(|(now, before)| match Arc::ptr_eq(now, before) {
                true => until,
                false => until.min(shared_until(now, before)),
            })
            .collect()
    }
}

/// The time of the last sample two schedules of one robot share from the start, before
/// which they move alike (−∞ when their first samples differ).
fn shared_until(a: &RobotSchedule, b: &RobotSchedule) -> f64 {
    /// The last of the items two lists share from the start.
    fn last_shared<'s, T: PartialEq>(a: &'s [T], b: &[T]) -> Option<&'s T> {
        let shared = a.iter().zip(b).take_while(|(x, y)| x == y);
        shared.last().map(|(x, _)| x)
    }
    let last = match a.joints.is_empty() && b.joints.is_empty() {
        true => last_shared(&a.samples, &b.samples).map(|s| s.t),
        // An arm moves as its joints do.
        false => last_shared(&a.joints, &b.joints).map(|q| q.t),
    };
    last.unwrap_or(f64::NEG_INFINITY)
}

#[cfg(test)]
mod tests {
    use super::super::Node;
    use super::*;
    use crate::geometry::Vec2;
    use crate::planning::Primitive;
    use crate::wcp::legs::{with_leg, Leg, Legs, Piece};
    use crate::wcp::options::SolveOptions;
    use crate::wcp::prepare::{prepare, StageTimes};
    use crate::wcp::schedule::RobotSchedule;
    use std::sync::Arc;

    /// R1 goes round a wall to its task; R2 stays far away at home.
    const CELL: &str = r#"{
        "delta": 0.01,
        "obstacles": [{"name": "wall", "shape": [[1.8, -1.5], [2.2, -1.5], [2.2, 1.5], [1.8, 1.5]]}],
        "robots": [
            {"name": "R1", "home": [0, 0, 0], "shape": [[-0.3, -0.3], [0.3, -0.3], [0.3, 0.3], [-0.3, 0.3]],
             "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5},
            {"name": "R2", "home": [0, 6, 0], "shape": [[-0.3, -0.3], [0.3, -0.3], [0.3, 0.3], [-0.3, 0.3]],
             "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5}
        ],
        "tasks": [{"name": "t1", "at": [4, 0, 0], "duration": 1.0, "robots": ["R1"]}]
    }"#;

    /// Node `root`'s legs and robots with R1 driving along `path` on its first leg instead.
    fn r1_along(search: &Search, root: usize, path: &[Vec2]) -> (Legs, Vec<Arc<RobotSchedule>>) {
        let (node, moves) = (&search.nodes[root], &search.prepared.moves);
        let primitive = Primitive {
            path: path.to_vec(),
            theta: 0.0,
            turn: 0.0,
        };
        let motion = moves.timed(0, &[primitive]);
        let leg = Leg {
            wait: 0.0,
            pieces: Some(vec![Piece::Go { motion, scale: 1.0 }].into()),
        };
        let legs = with_leg(&node.legs, 0, 0, leg);
        let r1 = RobotSchedule::build(search.cell, 0, &node.routes[0], &legs[0], moves).unwrap();
        let mut robots = node.robots.clone();
        robots[0] = Arc::new(r1);
        (legs, robots)
    }

    /// The fixtures are left out of a changed schedule's check only while every motion is
    /// certified clear of them: a node whose motion goes through the wall anyway (a remedy
    /// that broke that promise) is checked whole once its robots are found apart, and is
    /// no candidate answer.
    #[test]
    fn a_node_found_free_is_checked_with_the_fixtures() {
        let cell = crate::cell::parse_cell(CELL, "test.json".as_ref())
            .unwrap()
            .cell;
        let opts = SolveOptions::default();
        let prepared = prepare(&cell, &opts, &()).unwrap();
        let mut search = Search::new(&cell, &prepared, &opts, StageTimes::default(), 0.0);
        let routes = vec![vec![0], vec![]];
        let root = search.add_root(&routes).unwrap().unwrap();
        search.check_all(&[root], &());
        assert_eq!(search.best, Some(root), "round the wall: free");
        // R1 straight through the wall.
        let (legs, robots) = r1_along(&search, root, &[Vec2::new(0.0, 0.0), Vec2::new(4.0, 0.0)]);
        let child = search.add(Node::by_hand(root, &routes, legs, robots));
        let makespan = search.nodes[child].makespan;
        assert!(
            makespan < search.nodes[root].makespan,
            "shorter: worth taking"
        );
        search.check_all(&[child], &());
        let outcome = search.nodes[child].outcome.as_ref().unwrap();
        assert!(outcome.whole);
        assert_eq!(outcome.status(), Status::Collides);
        let c = outcome.collision.as_ref().unwrap();
        assert_eq!((c.robots.0, c.robots.1), (0, None), "R1 and the wall");
        assert_eq!(search.best, Some(root));
    }

    /// R1 drives to its task at (6, 0), where R2 crosses later; R3 stands at (3, 2), beside
    /// R1's way.
    const THREE: &str = r#"{
        "delta": 0.01,
        "robots": [
            {"name": "R1", "home": [0, 0, 0], "shape": [[-0.3, -0.3], [0.3, -0.3], [0.3, 0.3], [-0.3, 0.3]],
             "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5},
            {"name": "R2", "home": [6, -6, 0], "shape": [[-0.3, -0.3], [0.3, -0.3], [0.3, 0.3], [-0.3, 0.3]],
             "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5},
            {"name": "R3", "home": [3, 2, 0], "shape": [[-0.3, -0.3], [0.3, -0.3], [0.3, 0.3], [-0.3, 0.3]],
             "max_speed": 1.0, "max_accel": 2.0, "max_turn_rate": 1.5}
        ],
        "tasks": [{"name": "t1", "at": [6, 0, 0], "duration": 1.0, "robots": ["R1"]},
                  {"name": "t2", "at": [6, 6, 0], "duration": 1.0, "robots": ["R2"]}]
    }"#;

    /// A child is checked only where its parent's check did not already prove its pairs
    /// apart: from the parent's contact on for robots it kept, from the start for a robot it
    /// moved from the start. R1 re-routed through R3 hits it long before the parent's
    /// contact of R1 and R2; that collision is found, the one a whole check finds.
    #[test]
    fn a_child_is_checked_from_where_its_parent_proved_nothing() {
        let cell = crate::cell::parse_cell(THREE, "test.json".as_ref())
            .unwrap()
            .cell;
        let opts = SolveOptions::default();
        let prepared = prepare(&cell, &opts, &()).unwrap();
        let mut search = Search::new(&cell, &prepared, &opts, StageTimes::default(), 0.0);
        let routes = vec![vec![0], vec![1], vec![]];
        let root = search.add_root(&routes).unwrap().unwrap();
        search.check_all(&[root], &());
        let late = search
            .collision(root)
            .expect("R1 and R2 meet at R1's task")
            .clone();
        assert_eq!((late.robots.0, late.robots.1), (0, Some(1)));
        // R1 by way of R3's place.
        let by_r3 = [(0.0, 0.0), (3.0, 1.8), (6.0, 0.0)].map(|(x, y)| Vec2::new(x, y));
        let (legs, robots) = r1_along(&search, root, &by_r3);
        let whole = Outcome::of(
            &cell,
            &Schedule::of(robots.clone()),
            &opts.check,
            false,
            &[],
        );
        let child = search.add(Node::by_hand(root, &routes, legs, robots));
        let known = search.known_apart(root, &search.nodes[child].robots);
        assert!(
            known[1] > 0.9 * late.time && known[1] == known[2],
            "{known:?}"
        );
        assert!(
            known[0] < 1e-9,
            "R1 moves otherwise from the start: {known:?}"
        );
        search.check_all(&[child], &());
        let early = search.collision(child).expect("R1 hits R3");
        assert_eq!((early.robots.0, early.robots.1), (0, Some(2)));
        assert!(
            early.time < 0.8 * late.time,
            "{} vs {}",
            early.time,
            late.time
        );
        assert_eq!(Some(early), whole.collision.as_ref());
    }

    /// Two schedules of one robot move alike up to the last sample they share.
    #[test]
    fn schedules_share_their_samples_up_to_the_first_that_differs() {
        let cell = crate::cell::parse_cell(THREE, "test.json".as_ref())
            .unwrap()
            .cell;
        let prepared = prepare(&cell, &SolveOptions::default(), &()).unwrap();
        let build = |wait: f64| {
            let legs = vec![Leg { wait, pieces: None }];
            RobotSchedule::build(&cell, 0, &[0], &Arc::new(legs), &prepared.moves).unwrap()
        };
        let (now, later) = (build(0.0), build(2.0));
        assert_eq!(shared_until(&now, &now), now.samples.last().unwrap().t);
        // Waiting 2 s more: the same first sample at home, then apart.
        let shared = shared_until(&now, &later);
        assert_eq!(shared, now.samples[0].t, "{shared}");
        let mut moved = now.clone();
        moved.samples[3].pos.x += 1e-9;
        assert_eq!(shared_until(&now, &moved), now.samples[2].t);
    }
}
