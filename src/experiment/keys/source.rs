//! The sections' fields and doc comments, read from their source as compiled into the binary:
//! one list of the section types and the files that declare them.

/// A field of a section: its key, its Rust type, its doc comment on one line, and for a field
/// of a tagged enum's variant, the variant (`kind = "…"`) it belongs to.
#[derive(Clone, Debug, PartialEq)]
pub struct Field {
    /// The key (the field's name, or its `rename`).
    pub name: String,
    /// The Rust type as written.
    pub ty: String,
    /// The doc comment, intra-doc links reduced to their text.
    pub doc: String,
    /// The variant of a tagged enum this field belongs to.
    pub variant: Option<String>,
    /// Whether a file that has the field's table must set it (neither the type nor the field
    /// has a serde default).
    pub required: bool,
}

/// A section type: its doc comment and its fields.
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    /// The type's doc comment.
    pub doc: String,
    /// The keys, in declaration order.
    pub fields: Vec<Field>,
}

/// Every type that is a table of an experiment file outside the planner sections, with the
/// source that declares it.
const SECTION_TYPES: [(&str, &str); 10] = [
    ("ExperimentFile", include_str!("../file.rs")),
    ("OutputSection", include_str!("../../planner/sections.rs")),
    ("MapSection", include_str!("../../planner/sections.rs")),
    ("RobotSection", include_str!("../../planner/sections.rs")),
    ("StationsSection", include_str!("../../planner/sections.rs")),
    ("ScorerSection", include_str!("../../planner/sections.rs")),
    ("CameraSection", include_str!("../../planner/sections.rs")),
    ("BudgetSection", include_str!("../../planner/sections.rs")),
    ("RobotEntry", include_str!("../../fleet/config.rs")),
    ("FleetSection", include_str!("../../fleet/config.rs")),
];

/// Every type that is a table of an experiment file with the source that declares it: those of
/// [`SECTION_TYPES`], then each planner section's type and the types of its own tables, as
/// its declaration names them.
fn section_types() -> Vec<(&'static str, &'static str)> {
    let mut all = SECTION_TYPES.to_vec();
    for section in crate::experiment::registry::planner_sections() {
        let (name, source) = section.source();
        all.push((name, source));
        all.extend(section.tables().iter().map(|&t| (t, source)));
    }
    all
}

/// The section type a field of type `ty` holds, and whether it is an array of tables:
/// `Option<CellOrderSection>` → `CellOrderSection`; `Vec<…::RobotEntry>` → `RobotEntry`, an
/// array; a map of tables (`[plugins.<name>]`) → `Table`.
pub fn section_type(ty: &str) -> Option<(&'static str, bool)> {
    if ty.contains("BTreeMap<String, toml::Table>") {
        return Some(("Table", false));
    }
    let array = ty.starts_with("Vec<");
    let inner = ty.trim_start_matches("Option<").trim_start_matches("Vec<").trim_end_matches('>');
    let name = inner.rsplit("::").next().unwrap_or(inner);
    section_types().into_iter().find(|(n, _)| *n == name).map(|(n, _)| (n, array))
}

/// The fields of section type `name` (a struct, or a tagged enum whose `kind` picks the
/// variant).
pub fn struct_shape(name: &str) -> Shape {
    let source = section_types().into_iter().find(|(n, _)| *n == name).map(|(_, s)| s).expect("a section type");
    shape_in(source, name)
}

/// The public fields of struct `name` declared in `source`, with their doc comments.
pub fn fields_in(source: &str, name: &str) -> Vec<Field> {
    shape_in(source, name).fields
}

/// The shape of struct or tagged enum `name` declared in `source`.
pub fn shape_in(source: &str, name: &str) -> Shape {
    let lines: Vec<&str> = source.lines().collect();
    let struct_at = lines.iter().position(|l| *l == format!("pub struct {name} {{"));
    let enum_at = lines.iter().position(|l| *l == format!("pub enum {name} {{"));
    let at = struct_at.or(enum_at).unwrap_or_else(|| panic!("no declaration of {name}"));
    let doc = doc_above(&lines, at);
    let body = lines[at + 1..].iter().take_while(|l| **l != "}").copied();
    let fields = if struct_at.is_some() { struct_fields(body, defaults_all(&lines, at)) } else { variant_fields(body) };
    Shape { doc, fields }
}

/// Whether the type declared at line `at` takes its defaults for absent fields
/// (`#[serde(default)]` among its attributes).
fn defaults_all(lines: &[&str], at: usize) -> bool {
    lines[..at]
        .iter()
        .rev()
        .map(|l| l.trim())
        .take_while(|l| l.starts_with("#[") || l.starts_with("///"))
        .any(|l| l.starts_with("#[serde(") && l.contains("default"))
}

/// The doc comment above line `at`, attributes skipped.
fn doc_above(lines: &[&str], at: usize) -> String {
    let mut doc = Vec::new();
    for line in lines[..at].iter().rev() {
        let line = line.trim();
        if let Some(text) = line.strip_prefix("///") {
            doc.push(text.trim());
        } else if !line.starts_with("#[") {
            break;
        }
    }
    doc.reverse();
    clean_doc(&doc.join(" "))
}

/// The `pub` fields of a struct body, with their docs; `#[serde(skip)]` fields left out.
/// `all_default`: the struct takes defaults for absent fields.
fn struct_fields<'a>(body: impl Iterator<Item = &'a str>, all_default: bool) -> Vec<Field> {
    let mut fields = Vec::new();
    let (mut doc, mut rename, mut skip, mut default) = (Vec::new(), None, false, false);
    for line in body.map(str::trim) {
        if let Some(text) = line.strip_prefix("///") {
            doc.push(text.trim().to_string());
        } else if line.starts_with("#[serde(") {
            skip |= line.contains("(skip)");
            default |= line.contains("default");
            rename = line.split("rename = \"").nth(1).and_then(|r| r.split('"').next()).map(str::to_string);
        } else if let Some((name, ty)) = line.strip_prefix("pub ").and_then(|l| l.split_once(": ")) {
            if !skip {
                let name = rename.take().unwrap_or_else(|| name.to_string());
                let ty = ty.trim_end_matches(',').to_string();
                let required = !all_default && !default;
                fields.push(Field { name, ty, doc: clean_doc(&doc.join(" ")), variant: None, required });
            }
            (doc, rename, skip, default) = (Vec::new(), None, false, false);
        }
    }
    fields
}

/// The fields of a tagged enum (`#[serde(tag = "kind", rename_all = "lowercase")]`): `kind`,
/// whose doc lists the variants, then each variant's fields.
fn variant_fields<'a>(body: impl Iterator<Item = &'a str>) -> Vec<Field> {
    let mut kinds = Vec::new();
    let mut fields = Vec::new();
    let mut doc = Vec::new();
    let mut variant: Option<String> = None;
    let mut default = false;
    for line in body {
        let depth = line.len() - line.trim_start().len();
        let line = line.trim();
        if let Some(text) = line.strip_prefix("///") {
            doc.push(text.trim().to_string());
        } else if line.starts_with("#[") {
            default |= line.starts_with("#[serde(") && line.contains("default");
        } else if depth == 4 && line.starts_with(|c: char| c.is_ascii_uppercase()) {
            let name = line.trim_end_matches([',', '{', ' ']).to_lowercase();
            kinds.push(format!("`{name}`: {}", clean_doc(&doc.join(" "))));
            variant = line.ends_with('{').then_some(name);
            doc.clear();
        } else if let (Some((name, ty)), Some(v)) = (line.split_once(": "), &variant) {
            let ty = ty.trim_end_matches(',').to_string();
            let doc_line = format!("{} (with `kind = \"{v}\"`)", clean_doc(&doc.join(" ")));
            let required = !default;
            fields.push(Field { name: name.to_string(), ty, doc: doc_line, variant: Some(v.clone()), required });
            doc.clear();
            default = false;
        }
    }
    let kind =
        Field { name: "kind".into(), ty: "String".into(), doc: kinds.join("; "), variant: None, required: false };
    std::iter::once(kind).chain(fields).collect()
}

/// A doc comment for a table cell: intra-doc links `[text](path)` and `` [`name`] `` reduced
/// to their text.
fn clean_doc(doc: &str) -> String {
    let mut out = String::new();
    let mut rest = doc;
    while let Some(open) = rest.find('[') {
        out.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        let Some(close) = after.find(']') else {
            out.push_str(&rest[open..]);
            return out;
        };
        let text = &after[..close];
        let tail = &after[close + 1..];
        let is_link = text.starts_with('`') && text.ends_with('`');
        if let Some(target) = tail.strip_prefix('(').and_then(|t| t.find(')').map(|k| &t[k + 1..])) {
            out.push_str(text);
            rest = target;
        } else if is_link {
            out.push_str(text);
            rest = tail;
        } else {
            out.push('[');
            out.push_str(text);
            out.push(']');
            rest = tail;
        }
    }
    out.push_str(rest);
    out
}

/// The TOML type of a field of Rust type `ty` (an enum or a name is a string).
pub fn toml_type(ty: &str, default: Option<&toml::Value>) -> String {
    let inner = ty.trim_start_matches("Option<").trim_end_matches('>');
    match inner {
        "f64" => "number".into(),
        "u8" | "u32" | "u64" | "usize" | "i64" => "integer".into(),
        "bool" => "boolean".into(),
        "[f64; 2]" => "[x, y] (numbers)".into(),
        "[f64; 4]" => "array of 4 numbers".into(),
        "Vec<f64" => "array of numbers".into(),
        "Vec<[f64; 2]" => "array of [x, y]".into(),
        "SeedPlans" => "array of strings".into(),
        _ if matches!(default, Some(toml::Value::Array(_))) => "array of strings".into(),
        _ => "string".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn doc_links_keep_their_text() {
        for (doc, want) in [
            ("Absent: [`DEFAULT_WALL_BAND_M`], for all.", "Absent: `DEFAULT_WALL_BAND_M`, for all."),
            ("The [`Scenario`](super::Scenario) and more.", "The `Scenario` and more."),
            ("A range [0, 1] stays.", "A range [0, 1] stays."),
        ] {
            assert_eq!(clean_doc(doc), want);
        }
    }

    #[test]
    fn sections_are_found_through_their_wrappers() {
        assert_eq!(section_type("Option<CellOrderSection>"), Some(("CellOrderSection", false)));
        assert_eq!(section_type("Vec<crate::fleet::config::RobotEntry>"), Some(("RobotEntry", true)));
        assert_eq!(section_type("f64"), None);
        let control = struct_shape("ControlSection");
        let names: Vec<&str> = control.fields.iter().map(|f| f.name.as_str()).collect();
        assert_eq!(names, ["kind", "min", "max", "k1", "k2", "k"]);
        assert!(control.fields[0].doc.contains("`ramp`"), "{:?}", control.fields[0]);
    }
}
