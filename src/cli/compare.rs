//! `workcell compare`: every method on every scene, against the reference.

use indicatif::{ProgressBar, ProgressDrawTarget};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use workcell::cell::{check_precision, load_scene, InputError};
use workcell::compare::{
    compare, default_contenders, validate_contenders, Comparison, Contender, NamedScene,
    REFERENCE_TIME_TOL,
};
use workcell::view::chart;

/// Compares `contenders` on the scenes in `inputs` (files, or folders whose `*.json` files
/// are read, cell files `*-cell.json` aside). Exit 0, or 2 on unusable input or a method
/// given that cannot check one of the scenes.
pub fn run_compare(
    inputs: &[PathBuf],
    contenders: &[Contender],
    svg: Option<&Path>,
    json: bool,
) -> Result<ExitCode, InputError> {
    let files = scene_files(inputs)?;
    if let Some(svg) = svg {
        let inputs: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
        super::output::check_outputs(&inputs, &[("--svg", svg)])?;
    }
    let mut scenes = Vec::with_capacity(files.len());
    for file in &files {
        let loaded = load_scene(file)?;
        check_precision(&loaded.scene, loaded.scene.delta, file)?;
        scenes.push(NamedScene {
            name: file.display().to_string(),
            scene: loaded.scene,
        });
    }
    // The defaults skip a scene they cannot check (counted unsupported); a method the user
    // named is refused.
    if contenders != default_contenders() {
        validate_contenders(&scenes, contenders)?;
    }
    let bar =
        ProgressBar::with_draw_target(Some(scenes.len() as u64), ProgressDrawTarget::stderr());
    if json || !std::io::stderr().is_terminal() {
        bar.set_draw_target(ProgressDrawTarget::hidden());
    }
    let comparison = compare(&scenes, contenders, |done| bar.set_position(done as u64));
    bar.finish_and_clear();
    if let Some(path) = svg {
        super::output::write_file(path, chart(&comparison).as_bytes())?;
    }
    let text = if json {
        serde_json::to_string_pretty(&comparison).expect("a comparison serialises") + "\n"
    } else {
        table(&comparison)
    };
    // A closed pipe (`| head`) is the reader's choice, not an error of ours.
    let _ = std::io::stdout().write_all(text.as_bytes());
    Ok(ExitCode::SUCCESS)
}

/// The files named, and the `*.json` scene files of the folders named, in name order.
fn scene_files(inputs: &[PathBuf]) -> Result<Vec<PathBuf>, InputError> {
    let mut files = Vec::new();
    for input in inputs {
        if !input.is_dir() {
            files.push(input.clone());
            continue;
        }
        let entries = std::fs::read_dir(input).map_err(|e| InputError {
            file: input.clone(),
            body: None,
            field: String::new(),
            reason: format!("cannot read the folder: {e}"),
        })?;
        let mut found: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "json"))
            .filter(|p| !p.to_string_lossy().ends_with("-cell.json"))
            .collect();
        found.sort();
        files.extend(found);
    }
    if files.is_empty() {
        return Err(InputError {
            file: inputs.first().cloned().unwrap_or_default(),
            body: None,
            field: String::new(),
            reason: "no scene files (*.json) found".into(),
        });
    }
    Ok(files)
}

fn table(c: &Comparison) -> String {
    let mut out = format!(
        "{}, {} colliding according to the reference (adaptive at a time tolerance of {REFERENCE_TIME_TOL:e} of the horizon); {}\n\n",
        super::counted(c.scenes as u64, "scene"), c.colliding, super::counted(c.threads as u64, "thread")
    );
    out += "| method | median µs per check | missed | invented | max time error |\n";
    out += "|---|---:|---:|---:|---:|\n";
    for m in &c.methods {
        let error = m.max_time_error.map_or("-".into(), |e| format!("{e:.2e}"));
        let unsupported = if m.unsupported > 0 {
            format!(
                " ({} unsupported)",
                super::counted(m.unsupported as u64, "scene")
            )
        } else {
            String::new()
        };
        out += &format!(
            "| {}{unsupported} | {:.1} | {} | {} | {error} |\n",
            m.method, m.median_us, m.missed, m.invented
        );
    }
    if !c.disagreements.is_empty() {
        out += "\nparry and the reference disagree on:\n";
        for d in &c.disagreements {
            out += &format!("- {}: {}\n", d.scene, d.what);
        }
    }
    out
}
