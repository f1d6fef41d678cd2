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
    /// The file (a link's target).
    pub path: PathBuf,
    /// Its text with every old key under its new name.
    pub text: String,
    /// The keys moved, old → new (none: the file is current).
    pub moves: Moves,
}

/// The migration of the experiment or grid file at `path` (a grid has `base` and `axes` or
/// `seeds`), checked to mean what the file meant; for a grid whose `base` names a file, that
/// file's migration after it. A symbolic link is followed: its target is what is migrated.
pub fn migrate_file(path: &Path) -> Result<Vec<Migration>, UseCaseError> {
    let origin = path.display().to_string();
    let target = std::fs::canonicalize(path).map_err(|e| UseCaseError::Input(format!("{origin}: cannot read: {e}")))?;
    let text = crate::io::read_text_bounded(&target, crate::io::MAX_TEXT_FILE_BYTES)
        .map_err(|e| UseCaseError::Input(format!("{origin}: cannot read: {e}")))?;
    let (migrated, moves) = migrate_text(&text, &origin).map_err(UseCaseError::input)?;
    if !moves.is_empty() {
        same_meaning(&text, &migrated, path)?;
    }
    let mut out = vec![Migration { path: target, text: migrated, moves }];
    // A grid may take its base from another file: the grid is current only when that file is.
    let table: Option<toml::Table> = text.parse().ok();
    if let Some(base) = table.as_ref().and_then(|t| t.get("base")).and_then(toml::Value::as_str) {
        let base_path = path.parent().unwrap_or(Path::new(".")).join(base);
        out.extend(migrate_file(&base_path)?);
    }
    Ok(out)
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

/// Writes every migration that moved a key, each file replaced at once with the permissions
/// it had; a file that may not be written (read-only) is refused before any is written.
pub fn write(migrations: &[Migration]) -> Result<(), UseCaseError> {
    let stale: Vec<&Migration> = migrations.iter().filter(|m| !m.moves.is_empty()).collect();
    let mut modes = Vec::with_capacity(stale.len());
    for m in &stale {
        let meta = std::fs::metadata(&m.path)
            .map_err(|e| UseCaseError::Input(format!("{}: cannot read: {e}", m.path.display())))?;
        if meta.permissions().readonly() {
            return Err(UseCaseError::Input(format!(
                "{}: the file is read-only; make it writable to migrate it (nothing was written)",
                m.path.display()
            )));
        }
        modes.push(meta.permissions());
    }
    for (m, mode) in stale.into_iter().zip(modes) {
        crate::io::write_atomic_with(&m.path, m.text.as_bytes(), Some(mode))
            .map_err(|e| UseCaseError::Input(format!("{}: cannot write: {e}", m.path.display())))?;
    }
    Ok(())
}
