//! `covga gtsp`: write the tour problem of a cell-order experiment as a GTSPLIB instance, for
//! checking covga's searches with an established GTSP solver.

use super::CliError;
use crate::cell_order::config::CellOrderConfig;
use crate::usecase::run::{ExperimentText, prepare};
use std::path::{Path, PathBuf};

/// Arguments of `covga gtsp`.
#[derive(clap::Args, Debug)]
pub struct GtspArgs {
    /// A `planner = "cell_order"` experiment file (TOML).
    file: PathBuf,
    /// Where to write the instance: GTSPLIB `TYPE : AGTSP`, a full matrix of weights in
    /// milliseconds (leg plus the entered sweep's own time), one set per cell, node 1 the
    /// stations. A tour's weight is its mission time (a coverage goal is not part of it).
    #[arg(long)]
    out: PathBuf,
    /// Where to write what each node is (CSV: node, cell, choice, direction_deg, entry, as
    /// `summary.json`'s `tour` names a sweep).
    #[arg(long)]
    nodes: Option<PathBuf>,
}

/// Runs `covga gtsp` with its parsed arguments.
pub fn run(a: GtspArgs) -> Result<(), CliError> {
    if let Some(nodes) = &a.nodes
        && same_file(&a.out, nodes)
    {
        return Err(CliError::Input(format!(
            "--out {} and --nodes {} name the same file: the nodes would overwrite the instance; give two files",
            a.out.display(),
            nodes.display()
        )));
    }
    let source = ExperimentText::read(&a.file)?;
    let prepared = prepare(&source, None, None)?;
    let exp = &prepared.experiment;
    let Some(config) = exp.planner.downcast_ref::<CellOrderConfig>() else {
        return Err(CliError::Input(format!(
            "{}: covga gtsp writes the tour problem of planner = \"cell_order\"; this file's planner is `{}`",
            prepared.origin,
            exp.file.planner.name()
        )));
    };
    let name = format!("{}-{}", source.stem, exp.scenario.map.name());
    let (instance, nodes) =
        config.gtsplib(&exp.scenario, &name).map_err(|m| CliError::Input(format!("{}: {m}", prepared.origin)))?;
    let write = |path: &PathBuf, text: &str| {
        crate::io::write_atomic(path, text.as_bytes())
            .map_err(|e| CliError::Internal(format!("cannot write {}: {e}", path.display())))
    };
    write(&a.out, &instance)?;
    if let Some(path) = &a.nodes {
        write(path, &nodes)?;
    }
    Ok(())
}

/// Whether `a` and `b` name one file: the same path once made absolute, or, where both exist,
/// the same file (through links or `..`).
fn same_file(a: &Path, b: &Path) -> bool {
    let absolute = |p: &Path| std::path::absolute(p).ok();
    let canonical = |p: &Path| std::fs::canonicalize(p).ok();
    absolute(a).is_some_and(|x| Some(x) == absolute(b)) || canonical(a).is_some_and(|x| Some(x) == canonical(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_file_under_two_spellings_is_the_same() {
        assert!(same_file(Path::new("x.gtsp"), Path::new("./x.gtsp")));
        assert!(!same_file(Path::new("x.gtsp"), Path::new("x.csv")));
    }
}
