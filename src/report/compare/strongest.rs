//! A baseline of several controls, `KEY=A|B`: in each stratum the comparison is made against
//! the strongest of them there — the control whose executable plans have the lowest median
//! `time_s` (the controls of a study that fixes the coverage goal reach the same coverage, so
//! the faster one is the one a search has to beat). Which control that is, stratum by stratum,
//! is stated in the comparison's text.

use crate::stats::median;
use crate::study::records::RunsTable;
use std::collections::BTreeMap;

/// The controls of a baseline written `A|B|…` (one control for a plain baseline).
pub fn controls(baseline: &str) -> Vec<&str> {
    baseline.split('|').map(str::trim).collect()
}

/// Per stratum, the strongest of `controls` among the `cells` (`(stratum, value) → seed →
/// row`) of `t`: the lowest median `time_s` over its executable runs (a control with none
/// executable is never chosen; the first of equals wins). Strata holding none of them are
/// left out.
pub fn per_stratum(
    t: &RunsTable,
    cells: &BTreeMap<(String, String), BTreeMap<String, usize>>,
    controls: &[&str],
) -> BTreeMap<String, String> {
    let time = t.col("time_s");
    let executable = t.col("executable");
    let mut out: BTreeMap<String, (String, f64)> = BTreeMap::new();
    for ((stratum, value), runs) in cells {
        if !controls.contains(&value.as_str()) {
            continue;
        }
        let mut times: Vec<f64> = runs
            .values()
            .filter(|&&r| executable.is_none_or(|c| t.rows[r][c] == "true"))
            .filter_map(|&r| time.and_then(|c| t.rows[r][c].parse::<f64>().ok()))
            .collect();
        if times.is_empty() {
            continue;
        }
        let m = median(&mut times);
        let rank = |v: &str| controls.iter().position(|c| *c == v).unwrap_or(usize::MAX);
        match out.get(stratum) {
            Some((best, t)) if *t < m || (*t == m && rank(best) < rank(value)) => {}
            _ => {
                out.insert(stratum.clone(), (value.clone(), m));
            }
        }
    }
    out.into_iter().map(|(s, (v, _))| (s, v)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fastest_executable_control_is_the_baseline_of_its_stratum() {
        let text = "run_id,executable,time_s\na,true,10\nb,true,12\nc,false,5\nd,true,20\ne,true,8\n";
        let t = RunsTable::parse(text).unwrap();
        let cell = |rows: &[usize]| rows.iter().map(|&r| (r.to_string(), r)).collect::<BTreeMap<_, _>>();
        let mut cells = BTreeMap::new();
        // Stratum s1: A takes 10, B 12 and a non-executable 5 (not counted): A is the stronger.
        cells.insert(("s1".to_string(), "A".to_string()), cell(&[0]));
        cells.insert(("s1".to_string(), "B".to_string()), cell(&[1, 2]));
        // Stratum s2: A takes 20, B 8.
        cells.insert(("s2".to_string(), "A".to_string()), cell(&[3]));
        cells.insert(("s2".to_string(), "B".to_string()), cell(&[4]));
        cells.insert(("s2".to_string(), "ga".to_string()), cell(&[0]));
        let chosen = per_stratum(&t, &cells, &controls("A|B"));
        assert_eq!(chosen.get("s1").map(String::as_str), Some("A"));
        assert_eq!(chosen.get("s2").map(String::as_str), Some("B"));
        assert_eq!(controls("nearest"), ["nearest"]);
    }
}
