use super::*;
use crate::cell_order::config::CELL_ORDER_SECTION;

fn parse(text: &str) -> ExperimentFile {
    ExperimentFile::parse(text, "t.toml").unwrap()
}

#[test]
fn old_and_new_spellings_read_alike_and_hash_alike() {
    let old =
        parse("[thesis]\nprojection = \"f1\"\npop_min = 30\n[waypoint]\nscale = 0.1\nd_max = 5.0\nsections = 9\n");
    let new = parse(
        "[thesis]\npop_min = 30\n[scorer]\nprojection = \"f1\"\n[scorer.camera]\nscale = 0.1\nd_max = 5.0\nsections = 9\n",
    );
    assert_eq!(old, new);
    assert_eq!(new.scorer.projection, crate::coverage::fitness::Projection::F1);
    assert_eq!((new.scorer.camera.scale, new.scorer.camera.d_max, new.scorer.camera.sections), (0.1, 5.0, 9));
    assert_eq!(id_text(&old), id_text(&new));
}

#[test]
fn the_id_text_keeps_the_layout_of_the_moved_keys() {
    let text = id_text(&parse("[scorer]\nprojection = \"f1\"\n"));
    assert!(!text.contains("[scorer"), "{text}");
    assert!(text.contains("[thesis]\nprojection = \"f1\"\n"), "{text}");
    assert!(text.contains("[waypoint]\nscale = 0.15\n"), "{text}");
    assert!(text.contains("max_traverse = 4.0\nd_min = 0.2\nd_max = 7.0\nfov_deg = 69.4\nsections = 15\n"), "{text}");
    // A key with no old place stays where it is, so that it still changes the id.
    let banded = id_text(&parse("[scorer.camera]\nwall_band = 1.25\n"));
    assert!(banded.contains("[scorer.camera]\nwall_band = 1.25"), "{banded}");
    assert_ne!(banded, id_text(&ExperimentFile::default()));
}

#[test]
fn disagreeing_spellings_are_refused_by_name() {
    let e = ExperimentFile::parse("[thesis]\nprojection = \"f1\"\n[scorer]\nprojection = \"f2\"\n", "t.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("scorer.projection") && e.contains("thesis.projection"), "{e}");
    // The same value twice is one setting.
    parse("[thesis]\nprojection = \"f1\"\n[scorer]\nprojection = \"f1\"\n");
}

#[test]
fn migrated_text_keeps_comments_and_means_the_same() {
    let old = "# a run\nplanner = \"thesis\"\n[thesis]\nprojection = \"f1\"  # f1 for this one\npop_min = 30\n\
               [waypoint]\nfov_deg = 90.0\nhallway = 2.0\n";
    let (new, moves) = migrate_text(old, "t.toml").unwrap();
    assert_eq!(moves, [("thesis.projection", "scorer.projection"), ("waypoint.fov_deg", "scorer.camera.fov_deg")]);
    assert!(new.starts_with("# a run\n") && new.contains("# f1 for this one"), "{new}");
    assert!(
        new.contains("[scorer]") && new.contains("[scorer.camera]") && !new.contains("\n[scorer]\n\n[scorer.camera]"),
        "{new}"
    );
    assert_eq!(parse(old), parse(&new));
    assert!(renamed_in_text(&new).is_empty(), "{new}");
    // A current file is left as it is.
    assert_eq!(migrate_text(&new, "t.toml").unwrap(), (new.clone(), Moves::new()));
    // A grid: base, axes and conditionals, in their order.
    let grid = "seeds = 2\n[base.thesis]\nprojection = \"f2\"\n[axes]\n\"thesis.c_len\" = [0.1]\n\"thesis.projection\" = [\"f1\", \"f2\"]\n\
                [[conditional]]\nwhen = { \"thesis.projection\" = \"f1\" }\naxes = { \"waypoint.d_max\" = [5.0] }\n";
    let (g, moves) = migrate_text(grid, "g.toml").unwrap();
    assert_eq!(moves, [("thesis.projection", "scorer.projection"), ("waypoint.d_max", "scorer.camera.d_max")]);
    assert!(
        g.contains("[base.scorer]\nprojection = \"f2\"")
            && g.contains("\"thesis.c_len\" = [0.1]\n\"scorer.projection\""),
        "{g}"
    );
    assert!(
        g.contains("when = { \"scorer.projection\" = \"f1\" }") && g.contains("\"scorer.camera.d_max\" = [5.0]"),
        "{g}"
    );
    let e = migrate_text("[thesis]\nprojection = \"f1\"\n[scorer]\nprojection = \"f2\"\n", "t.toml").unwrap_err();
    assert!(e.to_string().contains("disagree"), "{e}");
}

#[test]
fn old_keys_are_found_in_text_for_the_warnings() {
    let text = "[thesis]\nprojection = \"f1\"\n[waypoint]\nfov_deg = 90\nhallway = 2.0\n";
    assert_eq!(
        renamed_in_text(text),
        [("thesis.projection", "scorer.projection"), ("waypoint.fov_deg", "scorer.camera.fov_deg")]
    );
    assert_eq!(current_key("waypoint.sections"), "scorer.camera.sections");
    assert_eq!(current_key("waypoint.hallway"), "waypoint.hallway");
    assert_eq!(old_key("scorer.projection"), Some("thesis.projection"));
}

/// The cell-order GA's `sp` and `select` took their new names in place: old files read and
/// hash as before (the id text keeps the old names, so committed ids stay), `covga migrate`
/// renames them where they stand, and both spellings with different values are refused.
#[test]
fn keys_renamed_in_place_read_hash_and_migrate_alike() {
    let old =
        "planner = \"cell_order\"\n[cell_order]\nselection = \"best\"\nsp = 1.4  # gentle\nselect = 6\nkeep = 1\n";
    let new = "planner = \"cell_order\"\n[cell_order]\nselection = \"best\"\nselection_pressure = 1.4\nbest_parents = 6\nkeep = 1\n";
    assert_eq!(parse(old), parse(new));
    let section = CELL_ORDER_SECTION.get(&parse(new)).unwrap().clone();
    assert_eq!((section.selection_pressure, section.best_parents), (1.4, 6));
    let text = id_text(&parse(new));
    let cell_order = &text[text.find("[cell_order]").unwrap()..];
    assert!(cell_order.contains("\ntournament_size = 3\nsp = 1.4\nselect = 6\nkeep = 1\n"), "{text}");
    let (migrated, moves) = migrate_text(old, "t.toml").unwrap();
    assert_eq!(
        moves,
        [("cell_order.select", "cell_order.best_parents"), ("cell_order.sp", "cell_order.selection_pressure")]
    );
    assert!(
        migrated.contains("selection = \"best\"\nselection_pressure = 1.4  # gentle\nbest_parents = 6\nkeep = 1\n"),
        "{migrated}"
    );
    assert_eq!(parse(&migrated), parse(old));
    let e = ExperimentFile::parse("[cell_order]\nsp = 1.4\nselection_pressure = 1.5\n", "t.toml").unwrap_err();
    assert!(e.to_string().contains("cell_order.selection_pressure") && e.to_string().contains("cell_order.sp"), "{e}");
    parse("[cell_order]\nsp = 1.5\nselection_pressure = 1.5\n");
}

/// The cell-order GA's draw from the best is `"best"` now; `"elite"` still reads there (the
/// thesis GA's `"elite"` is its families), hashes as before, warns and migrates.
#[test]
fn a_value_renamed_reads_hashes_warns_and_migrates() {
    let old = "planner = \"cell_order\"\n[cell_order]\nselection = \"elite\"  # from the best\n";
    let new = "planner = \"cell_order\"\n[cell_order]\nselection = \"best\"\n";
    assert_eq!(parse(old), parse(new));
    assert_eq!(CELL_ORDER_SECTION.get(&parse(new)).unwrap().selection.as_str(), "best");
    assert!(id_text(&parse(new)).contains("[cell_order]\nsolver = \"ga\"\ndirections = [0.0, 45.0, 90.0, 135.0]\npopulation = 100\nselection = \"elite\"\n"));
    assert_eq!(renamed_values_in_text(old), [(RENAMED_VALUES[0].said_old, RENAMED_VALUES[0].said_new)]);
    assert!(renamed_values_in_text(new).is_empty());
    assert!(renamed_values_in_text("[thesis]\nselection = \"elite\"\n").is_empty(), "the thesis GA's own elite");
    let (migrated, moves) = migrate_text(old, "t.toml").unwrap();
    assert!(migrated.contains("selection = \"best\"  # from the best"), "{migrated}");
    assert_eq!(moves.len(), 1);
    let grid = "[base]\nplanner = \"cell_order\"\n[axes]\n\"cell_order.selection\" = [\"elite\", \"rrws\"]\n";
    let (g, _) = migrate_text(grid, "g.toml").unwrap();
    assert!(g.contains("\"cell_order.selection\" = [\"best\", \"rrws\"]"), "{g}");
}
