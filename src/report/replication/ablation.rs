//! The planner comparison of a study with several planners (the ablation): per map, the
//! median \[IQR\] of every common metric per planner, pairwise Mann–Whitney U tests with Holm's
//! correction and Vargha–Delaney `A₁₂` effect sizes, box plots, convergence curves of the GAs,
//! the best path of each planner on each map, and findings in plain words derived from those
//! numbers. Planners are compared only through the common scorer's columns.

use super::comparing::{Comparing, Written, short_map};
use super::{ablation_plots, search_objective};
use crate::report::analysis::ReportError;
use crate::study::records::RunsTable;
use std::fmt::Write as _;
use std::path::Path;

/// Where the comparison's figures and tables go, and what it found.
pub struct PlannersCompared {
    /// The markdown section.
    pub markdown: String,
}

/// Whether the runs table holds several planners.
pub fn applies(t: &RunsTable) -> bool {
    let Some(c) = t.col("planner") else { return false };
    t.rows.iter().map(|r| &r[c]).collect::<std::collections::BTreeSet<_>>().len() > 1
}

/// Writes the comparison's files into `out` and returns its markdown section; `colours` gives
/// each run's series colour in the report (a variant is drawn in its first run's; a variant
/// with none there in its place among the variants).
pub fn compare(
    dir: &Path,
    t: &RunsTable,
    out: &Path,
    colours: &std::collections::BTreeMap<String, usize>,
) -> Result<PlannersCompared, ReportError> {
    let c = Comparing::new(t)?;
    let mut w = Written {
        csv: String::from("map,planner,metric,n,median,q1,q3,mean\n"),
        pair_csv: String::from("map,metric,a,b,n_a,n_b,u,p,p_holm,a12\n"),
        ..Written::default()
    };
    let _ = writeln!(w.md, "## Planner comparison\n");
    let _ = writeln!(
        w.md,
        "Every run is scored by the common scorer (same robot footprint, same camera); `reachable` coverage divides by the cells the footprint can sweep from the start, `all free` by every free cell. `executable`: plans a robot can drive (its body touches no occupied, unknown or off-map cell along the path); `planner-feasible`: plans that also meet their planner's own constraints. Metric values are median [q1, q3] over the executable plans of the replicates (deterministic planners run once); `cov (all plans)` is the median reachable coverage over every plan, executable or not. Tests and findings compare executable plans only. All values per metric: `planners.csv`; all pairwise tests: `pairwise.csv`.\n"
    );
    let _ = writeln!(
        w.md,
        "![Box plots](boxplots_cov.png)\n\n![Box plots](boxplots_time.png)\n\n![Convergence](convergence.png)\n\n![Best paths](planner_paths.png)\n"
    );
    for map in &c.maps {
        let name = short_map(map);
        c.map_table(map, &name, &mut w);
        c.pairwise_tests(map, &name, &mut w);
        c.designed_findings(map, &name, &mut w);
        c.leaders_and_left_out(map, &name, &mut w);
    }
    let write = |name: &str, text: &str| {
        crate::io::write_atomic(&out.join(name), text.as_bytes()).map_err(|e| ReportError::Io(format!("{name}: {e}")))
    };
    write("planners.csv", &w.csv)?;
    write("pairwise.csv", &w.pair_csv)?;
    ablation_plots::draw(&c, dir, out, colours)?;
    let mut md = w.md;
    if !w.two_by_two.is_empty() {
        search_objective::table_head(&mut md);
        md.push_str(&w.two_by_two);
        let _ = writeln!(md);
    }
    let _ = writeln!(md, "## Findings\n");
    for f in &w.findings {
        let _ = writeln!(md, "- {f}");
    }
    let _ = writeln!(md);
    Ok(PlannersCompared { markdown: md })
}
