//! `xglyph check` (not yet implemented).

use std::process::ExitCode;

use super::CommandError;

#[derive(Debug, clap::Args)]
pub struct CheckArgs {}

pub fn run(_args: CheckArgs) -> Result<ExitCode, CommandError> {
    Err("`xglyph check` is not implemented yet".into())
}
