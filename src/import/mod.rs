//! Importers: existing outlines -> editable X-spline sources.
//!
//! ```text
//! webfont.rs (WOFF, WOFF2 unpacked) -> font.rs (ttf-parser) | svg.rs (usvg)  ->  original BezPath per glyph
//! ufo.rs (norad): X-splines from the lib when an xglyph export wrote them, else as above
//!   -> contour.rs (closed contours, corners, edges, smooth stretches)
//!   -> fit.rs (X-spline control points within the fit target)
//!   -> a model::Font (emitted by source::emit) and a report.rs summary
//!
//! variable.rs (skrifa: each master of a variable font) | designspace.rs (foreign UFOs)
//!   -> masters.rs (one X-spline structure per glyph for every master: contour.rs's
//!      compatible_contours, fit.rs's fit_compatible)
//!   -> a model::Family (font.toml axes, masters, instances; one folder per master)
//! ```
//!
//! Glyphs are fitted in parallel on rayon's pool, each on its own, so the output does not
//! depend on the thread count; [`Progress`] reports the count as they finish.
//!
//! Tolerance budget: with an import tolerance `T` (default 1/1000 em), coordinates are
//! rounded to a decimal grid of at most `T / 10` (a hundred times finer if the coarse grid
//! would break the bound), the fitter aims at [`IMPORT_SHARE`]` · T` less what that
//! rounding can cost (at most [`FIT_SHARE`]` · T`), and every rounded contour is
//! re-measured independently: it is accepted only within [`IMPORT_SHARE`]` · T`, else
//! fitted again tighter (more points), else written as a polyline of the original, else
//! dropped and counted in the report. The written `tolerance` (the build's Bézier fitting
//! tolerance) is [`BUILD_SHARE`]` · T`. So import followed by build stays within `T` of
//! the original (triangle inequality on the two-sided distance).

pub mod anchors;
pub mod contour;
pub mod designspace;
pub mod discrete;
pub mod fea;
pub mod fit;
pub mod font;
mod gsub;
pub mod kerning;
pub mod masters;
pub mod report;
mod rules;
pub mod svg;
pub mod ufo;
pub mod variable;
pub mod webfont;

pub use ufo::{import_ufo, import_ufo_layer, UfoLayer};

use std::collections::{BTreeMap, HashMap};
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use kurbo::BezPath;
use rayon::prelude::*;

use crate::model::{Contour, FeatureFile, Font, FontInfo, Glyph};
use crate::source::check_tolerance_flag;
use crate::xspline::{ControlPoint, XSpline};
use report::{GlyphReport, Report};

/// The most of the tolerance the fitter aims at (measured by sampling): less when the
/// import bound less the rounding's reach ([`grid_for`]) is less. Aiming higher (up to
/// that reach, 0.68 T at 1/1000 em) saves a few points (3281 against 3285 on the 64 CJK
/// glyphs) but lets one interior point replace two where a line meets a curve, and the
/// X-spline then turns by up to 5° at joins the original has smooth (DejaVu `y`).
pub const FIT_SHARE: f64 = 0.65;
/// The share the rounded, re-measured contours must stay within.
pub const IMPORT_SHARE: f64 = 0.75;
/// The share written as the font's build tolerance.
pub const BUILD_SHARE: f64 = 0.25;

/// An import failure: the file (when there is one) and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportError {
    /// The input file at fault, if one is.
    pub path: Option<PathBuf>,
    /// What is wrong.
    pub message: String,
}

impl ImportError {
    /// An error about no file in particular.
    pub fn plain(message: impl Into<String>) -> Self {
        ImportError {
            path: None,
            message: message.into(),
        }
    }

    /// An error about the input file `path`.
    pub fn at(path: &Path, message: impl Into<String>) -> Self {
        ImportError {
            path: Some(path.to_path_buf()),
            message: message.into(),
        }
    }
}

impl fmt::Display for ImportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.path {
            Some(p) => write!(f, "{}: {}", p.display(), self.message),
            None => f.write_str(&self.message),
        }
    }
}

impl std::error::Error for ImportError {}

/// One original glyph: name, code points, advance and outline in font units (y up).
#[derive(Clone, Debug)]
pub struct SourceGlyph {
    /// Glyph name.
    pub name: String,
    /// Code points mapped to it.
    pub unicodes: Vec<char>,
    /// Advance, font units.
    pub advance: f64,
    /// The original outline, font units, y up.
    pub path: BezPath,
}

/// A callback told `(fitted, total)` glyph counts as fitting proceeds, from any thread,
/// in no particular order of glyphs (the counts only grow). The library never prints;
/// the command shows these on a terminal.
#[derive(Clone, Default)]
pub struct Progress(pub Option<Arc<dyn Fn(usize, usize) + Send + Sync>>);

impl fmt::Debug for Progress {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(if self.0.is_some() {
            "Progress(..)"
        } else {
            "Progress(None)"
        })
    }
}

/// Settings shared by both importers.
#[derive(Clone, Debug, Default)]
pub struct ImportOptions {
    /// Fonts: which font of a collection (.ttc, .otc); 0 for a single font.
    pub face: u32,
    /// Told the glyph counts while fitting.
    pub progress: Progress,
    /// Characters to import from a font, with the glyphs the features shaping applies
    /// unasked reach from them (`None`: every mapped character, and every glyph any
    /// feature reaches).
    pub glyphs: Option<Vec<char>>,
    /// Import tolerance `T` in font units (`None`: 1/1000 of the em).
    pub tolerance: Option<f64>,
    /// Family name instead of the font's own (SVG default: "Imported Icons").
    pub family: Option<String>,
    /// SVG: code point per glyph name (file stem).
    pub codepoints: BTreeMap<String, char>,
    /// SVG: first code point for files not in `codepoints` (default U+E000, private use).
    pub first_codepoint: Option<char>,
    /// SVG: units per em of the new font (default 1000).
    pub units_per_em: Option<u16>,
    /// Designspace: the discrete location to import, `--at`'s `TAG=VALUE[,…]` in user
    /// values (`None`: every discrete axis at its default; [`discrete`]).
    pub at: Option<String>,
}

/// A finished import: the font model to emit and the report to print.
#[derive(Clone, Debug)]
pub struct Imported {
    /// The fitted font model.
    pub font: Font,
    /// Points and errors per glyph.
    pub report: Report,
    /// The original outline of each glyph fitted from its outline (not taken from an
    /// xglyph lib), by name: what a compatible refit across masters starts from
    /// ([`designspace`]). Filled by the UFO import only.
    pub outlines: BTreeMap<String, SourceGlyph>,
}

/// Imports a TrueType/OpenType font from its bytes (`path` names it in messages).
pub fn import_font(
    path: &Path,
    data: &[u8],
    opts: &ImportOptions,
) -> Result<Imported, ImportError> {
    let skrifa_font = skrifa::FontRef::from_index(data, opts.face).ok();
    // The glyphs the substitutions reach (ligatures, alternates) come in with the mapped:
    // through every feature for the whole font, through those shaping applies unasked for
    // a character subset.
    let features = opts.glyphs.as_ref().map(|_| gsub::SHAPING_FEATURES);
    let source = font::read_font(path, data, opts.face, opts.glyphs.as_deref(), |mapped| {
        skrifa_font
            .as_ref()
            .map_or_else(Vec::new, |f| gsub::reachable(f, mapped, features))
    })?;
    if source.glyphs.is_empty() {
        return Err(ImportError::at(
            path,
            "none of the requested characters has a glyph in this font",
        ));
    }
    let tolerance = check_tolerance(opts.tolerance, source.info.units_per_em)?;
    let source_notes = source.notes();
    // Read before the glyphs are fitted: a damaged GPOS fails at once.
    let kerning = read_font_kerning(path, data, opts.face, &source, &[&[]])?;
    let anchors = read_font_anchors(path, data, opts.face, &source)?;
    let substitutions = read_font_gsub(path, data, opts.face, &source, &[])?;
    let info = FontInfo {
        family: opts.family.clone().unwrap_or(source.info.family),
        tolerance: BUILD_SHARE * tolerance,
        ..source.info
    };
    let mut imported = import_glyphs(&source.glyphs, info, tolerance, &opts.progress, &|_| {
        Some(path)
    })?;
    imported.font.kerning = kerning.pairs.into_iter().next().unwrap_or_default();
    imported.report.notes.extend(kerning.note);
    imported.font.features = substitutions.features;
    imported.report.notes.extend(substitutions.note);
    imported
        .report
        .notes
        .extend(gpos_unread_note(data, opts.face));
    anchors.give(imported.font.glyphs.iter_mut());
    imported.report.notes.extend(anchors.note);
    imported
        .report
        .notes
        .extend(anchors::outline_marks_note(&imported.font.glyphs));
    imported.report.notes.extend(source_notes);
    Ok(imported)
}

/// The GPOS features the import reads: kerning ([`kerning`]) and mark attachment
/// ([`anchors`]).
const GPOS_READ: [&str; 3] = ["kern", "mark", "mkmk"];

/// A note naming the font's GPOS features that the import does not read, such as `cpsp`,
/// `dist`, `abvm` or `curs` (their positions are not in the sources, so the built font
/// lacks them); none when the font has no others. A damaged table gives no note: the
/// kerning and anchor readers report it.
pub(crate) fn gpos_unread_note(data: &[u8], face: u32) -> Option<String> {
    use skrifa::raw::TableProvider;
    let font = skrifa::FontRef::from_index(data, face).ok()?;
    let features = font.gpos().ok()?.feature_list().ok()?;
    let mut tags: Vec<String> = features
        .feature_records()
        .iter()
        .map(|r| r.feature_tag().to_string())
        .filter(|tag| !GPOS_READ.contains(&tag.as_str()))
        .map(|tag| format!("`{tag}`"))
        .collect();
    tags.sort();
    tags.dedup();
    (!tags.is_empty()).then(|| {
        format!(
            "GPOS feature(s) not imported: {} (xglyph reads `kern`, `mark` and `mkmk`); \
             the built font does not position glyphs by them",
            tags.join(", ")
        )
    })
}

/// What [`read_font_kerning`] gives: pairs per location and a note on what it left out.
pub(crate) struct FontKerning {
    pairs: Vec<Vec<crate::model::KernPair>>,
    note: Option<String>,
}

/// The `kern` feature's pairs among the imported glyphs ([`kerning`]) at each of
/// `locations`; a damaged `GPOS` is an error naming the file.
pub(crate) fn read_font_kerning(
    path: &Path,
    data: &[u8],
    face: u32,
    source: &font::SourceFont,
    locations: &[&[skrifa::raw::types::F2Dot14]],
) -> Result<FontKerning, ImportError> {
    let font = skrifa::FontRef::from_index(data, face)
        .map_err(|e| ImportError::at(path, format!("not a readable font ({e})")))?;
    let glyphs: Vec<kerning::KernGlyph> = source
        .ids
        .iter()
        .zip(&source.glyphs)
        .map(|(&id, g)| kerning::KernGlyph {
            id,
            name: &g.name,
            unicodes: &g.unicodes,
        })
        .collect();
    let read = kerning::read_kerning(&font, &glyphs, locations).map_err(
        |kerning::DamagedTable(table, e)| {
            ImportError::at(path, format!("damaged {table} table: {e}"))
        },
    )?;
    let note = match read.legacy {
        Some(0) => None,
        Some(subtables) => Some(format!(
            "{subtables} subtable(s) of the legacy `kern` table left out: vertical, \
             cross-stream, minimum or Apple formats, which xglyph kerning (the first glyph's \
             advance) does not hold"
        )),
        None => (read.skipped > 0).then(|| {
            format!(
                "{} kerning pair(s) left out: they place glyphs or move the second glyph, \
                 which xglyph kerning (the first glyph's advance) cannot hold",
                read.skipped
            )
        }),
    };
    Ok(FontKerning {
        pairs: read.pairs,
        note,
    })
}

/// What [`read_font_gsub`] gives: the font's substitutions as `features.fea`, and a note.
pub(crate) struct FontSubstitutions {
    pub(crate) features: Option<FeatureFile>,
    pub(crate) note: Option<String>,
}

/// The font's GSUB as feature code over the imported glyphs ([`gsub`]), without the
/// features in `skip`; a damaged GSUB is an error naming the file. Feature code fea-rs
/// refuses (which would stop every build) is left out with a note instead.
pub(crate) fn read_font_gsub(
    path: &Path,
    data: &[u8],
    face: u32,
    source: &font::SourceFont,
    skip: &[&str],
) -> Result<FontSubstitutions, ImportError> {
    let font = skrifa::FontRef::from_index(data, face)
        .map_err(|e| ImportError::at(path, format!("not a readable font ({e})")))?;
    let names: HashMap<u16, String> = source
        .ids
        .iter()
        .zip(&source.glyphs)
        .map(|(&id, g)| (id, g.name.clone()))
        .collect();
    let read = gsub::read_gsub(&font, &names, skip)
        .map_err(|e| ImportError::at(path, format!("damaged GSUB table: {e}")))?;
    let Some(text) = read.text else {
        return Ok(FontSubstitutions {
            features: None,
            note: read.note,
        });
    };
    let features = FeatureFile {
        path: PathBuf::from("features.fea"),
        text,
    };
    // `check_features` puts `.notdef` first itself.
    let glyph_names: Vec<&str> = source.glyphs.iter().map(|g| g.name.as_str()).collect();
    let refused = crate::otf::check_features(&features, &glyph_names)
        .into_iter()
        .find(|d| d.severity == crate::source::Severity::Error);
    if let Some(d) = refused {
        let note = format!(
            "GSUB left out: its feature code does not compile ({}); please report this font",
            d.message
        );
        return Ok(FontSubstitutions {
            features: None,
            note: Some(note),
        });
    }
    Ok(FontSubstitutions {
        features: Some(features),
        note: read.note,
    })
}

/// What [`read_font_anchors`] gives: each glyph's anchors by name, the names of the
/// glyphs `GDEF` classes as marks, and a note on what it left out.
pub(crate) struct FontAnchors {
    by_name: HashMap<String, Vec<crate::model::Anchor>>,
    gdef_marks: std::collections::HashSet<String>,
    note: Option<String>,
}

impl FontAnchors {
    /// Sets the anchors of each glyph that has some, by name, and `mark = "outline"` on
    /// each mark that then has no `_` anchor ([`anchors::placed_by_outline`]).
    pub(crate) fn give<'a>(&self, glyphs: impl Iterator<Item = &'a mut crate::model::Glyph>) {
        for glyph in glyphs {
            if let Some(a) = self.by_name.get(&glyph.name) {
                glyph.anchors = a.clone();
            }
            let in_gdef = self.gdef_marks.contains(&glyph.name);
            glyph.outline_mark = anchors::placed_by_outline(glyph, in_gdef);
        }
    }
}

/// The mark attachment of the `mark` and `mkmk` features as named anchors of the imported
/// glyphs, and `GDEF`'s marks among them ([`anchors`]); a damaged `GPOS` or `GDEF` is an
/// error naming the file.
pub(crate) fn read_font_anchors(
    path: &Path,
    data: &[u8],
    face: u32,
    source: &font::SourceFont,
) -> Result<FontAnchors, ImportError> {
    let font = skrifa::FontRef::from_index(data, face)
        .map_err(|e| ImportError::at(path, format!("not a readable font ({e})")))?;
    let read = anchors::read_anchors(&font, &source.ids, source.info.units_per_em)
        .map_err(|e| ImportError::at(path, format!("damaged GPOS table: {e}")))?;
    let by_name = source
        .ids
        .iter()
        .zip(&source.glyphs)
        .filter_map(|(id, g)| Some((g.name.clone(), read.by_glyph.get(id)?.clone())))
        .collect();
    let marks = anchors::gdef_marks(&font, &source.ids)
        .map_err(|e| ImportError::at(path, format!("damaged GDEF table: {e}")))?;
    let gdef_marks = source
        .ids
        .iter()
        .zip(&source.glyphs)
        .filter(|(id, _)| marks.contains(id))
        .map(|(_, g)| g.name.clone())
        .collect();
    let note = (read.ligature_subtables > 0).then(|| {
        format!(
            "{} mark-to-ligature subtable(s) left out: xglyph has no ligature anchors",
            read.ligature_subtables
        )
    });
    Ok(FontAnchors {
        by_name,
        gdef_marks,
        note,
    })
}

/// Imports SVG drawings, one glyph per file: `(path, bytes)` in the order given.
pub fn import_svgs(
    files: &[(PathBuf, Vec<u8>)],
    opts: &ImportOptions,
) -> Result<Imported, ImportError> {
    let upm = opts.units_per_em.unwrap_or(1000);
    if !(16..=16384).contains(&upm) {
        return Err(ImportError::plain(format!(
            "--units-per-em {upm} is outside 16..16384"
        )));
    }
    let tolerance = check_tolerance(opts.tolerance, upm)?;
    let em = f64::from(upm);
    let em_box = svg::EmBox {
        ascender: 0.8 * em,
        descender: -0.2 * em,
    };
    let mut next_cp = u32::from(opts.first_codepoint.unwrap_or('\u{E000}'));
    let mut taken: std::collections::BTreeSet<char> = opts.codepoints.values().copied().collect();
    let mut glyphs = Vec::new();
    let mut names = std::collections::BTreeSet::new();
    let mut stems = std::collections::BTreeSet::new();
    let mut notes = Vec::new();
    let mut files_by_name: BTreeMap<String, &Path> = BTreeMap::new();
    for (path, data) in files {
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .filter(|s| !s.is_empty())
            .ok_or_else(|| ImportError::at(path, "cannot take a glyph name from this file name"))?;
        // The glyph-name rule of the sources: `arrow-left.svg` becomes `arrow_left`.
        let name = crate::names::glyph_name_from(&stem);
        if !names.insert(name.clone()) {
            return Err(ImportError::at(
                path,
                format!("two drawings would both become glyph `{name}`; rename one file"),
            ));
        }
        stems.insert(stem.clone());
        files_by_name.insert(name.clone(), path.as_path());
        let drawing = svg::read_svg(path, data, em_box)?;
        if drawing.outside > 0 {
            notes.push(format!(
                "{}: {} path(s) wholly outside the canvas left out (no viewer shows them)",
                path.display(),
                drawing.outside
            ));
        }
        let cp = match opts.codepoints.get(&stem) {
            Some(&c) => c,
            None => loop {
                let c = char::from_u32(next_cp).ok_or_else(|| {
                    ImportError::plain(format!("ran out of code points at U+{next_cp:04X}"))
                })?;
                next_cp += 1;
                if taken.insert(c) {
                    break c;
                }
            },
        };
        glyphs.push(SourceGlyph {
            name,
            unicodes: vec![cp],
            advance: drawing.advance,
            path: drawing.path,
        });
    }
    for name in opts.codepoints.keys() {
        if !stems.contains(name) {
            return Err(ImportError::plain(format!(
                "the code point map names `{name}`, but no drawing has that file name"
            )));
        }
    }
    let family = opts.family.clone();
    let info = FontInfo {
        ascender: em_box.ascender,
        descender: em_box.descender,
        tolerance: BUILD_SHARE * tolerance,
        ..FontInfo::with_em(family.unwrap_or_else(|| "Imported Icons".to_string()), upm)
    };
    let origin = |name: &str| files_by_name.get(name).copied();
    let mut imported = import_glyphs(&glyphs, info, tolerance, &opts.progress, &origin)?;
    imported.report.notes.extend(notes);
    Ok(imported)
}

pub(crate) fn check_tolerance(tolerance: Option<f64>, upm: u16) -> Result<f64, ImportError> {
    check_tolerance_flag(tolerance.unwrap_or(f64::from(upm) / 1000.0)).map_err(ImportError::plain)
}

/// Fits every glyph, in parallel on rayon's pool (each glyph alone, so the result does
/// not depend on the thread count); glyphs sorted by name in the model, the report in
/// the same order. `origin` names the file a glyph came from, for messages.
fn import_glyphs<'p>(
    sources: &[SourceGlyph],
    info: FontInfo,
    tolerance: f64,
    progress: &Progress,
    origin: &dyn Fn(&str) -> Option<&'p Path>,
) -> Result<Imported, ImportError> {
    let grid = grid_for(tolerance);
    let done = AtomicUsize::new(0);
    let mut fitted: Vec<FittedGlyph> = sources
        .par_iter()
        .map(|g| {
            let fitted = import_glyph(g, tolerance, grid);
            if let Some(tell) = &progress.0 {
                tell(done.fetch_add(1, Ordering::Relaxed) + 1, sources.len());
            }
            fitted
        })
        .collect();
    fitted.sort_by(|a, b| crate::model::glyph_order(&a.glyph.name, &b.glyph.name));
    for f in &fitted {
        check_fitted_limits(&f.glyph).map_err(|e| match origin(&f.glyph.name) {
            Some(path) => ImportError::at(path, e.message),
            None => e,
        })?;
    }
    let (glyphs, rows): (Vec<Glyph>, Vec<GlyphReport>) =
        fitted.into_iter().map(|f| (f.glyph, f.report)).unzip();
    Ok(Imported {
        font: Font {
            info,
            glyphs,
            kerning: Vec::new(),
            features: None,
        },
        report: Report {
            rows,
            tolerance,
            notes: Vec::new(),
        },
        outlines: BTreeMap::new(),
    })
}

/// Refuses a glyph whose fitted X-spline the sources could not hold
/// ([`crate::source::limits`]): a smooth control point sits outside the curve it shapes, so
/// an outline inside the limits can still need a point beyond them, and a drawing far
/// outside its viewBox scales past them (found by the `import_svg` fuzz target).
pub(crate) fn check_fitted_limits(glyph: &Glyph) -> Result<(), ImportError> {
    use crate::source::limits::MAX_COORDINATE;
    let far = glyph
        .contours
        .iter()
        .flat_map(|c| c.points())
        .flat_map(|p| [p.pos.x, p.pos.y])
        .find(|v| v.abs() > MAX_COORDINATE);
    match far {
        Some(v) => Err(ImportError::plain(format!(
            "glyph `{}` needs a control point at {v}, outside the -{MAX_COORDINATE}..{MAX_COORDINATE} \
             font units xglyph sources hold; scale the drawing down",
            glyph.name
        ))),
        None => Ok(()),
    }
}

/// The decimal rounding grid for written coordinates: the largest power of ten not above
/// `tolerance / 10` (0.1 for a 1000 or 2048 em at the default tolerance).
pub fn grid_for(tolerance: f64) -> f64 {
    10f64.powf((tolerance / 10.0).log10().floor())
}

pub(crate) fn round_to(x: f64, grid: f64) -> f64 {
    // Dividing by the integer 1/grid (not multiplying by grid) gives the shortest decimal.
    let inv = (1.0 / grid).round();
    if inv >= 1.0 {
        (x * inv).round() / inv + 0.0
    } else {
        (x / grid).round() * grid + 0.0
    }
}

/// One imported glyph and its report row.
#[derive(Clone, Debug)]
pub struct FittedGlyph {
    /// The glyph with its X-spline contours.
    pub glyph: Glyph,
    /// Its report row.
    pub report: GlyphReport,
}

/// Fits one glyph: its X-spline contours and its report row.
pub fn import_glyph(source: &SourceGlyph, tolerance: f64, grid: f64) -> FittedGlyph {
    let mut contours = Vec::new();
    let mut row = GlyphReport {
        name: source.name.clone(),
        original_points: 0,
        xspline_points: 0,
        max_error: 0.0,
        dropped_contours: 0,
    };
    for original in contour::contours(&source.path) {
        row.original_points += contour::stored_points(&original.segs);
        let Some(Measured { spline, error }) = import_contour(&original, tolerance, grid) else {
            row.dropped_contours += 1;
            continue;
        };
        row.max_error = row.max_error.max(error);
        row.xspline_points += spline.points().len();
        contours.push(Contour::from(spline));
    }
    let glyph = Glyph {
        name: source.name.clone(),
        unicodes: source.unicodes.clone(),
        advance: round_to(source.advance, grid),
        contours,
        components: Vec::new(),
        anchors: Vec::new(),
        outline_mark: false,
    };
    FittedGlyph { glyph, report: row }
}

/// Fit targets tried after the first (see [`import_contour`]), as shares of the tolerance,
/// when a fit's rounded contour measures above the bound: a tighter target buys more
/// points. The fitter measures by sampling, so a fit can pass its own measure and still
/// miss (each retry is a guard; on the 2,000 CJK glyphs U+4E00–U+55CF no glyph is over).
pub(crate) const RETRY_SHARES: [f64; 2] = [0.4, 0.2];

/// The first fit target: the bound less the most that rounding to `grid` can move a curve
/// point (half the grid cell's diagonal: the fitter's shapes are all in 0..1, whose
/// blending weights are non-negative and sum to one), at most [`FIT_SHARE`]` · T`.
pub(crate) fn first_target(tolerance: f64, grid: f64) -> f64 {
    (IMPORT_SHARE * tolerance - grid * std::f64::consts::FRAC_1_SQRT_2).min(FIT_SHARE * tolerance)
}

/// Fits one original contour and rounds it, and measures the result independently
/// ([`fit::contour_error`]): the first candidate within `IMPORT_SHARE · tolerance` is
/// returned, so nothing over the bound is ever accepted. Candidates, in order: the fit at
/// [`first_target`], then at each of [`RETRY_SHARES`], each rounded to `grid`, then to a grid a hundred times finer
/// (rounding can flatten a sliver into a spike the loader refuses); last, the original
/// flattened into a polyline of sharp points ([`fit::polyline_xspline`]). `None` when the
/// contour encloses nothing or no candidate holds (the caller drops and counts it).
fn import_contour(
    original: &contour::SourceContour,
    tolerance: f64,
    grid: f64,
) -> Option<Measured> {
    let bound = IMPORT_SHARE * tolerance;
    let cut = contour::cut(original);
    let measure = |points: &[ControlPoint]| {
        [grid, grid / 100.0].iter().find_map(|&g| {
            let spline = rounded(points, g)?;
            let error = fit::contour_error(&spline, &original.segs);
            (error <= bound).then_some(Measured { spline, error })
        })
    };
    let targets = std::iter::once(first_target(tolerance, grid))
        .chain(RETRY_SHARES.iter().map(|share| share * tolerance));
    for (k, target) in targets.enumerate() {
        match fit::fit_xspline(&cut, target) {
            Some(fitted) => {
                if let Some(measured) = measure(&fitted.points) {
                    return Some(measured);
                }
            }
            // Fewer than three points: the contour encloses nothing.
            None if k == 0 => return None,
            None => {}
        }
    }
    measure(&fit::polyline_xspline(&original.segs, 0.5 * bound))
}

/// A rounded contour and its independently measured error.
struct Measured {
    spline: XSpline,
    error: f64,
}

/// Rounds positions to `grid`, drops a point that then coincides with the one before it
/// (keeping sharp points), and validates the result. A contour that then encloses no area
/// (a sliver of the original flattened into a spike) is refused as the loader would refuse
/// it, so that every imported folder loads: the caller tries a finer grid, then drops it.
fn rounded(points: &[ControlPoint], grid: f64) -> Option<XSpline> {
    let mut out: Vec<ControlPoint> = points
        .iter()
        .map(|p| ControlPoint::new(round_to(p.pos.x, grid), round_to(p.pos.y, grid), p.s))
        .collect();
    let mut i = 0;
    while out.len() >= 3 && i < out.len() {
        let j = (i + 1) % out.len();
        if out[i].pos == out[j].pos {
            let drop = if out[j].is_sharp() { i } else { j };
            out.remove(drop);
        } else {
            i += 1;
        }
    }
    XSpline::new(out)
        .ok()
        .filter(|spline| crate::source::no_area(spline).is_none())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_contour_rounded_into_a_spike_is_refused() {
        // Out and back along itself once on the grid: the loader would refuse it ("encloses
        // no area"), so the importer must not write it.
        let p = |x: f64, y: f64| ControlPoint::new(x, y, 0.0);
        let spike = [p(0.0, 0.0), p(100.0, 0.0), p(100.0, 100.0), p(100.0, 0.2)];
        assert!(rounded(&spike, 1.0).is_none());
        // The same points on a fine grid keep a sliver of area and are kept.
        assert_eq!(rounded(&spike, 0.01).map(|s| s.points().len()), Some(4));
    }

    #[test]
    fn grid_and_rounding() {
        assert_eq!(grid_for(2.048), 0.1);
        assert_eq!(grid_for(1.0), 0.1);
        assert_eq!(grid_for(0.05), 0.001);
        assert_eq!(grid_for(40.0), 1.0);
        assert_eq!(round_to(280.34, 0.1), 280.3);
        assert_eq!(
            crate::source::emit::number(round_to(1030.7149, 0.1)),
            "1030.7"
        );
        assert_eq!(round_to(-0.04, 0.1).to_bits(), 0.0f64.to_bits());
        assert_eq!(round_to(1234.0, 10.0), 1230.0);
    }
}
