//! Every parent-selection scheme of the registry (`covga::ga::parents::SCHEMES`) is offered by
//! both GAs that draw their parents, from TOML: the cell-order GA and the thesis GA's
//! architecture (a) (but `"best"`, whose parameter the thesis GA does not set: its own `"elite"`
//! is its families).
//! A scheme added to the registry is covered here without an edit.

use crate::common::{run_text, summary};
use covga::experiment::file::ExperimentFile;
use covga::experiment::ignored::why_ignored;
use covga::ga::parents::{Param, SCHEMES};
use std::path::Path;

/// Runs `text` into a fresh folder and returns its `summary.json` and `config.toml`.
fn run(text: &str) -> (serde_json::Value, String) {
    let tmp = tempfile::tempdir().unwrap();
    run_text(text, Path::new("."), tmp.path());
    (summary(tmp.path()), std::fs::read_to_string(tmp.path().join("config.toml")).unwrap())
}

fn cell_order(scheme: &str) -> String {
    format!(
        "planner = \"cell_order\"\nseed = 3\n[map]\nsource = \"thesis-2\"\n[stations]\nstart = [1.3, 1.3]\n\
         [cell_order]\nselection = \"{scheme}\"\npopulation = 20\nselect = 5\n[budget]\nevaluations = 600\n"
    )
}

fn thesis(scheme: &str) -> String {
    format!(
        "planner = \"thesis\"\nseed = 3\n[map]\nsource = \"thesis-1\"\n[thesis]\nselection = \"{scheme}\"\n\
         pop_min = 20\ninit_individuals = 30\n[budget]\niterations = 15\n"
    )
}

#[test]
fn every_registered_scheme_runs_in_both_genetic_algorithms() {
    for s in SCHEMES {
        let mut texts = vec![cell_order(s.name())];
        if s.name() != "best" {
            texts.push(thesis(s.name()));
        }
        for text in texts {
            let (summary, config) = run(&text);
            assert!(config.contains(&format!("selection = \"{}\"", s.name())), "{}:\n{config}", s.name());
            assert!(summary["evaluations"].as_u64().unwrap() > 0, "{}: {summary}", s.name());
            // The same file and seed give the same plan.
            assert_eq!(run(&text).0["score"], summary["score"], "{}", s.name());
        }
    }
}

#[test]
fn keys_a_scheme_does_not_read_are_named_as_ignored() {
    let keys = [(Param::TournamentSize, "tournament_size"), (Param::Pressure, "sp"), (Param::BestParents, "select")];
    for s in SCHEMES {
        let file = ExperimentFile::parse(&cell_order(s.name()), "t.toml").unwrap();
        for (param, key) in keys {
            let why = why_ignored(&file, &format!("cell_order.{key}"));
            assert_eq!(why.is_some(), !s.reads().contains(&param), "{} and cell_order.{key}: {why:?}", s.name());
        }
    }
}

#[test]
fn an_unknown_scheme_is_refused_naming_the_registered_ones() {
    for text in [cell_order("roulette"), thesis("roulette")] {
        let err = ExperimentFile::parse(&text, "t.toml").unwrap_err().to_string();
        assert!(err.contains("roulette") && err.contains("`tournament`") && err.contains("`rrws`"), "{err}");
    }
}
