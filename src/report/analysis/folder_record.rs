//! What a report reads from its runs' folders, recorded beside it so that the report re-makes
//! from committed files.
//!
//! Two parts of the summary read the run folders: the claims of 003 §5.1 (each run's final
//! diversity, from `history.csv`) and the time-to-coverage table (each executable plan's times
//! to 80, 90 and 95 % of the reachable cells, from `coverage_curve.csv`). A committed study
//! keeps `runs.csv`, not its folders (tens of gigabytes of histories and paths). Where the
//! folders are there, the report writes what it read into `run-folders.csv` in the report
//! folder; where they are gone, it reads that file back, so that those tables come out as
//! they did. The figures cannot be redrawn from it (they need whole curves and paths); the
//! figure files made with the folders stay as they were.

use super::ReportError;
use crate::coverage::curve::{CoverageCurve, LEVELS};
use crate::study::records::RunsTable;
use std::cell::RefCell;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The file, in the report folder.
pub const FILE: &str = "run-folders.csv";

/// Its columns, in order.
const COLUMNS: [&str; 6] = ["run_id", "final_diversity", "curve", "time_to_80_s", "time_to_90_s", "time_to_95_s"];

/// What one run's folder said.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Record {
    /// Mean diversity over the last tenth of `history.csv` (`None`: not read, or no history).
    final_diversity: Option<f64>,
    /// Times to [`LEVELS`] along the plan's curve (`None`: not read, or no curve; a level the
    /// plan never reaches is `None` inside).
    times: Option<[Option<f64>; 3]>,
}

/// The run folders of a study, or what a report recorded of them.
pub struct FolderRecords {
    /// The study's `runs/` folder, where it exists.
    runs: Option<PathBuf>,
    /// What an earlier report recorded (read where `runs` is `None`).
    recorded: BTreeMap<String, Record>,
    /// What this report read from the folders, to record.
    read: RefCell<BTreeMap<String, Record>>,
}

impl FolderRecords {
    /// The folders of study `dir`, or, where it holds none, the record in the report folder
    /// `out`, else in the study's default report folder (`report/`, whose record a report of
    /// some of the runs, `--where`, can read); with neither, what the folders would give is
    /// left out, as the report says.
    pub fn open(dir: &Path, out: &Path) -> Result<Self, ReportError> {
        let runs = dir.join("runs");
        let recorded = match (runs.is_dir(), out.join(FILE).is_file()) {
            (true, _) => BTreeMap::new(),
            (false, true) => read(&out.join(FILE))?,
            (false, false) => read(&dir.join("report").join(FILE))?,
        };
        Ok(Self { runs: runs.is_dir().then_some(runs), recorded, read: RefCell::default() })
    }

    /// Whether the study's run folders are there.
    pub fn from_folders(&self) -> bool {
        self.runs.is_some()
    }

    /// Run `id`'s final diversity (claims of 003 §5.1).
    pub fn final_diversity(&self, id: &str) -> Option<f64> {
        let Some(runs) = &self.runs else { return self.recorded.get(id)?.final_diversity };
        let v = final_diversity(&runs.join(id).join("history.csv"));
        if v.is_some() {
            self.read.borrow_mut().entry(id.to_string()).or_default().final_diversity = v;
        }
        v
    }

    /// Run `id`'s coverage curve, read from its folder (`None` without folders).
    pub fn curve(&self, id: &str) -> Option<CoverageCurve> {
        let runs = self.runs.as_ref()?;
        CoverageCurve::parse_csv(&std::fs::read_to_string(runs.join(id).join("coverage_curve.csv")).ok()?)
    }

    /// Records run `id`'s times to [`LEVELS`], read from its curve, for the table that shows
    /// them (the time-to-coverage section records only what it tabulates).
    pub fn record_times(&self, id: &str, times: [Option<f64>; 3]) {
        if self.runs.is_some() {
            self.read.borrow_mut().entry(id.to_string()).or_default().times = Some(times);
        }
    }

    /// Run `id`'s times to [`LEVELS`]: from its curve where the folders are there, else as
    /// recorded (`None`: the run has no curve).
    pub fn times(&self, id: &str) -> Option<[Option<f64>; 3]> {
        match &self.runs {
            Some(_) => self.curve(id).map(|c| LEVELS.map(|l| c.time_to(l))),
            None => self.recorded.get(id)?.times,
        }
    }

    /// Writes what this report read from the folders into `out` (nothing where it read none).
    pub fn save(&self, out: &Path) -> Result<(), ReportError> {
        let read = self.read.borrow();
        if read.is_empty() {
            return Ok(());
        }
        let cell = |v: Option<f64>| v.map_or_else(String::new, |x| x.to_string());
        let mut s = COLUMNS.join(",");
        s.push('\n');
        for (id, r) in read.iter() {
            let times = r.times.map_or([None; 3], |t| t);
            let _ = writeln!(
                s,
                "{id},{},{},{},{},{}",
                cell(r.final_diversity),
                r.times.map_or("", |_| "true"),
                cell(times[0]),
                cell(times[1]),
                cell(times[2])
            );
        }
        let path = out.join(FILE);
        crate::io::write_atomic(&path, s.as_bytes()).map_err(|e| ReportError::Io(format!("{}: {e}", path.display())))
    }
}

/// Reads a record back; an absent file is an empty record.
fn read(file: &Path) -> Result<BTreeMap<String, Record>, ReportError> {
    let Ok(text) = std::fs::read_to_string(file) else { return Ok(BTreeMap::new()) };
    let bad = |m: String| ReportError::Input(format!("{}: {m}", file.display()));
    let t = RunsTable::parse(&text).map_err(bad)?;
    if t.header != COLUMNS {
        return Err(bad(format!("expected the columns {}", COLUMNS.join(","))));
    }
    let num = |v: &str| -> Result<Option<f64>, ReportError> {
        if v.is_empty() {
            return Ok(None);
        }
        v.parse::<f64>().map(Some).map_err(|_| bad(format!("`{v}` is not a number")))
    };
    let mut out = BTreeMap::new();
    for r in &t.rows {
        let times = match r[2].as_str() {
            "true" => Some([num(&r[3])?, num(&r[4])?, num(&r[5])?]),
            "" => None,
            other => return Err(bad(format!("`curve` is `{other}`: expected true or nothing"))),
        };
        out.insert(r[0].clone(), Record { final_diversity: num(&r[1])?, times });
    }
    Ok(out)
}

/// Mean diversity over the last tenth of the rows of a run's `history.csv`.
pub fn final_diversity(history: &Path) -> Option<f64> {
    let text = std::fs::read_to_string(history).ok()?;
    let mut lines = text.lines();
    let col = lines.next()?.split(',').position(|h| h == "diversity")?;
    let values: Vec<f64> = lines.filter_map(|l| l.split(',').nth(col)?.parse().ok()).collect();
    let tail = &values[values.len() - (values.len() / 10).max(1).min(values.len())..];
    (!tail.is_empty()).then(|| tail.iter().sum::<f64>() / tail.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn what_the_folders_said_reads_back_the_same() {
        let study = tempfile::tempdir().unwrap();
        let run = study.path().join("runs/a");
        std::fs::create_dir_all(&run).unwrap();
        let history: String = std::iter::once("iteration,diversity\n".to_string())
            .chain((0..20).map(|i| format!("{i},{}\n", i as f64 / 7.0)))
            .collect();
        std::fs::write(run.join("history.csv"), history).unwrap();
        std::fs::write(run.join("coverage_curve.csv"), "time_s,coverage_reach\n0,0\n10,0.85\n30,0.92\n").unwrap();
        let out = study.path().join("report");
        std::fs::create_dir_all(&out).unwrap();
        let folders = FolderRecords::open(study.path(), &out).unwrap();
        assert!(folders.from_folders());
        let d = folders.final_diversity("a");
        let t = folders.times("a");
        folders.record_times("a", t.unwrap());
        assert!(d.is_some() && t.is_some());
        assert_eq!(folders.final_diversity("missing"), None);
        folders.save(&out).unwrap();
        std::fs::remove_dir_all(study.path().join("runs")).unwrap();
        let recorded = FolderRecords::open(study.path(), &out).unwrap();
        assert!(!recorded.from_folders());
        assert_eq!((recorded.final_diversity("a"), recorded.times("a")), (d, t));
        assert_eq!(t.unwrap()[2], None, "a level the plan never reaches stays unreached");
        assert!(recorded.curve("a").is_none(), "curves come from folders only");
        assert_eq!(recorded.final_diversity("missing"), None, "a run without a history is not made one");
    }

    #[test]
    fn final_diversity_is_the_mean_of_the_last_tenth() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("history.csv");
        let mut text = String::from("iteration,diversity\n");
        for i in 0..20 {
            text.push_str(&format!("{i},{}\n", i * 10));
        }
        std::fs::write(&p, text).unwrap();
        // Last 2 of 20 rows: 180 and 190.
        assert_eq!(final_diversity(&p), Some(185.0));
        assert_eq!(final_diversity(&dir.path().join("none.csv")), None);
    }
}
