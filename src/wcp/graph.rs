//! The work-cell graph: homes and tasks as nodes, each robot's certified travel times as arcs.

use super::moves::{MoveFailure, MoveTable};
use super::sequencer::{Instance, SequencerError};
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
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TravelArc {
    /// The robot (index into the cell's robots).
    pub robot: usize,
    /// Its fastest certified obstacle-free move, task durations excluded.
    pub travel_time: f64,
}

/// The directed graph of the Work-Cell Problem (petgraph), one node per home and per task.
#[derive(Clone, Debug)]
pub struct WcpGraph {
    /// Homes first (in robot order), then tasks (in file order).
    pub graph: DiGraph<NodeKind, TravelArc>,
}

impl WcpGraph {
    /// The graph of the moves in `table`: an arc for every finite travel time.
    pub fn new(cell: &Cell, table: &MoveTable) -> Self {
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
            for a in 0..=tasks {
                for b in 0..=tasks {
                    let travel_time = table.travel(r, a, b);
                    if a != b && travel_time.is_finite() {
                        graph.add_edge(
                            index(r, a),
                            index(r, b),
                            TravelArc {
                                robot: r,
                                travel_time,
                            },
                        );
                    }
                }
            }
        }
        WcpGraph { graph }
    }

    /// The sequencer's instance: durations, permissions and each robot's travel matrix, read
    /// back from the arcs.
    pub fn instance(&self, cell: &Cell) -> Result<Instance, SequencerError> {
        let (robots, tasks) = (cell.robots.len(), cell.tasks.len());
        let n = tasks + 1;
        let local = |node: NodeIndex, r: usize| match self.graph[node] {
            NodeKind::Home(h) => (h == r).then_some(0),
            NodeKind::Task(t) => Some(t + 1),
        };
        let mut travel = vec![vec![f64::INFINITY; n * n]; robots];
        for m in &mut travel {
            for k in 0..n {
                m[k * n + k] = 0.0;
            }
        }
        for e in self.graph.edge_references() {
            let r = e.weight().robot;
            if let (Some(a), Some(b)) = (local(e.source(), r), local(e.target(), r)) {
                travel[r][a * n + b] = e.weight().travel_time;
            }
        }
        let allowed = (0..robots)
            .map(|r| cell.tasks.iter().map(|t| t.robots.contains(&r)).collect())
            .collect();
        let duration = cell.tasks.iter().map(|t| t.duration).collect();
        Instance::new(duration, allowed, travel)
    }

    /// The contract's `--export-graph` document.
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
    /// The robot's fastest certified obstacle-free move, task durations excluded.
    pub travel_time: f64,
}

/// Refuses a cell with a task that none of its allowed robots can reach from home: exit
/// status 2, naming the task and each robot's reason.
pub fn check_reachable(cell: &Cell, table: &MoveTable) -> Result<(), InputError> {
    // A home from which no move can start is the home's fault, not its tasks'.
    for (r, robot) in cell.robots.iter().enumerate() {
        let moves = cell.tasks.iter().filter(|t| t.robots.contains(&r)).count();
        let blocked: Vec<&str> = table.failures[r]
            .iter()
            .filter_map(|(a, _, why)| match why {
                MoveFailure::Blocked {
                    end: "start",
                    obstacle,
                } if *a == 0 => Some(obstacle.as_str()),
                _ => None,
            })
            .collect();
        if moves > 0 && blocked.len() == moves {
            let reason = format!(
                "no move can start from this home: the robot is too close to obstacle \"{}\" \
                 for the planner's clearance (delta + 2%, swept over each move's rotation)",
                blocked[0]
            );
            return Err(cell.error(Some(&robot.name), format!("robots[{r}].home"), reason));
        }
    }
    for (t, task) in cell.tasks.iter().enumerate() {
        let node = t + 1;
        if task
            .robots
            .iter()
            .any(|&r| table.travel(r, 0, node).is_finite())
        {
            continue;
        }
        let reasons: Vec<String> = task
            .robots
            .iter()
            .map(|&r| {
                let why = table.failures[r]
                    .iter()
                    .find(|(a, b, _)| (*a, *b) == (0, node))
                    .map_or_else(|| "no move".to_owned(), |(_, _, why)| why.to_string());
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
