//! What the readers of scene and cell files share: the file's text, one JSON document with
//! the field that does not fit named, δ, and polygons.

use super::InputError;
use crate::geometry::{ConvexPolygon, PolygonError, PolygonWarning};
use serde::Deserialize;
use std::path::Path;

/// δ when the file gives none.
pub const DEFAULT_DELTA: f64 = 0.001;

/// The file's δ, or [`DEFAULT_DELTA`], refused as [`Scene::new`] refuses it.
///
/// [`Scene::new`]: crate::collision::Scene::new
pub(super) fn delta(given: Option<f64>, file: &Path) -> Result<f64, InputError> {
    let delta = given.unwrap_or(DEFAULT_DELTA);
    crate::collision::check_delta(delta).map_err(|e| e.in_file(file))?;
    Ok(delta)
}

/// A vertex as written, `[x, y]`, read without a vector of its own (one allocation per
/// vertex was a tenth of loading); any other count of numbers is kept to be refused by name.
pub(super) struct Point {
    xy: [f64; 2],
    len: usize,
}

impl Point {
    /// No number yet.
    pub(super) fn empty() -> Self {
        Point {
            xy: [0.0; 2],
            len: 0,
        }
    }

    /// The next number of the vertex.
    pub(super) fn push(&mut self, v: f64) {
        if let Some(slot) = self.xy.get_mut(self.len) {
            *slot = v;
        }
        self.len += 1;
    }
}

impl<'de> Deserialize<'de> for Point {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Numbers;
        impl<'de> serde::de::Visitor<'de> for Numbers {
            type Value = Point;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                // What `Vec<f64>` says, as this was one.
                f.write_str("a sequence")
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<Point, A::Error> {
                let mut p = Point::empty();
                while let Some(v) = seq.next_element::<f64>()? {
                    p.push(v);
                }
                Ok(p)
            }
        }
        d.deserialize_seq(Numbers)
    }
}

/// The text of the file at `path`.
pub(super) fn read_file(path: &Path) -> Result<String, InputError> {
    std::fs::read_to_string(path)
        .map_err(|e| InputError::new(path, None, "", format!("cannot read the file: {e}")))
}

/// One JSON document of type `T` (a `what`: scene, cell) and nothing after it; a field that
/// does not fit is named by its path, with the body it belongs to when that can be told.
pub(super) fn document<T: serde::de::DeserializeOwned>(
    text: &str,
    file: &Path,
    what: &str,
) -> Result<T, InputError> {
    // Tracking the path of every field costs as much as the parse itself: parse without it,
    // and only a document that fails is read again to name the field.
    let de = &mut serde_json::Deserializer::from_str(text);
    if let Ok(raw) = T::deserialize(&mut *de).and_then(|raw| de.end().map(|()| raw)) {
        return Ok(raw);
    }
    refusal(text, file, what)
}

/// The error of [`document`] for a document that does not fit `T`.
#[cold]
fn refusal<T: serde::de::DeserializeOwned>(
    text: &str,
    file: &Path,
    what: &str,
) -> Result<T, InputError> {
    let de = &mut serde_json::Deserializer::from_str(text);
    let raw: T = serde_path_to_error::deserialize(&mut *de).map_err(|e| {
        let field = match e.path().to_string() {
            root if root == "." => String::new(),
            path => path,
        };
        let body = body_named_by(text, &field);
        let said = e.inner().to_string();
        // An unknown key is named by its own path (`tasks[3].robot`).
        let (field, reason) = match super::object_only::unknown_key(&said) {
            Some((key, reason)) if field.is_empty() => (key, reason),
            Some((key, reason)) => (format!("{field}.{key}"), reason),
            None => (field, said),
        };
        InputError::new(file, body.as_deref(), field, reason)
    })?;
    de.end().map_err(|e| {
        let reason = format!("unexpected data after the {what} document: {e}");
        InputError::new(file, None, "", reason)
    })?;
    Ok(raw)
}

/// The name of the robot, obstacle or task that a field path such as `robots[2].shape` points
/// into, when the document is valid enough JSON to find it.
fn body_named_by(text: &str, field: &str) -> Option<String> {
    // Only the names are read, everything else is skipped unparsed: the field that failed
    // (say a number out of range) must not fail this too.
    #[derive(Deserialize)]
    struct Named {
        name: Option<String>,
    }
    #[derive(Deserialize)]
    struct Names {
        #[serde(default)]
        robots: Vec<Named>,
        #[serde(default)]
        obstacles: Vec<Named>,
        #[serde(default)]
        tasks: Vec<Named>,
    }
    let (list, rest) = field.split_once('[')?;
    let index: usize = rest.split_once(']')?.0.parse().ok()?;
    let names: Names = serde_json::from_str(text).ok()?;
    let bodies = match list {
        "robots" => names.robots,
        "obstacles" => names.obstacles,
        "tasks" => names.tasks,
        _ => return None,
    };
    bodies.into_iter().nth(index)?.name
}

pub(super) fn polygon(
    file: &Path,
    body: &str,
    field: &str,
    points: &[Point],
    warnings: &mut Vec<String>,
) -> Result<ConvexPolygon, InputError> {
    let vertices = vertices(file, body, field, points)?;
    let (shape, repairs) = ConvexPolygon::new(&vertices).map_err(|e| {
        let field = match &e {
            PolygonError::NotFinite { vertex, .. } | PolygonError::NotConvex { vertex } => {
                format!("{field}[{vertex}]")
            }
            _ => field.to_owned(),
        };
        InputError::new(file, Some(body), field, e)
    })?;
    report_repairs(file, body, field, &repairs, warnings);
    Ok(shape)
}

/// The `[x, y]` vertices of a polygon's field.
pub(super) fn vertices(
    file: &Path,
    body: &str,
    field: &str,
    points: &[Point],
) -> Result<Vec<[f64; 2]>, InputError> {
    let mut vertices = Vec::with_capacity(points.len());
    for (k, p) in points.iter().enumerate() {
        match p.len {
            2 => vertices.push(p.xy),
            _ => {
                let reason = format!("a vertex is [x, y], found {} numbers", p.len);
                return Err(InputError::new(
                    file,
                    Some(body),
                    format!("{field}[{k}]"),
                    reason,
                ));
            }
        }
    }
    Ok(vertices)
}

/// The repairs made to a polygon's field, as warnings.
pub(super) fn report_repairs(
    file: &Path,
    body: &str,
    field: &str,
    repairs: &[PolygonWarning],
    warnings: &mut Vec<String>,
) {
    if repairs.is_empty() {
        return;
    }
    // A long list of repairs says no more than its first few and its length.
    const SHOWN: usize = 8;
    let at = format!("{}: body \"{body}\", field `{field}`", file.display());
    for r in repairs.iter().take(SHOWN) {
        warnings.push(format!("{at}: {r}"));
    }
    if repairs.len() > SHOWN {
        warnings.push(format!("{at}: and {} more repairs", repairs.len() - SHOWN));
    }
}
