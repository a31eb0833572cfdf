//! `xglyph import` (not yet implemented).

use std::process::ExitCode;

use super::CommandError;

#[derive(Debug, clap::Args)]
pub struct ImportArgs {}

pub fn run(_args: ImportArgs) -> Result<ExitCode, CommandError> {
    Err("`xglyph import` is not implemented yet".into())
}
