//! The timed schedule of every robot ([`Schedule`]): built robot by robot, turned into the
//! checker's scene, and a check's first contact located back on the robots, their
//! activities and their legs ([`Collision`]).

use super::activity::{RobotSchedule, Segment};
use super::timeline::BuildError;
use crate::cell::{Cell, RobotKind};
use crate::collision::{Body, CheckReport, Scene};
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
        let robots = (0..self.robots.len()).flat_map(|r| self.bodies(cell, r));
        Scene {
            delta: cell.delta,
            bodies: robots.chain(cell.obstacle_bodies()).collect(),
        }
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

    /// Robot `r` as checker bodies: one for a rigid robot, one per link for an arm.
    fn bodies(&self, cell: &Cell, r: usize) -> Vec<Body> {
        let name = &cell.robots[r].name;
        match &cell.robots[r].kind {
            RobotKind::Rigid(robot) => vec![robot.body(
                name,
                Trajectory::new(self.robots[r].samples.clone())
                    .expect("schedules sample increasing times"),
            )],
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
