//! The run loop of the thesis GA: the algorithm ([`ThesisGa`]: scenario, parameters, seed) is
//! kept apart from the state it evolves ([`GaState`]); every iteration's statistics go to
//! observers. The loop is the planner layer's executor: it stops at `Iter_max`, at the
//! optional evaluation, wall-clock or stall limit, or when interrupted; optionally marks a
//! region as covered part-way (retrain, 003 §3.5.3).

use super::architecture::{Effective, Generation, MutationRate, bounded_fitness};
use super::diversity::DiversityScratch;
use super::individual::{EvalScratch, Individual};
use super::member::{Member, Premark, ReachMask};
use super::params::{Control, Retrain, SeedBound, Selection, ThesisParams};
use crate::coverage::fitness::ThesisScore;
use crate::ga::control;
use crate::ga::observer::{GenerationRecord, GenerationStats, Observer, Observers, RunEvent};
use crate::ga::parents::Param;
use crate::ga::rng::{Purpose, Rng, stream};
use crate::planner::executor::{Interrupt, Search, StopRules, execute};
use crate::planner::{Budget, PlannerError, StopReason};
use std::time::Instant;

/// The algorithm: what stays fixed during a run. `T` is what the population holds: one
/// robot's genome ([`Individual`], the thesis GA) or one genome per robot of a fleet.
pub struct Ga<T: Member> {
    /// What an evaluation reads: map, robot(s), stations, projection.
    pub scenario: T::World,
    /// Operator and population parameters.
    pub params: ThesisParams,
    /// The run's seed.
    pub seed: u64,
    /// Unevaluated members whose genomes seed the initial population (a pattern's plan,
    /// `thesis.seed_population`), and how many initial slots they fill, cycling through them.
    pub seeds: (Vec<T>, usize),
}

/// The thesis GA of 003: a population of single-robot genomes.
pub type ThesisGa = Ga<Individual>;

/// What a run evolves.
pub struct GaState<T = Individual> {
    /// The current population.
    pub population: Vec<T>,
    /// Iterations completed.
    pub iteration: u32,
    /// Evaluations so far.
    pub evaluations: u64,
    /// `Div` of the current population, when measured.
    pub diversity: Option<f64>,
    /// `Div_max` of the current population (adaptive control only, else 0).
    pub diversity_max: f64,
    /// `(cov_final, t_final)` of the seed plans as evaluated, for `thesis.seed_bound =
    /// "dominate"` (empty otherwise).
    pub seed_points: Vec<(f64, f64)>,
    rng: Rng,
    /// Members that did not pass on, whose buffers the next generation's new members reuse.
    spare: Vec<T>,
    /// The diversity kept from one measured generation to the next.
    diversity_scratch: DiversityScratch,
}

/// The result of a run of the thesis GA.
pub struct ThesisOutcome<T = Individual> {
    /// Best individual of the final population (R30); under Pareto selection, the knee of
    /// its first front ([`knee_index`]).
    pub best: T,
    /// Best individual just before the environment changed, if it did.
    pub best_before_retrain: Option<T>,
    /// Iterations completed.
    pub iterations: u32,
    /// Evaluations spent.
    pub evaluations: u64,
    /// Why the run ended.
    pub stop: StopReason,
    /// Wall time in seconds (not part of the deterministic outputs).
    pub wall_s: f64,
    /// Every iteration's statistics (for the history figure).
    pub history: Vec<GenerationStats>,
    /// Iterations at which the environment changed.
    pub changes: Vec<u32>,
    /// The final population's scores, genome lengths and obstacle sweeps, in population order
    /// (its front is what 003's Pareto figures show).
    pub final_population: Vec<(ThesisScore, usize, u64)>,
    /// The final population's members themselves, in population order (their genomes for
    /// `output.population_genomes`).
    pub population: Vec<T>,
    /// The seed plans' `(cov_final, t_final)` that bounded Pareto selection (empty: none).
    pub seed_points: Vec<(f64, f64)>,
}

/// Index of the fittest individual (first on ties).
pub fn best_index<T: Member>(pop: &[T]) -> usize {
    best_index_within(pop, &[])
}

/// Index of the fittest individual by [`bounded_fitness`] within the seed plans' `bounds`
/// (first on ties; [`best_index`] without bounds).
pub fn best_index_within<T: Member>(pop: &[T], bounds: &[(f64, f64)]) -> usize {
    let Some(first) = pop.first() else { return 0 };
    let (mut best, mut best_key) = (0, bounded_fitness(first, bounds));
    for (i, m) in pop.iter().enumerate().skip(1) {
        let k = bounded_fitness(m, bounds);
        if k > best_key {
            (best, best_key) = (i, k);
        }
    }
    best
}

impl<T: Member> Ga<T> {
    fn scratches(&self) -> Vec<EvalScratch> {
        (0..rayon::current_num_threads().max(1)).map(|_| EvalScratch::default()).collect()
    }

    /// Whether the selection is Pareto selection (NSGA-II).
    fn pareto(&self) -> bool {
        matches!(self.params.selection, Selection::Nsga2)
    }

    fn adaptive(&self) -> bool {
        matches!(self.params.control, Control::Adaptive(_))
    }

    fn generation<'a>(&'a self, iteration: u32, effective: Effective, bounds: &'a [(f64, f64)]) -> Generation<'a, T> {
        Generation { scenario: &self.scenario, params: &self.params, effective, seed: self.seed, iteration, bounds }
    }

    fn fixed_effective(&self) -> Effective {
        let p = &self.params;
        // A parameter the scheme does not read is 0 (the history's `sp` column then reads the other).
        let (tournament_size, pressure) = p.selection.draw().map_or((0, 0.0), |d| {
            let reads = |param| d.scheme.reads().contains(&param);
            let size = if reads(Param::TournamentSize) { d.params.tournament_size } else { 0 };
            (size, if reads(Param::Pressure) { d.params.pressure } else { 0.0 })
        });
        Effective { p_c: p.p_c, p_mi: p.p_mi, p_ma: MutationRate::Fixed(p.p_ma), tournament_size, pressure }
    }

    /// Operator probabilities for `iteration` under the configured control (thesis-ga §12).
    pub fn effective(&self, state: &GaState<T>, iteration: u32, iter_max: u32) -> Effective {
        let mut e = self.fixed_effective();
        match self.params.control {
            Control::None => {}
            // Validation allows a ramp only for a scheme with a ramped parameter.
            Control::Ramp { min, max } => match self.params.selection.draw().and_then(|d| d.scheme.ramped()) {
                Some(Param::TournamentSize) => {
                    let ts = control::ramp_tournament_size(iteration, iter_max, min, max);
                    e.tournament_size = ts.min(state.population.len());
                }
                Some(Param::Pressure) => e.pressure = control::linear_ramp(iteration, iter_max, min, max),
                Some(Param::BestParents) | None => {}
            },
            Control::Adaptive(c) => {
                let fit = state.population.iter().map(T::fitness);
                let f_min = fit.clone().fold(f64::INFINITY, f64::min);
                let f_max = fit.fold(f64::NEG_INFINITY, f64::max);
                let div = state.diversity.expect("adaptive control measures the diversity");
                e.p_c = control::adaptive_p_c(div, state.diversity_max, &c);
                let diversity_part = control::adaptive_p_m_diversity(div, state.diversity_max, &c);
                e.p_ma = MutationRate::Adaptive { diversity_part, k: c.k, f_min, f_max };
            }
            Control::Muhlenbein => {
                e.p_ma = MutationRate::Fixed(control::muhlenbein_p_m(iteration, iter_max));
                e.p_c = control::muhlenbein_p_c(iteration, iter_max);
            }
        }
        e
    }

    /// Creates and evaluates the initial population (thesis-ga §6) — iteration 0. Measures the
    /// diversity when `measure_diversity` or the parameter control needs it.
    pub fn init(&self, measure_diversity: bool) -> GaState<T> {
        self.init_until(measure_diversity, &|| false).expect("a set-up that never stops")
    }

    /// [`Self::init`], giving up (`None`) when `stop` says so between blocks of members.
    pub fn init_until(&self, measure_diversity: bool, stop: &dyn Fn() -> bool) -> Option<GaState<T>> {
        let mut scratches = self.scratches();
        let size = self.params.initial_size();
        let (seeds, seeded) = (&self.seeds.0, self.seeds.1.min(size));
        let (population, evaluations) =
            self.generation(0, self.fixed_effective(), &[]).initial(size, &seeds[..], seeded, &mut scratches, stop)?;
        let seed_points = match self.params.seed_bound {
            SeedBound::None => Vec::new(),
            SeedBound::Dominate => {
                // One point per distinct seed plan (`seeded` cycles through the seeds).
                let mut points: Vec<(f64, f64)> = Vec::new();
                for m in &population[..seeded] {
                    let p = (m.score().cov_final, m.score().t_final);
                    if !points.contains(&p) {
                        points.push(p);
                    }
                }
                points
            }
        };
        let mut state = GaState {
            population,
            iteration: 0,
            evaluations,
            diversity: None,
            diversity_max: 0.0,
            seed_points,
            rng: stream(self.seed, Purpose::Main, &[]),
            spare: Vec::new(),
            diversity_scratch: DiversityScratch::default(),
        };
        self.measure_diversity(&mut state, measure_diversity);
        Some(state)
    }

    fn measure_diversity(&self, state: &mut GaState<T>, wanted: bool) {
        state.diversity =
            (wanted || self.adaptive()).then(|| T::diversity(&state.population, &mut state.diversity_scratch));
        if self.adaptive() {
            state.diversity_max = T::max_distance(&state.population) as f64;
        }
    }

    /// One iteration: both architectures share the loop, selection decides which runs.
    /// `measure`: whether the diversity is to be measured (always under adaptive control).
    pub fn step(&self, state: &mut GaState<T>, effective: Effective, scratches: &mut [EvalScratch], measure: bool) {
        state.iteration += 1;
        let generation = self.generation(state.iteration, effective, &state.seed_points);
        let pop = std::mem::take(&mut state.population);
        let (rng, spare) = (&mut state.rng, &mut state.spare);
        let (next, evaluations) = match self.params.selection {
            Selection::Nsga2 => generation.step_nsga2(pop, rng, scratches, spare),
            Selection::Elite => generation.step_b(pop, rng, scratches, spare),
            Selection::Draw(draw) => generation.step_a(draw, pop, rng, scratches, spare),
        };
        state.population = next;
        state.evaluations += evaluations;
        self.measure_diversity(state, measure);
    }

    /// A fresh scratch per worker thread, for [`Self::step`].
    pub fn new_scratches(&self) -> Vec<EvalScratch> {
        self.scratches()
    }

    fn reevaluate(&self, state: &mut GaState<T>) {
        let mut scratch = EvalScratch::default();
        for ind in &mut state.population {
            state.evaluations += ind.reevaluate(&self.scenario, self.params.evaluation, &mut scratch);
        }
        let wanted = state.diversity.is_some();
        self.measure_diversity(state, wanted);
    }

    /// Marks `region` as already covered and re-evaluates everyone (thesis-ga §13, R25).
    pub fn change_environment(&mut self, state: &mut GaState<T>, region: [f64; 4])
    where
        T::World: Premark,
    {
        let [x0, y0, x1, y1] = region;
        self.scenario.premark_rect(x0, y0, x1, y1);
        self.reevaluate(state);
    }

    /// Runs to the end of the budget ([`execute`]: the stop rules of `budget`), handing
    /// statistics to `observers`. The run's interrupt also ends the initial population's
    /// evaluation ([`PlannerError::Interrupted`]: there is no plan yet); the other stop rules
    /// let it finish, as the evaluation budget's rule says.
    pub fn run(
        &mut self,
        budget: &Budget,
        retrain: Option<&Retrain>,
        observers: &mut [&mut dyn Observer],
    ) -> Result<ThesisOutcome<T>, PlannerError>
    where
        T::World: Premark,
    {
        let started = Instant::now();
        let mut observers = Observers::new(observers);
        let interrupted = || budget.interrupt.as_ref().is_some_and(Interrupt::is_raised);
        let state = self.init_until(observers.wants_diversity(0), &interrupted).ok_or(PlannerError::Interrupted)?;
        // Reachability is measured only for someone who reads the records.
        let reach = if observers.is_empty() { ReachMask::default() } else { T::reach_mask(&self.scenario) };
        let best_seen = bounded_fitness(
            &state.population[best_index_within(&state.population, &state.seed_points)],
            &state.seed_points,
        );
        let mut running = Running {
            scratches: self.scratches(),
            effective: self.fixed_effective(),
            ga: self,
            state,
            reach,
            history: Vec::new(),
            changes: Vec::new(),
            best_seen,
            best_before_retrain: None,
            retrain,
            iter_max: budget.iterations,
        };
        let finish = execute(&mut running, &StopRules::of_budget(budget, None, started), &mut observers)?;
        let Running { ga, state, history, changes, best_before_retrain, .. } = running;
        let reported = if ga.pareto() {
            knee_index(&state.population, &state.seed_points)
        } else {
            best_index_within(&state.population, &state.seed_points)
        };
        let best = state.population[reported].clone();
        let final_population =
            state.population.iter().map(|m| (m.score(), m.genome_len(), m.obstacle_cells())).collect();
        Ok(ThesisOutcome {
            final_population,
            population: state.population,
            history,
            changes,
            best,
            best_before_retrain,
            iterations: finish.iterations,
            evaluations: finish.evaluations,
            stop: finish.stop,
            wall_s: started.elapsed().as_secs_f64(),
            seed_points: state.seed_points,
        })
    }
}

/// A thesis GA run between generations, as [`execute`] drives it.
struct Running<'a, T: Member> {
    ga: &'a mut Ga<T>,
    state: GaState<T>,
    scratches: Vec<EvalScratch>,
    /// The parameters the last generation ran with (the fixed ones before the first).
    effective: Effective,
    reach: ReachMask,
    history: Vec<GenerationStats>,
    /// Iterations at which the environment changed.
    changes: Vec<u32>,
    /// The best bounded fitness so far (since the last environment change).
    best_seen: f64,
    best_before_retrain: Option<T>,
    retrain: Option<&'a Retrain>,
    /// `Iter_max`, which ramped parameters read.
    iter_max: u32,
}

impl<T: Member> Search for Running<'_, T>
where
    T::World: Premark,
{
    type Error = std::io::Error;

    fn progress(&self) -> (u32, u64) {
        (self.state.iteration, self.state.evaluations)
    }

    fn step(&mut self, observers: &mut Observers) -> std::io::Result<bool> {
        let (ga, state) = (&mut *self.ga, &mut self.state);
        if let Some(r) = self.retrain.filter(|r| r.at_iteration == state.iteration) {
            self.best_before_retrain =
                Some(state.population[best_index_within(&state.population, &state.seed_points)].clone());
            ga.change_environment(state, r.region);
            self.scratches = ga.scratches();
            observers.event(RunEvent::EnvironmentChanged { iteration: state.iteration + 1 })?;
            self.changes.push(state.iteration + 1);
            self.best_seen = f64::NEG_INFINITY;
        }
        let effective = ga.effective(state, state.iteration + 1, self.iter_max);
        let wanted = observers.wants_diversity(state.iteration + 1);
        ga.step(state, effective, &mut self.scratches, wanted);
        self.effective = effective;
        let best = bounded_fitness(
            &state.population[best_index_within(&state.population, &state.seed_points)],
            &state.seed_points,
        );
        let improved = best > self.best_seen;
        if improved {
            self.best_seen = best;
        }
        Ok(improved)
    }

    fn report(&mut self, observers: &mut Observers) -> std::io::Result<()> {
        let now = stats(&self.state, &self.effective, self.ga.pareto());
        if observers.wants(now.iteration) {
            observers.generation(&record(&now, &self.state, &self.ga.scenario, &self.reach))?;
        }
        self.history.push(now);
        Ok(())
    }
}

impl ThesisGa {
    /// Makes the flagged free cells the pre-marked ones (what other robots cover, in a fleet's
    /// negotiation) and re-evaluates everyone.
    pub fn set_premarks(&mut self, state: &mut GaState, cells: &[bool]) {
        self.scenario.set_premarks(cells);
        self.reevaluate(state);
    }
}

/// The record observers receive: the statistics, and the best member's robots for a fleet.
fn record<T: Member>(
    stats: &GenerationStats,
    state: &GaState<T>,
    world: &T::World,
    reach: &ReachMask,
) -> GenerationRecord {
    let mut r = stats.record();
    let best = &state.population[best_index_within(&state.population, &state.seed_points)];
    r.best_coverage_reach = Some(reach.coverage(best.reached(reach)));
    r.robots = best.robot_records(world);
    r
}

/// Statistics of the current population (thesis-ga §17); with `pareto`, the hypervolume of its
/// plans without obstacle sweeps too.
pub fn stats<T: Member>(state: &GaState<T>, effective: &Effective, pareto: bool) -> GenerationStats {
    let pop = &state.population;
    let n = pop.len() as f64;
    let best = &pop[best_index_within(pop, &state.seed_points)];
    let (mut s, mut lo, mut hi) = ([0.0; 3], [f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    let (mut len_sum, mut len_min, mut len_max) = (0usize, usize::MAX, 0usize);
    let mut p_ma_sum = 0.0;
    for ind in pop {
        let score = ind.score();
        let v = [score.cov_final, score.t_final];
        for k in 0..2 {
            s[k] += v[k];
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
        s[2] += ind.fitness();
        let len = ind.genome_len();
        len_sum += len;
        len_min = len_min.min(len);
        len_max = len_max.max(len);
        p_ma_sum += effective.p_ma.for_fitness(ind.fitness());
    }
    GenerationStats {
        iteration: state.iteration,
        evaluations: state.evaluations,
        best_fitness: best.fitness(),
        best_cov_final: best.score().cov_final,
        best_t_final: best.score().t_final,
        mean_cov_final: s[0] / n,
        min_cov_final: lo[0],
        max_cov_final: hi[0],
        mean_t_final: s[1] / n,
        min_t_final: lo[1],
        max_t_final: hi[1],
        mean_fitness: s[2] / n,
        mean_genome_len: len_sum as f64 / n,
        min_genome_len: len_min as u32,
        max_genome_len: len_max as u32,
        diversity: state.diversity,
        p_c: effective.p_c,
        p_ma: p_ma_sum / n,
        sp: if effective.tournament_size > 0 { effective.tournament_size as f64 } else { effective.pressure },
        population: pop.len() as u32,
        feasible: pop.iter().filter(|m| m.obstacle_cells() == 0).count() as u32,
        hypervolume: pareto.then(|| {
            let clean: Vec<(f64, f64)> = pop
                .iter()
                .filter(|m| m.obstacle_cells() == 0)
                .map(|m| (m.score().cov_final, m.score().t_final))
                .collect();
            crate::ga::pareto::hypervolume_2d(&clean, (0.0, 0.0))
        }),
    }
}

/// The member a Pareto run reports: the knee ([`crate::ga::selection::nsga2::knee`]) of the
/// first front under constrained domination (the plans without obstacle sweeps, when there
/// are any; within `bounds`, the seed plans' objectives, when it has them).
pub fn knee_index<T: Member>(pop: &[T], bounds: &[(f64, f64)]) -> usize {
    let (points, violation) = super::architecture::objectives(pop, bounds);
    let rank = crate::ga::selection::nsga2::front_ranks(&points, &violation);
    let front: Vec<usize> = (0..pop.len()).filter(|&i| rank[i] == 0).collect();
    crate::ga::selection::nsga2::knee(&points, &front).expect("a population has a first front")
}
