//! `xglyph svg`: the SVG glyph set and the SVG font only.

use std::path::PathBuf;
use std::process::ExitCode;

use super::build::{load, svg_outputs, write_outputs};
use super::CommandError;

#[derive(Debug, clap::Args)]
#[command(after_help = "\
Writes into OUT:
  <Family>-<Style>.svg   SVG 1.1 font: y-up, absolute M L C Z, <hkern> from kerning
  svg/<glyph>.svg        one standalone SVG per glyph, y down, viewBox = advance x em

Examples:
  xglyph svg                      # glyphs/ -> out/
  xglyph svg my-font -o icons --tolerance 0.25")]
pub struct SvgArgs {
    /// Font directory (font.toml and one TOML file per glyph).
    #[arg(default_value = "glyphs")]
    pub font_dir: PathBuf,
    /// Output directory (created if needed).
    #[arg(short, long, default_value = "out")]
    pub out: PathBuf,
    /// Fitting tolerance in font units; overrides `tolerance` in font.toml.
    #[arg(long, value_name = "T")]
    pub tolerance: Option<f64>,
}

pub fn run(args: SvgArgs) -> Result<ExitCode, CommandError> {
    let loaded = load(&args.font_dir, args.tolerance)?;
    let files = svg_outputs(&loaded.font, &loaded.outlines);
    write_outputs(&args.out, &files)?;
    println!(
        "wrote {} files to {} (SVG font and {} glyph SVGs)",
        files.len(),
        args.out.display(),
        files.len() - 1
    );
    Ok(ExitCode::SUCCESS)
}
