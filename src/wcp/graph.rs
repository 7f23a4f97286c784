//! The work-cell graph: homes and tasks as nodes, each robot's travel times as arcs: the
//! certified time of every move planned so far, the admissible lower bound of the others.

use super::moves::{robot_nodes, MoveFailure, MoveStore};
use super::sequencer::task_node;
use super::sequencer::Bounds;
use crate::cell::{Cell, InputError};
use petgraph::graph::{DiGraph, NodeIndex};
use petgraph::visit::EdgeRef;
use serde::Serialize;

/// What a node of the graph stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeKind {
    /// The home of robot `.0`.
    Home(usize),
    /// Task `.0`.
    Task(usize),
}

/// An arc: robot `robot` can move from its source to its target in `travel_time`.
#[derive(Clone, Debug, PartialEq)]
pub struct TravelArc {
    /// The robot (index into the cell's robots).
    pub robot: usize,
    /// Its fastest certified obstacle-free move, task durations excluded; a lower bound of
    /// it when `exact` is false.
    pub travel_time: f64,
    /// The move was planned and certified; otherwise `travel_time` is its lower bound.
    pub exact: bool,
    /// For an arm, its joint angles at the two ends: the configurations the arc joins (the
    /// generalised TSP's (task, configuration) nodes).
    pub joints: Option<(Vec<f64>, Vec<f64>)>,
}

/// The directed graph of the Work-Cell Problem (petgraph), one node per home and per task.
#[derive(Clone, Debug)]
pub struct WcpGraph {
    /// Homes first (in robot order), then tasks (in file order).
    pub graph: DiGraph<NodeKind, TravelArc>,
}

impl WcpGraph {
    /// An arc for every robot and ordered pair of the nodes it may visit: the certified time
    /// of the moves `store` planned, the lower bound of `bounds` for the others; no arc for a
    /// move known to fail. Robots × nodes² arcs: meant for cells of a few hundred tasks.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{bounds, MoveStore, WcpGraph};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// store.get(0, 0, 1).unwrap(); // one move planned: its arcs are exact, the others bounds
    /// let g = WcpGraph::new(&cell, &store, &bounds(&cell, store.assignment())).graph;
    /// // 2 homes + 4 tasks; each robot: 5 nodes, 5·4 ordered pairs.
    /// assert_eq!((g.node_count(), g.edge_count()), (6, 40));
    /// assert_eq!(g.edge_weights().filter(|a| a.exact).count(), 2); // R1 home -> weld-1 and back
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn new(cell: &Cell, store: &MoveStore, bounds: &Bounds) -> Self {
        let (robots, tasks) = (cell.robots.len(), cell.tasks.len());
        let mut graph = DiGraph::with_capacity(robots + tasks, 0);
        for r in 0..robots {
            graph.add_node(NodeKind::Home(r));
        }
        for t in 0..tasks {
            graph.add_node(NodeKind::Task(t));
        }
        // Robot-local node 0 is the robot's home, 1 + t is task t.
        let index = |r: usize, node: usize| match node {
            0 => NodeIndex::new(r),
            n => NodeIndex::new(robots + n - 1),
        };
        for r in 0..robots {
            let nodes = robot_nodes(cell, r);
            for &a in &nodes {
                for &b in nodes.iter().filter(|&&b| b != a) {
                    let (travel_time, exact) = match store.known(r, a, b) {
                        Some(Ok(time)) => (time, true),
                        Some(Err(_)) => continue,
                        None => (bounds.bound(r, a, b), false),
                    };
                    let at = |n| store.assignment().joints(cell, r, n).map(<[f64]>::to_vec);
                    let arc = TravelArc {
                        robot: r,
                        travel_time,
                        exact,
                        joints: at(a).zip(at(b)),
                    };
                    graph.add_edge(index(r, a), index(r, b), arc);
                }
            }
        }
        WcpGraph { graph }
    }

    /// The contract's `--export-graph` document.
    ///
    /// ```
    /// use workcell::planning::PlannerOptions;
    /// use workcell::wcp::{bounds, MoveStore, WcpGraph};
    /// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
    /// let store = MoveStore::new(&cell, &PlannerOptions::default());
    /// let file = WcpGraph::new(&cell, &store, &bounds(&cell, store.assignment())).export(&cell);
    /// assert_eq!((file.nodes[0].name.as_str(), file.nodes[0].kind), ("R1", "home"));
    /// assert_eq!((file.nodes[2].name.as_str(), file.nodes[2].kind), ("weld-1", "task"));
    /// let arc = file.arcs.iter().find(|a| a.robot == "R2" && a.from == "R2" && a.to == "weld-4").unwrap();
    /// assert!(!arc.exact && arc.travel_time > 0.0); // not planned: a lower bound
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn export(&self, cell: &Cell) -> GraphFile {
        let name = |k: NodeKind| match k {
            NodeKind::Home(r) => cell.robots[r].name.clone(),
            NodeKind::Task(t) => cell.tasks[t].name.clone(),
        };
        let nodes = self
            .graph
            .node_weights()
            .map(|&k| GraphFileNode {
                name: name(k),
                kind: match k {
                    NodeKind::Home(_) => "home",
                    NodeKind::Task(_) => "task",
                },
            })
            .collect();
        let arcs = self
            .graph
            .edge_references()
            .map(|e| GraphFileArc {
                robot: cell.robots[e.weight().robot].name.clone(),
                from: name(self.graph[e.source()]),
                to: name(self.graph[e.target()]),
                travel_time: e.weight().travel_time,
                exact: e.weight().exact,
                from_configuration: e.weight().joints.as_ref().map(|j| j.0.clone()),
                to_configuration: e.weight().joints.as_ref().map(|j| j.1.clone()),
            })
            .collect();
        GraphFile { nodes, arcs }
    }
}

/// The `--export-graph` document (contract section 4).
#[derive(Clone, Debug, Serialize)]
pub struct GraphFile {
    /// Homes (named after their robot) and tasks.
    pub nodes: Vec<GraphFileNode>,
    /// One arc per robot and ordered pair of its nodes that it can travel between.
    pub arcs: Vec<GraphFileArc>,
}

/// A node of [`GraphFile`].
#[derive(Clone, Debug, Serialize)]
pub struct GraphFileNode {
    /// The robot's name for a home, the task's name for a task.
    pub name: String,
    /// `"home"` or `"task"`.
    pub kind: &'static str,
}

/// An arc of [`GraphFile`].
#[derive(Clone, Debug, Serialize)]
pub struct GraphFileArc {
    /// The robot that moves.
    pub robot: String,
    /// Source node's name.
    pub from: String,
    /// Target node's name.
    pub to: String,
    /// The robot's fastest certified obstacle-free move, task durations excluded; its lower
    /// bound when `exact` is false.
    pub travel_time: f64,
    /// Whether the move was planned and certified (`travel_time` is then its time) or not
    /// (`travel_time` is the time of the straight obstacle-free move, a lower bound).
    pub exact: bool,
    /// For an arm, its joint angles at `from` (the configuration the arc leaves).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub from_configuration: Option<Vec<f64>>,
    /// For an arm, its joint angles at `to`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub to_configuration: Option<Vec<f64>>,
}

/// Plans, for every task, the moves from the homes of its allowed robots, nearest robot
/// first by `bounds`, until one succeeds (in parallel over the tasks), starting no task's
/// moves once `deadline` has passed. Returns the moves planned, as `(robot, 0, node)`, and
/// the number of tasks left without them.
pub(crate) fn plan_reaches(
    cell: &Cell,
    store: &MoveStore,
    bounds: &Bounds,
    progress: &(dyn Fn() + Sync),
    deadline: Option<std::time::Instant>,
) -> (Vec<(usize, usize, usize)>, usize) {
    use rayon::prelude::*;
    let per_task: Vec<Option<Vec<(usize, usize, usize)>>> = (0..cell.tasks.len())
        .into_par_iter()
        .map(|t| {
            if deadline.is_some_and(|d| std::time::Instant::now() >= d) {
                return None;
            }
            let node = task_node(t);
            let mut robots = cell.tasks[t].robots.clone();
            robots.sort_by(|&a, &b| {
                bounds
                    .bound(a, 0, node)
                    .total_cmp(&bounds.bound(b, 0, node))
                    .then(a.cmp(&b))
            });
            let mut planned = Vec::new();
            for r in robots {
                planned.push((r, 0, node));
                let ok = store.duration(r, 0, node).is_ok();
                progress();
                if ok {
                    break;
                }
            }
            Some(planned)
        })
        .collect();
    let left = per_task.iter().filter(|p| p.is_none()).count();
    (per_task.into_iter().flatten().flatten().collect(), left)
}

/// Refuses a cell with a task that none of its allowed robots can reach from home: exit
/// status 2, naming the task and each robot's reason. Plans the moves between a home and an
/// allowed task that it needs and the store has not planned yet: none after
/// `plan_reaches` when the cell can be used.
///
/// ```
/// use workcell::cell::parse_cell;
/// use workcell::planning::PlannerOptions;
/// use workcell::wcp::{check_reachable, MoveStore};
/// // Task "boxed" lies inside four walls.
/// let wall = |x0: f64, y0: f64, x1: f64, y1: f64| format!(
///     r#"{{"name": "w{x0},{y0},{x1},{y1}", "shape": [[{x0},{y0}],[{x1},{y0}],[{x1},{y1}],[{x0},{y1}]]}}"#);
/// let text = format!(r#"{{"delta": 0.01,
///   "robots": [{{"name": "R1", "shape": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
///               "home": [0, 0, 0], "max_speed": 1, "max_accel": 2, "max_turn_rate": 1}}],
///   "obstacles": [{}, {}, {}, {}],
///   "tasks": [{{"name": "open", "at": [3, 0, 0], "duration": 1}},
///             {{"name": "boxed", "at": [10, 0, 0], "duration": 1}}]}}"#,
///     wall(7.0, -3.0, 8.0, 3.0), wall(12.0, -3.0, 13.0, 3.0), wall(7.0, 2.0, 13.0, 3.0), wall(7.0, -3.0, 13.0, -2.0));
/// let cell = parse_cell(&text, "c.json".as_ref())?.cell;
/// let e = check_reachable(&cell, &MoveStore::new(&cell, &PlannerOptions::default())).unwrap_err();
/// assert_eq!((e.body.as_deref(), e.field.as_str()), (Some("boxed"), "tasks[1].at"));
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn check_reachable(cell: &Cell, store: &MoveStore) -> Result<(), InputError> {
    // A home from which no move can start is the home's fault, not its tasks'.
    for (r, robot) in cell.robots.iter().enumerate() {
        let nodes = robot_nodes(cell, r);
        let home_blocked = |why: &Result<f64, MoveFailure>| {
            matches!(why, Err(MoveFailure::Blocked { end: "start", .. }))
        };
        // Only a robot whose known home moves all start blocked can be at fault: then every
        // one of them is planned to find out.
        let known: Vec<_> = nodes[1..]
            .iter()
            .filter_map(|&n| store.known(r, 0, n))
            .collect();
        if known.is_empty() || !known.iter().all(home_blocked) {
            continue;
        }
        let mut blocked = Vec::new();
        for &node in &nodes[1..] {
            if let Err(MoveFailure::Blocked {
                end: "start",
                obstacle,
            }) = store.duration(r, 0, node)
            {
                blocked.push(obstacle);
            }
        }
        if blocked.len() == nodes.len() - 1 {
            let reason = format!(
                "no move can start from this home: the robot is too close to obstacle \"{}\" \
                 for the planner's clearance (delta + 2%, swept over each move's rotation)",
                blocked[0]
            );
            return Err(cell.error(Some(&robot.name), format!("robots[{r}].home"), reason));
        }
    }
    for (t, task) in cell.tasks.iter().enumerate() {
        let node = task_node(t);
        // A move already known to succeed settles it without planning any other.
        let known_ok = |r: &usize| matches!(store.known(*r, 0, node), Some(Ok(_)));
        if task.robots.iter().any(known_ok)
            || task
                .robots
                .iter()
                .any(|&r| store.duration(r, 0, node).is_ok())
        {
            continue;
        }
        let reasons: Vec<String> = task
            .robots
            .iter()
            .map(|&r| {
                let why = store
                    .duration(r, 0, node)
                    .err()
                    .map_or_else(|| "no move".to_owned(), |why| why.to_string());
                format!("{}: {why}", cell.robots[r].name)
            })
            .collect();
        let reason = format!(
            "no allowed robot can reach the task ({})",
            reasons.join("; ")
        );
        return Err(cell.error(Some(&task.name), format!("tasks[{t}].at"), reason));
    }
    Ok(())
}
