//! The report of a fleet study (every run a fleet's plan): per map and fleet, union coverage and
//! makespan of each method as median \[IQR\] over seeds; pairwise Mann–Whitney U tests with Holm's
//! correction and Vargha–Delaney `A₁₂` (an exact sign test against a deterministic method's one
//! plan); the makespan speed-up with fleet size; the negotiation's convergence. Methods are
//! compared only through the fleet metrics of the common scorer ([`crate::fleet::metrics`]).

use crate::report::analysis::ReportError;
use crate::stats::{a12_magnitude, holm, mann_whitney_u, quartiles, sign_test, vargha_delaney_a12};
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

/// Whether every run of the table planned a fleet: its fleet columns hold a robot count and
/// its planner is one of the fleet modes.
pub fn applies(t: &RunsTable) -> bool {
    let planner = t.header.iter().rposition(|h| h == "planner");
    match (t.col("fleet_robots"), planner) {
        (Some(c), Some(p)) => {
            t.rows.iter().all(|r| r[c].parse::<u32>().is_ok_and(|n| n >= 1) && r[p].starts_with("fleet-"))
        }
        _ => false,
    }
}

/// A run's fleet label: the `fleet.name` it was given, else `homo-<n>` / `fleet-<n>`.
fn fleet_label(t: &RunsTable, r: &[String]) -> String {
    let name = t.col("fleet_name").map(|c| r[c].clone()).unwrap_or_default();
    if name.is_empty() { format!("fleet-{}", t.col("fleet_robots").map_or("?", |c| r[c].as_str())) } else { name }
}

fn short_map(source: &str) -> String {
    Path::new(source).file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| source.to_string())
}

/// Runs of one (map, fleet, method).
#[derive(Default)]
struct Cell {
    rows: Vec<usize>,
}

fn iqr(v: &[f64], decimals: usize) -> String {
    if v.is_empty() {
        return "–".into();
    }
    let (q1, m, q3) = quartiles(v);
    if v.len() == 1 { format!("{m:.decimals$}") } else { format!("{m:.decimals$} [{q1:.decimals$}, {q3:.decimals$}]") }
}

/// Which way a metric improves, for the effect sizes: `A₁₂` is reported as the probability that
/// a run of the first method is better than one of the second.
#[derive(Clone, Copy)]
enum Better {
    Higher,
    Lower,
}

fn oriented(v: &[f64], better: Better) -> Vec<f64> {
    match better {
        Better::Higher => v.to_vec(),
        Better::Lower => v.iter().map(|x| -x).collect(),
    }
}

/// The fleet section of the study report, written to `summary.md` in `out`.
pub fn write(dir: &Path, t: &RunsTable, out: &Path, incomplete: Option<&str>) -> Result<String, ReportError> {
    let num = |r: usize, c: &str| t.num(&t.rows[r], c).unwrap_or(f64::NAN);
    let text = |r: usize, c: &str| t.col(c).map(|i| t.rows[r][i].clone()).unwrap_or_default();
    // The metric `planner` column, not a swept `planner` key of the same name before it.
    let planner = t.header.iter().rposition(|h| h == "planner");
    // map -> fleet -> method -> runs.
    let mut cells: BTreeMap<String, BTreeMap<String, BTreeMap<String, Cell>>> = BTreeMap::new();
    for r in 0..t.rows.len() {
        let m = short_map(&text(r, "map"));
        let f = fleet_label(t, &t.rows[r]);
        let method = planner.map_or("", |c| t.rows[r][c].as_str()).trim_start_matches("fleet-").to_string();
        cells.entry(m).or_default().entry(f).or_default().entry(method).or_default().rows.push(r);
    }
    // Medians and tests over the executable plans (each robot at its own width: no obstacle or
    // unknown cell swept, on the map); the table gives their share.
    let executable = |r: usize| text(r, "executable") == "true";
    let values = |c: &Cell, metric: &str| -> Vec<f64> {
        c.rows.iter().filter(|&&r| executable(r)).map(|&r| num(r, metric)).collect()
    };
    let mut md = String::new();
    let _ = writeln!(md, "# Fleet study\n");
    if let Some(note) = incomplete {
        let _ = writeln!(md, "{note}\n");
    }
    let _ = writeln!(
        md,
        "{} runs from `{}`. Methods: `central` (the centralised fleet GA), `negotiate` (one thesis GA per robot, \
         plans exchanged every `fleet.round_iterations`), `divide` (area division + boustrophedon; deterministic, one run), \
         `waypoint` (000's multi-agent planner, homogeneous fleets only). Union = swept cells any robot can reach over \
         the cells the robots can reach; makespan = the slowest robot's time (length / speed + turning / rotation speed). \
         Medians [IQR] over the executable plans of the seeds; `executable` counts the plans every robot can drive at \
         its own width (its body touches no occupied, unknown or off-map cell along its path), `planner-feasible` those that also meet the \
         method's own constraints (the waypoint teams' loop closures and connectivity).\n",
        t.rows.len(),
        dir.display()
    );
    let _ = writeln!(md, "## Union coverage and makespan\n");
    for (m, fleets) in &cells {
        let _ = writeln!(md, "### {m}\n");
        let _ = writeln!(
            md,
            "| fleet | method | runs | union (reachable) | makespan [s] | overlap | balance | executable | planner-feasible |\n|---|---|---|---|---|---|---|---|---|"
        );
        for (f, methods) in fleets {
            for (method, c) in methods {
                let feasible = c.rows.iter().filter(|&&r| text(r, "planner_feasible") == "true").count();
                let drivable = c.rows.iter().filter(|&&r| executable(r)).count();
                let _ = writeln!(
                    md,
                    "| {f} | {method} | {} | {} | {} | {} | {} | {drivable}/{n} | {feasible}/{n} |",
                    c.rows.len(),
                    iqr(&values(c, "union_reach"), 3),
                    iqr(&values(c, "fleet_makespan_s"), 0),
                    iqr(&values(c, "overlap_fraction"), 3),
                    iqr(&values(c, "balance").into_iter().filter(|b| b.is_finite()).collect::<Vec<_>>(), 2),
                    n = c.rows.len()
                );
            }
        }
        let _ = writeln!(md);
    }
    md.push_str(&findings(&cells, &values));
    md.push_str(&pairwise(&cells, &values));
    md.push_str(&speed_up(&cells, &values));
    md.push_str(&convergence(dir, t, &cells));
    let path = out.join("summary.md");
    crate::io::write_atomic(&path, md.as_bytes()).map_err(|e| ReportError::Io(format!("{}: {e}", path.display())))?;
    Ok(md)
}

type Cells = BTreeMap<String, BTreeMap<String, BTreeMap<String, Cell>>>;

/// Pairwise tests of the methods within each map and fleet, Holm-corrected over the table.
fn pairwise(cells: &Cells, values: &dyn Fn(&Cell, &str) -> Vec<f64>) -> String {
    struct Test {
        row: String,
        p: Option<f64>,
        a12: f64,
        test: &'static str,
        /// Its p on the most extreme data of its sizes.
        extreme: f64,
    }
    let mut tests = Vec::new();
    for (m, fleets) in cells {
        for (f, methods) in fleets {
            let names: Vec<&String> = methods.keys().collect();
            for i in 0..names.len() {
                for j in i + 1..names.len() {
                    let (a, b) = (&methods[names[i]], &methods[names[j]]);
                    for (metric, better) in [("union_reach", Better::Higher), ("fleet_makespan_s", Better::Lower)] {
                        let (va, vb) = (oriented(&values(a, metric), better), oriented(&values(b, metric), better));
                        if va.is_empty() || vb.is_empty() {
                            // A method without an executable plan is compared with none.
                            continue;
                        }
                        let a12 = vargha_delaney_a12(&va, &vb);
                        let (p, test, extreme) = if va.len() == 1 || vb.len() == 1 {
                            // A deterministic method's one plan against the other's seeds.
                            let (seeds, plan) = if va.len() == 1 { (&vb, va[0]) } else { (&va, vb[0]) };
                            (sign_test(seeds, plan), "sign", crate::stats::design::signed_rank_min_p(seeds.len()))
                        } else {
                            let apart = crate::stats::design::groups_apart(&[va.len(), vb.len()]);
                            let extreme = mann_whitney_u(&apart[0], &apart[1]).map_or(1.0, |w| w.p_value);
                            (mann_whitney_u(&va, &vb).map(|w| w.p_value), "MWU", extreme)
                        };
                        let row = format!("| {m} | {f} | {} vs {} | {metric} |", names[i], names[j]);
                        tests.push(Test { row, p, a12, test, extreme });
                    }
                }
            }
        }
    }
    let ps: Vec<f64> = tests.iter().map(|t| t.p.unwrap_or(1.0)).collect();
    let adjusted = holm(&ps);
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Pairwise tests\n\n`A₁₂` = probability that a run of the first method is better than one of the second \
         (higher union, shorter makespan); 0.5 = no difference. p: two-sided Mann–Whitney U (normal approximation, \
         tie-corrected), or an exact sign test of the seeds against a deterministic method's single plan; Holm-corrected \
         over all {} tests.\n",
        tests.len()
    );
    let _ = writeln!(
        md,
        "| map | fleet | methods | metric | test | p (Holm) | A₁₂ | effect |\n|---|---|---|---|---|---|---|---|"
    );
    for (t, p) in tests.iter().zip(adjusted) {
        let p = if t.p.is_some() { format!("{p:.2e}") } else { "–".into() };
        let _ = writeln!(md, "{} {} | {p} | {:.2} | {} |", t.row, t.test, t.a12, a12_magnitude(t.a12));
    }
    let mut family = crate::stats::Family::new("the pairwise tests");
    for t in &tests {
        family.push(t.row.clone(), t.p.unwrap_or(1.0));
    }
    let extreme = tests.iter().map(|t| t.extreme).fold(1.0, f64::min);
    if let Some(floor) = family.floor(extreme, 0.05, "the test of its largest samples, wholly apart") {
        let _ = writeln!(md, "\n{}", floor.sentence);
    }
    md.push('\n');
    md
}

/// Findings in words, per map and fleet, from the executable plans: which method covers the
/// most and which is fastest, and the methods without an executable plan.
fn findings(cells: &Cells, values: &dyn Fn(&Cell, &str) -> Vec<f64>) -> String {
    let mut md = String::from("## Findings (executable plans only; medians over seeds)\n\n");
    for (m, fleets) in cells {
        for (f, methods) in fleets {
            let medians: Vec<(&String, f64, f64)> = methods
                .iter()
                .filter_map(|(method, c)| {
                    let union = values(c, "union_reach");
                    (!union.is_empty())
                        .then(|| (method, quartiles(&union).1, quartiles(&values(c, "fleet_makespan_s")).1))
                })
                .collect();
            let none: Vec<&str> =
                methods.iter().filter(|(_, c)| values(c, "union_reach").is_empty()).map(|(k, _)| k.as_str()).collect();
            let most = medians.iter().max_by(|a, b| a.1.total_cmp(&b.1));
            let fastest = medians.iter().min_by(|a, b| a.2.total_cmp(&b.2));
            let mut line = format!("- {m}, {f}:");
            if let (Some(most), Some(fastest)) = (most, fastest) {
                let _ = write!(
                    line,
                    " {} covers the most ({:.3} of the reachable cells, makespan {:.0} s); {} has the shortest makespan ({:.0} s, covering {:.3}).",
                    most.0, most.1, most.2, fastest.0, fastest.2, fastest.1
                );
            }
            if !none.is_empty() {
                let _ = write!(line, " No executable plan: {}.", none.join(", "));
            }
            let _ = writeln!(md, "{line}");
        }
    }
    md.push('\n');
    md
}

/// Median makespan of one robot over that of `n` identical robots, per map and method.
fn speed_up(cells: &Cells, values: &dyn Fn(&Cell, &str) -> Vec<f64>) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Makespan speed-up with fleet size (homogeneous fleets)\n\nMedian makespan of `homo-1` over that of \
         `homo-n`, with the median union coverage of `homo-n` beside it (a speed-up bought with less coverage is \
         no speed-up).\n"
    );
    let _ = writeln!(md, "| map | method | n = 2 | n = 3 | n = 5 |\n|---|---|---|---|---|");
    let med = |v: Vec<f64>| if v.is_empty() { f64::NAN } else { quartiles(&v).1 };
    for (m, fleets) in cells {
        let Some(one) = fleets.get("homo-1") else { continue };
        for (method, c1) in one {
            let base = med(values(c1, "fleet_makespan_s"));
            let cols: Vec<String> = [2, 3, 5]
                .iter()
                .map(|n| match fleets.get(&format!("homo-{n}")).and_then(|f| f.get(method)) {
                    // Without executable plans on either side there is nothing to compare.
                    Some(c) if base.is_finite() && !values(c, "fleet_makespan_s").is_empty() => {
                        format!(
                            "{:.2}× (union {:.3})",
                            base / med(values(c, "fleet_makespan_s")),
                            med(values(c, "union_reach"))
                        )
                    }
                    Some(_) | None => "–".into(),
                })
                .collect();
            let _ = writeln!(md, "| {m} | {method} | {} |", cols.join(" | "));
        }
    }
    md.push('\n');
    md
}

/// Rounds, settled runs and the last round's largest plan change of the negotiations, read from
/// each run's `summary.json`.
fn convergence(dir: &Path, t: &RunsTable, cells: &Cells) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Convergence of the negotiation\n\nRounds held, runs whose plans settled (every robot's plan changed by \
         at most `fleet.tolerance` of its swept cells in a round) before the evaluation budget ended, and the largest \
         plan change of the last round (medians over seeds).\n"
    );
    let _ = writeln!(md, "| map | fleet | runs | rounds | settled | last change |\n|---|---|---|---|---|---|");
    let (id, rounds_col, settled_col, change_col) =
        (t.col("run_id"), t.col("negotiation_rounds"), t.col("negotiation_settled"), t.col("negotiation_last_change"));
    for (m, fleets) in cells {
        for (f, methods) in fleets {
            let Some(c) = methods.get("negotiate") else { continue };
            let (mut rounds, mut settled, mut change) = (Vec::new(), 0, Vec::new());
            for &r in &c.rows {
                let field = |col: Option<usize>| col.map(|i| t.rows[r][i].as_str()).filter(|v| !v.is_empty());
                if let Some(n) = field(rounds_col).and_then(|v| v.parse::<f64>().ok()) {
                    rounds.push(n);
                    settled += usize::from(field(settled_col) == Some("true"));
                    change.extend(field(change_col).and_then(|v| v.parse::<f64>().ok()));
                    continue;
                }
                // Studies recorded before these columns existed: the run's own summary.
                let Some(i) = id else { continue };
                let path = dir.join("runs").join(&t.rows[r][i]).join("summary.json");
                let read = std::fs::read_to_string(path).ok();
                let Some(details) = read.and_then(|s| serde_json::from_str::<crate::fleet::details::Details>(&s).ok())
                else {
                    continue;
                };
                let Some(n) = crate::fleet::details::FleetDetails::read(&details).negotiation else { continue };
                rounds.push(f64::from(n.rounds));
                settled += usize::from(n.converged);
                change.extend(n.last_round_change);
            }
            let _ = writeln!(
                md,
                "| {m} | {f} | {} | {} | {settled}/{} | {} |",
                c.rows.len(),
                iqr(&rounds, 0),
                rounds.len(),
                iqr(&change, 3)
            );
        }
    }
    md.push('\n');
    md
}
