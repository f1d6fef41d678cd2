//! The floor plans of `experiments/maps/generated/` (the cell-order study's generated maps,
//! laid out by `scripts/cell-order-grid.py`) are what `covga maps generate` makes from their
//! names: each committed file is re-made byte for byte, so the study's maps carry no hand
//! edits and anyone can make more of the family.

use std::path::PathBuf;

#[test]
fn every_committed_generated_map_is_remade_byte_for_byte() {
    let committed = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("experiments/maps/generated");
    let dir = tempfile::tempdir().unwrap();
    let mut names: Vec<String> = std::fs::read_dir(&committed)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter_map(|n| n.strip_suffix(".yaml").map(str::to_string))
        .collect();
    names.sort();
    assert_eq!(names.len(), 20, "{names:?}");
    for name in &names {
        // `<kind>-<seed>[-noisy]`
        let noisy = name.ends_with("-noisy");
        let base = name.trim_end_matches("-noisy");
        let (kind, seed) = base.rsplit_once('-').unwrap();
        let mut args = vec!["maps", "generate", "--kind", kind, "--seed", seed, "--out"];
        let out = dir.path().to_str().unwrap();
        args.push(out);
        if noisy {
            args.push("--noisy");
        }
        let o = crate::common::command().args(&args).output().unwrap();
        assert!(o.status.success(), "{name}: {o:?}");
        for ext in ["yaml", "pgm"] {
            let file = format!("{name}.{ext}");
            let made = std::fs::read(dir.path().join(&file)).unwrap();
            assert!(
                made == std::fs::read(committed.join(&file)).unwrap(),
                "{file} differs from what the command makes"
            );
        }
    }
}
