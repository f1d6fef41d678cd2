//! `thesis.moves = "routed"`: moves that would sweep an obstacle drive around it.

use covga::experiment::file::ExperimentFile;
use covga::experiment::output::run_experiment;
use std::path::Path;

/// Runs `text` (map paths relative to `base`) into a fresh folder; returns the folder.
fn run(text: &str, base: &Path) -> tempfile::TempDir {
    let tmp = tempfile::tempdir().unwrap();
    let exp = ExperimentFile::parse(text, "test").unwrap().validate("test", base, "t").unwrap();
    run_experiment(&exp, tmp.path(), false, &mut []).unwrap();
    tmp
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

fn read(dir: &Path, file: &str) -> String {
    std::fs::read_to_string(dir.join(file)).unwrap()
}

const THESIS_2: &str = "seed = 7\nplanner = \"thesis\"\n[map]\nsource = \"thesis-2\"\n[stations]\nstart = [1.3, 1.3]\n\
                        [thesis]\npop_min = 40\ninit_actions = 30\n[budget]\niterations = 60\n";

#[test]
fn routed_moves_on_a_map_without_obstacles_are_the_straight_moves_bit_for_bit() {
    // A 12 m × 10 m room at 0.2 m whose every cell is free: no move needs a route.
    let maps = tempfile::tempdir().unwrap();
    let (cols, rows) = (60, 50);
    let mut pgm = format!("P5\n{cols} {rows}\n255\n").into_bytes();
    pgm.extend(std::iter::repeat_n(254u8, cols * rows));
    std::fs::write(maps.path().join("open.pgm"), pgm).unwrap();
    std::fs::write(
        maps.path().join("open.yaml"),
        "image: open.pgm\nresolution: 0.2\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    )
    .unwrap();
    let straight = "seed = 3\nplanner = \"thesis\"\n[map]\nsource = \"open.yaml\"\n[stations]\nstart = [1.0, 1.0]\n\
                    [robot]\nrot_speed = 0.5\n[thesis]\npop_min = 30\ninit_actions = 20\ninit_dist_max = 8.0\n\
                    [budget]\niterations = 80\n";
    let routed = straight.replace("[thesis]\n", "[thesis]\nmoves = \"routed\"\n");
    let (a, b) = (run(straight, maps.path()), run(&routed, maps.path()));
    for file in ["best_path.csv", "best_genome.csv", "history.csv", "population.csv"] {
        assert_eq!(read(a.path(), file), read(b.path(), file), "{file}");
    }
    let (sa, sb) = (summary(a.path()), summary(b.path()));
    assert_eq!(sa["score"], sb["score"]);
    assert_eq!(sb["moves"].as_str().map(|m| m.starts_with("routed")), Some(true), "{sb}");
}

#[test]
fn routed_moves_evaluated_incrementally_equal_full_evaluations() {
    let routed = THESIS_2.replace("[thesis]\n", "[thesis]\nmoves = \"routed\"\n");
    let full = routed.replace("[thesis]\n", "[thesis]\nevaluation = \"full\"\n");
    let (a, b) = (run(&routed, Path::new(".")), run(&full, Path::new(".")));
    for file in ["best_path.csv", "history.csv", "population.csv"] {
        assert_eq!(read(a.path(), file), read(b.path(), file), "{file}");
    }
}

#[test]
fn routed_moves_reach_past_the_start_room_without_sweeping_walls() {
    // The office floor plan from its corner room, a short run: straight moves that leave the
    // room sweep walls and are penalised, routed ones go through the doors.
    let text = "seed = 2\nplanner = \"thesis\"\n[map]\nsource = \"office\"\n[stations]\nstart = [2.0, 2.0]\n\
                [thesis]\npop_min = 40\ninit_actions = 60\ninit_dist_max = 6.0\n[budget]\nevaluations = 4000\n";
    let straight = summary(run(text, Path::new(".")).path());
    let routed = summary(run(&text.replace("[thesis]\n", "[thesis]\nmoves = \"routed\"\n"), Path::new(".")).path());
    let cov = |s: &serde_json::Value| s["score"]["cov_final_reach"].as_f64().unwrap();
    // Routes keep the swept rectangles off the walls (003's constraint); their line-of-sight
    // test does not yet keep the robot's body clear at a route's corners, so the body rule of
    // `executable` can still find contacts there.
    assert_eq!(routed["score"]["obstacle_sweeps"], 0, "{routed}");
    assert!(cov(&routed) > 2.0 * cov(&straight), "routed {} vs straight {}", cov(&routed), cov(&straight));
}

#[test]
fn routed_moves_are_refused_for_fleets() {
    let fleet = format!(
        "{}[[robots]]\nname = \"a\"\n[[robots]]\nname = \"b\"\nstart = [9.7, 1.3]\n",
        THESIS_2.replace("[thesis]\n", "[thesis]\nmoves = \"routed\"\n")
    );
    let e = match ExperimentFile::parse(&fleet, "test").and_then(|f| f.validate("test", Path::new("."), "t")) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("thesis.moves") && e.contains("fleet"), "{e}");
}
