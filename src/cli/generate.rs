//! `workcell generate`: write deterministic random scenes or cells of one kind.

use std::io::Write;
use std::path::Path;
use std::process::ExitCode;
use workcell::cell::{scene_document, InputError};
use workcell::generate::{
    conflict_file_name, generate_conflict_cell, generate_scene, scene_file_name, ConflictKind, Kind,
};

/// What `--kind` names: a family of scenes or of cells.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// Scenes for `check`.
    Scene(Kind),
    /// Conflict cells for `solve`.
    Conflict(ConflictKind),
}

impl Family {
    /// The families a `--kind` value names: one, `all` (every scene family) or `conflict`
    /// (every conflict family).
    pub fn parse(name: &str) -> Option<Vec<Family>> {
        match name {
            "all" => Some(Kind::ALL.map(Family::Scene).to_vec()),
            "conflict" => Some(ConflictKind::ALL.map(Family::Conflict).to_vec()),
            _ => Kind::from_name(name)
                .map(Family::Scene)
                .or(ConflictKind::from_name(name).map(Family::Conflict))
                .map(|f| vec![f]),
        }
    }

    /// Every accepted `--kind` value.
    pub fn names() -> Vec<&'static str> {
        let scenes = Kind::ALL.map(Kind::name).into_iter().chain(["all"]);
        let cells = ConflictKind::ALL.map(ConflictKind::name);
        scenes.chain(cells).chain(["conflict"]).collect()
    }
}

/// Writes `DIR/<kind>-<seed>-<k>.json` (scenes) or `DIR/<kind>-<seed>-<k>-cell.json`
/// (cells) for each family and k in 0..count, creating `out` if missing, and prints one line
/// per file. Same arguments, same bytes.
pub fn run_generate(
    families: &[Family],
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
    if let (Some(_), [family]) = (robots, families) {
        if *family != Family::Scene(Kind::Hall) {
            return Err(fail(
                out,
                format!(
                    "--robots applies only to --kind hall, not to {}",
                    family.name()
                ),
            ));
        }
    }
    std::fs::create_dir_all(out)
        .map_err(|e| fail(out, format!("cannot create the output folder: {e}")))?;
    let mut stdout = std::io::stdout().lock();
    for (&family, k) in families
        .iter()
        .flat_map(|family| (0..count).map(move |k| (family, k)))
    {
        let (doc, name) = match family {
            Family::Scene(kind) => (
                scene_document(&generate_scene(kind, seed, k, robots.unwrap_or(10))),
                scene_file_name(kind, seed, k),
            ),
            Family::Conflict(kind) => (
                generate_conflict_cell(kind, seed, k),
                conflict_file_name(kind, seed, k),
            ),
        };
        let text = serde_json::to_string_pretty(&doc).expect("a document serialises") + "\n";
        let file = out.join(name);
        super::output::write_file(&file, text.as_bytes())?;
        // A closed pipe (`| head`) is the reader's choice, not an error of ours.
        let _ = writeln!(stdout, "{}", file.display());
    }
    Ok(ExitCode::SUCCESS)
}

impl Family {
    fn name(self) -> &'static str {
        match self {
            Family::Scene(k) => k.name(),
            Family::Conflict(k) => k.name(),
        }
    }
}
