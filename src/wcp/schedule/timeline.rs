//! Building one robot's timed plan from its route and legs: each move taken from the
//! store, each task held, each wait, pause and parking laid on one time axis, and why that
//! can fail ([`BuildError`]). The `impl RobotSchedule` here is the one that builds; the
//! one that reads a built plan stands beside the type in `activity.rs`.

use super::activity::{route_nodes, Activity, RobotSchedule, Segment};
use crate::cell::Cell;
use crate::geometry::Vec2;
use crate::motion::{tool_pose, JointSample, Sample};
use crate::planning::PlannedMove;
use crate::wcp::legs::{HoldReason, Leg, Piece};
use crate::wcp::moves::{node_name, node_pose, MoveFailure, MoveStore};
use std::f64::consts::TAU;

/// Why a schedule cannot be built.
#[derive(Clone, Debug, PartialEq)]
pub enum BuildError {
    /// A robot has no certified move between two of its nodes.
    Move {
        /// The robot.
        robot: usize,
        /// The move's source node.
        from: usize,
        /// Its target node.
        to: usize,
        /// Why.
        why: MoveFailure,
    },
    /// A changed leg's motion does not start where the robot is, or the leg does not end at
    /// its end node.
    Discontinuous {
        /// The robot.
        robot: usize,
        /// The leg.
        leg: usize,
        /// When the robot would jump.
        time: f64,
    },
    /// At time `time`, f64 can no longer tell a robot's samples apart: durations and limits
    /// span too many orders of magnitude for one time axis.
    Precision {
        /// The robot.
        robot: usize,
        /// Where its samples merge.
        time: f64,
    },
}

impl BuildError {
    /// The robot concerned.
    pub fn robot(&self) -> usize {
        match self {
            BuildError::Move { robot, .. }
            | BuildError::Precision { robot, .. }
            | BuildError::Discontinuous { robot, .. } => *robot,
        }
    }

    /// Why, in words.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::legs::{default_legs, with_leg, Leg, Piece};
    /// use workcell::wcp::{BuildError, MoveStore, Schedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// // R2's first leg replaced by R1's move out of its home, far from R2.
    /// let wrong = [Piece::Go { motion: store.get(0, 0, 1).unwrap(), scale: 1.0 }];
    /// let legs = with_leg(&default_legs(2), 1, 0, Leg { wait: 0.0, pieces: Some(Arc::from(wrong)) });
    /// let e = Schedule::build(&cell, &[vec![0], vec![1]], &legs, &store).unwrap_err();
    /// assert!(matches!(e, BuildError::Discontinuous { robot: 1, leg: 0, .. }));
    /// assert!(e.reason(&cell).starts_with("its move 0 is not continuous"));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn reason(&self, cell: &Cell) -> String {
        match self {
            BuildError::Move {
                robot,
                from,
                to,
                why,
            } => format!(
                "{} cannot move from {} to {}: {why}",
                cell.robots[*robot].name,
                node_name(cell, *robot, *from),
                node_name(cell, *robot, *to)
            ),
            BuildError::Discontinuous { leg, time, .. } => format!(
                "its move {leg} is not continuous at t = {time}: each motion must start where \
                 the robot is (same position, same angle up to whole turns) and the move must \
                 end at its end node"
            ),
            BuildError::Precision { time, .. } => format!(
                "at t = {time:e} the time steps of its moves fall below what f64 resolves there \
                 ({:e}): task durations, waits and move times span too many orders of \
                 magnitude; rescale the time unit or the limits",
                time.abs() * f64::EPSILON
            ),
        }
    }
}

impl RobotSchedule {
    /// Times robot `r`'s route with its legs (missing ones default): from home at t = 0,
    /// every leg, every task held for its duration, back home. A robot without tasks stays
    /// home, unless its one leg is an excursion from home to home.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{Activity, MoveStore, RobotSchedule};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// // R1 does weld-1: out, the weld, back, then done.
    /// let r1 = RobotSchedule::build(&cell, 0, &[0], &[], &store).unwrap();
    /// let kinds: Vec<Activity> = r1.segments.iter().map(|s| s.activity).collect();
    /// assert_eq!(kinds, [Activity::Move { from: 0, to: 1 }, Activity::Work(0), Activity::Move { from: 1, to: 0 }, Activity::Done]);
    /// assert_eq!(r1.end, 2.0 * store.duration(0, 0, 1).unwrap() + 1.2);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn build(
        cell: &Cell,
        r: usize,
        route: &[usize],
        legs: &[Leg],
        moves: &MoveStore,
    ) -> Result<RobotSchedule, BuildError> {
        let mut line = Timeline::start(cell, r, moves);
        let nodes = route_nodes(route);
        let leg_count = if route.is_empty() {
            legs.len().min(1)
        } else {
            nodes.len() - 1
        };
        for m in 0..leg_count {
            let (from, to) = (nodes[m], nodes[m + 1]);
            let leg = legs.get(m).unwrap_or(&Leg::DEFAULT);
            line.wait(leg.wait, Activity::Wait(from), m)?;
            match &leg.pieces {
                None => {
                    let planned = moves.get(r, from, to).map_err(|why| BuildError::Move {
                        robot: r,
                        from,
                        to,
                        why,
                    })?;
                    line.go(&planned, Activity::Move { from, to }, m)?;
                }
                Some(pieces) => {
                    for piece in pieces.iter() {
                        match piece {
                            Piece::Go { motion, scale } if *scale == 1.0 => {
                                line.go(motion, Activity::Move { from, to }, m)?
                            }
                            Piece::Go { motion, scale } => {
                                line.go(&motion.slowed(*scale), Activity::Move { from, to }, m)?
                            }
                            Piece::Hold { duration, reason } => {
                                let activity = match reason {
                                    HoldReason::Pause => Activity::Pause { from, to },
                                    HoldReason::Park => Activity::Park { from, to },
                                };
                                line.wait(*duration, activity, m)?;
                            }
                        }
                    }
                }
            }
            if !line.is_at(cell, moves, to) {
                return Err(line.jump(m));
            }
            if to != 0 {
                let task = to - 1;
                line.wait(cell.tasks[task].duration, Activity::Work(task), m)?;
            }
        }
        Ok(line.finish(route))
    }
}

/// How far (radians, relative to the angle's size) a motion's first angle may be from the
/// robot's, up to whole turns: rounding of the turns added to keep the angle continuous.
const ANGLE_JOIN_TOL: f64 = 1e-9;

/// A robot's schedule under construction: samples, segments and path so far.
struct Timeline {
    robot: usize,
    samples: Vec<Sample>,
    segments: Vec<Segment>,
    path: Vec<Vec2>,
    now: f64,
    /// The angle so far, continuous: a move planned from a node's angle starts at that angle
    /// plus the whole turns the robot has made.
    theta: f64,
    /// An arm's joint samples so far (empty for a rigid robot; `samples` then follows its
    /// tool).
    joints: Vec<JointSample>,
    /// Per joint of an arm, whether it turns freely (no limits): only such a joint may stand
    /// whole turns away from a node's angle.
    free: Vec<bool>,
}

impl Timeline {
    fn start(cell: &Cell, r: usize, moves: &MoveStore) -> Timeline {
        let (home, joints, free) = match cell.robots[r].as_arm() {
            None => (node_pose(cell, r, 0), Vec::new(), Vec::new()),
            Some(arm) => {
                let lengths: Vec<f64> = arm.links.iter().map(|l| l.0).collect();
                let q = moves
                    .assignment()
                    .joints(cell, r, 0)
                    .expect("an arm's home");
                let rest = JointSample {
                    t: 0.0,
                    q: q.to_vec(),
                    qd: vec![0.0; q.len()],
                };
                let free = arm.limits.range.iter().map(Option::is_none).collect();
                (tool_pose(arm.base, &lengths, q), vec![rest], free)
            }
        };
        Timeline {
            robot: r,
            samples: vec![rest(0.0, home.pos, home.theta)],
            segments: Vec::new(),
            path: vec![home.pos],
            now: 0.0,
            theta: home.theta,
            joints,
            free,
        }
    }

    /// Whether the robot stands at node `node`: its position there (a rigid robot), or its
    /// joints at the node's angles (an arm; a free joint up to whole turns, each within the
    /// rounding of the moves' ends).
    fn is_at(&self, cell: &Cell, moves: &MoveStore, node: usize) -> bool {
        let Some(last) = self.joints.last() else {
            return self.position() == node_pose(cell, self.robot, node).pos;
        };
        let Some(q) = moves.assignment().joints(cell, self.robot, node) else {
            return false;
        };
        (0..q.len()).all(|j| self.whole_turns(j, last.q[j], q[j]).is_some())
    }

    /// The whole turns from angle `b` to angle `a` of joint `j` when they are the same up to
    /// rounding (none for a joint with limits), `None` when they differ.
    fn whole_turns(&self, j: usize, a: f64, b: f64) -> Option<f64> {
        let whole = if self.free[j] {
            TAU * ((a - b) / TAU).round()
        } else {
            0.0
        };
        ((a - b - whole).abs() <= ANGLE_JOIN_TOL * (1.0 + a.abs())).then_some(whole)
    }

    fn precision(&self, time: f64) -> BuildError {
        BuildError::Precision {
            robot: self.robot,
            time,
        }
    }

    /// Stands still for `duration` doing `activity`. A positive hold must leave a trace on
    /// the time axis: one that f64 rounds away would vanish from the schedule.
    fn wait(&mut self, duration: f64, activity: Activity, leg: usize) -> Result<(), BuildError> {
        if duration <= 0.0 {
            if activity_is_task(activity) {
                self.push(activity, self.now, leg);
            }
            return Ok(());
        }
        let end = self.now + duration;
        if end <= self.now || !end.is_finite() {
            return Err(self.precision(self.now));
        }
        let pos = self.samples.last().expect("starts with a sample").pos;
        self.push(activity, end, leg);
        self.samples.push(rest(end, pos, self.theta));
        if let Some(last) = self.joints.last() {
            let q = last.q.clone();
            self.joints.push(JointSample {
                t: end,
                qd: vec![0.0; q.len()],
                q,
            });
        }
        Ok(())
    }

    fn position(&self) -> Vec2 {
        self.samples.last().expect("starts with a sample").pos
    }

    fn jump(&self, leg: usize) -> BuildError {
        BuildError::Discontinuous {
            robot: self.robot,
            leg,
            time: self.now,
        }
    }

    /// Makes a planned motion from where the robot is.
    fn go(
        &mut self,
        planned: &PlannedMove,
        activity: Activity,
        leg: usize,
    ) -> Result<(), BuildError> {
        if !self.joints.is_empty() {
            return self.go_joints(planned, activity, leg);
        }
        let first = &planned.samples[0];
        let turns = TAU * ((self.theta - first.theta) / TAU).round();
        let off = (self.theta - first.theta - turns).abs();
        if first.pos != self.position() || off > ANGLE_JOIN_TOL * (1.0 + self.theta.abs()) {
            return Err(self.jump(leg));
        }
        // The first sample is where the robot already is; every later one must come later
        // on the time axis, or the move would silently vanish.
        for s in &planned.samples[1..] {
            let t = self.now + s.t;
            if t <= self.samples.last().expect("starts with a sample").t {
                return Err(self.precision(t));
            }
            self.samples.push(Sample {
                t,
                theta: s.theta + turns,
                ..*s
            });
        }
        self.path.extend(planned.path.iter().skip(1));
        self.theta = planned.samples.last().expect("a move has samples").theta + turns;
        self.push(activity, self.now + planned.duration, leg);
        Ok(())
    }

    /// An arm's [`Timeline::go`]: its joints from where they are (a free joint whole turns
    /// away from the move's first angle keeps those turns), its tool's samples beside them.
    fn go_joints(
        &mut self,
        planned: &PlannedMove,
        activity: Activity,
        leg: usize,
    ) -> Result<(), BuildError> {
        let now_q = &self.joints.last().expect("starts with a sample").q;
        let first = &planned.joints.first().ok_or_else(|| self.jump(leg))?.q;
        let turns = (0..now_q.len())
            .map(|j| self.whole_turns(j, now_q[j], first[j]))
            .collect::<Option<Vec<f64>>>()
            .ok_or_else(|| self.jump(leg))?;
        for (s, js) in planned.samples[1..].iter().zip(&planned.joints[1..]) {
            let t = self.now + s.t;
            if t <= self.samples.last().expect("starts with a sample").t {
                return Err(self.precision(t));
            }
            self.samples.push(Sample { t, ..*s });
            self.joints.push(JointSample {
                t,
                q: js.q.iter().zip(&turns).map(|(q, k)| q + k).collect(),
                qd: js.qd.clone(),
            });
        }
        self.path.extend(planned.path.iter().skip(1));
        self.theta = planned.samples.last().expect("a move has samples").theta;
        self.push(activity, self.now + planned.duration, leg);
        Ok(())
    }

    fn push(&mut self, activity: Activity, end: f64, leg: usize) {
        self.segments.push(Segment {
            activity,
            start: self.now,
            end,
            leg: Some(leg),
        });
        self.now = end;
    }

    fn finish(mut self, route: &[usize]) -> RobotSchedule {
        // The last sample is the arrival home (or the start, for a robot that stays home).
        let end = self.samples.last().expect("starts with a sample").t;
        self.segments.push(Segment {
            activity: Activity::Done,
            start: end,
            end: f64::INFINITY,
            leg: None,
        });
        RobotSchedule {
            route: route.to_vec(),
            segments: self.segments,
            samples: self.samples,
            joints: self.joints,
            path: self.path,
            end,
        }
    }
}

fn activity_is_task(a: Activity) -> bool {
    matches!(a, Activity::Work(_))
}

fn rest(t: f64, pos: Vec2, theta: f64) -> Sample {
    Sample {
        t,
        pos,
        theta,
        vel: Vec2::zeros(),
        omega: 0.0,
    }
}
