//! `xglyph render` (not yet implemented).

use std::process::ExitCode;

use super::CommandError;

#[derive(Debug, clap::Args)]
pub struct RenderArgs {}

pub fn run(_args: RenderArgs) -> Result<ExitCode, CommandError> {
    Err("`xglyph render` is not implemented yet".into())
}
