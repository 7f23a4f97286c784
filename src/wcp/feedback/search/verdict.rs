//! The checker's verdict on a node: a root checked whole, robots and fixtures; any other node
//! for its robots against each other, and whole once found free.

use super::{Outcome, Search, Status};
use crate::cell::Cell;
use crate::collision::CheckOptions;
use crate::wcp::prepare::Progress;
use crate::wcp::schedule::Schedule;
use rayon::prelude::*;
use std::time::Instant;

impl Outcome {
    /// The checker's verdict on `schedule`: with the fixtures when `whole`, else of its
    /// robots against each other.
    pub(super) fn of(
        cell: &Cell,
        schedule: &Schedule,
        opts: &CheckOptions,
        whole: bool,
    ) -> Outcome {
        let scene = match whole {
            true => schedule.scene(cell),
            false => schedule.robots_scene(cell),
        };
        let report = schedule.check(&scene, opts);
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
    /// of the aisle grids of 7 and 8 robots 15-20 % faster); one found free is then checked
    /// whole, and only that verdict makes it a candidate answer.
    pub(super) fn check_all(&mut self, ids: &[usize], progress: &dyn Progress) {
        let clock = Instant::now();
        let (cell, check_opts) = (self.cell, &self.opts.check);
        let outcomes: Vec<Outcome> = ids
            .par_iter()
            .map(|&id| {
                let schedule = Schedule::of(self.nodes[id].robots.clone());
                if self.nodes[id].parent.is_some() {
                    let robots = Outcome::of(cell, &schedule, check_opts, false);
                    if robots.status() != Status::Free {
                        return robots;
                    }
                }
                Outcome::of(cell, &schedule, check_opts, true)
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
}

#[cfg(test)]
mod tests {
    use super::super::Node;
    use super::*;
    use crate::geometry::Vec2;
    use crate::planning::Primitive;
    use crate::wcp::legs::{default_legs, Leg, Piece};
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
        let through = prepared.moves.timed(
            0,
            &[Primitive {
                path: vec![Vec2::new(0.0, 0.0), Vec2::new(4.0, 0.0)],
                theta: 0.0,
                turn: 0.0,
            }],
        );
        let leg = Leg {
            wait: 0.0,
            pieces: Some(
                vec![Piece::Go {
                    motion: through,
                    scale: 1.0,
                }]
                .into(),
            ),
        };
        let mut legs = default_legs(2);
        legs[0] = Arc::new(vec![leg]);
        let r1 = RobotSchedule::build(&cell, 0, &routes[0], &legs[0], &prepared.moves).unwrap();
        let mut robots = search.nodes[root].robots.clone();
        robots[0] = Arc::new(r1);
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
}
