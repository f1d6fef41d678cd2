//! The `covga` binary: a thin wrapper over [`covga::cli`].

use std::process::ExitCode;

fn main() -> ExitCode {
    match covga::cli::run(std::env::args_os()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}
