//! A schedule's changed legs in the result's terms (its `legs`): what each robot does
//! instead of a planned move, as `evaluate` reads it back (`cell::parse_legs`).

use super::legs::{HoldReason, Legs, Piece};
use super::remedy_json::move_name;
use super::schedule::route_nodes;
use crate::cell::Cell;
use crate::motion::JointSample;
use serde::Serialize;

/// A leg the loop changed, as `evaluate` reads it back (see `cell::parse_legs`).
#[derive(Serialize)]
pub struct LegJson {
    /// The robot.
    pub robot: String,
    /// The move of its route (0 out of home, k after its k-th task).
    #[serde(rename = "move")]
    pub leg: usize,
    /// That move in words, e.g. `move home -> weld-4`.
    pub on: String,
    /// What the robot does instead of the planned move.
    pub pieces: Vec<PieceJson>,
}

/// One piece of a changed leg.
#[derive(Serialize)]
#[serde(untagged)]
pub enum PieceJson {
    /// A motion.
    Go {
        /// Its primitives and time stretch.
        go: GoJson,
    },
    /// Standing still.
    Hold {
        /// How long.
        hold: f64,
        /// `pause` or `park`.
        reason: &'static str,
    },
}

/// A motion of a changed leg.
#[derive(Serialize)]
pub struct GoJson {
    /// Rest-to-rest primitives, one after the other (none for an arm).
    pub primitives: Vec<PrimitiveJson>,
    /// An arm's joint angles where it rests on the way, start and end included (the
    /// joint-space waypoints of its motion); absent for a rigid robot.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<Vec<f64>>,
    /// Time stretch (1 as timed).
    pub scale: f64,
}

/// One primitive: G along `path`, the angle from `theta` turning by `turn`.
#[derive(Serialize)]
pub struct PrimitiveJson {
    /// Waypoints of G.
    pub path: Vec<[f64; 2]>,
    /// Angle at the start.
    pub theta: f64,
    /// Signed rotation.
    pub turn: f64,
}

/// The changed legs of a schedule, robot by robot, leg by leg.
///
/// ```
/// use std::sync::Arc;
/// use serde_json::json;
/// use workcell::planning::PlannerOptions;
/// use workcell::wcp::legs::{default_legs, with_leg, HoldReason, Leg, Piece};
/// use workcell::wcp::{legs_json::legs_json, MoveStore};
/// let cell = workcell::cell::load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let store = MoveStore::new(&cell, &PlannerOptions::default());
/// let routes = [vec![0, 2], vec![3, 1]];
/// // A wait alone changes no motion: no leg to write.
/// let waits = with_leg(&default_legs(2), 1, 0, Leg { wait: 1.0, ..Leg::DEFAULT });
/// assert!(legs_json(&cell, &routes, &waits).is_empty());
/// // R2 holds 1 s at home, then makes its planned move to weld-4.
/// let pieces = vec![
///     Piece::Hold { duration: 1.0, reason: HoldReason::Pause },
///     Piece::Go { motion: store.get(1, 0, 4).unwrap(), scale: 1.0 },
/// ];
/// let changed = with_leg(&default_legs(2), 1, 0, Leg { wait: 0.0, pieces: Some(Arc::from(pieces)) });
/// let out = serde_json::to_value(legs_json(&cell, &routes, &changed))?;
/// assert_eq!((&out[0]["robot"], &out[0]["move"], &out[0]["on"]), (&json!("R2"), &json!(0), &json!("move home -> weld-4")));
/// assert_eq!(out[0]["pieces"][0], json!({"hold": 1.0, "reason": "pause"}));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn legs_json(cell: &Cell, routes: &[Vec<usize>], legs: &Legs) -> Vec<LegJson> {
    let mut out = Vec::new();
    for (r, list) in legs.iter().enumerate() {
        let nodes = route_nodes(&routes[r]);
        for (m, leg) in list.iter().enumerate() {
            let Some(pieces) = &leg.pieces else { continue };
            let pieces = pieces
                .iter()
                .map(|p| match p {
                    Piece::Go { motion, scale } => PieceJson::Go {
                        go: GoJson {
                            primitives: motion
                                .primitives
                                .iter()
                                .map(|q| PrimitiveJson {
                                    path: q.path.iter().map(|v| [v.x, v.y]).collect(),
                                    theta: q.theta,
                                    turn: q.turn,
                                })
                                .collect(),
                            joints: rests(&motion.joints),
                            scale: *scale,
                        },
                    },
                    Piece::Hold { duration, reason } => PieceJson::Hold {
                        hold: *duration,
                        reason: match reason {
                            HoldReason::Pause => "pause",
                            HoldReason::Park => "park",
                        },
                    },
                })
                .collect();
            out.push(LegJson {
                robot: cell.robots[r].name.clone(),
                leg: m,
                on: move_name(cell, r, (nodes[m], nodes[m + 1])),
                pieces,
            });
        }
    }
    out
}

/// The joint angles of an arm's motion where it is at rest: its start, every waypoint, its
/// end (none for a rigid robot's motion).
pub(crate) fn rests(joints: &[JointSample]) -> Vec<Vec<f64>> {
    let last = joints.len().saturating_sub(1);
    (joints.iter().enumerate())
        .filter(|&(k, s)| k == 0 || k == last || s.qd.iter().all(|&v| v == 0.0))
        .map(|(_, s)| s.q.clone())
        .collect()
}
