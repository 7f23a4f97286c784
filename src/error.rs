//! The one error type for unusable input.

use std::fmt;
use std::path::PathBuf;

/// Input that cannot be used: names the file, the body (when known) and the field.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub struct InputError {
    /// The file read; empty for arguments given in code (see [`InputError::in_file`]).
    pub file: PathBuf,
    /// The body (robot or obstacle) concerned, when there is one.
    pub body: Option<String>,
    /// Path of the field in the document, e.g. `robots[0].trajectory[3].t`.
    pub field: String,
    /// Why it cannot be used.
    pub reason: String,
}

impl InputError {
    pub(crate) fn new(
        file: &std::path::Path,
        body: Option<&str>,
        field: impl Into<String>,
        reason: impl fmt::Display,
    ) -> Self {
        InputError {
            file: file.to_path_buf(),
            body: body.map(str::to_owned),
            field: field.into(),
            reason: reason.to_string(),
        }
    }
}

impl InputError {
    /// The same error about `file`, when it names none yet: the library's checks of
    /// arguments know no file, the command line that passed them does.
    ///
    /// ```
    /// use workcell::collision::{validate, CheckOptions, Scene};
    /// use std::path::Path;
    /// let opts = CheckOptions { delta: Some(-1.0), ..CheckOptions::default() };
    /// let e = validate(&Scene::new(0.01)?, &opts).unwrap_err();
    /// assert_eq!(e.file, Path::new("")); // the library knows no file
    /// let e = e.in_file("scene.json".as_ref());
    /// assert!(e.to_string().starts_with("scene.json: "), "{e}");
    /// assert_eq!(e.in_file("other.json".as_ref()).file, Path::new("scene.json")); // kept
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn in_file(self, file: &std::path::Path) -> Self {
        if self.file.as_os_str().is_empty() {
            InputError {
                file: file.to_path_buf(),
                ..self
            }
        } else {
            self
        }
    }
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if !self.file.as_os_str().is_empty() {
            write!(f, "{}: ", self.file.display())?;
        }
        if let Some(body) = &self.body {
            write!(f, "body \"{body}\", ")?;
        }
        if !self.field.is_empty() {
            write!(f, "field `{}`: ", self.field)?;
        }
        write!(f, "{}", self.reason)
    }
}
