//! `xglyph svg` (not yet implemented).

use std::process::ExitCode;

use super::CommandError;

#[derive(Debug, clap::Args)]
pub struct SvgArgs {}

pub fn run(_args: SvgArgs) -> Result<ExitCode, CommandError> {
    Err("`xglyph svg` is not implemented yet".into())
}
