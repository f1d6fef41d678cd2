//! The strata of a comparison: the other parameters that vary on their own, the ones that
//! follow them or are set under some compared values only, each stratum's runs by value and
//! seed ([`Design`]), and how a baseline's runs pair with a value's ([`seed_pairs`]).

use super::{Comparison, strongest};
use crate::report::analysis::design::split_followers;
use crate::report::analysis::runs::param_columns;
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// The rows of runs.csv by stratum (the other parameters that vary on their own) and value.
pub(super) struct Design {
    pub(super) strata: Vec<String>,
    /// Their columns.
    pub(super) kept: Vec<usize>,
    /// Parameters that follow the strata's own (confounded with them), with the ones they follow.
    pub(super) followers: Vec<(String, String)>,
    /// Parameters set under some compared values only (never on the baseline's runs): written
    /// into those values' labels.
    pub(super) nested: Vec<String>,
    /// Settings of the planner that take one value on every baseline run and others elsewhere
    /// (the seeding of a search variant: the local search is always seeded, the GA alone and
    /// seeded), with that value: written into the other values' labels, so that every variant
    /// is compared with the baseline rather than only the one that shares its setting.
    pub(super) fixed_on_baseline: Vec<(String, String)>,
    /// With several controls as the baseline: the strongest in each stratum.
    pub(super) strongest: BTreeMap<String, String>,
    /// Whether a configuration recorded once pairs with every seed of the other side (a
    /// finished study); else runs pair by seed only.
    pub(super) once_run_pairs: bool,
    /// `(stratum, value) → seed → row`.
    pub(super) cells: BTreeMap<(String, String), BTreeMap<String, usize>>,
    /// Each stratum's label → its parameters, `(column, value)`.
    pub(super) params: BTreeMap<String, Vec<(String, String)>>,
}

impl Design {
    /// Whether some compared configuration ran once while others ran over several seeds.
    pub(super) fn once_run(&self) -> bool {
        let sizes: std::collections::BTreeSet<usize> = self.cells.values().map(BTreeMap::len).collect();
        sizes.contains(&1) && sizes.iter().any(|&n| n > 1)
    }

    /// Whether the comparisons are also pooled over the strata: when there is more than one.
    pub(super) fn pooled(&self) -> bool {
        let mut strata = self.cells.keys().map(|(s, _)| s);
        strata.next().is_some_and(|first| strata.any(|s| s != first))
    }
}

/// The design of comparison `cmp` (its key the column `key`) over `t`.
pub(super) fn design(t: &RunsTable, cmp: &Comparison, key: usize) -> Design {
    let others: Vec<usize> =
        param_columns(t).into_iter().filter(|p| *p != cmp.key).filter_map(|name| t.col(&name)).collect();
    // A parameter set only under some of the compared values (the GA's memetic step under
    // `solver = "ga"`) is empty on every baseline row: it is part of those values, not a stratum.
    let controls = strongest::controls(&cmp.baseline);
    let is_baseline = |r: &Vec<String>| controls.contains(&r[key].as_str());
    let (nested, candidates): (Vec<usize>, Vec<usize>) = others.into_iter().partition(|&c| {
        t.rows.iter().filter(|r| is_baseline(r)).all(|r| r[c].is_empty()) && t.rows.iter().any(|r| !r[c].is_empty())
    });
    let fixed = |c: usize| {
        let mut on_baseline = t.rows.iter().filter(|r| is_baseline(r)).map(|r| &r[c]);
        let first = on_baseline.next();
        let problem = ["map.", "robot.", "stations."].iter().any(|p| t.header[c].starts_with(p));
        // The baseline's setting must be shared by another value's runs (the seeded GA's with the
        // seeded local search): a parameter that only follows the key (a budget set per map)
        // tells nothing apart.
        first.is_some_and(|v| !v.is_empty() && on_baseline.all(|x| x == v))
            && !problem
            && t.rows.iter().any(|r| !is_baseline(r) && Some(&r[c]) != first)
            && t.rows.iter().any(|r| !is_baseline(r) && Some(&r[c]) == first)
    };
    let (fixed_cols, candidates): (Vec<usize>, Vec<usize>) = candidates.into_iter().partition(|&c| fixed(c));
    let (kept, followers) = split_followers(t, &candidates);
    let strata: Vec<String> = kept.iter().map(|&c| t.header[c].clone()).collect();
    let followers: Vec<(String, String)> = followers.into_iter().map(|(c, of)| (t.header[c].clone(), of)).collect();
    let seed = t.col("seed").unwrap_or(0);
    let mut cells: BTreeMap<(String, String), BTreeMap<String, usize>> = BTreeMap::new();
    let mut params = BTreeMap::new();
    for (i, r) in t.rows.iter().enumerate() {
        let label = kept.iter().map(|&c| format!("{}={}", t.header[c], r[c])).collect::<Vec<_>>().join(", ");
        params
            .entry(label.clone())
            .or_insert_with(|| kept.iter().map(|&c| (t.header[c].clone(), r[c].clone())).collect::<Vec<_>>());
        let mut value = r[key].clone();
        for &c in nested.iter().filter(|&&c| !r[c].is_empty()) {
            let _ = write!(value, " ({}={})", t.header[c], r[c]);
        }
        if !is_baseline(r) {
            for &c in fixed_cols.iter().filter(|&&c| !r[c].is_empty()) {
                let _ = write!(value, " ({}={})", t.header[c], r[c]);
            }
        }
        cells.entry((label, value)).or_default().insert(r[seed].clone(), i);
    }
    let nested = nested.iter().map(|&c| t.header[c].clone()).collect();
    let baseline_row = t.rows.iter().find(|r| is_baseline(r));
    let fixed_on_baseline = fixed_cols
        .iter()
        .map(|&c| (t.header[c].clone(), baseline_row.map(|r| r[c].clone()).unwrap_or_default()))
        .collect();
    // Several controls: each stratum's strongest stands for the baseline there, the controls
    // themselves are not compared.
    let mut strongest = BTreeMap::new();
    if controls.len() > 1 {
        strongest = strongest::per_stratum(t, &cells, &controls);
        for (stratum, control) in &strongest {
            let runs = cells[&(stratum.clone(), control.clone())].clone();
            cells.insert((stratum.clone(), cmp.baseline.clone()), runs);
        }
        cells.retain(|(_, v), _| !controls.contains(&v.as_str()));
    }
    Design { strata, kept, followers, nested, fixed_on_baseline, strongest, once_run_pairs: true, cells, params }
}

/// The pairs of a baseline's runs and a value's, by seed; where one side ran once and the other
/// over several seeds (a grid runs a configuration whose planner reads no seed once), its one
/// run pairs with every run of the other.
pub(super) fn seed_pairs(
    base: &BTreeMap<String, usize>,
    other: &BTreeMap<String, usize>,
    once_run: bool,
) -> Vec<(usize, usize)> {
    match (base.len(), other.len()) {
        _ if !once_run => base.iter().filter_map(|(seed, &b)| other.get(seed).map(|&o| (b, o))).collect(),
        (1, n) if n > 1 => {
            let b = *base.values().next().expect("one run");
            other.values().map(|&o| (b, o)).collect()
        }
        (n, 1) if n > 1 => {
            let o = *other.values().next().expect("one run");
            base.values().map(|&b| (b, o)).collect()
        }
        _ => base.iter().filter_map(|(seed, &b)| other.get(seed).map(|&o| (b, o))).collect(),
    }
}
