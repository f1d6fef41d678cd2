//! What a run records beside its plan: the history's reachable coverage and feasible members,
//! the population's genomes when asked, a waypoint team's section as written.

use super::*;

/// Every planner's history records the reachable coverage of its reported plan (the column
/// the ablation's convergence figure plots); where the reported plan is the plan itself (the
/// thesis GA, straight or routed, random search, a pattern), the last record equals the common
/// scorer's `cov_final_reach` in `summary.json`.
#[test]
fn the_history_records_the_reachable_coverage_the_scorer_reports() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("thesis", "[thesis]\npop_min = 20\ninit_actions = 30\n", true),
        ("thesis", "[thesis]\npop_min = 20\ninit_actions = 30\nmoves = \"routed\"\n", true),
        ("random_search", "", true),
        ("boustrophedon", "", true),
        ("cell_order", "", false),
        ("waypoint", "[waypoint]\ngenerations = 5\n", false),
    ];
    for (k, (planner, extra, exact)) in cases.into_iter().enumerate() {
        let text = format!(
            "seed = 3\nplanner = \"{planner}\"\n[map]\nsource = \"thesis-2\"\n{extra}[budget]\niterations = 20\nevaluations = 1500\n"
        );
        let exp = write(dir.path(), &format!("e{k}.toml"), &text);
        let out = dir.path().join(format!("o{k}"));
        let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "2");
        assert!(o.status.success(), "{planner}: {}", String::from_utf8_lossy(&o.stderr));
        let cov = column(&read(&out.join("history.csv")), "best_coverage_reach");
        assert!(!cov.is_empty() && cov.iter().all(|c| (0.0..=1.0).contains(c)), "{planner}: {cov:?}");
        if exact {
            let s: serde_json::Value = serde_json::from_str(&read(&out.join("summary.json"))).unwrap();
            let scored = s["score"]["cov_final_reach"].as_f64().unwrap();
            // serde_json reads floats to within an ulp (without its `float_roundtrip`
            // feature), so equal values are compared to 1e-12.
            assert!((cov.last().unwrap() - scored).abs() < 1e-12, "{planner} {extra}: {cov:?} vs {scored}");
        }
    }
}

#[test]
fn the_history_counts_the_feasible_members_of_the_thesis_ga_and_cell_order() {
    let dir = tempfile::tempdir().unwrap();
    // Thesis map 1 has walls: some members sweep them, the count lies in [0, population].
    let thesis = write(dir.path(), "t.toml", &small("").replace("iterations = 200", "iterations = 5"));
    let cells = write(
        dir.path(),
        "c.toml",
        "planner = \"cell_order\"\n[map]\nsource = \"thesis-2\"\n[stations]\nstart = [1.3, 1.3]\n\
         [cell_order]\npopulation = 20\n[budget]\nevaluations = 200\n",
    );
    for (file, population) in [(thesis, 40.0), (cells, 20.0)] {
        let out = dir.path().join(file.file_stem().unwrap());
        let o = covga_threads(&["run", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "1");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let feasible = column(&read(&out.join("history.csv")), "feasible");
        assert!(!feasible.is_empty() && feasible.iter().all(|&f| (0.0..=population).contains(&f)), "{feasible:?}");
        if population == 20.0 {
            // Every tour is driven on wall-free routes.
            assert!(feasible.iter().all(|&f| f == population), "{feasible:?}");
        }
    }
}

#[test]
fn population_genomes_are_written_when_asked_and_change_nothing_else() {
    let dir = tempfile::tempdir().unwrap();
    let mut outs = Vec::new();
    for (name, tail) in [("plain", ""), ("genomes", "[output]\npopulation_genomes = true\n")] {
        let exp = write(dir.path(), &format!("{name}.toml"), &(small("") + tail));
        let out = dir.path().join(name);
        let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "1");
        assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(o.stderr.is_empty(), "{name}: no warning: {}", String::from_utf8_lossy(&o.stderr));
        outs.push(out);
    }
    assert!(!outs[0].join("population_genomes.csv").exists(), "not written unless asked");
    for f in ["best_path.csv", "best_genome.csv", "population.csv", "history.csv"] {
        assert_eq!(read(&outs[0].join(f)), read(&outs[1].join(f)), "{f}");
    }
    // One row per live move of each member: population.csv's genome_len less the connector and E.
    let genomes = read(&outs[1].join("population_genomes.csv"));
    assert_eq!(genomes.lines().next(), Some("member,index,alpha_deg,dist_m"));
    let mut moves = std::collections::BTreeMap::<usize, usize>::new();
    for line in genomes.lines().skip(1) {
        *moves.entry(line.split(',').next().unwrap().parse().unwrap()).or_default() += 1;
    }
    let lengths = column(&read(&outs[1].join("population.csv")), "genome_len");
    assert_eq!(moves.len(), lengths.len());
    for (m, len) in lengths.iter().enumerate() {
        assert_eq!(moves[&m] + 2, *len as usize, "member {m}");
    }
    // Another planner does not write them, and says so.
    let exp = write(
        dir.path(),
        "spiral.toml",
        "planner = \"spiral\"\n[map]\nsource = \"thesis-1\"\n[output]\npopulation_genomes = true\n",
    );
    let o = covga_threads(
        &["run", exp.to_str().unwrap(), "--out", dir.path().join("spiral").to_str().unwrap(), "--quiet"],
        "1",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("output.population_genomes") && err.contains("only the single-robot thesis GA"), "{err}");
    assert!(!dir.path().join("spiral/population_genomes.csv").exists());
}

/// A waypoint team planned for `[[robots]]` (fleet.mode = "waypoint") leaves `[waypoint]` as
/// written: its `config.toml` holds no agents or starts the fleet made, and run again it gives
/// the same plan.
#[test]
fn a_waypoint_team_leaves_its_section_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let text = "seed = 2\nplanner = \"waypoint\"\n[map]\nsource = \"office\"\n[waypoint]\ngenerations = 4\n\
                population = 10\n[fleet]\nmode = \"waypoint\"\n[[robots]]\nname = \"a\"\nstart = [2.0, 2.0]\n\
                [[robots]]\nname = \"b\"\nstart = [2.0, 3.0]\n";
    let exp = write(dir.path(), "team.toml", text);
    let mut summaries = Vec::new();
    for (k, file) in [exp, dir.path().join("o0").join("config.toml")].into_iter().enumerate() {
        let out = dir.path().join(format!("o{k}"));
        let o = covga_threads(&["run", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "1");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let config: toml::Table = read(&out.join("config.toml")).parse().unwrap();
        assert_eq!(config["waypoint"]["agents"].as_integer(), Some(1), "as written");
        assert!(config["waypoint"]["starts"].as_array().unwrap().is_empty(), "as written");
        let mut s: serde_json::Value = serde_json::from_str(&read(&out.join("summary.json"))).unwrap();
        for timing in ["wall_s", "precompute_s"] {
            s.as_object_mut().unwrap().remove(timing);
        }
        assert_eq!(s["fleet"]["robots"].as_array().map(Vec::len), Some(2), "two agents flew");
        summaries.push(s);
    }
    assert_eq!(summaries[0], summaries[1]);
}
