//! Keys a configuration sets but its planner or selection scheme never reads. A key like that
//! is a silent no-op (an `init_individuals` under Elite, a tournament size swept under RRWS):
//! `covga run` warns about the ones the file sets, and a grid refuses to sweep one, since its
//! runs would differ only in a value nothing reads.

use super::file::ExperimentFile;
use super::registry::PlannerKind;
use crate::ga::parents::{self, Param};
use crate::thesis::config::SelectionName;
use crate::thesis::seeding::SeedPlan;

/// The `[thesis]` keys Elite's families and NSGA-II do not read (003 §3.4: Elite keeps the
/// `Pop_min` best of parents and children; architecture (a) draws `Select` pairs of parents).
const UNREAD_BY_ELITE_AND_NSGA2: [&str; 5] =
    ["thesis.init_individuals", "thesis.keep", "thesis.select", "thesis.tournament_size", "thesis.selection_pressure"];

/// Whether the thesis GA under `s` does not read `key` of `[thesis]`.
fn unread_by_selection(s: SelectionName, key: &str) -> bool {
    match s {
        SelectionName::Elite | SelectionName::Nsga2 => UNREAD_BY_ELITE_AND_NSGA2.contains(&key),
        SelectionName::Draw(name) => unread_by_scheme(name.as_str(), key, crate::thesis::config::param_key),
    }
}

/// The `[thesis]` keys random search reads (how it draws genomes).
const READ_BY_RANDOM_SEARCH: [&str; 4] =
    ["thesis.pop_min", "thesis.init_actions", "thesis.init_dist_max", "thesis.max_genome_len"];

/// The `[cell_order]` keys the thesis GA's `cell_order` seed plan reads (it runs no GA).
const READ_BY_CELL_ORDER_SEED: [&str; 3] =
    ["cell_order.directions", "cell_order.completion", "cell_order.completion_m_per_m2"];

/// The `[cell_order]` keys of its GA, which the exact solver does not read.
const CELL_ORDER_GA_KEYS: [&str; 11] = [
    "cell_order.population",
    "cell_order.selection",
    "cell_order.tournament_size",
    "cell_order.sp",
    "cell_order.select",
    "cell_order.keep",
    "cell_order.p_c",
    "cell_order.p_m",
    "cell_order.p_choice",
    "cell_order.memetic",
    "cell_order.seed_directions",
];

/// Whether `key` sets a selection parameter that the scheme `scheme` (a name of the registry,
/// [`crate::ga::parents`]) does not read, with `param_key` spelling the GA's keys.
fn unread_by_scheme(scheme: &str, key: &str, param_key: impl Fn(Param) -> Option<&'static str>) -> bool {
    parents::scheme(scheme)
        .is_some_and(|s| Param::ALL.iter().any(|&p| param_key(p) == Some(key) && !s.reads().contains(&p)))
}

/// Why the cell-order planner of `file` does not read `key` of `[cell_order]`.
fn unread_by_cell_order(file: &ExperimentFile, key: &str) -> Option<String> {
    use crate::cell_order::config::Solver;
    let section = file.cell_order.clone().unwrap_or_default();
    match section.solver {
        Solver::Exact if CELL_ORDER_GA_KEYS.contains(&key) => {
            Some("cell_order.solver = \"exact\" runs no GA (Held–Karp reads only the directions and completion)".into())
        }
        Solver::Exact => None,
        Solver::Ils if CELL_ORDER_GA_KEYS.contains(&key) && key != "cell_order.seed_directions" => Some(
            "cell_order.solver = \"ils\" runs no GA (iterated local search reads the directions, completion, \
             coverage_goal and seed_directions)"
                .into(),
        ),
        Solver::Ils => None,
        Solver::Nearest | Solver::Boustrophedon if CELL_ORDER_GA_KEYS.contains(&key) => Some(format!(
            "cell_order.solver = \"{}\" is a control with no search (it reads the directions, completion and coverage_goal)",
            if section.solver == Solver::Nearest { "nearest" } else { "boustrophedon" }
        )),
        Solver::Boustrophedon if key == "cell_order.completion_m_per_m2" => {
            Some("cell_order.solver = \"boustrophedon\" drives whole-map lanes: no tour cost charges completion".into())
        }
        Solver::Nearest | Solver::Boustrophedon => None,
        Solver::Ga => {
            unread_by_scheme(section.selection.as_str(), key, |p| Some(crate::cell_order::config::param_key(p)))
                .then(|| format!("cell_order.selection = \"{}\" does not use it", section.selection.as_str()))
        }
    }
}

/// Whether a planner other than the waypoint planner reads `waypoint.alpha_cov`: the thesis GA
/// with the camera objective weighs walls and open floor by it.
fn reads_alpha_cov(file: &ExperimentFile) -> bool {
    file.planner == PlannerKind::Thesis && file.thesis.objective == crate::thesis::objective::Objective::Camera
}

/// Whether `key` (dotted) lies in the section or key `prefix`.
fn within(key: &str, prefix: &str) -> bool {
    key == prefix || key.strip_prefix(prefix).is_some_and(|rest| rest.starts_with('.'))
}

/// Why `file`'s planner and selection do not read `key` (a dotted key such as
/// `thesis.keep`, or a section such as `pattern`; a renamed key by its current name), or
/// `None` when they read it. Every planner's plan is scored through `[scorer]`.
pub fn why_ignored(file: &ExperimentFile, key: &str) -> Option<String> {
    let key = super::renamed::current_key(key);
    let planner = file.planner;
    let name = planner.name();
    // Which of the planner-specific sections each planner reads besides its own.
    let (reads_retrain, reads_pattern, reads_cell_order) = match planner {
        // The thesis GA reads [pattern] and [cell_order] for the plans that seed its population.
        PlannerKind::Thesis => {
            let plans = file.thesis.seed_population.plans();
            let pattern = plans.iter().any(|p| matches!(p, SeedPlan::Boustrophedon | SeedPlan::Spiral));
            (true, pattern, plans.contains(&SeedPlan::CellOrder))
        }
        PlannerKind::Boustrophedon | PlannerKind::Spiral => (false, true, false),
        PlannerKind::CellOrder => (false, false, true),
        PlannerKind::Waypoint | PlannerKind::RandomSearch => (false, false, false),
    };
    if within(key, "retrain") && !reads_retrain {
        return Some(format!("only the thesis GA retrains; planner = \"{name}\""));
    }
    if within(key, "pattern") && !reads_pattern {
        return Some(format!(
            "only the boustrophedon and spiral patterns (and the thesis GA's seed plans) read [pattern]; planner = \"{name}\""
        ));
    }
    if within(key, "cell_order") && !reads_cell_order {
        return Some(format!(
            "only the cell-order planner (and the thesis GA's cell_order seed plan) reads [cell_order]; planner = \"{name}\""
        ));
    }
    if planner == PlannerKind::Thesis
        && within(key, "cell_order")
        && key != "cell_order"
        && !READ_BY_CELL_ORDER_SEED.iter().any(|k| within(key, k))
    {
        return Some(format!("the thesis GA's cell_order seed plan reads only {}", READ_BY_CELL_ORDER_SEED.join(", ")));
    }
    if planner == PlannerKind::CellOrder
        && let Some(why) = unread_by_cell_order(file, key)
    {
        return Some(why);
    }
    if within(key, "waypoint")
        && key != "waypoint"
        && planner != PlannerKind::Waypoint
        && !(key == "waypoint.alpha_cov" && reads_alpha_cov(file))
    {
        return Some(format!(
            "planner = \"{name}\" does not read [waypoint]{} (the common scorer's camera is [scorer.camera])",
            if file.planner == PlannerKind::Thesis {
                " (but alpha_cov with thesis.objective = \"camera\")"
            } else {
                ""
            }
        ));
    }
    if key == "output.population_genomes" && (planner != PlannerKind::Thesis || !file.robots.is_empty()) {
        return Some(format!(
            "only the single-robot thesis GA writes its population's genomes; planner = \"{name}\"{}",
            if file.robots.is_empty() { "" } else { " with [[robots]]" }
        ));
    }
    if key == "output.diversity_every" && planner != PlannerKind::Thesis {
        return Some(format!("only the thesis GA measures the population's diversity; planner = \"{name}\""));
    }
    if key == "waypoint.alpha_cov" && file.waypoint.objective == crate::waypoint::world::ObjectiveKind::Footprint {
        return Some(
            "waypoint.objective = \"footprint\" measures the swept area; only the camera objective blends walls and open floor by alpha_cov".into(),
        );
    }
    if key == "waypoint.near_wall" && file.waypoint.waypoint_set == crate::waypoint::world::WaypointSet::Full {
        return Some("waypoint.waypoint_set = \"full\" keeps every waypoint; only \"near_wall\" reads it".into());
    }
    if within(key, "thesis") {
        match planner {
            PlannerKind::Thesis => {
                let selection = file.thesis.selection;
                if key == "thesis.seed_share" && file.thesis.seed_population.is_empty() {
                    return Some("thesis.seed_population names no pattern to seed with".into());
                }
                if unread_by_selection(selection, key) {
                    return Some(format!("thesis.selection = \"{}\" does not use it", selection.name()));
                }
            }
            PlannerKind::RandomSearch => {
                if !READ_BY_RANDOM_SEARCH.contains(&key) {
                    return Some(format!("random search reads only {} of [thesis]", READ_BY_RANDOM_SEARCH.join(", ")));
                }
            }
            PlannerKind::Waypoint | PlannerKind::Boustrophedon | PlannerKind::Spiral | PlannerKind::CellOrder => {
                return Some(format!("planner = \"{name}\" does not read [thesis]"));
            }
        }
    }
    None
}

/// The dotted keys and sections set in the TOML `text` (tables and their keys, depth two),
/// with their why-ignored reason where `file` does not read them.
pub fn ignored_in_text(text: &str, file: &ExperimentFile) -> Vec<(String, String)> {
    let Ok(table) = text.parse::<toml::Table>() else { return Vec::new() };
    let mut out = Vec::new();
    for (section, value) in &table {
        match value {
            toml::Value::Table(t) if ["thesis", "waypoint", "output", "budget"].contains(&section.as_str()) => {
                for key in t.keys() {
                    let dotted = format!("{section}.{key}");
                    if let Some(why) = why_ignored(file, &dotted) {
                        out.push((dotted, why));
                    }
                }
            }
            // A section read as a whole may still hold keys its settings do not read.
            toml::Value::Table(t) if section == "cell_order" && why_ignored(file, section).is_none() => {
                for key in t.keys() {
                    let dotted = format!("{section}.{key}");
                    if let Some(why) = why_ignored(file, &dotted) {
                        out.push((dotted, why));
                    }
                }
            }
            _ => {
                if let Some(why) = why_ignored(file, section) {
                    out.push((section.clone(), why));
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(text: &str) -> ExperimentFile {
        ExperimentFile::parse(text, "t.toml").unwrap()
    }

    #[test]
    fn unread_keys_by_planner_and_selection() {
        let elite = file("[thesis]\nselection = \"elite\"\n");
        let rrws = file("[thesis]\nselection = \"rrws\"\n");
        let nsga2 = file("[thesis]\nselection = \"nsga2\"\n");
        let seeded = file("[thesis]\nseed_population = [\"boustrophedon\"]\n");
        let cell_seeded = file("[thesis]\nseed_population = [\"cell_order\"]\n");
        let waypoint = file("planner = \"waypoint\"\n");
        let random = file("planner = \"random_search\"\n");
        let cell_ga = file("planner = \"cell_order\"\n");
        let cell_elite = file("planner = \"cell_order\"\n[cell_order]\nselection = \"elite\"\n");
        let cell_exact = file("planner = \"cell_order\"\n[cell_order]\nsolver = \"exact\"\n");
        let cell_nearest = file("planner = \"cell_order\"\n[cell_order]\nsolver = \"nearest\"\n");
        let cell_lanes = file("planner = \"cell_order\"\n[cell_order]\nsolver = \"boustrophedon\"\n");
        for (f, key, ignored) in [
            (&elite, "thesis.init_individuals", true),
            (&elite, "thesis.keep", true),
            (&elite, "thesis.pop_min", false),
            (&elite, "thesis.p_mi", false),
            (&rrws, "thesis.selection_pressure", false),
            (&rrws, "thesis.tournament_size", true),
            (&rrws, "thesis.init_individuals", false),
            (&nsga2, "thesis.keep", true),
            (&nsga2, "thesis.tournament_size", true),
            (&nsga2, "thesis.p_ma", false),
            (&nsga2, "thesis.c_len", false),
            (&seeded, "pattern.angle_deg", false),
            (&seeded, "thesis.seed_share", false),
            (&seeded, "cell_order.directions", true),
            (&cell_seeded, "cell_order", false),
            (&cell_seeded, "cell_order.directions", false),
            (&cell_seeded, "cell_order.completion_m_per_m2", false),
            (&cell_seeded, "cell_order.population", true),
            (&cell_seeded, "cell_order.memetic", true),
            (&cell_seeded, "pattern.angle_deg", true),
            (&elite, "retrain", false),
            (&waypoint, "retrain", true),
            (&waypoint, "thesis.c_len", true),
            (&waypoint, "thesis.projection", false),
            (&waypoint, "scorer.projection", false),
            (&random, "scorer.camera.d_max", false),
            (&elite, "waypoint.hallway", true),
            (&elite, "waypoint.d_max", false),
            (&elite, "pattern", true),
            (&elite, "pattern.angle_deg", true),
            (&random, "thesis.init_actions", false),
            (&random, "thesis.c_len", true),
            (&elite, "thesis_x", false),
            (&waypoint, "waypoint.near_wall", true),
            (&file("planner = \"waypoint\"\n[waypoint]\nwaypoint_set = \"near_wall\"\n"), "waypoint.near_wall", false),
            (&file("planner = \"waypoint\"\n[waypoint]\nobjective = \"footprint\"\n"), "waypoint.alpha_cov", true),
            (&waypoint, "waypoint.alpha_cov", false),
            (&cell_ga, "cell_order.sp", true),
            (&cell_ga, "cell_order.select", true),
            (&cell_ga, "cell_order.tournament_size", false),
            (&cell_ga, "cell_order.population", false),
            (&cell_elite, "cell_order.sp", true),
            (&cell_elite, "cell_order.select", false),
            (&cell_exact, "cell_order.population", true),
            (&cell_exact, "cell_order.memetic", true),
            (&cell_exact, "cell_order.directions", false),
            (&cell_exact, "cell_order.completion", false),
            (&cell_nearest, "cell_order.population", true),
            (&cell_nearest, "cell_order.seed_directions", true),
            (&cell_nearest, "cell_order.coverage_goal", false),
            (&cell_nearest, "cell_order.completion_m_per_m2", false),
            (&cell_lanes, "cell_order.memetic", true),
            (&cell_lanes, "cell_order.completion_m_per_m2", true),
            (&cell_lanes, "cell_order.directions", false),
            (&cell_lanes, "cell_order.completion", false),
        ] {
            assert_eq!(why_ignored(f, key).is_some(), ignored, "{key} under {:?}", f.planner);
        }
    }

    #[test]
    fn only_keys_present_in_the_text_are_reported() {
        let text = "[thesis]\nselection = \"elite\"\ninit_individuals = 500\npop_min = 20\n[pattern]\nangle_deg = 0\n";
        let found: Vec<String> = ignored_in_text(text, &file(text)).into_iter().map(|(k, _)| k).collect();
        assert_eq!(found, ["pattern", "thesis.init_individuals"]);
        let text = "planner = \"cell_order\"\n[cell_order]\nsolver = \"exact\"\npopulation = 10\ndirections = [0.0]\n";
        let found: Vec<String> = ignored_in_text(text, &file(text)).into_iter().map(|(k, _)| k).collect();
        assert_eq!(found, ["cell_order.population"]);
    }
}
