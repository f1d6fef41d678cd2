//! The report's Kruskal–Wallis tests of the swept parameters: does a parameter's value shift
//! the run results? A row tests a parameter only where the question has an answer:
//!
//! - a parameter that follows another (a budget set per map) is not a factor of its own: it is
//!   tested as part of the one it follows, and named with it;
//! - a parameter whose values were run with different settings of the others (Elite with two
//!   objectives, NSGA-II only routed and seeded) is not crossed with them: a difference between
//!   its values is theirs as much as its own, so it is named, not tested;
//! - a parameter set to one value is listed, not tested.
//!
//! Two sets of plans are tested: the executable plans on the common scorer's measures of what
//! a robot can drive (reachable coverage, mission time), and every plan on 003's measures of
//! what its GA optimises (coverage of all free cells, `t_final`, f within one projection). All
//! tests of the section form one family, Holm-corrected, and the section says so.

use crate::report::analysis::design::{Crossing, PROJECTION, crossing, projection_levels, split_followers};
use crate::report::analysis::runs::cmp_group_values;
use crate::stats::{Family, kruskal_wallis, quartiles};
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Which plans a row tests, with its metric.
struct Test {
    parameter: String,
    plans: &'static str,
    metric: String,
    runs: usize,
    /// Each value's runs (sorted by value).
    values: Vec<(String, Vec<f64>)>,
}

/// The measures tested, with the plans they are read from: `(plans, column, executable only)`.
const MEASURES: [(&str, &str, bool); 5] = [
    ("executable", "cov_final_reach", true),
    ("executable", "time_s", true),
    ("every", "cov_final_free", false),
    ("every", "t_final", false),
    ("every", "f_free", false),
];

/// Appends the section to `md`: the tests of `params` (swept columns) over `t`'s runs.
pub(crate) fn section(md: &mut String, t: &RunsTable, params: &[String]) {
    let candidates: Vec<usize> = params.iter().filter_map(|p| t.col(p)).collect();
    let (kept, followers) = split_followers(t, &candidates);
    let name = |c: usize| t.header[c].clone();
    let constant: Vec<String> = candidates
        .iter()
        .filter(|c| !kept.contains(c) && !followers.iter().any(|(f, _)| f == *c))
        .map(|&c| name(c))
        .collect();
    let mut tests = Vec::new();
    let mut not_crossed = Vec::new();
    let mut nested_notes = Vec::new();
    for &p in &kept {
        let rows: Vec<usize> = (0..t.rows.len()).filter(|&r| !t.rows[r][p].is_empty()).collect();
        let label = with_followers(t, p, &followers);
        match crossing(t, p, &rows, &kept) {
            Crossing::NotCrossed { with } => not_crossed
                .push(format!("{label} (with {})", with.iter().map(|&q| name(q)).collect::<Vec<_>>().join(", "))),
            Crossing::Crossed { nested } => {
                if !nested.is_empty() {
                    let names: Vec<String> = nested.iter().map(|&q| name(q)).collect();
                    nested_notes.push(format!("{} within {}", names.join(", "), name(p)));
                }
                tests.extend(parameter_tests(t, p, &label, &rows));
            }
        }
    }
    let _ = writeln!(md, "\n## Kruskal–Wallis tests per swept parameter\n");
    let _ = writeln!(md, "{}\n", intro());
    write_table(md, &tests);
    let sentence = |what: &str, items: &[String]| (!items.is_empty()).then(|| format!("{what}: {}.", items.join("; ")));
    let followed: Vec<String> = followers.iter().map(|(c, of)| format!("{} follows {of}", name(*c))).collect();
    let notes: Vec<String> = [
        sentence(
            "Not tested, not crossed with the other parameters (its values were run with different settings of the ones named)",
            &not_crossed,
        ),
        sentence("Set under some values of the parameter named and pooled within them", &nested_notes),
        sentence("Tested as part of the parameter they follow (confounded with it)", &followed),
        sentence("One value in every run, not tested", &constant),
    ]
    .into_iter()
    .flatten()
    .collect();
    if !notes.is_empty() {
        let _ = writeln!(md, "\n{}", notes.join(" "));
    }
}

/// The parameter's name, with the parameters that follow it.
fn with_followers(t: &RunsTable, p: usize, followers: &[(usize, String)]) -> String {
    let name = &t.header[p];
    let theirs: Vec<&str> = followers.iter().filter(|(_, of)| of == name).map(|(c, _)| t.header[*c].as_str()).collect();
    if theirs.is_empty() { name.clone() } else { format!("{name} (with {})", theirs.join(", ")) }
}

/// The tests of parameter `p` (labelled `label`) over `rows`, one per measure (f per projection).
fn parameter_tests(t: &RunsTable, p: usize, label: &str, rows: &[usize]) -> Vec<Test> {
    let executable = |r: usize| t.col("executable").is_none_or(|c| t.rows[r][c] == "true");
    let mut out = Vec::new();
    for (plans, metric, executable_only) in MEASURES {
        if t.col(metric).is_none() {
            continue;
        }
        let scoped: Vec<usize> = rows.iter().copied().filter(|&r| !executable_only || executable(r)).collect();
        let scopes: Vec<(String, Vec<usize>)> = match projection_levels(t, metric) {
            None => vec![(metric.to_string(), scoped)],
            Some(_) if t.col(PROJECTION) == Some(p) => continue,
            Some(levels) => {
                let c = t.col(PROJECTION).expect("projection levels come from its column");
                levels
                    .into_iter()
                    .map(|l| {
                        (format!("{metric} ({l})"), scoped.iter().copied().filter(|&r| t.rows[r][c] == l).collect())
                    })
                    .collect()
            }
        };
        for (metric_label, rs) in scopes {
            let mut by_value: BTreeMap<String, Vec<f64>> = BTreeMap::new();
            for &r in &rs {
                if let Some(v) = t.num(&t.rows[r], metric).filter(|v| v.is_finite()) {
                    by_value.entry(t.rows[r][p].clone()).or_default().push(v);
                }
            }
            let mut values: Vec<(String, Vec<f64>)> = by_value.into_iter().collect();
            values.sort_by(|(a, _), (b, _)| cmp_group_values(std::slice::from_ref(a), std::slice::from_ref(b)));
            let runs = values.iter().map(|(_, v)| v.len()).sum();
            out.push(Test { parameter: label.to_string(), plans, metric: metric_label, runs, values });
        }
    }
    out
}

/// The paragraph saying what the rows test.
fn intro() -> String {
    "Does the parameter's value shift the distribution of the run results? Rows test the parameters crossed \
     with the others (every setting of the others run with each of its values); the runs where the parameter \
     does not apply are left out. Plans \"executable\": the plans a robot can drive, on the common scorer's \
     reachable coverage and mission time; \"every\": every plan, executable or not, on 003's measures of what its \
     GA optimises (coverage of all free cells, `t_final`, f within one projection). H (tie-corrected), degrees \
     of freedom, p-value and Holm's adjustment over every test of this section, effect size ε² = H/(N−1), and \
     the median of each value's runs (which way it shifts). A value with no runs in a row's plans is left out \
     of that row; a row with fewer than two values, or with every run equal, is not tested."
        .to_string()
}

/// The table and the family's statement.
fn write_table(md: &mut String, tests: &[Test]) {
    let results: Vec<Option<crate::stats::KruskalWallis>> =
        tests.iter().map(|t| kruskal_wallis(&t.values.iter().map(|(_, v)| v.clone()).collect::<Vec<_>>())).collect();
    let mut family = Family::new("this section (every tested parameter and measure)");
    for (t, r) in tests.iter().zip(&results) {
        if let Some(r) = r {
            family.push(format!("{} {} {}", t.parameter, t.plans, t.metric), r.p_value);
        }
    }
    let mut adjusted = family.adjusted().into_iter();
    let _ = writeln!(
        md,
        "| parameter | plans | metric | runs | groups | H | df | p | p (Holm) | ε² | median per value |\n|---|---|---|---|---|---|---|---|---|---|---|"
    );
    let p_text = |p: f64| if p > 0.0 { format!("{p:.3e}") } else { "< 1e-300".into() };
    for (t, r) in tests.iter().zip(&results) {
        let medians: Vec<String> = t.values.iter().map(|(v, runs)| format!("{v}: {:.4}", quartiles(runs).1)).collect();
        let stats = match r {
            Some(kw) => {
                let holm = adjusted.next().expect("one adjusted p per test");
                format!(
                    "{:.3} | {} | {} | {} | {:.4}",
                    kw.h,
                    kw.df,
                    p_text(kw.p_value),
                    p_text(holm),
                    kw.epsilon_squared
                )
            }
            None => "– | – | – | – | –".to_string(),
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {stats} | {} |",
            t.parameter,
            t.plans,
            t.metric,
            t.runs,
            t.values.len(),
            medians.join(" · ")
        );
    }
    let _ = writeln!(md, "\n{}{}", family.statement(), floor_sentence(&family, tests, &results));
}

/// The smallest p the section's family can reach: each tested row's test on its groups' sizes
/// with every group apart ([`crate::stats::design::groups_apart`]), the smallest of them, and
/// Holm's multiple.
fn floor_sentence(family: &Family, tests: &[Test], results: &[Option<crate::stats::KruskalWallis>]) -> String {
    let extreme = tests
        .iter()
        .zip(results)
        .filter(|(_, r)| r.is_some())
        .filter_map(|(t, _)| {
            let sizes: Vec<usize> = t.values.iter().map(|(_, v)| v.len()).collect();
            let p = kruskal_wallis(&crate::stats::design::groups_apart(&sizes))?.p_value;
            Some((p, t.runs, sizes.len()))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0));
    let Some((raw, runs, groups)) = extreme else { return String::new() };
    let best = format!("the test of {runs} runs in {groups} groups, every group apart");
    family.floor(raw, 0.05, &best).map_or(String::new(), |f| format!(" {}", f.sentence))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_crossed_parameters_are_tested_and_the_rest_are_named() {
        // p crossed with m; q follows p (a budget per map); r runs 1, 2 under m = x and 2, 3
        // under m = y, so m is not crossed with r either; k is one value.
        let mut text = String::from("p,q,m,r,k,executable,cov_final_reach,time_s,cov_final_free,t_final\n");
        for (i, (p, m, r)) in [
            ("a", "x", 1),
            ("a", "x", 2),
            ("b", "x", 1),
            ("b", "x", 2),
            ("a", "y", 2),
            ("a", "y", 3),
            ("b", "y", 2),
            ("b", "y", 3),
        ]
        .into_iter()
        .enumerate()
        {
            let q = if p == "a" { 100 } else { 200 };
            let cov = 0.1 * i as f64;
            let _ = writeln!(text, "{p},{q},{m},{r},c,{},{cov},{},{cov},0.5", i != 0, 10 + i);
        }
        let t = RunsTable::parse(&text).unwrap();
        let params: Vec<String> = ["p", "q", "m", "r", "k"].iter().map(|s| s.to_string()).collect();
        let mut md = String::new();
        section(&mut md, &t, &params);
        assert!(md.contains("| p (with q) | executable | cov_final_reach | 7 | 2 |"), "{md}");
        assert!(md.contains("| p (with q) | every | t_final | 8 | 2 | – |"), "every t_final equal: {md}");
        assert!(!md.contains("| q |") && !md.contains("| m |") && !md.contains("| r |"), "{md}");
        assert!(md.contains("m (with r); r (with m)"), "{md}");
        assert!(md.contains("q follows p") && md.contains("One value in every run, not tested: k."), "{md}");
        assert!(md.contains("Holm–Bonferroni over the 3 tests of this section"), "{md}");
    }
}
