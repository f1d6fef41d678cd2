//! The `covga` command line. The only place that prints for humans.

pub(crate) mod eval;
mod grid;
mod gtsp;
mod init;
mod maps;
mod migrate;
mod reference;
mod run;
mod signals;

use clap::{Parser, Subcommand};
use std::ffi::OsString;

/// Failure of a command: bad input (exit code 2) or an internal error (exit code 1).
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The user's input is wrong; the message says what is allowed.
    #[error("{0}")]
    Input(String),
    /// Something failed that is not the user's input (a file could not be written, …).
    #[error("{0}")]
    Internal(String),
    /// A signal (SIGINT, SIGTERM) stopped the command; what it wrote was removed.
    #[error("{0}")]
    Interrupted(String),
    /// The command line did not parse, or asked for help or the version: clap's own text,
    /// which the caller prints with [`CliError::print`] (help and version on stdout).
    #[error("{0}")]
    Usage(#[from] clap::Error),
}

impl CliError {
    /// Process exit code: 2 for bad input (a usage error included), 1 for an internal
    /// failure, 130 for a run a signal stopped, 0 for help and the version.
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Input(_) => 2,
            CliError::Internal(_) => 1,
            // As a shell reports a process ended by SIGINT.
            CliError::Interrupted(_) => 130,
            CliError::Usage(e) if e.use_stderr() => 2,
            CliError::Usage(_) => 0,
        }
    }

    /// Prints the error as the command line shows it: `error: …` on stderr, or clap's usage
    /// error, help or version text where clap sends it.
    pub fn print(&self) {
        match self {
            CliError::Usage(e) => {
                let _ = e.print();
            }
            CliError::Input(_) | CliError::Internal(_) | CliError::Interrupted(_) => eprintln!("error: {self}"),
        }
    }
    /// Wraps any displayable error as bad input.
    pub fn input(e: impl std::fmt::Display) -> Self {
        CliError::Input(e.to_string())
    }
    /// Wraps any displayable error as an internal failure.
    pub fn internal(e: impl std::fmt::Display) -> Self {
        CliError::Internal(e.to_string())
    }
}

impl From<crate::usecase::UseCaseError> for CliError {
    fn from(e: crate::usecase::UseCaseError) -> Self {
        match e {
            crate::usecase::UseCaseError::Input(m) => CliError::Input(m),
            crate::usecase::UseCaseError::Internal(m) => CliError::Internal(m),
            crate::usecase::UseCaseError::Interrupted(m) => CliError::Interrupted(m),
        }
    }
}

#[derive(Parser, Debug)]
#[command(name = "covga", version, about = "Coverage path planning with genetic algorithms")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run one experiment (TOML); without a file, the built-in thesis map 1 Elite run.
    Run(run::RunArgs),
    /// Score a pattern or a path file on a map: every metric, plus path.png / path.svg.
    Eval(eval::EvalArgs),
    /// Run a grid study (parallel, resumable, shardable), estimate it, or write a Slurm array.
    Grid(grid::GridArgs),
    /// Merge the shard outputs of a study into runs.csv.
    Merge(grid::MergeArgs),
    /// Figures, tables and statistics of a study folder (report/summary.md).
    Report(grid::ReportArgs),
    /// Write the recommended experiment file for a floor plan (map, start, robot), commented.
    Init(init::InitArgs),
    /// Write the built-in maps as ROS map_server files (YAML + PGM).
    Maps(maps::MapsArgs),
    /// Rewrite experiment and grid files to the current key names (keys that moved section).
    Migrate(migrate::MigrateArgs),
    /// Write a reference page of the book: every key of an experiment file, every command, or every
    /// output file and column.
    Reference(reference::ReferenceArgs),
    /// Write a cell-order experiment's tour problem as a GTSPLIB instance (for an established
    /// GTSP solver to check the searches against).
    Gtsp(gtsp::GtspArgs),
}

/// Parses `args` and runs the command.
pub fn run<I, T>(args: I) -> Result<(), CliError>
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    // Help and version come back as `Usage` errors with exit code 0, for `main` to print.
    let cli = Cli::try_parse_from(args)?;
    match cli.command {
        Command::Run(a) => run::run(a),
        Command::Eval(a) => eval::run(a),
        Command::Grid(a) => grid::run(a),
        Command::Merge(a) => grid::merge(a),
        Command::Report(a) => grid::report(a),
        Command::Init(a) => init::run(a),
        Command::Maps(a) => maps::run(a),
        Command::Migrate(a) => migrate::run(a),
        Command::Reference(a) => reference::run(a),
        Command::Gtsp(a) => gtsp::run(a),
    }
}

/// Parses `X,Y` in metres.
pub(crate) fn parse_point(s: &str) -> Result<crate::geom::Point, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    match parts[..] {
        [x, y] => match (x.parse::<f64>(), y.parse::<f64>()) {
            (Ok(x), Ok(y)) if x.is_finite() && y.is_finite() => Ok(crate::geom::Point::new(x, y)),
            _ => Err(format!("`{s}` is not X,Y with finite numbers in metres")),
        },
        _ => Err(format!("`{s}` is not X,Y in metres (two numbers separated by a comma)")),
    }
}

/// A progress bar on stderr counting `unit` (runs, iterations), drawn only when `show`.
pub(crate) fn progress_bar(len: u64, unit: &str, show: bool) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(len);
    if show {
        let template =
            format!("{{elapsed_precise}} [{{bar:30}}] {{pos}}/{{len}} {unit} {{per_sec}} eta {{eta}} {{msg}}");
        bar.set_style(
            indicatif::ProgressStyle::with_template(&template).expect("valid template").progress_chars("=> "),
        );
    } else {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    bar
}
