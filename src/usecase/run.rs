//! Running one experiment into its results folder: read and validate the experiment (the
//! ignored keys as warnings, the seed overridden, the memory checked before anything is
//! allocated), then run it into a folder that holds no other run's files, under the folder's
//! lock, leaving nothing behind that it made itself when it is refused or interrupted.

use super::UseCaseError;
use crate::experiment::file::{Experiment, ExperimentFile};
use crate::experiment::output::{OutputError, Summary, run_experiment};
use crate::ga::observer::Observer;
use std::path::{Path, PathBuf};

/// An experiment's text and where it came from.
#[derive(Clone, Debug)]
pub struct ExperimentText {
    /// The TOML text.
    pub text: String,
    /// How messages name it (the file's path, "experiment text", …).
    pub origin: String,
    /// The default results folder's name (`out/<stem>`).
    pub stem: String,
}

impl ExperimentText {
    /// The experiment file at `path` (bounded in size).
    pub fn read(path: &Path) -> Result<Self, UseCaseError> {
        let text = ExperimentFile::read_text(path).map_err(UseCaseError::input)?;
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "run".into());
        Ok(Self { text, origin: path.display().to_string(), stem })
    }
}

/// A validated experiment ready to run, with the warnings about its file.
pub struct Prepared {
    /// The experiment.
    pub experiment: Experiment,
    /// How messages name its file.
    pub origin: String,
    /// Warnings in words, each naming the file (keys the planner does not read).
    pub warnings: Vec<String>,
}

/// Parses and validates `source`, with `seed` in place of the file's when given, and checks
/// that one run fits in `max_memory` (default: the memory available). Relative map paths are
/// read from the working directory, whichever folder the file lies in: a run's `config.toml`,
/// a study's runs and `covga report` re-read the same path from there.
pub fn prepare(source: &ExperimentText, seed: Option<u64>, max_memory: Option<u64>) -> Result<Prepared, UseCaseError> {
    let origin = &source.origin;
    let mut file = ExperimentFile::parse(&source.text, origin).map_err(UseCaseError::input)?;
    // A run's own `config.toml` spells out every key with its default, read or not: run again,
    // it is not the user's choice of keys, and warning about each would bury the rest.
    let written_by_covga = toml::to_string_pretty(&file).is_ok_and(|t| t == source.text);
    let ignored =
        if written_by_covga { Vec::new() } else { crate::experiment::ignored::ignored_in_text(&source.text, &file) };
    if let Some(seed) = seed {
        file.seed = seed;
    }
    let renamed = crate::experiment::renamed::renamed_in_text(&source.text);
    let experiment = file.validate(origin, &PathBuf::from("."), &source.stem).map_err(|mut e| {
        // A renamed key is checked under its new name: say how this file spells it.
        if let Some((old, _)) = renamed.iter().find(|(_, new)| *new == e.key) {
            e.message.push_str(&format!(" (this file spells it `{old}`, its name before the move)"));
        }
        UseCaseError::input(e)
    })?;
    let limit = crate::experiment::memory::memory_limit(max_memory);
    experiment.check_memory(origin, limit.as_ref(), 1, rayon::current_num_threads()).map_err(UseCaseError::input)?;
    let values = crate::experiment::renamed::renamed_values_in_text(&source.text);
    let warnings = renamed
        .into_iter()
        .chain(values)
        .map(|(old, new)| crate::experiment::renamed::warning(origin, old, new))
        .chain(ignored.into_iter().map(|(key, why)| format!("{origin}: `{key}` is ignored: {why}")))
        .collect();
    Ok(Prepared { experiment, origin: origin.clone(), warnings })
}

/// Refuses a results folder that holds files of another run: a folder is this run's when it
/// is empty (but for the folder lock) or its `config.toml` is the one this run writes (the
/// same experiment run again). Another run's `best_genome.csv` or `history.png` would
/// otherwise stay beside this run's results.
fn check_results_folder(dir: &Path, file: &ExperimentFile) -> Result<(), String> {
    let entries: Vec<String> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != ".covga.lock")
        .collect();
    // A run killed where it could not clean up (SIGKILL, a power cut) leaves its temporary
    // files: they are covga's own, never results, and the folder is locked now, so no other
    // process is writing them. Removed, they do not make the folder another run's.
    let (leftovers, entries): (Vec<String>, Vec<String>) = entries.into_iter().partition(|n| is_leftover_temporary(n));
    for n in &leftovers {
        let _ = std::fs::remove_file(dir.join(n));
    }
    if entries.is_empty() {
        return Ok(());
    }
    let ours = toml::to_string_pretty(file).expect("experiment files serialise");
    if std::fs::read_to_string(dir.join("config.toml")).is_ok_and(|t| t == ours) {
        return Ok(());
    }
    let mut shown = entries.clone();
    shown.sort();
    shown.truncate(4);
    Err(format!(
        "{}: holds files of another run ({}{}): choose an empty folder with --out, or remove them",
        dir.display(),
        shown.join(", "),
        if entries.len() > shown.len() { ", …" } else { "" }
    ))
}

/// Whether `name` is a temporary file a covga run writes before renaming it into place: the
/// history while the run goes on, or an atomic write's sibling (`.NAME.tmpPID`).
fn is_leftover_temporary(name: &str) -> bool {
    name == crate::experiment::output::PARTIAL_HISTORY
        || name
            .strip_prefix('.')
            .and_then(|n| n.rsplit_once(".tmp"))
            .is_some_and(|(stem, pid)| !stem.is_empty() && !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()))
}

/// Runs `prepared` into `dir` (default: the experiment's own folder), with figures when
/// `figures`, handing each generation to `observers` too. The folder is made if missing and
/// locked while the run writes it; a folder with another run's files is refused. A refused,
/// failed or interrupted run removes its lock file and the folder when it made them.
pub fn run_in_folder(
    prepared: &Prepared,
    dir: Option<&Path>,
    figures: bool,
    observers: &mut [&mut dyn Observer],
) -> Result<(Summary, PathBuf), UseCaseError> {
    let exp = &prepared.experiment;
    let dir = dir.map_or_else(|| exp.output_dir.clone(), Path::to_path_buf);
    let existed = dir.exists();
    let lock_existed = dir.join(".covga.lock").exists();
    std::fs::create_dir_all(&dir)
        .map_err(|e| UseCaseError::Input(format!("{}: cannot create the results folder: {e}", dir.display())))?;
    let discard_folder = || {
        if !lock_existed {
            let _ = std::fs::remove_file(dir.join(".covga.lock"));
        }
        if !existed {
            let _ = std::fs::remove_dir(&dir);
        }
    };
    let lock = crate::io::FolderLock::take(&dir, true).map_err(|m| {
        if !existed {
            let _ = std::fs::remove_dir(&dir);
        }
        UseCaseError::Input(m)
    })?;
    check_results_folder(&dir, &exp.file).map_err(|m| {
        discard_folder();
        UseCaseError::Input(m)
    })?;
    let outcome = run_experiment(exp, &dir, figures, observers);
    drop(lock);
    let summary = outcome.map_err(|e| {
        discard_folder();
        match e {
            OutputError::Planner(m) => UseCaseError::Input(format!("{}: {m}", prepared.origin)),
            OutputError::Interrupted { .. } => UseCaseError::Interrupted(format!("{}: {e}", prepared.origin)),
            other => UseCaseError::internal(other),
        }
    })?;
    Ok((summary, dir))
}
