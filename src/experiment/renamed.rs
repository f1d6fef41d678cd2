//! Keys that moved to another section or took a new name in theirs, and what keeps their old
//! spelling working for one release. A file or grid that uses an old key still reads: the value moves to the new key
//! before anything else sees it (an experiment, a grid's base, axes and `when` tables), the
//! warning names the new key, and a study's column takes the new name. Run ids hash the
//! experiment in the layout ids were first defined with ([`id_text`]), so that a move changes
//! no id and forces no committed study to re-run.

use super::file::ExperimentFile;
use crate::config::ConfigError;
use toml::{Table, Value};

/// Old dotted key → new dotted key. The scorer's projection and camera were read from the
/// thesis GA's and the waypoint planner's sections until they got a section of their own; the
/// cell-order GA's `sp` and `select` took the names that say what they are (`select` is the
/// thesis GA's count of pairs drawn, a different thing).
pub const RENAMED_KEYS: [(&str, &str); 8] = [
    ("thesis.projection", "scorer.projection"),
    ("waypoint.scale", "scorer.camera.scale"),
    ("waypoint.d_min", "scorer.camera.d_min"),
    ("waypoint.d_max", "scorer.camera.d_max"),
    ("waypoint.fov_deg", "scorer.camera.fov_deg"),
    ("waypoint.sections", "scorer.camera.sections"),
    ("cell_order.sp", "cell_order.selection_pressure"),
    ("cell_order.select", "cell_order.best_parents"),
];

/// A value of a key that took a new spelling, and the words that say so.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenamedValue {
    /// The dotted key.
    pub key: &'static str,
    /// The old value.
    pub old: &'static str,
    /// The new value.
    pub new: &'static str,
    /// `key = "old"`, as warnings and `covga migrate` say it.
    pub said_old: &'static str,
    /// `key = "new"`.
    pub said_new: &'static str,
}

/// Values that took a new spelling: the cell-order GA's draw from the best was `"elite"`, the
/// thesis GA's name for its families (a different thing; see
/// [`crate::ga::parents::RENAMED_SCHEMES`], which keeps the old value read).
pub const RENAMED_VALUES: [RenamedValue; 1] = [RenamedValue {
    key: "cell_order.selection",
    old: "elite",
    new: "best",
    said_old: "cell_order.selection = \"elite\"",
    said_new: "cell_order.selection = \"best\"",
}];

/// The old values an experiment text sets, each with its new spelling (for warnings).
pub fn renamed_values_in_text(text: &str) -> Moves {
    let Ok(table) = text.parse::<Table>() else { return Vec::new() };
    RENAMED_VALUES
        .iter()
        .filter(|r| {
            let (section, key) = r.key.split_once('.').expect("a dotted key");
            table.get(section).and_then(|s| s.get(key)).and_then(Value::as_str) == Some(r.old)
        })
        .map(|r| (r.said_old, r.said_new))
        .collect()
}

/// Gives the old values a grid conditional's `when` table `t` (dotted keys) tests their new
/// spelling, returning the renames made: a run's experiment reads an old value under its new
/// spelling, so a `when` that kept the old one would match no run.
pub fn current_when_values(t: &mut Table) -> Moves {
    let mut moved = Moves::new();
    for r in RENAMED_VALUES {
        if let Some(v) = t.get_mut(r.key).filter(|v| v.as_str() == Some(r.old)) {
            *v = Value::String(r.new.to_string());
            moved.push((r.said_old, r.said_new));
        }
    }
    moved
}

/// Gives the old values of the experiment table `t` (nested sections) their new spelling,
/// with the decor of each value kept.
fn rename_values(t: &mut dyn toml_edit::TableLike, moved: &mut Moves) {
    for r in RENAMED_VALUES {
        let (section, key) = r.key.split_once('.').expect("a dotted key");
        let Some(item) = t.get_mut(section).and_then(toml_edit::Item::as_table_like_mut).and_then(|s| s.get_mut(key))
        else {
            continue;
        };
        if item.as_str() == Some(r.old)
            && let Some(value) = item.as_value_mut()
        {
            let decor = value.decor().clone();
            *value = toml_edit::Value::from(r.new);
            *value.decor_mut() = decor;
            moved.push((r.said_old, r.said_new));
        }
    }
}

/// Gives the old values in a grid's axes `t` (`"cell_order.selection" = ["elite", …]`) their
/// new spelling.
fn rename_axis_values(t: &mut dyn toml_edit::TableLike, moved: &mut Moves) {
    for r in RENAMED_VALUES {
        let Some(values) = t.get_mut(r.key).and_then(toml_edit::Item::as_array_mut) else { continue };
        for value in values.iter_mut().filter(|v| v.as_str() == Some(r.old)) {
            let decor = value.decor().clone();
            *value = toml_edit::Value::from(r.new);
            *value.decor_mut() = decor;
            moved.push((r.said_old, r.said_new));
        }
    }
}

/// Gives the old values a conditional's `when` table `t` tests (`"cell_order.selection" =
/// "elite"`) their new spelling: the axes they are tested against take it too, so a `when`
/// left with the old value would match no run.
fn rename_when_values(t: &mut dyn toml_edit::TableLike, moved: &mut Moves) {
    for r in RENAMED_VALUES {
        let Some(value) = t.get_mut(r.key).and_then(toml_edit::Item::as_value_mut) else { continue };
        if value.as_str() == Some(r.old) {
            let decor = value.decor().clone();
            *value = toml_edit::Value::from(r.new);
            *value.decor_mut() = decor;
            moved.push((r.said_old, r.said_new));
        }
    }
}

/// Whether a renamed key stays in its section (renamed in place, not moved).
fn in_place(old: &str, new: &str) -> bool {
    old.rsplit_once('.').map(|p| p.0) == new.rsplit_once('.').map(|p| p.0)
}

/// Old keys met, each with its new name.
pub type Moves = Vec<(&'static str, &'static str)>;

/// The current spelling of a dotted key (`key` itself unless it was renamed).
pub fn current_key(key: &str) -> &str {
    RENAMED_KEYS.iter().find(|(old, _)| *old == key).map_or(key, |(_, new)| new)
}

/// The dotted key's old spelling, where it had one.
pub fn old_key(key: &str) -> Option<&'static str> {
    RENAMED_KEYS.iter().find(|(_, new)| *new == key).map(|(old, _)| *old)
}

/// The value at a dotted key of `t`, removed.
fn take(t: &mut Table, key: &str) -> Option<Value> {
    let (head, last) = key.rsplit_once('.').unwrap_or(("", key));
    let mut table = t;
    for part in head.split('.').filter(|p| !p.is_empty()) {
        table = table.get_mut(part)?.as_table_mut()?;
    }
    table.remove(last)
}

/// Sets a dotted key of `t`, making the tables on the way; the value already there, if any.
fn put(t: &mut Table, key: &str, value: Value) -> Result<Option<Value>, String> {
    let (head, last) = key.rsplit_once('.').unwrap_or(("", key));
    let mut table = t;
    for part in head.split('.').filter(|p| !p.is_empty()) {
        table = table
            .entry(part.to_string())
            .or_insert_with(|| Value::Table(Table::new()))
            .as_table_mut()
            .ok_or_else(|| format!("`{part}` is not a table"))?;
    }
    Ok(table.insert(last.to_string(), value))
}

/// Moves every old key of the experiment table `t` to its new place, returning the moves
/// made. An old and a new key both set to different values are refused, naming both.
pub fn rename_in_table(t: &mut Table, origin: &str) -> Result<Moves, ConfigError> {
    let mut moved = Vec::new();
    for (old, new) in RENAMED_KEYS {
        let Some(value) = take(t, old) else { continue };
        match put(t, new, value.clone()).map_err(|m| ConfigError::new(origin, new, m))? {
            Some(there) if there != value => {
                return Err(ConfigError::new(
                    origin,
                    new,
                    format!("= {there} and its old spelling `{old}` = {value} disagree: keep `{new}` only"),
                ));
            }
            _ => moved.push((old, new)),
        }
    }
    Ok(moved)
}

/// The old keys an experiment text sets, with their new names (for warnings).
pub fn renamed_in_text(text: &str) -> Moves {
    let Ok(mut table) = text.parse::<Table>() else { return Vec::new() };
    rename_in_table(&mut table, "").unwrap_or_default()
}

/// The warning for a file or grid that spells `old` (now `new`), naming `origin`.
pub fn warning(origin: &str, old: &str, new: &str) -> String {
    format!("{origin}: `{old}` is now `{new}`; the old name is read for one more release")
}

/// The text of an experiment or grid file with every old key under its new name (the file's
/// comments and layout kept; a section that gains its first key is added at the end), and the
/// moves made. A grid's base (`[base.…]`), axes and conditionals (`when`, `axes`) are migrated
/// alike. An old and a new key both set to different values are refused, naming both.
pub fn migrate_text(text: &str, origin: &str) -> Result<(String, Moves), ConfigError> {
    let mut doc: toml_edit::DocumentMut =
        text.parse().map_err(|e: toml_edit::TomlError| ConfigError::new(origin, "", e.message().trim()))?;
    let mut moved = Moves::new();
    let is_grid = doc.contains_key("base") && (doc.contains_key("axes") || doc.contains_key("seeds"));
    let root = doc.as_table_mut() as &mut dyn toml_edit::TableLike;
    let experiment =
        if is_grid { root.get_mut("base").and_then(toml_edit::Item::as_table_like_mut) } else { Some(root) };
    if let Some(t) = experiment {
        move_keys(t, origin, &mut moved)?;
        rename_values(t, &mut moved);
    }
    if is_grid {
        if let Some(axes) = doc.get_mut("axes").and_then(toml_edit::Item::as_table_like_mut) {
            rename_dotted(axes, origin, "axes", &mut moved)?;
            rename_axis_values(axes, &mut moved);
            refuse_moved_table_axes(axes, origin, "axes")?;
        }
        if let Some(conds) = doc.get_mut("conditional").and_then(toml_edit::Item::as_array_of_tables_mut) {
            for (n, c) in conds.iter_mut().enumerate() {
                for part in ["when", "axes"] {
                    if let Some(t) = c.get_mut(part).and_then(toml_edit::Item::as_table_like_mut) {
                        rename_dotted(t, origin, &format!("conditional[{n}].{part}"), &mut moved)?;
                        if part == "axes" {
                            rename_axis_values(t, &mut moved);
                            refuse_moved_table_axes(t, origin, &format!("conditional[{n}].axes"))?;
                        } else {
                            rename_when_values(t, &mut moved);
                        }
                    }
                }
            }
        }
    }
    moved.sort_unstable();
    moved.dedup();
    let out = doc.to_string();
    // A file written with Windows line ends keeps them.
    let out = if text.contains("\r\n") { out.replace("\r\n", "\n").replace('\n', "\r\n") } else { out };
    Ok((out, moved))
}

/// Moves the old keys of the experiment table `t` (nested sections) to their new place.
fn move_keys(t: &mut dyn toml_edit::TableLike, origin: &str, moved: &mut Moves) -> Result<(), ConfigError> {
    for (old, new) in RENAMED_KEYS {
        let (old_section, old_key) = old.split_once('.').expect("a dotted key");
        if in_place(old, new) {
            let Some(section) = t.get_mut(old_section).and_then(toml_edit::Item::as_table_like_mut) else { continue };
            if section.contains_key(old_key) {
                let new_key = new.rsplit_once('.').expect("a dotted key").1;
                rename_in_section(section, (old, old_key), (new, new_key), origin)?;
                moved.push((old, new));
            }
            continue;
        }
        // The comment lines above the key belong to it: they move with it.
        let above = t
            .get(old_section)
            .and_then(toml_edit::Item::as_table_like)
            .and_then(|s| s.key(old_key))
            .and_then(|k| k.leaf_decor().prefix().cloned());
        let Some(value) =
            t.get_mut(old_section).and_then(toml_edit::Item::as_table_like_mut).and_then(|s| s.remove(old_key))
        else {
            continue;
        };
        let (new_head, new_key) = new.rsplit_once('.').expect("a dotted key");
        let table =
            section_at(t, new_head).ok_or_else(|| ConfigError::new(origin, new, "is not in a table".to_string()))?;
        match table.get(new_key) {
            Some(there) if bare(there) != bare(&value) => {
                return Err(ConfigError::new(
                    origin,
                    new,
                    format!(
                        "= {} and its old spelling `{old}` = {} disagree: keep `{new}` only",
                        bare(there),
                        bare(&value)
                    ),
                ));
            }
            Some(_) => {}
            None => {
                table.insert(new_key, value);
                keep_above(table, new_key, above);
            }
        }
        moved.push((old, new));
    }
    Ok(())
}

/// Renames `old_key` of the section `t` to `new_key` where it stands, the keys' order and the
/// text above each kept. Both spellings set to different values are refused, naming both.
fn rename_in_section(
    t: &mut dyn toml_edit::TableLike,
    (old, old_key): (&str, &str),
    (new, new_key): (&str, &str),
    origin: &str,
) -> Result<(), ConfigError> {
    if let (Some(there), Some(value)) = (t.get(new_key), t.get(old_key)) {
        if bare(there) != bare(value) {
            return Err(ConfigError::new(
                origin,
                new,
                format!("= {} and its old spelling `{old}` = {} disagree: keep `{new}` only", bare(there), bare(value)),
            ));
        }
        t.remove(old_key);
        return Ok(());
    }
    rename_keeping_order(t, |k| if k == old_key { new_key } else { k }.to_string());
    Ok(())
}

/// Renames every key of `t` by `name` where it stands: the keys' order and the text above
/// each kept (toml_edit renames a key only by removing it and inserting it again at the end).
fn rename_keeping_order(t: &mut dyn toml_edit::TableLike, name: impl Fn(&str) -> String) {
    let keys: Vec<String> = t.iter().map(|(k, _)| k.to_string()).collect();
    let items: Vec<(String, Option<toml_edit::RawString>, toml_edit::Item)> = keys
        .iter()
        .map(|k| {
            let above = t.key(k).and_then(|key| key.leaf_decor().prefix().cloned());
            (k.clone(), above, t.remove(k).expect("a key listed"))
        })
        .collect();
    for (k, above, item) in items {
        let k = name(&k);
        t.insert(&k, item);
        keep_above(t, &k, above);
    }
}

/// The table at the dotted `path` below `t`, made where missing (a parent made only to hold
/// a sub-table is implicit: it writes no header of its own); `None` where a value is in the way.
fn section_at<'b>(t: &'b mut dyn toml_edit::TableLike, path: &str) -> Option<&'b mut dyn toml_edit::TableLike> {
    let Some((head, last)) = path.rsplit_once('.') else {
        return entry_table(t, path, false);
    };
    let mut parent = t;
    for part in head.split('.') {
        parent = entry_table(parent, part, true)?;
    }
    entry_table(parent, last, false)
}

/// The table `key` of `t`, made (implicit when `implicit`) where missing.
fn entry_table<'b>(
    t: &'b mut dyn toml_edit::TableLike,
    key: &str,
    implicit: bool,
) -> Option<&'b mut dyn toml_edit::TableLike> {
    if t.get(key).is_none() {
        let mut fresh = toml_edit::Table::new();
        fresh.set_implicit(implicit);
        t.insert(key, toml_edit::Item::Table(fresh));
    }
    t.get_mut(key)?.as_table_like_mut()
}

/// Renames the old dotted keys of a grid's axes or `when` table `t`, keeping their order.
fn rename_dotted(
    t: &mut dyn toml_edit::TableLike,
    origin: &str,
    section: &str,
    moved: &mut Moves,
) -> Result<(), ConfigError> {
    let keys: Vec<String> = t.iter().map(|(k, _)| k.to_string()).collect();
    if !keys.iter().any(|k| old_key_of(k)) {
        return Ok(());
    }
    for (old, new) in RENAMED_KEYS {
        if keys.iter().any(|k| k == old) && keys.iter().any(|k| k == new) {
            return Err(ConfigError::new(
                origin,
                &format!("{section}.\"{new}\""),
                format!("is also given under its old name `{old}`: keep `{new}` only"),
            ));
        }
    }
    moved.extend(RENAMED_KEYS.iter().filter(|(old, _)| keys.iter().any(|k| k == old)).copied());
    rename_keeping_order(t, |k| current_key(k).to_string());
    Ok(())
}

/// Gives `key` of `t` the text that stood above its old spelling (comment lines, blank lines).
fn keep_above(t: &mut dyn toml_edit::TableLike, key: &str, above: Option<toml_edit::RawString>) {
    if let (Some(above), Some(mut k)) = (above, t.key_mut(key)) {
        k.leaf_decor_mut().set_prefix(above);
    }
}

/// Refuses a grid axis whose values are tables of one section (`"thesis" = [{ projection =
/// "f1" }]`) holding a key that moved: such an axis was never read (the grid refuses the
/// unknown field), so no migration can be checked to keep its meaning; the message says how
/// to write it.
fn refuse_moved_table_axes(axes: &dyn toml_edit::TableLike, origin: &str, section: &str) -> Result<(), ConfigError> {
    for (name, item) in axes.iter() {
        let Some(values) = item.as_array() else { continue };
        let keys = values.iter().filter_map(toml_edit::Value::as_inline_table).flat_map(|t| t.iter().map(|(k, _)| k));
        let mut moves: Vec<String> = keys
            .filter_map(|k| {
                let dotted = format!("{name}.{k}");
                RENAMED_KEYS.iter().find(|(old, _)| *old == dotted).map(|(o, n)| format!("`{o}` is now `{n}`"))
            })
            .collect();
        moves.sort();
        moves.dedup();
        if let Some(first) = moves.first() {
            let new = first.rsplit('`').nth(1).unwrap_or_default();
            return Err(ConfigError::new(
                origin,
                &format!("{section}.\"{name}\""),
                format!(
                    "holds tables with keys that moved section ({}): covga cannot read this axis, so it cannot be \
                     migrated; write each moved key as an axis of its own (e.g. \"{new}\" = [...])",
                    moves.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

/// Whether `key` is an old spelling.
fn old_key_of(key: &str) -> bool {
    RENAMED_KEYS.iter().any(|(old, _)| *old == key)
}

/// A value as TOML text without its comments and spacing.
fn bare(item: &toml_edit::Item) -> String {
    item.as_value().map_or_else(
        || item.to_string(),
        |v| {
            let mut v = v.clone();
            v.decor_mut().clear();
            v.to_string()
        },
    )
}

/// The keys of `[thesis]` and `[waypoint]`, in the order that section was written in when the
/// moved keys still lay there, that come before each moved key (the moved key goes after the
/// last of them present; `None`: at the top of its section).
const OLD_PLACES: [(&str, &str, Option<&str>); 6] = [
    ("thesis", "projection", None),
    ("waypoint", "scale", None),
    ("waypoint", "d_min", Some("max_traverse")),
    ("waypoint", "d_max", Some("d_min")),
    ("waypoint", "fov_deg", Some("d_max")),
    ("waypoint", "sections", Some("fov_deg")),
];

/// The text a run id hashes: the experiment as `toml::to_string` writes it, in the layout of
/// the file before `[scorer]` existed (projection the first key of `[thesis]`, the camera's
/// scale first in `[waypoint]` and its depth range, field of view and sections after
/// `max_traverse`). Ids hash a canonical text so that the old and new spelling of a key give
/// one id, and this layout so that the ids of committed studies stay what they were. Keys of
/// `[scorer]` that never had another place (`camera.wall_band`) stay in `[scorer.camera]`;
/// keys renamed in place (`cell_order.selection_pressure`) hash under their old name, and
/// values that took a new spelling (`cell_order.selection = "best"`) under their old one.
pub fn id_text(file: &ExperimentFile) -> String {
    let text = toml::to_string(file).expect("experiment files serialise");
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut moved: Vec<(&str, &str, String)> = Vec::new();
    for (section, key, _) in OLD_PLACES {
        let new = RENAMED_KEYS.iter().find(|(old, _)| *old == format!("{section}.{key}")).expect("a renamed key").1;
        let (new_section, new_key) = new.rsplit_once('.').expect("a dotted key");
        if let Some(line) = take_line(&mut lines, new_section, new_key) {
            moved.push((section, key, line));
        }
    }
    for (old, new) in RENAMED_KEYS.iter().filter(|(old, new)| in_place(old, new)) {
        let (section, old_key) = old.rsplit_once('.').expect("a dotted key");
        let new_key = new.rsplit_once('.').expect("a dotted key").1;
        rename_line(&mut lines, section, new_key, old_key);
    }
    for r in RENAMED_VALUES {
        let (section, key) = r.key.rsplit_once('.').expect("a dotted key");
        let (new, old) = (format!("{key} = \"{}\"", r.new), format!("{key} = \"{}\"", r.old));
        if let Some((start, end)) = section_lines(&lines, section)
            && let Some(at) = (start..end).find(|&i| lines[i] == new)
        {
            lines[at] = old;
        }
    }
    drop_empty_sections(&mut lines, &["scorer.camera", "scorer"]);
    for (section, key, line) in moved {
        let after = OLD_PLACES.iter().find(|(s, k, _)| *s == section && *k == key).and_then(|p| p.2);
        insert_line(&mut lines, section, after, line);
    }
    let mut out = lines.join("\n");
    out.push('\n');
    out
}

/// The line range of `[section]`'s own keys: from after its header to the next header.
fn section_lines(lines: &[String], section: &str) -> Option<(usize, usize)> {
    let header = format!("[{section}]");
    let start = lines.iter().position(|l| *l == header)? + 1;
    let end = lines[start..].iter().position(|l| l.starts_with('[')).map_or(lines.len(), |n| start + n);
    Some((start, end))
}

/// Removes and returns the line `key = …` of `[section]`.
fn take_line(lines: &mut Vec<String>, section: &str, key: &str) -> Option<String> {
    let (start, end) = section_lines(lines, section)?;
    let prefix = format!("{key} = ");
    let at = (start..end).find(|&i| lines[i].starts_with(&prefix))?;
    Some(lines.remove(at))
}

/// Gives the line of `key` in `[section]` the name `to`, its value kept.
fn rename_line(lines: &mut [String], section: &str, key: &str, to: &str) {
    let Some((start, end)) = section_lines(lines, section) else { return };
    let prefix = format!("{key} = ");
    if let Some(at) = (start..end).find(|&i| lines[i].starts_with(&prefix)) {
        lines[at] = format!("{to} = {}", &lines[at][prefix.len()..]);
    }
}

/// Removes the headers of `sections` left without keys, with the blank lines after them (the
/// blank line before each header then precedes the next section).
fn drop_empty_sections(lines: &mut Vec<String>, sections: &[&str]) {
    for section in sections {
        let Some((start, end)) = section_lines(lines, section) else { continue };
        if lines[start..end].iter().all(|l| l.trim().is_empty()) {
            lines.drain(start - 1..end);
        }
    }
}

/// Inserts `line` into `[section]` after the key `after` (at the top when `None`).
fn insert_line(lines: &mut Vec<String>, section: &str, after: Option<&str>, line: String) {
    let Some((start, end)) = section_lines(lines, section) else { return };
    let at = after
        .and_then(|k| {
            let prefix = format!("{k} = ");
            (start..end).find(|&i| lines[i].starts_with(&prefix)).map(|i| i + 1)
        })
        .unwrap_or(start);
    lines.insert(at, line);
}

#[cfg(test)]
mod tests;
