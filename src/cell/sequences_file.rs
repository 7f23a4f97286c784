//! Reading a sequences file (input of `workcell evaluate`): each robot's tasks in order.

use super::{Cell, InputError};
use serde_json::Value;
use std::path::Path;

/// Sequences read from a file: each robot's tasks, and waits before given moves.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sequences {
    /// Task indices of each robot, in the cell's robot order.
    pub routes: Vec<Vec<usize>>,
    /// Waits, as a `solve` result lists them in `waits`.
    pub waits: Vec<Wait>,
    /// Moves the feedback loop changed, as a `solve` result lists them in `legs`.
    pub legs: Vec<super::LegSpec>,
}

/// A wait before one of a robot's moves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wait {
    /// The robot.
    pub robot: usize,
    /// The move it waits before: 0 is the move out of home, k the move after its k-th task.
    pub before_move: usize,
    /// How long.
    pub duration: f64,
}

/// Reads the sequences at `path` against `cell`: see [`parse_sequences`].
pub fn load_sequences(path: &Path, cell: &Cell) -> Result<Sequences, InputError> {
    parse_sequences(&super::scene_file::read_file(path)?, path, cell)
}

/// Parses `{"R1": ["weld-3", "weld-1"], "R2": ["weld-2"]}`, or a whole `solve --json`
/// result (recognised by its `sequences` and `makespan`; its `sequences` object is read), into each robot's task indices, in the cell's robot
/// order. A robot left out does no task. Refused: unknown robots or tasks, a task given to a
/// robot not allowed to do it, a task listed twice, a task left out.
///
/// A whole result also brings its `waits` (`[{"robot", "before_move", "duration"}]`) and
/// `legs` (see [`super::parse_legs`]), so that the schedule is the one `solve` certified.
pub fn parse_sequences(text: &str, file: &Path, cell: &Cell) -> Result<Sequences, InputError> {
    let err = |body: Option<&str>, field: String, reason: String| {
        InputError::new(file, body, field, reason)
    };
    let doc: Value = serde_json::from_str(text)
        .map_err(|e| err(None, String::new(), format!("not valid JSON: {e}")))?;
    // A whole `solve` result has `makespan` beside `sequences`; otherwise `sequences` may be
    // a robot's name.
    let whole = doc.get("sequences").is_some() && doc.get("makespan").is_some();
    let prefix = if whole { "sequences." } else { "" };
    // Read again, keeping every key: `Value` would let a repeated robot overwrite the first.
    let entries = if whole {
        serde_json::from_str::<Whole>(text).map(|w| w.sequences)
    } else {
        serde_json::from_str::<Entries>(text)
    }
    .map_err(|_| {
        let reason = "expected an object mapping robot names to lists of task names".to_owned();
        err(None, prefix.trim_end_matches('.').to_owned(), reason)
    })?;
    let mut seen = std::collections::HashSet::new();
    if let Some((robot, _)) = entries.0.iter().find(|(k, _)| !seen.insert(k.as_str())) {
        let reason = "the robot is listed twice".to_owned();
        return Err(err(Some(robot), format!("{prefix}{robot}"), reason));
    }
    let map = entries.0;
    let mut routes = vec![Vec::new(); cell.robots.len()];
    let mut done_by: Vec<Option<String>> = vec![None; cell.tasks.len()];
    for (robot, list) in &map {
        let field = format!("{prefix}{robot}");
        let Some(r) = cell.robots.iter().position(|x| &x.name == robot) else {
            return Err(err(
                Some(robot),
                field,
                "the cell has no robot of this name".into(),
            ));
        };
        let Value::Array(items) = list else {
            return Err(err(
                Some(robot),
                field,
                "expected a list of task names".into(),
            ));
        };
        for (k, item) in items.iter().enumerate() {
            let field = format!("{field}[{k}]");
            let Value::String(name) = item else {
                return Err(err(
                    Some(robot),
                    field,
                    format!("expected a task name, found {item}"),
                ));
            };
            let Some(t) = cell.tasks.iter().position(|x| &x.name == name) else {
                return Err(err(
                    Some(robot),
                    field,
                    format!("the cell has no task \"{name}\""),
                ));
            };
            if !cell.tasks[t].robots.contains(&r) {
                return Err(err(
                    Some(robot),
                    field,
                    format!("{robot} is not allowed to do task \"{name}\""),
                ));
            }
            if let Some(first) = &done_by[t] {
                return Err(err(
                    Some(robot),
                    field,
                    format!("task \"{name}\" is already done at `{first}`"),
                ));
            }
            done_by[t] = Some(field.clone());
            routes[r].push(t);
        }
    }
    if let Some(t) = done_by.iter().position(Option::is_none) {
        let name = &cell.tasks[t].name;
        let reason =
            format!("task \"{name}\" is in no robot's sequence: every task must be done once");
        let field = if whole {
            "sequences"
        } else {
            "(every robot's list)"
        };
        return Err(err(Some(name), field.to_owned(), reason));
    }
    let waits = match doc.get("waits").filter(|_| whole) {
        None | Some(Value::Null) => Vec::new(),
        Some(list) => waits(list, file, cell, &routes)?,
    };
    let legs = match doc.get("legs").filter(|_| whole) {
        None | Some(Value::Null) => Vec::new(),
        Some(list) => super::parse_legs(list, file, cell, &routes)?,
    };
    Ok(Sequences {
        routes,
        waits,
        legs,
    })
}

/// An object's entries in document order, repeated keys kept.
struct Entries(Vec<(String, Value)>);

impl<'de> serde::Deserialize<'de> for Entries {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = Entries;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("an object")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut map: A,
            ) -> Result<Entries, A::Error> {
                let mut entries = Vec::new();
                while let Some(entry) = map.next_entry::<String, Value>()? {
                    entries.push(entry);
                }
                Ok(Entries(entries))
            }
        }
        d.deserialize_map(Visitor)
    }
}

/// The part of a `solve` result read here.
#[derive(serde::Deserialize)]
struct Whole {
    sequences: Entries,
}

fn waits(
    list: &Value,
    file: &Path,
    cell: &Cell,
    routes: &[Vec<usize>],
) -> Result<Vec<Wait>, InputError> {
    let Value::Array(items) = list else {
        let reason = "expected a list of {\"robot\", \"before_move\", \"duration\"}";
        return Err(InputError::new(file, None, "waits", reason));
    };
    let mut waits = Vec::with_capacity(items.len());
    for (k, item) in items.iter().enumerate() {
        let at = format!("waits[{k}]");
        let name = item.get("robot").and_then(Value::as_str);
        let Some(robot) = name.and_then(|n| cell.robots.iter().position(|r| r.name == n)) else {
            let reason = "`robot` must name a robot of the cell";
            return Err(InputError::new(file, name, format!("{at}.robot"), reason));
        };
        let moves = routes[robot].len() + 1;
        let before_move = item.get("before_move").and_then(Value::as_u64);
        let Some(before_move) = before_move.filter(|&m| m < moves as u64) else {
            let reason = format!(
                "`before_move` must be a move of the robot: 0 to {}",
                moves - 1
            );
            return Err(InputError::new(
                file,
                name,
                format!("{at}.before_move"),
                reason,
            ));
        };
        let duration = item.get("duration").and_then(Value::as_f64);
        let Some(duration) = duration.filter(|d| d.is_finite() && *d >= 0.0) else {
            let reason = "`duration` must be a non-negative number";
            return Err(InputError::new(
                file,
                name,
                format!("{at}.duration"),
                reason,
            ));
        };
        waits.push(Wait {
            robot,
            before_move: before_move as usize,
            duration,
        });
    }
    Ok(waits)
}
