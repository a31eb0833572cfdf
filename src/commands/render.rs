//! `xglyph render`: the glyph sheet and/or the text proof as PNG.

use std::path::PathBuf;
use std::process::ExitCode;

use super::build::load;
use super::{CommandError, FontArgs};
use crate::pipeline::write_outputs;
use crate::render::{encode_png, render_proof, render_sheet, ProofOptions, SheetOptions};

/// Which image to render.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Only {
    Sheet,
    Proof,
}

#[derive(Debug, clap::Args)]
#[command(after_help = "\
Writes into OUT: sheet.png (sheet-overlay.png with --overlay) and proof.png.

Sheet guides: grey ascender/descender, blue cap height, green x-height, dark baseline,
red advance box. Overlay: grey glyph with its exported outline as a dark line, the
blue-grey X-spline control polygon; control points as red
squares (sharp, s = 0), blue circles (approximating, s > 0), green diamonds
(interpolating, s < 0); orange dots on the on-curve points of the exported Béziers.

Examples:
  xglyph render                              # both images, glyphs/ -> out/
  xglyph render --only sheet --overlay --cell 320 --columns 4
  xglyph render --only proof --text 'Hamburgefonstiv\\nHOHOHO' --sizes 18,36,72")]
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
    /// Proof sizes, pixels per em, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "12,16,24,36,48,72")]
    pub sizes: Vec<f64>,
    /// Largest proof width, pixels (the image fits its longest line up to this).
    #[arg(long, default_value_t = ProofOptions::default().width_px)]
    pub width: u32,
}

/// Runs `xglyph render`.
pub fn run(args: RenderArgs) -> Result<ExitCode, CommandError> {
    let loaded = load(&args.font.font_dir, args.font.tolerance)?;
    let font = &loaded.font;
    let mut files = Vec::new();
    if args.only != Some(Only::Proof) {
        let opts = SheetOptions {
            cell_px: args.cell,
            columns: args.columns,
            overlay: args.overlay,
        };
        let name = if args.overlay {
            "sheet-overlay.png"
        } else {
            "sheet.png"
        };
        files.push((
            PathBuf::from(name),
            encode_png(&render_sheet(font, &opts)?)?,
        ));
    }
    if args.only != Some(Only::Sheet) {
        let opts = ProofOptions {
            text: args.text.map(|t| t.replace("\\n", "\n")),
            sizes: args.sizes,
            width_px: args.width,
        };
        files.push((
            PathBuf::from("proof.png"),
            encode_png(&render_proof(font, &opts)?)?,
        ));
    }
    write_outputs(&args.font.out, &files)?;
    for (path, _) in &files {
        println!("wrote {}", args.font.out.join(path).display());
    }
    Ok(ExitCode::SUCCESS)
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
