//! `covga report DIR --seed-to-seed`: how far one seed's conclusions carry to another (003
//! §5.3 names its single seed as the weak point of its conclusions), written to
//! `seed-to-seed.md` from runs.csv alone:
//!
//! - the Spearman correlation, between every two replicates, of the configurations' `f_free`,
//!   `cov_final_free` and `t_final` (configurations recorded in every replicate);
//! - where each replicate's best configuration ranks in the others, and how much of its top 1 %
//!   stays in the others' top 10 %;
//! - per replicate and group (`--by`), the runs whose best plan sweeps obstacle cells (003's
//!   penalty, `obstacle_sweeps` > 0) and the runs whose plan is not executable;
//! - on a study of the thesis maps, each cell of 003 Tables A.1/A.2 (map × `R_rot` × fitness
//!   function × selection; the thesis's best individual, one seed) beside the same cell here:
//!   the best run by f, the median run, and how many runs reach or dominate the thesis's point.

use crate::report::analysis::ReportError;
use crate::report::analysis::runs::cell_matches;
use crate::stats::{quartiles, spearman};
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// 003 Tables A.1 (thesis-1) and A.2 (thesis-2): per map, `R_rot`, fitness function and
/// selection, the (`cov_final`, `t_final`) of the thesis's best individual. Several of its rows
/// use `C_len` values outside Table 4.3, so configurations cannot be matched one to one; cells
/// can.
const THESIS_BEST: [(&str, &str, &str, &str, f64, f64); 32] = [
    ("thesis-1", "0.0", "f1", "elite", 0.810864, 0.889973),
    ("thesis-1", "0.0", "f1", "tournament", 0.743704, 0.963532),
    ("thesis-1", "0.0", "f1", "prws", 0.827654, 0.794313),
    ("thesis-1", "0.0", "f1", "rrws", 0.768395, 0.825027),
    ("thesis-1", "0.0", "f2", "elite", 0.858765, 0.805839),
    ("thesis-1", "0.0", "f2", "tournament", 0.784198, 0.852389),
    ("thesis-1", "0.0", "f2", "prws", 0.814815, 0.818859),
    ("thesis-1", "0.0", "f2", "rrws", 0.777778, 0.795455),
    ("thesis-1", "6.28", "f1", "elite", 0.874074, 0.776625),
    ("thesis-1", "6.28", "f1", "tournament", 0.822222, 0.926432),
    ("thesis-1", "6.28", "f1", "prws", 0.692346, 0.897165),
    ("thesis-1", "6.28", "f1", "rrws", 0.824691, 0.799912),
    ("thesis-1", "6.28", "f2", "elite", 0.84642, 0.799684),
    ("thesis-1", "6.28", "f2", "tournament", 0.813333, 0.782359),
    ("thesis-1", "6.28", "f2", "prws", 0.809383, 0.810188),
    ("thesis-1", "6.28", "f2", "rrws", 0.781235, 0.791927),
    ("thesis-2", "0.0", "f1", "elite", 0.866279, 0.817783),
    ("thesis-2", "0.0", "f1", "tournament", 0.819186, 0.876244),
    ("thesis-2", "0.0", "f1", "prws", 0.86686, 0.846678),
    ("thesis-2", "0.0", "f1", "rrws", 0.836628, 0.78249),
    ("thesis-2", "0.0", "f2", "elite", 0.861628, 0.830717),
    ("thesis-2", "0.0", "f2", "tournament", 0.796512, 0.875399),
    ("thesis-2", "0.0", "f2", "prws", 0.843605, 0.783901),
    ("thesis-2", "0.0", "f2", "rrws", 0.830233, 0.787211),
    ("thesis-2", "6.28", "f1", "elite", 0.819767, 0.864434),
    ("thesis-2", "6.28", "f1", "tournament", 0.845349, 0.830881),
    ("thesis-2", "6.28", "f1", "prws", 0.794186, 0.853525),
    ("thesis-2", "6.28", "f1", "rrws", 0.773256, 0.866285),
    ("thesis-2", "6.28", "f2", "elite", 0.853488, 0.868523),
    ("thesis-2", "6.28", "f2", "tournament", 0.859884, 0.837755),
    ("thesis-2", "6.28", "f2", "prws", 0.85814, 0.817946),
    ("thesis-2", "6.28", "f2", "rrws", 0.82093, 0.779031),
];

/// The metrics whose configuration rankings are compared between replicates.
const RANKED: [&str; 3] = ["f_free", "cov_final_free", "t_final"];

/// `seed-to-seed.md` of the runs `t` (failed runs and `--where` already left out), its
/// infeasibility table grouped by the columns `by`.
pub fn render(t: &RunsTable, by: &[String]) -> Result<String, ReportError> {
    let need = |name: &str| {
        t.col(name).ok_or_else(|| ReportError::Input(format!("--seed-to-seed: runs.csv has no `{name}` column")))
    };
    let (config, replicate) = (need("config_id")?, need("replicate")?);
    let (sweeps, executable) = (need("obstacle_sweeps")?, need("executable")?);
    let ranked: Vec<usize> = RANKED.iter().map(|m| need(m)).collect::<Result<_, _>>()?;
    let by_cols: Vec<usize> = by
        .iter()
        .map(|b| t.col(b).ok_or_else(|| ReportError::Input(format!("--by {b}: no such column in runs.csv"))))
        .collect::<Result<_, _>>()?;
    let num = |r: &Vec<String>, c: usize| r[c].parse::<f64>().unwrap_or(f64::NAN);
    let (by_config, reps) = replicates_of(t, config, replicate)?;
    let complete: Vec<&BTreeMap<u64, &Vec<String>>> =
        by_config.values().filter(|v| reps.iter().all(|k| v.contains_key(k))).collect();
    let n = complete.len();
    let mut md = String::from("# Seed to seed\n\n");
    let _ = writeln!(
        md,
        "Written by `covga report --seed-to-seed` from `runs.csv`: how far one replicate's ranking of the \
         configurations carries to another (every configuration of a replicate runs with the replicate's seed).\n"
    );
    let _ = writeln!(md, "## Seed to seed ({n} configurations with all {} replicates)\n", reps.len());
    let _ = writeln!(md, "| replicates | Spearman ρ of f | of cov_final | of t_final |\n|---|---|---|---|");
    let values = |k: u64, c: usize| -> Vec<f64> { complete.iter().map(|v| num(v[&k], c)).collect() };
    for (i, &a) in reps.iter().enumerate() {
        for &b in &reps[i + 1..] {
            let rho: Vec<String> = ranked
                .iter()
                .map(|&c| spearman(&values(a, c), &values(b, c)).map_or("–".into(), |r| format!("{r:.3}")))
                .collect();
            let _ = writeln!(md, "| {a} vs {b} | {} |", rho.join(" | "));
        }
    }
    // Each replicate's configurations by decreasing f, ties in configuration order.
    let order: BTreeMap<u64, Vec<usize>> = reps
        .iter()
        .map(|&k| {
            let f = values(k, ranked[0]);
            let mut o: Vec<usize> = (0..n).collect();
            o.sort_by(|&x, &y| f[y].total_cmp(&f[x]));
            (k, o)
        })
        .collect();
    let rank_of: BTreeMap<u64, Vec<usize>> = order
        .iter()
        .map(|(&k, o)| {
            let mut r = vec![0; n];
            for (pos, &i) in o.iter().enumerate() {
                r[i] = pos + 1;
            }
            (k, r)
        })
        .collect();
    let (top1, top10) = ((n / 100).max(1), (n / 10).max(1));
    let _ = writeln!(
        md,
        "\n| replicate | its best configuration: rank in the other replicates (of {n}) | its top 1 % still in the other \
         replicates' top 10 % |\n|---|---|---|"
    );
    for &k in &reps {
        if n == 0 {
            break;
        }
        let best = order[&k][0];
        let others: Vec<u64> = reps.iter().copied().filter(|&b| b != k).collect();
        let ranks: Vec<String> = others.iter().map(|b| rank_of[b][best].to_string()).collect();
        let kept: Vec<String> = others
            .iter()
            .map(|b| {
                let stayed = order[&k][..top1].iter().filter(|&&i| rank_of[b][i] <= top10).count();
                format!("{:.0}%", 100.0 * stayed as f64 / top1 as f64)
            })
            .collect();
        let _ = writeln!(md, "| {k} | {} | {} |", ranks.join(", "), kept.join(", "));
    }
    md.push_str(&thesis_cells(t));
    md.push_str(&infeasible(t, &by_cols, replicate, sweeps, executable));
    Ok(md)
}

/// The rows of `t` by configuration (column `config`) and replicate (column `replicate`), and
/// the replicates; refused with fewer than two replicates, which leave nothing to compare.
#[allow(clippy::type_complexity)]
fn replicates_of(
    t: &RunsTable,
    config: usize,
    replicate: usize,
) -> Result<(BTreeMap<&str, BTreeMap<u64, &Vec<String>>>, Vec<u64>), ReportError> {
    let mut by_config: BTreeMap<&str, BTreeMap<u64, &Vec<String>>> = BTreeMap::new();
    let mut reps = std::collections::BTreeSet::new();
    for r in &t.rows {
        let k: u64 = r[replicate].parse().map_err(|_| ReportError::Input(format!("replicate `{}`", r[replicate])))?;
        reps.insert(k);
        by_config.entry(&r[config]).or_default().insert(k, r);
    }
    let reps: Vec<u64> = reps.into_iter().collect();
    if reps.len() < 2 {
        return Err(ReportError::Input(format!(
            "--seed-to-seed compares replicates, and the runs hold {} (seeds = 2 or more in the grid makes more)",
            if reps.is_empty() { "none".to_string() } else { format!("only replicate {}", reps[0]) }
        )));
    }
    Ok((by_config, reps))
}

/// 003 Tables A.1/A.2 beside the same cells of the study, where the study has them.
fn thesis_cells(t: &RunsTable) -> String {
    let cols = ["map.source", "robot.rot_speed", "scorer.projection", "thesis.selection"].map(|c| t.col(c));
    let [Some(map), Some(rot), Some(proj), Some(sel)] = cols else { return String::new() };
    let (Some(f), Some(cov), Some(tf)) = (t.col("f_free"), t.col("cov_final_free"), t.col("t_final")) else {
        return String::new();
    };
    let num = |r: &Vec<String>, c: usize| r[c].parse::<f64>().unwrap_or(f64::NAN);
    let mut lines = Vec::new();
    for (m, r_rot, fitness, selection, tc, tt) in THESIS_BEST {
        let runs: Vec<&Vec<String>> = t
            .rows
            .iter()
            .filter(|r| r[map] == m && cell_matches(&r[rot], r_rot) && r[proj] == fitness && r[sel] == selection)
            .collect();
        let Some(best) = runs.iter().copied().reduce(|a, b| if num(b, f) > num(a, f) { b } else { a }) else {
            continue;
        };
        let covs: Vec<f64> = runs.iter().map(|r| num(r, cov)).collect();
        let ts: Vec<f64> = runs.iter().map(|r| num(r, tf)).collect();
        let reach = covs.iter().zip(&ts).filter(|&(&c, &t)| c >= tc && t >= tt).count();
        lines.push(format!(
            "| {m} | {r_rot} | {fitness} | {selection} | {tc:.3} / {tt:.3} | {:.3} / {:.3} | {:.3} / {:.3} | {} | {reach} ({:.1}%) |",
            num(best, cov),
            num(best, tf),
            quartiles(&covs).1,
            quartiles(&ts).1,
            runs.len(),
            100.0 * reach as f64 / runs.len() as f64
        ));
    }
    if lines.is_empty() {
        return String::new();
    }
    format!(
        "\n## 003 Tables A.1/A.2 beside this study\n\nPer cell: the thesis's best individual (one seed, its own \
         `C_len` values, some outside Table 4.3), the best run here by f over all configurations and seeds of the \
         cell, the median run (`cov_final` and `t_final` medians), and how many runs reach or dominate the thesis's \
         point in (`cov_final`, `t_final`).\n\n| map | R_rot | fitness | selection | thesis cov / t | best run cov / t \
         | median cov / t | runs | reach the thesis point |\n|---|---|---|---|---|---|---|---|---|\n{}\n",
        lines.join("\n")
    )
}

/// Runs whose plan sweeps obstacle cells, and runs whose plan is not executable, per replicate
/// and group.
fn infeasible(t: &RunsTable, by: &[usize], replicate: usize, sweeps: usize, executable: usize) -> String {
    let mut groups: BTreeMap<Vec<&str>, (usize, usize, usize)> = BTreeMap::new();
    for r in &t.rows {
        let mut key = vec![r[replicate].as_str()];
        key.extend(by.iter().map(|&c| r[c].as_str()));
        let g = groups.entry(key).or_default();
        g.0 += usize::from(r[sweeps].parse::<u64>().is_ok_and(|s| s > 0));
        g.1 += usize::from(r[executable] == "false");
        g.2 += 1;
    }
    let names: Vec<String> = by.iter().map(|&c| format!("`{}`", t.header[c])).collect();
    let mut md = String::from(
        "\n## Infeasible runs\n\nInfeasible: the best path's footprint rectangles sweep obstacle cells (003's penalty, \
         `obstacle_sweeps` > 0). Not executable: the robot's body touches a non-free cell anywhere on the path, \
         vertices and turns included (`executable` false).\n\n",
    );
    let head =
        [vec!["replicate".to_string()], names, ["infeasible runs", "not executable", "of"].map(String::from).to_vec()]
            .concat();
    let _ = writeln!(md, "| {} |\n|{}", head.join(" | "), "---|".repeat(head.len()));
    let pct = |k: usize, n: usize| format!("{k} ({:.1}%)", 100.0 * k as f64 / n as f64);
    for (key, (bad, body, n)) in groups {
        let _ = writeln!(md, "| {} | {} | {} | {n} |", key.join(" | "), pct(bad, n), pct(body, n));
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four configurations in two replicates; replicate 1 swaps the order of the two best.
    fn table() -> RunsTable {
        let mut text = String::from(
            "run_id,config_id,replicate,map.source,f_free,cov_final_free,t_final,obstacle_sweeps,executable\n",
        );
        for (k, fs) in [(0, [0.9, 0.8, 0.5, 0.1]), (1, [0.8, 0.9, 0.5, 0.1])] {
            for (c, f) in fs.iter().enumerate() {
                let sweeps = usize::from(c == 3);
                let executable = if c >= 2 { "false" } else { "true" };
                text.push_str(&format!("r{k}{c},c{c},{k},thesis-1,{f},{f},{f},{sweeps},{executable}\n"));
            }
        }
        RunsTable::parse(&text).unwrap()
    }

    #[test]
    fn replicates_are_compared_configuration_by_configuration() {
        let md = render(&table(), &["map.source".to_string()]).unwrap();
        // Ranks 1 2 3 4 against 2 1 3 4: ρ = 1 − 6·2 / (4·15) = 0.8.
        assert!(md.contains("| 0 vs 1 | 0.800 | 0.800 | 0.800 |"), "{md}");
        // Replicate 0's best (c0) is second in replicate 1, and the other way round; with four
        // configurations the top 1 % and the top 10 % are the best one, so none stays.
        assert!(md.contains("| 0 | 2 | 0% |"), "{md}");
        assert!(md.contains("| 1 | 2 | 0% |"), "{md}");
        // One of four runs sweeps obstacle cells, two are not executable, per replicate.
        assert!(md.contains("| 0 | thesis-1 | 1 (25.0%) | 2 (50.0%) | 4 |"), "{md}");
        // No selection or projection column: no thesis cells.
        assert!(!md.contains("Tables A.1/A.2"));
    }

    #[test]
    fn a_missing_column_is_named() {
        let t = RunsTable::parse("run_id,replicate\na,0\n").unwrap();
        let Err(ReportError::Input(m)) = render(&t, &[]) else { panic!("refused") };
        assert!(m.contains("config_id"), "{m}");
    }
}
