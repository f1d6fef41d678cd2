//! A planner added from outside covga, through its public API alone: a toy planner ("rays":
//! out from the start station and back along evenly spread directions) registers itself, and
//! an experiment file then selects it with `planner = "rays"` and sets it with
//! `[plugins.rays]`. Checked with no edit of covga: validation names its keys, the warnings
//! name what it does not read, a run writes the usual folder scored by the common scorer, runs
//! repeat exactly, and a grid study sweeps it beside a built-in planner. It takes everything it
//! uses from `covga::prelude`, the crate's one import for planners from outside.

use covga::prelude::{
    Budget, ConfigError, Context, ExperimentText, Observer, Planner, PlannerError, PlannerKind, PlannerPlugin,
    PluginError, Point, RegisteredPlanner, RunDone, RunOutcome, Scenario, StopReason, Study, check_range, details,
    prepare, register, run_in_folder, run_study, write_report,
};
use std::path::Path;
use std::sync::{Arc, Once};

/// The toy planner's settings, checked.
#[derive(Debug)]
struct Rays {
    rays: u32,
    reach_m: f64,
}

impl Planner for Rays {
    fn name(&self) -> &'static str {
        "rays"
    }
    fn run(
        &self,
        s: &Scenario,
        _seed: u64,
        _: &Budget,
        _: &mut [&mut dyn Observer],
    ) -> Result<RunOutcome, PlannerError> {
        let mut path = vec![s.start];
        for k in 0..self.rays {
            let angle = std::f64::consts::TAU * f64::from(k) / f64::from(self.rays);
            path.push(Point::new(s.start.x + self.reach_m * angle.cos(), s.start.y + self.reach_m * angle.sin()));
            path.push(s.start);
        }
        Ok(RunOutcome::new(vec![path], StopReason::Completed)
            .with_objectives(vec![("rays", f64::from(self.rays))])
            .with_effort(1, 0)
            .with_details(details(serde_json::json!({ "rays": self.rays }))))
    }
}

impl RegisteredPlanner for Rays {}

/// `[plugins.rays]`: `rays` in 1..=64 (default 4), `reach_m` in (0, 100] (default 1).
fn validate(section: &toml::Table, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
    let number = |key: &str, default: f64| match section.get(key) {
        None => Ok(default),
        Some(v) => v.as_float().or_else(|| v.as_integer().map(|i| i as f64)).ok_or_else(|| {
            ConfigError::new(ctx.origin, &format!("plugins.rays.{key}"), format!("= {v} is not a number"))
        }),
    };
    let rays = number("rays", 4.0)?;
    check_range(ctx.origin, "plugins.rays.rays", rays, 1.0, 64.0, "integers 1..=64")?;
    let reach_m = number("reach_m", 1.0)?;
    check_range(ctx.origin, "plugins.rays.reach_m", reach_m, 1e-3, 100.0, "(0, 100] metres")?;
    Ok(Arc::new(Rays { rays: rays as u32, reach_m }))
}

static RAYS: PlannerPlugin = PlannerPlugin { name: "rays", deterministic: true, keys: &["rays", "reach_m"], validate };

/// Registers the toy planner once for the whole test binary.
fn registered() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| register(&RAYS).expect("a new name"));
}

fn experiment(extra: &str) -> ExperimentText {
    ExperimentText {
        text: format!(
            "planner = \"rays\"\n[map]\nsource = \"thesis-2\"\n[stations]\nstart = [1.3, 1.3]\n[plugins.rays]\nrays = 6\n{extra}"
        ),
        origin: "rays.toml".into(),
        stem: "rays".into(),
    }
}

#[test]
fn a_planner_from_outside_is_checked_warned_about_and_registered_once() {
    registered();
    assert!(PlannerKind::all().iter().any(|k| k.name() == "rays"));
    assert_eq!(PlannerKind::named("rays").map(PlannerKind::is_deterministic), Some(true));
    assert_eq!(register(&RAYS), Err(PluginError::Taken("rays")));
    static THESIS: PlannerPlugin = PlannerPlugin { name: "thesis", deterministic: true, keys: &[], validate };
    assert_eq!(register(&THESIS), Err(PluginError::Taken("thesis")));
    static BAD: PlannerPlugin = PlannerPlugin { name: "Rays 2", deterministic: true, keys: &[], validate };
    assert_eq!(register(&BAD), Err(PluginError::BadName("Rays 2")));
    let refused =
        |extra: &str| prepare(&experiment(extra), None, None).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(refused("reach_m = 0.0\n").contains("plugins.rays.reach_m"), "{}", refused("reach_m = 0.0\n"));
    assert!(refused("[plugins.nope]\nx = 1\n").contains("plugins.nope"), "{}", refused("[plugins.nope]\nx = 1\n"));
    let unknown = ExperimentText { text: "planner = \"nope\"\n".into(), ..experiment("") };
    let message = prepare(&unknown, None, None).err().unwrap().to_string();
    assert!(message.contains("unknown variant `nope`") && message.contains("`rays`"), "{message}");
    let warned = prepare(&experiment("colour = 3\n[thesis]\npop_min = 5\n"), None, None).unwrap().warnings;
    assert!(warned.iter().any(|w| w.contains("`plugins.rays.colour` is ignored")), "{warned:?}");
    assert!(warned.iter().any(|w| w.contains("`thesis` is ignored")), "{warned:?}");
    assert_eq!(warned.len(), 2, "{warned:?}");
}

#[test]
fn a_planner_from_outside_runs_like_a_built_in_one_alone_and_in_a_grid() {
    registered();
    let tmp = tempfile::tempdir().unwrap();
    let prepared = prepare(&experiment(""), None, None).unwrap();
    let mut summaries = Vec::new();
    for run in ["a", "b"] {
        let dir = tmp.path().join(run);
        run_in_folder(&prepared, Some(&dir), false, &mut []).unwrap();
        let mut s: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join("summary.json")).unwrap()).unwrap();
        s.as_object_mut().unwrap().remove("wall_s");
        summaries.push((s, std::fs::read(dir.join("best_path.csv")).unwrap()));
        let config = std::fs::read_to_string(dir.join("config.toml")).unwrap();
        assert!(config.contains("planner = \"rays\"") && config.contains("[plugins.rays]\nrays = 6"), "{config}");
    }
    assert_eq!(summaries[0], summaries[1], "the same file gives the same files");
    let s = &summaries[0].0;
    assert_eq!((s["planner"].as_str(), s["rays"].as_u64()), (Some("rays"), Some(6)));
    let coverage = s["score"]["cov_final_reach"].as_f64().unwrap();
    assert!(coverage > 0.0 && coverage < 1.0, "scored by the common scorer: {coverage}");
    // A grid sweeps it beside a built-in planner; deterministic, each configuration runs once.
    let grid = tmp.path().join("g.toml");
    std::fs::write(
        &grid,
        "seeds = 3\n[base]\n[base.map]\nsource = \"thesis-2\"\n[base.stations]\nstart = [1.3, 1.3]\n\
         [axes]\nplanner = [\"boustrophedon\", \"rays\"]\n[[conditional]]\nwhen = { planner = \"rays\" }\n\
         axes = { \"plugins.rays.rays\" = [3, 8] }\n",
    )
    .unwrap();
    let study = Study::load(&grid).unwrap();
    assert_eq!(study.runs.len(), 3, "one boustrophedon run and two of the toy");
    let quiet = |_: RunDone| {};
    let opts = crate::common::runner_options(&tmp.path().join("study"), 2, &quiet);
    assert_eq!(run_study(&study, &opts).unwrap().completed, 3);
    let runs = std::fs::read_to_string(tmp.path().join("study/runs.csv")).unwrap();
    assert!(runs.lines().next().unwrap().contains("plugins.rays.rays"), "{runs}");
    assert_eq!(runs.lines().filter(|l| l.contains(",rays,")).count(), 2, "{runs}");
}

/// `covga report` over a study of the toy planner beside the thesis GA: the toy's runs are
/// its own planner in the report (measured by the common scorer as every planner other than
/// the thesis GA is, and labelled with its name), not runs of the thesis GA.
#[test]
fn a_planner_from_outside_is_reported_under_its_own_name() {
    registered();
    let tmp = tempfile::tempdir().unwrap();
    let grid = tmp.path().join("g.toml");
    std::fs::write(
        &grid,
        "seeds = 1\n[base]\n[base.map]\nsource = \"thesis-2\"\n[base.stations]\nstart = [1.3, 1.3]\n\
         [base.budget]\niterations = 3\n[axes]\nplanner = [\"thesis\", \"rays\"]\n",
    )
    .unwrap();
    let study = Study::load(&grid).unwrap();
    let quiet = |_: RunDone| {};
    let dir = tmp.path().join("study");
    assert_eq!(run_study(&study, &crate::common::runner_options(&dir, 2, &quiet)).unwrap().completed, 2);
    let summary = std::fs::read_to_string(write_report(&dir, &[]).unwrap()).unwrap();
    assert!(summary.contains("Mission time against reachable coverage"), "{summary}");
    let pareto = std::fs::read_to_string(dir.join("report/pareto.svg")).unwrap();
    let labels: Vec<&str> =
        pareto.split('>').filter_map(|t| t.split('<').next()).filter(|t| t.contains("rays")).collect();
    assert!(!labels.is_empty(), "the toy planner's runs carry its name in the figure's legend");
    assert!(labels.iter().all(|l| !l.contains("thesis")), "{labels:?}");
}

/// The toy planner reaches covga through the prelude alone: every `covga::` path of this file
/// starts with `covga::prelude`, so what a planner from outside needs is there.
#[test]
fn the_toy_planner_imports_from_the_prelude_alone() {
    let source = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/it/plugins.rs")).unwrap();
    let needle = ["covga", "::"].concat();
    let outside: Vec<&str> = source
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .filter(|l| l.match_indices(&needle).any(|(k, _)| !l[k + needle.len()..].starts_with("prelude")))
        .collect();
    assert!(outside.is_empty(), "paths into covga past its prelude:\n{}", outside.join("\n"));
}
