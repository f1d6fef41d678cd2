//! The runs of a planner comparison by map and planner, and what is written of them: the table
//! of every common metric per planner, the pairwise tests, the 2 × 2 of search and objective
//! and the findings in words ([`super::ablation`] puts them together, [`super::ablation_plots`]
//! draws them).

use super::search_objective::{self, MapRuns};
use crate::report::analysis::ReportError;
use crate::report::analysis::level::{Basis, TimeMeasure};
use crate::report::analysis::runs::param_columns;
use crate::stats::{a12_magnitude, holm, mann_whitney_u, quartiles, vargha_delaney_a12};
use crate::study::records::RunsTable;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::Path;

/// The metrics tabulated per planner: column, heading, decimals.
const TABLE: [(&str, &str, usize); 10] = [
    ("cov_final_reach", "cov_final (reachable)", 3),
    ("cov_final_free", "cov_final (all free)", 3),
    ("t_final", "t_final", 3),
    ("f_reach", "f (reachable)", 3),
    ("cam_walls_free", "camera walls", 3),
    ("cam_open_free", "camera open", 3),
    ("length_m", "length [m]", 0),
    ("time_s", "time [s]", 0),
    ("turns", "turns", 0),
    ("obstacle_cells", "obstacle cells", 0),
];

/// The measures tested between planners: the common scorer's, which every planner shares
/// (003's `t_final` and `f` are one GA's own and do not compare planners); `time_s` stands for
/// the map's time measure ([`Comparing::time_measure`]).
const TESTED: [&str; 3] = ["cov_final_reach", "time_s", "cam_walls_free"];

/// A map's short name: its file stem.
pub(super) fn short_map(source: &str) -> String {
    Path::new(source).file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| source.to_string())
}

/// The finding of a seeded variant's executable plans `runs` against the plan it was seeded
/// with (`plan`, one row: a deterministic pattern), or `None` where either is missing.
fn against_seed(
    map: &str,
    variant: &str,
    seed: &str,
    runs: &[usize],
    plan: &[usize],
    (num, measure): (impl Fn(usize, &str) -> f64, &TimeMeasure),
) -> Option<String> {
    let &[p] = plan else { return None };
    if runs.is_empty() {
        return None;
    }
    let column = measure.column;
    let (cp, tp) = (num(p, "cov_final_reach"), num(p, column));
    let median = |c: &str| quartiles(&runs.iter().map(|&r| num(r, c)).collect::<Vec<_>>()).1;
    let (cov, time) = (median("cov_final_reach"), median(column));
    let both = runs.iter().filter(|&&r| num(r, "cov_final_reach") >= cp && num(r, column) <= tp).count();
    Some(format!(
        "On {map}, {variant}, whose initial population holds the {seed} plan, against that plan: median coverage {cov:.3} against {cp:.3}, median {} {time:.0} s against {tp:.0} s ({:+.1} %); {both} of {} plans at least as good on both.",
        measure.name(),
        100.0 * (time / tp - 1.0),
        runs.len()
    ))
}

/// A swept value as it reads in a label: a list's items joined by `+` without brackets or
/// quotes (`["boustrophedon"]` → `boustrophedon`, `[]` → nothing), anything else as it is.
fn label_part(v: &str) -> String {
    match v.strip_prefix('[').and_then(|v| v.strip_suffix(']')) {
        Some(items) => {
            items.split(',').map(|i| i.trim().trim_matches('"')).filter(|i| !i.is_empty()).collect::<Vec<_>>().join("+")
        }
        None => v.to_string(),
    }
}

/// A planner's label: its name plus the text values of the swept keys that tell its variants
/// apart on one map (e.g. `thesis-prws`); numeric values and map-wide settings are left out.
fn labels(t: &RunsTable) -> Vec<String> {
    let params: Vec<String> = param_columns(t).into_iter().filter(|p| p != "map.source" && p != "planner").collect();
    let (pc, mc) = (t.col("planner").unwrap_or(0), t.col("map").unwrap_or(0));
    let varying: Vec<usize> = params
        .iter()
        .filter_map(|p| t.col(p))
        .filter(|&c| {
            let mut by_map: BTreeMap<&str, std::collections::BTreeSet<&str>> = BTreeMap::new();
            for r in &t.rows {
                by_map.entry(&r[mc]).or_default().insert(&r[c]);
            }
            by_map.values().any(|v| v.len() > 1)
        })
        .collect();
    t.rows
        .iter()
        .map(|r| {
            let mut l = r[pc].clone();
            for &c in &varying {
                let v = label_part(&r[c]);
                if !v.is_empty() && v.parse::<f64>().is_err() && v != r[pc] {
                    l.push('-');
                    l.push_str(&v);
                }
            }
            l
        })
        .collect()
}

/// A planner comparison: the runs with each row's planner label, the maps in order of first
/// appearance and the labels in the registry's order of their planners.
pub(super) struct Comparing<'a> {
    pub t: &'a RunsTable,
    label: Vec<String>,
    /// The `map` column.
    mc: usize,
    pub maps: Vec<String>,
    pub variants: Vec<String>,
    /// Variants whose initial population holds a planner's plan (`thesis.seed_population`):
    /// compared with that plan, not with random search.
    seeded: BTreeMap<String, String>,
    /// Variants of the thesis GA optimising the camera (`thesis.objective`): random search
    /// draws for the footprint's fitness, so their footprint coverage is not its to compare.
    camera_objective: BTreeSet<String>,
}

/// (map, metric, first, second) -> (Holm p, A12) of the pairs tested, for the sentences.
type Tested = BTreeMap<(String, &'static str, String, String), (f64, f64)>;

/// What the comparison writes as it goes through the maps.
#[derive(Default)]
pub(super) struct Written {
    pub(super) md: String,
    /// `planners.csv`.
    pub(super) csv: String,
    /// `pairwise.csv`.
    pub(super) pair_csv: String,
    pub(super) findings: Vec<String>,
    pub(super) tested: Tested,
    /// The rows of the search-versus-objective table, on the maps that have all four cells.
    pub(super) two_by_two: String,
}

impl<'a> Comparing<'a> {
    pub(super) fn new(t: &'a RunsTable) -> Result<Self, ReportError> {
        let label = labels(t);
        let mc = t.col("map").ok_or_else(|| ReportError::Input("runs.csv has no `map` column".into()))?;
        let mut maps: Vec<String> = Vec::new();
        for r in &t.rows {
            if !maps.contains(&r[mc]) {
                maps.push(r[mc].clone());
            }
        }
        let order: Vec<&str> = crate::experiment::registry::PlannerKind::all().iter().map(|k| k.name()).collect();
        let mut variants: Vec<String> = label.clone();
        variants.sort_by_key(|l| (order.iter().position(|o| l.starts_with(o)).unwrap_or(order.len()), l.clone()));
        variants.dedup();
        let seeded = t
            .col("thesis.seed_population")
            .map(|c| {
                (0..t.rows.len())
                    .map(|r| (label[r].clone(), label_part(&t.rows[r][c])))
                    .filter(|(_, seed)| !seed.is_empty())
                    .collect()
            })
            .unwrap_or_default();
        let camera_objective = t
            .col("thesis.objective")
            .map(|c| (0..t.rows.len()).filter(|&r| t.rows[r][c] == "camera").map(|r| label[r].clone()).collect())
            .unwrap_or_default();
        Ok(Self { t, label, mc, maps, variants, seeded, camera_objective })
    }

    /// A number of row `r` (NaN where absent).
    pub fn num(&self, r: usize, c: &str) -> f64 {
        self.t.num(&self.t.rows[r], c).unwrap_or(f64::NAN)
    }

    /// Whether row `r`'s column `c` is `true`.
    pub fn flag(&self, r: usize, c: &str) -> bool {
        self.t.col(c).is_some_and(|i| self.t.rows[r][i] == "true")
    }

    /// Every run of variant `v` on `map`.
    pub fn all_rows_of(&self, map: &str, v: &str) -> Vec<usize> {
        (0..self.t.rows.len()).filter(|&r| self.t.rows[r][self.mc] == map && self.label[r] == v).collect()
    }

    /// The executable runs of variant `v` on `map`: tables, tests and findings compare plans a
    /// robot can drive (its body touches no occupied, unknown or off-map cell); the share and
    /// the all-plans coverage stand beside them.
    pub fn rows_of(&self, map: &str, v: &str) -> Vec<usize> {
        self.all_rows_of(map, v).into_iter().filter(|&r| self.flag(r, "executable")).collect()
    }

    /// The time the plans on `map` are compared on: mission time where their reachable
    /// coverage is equal, else the time to the highest level all of them reach.
    pub fn time_measure(&self, map: &str) -> TimeMeasure {
        let rows: Vec<usize> = (0..self.t.rows.len()).filter(|&r| self.t.rows[r][self.mc] == map).collect();
        TimeMeasure::of(self.t, &rows)
    }

    /// The variants with a run on `map` (`executable`: with an executable one).
    fn present(&self, map: &str, executable: bool) -> Vec<&String> {
        let rows = |v: &str| if executable { self.rows_of(map, v) } else { self.all_rows_of(map, v) };
        self.variants.iter().filter(|v| !rows(v).is_empty()).collect()
    }

    /// The table of one map: each variant's runs, executable and feasible shares, and the
    /// median [quartiles] of every metric of [`TABLE`].
    pub(super) fn map_table(&self, map: &str, name: &str, w: &mut Written) {
        let measure = self.time_measure(map);
        let _ = writeln!(w.md, "### {name}\n");
        let _ = writeln!(w.md, "{}\n", measure.sentence());
        let level = matches!(measure.basis, Basis::Level(_)).then_some(measure.column);
        let mut columns: Vec<(&str, String, usize)> = TABLE.iter().map(|&(c, h, d)| (c, h.to_string(), d)).collect();
        if let Some(c) = level {
            columns.push((c, format!("{} [s]", measure.name()), 0));
        }
        let _ = writeln!(
            w.md,
            "| planner | runs | executable | planner-feasible | {} | cov (all plans) |",
            columns.iter().map(|(_, h, _)| h.as_str()).collect::<Vec<_>>().join(" | ")
        );
        let _ = writeln!(w.md, "|---|---|---|---|{}---|", "---|".repeat(columns.len()));
        for v in self.present(map, false) {
            let all = self.all_rows_of(map, v);
            let rows = self.rows_of(map, v);
            let feasible = all.iter().filter(|&&r| self.flag(r, "planner_feasible")).count();
            let mut cells = Vec::new();
            for &(c, _, d) in &columns {
                let vals: Vec<f64> = rows.iter().map(|&r| self.num(r, c)).collect();
                if vals.is_empty() {
                    cells.push("–".to_string());
                    continue;
                }
                let (q1, med, q3) = quartiles(&vals);
                let mean = vals.iter().sum::<f64>() / vals.len() as f64;
                let _ = writeln!(w.csv, "{name},{v},{c},{},{med},{q1},{q3},{mean}", vals.len());
                cells.push(if vals.len() > 1 {
                    format!("{med:.d$} [{q1:.d$}, {q3:.d$}]")
                } else {
                    format!("{med:.d$}")
                });
            }
            let cov_all = quartiles(&all.iter().map(|&r| self.num(r, "cov_final_reach")).collect::<Vec<_>>()).1;
            let _ = writeln!(
                w.md,
                "| {v} | {n} | {}/{n} | {feasible}/{n} | {} | {cov_all:.3} |",
                rows.len(),
                cells.join(" | "),
                n = all.len()
            );
        }
    }

    /// Pairwise two-sided Mann–Whitney U tests on one map, Holm-corrected over the pairs of a
    /// metric, with A₁₂; a GA against random search in words.
    pub(super) fn pairwise_tests(&self, map: &str, name: &str, w: &mut Written) {
        let _ = writeln!(
            w.md,
            "\nPairwise two-sided Mann–Whitney U tests (Holm-corrected over the pairs of a metric), A₁₂ = P(first > second):\n"
        );
        let _ = writeln!(w.md, "| metric | first | second | p (Holm) | A₁₂ | effect |\n|---|---|---|---|---|---|");
        type Sample<'a> = (&'a String, Vec<usize>);
        let (samples, too_few): (Vec<Sample>, Vec<Sample>) =
            self.present(map, true).into_iter().map(|v| (v, self.rows_of(map, v))).partition(|(_, r)| r.len() >= 2);
        let time = self.time_measure(map).column;
        for metric in TESTED.map(|m| if m == "time_s" { time } else { m }) {
            let mut pairs = Vec::new();
            for i in 0..samples.len() {
                for j in i + 1..samples.len() {
                    let a: Vec<f64> = samples[i].1.iter().map(|&r| self.num(r, metric)).collect();
                    let b: Vec<f64> = samples[j].1.iter().map(|&r| self.num(r, metric)).collect();
                    let a12 = vargha_delaney_a12(&a, &b);
                    let test = mann_whitney_u(&a, &b);
                    pairs.push((samples[i].0, samples[j].0, a.len(), b.len(), test, a12));
                }
            }
            let raw: Vec<f64> = pairs.iter().map(|p| p.4.map_or(1.0, |t| t.p_value)).collect();
            let adjusted = holm(&raw);
            for (k, (a, b, na, nb, test, a12)) in pairs.iter().enumerate() {
                let u = test.map_or(f64::NAN, |t| t.u);
                let _ = writeln!(w.pair_csv, "{name},{metric},{a},{b},{na},{nb},{u},{},{},{a12}", raw[k], adjusted[k]);
                w.tested.insert((name.to_string(), metric, a.to_string(), b.to_string()), (adjusted[k], *a12));
                let _ = writeln!(
                    w.md,
                    "| {metric} | {a} | {b} | {:.2e} | {a12:.2} | {} |",
                    adjusted[k],
                    a12_magnitude(*a12)
                );
                if metric == "cov_final_reach"
                    && b.as_str() == "random_search"
                    && a.starts_with("thesis")
                    && !self.seeded.contains_key(*a)
                    && !self.camera_objective.contains(*a)
                {
                    w.findings.push(format!(
                        "On {name}, {a} against random search with the same evaluations: A₁₂ = {a12:.2} ({}), Holm-corrected p = {:.1e}: the GA's machinery {} coverage here.",
                        a12_magnitude(*a12),
                        adjusted[k],
                        if adjusted[k] < 0.05 && *a12 > 0.5 { "improves" } else if adjusted[k] < 0.05 { "worsens" } else { "does not detectably change" }
                    ));
                }
            }
        }
        let sizes = |i: usize| samples[i].1.len();
        let extreme = (0..samples.len())
            .flat_map(|i| (i + 1..samples.len()).map(move |j| (i, j)))
            .filter_map(|(i, j)| {
                let apart = crate::stats::design::groups_apart(&[sizes(i), sizes(j)]);
                mann_whitney_u(&apart[0], &apart[1]).map(|t| t.p_value)
            })
            .fold(1.0, f64::min);
        let tests = samples.len() * samples.len().saturating_sub(1) / 2;
        if !too_few.is_empty() {
            let named: Vec<String> = too_few.iter().map(|(v, r)| format!("{v} ({} executable)", r.len())).collect();
            let _ = writeln!(w.md, "\nNot tested (fewer than two executable plans): {}.", named.join(", "));
        }
        let best = "the test of its largest groups, wholly apart";
        if let Some(floor) = crate::stats::family::floor(tests, extreme, 0.05, best) {
            let _ = writeln!(w.md, "\n{} Each metric's pairs are a family of their own.", floor.sentence);
        }
        let _ = writeln!(w.md);
    }

    /// Search against objective (`search_objective`: one search with two objectives, and two
    /// searches with one objective) and seeded variants against their seed, on one map.
    pub(super) fn designed_findings(&self, map: &str, name: &str, w: &mut Written) {
        let tested = &w.tested;
        let pair = |a: &str, b: &str, metric: &str| {
            let key = |a: &str, b: &str| (name.to_string(), metric, a.to_string(), b.to_string());
            let swap = |&(p, x): &(f64, f64)| (p, 1.0 - x);
            tested.get(&key(a, b)).copied().or_else(|| tested.get(&key(b, a)).map(swap))
        };
        let split = |v: &str| {
            let all = self.all_rows_of(map, v);
            let exec = all.iter().copied().filter(|&r| self.flag(r, "executable")).collect();
            (all, exec)
        };
        let num = |r: usize, c: &str| self.num(r, c);
        let measure = self.time_measure(map);
        let cell_list: Vec<(&String, Option<(&'static str, &'static str)>)> = self
            .present(map, false)
            .into_iter()
            .map(|v| {
                let first = self.all_rows_of(map, v)[0];
                (v, search_objective::cell_of(&|c: &str| self.t.col(c).map(|i| self.t.rows[first][i].clone())))
            })
            .collect();
        let cells = MapRuns { name, cells: &cell_list, rows: &split, num: &num, pair: &pair };
        if cells.complete() {
            cells.table_rows(&mut w.two_by_two);
        }
        let mut found = cells.findings();
        for (v, seed) in &self.seeded {
            let (runs, plan) = (self.rows_of(map, v), self.rows_of(map, seed));
            found.extend(against_seed(name, v, seed, &runs, &plan, (num, &measure)));
        }
        w.findings.extend(found);
    }

    /// The coverage and time leaders of one map, and the plans left out and why.
    pub(super) fn leaders_and_left_out(&self, map: &str, name: &str, w: &mut Written) {
        let present = self.present(map, true);
        let med = |v: &String, c: &str| {
            quartiles(&self.rows_of(map, v).iter().map(|&r| self.num(r, c)).collect::<Vec<_>>()).1
        };
        let mut by_cov: Vec<&String> = present.clone();
        by_cov.sort_by(|a, b| med(b, "cov_final_reach").total_cmp(&med(a, "cov_final_reach")));
        let measure = self.time_measure(map);
        let time = measure.column;
        let mut by_time: Vec<&String> = present.clone();
        by_time.sort_by(|a, b| med(a, time).total_cmp(&med(b, time)));
        if let (Some(first), Some(fast)) = (by_cov.first(), by_time.first()) {
            let ranking: Vec<String> = by_cov.iter().map(|v| format!("{v} {:.3}", med(v, "cov_final_reach"))).collect();
            let (t_fast, t_first) = (med(fast, time), med(first, time));
            let which = match measure.basis {
                Basis::EqualCoverage => "shortest median mission time (every plan covers the same share)".to_string(),
                Basis::Level(l) => format!(
                    "shortest median time to {:.0} % of the reachable cells (the highest level every plan reaches; \
                     mission times are not compared across unequal coverage)",
                    l * 100.0
                ),
                Basis::Unavailable => "shortest median mission time, although the plans stop at different coverage \
                                       (their curves are not here to compare them at one level)"
                    .to_string(),
            };
            let leaders = match fast == first {
                true => format!("{first} covers most and has the {which}: {t_fast:.0} s"),
                false => format!(
                    "{first} covers most, {fast} has the {which}: {t_fast:.0} s, against {t_first:.0} s for {first}"
                ),
            };
            w.findings.push(format!(
                "On {name}, median coverage of the reachable cells ranks {}; {leaders}.",
                ranking.join(" > "),
            ));
        }
        let count_of = |f: &dyn Fn(usize) -> bool| -> Vec<String> {
            self.present(map, false)
                .into_iter()
                .filter_map(|v| {
                    let all = self.all_rows_of(map, v);
                    let bad = all.iter().filter(|&&r| f(r)).count();
                    (bad > 0).then(|| format!("{v} {bad}/{}", all.len()))
                })
                .collect()
        };
        let not_executable = count_of(&|r| !self.flag(r, "executable"));
        if !not_executable.is_empty() {
            w.findings.push(format!(
                "On {name}, plans a robot cannot drive (its body touches an occupied, unknown or off-map cell), left out of the medians, tests and rankings above: {}.",
                not_executable.join(", ")
            ));
        }
        let infeasible = count_of(&|r| self.flag(r, "executable") && !self.flag(r, "planner_feasible"));
        if !infeasible.is_empty() {
            w.findings.push(format!(
                "On {name}, executable plans that break their planner's own constraints (loop closures, connectivity or the coverage ramp for the waypoint planner): {}.",
                infeasible.join(", ")
            ));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::label_part;

    #[test]
    fn list_values_read_as_their_items() {
        for (value, label) in [
            (r#"["boustrophedon"]"#, "boustrophedon"),
            (r#"["boustrophedon", "spiral"]"#, "boustrophedon+spiral"),
            ("[]", ""),
            ("prws", "prws"),
            ("0.5", "0.5"),
        ] {
            assert_eq!(label_part(value), label, "{value}");
        }
    }
}
