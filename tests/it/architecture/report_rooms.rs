//! The rooms of `src/report/`, bottom to top: a file of a room imports only from its own room
//! and the rooms below; the replication of the papers and committed studies stands above every
//! generic room, so no generic room reads from it; figure code lives in the figures room; and
//! no room reads from the report's face (`src/report/mod.rs`), which puts the rooms together.
//! The order is written once, here; `src/report/mod.rs` and the book's "Layers and data flow"
//! describe it in words.

use super::source_files;
use std::path::Path;

/// The rooms of `src/report/`, bottom room first; rooms in one layer are peers and may not
/// import each other. A room is `src/report/<room>.rs` and everything under
/// `src/report/<room>/`; the face, `src/report/mod.rs`, stands above them all.
const REPORT_ROOMS: &[&[&str]] = &[
    // Every figure, drawn from the numbers it is given, and the legend and colour helpers.
    &["figures"],
    // The study as read and checked, its groups, fronts, best runs, design and run records.
    &["analysis"],
    // The tables and the `--compare` comparisons.
    &["tables", "compare"],
    // The papers' and committed studies' replication.
    &["replication"],
    // The summary's sections, in the order of `summary.md`.
    &["sections"],
];

/// The room that holds the report's figures, the one room whose code draws.
const FIGURES_ROOM: &str = "figures";

/// The layer of a room, or `None` for a name that is no room.
fn room_layer(room: &str) -> Option<usize> {
    REPORT_ROOMS.iter().position(|l| l.contains(&room))
}

/// The module path below `report` of a file relative to `src/report/` (`tables/anova.rs` →
/// `[tables, anova]`, `figures.rs` → `[figures]`, `mod.rs` → `[]`).
fn module_path(relative: &str) -> Vec<String> {
    let trimmed = relative.trim_end_matches(".rs");
    let mut path: Vec<String> = trimmed.split('/').map(str::to_string).collect();
    if path.last().is_some_and(|l| l == "mod") {
        path.pop();
    }
    path
}

/// The code of a line: what stands before a `//` comment.
fn code(line: &str) -> &str {
    line.find("//").map_or(line, |k| &line[..k])
}

/// The identifier at the start of `text`.
fn ident(text: &str) -> String {
    text.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect()
}

/// The names right after `prefix` in `text`: one name, or each item of a group `{a, b::c}`.
fn names_after(text: &str) -> Vec<String> {
    match text.strip_prefix('{') {
        Some(group) => {
            let end = group.find('}').unwrap_or(group.len());
            group[..end].split(',').map(|item| ident(item.trim())).filter(|n| !n.is_empty() && n != "self").collect()
        }
        None => vec![ident(text)].into_iter().filter(|n| !n.is_empty()).collect(),
    }
}

/// What the code of one file under `src/report/` (`relative`, its text `source`) reaches: for
/// each `crate::report::…` and each `super::…` path that leaves the file's own module, the
/// first module below `report` that it names (a room, or an item of the face). Inline modules
/// (`mod tests {`, closed by a `}` at their indentation, as rustfmt writes them) count as a
/// level of the path, so that their `super::` means the file's module.
fn reached(relative: &str, source: &str) -> Vec<String> {
    let base = module_path(relative);
    let mut inline: Vec<(usize, String)> = Vec::new();
    let mut out = Vec::new();
    for line in source.lines() {
        let indent = line.len() - line.trim_start().len();
        if inline.last().is_some_and(|(i, _)| *i == indent && line.trim() == "}") {
            inline.pop();
            continue;
        }
        let text = code(line);
        let mut rest = text;
        while let Some(k) = rest.find("crate::report::") {
            rest = &rest[k + "crate::report::".len()..];
            out.extend(names_after(rest));
        }
        let mut rest = text;
        while let Some(k) = rest.find("super::") {
            // Only the start of a chain: `super::super::x` is one path.
            let chain_start = k == 0 || !rest[..k].ends_with("::");
            let mut tail = &rest[k..];
            let mut ups = 0;
            while let Some(t) = tail.strip_prefix("super::") {
                tail = t;
                ups += 1;
            }
            if chain_start {
                let here: Vec<String> = base.iter().cloned().chain(inline.iter().map(|(_, n)| n.clone())).collect();
                let kept = here.len().saturating_sub(ups);
                match kept {
                    0 => out.extend(names_after(tail)),
                    _ => out.push(here[0].clone()),
                }
            }
            rest = tail;
        }
        let opened = text.trim_start().trim_start_matches("pub(crate) ").trim_start_matches("pub ");
        if let Some(name) = opened.strip_prefix("mod ").filter(|m| m.trim_end().ends_with('{')) {
            inline.push((indent, ident(name)));
        }
    }
    out
}

/// Every broken border among `files` (path relative to `src/report/`, source text).
fn room_violations(files: &[(String, String)]) -> Vec<String> {
    let mut problems = Vec::new();
    for (path, source) in files {
        let from = module_path(path).first().cloned().unwrap_or_default();
        // The face puts the rooms together: it may read every room.
        if from.is_empty() {
            continue;
        }
        let Some(from_layer) = room_layer(&from) else {
            problems.push(format!("src/report/{path}: `{from}` is in no room of REPORT_ROOMS"));
            continue;
        };
        for to in reached(path, source) {
            if to == from {
                continue;
            }
            match room_layer(&to) {
                Some(to_layer) if to_layer < from_layer => {}
                Some(to_layer) if to_layer == from_layer => problems.push(format!(
                    "src/report/{path}: the room `{from}` imports its peer `{to}` (rooms of one layer stay apart)"
                )),
                Some(_) => problems.push(format!(
                    "src/report/{path}: the room `{from}` imports `report::{to}`, a room above it{}",
                    if to == "replication" { " (no generic room reads from the replication)" } else { "" }
                )),
                None => problems.push(format!(
                    "src/report/{path}: imports `report::{to}` from the report's face (src/report/mod.rs): \
                     import it from the room that defines it"
                )),
            }
        }
        let draws = source.lines().map(code).any(|l| l.contains("plotters::") || l.contains("Figure for "));
        if draws && from != FIGURES_ROOM {
            problems.push(format!(
                "src/report/{path}: draws (plotters, or a `Figure` implemented) outside the figures room"
            ));
        }
    }
    problems.sort();
    problems.dedup();
    problems
}

#[test]
fn every_report_room_imports_only_from_its_room_and_below() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/report");
    let mut files = Vec::new();
    source_files(&root, &root, &mut files);
    assert!(files.len() > 40, "read {} files of src/report/", files.len());
    let problems = room_violations(&files);
    assert!(problems.is_empty(), "the rooms of src/report/ broken:\n{}", problems.join("\n"));
    // Every room of the order is there.
    for room in REPORT_ROOMS.iter().flat_map(|l| l.iter()) {
        assert!(files.iter().any(|(p, _)| p == &format!("{room}.rs")), "no src/report/{room}.rs");
    }
}

#[test]
fn the_room_checker_finds_what_crosses_a_border() {
    let file = |path: &str, text: &str| (path.to_string(), text.to_string());
    let found = |path: &str, text: &str| room_violations(&[file(path, text)]);
    // A generic room reading the replication, written either way.
    let up = found("figures/curves.rs", "use crate::report::replication::ablation_plots::draw;\n");
    assert!(up.len() == 1 && up[0].contains("replication"), "{up:?}");
    let grouped = found("analysis/folder_record.rs", "use crate::report::{figures::pareto, replication::claims};\n");
    assert!(grouped.len() == 1 && grouped[0].contains("replication"), "{grouped:?}");
    // `super::` that leaves the room: from a room's root, and two levels up from inside it.
    assert_eq!(found("tables.rs", "use super::replication::claims;\n").len(), 1);
    assert_eq!(found("tables/anova.rs", "use super::super::sections::Section;\n").len(), 1);
    // Within a room, and an inline test module's `super::`, are the room's own.
    assert!(
        found("tables/anova.rs", "use super::effects;\n#[cfg(test)]\nmod tests {\n    use super::*;\n}\n").is_empty()
    );
    assert!(
        found("figures/layout_tests.rs", "mod study {\n    use super::super::pareto::ParetoFigure;\n}\n").is_empty()
    );
    // Peers stay apart; downward is free; comments are not code.
    assert_eq!(found("compare/units.rs", "use crate::report::tables::anova;\n").len(), 1);
    assert!(
        found("replication/claims.rs", "use crate::report::analysis::runs::Group; // crate::report::sections\n")
            .is_empty()
    );
    // The face's items are read from their rooms.
    assert_eq!(found("analysis/study.rs", "use crate::report::ReportError;\n").len(), 1);
    assert!(found("mod.rs", "use replication::plans;\nuse crate::report::sections::SECTIONS;\n").is_empty());
    // Drawing outside the figures room.
    assert_eq!(found("sections.rs", "use plotters::prelude::*;\n").len(), 1);
    assert_eq!(found("replication/ablation_plots.rs", "impl Figure for Boxes {\n}\n").len(), 1);
    assert!(found("figures/boxes.rs", "use plotters::prelude::*;\nimpl Figure for BoxFigure {\n}\n").is_empty());
}
