//! Grid studies: a base experiment, axes given as dotted keys with value lists, conditional
//! axes that apply only where another key has a given value, and `seeds` replicates (003 §4.1.2,
//! Table 4.3). Expansion is deterministic; every run gets a stable id from its resolved
//! configuration and replicate.

use crate::config::ConfigError;
use crate::experiment::file::ExperimentFile;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use toml::{Table, Value};

mod expand;

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
    /// Warnings in words, each naming the grid file (keys spelt as they were before a rename).
    pub warnings: Vec<String>,
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

/// A table of dotted keys (axes, `when`) with every old key under its current name
/// ([`crate::experiment::renamed`]); `renamed` collects the old keys met.
fn current_spelling(
    t: &Table,
    origin: &str,
    section: &str,
    renamed: &mut crate::experiment::renamed::Moves,
) -> Result<Table, ConfigError> {
    use crate::experiment::renamed::RENAMED_KEYS;
    for (old, new) in RENAMED_KEYS {
        if t.contains_key(old) {
            if t.contains_key(new) {
                return Err(ConfigError::new(
                    origin,
                    &format!("{section}.\"{new}\""),
                    format!("is also given under its old name `{old}`: keep `{new}` only"),
                ));
            }
            renamed.push((old, new));
        }
    }
    Ok(t.iter().map(|(k, v)| (crate::experiment::renamed::current_key(k).to_string(), v.clone())).collect())
}

/// The axes of `axes` (dotted key → values), in the order of their keys as first spelt (a
/// renamed key sorts under its old name), so that a rename keeps a study's columns in place.
fn values_of(axes: &Table, origin: &str, section: &str) -> Result<Vec<(String, Vec<Value>)>, ConfigError> {
    let mut keyed: Vec<(&String, &Value)> = axes.iter().collect();
    keyed.sort_by_key(|(k, _)| crate::experiment::renamed::old_key(k).unwrap_or(k));
    keyed
        .into_iter()
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
        let mut grid: GridFile = toml::from_str(text).map_err(|e| ConfigError::from_toml(&origin, text, &e))?;
        let (base, mut renamed) = read_base(&grid, path, &origin)?;
        if grid.seeds == 0 {
            return Err(ConfigError::new(&origin, "seeds", "= 0 is out of range: at least 1 replicate"));
        }
        grid.axes = current_spelling(&grid.axes, &origin, "axes", &mut renamed)?;
        for (n, c) in grid.conditional.iter_mut().enumerate() {
            c.axes = current_spelling(&c.axes, &origin, &format!("conditional[{n}].axes"), &mut renamed)?;
            c.when = current_spelling(&c.when, &origin, &format!("conditional[{n}].when"), &mut renamed)?;
            renamed.extend(crate::experiment::renamed::current_when_values(&mut c.when));
        }
        let axes = values_of(&grid.axes, &origin, "axes")?;
        for (k, vals) in &axes {
            check_key(&base, k, &vals[0], &origin, "axes")?;
        }
        let (columns, conds) = conditionals(&grid, &base, &axes, &origin)?;
        // Count before enumerating: an upper bound (every conditional applying everywhere),
        // refused above the limit without allocating anything for the runs.
        let bound = axes
            .iter()
            .map(|(_, v)| v.len())
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
        let expansion =
            expand::Expansion { origin: &origin, grid: &grid, columns: &columns, axes: &axes, conds: &conds };
        let runs = expansion.runs(&base)?;
        expand::check_unread_alike(&origin, &columns, &runs)?;
        expand::check_distinct_ids(&origin, &grid, &columns, &runs)?;
        renamed.sort_unstable();
        renamed.dedup();
        let mut warnings: Vec<String> =
            renamed.into_iter().map(|(old, new)| crate::experiment::renamed::warning(&origin, old, new)).collect();
        warnings.extend(expand::unread_budget(&origin, &base, &columns, &runs));
        Ok(Self { path: path.to_path_buf(), text: text.to_string(), columns, runs, warnings })
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

/// Keys that an experiment has through defaults even when the base omits them.
fn default_has(key: &str) -> bool {
    let t = Table::try_from(ExperimentFile::default()).expect("experiment files serialise");
    get(&t, key).is_some()
}

/// The grid's base experiment (inline, or the file it names beside the grid), its `[output]`
/// checked and without a folder, its old keys moved to their new names, checked as an experiment file; and the
/// old keys it used.
fn read_base(
    grid: &GridFile,
    path: &Path,
    origin: &str,
) -> Result<(Table, crate::experiment::renamed::Moves), ConfigError> {
    let mut base = match &grid.base {
        BaseRef::Inline(t) => t.clone(),
        BaseRef::Path(p) => {
            let full = path.parent().unwrap_or(Path::new(".")).join(p);
            let body = crate::io::read_text_bounded(&full, crate::io::MAX_TEXT_FILE_BYTES)
                .map_err(|e| ConfigError::new(origin, "base", format!("cannot read {}: {e}", full.display())))?;
            // Its map path, like every relative map path, is read from the working directory.
            toml::from_str(&body).map_err(|e| ConfigError::from_toml(&full.display().to_string(), &body, &e))?
        }
    };
    // A grid names each run's folder itself; what else `[output]` asks (the diversity's
    // interval, the population's genomes) applies to every run, checked as a file's is.
    if let Some(output) = base.get_mut("output") {
        let Some(section) = output.as_table_mut() else {
            return Err(ConfigError::new(origin, "base.output", "is not a table".to_string()));
        };
        // A base file that is an experiment of its own names its folder: each run's is below
        // --out instead.
        section.remove("dir");
        Value::Table(section.clone())
            .try_into::<crate::experiment::file::OutputSection>()
            .map_err(|e| ConfigError::new(origin, "base.output", e.message().trim().to_string()))?;
        if section.is_empty() {
            base.remove("output");
        }
    }
    let renamed = crate::experiment::renamed::rename_in_table(&mut base, origin)?;
    // The base itself must be a valid experiment file.
    Value::Table(base.clone())
        .try_into::<ExperimentFile>()
        .map_err(|e| ConfigError::new(origin, "base", e.message().trim().to_string()))?;
    Ok((base, renamed))
}

/// The grid's columns (the unconditional axes', then each conditional's new keys) and its
/// conditionals (`when` and axes), each key checked against the base.
fn conditionals(
    grid: &GridFile,
    base: &Table,
    axes: &expand::Axes,
    origin: &str,
) -> Result<(Vec<String>, Vec<expand::Conditional>), ConfigError> {
    let mut columns: Vec<String> = axes.iter().map(|(k, _)| k.clone()).collect();
    let mut conds = Vec::new();
    for (n, c) in grid.conditional.iter().enumerate() {
        let section = format!("conditional[{n}].axes");
        let cax = values_of(&c.axes, origin, &section)?;
        for (k, v) in &cax {
            check_key(base, k, &v[0], origin, &section)?;
            // Overriding an unconditional axis would fold its values into one
            // configuration: several runs with one id. Say so instead.
            if axes.iter().any(|(a, _)| a == k) {
                return Err(ConfigError::new(
                    origin,
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
            if get(base, k).is_none() && !swept && !default_has(k) {
                return Err(ConfigError::new(
                    origin,
                    &format!("conditional[{n}].when.\"{k}\""),
                    "names a key that is neither in the base experiment nor swept",
                ));
            }
            check_key(base, k, v, origin, &format!("conditional[{n}].when"))?;
        }
        conds.push((c.when.clone(), cax));
    }
    Ok((columns, conds))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::thesis::config::THESIS_SECTION;

    fn parse(text: &str) -> Result<Study, ConfigError> {
        Study::parse(text, Path::new("g.toml"))
    }

    const BASE: &str = "[base]\n[base.budget]\niterations = 10\n";

    #[test]
    fn a_table_valued_axis_keeps_the_base_keys_it_does_not_set() {
        let text = "[base]\n[base.thesis]\npop_min = 20\nc_len = 0.4\n[base.budget]\niterations = 10\n\
                    [axes]\n\"thesis\" = [{ pop_min = 10 }, { pop_min = 30 }]\n";
        let study = parse(text).unwrap();
        let got: Vec<(usize, f64)> =
            study.runs.iter().map(|r| THESIS_SECTION.get(&r.file).map(|t| (t.pop_min, t.c_len)).unwrap()).collect();
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
        assert_eq!(s.runs.iter().filter(|r| THESIS_SECTION.get(&r.file).unwrap().c_len == 0.1).count(), 2);
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
