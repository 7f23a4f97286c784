//! Joint-space paths around fixtures (contract section 7): where the straight joint-space
//! move hits a fixture, RRT-Connect in the joints (Kuffner & LaValle, ICRA 2000) finds
//! waypoints whose every edge the checker certifies clear, deterministic under the seed; the
//! path is then shortened by joining waypoints directly wherever that is clear too.

use super::arm_reach::ArmModel;
use super::joint_move::{joint_move, JointMove};
use crate::collision::Body;
use crate::motion::JointSample;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{PI, TAU};

/// How hard to look for a path, and how fine its steps are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointPathSettings {
    /// The largest step of the trees, in joint space (radians, the largest joint's change).
    pub step: f64,
    /// At most this many random samples before giving up.
    pub max_samples: usize,
    /// The seed of the samples.
    pub seed: u64,
    /// Samples per profile phase of each move (see [`joint_move`]).
    pub samples_per_phase: usize,
}

impl Default for JointPathSettings {
    fn default() -> Self {
        JointPathSettings {
            step: 0.3,
            max_samples: 2000,
            seed: 0,
            samples_per_phase: 4,
        }
    }
}

/// A move through joint-space waypoints, rest to rest at each: the waypoints and the move,
/// every edge certified clear of the fixtures.
#[derive(Clone, Debug, PartialEq)]
pub struct JointPath {
    /// From the start to the goal (up to whole turns of free joints).
    pub waypoints: Vec<Vec<f64>>,
    /// The edges one after the other.
    pub motion: JointMove,
}

/// One tree of RRT-Connect: configurations and each one's parent.
struct Tree {
    nodes: Vec<Vec<f64>>,
    parent: Vec<usize>,
}

impl Tree {
    fn nearest(&self, arm: &ArmModel, q: &[f64]) -> usize {
        let d = |k: &usize| distance(arm, &self.nodes[*k], q);
        (0..self.nodes.len())
            .min_by(|a, b| d(a).total_cmp(&d(b)))
            .expect("a tree has its root")
    }

    /// The path from the root to node `k`.
    fn path_to(&self, mut k: usize) -> Vec<Vec<f64>> {
        let mut out = vec![self.nodes[k].clone()];
        while k != 0 {
            k = self.parent[k];
            out.push(self.nodes[k].clone());
        }
        out.reverse();
        out
    }
}

/// The joint-space change from `a` to `b`: the shorter way for a joint without limits.
fn delta(arm: &ArmModel, a: &[f64], b: &[f64]) -> Vec<f64> {
    (0..a.len())
        .map(|j| match arm.limits.range.get(j).copied().flatten() {
            Some(_) => b[j] - a[j],
            None => {
                let w = (b[j] - a[j]).rem_euclid(TAU);
                if w > PI {
                    w - TAU
                } else {
                    w
                }
            }
        })
        .collect()
}

fn distance(arm: &ArmModel, a: &[f64], b: &[f64]) -> f64 {
    delta(arm, a, b).iter().fold(0.0, |m, d| m.max(d.abs()))
}

impl ArmModel {
    /// The straight joint-space move from `from` to `to` when it is clear of the fixtures,
    /// else a path around them found by RRT-Connect and shortened; `None` when none is found
    /// within the settings' samples.
    ///
    /// ```
    /// use workcell::collision::Body;
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// use workcell::motion::Pose;
    /// use workcell::motion::JointLimits;
    /// use workcell::planning::{ArmModel, JointPathSettings};
    /// let bar = |l: f64| Parts::new(vec![ConvexPolygon::from_vertices(&[[-0.05, -0.05], [l + 0.05, -0.05], [l + 0.05, 0.05], [-0.05, 0.05]])?]);
    /// let limits = JointLimits { range: vec![None, None], max_speed: vec![1.0, 1.0], max_accel: vec![2.0, 2.0] };
    /// let arm = ArmModel { name: "A1".into(), base: Pose::new(0.0, 0.0, 0.0), links: vec![(1.0, bar(1.0)?), (1.0, bar(1.0)?)], limits };
    /// // A post in the quarter the straight arm sweeps, beyond the folded arm's reach.
    /// let post = Body::obstacle("post", &ConvexPolygon::from_vertices(&[[1.1, 1.1], [1.3, 1.1], [1.3, 1.3], [1.1, 1.3]])?);
    /// let path = arm.joint_path(&[0.0, 0.0], &[1.57, 0.0], &[post], 0.01, &JointPathSettings::default()).expect("a path");
    /// assert!(path.waypoints.len() > 2); // around the post: the elbow folds on the way
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn joint_path(
        &self,
        from: &[f64],
        to: &[f64],
        fixtures: &[Body],
        delta_: f64,
        s: &JointPathSettings,
    ) -> Option<JointPath> {
        let clear = |a: &[f64], b: &[f64]| {
            let m = joint_move(a, b, &self.limits, s.samples_per_phase);
            self.move_is_clear(&m, fixtures, delta_)
        };
        let waypoints = if clear(from, to) {
            vec![from.to_vec(), to.to_vec()]
        } else {
            let found = self.rrt_connect(from, to, &clear, s)?;
            shortened(found, &clear)
        };
        Some(JointPath {
            motion: self.chained(&waypoints, s.samples_per_phase),
            waypoints,
        })
    }

    /// RRT-Connect between `from` and `to`: a tree from each, one extended towards a random
    /// configuration, the other connected towards the new node, roles swapped each round.
    fn rrt_connect(
        &self,
        from: &[f64],
        to: &[f64],
        clear: &dyn Fn(&[f64], &[f64]) -> bool,
        s: &JointPathSettings,
    ) -> Option<Vec<Vec<f64>>> {
        let mut rng = ChaCha8Rng::seed_from_u64(s.seed);
        let root = |q: &[f64]| Tree {
            nodes: vec![q.to_vec()],
            parent: vec![0],
        };
        let (mut a, mut b) = (root(from), root(to));
        let mut a_is_start = true;
        for _ in 0..s.max_samples {
            let target: Vec<f64> = (0..from.len())
                .map(|j| match self.limits.range.get(j).copied().flatten() {
                    Some([lo, hi]) => rng.random_range(lo..=hi),
                    None => rng.random_range(-PI..PI),
                })
                .collect();
            if let Some(new) = self.extend(&mut a, &target, clear, s.step) {
                let q = a.nodes[new].clone();
                // Connect: step the other tree towards the new node while each step is clear.
                let mut reached = None;
                while let Some(k) = self.extend(&mut b, &q, clear, s.step) {
                    if distance(self, &b.nodes[k], &q) <= 1e-12 {
                        reached = Some(k);
                        break;
                    }
                }
                if let Some(k) = reached {
                    let (mut start, mut goal) = (a.path_to(new), b.path_to(k));
                    if !a_is_start {
                        std::mem::swap(&mut start, &mut goal);
                    }
                    goal.pop(); // the meeting node, once
                    goal.reverse();
                    start.extend(goal);
                    return Some(start);
                }
            }
            std::mem::swap(&mut a, &mut b);
            a_is_start = !a_is_start;
        }
        None
    }

    /// Adds to `tree` the step from its nearest node towards `target` (at most `step`), when
    /// that edge is clear; its index.
    fn extend(
        &self,
        tree: &mut Tree,
        target: &[f64],
        clear: &dyn Fn(&[f64], &[f64]) -> bool,
        step: f64,
    ) -> Option<usize> {
        let near = tree.nearest(self, target);
        let q = &tree.nodes[near];
        let d = delta(self, q, target);
        let length = d.iter().fold(0.0, |m: f64, x| m.max(x.abs()));
        let scale = if length <= step { 1.0 } else { step / length };
        let new: Vec<f64> = q.iter().zip(&d).map(|(a, x)| a + x * scale).collect();
        if length <= 1e-12 || !clear(q, &new) {
            return None;
        }
        tree.nodes.push(new);
        tree.parent.push(near);
        Some(tree.nodes.len() - 1)
    }

    /// The move through `waypoints` (at least one), rest to rest at each: what
    /// [`ArmModel::joint_path`] returns for its waypoints, sample for sample, so that a path
    /// written as its waypoints is replayed exactly.
    ///
    /// ```
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// use workcell::motion::{JointLimits, Pose};
    /// use workcell::planning::{joint_move, ArmModel};
    /// let bar = Parts::new(vec![ConvexPolygon::from_vertices(&[[-0.05, -0.05], [1.05, -0.05], [1.05, 0.05], [-0.05, 0.05]])?])?;
    /// let limits = JointLimits { range: vec![None], max_speed: vec![1.0], max_accel: vec![1.0] };
    /// let arm = ArmModel { name: "A1".into(), base: Pose::new(0.0, 0.0, 0.0), links: vec![(1.0, bar)], limits };
    /// let there = arm.through(&[vec![0.0], vec![1.0]], 4);
    /// assert_eq!(there, joint_move(&[0.0], &[1.0], &arm.limits, 4));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn through(&self, waypoints: &[Vec<f64>], samples_per_phase: usize) -> JointMove {
        self.chained(waypoints, samples_per_phase)
    }

    /// The rest-to-rest moves between consecutive waypoints, one after the other.
    fn chained(&self, waypoints: &[Vec<f64>], samples_per_phase: usize) -> JointMove {
        let mut samples: Vec<JointSample> = Vec::new();
        let mut t0 = 0.0;
        let mut at = waypoints[0].clone();
        for next in &waypoints[1..] {
            let m = joint_move(&at, next, &self.limits, samples_per_phase);
            // Each move starts where the last one stopped (its first sample is that one).
            let skip = usize::from(!samples.is_empty());
            samples.extend(m.samples.iter().skip(skip).map(|s| JointSample {
                t: t0 + s.t,
                ..s.clone()
            }));
            t0 += m.duration;
            at = m.end().to_vec();
        }
        if samples.is_empty() {
            samples.push(JointSample {
                t: 0.0,
                q: at.clone(),
                qd: vec![0.0; at.len()],
            });
        }
        JointMove {
            duration: t0,
            samples,
        }
    }
}

/// `path` with every waypoint dropped that the one before can skip: from each kept waypoint,
/// the farthest later one it reaches clearly.
fn shortened(path: Vec<Vec<f64>>, clear: &dyn Fn(&[f64], &[f64]) -> bool) -> Vec<Vec<f64>> {
    let mut out = vec![path[0].clone()];
    let mut i = 0;
    while i + 1 < path.len() {
        let j = (i + 1..path.len())
            .rev()
            .find(|&j| j == i + 1 || clear(&path[i], &path[j]))
            .expect("the next waypoint is always reachable");
        out.push(path[j].clone());
        i = j;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::ConvexPolygon;
    use crate::motion::JointLimits;
    use crate::motion::Pose;
    use crate::planning::arm_reach::tests::bar;

    fn arm() -> ArmModel {
        ArmModel {
            name: "A1".into(),
            base: Pose::new(0.0, 0.0, 0.0),
            links: vec![(1.0, bar(1.0)), (1.0, bar(1.0))],
            limits: JointLimits {
                range: vec![None, Some([-2.9, 2.9])],
                max_speed: vec![1.0, 1.5],
                max_accel: vec![2.0, 3.0],
            },
        }
    }

    fn post(x: f64, y: f64) -> Body {
        let c = [
            [x - 0.1, y - 0.1],
            [x + 0.1, y - 0.1],
            [x + 0.1, y + 0.1],
            [x - 0.1, y + 0.1],
        ];
        Body::obstacle("post", &ConvexPolygon::from_vertices(&c).unwrap())
    }

    #[test]
    fn a_clear_move_is_straight() {
        let s = JointPathSettings::default();
        let path = arm().joint_path(&[0.0, 0.0], &[1.0, 0.5], &[post(-1.5, 0.0)], 0.01, &s);
        assert_eq!(path.unwrap().waypoints.len(), 2);
    }

    #[test]
    fn a_blocked_move_goes_around_every_edge_clear_and_the_same_each_time() {
        let arm = arm();
        let s = JointPathSettings::default();
        let fixtures = [post(1.2, 1.2)];
        let (from, to) = ([0.0, 0.0], [std::f64::consts::FRAC_PI_2, 0.0]);
        let path = arm
            .joint_path(&from, &to, &fixtures, 0.01, &s)
            .expect("a path");
        assert!(path.waypoints.len() > 2, "{:?}", path.waypoints);
        assert!(
            arm.move_is_clear(&path.motion, &fixtures, 0.01),
            "the whole path certified"
        );
        assert_eq!(path.waypoints[0], from);
        // The free base joint may end whole turns away; the elbow (with limits) exactly.
        let end = path.motion.end();
        let turns = (end[0] - to[0]) / TAU;
        assert!(
            (turns - turns.round()).abs() < 1e-12 && end[1] == to[1],
            "{end:?}"
        );
        // Within the elbow's limits all along.
        assert!(path.motion.samples.iter().all(|q| q.q[1].abs() <= 2.9));
        let again = arm.joint_path(&from, &to, &fixtures, 0.01, &s).unwrap();
        assert_eq!(again, path, "deterministic under the seed");
    }

    #[test]
    fn no_path_within_the_budget_is_none() {
        // A ring of posts around the arm's whole reach at the elbow: the goal lies beyond.
        let s = JointPathSettings {
            max_samples: 200,
            ..JointPathSettings::default()
        };
        let fixtures: Vec<Body> = (0..24)
            .map(|k| {
                let a = TAU * k as f64 / 24.0;
                post(1.0 * a.cos(), 1.0 * a.sin())
            })
            .collect();
        // Start and goal both collide with the ring: nothing is clear.
        assert_eq!(
            arm().joint_path(&[0.0, 0.0], &[1.0, 0.0], &fixtures, 0.01, &s),
            None
        );
    }
}
