//! `runs.csv`: one tidy row per finished run — id, replicate, seed, every swept parameter as
//! its own column named by its dotted key, then the final metrics and timing.

use super::grid::RunSpec;
use crate::experiment::output::Summary;
use std::collections::BTreeMap;

/// Columns before the swept parameters.
pub const ID_COLUMNS: [&str; 4] = ["run_id", "config_id", "replicate", "seed"];
/// Columns after the swept parameters and before the scorer's: which planner on which map,
/// and whether its plan meets the planner's own constraints (executability is the scorer's).
pub const RUN_COLUMNS: [&str; 4] = ["planner", "map", "planner_feasible", "violations"];
/// Columns after the scorer's: effort and timing.
pub const EFFORT_COLUMNS: [&str; 4] = ["evaluations", "iterations", "stop", "wall_s"];
/// Columns of a fleet's plan (two agents or more; empty for a single robot): the fleet's
/// label, robot count and the fleet metrics of [`crate::fleet::metrics::FleetScore`].
pub const FLEET_COLUMNS: [&str; 12] = [
    "fleet_name",
    "fleet_robots",
    "union_free",
    "union_reach",
    "overlap_fraction",
    "fleet_makespan_s",
    "balance",
    "fleet_cov_final",
    "fleet_t_final",
    "negotiation_rounds",
    "negotiation_settled",
    "negotiation_last_change",
];
/// What the columns of `runs.csv` other than the common scorer's hold (those are documented on
/// [`crate::coverage::score::Score`]'s fields).
const COLUMN_MEANINGS: [(&str, &str); 24] = [
    ("run_id", "the run's id: a hash of its written configuration and its replicate"),
    ("config_id", "the configuration's id: the same for every replicate of a configuration"),
    ("replicate", "the replicate's number, from 0"),
    ("seed", "the run's seed, derived from the study's seed and the replicate"),
    ("planner", "the planner that made the plan (`fleet-…` for a fleet's method)"),
    ("map", "the map's name"),
    ("planner_feasible", "whether the plan meets the planner's own constraints (the waypoint planner's)"),
    ("violations", "the planner's constraints the plan violates, in words"),
    ("evaluations", "fitness evaluations spent"),
    ("iterations", "iterations (generations) completed"),
    ("stop", "why the run stopped: the budget's rule that ended it, or the planner's own"),
    ("wall_s", "wall-clock seconds of the run (the one column that differs between identical runs)"),
    ("fleet_name", "the fleet's label (`fleet.name`)"),
    ("fleet_robots", "robots in the fleet"),
    ("union_free", "free cells swept by any robot over all free cells"),
    ("union_reach", "swept cells some robot can reach over the cells the robots can reach"),
    ("overlap_fraction", "cells swept by two robots or more over the union"),
    ("fleet_makespan_s", "the slowest robot's time in seconds"),
    ("balance", "the slowest robot's time over the fastest's"),
    ("fleet_cov_final", "003 eq. 3.10 over the union of the robots' sweeps"),
    (
        "fleet_t_final",
        "003's `t_final` for the fleet: the covered area over the fleet's summed rate against its makespan",
    ),
    ("negotiation_rounds", "rounds of plan exchange (negotiation)"),
    ("negotiation_settled", "whether the negotiation's plans settled"),
    ("negotiation_last_change", "the share of swept cells the last round changed (negotiation)"),
];

/// What column `name` holds, for the id, run, effort and fleet columns.
pub fn column_meaning(name: &str) -> Option<&'static str> {
    COLUMN_MEANINGS.iter().find(|(c, _)| *c == name).map(|(_, m)| *m)
}

/// Columns that measure time and so differ between otherwise identical runs.
pub const TIMING_COLUMNS: [&str; 1] = ["wall_s"];

/// What a column of `runs.csv` holds, whatever values a study happens to have (a float column
/// whose values are all whole still holds floats): what a reader types it as. Any column may
/// be empty in a row (a failed run's metrics, a single robot's fleet columns).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColumnKind {
    /// Whole numbers (counts).
    Integer,
    /// Whole numbers that may exceed a signed 64-bit integer (seeds).
    Unsigned,
    /// Real numbers.
    Float,
    /// `true` or `false`.
    Flag,
    /// Text: ids, names, messages.
    Text,
}

impl ColumnKind {
    /// The kind's name as the Python package reads it.
    pub fn name(self) -> &'static str {
        match self {
            ColumnKind::Integer => "integer",
            ColumnKind::Unsigned => "unsigned",
            ColumnKind::Float => "float",
            ColumnKind::Flag => "flag",
            ColumnKind::Text => "text",
        }
    }
}

/// Columns of whole numbers among the id and metric columns.
const INTEGER_COLUMNS: [&str; 16] = [
    "replicate",
    "agents",
    "unique_cells",
    "unique_reach_cells",
    "cells_swept",
    "crossings",
    "obstacle_cells",
    "obstacle_sweeps",
    "free_cells",
    "reachable_cells",
    "pocket_cells",
    "turns",
    "evaluations",
    "iterations",
    "fleet_robots",
    "negotiation_rounds",
];
/// Flag columns among the id and metric columns.
const FLAG_COLUMNS: [&str; 3] = ["executable", "planner_feasible", "negotiation_settled"];
/// Text columns among the id and metric columns.
const TEXT_COLUMNS: [&str; 7] = ["run_id", "config_id", "planner", "map", "violations", "stop", "fleet_name"];

/// The kind of an id or metric column of `runs.csv` (every other metric column is a float);
/// `None` for a swept key's column, whose kind is its key's.
pub fn column_kind(name: &str) -> Option<ColumnKind> {
    if name == "seed" {
        Some(ColumnKind::Unsigned)
    } else if INTEGER_COLUMNS.contains(&name) {
        Some(ColumnKind::Integer)
    } else if FLAG_COLUMNS.contains(&name) {
        Some(ColumnKind::Flag)
    } else if TEXT_COLUMNS.contains(&name) {
        Some(ColumnKind::Text)
    } else if ID_COLUMNS.contains(&name) || metric_columns().iter().any(|c| c == name) {
        Some(ColumnKind::Float)
    } else {
        None
    }
}

/// The metric columns of every run, whatever its planner: run columns, the common scorer's
/// ([`crate::coverage::score::Score::columns`]), effort, fleet.
pub fn metric_columns() -> Vec<String> {
    RUN_COLUMNS
        .iter()
        .copied()
        .chain(crate::coverage::score::Score::column_names())
        .chain(EFFORT_COLUMNS.iter().copied())
        .chain(FLEET_COLUMNS.iter().copied())
        .map(str::to_string)
        .collect()
}

/// Whether each of the swept keys `params` gets a column of its own: a key named like a
/// metric column (`planner`, swept to compare planners) has its value there already, and a
/// table with two columns of one name could not be read by name.
fn own_column(params: &[String]) -> Vec<bool> {
    let metrics = metric_columns();
    params.iter().map(|p| !metrics.contains(p)).collect()
}

/// The swept values of `run` that get a column of their own (see [`own_column`]).
fn param_fields(params: &[String], run: &RunSpec) -> Vec<String> {
    run.params
        .iter()
        .zip(own_column(params))
        .filter(|(_, own)| *own)
        .map(|(v, _)| v.clone().unwrap_or_default())
        .collect()
}

/// The header for a study with `params` swept keys.
pub fn header(params: &[String]) -> Vec<String> {
    let own = own_column(params);
    let params = params.iter().zip(own).filter(|(_, own)| *own).map(|(p, _)| p.clone());
    ID_COLUMNS.iter().map(|s| s.to_string()).chain(params).chain(metric_columns()).collect()
}

/// The row of a finished run of a study with `params` swept keys.
pub fn row(params: &[String], run: &RunSpec, summary: &Summary) -> Vec<String> {
    let mut out = vec![run.id.clone(), run.config_id.clone(), run.replicate.to_string(), run.file.seed.to_string()];
    out.extend(param_fields(params, run));
    out.extend([
        summary.planner.to_string(),
        run.file.map.source.clone(),
        summary.planner_feasible.to_string(),
        summary.violations.join("; "),
    ]);
    out.extend(summary.score.columns().into_iter().map(|(_, v)| v));
    let stop = serde_json::to_value(summary.stop).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default();
    out.extend([
        summary.evaluations.to_string(),
        summary.iterations.to_string(),
        stop,
        format!("{:.3}", summary.wall_s),
    ]);
    out.extend(fleet_fields(summary));
    out
}

/// The `stop` of a run that failed while running (a refusal only its planning could find,
/// such as more cells than the exact solver takes): its row says why in `violations` and
/// leaves every metric empty; `covga report` counts such rows and leaves them out.
pub const FAILED_STOP: &str = "failed";

/// The row of a run (of a study with `params` swept keys) that failed while running: `reason`
/// (one line) in `violations`, `stop` =
/// [`FAILED_STOP`], the metrics empty.
pub fn failed_row(params: &[String], run: &RunSpec, reason: &str, wall_s: f64) -> Vec<String> {
    let mut out = vec![run.id.clone(), run.config_id.clone(), run.replicate.to_string(), run.file.seed.to_string()];
    out.extend(param_fields(params, run));
    let reason = reason.split_whitespace().collect::<Vec<_>>().join(" ");
    out.extend([run.file.planner.name().to_string(), run.file.map.source.clone(), "false".to_string(), reason]);
    out.extend(crate::coverage::score::Score::column_names().into_iter().map(|_| String::new()));
    out.extend([String::new(), String::new(), FAILED_STOP.to_string(), format!("{wall_s:.3}")]);
    out.extend(std::iter::repeat_n(String::new(), FLEET_COLUMNS.len()));
    out
}

/// The [`FLEET_COLUMNS`] of a run (empty fields for a single robot's plan).
fn fleet_fields(summary: &Summary) -> Vec<String> {
    let Some(f) = &summary.fleet else { return vec![String::new(); FLEET_COLUMNS.len()] };
    let details = crate::fleet::details::FleetDetails::read(&summary.details);
    let num = |v: f64| format!("{v}");
    // Only a negotiation has rounds; other fleet methods leave the fields empty.
    let [rounds, settled, change] = details.negotiation.map(|n| n.fields()).unwrap_or_default();
    vec![
        details.fleet_name.unwrap_or_default(),
        f.robots.len().to_string(),
        num(f.union_free),
        num(f.union_reach),
        num(f.overlap_fraction),
        num(f.makespan_s),
        f.balance.map(num).unwrap_or_default(),
        num(f.cov_final),
        num(f.t_final),
        rounds,
        settled,
        change,
    ]
}

/// One CSV line (with its newline) for `fields`.
pub fn csv_line(fields: &[String]) -> Vec<u8> {
    let mut w = csv::WriterBuilder::new().from_writer(Vec::new());
    w.write_record(fields).expect("writing to memory");
    w.into_inner().expect("writing to memory")
}

/// A parsed `runs.csv`: header and rows keyed by column.
#[derive(Clone, Debug, Default)]
pub struct RunsTable {
    /// Column names.
    pub header: Vec<String>,
    /// Rows as field lists.
    pub rows: Vec<Vec<String>>,
}

impl RunsTable {
    /// Parses CSV text; a last line without its newline (a killed writer) is dropped.
    pub fn parse(text: &str) -> Result<Self, String> {
        let complete = match text.rfind('\n') {
            Some(end) => &text[..=end],
            None => "",
        };
        let mut r = csv::ReaderBuilder::new().from_reader(complete.as_bytes());
        let header: Vec<String> = r.headers().map_err(|e| e.to_string())?.iter().map(str::to_string).collect();
        let mut rows = Vec::new();
        for rec in r.records() {
            let rec = rec.map_err(|e| e.to_string())?;
            if rec.len() != header.len() {
                return Err(format!("a row has {} fields, the header {}", rec.len(), header.len()));
            }
            rows.push(rec.iter().map(str::to_string).collect());
        }
        Ok(Self { header, rows })
    }

    /// Index of a column. A renamed key finds its column under either name
    /// ([`crate::experiment::renamed`]): a study made before the rename keeps the old one.
    pub fn col(&self, name: &str) -> Option<usize> {
        let other = crate::experiment::renamed::old_key(name)
            .or_else(|| Some(crate::experiment::renamed::current_key(name)).filter(|k| *k != name));
        self.header
            .iter()
            .position(|h| h == name)
            .or_else(|| other.and_then(|o| self.header.iter().position(|h| h == o)))
    }

    /// Rows by run id.
    pub fn by_id(&self) -> BTreeMap<String, &Vec<String>> {
        let i = self.col("run_id").unwrap_or(0);
        self.rows.iter().map(|r| (r[i].clone(), r)).collect()
    }

    /// The whole table as CSV, rows sorted by run id.
    pub fn to_csv_sorted(&self) -> Vec<u8> {
        let mut out = csv_line(&self.header);
        for r in self.by_id().values() {
            out.extend(csv_line(r));
        }
        out
    }

    /// A row without its timing columns (for comparisons).
    pub fn without_timing(&self, row: &[String]) -> Vec<String> {
        row.iter()
            .zip(&self.header)
            .filter(|(_, h)| !TIMING_COLUMNS.contains(&h.as_str()))
            .map(|(v, _)| v.clone())
            .collect()
    }

    /// The rows of runs that failed while running ([`FAILED_STOP`]).
    pub fn failed_rows(&self) -> Vec<&Vec<String>> {
        let Some(stop) = self.col("stop") else { return Vec::new() };
        self.rows.iter().filter(|r| r[stop] == FAILED_STOP).collect()
    }

    /// A numeric column of a row.
    pub fn num(&self, row: &[String], name: &str) -> Option<f64> {
        self.col(name).and_then(|i| row[i].parse().ok())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_id_and_metric_column_has_a_kind_and_the_kind_lists_name_real_columns() {
        let all = header(&[]);
        for name in &all {
            assert!(column_kind(name).is_some(), "{name}");
        }
        for name in INTEGER_COLUMNS.iter().chain(&FLAG_COLUMNS).chain(&TEXT_COLUMNS) {
            assert!(all.iter().any(|c| c == name), "{name} is no column");
        }
        assert_eq!(column_kind("thesis.tournament_size"), None, "a swept key's kind is its key's");
        assert_eq!(column_kind("cam_walls_free"), Some(ColumnKind::Float));
    }

    /// Every column that is not the common scorer's has its meaning, and every meaning names a
    /// real column (the scorer's columns are documented on its fields).
    #[test]
    fn every_column_outside_the_scorer_has_a_meaning() {
        let all = header(&[]);
        let scorer = crate::coverage::score::Score::column_names();
        for name in all.iter().filter(|c| !scorer.contains(&c.as_str())) {
            assert!(column_meaning(name).is_some(), "{name} has no meaning");
        }
        for (name, _) in COLUMN_MEANINGS {
            assert!(all.iter().any(|c| c == name), "{name} is no column");
        }
    }

    #[test]
    fn half_written_last_line_is_dropped() {
        let t = RunsTable::parse("run_id,x\na,1\nb,2\nc,").unwrap();
        assert_eq!(t.rows.len(), 2);
        let t = RunsTable::parse("run_id,x\na,1\n").unwrap();
        assert_eq!(t.rows, vec![vec!["a".to_string(), "1".to_string()]]);
    }

    #[test]
    fn quoting_round_trips() {
        let line = csv_line(&["a,b".to_string(), "c\"d".to_string()]);
        let t = RunsTable::parse(&format!("x,y\n{}", String::from_utf8(line).unwrap())).unwrap();
        assert_eq!(t.rows[0], vec!["a,b".to_string(), "c\"d".to_string()]);
    }
}
