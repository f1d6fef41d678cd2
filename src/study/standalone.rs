//! The grid file a study folder keeps (`grid.toml`), standing on its own: a grid whose `base`
//! names an experiment file beside it would, copied into the study folder, resolve that path
//! against the study folder, where the file is not, and every later reader of the copy (the
//! report's lower bound, its check of the runs against the grid) would fail. The copy holds the
//! base file's table in its place instead.

use super::grid::Study;
use std::path::Path;

/// The text `covga grid` writes as the study folder's `grid.toml`: the grid as run, with a
/// `base` that names a file replaced by that file's table (read beside the grid, as the grid
/// read it). A grid with an inline base is written as it is.
pub fn grid_text(study: &Study) -> String {
    inlined(&study.text, &study.path).unwrap_or_else(|| study.text.clone())
}

/// `text` (a grid file at `path`) with its base file inlined; `None` where its base is inline
/// already (or the text cannot be read back, which a loaded grid rules out).
fn inlined(text: &str, path: &Path) -> Option<String> {
    let mut grid: toml::Table = toml::from_str(text).ok()?;
    let file = grid.get("base")?.as_str()?.to_string();
    let full = path.parent().unwrap_or(Path::new(".")).join(&file);
    let body = crate::io::read_text_bounded(&full, crate::io::MAX_TEXT_FILE_BYTES).ok()?;
    let base: toml::Table = toml::from_str(&body).ok()?;
    grid.insert("base".into(), toml::Value::Table(base));
    let written = toml::to_string(&grid).ok()?;
    Some(format!(
        "# The grid file as run ({}), its base ({file}) inlined so that this copy stands on its own.\n{written}",
        path.display()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_base_file_is_inlined_and_the_copy_expands_to_the_same_runs() {
        let dir = tempfile::tempdir().unwrap();
        let base = "planner = \"boustrophedon\"\n[map]\nsource = \"office\"\n[stations]\nstart = [2.0, 2.0]\n";
        std::fs::write(dir.path().join("house.toml"), base).unwrap();
        let grid = "base = \"house.toml\"\nseeds = 1\n[axes]\n\"planner\" = [\"boustrophedon\", \"spiral\"]\n";
        let path = dir.path().join("grid.toml");
        std::fs::write(&path, grid).unwrap();
        let study = Study::load(&path).unwrap();
        let copy_dir = tempfile::tempdir().unwrap();
        let copy = copy_dir.path().join("grid.toml");
        std::fs::write(&copy, grid_text(&study)).unwrap();
        let again = Study::load(&copy).expect("the copy reads without the base file beside it");
        let ids = |s: &Study| s.runs.iter().map(|r| r.id.clone()).collect::<Vec<_>>();
        assert_eq!(ids(&again), ids(&study), "the same runs");
        let inline = "seeds = 1\n[base]\nplanner = \"spiral\"\n[base.map]\nsource = \"office\"\n";
        std::fs::write(&path, inline).unwrap();
        assert_eq!(grid_text(&Study::load(&path).unwrap()), inline, "an inline base is written as it is");
    }
}
