//! Output files: written whole or not at all, never over an input, and never in place of
//! something that is not a plain file.
//!
//! What an output path names decides how it is written ([`Target`]): a plain file (or a new
//! one) is replaced whole through a temporary file; a symbolic link is followed, and what it
//! points to written (the link stays); a character device, a FIFO or an open descriptor
//! (`/dev/stdout`, a shell's `>(…)`) is written through, never replaced; a FIFO nobody reads
//! is refused at once rather than waited on. Nothing here opens a path to compare it: two
//! paths are one file when `stat` gives the same device and inode.

use std::io::Write;
use std::path::{Path, PathBuf};
use workcell::cell::InputError;

/// How an output path is written.
#[derive(Debug, PartialEq)]
enum Target {
    /// A plain file, or none yet: replaced whole by renaming a complete temporary file.
    Replace(PathBuf),
    /// A plain file with other names (hard links): rewritten in place, so that every name
    /// keeps showing it. The text is complete in memory before the file is opened.
    InPlace(PathBuf),
    /// A character device, a FIFO or an open descriptor: written through as a stream.
    Through(PathBuf),
}

fn error(file: &Path, reason: String) -> InputError {
    InputError {
        file: file.to_path_buf(),
        body: None,
        field: String::new(),
        reason,
    }
}

/// Writes `text` to `file` as its [`Target`] asks (see the module documentation).
pub fn write_file(file: &Path, text: &[u8]) -> Result<(), InputError> {
    match target(file)? {
        Target::Replace(path) => replace(file, &path, text),
        Target::InPlace(path) => in_place(file, &path, text),
        Target::Through(path) => through(file, &path, text),
    }
}

/// Whether `file` names an open descriptor of this process, written through whatever it is
/// (`/dev/stdout` into a file the shell opened appends, as `>>` would).
fn is_descriptor(file: &Path) -> bool {
    ["/dev/stdout", "/dev/stderr", "/dev/fd/", "/proc/self/fd/"]
        .iter()
        .any(|p| {
            file.to_str()
                .is_some_and(|f| f == *p || (p.ends_with('/') && f.starts_with(p)))
        })
}

/// What `file` names, links followed.
fn target(file: &Path) -> Result<Target, InputError> {
    if is_descriptor(file) {
        return Ok(Target::Through(file.to_path_buf()));
    }
    let link = std::fs::symlink_metadata(file).is_ok_and(|m| m.file_type().is_symlink());
    let path = match link {
        true => file.canonicalize().map_err(|e| {
            let reason = format!(
                "is a symbolic link to a file that cannot be reached ({e}); write to the \
                 target's own path, or remove the link"
            );
            error(file, reason)
        })?,
        false => file.to_path_buf(),
    };
    use std::io::ErrorKind::{NotADirectory, NotFound};
    let meta = match std::fs::metadata(&path) {
        Ok(meta) => meta,
        // No file yet (perhaps no folder either: the check before any work says which).
        Err(e) if matches!(e.kind(), NotFound | NotADirectory) => return Ok(Target::Replace(path)),
        Err(e) => return Err(error(file, format!("cannot write the file: {e}"))),
    };
    let kind = meta.file_type();
    if kind.is_file() {
        return Ok(match links(&meta) > 1 {
            true => Target::InPlace(path),
            false => Target::Replace(path),
        });
    }
    if kind.is_dir() {
        return Err(error(file, "is a folder, not a file".into()));
    }
    if streamed(&kind) {
        return Ok(Target::Through(path));
    }
    let reason = "is neither a file, a character device nor a FIFO (a block device or a \
                  socket): workcell writes no output there";
    Err(error(file, reason.into()))
}

#[cfg(unix)]
fn links(meta: &std::fs::Metadata) -> u64 {
    use std::os::unix::fs::MetadataExt;
    meta.nlink()
}

#[cfg(not(unix))]
fn links(_: &std::fs::Metadata) -> u64 {
    1
}

/// A character device or a FIFO: what takes a stream.
#[cfg(unix)]
fn streamed(kind: &std::fs::FileType) -> bool {
    use std::os::unix::fs::FileTypeExt;
    kind.is_char_device() || kind.is_fifo()
}

#[cfg(not(unix))]
fn streamed(_: &std::fs::FileType) -> bool {
    false
}

/// Writes `text` to `path` through a temporary file in the same folder, renamed over `path`
/// once complete: a full disk or a crash leaves the previous file (or none), never part of
/// the new one. An existing file keeps its permissions. Errors name `file`, the path given.
fn replace(file: &Path, path: &Path, text: &[u8]) -> Result<(), InputError> {
    let fail = |e: std::io::Error| {
        // tempfile appends ` at path "<the temporary file>"`, a name the user never gave.
        let text = e.to_string();
        let why = text.split(" at path \"").next().unwrap_or(&text);
        error(file, format!("cannot write the file: {why}"))
    };
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".workcell-").suffix(".tmp");
    match std::fs::metadata(path) {
        Ok(existing) => {
            builder.permissions(existing.permissions());
        }
        Err(_) => new_file_permissions(&mut builder),
    }
    let mut temp = builder.tempfile_in(folder).map_err(fail)?;
    temp.write_all(text).map_err(fail)?;
    temp.as_file().sync_all().map_err(fail)?;
    // On failure the temporary file is dropped, and with it removed.
    temp.persist(path).map_err(|e| fail(e.error))?;
    Ok(())
}

/// Rewrites a file with several names in place (see [`Target::InPlace`]).
fn in_place(file: &Path, path: &Path, text: &[u8]) -> Result<(), InputError> {
    let fail = |e: std::io::Error| error(file, format!("cannot write the file: {e}"));
    let mut out = std::fs::OpenOptions::new()
        .write(true)
        .truncate(true)
        .open(path)
        .map_err(fail)?;
    out.write_all(text).map_err(fail)?;
    out.sync_all().map_err(fail)
}

/// Writes `text` through to a device, a FIFO or a descriptor (see [`Target::Through`]).
fn through(file: &Path, path: &Path, text: &[u8]) -> Result<(), InputError> {
    let fail = |e: std::io::Error| error(file, format!("cannot write the file: {e}"));
    let mut out = open_stream(path).map_err(|e| match e.raw_os_error() {
        Some(code) if is_no_reader(code) => {
            let reason = "is a FIFO that no process reads: start its reader first (workcell \
                          does not wait for one)";
            error(file, reason.into())
        }
        _ => fail(e),
    })?;
    out.write_all(text).map_err(fail)?;
    out.flush().map_err(fail)
}

/// Opens a stream for writing without creating, truncating or waiting: a FIFO without a
/// reader fails at once (`ENXIO`) instead of blocking; once open, writes block as usual.
#[cfg(unix)]
fn open_stream(path: &Path) -> std::io::Result<std::fs::File> {
    use std::os::unix::fs::OpenOptionsExt;
    use std::os::unix::io::AsRawFd;
    let out = std::fs::OpenOptions::new()
        .append(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)?;
    // SAFETY: fcntl on a descriptor this function owns, with flags it read from it.
    unsafe {
        let fd = out.as_raw_fd();
        let flags = libc::fcntl(fd, libc::F_GETFL);
        if flags < 0 || libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK) < 0 {
            return Err(std::io::Error::last_os_error());
        }
    }
    Ok(out)
}

#[cfg(not(unix))]
fn open_stream(path: &Path) -> std::io::Result<std::fs::File> {
    std::fs::OpenOptions::new().append(true).open(path)
}

#[cfg(unix)]
fn is_no_reader(code: i32) -> bool {
    code == libc::ENXIO
}

#[cfg(not(unix))]
fn is_no_reader(_: i32) -> bool {
    false
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
/// option that names it. Outputs written through (devices, FIFOs, descriptors) replace
/// nothing and are not compared; a path no output can be written to is refused here.
pub fn check_outputs(inputs: &[&Path], outputs: &[(&str, &Path)]) -> Result<(), InputError> {
    for (k, &(option, output)) in outputs.iter().enumerate() {
        // A path that cannot take an output (a folder, a link to nothing) is refused now,
        // before any work.
        match target(output)? {
            Target::Through(_) => continue,
            Target::Replace(path) => can_create(option, output, &path)?,
            Target::InPlace(path) => {
                let open = std::fs::OpenOptions::new().write(true).open(&path);
                open.map_err(|e| error(output, format!("`{option}` cannot write it: {e}")))?;
            }
        }
        let refuse = |what: String| {
            error(
                output,
                format!("`{option}` names {what}; choose another path"),
            )
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

/// Whether a file can be created beside `path` (which a replacement does): its folder
/// exists and takes a new file. Tried with a temporary file, removed at once, so that
/// permissions, read-only mounts and quotas all answer as they will for the output.
fn can_create(option: &str, output: &Path, path: &Path) -> Result<(), InputError> {
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !folder.is_dir() {
        let why = match folder.exists() {
            true => "which is not a folder",
            false => "which does not exist; create it first",
        };
        let reason = format!(
            "`{option}` names a file in the folder {}, {why}",
            folder.display()
        );
        return Err(error(output, reason));
    }
    let probe = tempfile::Builder::new()
        .prefix(".workcell-")
        .suffix(".tmp")
        .tempfile_in(folder);
    probe.map(drop).map_err(|e| {
        let text = e.to_string();
        let why = text.split(" at path \"").next().unwrap_or(&text);
        let reason = format!(
            "`{option}` cannot create a file in the folder {}: {why}",
            folder.display()
        );
        error(output, reason)
    })
}

/// Whether two paths name one file: the same file on disk (links of either kind included),
/// or, for a file not yet written, the same name in the same existing folder. Nothing is
/// opened (a FIFO would block).
fn same(a: &Path, b: &Path) -> bool {
    if let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) {
        return same_inode(&ma, &mb);
    }
    matches!((resolved(a), resolved(b)), (Some(ra), Some(rb)) if ra == rb)
}

#[cfg(unix)]
fn same_inode(a: &std::fs::Metadata, b: &std::fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    (a.dev(), a.ino()) == (b.dev(), b.ino())
}

#[cfg(not(unix))]
fn same_inode(_: &std::fs::Metadata, _: &std::fs::Metadata) -> bool {
    false
}

/// The path with its folder resolved (links, `.` and `..`), when the folder exists; the
/// path of a link is that of what it points to.
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

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("workcell-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn paths_are_compared_by_inode_and_missing_folders_are_not_one() {
        let d = dir("same");
        let a = d.join("a.json");
        std::fs::write(&a, "{}").unwrap();
        std::fs::hard_link(&a, d.join("b.json")).unwrap();
        std::os::unix::fs::symlink(&a, d.join("c.json")).unwrap();
        assert!(same(&a, &d.join("b.json")) && same(&a, &d.join("c.json")));
        assert!(same(&d.join("new.svg"), &d.join("./new.svg")));
        // Two files in folders that do not exist are not one file.
        assert!(!same(
            Path::new("/nonexistent-a/x.svg"),
            Path::new("/nonexistent-b/y.svg")
        ));
        let outputs = [
            ("--svg", Path::new("/nonexistent-a/x.svg")),
            ("--gantt", Path::new("/nonexistent-b/y.svg")),
        ];
        // Refused for its own cause: the first folder is missing.
        let refused = check_outputs(&[&a], &outputs).unwrap_err();
        assert!(refused
            .reason
            .contains("/nonexistent-a, which does not exist"));
        assert!(check_outputs(&[&a], &[("--svg", &d.join("new.svg"))]).is_ok());
    }

    #[test]
    fn an_output_folder_that_takes_no_file_is_refused_before_any_work() {
        use std::os::unix::fs::PermissionsExt;
        let d = dir("readonly");
        let locked = d.join("locked");
        std::fs::create_dir(&locked).unwrap();
        std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o555)).unwrap();
        let probe = tempfile::tempfile_in(&locked);
        let result = check_outputs(&[], &[("--svg", &locked.join("x.svg"))]);
        // Root writes anywhere: then the check must let it through, as the write would.
        match probe {
            Ok(_) => assert!(result.is_ok()),
            Err(_) => {
                let reason = result.unwrap_err().reason;
                assert!(
                    reason.contains("cannot create a file in the folder"),
                    "{reason}"
                );
            }
        }
        assert!(
            std::fs::read_dir(&locked).unwrap().next().is_none(),
            "probe left behind"
        );
        std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o755)).unwrap();
        // A folder no one writes in, root included.
        if Path::new("/proc/self").exists() {
            let reason = check_outputs(&[], &[("--svg", Path::new("/proc/x.svg"))])
                .unwrap_err()
                .reason;
            assert!(
                reason.contains("cannot create a file in the folder /proc"),
                "{reason}"
            );
        }
        let file = d.join("plain.txt");
        std::fs::write(&file, "").unwrap();
        let reason = check_outputs(&[], &[("--svg", &file.join("x.svg"))])
            .unwrap_err()
            .reason;
        assert!(reason.contains("which is not a folder"), "{reason}");
    }

    #[test]
    fn each_kind_of_path_is_written_its_own_way() {
        let d = dir("kinds");
        let plain = d.join("plain.svg");
        assert_eq!(target(&plain).unwrap(), Target::Replace(plain.clone()));
        std::fs::write(&plain, "old").unwrap();
        let link = d.join("link.svg");
        std::os::unix::fs::symlink(&plain, &link).unwrap();
        let canonical = plain.canonicalize().unwrap();
        assert_eq!(target(&link).unwrap(), Target::Replace(canonical.clone()));
        write_file(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read_to_string(&plain).unwrap(), "new");
        let hard = d.join("hard.svg");
        std::fs::hard_link(&plain, &hard).unwrap();
        assert_eq!(target(&hard).unwrap(), Target::InPlace(hard.clone()));
        write_file(&hard, b"both").unwrap();
        assert_eq!(std::fs::read_to_string(&plain).unwrap(), "both");
        let dangling = d.join("dangling.svg");
        std::os::unix::fs::symlink(d.join("missing/x.svg"), &dangling).unwrap();
        assert!(target(&dangling)
            .unwrap_err()
            .reason
            .contains("symbolic link"));
        assert!(target(&d).unwrap_err().reason.contains("folder"));
        // Refused before any work, as a folder is.
        assert!(check_outputs(&[], &[("--svg", &dangling)]).is_err());
        assert!(check_outputs(&[], &[("--svg", &d)]).is_err());
        assert!(check_outputs(&[], &[("--svg", Path::new("/dev/null"))]).is_ok());
        assert!(matches!(
            target(Path::new("/dev/null")),
            Ok(Target::Through(_))
        ));
        assert!(matches!(
            target(Path::new("/dev/stdout")),
            Ok(Target::Through(_))
        ));
        write_file(Path::new("/dev/null"), b"gone").unwrap();
    }
}
