//! Migrating experiment and grid files to the current key names (keys that moved section,
//! [`crate::experiment::renamed`]): each file rewritten with its comments and layout, checked to
//! mean what it meant (the same experiment; for a grid the same runs, ids and columns), and
//! written only when every file given migrates, each at once (no file half written).

use super::UseCaseError;
use crate::experiment::file::ExperimentFile;
use crate::experiment::renamed::{Moves, migrate_text};
use std::path::{Path, PathBuf};

/// One file's migration.
#[derive(Clone, Debug)]
pub struct Migration {
    /// The file.
    pub path: PathBuf,
    /// Its text with every old key under its new name.
    pub text: String,
    /// The keys moved, old → new (none: the file is current).
    pub moves: Moves,
}

/// The migration of the experiment or grid file at `path` (a grid has `base` and `axes` or
/// `seeds`), checked to mean what the file meant.
pub fn migrate_file(path: &Path) -> Result<Migration, UseCaseError> {
    let origin = path.display().to_string();
    let text = crate::io::read_text_bounded(path, crate::io::MAX_TEXT_FILE_BYTES)
        .map_err(|e| UseCaseError::Input(format!("{origin}: cannot read: {e}")))?;
    let (migrated, moves) = migrate_text(&text, &origin).map_err(UseCaseError::input)?;
    if !moves.is_empty() {
        same_meaning(&text, &migrated, path)?;
    }
    Ok(Migration { path: path.to_path_buf(), text: migrated, moves })
}

/// Refuses a migration whose text would not mean what the file meant.
fn same_meaning(old: &str, new: &str, path: &Path) -> Result<(), UseCaseError> {
    let origin = path.display().to_string();
    let table: toml::Table = old.parse().map_err(UseCaseError::input)?;
    let same = if table.contains_key("base") {
        let (a, b) = (
            crate::study::grid::Study::parse(old, path).map_err(UseCaseError::input)?,
            crate::study::grid::Study::parse(new, path).map_err(UseCaseError::input)?,
        );
        let ids = |s: &crate::study::grid::Study| s.runs.iter().map(|r| r.id.clone()).collect::<Vec<_>>();
        a.columns == b.columns && ids(&a) == ids(&b)
    } else {
        ExperimentFile::parse(old, &origin).map_err(UseCaseError::input)?
            == ExperimentFile::parse(new, &origin).map_err(UseCaseError::input)?
    };
    if same {
        Ok(())
    } else {
        Err(UseCaseError::Internal(format!("{origin}: the migrated file would mean something else; nothing written")))
    }
}

/// Writes every migration that moved a key, each file replaced at once.
pub fn write(migrations: &[Migration]) -> Result<(), UseCaseError> {
    for m in migrations.iter().filter(|m| !m.moves.is_empty()) {
        crate::io::write_atomic(&m.path, m.text.as_bytes())
            .map_err(|e| UseCaseError::Internal(format!("{}: cannot write: {e}", m.path.display())))?;
    }
    Ok(())
}
