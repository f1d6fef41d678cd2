//! Per-generation statistics and the observers that receive them (history writer, progress
//! bar, …). Algorithm code hands statistics to observers and never prints.

use serde::Serialize;

/// The statistics of one generation (003 §4.1.2, spec §17).
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
    /// Population diversity `Div` (spec §5).
    pub diversity: f64,
    /// Effective crossover probability `P_c`.
    pub p_c: f64,
    /// Effective action-mutation probability `P_mA` (mean over individuals when adaptive).
    pub p_ma: f64,
    /// Effective selection pressure `SP` (RRWS) or tournament size `TS` (0 when unused).
    pub sp: f64,
    /// Population size.
    pub population: u32,
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

/// Receives statistics during a run.
pub trait Observer {
    /// Called after the initial population (iteration 0) and after every iteration.
    fn generation(&mut self, stats: &GenerationStats) -> std::io::Result<()>;
    /// Called on other run events.
    fn event(&mut self, _event: RunEvent) -> std::io::Result<()> {
        Ok(())
    }
}

/// Keeps every generation's statistics in memory (for figures and tests).
#[derive(Default, Debug)]
pub struct Recorder {
    /// The statistics, in order.
    pub history: Vec<GenerationStats>,
    /// Iterations at which the environment changed.
    pub changes: Vec<u32>,
}

impl Observer for Recorder {
    fn generation(&mut self, stats: &GenerationStats) -> std::io::Result<()> {
        self.history.push(*stats);
        Ok(())
    }
    fn event(&mut self, event: RunEvent) -> std::io::Result<()> {
        let RunEvent::EnvironmentChanged { iteration } = event;
        self.changes.push(iteration);
        Ok(())
    }
}
