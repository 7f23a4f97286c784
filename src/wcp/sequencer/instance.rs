//! The data of one sequencing problem and the cost of a plan.

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
    pub fn bounds(&self) -> Option<&Bounds> {
        match &self.travel {
            Travel::Dense(_) => None,
            Travel::Bounded { bounds, .. } => Some(bounds),
        }
    }

    /// Whether the travel time of robot `r` from `from` to `to` is exact (always, unless
    /// the instance is bounded and does not hold it).
    pub fn is_exact(&self, r: usize, from: usize, to: usize) -> bool {
        match &self.travel {
            Travel::Dense(_) => true,
            Travel::Bounded { exact, .. } => from == to || exact[r].contains_key(&(from, to)),
        }
    }

    /// Builds the matrices from `travel(robot, from_node, to_node)`.
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
    pub fn route_time(&self, r: usize, seq: &[usize]) -> f64 {
        // Summed left to right, as the exact search does, so equal plans cost
        // exactly the same whichever way they were found.
        let mut acc = 0.0;
        let mut prev = 0;
        for &t in seq {
            acc += self.travel(r, prev, t + 1);
            acc += self.duration[t];
            prev = t + 1;
        }
        if !seq.is_empty() {
            acc += self.travel(r, prev, 0);
        }
        acc
    }

    /// Longest route time; `seqs[r]` is robot `r`'s route (missing robots stay home).
    pub fn makespan(&self, seqs: &[Vec<usize>]) -> f64 {
        seqs.iter()
            .enumerate()
            .map(|(r, s)| self.route_time(r, s))
            .fold(0.0, f64::max)
    }

    /// Sum of the route times, in robot order.
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
