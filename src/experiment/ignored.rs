//! Keys a configuration sets but its planner or selection scheme never reads. A key like that
//! is a silent no-op (an `init_individuals` under Elite, a tournament size swept under RRWS):
//! `covga run` warns about the ones the file sets, and a grid refuses to sweep one, since its
//! runs would differ only in a value nothing reads.

use super::file::ExperimentFile;

/// Why `file`'s planner and selection do not read `key` (a dotted key such as
/// `thesis.keep`, or a section such as `pattern`; a renamed key by its current name), or
/// `None` when they read it. Each planner's module says which keys of the planner sections it
/// reads ([`super::registry::PlannerKind::why_unread`]); every planner reads the shared sections (`[scorer]`
/// scores every plan), and what `[output]` asks of a run is said here.
pub fn why_ignored(file: &ExperimentFile, key: &str) -> Option<String> {
    let key = super::renamed::current_key(key);
    let planner = file.planner;
    let name = planner.name();
    if key == "output.population_genomes" && (!planner.entry().reads_output(key) || !file.robots.is_empty()) {
        return Some(format!(
            "only the single-robot thesis GA writes its population's genomes; planner = \"{name}\"{}",
            if file.robots.is_empty() { "" } else { " with [[robots]]" }
        ));
    }
    if key == "output.diversity_every" && !planner.entry().reads_output(key) {
        return Some(format!("only the thesis GA measures the population's diversity; planner = \"{name}\""));
    }
    planner.why_unread(file, key)
}

/// Why `file`'s planner reads no `[budget]` key, if it reads none: it plans once, in full.
/// A grid may give a budget to every planner of a `planner` axis, and its run ids count the
/// budget whether the planner reads it or not: a grid warns how many of its runs ignore it.
pub fn why_budget_unread(file: &ExperimentFile) -> Option<String> {
    let divide = !file.robots.is_empty()
        && file.fleet.as_ref().is_some_and(|f| f.mode == crate::fleet::config::FleetMode::Divide);
    let what = if file.planner.entry().plans_once() {
        format!("planner = \"{}\"", file.planner.name())
    } else if divide {
        "fleet.mode = \"divide\"".to_string()
    } else {
        return None;
    };
    Some(format!("{what} plans once, in full, and reads no budget (no limit of time or evaluations)"))
}

/// The dotted keys and sections set in the TOML `text` (tables and their keys, depth two),
/// with their why-ignored reason where `file` does not read them. A section none of whose keys
/// is read, by a planner that does not read the section, is named once; otherwise each key it
/// does not read is (a section may be unread as a whole and still hold a key that moved
/// elsewhere, such as `thesis.projection`).
pub fn ignored_in_text(text: &str, file: &ExperimentFile) -> Vec<(String, String)> {
    let Ok(table) = text.parse::<toml::Table>() else { return Vec::new() };
    let budget = why_budget_unread(file);
    let mut out = Vec::new();
    for (section, value) in &table {
        let whole = why_ignored(file, section);
        let toml::Value::Table(keys) = value else {
            out.extend(whole.map(|why| (section.clone(), why)));
            continue;
        };
        // `[plugins.<name>]` is a section of its own: its keys are one level further down.
        let dotted_keys: Vec<String> = if section == "plugins" {
            keys.iter()
                .flat_map(|(name, inner)| match inner {
                    toml::Value::Table(t) if why_ignored(file, &format!("plugins.{name}")).is_none() => {
                        t.keys().map(|k| format!("{name}.{k}")).collect()
                    }
                    _ => vec![name.clone()],
                })
                .collect()
        } else {
            keys.keys().cloned().collect()
        };
        let unread: Vec<(String, String)> = dotted_keys
            .iter()
            .filter_map(|key| {
                let dotted = format!("{section}.{key}");
                let why = if section == "budget" { budget.clone() } else { None };
                why.or_else(|| why_ignored(file, &dotted)).map(|why| (dotted, why))
            })
            .collect();
        match whole {
            Some(why) if unread.len() == dotted_keys.len() => out.push((section.clone(), why)),
            Some(_) | None => out.extend(unread),
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
            // The thesis GA's camera objective reads alpha_cov whatever the waypoint planner's own
            // objective (a warning said otherwise before the rules moved to the planners).
            (
                &file("[thesis]\nobjective = \"camera\"\n[waypoint]\nobjective = \"footprint\"\n"),
                "waypoint.alpha_cov",
                false,
            ),
            (&file("[thesis]\nobjective = \"camera\"\n"), "waypoint.hallway", true),
            (&cell_ga, "cell_order.selection_pressure", true),
            (&cell_ga, "cell_order.best_parents", true),
            (&cell_ga, "cell_order.tournament_size", false),
            (&cell_ga, "cell_order.population", false),
            (&cell_elite, "cell_order.selection_pressure", true),
            (&cell_elite, "cell_order.best_parents", false),
            (&cell_exact, "cell_order.population", true),
            (&cell_exact, "cell_order.memetic", true),
            (&cell_exact, "cell_order.directions", false),
            (&cell_exact, "cell_order.completion", false),
            (&cell_nearest, "cell_order.population", true),
            (&cell_nearest, "cell_order.seed_directions", true),
            (&cell_nearest, "cell_order.coverage_goal", false),
            (&cell_nearest, "cell_order.completion_m_per_m2", false),
            (&cell_lanes, "cell_order.memetic", true),
            // The control still reports the nearest-neighbour order's cost, which charges it.
            (&cell_lanes, "cell_order.completion_m_per_m2", false),
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
        // A section its planner does not read is named once, unless a key in it is read (a key
        // that moved: thesis.projection is scorer.projection).
        for (text, wanted) in [
            ("planner = \"waypoint\"\n[thesis]\nc_len = 0.1\npop_min = 20\n", vec!["thesis"]),
            ("planner = \"waypoint\"\n[thesis]\nc_len = 0.1\nprojection = \"f1\"\n", vec!["thesis.c_len"]),
            ("planner = \"spiral\"\n[cell_order]\n[budget]\niterations = 3\n", vec!["budget.iterations", "cell_order"]),
        ] {
            let found: Vec<String> = ignored_in_text(text, &file(text)).into_iter().map(|(k, _)| k).collect();
            assert_eq!(found, wanted, "{text}");
        }
    }

    #[test]
    fn every_planner_section_is_a_section_of_the_file() {
        let text = "[cell_order]\n[layouts]\n[retrain]\nat_iteration = 1\n";
        let table = toml::Table::try_from(ExperimentFile::parse(text, "t.toml").unwrap()).unwrap();
        let sections = crate::experiment::registry::planner_sections();
        assert!(sections.len() >= 5, "{}", sections.len());
        for section in sections {
            assert!(
                table.get(section.name()).is_some_and(toml::Value::is_table),
                "[{}] is not in the file",
                section.name()
            );
        }
    }
}
