//! The book's reference pages are what the program writes: `covga reference keys` (every key,
//! its type, default and checked range, from the configuration types) and `covga reference
//! commands` (every command's help) and `covga reference outputs` (every output file and
//! `runs.csv` column). A default, a range, a doc comment or a flag changed
//! without the page re-made fails here.

use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn the_reference_pages_are_what_the_program_writes() {
    for (page, file) in [
        ("keys", "docs/src/reference/keys.md"),
        ("commands", "docs/src/reference/commands.md"),
        ("outputs", "docs/src/reference/outputs.md"),
    ] {
        let o = crate::common::covga_in(root(), &["reference", page]);
        assert!(o.status.success(), "covga reference {page}: {}", String::from_utf8_lossy(&o.stderr));
        let written = String::from_utf8(o.stdout).expect("UTF-8");
        let committed = std::fs::read_to_string(root().join(file)).unwrap_or_default();
        assert!(
            written == committed,
            "{file} is not what `covga reference {page}` writes: re-make it with \
             `cargo run --release -- reference {page} > {file}`"
        );
    }
}
