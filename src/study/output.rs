//! Running one experiment and writing its results folder: `config.toml`, `history.csv`
//! (streamed), `best_path.csv`, `best_genome.csv`, `summary.json`, `path.png/.svg`,
//! `history.png/.svg` (and `path_before_retrain.png/.svg` after a retrain). Every file is
//! written to a temporary name and renamed when complete.

use super::experiment::Experiment;
use crate::ga::observer::{GenerationStats, Observer, Recorder};
use crate::plot::history::HistoryFigure;
use crate::plot::path::PathFigure;
use crate::thesis::individual::{Individual, Scenario};
use crate::thesis::run::{RunOutcome, ThesisGa};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Failure while running or writing results.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// A results file could not be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A figure could not be drawn.
    #[error(transparent)]
    Plot(#[from] crate::plot::PlotError),
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io { path: path.to_path_buf(), source }
}

/// Column names of `history.csv`.
pub const HISTORY_HEADER: &str = "iteration,evaluations,best_fitness,best_cov_final,best_t_final,mean_cov_final,min_cov_final,max_cov_final,mean_t_final,min_t_final,max_t_final,mean_fitness,mean_genome_len,min_genome_len,max_genome_len,diversity,p_c,p_ma,sp,population";

/// One `history.csv` row.
pub fn history_row(s: &GenerationStats) -> String {
    format!(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
        s.iteration,
        s.evaluations,
        s.best_fitness,
        s.best_cov_final,
        s.best_t_final,
        s.mean_cov_final,
        s.min_cov_final,
        s.max_cov_final,
        s.mean_t_final,
        s.min_t_final,
        s.max_t_final,
        s.mean_fitness,
        s.mean_genome_len,
        s.min_genome_len,
        s.max_genome_len,
        s.diversity,
        s.p_c,
        s.p_ma,
        s.sp,
        s.population
    )
}

/// Streams `history.csv` row by row into a temporary file, renamed by [`HistoryCsv::finish`].
pub struct HistoryCsv {
    tmp: PathBuf,
    path: PathBuf,
    out: std::io::BufWriter<std::fs::File>,
}

impl HistoryCsv {
    /// Opens `<dir>/history.csv` (as a temporary file until finished).
    pub fn create(dir: &Path) -> std::io::Result<Self> {
        let path = dir.join("history.csv");
        let tmp = dir.join(".history.csv.partial");
        let mut out = std::io::BufWriter::new(std::fs::File::create(&tmp)?);
        writeln!(out, "{HISTORY_HEADER}")?;
        Ok(Self { tmp, path, out })
    }
    /// Flushes, syncs and renames into place.
    pub fn finish(mut self) -> std::io::Result<()> {
        self.out.flush()?;
        self.out.get_ref().sync_all()?;
        std::fs::rename(&self.tmp, &self.path)
    }
}

impl Observer for HistoryCsv {
    fn generation(&mut self, stats: &GenerationStats) -> std::io::Result<()> {
        writeln!(self.out, "{}", history_row(stats))
    }
}

/// `best_genome.csv`: one row per action with its role, move and viewpoint.
pub fn genome_csv(ind: &Individual) -> Vec<u8> {
    let n = ind.genome.len();
    let mut s = String::from("index,role,alpha_deg,dist_m,x_m,y_m\n");
    for (i, (a, p)) in ind.genome.iter().zip(&ind.points).enumerate() {
        let role = match i {
            0 => "start",
            _ if i == n - 1 => "end",
            _ if i == n - 2 => "connector",
            _ => "action",
        };
        s.push_str(&format!("{i},{role},{},{},{},{}\n", a.alpha_deg, a.dist_m, p.x, p.y));
    }
    s.into_bytes()
}

/// What a finished run reports.
#[derive(serde::Serialize)]
pub struct Summary {
    /// Best individual's `cov_final`.
    pub cov_final: f64,
    /// Best individual's `t_final`.
    pub t_final: f64,
    /// Best individual's `f_obstacle`.
    pub fitness: f64,
    /// `f1` of the best individual.
    pub f1: f64,
    /// `f2` of the best individual.
    pub f2: f64,
    /// Evaluations spent.
    pub evaluations: u64,
    /// Iterations completed.
    pub iterations: u32,
    /// The seed.
    pub seed: u64,
    /// Why the run stopped.
    pub stop: crate::thesis::run::StopReason,
    /// Genome length of the best individual.
    pub genome_len: usize,
    /// Footprint metrics of the best path.
    pub metrics: crate::coverage::PathMetrics,
    /// Best before the environment changed, if it did: `[cov_final, t_final, fitness]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub before_retrain: Option<[f64; 3]>,
    /// Wall time in seconds (the only field that differs between identical runs).
    pub wall_s: f64,
}

/// Runs the experiment, streaming history to `dir`, and writes every result file; `figures`
/// adds the PNG/SVG pictures (studies leave them out: one picture costs more than a run).
pub fn run_experiment(
    exp: &Experiment,
    dir: &Path,
    figures: bool,
    extra: &mut [&mut dyn Observer],
) -> Result<(RunOutcome, Summary), OutputError> {
    std::fs::create_dir_all(dir).map_err(io_err(dir))?;
    let config = toml::to_string_pretty(&exp.file).expect("experiment files serialise");
    crate::io::write_atomic(&dir.join("config.toml"), config.as_bytes()).map_err(io_err(dir))?;
    let scenario = Scenario::new(exp.map.clone(), exp.robot, exp.start, exp.end, exp.projection);
    let mut ga = ThesisGa { scenario, params: exp.params, seed: exp.file.seed };
    let mut history = HistoryCsv::create(dir).map_err(io_err(dir))?;
    let mut recorder = Recorder::default();
    let outcome = {
        let mut observers: Vec<&mut dyn Observer> = vec![&mut history];
        if figures {
            observers.push(&mut recorder);
        }
        observers.extend(extra.iter_mut().map(|o| &mut **o as &mut dyn Observer));
        ga.run(&exp.budget, exp.retrain.as_ref(), &mut observers).map_err(io_err(dir))?
    };
    history.finish().map_err(io_err(dir))?;
    let best = &outcome.best;
    let write = |name: &str, bytes: &[u8]| crate::io::write_atomic(&dir.join(name), bytes).map_err(io_err(dir));
    write("best_path.csv", &crate::io::path_csv(std::slice::from_ref(&best.points)))?;
    write("best_genome.csv", &genome_csv(best))?;
    let summary = Summary {
        cov_final: best.score.cov_final,
        t_final: best.score.t_final,
        fitness: best.score.fitness,
        f1: best.score.f1,
        f2: best.score.f2,
        evaluations: outcome.evaluations,
        iterations: outcome.iterations,
        seed: exp.file.seed,
        stop: outcome.stop,
        genome_len: best.len(),
        metrics: best.metrics,
        before_retrain: outcome
            .best_before_retrain
            .as_ref()
            .map(|b| [b.score.cov_final, b.score.t_final, b.score.fitness]),
        wall_s: outcome.wall_s,
    };
    write("summary.json", serde_json::to_string_pretty(&summary).expect("summary serialises").as_bytes())?;
    if !figures {
        return Ok((outcome, summary));
    }
    let title = |ind: &Individual, what: &str| {
        format!(
            "{what} on {}: cov_final {:.3}, t_final {:.3}, G_len {}",
            exp.map.name(),
            ind.score.cov_final,
            ind.score.t_final,
            ind.len()
        )
    };
    let figure = PathFigure {
        map: &exp.map,
        grid: &ga.scenario.grid,
        paths: vec![best.points.clone()],
        width: exp.robot.width,
        title: title(best, "best path"),
    };
    crate::plot::save(&figure, &dir.join("path"))?;
    if let Some(before) = &outcome.best_before_retrain {
        let plain = crate::coverage::CoverageGrid::new(&exp.map);
        let figure = PathFigure {
            grid: &plain,
            paths: vec![before.points.clone()],
            title: title(before, "best before retrain"),
            ..figure
        };
        crate::plot::save(&figure, &dir.join("path_before_retrain"))?;
    }
    let changes: Vec<u32> = recorder.changes.clone();
    let hist = HistoryFigure {
        history: &recorder.history,
        changes: &changes,
        title: format!("{} on {}, seed {}", exp.params.selection.name(), exp.map.name(), exp.file.seed),
    };
    crate::plot::save(&hist, &dir.join("history"))?;
    Ok((outcome, summary))
}
