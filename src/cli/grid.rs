//! `covga grid` (run, dry-run, Slurm script) and `covga merge`.

use super::CliError;
use crate::study::estimate::{self, human};
use crate::study::grid::Study;
use crate::study::order::{self, RunOrder};
use crate::study::runner::{RunDone, RunnerOptions, Shard, run_study};
use crate::study::slurm::{SlurmOptions, check_time, sbatch_script};
use clap::ValueEnum;
use std::io::IsTerminal;
use std::path::PathBuf;

/// Arguments of `covga grid`.
#[derive(clap::Args, Debug)]
pub struct GridArgs {
    /// Grid file (TOML).
    file: PathBuf,
    /// Runs in parallel (at most the number of runs: more would idle).
    #[arg(long, default_value_t = 1)]
    jobs: usize,
    /// Run only shard K of N (0 <= K < N): every N-th run in sorted id order. Not with
    /// --slurm, whose array tasks are the shards.
    #[arg(long, conflicts_with = "slurm")]
    shard: Option<String>,
    /// Study folder (default out/<grid stem>).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the runs per branch and a time estimate; run nothing.
    #[arg(long)]
    dry_run: bool,
    /// With --dry-run: time full-length runs sampled per branch until the mean run time is known to 8 %.
    #[arg(long, requires = "dry_run")]
    calibrate: bool,
    /// The order runs start in: longest-first (by the times recorded in the study folder or
    /// its calibration, else by budget times the map's free cells) leaves fewer cores idle at the end;
    /// seeds runs replicate by replicate. Results are the same in either order.
    #[arg(long, value_enum, default_value_t = RunOrder::LongestFirst)]
    order: RunOrder,
    /// Run again the runs recorded as failed (after fixing what made them fail); without it a
    /// resume keeps their rows and runs them no more.
    #[arg(long)]
    retry_failed: bool,
    /// Crash tests only: abort like a killed process after N runs are recorded.
    #[arg(long, hide = true, value_name = "N")]
    abort_after_runs: Option<usize>,
    /// Write study.sbatch (a Slurm job array over shards) instead of running.
    #[arg(long)]
    slurm: bool,
    /// Slurm array tasks (shards).
    #[arg(long, default_value_t = 16)]
    array_size: usize,
    /// Slurm time limit per task, HH:MM:SS.
    #[arg(long, default_value = "04:00:00")]
    time: String,
    /// CPUs per Slurm task (each shard runs that many runs at once).
    #[arg(long, default_value_t = 1)]
    cpus_per_task: usize,
    /// Memory the runs may use at once (8G, 512M, 2GiB; default: the memory available); runs
    /// that would need more are refused before anything is allocated.
    #[arg(long, value_parser = crate::io::parse_bytes)]
    max_memory: Option<u64>,
}

/// Arguments of `covga merge`.
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// Study folder holding runs-shard-*.csv files.
    dir: PathBuf,
    /// Merge what is there even when shards or runs are missing (and say what is missing).
    #[arg(long)]
    allow_partial: bool,
}

/// One finished run as `covga grid` shows it: the progress bar on a terminal, else one line
/// on stderr (a failure with its reason).
fn show_run_done(bar: &indicatif::ProgressBar, terminal: bool, d: RunDone) {
    let count = format!("[{}/{}] {} replicate {}", d.done + d.skipped, d.total + d.skipped, d.run.id, d.run.replicate);
    if terminal {
        bar.set_length(d.total as u64);
        bar.set_position(d.done as u64);
        bar.set_message(format!("last cov_final_reach {:.3} t_final {:.3}", d.result.0, d.result.1));
    } else if let Some(why) = d.failure {
        eprintln!("{count} failed: {why}");
    } else {
        // The common scorer's coverage of the reachable cells, named as runs.csv names it.
        eprintln!("{count} cov_final_reach {:.4} t_final {:.4} {:.2} s", d.result.0, d.result.1, d.result.2);
    }
}

/// Runs `covga grid`: a study, its dry run, or its Slurm script.
pub fn run(a: GridArgs) -> Result<(), CliError> {
    let study = Study::load(&a.file).map_err(CliError::input)?;
    for w in &study.warnings {
        eprintln!("warning: {w}");
    }
    if a.jobs == 0 {
        return Err(CliError::Input("--jobs = 0 is out of range: at least 1".into()));
    }
    let shard = a.shard.as_deref().map(Shard::parse).transpose().map_err(CliError::Input)?;
    let stem = a.file.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "study".into());
    let out = a.out.clone().unwrap_or_else(|| PathBuf::from("out").join(&stem));
    let all: Vec<&crate::study::grid::RunSpec> = study.runs.iter().collect();
    // A Slurm script runs on other machines: their memory is checked there, by each shard.
    let (limit, parallel) = if a.slurm {
        (a.max_memory.and_then(|given| crate::experiment::memory::memory_limit(Some(given))), a.cpus_per_task)
    } else {
        (crate::experiment::memory::memory_limit(a.max_memory), a.jobs.min(all.len().max(1)))
    };
    // A dry run answers at once: it checks keys, ranges, maps and stations, and plans nothing
    // (a pattern seed's plan, the exact solver's cell count wait for the run).
    let checks = if a.dry_run { crate::planner::Checks::KeysOnly } else { crate::planner::Checks::Full };
    let largest_run_bytes = crate::study::runner::validate_runs(
        &study,
        &all,
        &crate::study::runner::MapCache::default(),
        limit.as_ref(),
        parallel,
        checks,
    )
    .map_err(CliError::input)?;
    if a.dry_run {
        return dry_run(&study, &a, &out);
    }
    if a.slurm {
        return write_slurm(&a, &out, &stem, largest_run_bytes, all.len());
    }
    let terminal = std::io::stderr().is_terminal();
    let bar = super::progress_bar(0, "runs", terminal);
    let on_done = |d: RunDone| show_run_done(&bar, terminal, d);
    let opts = RunnerOptions {
        jobs: a.jobs,
        shard,
        out: out.clone(),
        max_memory: a.max_memory,
        on_done: &on_done,
        stop: None,
        order: a.order,
        abort_after_runs: a.abort_after_runs,
        retry_failed: a.retry_failed,
    };
    let outcome = run_study(&study, &opts).map_err(|e| match e {
        crate::study::runner::StudyError::Config(c) => CliError::input(c),
        crate::study::runner::StudyError::Mismatch { .. } | crate::study::runner::StudyError::Folder { .. } => {
            CliError::input(e)
        }
        other => CliError::internal(other),
    })?;
    bar.finish_and_clear();
    println!(
        "{}: {} runs{}: {} already recorded, {} run now; results in {}",
        a.file.display(),
        outcome.selected,
        shard.map(|s| format!(" in shard {}/{}", s.index, s.count)).unwrap_or_default(),
        outcome.skipped,
        outcome.completed,
        out.display()
    );
    match outcome.first_failure {
        // The other runs are recorded; the exit status still says that not all could run.
        Some((id, why)) => Err(CliError::Input(format!(
            "{}: {} of {} runs failed while running and are recorded as such (stop = failed, the reason in \
             violations); the first, run {id}: {why}",
            out.join(shard.map_or("runs.csv".to_string(), |s| s.file_name())).display(),
            outcome.failed,
            outcome.selected
        ))),
        None => Ok(()),
    }
}

fn dry_run(study: &Study, a: &GridArgs, out: &std::path::Path) -> Result<(), CliError> {
    let configs = study.runs.iter().map(|r| &r.config_id).collect::<std::collections::HashSet<_>>().len();
    println!("{}: {} runs ({} configurations x replicates)", study.path.display(), study.runs.len(), configs);
    println!("  checked: keys, ranges, maps, stations and memory; seed plans and cell counts are checked when it runs");
    for (branch, n) in study.branches() {
        println!("  {n:>7} runs  {branch}");
    }
    let times = if a.calibrate {
        let times = estimate::calibrate(study).map_err(CliError::internal)?;
        // Kept in the study folder for `--order longest-first` (the folder must hold this
        // study or none, as for a run).
        crate::study::runner::check_identity(study, out).map_err(CliError::input)?;
        let file = out.join(order::CALIBRATION_FILE);
        std::fs::create_dir_all(out)
            .and_then(|()| crate::io::write_atomic(&file, order::calibration_csv(&times).as_bytes()))
            .map_err(|e| CliError::Internal(format!("{}: {e}", file.display())))?;
        crate::study::runner::write_study_files(study, out).map_err(CliError::internal)?;
        println!("calibration written to {}", file.display());
        Some((times, "calibrated on full-length runs sampled at random per branch"))
    } else {
        estimate::from_records(study, out).map(|t| (t, "from runs recorded in the study folder")).or_else(|| {
            let calibrated = order::read_calibration(&out.join(order::CALIBRATION_FILE));
            (!calibrated.is_empty()).then_some((calibrated, "from the calibration in the study folder"))
        })
    };
    match times {
        None => println!("estimate: none yet (add --calibrate, or run a few runs first)"),
        Some((times, source)) => {
            println!("estimate ({source}, one core per run):");
            for b in &times {
                println!(
                    "  {:>8.2} s per run  x {:>6}  {}  ({} runs timed)",
                    b.seconds_per_run, b.runs, b.branch, b.samples
                );
            }
            println!(
                "  CPU time {}; wall time with --jobs {} in --order {}: {}",
                human(estimate::cpu_seconds(&times)),
                a.jobs,
                a.order.to_possible_value().map_or_else(String::new, |v| v.get_name().to_string()),
                human(estimate::scheduled_wall_seconds(study, &times, a.jobs, a.order))
            );
        }
    }
    Ok(())
}

/// Slurm's default `MaxArraySize`: array indices run from 0 to one less.
const SLURM_MAX_ARRAY_SIZE: usize = 1001;

fn write_slurm(
    a: &GridArgs,
    out: &std::path::Path,
    stem: &str,
    largest_run_bytes: f64,
    runs: usize,
) -> Result<(), CliError> {
    check_time(&a.time).map_err(CliError::Input)?;
    if a.array_size == 0 || a.cpus_per_task == 0 {
        return Err(CliError::Input("--array-size and --cpus-per-task must be at least 1".into()));
    }
    // A task beyond the number of runs would get an empty shard.
    let array_size = a.array_size.min(runs.max(1));
    if array_size < a.array_size {
        eprintln!("note: --array-size {} clamped to the study's {runs} runs (one task per run at most)", a.array_size);
    }
    if array_size > SLURM_MAX_ARRAY_SIZE {
        eprintln!(
            "warning: --array-size {array_size} asks for --array=0-{}, beyond Slurm's default MaxArraySize of {SLURM_MAX_ARRAY_SIZE} \
             (tasks 0-{}); sbatch refuses it unless the cluster raised the limit (scontrol show config | grep MaxArraySize)",
            array_size - 1,
            SLURM_MAX_ARRAY_SIZE - 1
        );
    }
    let abs =
        |p: &std::path::Path| std::path::absolute(p).map_err(|e| CliError::Internal(format!("{}: {e}", p.display())));
    let exe = std::env::current_exe().map_err(CliError::internal)?;
    let (grid, out_abs) = (abs(&a.file)?, abs(out)?);
    std::fs::create_dir_all(out_abs.join("slurm"))
        .map_err(|e| CliError::Internal(format!("{}: {e}", out_abs.display())))?;
    let opts = SlurmOptions {
        array_size,
        time: a.time.clone(),
        cpus_per_task: a.cpus_per_task,
        mem_bytes: a.max_memory.unwrap_or_else(|| task_memory(largest_run_bytes, a.cpus_per_task)),
    };
    let dir = std::env::current_dir().map_err(CliError::internal)?;
    let paths = crate::study::slurm::TaskPaths { exe: &exe, grid: &grid, out: &out_abs, dir: &dir };
    let script = sbatch_script(paths, stem, &opts);
    let path = out_abs.join("study.sbatch");
    crate::io::write_atomic(&path, script.as_bytes()).map_err(CliError::internal)?;
    println!("wrote {}", path.display());
    println!("submit:  sbatch {}", path.display());
    println!("then:    covga merge {}", out_abs.display());
    Ok(())
}

/// The memory to request per array task: the largest run's estimate for each CPU, a quarter
/// more for what the estimate leaves out, at least 512 MiB, in whole MiB.
fn task_memory(largest_run_bytes: f64, cpus: usize) -> u64 {
    const MIB: f64 = 1024.0 * 1024.0;
    let bytes = (1.25 * largest_run_bytes * cpus as f64).max(512.0 * MIB);
    ((bytes / MIB).ceil() * MIB) as u64
}

pub fn merge(a: MergeArgs) -> Result<(), CliError> {
    let (files, runs, missing) = crate::study::merge::merge(&a.dir, a.allow_partial).map_err(CliError::input)?;
    println!("merged {files} files into {} ({runs} runs)", a.dir.join("runs.csv").display());
    if !missing.is_empty() {
        eprintln!("warning: partial merge, missing {}", missing.join(", "));
    }
    Ok(())
}

/// Arguments of `covga report`.
#[derive(clap::Args, Debug)]
pub struct ReportArgs {
    /// Study folder (with runs.csv).
    dir: PathBuf,
    /// Group (facet) by these columns, e.g. --by thesis.selection --by scorer.projection.
    #[arg(long)]
    by: Vec<String>,
    /// Only the runs whose column has this value, e.g. --where map.source=thesis-1 --where
    /// robot.rot_speed=0 (numbers compare as numbers). Repeatable: different keys must all
    /// hold, one key given twice keeps the runs with either value.
    #[arg(long = "where", value_name = "KEY=VALUE")]
    filter: Vec<String>,
    /// Write into `<DIR>/report-NAME` instead of `<DIR>/report`, so that several reports of one
    /// study (e.g. one per figure of 003) stand side by side.
    #[arg(long)]
    name: Option<String>,
    /// An earlier `runs.csv` of the same study (e.g. the committed one before a re-run): also
    /// write `rescore.md`, what the re-run changed (executable plans per planner and map, the
    /// columns that moved), into the report folder.
    #[arg(long, value_name = "RUNS_CSV")]
    previous: Option<PathBuf>,
    /// Compare every other value of a swept parameter with BASELINE, within each combination of
    /// the other parameters, runs paired by seed, executable plans only (coverage and mission
    /// time; bootstrap intervals, Wilcoxon signed-rank tests, Holm-corrected): writes
    /// `compare-KEY.md` and `.csv` into the report folder (`compare-KEY-BASELINE.*` where one
    /// key is compared with several baselines). Repeatable.
    #[arg(long, value_name = "KEY=BASELINE")]
    compare: Vec<String>,
    /// As --compare, over every plan, executable or not (what the planner optimised, whether a
    /// robot can drive its plan or not): writes `compare-KEY-every-plan.md` and `.csv`.
    /// Repeatable.
    #[arg(long, value_name = "KEY=BASELINE")]
    compare_every_plan: Vec<String>,
    /// With --compare: also write `design-KEY.md`, what each comparison's design can show (each
    /// family's smallest p after its correction) and how many seeds, strata or floor plans it
    /// needs to show an effect of a given size, from the runs the study has (a pilot's will do).
    #[arg(long)]
    design: bool,
    /// Also write `anova-condensed.md`: each analysis of variance's main effects, three largest
    /// interactions and residual, its rows as in `summary.md`.
    #[arg(long)]
    anova_condensed: bool,
    /// Also write `plans.md` and `plans.csv`: every configuration's plans (executable, coverage,
    /// time) and its runs' final populations (the hypervolume of each run's final population,
    /// the best coverage of its initial one, whether a seeded run kept within its seed bound),
    /// with findings in words. Where the run folders are gone, the `plans.csv` of the report
    /// folder is read back.
    #[arg(long)]
    plans: bool,
    /// With --plans: a runs.csv of one plan per `map.source` (e.g. the boustrophedon plans a
    /// study's GA was seeded with) to set every run against: `plans.md` gains a table of each
    /// run against its map's reference plan and findings per factor value.
    #[arg(long, value_name = "RUNS_CSV", requires = "plans")]
    reference: Option<PathBuf>,
    /// Also write `seed-to-seed.md`: the Spearman correlation of the configurations' f,
    /// coverage and t_final between replicates, where each replicate's best configurations rank
    /// in the others, infeasible and non-executable runs per replicate and --by group, and, on
    /// the thesis maps, 003 Tables A.1/A.2 beside the same cells of the study.
    #[arg(long)]
    seed_to_seed: bool,
    /// Also write `measures.md` and `measures.csv`: this figure per --by group (numbers as
    /// median [min, max], yes/no figures as counts), read from the runs.csv column of that name,
    /// else `history.COLUMN@ITERATION` (the run's history.csv at that iteration), else a dotted
    /// path into each run's summary.json (e.g. objectives.wall_coverage). Where the run folders
    /// are gone, the `measures.csv` of the report folder is read back. Repeatable.
    #[arg(long, value_name = "KEY")]
    measure: Vec<String>,
}

pub fn report(a: ReportArgs) -> Result<(), CliError> {
    let mut filter = Vec::new();
    for f in &a.filter {
        let Some((k, v)) = f.split_once('=') else {
            return Err(CliError::Input(format!("--where {f}: expected KEY=VALUE, e.g. map.source=thesis-1")));
        };
        filter.push((k.trim().to_string(), v.trim().to_string()));
    }
    let comparisons = a
        .compare
        .iter()
        .map(|c| crate::report::compare::Comparison::parse(c))
        .chain(a.compare_every_plan.iter().map(|c| crate::report::compare::Comparison::parse_every_plan(c)))
        .collect::<Result<Vec<_>, _>>()
        .map_err(CliError::Input)?;
    let input = |e| match e {
        crate::report::ReportError::Input(m) => CliError::Input(m),
        other => CliError::internal(other),
    };
    // Comparisons are made before anything is written, so that one that cannot be made leaves
    // no half-written report.
    if a.design && comparisons.is_empty() {
        return Err(CliError::Input("--design: tells what a comparison can show; name one with --compare".into()));
    }
    let out = crate::report::analysis::study::report_folder(&a.dir, a.name.as_deref()).map_err(input)?;
    let rendered = crate::report::compare::render_all(&a.dir, &filter, &comparisons, &out).map_err(input)?;
    let opts = crate::report::ReportOptions {
        by: a.by,
        filter,
        name: a.name,
        anova_condensed: a.anova_condensed,
        plans: a.plans,
        reference: a.reference,
        seed_to_seed: a.seed_to_seed,
        measures: a.measure,
    };
    let path = crate::report::write_report_with(&a.dir, &opts).map_err(|e| match e {
        crate::report::ReportError::Input(m) => CliError::Input(m),
        other => CliError::internal(other),
    })?;
    println!("wrote {} and the figures beside it", path.display());
    if let Some(previous) = &a.previous {
        let folder = path.parent().unwrap_or(&a.dir);
        let file = crate::report::tables::rescore::write(&a.dir, previous, folder).map_err(|e| match e {
            crate::report::ReportError::Input(m) => CliError::Input(m),
            other => CliError::internal(other),
        })?;
        println!("wrote {}", file.display());
    }
    let folder = path.parent().unwrap_or(&a.dir);
    if opts.plans {
        println!("wrote {}", folder.join("plans.md").display());
    }
    if opts.seed_to_seed {
        println!("wrote {}", folder.join("seed-to-seed.md").display());
    }
    if !opts.measures.is_empty() {
        println!("wrote {}", folder.join("measures.md").display());
    }
    for r in &rendered {
        println!("wrote {}", r.save(folder).map_err(input)?.display());
        if a.design
            && let Some(path) = r.save_design(folder).map_err(input)?
        {
            println!("wrote {}", path.display());
        }
    }
    Ok(())
}
