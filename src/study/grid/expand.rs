//! The expansion of a grid into its runs: the Cartesian product of the unconditional axes,
//! each combination through the conditionals in order, each configuration into its
//! replicates; and the checks that no two runs fold into one.

use super::{GridFile, RunSpec, fnv1a, get, scalar_text, set};
use crate::config::ConfigError;
use crate::experiment::file::ExperimentFile;
use crate::ga::rng::{Purpose, derive};
use std::collections::{BTreeMap, HashMap};
use toml::{Table, Value};

/// Swept keys with their values, in order.
pub(super) type Axes = Vec<(String, Vec<Value>)>;

/// A conditional's `when` table and its axes.
pub(super) type Conditional = (Table, Axes);

/// A configuration on its way through the conditionals: its table, the swept values set so
/// far, the branch (the `when`s that applied) and the next conditional to try.
type Pending = (Table, Vec<(String, Value)>, Vec<String>, usize);

/// What a grid expands from.
pub(super) struct Expansion<'a> {
    pub origin: &'a str,
    pub grid: &'a GridFile,
    /// The runs table's parameter columns.
    pub columns: &'a [String],
    pub axes: &'a Axes,
    /// Each conditional's `when` and axes.
    pub conds: &'a [Conditional],
}

impl Expansion<'_> {
    /// Every run of the grid on `base`. Depth first: each combination of the unconditional
    /// axes goes through the conditionals and becomes runs at once, so only the runs stay in
    /// memory. A conditional that applies to no run is an error (its axes would be dropped).
    pub fn runs(&self, base: &Table) -> Result<Vec<RunSpec>, ConfigError> {
        let mut runs = Vec::new();
        let combos: usize = self.axes.iter().map(|(_, v)| v.len()).product();
        let mut applied = vec![false; self.conds.len()];
        for mut index in 0..combos {
            let mut table = base.clone();
            let mut params = Vec::with_capacity(self.axes.len());
            for (k, vals) in self.axes.iter().rev() {
                let v = &vals[index % vals.len()];
                index /= vals.len();
                set(&mut table, k, v.clone()).map_err(|m| ConfigError::new(self.origin, k, m))?;
                params.push((k.clone(), v.clone()));
            }
            params.reverse();
            self.through_conditionals((table, params, Vec::new(), 0), &mut applied, &mut runs)?;
        }
        if let Some(n) = applied.iter().position(|a| !a) {
            let when: Vec<String> =
                self.grid.conditional[n].when.iter().map(|(k, v)| format!("{k} = {}", scalar_text(v))).collect();
            return Err(ConfigError::new(
                self.origin,
                &format!("conditional[{n}].when"),
                format!(
                    "({}) matches no run of the grid, so its axes would be silently dropped: check the values against the axes, the earlier conditionals and the base",
                    when.join(", ")
                ),
            ));
        }
        Ok(runs)
    }

    /// Takes one combination of the unconditional axes through the conditionals, pushing
    /// its runs; marks the conditionals that applied.
    fn through_conditionals(
        &self,
        first: Pending,
        applied: &mut [bool],
        runs: &mut Vec<RunSpec>,
    ) -> Result<(), ConfigError> {
        let mut stack = vec![first];
        while let Some((t, params, branch, next_cond)) = stack.pop() {
            let Some((when, cax)) = self.conds.get(next_cond) else {
                self_runs(self.origin, self.grid, self.columns, t, &params, &branch, runs)?;
                continue;
            };
            let resolved: ExperimentFile = Value::Table(t.clone())
                .try_into()
                .map_err(|e| ConfigError::new(self.origin, "", e.message().trim().to_string()))?;
            let resolved_table = Table::try_from(resolved).expect("experiment files serialise");
            if !when.iter().all(|(k, v)| get(&resolved_table, k).map(scalar_text) == Some(scalar_text(v))) {
                stack.push((t, params, branch, next_cond + 1));
                continue;
            }
            applied[next_cond] = true;
            self.check_not_set_before(next_cond, cax, &params)?;
            let mut b = branch.clone();
            b.push(when.iter().map(|(k, v)| format!("{k}={}", scalar_text(v))).collect::<Vec<_>>().join(","));
            let mut expanded = vec![(t, params)];
            for (k, vals) in cax {
                let mut next = Vec::with_capacity(expanded.len() * vals.len());
                for (t, p) in &expanded {
                    for v in vals {
                        let mut t = t.clone();
                        set(&mut t, k, v.clone()).map_err(|m| ConfigError::new(self.origin, k, m))?;
                        let mut p = p.clone();
                        p.push((k.clone(), v.clone()));
                        next.push((t, p));
                    }
                }
                expanded = next;
            }
            // Reversed, so that the stack pops them in expansion order.
            for (t, p) in expanded.into_iter().rev() {
                stack.push((t, p, b.clone(), next_cond + 1));
            }
        }
        Ok(())
    }

    /// A key an earlier conditional already set in this run: the later one would silently
    /// replace its values (and fold its configurations into one).
    fn check_not_set_before(&self, n: usize, cax: &Axes, params: &[(String, Value)]) -> Result<(), ConfigError> {
        let Some((k, _)) = cax.iter().find(|(k, _)| params.iter().any(|(p, _)| p == k)) else { return Ok(()) };
        let earlier = (0..n)
            .rev()
            .find(|&m| self.grid.conditional[m].axes.contains_key(k.as_str()))
            .map_or_else(|| "an earlier conditional".to_string(), |m| format!("conditional[{m}]"));
        Err(ConfigError::new(
            self.origin,
            &format!("conditional[{n}].axes.\"{k}\""),
            format!(
                "is also set by {earlier}, and both apply to the runs with {}: conditional axes that set the same key must not both apply (make their `when` tables exclusive, or merge their values into one conditional)",
                params.iter().map(|(k, v)| format!("{k} = {}", scalar_text(v))).collect::<Vec<_>>().join(", ")
            ),
        ))
    }
}

/// A key a run's planner or selection does not read, swept so that two runs differ only in
/// such keys, makes runs that differ in a value nothing reads (the same run twice under two
/// ids). A key set but unread where no other run differs from it only there (the exact solver
/// on the branch of a GA setting) is what it is: a recorded value.
pub(super) fn check_unread_alike(origin: &str, columns: &[String], runs: &[RunSpec]) -> Result<(), ConfigError> {
    let mut unread_alike: HashMap<(Vec<Option<String>>, u32), &RunSpec> = HashMap::new();
    for r in runs {
        let mut read = r.params.clone();
        let mut unread = Vec::new();
        for ((k, v), kept) in columns.iter().zip(&r.params).zip(read.iter_mut()) {
            if v.is_some()
                && let Some(why) = crate::experiment::ignored::why_ignored(&r.file, k)
            {
                *kept = None;
                unread.push((k, why));
            }
        }
        if let Some(other) = unread_alike.insert((read, r.replicate), r) {
            let differs = |k: &String| {
                let i = columns.iter().position(|c| c == k).expect("a column");
                other.params[i] != r.params[i]
            };
            if let Some((k, why)) = unread.iter().find(|(k, _)| differs(k)) {
                return Err(ConfigError::new(
                    origin,
                    k,
                    format!(
                        "is swept but ignored in run {} ({why}), which then differs from run {} only in keys \
                         nothing reads; sweep it in a conditional axis where it is read, e.g. [[conditional]] \
                         when = {{ {} }}",
                        r.id,
                        other.id,
                        super::deciding_key(k)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Two conditionals setting one key, or two values that read as one, can still fold
/// configurations together: two runs with one id.
pub(super) fn check_distinct_ids(
    origin: &str,
    grid: &GridFile,
    columns: &[String],
    runs: &[RunSpec],
) -> Result<(), ConfigError> {
    let mut seen: HashMap<&str, &RunSpec> = HashMap::new();
    for r in runs {
        let Some(first) = seen.insert(&r.id, r) else { continue };
        let setting = |run: &RunSpec| {
            let set: Vec<String> =
                columns.iter().zip(&run.params).filter_map(|(k, v)| v.as_ref().map(|v| format!("{k} = {v}"))).collect();
            format!("{} (branch `{}`)", set.join(", "), run.branch)
        };
        let (key, why) = if grid.conditional.is_empty() {
            ("axes", "two values of an axis that read as one setting (such as 1 and 1.0) fold into one run")
        } else {
            (
                "conditional",
                "conditional axes that set the same key must not both apply, and two values that read as one setting (such as 1 and 1.0) fold into one run",
            )
        };
        return Err(ConfigError::new(
            origin,
            key,
            format!(
                "two runs resolve to one configuration (run id {}): {} and {}; {why}",
                r.id,
                setting(first),
                setting(r)
            ),
        ));
    }
    Ok(())
}

/// Turns one fully expanded configuration into its replicate runs.
fn self_runs(
    origin: &str,
    grid: &GridFile,
    columns: &[String],
    t: Table,
    params: &[(String, Value)],
    branch: &[String],
    runs: &mut Vec<RunSpec>,
) -> Result<(), ConfigError> {
    let mut file: ExperimentFile =
        Value::Table(t).try_into().map_err(|e| ConfigError::new(origin, "", e.message().trim().to_string()))?;
    file.output.dir = None;
    let by_key: BTreeMap<&String, &Value> = params.iter().map(|(k, v)| (k, v)).collect();
    let cells: Vec<Option<String>> = columns.iter().map(|c| by_key.get(c).map(|v| scalar_text(v))).collect();
    file.seed = 0;
    let config_text = crate::experiment::renamed::id_text(&file);
    let config_id = format!("{:016x}", fnv1a(config_text.as_bytes()));
    let branch = if branch.is_empty() { "no conditional axes".to_string() } else { branch.join(" & ") };
    // A deterministic planner gives the same plan for every seed: it runs once.
    let replicates = if file.is_deterministic() { 1 } else { grid.seeds };
    for replicate in 0..replicates {
        let mut f = file.clone();
        // TOML integers are signed 64-bit: keep run seeds below 2^63.
        f.seed = derive(grid.seed, &[Purpose::Run as u64, u64::from(replicate)]) >> 1;
        let text = crate::experiment::renamed::id_text(&f);
        let id = format!("{:016x}", fnv1a(format!("{text}\nreplicate={replicate}").as_bytes()));
        runs.push(RunSpec {
            id,
            config_id: config_id.clone(),
            replicate,
            file: f,
            params: cells.clone(),
            branch: branch.clone(),
        });
    }
    Ok(())
}

/// The warning for a grid that sets a budget (in its base or an axis) some of whose runs' planners
/// read none (patterns, area division: they plan once, in full), with how many runs and why;
/// `None` where every run reads its budget or the grid sets none.
pub(super) fn unread_budget(origin: &str, base: &Table, columns: &[String], runs: &[RunSpec]) -> Option<String> {
    let mut keys: Vec<String> = base
        .get("budget")
        .and_then(toml::Value::as_table)
        .map(|t| t.keys().map(|k| format!("budget.{k}")).collect())
        .unwrap_or_default();
    keys.extend(columns.iter().filter(|c| c.starts_with("budget.")).cloned());
    keys.sort();
    keys.dedup();
    if keys.is_empty() {
        return None;
    }
    let mut reasons: Vec<String> = Vec::new();
    let mut unread = 0;
    for why in runs.iter().filter_map(|r| crate::experiment::ignored::why_budget_unread(&r.file)) {
        unread += 1;
        if !reasons.contains(&why) {
            reasons.push(why);
        }
    }
    (unread > 0).then(|| {
        format!(
            "{origin}: `{}` is ignored by {unread} of {} runs: {}",
            keys.join("`, `"),
            runs.len(),
            reasons.join("; ")
        )
    })
}
