//! The run loop every iterative planner shares, after argmin's `Executor`: a planner is a
//! [`Search`] (its state and one step), and [`execute`] owns what is common to all of them —
//! the stop conditions, the stall count, the interrupt and the order in which records reach
//! the observers. No planner writes its own loop, so a budget means the same for every one.
//!
//! Stop conditions combine as MAHF's do: a [`StopRules`] is any of several [`StopRule`]s, the
//! first met, in order, naming why the run ended. A run's budget gives the rules
//! [`StopRules::of_budget`]; a library caller adds its own with `|`.

use super::{Budget, StopReason};
use crate::ga::observer::Observers;
use std::ops::BitOr;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// A flag another thread raises to end a run at its next iteration (Ctrl-C, a notebook's
/// interrupt, a study that is stopping): the run then ends with [`StopReason::Interrupted`]
/// and returns what it has. Clones share the flag.
#[derive(Clone, Debug, Default)]
pub struct Interrupt(Arc<AtomicBool>);

impl Interrupt {
    /// A flag not yet raised.
    pub fn new() -> Self {
        Self::default()
    }
    /// Raises the flag: every run reading it stops at its next iteration.
    pub fn raise(&self) {
        self.0.store(true, Ordering::SeqCst);
    }
    /// Whether the flag is raised.
    pub fn is_raised(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

impl PartialEq for Interrupt {
    /// The same flag.
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// When a planner's set-up (what it does before its first iteration: a cell decomposition and
/// its transit routes, the waypoint planner's views) gives up: at the run's wall clock, or as
/// soon as its interrupt is raised. The rules of [`StopRules`] are read between iterations;
/// set-up reads these two between its own pieces of work, so that Ctrl-C or a stopping study
/// does not wait for a preparation of minutes.
#[derive(Clone, Debug, Default)]
pub struct SetupCutoff {
    /// The wall-clock limit and when it ends.
    pub wall_clock: Option<(Instant, Duration)>,
    /// The run's interrupt.
    pub interrupt: Option<Interrupt>,
}

impl SetupCutoff {
    /// The cutoff of `budget` for a run started at `started`.
    pub fn of_budget(budget: &Budget, started: Instant) -> Self {
        Self { wall_clock: budget.wall_clock.map(|d| (started + d, d)), interrupt: budget.interrupt.clone() }
    }

    /// Why set-up ends now, if it does: the interrupt first, then the wall clock.
    pub fn reached(&self) -> Option<StopReason> {
        if self.interrupt.as_ref().is_some_and(Interrupt::is_raised) {
            return Some(StopReason::Interrupted);
        }
        self.wall_clock.filter(|(end, _)| Instant::now() >= *end).map(|_| StopReason::WallClock)
    }

    /// The wall-clock limit in seconds (0 without one), for messages.
    pub fn limit_s(&self) -> f64 {
        self.wall_clock.map_or(0.0, |(_, d)| d.as_secs_f64())
    }
}

/// Where a run stands between two iterations: what the stop rules read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    /// Iterations completed (0: the initial population, or first batch, only).
    pub iteration: u32,
    /// Fitness evaluations spent.
    pub evaluations: u64,
    /// Iterations since the last one that improved the best.
    pub since_better: u32,
}

/// One condition that ends a run.
#[derive(Clone, Debug, PartialEq)]
pub enum StopRule {
    /// The flag is raised.
    Interrupted(Interrupt),
    /// This many iterations in a row without a better best.
    Stall(u32),
    /// This many iterations completed.
    Iterations(u32),
    /// This many evaluations spent.
    Evaluations(u64),
    /// This much wall time passed since `since` (the run's start: preparation counts).
    WallClock {
        /// The limit.
        limit: Duration,
        /// When the clock started.
        since: Instant,
    },
}

impl StopRule {
    /// Why the run ends now under this rule, if it does.
    pub fn met(&self, at: &Progress) -> Option<StopReason> {
        let met = match self {
            Self::Interrupted(flag) => flag.is_raised(),
            Self::Stall(limit) => at.since_better >= *limit,
            Self::Iterations(limit) => at.iteration >= *limit,
            Self::Evaluations(limit) => at.evaluations >= *limit,
            Self::WallClock { limit, since } => since.elapsed() >= *limit,
        };
        met.then_some(match self {
            Self::Interrupted(_) => StopReason::Interrupted,
            Self::Stall(_) => StopReason::Stall,
            Self::Iterations(_) => StopReason::Iterations,
            Self::Evaluations(_) => StopReason::Evaluations,
            Self::WallClock { .. } => StopReason::WallClock,
        })
    }
}

/// Any of several rules; the first met, in order, names the stop.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StopRules(Vec<StopRule>);

impl StopRules {
    /// The rules of `budget` for a run started at `started`, in the order that names a stop
    /// when several hold at once: the interrupt, the stall limit, the iteration limit, the
    /// evaluation budget, the wall clock. `iterations` is the planner's own limit when it has
    /// one of its own (the waypoint planner's `generations`), else `budget.iterations`.
    pub fn of_budget(budget: &Budget, iterations: Option<u32>, started: Instant) -> Self {
        let mut rules = Vec::with_capacity(5);
        rules.extend(budget.interrupt.clone().map(StopRule::Interrupted));
        rules.extend(budget.stall_iterations.map(StopRule::Stall));
        rules.extend(iterations.or(Some(budget.iterations)).map(StopRule::Iterations));
        rules.extend(budget.evaluations.map(StopRule::Evaluations));
        rules.extend(budget.wall_clock.map(|limit| StopRule::WallClock { limit, since: started }));
        Self(rules)
    }
    /// The first rule met at `at`, if any.
    pub fn first_met(&self, at: &Progress) -> Option<StopReason> {
        self.0.iter().find_map(|rule| rule.met(at))
    }
    /// The rules, in order.
    pub fn rules(&self) -> &[StopRule] {
        &self.0
    }
}

impl BitOr<StopRule> for StopRules {
    type Output = StopRules;
    /// These rules, then `rule`.
    fn bitor(mut self, rule: StopRule) -> StopRules {
        self.0.push(rule);
        self
    }
}

/// A planner's search as the executor drives it: its state between iterations, one step, and
/// the record of where it stands, which goes to the run's [`Observers`] (each as its mode says).
pub trait Search {
    /// What a step or a report can fail with (an observer's write, the caller's own error).
    type Error;
    /// Iterations completed and evaluations spent so far.
    fn progress(&self) -> (u32, u64);
    /// Why the search has ended by its own rule, if it has (a fleet's plans settled, every
    /// robot's share of the budget spent); read before the stop rules. Most searches run until
    /// a rule stops them.
    fn finished(&self) -> Option<StopReason> {
        None
    }
    /// One iteration (a generation, a batch); whether it made the best better (the planner
    /// says what better means). Run events (an environment change) go to `observers`.
    fn step(&mut self, observers: &mut Observers) -> Result<bool, Self::Error>;
    /// Hands the record of where the search stands to `observers` (after the initial
    /// population and after every step); a record that costs something to build is built
    /// only when [`Observers::wants`] it.
    fn report(&mut self, observers: &mut Observers) -> Result<(), Self::Error>;
}

/// How an executed search ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Finish {
    /// Why it ended.
    pub stop: StopReason,
    /// Iterations completed.
    pub iterations: u32,
    /// Evaluations spent.
    pub evaluations: u64,
}

/// Runs `search` from its initial state until it has finished by its own rule or a rule of
/// `rules` is met: reports the initial state, then, while neither holds, steps and reports. The stall count is the executor's:
/// iterations since the last step that said it improved the best; the same judgement tells
/// [`ObserverMode::NewBest`](crate::ga::observer::ObserverMode::NewBest) observers which
/// records to take.
pub fn execute<S: Search>(search: &mut S, rules: &StopRules, observers: &mut Observers) -> Result<Finish, S::Error> {
    observers.set_improved(true);
    search.report(observers)?;
    let mut since_better = 0u32;
    loop {
        let (iteration, evaluations) = search.progress();
        let progress = Progress { iteration, evaluations, since_better };
        if let Some(stop) = search.finished().or_else(|| rules.first_met(&progress)) {
            return Ok(Finish { stop, iterations: iteration, evaluations });
        }
        let improved = search.step(observers)?;
        since_better = if improved { 0 } else { since_better + 1 };
        observers.set_improved(improved);
        search.report(observers)?;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ga::observer::{GenerationRecord, Observer, ObserverMode, Recorder};
    use crate::planner::PlannerError;

    /// Counts up by `per_step` evaluations, better every `better_every` steps; keeps reports.
    struct Counter {
        iteration: u32,
        evaluations: u64,
        per_step: u64,
        better_every: u32,
    }

    impl Search for Counter {
        type Error = PlannerError;
        fn progress(&self) -> (u32, u64) {
            (self.iteration, self.evaluations)
        }
        fn step(&mut self, _: &mut Observers) -> Result<bool, PlannerError> {
            self.iteration += 1;
            self.evaluations += self.per_step;
            Ok(self.iteration.is_multiple_of(self.better_every))
        }
        fn report(&mut self, observers: &mut Observers) -> Result<(), PlannerError> {
            let record = GenerationRecord {
                iteration: self.iteration,
                evaluations: self.evaluations,
                ..GenerationRecord::default()
            };
            Ok(observers.generation(&record)?)
        }
    }

    /// Runs `counter` under `rules` with a recorder of `mode`: how it ended, and the
    /// (iteration, evaluations) of the records the recorder took.
    fn run(counter: &mut Counter, rules: &StopRules, mode: ObserverMode) -> (Finish, Vec<(u32, u64)>) {
        let mut recorder = Recorder { mode, ..Recorder::default() };
        let mut list: [&mut dyn Observer; 1] = [&mut recorder];
        let finish = execute(counter, rules, &mut Observers::new(&mut list)).unwrap();
        (finish, recorder.history.iter().map(|r| (r.iteration, r.evaluations)).collect())
    }

    fn budget(iterations: u32, evaluations: Option<u64>, stall: Option<u32>) -> Budget {
        Budget { evaluations, stall_iterations: stall, ..Budget::iterations(iterations) }
    }

    #[test]
    fn each_rule_stops_where_it_says_and_the_first_met_names_the_stop() {
        // (budget, better every, iterations run, stop)
        let cases = [
            (budget(7, None, None), 1, 7, StopReason::Iterations),
            (budget(100, Some(35), None), 1, 4, StopReason::Evaluations),
            (budget(100, Some(40), None), 1, 4, StopReason::Evaluations),
            (budget(100, None, Some(3)), 50, 3, StopReason::Stall),
            // Better every 4th step: never 4 in a row without, so the stall limit 4 never holds.
            (budget(20, None, Some(4)), 4, 20, StopReason::Iterations),
            // Stall and iterations at once: the stall names it.
            (budget(3, None, Some(3)), 50, 3, StopReason::Stall),
            // Iterations and evaluations at once: the iterations name it.
            (budget(4, Some(40), None), 1, 4, StopReason::Iterations),
        ];
        for (b, better_every, iterations, stop) in cases {
            let mut counter = Counter { iteration: 0, evaluations: 0, per_step: 10, better_every };
            let rules = StopRules::of_budget(&b, None, Instant::now());
            let (finish, reports) = run(&mut counter, &rules, ObserverMode::Always);
            assert_eq!((finish.iterations, finish.stop), (iterations, stop), "{b:?}");
            assert_eq!(finish.evaluations, u64::from(iterations) * 10);
            let want: Vec<(u32, u64)> = (0..=iterations).map(|k| (k, u64::from(k) * 10)).collect();
            assert_eq!(reports, want, "{b:?}: one report for the start and one per step");
        }
    }

    #[test]
    fn a_raised_interrupt_stops_before_the_next_step_and_a_planners_own_limit_replaces_the_budgets() {
        let flag = Interrupt::new();
        let b = Budget { interrupt: Some(flag.clone()), ..budget(100, None, None) };
        let rules = StopRules::of_budget(&b, Some(5), Instant::now());
        let mut counter = Counter { iteration: 0, evaluations: 0, per_step: 1, better_every: 1 };
        assert_eq!(execute(&mut counter, &rules, &mut Observers::none()).unwrap().iterations, 5);
        flag.raise();
        let mut counter = Counter { iteration: 0, evaluations: 0, per_step: 1, better_every: 1 };
        let finish = execute(&mut counter, &rules, &mut Observers::none()).unwrap();
        assert_eq!((finish.iterations, finish.stop), (0, StopReason::Interrupted));
    }

    /// The executor's judgement of "better" (the one the stall count reads) is what a
    /// new-best observer takes records by; an every-n observer takes iteration 0, n, 2n, ….
    #[test]
    fn observers_take_records_by_their_mode() {
        let rules = StopRules::of_budget(&budget(9, None, None), None, Instant::now());
        // (better every, mode, iterations recorded)
        let cases: [(u32, ObserverMode, &[u32]); 4] = [
            (3, ObserverMode::NewBest, &[0, 3, 6, 9]),
            (100, ObserverMode::NewBest, &[0]),
            (1, ObserverMode::Every(4), &[0, 4, 8]),
            (1, ObserverMode::Always, &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]),
        ];
        for (better_every, mode, want) in cases {
            let mut counter = Counter { iteration: 0, evaluations: 0, per_step: 1, better_every };
            let (finish, reports) = run(&mut counter, &rules, mode);
            assert_eq!(finish.iterations, 9);
            assert_eq!(reports.iter().map(|r| r.0).collect::<Vec<_>>(), want, "{mode:?}, better every {better_every}");
        }
    }

    #[test]
    fn rules_combine_with_or_in_order() {
        let rules = StopRules::default() | StopRule::Evaluations(5) | StopRule::Iterations(5);
        let at = Progress { iteration: 5, evaluations: 5, since_better: 0 };
        assert_eq!(rules.first_met(&at), Some(StopReason::Evaluations));
        let clock = StopRule::WallClock { limit: Duration::ZERO, since: Instant::now() };
        assert_eq!((StopRules::default() | clock).first_met(&at), Some(StopReason::WallClock));
        assert_eq!(StopRules::default().first_met(&at), None);
    }
}
