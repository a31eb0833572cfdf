//! `xglyph svg`: the SVG glyph set and the SVG font only.

use std::process::ExitCode;

use super::build::load;
use super::{CommandError, FontArgs};
use crate::pipeline::{svg_outputs, write_outputs};
use crate::terminal::outln;

#[derive(Debug, clap::Args)]
#[command(after_help = "\
Writes into OUT:
  <Family>-<Style>.svg   SVG 1.1 font: y-up, absolute M L C Z, <hkern> from kerning
  svg/<glyph>.svg        one standalone SVG per glyph, y down, viewBox = advance x em

Examples:
  xglyph svg                      # glyphs/ -> out/
  xglyph svg my-font -o icons --tolerance 0.25")]
pub struct SvgArgs {
    #[command(flatten)]
    pub font: FontArgs,
}

/// Runs `xglyph svg`.
pub fn run(args: SvgArgs) -> Result<ExitCode, CommandError> {
    let loaded = load(&args.font.font_dir, args.font.tolerance)?;
    let files = svg_outputs(&loaded.font);
    write_outputs(&args.font.out, &files)?;
    outln!(
        "wrote {} files to {} (SVG font and {} glyph SVGs)",
        files.len(),
        args.font.out.display(),
        files.len() - 1
    );
    Ok(ExitCode::SUCCESS)
}
