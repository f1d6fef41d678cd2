//! Random search: the control that tells whether a GA's machinery helps at all. It draws
//! random action genomes exactly as the thesis GA draws its initial population (003 §3.3.1,
//! thesis-ga §6: `Init_AC` actions, moves up to `init_dist_max`, corrected and evaluated as in R17)
//! in batches of `Pop_min`, until the budget is spent (the executor's stop rules, as every planner's), and keeps the fittest by the
//! thesis fitness `f_obstacle`. Budget-matched to the GAs through `budget.evaluations`.

use crate::config::ConfigError;
use crate::coverage::score::obstacle_violations;
use crate::ga::observer::{GenerationRecord, Observer, Observers};
use crate::ga::rng::{Purpose, stream};
use crate::planner::entry::{FileSections, PlannerEntry, RegisteredPlanner};
use crate::planner::executor::{Search, StopRules, execute};
use crate::planner::memory::{MemoryEstimate, bitset_bytes};
use crate::planner::{Budget, Context, Planner, PlannerError, RunOutcome, Scenario};
use crate::thesis::config::{THESIS_SECTION, ThesisSection};
use crate::thesis::genome::random_genome;
use crate::thesis::individual::{Base, EvalScratch, EvaluationMode, Individual, InitParams, correct_and_evaluate};
use crate::thesis::member::{Member, ReachMask};
use crate::thesis::scenario::ThesisScenario;
use rayon::prelude::*;
use std::sync::Arc;
use std::time::Instant;

/// Random search over thesis genomes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RandomSearch {
    /// How genomes are drawn (`thesis.init_actions`, `thesis.init_dist_max`).
    pub init: InitParams,
    /// Genomes per batch (`thesis.pop_min`); one batch is one iteration in the history.
    pub batch: usize,
}

/// The `[thesis]` keys random search reads: how it draws genomes (003's initialisation) and
/// how many per batch.
const READ_FROM_THESIS: [&str; 4] =
    ["thesis.pop_min", "thesis.init_actions", "thesis.init_dist_max", "thesis.max_genome_len"];

/// Why random search does not read `key` (a dotted key or a section of the planner sections),
/// or `None` when it reads it.
pub fn why_unread(key: &str) -> Option<String> {
    use crate::planner::sections::within;
    (within(key, "thesis") && key != "thesis" && !READ_FROM_THESIS.contains(&key))
        .then(|| format!("random search reads only {} of [thesis]", READ_FROM_THESIS.join(", ")))
}

impl RandomSearch {
    /// Reads the draw from the `[thesis]` section; the evaluation budget is required.
    pub fn validate(thesis: &ThesisSection, ctx: &Context) -> Result<Self, ConfigError> {
        let t = crate::thesis::config::validate_params(thesis, ctx.origin)?;
        if ctx.budget.evaluations.is_none() {
            return Err(ConfigError::new(
                ctx.origin,
                "budget.evaluations",
                "= 0: random search needs an evaluation budget (the GAs' budget, for a fair comparison)",
            ));
        }
        Ok(Self { init: t.init, batch: t.pop_min })
    }
}

impl RandomSearch {
    /// An upper estimate of a run's memory on `map`: a batch of genomes with their visit maps.
    pub fn memory_estimate(&self, map: &crate::map::GridMap) -> MemoryEstimate {
        let cells = (map.rows() * map.cols()) as f64;
        MemoryEstimate {
            bytes: self.batch as f64 * (32.0 * self.init.actions as f64 + bitset_bytes(cells)),
            key: "thesis.pop_min",
            what: format!("batches of {} random genomes", self.batch),
        }
    }
}

/// Random search's entry in the registry of planners: `planner = "random_search"`, drawing as
/// `[thesis]` says.
pub struct RandomSearchEntry;

impl PlannerEntry for RandomSearchEntry {
    fn name(&self) -> &'static str {
        "random_search"
    }

    /// It reads `[thesis]`, which the thesis GA declares.
    fn sections_read(&self, _file: &dyn FileSections) -> Vec<&'static str> {
        vec![THESIS_SECTION.name()]
    }

    fn why_unread(&self, _file: &dyn FileSections, key: &str) -> Option<String> {
        why_unread(key)
    }

    fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
        Ok(Arc::new(RandomSearch::validate(&THESIS_SECTION.get_or_default(file), ctx)?))
    }
}

impl RegisteredPlanner for RandomSearch {
    fn memory_estimate(&self, map: &crate::map::GridMap, _threads: usize) -> MemoryEstimate {
        RandomSearch::memory_estimate(self, map)
    }

    fn evaluation_rule(&self) -> &'static str {
        "stops after the first batch that reaches the limit: fewer than random_search.batch evaluations past it"
    }

    fn progress_length(&self, budget: &Budget) -> u64 {
        u64::from(budget.iterations)
    }
}

impl Planner for RandomSearch {
    fn name(&self) -> &'static str {
        "random_search"
    }

    fn run(
        &self,
        scenario: &Scenario,
        seed: u64,
        budget: &Budget,
        observers: &mut [&mut dyn Observer],
    ) -> Result<RunOutcome, PlannerError> {
        let started = Instant::now();
        let th = ThesisScenario::from_common(scenario);
        let reach = if observers.is_empty() { ReachMask::default() } else { Individual::reach_mask(&th) };
        let mut batches =
            Batches { search: self, th: &th, seed, reach, iteration: 0, evaluations: 0, best: None, mean: 0.0 };
        // The first batch is the run's start, as a GA's initial population (iteration 0).
        batches.draw(0);
        // Without an evaluation budget (a library caller's), one batch.
        let budget = Budget { evaluations: Some(budget.evaluations.unwrap_or(self.batch as u64)), ..budget.clone() };
        let finish =
            execute(&mut batches, &StopRules::of_budget(&budget, None, started), &mut Observers::new(observers))?;
        let (iteration, evaluations, stop, best) = (finish.iterations, finish.evaluations, finish.stop, batches.best);
        let best = best.ok_or_else(|| PlannerError::Input("random search: the evaluation budget is 0".into()))?;
        let sc = best.score;
        let details = crate::planner::details(serde_json::json!({
            "cov_final": sc.cov_final,
            "t_final": sc.t_final,
            "fitness": sc.fitness,
            "genome_len": best.len(),
        }));
        Ok(RunOutcome::new(vec![best.points.clone()], stop)
            .with_objectives(vec![("cov_final", sc.cov_final), ("t_final", sc.t_final), ("fitness", sc.fitness)])
            .with_violations(obstacle_violations(best.sweep.obj_pix))
            .with_feasible(best.sweep.obj_pix == 0)
            .with_effort(evaluations, iteration)
            .with_wall_s(started.elapsed().as_secs_f64())
            .with_details(details)
            .with_files(vec![("best_genome.csv".into(), best.genome_csv())])
            .with_history(crate::planner::History::Generations))
    }
}

/// A random search between batches, as [`execute`] drives it.
struct Batches<'a> {
    search: &'a RandomSearch,
    th: &'a ThesisScenario,
    seed: u64,
    reach: ReachMask,
    /// The last batch drawn (0: the first).
    iteration: u32,
    evaluations: u64,
    best: Option<Individual>,
    /// The last batch's mean fitness.
    mean: f64,
}

impl Batches<'_> {
    /// Draws batch `iteration` and keeps its fittest if it beats the best so far; whether it did.
    fn draw(&mut self, iteration: u32) -> bool {
        let (th, seed, init) = (self.th, self.seed, &self.search.init);
        let batch: Vec<(Individual, u64)> = (0..self.search.batch)
            .into_par_iter()
            .map_init(EvalScratch::default, |scratch, slot| {
                let mut rng = stream(seed, Purpose::Individual, &[u64::from(iteration), slot as u64]);
                let mut ind = Individual::default();
                random_genome(&mut rng, init.actions, init.dist_max, &mut ind.genome);
                let e = correct_and_evaluate(&mut ind, th, Base::None, EvaluationMode::Full, scratch, init, &mut rng);
                (ind, e)
            })
            .collect();
        self.mean = batch.iter().map(|(i, _)| i.fitness()).sum::<f64>() / batch.len() as f64;
        self.iteration = iteration;
        let mut improved = false;
        for (ind, e) in batch {
            self.evaluations += e;
            if self.best.as_ref().is_none_or(|b| ind.fitness() > b.fitness()) {
                self.best = Some(ind);
                improved = true;
            }
        }
        improved
    }
}

impl Search for Batches<'_> {
    type Error = std::io::Error;

    fn progress(&self) -> (u32, u64) {
        (self.iteration, self.evaluations)
    }

    fn step(&mut self, _: &mut Observers) -> std::io::Result<bool> {
        Ok(self.draw(self.iteration + 1))
    }

    fn report(&mut self, observers: &mut Observers) -> std::io::Result<()> {
        if !observers.wants(self.iteration) {
            return Ok(());
        }
        let b = self.best.as_ref().expect("a batch was drawn");
        let record = GenerationRecord {
            iteration: self.iteration,
            evaluations: self.evaluations,
            best_fitness: b.fitness(),
            mean_fitness: self.mean,
            best_coverage: b.score.cov_final,
            best_coverage_reach: Some(self.reach.coverage(b.reached(&self.reach))),
            feasible: None,
            diversity: None,
            robots: Vec::new(),
            extras: vec![("best_t_final", b.score.t_final), ("best_genome_len", b.len() as f64)],
        };
        observers.generation(&record)
    }
}
