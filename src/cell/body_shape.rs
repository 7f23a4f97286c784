//! A body's geometry as a file gives it: `shape` (one convex polygon), `parts` (convex
//! polygons, their union) or `outline` (one simple polygon), exactly one of them (contract
//! sections 1 and 5).

use super::reading::{polygon, report_repairs, vertices, Point};
use super::InputError;
use crate::geometry::{Outline, OutlineError, Parts};
use std::path::Path;

/// The three ways of giving a body's geometry, as read; [`BodyShape::parts`] checks that
/// exactly one is there.
#[derive(Default)]
pub(super) struct BodyShape<'a> {
    pub shape: Option<&'a [Point]>,
    pub parts: Option<&'a [Vec<Point>]>,
    pub outline: Option<&'a [Point]>,
}

impl BodyShape<'_> {
    /// The body's region as convex parts (one for a `shape`), validated; `at` is the body's
    /// field path (`robots[2]`), warnings get the repairs.
    pub fn parts(
        &self,
        file: &Path,
        body: &str,
        at: &str,
        warnings: &mut Vec<String>,
    ) -> Result<Parts, InputError> {
        let error =
            |field: String, reason: String| InputError::new(file, Some(body), field, reason);
        let given: Vec<&str> = [
            ("shape", self.shape.is_some()),
            ("parts", self.parts.is_some()),
            ("outline", self.outline.is_some()),
        ]
        .into_iter()
        .filter_map(|(key, there)| there.then_some(key))
        .collect();
        match given.as_slice() {
            [] => {
                let reason = "a body needs one of `shape`, `parts` or `outline`".to_owned();
                return Err(error(format!("{at}.shape"), reason));
            }
            [_] => {}
            [first, second, ..] => {
                let reason = format!(
                    "`{first}` and `{second}` are both given: a body takes exactly one of \
                     `shape`, `parts` or `outline`"
                );
                return Err(error(format!("{at}.{second}"), reason));
            }
        }
        let hull_error =
            |field: String| move |e| error(field, format!("the convex hull of the parts: {e}"));
        if let Some(points) = self.shape {
            let field = format!("{at}.shape");
            let shape = polygon(file, body, &field, points, warnings)?;
            return Parts::new(vec![shape]).map_err(hull_error(field));
        }
        if let Some(list) = self.parts {
            let field = format!("{at}.parts");
            if list.is_empty() {
                return Err(error(
                    field,
                    "`parts` needs at least one convex polygon".into(),
                ));
            }
            let parts = list
                .iter()
                .enumerate()
                .map(|(k, points)| polygon(file, body, &format!("{field}[{k}]"), points, warnings))
                .collect::<Result<Vec<_>, _>>()?;
            return Parts::new(parts).map_err(hull_error(field));
        }
        let points = self.outline.unwrap_or_default();
        let field = format!("{at}.outline");
        let outline = Outline::new(&vertices(file, body, &field, points)?)
            .map_err(|e| outline_error(file, body, &field, e))?;
        report_repairs(file, body, &field, outline.warnings(), warnings);
        Parts::from_outline(&outline).map_err(|e| outline_error(file, body, &field, e))
    }
}

/// An outline's error, naming the vertex where there is one.
fn outline_error(file: &Path, body: &str, field: &str, e: OutlineError) -> InputError {
    let field = match &e {
        OutlineError::NotFinite { vertex, .. }
        | OutlineError::DoublesBack { vertex }
        | OutlineError::Sliver { vertex } => format!("{field}[{vertex}]"),
        _ => field.to_owned(),
    };
    InputError::new(file, Some(body), field, e)
}
