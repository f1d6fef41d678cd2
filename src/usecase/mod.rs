//! The use cases of covga as library functions, under the command line and the Python
//! bindings alike: a front end parses its arguments into a request, calls one function here and
//! prints or converts what comes back. The checks and the files written are the same whichever
//! front end asks.
//!
//! - [`eval`]: score a pattern, a path file or a fleet's area division on a map, and write
//!   `metrics.json`, `path.csv` and the path figure;
//! - [`run`]: read, validate and run one experiment into a results folder that holds no other
//!   run's files, leaving nothing behind when it is refused or interrupted;
//! - [`migrate`]: rewrite experiment and grid files to the current key names;
//! - [`init`]: write the recommended experiment file for a floor plan, validated first.
//!
//! Grid studies ([`crate::study::runner::run_study`]) and reports
//! ([`crate::report::write_report`]) are library functions of their own layers already.

pub mod eval;
pub mod eval_memory;
pub mod init;
pub mod migrate;
pub mod run;

/// Why a use case did not complete: the user's input (exit code 2, `ValueError` in Python) or
/// an internal failure (exit code 1).
#[derive(Debug, thiserror::Error)]
pub enum UseCaseError {
    /// The request is wrong; the message names the file, key or flag and what is allowed.
    #[error("{0}")]
    Input(String),
    /// Something failed that is not the user's input (a file could not be written, …).
    #[error("{0}")]
    Internal(String),
    /// The run was interrupted (Ctrl-C, Python's KeyboardInterrupt); it wrote nothing.
    #[error("{0}")]
    Interrupted(String),
}

impl UseCaseError {
    /// Wraps any displayable error as bad input.
    pub fn input(e: impl std::fmt::Display) -> Self {
        UseCaseError::Input(e.to_string())
    }
    /// Wraps any displayable error as an internal failure.
    pub fn internal(e: impl std::fmt::Display) -> Self {
        UseCaseError::Internal(e.to_string())
    }
}
