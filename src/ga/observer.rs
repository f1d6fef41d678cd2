//! Per-generation records and the observers that receive them (history writer, progress
//! bar, …). Every planner hands the same planner-neutral [`GenerationRecord`] (with named
//! extras of its own) to observers; algorithm code never prints.

use serde::Serialize;

/// One generation of any planner: planner-neutral columns, then the planner's named extras.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GenerationRecord {
    /// Iteration (generation) number; 0 is the initial population.
    pub iteration: u32,
    /// Fitness evaluations so far.
    pub evaluations: u64,
    /// The planner's own scalar objective of its currently reported plan (higher is better).
    pub best_fitness: f64,
    /// Its population mean.
    pub mean_fitness: f64,
    /// Footprint coverage (`cov_final` over the scenario's free cells) of the reported plan.
    pub best_coverage: f64,
    /// Footprint coverage of the reachable cells (the common scorer's `cov_final_reach`: cells
    /// the robot's footprint can sweep from the start) of the reported plan, for planners that
    /// measure it.
    pub best_coverage_reach: Option<f64>,
    /// Members meeting every constraint, for planners with constraints.
    pub feasible: Option<u32>,
    /// Population diversity, for planners that measure it.
    pub diversity: Option<f64>,
    /// Planner-specific columns, the same names in every record of a run.
    pub extras: Vec<(&'static str, f64)>,
    /// The reported plan's robots, for planners of fleets (empty otherwise).
    pub robots: Vec<RobotRecord>,
}

/// One robot of a fleet's reported plan in a generation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RobotRecord {
    /// Its genome length.
    pub genome_len: u32,
    /// Distinct countable cells it sweeps.
    pub swept_cells: u64,
    /// Its time as the fitness reads it: 003 eq. 3.12 over its swept area, plus rotation.
    pub t_actual_s: f64,
}

/// Column names of the planner-neutral part of a [`GenerationRecord`].
pub const NEUTRAL_COLUMNS: [&str; 8] = [
    "iteration",
    "evaluations",
    "best_fitness",
    "mean_fitness",
    "best_coverage",
    "best_coverage_reach",
    "feasible",
    "diversity",
];

impl GenerationRecord {
    /// The CSV header for records with these extras.
    pub fn header(&self) -> String {
        NEUTRAL_COLUMNS.iter().copied().chain(self.extras.iter().map(|(k, _)| *k)).collect::<Vec<_>>().join(",")
    }
    /// The record as one CSV line (without newline); absent optional values are empty cells.
    pub fn csv_row(&self) -> String {
        let opt = |v: Option<String>| v.unwrap_or_default();
        let mut cells = vec![
            self.iteration.to_string(),
            self.evaluations.to_string(),
            self.best_fitness.to_string(),
            self.mean_fitness.to_string(),
            self.best_coverage.to_string(),
            opt(self.best_coverage_reach.map(|c| c.to_string())),
            opt(self.feasible.map(|f| f.to_string())),
            opt(self.diversity.map(|d| d.to_string())),
        ];
        cells.extend(self.extras.iter().map(|(_, v)| v.to_string()));
        cells.join(",")
    }
    /// An extra column's value.
    pub fn extra(&self, name: &str) -> Option<f64> {
        self.extras.iter().find(|(k, _)| *k == name).map(|(_, v)| *v)
    }
}

/// The statistics of one generation of the thesis GA (003 §4.1.2, spec §17).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct GenerationStats {
    /// Iteration number (0 = the initial population).
    pub iteration: u32,
    /// Evaluations so far.
    pub evaluations: u64,
    /// Best individual's `f_obstacle`.
    pub best_fitness: f64,
    /// Best individual's `cov_final`.
    pub best_cov_final: f64,
    /// Best individual's `t_final`.
    pub best_t_final: f64,
    /// Population mean `cov_final`.
    pub mean_cov_final: f64,
    /// Population minimum `cov_final`.
    pub min_cov_final: f64,
    /// Population maximum `cov_final`.
    pub max_cov_final: f64,
    /// Population mean `t_final`.
    pub mean_t_final: f64,
    /// Population minimum `t_final`.
    pub min_t_final: f64,
    /// Population maximum `t_final`.
    pub max_t_final: f64,
    /// Population mean `f_obstacle`.
    pub mean_fitness: f64,
    /// Mean genome length `G_len`.
    pub mean_genome_len: f64,
    /// Shortest genome.
    pub min_genome_len: u32,
    /// Longest genome.
    pub max_genome_len: u32,
    /// Population diversity `Div` (spec §5), when it was measured (see
    /// [`Observer::diversity_every`]).
    pub diversity: Option<f64>,
    /// Effective crossover probability `P_c`.
    pub p_c: f64,
    /// Effective action-mutation probability `P_mA` (mean over individuals when adaptive).
    pub p_ma: f64,
    /// Effective selection pressure `SP` (RRWS) or tournament size `TS` (0 when unused).
    pub sp: f64,
    /// Population size.
    pub population: u32,
    /// Members whose plans sweep no obstacle cell (003's constraint `obj_pix` = 0).
    pub feasible: u32,
    /// Hypervolume of the population's plans without obstacle sweeps over
    /// (`cov_final`, `t_final`) from (0, 0), for Pareto selection (NSGA-II) only.
    pub hypervolume: Option<f64>,
}

/// Events of a run other than a finished generation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RunEvent {
    /// The environment changed before this iteration (retrain, 003 §3.5.3).
    EnvironmentChanged {
        /// First iteration on the changed map.
        iteration: u32,
    },
}

impl GenerationStats {
    /// The planner-neutral record, the thesis's own statistics as extras.
    pub fn record(&self) -> GenerationRecord {
        let mut r = GenerationRecord {
            iteration: self.iteration,
            evaluations: self.evaluations,
            best_fitness: self.best_fitness,
            mean_fitness: self.mean_fitness,
            best_coverage: self.best_cov_final,
            best_coverage_reach: None,
            feasible: Some(self.feasible),
            diversity: self.diversity,
            robots: Vec::new(),
            extras: vec![
                ("best_cov_final", self.best_cov_final),
                ("best_t_final", self.best_t_final),
                ("mean_cov_final", self.mean_cov_final),
                ("min_cov_final", self.min_cov_final),
                ("max_cov_final", self.max_cov_final),
                ("mean_t_final", self.mean_t_final),
                ("min_t_final", self.min_t_final),
                ("max_t_final", self.max_t_final),
                ("mean_genome_len", self.mean_genome_len),
                ("min_genome_len", f64::from(self.min_genome_len)),
                ("max_genome_len", f64::from(self.max_genome_len)),
                ("p_c", self.p_c),
                ("p_ma", self.p_ma),
                ("sp", self.sp),
                ("population", f64::from(self.population)),
            ],
        };
        if let Some(h) = self.hypervolume {
            r.extras.push(("hypervolume", h));
        }
        r
    }
}

/// Receives records during a run.
pub trait Observer {
    /// Called after the initial population (iteration 0) and after every iteration.
    fn generation(&mut self, record: &GenerationRecord) -> std::io::Result<()>;
    /// Called on other run events.
    fn event(&mut self, _event: RunEvent) -> std::io::Result<()> {
        Ok(())
    }
    /// Every how many iterations this observer reads the population diversity (iteration 0
    /// included), or `None` when it never does. Measuring it costs a pass over every visit
    /// map, so planners measure it only when someone reads it (or their own parameter
    /// control does).
    fn diversity_every(&self) -> Option<u32> {
        None
    }
}

/// Keeps every generation's record in memory (for figures and tests).
#[derive(Default, Debug)]
pub struct Recorder {
    /// The records, in order.
    pub history: Vec<GenerationRecord>,
    /// Iterations at which the environment changed.
    pub changes: Vec<u32>,
}

impl Observer for Recorder {
    fn generation(&mut self, record: &GenerationRecord) -> std::io::Result<()> {
        self.history.push(record.clone());
        Ok(())
    }
    fn diversity_every(&self) -> Option<u32> {
        Some(1)
    }
    fn event(&mut self, event: RunEvent) -> std::io::Result<()> {
        let RunEvent::EnvironmentChanged { iteration } = event;
        self.changes.push(iteration);
        Ok(())
    }
}
