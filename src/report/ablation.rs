//! The planner comparison of a study with several planners (the ablation): per map, the
//! median [IQR] of every common metric per planner, pairwise Mann–Whitney U tests with Holm's
//! correction and Vargha–Delaney `A₁₂` effect sizes, box plots, convergence curves of the GAs,
//! the best path of each planner on each map, and findings in plain words derived from those
//! numbers. Planners are compared only through the common scorer's columns.

use super::ablation_figures::{BoxFigure, BoxSeries, ConvergenceFigure, Curve, PlannerPathsFigure};
use super::search_objective::{self, MapRuns};
use super::{ReportError, param_columns};
use crate::coverage::CoverageGrid;
use crate::plot::path::PathFigure;
use crate::stats::{a12_magnitude, holm, mann_whitney_u, quartiles, vargha_delaney_a12};
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
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

/// A best run loaded for its panel: map, visit grid, plan, robot width, title.
type LoadedPanel = (crate::map::GridMap, CoverageGrid, Vec<Vec<crate::geom::Point>>, f64, String);

/// The metrics tested pairwise.
const TESTED: [&str; 4] = ["cov_final_reach", "t_final", "f_reach", "cam_walls_free"];

/// Where the comparison's figures and tables go, and what it found.
pub struct Comparison {
    /// The markdown section.
    pub markdown: String,
}

fn short_map(source: &str) -> String {
    Path::new(source).file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| source.to_string())
}

/// Whether the runs table holds several planners.
pub fn applies(t: &RunsTable) -> bool {
    let Some(c) = t.col("planner") else { return false };
    t.rows.iter().map(|r| &r[c]).collect::<std::collections::BTreeSet<_>>().len() > 1
}

/// The finding of a seeded variant's executable plans `runs` against the plan it was seeded
/// with (`plan`, one row: a deterministic pattern), or `None` where either is missing.
fn against_seed(
    map: &str,
    variant: &str,
    seed: &str,
    runs: &[usize],
    plan: &[usize],
    num: impl Fn(usize, &str) -> f64,
) -> Option<String> {
    let &[p] = plan else { return None };
    if runs.is_empty() {
        return None;
    }
    let (cp, tp) = (num(p, "cov_final_reach"), num(p, "time_s"));
    let median = |c: &str| quartiles(&runs.iter().map(|&r| num(r, c)).collect::<Vec<_>>()).1;
    let (cov, time) = (median("cov_final_reach"), median("time_s"));
    let both = runs.iter().filter(|&&r| num(r, "cov_final_reach") >= cp && num(r, "time_s") <= tp).count();
    Some(format!(
        "On {map}, {variant}, whose initial population holds the {seed} plan, against that plan: median coverage {cov:.3} against {cp:.3}, median time {time:.0} s against {tp:.0} s ({:+.1} %); {both} of {} plans at least as good on both.",
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

/// The best coverage at evaluation `e` of a history (a step function of the evaluations).
fn at(curve: &[(f64, f64)], e: f64) -> Option<f64> {
    curve.iter().take_while(|(x, _)| *x <= e).last().map(|(_, y)| *y)
}

/// A run's `(evaluations, best_coverage_reach)` curve: the reachable coverage the tables
/// headline (histories written before that column existed have none).
fn history(path: &Path) -> Option<Vec<(f64, f64)>> {
    let t = RunsTable::parse(&std::fs::read_to_string(path).ok()?).ok()?;
    let (e, c) = (t.col("evaluations")?, t.col("best_coverage_reach")?);
    let v: Option<Vec<(f64, f64)>> = t.rows.iter().map(|r| Some((r[e].parse().ok()?, r[c].parse().ok()?))).collect();
    v.filter(|v| v.len() > 1)
}

/// Writes the comparison's files into `out` and returns its markdown section.
pub fn compare(dir: &Path, t: &RunsTable, out: &Path) -> Result<Comparison, ReportError> {
    let label = labels(t);
    let mc = t.col("map").ok_or_else(|| ReportError::Input("runs.csv has no `map` column".into()))?;
    let num = |r: usize, c: &str| t.num(&t.rows[r], c).unwrap_or(f64::NAN);
    // Maps in order of first appearance, planners in a fixed order of their names.
    let mut maps: Vec<String> = Vec::new();
    for r in &t.rows {
        if !maps.contains(&r[mc]) {
            maps.push(r[mc].clone());
        }
    }
    let order: Vec<&str> = crate::experiment::registry::PlannerKind::ALL.iter().map(|k| k.name()).collect();
    let mut variants: Vec<String> = label.clone();
    variants.sort_by_key(|l| (order.iter().position(|o| l.starts_with(o)).unwrap_or(order.len()), l.clone()));
    variants.dedup();
    let flag = |r: usize, c: &str| t.col(c).is_some_and(|i| t.rows[r][i] == "true");
    let all_rows_of = |map: &str, v: &str| -> Vec<usize> {
        (0..t.rows.len()).filter(|&r| t.rows[r][mc] == map && label[r] == v).collect()
    };
    // Tables, tests and findings compare executable plans only (plans a robot can drive:
    // the robot's body touches no occupied, unknown or off-map cell); the share and the all-plans coverage
    // stand beside them.
    let rows_of = |map: &str, v: &str| -> Vec<usize> {
        all_rows_of(map, v).into_iter().filter(|&r| flag(r, "executable")).collect()
    };
    let mut md = String::new();
    let mut csv = String::from("map,planner,metric,n,median,q1,q3,mean\n");
    let mut pair_csv = String::from("map,metric,a,b,n_a,n_b,u,p,p_holm,a12\n");
    let _ = writeln!(md, "## Planner comparison\n");
    let _ = writeln!(
        md,
        "Every run is scored by the common scorer (same robot footprint, same camera); `reachable` coverage divides by the cells the footprint can sweep from the start, `all free` by every free cell. `executable`: plans a robot can drive (its body touches no occupied, unknown or off-map cell along the path); `planner-feasible`: plans that also meet their planner's own constraints. Metric values are median [q1, q3] over the executable plans of the replicates (deterministic planners run once); `cov (all plans)` is the median reachable coverage over every plan, executable or not. Tests and findings compare executable plans only. All values per metric: `planners.csv`; all pairwise tests: `pairwise.csv`.\n"
    );
    let _ = writeln!(
        md,
        "![Box plots](boxplots_cov.png)\n\n![Box plots](boxplots_time.png)\n\n![Convergence](convergence.png)\n\n![Best paths](planner_paths.png)\n"
    );
    let mut findings = Vec::new();
    // Variants whose initial population holds a planner's plan (`thesis.seed_population`):
    // compared with that plan, not with random search.
    let seeded: BTreeMap<&String, String> = t
        .col("thesis.seed_population")
        .map(|c| {
            (0..t.rows.len())
                .map(|r| (&label[r], label_part(&t.rows[r][c])))
                .filter(|(_, seed)| !seed.is_empty())
                .collect()
        })
        .unwrap_or_default();
    // Variants of the thesis GA optimising the camera (`thesis.objective`): random search
    // draws for the footprint's fitness, so their footprint coverage is not its to compare.
    let camera_objective: std::collections::BTreeSet<&String> = t
        .col("thesis.objective")
        .map(|c| (0..t.rows.len()).filter(|&r| t.rows[r][c] == "camera").map(|r| &label[r]).collect())
        .unwrap_or_default();
    // (map, metric, first, second) -> (Holm p, A12), for the sentences below.
    let mut tested: BTreeMap<(String, &str, String, String), (f64, f64)> = BTreeMap::new();
    // The rows of the search-versus-objective table, on the maps that have all four cells.
    let mut two_by_two = String::new();
    for map in &maps {
        let name = short_map(map);
        let present: Vec<&String> = variants.iter().filter(|v| !rows_of(map, v).is_empty()).collect();
        let _ = writeln!(md, "### {name}\n");
        let _ = writeln!(
            md,
            "| planner | runs | executable | planner-feasible | {} | cov (all plans) |",
            TABLE.iter().map(|(_, h, _)| *h).collect::<Vec<_>>().join(" | ")
        );
        let _ = writeln!(md, "|---|---|---|---|{}---|", "---|".repeat(TABLE.len()));
        let present_all: Vec<&String> = variants.iter().filter(|v| !all_rows_of(map, v).is_empty()).collect();
        for v in &present_all {
            let all = all_rows_of(map, v);
            let rows = rows_of(map, v);
            let feasible = all.iter().filter(|&&r| flag(r, "planner_feasible")).count();
            let mut cells = Vec::new();
            for (c, _, d) in TABLE {
                let vals: Vec<f64> = rows.iter().map(|&r| num(r, c)).collect();
                if vals.is_empty() {
                    cells.push("–".to_string());
                    continue;
                }
                let (q1, med, q3) = quartiles(&vals);
                let mean = vals.iter().sum::<f64>() / vals.len() as f64;
                let _ = writeln!(csv, "{name},{v},{c},{},{med},{q1},{q3},{mean}", vals.len());
                cells.push(if vals.len() > 1 {
                    format!("{med:.d$} [{q1:.d$}, {q3:.d$}]")
                } else {
                    format!("{med:.d$}")
                });
            }
            let cov_all = quartiles(&all.iter().map(|&r| num(r, "cov_final_reach")).collect::<Vec<_>>()).1;
            let _ = writeln!(
                md,
                "| {v} | {n} | {}/{n} | {feasible}/{n} | {} | {cov_all:.3} |",
                rows.len(),
                cells.join(" | "),
                n = all.len()
            );
        }
        // Pairwise tests.
        let _ = writeln!(
            md,
            "\nPairwise two-sided Mann–Whitney U tests (Holm-corrected over the pairs of a metric), A₁₂ = P(first > second):\n"
        );
        let _ = writeln!(md, "| metric | first | second | p (Holm) | A₁₂ | effect |\n|---|---|---|---|---|---|");
        let samples: Vec<(&String, Vec<usize>)> =
            present.iter().map(|v| (*v, rows_of(map, v))).filter(|(_, r)| r.len() >= 2).collect();
        for metric in TESTED {
            let mut pairs = Vec::new();
            for i in 0..samples.len() {
                for j in i + 1..samples.len() {
                    let a: Vec<f64> = samples[i].1.iter().map(|&r| num(r, metric)).collect();
                    let b: Vec<f64> = samples[j].1.iter().map(|&r| num(r, metric)).collect();
                    let a12 = vargha_delaney_a12(&a, &b);
                    let test = mann_whitney_u(&a, &b);
                    pairs.push((samples[i].0, samples[j].0, a.len(), b.len(), test, a12));
                }
            }
            let raw: Vec<f64> = pairs.iter().map(|p| p.4.map_or(1.0, |t| t.p_value)).collect();
            let adjusted = holm(&raw);
            for (k, (a, b, na, nb, test, a12)) in pairs.iter().enumerate() {
                let u = test.map_or(f64::NAN, |t| t.u);
                let _ = writeln!(pair_csv, "{name},{metric},{a},{b},{na},{nb},{u},{},{},{a12}", raw[k], adjusted[k]);
                tested.insert((name.clone(), metric, a.to_string(), b.to_string()), (adjusted[k], *a12));
                let _ =
                    writeln!(md, "| {metric} | {a} | {b} | {:.2e} | {a12:.2} | {} |", adjusted[k], a12_magnitude(*a12));
                if metric == "cov_final_reach"
                    && b.as_str() == "random_search"
                    && a.starts_with("thesis")
                    && !seeded.contains_key(a)
                    && !camera_objective.contains(a)
                {
                    findings.push(format!(
                        "On {name}, {a} against random search with the same evaluations: A₁₂ = {a12:.2} ({}), Holm-corrected p = {:.1e}: the GA's machinery {} coverage here.",
                        a12_magnitude(*a12),
                        adjusted[k],
                        if adjusted[k] < 0.05 && *a12 > 0.5 { "improves" } else if adjusted[k] < 0.05 { "worsens" } else { "does not detectably change" }
                    ));
                }
            }
        }
        let _ = writeln!(md);
        // Search versus objective (`search_objective`): one search with two objectives, and
        // two searches with one objective.
        let pair = |a: &str, b: &str, metric: &str| {
            tested.get(&(name.clone(), metric, a.to_string(), b.to_string())).copied().or_else(|| {
                tested.get(&(name.clone(), metric, b.to_string(), a.to_string())).map(|&(p, x)| (p, 1.0 - x))
            })
        };
        let split = |v: &str| {
            let all = all_rows_of(map, v);
            let exec = all.iter().copied().filter(|&r| flag(r, "executable")).collect();
            (all, exec)
        };
        let cell_list: Vec<(&String, Option<(&'static str, &'static str)>)> = present_all
            .iter()
            .map(|v| {
                let first = all_rows_of(map, v)[0];
                (*v, search_objective::cell_of(&|c: &str| t.col(c).map(|i| t.rows[first][i].clone())))
            })
            .collect();
        let cells = MapRuns { name: &name, cells: &cell_list, rows: &split, num: &num, pair: &pair };
        if cells.complete() {
            cells.table_rows(&mut two_by_two);
        }
        findings.extend(cells.findings());
        for (v, seed) in &seeded {
            let (runs, plan) = (rows_of(map, v), rows_of(map, seed));
            if let Some(sentence) = against_seed(&name, v, seed, &runs, &plan, num) {
                findings.push(sentence);
            }
        }
        // Findings per map: coverage and time leaders.
        let med = |v: &String, c: &str| quartiles(&rows_of(map, v).iter().map(|&r| num(r, c)).collect::<Vec<_>>()).1;
        let mut by_cov: Vec<&String> = present.clone();
        by_cov.sort_by(|a, b| med(b, "cov_final_reach").total_cmp(&med(a, "cov_final_reach")));
        let mut by_time: Vec<&String> = present.clone();
        by_time.sort_by(|a, b| med(a, "time_s").total_cmp(&med(b, "time_s")));
        if let (Some(first), Some(fast)) = (by_cov.first(), by_time.first()) {
            let ranking: Vec<String> = by_cov.iter().map(|v| format!("{v} {:.3}", med(v, "cov_final_reach"))).collect();
            findings.push(format!(
                "On {name}, median coverage of the reachable cells ranks {}; {first} covers most, {fast} has the shortest median time ({:.0} s, against {:.0} s for {first}).",
                ranking.join(" > "),
                med(fast, "time_s"),
                med(first, "time_s"),
            ));
        }
        let count_of = |f: &dyn Fn(usize) -> bool| -> Vec<String> {
            present_all
                .iter()
                .filter_map(|v| {
                    let all = all_rows_of(map, v);
                    let bad = all.iter().filter(|&&r| f(r)).count();
                    (bad > 0).then(|| format!("{v} {bad}/{}", all.len()))
                })
                .collect()
        };
        let not_executable = count_of(&|r| !flag(r, "executable"));
        if !not_executable.is_empty() {
            findings.push(format!(
                "On {name}, plans a robot cannot drive (its body touches an occupied, unknown or off-map cell), left out of the medians, tests and rankings above: {}.",
                not_executable.join(", ")
            ));
        }
        let infeasible = count_of(&|r| flag(r, "executable") && !flag(r, "planner_feasible"));
        if !infeasible.is_empty() {
            findings.push(format!(
                "On {name}, executable plans that break their planner's own constraints (loop closures, connectivity or the coverage ramp for the waypoint planner): {}.",
                infeasible.join(", ")
            ));
        }
    }
    let write = |name: &str, text: &str| {
        crate::io::write_atomic(&out.join(name), text.as_bytes()).map_err(|e| ReportError::Io(format!("{name}: {e}")))
    };
    write("planners.csv", &csv)?;
    write("pairwise.csv", &pair_csv)?;
    // Box plots.
    let boxes = |metric: &str| -> Vec<(String, Vec<BoxSeries>)> {
        maps.iter()
            .map(|map| {
                let series = variants
                    .iter()
                    .map(|v| BoxSeries {
                        label: v.clone(),
                        values: rows_of(map, v).iter().map(|&r| num(r, metric)).collect(),
                        excluded: all_rows_of(map, v)
                            .into_iter()
                            .filter(|&r| !flag(r, "executable"))
                            .map(|r| num(r, metric))
                            .collect(),
                    })
                    .filter(|b| !b.values.is_empty() || !b.excluded.is_empty())
                    .collect();
                (short_map(map), series)
            })
            .collect()
    };
    crate::plot::save(
        &BoxFigure { metric: "cov_final over reachable cells".into(), panels: boxes("cov_final_reach") },
        &out.join("boxplots_cov"),
    )?;
    crate::plot::save(&BoxFigure { metric: "time [s]".into(), panels: boxes("time_s") }, &out.join("boxplots_time"))?;
    // Convergence curves of the planners with a history.
    let mut panels = Vec::new();
    for map in &maps {
        let mut curves = Vec::new();
        for v in &variants {
            let hs: Vec<Vec<(f64, f64)>> = rows_of(map, v)
                .iter()
                .filter_map(|&r| history(&dir.join("runs").join(&t.rows[r][0]).join("history.csv")))
                .collect();
            if hs.is_empty() {
                continue;
            }
            let x_max = hs.iter().flat_map(|h| h.last().map(|p| p.0)).fold(0.0, f64::max);
            let points = (0..=60)
                .map(|k| {
                    let e = x_max * k as f64 / 60.0;
                    let vals: Vec<f64> = hs.iter().filter_map(|h| at(h, e)).collect();
                    let (q1, m, q3) = quartiles(&vals);
                    (e, q1, m, q3)
                })
                .filter(|p| p.2.is_finite())
                .collect();
            curves.push(Curve { label: v.clone(), runs: hs.len(), points });
        }
        panels.push((short_map(map), curves));
    }
    crate::plot::save(&ConvergenceFigure { panels }, &out.join("convergence"))?;
    // Best path of each planner on each map.
    let mut loaded: Vec<Vec<Option<LoadedPanel>>> = Vec::new();
    // What an empty panel says: a planner that ran on the map without an executable plan.
    let mut missing: Vec<Vec<Option<String>>> = Vec::new();
    for map in &maps {
        let (mut row, mut notes) = (Vec::new(), Vec::new());
        for v in &variants {
            let rows = rows_of(map, v);
            let ran = all_rows_of(map, v).len();
            notes.push((ran > 0 && rows.is_empty()).then(|| format!("{v}: no executable plan (0/{ran})")));
            let Some(&best) = rows.iter().max_by(|&&a, &&b| num(a, "f_reach").total_cmp(&num(b, "f_reach"))) else {
                row.push(None);
                continue;
            };
            let run_dir = dir.join("runs").join(&t.rows[best][0]);
            let cfg = crate::experiment::file::ExperimentFile::read(&run_dir.join("config.toml")).ok();
            let paths = crate::io::read_path_csv(&run_dir.join("best_path.csv")).ok();
            let panel = cfg.zip(paths).and_then(|(cfg, paths)| {
                let m = crate::map::ros::load_map(&cfg.map.source, &cfg.map.bare_image()).ok()?;
                let g = CoverageGrid::new(&m);
                let title = format!(
                    "{v}, {}: cov {:.3}, t {:.3}",
                    short_map(map),
                    num(best, "cov_final_reach"),
                    num(best, "t_final")
                );
                Some((m, g, paths, cfg.robot.width, title))
            });
            row.push(panel);
        }
        loaded.push(row);
        missing.push(notes);
    }
    let rows: Vec<Vec<Option<PathFigure>>> = loaded
        .iter()
        .map(|row| {
            row.iter()
                .map(|p| {
                    p.as_ref().map(|(m, g, paths, w, title)| PathFigure {
                        map: m,
                        grid: g,
                        paths: paths.clone(),
                        width: *w,
                        robots: Vec::new(),
                        title: title.clone(),
                    })
                })
                .collect()
        })
        .collect();
    crate::plot::save(&PlannerPathsFigure { rows, missing }, &out.join("planner_paths"))?;
    if !two_by_two.is_empty() {
        search_objective::table_head(&mut md);
        md.push_str(&two_by_two);
        let _ = writeln!(md);
    }
    let _ = writeln!(md, "## Findings\n");
    for f in &findings {
        let _ = writeln!(md, "- {f}");
    }
    let _ = writeln!(md);
    Ok(Comparison { markdown: md })
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
