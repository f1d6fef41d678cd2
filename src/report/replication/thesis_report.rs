//! Thesis-specific tables of `covga report`, added when the runs table has a
//! `thesis.selection` column: run durations per selection scheme beside 003 Table 4.4.

use crate::study::records::RunsTable;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// 003 Table 4.4: runs, average, maximum and minimum duration in seconds per selection scheme,
/// from the thesis's grid search (one seed, its C++ code and machine).
const TABLE_4_4: [(&str, u32, f64, f64, f64); 4] = [
    ("elite", 5201, 269.0, 846.0, 26.0),
    ("tournament", 20779, 123.0, 715.0, 21.0),
    ("prws", 10392, 106.0, 497.0, 17.0),
    ("rrws", 17318, 143.0, 620.0, 25.0),
];

/// Whether the runs are thesis GA runs swept over the selection scheme.
pub fn applies(t: &RunsTable) -> bool {
    t.col("thesis.selection").is_some() && t.col("wall_s").is_some()
}

/// Run count and duration (mean, min, max seconds) per selection scheme of `t`.
pub fn durations(t: &RunsTable) -> BTreeMap<String, (usize, f64, f64, f64)> {
    let (sel, wall) = (t.col("thesis.selection").expect("applies"), t.col("wall_s").expect("applies"));
    let mut by: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for r in &t.rows {
        if let Ok(w) = r[wall].parse::<f64>() {
            by.entry(r[sel].clone()).or_default().push(w);
        }
    }
    by.into_iter()
        .map(|(k, v)| {
            let (mean, lo, hi) = crate::stats::mean_min_max(&v);
            (k, (v.len(), mean, lo, hi))
        })
        .collect()
}

/// The thesis sections: run durations beside Table 4.4 and, for studies over the Table 4.3
/// operators, the claims of 003 §5.1 checked on the runs of `t` (their histories read through
/// `folders`).
pub fn sections(t: &RunsTable, folders: &crate::report::analysis::folder_record::FolderRecords) -> String {
    let mut md = section(t);
    if ["thesis.c_len", "thesis.c_child", "thesis.p_mi"].iter().all(|c| t.col(c).is_some()) {
        md.push_str(&super::claims::section(t, folders));
    }
    md
}

/// The markdown table of run durations beside Table 4.4.
pub fn section(t: &RunsTable) -> String {
    let ours = durations(t);
    let mut md = String::from("\n## Run durations per selection scheme beside 003 Table 4.4\n\n");
    md.push_str(
        "Seconds of wall time per run (covga: one run per core as the study ran; the thesis: its \
         own code and machine, one seed of the full grid).\n\n",
    );
    md.push_str("| selection | runs (covga) | avg | min | max | runs (thesis) | avg | min | max | avg ratio |\n");
    md.push_str("|---|---|---|---|---|---|---|---|---|---|\n");
    for (name, n, avg, max, min) in TABLE_4_4 {
        match ours.get(name) {
            Some(&(k, mean, lo, hi)) => {
                let _ = writeln!(
                    md,
                    "| {name} | {k} | {mean:.2} | {lo:.2} | {hi:.2} | {n} | {avg:.0} | {min:.0} | {max:.0} | {:.0}× |",
                    avg / mean
                );
            }
            None => {
                let _ = writeln!(md, "| {name} | 0 | – | – | – | {n} | {avg:.0} | {min:.0} | {max:.0} | – |");
            }
        }
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_per_scheme_and_the_thesis_beside_them() {
        let text = "run_id,thesis.selection,wall_s\na,elite,2.0\nb,elite,4.0\nc,prws,1.0\nd,prws,x\n";
        let t = RunsTable::parse(text).unwrap();
        assert!(applies(&t));
        let d = durations(&t);
        assert_eq!(d["elite"], (2, 3.0, 2.0, 4.0));
        assert_eq!(d["prws"], (1, 1.0, 1.0, 1.0), "a run without a number is left out");
        let md = section(&t);
        assert!(md.contains("| elite | 2 | 3.00 | 2.00 | 4.00 | 5201 | 269 | 26 | 846 | 90× |"), "{md}");
        assert!(md.contains("| tournament | 0 | – | – | – | 20779 | 123 | 21 | 715 | – |"), "{md}");
    }
}
