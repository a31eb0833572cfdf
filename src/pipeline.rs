//! The whole pipeline as library calls that return data: a font directory to the outlined
//! font ([`load`]), the outlined font to every output file in memory ([`outputs`]), the
//! files to disk ([`write_outputs`]), and the numbers a summary reports ([`Summary`]).
//!
//! Nothing here prints: warnings and errors come back as [`Diagnostic`]s for the caller
//! (the command line prints them; a server would send them).

use std::convert::Infallible;
use std::fmt;
use std::path::{Path, PathBuf};

use rayon::prelude::*;

use crate::cache::FitCache;
use crate::designspace::Location;
use crate::family::{outline_family_with, FamilyError, FamilySummary};
use crate::instance::InstanceError;
use crate::layout::Layout;
use crate::model::Family;
use crate::names::file_stems;
use crate::otf::{self, OtfError};
use crate::outline::{outline_font_with, OutlineOptions, OutlinedFont};
use crate::overlap::Unions;
use crate::render::{
    encode_png, page_file_names, render_proof_with, sheet_png_files_reusing, InstancesProof,
    ProofOptions, RenderError, SheetOptions,
};
use crate::reuse::{font_key, glyph_key, KeyBuilder, OutlineKeys, Reuse};
use crate::source::{check_tolerance_flag, load_family_with, Diagnostic, Severity, SourceMemo};
use crate::svg::{glyph_elements, glyph_svg, output_stem, svg_font, svg_font_with, svg_glyph_key};
use crate::write::{OutputSet, WriteError};

/// A font directory loaded and outlined, and the warnings of its sources.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// Every glyph of the default master fitted.
    pub font: OutlinedFont,
    /// The sources' model with its masters (a single-master font has no axes).
    pub family: Family,
    /// Warnings of the sources (errors stop [`load`]).
    pub warnings: Vec<Diagnostic>,
}

/// Why a pipeline step failed.
#[derive(Debug)]
pub enum PipelineError {
    /// The `--tolerance` value is not usable.
    Tolerance(String),
    /// The sources have errors: every diagnostic (warnings included), in file order.
    Sources {
        /// The font directory.
        dir: PathBuf,
        /// Every problem found.
        diagnostics: Vec<Diagnostic>,
    },
    /// The font directory holds `font.toml` but no glyph.
    NoGlyphs(PathBuf),
    /// A PNG output could not be rendered.
    Render(RenderError),
    /// The font does not fit into OpenType.
    Otf(OtfError),
    /// An instance of the masters could not be built.
    Instance(String),
    /// The masters could not be fitted compatibly.
    Family(FamilyError),
    /// The UFO export failed.
    Ufo(crate::ufo::UfoError),
    /// Writing the outputs failed; the output directory is as it was.
    Write {
        /// The output directory.
        dir: PathBuf,
        /// What went wrong.
        error: WriteError,
    },
}

impl fmt::Display for PipelineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PipelineError::Tolerance(msg) => write!(f, "{msg}"),
            PipelineError::Sources { dir, diagnostics } => {
                // `count`: an "… and N more" line stands for N problems.
                let errors: usize = diagnostics
                    .iter()
                    .filter(|d| d.severity == Severity::Error)
                    .map(|d| d.count)
                    .sum();
                let noun = if errors == 1 { "error" } else { "errors" };
                write!(
                    f,
                    "{errors} {noun} in {}; nothing was written",
                    dir.display()
                )
            }
            PipelineError::NoGlyphs(dir) => write!(
                f,
                "{} has no glyph files yet (only font.toml); add one TOML file per glyph",
                dir.display()
            ),
            PipelineError::Render(e) => write!(f, "{e}"),
            PipelineError::Otf(e) => write!(f, "{e}"),
            PipelineError::Instance(msg) => write!(f, "{msg}"),
            PipelineError::Family(e) => write!(f, "{e}"),
            PipelineError::Ufo(e) => write!(f, "{e}"),
            PipelineError::Write { dir, error } => {
                write!(f, "{error}; {} is unchanged", dir.display())
            }
        }
    }
}

impl std::error::Error for PipelineError {}

impl From<RenderError> for PipelineError {
    fn from(e: RenderError) -> Self {
        PipelineError::Render(e)
    }
}

impl From<OtfError> for PipelineError {
    fn from(e: OtfError) -> Self {
        PipelineError::Otf(e)
    }
}

/// Loads `font_dir` and fits every glyph, with `tolerance` overriding the font's own.
pub fn load(font_dir: &Path, tolerance: Option<f64>) -> Result<Loaded, PipelineError> {
    load_with(font_dir, tolerance, OutlineOptions::default())
}

/// [`load`] with a fit cache and a progress count ([`OutlineOptions`]).
pub fn load_with(
    font_dir: &Path,
    tolerance: Option<f64>,
    opts: OutlineOptions<'_>,
) -> Result<Loaded, PipelineError> {
    Ok(read_sources(font_dir, tolerance)?.outline(opts))
}

/// A font directory loaded and checked, not yet fitted: [`read_sources`].
#[derive(Debug)]
pub struct Sources {
    family: Family,
    warnings: Vec<Diagnostic>,
    tolerance: f64,
}

impl Sources {
    /// Fits every glyph of the default master ([`outline_font_with`]).
    pub fn outline(self, opts: OutlineOptions<'_>) -> Loaded {
        Loaded {
            font: outline_font_with(&self.family.default, self.tolerance, opts),
            family: self.family,
            warnings: self.warnings,
        }
    }
}

/// The first half of [`load_with`]: `font_dir` loaded and checked (the `--tolerance`
/// value, the sources, `features.fea`), so that a caller can load its caches meanwhile.
pub fn read_sources(font_dir: &Path, tolerance: Option<f64>) -> Result<Sources, PipelineError> {
    read_sources_with(font_dir, tolerance, &SourceMemo::off())
}

/// [`read_sources`], taking the glyph files that did not change since the last build from
/// `memo` ([`SourceMemo`]).
pub fn read_sources_with(
    font_dir: &Path,
    tolerance: Option<f64>,
    memo: &SourceMemo,
) -> Result<Sources, PipelineError> {
    if let Some(t) = tolerance {
        check_tolerance_flag(t).map_err(PipelineError::Tolerance)?;
    }
    let (family, warnings) =
        load_family_with(font_dir, memo).map_err(|diagnostics| PipelineError::Sources {
            dir: font_dir.to_path_buf(),
            diagnostics,
        })?;
    if family.default.glyphs.is_empty() {
        return Err(PipelineError::NoGlyphs(font_dir.to_path_buf()));
    }
    // features.fea errors stop the build here, like every other source error.
    let feature_errors = feature_diagnostics(&family.default);
    if !feature_errors.is_empty() {
        let mut diagnostics = warnings;
        diagnostics.extend(feature_errors);
        return Err(PipelineError::Sources {
            dir: font_dir.to_path_buf(),
            diagnostics,
        });
    }
    let tolerance = tolerance.unwrap_or(family.default.info.tolerance);
    Ok(Sources {
        family,
        warnings,
        tolerance,
    })
}

/// The errors of the font's `features.fea` (none without one), checked against its glyph
/// names.
pub fn feature_diagnostics(font: &crate::model::Font) -> Vec<Diagnostic> {
    let Some(features) = &font.features else {
        return Vec::new();
    };
    let names: Vec<&str> = font.glyphs.iter().map(|g| g.name.as_str()).collect();
    otf::check_features(features, &names)
}

impl From<crate::ufo::UfoError> for PipelineError {
    fn from(e: crate::ufo::UfoError) -> Self {
        PipelineError::Ufo(e)
    }
}

impl From<InstanceError> for PipelineError {
    fn from(e: InstanceError) -> Self {
        PipelineError::Instance(e.to_string())
    }
}

/// The static font at `location` (see [`Family::instance_at`]), fitted statically to the
/// tolerance of `loaded`; its style is `style` when given (a named instance's name).
pub fn instance(
    loaded: &Loaded,
    location: &Location,
    style: Option<&str>,
) -> Result<OutlinedFont, PipelineError> {
    instance_with(loaded, location, style, OutlineOptions::default())
}

/// [`instance`] with a fit cache (the instance's blended contours are keyed like any
/// other: a rebuild refits only those that changed).
pub fn instance_with(
    loaded: &Loaded,
    location: &Location,
    style: Option<&str>,
    opts: OutlineOptions<'_>,
) -> Result<OutlinedFont, PipelineError> {
    let mut font = loaded.family.instance_at(location)?;
    if let Some(style) = style {
        font.info.style = style.to_string();
    }
    Ok(outline_font_with(&font, loaded.font.tolerance, opts))
}

/// Every named instance of a font with masters, fitted statically, in `font.toml` order.
pub fn named_instances(loaded: &Loaded) -> Result<Vec<(String, OutlinedFont)>, PipelineError> {
    named_instances_with(loaded, None)
}

/// [`named_instances`] with fits from `cache`.
pub fn named_instances_with(
    loaded: &Loaded,
    cache: Option<&FitCache>,
) -> Result<Vec<(String, OutlinedFont)>, PipelineError> {
    let opts = OutlineOptions {
        cache,
        progress: None,
    };
    loaded
        .family
        .designspace
        .instances
        .iter()
        .map(|i| {
            Ok((
                i.name.clone(),
                instance_with(loaded, &i.location, Some(&i.name), opts)?,
            ))
        })
        .collect()
}

/// The outputs a font with masters adds to [`outputs`]: each named instance as a static
/// `<Family>-<Instance>.ttf`, `.otf` and `.svg` font, and `proof-instances.png` (the proof
/// text at each named instance, one labelled block each). Nothing for a single-master font.
///
/// An instance whose files would have the default master's names is left out when it sits
/// at the default location (the default master's files are that instance); anywhere else
/// it is an error, since its files would replace the default's.
pub fn instance_outputs(
    loaded: &Loaded,
    opts: &BuildOptions,
) -> Result<Vec<OutputFile>, PipelineError> {
    instance_outputs_with(loaded, opts, None)
}

/// [`instance_outputs`] with the instances' fits from `cache`.
pub fn instance_outputs_with(
    loaded: &Loaded,
    opts: &BuildOptions,
    cache: Option<&FitCache>,
) -> Result<Vec<OutputFile>, PipelineError> {
    instance_outputs_reusing(loaded, opts, cache, &Reuse::off())
}

/// [`instance_outputs_with`], taking the instances' unions from `reuse`, and
/// `proof-instances.png` from OUT when no instance changed since the last build.
pub fn instance_outputs_reusing(
    loaded: &Loaded,
    opts: &BuildOptions,
    cache: Option<&FitCache>,
    reuse: &Reuse,
) -> Result<Vec<OutputFile>, PipelineError> {
    if !loaded.family.is_variable() || loaded.family.designspace.instances.is_empty() {
        return Ok(Vec::new());
    }
    let instances = named_instances_with(loaded, cache)?;
    let default_stem = output_stem(&loaded.font.info);
    let named = &loaded.family.designspace.instances;
    // Each instance's outlines hashed once for its keys.
    let outlines: Vec<OutlineKeys> = instances
        .iter()
        .map(|(_, font)| OutlineKeys::new(font, reuse))
        .collect();
    // Which instances get files of their own (checked in order, before any work).
    let mut written = Vec::new();
    for (((name, font), named), outlines) in instances.iter().zip(named).zip(&outlines) {
        let stem = output_stem(&font.info);
        if stem == default_stem {
            let at_default = loaded
                .family
                .designspace
                .normalize(&named.location)
                .iter()
                .all(|&v| v == 0.0);
            if at_default {
                continue;
            }
            return Err(PipelineError::Instance(format!(
                "the named instance `{name}` away from the default location would write \
                 {stem}.ttf, the default master's file; rename the instance or the default \
                 `style`"
            )));
        }
        written.push((stem, font, outlines));
    }
    // Each instance's fonts in parallel, in order; its TTF also shapes its proof block.
    let built: Vec<Result<InstanceFonts, PipelineError>> = written
        .par_iter()
        .map(|(stem, font, outlines)| instance_fonts(stem, font, opts, reuse, outlines))
        .collect();
    let built = built.into_iter().collect::<Result<Vec<_>, _>>()?;
    let mut files = Vec::new();
    for b in &built {
        files.extend(b.files.iter().cloned());
    }
    let mut layouts = Vec::with_capacity(instances.len());
    // What the proof depends on: each instance as drawn (its TTF and glyphs).
    let mut drawn = Vec::new();
    for ((name, font), outlines) in instances.iter().zip(&outlines) {
        let stem = output_stem(&font.info);
        let ttf = match built.iter().find(|b| b.stem == stem) {
            Some(b) => b.ttf.clone(),
            // The instance at the default location: the default master's TTF is its own.
            None => otf::ttf(font)?,
        };
        if reuse.is_on() {
            drawn.push(font_key(font, &ttf, outlines));
        }
        layouts.push((
            name,
            Layout::with_ttf(font, ttf).map_err(RenderError::from)?,
        ));
    }
    let labelled: Vec<(String, &Layout<'_>)> = layouts
        .iter()
        .zip(named)
        .map(|((name, layout), named)| {
            let at: Vec<String> = loaded
                .family
                .designspace
                .axes
                .iter()
                .map(|a| {
                    format!(
                        "{} {}",
                        a.tag,
                        crate::source::emit::number(named.location.get(a))
                    )
                })
                .collect();
            (format!("{name} ({})", at.join(", ")), layout)
        })
        .collect();
    let proof_opts = instances_proof_options(&opts.proof);
    // `proof-instances.png`, or `proof-instances-1.png`, … when the blocks of many
    // instances (Roboto Flex has 20) would make one image taller than the limits.
    let proof = InstancesProof::new(&labelled, &proof_opts)?;
    let pages = proof.pages();
    let names = page_file_names("proof-instances", pages.len());
    for (page, name) in pages.into_iter().zip(names) {
        let draw = || encode_png(&proof.render(page.clone())?);
        let png = if reuse.is_on() {
            let mut key = KeyBuilder::new("instances proof");
            key.str(&format!("{proof_opts:?}"))
                .u64(labelled.len() as u64)
                .u64(page.start as u64)
                .u64(page.end as u64);
            for ((label, _), drawn) in labelled.iter().zip(&drawn) {
                key.str(label).key(drawn);
            }
            reuse.get_or_make(Path::new(&name), key.finish(), draw)?
        } else {
            draw()?
        };
        files.push((PathBuf::from(name), png));
    }
    Ok(files)
}

/// One named instance's static fonts: `<stem>.ttf`, `.otf` and `.svg`, and its TTF.
struct InstanceFonts {
    stem: String,
    ttf: Vec<u8>,
    files: Vec<OutputFile>,
}

fn instance_fonts(
    stem: &str,
    font: &OutlinedFont,
    opts: &BuildOptions,
    reuse: &Reuse,
    outlines: &OutlineKeys,
) -> Result<InstanceFonts, PipelineError> {
    let ot = ForOpenType::new(font, opts, reuse, outlines);
    let (ttf, (otf, svg)) = rayon::join(
        || ot.ttf(),
        || rayon::join(|| ot.otf(), || svg_font(font).into_bytes()),
    );
    let ttf = ttf?;
    Ok(InstanceFonts {
        stem: stem.to_string(),
        files: vec![
            (PathBuf::from(format!("{stem}.ttf")), ttf.clone()),
            (PathBuf::from(format!("{stem}.otf")), otf?),
            (PathBuf::from(format!("{stem}.svg")), svg),
        ],
        ttf,
    })
}

/// The variable font of a font with masters, `<Family>[<axis tags>].ttf` and `.woff2`
/// (the naming Google Fonts uses), plus `<Family>-<Master>.ufo` per master and
/// `<Family>.designspace` ([`crate::ufo::designspace`]), all from the compatible outlines
/// ([`outline_family_with`]), with the fit's summary. `None` for a single-master font. The
/// compatible fits come from `cache` when it holds them.
pub fn variable_outputs(
    loaded: &Loaded,
    cache: Option<&crate::cache::FitCache>,
) -> Result<Option<(Vec<OutputFile>, FamilySummary)>, PipelineError> {
    variable_outputs_with(loaded, cache, &Reuse::off())
}

/// [`variable_outputs`], taking the variable WOFF2 from OUT when the variable TTF's bytes
/// did not change since the last build ([`Reuse`]).
pub fn variable_outputs_with(
    loaded: &Loaded,
    cache: Option<&crate::cache::FitCache>,
    reuse: &Reuse,
) -> Result<Option<(Vec<OutputFile>, FamilySummary)>, PipelineError> {
    if !loaded.family.is_variable() {
        return Ok(None);
    }
    let (family, summary) = outline_family_with(&loaded.family, loaded.font.tolerance, cache)
        .map_err(PipelineError::Family)?;
    // Each master's anchors with those its components bring, as the default's
    // `placed_anchors`.
    let anchors: Vec<Vec<_>> = loaded
        .family
        .masters
        .iter()
        .map(|m| {
            let font = crate::model::Font {
                glyphs: m.glyphs.clone(),
                kerning: Vec::new(),
                ..loaded.family.default.clone()
            };
            let index = font.index();
            font.glyphs
                .iter()
                .map(|g| font.anchors_in(&index, g))
                .collect()
        })
        .collect();
    let tags: Vec<&str> = family
        .designspace
        .axes
        .iter()
        .map(|a| a.tag.as_str())
        .collect();
    // The static stem without its `-<style>`.
    let info = &family.default.info;
    let static_stem = output_stem(info);
    let style: String = info.style.chars().filter(|c| !c.is_whitespace()).collect();
    let family_stem = static_stem
        .strip_suffix(&format!("-{style}"))
        .unwrap_or(&static_stem);
    let stem = format!("{family_stem}[{}]", tags.join(","));
    // The font and its WOFF2 on one core, the UFOs on another (rayon); the same bytes
    // whatever the thread count.
    let (fonts, ufos) = rayon::join(
        || -> Result<_, PipelineError> {
            let ttf = otf::variable_ttf_with_anchors(&family, &anchors)?;
            let woff2 = woff2_reusing(&ttf, &format!("{stem}.woff2"), reuse)?;
            Ok((ttf, woff2))
        },
        || crate::ufo::designspace::output_files_reusing(&family, &loaded.family, reuse),
    );
    let (ttf, woff2) = fonts?;
    let mut files = vec![
        (PathBuf::from(format!("{stem}.ttf")), ttf),
        (PathBuf::from(format!("{stem}.woff2")), woff2),
    ];
    // One UFO per master from the same compatible outlines, and the `.designspace`; the
    // default master's UFO replaces the static one of [`outputs`].
    files.extend(ufos?);
    Ok(Some((files, summary)))
}

/// The instances proof: the build's proof text at three sizes (every instance is a block).
fn instances_proof_options(proof: &ProofOptions) -> ProofOptions {
    ProofOptions {
        sizes: vec![24.0, 48.0, 96.0],
        ..proof.clone()
    }
}

/// Options for every output of a build.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildOptions {
    /// The glyph sheet.
    pub sheet: SheetOptions,
    /// The text proof.
    pub proof: ProofOptions,
    /// Write the TTF, OTF and WOFF2 with overlapping contours as they are (by default they
    /// are unioned: [`crate::overlap::remove_overlaps_font`]).
    pub keep_overlaps: bool,
}

/// One output file: its path relative to the output directory, and its bytes.
pub type OutputFile = (PathBuf, Vec<u8>);

/// Every output of a build, rendered in memory. This is the one list of build outputs;
/// add a new output here.
///
/// The work runs in parallel (rayon): the text outputs (SVG, UFO, specimen) beside the
/// binary ones, and among those the sheet pages, the proof, the OTF and the WOFF2 beside
/// each other. The TTF is built once, and the proof and the sheet labels are shaped on it
/// (its overlaps removed changes no position a shaper reads: advances, `cmap`, GSUB and
/// GPOS are the same). Each output is a pure function of `font` and `opts`, and the list
/// keeps its order, so the bytes do not depend on the thread count.
pub fn outputs(font: &OutlinedFont, opts: &BuildOptions) -> Result<Vec<OutputFile>, PipelineError> {
    outputs_with(font, opts, &Reuse::off())
}

/// [`outputs`], taking from OUT the sheet pages, proof and WOFF2 whose inputs did not
/// change since the last build ([`Reuse`]); the same bytes as [`outputs`].
///
/// An SVG glyph file or `.glif` whose glyph did not change is not made at all when OUT
/// holds it as the last build wrote it ([`Reuse::kept_or_make`]): it is missing from the
/// list, and [`Reuse::kept_paths`] names it.
pub fn outputs_with(
    font: &OutlinedFont,
    opts: &BuildOptions,
    reuse: &Reuse,
) -> Result<Vec<OutputFile>, PipelineError> {
    static_outputs_with(font, opts, reuse, true)
}

/// [`outputs_with`], without the UFO unless `ufo` (a font with masters writes the UFOs of
/// [`variable_outputs_with`] instead).
pub fn static_outputs_with(
    font: &OutlinedFont,
    opts: &BuildOptions,
    reuse: &Reuse,
    ufo: bool,
) -> Result<Vec<OutputFile>, PipelineError> {
    let stem = output_stem(&font.info);
    // Each glyph's outline hashed once, for the keys of every output below.
    let outlines = OutlineKeys::new(font, reuse);
    let outlines = &outlines;
    let (binary, text) = rayon::join(
        || opentype_and_images(font, opts, &stem, reuse, outlines),
        || -> Result<_, PipelineError> {
            let (svg, ufo) = rayon::join(
                || svg_outputs_reusing(font, reuse, outlines),
                || {
                    if ufo {
                        crate::ufo::output_files_reusing(font, reuse, outlines, &[])
                    } else {
                        Ok(Vec::new())
                    }
                },
            );
            Ok((svg, ufo?))
        },
    );
    let (svg, ufo) = text?;
    let Binary {
        sheets,
        proof,
        ttf,
        otf,
        woff2,
    } = binary?;
    let mut files = svg;
    files.extend(
        sheets
            .into_iter()
            .map(|(name, png)| (PathBuf::from(name), png)),
    );
    files.push((PathBuf::from("proof.png"), proof));
    files.push((PathBuf::from(format!("{stem}.ttf")), ttf));
    files.push((PathBuf::from(format!("{stem}.otf")), otf));
    files.push((PathBuf::from(format!("{stem}.woff2")), woff2));
    files.extend(ufo);
    let (woff2_name, otf_name) = (format!("{stem}.woff2"), format!("{stem}.otf"));
    files.push((
        PathBuf::from("specimen.html"),
        otf::specimen_html_sources(font, &[&woff2_name, &otf_name]).into_bytes(),
    ));
    Ok(files)
}

/// The binary outputs of [`outputs`]: the PNGs and the fonts.
struct Binary {
    sheets: Vec<(String, Vec<u8>)>,
    proof: Vec<u8>,
    ttf: Vec<u8>,
    otf: Vec<u8>,
    woff2: Vec<u8>,
}

/// The TTF once, then in parallel: its WOFF2, the OTF, and the sheet pages and the proof
/// shaped on it.
fn opentype_and_images(
    font: &OutlinedFont,
    opts: &BuildOptions,
    stem: &str,
    reuse: &Reuse,
    outlines: &OutlineKeys,
) -> Result<Binary, PipelineError> {
    let ot = ForOpenType::new(font, opts, reuse, outlines);
    let ttf = ot.ttf()?;
    // The images draw `font` (overlaps as drawn) with the positions of the shipped TTF.
    let layout = Layout::with_ttf(font, ttf.clone()).map_err(RenderError::from)?;
    // What the proof and the sheet labels set in the font depend on.
    let drawn = reuse.is_on().then(|| font_key(font, &ttf, outlines));
    let proof_key = drawn.map(|drawn| {
        KeyBuilder::new("proof")
            .key(&drawn)
            .str(&format!("{:?}", opts.proof))
            .finish()
    });
    // The WOFF2 first: Brotli runs on one core, the images on every core around it.
    let ((woff2, otf), (sheets, proof)) = rayon::join(
        || {
            rayon::join(
                || woff2_reusing(&ttf, &format!("{stem}.woff2"), reuse),
                || ot.otf(),
            )
        },
        || {
            rayon::join(
                || {
                    sheet_png_files_reusing(
                        &layout,
                        &opts.sheet,
                        "sheet",
                        reuse,
                        drawn.as_ref(),
                        outlines,
                    )
                },
                || {
                    let draw = || encode_png(&render_proof_with(&layout, &opts.proof)?);
                    match proof_key {
                        Some(key) => reuse.get_or_make(Path::new("proof.png"), key, draw),
                        None => draw(),
                    }
                },
            )
        },
    );
    Ok(Binary {
        sheets: sheets?,
        proof: proof?,
        otf: otf?,
        woff2: woff2?,
        ttf,
    })
}

/// The WOFF2 of `ttf`, taken from OUT's `name` when the last build made it from the same
/// bytes (Brotli at quality 11 is the slowest step of a small font's build). A large font's
/// WOFF2 is made from slices instead, each kept for the next build and taken back when its
/// bytes are the same and the kept stream still decodes to them: an edit of one glyph
/// compresses about 2 of a CJK font's 22 slices.
fn woff2_reusing(ttf: &[u8], name: &str, reuse: &Reuse) -> Result<Vec<u8>, OtfError> {
    if !reuse.is_on() {
        return otf::woff2_from_ttf(ttf);
    }
    if ttf.len() > otf::LARGE_SFNT {
        return otf::woff2_from_ttf_with(ttf, &|bytes, quality| {
            let key = KeyBuilder::new("woff2 slice")
                .u64(quality.into())
                .bytes(bytes)
                .finish();
            reuse.data_or_make(
                key,
                |stream: &Vec<u8>| stream.clone(),
                |kept| otf::slice_holds(kept, bytes).then(|| kept.to_vec()),
                || otf::compress_slice(bytes, quality),
            )
        });
    }
    let key = KeyBuilder::new("woff2").bytes(ttf).finish();
    reuse.get_or_make(Path::new(name), key, || otf::woff2_from_ttf(ttf))
}

/// What the TTF, OTF and WOFF2 are built from: `font` with its overlaps removed, unless
/// `opts.keep_overlaps`. Unions made by the last build are taken from `reuse` when a
/// flavour needs them ([`Unions`]; `outlines`: `font`'s [`OutlineKeys`]).
struct ForOpenType<'a> {
    font: &'a OutlinedFont,
    unions: Option<Unions<'a>>,
    outlines: &'a OutlineKeys,
    reuse: &'a Reuse,
}

impl<'a> ForOpenType<'a> {
    fn new(
        font: &'a OutlinedFont,
        opts: &BuildOptions,
        reuse: &'a Reuse,
        outlines: &'a OutlineKeys,
    ) -> Self {
        let unions = (!opts.keep_overlaps).then(|| Unions::new(font, reuse, outlines));
        ForOpenType {
            font,
            unions,
            outlines,
            reuse,
        }
    }

    /// The outlines and their keys for [`otf::ttf_reusing_paths`] and
    /// [`otf::otf_reusing_paths`].
    fn paths(&self) -> (Option<&dyn otf::GlyphPaths>, &OutlineKeys) {
        match &self.unions {
            Some(unions) => (Some(unions), unions.keys()),
            None => (None, self.outlines),
        }
    }

    fn ttf(&self) -> Result<Vec<u8>, otf::OtfError> {
        let (paths, keys) = self.paths();
        otf::ttf_reusing_paths(self.font, paths, self.reuse, keys)
    }

    fn otf(&self) -> Result<Vec<u8>, otf::OtfError> {
        let (paths, keys) = self.paths();
        otf::otf_reusing_paths(self.font, paths, self.reuse, keys)
    }
}

/// The SVG font and the SVG glyph set (`svg/<glyph>.svg`).
pub fn svg_outputs(font: &OutlinedFont) -> Vec<OutputFile> {
    svg_outputs_reusing(font, &Reuse::off(), &OutlineKeys::default())
}

/// [`svg_outputs`], leaving out each glyph's SVG that OUT holds already as the last build
/// made it from the same glyph ([`Reuse::kept_or_make`]). The glyph files are made on
/// every core. `outlines`: `font`'s [`OutlineKeys`].
pub fn svg_outputs_reusing(
    font: &OutlinedFont,
    reuse: &Reuse,
    outlines: &OutlineKeys,
) -> Vec<OutputFile> {
    let (font_svg, glyphs) = rayon::join(
        || {
            // Each glyph's elements kept in the record, as the TTF's and CFF's glyphs are:
            // writing the path data of 20,000 glyphs was a twelfth of an edited build.
            svg_font_with(font, |i, g| {
                if !reuse.is_on() {
                    return glyph_elements(g);
                }
                let outline = outlines.get(i, &g.path);
                let key = KeyBuilder::new("svg font glyph")
                    .key(&glyph_key(g, &outline, false))
                    .finish();
                let kept = reuse.data_or_make(
                    key,
                    |s: &String| s.as_bytes().to_vec(),
                    |bytes| String::from_utf8(bytes.to_vec()).ok(),
                    || Ok::<_, Infallible>(glyph_elements(g)),
                );
                let Ok(elements) = kept;
                elements
            })
            .into_bytes()
        },
        || {
            let stems = file_stems(font.glyphs.iter().map(|g| g.name.as_str()));
            font.glyphs
                .par_iter()
                .zip(stems)
                .enumerate()
                .filter_map(|(i, (g, stem))| {
                    let path = Path::new("svg").join(format!("{stem}.svg"));
                    let key = svg_glyph_key(&font.info, g, &outlines.get(i, &g.path));
                    let make = || Ok::<_, Infallible>(glyph_svg(&font.info, g).into_bytes());
                    let Ok(bytes) = reuse.kept_or_make(&path, key, make);
                    bytes.map(|bytes| (path, bytes))
                })
                .collect::<Vec<_>>()
        },
    );
    let mut files = vec![(
        PathBuf::from(format!("{}.svg", output_stem(&font.info))),
        font_svg,
    )];
    files.extend(glyphs);
    files
}

/// Writes `files` (relative paths) under `out`, all or none ([`OutputSet`]).
pub fn write_outputs(out: &Path, files: &[OutputFile]) -> Result<(), PipelineError> {
    write_output_files(out, files.to_vec())
}

/// [`write_outputs`] taking the files, so that their bytes are not copied (a CJK font's
/// outputs are hundreds of megabytes).
pub fn write_output_files(out: &Path, files: Vec<OutputFile>) -> Result<(), PipelineError> {
    write_output_files_with(out, files, &Reuse::off())
}

/// [`write_output_files`] trusting the file stamps `reuse` holds from the last build (a
/// file not touched since is not read back: [`OutputSet::trusting`]), and giving it this
/// build's stamps to save.
pub fn write_output_files_with(
    out: &Path,
    files: Vec<OutputFile>,
    reuse: &Reuse,
) -> Result<(), PipelineError> {
    let mut set = OutputSet::new();
    for (path, bytes) in files {
        set.add(out.join(path), bytes);
    }
    let result = if reuse.is_on() {
        let kept = reuse.kept_paths().iter().map(|p| out.join(p)).collect();
        set.trusting(reuse.file_stamps())
            .keeping(kept)
            .commit_stamped()
            .map(|stamps| reuse.files_written(stamps))
    } else {
        set.commit()
    };
    result.map_err(|error| PipelineError::Write {
        dir: out.to_path_buf(),
        error,
    })
}

/// The numbers a build reports.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Glyphs in the font.
    pub glyphs: usize,
    /// Contours over all glyph outlines (components counted where placed).
    pub contours: usize,
    /// Segments (lines and cubics) over all glyph outlines.
    pub segments: usize,
    /// The glyph with the largest measured error, and that error (font units).
    pub worst: Option<(String, f64)>,
    /// The tolerance the outlines were fitted to.
    pub tolerance: f64,
}

impl Summary {
    /// The counts of `font`.
    pub fn new(font: &OutlinedFont) -> Self {
        let worst = font
            .glyphs
            .iter()
            .max_by(|a, b| a.max_error.total_cmp(&b.max_error))
            .map(|g| (g.name.clone(), g.max_error));
        Summary {
            glyphs: font.glyphs.len(),
            contours: font.glyphs.iter().map(|g| g.contours.len()).sum(),
            segments: font.glyphs.iter().map(|g| g.segments).sum(),
            worst,
            tolerance: font.tolerance,
        }
    }
}
