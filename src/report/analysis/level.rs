//! The time plans are compared on: whole-mission time only between plans of equal coverage.
//!
//! Plans that stop at different coverage — a planner that stops at a coverage goal against one
//! that sweeps on, or two plans that overshoot one goal by different amounts — do not finish
//! the same job, and their mission times do not compare. Where the compared plans' reachable
//! coverage differs, every finding, test, figure and comparison of the report reads the time
//! each plan takes to a common coverage level instead: the highest of
//! [`crate::coverage::curve::LEVELS`] (80, 90, 95 % of the reachable cells) that every compared
//! plan reaches, read off its coverage curve (for a plan stopped at a goal of 0.9, 90 %: the
//! goal). The times come from the run folders' curves, or from the record a report kept of them
//! ([`super::folder_record`]); where neither is there, the report says that its times compare
//! plans of unequal coverage.

use super::folder_record::FolderRecords;
use crate::coverage::curve::LEVELS;
use crate::study::records::RunsTable;

/// The columns a report adds to its runs table, one per level of [`LEVELS`]: each executable
/// plan's time to that share of the reachable cells (empty where it never reaches it, or where
/// its curve is not there). They follow the metric columns, so that
/// [`super::runs::param_columns`] passes over them.
pub const LEVEL_COLUMNS: [&str; 3] = ["time_to_80_s", "time_to_90_s", "time_to_95_s"];

/// The mission time column.
pub const MISSION_TIME: &str = "time_s";

/// Reachable coverage that differs by less than this is equal: plans of one coverage.
pub const EQUAL_COVERAGE: f64 = 1e-9;

/// Appends [`LEVEL_COLUMNS`] to `t`, read for every executable run from its folder's curve or
/// from the record (recorded, for a report made again without the folders).
pub fn add_level_columns(t: &mut RunsTable, folders: &FolderRecords) {
    if LEVEL_COLUMNS.iter().any(|c| t.header.iter().any(|h| h == c)) {
        return;
    }
    let (id, exec) = (t.col("run_id"), t.col("executable"));
    for row in &mut t.rows {
        let executable = exec.is_none_or(|c| row[c] == "true");
        let times = match (id, executable) {
            (Some(c), true) => folders.times(&row[c]),
            _ => None,
        };
        if let (Some(c), Some(times)) = (id, times) {
            folders.record_times(&row[c], times);
        }
        let cells = times.map_or([None; 3], |t| t);
        row.extend(cells.iter().map(|x| x.map_or_else(String::new, |v| v.to_string())));
    }
    t.header.extend(LEVEL_COLUMNS.iter().map(|c| c.to_string()));
}

/// Why a comparison reads the time it reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Basis {
    /// Every compared plan covers the same share: the whole mission compares.
    EqualCoverage,
    /// The plans' coverage differs; every one reaches this level (the highest of [`LEVELS`]).
    Level(f64),
    /// The plans' coverage differs and their curves are not there (no run folders, no record),
    /// or they share no level: mission time, said to compare unequal coverage.
    Unavailable,
}

/// The time a set of plans is compared on: a column of the runs table and why.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeMeasure {
    /// [`MISSION_TIME`] or one of [`LEVEL_COLUMNS`].
    pub column: &'static str,
    /// Why.
    pub basis: Basis,
}

impl TimeMeasure {
    /// The measure of the plans `rows` of `t` (their executable ones): mission time where their
    /// reachable coverage is equal, else the time to the highest level all of them reach.
    pub fn of(t: &RunsTable, rows: &[usize]) -> Self {
        let exec = t.col("executable");
        let rows: Vec<usize> = rows.iter().copied().filter(|&r| exec.is_none_or(|c| t.rows[r][c] == "true")).collect();
        let cov = |r: usize| t.num(&t.rows[r], "cov_final_reach").unwrap_or(f64::NAN);
        let (lo, hi) =
            rows.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &r| (a.min(cov(r)), b.max(cov(r))));
        if rows.is_empty() || hi - lo <= EQUAL_COVERAGE {
            return Self { column: MISSION_TIME, basis: Basis::EqualCoverage };
        }
        for (i, &level) in LEVELS.iter().enumerate().rev() {
            let reached = t.col(LEVEL_COLUMNS[i]).is_some_and(|c| rows.iter().all(|&r| !t.rows[r][c].is_empty()));
            if reached {
                return Self { column: LEVEL_COLUMNS[i], basis: Basis::Level(level) };
            }
        }
        Self { column: MISSION_TIME, basis: Basis::Unavailable }
    }

    /// The measure in a few words: "time to 90 %" or "mission time".
    pub fn name(&self) -> String {
        match self.basis {
            Basis::Level(l) => format!("time to {:.0} %", l * 100.0),
            _ => "mission time".to_string(),
        }
    }

    /// One sentence on which time is compared and why.
    pub fn sentence(&self) -> String {
        match self.basis {
            Basis::EqualCoverage => {
                "Every compared plan covers the same share of the reachable cells, so time is the whole mission's \
                 (`time_s`)."
                    .to_string()
            }
            Basis::Level(l) => format!(
                "The compared plans stop at different coverage, so time is the time to {:.0} % of the reachable cells \
                 (`{}`, read off each plan's coverage curve): the highest of 80, 90 and 95 % that every compared \
                 plan reaches (a plan stopped at a coverage goal of {l} reaches no more); whole-mission time would \
                 set plans of unequal coverage against each other.",
                l * 100.0,
                self.column
            ),
            Basis::Unavailable => "The compared plans stop at different coverage, but their coverage curves are not \
                                   here (no run folders, no record of them) or share no level of 80, 90 and 95 %: \
                                   time is the whole mission's (`time_s`), which sets plans of unequal coverage \
                                   against each other."
                .to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(rows: &[(&str, &str, &str)]) -> RunsTable {
        let mut text =
            String::from("run_id,executable,cov_final_reach,time_s,time_to_80_s,time_to_90_s,time_to_95_s\n");
        for (i, (cov, t90, t95)) in rows.iter().enumerate() {
            text.push_str(&format!("r{i},true,{cov},100,10,{t90},{t95}\n"));
        }
        RunsTable::parse(&text).unwrap()
    }

    #[test]
    fn equal_coverage_compares_the_mission_and_unequal_the_highest_common_level() {
        let equal = table(&[("0.9", "50", ""), ("0.9", "60", "")]);
        assert_eq!(TimeMeasure::of(&equal, &[0, 1]).column, MISSION_TIME);
        let goal = table(&[("0.901", "50", ""), ("0.96", "80", "90")]);
        let m = TimeMeasure::of(&goal, &[0, 1]);
        assert_eq!((m.column, m.basis), ("time_to_90_s", Basis::Level(0.9)));
        assert!(m.sentence().contains("time to 90 %"), "{}", m.sentence());
        let all_95 = table(&[("0.96", "50", "70"), ("0.97", "60", "80")]);
        assert_eq!(TimeMeasure::of(&all_95, &[0, 1]).column, "time_to_95_s");
        let none = table(&[("0.7", "", ""), ("0.96", "60", "80")]);
        let m = TimeMeasure::of(&none, &[0, 1]);
        assert_eq!(m.column, "time_to_80_s", "both reach 80 %");
        let t = RunsTable::parse("run_id,executable,cov_final_reach,time_s\na,true,0.5,1\nb,true,0.6,2\n").unwrap();
        assert_eq!(TimeMeasure::of(&t, &[0, 1]).basis, Basis::Unavailable);
    }
}
