//! `xglyph svg`: the SVG glyph set and the SVG font only.

use std::process::ExitCode;

use super::build::load_stored;
use super::{CommandError, FontArgs};
use crate::instance::{parse_location, style_at};
use crate::outline::OutlineOptions;
use crate::pipeline::{instance_with, svg_outputs};
use crate::terminal::outln;

#[derive(Debug, clap::Args)]
#[command(after_help = "\
Writes into OUT:
  <Family>-<Style>.svg   SVG 1.1 font: y-up, absolute M L C Z, <hkern> from kerning
  svg/<glyph>.svg        one standalone SVG per glyph, y down, viewBox = advance x em
  .xglyph-cache, .xglyph-sources
                         the fits and the parsed glyph files, for the next run (shared
                         with `xglyph build` into the same OUT)

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
///
/// It keeps the source memo and the fit cache in OUT as `build` does
/// ([`super::build::load_stored`]), so that `svg` run again refits only the contours that
/// changed, and `svg` and `build` into one OUT share them. What the cache keeps: for a
/// font without masters, only the entries this run used or made, as `build` does (`svg`
/// fits the same contours as `build` then, so an entry not used is one of a contour edited
/// or deleted since); for a font with masters, also every entry it did not use
/// ([`crate::cache::FitCache::keep_unused`]), since `svg` fits only the default master (or
/// the one position of `--at`) and the rest is `build`'s compatible fits and named
/// instances, which a build would otherwise refit. Those entries of edited contours then
/// stay until the next `build` (entries are keyed, so they never make a fit wrong).
pub fn run(args: SvgArgs) -> Result<ExitCode, CommandError> {
    // Ctrl-C leaves OUT as it was (a handler already set only means plain SIGINT).
    let _ = crate::write::exit_on_interrupt();
    let (loaded, stores, ()) = load_stored(&args.font, || ())?;
    let cache = &stores.cache;
    let at_font = match &args.at {
        Some(at) => {
            let location = parse_location(&loaded.family.designspace, at)?;
            let style = style_at(&loaded.family.designspace, &location);
            let opts = OutlineOptions {
                cache: Some(cache),
                progress: None,
            };
            Some(instance_with(&loaded, &location, Some(&style), opts)?)
        }
        None => None,
    };
    let written = stores.make_and_write(
        &loaded,
        &args.font.out,
        || svg_outputs(at_font.as_ref().unwrap_or(&loaded.font)),
        Ok,
    )?;
    let count = written.paths.len();
    outln!(
        "wrote {count} files to {} (SVG font and {} glyph SVGs)",
        args.font.out.display(),
        count - 1
    );
    written.save_records();
    // As in `build`: a large font's fits and memo are left to the exit, not freed one by one.
    std::mem::forget((loaded, stores, at_font));
    Ok(ExitCode::SUCCESS)
}
