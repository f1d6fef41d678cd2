//! The layers of the crate, bottom to top: a module may import (`crate::…`) only from its own
//! layer and the layers below, and top-level modules never form a cycle. The order is written
//! once, here; `src/lib.rs` and the book's "Layers and data flow" describe it in words.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

mod planners;
mod report_rooms;

/// Top-level modules of `src/`, bottom layer first. Modules in one layer are peers: they may
/// import each other, but never in a cycle. `ga` (selection, control, RNG streams, observers)
/// needs nothing of the maps and sits below them, since the coverage layer hashes with its
/// streams; `plot` draws maps and coverage and sits above them.
const LAYERS: &[&[&str]] = &[
    &["geom", "stats"],
    &["io"],
    &["config"],
    &["ga"],
    &["map"],
    &["coverage"],
    &["routing", "lanes"],
    &["plot"],
    &["planner"],
    &["thesis", "waypoint", "patterns", "cell_order", "layouts"],
    &["random_search", "seeded"],
    &["fleet"],
    &["experiment"],
    &["study"],
    &["report"],
    &["usecase"],
    &["cli"],
    &["fuzz_entry"],
    // Names what the layers hold for users and plugins; nothing imports it.
    &["prelude"],
];

/// The layer of a top-level module, or `None` for one the order does not name.
fn layer(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

/// The top-level modules that the code of `source` names as `crate::<module>` (comments and
/// doc comments aside), including grouped imports `use crate::{a, b::c}`.
fn imported_modules(source: &str) -> BTreeSet<String> {
    let code: String = source
        .lines()
        .map(|l| match l.find("//") {
            Some(k) => &l[..k],
            None => l,
        })
        .collect::<Vec<_>>()
        .join("\n");
    let mut out = BTreeSet::new();
    let mut rest = code.as_str();
    while let Some(k) = rest.find("crate::") {
        let after = &rest[k + "crate::".len()..];
        if let Some(group) = after.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                let name: String = item.trim().chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
                if !name.is_empty() && name != "self" {
                    out.insert(name);
                }
            }
        } else {
            let name: String = after.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            if !name.is_empty() {
                out.insert(name);
            }
        }
        rest = after;
    }
    out
}

/// The top-level module of a file path relative to `src/` (`thesis/run.rs` → `thesis`).
fn top_module(relative: &str) -> String {
    relative.split('/').next().unwrap_or("").trim_end_matches(".rs").to_string()
}

/// Every violation of the layer order in `files` (relative path under `src/`, source text):
/// imports from a layer above, modules the order does not name, and cycles between top-level
/// modules.
fn violations(files: &[(String, String)]) -> Vec<String> {
    let mut problems = Vec::new();
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (path, source) in files {
        let from = top_module(path);
        if from == "lib" || from == "main" {
            continue;
        }
        let Some(from_layer) = layer(&from) else {
            problems.push(format!("src/{path}: top-level module `{from}` is in no layer of LAYERS"));
            continue;
        };
        for to in imported_modules(source) {
            if to == from {
                continue;
            }
            match layer(&to) {
                Some(to_layer) if to_layer > from_layer => problems.push(format!(
                    "src/{path}: `{from}` (layer {from_layer}) imports `crate::{to}` from the layer above it ({to_layer})"
                )),
                Some(_) => {
                    graph.entry(from.clone()).or_default().insert(to);
                }
                None => problems.push(format!("src/{path}: imports `crate::{to}`, which is in no layer")),
            }
        }
    }
    // Cycles among peers (imports across layers only go down, so a cycle stays in one layer).
    for start in graph.keys() {
        let mut stack: Vec<(String, Vec<String>)> = vec![(start.clone(), vec![start.clone()])];
        let mut seen = BTreeSet::new();
        while let Some((node, trail)) = stack.pop() {
            for next in graph.get(&node).into_iter().flatten() {
                if next == start {
                    problems.push(format!("import cycle: {} -> {start}", trail.join(" -> ")));
                } else if seen.insert(next.clone()) {
                    let mut longer = trail.clone();
                    longer.push(next.clone());
                    stack.push((next.clone(), longer));
                }
            }
        }
    }
    problems.sort();
    problems.dedup();
    problems
}

fn source_files(dir: &Path, root: &Path, out: &mut Vec<(String, String)>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir).expect("src/ is readable").map(|e| e.unwrap().path()).collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            source_files(&path, root, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let relative = path.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/");
            out.push((relative, std::fs::read_to_string(&path).unwrap()));
        }
    }
}

#[test]
fn every_module_imports_only_from_its_layer_and_below() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    source_files(&root, &root, &mut files);
    assert!(files.len() > 100, "read {} files of src/", files.len());
    let problems = violations(&files);
    assert!(problems.is_empty(), "layer order broken:\n{}", problems.join("\n"));
}

#[test]
fn every_top_level_module_has_a_layer() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let lib = std::fs::read_to_string(root.join("lib.rs")).unwrap();
    let declared: Vec<&str> =
        lib.lines().filter_map(|l| l.strip_prefix("pub mod ")).map(|m| m.trim_end_matches(';')).collect();
    assert!(declared.len() >= 15, "{declared:?}");
    for m in &declared {
        assert!(layer(m).is_some(), "`{m}` of src/lib.rs is in no layer of LAYERS");
    }
    let listed: usize = LAYERS.iter().map(|l| l.len()).sum();
    assert_eq!(listed, declared.len(), "LAYERS names a module that src/lib.rs does not declare");
}

#[test]
fn the_checker_finds_an_upward_import_a_cycle_and_grouped_imports() {
    let file = |path: &str, text: &str| (path.to_string(), text.to_string());
    // A map module reaching up to the study layer.
    let up = violations(&[file("map/mod.rs", "use crate::geom::Point;\nuse crate::study::grid::Study;\n")]);
    assert_eq!(up.len(), 1, "{up:?}");
    assert!(up[0].contains("`map`") && up[0].contains("crate::study"), "{up:?}");
    // Grouped imports are read item by item; comments are not code.
    let grouped =
        violations(&[file("coverage/score.rs", "use crate::{geom::Point, thesis::genome};\n// crate::cli\n")]);
    assert_eq!(grouped.len(), 1, "{grouped:?}");
    assert!(grouped[0].contains("crate::thesis"), "{grouped:?}");
    // Peers may import each other, but not both ways.
    let cycle = violations(&[
        file("thesis/run.rs", "use crate::waypoint::run::Organism;\n"),
        file("waypoint/run.rs", "use crate::thesis::run::Ga;\n"),
    ]);
    assert!(cycle.iter().any(|p| p.starts_with("import cycle")), "{cycle:?}");
    let one_way = violations(&[file("thesis/run.rs", "use crate::waypoint::run::Organism;\n")]);
    assert!(one_way.is_empty(), "{one_way:?}");
    // A module the order does not know is named.
    assert_eq!(violations(&[file("newthing.rs", "")]).len(), 1);
}

/// The book's page whose table describes the layers.
const LAYERS_PAGE: &str = "docs/src/concepts/layers.md";

/// The module names of each layer as `text` writes them: one group per line that `starts`
/// accepts, the backticked names up to the line's `stop` (the book's table cell, the lib.rs
/// list item's colon).
fn described_layers(text: &str, starts: impl Fn(&str) -> Option<&str>, stop: char) -> Vec<Vec<String>> {
    text.lines()
        .filter_map(|l| starts(l.trim_start()))
        .map(|rest| {
            let names = rest.split(stop).next().unwrap_or("");
            names.split('`').skip(1).step_by(2).map(str::to_string).collect()
        })
        .collect()
}

/// Whether `described` (coarser groups, in order) is `LAYERS` read in order, each group a run of
/// whole layers; the problems otherwise.
fn layer_order_problems(what: &str, described: &[Vec<String>]) -> Vec<String> {
    let flat: Vec<&str> = described.iter().flatten().map(String::as_str).collect();
    let ordered: Vec<&str> = LAYERS.iter().flat_map(|l| l.iter().copied()).collect();
    if flat != ordered {
        return vec![format!("{what} lists the modules as {flat:?}; tests/it/architecture.rs as {ordered:?}")];
    }
    // With the order equal, groups are runs of whole layers when each starts a layer.
    described
        .iter()
        .filter(|g| g.first().is_some_and(|m| layer(m).is_some_and(|l| LAYERS[l][0] != m.as_str())))
        .map(|g| format!("{what}: the group {g:?} splits a layer of tests/it/architecture.rs"))
        .collect()
}

#[test]
fn the_book_and_lib_rs_describe_the_layer_order_of_this_test() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let layout = std::fs::read_to_string(root.join(LAYERS_PAGE)).unwrap();
    let table = described_layers(
        &layout,
        |l| {
            l.strip_prefix("| ")
                .filter(|r| r.starts_with(|c: char| c.is_ascii_digit()))
                .and_then(|r| r.split_once(" | "))
                .map(|(_, r)| r)
        },
        '|',
    );
    // A list item of lib.rs's doc may run over several indented lines: one line per item.
    let mut lib = String::new();
    for line in std::fs::read_to_string(root.join("src/lib.rs")).unwrap().lines() {
        match line.strip_prefix("//!    ") {
            Some(more) if !lib.is_empty() => lib = format!("{} {}", lib.trim_end_matches('\n'), more.trim()) + "\n",
            _ => lib += &format!("{line}\n"),
        }
    }
    let list = described_layers(
        &lib,
        |l| {
            let item = l.strip_prefix("//! ")?;
            let (number, rest) = item.split_once(". ")?;
            number.parse::<u32>().ok().map(|_| rest)
        },
        ':',
    );
    let mut problems = layer_order_problems(LAYERS_PAGE, &table);
    problems.extend(layer_order_problems("src/lib.rs's list of layers", &list));
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // The check fails where it should: two modules swapped.
    let mut swapped = table.clone();
    swapped[1].insert(0, "cli".into());
    assert!(!layer_order_problems("swapped", &swapped).is_empty());
    // And where a group starts inside a layer: `waypoint` split from `thesis`.
    let split: Vec<Vec<String>> = LAYERS
        .iter()
        .flat_map(|l| {
            if l[0] == "thesis" {
                vec![vec![l[0].to_string()], l[1..].iter().map(|m| m.to_string()).collect()]
            } else {
                vec![l.iter().map(|m| m.to_string()).collect()]
            }
        })
        .collect();
    assert!(layer_order_problems("split", &split).iter().any(|p| p.contains("splits a layer")), "{split:?}");
}
