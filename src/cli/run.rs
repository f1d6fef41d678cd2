//! `covga run`: one experiment, with a progress bar on a terminal.

use super::CliError;
use crate::experiment::file::ExperimentFile;
use crate::experiment::output::{OutputError, run_experiment};
use crate::experiment::registry::PlannerConfig;
use crate::ga::observer::{GenerationRecord, Observer};
use std::io::IsTerminal;
use std::path::PathBuf;

/// The built-in experiment run when no file is given.
pub const DEFAULT_EXPERIMENT: &str = include_str!("../../experiments/thesis-map1-elite.toml");

/// Arguments of `covga run`.
#[derive(clap::Args, Debug)]
pub struct RunArgs {
    /// Experiment file (TOML); without it, the built-in thesis map 1 Elite experiment.
    file: Option<PathBuf>,
    /// Results folder (default: the file's [output] dir, else out/<file stem>).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Override the file's seed.
    #[arg(long)]
    seed: Option<u64>,
    /// No progress bar and no summary.
    #[arg(long)]
    quiet: bool,
    /// Memory the run may use (8G, 512M, 2GiB; default: the memory available); a run that
    /// would need more is refused before anything is allocated.
    #[arg(long, value_parser = crate::io::parse_bytes)]
    max_memory: Option<u64>,
}

/// Progress bar over iterations.
struct Progress(indicatif::ProgressBar);

impl Observer for Progress {
    fn generation(&mut self, r: &GenerationRecord) -> std::io::Result<()> {
        self.0.set_position(u64::from(r.iteration));
        if r.iteration.is_multiple_of(25) {
            self.0.set_message(format!("coverage {:.3} best {:.4}", r.best_coverage, r.best_fitness));
        }
        Ok(())
    }
}

/// Refuses a results folder that holds files of another run: a folder is this run's when it
/// is empty (but for the folder lock) or its `config.toml` is the one this run writes (the
/// same experiment run again). Another run's `best_genome.csv` or `history.png` would
/// otherwise stay beside this run's results.
fn check_results_folder(dir: &std::path::Path, file: &ExperimentFile) -> Result<(), String> {
    let entries: Vec<String> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != ".covga.lock")
        .collect();
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

pub fn run(a: RunArgs) -> Result<(), CliError> {
    let (mut file, origin, base, stem, ignored) = match &a.file {
        Some(path) => {
            let origin = path.display().to_string();
            let text = ExperimentFile::read_text(path).map_err(CliError::input)?;
            let file = ExperimentFile::parse(&text, &origin).map_err(CliError::input)?;
            let ignored = crate::experiment::ignored::ignored_in_text(&text, &file);
            // One rule for relative map paths in run and grid files: the working directory.
            // A run's config.toml, a study's runs and `covga report` re-read the same path
            // from there, wherever the file that first named it lies.
            let base = PathBuf::from(".");
            let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "run".into());
            (file, origin, base, stem, ignored)
        }
        None => {
            let origin = "built-in experiment thesis-map1-elite";
            (
                ExperimentFile::parse(DEFAULT_EXPERIMENT, origin).map_err(CliError::input)?,
                origin.to_string(),
                PathBuf::from("."),
                "thesis-map1-elite".to_string(),
                Vec::new(),
            )
        }
    };
    if let Some(seed) = a.seed {
        file.seed = seed;
    }
    let exp = file.validate(&origin, &base, &stem).map_err(CliError::input)?;
    for (key, why) in ignored {
        eprintln!("warning: {origin}: `{key}` is ignored: {why}");
    }
    exp.check_memory(&origin, crate::experiment::memory::memory_limit(a.max_memory), 1, rayon::current_num_threads())
        .map_err(CliError::input)?;
    let dir = a.out.clone().unwrap_or_else(|| exp.output_dir.clone());
    let existed = dir.exists();
    let lock_existed = dir.join(".covga.lock").exists();
    std::fs::create_dir_all(&dir)
        .map_err(|e| CliError::Input(format!("{}: cannot create the results folder: {e}", dir.display())))?;
    // A refused run leaves nothing behind that it made itself: its lock file, and the folder
    // while still empty.
    let discard_folder = || {
        if !lock_existed {
            let _ = std::fs::remove_file(dir.join(".covga.lock"));
        }
        if !existed {
            let _ = std::fs::remove_dir(&dir);
        }
    };
    let _lock = crate::io::FolderLock::take(&dir, true).map_err(|m| {
        if !existed {
            let _ = std::fs::remove_dir(&dir);
        }
        CliError::Input(m)
    })?;
    check_results_folder(&dir, &exp.file).map_err(|m| {
        discard_folder();
        CliError::Input(m)
    })?;
    let show = !a.quiet && std::io::stderr().is_terminal();
    let length = exp.planner.progress_length(&exp.budget);
    let mut progress = Progress(super::progress_bar(length, "it", show));
    let summary = run_experiment(&exp, &dir, true, &mut [&mut progress]).map_err(|e| {
        discard_folder();
        match e {
            OutputError::Planner(m) => CliError::Input(format!("{origin}: {m}")),
            other => CliError::internal(other),
        }
    })?;
    progress.0.finish_and_clear();
    for w in &summary.warnings {
        eprintln!("warning: {origin}: {w}");
    }
    if !a.quiet {
        let s = &summary.score;
        println!(
            "{origin}: {} on {}, seed {}, {} iterations, {} evaluations, {:.2} s",
            summary.planner, summary.map, summary.seed, summary.iterations, summary.evaluations, summary.wall_s
        );
        let own: Vec<String> = summary.objectives.iter().map(|(k, v)| format!("{k} {v:.4}")).collect();
        println!("planner's objectives: {}", own.join("  "));
        if let Some(f) = &summary.fleet {
            if let Some(n) = crate::fleet::details::FleetDetails::read(&summary.details).negotiation {
                println!("negotiation: {} rounds, {}", n.rounds, if n.converged { "settled" } else { "budget ended" });
            }
            println!(
                "fleet of {} ({}): union {:.4} of free ({:.4} of reachable), overlap {:.4}, makespan {:.0} s, balance {}, cov_final {:.4}, t_final {:.4}",
                f.robots.len(),
                f.robots.join(", "),
                f.union_free,
                f.union_reach,
                f.overlap_fraction,
                f.makespan_s,
                f.balance.map_or("-".into(), |b| format!("{b:.2}")),
                f.cov_final,
                f.t_final
            );
        }
        if !matches!(exp.planner, PlannerConfig::Fleet(_)) {
            println!(
                "common score: cov_final {:.4} (reachable {:.4})  t_final {:.4}  camera walls {:.4}  length {:.1} m  time {:.0} s",
                s.cov_final_free, s.cov_final_reach, s.t_final, s.cam_walls_free, s.length_m, s.time_s
            );
        }
        if s.executable {
            println!("executable: yes");
        } else {
            println!("executable: NO ({})", super::eval::not_executable_why(s));
        }
        if summary.planner_feasible {
            println!("planner constraints: met");
        } else {
            println!("planner constraints: NOT met ({})", summary.violations.join("; "));
        }
        println!("wrote {}", dir.display());
    }
    Ok(())
}
