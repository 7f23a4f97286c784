//! Reading a sequences file (input of `workcell evaluate`): each robot's tasks in order.
//!
//! The document is read over borrowed raw JSON (serde_json's `RawValue`) and each list is
//! walked item by item: only what is used is parsed, so that a result with 2·10⁶ waits costs
//! about its list of waits, not a tree of maps 18 times the file's size.

use super::{Cell, InputError};
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::value::RawValue;
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
    /// Each arm's joint angles at the tasks of its route, in order, as a `solve` result
    /// lists them in `configurations` (empty for a robot not listed there).
    pub configurations: Vec<Vec<Vec<f64>>>,
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
///
/// ```
/// use workcell::cell::{load_cell, load_sequences};
/// let cell = load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let path = std::env::temp_dir().join(format!("workcell-doc-{}-seq.json", std::process::id()));
/// std::fs::write(&path, r#"{"R1": ["weld-3", "weld-1"], "R2": ["weld-4", "weld-2"]}"#)?;
/// let sequences = load_sequences(&path, &cell);
/// std::fs::remove_file(&path)?;
/// assert_eq!(sequences?.routes, [vec![2, 0], vec![3, 1]]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn load_sequences(path: &Path, cell: &Cell) -> Result<Sequences, InputError> {
    parse_sequences(&super::reading::read_file(path)?, path, cell)
}

/// The keys of a whole result, as `solve --json` and `evaluate --json` write them
/// (`wcp::ResultJson`): any other is refused, so that a misspelt `waits` is not dropped.
const RESULT_KEYS: &[&str] = &[
    "makespan",
    "collision_free",
    "sequences",
    "configurations",
    "iterations",
    "schedules_checked",
    "found_after",
    "waits",
    "legs",
    "blind_sequences",
    "blind_makespan",
    "blind_optimal",
    "first_collision",
    "feedback",
    "failure",
    "schedule",
    "check_stats",
    "stages_ms",
];

/// What a sequences document is when it is not one.
const NOT_SEQUENCES: &str = "expected an object mapping robot names to lists of task names";

/// Parses `{"R1": ["weld-3", "weld-1"], "R2": ["weld-2"]}`, or a whole `solve --json`
/// result (recognised by its `sequences` and `makespan`; its `sequences` object is read),
/// into each robot's task indices, in the cell's robot order. A robot left out does no
/// task. Refused: unknown robots or tasks, a task given to a robot not allowed to do it, a
/// task listed twice, a task left out.
///
/// A whole result also brings its `waits` (`[{"robot", "before_move", "duration"}]`) and
/// `legs` (see [`super::parse_legs`]), so that the schedule is the one `solve` certified.
///
/// ```
/// use workcell::cell::{load_cell, parse_sequences};
/// let cell = load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let file = "seq.json".as_ref();
/// // R2 left out: it does no task.
/// let s = parse_sequences(r#"{"R1": ["weld-2", "weld-1", "weld-3", "weld-4"]}"#, file, &cell)?;
/// assert_eq!(s.routes, [vec![1, 0, 2, 3], vec![]]);
/// assert!(s.waits.is_empty() && s.legs.is_empty());
/// let e = parse_sequences(r#"{"R1": ["weld-1", "weld-2", "weld-3"]}"#, file, &cell).unwrap_err();
/// assert!(e.reason.contains("weld-4"), "{e}"); // a task left out
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn parse_sequences(text: &str, file: &Path, cell: &Cell) -> Result<Sequences, InputError> {
    parse(text, file, cell, "sequences")
}

/// Reads the collision-blind sequences of the `solve --json` result at `path` (its
/// `blind_sequences`): see [`parse_blind_sequences`].
///
/// ```
/// use workcell::cell::{load_blind_sequences, load_cell};
/// let cell = load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let path = std::env::temp_dir().join(format!("workcell-doc-{}-blind.json", std::process::id()));
/// std::fs::write(&path, r#"{"makespan": 15.7, "sequences": {"R1": ["weld-1", "weld-2"], "R2": ["weld-3", "weld-4"]},
///     "blind_sequences": {"R1": ["weld-1"], "R2": ["weld-2", "weld-3", "weld-4"]}}"#)?;
/// let blind = load_blind_sequences(&path, &cell);
/// std::fs::remove_file(&path)?;
/// assert_eq!(blind?.routes, [vec![0], vec![1, 2, 3]]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn load_blind_sequences(path: &Path, cell: &Cell) -> Result<Sequences, InputError> {
    parse_blind_sequences(&super::reading::read_file(path)?, path, cell)
}

/// The sequencer's collision-blind sequences of a whole `solve --json` result, read from its
/// `blind_sequences` as [`parse_sequences`] reads `sequences`, without waits or changed
/// legs (they belong to the final schedule). Refused as there, and when `text` is not a
/// whole result or has no `blind_sequences` (an `evaluate` result has none).
///
/// ```
/// use workcell::cell::{load_cell, parse_blind_sequences};
/// let cell = load_cell(concat!(env!("CARGO_MANIFEST_DIR"), "/cells/feedback-cell.json").as_ref())?.cell;
/// let file = "result.json".as_ref();
/// let result = r#"{"makespan": 15.7, "sequences": {"R1": ["weld-1", "weld-2"], "R2": ["weld-3", "weld-4"]},
///     "blind_sequences": {"R1": ["weld-2", "weld-1"], "R2": ["weld-3", "weld-4"]}}"#;
/// assert_eq!(parse_blind_sequences(result, file, &cell)?.routes, [vec![1, 0], vec![2, 3]]);
/// // Plain sequences are not a solve result: they have no blind ones.
/// assert!(parse_blind_sequences(r#"{"R1": ["weld-1"]}"#, file, &cell).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn parse_blind_sequences(
    text: &str,
    file: &Path,
    cell: &Cell,
) -> Result<Sequences, InputError> {
    parse(text, file, cell, "blind_sequences")
}

/// Reads the routes of `key` in a whole result (`sequences`: with its waits and legs), or,
/// for `sequences` only, the document itself as a map of robots to task lists.
fn parse(text: &str, file: &Path, cell: &Cell, key: &str) -> Result<Sequences, InputError> {
    let blind = key != "sequences";
    let err = |body: Option<&str>, field: &str, reason: String| {
        InputError::new(file, body, field, reason)
    };
    let top = entries(text).map_err(|e| match e.classify() {
        serde_json::error::Category::Data => err(None, "", NOT_SEQUENCES.to_owned()),
        _ => err(None, "", format!("not valid JSON: {e}")),
    })?;
    let find = |key: &str| {
        let mut found = top.iter().filter(|(k, _)| k == key).map(|(_, v)| *v);
        match (found.next(), found.next()) {
            (_, Some(_)) => Err(err(None, key, "the key is given twice".to_owned())),
            (one, None) => Ok(one),
        }
    };
    // A whole `solve` result has `makespan` beside `sequences`; otherwise `sequences` may be
    // a robot's name.
    let whole =
        top.iter().any(|(k, _)| k == "makespan") && top.iter().any(|(k, _)| k == "sequences");
    if whole {
        let keys = top.iter().map(|(k, _)| k.as_str());
        if let Some((key, reason)) = super::object_only::first_unknown(keys, RESULT_KEYS) {
            return Err(err(None, &key, reason));
        }
    }
    if blind && !whole {
        let reason = "not a whole `solve --json` result (with `makespan` and `sequences`)";
        return Err(err(None, "", reason.to_owned()));
    }
    let prefix = format!("{key}.");
    let (prefix, robots) = if whole {
        let raw = match find(key)? {
            Some(raw) if raw.get() != "null" => raw,
            _ => {
                let reason =
                    "the result has no collision-blind sequences (only `solve` gives them)";
                return Err(err(None, key, reason.to_owned()));
            }
        };
        let robots = entries(raw.get()).map_err(|_| err(None, key, NOT_SEQUENCES.to_owned()))?;
        (prefix.as_str(), robots)
    } else {
        // A key beginning with `_` is a comment, unless a robot has that name.
        let comment = |k: &str| k.starts_with('_') && !cell.robots.iter().any(|r| r.name == k);
        let robots = top.iter().filter(|(k, _)| !comment(k)).cloned().collect();
        ("", robots)
    };
    let (routes, done_by) = routes(&robots, prefix, file, cell)?;
    if let Some(t) = done_by.iter().position(Option::is_none) {
        let name = &cell.tasks[t].name;
        let reason =
            format!("task \"{name}\" is in no robot's sequence: every task must be done once");
        let field = if whole { key } else { "(every robot's list)" };
        return Err(err(Some(name), field, reason));
    }
    let waits = match find("waits")?.filter(|_| whole && !blind) {
        Some(list) if list.get() != "null" => waits(list, file, cell, &routes)?,
        _ => Vec::new(),
    };
    // Changed moves are few (one per remedy): read as a tree.
    let legs = match find("legs")?.filter(|_| whole && !blind) {
        Some(list) if list.get() != "null" => {
            let list: serde_json::Value = serde_json::from_str(list.get())
                .map_err(|e| err(None, "legs", format!("not valid JSON: {e}")))?;
            super::parse_legs(&list, file, cell, &routes)?
        }
        _ => Vec::new(),
    };
    let configurations = match find("configurations")?.filter(|_| whole && !blind) {
        Some(list) if list.get() != "null" => configurations(list, file, cell, &routes)?,
        _ => vec![Vec::new(); cell.robots.len()],
    };
    Ok(Sequences {
        routes,
        waits,
        legs,
        configurations,
    })
}

/// A result's `configurations`: per arm, one list of joint angles (one per link) per task
/// of its route. Whether each puts the tool on its task is for `evaluate` to judge.
fn configurations(
    raw: &RawValue,
    file: &Path,
    cell: &Cell,
    routes: &[Vec<usize>],
) -> Result<Vec<Vec<Vec<f64>>>, InputError> {
    let err = |body: Option<&str>, field: String, reason: String| {
        InputError::new(file, body, field, reason)
    };
    let lists: std::collections::BTreeMap<String, Vec<Vec<f64>>> = serde_json::from_str(raw.get())
        .map_err(|e| {
            let reason = format!("expected each arm's list of joint angles per task: {e}");
            err(None, "configurations".into(), reason)
        })?;
    let mut out = vec![Vec::new(); cell.robots.len()];
    for (name, list) in lists {
        if name.starts_with('_') && !cell.robots.iter().any(|r| r.name == name) {
            continue;
        }
        let field = format!("configurations.{name}");
        let Some(r) = cell.robots.iter().position(|x| x.name == name) else {
            return Err(err(
                Some(&name),
                field,
                "the cell has no robot of this name".into(),
            ));
        };
        let Some(arm) = cell.robots[r].as_arm() else {
            return Err(err(
                Some(&name),
                field,
                "a rigid robot has no joints".into(),
            ));
        };
        if list.len() != routes[r].len() {
            let reason = format!(
                "{} configurations for the {} tasks of its sequence",
                list.len(),
                routes[r].len()
            );
            return Err(err(Some(&name), field, reason));
        }
        if let Some(k) = list.iter().position(|q| q.len() != arm.links.len()) {
            let reason = format!(
                "{} angles for an arm of {} links",
                list[k].len(),
                arm.links.len()
            );
            return Err(err(Some(&name), format!("{field}[{k}]"), reason));
        }
        out[r] = list;
    }
    Ok(out)
}

/// For each task, the field of the list that names it (none: no list does).
type DoneBy = Vec<Option<String>>;

/// Robots' names with their raw lists, in file order.
type NamedLists<'t> = [(String, &'t RawValue)];

/// Each robot's route from its list of task names (`robots`: name to raw list, `prefix` the
/// lists' field), and for each task the field that names it (none: no list does). A robot
/// listed twice, an unknown robot or task, a task the robot may not do, or one listed twice
/// is refused.
fn routes(
    robots: &NamedLists,
    prefix: &str,
    file: &Path,
    cell: &Cell,
) -> Result<(Vec<Vec<usize>>, DoneBy), InputError> {
    let err = |body: Option<&str>, field: &str, reason: String| {
        InputError::new(file, body, field, reason)
    };
    let mut seen = std::collections::HashSet::new();
    if let Some((robot, _)) = robots.iter().find(|(k, _)| !seen.insert(k.as_str())) {
        let reason = "the robot is listed twice".to_owned();
        return Err(err(Some(robot), &key_field(prefix, robot), reason));
    }
    let task_index: std::collections::HashMap<&str, usize> = cell
        .tasks
        .iter()
        .enumerate()
        .map(|(k, t)| (t.name.as_str(), k))
        .collect();
    let mut routes = vec![Vec::new(); cell.robots.len()];
    let mut done_by: Vec<Option<String>> = vec![None; cell.tasks.len()];
    for (robot, list) in robots {
        let field = key_field(prefix, robot);
        let Some(r) = cell.robots.iter().position(|x| &x.name == robot) else {
            let reason = "the cell has no robot of this name".to_owned();
            return Err(err(Some(robot), &field, reason));
        };
        let mut route = Vec::new();
        for_each_item(list, &mut |k, item| {
            let field = format!("{field}[{k}]");
            let Ok(name) = serde_json::from_str::<String>(item.get()) else {
                let reason = format!("expected a task name, found {}", item.get());
                return Err(err(Some(robot), &field, reason));
            };
            let Some(&t) = task_index.get(name.as_str()) else {
                let reason = format!("the cell has no task \"{name}\"");
                return Err(err(Some(robot), &field, reason));
            };
            if !cell.tasks[t].robots.contains(&r) {
                let reason = format!("{robot} is not allowed to do task \"{name}\"");
                return Err(err(Some(robot), &field, reason));
            }
            if let Some(first) = &done_by[t] {
                let reason = format!("task \"{name}\" is already done at `{first}`");
                return Err(err(Some(robot), &field, reason));
            }
            done_by[t] = Some(field);
            route.push(t);
            Ok(())
        })
        .map_err(|refused| {
            refused
                .unwrap_or_else(|| err(Some(robot), &field, "expected a list of task names".into()))
        })?;
        routes[r] = route;
    }
    Ok((routes, done_by))
}

/// The field of a robot's list: its key, or `""` for the empty key (found by fuzzing: an
/// empty key made an error that named no field).
fn key_field(prefix: &str, robot: &str) -> String {
    if robot.is_empty() {
        format!("{prefix}\"\"")
    } else {
        format!("{prefix}{robot}")
    }
}

/// An object's entries in document order, repeated keys kept, their values unparsed.
fn entries(text: &str) -> Result<Vec<(String, &RawValue)>, serde_json::Error> {
    struct Entries;
    impl<'de> Visitor<'de> for Entries {
        type Value = Vec<(String, &'de RawValue)>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("an object")
        }
        fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
            let mut out = Vec::new();
            while let Some(entry) = map.next_entry::<String, &'de RawValue>()? {
                out.push(entry);
            }
            Ok(out)
        }
    }
    let mut de = serde_json::Deserializer::from_str(text);
    let out = (&mut de).deserialize_map(Entries)?;
    de.end()?;
    Ok(out)
}

/// Calls `each` on every item of the JSON array `raw`, in order, keeping none of them.
/// `Err(None)`: `raw` is not an array; `Err(Some(e))`: `each` refused an item.
fn for_each_item<'a>(
    raw: &'a RawValue,
    each: &mut dyn FnMut(usize, &'a RawValue) -> Result<(), InputError>,
) -> Result<(), Option<InputError>> {
    struct Items<'f, 'a> {
        each: &'f mut dyn FnMut(usize, &'a RawValue) -> Result<(), InputError>,
        refused: &'f mut Option<InputError>,
    }
    impl<'f, 'de> Visitor<'de> for Items<'f, 'de> {
        type Value = ();
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a list")
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
            let mut k = 0;
            while let Some(item) = seq.next_element::<&'de RawValue>()? {
                if let Err(e) = (self.each)(k, item) {
                    *self.refused = Some(e);
                    return Err(de::Error::custom("refused"));
                }
                k += 1;
            }
            Ok(())
        }
    }
    let mut refused = None;
    let mut de = serde_json::Deserializer::from_str(raw.get());
    let items = Items {
        each,
        refused: &mut refused,
    };
    match (&mut de).deserialize_seq(items) {
        Ok(()) => Ok(()),
        Err(_) => Err(refused),
    }
}

/// The fields of one wait, unparsed.
#[derive(Default)]
struct RawWait<'a> {
    robot: Option<&'a RawValue>,
    before_move: Option<&'a RawValue>,
    duration: Option<&'a RawValue>,
}

/// A wait's keys: `before` is the move in words, as `solve` writes it (not read).
const WAIT_KEYS: &[&str] = &["robot", "before_move", "before", "duration"];

impl<'de: 'a, 'a> serde::Deserialize<'de> for RawWait<'a> {
    /// An object of [`WAIT_KEYS`]; keys beginning with `_` skipped, any other refused.
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Fields;
        impl<'de> Visitor<'de> for Fields {
            type Value = RawWait<'de>;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a wait: an object with `robot`, `before_move` and `duration`")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
                let mut raw = RawWait::default();
                while let Some(key) = map.next_key::<&'de str>()? {
                    let slot = match key {
                        "robot" => &mut raw.robot,
                        "before_move" => &mut raw.before_move,
                        "duration" => &mut raw.duration,
                        "before" => {
                            map.next_value::<de::IgnoredAny>()?;
                            continue;
                        }
                        _ if key.starts_with('_') => {
                            map.next_value::<de::IgnoredAny>()?;
                            continue;
                        }
                        _ => return Err(de::Error::unknown_field(key, WAIT_KEYS)),
                    };
                    *slot = Some(map.next_value()?);
                }
                Ok(raw)
            }
        }
        d.deserialize_map(Fields)
    }
}

fn waits(
    list: &RawValue,
    file: &Path,
    cell: &Cell,
    routes: &[Vec<usize>],
) -> Result<Vec<Wait>, InputError> {
    let mut waits = Vec::new();
    for_each_item(list, &mut |k, item| {
        let at = format!("waits[{k}]");
        // Only an object: serde would read an array positionally.
        if !item.get().starts_with('{') {
            let reason = "expected an object {\"robot\", \"before_move\", \"duration\"}";
            return Err(InputError::new(file, None, at, reason));
        }
        let raw: RawWait = serde_json::from_str(item.get()).map_err(|e| {
            // serde_json's place is in the wait's own text, not the file's: left out.
            let said = e.to_string();
            let said = said.split(" at line ").next().unwrap_or_default();
            match super::object_only::unknown_key(said) {
                Some((key, reason)) => InputError::new(file, None, format!("{at}.{key}"), reason),
                None => InputError::new(file, None, at.as_str(), said.to_owned()),
            }
        })?;
        let name = raw
            .robot
            .and_then(|v| serde_json::from_str::<String>(v.get()).ok());
        let Some(robot) = name
            .as_deref()
            .and_then(|n| cell.robots.iter().position(|r| r.name == n))
        else {
            let reason = "`robot` must name a robot of the cell";
            return Err(InputError::new(
                file,
                name.as_deref(),
                format!("{at}.robot"),
                reason,
            ));
        };
        let moves = routes[robot].len() + 1;
        let before_move = raw
            .before_move
            .and_then(|v| serde_json::from_str::<u64>(v.get()).ok());
        let Some(before_move) = before_move.filter(|&m| m < moves as u64) else {
            let reason = format!(
                "`before_move` must be a move of the robot: 0 to {}",
                moves - 1
            );
            let field = format!("{at}.before_move");
            return Err(InputError::new(file, name.as_deref(), field, reason));
        };
        let duration = raw
            .duration
            .and_then(|v| serde_json::from_str::<f64>(v.get()).ok());
        let Some(duration) = duration.filter(|d| d.is_finite() && *d >= 0.0) else {
            let reason = "`duration` must be a non-negative number";
            let field = format!("{at}.duration");
            return Err(InputError::new(file, name.as_deref(), field, reason));
        };
        waits.push(Wait {
            robot,
            before_move: before_move as usize,
            duration,
        });
        Ok(())
    })
    .map_err(|refused| {
        refused.unwrap_or_else(|| {
            let reason = "expected a list of {\"robot\", \"before_move\", \"duration\"}";
            InputError::new(file, None, "waits", reason)
        })
    })?;
    Ok(waits)
}
