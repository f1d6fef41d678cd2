//! `covga reference`: the book's reference pages as the program writes them: every key of an
//! experiment file (`keys`), every command with its flags (`commands`) and every output file
//! and column (`outputs`), in Markdown.

use super::CliError;
use clap::{Args, CommandFactory, ValueEnum};

/// Arguments of `covga reference`.
#[derive(Args, Debug)]
pub struct ReferenceArgs {
    /// Which page: `keys` (docs/src/reference/keys.md), `commands`
    /// (docs/src/reference/commands.md) or `outputs` (docs/src/reference/outputs.md)
    page: Page,
}

/// A reference page of the book.
#[derive(Clone, Copy, Debug, ValueEnum)]
enum Page {
    /// Every key of every section of an experiment file.
    Keys,
    /// Every command and flag.
    Commands,
    /// Every output file and `runs.csv` column.
    Outputs,
}

/// Runs `covga reference`: the page on standard output.
/// A page that cannot be written (standard output closed or full) is an error, not a panic.
pub fn run(a: ReferenceArgs) -> Result<(), CliError> {
    use std::io::Write;
    let page = match a.page {
        Page::Keys => crate::experiment::keys::markdown(),
        Page::Commands => commands_markdown(),
        Page::Outputs => crate::study::outputs::markdown(),
    };
    let mut out = std::io::stdout().lock();
    out.write_all(page.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| CliError::Internal(format!("cannot write the page to standard output: {e}")))
}

/// Every command's long help, as `covga COMMAND --help` prints it.
fn commands_markdown() -> String {
    let mut root = super::Cli::command().bin_name("covga");
    root.build();
    let mut md = String::from(
        "# Commands and flags\n\n\
         Every command of `covga` with its flags, as `covga COMMAND --help` prints them. This page is\n\
         written by `covga reference commands`; `tests/it/reference.rs` requires it to equal what the\n\
         program writes.\n",
    );
    let mut stack = vec![root];
    let mut pages = Vec::new();
    while let Some(mut command) = stack.pop() {
        let name = command.get_bin_name().unwrap_or("covga").to_string();
        let help = command.render_long_help().to_string();
        pages.push((name, help));
        let mut children: Vec<clap::Command> = command.get_subcommands().cloned().collect();
        children.reverse();
        stack.extend(children.into_iter().filter(|c| c.get_name() != "help"));
    }
    for (name, help) in pages {
        md.push_str(&format!("\n## `{name}`\n\n```text\n{}\n```\n", help.trim_end()));
    }
    md
}
