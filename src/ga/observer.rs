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

/// The statistics of one generation of the thesis GA (003 §4.1.2, thesis-ga §17).
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
    /// Population diversity `Div` (thesis-ga §5), when it was measured (see
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

/// Which records an observer is handed (argmin's observer modes). Events
/// ([`Observer::event`]) reach every observer whatever its mode.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ObserverMode {
    /// Every record: the initial population's and each iteration's.
    #[default]
    Always,
    /// The records of iterations that are multiples of `n` (0, `n`, `2n`, …; `n` ≥ 1).
    Every(u32),
    /// The initial population's record and those of iterations that made the best better (as
    /// the planner's search says, the same judgement the stall limit reads).
    NewBest,
}

impl ObserverMode {
    /// Whether an observer in this mode takes the record of `iteration`, which made the best
    /// better or not (`improved`; the initial population's counts as better).
    pub fn takes(self, iteration: u32, improved: bool) -> bool {
        match self {
            Self::Always => true,
            Self::Every(n) => iteration.is_multiple_of(n.max(1)),
            Self::NewBest => iteration == 0 || improved,
        }
    }
}

/// Receives records during a run.
pub trait Observer {
    /// Called after the initial population (iteration 0) and after every iteration, as
    /// [`Self::mode`] says.
    fn generation(&mut self, record: &GenerationRecord) -> std::io::Result<()>;
    /// Which records this observer takes ([`ObserverMode::Always`] unless it says otherwise).
    fn mode(&self) -> ObserverMode {
        ObserverMode::Always
    }
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

/// Keeps the records of its mode in memory (every one by default; for figures and tests).
#[derive(Default, Debug)]
pub struct Recorder {
    /// The records, in order.
    pub history: Vec<GenerationRecord>,
    /// Iterations at which the environment changed.
    pub changes: Vec<u32>,
    /// Which records it keeps.
    pub mode: ObserverMode,
}

impl Observer for Recorder {
    fn generation(&mut self, record: &GenerationRecord) -> std::io::Result<()> {
        self.history.push(record.clone());
        Ok(())
    }
    fn mode(&self) -> ObserverMode {
        self.mode
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

/// The observers of one run, as a search and the executor hand them records: each record to
/// the observers whose mode takes it, each event to all. The executor tells it whether the
/// last iteration made the best better ([`Self::set_improved`]); a search asks
/// [`Self::wants`] before it builds a record that costs something to make.
pub struct Observers<'a, 'o> {
    list: &'a mut [&'o mut dyn Observer],
    improved: bool,
}

impl<'a, 'o> Observers<'a, 'o> {
    /// The observers of `list`.
    pub fn new(list: &'a mut [&'o mut dyn Observer]) -> Self {
        Self { list, improved: true }
    }
    /// No observer: records are never built.
    pub fn none() -> Observers<'static, 'static> {
        Observers { list: &mut [], improved: true }
    }
    /// Whether there is no observer at all.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }
    /// Whether the iteration about to be reported made the best better (the executor's call).
    pub fn set_improved(&mut self, improved: bool) {
        self.improved = improved;
    }
    /// Whether some observer takes the record of `iteration`.
    pub fn wants(&self, iteration: u32) -> bool {
        self.list.iter().any(|o| o.mode().takes(iteration, self.improved))
    }
    /// Whether some observer that may take the record of `iteration` reads its diversity then.
    /// Asked before the iteration runs, so whether it makes the best better is not known yet:
    /// a [`ObserverMode::NewBest`] observer may take it.
    pub fn wants_diversity(&self, iteration: u32) -> bool {
        self.list.iter().any(|o| {
            o.mode().takes(iteration, true) && o.diversity_every().is_some_and(|e| iteration.is_multiple_of(e.max(1)))
        })
    }
    /// Hands `record` to each observer whose mode takes it.
    pub fn generation(&mut self, record: &GenerationRecord) -> std::io::Result<()> {
        let improved = self.improved;
        for o in self.list.iter_mut().filter(|o| o.mode().takes(record.iteration, improved)) {
            o.generation(record)?;
        }
        Ok(())
    }
    /// Hands `event` to every observer.
    pub fn event(&mut self, event: RunEvent) -> std::io::Result<()> {
        self.list.iter_mut().try_for_each(|o| o.event(event))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_mode_takes_the_records_it_says() {
        // (mode, (iteration, improved) of the records offered, iterations taken)
        let offered = [(0, true), (1, false), (2, true), (3, false), (4, false), (5, true), (6, false)];
        let cases: [(ObserverMode, &[u32]); 4] = [
            (ObserverMode::Always, &[0, 1, 2, 3, 4, 5, 6]),
            (ObserverMode::Every(3), &[0, 3, 6]),
            (ObserverMode::Every(1), &[0, 1, 2, 3, 4, 5, 6]),
            (ObserverMode::NewBest, &[0, 2, 5]),
        ];
        for (mode, taken) in cases {
            let mut recorder = Recorder { mode, ..Recorder::default() };
            let mut always = Recorder::default();
            let mut list: [&mut dyn Observer; 2] = [&mut recorder, &mut always];
            let mut observers = Observers::new(&mut list);
            for (iteration, improved) in offered {
                observers.set_improved(improved);
                assert!(observers.wants(iteration), "the always-observer takes every record");
                observers.generation(&GenerationRecord { iteration, ..GenerationRecord::default() }).unwrap();
            }
            observers.event(RunEvent::EnvironmentChanged { iteration: 4 }).unwrap();
            let got: Vec<u32> = recorder.history.iter().map(|r| r.iteration).collect();
            assert_eq!(got, taken, "{mode:?}");
            assert_eq!(always.history.len(), offered.len());
            assert_eq!(recorder.changes, [4], "events reach every observer: {mode:?}");
        }
    }

    #[test]
    fn diversity_is_wanted_only_where_a_taking_observer_reads_it() {
        let mut every_two = Recorder { mode: ObserverMode::Every(2), ..Recorder::default() };
        let mut list: [&mut dyn Observer; 1] = [&mut every_two];
        let observers = Observers::new(&mut list);
        assert!(observers.wants_diversity(0), "iteration 0 is a multiple of every period");
        assert!(observers.wants_diversity(4) && !observers.wants_diversity(3));
        assert!(!Observers::none().wants(0) && !Observers::none().wants_diversity(0));
    }
}
