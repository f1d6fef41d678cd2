//! The text of a comparison's files: the paragraph on how it is made, the executability
//! table and one section per metric, in markdown and CSV.

use super::*;
pub(super) use crate::stats::family::Floor;

/// The paragraph saying how the comparison is made.
pub(super) fn intro(
    d: &Design,
    (cmp, measure): (&Comparison, &crate::report::analysis::level::TimeMeasure),
    units: Option<&super::units::Units>,
    values: &[String],
) -> String {
    let strata = if d.strata.is_empty() {
        "one stratum (no other parameter varies)".to_string()
    } else {
        format!("within each combination of {}", d.strata.join(", "))
    };
    let which = match cmp.plans {
        Plans::Executable => "a pair counts where both plans are executable",
        Plans::Every => {
            "every pair counts, executable or not (what the planner optimised, whether a robot can drive \
             its plan or not)"
        }
    };
    let mut s = format!(
        "Each value of `{}` against `{}`, {strata}. Runs are paired by seed (replicate `i` of every \
         configuration has the same seed); {which}. Coverage is \
         `cov_final_reach` (higher is better), compared as the median of the value's runs minus the \
         baseline's; time is `{}` (lower is better), compared as the ratio of medians. {} Intervals: \
         {:.0} % percentile bootstrap over pairs ({RESAMPLES} resamples, seed {BOOTSTRAP_SEED}). Tests: \
         two-sided Wilcoxon signed-rank over the pairs (exact up to 50 pairs), Holm–Bonferroni over \
         the family of the metric's comparisons below; \"shown\" means a Holm-adjusted p below {:.2}.",
        cmp.key,
        cmp.baseline,
        measure.column,
        measure.sentence(),
        LEVEL * 100.0,
        1.0 - LEVEL
    );
    design_notes(&mut s, d, cmp);
    if let Some(rules) = super::like::return_rules(&cmp.key, &cmp.baseline, values) {
        let _ = write!(s, " {rules}");
    }
    s.push_str(
        " Within a stratum the unit is the seed: each seed is a run of its own, and a control that reads \
         no seed is one fixed value its seeds are compared with.",
    );
    if let (true, Some(units)) = (d.pooled(), units) {
        let _ = write!(
            s,
            " The comparisons are made twice: first pooled over the {} (the pair effect is the difference, or \
             for time the ratio, within each pair; its median over every pair with a bootstrap interval that \
             resamples whole units; the signed-rank test of the unit effects, of their log-ratios for time; Holm \
             over the values of each metric; the pairs are described, not tested), then stratum by stratum. {}",
            units.kind.names().1,
            units.reason
        );
    }
    s
}

/// The sentences of [`intro`] on how the design was read: confounded, fixed and nested
/// parameters, the strongest control, and configurations that ran once.
fn design_notes(s: &mut String, d: &Design, cmp: &Comparison) {
    for (name, of) in &d.followers {
        let _ = write!(s, " `{name}` follows {of} (confounded with it: not a stratum of its own).");
    }
    for (name, value) in &d.fixed_on_baseline {
        let _ = write!(
            s,
            " `{name}` is `{value}` on every run of the baseline and takes other values elsewhere: the values are \
             told apart by it (every variant against the baseline), not stratified."
        );
    }
    for name in &d.nested {
        let _ = write!(
            s,
            " `{name}` is set under some values of `{}` only: the values are told apart by it, not stratified.",
            cmp.key
        );
    }
    if !d.strongest.is_empty() {
        let _ = write!(
            s,
            " `{}` stands for the strongest of these controls in each stratum: the one whose executable \
             plans have the lowest median `time_s` there (named stratum by stratum below).",
            cmp.baseline,
        );
    }
    if d.once_run() && !d.once_run_pairs {
        s.push_str(
            " The study is not finished: a configuration recorded once is paired by seed only, as if its \
             other seeds had not run yet.",
        );
    } else if d.once_run() {
        s.push_str(
            " Where one side of a comparison ran once (a configuration whose planner reads no seed \
             runs once in a grid) its one run pairs with every seed of the other.",
        );
    }
}

/// Pairs where only the value's plan is executable, and where only the baseline's is.
fn discordant(r: &Row) -> (usize, usize) {
    (r.pairs.iter().filter(|(b, v)| v > b).count(), r.pairs.iter().filter(|(b, v)| v < b).count())
}

/// The family of executability tests of `rows` and each row's exact McNemar p (none where the
/// pairs agree, or where a side is executable by construction).
fn executability_tests(
    rows: &[Row],
    cmp: &Comparison,
    built: &dyn Fn(&str) -> Option<&'static str>,
) -> (Family, Vec<Option<f64>>) {
    let mut family =
        Family::new(format!("executability ({} comparisons of `{}` against `{}`)", rows.len(), cmp.key, cmp.baseline));
    let tests: Vec<Option<f64>> = rows
        .iter()
        .map(|r| {
            if built(&r.value).is_some() || built(&cmp.baseline).is_some() {
                return None;
            }
            let (gained, lost) = discordant(r);
            let signs: Vec<f64> = std::iter::repeat_n(1.0, gained).chain(std::iter::repeat_n(-1.0, lost)).collect();
            crate::stats::sign_test(&signs, 0.0)
        })
        .collect();
    for (r, p) in rows.iter().zip(&tests) {
        if let Some(p) = p {
            family.push(format!("{} {}", r.stratum, r.value), *p);
        }
    }
    (family, tests)
}

/// The executable plans of each value against the baseline's, pair by pair: the exact
/// McNemar test, i.e. the sign test over the pairs where one plan is executable and the other
/// not, Holm-corrected over the file's comparisons. `pairs` hold 1 (executable) or 0.
pub(super) fn executability(
    md: &mut String,
    csv: &mut String,
    rows: &[Row],
    cmp: &Comparison,
    built: &dyn Fn(&str) -> Option<&'static str>,
) {
    let (family, tests) = executability_tests(rows, cmp, built);
    let best = rows.iter().zip(&tests).filter(|(_, t)| t.is_some()).map(|(r, _)| r.pairs.len()).max();
    let floor = best.and_then(|n| floor(&family, n, "seeds"));
    let mut adjusted = family.adjusted().into_iter();
    let _ = writeln!(md, "## Executable plans\n");
    let _ = writeln!(
        md,
        "| stratum | value | executable (baseline, value) | pairs | only the value's executable | only the baseline's executable | p (exact McNemar) | p (Holm) | finding |"
    );
    let _ = writeln!(md, "| --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    let mut shown = (0, 0);
    for (r, p) in rows.iter().zip(&tests) {
        let (gained, lost) = discordant(r);
        let holm = p.map(|_| adjusted.next().expect("one adjusted p per test"));
        let finding = match holm {
            _ if r.pairs.is_empty() => "no pair: not compared".to_string(),
            None => match built(&r.value).or(built(&cmp.baseline)) {
                Some(why) => format!("executable by construction ({why}): stated, not tested"),
                None => "the same in every pair: not tested".to_string(),
            },
            Some(h) if h < 1.0 - LEVEL => {
                let more = gained > lost;
                if more {
                    shown.0 += 1
                } else {
                    shown.1 += 1
                }
                format!("{} often executable than {} (shown)", if more { "more" } else { "less" }, cmp.baseline)
            }
            Some(_) if floor.as_ref().is_some_and(|f| !f.reachable) => "cannot show by design".to_string(),
            Some(_) => "not shown".to_string(),
        };
        let _ = writeln!(
            md,
            "{} {gained} | {lost} | {} | {} | {finding} |",
            r.lead_md(),
            p.map_or("–".into(), p_text),
            holm.map_or("–".into(), p_text),
        );
        let field = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x}"));
        let _ = writeln!(
            csv,
            "{},,,,,,,{gained},{lost},,{},{},{},{},{}",
            r.lead_csv("executable", "seed", r.pairs.len()),
            if p.is_some() { "mcnemar exact" } else { "" },
            field(*p),
            field(holm),
            field(floor.as_ref().map(|f| f.p)),
            quoted(&finding),
        );
    }
    let _ = writeln!(
        md,
        "\n{}{} Of {} comparisons, {} show the value's plans more often executable than `{}`'s and {} less often.\n",
        family.statement(),
        floor.map_or(String::new(), |f| format!(" {}", f.sentence)),
        rows.len(),
        shown.0,
        cmp.baseline,
        shown.1
    );
}

/// The floor of `family` whose largest comparison has `units` units (`unit_plural` names
/// them): every unit pointing one way gives an exact signed-rank (or sign) p of `2 · 2⁻ⁿ`, and
/// Holm multiplies the smallest by the family's size. `None` for a family without a test.
pub(super) fn floor(family: &Family, units: usize, unit_plural: &str) -> Option<Floor> {
    let raw = crate::stats::design::signed_rank_min_p(units);
    family.floor(raw, 1.0 - LEVEL, &format!("its largest comparison, {units} {unit_plural}, all pointing one way"))
}

pub(super) fn p_text(p: f64) -> String {
    if p < 1e-4 { format!("{p:.1e}") } else { format!("{p:.4}") }
}

/// One compared row's numbers: both sides' medians, pairs better and worse, the bootstrap
/// interval of the contrast, A₁₂, the signed-rank test and its Holm-adjusted p, the finding.
struct RowStats {
    medians: (Option<f64>, Option<f64>),
    better: usize,
    worse: usize,
    ci: Option<crate::stats::Interval>,
    a12: f64,
    test: Option<crate::stats::SignedRank>,
    holm: Option<f64>,
    finding: String,
}

/// The numbers of row `r` of metric `m` against `cmp`'s baseline, with its test's Holm-adjusted
/// p; `shown` counts the rows shown better and worse.
fn row_stats(
    m: &Metric,
    r: &Row,
    cmp: &Comparison,
    (test, holm): (Option<crate::stats::SignedRank>, Option<f64>),
    (shown, floor): (&mut (usize, usize), Option<&Floor>),
) -> RowStats {
    let (b, v): (Vec<f64>, Vec<f64>) = r.pairs.iter().copied().unzip();
    let better = r.pairs.iter().filter(|(b, v)| if m.higher_is_better { v > b } else { v < b }).count();
    let worse = r.pairs.iter().filter(|(b, v)| if m.higher_is_better { v < b } else { v > b }).count();
    let median = |x: &[f64]| (!x.is_empty()).then(|| crate::stats::quartiles(x).1);
    let ci = bootstrap_ci(&v, &b, m.contrast, true, LEVEL, RESAMPLES, BOOTSTRAP_SEED);
    let a12 = if r.pairs.is_empty() { f64::NAN } else { vargha_delaney_a12(&v, &b) };
    let min_p = 2.0 * 0.5f64.powi(r.pairs.len() as i32);
    let finding = match (test, holm) {
        _ if r.pairs.is_empty() => "no pair of executable plans: not compared".to_string(),
        (None, _) => "equal in every pair: not tested".to_string(),
        (Some(_), Some(h)) if h < 1.0 - LEVEL => {
            let word = if better > worse { "better" } else { "worse" };
            if better > worse {
                shown.0 += 1
            } else {
                shown.1 += 1
            }
            format!("{word} than {} (shown)", cmp.baseline)
        }
        (Some(_), _) if min_p >= 1.0 - LEVEL => {
            format!("not shown: {} pairs cannot reach p < {:.2}", r.pairs.len(), 1.0 - LEVEL)
        }
        (Some(_), _) if floor.is_some_and(|f| !f.reachable) => "cannot show by design".to_string(),
        (Some(_), _) => "not shown".to_string(),
    };
    RowStats { medians: (median(&b), median(&v)), better, worse, ci, a12, test, holm, finding }
}

/// Row `r`'s line of the metric's table in `summary.md`.
fn md_row(m: &Metric, r: &Row, st: &RowStats) -> String {
    let d = m.decimals;
    let ci_text = match st.ci {
        Some(c) if m.contrast == Contrast::MedianRatio => format!("{:.3}× [{:.3}, {:.3}]", c.estimate, c.low, c.high),
        Some(c) => format!("{:+.4} [{:+.4}, {:+.4}]", c.estimate, c.low, c.high),
        None => "–".into(),
    };
    let median = |x: Option<f64>| x.map_or("–".into(), |x| format!("{x:.d$}"));
    format!(
        "{} {} | {} | {} | {} of {} | {} | {} | {} | {} |",
        r.lead_md(),
        median(st.medians.0),
        median(st.medians.1),
        ci_text,
        st.better,
        r.pairs.len(),
        if st.a12.is_nan() { "–".into() } else { format!("{:.2}", st.a12) },
        st.test.map_or("–".into(), |t| format!("{} ({})", p_text(t.p_value), t.method.name())),
        st.holm.map_or("–".into(), p_text),
        st.finding
    )
}

/// Row `r`'s line of the comparisons CSV.
fn csv_row(m: &Metric, r: &Row, st: &RowStats, floor: Option<&Floor>) -> String {
    let field = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x}"));
    format!(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
        r.lead_csv(m.column, "seed", r.pairs.len()),
        field(st.medians.0),
        field(st.medians.1),
        match m.contrast {
            Contrast::MedianDifference => "difference",
            Contrast::MedianRatio => "ratio",
        },
        field(st.ci.map(|c| c.estimate)),
        field(st.ci.map(|c| c.low)),
        field(st.ci.map(|c| c.high)),
        st.better,
        st.worse,
        field((!st.a12.is_nan()).then_some(st.a12)),
        st.test.map_or(String::new(), |t| format!("wilcoxon {}", t.method.name())),
        field(st.test.map(|t| t.p_value)),
        field(st.holm),
        field(floor.map(|f| f.p)),
        quoted(&st.finding)
    )
}

/// The table and findings of one metric.
pub(super) fn section(md: &mut String, csv: &mut String, m: &Metric, rows: &[Row], cmp: &Comparison) {
    let mut family =
        Family::new(format!("`{}` ({} comparisons of `{}` against `{}`)", m.column, rows.len(), cmp.key, cmp.baseline));
    let tests: Vec<Option<crate::stats::SignedRank>> = rows
        .iter()
        .map(|r| {
            let (b, v): (Vec<f64>, Vec<f64>) = r.pairs.iter().copied().unzip();
            wilcoxon_signed_rank(&v, &b)
        })
        .collect();
    for (r, t) in rows.iter().zip(&tests) {
        if let Some(t) = t {
            family.push(format!("{} {}", r.stratum, r.value), t.p_value);
        }
    }
    let best = rows.iter().zip(&tests).filter(|(_, t)| t.is_some()).map(|(r, _)| r.pairs.len()).max();
    let floor = best.and_then(|n| floor(&family, n, "seeds"));
    let mut adjusted = family.adjusted().into_iter();
    let effect = match m.contrast {
        Contrast::MedianDifference => "difference of medians",
        Contrast::MedianRatio => "ratio of medians",
    };
    let _ = writeln!(md, "## `{}`\n", m.column);
    let _ = writeln!(
        md,
        "| stratum | value | executable (baseline, value) | pairs | median baseline | median value | {effect} [{:.0} % CI] | value better in | A₁₂ (value > baseline) | p | p (Holm) | finding |",
        LEVEL * 100.0
    );
    let _ = writeln!(md, "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    let mut shown = (0, 0);
    for (r, t) in rows.iter().zip(&tests) {
        let holm = t.map(|_| adjusted.next().expect("one adjusted p per test"));
        let st = row_stats(m, r, cmp, (*t, holm), (&mut shown, floor.as_ref()));
        let _ = writeln!(md, "{}", md_row(m, r, &st));
        let _ = writeln!(csv, "{}", csv_row(m, r, &st, floor.as_ref()));
    }
    let _ = writeln!(
        md,
        "\n{}{} Of {} comparisons, {} show the value better than `{}` and {} worse; the rest show no \
         difference at this level (which is not evidence of equality).\n",
        family.statement(),
        floor.map_or(String::new(), |f| format!(" {}", f.sentence)),
        rows.len(),
        shown.0,
        cmp.baseline,
        shown.1
    );
}
