//! The timed schedule of every robot ([`Schedule`]): built robot by robot, turned into the
//! checker's scene, and a check's first contact located back on the robots, their
//! activities and their legs ([`Collision`]).

use super::activity::{Activity, RobotSchedule, Segment};
use super::timeline::BuildError;
use crate::cell::{Cell, RobotKind};
use crate::collision::{Body, CheckOptions, CheckReport, Scene, DEFAULT_TIME_TOL_OVER_HORIZON};
use crate::geometry::{closest_features, ConvexPolygon, Posed, Vec2, WalkTolerances};
use crate::motion::{Pose, Trajectory};
use crate::wcp::legs::Leg;
use crate::wcp::moves::MoveStore;
use std::sync::Arc;

/// The timed schedule of every robot.
#[derive(Clone, Debug)]
pub struct Schedule {
    /// One per robot, in the cell's order (shared between schedules that differ in other
    /// robots only).
    pub robots: Vec<Arc<RobotSchedule>>,
    /// When the last robot is back home.
    pub makespan: f64,
}

impl Schedule {
    /// Times every robot's route: from home at t = 0, each leg (by default the planned
    /// move, at once; see [`Leg`]), each task held for its duration, back home. The moves
    /// come from the store (planned there if they were not yet).
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{legs::default_legs, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let routes = [vec![0, 2], vec![3, 1]];
    /// let schedule = Schedule::build(&cell, &routes, &default_legs(2), &store).unwrap();
    /// assert_eq!(schedule.robots[1].route, [3, 1]);
    /// assert_eq!(schedule.makespan, schedule.robots[0].end.max(schedule.robots[1].end));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn build(
        cell: &Cell,
        routes: &[Vec<usize>],
        legs: &[Arc<Vec<Leg>>],
        moves: &MoveStore,
    ) -> Result<Schedule, BuildError> {
        let robots = (0..routes.len())
            .map(|r| {
                let list = legs.get(r).map_or(&[][..], |l| l.as_slice());
                RobotSchedule::build(cell, r, &routes[r], list, moves).map(Arc::new)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Schedule::of(robots))
    }

    /// The schedule of these robot schedules, in robot order.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{MoveStore, RobotSchedule, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let r1 = RobotSchedule::build(&cell, 0, &[0, 1], &[], &store).unwrap();
    /// let r2 = RobotSchedule::build(&cell, 1, &[2, 3], &[], &store).unwrap();
    /// let (e1, e2) = (r1.end, r2.end);
    /// let schedule = Schedule::of(vec![Arc::new(r1), Arc::new(r2)]);
    /// assert_eq!(schedule.makespan, e1.max(e2));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn of(robots: Vec<Arc<RobotSchedule>>) -> Schedule {
        let makespan = robots.iter().map(|s| s.end).fold(0.0, f64::max);
        Schedule { robots, makespan }
    }

    /// The schedule as a scene for the checker (and `--export-scene`): robots with their
    /// trajectories, then the obstacles.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{legs::default_legs, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let schedule = Schedule::build(&cell, &[vec![0, 1], vec![2, 3]], &default_legs(2), &store).unwrap();
    /// let scene = schedule.scene(&cell);
    /// let names: Vec<&str> = scene.bodies.iter().map(|b| b.name.as_str()).collect();
    /// assert_eq!(names, ["R1", "R2", "fixture"]);
    /// assert_eq!((scene.delta, scene.horizon()), (cell.delta, (0.0, schedule.makespan)));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn scene(&self, cell: &Cell) -> Scene {
        let mut scene = self.robots_scene(cell);
        scene.bodies.extend(cell.obstacle_bodies());
        scene
    }

    /// The robots alone, as in [`Schedule::scene`] without the obstacles: what a schedule
    /// whose every motion was certified clear of the fixtures leaves to check.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{legs::default_legs, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let schedule = Schedule::build(&cell, &[vec![0, 1], vec![2, 3]], &default_legs(2), &store).unwrap();
    /// let names: Vec<String> = schedule.robots_scene(&cell).bodies.into_iter().map(|b| b.name).collect();
    /// assert_eq!(names, ["R1", "R2"]);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn robots_scene(&self, cell: &Cell) -> Scene {
        Scene {
            delta: cell.delta,
            bodies: (0..self.robots.len())
                .flat_map(|r| self.bodies(cell, r))
                .collect(),
        }
    }

    /// Checks `scene`, a scene of this schedule (all of it, or some of its robots), with
    /// `opts`. When that check finds no contact but cannot certify the schedule because a
    /// pair grazes δ on an interval shorter than the time tolerance, and `opts` set no
    /// tolerance, the scene is checked again with [`DEFAULT_TIME_TOL_OVER_HORIZON`] of the
    /// shortest move instead of the makespan (no finer than 10⁻⁹ of the makespan): each move
    /// was certified at that fraction of its own length when it was planned, and a schedule
    /// of thousands of moves, hours long, would otherwise take a near miss its moves were
    /// proven clear of (10⁻⁶ of 8 hours is 29 ms) for a graze. Other schedules are checked
    /// once, as before.
    ///
    /// ```
    /// use workcell::collision::CheckOptions;
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{legs::default_legs, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let schedule = Schedule::build(&cell, &[vec![0, 1], vec![2, 3]], &default_legs(2), &store).unwrap();
    /// let report = schedule.check(&schedule.scene(&cell), &CheckOptions::default());
    /// assert!(report.collision);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn check(&self, scene: &Scene, opts: &CheckOptions) -> CheckReport {
        self.check_known(scene, opts, &[])
    }

    /// [`Schedule::check`] of pairs known δ apart up to a time (see
    /// [`crate::collision::check_known`]): the same report.
    pub(crate) fn check_known(
        &self,
        scene: &Scene,
        opts: &CheckOptions,
        known: &[f64],
    ) -> CheckReport {
        let report = crate::collision::check_known(scene, opts, known);
        let grazed = !report.collision && report.stats.grazing > 0;
        if !grazed || opts.time_tol.is_some() {
            return report;
        }
        let shortest = (self.robots.iter())
            .flat_map(|r| &r.segments)
            .filter(|s| matches!(s.activity, Activity::Move { .. }) && s.end > s.start)
            .map(|s| s.end - s.start)
            .fold(f64::INFINITY, f64::min);
        let tol = (DEFAULT_TIME_TOL_OVER_HORIZON * shortest).max(1e-9 * self.makespan);
        if !(tol.is_finite() && tol > 0.0 && tol < report.time_tol) {
            return report;
        }
        let finer = CheckOptions {
            time_tol: Some(tol),
            ..*opts
        };
        crate::collision::check_known(scene, &finer, known)
    }

    /// Robots `a` and `b` alone: the scene of one pair.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{legs::default_legs, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let schedule = Schedule::build(&cell, &[vec![0, 1], vec![2, 3]], &default_legs(2), &store).unwrap();
    /// let pair = schedule.pair_scene(&cell, 1, 0);
    /// let names: Vec<&str> = pair.bodies.iter().map(|b| b.name.as_str()).collect();
    /// assert_eq!(names, ["R2", "R1"]); // no fixture
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn pair_scene(&self, cell: &Cell, a: usize, b: usize) -> Scene {
        let mut bodies = self.bodies(cell, a);
        bodies.extend(self.bodies(cell, b));
        Scene {
            delta: cell.delta,
            bodies,
        }
    }

    /// Each checker body's robot, in the order of [`Schedule::robots_scene`].
    pub(crate) fn body_robots(&self, cell: &Cell) -> Vec<usize> {
        (0..self.robots.len())
            .flat_map(|r| {
                let n = match &cell.robots[r].kind {
                    RobotKind::Rigid(_) => 1,
                    RobotKind::Arm(arm) => arm.links.len(),
                };
                std::iter::repeat_n(r, n)
            })
            .collect()
    }

    /// Robot `r` as checker bodies: one for a rigid robot, one per link for an arm.
    fn bodies(&self, cell: &Cell, r: usize) -> Vec<Body> {
        let name = &cell.robots[r].name;
        match &cell.robots[r].kind {
            RobotKind::Rigid(robot) => {
                vec![robot.body(name, Trajectory::trusted(self.robots[r].samples.clone()))]
            }
            RobotKind::Arm(arm) => arm.bodies(name, self.robots[r].joints.clone()),
        }
    }

    /// The first collision of a check of [`Schedule::scene`], located in the schedule.
    ///
    /// ```
    /// use workcell::collision::{check, CheckOptions};
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{legs::default_legs, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// // Welds 2 and 4 lie too close for R1 and R2 at once.
    /// let routes = [vec![1, 0, 2], vec![3]];
    /// let schedule = Schedule::build(&cell, &routes, &default_legs(2), &store).unwrap();
    /// let report = check(&schedule.scene(&cell), &CheckOptions::default());
    /// let c = schedule.collision(&cell, &report).expect("a collision");
    /// assert_eq!((c.robots, c.bodies.clone()), ((0, Some(1)), ["R1".into(), "R2".into()]));
    /// assert!(c.segments.0.start <= c.time && c.time <= c.segments.0.end);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn collision(&self, cell: &Cell, report: &CheckReport) -> Option<Collision> {
        let contact = report.first_contact.as_ref()?;
        let robot = |name: &str| cell.robots.iter().position(|r| r.name == name);
        let a = robot(&contact.bodies[0]).expect("the checker names a robot first");
        let b = robot(&contact.bodies[1]);
        let placed_a = self.robots[a].placed(&cell.robots[a], contact.time);
        let placed_b = match b {
            Some(b) => self.robots[b].placed(&cell.robots[b], contact.time),
            None => {
                let o = cell
                    .obstacles
                    .iter()
                    .find(|o| o.name == contact.bodies[1])?;
                vec![(o.pieces(), Pose::new(0.0, 0.0, 0.0))]
            }
        };
        // The nearest pair of pieces (the one pair of a convex robot and obstacle).
        let posed = |s, p: Pose| Posed::new(s, p.pos.x, p.pos.y, p.theta);
        let pieces = |placed: &[(&'_ [ConvexPolygon], Pose)]| -> Vec<(ConvexPolygon, Pose)> {
            (placed.iter())
                .flat_map(|&(list, pose)| list.iter().map(move |p| (p.clone(), pose)))
                .collect()
        };
        let (pieces_a, pieces_b) = (pieces(&placed_a), pieces(&placed_b));
        let d = pieces_a
            .iter()
            .flat_map(|x| pieces_b.iter().map(move |y| (x, y)))
            .map(|((x, pa), (y, pb))| {
                let tol = WalkTolerances::default();
                closest_features(&posed(x, *pa), &posed(y, *pb), None, &tol)
            })
            .min_by(|p, q| p.distance.total_cmp(&q.distance))
            .expect("a body has at least one piece");
        Some(Collision {
            time: contact.time,
            bodies: contact.bodies.clone(),
            robots: (a, b),
            segments: (
                *self.robots[a].segment_at(contact.time),
                b.map(|b| *self.robots[b].segment_at(contact.time)),
            ),
            point: (d.point_a + d.point_b) / 2.0,
        })
    }
}

/// Where and when two bodies of a schedule first come closer than δ.
#[derive(Clone, Debug, PartialEq)]
pub struct Collision {
    /// Time of the first contact.
    pub time: f64,
    /// The two bodies, robot first.
    pub bodies: [String; 2],
    /// The robot, and the other robot (`None` for an obstacle).
    pub robots: (usize, Option<usize>),
    /// What each robot was doing.
    pub segments: (Segment, Option<Segment>),
    /// Midpoint of the closest points at that time.
    pub point: Vec2,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::Sample;

    /// A square turning a quarter turn in its first second, its corner passing a wall at
    /// δ·(1 + 10⁻³), then holding still until t = 1000: checked at 10⁻⁶ of the makespan,
    /// the pass only grazes δ; at 10⁻⁶ of its one-second move, it is proven clear.
    #[test]
    fn a_long_schedule_is_checked_as_finely_as_its_moves() {
        let (delta, half) = (0.01, 0.5);
        let y = delta * (1.0 + 1e-3) + half * 2f64.sqrt();
        let turn = std::f64::consts::FRAC_PI_2;
        let sample = |t: f64, theta: f64, omega: f64| Sample {
            t,
            pos: Vec2::new(0.0, y),
            theta,
            vel: Vec2::zeros(),
            omega,
        };
        let mut samples: Vec<Sample> = (0..=20)
            .map(|k| sample(k as f64 / 20.0, turn * k as f64 / 20.0, turn))
            .collect();
        samples.push(sample(1000.0, turn, 0.0));
        let square = ConvexPolygon::rectangle(2.0 * half, 2.0 * half).unwrap();
        let wall =
            ConvexPolygon::from_vertices(&[[-3.0, -1.0], [3.0, -1.0], [3.0, 0.0], [-3.0, 0.0]])
                .unwrap();
        let robot = Body::robot("R", square, Trajectory::new(samples.clone()).unwrap());
        let scene = Scene::with_bodies(delta, [robot, Body::obstacle("wall", &wall)]).unwrap();
        let segment = |activity, start, end| Segment {
            activity,
            start,
            end,
            leg: Some(0),
        };
        let schedule = |segments: Vec<Segment>| Schedule {
            robots: vec![Arc::new(RobotSchedule {
                route: vec![],
                segments,
                samples: samples.clone(),
                joints: vec![],
                path: vec![],
                end: 1000.0,
            })],
            makespan: 1000.0,
        };
        let moved = schedule(vec![
            segment(Activity::Move { from: 0, to: 0 }, 0.0, 1.0),
            segment(Activity::Wait(0), 1.0, 1000.0),
            segment(Activity::Done, 1000.0, f64::INFINITY),
        ]);
        let coarse = crate::collision::check(&scene, &CheckOptions::default());
        assert!(!coarse.collision && coarse.stats.grazing > 0 && !coarse.certified);
        let report = moved.check(&scene, &CheckOptions::default());
        assert!(report.verdict().is_certified_free(), "{report:?}");
        assert!(
            (report.time_tol - 1e-6).abs() < 1e-15,
            "{}",
            report.time_tol
        );
        // A tolerance given is kept, graze and all.
        let given = CheckOptions {
            time_tol: Some(coarse.time_tol),
            ..CheckOptions::default()
        };
        assert!(!moved.check(&scene, &given).certified);
        // Without a move to measure by, the makespan's tolerance stands.
        let still = schedule(vec![segment(Activity::Wait(0), 0.0, 1000.0)]);
        assert!(!still.check(&scene, &CheckOptions::default()).certified);
    }
}
