//! The report's figures, one module per kind: each a type behind [`crate::plot::Figure`] drawn
//! from the numbers it is given, knowing nothing of a study folder (the sections and the
//! replication read the study and fill them in). What every figure shares, the legend strip
//! below the panels, the series' colours and the panel grids, is [`panels`]; the drawing
//! primitives under them are [`crate::plot`]'s.

pub mod boxes;
pub mod convergence;
pub mod curves;
pub mod diversity;
pub mod forest;
pub mod panels;
pub mod pareto;
pub mod paths;
pub mod planners_pareto;

#[cfg(test)]
mod layout_tests;
