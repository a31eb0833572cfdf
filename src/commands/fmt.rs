//! `xglyph fmt` (not yet implemented).

use std::process::ExitCode;

use super::CommandError;

#[derive(Debug, clap::Args)]
pub struct FmtArgs {}

pub fn run(_args: FmtArgs) -> Result<ExitCode, CommandError> {
    Err("`xglyph fmt` is not implemented yet".into())
}
