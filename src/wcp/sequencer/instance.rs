//! The data of one sequencing problem and the cost of a plan.

use super::terms::task_node;
use std::collections::HashMap;
use std::sync::Arc;

use super::bounds::Bounds;
use super::SequencerError;

/// Travel times known exactly, per robot: `(from, to)` to the time (infinite: no move).
pub type ExactArcs = Vec<HashMap<(usize, usize), f64>>;

/// Where an instance's travel times come from.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Travel {
    /// Per robot, `(tasks + 1)²` travel times in row-major order (from, to).
    Dense(Vec<Vec<f64>>),
    /// Exact times where known, lower bounds elsewhere.
    Bounded {
        bounds: Arc<Bounds>,
        exact: Arc<ExactArcs>,
    },
}

/// Robots, tasks, who may do what and the travel times.
///
/// Node indices inside one robot's matrix: 0 = the robot's home, `1 + t` = task `t`.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// Number of robots.
    pub robots: usize,
    /// Number of tasks.
    pub tasks: usize,
    /// How long the robot doing task `t` stays at it: `duration[t]`, finite and >= 0.
    pub duration: Vec<f64>,
    /// `allowed[r][t]`: robot `r` may do task `t`.
    pub allowed: Vec<Vec<bool>>,
    pub(super) travel: Travel,
}

impl Instance {
    /// Checks and wraps the data: `allowed` has one row of `duration.len()`
    /// flags per robot; `travel` one row-major `(tasks + 1)²` matrix per robot,
    /// whose entries are >= 0 or `f64::INFINITY` (no move). The diagonal is
    /// never used.
    ///
    /// ```
    /// use workcell::wcp::sequencer::Instance;
    /// let inf = f64::INFINITY;
    /// // One robot, one task; row-major (tasks + 1)² travel matrix: home <-> task 2 each way.
    /// let inst = Instance::new(vec![1.0], vec![vec![true]], vec![vec![0.0, 2.0, 2.0, 0.0]])?;
    /// assert_eq!(inst.route_time(0, &[0]), 5.0);
    /// // A missing move is allowed (infinite), a negative one is not.
    /// assert!(Instance::new(vec![1.0], vec![vec![true]], vec![vec![0.0, inf, 2.0, 0.0]]).is_ok());
    /// assert!(Instance::new(vec![1.0], vec![vec![true]], vec![vec![0.0, -2.0, 2.0, 0.0]]).is_err());
    /// # Ok::<(), workcell::wcp::sequencer::SequencerError>(())
    /// ```
    pub fn new(
        duration: Vec<f64>,
        allowed: Vec<Vec<bool>>,
        travel: Vec<Vec<f64>>,
    ) -> Result<Self, SequencerError> {
        let inst = Instance {
            robots: allowed.len(),
            tasks: duration.len(),
            duration,
            allowed,
            travel: Travel::Dense(Vec::new()),
        };
        inst.check()?;
        let n1 = inst.tasks + 1;
        if travel.len() != inst.robots {
            return Err(bad(format!(
                "{} travel matrices for {} robots",
                travel.len(),
                inst.robots
            )));
        }
        for (r, m) in travel.iter().enumerate() {
            if m.len() != n1 * n1 {
                return Err(bad(format!(
                    "robot {r}: {} travel times, not {}",
                    m.len(),
                    n1 * n1
                )));
            }
            for (k, &v) in m.iter().enumerate() {
                let (from, to) = (k / n1, k % n1);
                if from != to && (v.is_nan() || v < 0.0) {
                    return Err(bad(format!("robot {r}: travel {from} -> {to} is {v}")));
                }
            }
        }
        Ok(Instance {
            travel: Travel::Dense(travel),
            ..inst
        })
    }

    /// An instance whose travel times are `exact` where it holds them (infinite: no move)
    /// and the lower bounds of `bounds` elsewhere. Nothing is stored per pair of nodes.
    ///
    /// ```
    /// use std::{collections::HashMap, sync::Arc};
    /// use workcell::wcp::sequencer::Instance;
    /// use workcell::geometry::Vec2;
    /// use workcell::wcp::sequencer::{BoundLimits, Bounds};
    /// let limits = BoundLimits { max_speed: 1.0, max_accel: 2.0, max_angular_accel: 2.0, max_turn_rate: 1.0 };
    /// let at = |x: f64, y: f64| (Vec2::new(x, y), 0.0);
    /// let b = Bounds::new(vec![limits], vec![at(0.0, 0.0)], vec![at(3.0, 4.0), at(6.0, 8.0)]);
    /// // The move home -> task 0 is known (9 s, around something); the others are bounds.
    /// let exact = vec![HashMap::from([((0, 1), 9.0)])];
    /// let inst = Instance::bounded(vec![1.0, 1.0], vec![vec![true, true]], Arc::new(b.clone()), Arc::new(exact))?;
    /// assert_eq!((inst.travel(0, 0, 1), inst.is_exact(0, 0, 1)), (9.0, true));
    /// assert_eq!((inst.travel(0, 1, 2), inst.is_exact(0, 1, 2)), (b.bound(0, 1, 2), false));
    /// assert_eq!(inst.bounds(), Some(&b));
    /// # Ok::<(), workcell::wcp::sequencer::SequencerError>(())
    /// ```
    pub fn bounded(
        duration: Vec<f64>,
        allowed: Vec<Vec<bool>>,
        bounds: Arc<Bounds>,
        exact: Arc<ExactArcs>,
    ) -> Result<Self, SequencerError> {
        let inst = Instance {
            robots: allowed.len(),
            tasks: duration.len(),
            duration,
            allowed,
            travel: Travel::Dense(Vec::new()),
        };
        inst.check()?;
        if bounds.robots() != inst.robots || bounds.tasks() != inst.tasks {
            return Err(bad(format!(
                "bounds for {} robots and {} tasks, not {} and {}",
                bounds.robots(),
                bounds.tasks(),
                inst.robots,
                inst.tasks
            )));
        }
        if exact.len() != inst.robots {
            return Err(bad(format!(
                "{} exact tables for {} robots",
                exact.len(),
                inst.robots
            )));
        }
        for (r, arcs) in exact.iter().enumerate() {
            for (&(from, to), &v) in arcs {
                if from > inst.tasks || to > inst.tasks || v.is_nan() || v < 0.0 {
                    return Err(bad(format!("robot {r}: travel {from} -> {to} is {v}")));
                }
            }
        }
        Ok(Instance {
            travel: Travel::Bounded { bounds, exact },
            ..inst
        })
    }

    /// The lower bounds of a bounded instance.
    ///
    /// ```
    /// use workcell::wcp::sequencer::Instance;
    /// // One robot, home at 0, tasks at 1 and 3 on a line (unit speed), each lasting 0.5.
    /// let pos = [0.0, 1.0, 3.0];
    /// let inst = Instance::from_fn(vec![0.5, 0.5], vec![vec![true, true]], |_, a, b| f64::abs(pos[a] - pos[b]))?;
    /// assert!(inst.bounds().is_none()); // matrices, not bounds
    /// # Ok::<(), workcell::wcp::sequencer::SequencerError>(())
    /// ```
    pub fn bounds(&self) -> Option<&Bounds> {
        match &self.travel {
            Travel::Dense(_) => None,
            Travel::Bounded { bounds, .. } => Some(bounds),
        }
    }

    /// Whether the travel time of robot `r` from `from` to `to` is exact (always, unless
    /// the instance is bounded and does not hold it).
    ///
    /// ```
    /// use workcell::wcp::sequencer::Instance;
    /// // One robot, home at 0, tasks at 1 and 3 on a line (unit speed), each lasting 0.5.
    /// let pos = [0.0, 1.0, 3.0];
    /// let inst = Instance::from_fn(vec![0.5, 0.5], vec![vec![true, true]], |_, a, b| f64::abs(pos[a] - pos[b]))?;
    /// assert!(inst.is_exact(0, 1, 2)); // a matrix holds every time
    /// # Ok::<(), workcell::wcp::sequencer::SequencerError>(())
    /// ```
    pub fn is_exact(&self, r: usize, from: usize, to: usize) -> bool {
        match &self.travel {
            Travel::Dense(_) => true,
            Travel::Bounded { exact, .. } => from == to || exact[r].contains_key(&(from, to)),
        }
    }

    /// Builds the matrices from `travel(robot, from_node, to_node)`.
    ///
    /// ```
    /// use workcell::wcp::sequencer::Instance;
    /// // One robot, home at 0, tasks at 1 and 3 on a line (unit speed), each lasting 0.5.
    /// let pos = [0.0, 1.0, 3.0];
    /// let inst = Instance::from_fn(vec![0.5, 0.5], vec![vec![true, true]], |_, a, b| f64::abs(pos[a] - pos[b]))?;
    /// assert_eq!((inst.robots, inst.tasks), (1, 2));
    /// assert_eq!(inst.travel(0, 2, 1), 2.0);
    /// # Ok::<(), workcell::wcp::sequencer::SequencerError>(())
    /// ```
    pub fn from_fn(
        duration: Vec<f64>,
        allowed: Vec<Vec<bool>>,
        mut travel: impl FnMut(usize, usize, usize) -> f64,
    ) -> Result<Self, SequencerError> {
        let n1 = duration.len() + 1;
        let matrices = (0..allowed.len())
            .map(|r| (0..n1 * n1).map(|k| travel(r, k / n1, k % n1)).collect())
            .collect();
        Instance::new(duration, allowed, matrices)
    }

    /// Travel time of robot `r` from node `from` to node `to` (a lower bound where a
    /// bounded instance does not know it).
    ///
    /// ```
    /// use workcell::wcp::sequencer::Instance;
    /// // One robot, home at 0, tasks at 1 and 3 on a line (unit speed), each lasting 0.5.
    /// let pos = [0.0, 1.0, 3.0];
    /// let inst = Instance::from_fn(vec![0.5, 0.5], vec![vec![true, true]], |_, a, b| f64::abs(pos[a] - pos[b]))?;
    /// assert_eq!((inst.travel(0, 0, 2), inst.travel(0, 1, 2)), (3.0, 2.0));
    /// # Ok::<(), workcell::wcp::sequencer::SequencerError>(())
    /// ```
    pub fn travel(&self, r: usize, from: usize, to: usize) -> f64 {
        match &self.travel {
            Travel::Dense(m) => m[r][from * (self.tasks + 1) + to],
            Travel::Bounded { bounds, exact } => match exact[r].get(&(from, to)) {
                Some(&v) => v,
                None if from == to => 0.0,
                None => bounds.bound(r, from, to),
            },
        }
    }

    /// Time robot `r` needs to do the tasks of `seq` in order and come back
    /// home (0 for an empty route; infinite if an arc is missing). The
    /// `allowed` flags are not checked.
    ///
    /// ```
    /// use workcell::wcp::sequencer::Instance;
    /// // One robot, home at 0, tasks at 1 and 3 on a line (unit speed), each lasting 0.5.
    /// let pos = [0.0, 1.0, 3.0];
    /// let inst = Instance::from_fn(vec![0.5, 0.5], vec![vec![true, true]], |_, a, b| f64::abs(pos[a] - pos[b]))?;
    /// // 0 -> 1 -> 3 -> 0 with two tasks of 0.5: 1 + 0.5 + 2 + 0.5 + 3.
    /// assert_eq!(inst.route_time(0, &[0, 1]), 7.0);
    /// assert_eq!(inst.route_time(0, &[]), 0.0);
    /// # Ok::<(), workcell::wcp::sequencer::SequencerError>(())
    /// ```
    pub fn route_time(&self, r: usize, seq: &[usize]) -> f64 {
        // Summed left to right, as the exact search does, so equal plans cost
        // exactly the same whichever way they were found.
        let mut acc = 0.0;
        let mut prev = 0;
        for &t in seq {
            acc += self.travel(r, prev, task_node(t));
            acc += self.duration[t];
            prev = task_node(t);
        }
        if !seq.is_empty() {
            acc += self.travel(r, prev, 0);
        }
        acc
    }

    /// Longest route time; `seqs[r]` is robot `r`'s route (missing robots stay home).
    ///
    /// ```
    /// use workcell::wcp::sequencer::Instance;
    /// // Two robots with homes at 0 and 4, tasks at 1 and 3 on a line, each lasting 0.5.
    /// let (homes, tasks) = ([0.0, 4.0], [1.0, 3.0]);
    /// let at = |r: usize, n: usize| if n == 0 { homes[r] } else { tasks[n - 1] };
    /// let inst = Instance::from_fn(vec![0.5, 0.5], vec![vec![true, true]; 2], |r, a, b| f64::abs(at(r, a) - at(r, b)))?;
    /// assert_eq!(inst.makespan(&[vec![0], vec![1]]), 2.5);
    /// assert_eq!(inst.makespan(&[vec![0, 1]]), 7.0); // robot 1 left out: it stays home
    /// # Ok::<(), workcell::wcp::sequencer::SequencerError>(())
    /// ```
    pub fn makespan(&self, seqs: &[Vec<usize>]) -> f64 {
        seqs.iter()
            .enumerate()
            .map(|(r, s)| self.route_time(r, s))
            .fold(0.0, f64::max)
    }

    /// Sum of the route times, in robot order.
    ///
    /// ```
    /// use workcell::wcp::sequencer::Instance;
    /// let (homes, tasks) = ([0.0, 4.0], [1.0, 3.0]);
    /// let at = |r: usize, n: usize| if n == 0 { homes[r] } else { tasks[n - 1] };
    /// let inst = Instance::from_fn(vec![0.5, 0.5], vec![vec![true, true]; 2], |r, a, b| f64::abs(at(r, a) - at(r, b)))?;
    /// assert_eq!(inst.total(&[vec![0], vec![1]]), 5.0); // 2.5 each
    /// # Ok::<(), workcell::wcp::sequencer::SequencerError>(())
    /// ```
    pub fn total(&self, seqs: &[Vec<usize>]) -> f64 {
        seqs.iter()
            .enumerate()
            .map(|(r, s)| self.route_time(r, s))
            .sum()
    }

    /// Checks the public fields again: they may have been changed since [`Instance::new`].
    pub(super) fn check(&self) -> Result<(), SequencerError> {
        if self.duration.len() != self.tasks {
            return Err(bad(format!(
                "{} durations for {} tasks",
                self.duration.len(),
                self.tasks
            )));
        }
        if self.allowed.len() != self.robots {
            return Err(bad(format!(
                "{} rows of allowed tasks for {} robots",
                self.allowed.len(),
                self.robots
            )));
        }
        if let Some(r) = self.allowed.iter().position(|row| row.len() != self.tasks) {
            return Err(bad(format!(
                "robot {r}: allowed has not {} flags",
                self.tasks
            )));
        }
        if let Some(t) = self
            .duration
            .iter()
            .position(|d| !(d.is_finite() && *d >= 0.0))
        {
            return Err(bad(format!("task {t}: duration {}", self.duration[t])));
        }
        Ok(())
    }
}

fn bad(msg: String) -> SequencerError {
    SequencerError::BadInstance(msg)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line() -> Instance {
        let x = [0.0, 1.0, 3.0];
        Instance::from_fn(vec![0.5, 0.25], vec![vec![true, true]], |_, a, b| {
            f64::abs(x[a] - x[b])
        })
        .unwrap()
    }

    #[test]
    fn route_time_sums_arcs_and_durations() {
        let inst = line();
        assert_eq!(inst.route_time(0, &[]), 0.0);
        assert_eq!(inst.route_time(0, &[0, 1]), 1.0 + 0.5 + 2.0 + 0.25 + 3.0);
        assert_eq!(inst.makespan(&[vec![1]]), 6.25);
        assert_eq!(inst.total(&[vec![1, 0]]), 6.75);
    }

    #[test]
    fn rejects_bad_data() {
        let ok = |v: f64| Instance::new(vec![1.0], vec![vec![true]], vec![vec![0.0, v, 1.0, 0.0]]);
        assert!(ok(f64::INFINITY).is_ok());
        assert!(ok(f64::NAN).is_err());
        assert!(ok(-1.0).is_err());
        assert!(Instance::new(vec![f64::NAN], vec![vec![true]], vec![vec![0.0; 4]]).is_err());
        assert!(Instance::new(vec![1.0], vec![vec![true]], vec![vec![0.0; 3]]).is_err());
        assert!(Instance::new(vec![1.0], vec![vec![true, false]], vec![vec![0.0; 4]]).is_err());
        assert!(Instance::new(vec![1.0], vec![vec![true]], vec![]).is_err());
    }
}
