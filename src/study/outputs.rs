//! The book's page of output files and columns (`covga reference outputs`): the files of a run,
//! a study, a report and `covga eval`, and every metric column of `runs.csv` with its kind and
//! meaning, read from the types that write them.

use crate::experiment::keys::source::fields_in;
use crate::study::records::{ColumnKind, column_kind, column_meaning, metric_columns};

/// The files of one folder kind: (file, what it holds).
const RUN_FILES: [(&str, &str); 12] = [
    ("config.toml", "the experiment with every default filled in (its run id hashes it)"),
    (
        "summary.json",
        "the plan's objectives, the common scorer's metrics (`common`), the time model, the times to 80, 90 and 95 % (`coverage_curve`), evaluations, iterations, why the run stopped, `wall_s`",
    ),
    (
        "history.csv",
        "one row per iteration (per generation): the best and population statistics of the planner's objectives, genome lengths, diversity, effective operator rates",
    ),
    ("best_path.csv", "`agent,index,x_m,y_m`: the returned plan, one path per agent (readable by `covga eval --path`)"),
    ("coverage_curve.csv", "`time_s,coverage_reach`: reachable coverage against mission time along the plan"),
    ("path.png, path.svg", "the plan over the map, swept cells coloured by visits"),
    ("best_genome.csv", "thesis GA: the returned plan's actions (role, `alpha_deg`, `dist_m`, viewpoint)"),
    ("population.csv", "thesis GA: the final population's objectives, one row per member"),
    ("population_genomes.csv", "thesis GA with `output.population_genomes = true`: every member's live moves"),
    ("history.png, history.svg", "thesis GA: the five panels of 003 Fig. 4.8"),
    (
        "waypoints, paths, coverage, pareto_snapshots, objectives (.png, .svg)",
        "waypoint planner: the graph, the paths with their loop closures, what the camera saw, the population at four generations, the objectives over generations",
    ),
    (
        "robots_history.csv",
        "the centralised fleet GA: per generation and robot of the best crew, its genome length, distinct swept cells and time",
    ),
];

/// The files of a study folder.
const STUDY_FILES: [(&str, &str); 5] = [
    ("grid.toml", "the grid file as run"),
    ("study.json", "the covga version, the git commit built from, a hash of the grid's runs, the run count"),
    ("runs.csv", "one row per finished run (columns below), appended and synced as each run ends"),
    ("runs/<run id>/", "each run's folder, as above (figures left out)"),
    ("calibration.csv", "with `--dry-run --calibrate`: the timed sample runs the estimate and the start order read"),
];

/// The files of `covga eval --out DIR`.
const EVAL_FILES: [(&str, &str); 4] = [
    (
        "metrics.json",
        "the common scorer's metrics of the plan (and a fleet's with `--fleet`), the time model, the lower bound (area and turning)",
    ),
    ("path.csv", "the plan scored, `agent,index,x_m,y_m`"),
    ("coverage_curve.csv", "reachable coverage against mission time along the plan"),
    ("path.png, path.svg", "the plan over the map"),
];

/// The page as Markdown.
pub fn markdown() -> String {
    let mut md = String::from(
        "# Output files and columns\n\n\
         What covga writes. This page is written by `covga reference outputs` from the types that\n\
         write the files; `tests/it/reference.rs` requires it to equal what the program writes.\n\
         Every file is written to a temporary name and renamed into place, so a killed run leaves\n\
         nothing half written. CSV files are tidy: one header row, `snake_case` columns.\n",
    );
    for (title, files) in [
        ("A run's folder (`covga run`)", &RUN_FILES[..]),
        ("A study's folder (`covga grid`)", &STUDY_FILES[..]),
        ("A scored plan's folder (`covga eval`)", &EVAL_FILES[..]),
    ] {
        md.push_str(&format!("\n## {title}\n\n| file | what it holds |\n| --- | --- |\n"));
        for (file, what) in files {
            md.push_str(&format!("| `{file}` | {what} |\n"));
        }
    }
    md.push_str(
        "\n## A report's folder (`covga report`)\n\n\
         `report/summary.md` with its figures, and one file per mode: see\n\
         [`covga report`, mode by mode](../guide/report.md).\n",
    );
    md.push_str(&columns_section());
    md
}

/// `runs.csv`'s columns: the ids, one column per swept key, then every metric column.
fn columns_section() -> String {
    let score = fields_in(include_str!("../coverage/score.rs"), "Score");
    let mut md = String::from(
        "\n## The columns of `runs.csv`\n\n\
         `run_id`, `config_id`, `replicate` and `seed` first, then one column per swept key (named by\n\
         its dotted key, typed as the key), then the metric columns below, the same for every\n\
         planner (a column a run does not measure is empty: a single robot's fleet columns, a failed\n\
         run's metrics).\n\n| column | kind | meaning |\n| --- | --- | --- |\n",
    );
    let ids = crate::study::records::ID_COLUMNS.iter().map(|c| c.to_string());
    for column in ids.chain(metric_columns()) {
        let kind = column_kind(&column).map_or("", ColumnKind::name);
        let meaning = score
            .iter()
            .find(|f| f.name == column)
            .map(|f| f.doc.clone())
            .or_else(|| column_meaning(&column).map(str::to_string))
            .unwrap_or_default();
        md.push_str(&format!("| `{column}` | {kind} | {} |\n", meaning.replace('|', "\\|")));
    }
    md
}
