//! Reading a sequences file (input of `workcell evaluate`): each robot's tasks in order.

use super::{Cell, InputError};
use serde_json::Value;
use std::path::Path;

/// Reads the sequences at `path` against `cell`: see [`parse_sequences`].
pub fn load_sequences(path: &Path, cell: &Cell) -> Result<Vec<Vec<usize>>, InputError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| InputError::new(path, None, "", format!("cannot read the file: {e}")))?;
    parse_sequences(&text, path, cell)
}

/// Parses `{"R1": ["weld-3", "weld-1"], "R2": ["weld-2"]}`, or a whole `solve --json`
/// result (its `sequences` object), into each robot's task indices, in the cell's robot
/// order. A robot left out does no task. Refused: unknown robots or tasks, a task given to a
/// robot not allowed to do it, a task listed twice, a task left out.
pub fn parse_sequences(
    text: &str,
    file: &Path,
    cell: &Cell,
) -> Result<Vec<Vec<usize>>, InputError> {
    let err = |body: Option<&str>, field: String, reason: String| {
        InputError::new(file, body, field, reason)
    };
    let doc: Value = serde_json::from_str(text)
        .map_err(|e| err(None, String::new(), format!("not valid JSON: {e}")))?;
    let (object, prefix) = match doc.get("sequences") {
        Some(inner) => (inner, "sequences."),
        None => (&doc, ""),
    };
    let Value::Object(map) = object else {
        let reason = "expected an object mapping robot names to lists of task names".to_owned();
        return Err(err(None, prefix.trim_end_matches('.').to_owned(), reason));
    };
    let mut routes = vec![Vec::new(); cell.robots.len()];
    let mut done_by: Vec<Option<String>> = vec![None; cell.tasks.len()];
    for (robot, list) in map {
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
        return Err(err(
            Some(name),
            prefix.trim_end_matches('.').to_owned(),
            reason,
        ));
    }
    Ok(routes)
}
