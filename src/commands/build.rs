//! `xglyph build`: the main job. Load, outline, render every output in memory, write them
//! all atomically, print a summary.
//!
//! Nothing is written unless every output rendered: a source error or a render error
//! leaves OUT untouched (not even created).

use std::path::Path;
use std::process::ExitCode;

use super::{CommandError, FontArgs};
use crate::pipeline::{self, BuildOptions, Loaded, OutputFile, PipelineError, Summary};
use crate::render::ProofOptions;
use crate::source::Diagnostic;
use crate::terminal::{err, out};

#[derive(Debug, clap::Args)]
#[command(after_help = "\
Writes into OUT:
  <Family>-<Style>.svg   SVG 1.1 font (FontForge, svg2ttf)
  svg/<glyph>.svg        one standalone SVG per glyph
  sheet.png              glyph sheet with metric guides
  proof.png              text proof at several sizes
  <Family>-<Style>.ttf   TrueType font (quadratic outlines within the tolerance)
  <Family>-<Style>.otf   OpenType CFF font (the cubics)
  specimen.html          specimen page loading the OTF with @font-face

Examples:
  xglyph build                            # glyphs/ -> out/
  xglyph build my-font -o dist
  xglyph build --tolerance 0.1 --text 'Hamburgefonstiv'")]
pub struct BuildArgs {
    #[command(flatten)]
    pub font: FontArgs,
    /// Proof text (default: lines the font covers); `\n` in the text starts a new line.
    #[arg(long)]
    pub text: Option<String>,
}

/// Prints a diagnostic as `check` does (source line and caret), to stderr.
pub fn print_diagnostic(d: &Diagnostic) {
    err!("{}", crate::commands::check::text(d));
}

/// [`pipeline::load`], printing the warnings, or every diagnostic of a failed load.
pub fn load(font_dir: &Path, tolerance: Option<f64>) -> Result<Loaded, CommandError> {
    match pipeline::load(font_dir, tolerance) {
        Ok(loaded) => {
            loaded.warnings.iter().for_each(print_diagnostic);
            Ok(loaded)
        }
        Err(err) => {
            if let PipelineError::Sources { diagnostics, .. } = &err {
                diagnostics.iter().for_each(print_diagnostic);
            }
            Err(err.into())
        }
    }
}

/// The summary printed after a build.
pub fn summary(summary: &Summary, family: &str, out: &Path, files: &[OutputFile]) -> String {
    // Three significant digits of the tolerance's order, at least three decimals.
    let digits = (2.0 - summary.tolerance.log10().floor()).clamp(3.0, 12.0) as usize;
    let worst = match &summary.worst {
        Some((name, error)) => format!("{error:.digits$} font units (glyph `{name}`)"),
        None => "none".into(),
    };
    let top: Vec<String> = files
        .iter()
        .filter(|(p, _)| p.parent() == Some(Path::new("")))
        .map(|(p, _)| p.display().to_string())
        .collect();
    let in_svg = files.iter().filter(|(p, _)| p.starts_with("svg")).count();
    format!(
        "built {family}: {} glyphs, {} contours, {} segments\n\
         worst error against the X-splines: {worst}, tolerance {}\n\
         wrote {} files to {}: {}, svg/ ({in_svg} glyph SVGs)\n",
        summary.glyphs,
        summary.contours,
        summary.segments,
        summary.tolerance,
        files.len(),
        out.display(),
        top.join(", "),
    )
}

/// Runs `xglyph build`.
pub fn run(args: BuildArgs) -> Result<ExitCode, CommandError> {
    let loaded = load(&args.font.font_dir, args.font.tolerance)?;
    let opts = BuildOptions {
        proof: ProofOptions {
            text: args.text.map(|t| t.replace("\\n", "\n")),
            ..ProofOptions::default()
        },
        ..BuildOptions::default()
    };
    let files = pipeline::outputs(&loaded.font, &opts)?;
    pipeline::write_outputs(&args.font.out, &files)?;
    let info = &loaded.font.info;
    let family = format!("{} {}", info.family, info.style);
    out!(
        "{}",
        summary(&Summary::new(&loaded.font), &family, &args.font.out, &files)
    );
    Ok(ExitCode::SUCCESS)
}
