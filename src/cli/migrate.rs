//! `covga migrate`: experiment and grid files rewritten to the current key names.

use super::CliError;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `covga migrate`.
#[derive(Args, Debug)]
pub struct MigrateArgs {
    /// Experiment or grid files (TOML) to rewrite in place
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Write nothing; exit 1 when a file still uses an old key name
    #[arg(long)]
    check: bool,
}

/// Runs `covga migrate`: every file is read and migrated first, and written only when all of
/// them migrate.
pub fn run(a: MigrateArgs) -> Result<(), CliError> {
    let mut migrations: Vec<crate::usecase::migrate::Migration> = Vec::new();
    for f in &a.files {
        for m in crate::usecase::migrate::migrate_file(f).map_err(CliError::from)? {
            // A base file shared by several grids (or a link and its target) is migrated once.
            if !migrations.iter().any(|seen| seen.path == m.path) {
                migrations.push(m);
            }
        }
    }
    for m in &migrations {
        if m.moves.is_empty() {
            println!("{}: current", m.path.display());
        }
        for (old, new) in &m.moves {
            println!("{}: `{old}` -> `{new}`", m.path.display());
        }
    }
    let stale = migrations.iter().filter(|m| !m.moves.is_empty()).count();
    if a.check {
        return if stale == 0 {
            Ok(())
        } else {
            Err(CliError::Internal(format!("{stale} of {} files use old key names", migrations.len())))
        };
    }
    crate::usecase::migrate::write(&migrations).map_err(CliError::from)
}
