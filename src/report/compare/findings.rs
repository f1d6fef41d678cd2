//! The comparison's findings in plain words, written from its own table (`compare-KEY.csv`):
//! for each compared value, its time and coverage against the baseline pooled over the strata
//! (where there are several), and how the strata split — shown better, shown worse, neither —
//! with the range of the strata's effects. Nothing here computes a statistic: every number is
//! a cell of the table.

use crate::study::records::RunsTable;
use std::fmt::Write as _;

/// The findings of the comparison whose table is `csv`, against `baseline`; `effort` gives, per
/// compared value (and the baseline), its runs and the most evaluations one of them made.
pub fn findings(csv: &str, baseline: &str, effort: &[(String, usize, u64)]) -> String {
    let Ok(t) = RunsTable::parse(csv) else { return String::new() };
    let col = |name: &str| t.col(name).expect("the comparison table's columns");
    let (stratum, value, metric, estimate, note, pairs) =
        (col("stratum"), col("value"), col("metric"), col("estimate"), col("note"), col("pairs"));
    let (low, high) = (col("ci_low"), col("ci_high"));
    let mut values: Vec<&str> = Vec::new();
    for r in &t.rows {
        if !values.contains(&r[value].as_str()) {
            values.push(&r[value]);
        }
    }
    let mut out = String::from("## Findings\n\n");
    for v in values {
        let _ = writeln!(out, "- **`{v}`**");
        for (m, what, as_ratio) in [("time_s", "time", true), ("cov_final_reach", "reachable coverage", false)] {
            let rows: Vec<&Vec<String>> = t.rows.iter().filter(|r| r[value] == v && r[metric] == m).collect();
            let number = |r: &Vec<String>, c: usize| r[c].parse::<f64>().ok();
            let effect = |x: f64| if as_ratio { format!("{x:.3}×") } else { format!("{x:+.4}") };
            if let Some(p) = rows.iter().find(|r| r[stratum] == "pooled")
                && let (Some(e), Some(lo), Some(hi)) = (number(p, estimate), number(p, low), number(p, high))
            {
                let kind = if as_ratio { "ratio" } else { "difference" };
                let _ = writeln!(
                    out,
                    "  - {what}, pooled over the strata: median pair {kind} {} [{}, {}] over {} pairs; {}.",
                    effect(e),
                    effect(lo),
                    effect(hi),
                    p[pairs],
                    p[note]
                );
            }
            let strata: Vec<&&Vec<String>> = rows.iter().filter(|r| r[stratum] != "pooled").collect();
            if strata.is_empty() {
                continue;
            }
            let count = |word: &str| strata.iter().filter(|r| r[note].starts_with(word)).count();
            let (better, worse) = (count("better than"), count("worse than"));
            let with_effect: Vec<(f64, &str)> =
                strata.iter().filter_map(|r| Some((number(r, estimate)?, r[stratum].as_str()))).collect();
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
                let _ =
                    write!(out, "; {kind} from {} ({}) to {} ({})", effect(lo.0), name(lo.1), effect(hi.0), name(hi.1));
            }
            out.push_str(".\n");
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn findings_count_the_strata_and_quote_the_pooled_effect_from_the_table() {
        let csv = "stratum,value,metric,pairs,estimate,ci_low,ci_high,note\n\
                   pooled,ga,time_s,20,0.9,0.85,0.95,better than c (shown)\n\
                   m=1,ga,time_s,10,0.8,0.7,0.9,better than c (shown)\n\
                   m=2,ga,time_s,10,1.1,0.9,1.2,not shown\n\
                   m=1,ga,cov_final_reach,10,0.001,0,0.002,not shown\n";
        let text = findings(csv, "c", &[("ga".into(), 20, 50_009)]);
        assert!(
            text.contains("time, pooled over the strata: median pair ratio 0.900× [0.850×, 0.950×] over 20 pairs"),
            "{text}"
        );
        assert!(text.contains("shown better than `c` in 1 of 2, shown worse in 0"), "{text}");
        assert!(text.contains("its median time is below the baseline's in 1, above in 1; ratio of medians from 0.800× (m=1) to 1.100× (m=2)"), "{text}");
        assert!(text.contains("reachable coverage, stratum by stratum: shown better than `c` in 0 of 1"), "{text}");
        assert!(text.contains("Evaluations per run: `ga` at most 50009 (20 runs)."), "{text}");
    }
}
