//! `xglyph svg`: the SVG glyph set and the SVG font only.

use std::process::ExitCode;

use super::build::load;
use super::{CommandError, FontArgs};
use crate::instance::{parse_location, style_at};
use crate::pipeline::{instance, svg_outputs, write_output_files};
use crate::terminal::outln;

#[derive(Debug, clap::Args)]
#[command(after_help = "\
Writes into OUT:
  <Family>-<Style>.svg   SVG 1.1 font: y-up, absolute M L C Z, <hkern> from kerning
  svg/<glyph>.svg        one standalone SVG per glyph, y down, viewBox = advance x em

Examples:
  xglyph svg                      # glyphs/ -> out/
  xglyph svg my-font -o icons --tolerance 0.25
  xglyph svg --at wght=650        # a font with masters, at weight 650")]
pub struct SvgArgs {
    #[command(flatten)]
    pub font: FontArgs,
    /// Write the font at this position of its design space (a font with masters), user
    /// coordinates: TAG=VALUE, several separated by commas, e.g. `wght=650`.
    #[arg(long, value_name = "TAG=VALUE")]
    pub at: Option<String>,
}

/// Runs `xglyph svg`.
pub fn run(args: SvgArgs) -> Result<ExitCode, CommandError> {
    // Ctrl-C leaves OUT as it was (a handler already set only means plain SIGINT).
    let _ = crate::write::exit_on_interrupt();
    let loaded = load(&args.font.font_dir, args.font.tolerance)?;
    let at_font = match &args.at {
        Some(at) => {
            let location = parse_location(&loaded.family.designspace, at)?;
            let style = style_at(&loaded.family.designspace, &location);
            Some(instance(&loaded, &location, Some(&style))?)
        }
        None => None,
    };
    let files = svg_outputs(at_font.as_ref().unwrap_or(&loaded.font));
    let count = files.len();
    super::build::show_phase(&format!("writing {count} files"), || {
        write_output_files(&args.font.out, files)
    })?;
    outln!(
        "wrote {count} files to {} (SVG font and {} glyph SVGs)",
        args.font.out.display(),
        count - 1
    );
    Ok(ExitCode::SUCCESS)
}
