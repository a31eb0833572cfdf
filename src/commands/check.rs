//! `xglyph check`: load and validate a font directory, printing every diagnostic.

use std::path::PathBuf;
use std::process::ExitCode;

use super::CommandError;
use crate::source::{load_font, Diagnostic, Severity};

#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// Font directory to check.
    #[arg(default_value = "glyphs")]
    pub font_dir: PathBuf,
}

/// Print one diagnostic with its source line and a caret under the column.
fn print(d: &Diagnostic) {
    println!("{d}");
    if let Ok(text) = std::fs::read_to_string(&d.path) {
        if let Some(line) = text.lines().nth(d.line.saturating_sub(1)) {
            println!("  | {line}");
            println!("  | {}^", " ".repeat(d.col.saturating_sub(1)));
        }
    }
}

pub fn run(args: CheckArgs) -> Result<ExitCode, CommandError> {
    let diags = match load_font(&args.font_dir) {
        Ok((_, warnings)) => warnings,
        Err(diags) => diags,
    };
    for d in &diags {
        print(d);
    }
    let errors = diags
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .count();
    let warnings = diags.len() - errors;
    println!("{errors} errors, {warnings} warnings");
    Ok(if errors > 0 {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}
