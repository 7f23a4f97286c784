//! `workcell generate`: write deterministic random scenes, conflict cells, or cells.

use std::io::Write;
use std::path::Path;
use std::process::ExitCode;
use workcell::cell::{scene_document, InputError};
use workcell::generate::{
    cell_file_name, conflict_file_name, generate_cell, generate_conflict_cell, generate_scara_cell,
    generate_scene, scara_file_name, scene_file_name, CellRequest, ConflictKind, Kind,
    ScaraRequest,
};

/// Every accepted `--kind` value: the scene families and `all`, the conflict families and
/// `conflict`, `cell` and `scara`.
pub fn kind_names() -> Vec<&'static str> {
    let scenes = Kind::ALL.map(Kind::name).into_iter().chain(["all"]);
    let conflicts = ConflictKind::ALL
        .map(ConflictKind::name)
        .into_iter()
        .chain(["conflict"]);
    scenes.chain(conflicts).chain(["cell", "scara"]).collect()
}

/// What `generate` writes.
pub enum What<'a> {
    /// Scenes of these kinds; `robots` for the halls.
    Scenes {
        /// The kinds.
        kinds: &'a [Kind],
        /// Robots of a hall.
        robots: Option<usize>,
    },
    /// Conflict cells of these families, for the feedback loop.
    Conflicts(&'a [ConflictKind]),
    /// Cells for `solve`.
    Cells(CellRequest),
    /// SCARA cells for `solve`.
    Scara(ScaraRequest),
}

/// Writes one file's text when called, or says why it cannot.
type Maker<'a> = Box<dyn Fn() -> Result<String, String> + 'a>;

fn fail(file: &Path, reason: String) -> InputError {
    InputError {
        file: file.to_path_buf(),
        body: None,
        field: String::new(),
        reason,
    }
}

/// Writes `DIR/<kind>-<seed>-<k>.json` for each kind and k in 0..count (conflict cells
/// `DIR/<kind>-<seed>-<k>-cell.json`, or the cells of [`cell_file_name`]), creating `out` if
/// missing, and prints one line per file. Same arguments, same bytes.
pub fn run_generate(
    what: &What,
    seed: u64,
    count: u64,
    out: &Path,
) -> Result<ExitCode, InputError> {
    let mut files: Vec<(String, Maker)> = Vec::new();
    match what {
        What::Scenes { kinds, robots } => {
            if let (Some(_), [kind]) = (robots, kinds) {
                if !matches!(kind, Kind::Hall | Kind::ArmHall) {
                    return Err(fail(
                        out,
                        format!(
                            "--robots applies only to --kind hall, arm-hall and cell, not to {}",
                            kind.name()
                        ),
                    ));
                }
            }
            for &kind in kinds.iter() {
                for k in 0..count {
                    let robots = robots.unwrap_or(10);
                    files.push((
                        scene_file_name(kind, seed, k),
                        Box::new(move || {
                            let scene = generate_scene(kind, seed, k, robots);
                            Ok(serde_json::to_string_pretty(&scene_document(&scene))
                                .expect("a scene serialises"))
                        }),
                    ));
                }
            }
        }
        What::Conflicts(kinds) => {
            for &kind in kinds.iter() {
                for k in 0..count {
                    files.push((
                        conflict_file_name(kind, seed, k),
                        Box::new(move || {
                            let doc = generate_conflict_cell(kind, seed, k);
                            Ok(serde_json::to_string_pretty(&doc).expect("a cell serialises"))
                        }),
                    ));
                }
            }
        }
        What::Scara(req) => {
            for k in 0..count {
                files.push((
                    scara_file_name(req, seed, k),
                    Box::new(move || {
                        generate_scara_cell(req, seed, k)
                            .map(|doc| serde_json::to_string_pretty(&doc).expect("serialises"))
                    }),
                ));
            }
        }
        What::Cells(req) => {
            for k in 0..count {
                files.push((
                    cell_file_name(req, seed, k),
                    Box::new(move || {
                        generate_cell(req, seed, k)
                            .map(|doc| serde_json::to_string_pretty(&doc).expect("serialises"))
                    }),
                ));
            }
        }
    }
    std::fs::create_dir_all(out)
        .map_err(|e| fail(out, format!("cannot create the output folder: {e}")))?;
    let mut stdout = std::io::stdout().lock();
    for (name, make) in files {
        let file = out.join(name);
        let text = make().map_err(|reason| fail(&file, reason))? + "\n";
        super::output::write_file(&file, text.as_bytes())?;
        // A closed pipe (`| head`) is the reader's choice, not an error of ours.
        let _ = writeln!(stdout, "{}", file.display());
    }
    Ok(ExitCode::SUCCESS)
}
