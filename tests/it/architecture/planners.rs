//! The registry of planners: `PLANNERS` (`src/experiment/registry.rs`) is the one list of
//! covga's own planners, each line naming the entry its planner's module holds, so that a new
//! planner is its folder and its line there (the developer guide's count). Nothing else outside
//! a planner's module names its entry, and no code outside the planners picks one by name.

use super::{LAYERS, layer, source_files};
use std::path::Path;

/// The registry's source, relative to `src/`.
const REGISTRY: &str = "experiment/registry.rs";

/// The entries of `PLANNERS` in `registry` (its source text): each line's path without its
/// `&crate::` and its arguments (`thesis::entry::Thesis`).
fn listed_entries(registry: &str) -> Vec<String> {
    let Some(start) = registry.find("pub const PLANNERS") else { return Vec::new() };
    let body = &registry[start..];
    let body = &body[..body.find("];").unwrap_or(body.len())];
    body.lines()
        .filter_map(|l| l.trim().strip_prefix("&crate::"))
        .map(|p| p.split(['(', ',']).next().unwrap_or(p).to_string())
        .collect()
}

/// The top-level module of an entry path (`thesis::entry::Thesis` → `thesis`).
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
