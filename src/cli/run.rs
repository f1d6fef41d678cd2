//! `covga run`: one experiment, with a progress bar on a terminal.

use super::CliError;
use crate::experiment::output::Summary;
use crate::fleet::planner::FleetPlanner;
use crate::ga::observer::{GenerationRecord, Observer};
use crate::usecase::run::{ExperimentText, Prepared, prepare, run_in_folder};
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

/// Runs `covga run` with its parsed arguments.
pub fn run(a: RunArgs) -> Result<(), CliError> {
    let source = match &a.file {
        Some(path) => ExperimentText::read(path)?,
        None => ExperimentText {
            text: DEFAULT_EXPERIMENT.to_string(),
            origin: "built-in experiment thesis-map1-elite".into(),
            stem: "thesis-map1-elite".into(),
        },
    };
    let mut prepared = prepare(&source, a.seed, a.max_memory)?;
    let interrupt = crate::planner::executor::Interrupt::new();
    prepared.experiment.budget.interrupt = Some(interrupt.clone());
    let watch = super::signals::SignalWatch::start(interrupt);
    for w in &prepared.warnings {
        eprintln!("warning: {w}");
    }
    let exp = &prepared.experiment;
    let origin = &prepared.origin;
    let show = !a.quiet && std::io::stderr().is_terminal();
    let length = exp.planner.progress_length(&exp.budget);
    let mut progress = Progress(super::progress_bar(length, "it", show));
    let ran = run_in_folder(&prepared, a.out.as_deref(), true, &mut [&mut progress]);
    drop(watch);
    progress.0.finish_and_clear();
    let (summary, dir) = ran?;
    for w in summary.warnings.iter().cloned().chain(missed_goal(&summary.details, summary.score.cov_final_reach)) {
        eprintln!("warning: {origin}: {w}");
    }
    if !a.quiet {
        print_summary(&prepared, &summary, &dir);
    }
    Ok(())
}

/// The warning for a coverage goal (`coverage_goal` among the planner's `details`, as
/// `cell_order.coverage_goal` records it) that the scored plan does not reach: `reached`, its
/// share of the reachable cells, is below the goal.
fn missed_goal(details: &serde_json::Map<String, serde_json::Value>, reached: f64) -> Option<String> {
    let goal = details.get("coverage_goal")?.as_f64()?;
    (reached < goal).then(|| {
        format!(
            "the plan covers {reached:.4} of the reachable cells, short of its coverage goal \
             (cell_order.coverage_goal = {goal})"
        )
    })
}

/// The line that says the cell-order search returned the classical control's plan rather than
/// its own (`classical_chosen` among the planner's `details`: with `classical_finalists`, the
/// classical plans stand among the search's finalists, and one of them reached the goal first).
fn classical_chosen(details: &serde_json::Map<String, serde_json::Value>) -> Option<String> {
    details.get("classical_chosen").and_then(serde_json::Value::as_bool).filter(|&c| c).map(|_| {
        "plan chosen: the classical control's (boustrophedon sweeps), faster to the goal than the search's \
         own plan (cell_order.classical_finalists = true)"
            .to_string()
    })
}

/// The run's summary as `covga run` prints it.
fn print_summary(prepared: &Prepared, summary: &Summary, dir: &std::path::Path) {
    let (exp, origin) = (&prepared.experiment, &prepared.origin);
    {
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
        if exp.planner.downcast_ref::<FleetPlanner>().is_none() {
            println!(
                "common score: cov_final {:.4} (reachable {:.4})  t_final {:.4}  camera walls {:.4}  length {:.1} m  time {:.0} s",
                s.cov_final_free, s.cov_final_reach, s.t_final, s.cam_walls_free, s.length_m, s.time_s
            );
        }
        match summary.fleet.as_ref().filter(|_| exp.planner.downcast_ref::<FleetPlanner>().is_some()) {
            // A fleet's robots each drive at their own speeds: each one's time model is named.
            Some(f) => {
                println!("robots (each with its own time model):");
                for (name, model) in f.robots.iter().zip(&f.robot_time_model) {
                    println!("  {name}: {model}");
                }
            }
            None => println!("robot: {}", summary.time_model),
        }
        if let Some(line) = classical_chosen(&summary.details) {
            println!("{line}");
        }
        if s.executable {
            println!("executable: yes");
        } else {
            println!("executable: NO ({})", s.not_executable_why());
        }
        if summary.planner_feasible {
            println!("planner constraints: met");
        } else {
            println!("planner constraints: NOT met ({})", summary.violations.join("; "));
        }
        println!("wrote {}", dir.display());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_coverage_goal_the_plan_misses_is_warned_about() {
        let details = serde_json::json!({"coverage_goal": 0.9}).as_object().cloned().unwrap();
        let warning = missed_goal(&details, 0.848).expect("a warning");
        assert!(warning.contains("0.8480") && warning.contains("cell_order.coverage_goal = 0.9"), "{warning}");
        assert_eq!(missed_goal(&details, 0.9), None);
        assert_eq!(missed_goal(&serde_json::Map::new(), 0.1), None);
    }

    #[test]
    fn a_classical_plan_chosen_over_the_search_is_said() {
        let details = serde_json::json!({"classical_chosen": true}).as_object().cloned().unwrap();
        let line = classical_chosen(&details).expect("a line");
        assert!(line.contains("classical control") && line.contains("classical_finalists"), "{line}");
        assert_eq!(classical_chosen(&serde_json::Map::new()), None, "the search's own plan says nothing");
    }
}
