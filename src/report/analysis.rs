//! The study as a report reads it, and what every part of a report computes from it: the runs
//! table checked once and filtered (`study::Loaded`), the groups, fronts, best runs and
//! configurations the sections share (`study::Study`), the values' checks ([`values`]), how
//! the swept parameters relate ([`design`]), the best plan of a set ([`best`]), the run folders'
//! records ([`folder_record`]), the lower bound on the times to coverage (`bound`) and a
//! report file made but not yet written ([`rendered`]). The room at the bottom of the report:
//! the tables, the comparisons, the replication and the sections read from here, and nothing
//! here reads from them.

pub mod best;
pub mod bound;
pub mod design;
pub mod folder_record;
pub mod level;
pub mod rendered;
pub mod runs;
pub(crate) mod study;
pub mod values;

/// Report failures.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// Bad input (no runs, unknown column).
    #[error("{0}")]
    Input(String),
    /// A file could not be read or written.
    #[error("{0}")]
    Io(String),
    /// A figure failed.
    #[error(transparent)]
    Plot(#[from] crate::plot::PlotError),
}
