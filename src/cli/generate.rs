//! `workcell generate`: write deterministic random scenes of one kind.

use std::io::Write;
use std::path::Path;
use std::process::ExitCode;
use workcell::cell::{scene_document, InputError};
use workcell::generate::{generate_scene, scene_file_name, Kind};

/// Writes `DIR/<kind>-<seed>-<k>.json` for each kind and k in 0..count, creating `out` if
/// missing, and prints one line per file. Same arguments, same bytes.
pub fn run_generate(
    kinds: &[Kind],
    seed: u64,
    robots: Option<usize>,
    count: u64,
    out: &Path,
) -> Result<ExitCode, InputError> {
    let fail = |file: &Path, reason: String| InputError {
        file: file.to_path_buf(),
        body: None,
        field: String::new(),
        reason,
    };
    if let (Some(_), [kind]) = (robots, kinds) {
        if *kind != Kind::Hall {
            return Err(fail(
                out,
                format!(
                    "--robots applies only to --kind hall, not to {}",
                    kind.name()
                ),
            ));
        }
    }
    std::fs::create_dir_all(out)
        .map_err(|e| fail(out, format!("cannot create the output folder: {e}")))?;
    let mut stdout = std::io::stdout().lock();
    for (&kind, k) in kinds
        .iter()
        .flat_map(|kind| (0..count).map(move |k| (kind, k)))
    {
        let scene = generate_scene(kind, seed, k, robots.unwrap_or(10));
        let text = serde_json::to_string_pretty(&scene_document(&scene))
            .expect("a scene serialises")
            + "\n";
        let file = out.join(scene_file_name(kind, seed, k));
        std::fs::write(&file, text)
            .map_err(|e| fail(&file, format!("cannot write the file: {e}")))?;
        // A closed pipe (`| head`) is the reader's choice, not an error of ours.
        let _ = writeln!(stdout, "{}", file.display());
    }
    Ok(ExitCode::SUCCESS)
}
