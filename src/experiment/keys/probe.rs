//! The values the checks allow for a key, found by asking them: the key is set, in a file whose
//! planner reads it, to values outside any range (a huge negative and a huge positive number, a
//! zero and a huge whole number, a name no enum has), and the messages that refuse them are kept
//! in their own words. A key no probe is refused for takes any value of its type.

use crate::experiment::file::ExperimentFile;
use crate::planner::Checks;
use toml::Value;

/// What the checks allow for `key` of TOML type `kind` (`variant`: the `kind` of a tagged
/// enum's table it belongs to), or empty.
pub fn allowed(key: &str, kind: &str, variant: Option<&str>) -> String {
    let base = base_file(key, variant);
    if refusal(key, &base).is_some() {
        return String::new();
    }
    let probes: Vec<Value> = match kind {
        "number" => vec![Value::Float(-1e9), Value::Float(1e9)],
        "integer" => vec![Value::Integer(0), Value::Integer(4_294_967_295)],
        "string" => vec![Value::String("?".into())],
        _ => Vec::new(),
    };
    let mut found: Vec<String> = Vec::new();
    for value in probes {
        let mut file = base.clone();
        set(&mut file, key, value.clone());
        let mut message = refusal(key, &file);
        // A small integer type refuses a huge value as a type error: its largest value instead.
        if message.as_deref().is_some_and(|m| m.contains("expected u8")) {
            set(&mut file, key, Value::Integer(255));
            message = refusal(key, &file);
        }
        let shown = match &value {
            Value::Integer(i) => i.to_string(),
            other => other.to_string(),
        };
        let Some(message) = message.map(|m| in_words(&m, &shown)) else { continue };
        // A free string (a path, a name) is refused for reasons of its own, not a range.
        if kind == "string" && !message.starts_with("one of ") {
            continue;
        }
        if !found.contains(&message) {
            found.push(message);
        }
    }
    found.join("; ")
}

/// A file whose planner reads `key`, with what that key's table needs to be read at all.
fn base_file(key: &str, variant: Option<&str>) -> toml::Table {
    let section = key.split('.').next().unwrap_or(key);
    // The first registered planner that declares the section reads it; the file's own tables
    // are read by the thesis GA, the first of them.
    let declares =
        |k: &crate::experiment::registry::PlannerKind| k.entry().sections().iter().any(|s| s.name() == section);
    let kinds = crate::experiment::registry::PlannerKind::all();
    let planner = kinds.iter().find(|k| declares(k)).map_or("thesis", |k| k.name());
    let mut file = toml::Table::new();
    file.insert("planner".into(), Value::String(planner.into()));
    match section {
        "retrain" => set(&mut file, "retrain.at_iteration", Value::Integer(10)),
        "robots[]" | "fleet" => set(&mut file, "robots[].name", Value::String("a".into())),
        _ => {}
    }
    for &(read_key, setting, value) in &READ_WHEN {
        if key == read_key {
            set(&mut file, setting, value.into_value());
        }
    }
    if let Some(v) = variant {
        set(&mut file, "thesis.control.kind", Value::String(v.into()));
        if v == "ramp" {
            set(&mut file, "thesis.control.min", Value::Float(1.0));
            set(&mut file, "thesis.control.max", Value::Float(2.0));
        }
    }
    file
}

/// A setting that makes the planner read a key (its check runs only then).
#[derive(Clone, Copy)]
enum Setting {
    /// A name.
    Name(&'static str),
    /// A list of names.
    Names(&'static [&'static str]),
}

impl Setting {
    fn into_value(self) -> Value {
        match self {
            Setting::Name(n) => Value::String(n.into()),
            Setting::Names(ns) => Value::Array(ns.iter().map(|n| Value::String((*n).into())).collect()),
        }
    }
}

/// Keys read only under another setting: the key, the setting, its value.
const READ_WHEN: [(&str, &str, Setting); 8] = [
    ("thesis.init_individuals", "thesis.selection", Setting::Name("tournament")),
    ("thesis.keep", "thesis.selection", Setting::Name("tournament")),
    ("thesis.select", "thesis.selection", Setting::Name("tournament")),
    ("thesis.tournament_size", "thesis.selection", Setting::Name("tournament")),
    ("thesis.selection_pressure", "thesis.selection", Setting::Name("rrws")),
    ("thesis.seed_share", "thesis.seed_population", Setting::Names(&["boustrophedon"])),
    ("cell_order.selection_pressure", "cell_order.selection", Setting::Name("rrws")),
    ("cell_order.best_parents", "cell_order.selection", Setting::Name("best")),
];

/// Sets dotted `key` in `file` (`robots[]` is the first entry of the array of tables).
fn set(file: &mut toml::Table, key: &str, value: Value) {
    let parts: Vec<&str> = key.split('.').collect();
    let (last, path) = parts.split_last().expect("a key");
    let mut table = file;
    for part in path {
        table = match part.strip_suffix("[]") {
            Some(name) => {
                let entries = table.entry(name).or_insert_with(|| Value::Array(vec![Value::Table(Default::default())]));
                entries.as_array_mut().and_then(|a| a.first_mut()).and_then(Value::as_table_mut).expect("a table")
            }
            None => {
                table.entry(*part).or_insert_with(|| Value::Table(Default::default())).as_table_mut().expect("a table")
            }
        };
    }
    table.insert((*last).to_string(), value);
}

/// The message refusing `file` at `key` (or refusing the value's type or name, which names no
/// key), if the file is refused there.
fn refusal(key: &str, file: &toml::Table) -> Option<String> {
    let text = toml::to_string(file).ok()?;
    let load = |src: &str, image: &crate::map::ros::BareImage| crate::map::ros::load_map(src, image);
    let result = ExperimentFile::parse(&text, "probe")
        .and_then(|f| f.validate_with("probe", std::path::Path::new("."), "probe", &load, Checks::KeysOnly));
    let e = result.err()?;
    let leaf = key.rsplit('.').next().unwrap_or(key);
    let section = key.split('.').next().unwrap_or(key).trim_end_matches("[]");
    let about_key = e.key.is_empty()
        || e.key == key
        || (e.key.starts_with(section) && (e.key.ends_with(leaf) || e.key.contains(&format!(".{leaf} "))));
    about_key.then_some(e.message)
}

/// A refusal in the reference's words: the allowed range or names, without the probe's value.
fn in_words(message: &str, value: &str) -> String {
    let message = message.trim();
    if let Some(names) = message.split("expected one of ").nth(1) {
        return format!("one of {}", names.trim());
    }
    if let Some((a, b)) = message.split("expected `").nth(1).and_then(|n| n.split_once("` or `")) {
        return format!("one of `{a}`, `{}", b.trim());
    }
    if let Some(range) = message.split("allowed ").nth(1) {
        return range.trim().to_string();
    }
    let without_value = match message.strip_prefix("= ") {
        Some(rest) => rest.split_once(' ').map_or("", |(_, tail)| tail),
        None => message,
    };
    let words = without_value.trim_start_matches("m ").trim_start_matches("is out of range");
    let words = words.trim_start_matches(':').trim().trim_start_matches("is ").trim_start_matches("outside ");
    without_number(words, value)
}

/// `text` with the probe's `value` where a message quotes it in parentheses (`l_init (0)`)
/// written as `(…)`, so that the probes of one check read alike.
fn without_number(text: &str, value: &str) -> String {
    text.replace(&format!("({value})"), "(…)")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refusals_are_put_in_the_references_words() {
        for (message, want) in [
            ("= -1000000000 is out of range: allowed [0, 1]", "[0, 1]"),
            ("unknown variant `?`, expected one of `a`, `b`, `c`", "one of `a`, `b`, `c`"),
            ("unknown variant `?`, expected `f1` or `f2`", "one of `f1`, `f2`"),
            ("= 1000000000 is out of range (0, 360] degrees", "(0, 360] degrees"),
            (
                "= -1000000000 must exceed d_min = 0.2 (camera depth range)",
                "must exceed d_min = 0.2 (camera depth range)",
            ),
            (
                "= 0 needs 2 <= l_min (75) <= l_init (0) <= l_max (250)",
                "needs 2 <= l_min (75) <= l_init (…) <= l_max (250)",
            ),
            ("= 0 is out of range [100, 1000000]", "[100, 1000000]"),
            ("= 0 is out of range (0, 360] degrees", "(0, 360] degrees"),
        ] {
            assert_eq!(in_words(message, "0"), want, "{message}");
        }
    }

    #[test]
    fn keys_are_set_in_nested_tables_and_arrays() {
        let mut file = toml::Table::new();
        set(&mut file, "scorer.camera.scale", Value::Float(0.5));
        set(&mut file, "robots[].width", Value::Float(0.4));
        let text = toml::to_string(&file).unwrap();
        assert!(text.contains("[scorer.camera]\nscale = 0.5") && text.contains("[[robots]]\nwidth = 0.4"), "{text}");
    }
}
