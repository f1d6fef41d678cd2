//! A key reported as ignored is ignored: for every planner and each of its variants (selection
//! schemes, cell-order solvers), every key of the planner sections that `why_ignored` calls
//! unread is set to another valid value and the run is made again; its summary (the plan's
//! scores, the planner's objectives, the effort) must be the run's without the change. The
//! keys come from the sections' own serialisation, so a key added to a section is covered
//! without an edit here; the warnings' rules (`covga::experiment::ignored`) are checked against
//! what the planners do, not against another list.

use covga::cell_order::config::CELL_ORDER_SECTION;
use covga::experiment::file::ExperimentFile;
use covga::experiment::ignored::why_ignored;
use covga::experiment::output::run_experiment;
use covga::experiment::registry::PlannerKind;
use covga::experiment::registry::planner_sections;
use covga::thesis::config::THESIS_SECTION;
use covga::waypoint::config::WAYPOINT_SECTION;
use std::path::Path;
use toml::{Table, Value};

/// Variants beyond each planner's defaults (every kind of the registry runs with its defaults
/// too, so a planner added there is covered without an edit here): selection schemes,
/// cell-order solvers, seed plans and objectives, on thesis-1; every planner section is written
/// out (its defaults included) so that each of its keys can be changed.
const VARIANTS: [&str; 10] = [
    "planner = \"thesis\"\n[thesis]\nselection = \"tournament\"\n",
    "planner = \"thesis\"\n[thesis]\nselection = \"rrws\"\n",
    "planner = \"thesis\"\n[thesis]\nselection = \"nsga2\"\n",
    "planner = \"thesis\"\n[thesis]\nseed_population = [\"cell_order\"]\n",
    // The camera objective weighs walls and open floor by waypoint.alpha_cov, whatever the
    // waypoint planner's own objective.
    "planner = \"thesis\"\n[thesis]\nobjective = \"camera\"\n[waypoint]\nobjective = \"footprint\"\n",
    "planner = \"cell_order\"\n[cell_order]\nselection = \"elite\"\n",
    "planner = \"cell_order\"\n[cell_order]\nsolver = \"ils\"\n",
    "planner = \"cell_order\"\n[cell_order]\nsolver = \"nearest\"\n",
    "planner = \"cell_order\"\n[cell_order]\nsolver = \"boustrophedon\"\n",
    "planner = \"waypoint\"\n[waypoint]\nwaypoint_set = \"near_wall\"\n",
];

/// The small budget every variant runs with.
const SMALL: &str = "seed = 3\n[map]\nsource = \"thesis-1\"\n[budget]\nevaluations = 300\niterations = 4\n";

/// The variant's file as a table, with every planner section written out in full.
fn full_table(variant: &str) -> Table {
    let (planner, sections) = variant.split_once('\n').expect("a planner line first");
    let mut file = ExperimentFile::parse(&format!("{planner}\n{SMALL}{sections}"), "u.toml").unwrap();
    let thesis = file.sections.get_mut(&THESIS_SECTION);
    thesis.pop_min = 10;
    thesis.init_individuals = 20;
    thesis.init_actions = 15;
    thesis.select = 8;
    thesis.keep = 2;
    let waypoint = file.sections.get_mut(&WAYPOINT_SECTION);
    waypoint.population = 6;
    waypoint.l_init = 20;
    waypoint.l_min = 10;
    let cell_order = file.sections.get_mut(&CELL_ORDER_SECTION);
    cell_order.population = 10;
    cell_order.best_parents = 4;
    cell_order.keep = 2;
    Table::try_from(file).unwrap()
}

/// The run's summary without its timings.
fn outcome(table: &Table) -> Option<serde_json::Value> {
    let file: ExperimentFile = Value::Table(table.clone()).try_into().ok()?;
    let exp = match file.validate("u.toml", Path::new("."), "u") {
        Ok(exp) => exp,
        Err(e) => {
            eprintln!("{e}");
            return None;
        }
    };
    let dir = tempfile::tempdir().unwrap();
    let summary = run_experiment(&exp, dir.path(), false, &mut []).unwrap();
    let mut v = serde_json::to_value(&summary).unwrap();
    let obj = v.as_object_mut().unwrap();
    for timing in ["wall_s", "precompute_s"] {
        obj.remove(timing);
    }
    Some(v)
}

/// Other values for a setting: numbers moved up and down, booleans flipped. Text and lists
/// (names, directions) are not varied.
fn alternatives(v: &Value) -> Vec<Value> {
    match v {
        Value::Integer(i) => {
            [i + 1, i - 1, i * 2].into_iter().filter(|n| *n >= 0 && n != i).map(Value::Integer).collect()
        }
        Value::Float(f) => [f * 1.1 + 0.01, f * 0.8, f + 1.0, f / 2.0].into_iter().map(Value::Float).collect(),
        Value::Boolean(b) => vec![Value::Boolean(!b)],
        Value::String(_) | Value::Array(_) | Value::Table(_) | Value::Datetime(_) => Vec::new(),
    }
}

#[test]
fn a_key_reported_unread_changes_nothing_in_the_run() {
    let mut checked = 0;
    let mut failures = Vec::new();
    let defaults: Vec<String> = PlannerKind::built_in().map(|k| format!("planner = \"{}\"\n", k.name())).collect();
    for variant in defaults.iter().map(String::as_str).chain(VARIANTS) {
        let table = full_table(variant);
        let file: ExperimentFile = Value::Table(table.clone()).try_into().unwrap();
        let reference = outcome(&table).unwrap_or_else(|| panic!("{variant}: the reference run fails"));
        for section in planner_sections().iter().map(|s| s.name()) {
            let Some(Value::Table(keys)) = table.get(section) else { continue };
            for (key, value) in keys {
                let dotted = format!("{section}.{key}");
                if why_ignored(&file, &dotted).is_none() {
                    continue;
                }
                // The first other value that is valid: an unread key is still range-checked.
                let changed = alternatives(value).into_iter().find_map(|other| {
                    let mut t = table.clone();
                    t[section].as_table_mut().unwrap().insert(key.clone(), other.clone());
                    outcome(&t).map(|o| (other, o))
                });
                let Some((other, got)) = changed else { continue };
                checked += 1;
                if got != reference {
                    failures.push(format!("{}: {dotted} = {other} changed the run", variant.lines().next().unwrap()));
                }
            }
        }
    }
    eprintln!("{checked} keys reported unread were varied");
    assert!(failures.is_empty(), "keys reported unread that change the run:\n{}", failures.join("\n"));
    assert!(checked >= 150, "only {checked} unread keys were varied");
}
