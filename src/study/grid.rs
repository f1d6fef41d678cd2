//! Grid studies: a base experiment, axes given as dotted keys with value lists, conditional
//! axes that apply only where another key has a given value, and `seeds` replicates (003 §4.1.2,
//! Table 4.3). Expansion is deterministic; every run gets a stable id from its resolved
//! configuration and replicate.

use crate::config::ConfigError;
use crate::experiment::file::ExperimentFile;
use crate::ga::rng::{Purpose, derive};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use toml::{Table, Value};

/// The base experiment: a path (relative to the grid file) or an inline table.
#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum BaseRef {
    /// Path to an experiment file.
    Path(String),
    /// The experiment inline.
    Inline(Table),
}

/// Axes that apply only where the `when` keys have the given values.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Conditional {
    /// Dotted key → required value.
    pub when: Table,
    /// Dotted key → values.
    pub axes: Table,
}

/// A grid file as written.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridFile {
    /// The base experiment.
    pub base: BaseRef,
    /// The study seed; each replicate's run seed is derived from it.
    #[serde(default = "one")]
    pub seed: u64,
    /// Replicates per configuration.
    #[serde(default = "one_u32")]
    pub seeds: u32,
    /// Unconditional axes: dotted key → values.
    #[serde(default)]
    pub axes: Table,
    /// Conditional axes, applied in order.
    #[serde(default)]
    pub conditional: Vec<Conditional>,
}

/// The key whose value decides whether `key` is read, for the hint of a swept unread key.
fn deciding_key(key: &str) -> &'static str {
    match key.split('.').next() {
        Some("thesis") => "\"thesis.selection\" = \"…\"",
        Some("cell_order") => "\"cell_order.solver\" = \"ga\", \"cell_order.selection\" = \"…\"",
        Some("waypoint") => "\"waypoint.waypoint_set\" = \"…\"",
        _ => "\"planner\" = \"…\"",
    }
}

fn one() -> u64 {
    1
}
fn one_u32() -> u32 {
    1
}

/// One run of a study.
#[derive(Clone, Debug)]
pub struct RunSpec {
    /// Stable id: hash of the resolved configuration and the replicate.
    pub id: String,
    /// Hash of the configuration without seed and replicate (groups replicates).
    pub config_id: String,
    /// Replicate index.
    pub replicate: u32,
    /// The resolved experiment (seed set, output folder cleared).
    pub file: ExperimentFile,
    /// The swept keys' values for this run in [`Study::columns`] order (`None` where a
    /// conditional axis does not apply).
    pub params: Vec<Option<String>>,
    /// The conditionals that applied (for `--dry-run`), e.g. `thesis.selection=tournament`.
    pub branch: String,
}

/// An expanded study.
#[derive(Clone, Debug)]
pub struct Study {
    /// The grid file.
    pub path: PathBuf,
    /// The file's text.
    pub text: String,
    /// Every swept key, in column order.
    pub columns: Vec<String>,
    /// All runs, in expansion order.
    pub runs: Vec<RunSpec>,
}

/// The most runs one study may hold (the largest published grid, 003's Table 4.3 with its
/// extension, is 27 216 configurations).
pub const MAX_RUNS: usize = 5_000_000;

/// FNV-1a, 64 bit: a stable hash for ids.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
}

/// Merges `value` into `slot`: a table into a table key by key (so that an axis value
/// `thesis = {pop_min = 10}` keeps the base's other `[thesis]` keys), anything else replaces.
fn merge(slot: &mut Value, value: Value) {
    match (slot, value) {
        (Value::Table(old), Value::Table(new)) => {
            for (k, v) in new {
                match old.get_mut(&k) {
                    Some(existing) => merge(existing, v),
                    None => {
                        old.insert(k, v);
                    }
                }
            }
        }
        (slot, value) => *slot = value,
    }
}

/// Sets a dotted key in a table, creating intermediate tables; a table value is merged into
/// a table already there ([`merge`]).
fn set(table: &mut Table, key: &str, value: Value) -> Result<(), String> {
    let mut parts = key.split('.').peekable();
    let mut t = table;
    while let Some(p) = parts.next() {
        if parts.peek().is_none() {
            match t.get_mut(p) {
                Some(slot) => merge(slot, value),
                None => {
                    t.insert(p.to_string(), value);
                }
            }
            return Ok(());
        }
        let entry = t.entry(p.to_string()).or_insert_with(|| Value::Table(Table::new()));
        t = entry.as_table_mut().ok_or_else(|| format!("`{p}` in `{key}` is not a table"))?;
    }
    Err(format!("empty key `{key}`"))
}

/// Reads a dotted key.
fn get<'a>(table: &'a Table, key: &str) -> Option<&'a Value> {
    let mut parts = key.split('.');
    let first = table.get(parts.next()?)?;
    parts.try_fold(first, |v, p| v.as_table()?.get(p))
}

/// A scalar as text for a CSV cell.
pub fn scalar_text(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

fn values_of(axes: &Table, origin: &str, section: &str) -> Result<Vec<(String, Vec<Value>)>, ConfigError> {
    axes.iter()
        .map(|(k, v)| match v {
            // The grid sets these itself: one seed per replicate, one folder per run.
            _ if k == "seed" => Err(ConfigError::new(
                origin,
                &format!("{section}.\"seed\""),
                "cannot be swept: the grid derives each run's seed from its top-level `seed` (the study seed) and `seeds` (replicates per configuration); set `seeds = N` for N replicates",
            )),
            _ if k == "output" || k.starts_with("output.") => Err(ConfigError::new(
                origin,
                &format!("{section}.\"{k}\""),
                "cannot be swept: a study writes each run to its own folder under `--out` (runs/<run id>)",
            )),
            Value::Array(a) if !a.is_empty() => {
                let texts: Vec<String> = a.iter().map(scalar_text).collect();
                match texts.iter().enumerate().find(|(i, t)| texts[..*i].contains(t)) {
                    Some((_, t)) => Err(ConfigError::new(
                        origin,
                        &format!("{section}.\"{k}\""),
                        format!(
                            "lists the value {t} twice; each value of an axis must differ (replicates come from `seeds`)"
                        ),
                    )),
                    None => Ok((k.clone(), a.clone())),
                }
            }
            Value::Array(_) => Err(ConfigError::new(
                origin,
                &format!("{section}.\"{k}\""),
                "has an empty value list; give at least one value",
            )),
            _ => Err(ConfigError::new(
                origin,
                &format!("{section}.\"{k}\""),
                "must be a list of values, e.g. [0.2, 0.4]",
            )),
        })
        .collect()
}

/// Checks that a dotted key names a field of an experiment file.
fn check_key(base: &Table, key: &str, sample: &Value, origin: &str, section: &str) -> Result<(), ConfigError> {
    let mut t = base.clone();
    set(&mut t, key, sample.clone()).map_err(|m| ConfigError::new(origin, &format!("{section}.\"{key}\""), m))?;
    match Value::Table(t).try_into::<ExperimentFile>() {
        Ok(_) => Ok(()),
        Err(e) if e.message().contains("unknown field") => Err(ConfigError::new(
            origin,
            &format!("{section}.\"{key}\""),
            format!("is not an experiment key: {}", e.message().trim()),
        )),
        Err(e) => Err(ConfigError::new(
            origin,
            &format!("{section}.\"{key}\""),
            format!("has a bad value: {}", e.message().trim()),
        )),
    }
}

impl Study {
    /// Reads and expands a grid file.
    pub fn load(path: &Path) -> Result<Self, ConfigError> {
        let text = crate::io::read_text_bounded(path, crate::io::MAX_TEXT_FILE_BYTES)
            .map_err(|e| ConfigError::new(path.display(), "", format!("cannot read grid file: {e}")))?;
        Self::parse(&text, path)
    }

    /// Expands grid text; `path` names the file and resolves a base path.
    pub fn parse(text: &str, path: &Path) -> Result<Self, ConfigError> {
        let origin = path.display().to_string();
        let grid: GridFile = toml::from_str(text).map_err(|e| ConfigError::from_toml(&origin, text, &e))?;
        let mut base = match &grid.base {
            BaseRef::Inline(t) => t.clone(),
            BaseRef::Path(p) => {
                let full = path.parent().unwrap_or(Path::new(".")).join(p);
                let body = crate::io::read_text_bounded(&full, crate::io::MAX_TEXT_FILE_BYTES)
                    .map_err(|e| ConfigError::new(&origin, "base", format!("cannot read {}: {e}", full.display())))?;
                // Its map path, like every relative map path, is read from the working directory.
                toml::from_str(&body).map_err(|e| ConfigError::from_toml(&full.display().to_string(), &body, &e))?
            }
        };
        base.remove("output");
        // The base itself must be a valid experiment file.
        Value::Table(base.clone())
            .try_into::<ExperimentFile>()
            .map_err(|e| ConfigError::new(&origin, "base", e.message().trim().to_string()))?;
        if grid.seeds == 0 {
            return Err(ConfigError::new(&origin, "seeds", "= 0 is out of range: at least 1 replicate"));
        }
        let axes = values_of(&grid.axes, &origin, "axes")?;
        let mut columns: Vec<String> = axes.iter().map(|(k, _)| k.clone()).collect();
        for (k, vals) in &axes {
            check_key(&base, k, &vals[0], &origin, "axes")?;
        }
        let mut conds = Vec::new();
        for (n, c) in grid.conditional.iter().enumerate() {
            let section = format!("conditional[{n}].axes");
            let cax = values_of(&c.axes, &origin, &section)?;
            for (k, v) in &cax {
                check_key(&base, k, &v[0], &origin, &section)?;
                // Overriding an unconditional axis would fold its values into one
                // configuration: several runs with one id. Say so instead.
                if axes.iter().any(|(a, _)| a == k) {
                    return Err(ConfigError::new(
                        &origin,
                        &format!("{section}.\"{k}\""),
                        "is also an unconditional axis; a conditional axis may not override it (move its values into the conditional, or split the axis into conditionals)",
                    ));
                }
                if !columns.contains(k) {
                    columns.push(k.clone());
                }
            }
            for (k, v) in &c.when {
                let swept =
                    axes.iter().any(|(a, _)| a == k) || grid.conditional[..n].iter().any(|p| p.axes.contains_key(k));
                if get(&base, k).is_none() && !swept && !default_has(k) {
                    return Err(ConfigError::new(
                        &origin,
                        &format!("conditional[{n}].when.\"{k}\""),
                        "names a key that is neither in the base experiment nor swept",
                    ));
                }
                check_key(&base, k, v, &origin, &format!("conditional[{n}].when"))?;
            }
            conds.push((c.when.clone(), cax));
        }
        // Cartesian product of the unconditional axes, then each conditional in order.
        // Depth first: each combination of the unconditional axes goes through the
        // conditionals and becomes runs at once, so only the runs stay in memory.
        let mut runs = Vec::new();
        let radix: Vec<usize> = axes.iter().map(|(_, v)| v.len()).collect();
        // Count before enumerating: an upper bound (every conditional applying everywhere),
        // refused above the limit without allocating anything for the runs.
        let bound = radix
            .iter()
            .copied()
            .chain(conds.iter().flat_map(|(_, cax)| cax.iter().map(|(_, v)| v.len())))
            .fold(f64::from(grid.seeds), |acc, n| acc * n as f64);
        if bound > MAX_RUNS as f64 {
            return Err(ConfigError::new(
                &origin,
                "axes",
                format!(
                    "expands to up to {bound:.3e} runs; a study may hold at most {MAX_RUNS} (split it into several grids)"
                ),
            ));
        }
        let combos: usize = radix.iter().product();
        let mut applied = vec![false; conds.len()];
        for mut index in 0..combos {
            let mut table = base.clone();
            let mut params = Vec::with_capacity(axes.len());
            for (k, vals) in axes.iter().rev() {
                let v = &vals[index % vals.len()];
                index /= vals.len();
                set(&mut table, k, v.clone()).map_err(|m| ConfigError::new(&origin, k, m))?;
                params.push((k.clone(), v.clone()));
            }
            params.reverse();
            let mut stack = vec![(table, params, Vec::<String>::new(), 0usize)];
            while let Some((t, params, branch, next_cond)) = stack.pop() {
                let Some((when, cax)) = conds.get(next_cond) else {
                    self_runs(&origin, &grid, &columns, t, &params, &branch, &mut runs)?;
                    continue;
                };
                let resolved: ExperimentFile = Value::Table(t.clone())
                    .try_into()
                    .map_err(|e| ConfigError::new(&origin, "", e.message().trim().to_string()))?;
                let resolved_table = Table::try_from(resolved).expect("experiment files serialise");
                if !when.iter().all(|(k, v)| get(&resolved_table, k).map(scalar_text) == Some(scalar_text(v))) {
                    stack.push((t, params, branch, next_cond + 1));
                    continue;
                }
                applied[next_cond] = true;
                // A key an earlier conditional already set in this run: the later one would
                // silently replace its values (and fold its configurations into one).
                if let Some((k, _)) = cax.iter().find(|(k, _)| params.iter().any(|(p, _)| p == k)) {
                    let earlier = (0..next_cond)
                        .rev()
                        .find(|&m| grid.conditional[m].axes.contains_key(k.as_str()))
                        .map_or_else(|| "an earlier conditional".to_string(), |m| format!("conditional[{m}]"));
                    return Err(ConfigError::new(
                        &origin,
                        &format!("conditional[{next_cond}].axes.\"{k}\""),
                        format!(
                            "is also set by {earlier}, and both apply to the runs with {}: conditional axes that set the same key must not both apply (make their `when` tables exclusive, or merge their values into one conditional)",
                            params
                                .iter()
                                .map(|(k, v)| format!("{k} = {}", scalar_text(v)))
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    ));
                }
                let mut b = branch.clone();
                b.push(when.iter().map(|(k, v)| format!("{k}={}", scalar_text(v))).collect::<Vec<_>>().join(","));
                let mut expanded = vec![(t, params)];
                for (k, vals) in cax {
                    let mut next = Vec::with_capacity(expanded.len() * vals.len());
                    for (t, p) in &expanded {
                        for v in vals {
                            let mut t = t.clone();
                            set(&mut t, k, v.clone()).map_err(|m| ConfigError::new(&origin, k, m))?;
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
        }
        if let Some(n) = applied.iter().position(|a| !a) {
            let when: Vec<String> =
                grid.conditional[n].when.iter().map(|(k, v)| format!("{k} = {}", scalar_text(v))).collect();
            return Err(ConfigError::new(
                &origin,
                &format!("conditional[{n}].when"),
                format!(
                    "({}) matches no run of the grid, so its axes would be silently dropped: check the values against the axes, the earlier conditionals and the base",
                    when.join(", ")
                ),
            ));
        }
        // A key a run's planner or selection does not read, swept so that two runs differ only
        // in such keys, makes runs that differ in a value nothing reads (the same run twice
        // under two ids). A key set but unread where no other run differs from it only there
        // (the exact solver on the branch of a GA setting) is what it is: a recorded value.
        let mut unread_alike: std::collections::HashMap<(Vec<Option<String>>, u32), &RunSpec> =
            std::collections::HashMap::new();
        for r in &runs {
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
                        &origin,
                        k,
                        format!(
                            "is swept but ignored in run {} ({why}), which then differs from run {} only in keys \
                             nothing reads; sweep it in a conditional axis where it is read, e.g. [[conditional]] \
                             when = {{ {} }}",
                            r.id,
                            other.id,
                            deciding_key(k)
                        ),
                    ));
                }
            }
        }
        // Two conditionals setting one key can still fold configurations together.
        let mut seen: std::collections::HashMap<&str, &RunSpec> = std::collections::HashMap::new();
        for r in &runs {
            if let Some(first) = seen.insert(&r.id, r) {
                let setting = |run: &RunSpec| {
                    let set: Vec<String> = columns
                        .iter()
                        .zip(&run.params)
                        .filter_map(|(k, v)| v.as_ref().map(|v| format!("{k} = {v}")))
                        .collect();
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
                    &origin,
                    key,
                    format!(
                        "two runs resolve to one configuration (run id {}): {} and {}; {why}",
                        r.id,
                        setting(first),
                        setting(r)
                    ),
                ));
            }
        }
        Ok(Self { path: path.to_path_buf(), text: text.to_string(), columns, runs })
    }

    /// Run counts per branch, in first-seen order.
    pub fn branches(&self) -> Vec<(String, usize)> {
        let mut out: Vec<(String, usize)> = Vec::new();
        for r in &self.runs {
            match out.iter_mut().find(|(b, _)| *b == r.branch) {
                Some((_, n)) => *n += 1,
                None => out.push((r.branch.clone(), 1)),
            }
        }
        out
    }

    /// The runs of shard `k` of `n` (0-based): every `n`-th run in sorted id order.
    pub fn shard(&self, k: usize, n: usize) -> Vec<&RunSpec> {
        let mut sorted: Vec<&RunSpec> = self.runs.iter().collect();
        sorted.sort_by(|a, b| a.id.cmp(&b.id));
        sorted.into_iter().enumerate().filter(|(i, _)| i % n == k).map(|(_, r)| r).collect()
    }
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
    let config_text = toml::to_string(&file).expect("experiment files serialise");
    let config_id = format!("{:016x}", fnv1a(config_text.as_bytes()));
    let branch = if branch.is_empty() { "no conditional axes".to_string() } else { branch.join(" & ") };
    // A deterministic planner gives the same plan for every seed: it runs once.
    let replicates = if file.is_deterministic() { 1 } else { grid.seeds };
    for replicate in 0..replicates {
        let mut f = file.clone();
        // TOML integers are signed 64-bit: keep run seeds below 2^63.
        f.seed = derive(grid.seed, &[Purpose::Run as u64, u64::from(replicate)]) >> 1;
        let text = toml::to_string(&f).expect("experiment files serialise");
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

/// Keys that an experiment has through defaults even when the base omits them.
fn default_has(key: &str) -> bool {
    let t = Table::try_from(ExperimentFile::default()).expect("experiment files serialise");
    get(&t, key).is_some()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Study, ConfigError> {
        Study::parse(text, Path::new("g.toml"))
    }

    const BASE: &str = "[base]\n[base.budget]\niterations = 10\n";

    #[test]
    fn a_table_valued_axis_keeps_the_base_keys_it_does_not_set() {
        let text = "[base]\n[base.thesis]\npop_min = 20\nc_len = 0.4\n[base.budget]\niterations = 10\n\
                    [axes]\n\"thesis\" = [{ pop_min = 10 }, { pop_min = 30 }]\n";
        let study = parse(text).unwrap();
        let got: Vec<(usize, f64)> = study.runs.iter().map(|r| (r.file.thesis.pop_min, r.file.thesis.c_len)).collect();
        assert_eq!(got, [(10, 0.4), (30, 0.4)]);
    }

    #[test]
    fn a_conditional_may_not_override_an_unconditional_axis() {
        let text = format!(
            "{BASE}[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n\"thesis.selection\" = [\"elite\", \"tournament\"]\n[[conditional]]\nwhen = {{ \"thesis.selection\" = \"tournament\" }}\naxes = {{ \"thesis.c_len\" = [0.8] }}\n"
        );
        let e = parse(&text).unwrap_err();
        assert!(e.key.contains("thesis.c_len") && e.message.contains("unconditional axis"), "{e}");
    }

    #[test]
    fn two_conditionals_folding_configurations_are_refused() {
        let text = format!(
            "{BASE}[axes]\n\"thesis.selection\" = [\"elite\", \"prws\"]\n[[conditional]]\nwhen = {{ \"thesis.selection\" = \"prws\" }}\naxes = {{ \"thesis.p_mi\" = [0.1, 0.2] }}\n[[conditional]]\nwhen = {{ \"thesis.selection\" = \"prws\" }}\naxes = {{ \"thesis.p_mi\" = [0.3] }}\n"
        );
        let e = parse(&text).unwrap_err();
        assert!(e.key.contains("conditional[1].axes") && e.message.contains("must not both apply"), "{e}");
    }

    /// Two conditionals that apply to the same run and set one key with single values: the
    /// second used to replace the first silently (one configuration, the second's value).
    #[test]
    fn two_conditionals_setting_one_key_for_one_run_are_refused() {
        let text = format!(
            "{BASE}[axes]\n\"thesis.c_len\" = [0.1]\n[[conditional]]\nwhen = {{ \"thesis.c_len\" = 0.1 }}\naxes = {{ \"thesis.p_ma\" = [0.1] }}\n[[conditional]]\nwhen = {{ \"thesis.c_len\" = 0.1 }}\naxes = {{ \"thesis.p_ma\" = [0.2] }}\n"
        );
        let e = parse(&text).unwrap_err();
        assert_eq!(e.key, "conditional[1].axes.\"thesis.p_ma\"", "{e}");
        assert!(e.message.contains("conditional[0]") && e.message.contains("thesis.c_len = 0.1"), "{e}");
    }

    #[test]
    fn chained_and_numeric_conditionals_expand_with_distinct_ids() {
        // c_len 0.4 (numeric `when`) gets two C_child values; C_child 2 (set by that
        // conditional) gets two P_mA values: 1 + (1 + 2) = 4 configurations, 2 seeds each.
        let text = format!(
            "seeds = 2\n{BASE}[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n[[conditional]]\nwhen = {{ \"thesis.c_len\" = 0.4 }}\naxes = {{ \"thesis.c_child\" = [0, 2] }}\n[[conditional]]\nwhen = {{ \"thesis.c_child\" = 2, \"thesis.c_len\" = 0.4 }}\naxes = {{ \"thesis.p_ma\" = [0.0, 0.1] }}\n"
        );
        let s = parse(&text).unwrap();
        assert_eq!(s.runs.len(), 2 * (1 + 1 + 2), "{:?}", s.branches());
        let ids: std::collections::BTreeSet<&str> = s.runs.iter().map(|r| r.id.as_str()).collect();
        assert_eq!(ids.len(), s.runs.len());
        // The default C_child is 2: with c_len 0.1 the second conditional does not apply
        // (c_len differs), so the 0.1 configuration keeps its defaults.
        assert_eq!(s.runs.iter().filter(|r| r.file.thesis.c_len == 0.1).count(), 2);
    }

    #[test]
    fn a_huge_grid_is_refused_before_it_is_enumerated() {
        let values: Vec<String> = (0..1000).map(|k| format!("{}", 0.0005 * k as f64)).collect();
        let list = values.join(", ");
        let text = format!(
            "seeds = 1000\n{BASE}[axes]\n\"thesis.c_len\" = [{list}]\n\"thesis.p_c\" = [{list}]\n\"thesis.p_ma\" = [{list}]\n"
        );
        let started = std::time::Instant::now();
        let e = parse(&text).unwrap_err();
        assert!(e.message.contains("1.000e12 runs"), "{e}");
        assert!(started.elapsed().as_secs() < 5);
    }

    #[test]
    fn deterministic_planners_run_once_whatever_the_seeds() {
        let text = format!("seeds = 3\n{BASE}[axes]\n\"planner\" = [\"thesis\", \"spiral\", \"boustrophedon\"]\n");
        let s = parse(&text).unwrap();
        assert_eq!(s.runs.len(), 3 + 1 + 1);
        assert!(s.runs.iter().filter(|r| r.file.planner.is_deterministic()).all(|r| r.replicate == 0));
    }
}
