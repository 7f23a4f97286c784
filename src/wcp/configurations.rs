//! Where each arm may work (contract section 7): for every task an arm is allowed to do,
//! the joint configurations that put its tool at the task's pose within its joint limits
//! and δ clear of the fixtures ([`ArmModel::configurations`]). A task that no allowed robot
//! can do is refused, with each arm's reason.

use crate::cell::{Cell, InputError};
use crate::motion::{IkSettings, ToolGoal};
use crate::planning::{joint_move_time, ArmModel, Refusal};
use crate::wcp::sequencer::node_task;
use rayon::prelude::*;
use std::sync::Arc;

/// One joint configuration of an arm: an angle per joint.
pub type Configuration = Arc<[f64]>;

/// The configurations of every arm at every task, `[robot][task]`: empty for a rigid robot,
/// a task the arm may not do, or one it cannot reach.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Configurations {
    per_robot: Vec<Vec<Vec<Configuration>>>,
}

impl Configurations {
    /// The configurations arm `r` may take at task `t` (none for a rigid robot).
    ///
    /// ```
    /// use workcell::cell::parse_cell;
    /// use workcell::motion::IkSettings;
    /// use workcell::wcp::task_configurations;
    /// let bar = "[[-0.1, -0.1], [1.1, -0.1], [1.1, 0.1], [-0.1, 0.1]]";
    /// let text = format!(r#"{{"robots": [{{"name": "A1", "base": [0, 0], "home": [1.2, 1.0],
    ///     "links": [{{"length": 1, "shape": {bar}}}, {{"length": 1, "shape": {bar}}}],
    ///     "max_joint_speed": 2, "max_joint_accel": 4}}],
    ///   "tasks": [{{"name": "t", "at": [1.2, 0.8], "duration": 1}}]}}"#);
    /// let cell = parse_cell(&text, "arm.json".as_ref())?.cell;
    /// let found = task_configurations(&cell, &IkSettings::default())?;
    /// assert_eq!(found.at(0, 0).len(), 2); // elbow up, elbow down
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn at(&self, r: usize, t: usize) -> &[Configuration] {
        (self.per_robot.get(r))
            .and_then(|tasks| tasks.get(t))
            .map_or(&[], Vec::as_slice)
    }
}

/// Which configuration each arm takes at each task it may do (an index into
/// [`Configurations::at`]): what turns an arm's task into one node of the sequencer's graph.
/// The solver changes it between sequencing rounds (see `choose.rs`).
#[derive(Clone, Debug, PartialEq)]
pub struct Assignment {
    configurations: Arc<Configurations>,
    /// `[robot][task]`: the index of the configuration taken (0 where there is none).
    chosen: Vec<Vec<usize>>,
}

impl Assignment {
    /// Each arm at each task in the configuration it reaches soonest from home (the first
    /// of equals), as the sequencer's first guess.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::motion::IkSettings;
    /// use workcell::wcp::{task_configurations, Assignment};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let found = Arc::new(task_configurations(&cell, &IkSettings::default())?);
    /// let chosen = Assignment::nearest_home(&cell, found);
    /// assert_eq!(chosen.joints(&cell, 0, 1), None); // a rigid robot has no joints
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn nearest_home(cell: &Cell, configurations: Arc<Configurations>) -> Assignment {
        let chosen = (0..cell.robots.len())
            .map(|r| {
                let Some(arm) = cell.robots[r].as_arm() else {
                    return Vec::new();
                };
                (0..cell.tasks.len())
                    .map(|t| {
                        let time = |q: &Configuration| joint_move_time(&arm.home, q, &arm.limits);
                        (configurations.at(r, t).iter().enumerate())
                            .min_by(|(_, a), (_, b)| time(a).total_cmp(&time(b)))
                            .map_or(0, |(k, _)| k)
                    })
                    .collect()
            })
            .collect();
        Assignment {
            configurations,
            chosen,
        }
    }

    /// Each arm at each task in its first configuration (the order of
    /// [`inverse_kinematics`](crate::motion::inverse_kinematics)).
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::wcp::{task_configurations, Assignment, SolveOptions};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/scara-cell.json").as_ref())?.cell;
    /// let found = Arc::new(task_configurations(&cell, &SolveOptions::default().ik)?);
    /// assert_eq!(Assignment::first(&cell, found).index(0, 0), 0);
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn first(cell: &Cell, configurations: Arc<Configurations>) -> Assignment {
        let chosen = (cell.robots.iter())
            .map(|r| match r.as_arm() {
                Some(_) => vec![0; cell.tasks.len()],
                None => Vec::new(),
            })
            .collect();
        Assignment {
            configurations,
            chosen,
        }
    }

    /// The configurations found, shared.
    pub(crate) fn configurations_arc(&self) -> Arc<Configurations> {
        self.configurations.clone()
    }

    /// The configurations found, whatever was chosen.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::wcp::{task_configurations, Assignment, SolveOptions};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/scara-cell.json").as_ref())?.cell;
    /// let found = Arc::new(task_configurations(&cell, &SolveOptions::default().ik)?);
    /// let chosen = Assignment::nearest_home(&cell, found);
    /// // A1 at weld-1 (task 0, node 1): elbow up and elbow down; the other one is chosen now.
    /// assert_eq!(chosen.configurations().at(0, 0).len(), 2);
    /// let other = chosen.with(0, 0, 1 - chosen.index(0, 0));
    /// assert_ne!(other.joints(&cell, 0, 1), chosen.joints(&cell, 0, 1));
    /// assert_eq!(other.joints(&cell, 0, 0), Some(&cell.robots[0].as_arm().unwrap().home[..]));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn configurations(&self) -> &Configurations {
        &self.configurations
    }

    /// `[robot][task]`: the configuration taken, as [`Assignment::index`] gives it.
    pub(crate) fn chosen(&self) -> &[Vec<usize>] {
        &self.chosen
    }

    /// The index of arm `r`'s configuration at task `t`.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::wcp::{task_configurations, Assignment, SolveOptions};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/scara-cell.json").as_ref())?.cell;
    /// let found = Arc::new(task_configurations(&cell, &SolveOptions::default().ik)?);
    /// let chosen = Assignment::nearest_home(&cell, found);
    /// // A1 at weld-1 (task 0, node 1): elbow up and elbow down; the other one is chosen now.
    /// assert_eq!(chosen.configurations().at(0, 0).len(), 2);
    /// let other = chosen.with(0, 0, 1 - chosen.index(0, 0));
    /// assert_ne!(other.joints(&cell, 0, 1), chosen.joints(&cell, 0, 1));
    /// assert_eq!(other.joints(&cell, 0, 0), Some(&cell.robots[0].as_arm().unwrap().home[..]));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn index(&self, r: usize, t: usize) -> usize {
        self.chosen
            .get(r)
            .and_then(|c| c.get(t))
            .copied()
            .unwrap_or(0)
    }

    /// The same, with arm `r` at task `t` in its configuration `k`.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::wcp::{task_configurations, Assignment, SolveOptions};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/scara-cell.json").as_ref())?.cell;
    /// let found = Arc::new(task_configurations(&cell, &SolveOptions::default().ik)?);
    /// let chosen = Assignment::nearest_home(&cell, found);
    /// // A1 at weld-1 (task 0, node 1): elbow up and elbow down; the other one is chosen now.
    /// assert_eq!(chosen.configurations().at(0, 0).len(), 2);
    /// let other = chosen.with(0, 0, 1 - chosen.index(0, 0));
    /// assert_ne!(other.joints(&cell, 0, 1), chosen.joints(&cell, 0, 1));
    /// assert_eq!(other.joints(&cell, 0, 0), Some(&cell.robots[0].as_arm().unwrap().home[..]));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn with(&self, r: usize, t: usize, k: usize) -> Assignment {
        let mut next = self.clone();
        next.chosen[r][t] = k;
        next
    }

    /// Arm `r`'s joint angles at node `node` (0: home, `1 + t`: task `t`); `None` for a
    /// rigid robot, or a task the arm cannot reach.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::wcp::{task_configurations, Assignment, SolveOptions};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/scara-cell.json").as_ref())?.cell;
    /// let found = Arc::new(task_configurations(&cell, &SolveOptions::default().ik)?);
    /// let chosen = Assignment::nearest_home(&cell, found);
    /// // A1 at weld-1 (task 0, node 1): elbow up and elbow down; the other one is chosen now.
    /// assert_eq!(chosen.configurations().at(0, 0).len(), 2);
    /// let other = chosen.with(0, 0, 1 - chosen.index(0, 0));
    /// assert_ne!(other.joints(&cell, 0, 1), chosen.joints(&cell, 0, 1));
    /// assert_eq!(other.joints(&cell, 0, 0), Some(&cell.robots[0].as_arm().unwrap().home[..]));
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn joints<'a>(&'a self, cell: &'a Cell, r: usize, node: usize) -> Option<&'a [f64]> {
        let arm = cell.robots[r].as_arm()?;
        match node {
            0 => Some(&arm.home),
            n => {
                let t = node_task(n);
                (self.configurations.at(r, t).get(self.index(r, t))).map(|q| &q[..])
            }
        }
    }
}

/// Every arm's configurations at every task it may do. Refuses (naming the task and each
/// arm's reason) a task that none of its robots can do: a rigid robot can always go there
/// (the reader refused task poses inside fixtures), an arm only with a configuration.
///
/// ```
/// use workcell::wcp::task_configurations;
/// use workcell::motion::IkSettings;
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json");
/// let cell = workcell::cell::load_cell(path.as_ref())?.cell;
/// let found = task_configurations(&cell, &IkSettings::default())?;
/// assert!(found.at(0, 0).is_empty()); // a rigid robot has no joints
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn task_configurations(cell: &Cell, ik: &IkSettings) -> Result<Configurations, InputError> {
    let (configurations, refusals) = found(cell, ik);
    for (t, task) in cell.tasks.iter().enumerate() {
        let able =
            |&r: &usize| cell.robots[r].as_rigid().is_some() || !configurations.at(r, t).is_empty();
        if !task.robots.iter().any(able) {
            let reasons: Vec<String> = (refusals[t].iter())
                .map(|&(r, why)| format!("\"{}\": {why}", cell.robots[r].name))
                .collect();
            let reason = format!(
                "no robot allowed to do the task can reach its pose ({})",
                reasons.join("; ")
            );
            return Err(cell.error(Some(&task.name), format!("tasks[{t}].at"), reason));
        }
    }
    Ok(configurations)
}

/// Per task, each arm that cannot do it and why.
type Refusals = Vec<Vec<(usize, Refusal)>>;

/// Every arm's configurations at every task it may do, and the refusals.
fn found(cell: &Cell, ik: &IkSettings) -> (Configurations, Refusals) {
    let fixtures = cell.obstacle_bodies();
    let jobs: Vec<(usize, usize)> = (0..cell.robots.len())
        .filter(|&r| cell.robots[r].as_arm().is_some())
        .flat_map(|r| {
            (cell.tasks.iter().enumerate())
                .filter(move |(_, task)| task.robots.contains(&r))
                .map(move |(t, _)| (r, t))
        })
        .collect();
    let results: Vec<Result<Vec<Vec<f64>>, Refusal>> = jobs
        .par_iter()
        .map(|&(r, t)| {
            let arm = cell.robots[r].as_arm().expect("arms only");
            let task = &cell.tasks[t];
            let goal = ToolGoal {
                pos: task.at.pos,
                theta: (!task.free_angle).then_some(task.at.theta),
            };
            ArmModel::new(&cell.robots[r].name, arm).configurations(goal, &fixtures, cell.delta, ik)
        })
        .collect();
    let mut per_robot = vec![vec![Vec::new(); cell.tasks.len()]; cell.robots.len()];
    let mut refusals: Refusals = vec![Vec::new(); cell.tasks.len()];
    for (&(r, t), result) in jobs.iter().zip(results) {
        match result {
            Ok(list) => per_robot[r][t] = list.into_iter().map(Configuration::from).collect(),
            Err(why) => refusals[t].push((r, why)),
        }
    }
    (Configurations { per_robot }, refusals)
}

/// Every arm's configurations at every task it may do, none where it cannot reach: as
/// [`task_configurations`], without refusing anything (a library's store plans what it can).
pub(crate) fn configurations_found(cell: &Cell, ik: &IkSettings) -> Configurations {
    found(cell, ik).0
}
