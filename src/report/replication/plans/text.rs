//! `plans.md`: the configurations' plans and final populations, each run against its map's
//! reference plan, and findings in words. Every number is a count, a median, a quartile or a
//! range of the runs' own values (`crate::stats::quartiles`); nothing is tested here — the
//! paired tests between a factor's values are `covga report --compare`'s.

use super::{EQUAL, HOLDS_TOLERANCE, Reference, RunPlans};
use crate::report::analysis::design::split_followers;
use crate::report::analysis::runs::{cmp_group_values, param_columns};
use crate::stats::quartiles;
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// The runs of one configuration (one value of every factor).
struct Config<'a> {
    values: Vec<String>,
    rows: Vec<&'a Vec<String>>,
}

/// A run against its map's reference plan.
struct Against {
    /// Coverage minus the reference's.
    coverage: f64,
    /// Time over the reference's, minus one.
    time: f64,
    /// At least as good on both.
    both: bool,
    /// `f_free` (the GA's own objective over all free cells) at least the reference's.
    fitter: bool,
}

/// The whole of `plans.md`.
/// What every table reads: the runs, their configurations and what their folders said.
struct View<'a> {
    t: &'a RunsTable,
    configs: Vec<Config<'a>>,
    /// The factors' column names, the map first.
    names: Vec<&'a str>,
    map: usize,
    id: usize,
    runs: &'a BTreeMap<String, RunPlans>,
    reference: Option<&'a Reference>,
    /// Whether the runs' folders held final populations.
    populations: bool,
    /// Whether the runs had a seed bound.
    bound: bool,
}

/// The whole of `plans.md`.
pub(super) fn markdown(t: &RunsTable, runs: &BTreeMap<String, RunPlans>, reference: Option<&Reference>) -> String {
    let map = super::map_column(t).expect("checked by render");
    let id = t.col("run_id").expect("checked by render");
    // The map first, so that what is set per map (budget, station) follows it.
    let params = param_columns(t);
    let mut candidates = vec![map];
    candidates.extend(params.iter().filter_map(|p| t.col(p)).filter(|&c| c != map));
    let (mut factors, followers) = split_followers(t, &candidates);
    if !factors.contains(&map) {
        factors.insert(0, map);
    }
    let mut configs: BTreeMap<Vec<String>, Vec<&Vec<String>>> = BTreeMap::new();
    for r in &t.rows {
        configs.entry(factors.iter().map(|&c| r[c].clone()).collect()).or_default().push(r);
    }
    let mut configs: Vec<Config> = configs.into_iter().map(|(values, rows)| Config { values, rows }).collect();
    configs.sort_by(|a, b| cmp_group_values(&a.values, &b.values));
    let has = |f: fn(&RunPlans) -> bool| t.rows.iter().any(|r| f(&runs[&r[id]]));
    let v = View {
        t,
        configs,
        names: factors.iter().map(|&c| t.header[c].as_str()).collect(),
        map,
        id,
        runs,
        reference,
        populations: has(|p| p.hypervolume.is_some()),
        bound: has(|p| p.within_bound.is_some()),
    };
    let mut md = String::from("# Plans and final populations\n\n");
    let _ = write!(
        md,
        "Written by `covga report --plans{}` from `runs.csv` and each run's folder (`plans.csv` beside this file holds \
         what the folders said, and the report reads it back where they are gone). {} runs, {} configurations. \
         Coverage is `cov_final_reach` (of the cells the robot can reach), time `time_s`, both of the common scorer; \
         medians [quartiles] over the runs of a configuration; coverage and time_s are over the executable plans \
         (– where there is none), with the median coverage of all plans beside them.",
        reference.map_or(String::new(), |r| format!(" --reference {}", r.file.display())),
        t.rows.len(),
        v.configs.len()
    );
    if v.populations {
        md.push_str(
            " HV is the hypervolume of the non-dominated set of the final population's members that sweep no obstacle \
             cell, in 003's two objectives (`cov_final`, `t_final`, both over all free cells) above (0, 0): a measure of \
             the whole population, not of the plan a run returns, and by construction larger for a population kept \
             spread along its front (NSGA-II) than for one driven to a single scalar's best; it is reported, not tested. \
             Front size: the distinct points of that set (members that score alike count once).",
        );
    }
    if !followers.is_empty() {
        let set: Vec<String> = followers.iter().map(|(c, of)| format!("`{}` (set by {of})", t.header[*c])).collect();
        let _ = write!(md, " Not factors of their own: {}.", set.join(", "));
    }
    md.push_str("\n\n");
    md.push_str(&v.findings());
    md.push_str(&v.settings_table());
    md.push_str(&v.reference_table());
    md
}

impl View<'_> {
    fn plan(&self, r: &[String]) -> &RunPlans {
        &self.runs[&r[self.id]]
    }

    /// A run against its map's reference plan; `None` without a reference.
    fn against(&self, r: &[String]) -> Option<Against> {
        let reference = self.reference?;
        let (t, m) = (self.t, &r[self.map]);
        let (rc, rt, rf) =
            (reference.num(m, "cov_final_reach")?, reference.num(m, "time_s")?, reference.num(m, "f_free")?);
        let (c, time, f) = (t.num(r, "cov_final_reach")?, t.num(r, "time_s")?, t.num(r, "f_free")?);
        let (coverage, time) = (c - rc, time / rt - 1.0);
        Some(Against { coverage, time, both: coverage >= -EQUAL && time <= EQUAL, fitter: f >= rf - EQUAL })
    }

    /// The factor values of a configuration, as the tables print them.
    fn cells(&self, c: &Config) -> Vec<String> {
        self.names.iter().zip(&c.values).map(|(n, v)| shown(n, v)).collect()
    }

    /// The table's head: the factors, then `columns`.
    fn head(&self, columns: &[&str]) -> String {
        let mut head: Vec<String> = self.names.iter().map(|n| format!("`{n}`")).collect();
        head.extend(columns.iter().map(|c| c.to_string()));
        format!("| {} |\n|{}\n", head.join(" | "), "---|".repeat(head.len()))
    }
}

/// `a to b`, or `a` where both read the same.
fn span(values: &[f64], fmt: impl Fn(f64) -> String) -> String {
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (a, b) = (fmt(lo), fmt(hi));
    if a == b { a } else { format!("{a} to {b}") }
}

fn median(values: &[f64]) -> f64 {
    quartiles(values).1
}

/// `median [q1, q3]` with `digits` decimals, `–` for no values.
fn median_iqr(values: &[f64], digits: usize) -> String {
    if values.is_empty() {
        return "–".into();
    }
    let (q1, m, q3) = quartiles(values);
    format!("{m:.digits$} [{q1:.digits$}, {q3:.digits$}]")
}

fn percent(x: f64) -> String {
    format!("{:+.1}%", 100.0 * x)
}

/// A factor's value as the tables print it: a map by its file's stem.
fn shown(name: &str, value: &str) -> String {
    if name == "map.source" || name == "map" {
        std::path::Path::new(value).file_stem().map_or(value, |s| s.to_str().unwrap_or(value)).to_string()
    } else {
        value.to_string()
    }
}

fn executable(t: &RunsTable, rows: &[&Vec<String>]) -> Vec<usize> {
    let e = t.col("executable");
    (0..rows.len()).filter(|&i| e.is_some_and(|c| rows[i][c] == "true")).collect()
}

impl View<'_> {
    /// Every configuration's runs: executable, coverage, time, populations, the seed bound;
    /// after each map's configurations, its reference plan.
    fn settings_table(&self) -> String {
        let t = self.t;
        let mut md = String::from("## Every configuration\n\n");
        let mut columns = vec!["runs", "executable", "coverage", "time_s", "coverage (all plans)"];
        if self.populations {
            columns.extend(["HV", "front size"]);
        }
        if self.bound {
            columns.push("within the seed bound");
        }
        md.push_str(&self.head(&columns));
        for (k, c) in self.configs.iter().enumerate() {
            let n = c.rows.len();
            let ok = executable(t, &c.rows);
            let col = |name: &str, which: &[usize]| -> Vec<f64> {
                which.iter().filter_map(|&i| t.num(c.rows[i], name)).collect()
            };
            let all: Vec<usize> = (0..n).collect();
            let mut cells = self.cells(c);
            cells.push(n.to_string());
            cells.push(format!("{}/{n}", ok.len()));
            cells.push(median_iqr(&col("cov_final_reach", &ok), 4));
            cells.push(median_iqr(&col("time_s", &ok), 0));
            cells.push(format!("{:.4}", median(&col("cov_final_reach", &all))));
            let plans: Vec<&RunPlans> = c.rows.iter().map(|r| self.plan(r)).collect();
            if self.populations {
                let hv: Vec<f64> = plans.iter().filter_map(|p| p.hypervolume).collect();
                let front: Vec<f64> = plans.iter().filter_map(|p| p.front_size.map(|s| s as f64)).collect();
                cells.push(median_iqr(&hv, 4));
                cells.push(if front.is_empty() { "–".into() } else { format!("{}", median(&front)) });
            }
            if self.bound {
                cells.push(count(plans.iter().filter_map(|p| p.within_bound)));
            }
            let _ = writeln!(md, "| {} |", cells.join(" | "));
            let last_of_map = self.configs.get(k + 1).is_none_or(|next| next.rows[0][self.map] != c.rows[0][self.map]);
            if last_of_map {
                md.push_str(&self.reference_row(&c.rows[0][self.map]));
            }
        }
        md.push('\n');
        md
    }

    /// The row of `map`'s reference plan in the table of every configuration.
    fn reference_row(&self, map: &str) -> String {
        let Some(r) = self.reference else { return String::new() };
        let row = &r.table.rows[r.by_map[map]];
        let num = |name: &str| r.table.num(row, name).unwrap_or(f64::NAN);
        let mut cells: Vec<String> = (0..self.names.len())
            .map(|k| match k {
                0 => shown("map.source", map),
                1 => "the reference plan".into(),
                _ => "–".into(),
            })
            .collect();
        if self.names.len() == 1 {
            cells[0] = format!("{} (the reference plan)", shown("map.source", map));
        }
        let executable = r.table.col("executable").is_some_and(|e| row[e] == "true");
        cells.push("1".into());
        cells.push(if executable { "1/1" } else { "0/1" }.into());
        cells.push(if executable { format!("{:.4}", num("cov_final_reach")) } else { "–".into() });
        cells.push(if executable { format!("{:.0}", num("time_s")) } else { "–".into() });
        cells.push(format!("{:.4}", num("cov_final_reach")));
        cells.extend((0..usize::from(self.populations) * 2 + usize::from(self.bound)).map(|_| "–".to_string()));
        format!("| {} |\n", cells.join(" | "))
    }

    /// Each configuration's runs against their map's reference plan.
    fn reference_table(&self) -> String {
        let Some(r) = self.reference else { return String::new() };
        let mut md = String::from("## Each run against its map's reference plan\n\n");
        let _ = writeln!(
            md,
            "Every run, executable or not, against the plan of its map in `{}`: coverage minus the reference's \
             (median), time_s over the reference's minus one (median and range), how many runs are at least as good \
             on both (coverage at least and time_s at most the reference's; differences below {EQUAL:e}, in coverage \
             or in time relative to the reference's, count as equal) and how many end with `f_free` (the GA's \
             objective over all free cells, 003 eq. 3.15) at least the reference's.{}\n",
            r.file.display(),
            if self.populations {
                format!(
                    " Then how many final populations still hold a member that sweeps no obstacle cell and is at \
                     least as good as the reference plan on both `cov_final` and `t_final` (within \
                     {HOLDS_TOLERANCE:e} relative), and the best `cov_final` of the initial population, the \
                     reference plan's own beside it (a seed genome scores as the plan it encodes up to a few cells)."
                )
            } else {
                String::new()
            }
        );
        let mut columns =
            vec!["coverage − reference", "time change (median, range)", "≥ reference on both", "f_free ≥ reference's"];
        if self.populations {
            columns
                .extend(["population holds a plan ≥ reference", "initial population's best cov_final (reference's)"]);
        }
        md.push_str(&self.head(&columns));
        for c in &self.configs {
            let a: Vec<Against> = c.rows.iter().filter_map(|r| self.against(r)).collect();
            if a.is_empty() {
                continue;
            }
            let dc: Vec<f64> = a.iter().map(|x| x.coverage).collect();
            let dt: Vec<f64> = a.iter().map(|x| x.time).collect();
            let mut cells = self.cells(c);
            cells.push(format!("{:+.4}", median(&dc)));
            cells.push(format!("{} ({})", percent(median(&dt)), span(&dt, percent)));
            cells.push(count(a.iter().map(|x| x.both)));
            cells.push(count(a.iter().map(|x| x.fitter)));
            if self.populations {
                let plans: Vec<&RunPlans> = c.rows.iter().map(|r| self.plan(r)).collect();
                cells.push(count(plans.iter().filter_map(|p| p.holds_reference)));
                let start: Vec<f64> = plans.iter().filter_map(|p| p.start_max_cov_final).collect();
                let own = r.num(&c.rows[0][self.map], "cov_final_free").unwrap_or(f64::NAN);
                cells.push(if start.is_empty() { "–".into() } else { format!("{:.4} ({own:.4})", median(&start)) });
            }
            let _ = writeln!(md, "| {} |", cells.join(" | "));
        }
        md.push('\n');
        md
    }

    /// The findings in words, each built from the tables' own numbers.
    fn findings(&self) -> String {
        let t = self.t;
        let mut lines = Vec::new();
        let ok = executable(t, &t.rows.iter().collect::<Vec<_>>()).len();
        lines.push(format!("**Executable**: {ok} of {} plans (per configuration in the first table).", t.rows.len()));
        let within: Vec<bool> = t.rows.iter().filter_map(|r| self.plan(r).within_bound).collect();
        if !within.is_empty() {
            lines.push(format!(
                "**The seed bound holds**: {} of {} runs with a seed bound report a plan within it (`cov_final` and \
                 `t_final` both at least a seed plan's).",
                within.iter().filter(|&&w| w).count(),
                within.len()
            ));
        }
        if self.reference.is_some() {
            let a: Vec<Against> = t.rows.iter().filter_map(|r| self.against(r)).collect();
            let both = a.iter().filter(|x| x.both).count();
            let dt: Vec<f64> = a.iter().map(|x| x.time).collect();
            let dc: Vec<f64> = a.iter().map(|x| x.coverage).collect();
            lines.push(format!(
                "**Against the reference plan**: {both} of {} runs are at least as good on both coverage and time_s; \
                 {} of {} end with `f_free` at least the reference's. Over all of them time_s changes by {} and \
                 coverage by {}{}",
                a.len(),
                a.iter().filter(|x| x.fitter).count(),
                a.len(),
                span(&dt, percent),
                span(&dc, |x| format!("{x:+.4}")),
                if both == 0 && !a.is_empty() { ": no run improves on both at once." } else { "." }
            ));
            lines.extend(self.factor_findings());
        }
        lines.extend(self.best_per_map());
        let mut md = String::from("## Findings\n\n");
        for (k, line) in lines.iter().enumerate() {
            let _ = writeln!(md, "{}. {line}", k + 1);
        }
        md.push('\n');
        md
    }

    /// Per value of each factor but the map: the median changes against the reference per
    /// configuration, and how many final populations still hold a plan as good as it.
    fn factor_findings(&self) -> Vec<String> {
        let mut lines = Vec::new();
        for (k, name) in self.names.iter().enumerate().skip(1) {
            let mut values: Vec<&String> = self.configs.iter().map(|c| &c.values[k]).collect();
            values.sort_by(|a, b| cmp_group_values(&[(*a).clone()], &[(*b).clone()]));
            values.dedup();
            for v in values {
                let of_value: Vec<&Config> = self.configs.iter().filter(|c| &c.values[k] == v).collect();
                let medians = |f: fn(&Against) -> f64| -> Vec<f64> {
                    of_value
                        .iter()
                        .filter_map(|c| {
                            let x: Vec<f64> = c.rows.iter().filter_map(|r| self.against(r)).map(|a| f(&a)).collect();
                            (!x.is_empty()).then(|| median(&x))
                        })
                        .collect()
                };
                let (mt, mc) = (medians(|a| a.time), medians(|a| a.coverage));
                if mt.is_empty() {
                    continue;
                }
                let held: Vec<bool> =
                    of_value.iter().flat_map(|c| c.rows.iter().filter_map(|r| self.plan(r).holds_reference)).collect();
                let mut line = format!(
                    "**`{name}` = `{v}`**: the median time change against the reference per configuration is {}, the \
                     median coverage change {}",
                    span(&mt, percent),
                    span(&mc, |x| format!("{x:+.4}"))
                );
                if !held.is_empty() {
                    let _ = write!(
                        line,
                        "; the final population still holds a plan at least as good as the reference on both \
                         objectives in {} of {} runs",
                        held.iter().filter(|&&h| h).count(),
                        held.len()
                    );
                }
                line.push('.');
                lines.push(line);
            }
        }
        lines
    }

    /// Per map, the configuration with the highest median coverage of executable plans.
    fn best_per_map(&self) -> Option<String> {
        let mut best = Vec::new();
        let mut maps: Vec<&String> = self.configs.iter().map(|c| &c.rows[0][self.map]).collect();
        maps.dedup();
        for m in maps {
            let scored = self.configs.iter().filter(|c| &c.rows[0][self.map] == m).filter_map(|c| {
                let ok = executable(self.t, &c.rows);
                let cov: Vec<f64> = ok.iter().filter_map(|&i| self.t.num(c.rows[i], "cov_final_reach")).collect();
                (!cov.is_empty()).then(|| (median(&cov), c))
            });
            if let Some((cov, c)) = scored.max_by(|a, b| a.0.total_cmp(&b.0)) {
                let set: Vec<String> =
                    self.names.iter().zip(&c.values).skip(1).map(|(name, v)| format!("{name} = {v}")).collect();
                best.push(format!("{}: {} ({cov:.4})", shown("map.source", m), set.join(", ")));
            }
        }
        (!best.is_empty()).then(|| {
            format!(
                "**The configuration with the highest median coverage of executable plans**, per map: {}.",
                best.join("; ")
            )
        })
    }
}

/// `k/n`: how many of the answers are yes; `–` for none.
fn count(answers: impl Iterator<Item = bool>) -> String {
    let (mut yes, mut n) = (0, 0);
    for a in answers {
        yes += usize::from(a);
        n += 1;
    }
    if n == 0 { "–".into() } else { format!("{yes}/{n}") }
}
