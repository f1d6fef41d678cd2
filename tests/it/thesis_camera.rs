//! `thesis.objective = "camera"` refused where it does not apply, at its key.

use covga::experiment::file::ExperimentFile;

/// The camera objective is for one robot's GA on a fixed map: with `[retrain]`, with a
/// fleet or with an `α_cov` outside [0, 1] the file is refused at the key.
#[test]
fn the_camera_objective_is_refused_where_it_does_not_apply() {
    let base = "planner = \"thesis\"\n[map]\nsource = \"thesis-1\"\n[thesis]\nobjective = \"camera\"\n";
    let check = |extra: &str, key: &str| {
        let text = format!("{base}{extra}");
        let file = ExperimentFile::parse(&text, "t.toml").unwrap();
        let Err(e) = file.validate("t.toml", std::path::Path::new("."), "t") else { panic!("{text} is accepted") };
        assert_eq!(e.key, key, "{text}: {}", e.message);
    };
    check(
        "[retrain]\nat_iteration = 5\nregion = [0.0, 0.0, 1.0, 1.0]\n[budget]\niterations = 10\n",
        "thesis.objective",
    );
    check("[[robots]]\nname = \"a\"\n[[robots]]\nname = \"b\"\nstart = [2.0, 2.0]\n", "thesis.objective");
    check("[waypoint]\nalpha_cov = 1.5\n", "waypoint.alpha_cov");
    let fine = ExperimentFile::parse(base, "t.toml").unwrap();
    assert!(fine.validate("t.toml", std::path::Path::new("."), "t").is_ok());
}
