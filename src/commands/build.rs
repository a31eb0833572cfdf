//! `xglyph build`: the main job. Load, outline, render every output in memory, write them
//! all atomically, print a summary.
//!
//! Nothing is written unless every output rendered: a source error or a render error
//! leaves OUT untouched (not even created).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use kurbo::PathEl;

use super::{CommandError, FontArgs};
use crate::model::Font;
use crate::otf;
use crate::outline::{outline_font, FontOutlines};
use crate::render::{encode_png, render_proof, render_sheet, ProofOptions, SheetOptions};
use crate::source::{check_tolerance_flag, load_font, Diagnostic, Severity};
use crate::svg::{glyph_set, output_stem, svg_font};
use crate::terminal::{err, out};
use crate::write::OutputSet;

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

/// A font loaded and outlined, ready for every output.
pub struct Loaded {
    pub font: Font,
    pub outlines: FontOutlines,
}

/// Prints a diagnostic as `check` does (source line and caret), to stderr.
pub fn print_diagnostic(d: &Diagnostic) {
    err!("{}", crate::commands::check::text(d));
}

/// Loads `font_dir` (printing its diagnostics) and fits every glyph, with `tolerance`
/// overriding the font's own.
pub fn load(font_dir: &Path, tolerance: Option<f64>) -> Result<Loaded, CommandError> {
    if let Some(t) = tolerance {
        check_tolerance_flag(t)?;
    }
    let font = match load_font(font_dir) {
        Ok((font, _)) if font.glyphs.is_empty() => {
            return Err(format!(
                "{} has no glyph files yet (only font.toml); add one TOML file per glyph",
                font_dir.display()
            )
            .into());
        }
        Ok((font, warnings)) => {
            warnings.iter().for_each(print_diagnostic);
            font
        }
        Err(diags) => {
            diags.iter().for_each(print_diagnostic);
            let errors = diags
                .iter()
                .filter(|d| d.severity == Severity::Error)
                .count();
            let noun = if errors == 1 { "error" } else { "errors" };
            return Err(format!(
                "{errors} {noun} in {}; nothing was written",
                font_dir.display()
            )
            .into());
        }
    };
    let outlines = outline_font(&font, tolerance.unwrap_or(font.info.tolerance))?;
    Ok(Loaded { font, outlines })
}

/// Options for every output of a build.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildOptions {
    pub sheet: SheetOptions,
    pub proof: ProofOptions,
}

/// Every output of a build, rendered in memory: paths relative to OUT, and bytes.
/// This is the one list of build outputs; add a new output here.
pub fn outputs(
    font: &Font,
    outlines: &FontOutlines,
    opts: &BuildOptions,
) -> Result<Vec<(PathBuf, Vec<u8>)>, CommandError> {
    let mut files = Vec::new();
    files.extend(svg_outputs(font, outlines));
    files.push((
        PathBuf::from("sheet.png"),
        encode_png(&render_sheet(font, outlines, &opts.sheet)?)?,
    ));
    files.push((
        PathBuf::from("proof.png"),
        encode_png(&render_proof(font, outlines, &opts.proof)?)?,
    ));
    let stem = output_stem(&font.info);
    files.push((
        PathBuf::from(format!("{stem}.ttf")),
        otf::ttf(font, outlines)?,
    ));
    files.push((
        PathBuf::from(format!("{stem}.otf")),
        otf::otf(font, outlines)?,
    ));
    files.push((
        PathBuf::from("specimen.html"),
        otf::specimen_html(font, &format!("{stem}.otf")).into_bytes(),
    ));
    Ok(files)
}

/// The SVG font and the SVG glyph set, paths relative to OUT.
pub fn svg_outputs(font: &Font, outlines: &FontOutlines) -> Vec<(PathBuf, Vec<u8>)> {
    let mut files = vec![(
        PathBuf::from(format!("{}.svg", output_stem(&font.info))),
        svg_font(font, outlines).into_bytes(),
    )];
    for g in glyph_set(&font.info, outlines) {
        files.push((
            Path::new("svg").join(format!("{}.svg", g.stem)),
            g.svg.into_bytes(),
        ));
    }
    files
}

/// Writes `files` (relative paths) under `out`, all or none ([`OutputSet`]).
pub fn write_outputs(out: &Path, files: &[(PathBuf, Vec<u8>)]) -> Result<(), CommandError> {
    let mut set = OutputSet::new();
    for (path, bytes) in files {
        set.add(out.join(path), bytes.clone());
    }
    set.commit()
        .map_err(|e| format!("{e}; {} is unchanged", out.display()))?;
    Ok(())
}

/// Counts for the summary: `(contours, segments)` over all glyph outlines.
pub fn count_contours_segments(outlines: &FontOutlines) -> (usize, usize) {
    let mut contours = 0;
    let mut segments = 0;
    for g in &outlines.glyphs {
        for el in g.path.elements() {
            match el {
                PathEl::MoveTo(_) => contours += 1,
                PathEl::LineTo(_) | PathEl::QuadTo(..) | PathEl::CurveTo(..) => segments += 1,
                PathEl::ClosePath => {}
            }
        }
    }
    (contours, segments)
}

/// The summary printed after a build.
pub fn summary(loaded: &Loaded, out: &Path, files: &[(PathBuf, Vec<u8>)]) -> String {
    let (contours, segments) = count_contours_segments(&loaded.outlines);
    let worst = loaded
        .outlines
        .glyphs
        .iter()
        .max_by(|a, b| a.max_error.total_cmp(&b.max_error));
    // Three significant digits of the tolerance's order, at least three decimals.
    let digits = (2.0 - loaded.outlines.tolerance.log10().floor()).clamp(3.0, 12.0) as usize;
    let worst = match worst {
        Some(g) => format!("{:.digits$} font units (glyph `{}`)", g.max_error, g.name),
        None => "none".into(),
    };
    let top: Vec<String> = files
        .iter()
        .filter(|(p, _)| p.parent() == Some(Path::new("")))
        .map(|(p, _)| p.display().to_string())
        .collect();
    let in_svg = files.iter().filter(|(p, _)| p.starts_with("svg")).count();
    format!(
        "built {} {}: {} glyphs, {contours} contours, {segments} segments\n\
         worst error against the X-splines: {worst}, tolerance {}\n\
         wrote {} files to {}: {}, svg/ ({in_svg} glyph SVGs)\n",
        loaded.font.info.family,
        loaded.font.info.style,
        loaded.outlines.glyphs.len(),
        loaded.outlines.tolerance,
        files.len(),
        out.display(),
        top.join(", "),
    )
}

pub fn run(args: BuildArgs) -> Result<ExitCode, CommandError> {
    let loaded = load(&args.font.font_dir, args.font.tolerance)?;
    let opts = BuildOptions {
        proof: ProofOptions {
            text: args.text.map(|t| t.replace("\\n", "\n")),
            ..ProofOptions::default()
        },
        ..BuildOptions::default()
    };
    let files = outputs(&loaded.font, &loaded.outlines, &opts)?;
    write_outputs(&args.font.out, &files)?;
    out!("{}", summary(&loaded, &args.font.out, &files));
    Ok(ExitCode::SUCCESS)
}
