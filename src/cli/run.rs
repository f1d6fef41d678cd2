//! `covga run`: one experiment, with a progress bar on a terminal.

use super::CliError;
use crate::ga::observer::{GenerationStats, Observer};
use crate::study::experiment::ExperimentFile;
use crate::study::output::run_experiment;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

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
}

/// Progress bar over iterations.
struct Progress(indicatif::ProgressBar);

impl Observer for Progress {
    fn generation(&mut self, s: &GenerationStats) -> std::io::Result<()> {
        self.0.set_position(u64::from(s.iteration));
        if s.iteration.is_multiple_of(25) {
            self.0.set_message(format!("cov {:.3} t {:.3} f {:.4}", s.best_cov_final, s.best_t_final, s.best_fitness));
        }
        Ok(())
    }
}

pub fn run(a: RunArgs) -> Result<(), CliError> {
    let (mut file, origin, base, stem) = match &a.file {
        Some(path) => {
            let file = ExperimentFile::read(path).map_err(CliError::input)?;
            let base = path.parent().unwrap_or(Path::new(".")).to_path_buf();
            let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "run".into());
            (file, path.display().to_string(), base, stem)
        }
        None => {
            let origin = "built-in experiment thesis-map1-elite";
            (
                ExperimentFile::parse(DEFAULT_EXPERIMENT, origin).map_err(CliError::input)?,
                origin.to_string(),
                PathBuf::from("."),
                "thesis-map1-elite".to_string(),
            )
        }
    };
    if let Some(seed) = a.seed {
        file.seed = seed;
    }
    let exp = file.validate(&origin, &base, &stem).map_err(CliError::input)?;
    let dir = a.out.clone().unwrap_or_else(|| exp.output_dir.clone());
    let show = !a.quiet && std::io::stderr().is_terminal();
    let bar = super::progress_bar(u64::from(exp.budget.iterations), "it", show);
    if exp.waypoint.is_some() {
        bar.set_length(u64::from(exp.file.waypoint.generations));
        let summary = crate::study::waypoint_output::run_waypoint(&exp, &dir, &mut |s| {
            bar.set_position(u64::from(s.generation));
            bar.set_message(format!("C {:.3} walls {:.3} feasible {}", s.max_coverage, s.mean_walls, s.feasible));
        })
        .map_err(CliError::internal)?;
        bar.finish_and_clear();
        if !a.quiet {
            println!(
                "{origin}: seed {}, {} agent(s), {} generations, {} waypoints, {:.2} s (precompute {:.2} s)",
                summary.seed,
                summary.agents,
                summary.generations,
                summary.waypoints,
                summary.wall_s,
                summary.precompute_s
            );
            println!(
                "best: wall coverage {:.4}  open {:.4}  flight time {:.0}  loop closures ok {}  connected {}",
                summary.wall_coverage,
                summary.open_coverage,
                summary.flight_time,
                summary.loop_closures_ok,
                summary.connected
            );
            println!("wrote {}", dir.display());
        }
        return Ok(());
    }
    let mut progress = Progress(bar);
    let (_, summary) = run_experiment(&exp, &dir, true, &mut [&mut progress]).map_err(CliError::internal)?;
    progress.0.finish_and_clear();
    if !a.quiet {
        println!(
            "{origin}: seed {}, {} iterations, {} evaluations, {:.2} s",
            summary.seed, summary.iterations, summary.evaluations, summary.wall_s
        );
        println!(
            "best: cov_final {:.4}  t_final {:.4}  f_obstacle {:.4}  G_len {}",
            summary.cov_final, summary.t_final, summary.fitness, summary.genome_len
        );
        println!("wrote {}", dir.display());
    }
    Ok(())
}
