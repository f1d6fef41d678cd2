//! The comparison's findings in plain words, written from its own table (`compare-KEY.csv`):
//! for each compared value, its time and coverage against the baseline pooled over the strata
//! (where there are several), and how the strata split — shown better, shown worse, neither —
//! with the range of the strata's effects. Nothing here computes a statistic: every number is
//! a cell of the table.

use crate::study::records::RunsTable;
use std::fmt::Write as _;

/// The findings of the comparison whose table is `csv`, against `baseline`; `effort` gives, per
/// compared value (and the baseline), its runs and the most evaluations one of them made;
/// `time` the time column compared and its name ("time to 90 %").
pub fn findings(csv: &str, baseline: &str, effort: &[(String, usize, u64)], time: (&str, String)) -> String {
    let Ok(t) = RunsTable::parse(csv) else { return String::new() };
    let c = Columns::of(&t);
    let mut values: Vec<&str> = Vec::new();
    for r in &t.rows {
        if !values.contains(&r[c.value].as_str()) {
            values.push(&r[c.value]);
        }
    }
    let mut out = String::from("## Findings\n\n");
    for v in values {
        match v.is_empty() {
            // Runs whose configuration leaves the key out (a conditional sets it for some only).
            true => {
                let _ = writeln!(out, "- **the runs that do not set the key**");
            }
            false => {
                let _ = writeln!(out, "- **`{v}`**");
            }
        }
        let pooled_executable =
            t.rows.iter().find(|r| r[c.value] == v && r[c.metric] == "executable" && r[c.stratum] == "pooled");
        if let Some(p) = pooled_executable {
            let _ = writeln!(
                out,
                "  - executable plans, pooled over the {} {}: `{baseline}` {}/{}, the value {}/{}; {}.",
                p[c.units],
                plural(&p[c.unit]),
                p[c.exec.0],
                p[c.runs.0],
                p[c.exec.1],
                p[c.runs.1],
                p[c.note]
            );
        }
        for (m, what, as_ratio) in [(time.0, time.1.as_str(), true), ("cov_final_reach", "reachable coverage", false)] {
            let rows: Vec<&Vec<String>> = t.rows.iter().filter(|r| r[c.value] == v && r[c.metric] == m).collect();
            metric_lines(&mut out, &c, &rows, baseline, (what, as_ratio));
            let margin = format!("{m} margin");
            if let Some(r) = t.rows.iter().find(|r| r[c.value] == v && r[c.metric] == margin) {
                let _ = writeln!(
                    out,
                    "  - {what} against a margin, over the {} {}: median unit ratio {} [{}, {}]; below the margin in {}, \
                     at or above it in {}; {}.",
                    r[c.units],
                    plural(&r[c.unit]),
                    ratio(&r[c.estimate]),
                    ratio(&r[c.low]),
                    ratio(&r[c.high]),
                    r[c.better],
                    r[c.worse],
                    r[c.note]
                );
            }
        }
    }
    if !effort.is_empty() {
        let each: Vec<String> =
            effort.iter().map(|(v, runs, most)| format!("`{v}` at most {most} ({runs} runs)")).collect();
        let _ = writeln!(out, "- Evaluations per run: {}.", each.join(", "));
    }
    out.push_str(
        "\n\"Shown\" is a Holm-adjusted p below 0.05 in its family (the tables below); a comparison not shown \
         is no evidence of equality.\n\n",
    );
    out
}

/// The columns of the comparison table the findings read.
struct Columns {
    stratum: usize,
    value: usize,
    metric: usize,
    estimate: usize,
    note: usize,
    pairs: usize,
    low: usize,
    high: usize,
    unit: usize,
    units: usize,
    better: usize,
    worse: usize,
    runs: (usize, usize),
    exec: (usize, usize),
}

impl Columns {
    fn of(t: &RunsTable) -> Self {
        let col = |name: &str| t.col(name).expect("the comparison table's columns");
        Columns {
            stratum: col("stratum"),
            value: col("value"),
            metric: col("metric"),
            estimate: col("estimate"),
            note: col("note"),
            pairs: col("pairs"),
            low: col("ci_low"),
            high: col("ci_high"),
            unit: col("unit"),
            units: col("units"),
            better: col("value_better"),
            worse: col("value_worse"),
            runs: (col("runs_baseline"), col("runs_value")),
            exec: (col("executable_baseline"), col("executable_value")),
        }
    }
}

/// The lines of one value and metric (`rows`: its table rows): pooled, then stratum by stratum.
fn metric_lines(out: &mut String, c: &Columns, rows: &[&Vec<String>], baseline: &str, (what, as_ratio): (&str, bool)) {
    let number = |r: &Vec<String>, col: usize| r[col].parse::<f64>().ok();
    let effect = |x: f64| if as_ratio { format!("{x:.3}×") } else { format!("{x:+.4}") };
    if let Some(p) = rows.iter().find(|r| r[c.stratum] == "pooled")
        && let (Some(e), Some(lo), Some(hi)) = (number(p, c.estimate), number(p, c.low), number(p, c.high))
    {
        let kind = if as_ratio { "ratio" } else { "difference" };
        let _ = writeln!(
            out,
            "  - {what}, pooled over the {} {}: median pair {kind} {} [{}, {}] over {} pairs; better in {} and \
             worse in {} of the {}; {}.",
            p[c.units],
            plural(&p[c.unit]),
            effect(e),
            effect(lo),
            effect(hi),
            p[c.pairs],
            p[c.better],
            p[c.worse],
            plural(&p[c.unit]),
            p[c.note]
        );
    }
    let strata: Vec<&&Vec<String>> = rows.iter().filter(|r| r[c.stratum] != "pooled").collect();
    if strata.is_empty() {
        return;
    }
    let count = |word: &str| strata.iter().filter(|r| r[c.note].starts_with(word)).count();
    let (better, worse) = (count("better than"), count("worse than"));
    let with_effect: Vec<(f64, &str)> =
        strata.iter().filter_map(|r| Some((number(r, c.estimate)?, r[c.stratum].as_str()))).collect();
    let lowest = with_effect.iter().copied().min_by(|a, b| a.0.total_cmp(&b.0));
    let highest = with_effect.iter().copied().max_by(|a, b| a.0.total_cmp(&b.0));
    let _ = write!(
        out,
        "  - {what}, stratum by stratum: shown better than `{baseline}` in {better} of {}, shown worse in {worse}",
        strata.len()
    );
    if as_ratio {
        let below = with_effect.iter().filter(|e| e.0 < 1.0).count();
        let above = with_effect.iter().filter(|e| e.0 > 1.0).count();
        let _ = write!(out, "; its median time is below the baseline's in {below}, above in {above}");
    }
    if let (Some(lo), Some(hi)) = (lowest, highest) {
        let name = |s: &str| if s.is_empty() { "all".to_string() } else { s.to_string() };
        let kind = if as_ratio { "ratio of medians" } else { "difference of medians" };
        let _ = write!(out, "; {kind} from {} ({}) to {} ({})", effect(lo.0), name(lo.1), effect(hi.0), name(hi.1));
    }
    out.push_str(".\n");
}

/// A ratio cell as the findings write it (`0.950×`), or the cell itself where it is no number.
fn ratio(cell: &str) -> String {
    cell.parse::<f64>().map_or_else(|_| cell.to_string(), |x| format!("{x:.3}×"))
}

/// The plural of a unit's name as the comparison table writes it.
fn plural(unit: &str) -> String {
    match unit {
        "stratum" => "strata".into(),
        other => format!("{other}s"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_that_do_not_set_the_key_are_named_as_such() {
        let csv = "stratum,value,metric,runs_baseline,runs_value,executable_baseline,executable_value,pairs,unit,\
                   units,estimate,ci_low,ci_high,value_better,value_worse,note\n\
                   m=1,,time_s,10,10,9,10,10,seed,10,0.8,0.7,0.9,10,0,better than c (shown)\n";
        let text = findings(csv, "c", &[], ("time_s", "time".into()));
        assert!(text.contains("- **the runs that do not set the key**"), "{text}");
        assert!(!text.contains("**``**"), "{text}");
    }

    #[test]
    fn findings_count_the_strata_and_quote_the_pooled_effect_from_the_table() {
        let csv = "stratum,value,metric,runs_baseline,runs_value,executable_baseline,executable_value,pairs,unit,\
                   units,estimate,ci_low,ci_high,value_better,value_worse,note\n\
                   pooled,ga,executable,20,20,18,20,20,stratum,2,,,,1,0,cannot show by design\n\
                   pooled,ga,time_s,20,20,18,20,20,stratum,2,0.9,0.85,0.95,2,0,cannot show by design\n\
                   m=1,ga,time_s,10,10,9,10,10,seed,10,0.8,0.7,0.9,10,0,better than c (shown)\n\
                   m=2,ga,time_s,10,10,9,10,10,seed,10,1.1,0.9,1.2,2,8,not shown\n\
                   m=1,ga,cov_final_reach,10,10,9,10,10,seed,10,0.001,0,0.002,2,1,not shown\n";
        let csv = format!(
            "{csv}pooled,ga,time_s margin,20,20,18,20,20,stratum,2,0.9,0.85,0.95,2,0,\"not shown at least 5 % faster\"\n"
        );
        let text = findings(&csv, "c", &[("ga".into(), 20, 50_009)], ("time_s", "time".into()));
        assert!(
            text.contains(
                "time against a margin, over the 2 strata: median unit ratio 0.900× [0.850×, 0.950×]; below the margin \
                 in 2, at or above it in 0; not shown at least 5 % faster."
            ),
            "{text}"
        );
        assert!(
            text.contains(
                "time, pooled over the 2 strata: median pair ratio 0.900× [0.850×, 0.950×] over 20 pairs; better in 2 \
                 and worse in 0 of the strata; cannot show by design."
            ),
            "{text}"
        );
        assert!(
            text.contains(
                "executable plans, pooled over the 2 strata: `c` 18/20, the value 20/20; cannot show by design."
            ),
            "{text}"
        );
        assert!(text.contains("shown better than `c` in 1 of 2, shown worse in 0"), "{text}");
        assert!(text.contains("its median time is below the baseline's in 1, above in 1; ratio of medians from 0.800× (m=1) to 1.100× (m=2)"), "{text}");
        assert!(text.contains("reachable coverage, stratum by stratum: shown better than `c` in 0 of 1"), "{text}");
        assert!(text.contains("Evaluations per run: `ga` at most 50009 (20 runs)."), "{text}");
    }
}
