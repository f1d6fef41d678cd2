//! Replays the fuzzing corpus (`fuzz/corpus/<target>/`, minimised inputs that libFuzzer found
//! to reach new code, and `fuzz/regressions/<target>/`, inputs that once crashed, hung or
//! allocated without bound) through the same entry points the fuzz targets call: a stable
//! `cargo test` keeps every finding fixed without the nightly toolchain.

use std::path::Path;
use std::time::{Duration, Instant};

#[test]
fn every_corpus_input_loads_or_fails_cleanly() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz");
    let mut replayed = 0;
    for (target, entry) in covga::fuzz_entry::TARGETS {
        let mut inputs = 0;
        for folder in ["corpus", "regressions"] {
            let Ok(dir) = std::fs::read_dir(root.join(folder).join(target)) else { continue };
            let mut files: Vec<_> = dir.flatten().map(|e| e.path()).filter(|p| p.is_file()).collect();
            files.sort();
            for file in files {
                let data = std::fs::read(&file).unwrap();
                let started = Instant::now();
                // A panic fails the test and names the input through the panic message below.
                let outcome = std::panic::catch_unwind(|| entry(&data));
                assert!(outcome.is_ok(), "{target} panicked on {}", file.display());
                // A hang, not a big input: the corpus holds the shipped 27 216-run grid, whose
                // expansion takes a few seconds.
                assert!(
                    started.elapsed() < Duration::from_secs(20),
                    "{target} took {:?} on {}",
                    started.elapsed(),
                    file.display()
                );
                inputs += 1;
            }
        }
        assert!(inputs > 0, "no corpus for {target}");
        replayed += inputs;
    }
    eprintln!("replayed {replayed} fuzz inputs");
}
