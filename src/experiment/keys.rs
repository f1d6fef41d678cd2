//! The reference of every key of an experiment file, read from the configuration types
//! themselves: the sections' fields and their doc comments from their source (compiled into
//! the binary), the defaults from the default file as it is written, and the allowed values and
//! ranges from the checks (each key is set to values out of any range and the messages of
//! [`ExperimentFile::validate`] are kept). `covga reference keys` writes it as the book's key
//! reference, and a test requires the committed page to equal it: a default or a range changed
//! without the page re-made fails.

mod probe;
pub mod source;

use super::file::ExperimentFile;
use source::{Field, Shape};

/// One key of an experiment file as the reference gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct KeyDoc {
    /// Dotted key (`thesis.p_c`; `robots[].width` for an entry of an array of tables).
    pub key: String,
    /// Its TOML type.
    pub kind: String,
    /// Its default as written in `config.toml`, or `unset`.
    pub default: String,
    /// The values the checks allow, in their own words (empty: any value of the type).
    pub allowed: String,
    /// The field's doc comment, on one line.
    pub doc: String,
}

/// A section of the reference: its table name, the doc comment of its type, its keys.
#[derive(Clone, Debug, PartialEq)]
pub struct SectionDoc {
    /// `[thesis]`, `[scorer.camera]`, `[[robots]]`; empty for the top-level keys.
    pub table: String,
    /// The doc comment of the section's type.
    pub doc: String,
    /// The keys of the section.
    pub keys: Vec<KeyDoc>,
}

/// Every section of an experiment file with its keys, in the order the file's type declares
/// them.
pub fn sections() -> Vec<SectionDoc> {
    sections_with(&default_table())
}

/// [`sections`] with the defaults of `defaults` (a written experiment file).
fn sections_with(defaults: &toml::Table) -> Vec<SectionDoc> {
    let mut out = Vec::new();
    collect(&mut out, "", "", &file_shape(), defaults);
    out
}

/// The top level of an experiment file: its own keys, every one optional, with the planner
/// sections where the file places them (before `[budget]`, or after it).
fn file_shape() -> source::Shape {
    use crate::planner::section::Placement;
    let mut shape = source::struct_shape("ExperimentFile");
    let sections = crate::experiment::registry::planner_sections();
    let field = |p: Placement| {
        sections.iter().filter(move |s| s.placement() == p).map(|s| Field {
            name: s.name().to_string(),
            ty: s.source().0.to_string(),
            doc: String::new(),
            variant: None,
            required: false,
        })
    };
    let at = shape.fields.iter().position(|f| f.name == "sections").expect("the file's planner sections");
    shape.fields.splice(at..=at, field(Placement::BeforeBudget));
    let budget = shape.fields.iter().position(|f| f.name == "budget").expect("[budget]");
    let after: Vec<Field> = field(Placement::AfterBudget).collect();
    shape.fields.splice(budget + 1..budget + 1, after);
    for f in &mut shape.fields {
        f.required = false;
    }
    shape
}

/// The written default file with every optional section present at its defaults.
fn default_table() -> toml::Table {
    let mut file = ExperimentFile { fleet: Some(Default::default()), ..ExperimentFile::default() };
    for section in crate::experiment::registry::planner_sections() {
        // A section with a required key (`retrain.at_iteration`, the page says so) sets it to
        // zero; the rest of its table takes its defaults.
        let value = section.default_value().unwrap_or_else(|| {
            let (type_name, source) = section.source();
            let shape = source::shape_in(source, type_name);
            let required: toml::Table =
                shape.fields.iter().filter(|f| f.required).map(|f| (f.name.clone(), toml::Value::Integer(0))).collect();
            section.read_value(toml::Value::Table(required)).expect("a section of zeros")
        });
        file.sections.insert(section.name(), value);
    }
    toml::Table::try_from(&file).expect("the default experiment file serialises")
}

/// Adds the section `table` (dotted `prefix` for its keys) and, depth first, its subsections.
fn collect(out: &mut Vec<SectionDoc>, table: &str, prefix: &str, shape: &Shape, defaults: &toml::Table) {
    let mut keys = Vec::new();
    let mut nested = Vec::new();
    for field in &shape.fields {
        let key = if prefix.is_empty() { field.name.clone() } else { format!("{prefix}.{}", field.name) };
        match source::section_type(&field.ty) {
            Some((type_name, array)) => nested.push((field, key, type_name, array)),
            None => keys.push(key_doc(&key, field, defaults)),
        }
    }
    out.push(SectionDoc { table: table.to_string(), doc: shape.doc.clone(), keys });
    for (field, key, type_name, array) in nested {
        let table = if array { format!("[[{key}]]") } else { format!("[{key}]") };
        let prefix = if array { format!("{key}[]") } else { key.clone() };
        if type_name == "Table" {
            let doc = format!("{} Each planner checks its own keys.", field.doc);
            out.push(SectionDoc { table: format!("[{key}.<name>]"), doc, keys: Vec::new() });
            continue;
        }
        let shape = source::struct_shape(type_name);
        collect(out, &table, &prefix, &shape, defaults);
    }
}

/// The reference of one key.
fn key_doc(key: &str, field: &Field, defaults: &toml::Table) -> KeyDoc {
    let value = lookup(defaults, key);
    let default = match value {
        _ if field.required => "required".to_string(),
        Some(v) => show_value(v),
        None => "unset".to_string(),
    };
    let kind = source::toml_type(&field.ty, value);
    KeyDoc {
        key: key.to_string(),
        allowed: probe::allowed(key, &kind, field.variant.as_deref()),
        kind,
        default,
        doc: field.doc.clone(),
    }
}

/// The value at dotted `key` (`robots[].x` reads the first entry, `thesis.control.min` the
/// control table), if the default file writes one.
fn lookup<'a>(table: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let mut parts = key.split('.');
    let first = parts.next()?;
    let mut value = table.get(first.trim_end_matches("[]"))?;
    for part in parts {
        value = match value {
            toml::Value::Array(a) => a.first()?.as_table()?.get(part)?,
            toml::Value::Table(t) => t.get(part)?,
            _ => return None,
        };
    }
    Some(value)
}

/// A value as TOML writes it inline.
fn show_value(value: &toml::Value) -> String {
    match value {
        toml::Value::Float(f) if f.fract() == 0.0 && f.abs() < 1e15 => format!("{f:.1}"),
        _ => value.to_string(),
    }
}

/// The reference as the book's Markdown page.
pub fn markdown() -> String {
    render(&sections())
}

/// The Markdown page of `sections`.
fn render(sections: &[SectionDoc]) -> String {
    let mut md = String::from(
        "# Experiment keys\n\n\
         Every key of an experiment file, section by section, with its TOML type, its default (as\n\
         `config.toml` writes it; `unset` where the key is optional; `required` where a file that\n\
         has the key's table must set it) and the values its checks allow. This page is written\n\
         by `covga reference keys` from the configuration types, their\n\
         doc comments and their checks; `tests/it/reference.rs` requires it to equal what the program\n\
         writes, so a default or a range cannot change without it. Symbols in backticks are the\n\
         papers' (`P_mA`, `C_len`: 003, the thesis; `p_A`, `T_x`: 000, the waypoint planner).\n\
         A key a planner does not read is named in a warning when a run starts.\n",
    );
    for section in sections {
        let title =
            if section.table.is_empty() { "Top-level keys".to_string() } else { format!("`{}`", section.table) };
        md.push_str(&format!("\n## {title}\n\n"));
        if !section.doc.is_empty() {
            md.push_str(&format!("{}\n\n", section.doc));
        }
        if section.keys.is_empty() {
            continue;
        }
        md.push_str("| key | type | default | allowed | meaning |\n| --- | --- | --- | --- | --- |\n");
        for k in &section.keys {
            let leaf = k.key.rsplit('.').next().unwrap_or(&k.key);
            md.push_str(&format!(
                "| `{leaf}` | {} | `{}` | {} | {} |\n",
                k.kind,
                k.default.replace('|', "\\|"),
                cell(&k.allowed),
                cell(&k.doc)
            ));
        }
    }
    md
}

/// Text safe inside a Markdown table cell.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference holds every section of the file and keys with their defaults, types and
    /// checked ranges; the numbers come from the defaults and the checks, not from this test.
    #[test]
    fn the_reference_reads_types_defaults_and_ranges_from_the_code() {
        let all = sections();
        let tables: Vec<&str> = all.iter().map(|s| s.table.as_str()).collect();
        for t in
            ["", "[map]", "[robot]", "[thesis]", "[thesis.control]", "[scorer.camera]", "[cell_order]", "[[robots]]"]
        {
            assert!(tables.contains(&t), "no section {t:?} in {tables:?}");
        }
        let key = |k: &str| all.iter().flat_map(|s| &s.keys).find(|d| d.key == k).cloned().unwrap();
        let width = key("robot.width");
        assert_eq!((width.kind.as_str(), width.default.as_str()), ("number", "0.6"));
        assert!(width.doc.contains("R_width"), "{width:?}");
        assert_eq!(key("thesis.p_c").allowed, "[0, 1]");
        let projection = key("scorer.projection");
        assert!(projection.allowed.contains("`f1`") && projection.allowed.contains("`f2`"), "{projection:?}");
        assert_eq!(key("map.resolution").default, "unset");
        assert_eq!(key("stations.start").default, "[1.3, 1.3]");
        for required in ["retrain.at_iteration", "robots[].name", "thesis.control.min"] {
            assert_eq!(key(required).default, "required", "{required}");
        }
        assert_eq!(key("retrain.region").default, "[5.0, 5.0, 10.0, 10.0]");
        assert_eq!(key("thesis.control.k1").default, "unset", "a variant's field with a default");
    }

    /// A default that changes changes the page (so the committed page no longer equals it), and
    /// every key the default file writes has its row.
    #[test]
    fn the_page_follows_the_defaults_and_misses_no_written_key() {
        let mut defaults = default_table();
        let page = render(&sections_with(&defaults));
        defaults["robot"].as_table_mut().unwrap().insert("width".into(), toml::Value::Float(0.7));
        let changed = render(&sections_with(&defaults));
        assert_ne!(page, changed);
        assert!(changed.contains("| `width` | number | `0.7` |"), "the new default is shown");
        let documented: Vec<String> = sections().iter().flat_map(|s| s.keys.iter().map(|k| k.key.clone())).collect();
        let mut written = Vec::new();
        dotted_keys(&default_table(), "", &mut written);
        for key in written {
            assert!(documented.contains(&key), "`{key}` is written by the default file but has no row");
        }
    }

    /// The dotted leaf keys of `table` (a table of a tagged enum ends at its `kind`).
    fn dotted_keys(table: &toml::Table, prefix: &str, out: &mut Vec<String>) {
        for (name, value) in table {
            let key = if prefix.is_empty() { name.clone() } else { format!("{prefix}.{name}") };
            match value {
                toml::Value::Table(t) => dotted_keys(t, &key, out),
                _ => out.push(key),
            }
        }
    }
}
