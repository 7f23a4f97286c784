//! Output files: written whole or not at all, and never over an input.

use std::io::Write;
use std::path::{Path, PathBuf};
use workcell::cell::InputError;

/// Writes `text` to `file` through a temporary file in the same folder, renamed over `file`
/// once complete: a full disk or a crash leaves the previous file (or none), never part of
/// the new one. An existing file keeps its permissions.
pub fn write_file(file: &Path, text: &[u8]) -> Result<(), InputError> {
    let fail = |e: std::io::Error| {
        // tempfile appends ` at path "<the temporary file>"`, a name the user never gave.
        let text = e.to_string();
        let why = text.split(" at path \"").next().unwrap_or(&text);
        InputError {
            file: file.to_path_buf(),
            body: None,
            field: String::new(),
            reason: format!("cannot write the file: {why}"),
        }
    };
    let folder = match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".workcell-").suffix(".tmp");
    match std::fs::metadata(file) {
        Ok(existing) => {
            builder.permissions(existing.permissions());
        }
        Err(_) => new_file_permissions(&mut builder),
    }
    let mut temp = builder.tempfile_in(folder).map_err(fail)?;
    temp.write_all(text).map_err(fail)?;
    temp.as_file().sync_all().map_err(fail)?;
    // On failure the temporary file is dropped, and with it removed.
    temp.persist(file).map_err(|e| fail(e.error))?;
    Ok(())
}

/// What `std::fs::write` gives a new file, not the temporary file's owner-only mode: read
/// and write for all, less the umask (which the system applies on creation).
#[cfg(unix)]
fn new_file_permissions(builder: &mut tempfile::Builder) {
    use std::os::unix::fs::PermissionsExt;
    builder.permissions(std::fs::Permissions::from_mode(0o666));
}

#[cfg(not(unix))]
fn new_file_permissions(_: &mut tempfile::Builder) {}

/// Refuses an output that names one of the inputs, or the same file as another output,
/// however the paths are spelled (`./a/../cell.json`, a link): writing it would replace a
/// file still to be read, or one result by another. `outputs` pairs each path with the
/// option that names it.
pub fn check_outputs(inputs: &[&Path], outputs: &[(&str, &Path)]) -> Result<(), InputError> {
    for (k, &(option, output)) in outputs.iter().enumerate() {
        let refuse = |what: String| InputError {
            file: output.to_path_buf(),
            body: None,
            field: String::new(),
            reason: format!("`{option}` names {what}; choose another path"),
        };
        if let Some(input) = inputs.iter().find(|i| same(i, output)) {
            let what = format!("the input file {}, which it would replace", input.display());
            return Err(refuse(what));
        }
        if let Some((other, _)) = outputs[..k].iter().find(|(_, o)| same(o, output)) {
            return Err(refuse(format!("the same file as `{other}`")));
        }
    }
    Ok(())
}

/// Whether two paths name one file: the same file on disk (hard links included), or, for a
/// file not yet written, the same name in the same folder.
fn same(a: &Path, b: &Path) -> bool {
    same_file::is_same_file(a, b).unwrap_or(false) || resolved(a) == resolved(b)
}

/// The path with its folder resolved (links, `.` and `..`), when the folder exists.
fn resolved(p: &Path) -> Option<PathBuf> {
    if let Ok(full) = p.canonicalize() {
        return Some(full);
    }
    let name = p.file_name()?;
    let folder = match p.parent() {
        Some(f) if !f.as_os_str().is_empty() => f,
        _ => Path::new("."),
    };
    Some(folder.canonicalize().ok()?.join(name))
}
