//! `xglyph build` (not yet implemented).

use std::process::ExitCode;

use super::CommandError;

#[derive(Debug, clap::Args)]
pub struct BuildArgs {}

pub fn run(_args: BuildArgs) -> Result<ExitCode, CommandError> {
    Err("`xglyph build` is not implemented yet".into())
}
