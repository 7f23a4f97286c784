//! Where each arm may work (contract section 7): for every task an arm is allowed to do,
//! the joint configurations that put its tool at the task's pose within its joint limits
//! and δ clear of the fixtures ([`ArmModel::configurations`]). A task that no allowed robot
//! can do is refused, with each arm's reason.

use crate::cell::{Cell, InputError};
use crate::motion::{IkSettings, ToolGoal};
use crate::planning::{ArmModel, Refusal};
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
    let fixtures = cell.obstacle_bodies();
    let jobs: Vec<(usize, usize)> = (0..cell.robots.len())
        .filter(|&r| cell.robots[r].as_arm().is_some())
        .flat_map(|r| {
            (cell.tasks.iter().enumerate())
                .filter(move |(_, task)| task.robots.contains(&r))
                .map(move |(t, _)| (r, t))
        })
        .collect();
    let found: Vec<Result<Vec<Vec<f64>>, Refusal>> = jobs
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
    let mut refusals: Vec<Vec<(usize, Refusal)>> = vec![Vec::new(); cell.tasks.len()];
    for (&(r, t), result) in jobs.iter().zip(found) {
        match result {
            Ok(list) => per_robot[r][t] = list.into_iter().map(Configuration::from).collect(),
            Err(why) => refusals[t].push((r, why)),
        }
    }
    let configurations = Configurations { per_robot };
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

/// Refuses a cell with an arm until the solver schedules arms, after refusing (with
/// [`task_configurations`]) any task that no robot can reach: the field names the arm.
pub(super) fn refuse_arms(cell: &Cell) -> Result<(), InputError> {
    let Some(r) = cell.robots.iter().position(|r| r.as_arm().is_some()) else {
        return Ok(());
    };
    task_configurations(cell, &IkSettings::default())?;
    let reason = "an arm (contract section 7): `workcell solve` and `evaluate` do not schedule \
                  arms yet; `workcell check` checks an arm's trajectory (section 6)";
    Err(cell.error(
        Some(&cell.robots[r].name),
        format!("robots[{r}].links"),
        reason,
    ))
}
