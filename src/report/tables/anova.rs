//! The ANOVA section of `covga report` (003 §5.3): which swept parameters explain how much of
//! each metric's spread, and how much is left to the seed.

use crate::report::analysis::design::{Crossing, PROJECTION, crossing, projection_levels, split_followers};
use crate::stats::anova::{Anova, Factor, TermSpec, anova, replicate_spread};
use crate::study::records::RunsTable;
use std::fmt::Write as _;

/// Largest model (columns) the report fits; beyond it the interactions are left out.
const MAX_COLUMNS: usize = 2_000;

/// The metrics the report analyses.
pub const METRICS: [&str; 3] = ["cov_final_free", "t_final", "f_free"];

/// Factors and terms for the swept columns of `t`: every column with two or more values is a
/// factor; those set in every run get main effects and all two-way interactions, those that
/// apply to some runs only (scheme-specific keys, empty elsewhere) main effects after them.
pub fn model(t: &RunsTable, params: &[String]) -> (Vec<Factor>, Vec<TermSpec>, bool) {
    let mut factors = Vec::new();
    let mut conditional = Vec::new();
    for p in params {
        let Some(c) = t.col(p) else { continue };
        let levels: Vec<String> = t.rows.iter().map(|r| r[c].clone()).collect();
        let distinct = levels.iter().collect::<std::collections::BTreeSet<_>>().len();
        if distinct < 2 {
            continue;
        }
        let f = Factor { name: p.clone(), levels };
        if f.levels.iter().any(String::is_empty) { conditional.push(f) } else { factors.push(f) }
    }
    let unconditional = factors.len();
    factors.extend(conditional);
    let mut terms: Vec<TermSpec> = (0..factors.len()).map(TermSpec::Main).collect();
    let levels = |f: &Factor| f.levels.iter().collect::<std::collections::BTreeSet<_>>().len() - 1;
    let mains: usize = factors.iter().map(levels).sum();
    let pairs: Vec<TermSpec> =
        (0..unconditional).flat_map(|i| (i + 1..unconditional).map(move |j| TermSpec::Pair(i, j))).collect();
    let pair_columns: usize = pairs
        .iter()
        .map(|p| match *p {
            TermSpec::Pair(i, j) => levels(&factors[i]) * levels(&factors[j]),
            TermSpec::Main(_) => 0,
        })
        .sum();
    let with_pairs = 1 + mains + pair_columns < MAX_COLUMNS.min(t.rows.len() / 2);
    if with_pairs {
        terms.extend(pairs);
    }
    (factors, terms, with_pairs)
}

/// The analyses in their two forms: the report's section, and its condensed tables (per
/// metric the main effects, the three largest two-way interactions, the residual and its part
/// between replicates; `covga report --anova-condensed`).
#[derive(Default)]
struct Written {
    full: String,
    condensed: String,
}

/// How many of the largest interactions the condensed tables keep.
const CONDENSED_INTERACTIONS: usize = 3;

fn table(out: &mut Written, a: &Anova, spread: (f64, f64)) {
    let header = "| term | df | η² (share of SS) | F | p | p on ranks |\n|---|---|---|---|---|---|\n";
    out.full.push_str(header);
    out.condensed.push_str(header);
    let mut order: Vec<&crate::stats::anova::TermTest> = a.terms.iter().collect();
    order.sort_by(|x, y| y.eta2.total_cmp(&x.eta2));
    let p = |p: f64| if p == 0.0 { "< 1e-300".to_string() } else { format!("{p:.2e}") };
    let rows: Vec<(bool, String)> = order
        .iter()
        .map(|t| {
            let row = if t.df == 0 {
                format!("| {} | 0 | aliased: nested in the terms above | | | |\n", t.name)
            } else {
                format!("| {} | {} | {:.4} | {:.2} | {} | {} |\n", t.name, t.df, t.eta2, t.f, p(t.p), p(t.rank_p))
            };
            (t.name.contains('×'), row)
        })
        .collect();
    for (_, row) in &rows {
        out.full.push_str(row);
    }
    let mains = rows.iter().filter(|(pair, _)| !pair);
    let pairs = rows.iter().filter(|(pair, _)| *pair).take(CONDENSED_INTERACTIONS);
    for (_, row) in mains.chain(pairs) {
        out.condensed.push_str(row);
    }
    let (rss, df) = a.residual;
    let share = if a.total_ss > 0.0 { rss / a.total_ss } else { 0.0 };
    let residual = format!(
        "| residual | {df} | {share:.4} | | | |\n| of which between replicates of one configuration | | {:.4} | | | |\n",
        spread.1
    );
    out.full.push_str(&residual);
    out.full.push('\n');
    out.condensed.push_str(&residual);
    out.condensed.push('\n');
}

/// The rows of `t` whose `column` is `value`.
pub fn subset(t: &RunsTable, column: &str, value: &str) -> RunsTable {
    let c = t.col(column).expect("a column of the table");
    RunsTable { header: t.header.clone(), rows: t.rows.iter().filter(|r| r[c] == value).cloned().collect() }
}

/// One metric's ANOVA table under `heading`.
fn analyse(out: &mut Written, t: &RunsTable, factors: &[Factor], terms: &[TermSpec], metric: &str, heading: &str) {
    let md = &mut out.full;
    let configs: Vec<String> = match t.col("config_id") {
        Some(c) => t.rows.iter().map(|r| r[c].clone()).collect(),
        None => (0..t.rows.len()).map(|i| i.to_string()).collect(),
    };
    let y: Vec<f64> = t.rows.iter().map(|r| t.num(r, metric).unwrap_or(f64::NAN)).collect();
    if y.iter().any(|v| !v.is_finite()) {
        let _ = writeln!(md, "### {heading}\n\nSome runs have no value: not analysed.\n");
        return;
    }
    if factors.is_empty() {
        let _ = writeln!(md, "### {heading}\n\nNo other parameter takes two or more values: nothing to analyse.\n");
        return;
    }
    match anova(factors, terms, &y) {
        Ok(a) => {
            let normal = if a.normality_p < 1e-3 {
                let p = if a.normality_p > 0.0 { format!("{:.1e}", a.normality_p) } else { "< 1e-15".into() };
                format!("residuals far from normal (Jarque–Bera p = {p}): read the rank p-values")
            } else {
                format!("residuals close to normal (Jarque–Bera p = {:.3})", a.normality_p)
            };
            let _ = writeln!(md, "### {heading}\n\n{} runs; {normal}.\n", a.n);
            let _ = writeln!(out.condensed, "### {heading}\n");
            table(out, &a, replicate_spread(&configs, &y));
        }
        Err(e) => {
            let _ = writeln!(md, "### {heading}\n\nNot analysed: {e}.\n");
        }
    }
}

/// The swept parameters an analysis of variance can take as factors, and the sentence that
/// names the ones it leaves out: a parameter that follows another is aliased with it (named,
/// left out); the rest must form a crossed, balanced grid (every parameter set in every run
/// crossed with the others, each combination of them run equally often), where sequential
/// sums of squares equal the type II ones; parameters set under some values of another only
/// are nested in it and enter after the crossed ones. `Err` says why the design is no such grid.
pub fn factors_of_design(t: &RunsTable, params: &[String]) -> Result<(Vec<String>, String), String> {
    let candidates: Vec<usize> = params.iter().filter_map(|p| t.col(p)).collect();
    let (kept, followers) = split_followers(t, &candidates);
    let name = |c: usize| t.header[c].clone();
    let crossed: Vec<usize> = kept.iter().copied().filter(|&c| t.rows.iter().all(|r| !r[c].is_empty())).collect();
    let all: Vec<usize> = (0..t.rows.len()).collect();
    for &p in &crossed {
        if let Crossing::NotCrossed { with } = crossing(t, p, &all, &crossed) {
            let with: Vec<String> = with.into_iter().map(name).collect();
            return Err(format!("{} is not crossed with {}", name(p), with.join(", ")));
        }
    }
    for &q in kept.iter().filter(|c| !crossed.contains(c)) {
        let set = |r: &Vec<String>| !r[q].is_empty();
        let parent = crossed.iter().copied().find(|&p| {
            let mut decided: std::collections::BTreeMap<&str, bool> = std::collections::BTreeMap::new();
            t.rows.iter().all(|r| *decided.entry(r[p].as_str()).or_insert(set(r)) == set(r))
        });
        if parent.is_none() {
            return Err(format!(
                "{} is set in some runs only, and no parameter set in every run decides which (the runs are not one grid)",
                name(q)
            ));
        }
        let rows: Vec<usize> = (0..t.rows.len()).filter(|&r| set(&t.rows[r])).collect();
        if let Crossing::NotCrossed { with } = crossing(t, q, &rows, &kept) {
            let with: Vec<String> = with.into_iter().map(name).collect();
            return Err(format!("{} is not crossed with {} where it is set", name(q), with.join(", ")));
        }
    }
    // Every configuration of the factors run equally often: the crossed factors then have
    // proportional cell frequencies (nested ones multiply a parent's cells evenly).
    let mut cells: std::collections::BTreeMap<Vec<&str>, usize> = std::collections::BTreeMap::new();
    for r in &t.rows {
        *cells.entry(kept.iter().map(|&c| r[c].as_str()).collect()).or_default() += 1;
    }
    let counts: std::collections::BTreeSet<usize> = cells.values().copied().collect();
    if counts.len() > 1 {
        return Err(format!(
            "its configurations hold {} to {} runs each (not balanced)",
            counts.first().copied().unwrap_or(0),
            counts.last().copied().unwrap_or(0)
        ));
    }
    let left_out = if followers.is_empty() {
        String::new()
    } else {
        let names: Vec<String> = followers.iter().map(|(c, of)| format!("{} follows {of}", name(*c))).collect();
        format!(" Left out as aliased with the parameter they follow: {}.", names.join("; "))
    };
    Ok((kept.into_iter().map(name).collect(), left_out))
}

/// The markdown section, or a line saying why there is none.
pub fn section(t: &RunsTable, params: &[String]) -> String {
    written(t, params).full
}

/// The condensed tables of [`section`]'s analyses (empty where it makes none): per metric, the
/// main effects, the three largest two-way interactions, the residual and its part between
/// replicates, each row as the full table has it.
pub fn condensed(t: &RunsTable, params: &[String]) -> String {
    written(t, params).condensed
}

/// The analyses of [`section`], in both forms.
fn written(t: &RunsTable, params: &[String]) -> Written {
    let mut out = Written { full: String::from("\n## Analysis of variance (003 §5.3)\n\n"), condensed: String::new() };
    let md = &mut out.full;
    let (params, left_out) = match factors_of_design(t, params) {
        Ok(design) => design,
        Err(why) => {
            let _ = writeln!(
                md,
                "Not made: an analysis of variance of these runs would attribute to one parameter what \
                 another did, because {why}. The Kruskal–Wallis section tests each parameter where it is \
                 crossed with the others, and `covga report --compare` compares values paired by seed \
                 within each setting of the others."
            );
            return out;
        }
    };
    let params = &params[..];
    let (factors, terms, with_pairs) = model(t, params);
    if factors.is_empty() {
        md.push_str("No parameter takes two or more values: nothing to analyse.\n");
        return out;
    }
    let _ = writeln!(
        md,
        "A linear model of each metric over the swept parameters as categorical factors ({}), \
         solved by least squares (QR); sequential sums of squares, main effects first{}; the \
         parameters set in every run form a crossed, balanced grid, where these equal the type II \
         sums of squares, and those set under some values of another only are nested in it and \
         come after them.{left_out} \
         η² is each term's share of the total sum of squares; the residual row is what the model \
         leaves, and its part between replicates of one configuration (same parameters, other \
         seed) is the share of the spread that is luck. \"p on ranks\" refits the model to the \
         ranks of the metric, to read where the residuals are far from normal.\n",
        factors.iter().map(|f| f.name.as_str()).collect::<Vec<_>>().join(", "),
        if with_pairs {
            ", then every two-way interaction of the parameters set in every run"
        } else {
            "; too many columns for the interactions, which are left out"
        }
    );
    for metric in METRICS {
        match projection_levels(t, metric) {
            None => analyse(&mut out, t, &factors, &terms, metric, metric),
            Some(levels) => {
                // f1 and f2 are different functions: f is analysed within each projection.
                let _ = writeln!(
                    out.full,
                    "### {metric}\n\nf1 (003 eq. 3.14) and f2 (eq. 3.15) are different functions, so {metric} is analysed within each projection, over the other parameters.\n"
                );
                let others: Vec<String> = params
                    .iter()
                    .filter(|p| crate::experiment::renamed::current_key(p) != PROJECTION)
                    .cloned()
                    .collect();
                for level in levels {
                    let sub = subset(t, PROJECTION, &level);
                    let (factors, terms, _) = model(&sub, &others);
                    analyse(
                        &mut out,
                        &sub,
                        &factors,
                        &terms,
                        metric,
                        &format!("{metric} within {PROJECTION} = {level}"),
                    );
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(header: &str, rows: &[&str]) -> RunsTable {
        RunsTable::parse(&format!("{header}\n{}\n", rows.join("\n"))).unwrap()
    }

    #[test]
    fn the_design_decides_whether_an_anova_is_made() {
        let names = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        // a × m crossed, two runs each; b follows m (a budget per map).
        let grid = table("a,m,b", &["1,x,5", "1,x,5", "2,x,5", "2,x,5", "1,y,9", "1,y,9", "2,y,9", "2,y,9"]);
        let (kept, left_out) = factors_of_design(&grid, &names(&["a", "m", "b"])).unwrap();
        assert_eq!(kept, names(&["a", "m"]));
        assert!(left_out.contains("b follows m"), "{left_out}");
        // One configuration run once more than the others.
        let mut uneven = grid.clone();
        uneven.rows.push(uneven.rows[0].clone());
        assert!(factors_of_design(&uneven, &names(&["a", "m"])).unwrap_err().contains("2 to 3 runs"));
        // t set under s = tour only (a tournament size), crossed with m there: nested, made.
        let nested = table("s,t,m", &["elite,,x", "elite,,y", "tour,3,x", "tour,7,x", "tour,3,y", "tour,7,y"]);
        assert_eq!(factors_of_design(&nested, &names(&["s", "t", "m"])).unwrap().0, names(&["s", "t", "m"]));
        // k set in some runs only and decided by no parameter set in every run: not one grid.
        let mixed = table("k,m", &["c,x", ",x", "c,y", ",y"]);
        let why = factors_of_design(&mixed, &names(&["k", "m"])).unwrap_err();
        assert!(why.contains("k is set in some runs only"), "{why}");
        // a runs 1, 2 on x and 2, 3 on y: neither follows the other, and they are not crossed.
        let apart = table("a,m", &["1,x", "2,x", "2,y", "3,y"]);
        let why = factors_of_design(&apart, &names(&["a", "m"])).unwrap_err();
        assert!(why.contains("is not crossed with"), "{why}");
    }
}
