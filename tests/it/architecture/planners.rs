//! The planners: peers on one floor, none importing another (what one planner makes of
//! another's plan, a fleet of a planner, random search with the thesis GA's section are
//! compositions in the layers above them), and the registry of them: `PLANNERS`
//! (`src/experiment/registry.rs`) is the one list of covga's own planners, each line naming
//! the entry its planner's module holds, so that a new planner is its folder and its line there
//! (the developer guide's count). Nothing else outside a planner's module names its entry, and
//! no code outside the planners picks one by name.

use super::{LAYERS, imported_modules, layer, source_files, top_module};
use std::path::Path;

/// The registry's source, relative to `src/`.
const REGISTRY: &str = "experiment/registry.rs";

/// The entries of `PLANNERS` in `registry` (its source text): each line's path without its
/// `&crate::` and its arguments (`cell_order::entry::CellOrder`).
fn listed_entries(registry: &str) -> Vec<String> {
    let Some(start) = registry.find("pub const PLANNERS") else { return Vec::new() };
    let body = &registry[start..];
    let body = &body[..body.find("];").unwrap_or(body.len())];
    body.lines()
        .filter_map(|l| l.trim().strip_prefix("&crate::"))
        .map(|p| p.split(['(', ',']).next().unwrap_or(p).to_string())
        .collect()
}

/// The top-level module of an entry path (`cell_order::entry::CellOrder` → `cell_order`).
fn module_of(entry: &str) -> &str {
    entry.split("::").next().unwrap_or(entry)
}

/// The files of `files` outside `module`'s own (`src/<module>.rs`, `src/<module>/`) and the
/// registry that name `entry`; the code of tests (`#[cfg(test)]` and on, `tests.rs` files)
/// aside.
fn named_elsewhere(files: &[(String, String)], entry: &str) -> Vec<String> {
    let module = module_of(entry);
    let own = |path: &str| path == format!("{module}.rs") || path.starts_with(&format!("{module}/"));
    files
        .iter()
        .filter(|(path, _)| !own(path) && path != REGISTRY)
        .filter(|(_, source)| source.split("#[cfg(test)]").next().unwrap_or("").contains(entry))
        .map(|(path, _)| format!("src/{path} names {entry}"))
        .collect()
}

/// The files outside the tests that pick a planner by its name.
fn picked_by_name(files: &[(String, String)]) -> Vec<String> {
    files
        .iter()
        .filter(|(path, _)| !path.ends_with("tests.rs"))
        .filter(|(_, source)| source.split("#[cfg(test)]").next().unwrap_or("").contains("PlannerKind::named(\""))
        .map(|(path, _)| format!("src/{path} picks a planner by name"))
        .collect()
}

/// The planners' floor: the layer of `LAYERS` that holds the thesis GA.
fn planners_floor() -> &'static [&'static str] {
    LAYERS[layer("thesis").expect("the thesis GA has a layer")]
}

/// Every import of `files` from one planner of `floor` into another (tests included).
fn imports_between_planners(files: &[(String, String)], floor: &[&str]) -> Vec<String> {
    let mut out = Vec::new();
    for (path, source) in files {
        let from = top_module(path);
        if !floor.contains(&from.as_str()) {
            continue;
        }
        for to in imported_modules(source) {
            if to != from && floor.contains(&to.as_str()) {
                out.push(format!("src/{path}: the planner `{from}` imports the planner `{to}`"));
            }
        }
    }
    out
}

#[test]
fn no_planner_imports_another() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    source_files(&root, &root, &mut files);
    let floor = planners_floor();
    assert!(floor.len() >= 4, "{floor:?}");
    let problems = imports_between_planners(&files, floor);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // The check fails where it should: a seed plan made inside the thesis GA.
    let seeding = [("thesis/seeding.rs".to_string(), "use crate::cell_order::local_optimum_plan;\n".to_string())];
    assert_eq!(imports_between_planners(&seeding, floor).len(), 1);
    let own = [("thesis/seeding.rs".to_string(), "use crate::thesis::genome::Action;\n".to_string())];
    assert!(imports_between_planners(&own, floor).is_empty());
}

#[test]
fn the_registry_list_is_the_one_place_that_names_a_planner() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    source_files(&root.join("src"), &root.join("src"), &mut files);
    let registry = &files.iter().find(|(p, _)| p == REGISTRY).expect("the registry").1;
    let entries = listed_entries(registry);
    assert!(entries.len() >= 6, "{entries:?}");
    // Every entry is a planner module's: a layer between the planner interface and the
    // experiment file.
    let (planner, experiment) = (layer("planner").unwrap(), layer("experiment").unwrap());
    for e in &entries {
        let l = layer(module_of(e)).unwrap_or_else(|| panic!("{e} is in no module of LAYERS"));
        assert!(planner < l && l < experiment, "{e} is not a planner's ({:?})", LAYERS[l]);
    }
    let mut problems: Vec<String> = entries.iter().flat_map(|e| named_elsewhere(&files, e)).collect();
    problems.extend(picked_by_name(&files));
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // The checks fail where they should.
    let file = |path: &str, text: &str| (path.to_string(), text.to_string());
    let listed =
        listed_entries("pub const PLANNERS: &[&dyn E] = &[\n    &crate::a::entry::A,\n    &crate::b::B(x),\n];");
    assert_eq!(listed, ["a::entry::A", "b::B"]);
    let stray =
        [file("a/entry.rs", "a::entry::A"), file("c.rs", "use crate::a::entry::A;"), file(REGISTRY, "a::entry::A")];
    assert_eq!(named_elsewhere(&stray, "a::entry::A"), ["src/c.rs names a::entry::A"]);
    let picked = [file("c.rs", "PlannerKind::named(\"a\")"), file("d/tests.rs", "PlannerKind::named(\"a\")")];
    assert_eq!(picked_by_name(&picked).len(), 1);
    // The developer guide counts what this test keeps true.
    let guide = std::fs::read_to_string(root.join("docs/src/developer/adding-a-planner.md")).unwrap();
    assert!(guide.contains("its folder and its line in `PLANNERS`"), "the guide's count");
}

/// The sources of the experiment file (`experiment/file.rs`, `experiment/file/`).
fn experiment_file(path: &str) -> bool {
    path == "experiment/file.rs" || path.starts_with("experiment/file/")
}

/// Every import from a planner (its floor, and the compositions just above it) in the
/// experiment file's sources among `files`.
fn planners_named_by_the_file(files: &[(String, String)]) -> Vec<String> {
    let floor = layer("thesis").expect("the planners' floor");
    let planners: Vec<&str> = LAYERS[floor].iter().chain(LAYERS[floor + 1]).copied().collect();
    files
        .iter()
        .filter(|(path, _)| experiment_file(path))
        .flat_map(|(path, source)| {
            imported_modules(source)
                .into_iter()
                .filter(|m| planners.contains(&m.as_str()))
                .map(move |m| format!("src/{path} names the planner `{m}`"))
        })
        .collect()
}

/// A planner's section is its entry's declaration: the experiment file holds, checks and writes
/// every planner section from the declarations alone and names no planner, so that a planner
/// with a section of its own is its folder and its line in `PLANNERS` too.
#[test]
fn the_experiment_file_names_no_planner() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    source_files(&root, &root, &mut files);
    assert!(files.iter().filter(|(p, _)| experiment_file(p)).count() >= 2);
    let problems = planners_named_by_the_file(&files);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // The check fails where it should: a section's type named in the file.
    let typed = [("experiment/file.rs".to_string(), "use crate::cell_order::config::CellOrderSection;\n".to_string())];
    assert_eq!(planners_named_by_the_file(&typed).len(), 1);
    let composed = [("experiment/file/written.rs".to_string(), "crate::seeded::Thesis".to_string())];
    assert_eq!(planners_named_by_the_file(&composed).len(), 1);
}
