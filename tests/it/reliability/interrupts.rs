//! Every planner's work stops on an interrupt, set-up included: a cell decomposition's
//! transit routes, the waypoint planner's waypoints and views, the thesis GA's initial population, a fleet's
//! negotiation rounds and a GA's generations. Each run gets SIGINT while that phase is under way (it would go on for
//! seconds) and must end, with exit code 130 and nothing written, well within a second.

use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

/// How long after the signal a run may take to end: the phases check every few milliseconds
/// (26 ms measured for the pillar hall's transit); the rest is slack for a loaded machine.
const STOP_WITHIN: Duration = Duration::from_millis(700);

/// Runs `covga run e.toml` in `dir`, sends SIGINT after `after`, and checks how it ended.
#[cfg(unix)]
fn interrupted(dir: &Path, experiment: &str, after: Duration, what: &str) {
    std::fs::write(dir.join("e.toml"), experiment).unwrap();
    let out = dir.join(format!("out-{}", what.replace(' ', "-")));
    let child = crate::common::command()
        .current_dir(dir)
        .args(["run", "e.toml", "--quiet", "--out"])
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(after);
    let signalled = Instant::now();
    // SAFETY: a signal to the child this test started.
    assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) }, 0);
    let o = child.wait_with_output().unwrap();
    let took = signalled.elapsed();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(130), "{what}: {err}");
    assert!(err.contains("interrupted"), "{what}: {err}");
    assert!(took < STOP_WITHIN, "{what}: ended {took:?} after the signal");
    assert!(!out.exists(), "{what}: nothing is left");
}

#[cfg(unix)]
#[test]
fn every_planner_stops_on_an_interrupt_in_set_up_and_in_its_loop() {
    let dir = tempfile::tempdir().unwrap();
    super::pillar_hall(dir.path());
    let basement = concat!(env!("CARGO_MANIFEST_DIR"), "/experiments/maps/basement.yaml");
    let cases = [
        (
            format!("planner = \"cell_order\"\n{}[budget]\nevaluations = 1\n", super::HALL),
            800,
            "cell_order preparation",
        ),
        (
            format!(
                "planner = \"waypoint\"\n[map]\nsource = \"{basement}\"\n[stations]\nstart = [0.0, 0.0]\n[waypoint]\ngenerations = 1\n[scorer.camera]\nscale = 0.02\n"
            ),
            1500,
            "waypoint views",
        ),
        (
            format!(
                "planner = \"waypoint\"\n[map]\nsource = \"{basement}\"\n[stations]\nstart = [0.0, 0.0]\n[waypoint]\ngenerations = 1\n[scorer.camera]\nscale = 0.02\n"
            ),
            250,
            "waypoint placement",
        ),
        (
            "seed = 3\n[map]\nsource = \"thesis-1\"\n[thesis]\npop_min = 400\ninit_actions = 20\n[budget]\niterations = 10000000\n[fleet]\ntolerance = 0\n[[robots]]\nname = \"a\"\nstart = [1.3, 1.3]\n[[robots]]\nname = \"b\"\nstart = [9.5, 9.5]\n".to_string(),
            800,
            "fleet negotiation",
        ),
        (
            // The camera objective's initial population: about 7 s of evaluation on 2 cores.
            "seed = 3\n[map]\nsource = \"thesis-1\"\n[thesis]\nselection = \"tournament\"\nobjective = \"camera\"\ninit_individuals = 2000\ninit_actions = 1000\nmax_genome_len = 2000\n[budget]\niterations = 1\n".to_string(),
            1500,
            "thesis initial population",
        ),
        (
            "planner = \"cell_order\"\n[map]\nsource = \"thesis-1\"\n[budget]\niterations = 10000000\n".to_string(),
            800,
            "cell_order generations",
        ),
        (
            "planner = \"waypoint\"\n[map]\nsource = \"thesis-1\"\n[waypoint]\ngenerations = 10000000\n[budget]\niterations = 10000000\n".to_string(),
            800,
            "waypoint generations",
        ),
        (
            "planner = \"random_search\"\n[map]\nsource = \"thesis-1\"\n[budget]\nevaluations = 100000000\niterations = 10000000\n".to_string(),
            800,
            "random search batches",
        ),
    ];
    for (experiment, after_ms, what) in cases {
        interrupted(dir.path(), &experiment, Duration::from_millis(after_ms), what);
    }
}
