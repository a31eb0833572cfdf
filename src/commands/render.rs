//! `xglyph render`: the glyph sheet and/or the text proof as PNG.

use std::path::PathBuf;
use std::process::ExitCode;

use super::build::load_stored;
use super::{CommandError, FontArgs};
use crate::instance::parse_location;
use crate::layout::Layout;
use crate::outline::OutlineOptions;
use crate::pipeline;
use crate::render::{
    encode_png, render_proof_with, sheet_png_files_with, ProofOptions, RenderError, SheetOptions,
    MAX_AREA, MAX_SIDE,
};
use crate::terminal::outln;

/// Which image to render.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Only {
    Sheet,
    Proof,
}

#[derive(Debug, clap::Args)]
#[command(after_help = "\
Writes into OUT: sheet.png (sheet-overlay.png with --overlay) and proof.png. A sheet of
more than one page (512 glyphs at the default cell and columns) is sheet-1.png, sheet-2.png, ...
Also .xglyph-cache and .xglyph-sources: the fits and the parsed glyph files, for the next
run (shared with `xglyph build` and `xglyph svg` into the same OUT).

Sheet guides: grey ascender/descender, blue cap height, green x-height, dark baseline,
red advance box. Overlay: grey glyph with its exported outline as a dark line, the
blue-grey X-spline control polygon; control points as red
squares (sharp, s = 0), blue circles (approximating, s > 0), green diamonds
(interpolating, s < 0); orange dots on the on-curve points of the exported Béziers.

Examples:
  xglyph render                              # both images, glyphs/ -> out/
  xglyph render --only sheet --overlay --cell 320 --columns 4
  xglyph render --only proof --text 'Hamburgefonstiv\\nHOHOHO' --sizes 18,36,72
  xglyph render --at wght=650                # a font with masters, at weight 650")]
pub struct RenderArgs {
    #[command(flatten)]
    pub font: FontArgs,
    /// Render only this image.
    #[arg(long, value_enum)]
    pub only: Option<Only>,
    /// Sheet cell size, pixels (32..=2048).
    #[arg(long, default_value_t = SheetOptions::default().cell_px)]
    pub cell: u32,
    /// Sheet cells per row.
    #[arg(long, default_value_t = SheetOptions::default().columns)]
    pub columns: u32,
    /// Draw the X-spline control points and Bézier on-curve points (sheet-overlay.png).
    #[arg(long)]
    pub overlay: bool,
    /// Proof text (default: lines the font covers); `\n` starts a new line.
    #[arg(long)]
    pub text: Option<String>,
    /// Proof sizes, pixels per em (each 1..=1000), comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "12,16,24,36,48,72")]
    pub sizes: Vec<f64>,
    /// Largest proof width, pixels, 1..=30000 (the image fits its longest line up to this).
    #[arg(long, default_value_t = ProofOptions::default().width_px)]
    pub width: u32,
    /// Render the font at this position of its design space (a font with masters), user
    /// coordinates: TAG=VALUE, several separated by commas, e.g. `wght=650`.
    #[arg(long, value_name = "TAG=VALUE")]
    pub at: Option<String>,
}

/// Runs `xglyph render`.
///
/// It keeps the source memo and the fit cache in OUT as `svg` does (see
/// [`super::svg::run`]): `render` run again, or after a `build` into the same OUT, refits
/// only the contours that changed (a CJK font's 20,902 glyphs were refitted on every run).
pub fn run(args: RenderArgs) -> Result<ExitCode, CommandError> {
    // Ctrl-C leaves OUT as it was (a handler already set only means plain SIGINT).
    let _ = crate::write::exit_on_interrupt();
    check_flags(&args)?;
    let (loaded, stores, ()) = load_stored(&args.font, || ())?;
    let cache = &stores.cache;
    let at_font = match &args.at {
        Some(at) => {
            let location = parse_location(&loaded.family.designspace, at)?;
            let opts = OutlineOptions {
                cache: Some(cache),
                progress: None,
            };
            Some(pipeline::instance_with(&loaded, &location, None, opts)?)
        }
        None => None,
    };
    let font = at_font.as_ref().unwrap_or(&loaded.font);
    // One TTF shapes the sheet labels and the proof; the two images render in parallel.
    let layout = Layout::new(font).map_err(RenderError::from)?;
    let sheet_opts = SheetOptions {
        cell_px: args.cell,
        columns: args.columns,
        overlay: args.overlay,
    };
    let stem = if args.overlay {
        "sheet-overlay"
    } else {
        "sheet"
    };
    let proof_opts = ProofOptions {
        text: args.text.map(|t| t.replace("\\n", "\n")),
        sizes: args.sizes,
        width_px: args.width,
    };
    // The two images on every core while the fit cache is encoded, then written.
    let made = || {
        rayon::join(
            || {
                (args.only != Some(Only::Proof))
                    .then(|| sheet_png_files_with(&layout, &sheet_opts, stem))
                    .transpose()
            },
            || {
                (args.only != Some(Only::Sheet))
                    .then(|| render_proof_with(&layout, &proof_opts).and_then(|p| encode_png(&p)))
                    .transpose()
            },
        )
    };
    let written = stores.make_and_write(&loaded, &args.font.out, made, |(sheets, proof)| {
        let sheets = sheets.map_err(|e| sheet_flags(e, &sheet_opts))?;
        let mut files: Vec<_> = (sheets.into_iter().flatten())
            .map(|(name, png)| (PathBuf::from(name), png))
            .collect();
        if let Some(proof) = proof.map_err(|e| proof_flags(e, &proof_opts))? {
            files.push((PathBuf::from("proof.png"), proof));
        }
        Ok(files)
    })?;
    for path in &written.paths {
        outln!("wrote {}", args.font.out.join(path).display());
    }
    written.save_records();
    // As in `build`: a large font's fits and memo are left to the exit, not freed one by one.
    std::mem::forget((loaded, stores, at_font));
    Ok(ExitCode::SUCCESS)
}

/// Checks each flag's own range before any work; the error names the flag.
fn check_flags(args: &RenderArgs) -> Result<(), String> {
    if !(32..=2048).contains(&args.cell) {
        return Err(format!(
            "--cell {}: the cell size must be 32..=2048 px",
            args.cell
        ));
    }
    if args.columns == 0 {
        return Err("--columns 0: at least 1 column is needed".into());
    }
    if !(1..=MAX_SIDE).contains(&args.width) {
        return Err(format!(
            "--width {}: the proof width must be 1..={MAX_SIDE} px",
            args.width
        ));
    }
    if args.sizes.is_empty() {
        return Err("--sizes: at least one size is needed".into());
    }
    if let Some(bad) = args
        .sizes
        .iter()
        .find(|s| !(s.is_finite() && (1.0..=1000.0).contains(*s)))
    {
        return Err(format!("--sizes: {bad} px per em is out of range 1..=1000"));
    }
    Ok(())
}

/// An image too large for the sheet flags, said in their terms.
fn sheet_flags(e: RenderError, opts: &SheetOptions) -> CommandError {
    match e {
        RenderError::Size { width, height } => format!(
            "--cell {} --columns {}: the sheet would be {width} x {height} px; at most \
             {MAX_SIDE} px a side and {MAX_AREA} px in all (use a smaller --cell or fewer \
             --columns)",
            opts.cell_px, opts.columns
        )
        .into(),
        e => e.into(),
    }
}

/// An image too large for the proof flags, said in their terms.
fn proof_flags(e: RenderError, opts: &ProofOptions) -> CommandError {
    match e {
        RenderError::Size { width, height } => format!(
            "--sizes: {} sizes make an image of {width} x {height} px; at most {MAX_SIDE} px \
             a side and {MAX_AREA} px in all (give fewer or smaller sizes, or a shorter --text)",
            opts.sizes.len()
        )
        .into(),
        e => e.into(),
    }
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;
    use crate::cli::{Cli, Command};

    #[test]
    fn defaults_match_the_library_defaults() {
        let cli = Cli::try_parse_from(["xglyph", "render"]).unwrap();
        let Command::Render(args) = cli.command else {
            panic!("not the render command");
        };
        let (sheet, proof) = (SheetOptions::default(), ProofOptions::default());
        assert_eq!(args.sizes, proof.sizes);
        assert_eq!(args.width, proof.width_px);
        assert_eq!((args.cell, args.columns), (sheet.cell_px, sheet.columns));
        assert_eq!(args.font.font_dir, PathBuf::from("glyphs"));
    }
}
