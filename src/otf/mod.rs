//! TTF and OTF export: the fitted outlines as installable OpenType fonts.
//!
//! Both read the outlined font only ([`OutlinedFont`]) and share one glyph order (its
//! order, which has `.notdef` first, with the [`notdef_box`] put first when the font has
//! none), one set of PostScript glyph names and the tables built in `tables.rs` (one module
//! per table); they differ only in the outline table:
//!
//! - TTF: `glyf`/`loca` with the cubics converted to quadratic splines within the font's
//!   tolerance (`quadratic.rs`), points on the integer grid, outer contours clockwise.
//! - OTF: a `CFF ` table (`cff.rs`, `charstring.rs`) holding the cubics exactly, points
//!   rounded to the integer grid, outer contours counter-clockwise.
//!
//! Rounding a control point moves it at most √2/2 font units, and a Bézier curve is a
//! convex combination of its control points, so grid rounding moves any outline point by at
//! most √2/2 ≈ 0.71 units on top of the quadratic conversion (TTF only). Three rules may
//! move a point up to a unit, and keep the outline within [`PULLED`] (one unit): an
//! off-curve point moved to keep a monotone curve monotone, so that rounding makes no
//! extreme without a point (both, `monotone.rs`), a cubic's handle kept a unit off its end
//! point (CFF, `grid.rs`), and a point moved to keep a narrow notch's sides in order (both,
//! `spike.rs`).
//!
//! The WOFF2 (`woff2.rs`) is the TTF compressed for the web.
//!
//! The variable TTF ([`variable_ttf`], `variable/`) reads an [`OutlinedFamily`]
//! (`crate::family`): the default master through the same tables as the static TTF, plus
//! `gvar`, `HVAR`, `fvar`, `STAT` and kerning with variations (GPOS + GDEF).
//!
//! [`OutlinedFamily`]: crate::family::OutlinedFamily
//!
//! Layout (`features.rs`): the font's `features.fea` compiled by fea-rs with the
//! generated `kern`, `mark` and `mkmk` features and GDEF classes, in GSUB, GPOS and GDEF;
//! the TTF also has a legacy `kern` table (`kern.rs`). Components are already resolved into the outlines; no
//! composite glyphs.

mod cff;
mod charstring;
mod cmap;
mod features;
mod gasp;
mod glyph_names;
mod grid;
mod head;
mod hmtx;
mod kern;
mod maxp;
mod monotone;
mod naming;
mod os2;
mod post;
mod prep;
mod quadratic;
mod specimen;
mod spike;
mod tables;
mod truetype;
mod variable;
mod woff2;
pub use woff2::{compress_slice, slice_holds, CompressSlice, LARGE_SFNT};

use std::borrow::Cow;
use std::collections::BTreeMap;

use kurbo::BezPath;
use rayon::prelude::*;

use crate::outline::{notdef_box, OutlinedFont, OutlinedGlyph};
use crate::reuse::{outline_key, Key, OutlineKeys, Reuse};

pub use features::check_features;
/// How far the CFF outlines may be from the exact ones (rounding, and a pulled handle).
pub use grid::PULLED;
pub use specimen::{specimen_html, specimen_html_sources, specimen_text, KERN_ROWS};
pub use variable::{variable_ttf, variable_ttf_explicit_deltas, variable_ttf_with_anchors};

/// Something the model holds that an OpenType font cannot.
#[derive(Debug)]
pub enum OtfError {
    /// More glyphs than the 65 535 an OpenType font can address.
    TooManyGlyphs(usize),
    /// A coordinate, advance or metric outside the signed 16-bit range of the tables.
    OutOfRange {
        /// What the value is, e.g. `advance of 'A'`.
        what: String,
        /// The value.
        value: f64,
        /// The range it must be in, e.g. `-32768..=32767`.
        range: &'static str,
    },
    /// Two glyphs mapped to one code point.
    CmapConflict(String),
    /// write-fonts rejected a table.
    Table(String),
    /// `features.fea` has errors, each at its file:line:col.
    Features(Vec<crate::source::Diagnostic>),
}

impl std::fmt::Display for OtfError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OtfError::TooManyGlyphs(n) => {
                write!(f, "{n} glyphs: an OpenType font holds at most 65535")
            }
            OtfError::OutOfRange { what, value, range } => {
                write!(f, "{what} is {value}, outside the OpenType range {range}")
            }
            OtfError::CmapConflict(msg) => write!(f, "cmap: {msg}"),
            OtfError::Table(msg) => write!(f, "{msg}"),
            OtfError::Features(diags) => {
                let lines: Vec<String> = diags.iter().map(ToString::to_string).collect();
                write!(f, "{}", lines.join("\n"))
            }
        }
    }
}

impl std::error::Error for OtfError {}

/// One glyph as both flavours see it: final name, code points, advance and outline (the
/// outlined font's, borrowed: a CJK font's outlines are 130 MB, and the TTF and the OTF
/// are made at once).
#[derive(Clone, Debug)]
pub(crate) struct OtGlyph<'a> {
    /// The model's name (used for kerning lookups).
    pub model_name: String,
    /// The PostScript name written into `post` / the CFF charset.
    pub ps_name: String,
    pub unicodes: Vec<char>,
    /// Advance in font units, on the grid.
    pub advance: u16,
    /// y-up outline, outer contours counter-clockwise, not yet rounded ([`OtGlyph::path`]).
    pub path: OtPath<'a>,
    /// The outline includes resolved components, whose contours may overlap.
    pub from_components: bool,
    /// Anchors, the components' included (mark positioning, see `features.rs`).
    pub anchors: Vec<crate::model::Anchor>,
    /// A mark its outline places (GDEF class Mark without anchors).
    pub outline_mark: bool,
}

/// Where an [`OtGlyph`]'s outline is: given, or made by a [`GlyphPaths`] when a flavour
/// has to convert it (most glyphs of a rebuild come from the record by key, and their
/// outlines are then never needed).
#[derive(Clone)]
pub(crate) enum OtPath<'a> {
    /// The outline itself.
    Given(Cow<'a, BezPath>),
    /// The outline of the font's glyph at this index, asked of `paths` when used.
    Later(&'a dyn GlyphPaths, usize),
}

impl std::fmt::Debug for OtPath<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OtPath::Given(path) => f.debug_tuple("Given").field(path).finish(),
            OtPath::Later(_, index) => f.debug_tuple("Later").field(index).finish(),
        }
    }
}

/// The outlines of a font's glyphs, by index, made or decoded when asked (e.g. each glyph's
/// union of overlaps, [`crate::overlap::Unions`]).
pub trait GlyphPaths: Sync {
    /// The outline of the glyph at `index`.
    fn path(&self, index: usize) -> Cow<'_, BezPath>;
}

impl OtGlyph<'_> {
    /// The outline (asked of its [`GlyphPaths`] now if it was not given).
    pub fn path(&self) -> Cow<'_, BezPath> {
        match &self.path {
            OtPath::Given(path) => Cow::Borrowed(path.as_ref()),
            OtPath::Later(paths, index) => paths.path(*index),
        }
    }
}

/// The glyph order shared by both flavours.
pub(crate) struct GlyphSet<'a> {
    pub glyphs: Vec<OtGlyph<'a>>,
    /// Model name -> glyph id.
    ids: BTreeMap<String, u16>,
}

impl<'a> GlyphSet<'a> {
    /// The outlined font's glyphs in its order, after the [`notdef_box`] when the font
    /// has no `.notdef`.
    pub fn new(font: &'a OutlinedFont) -> Result<Self, OtfError> {
        GlyphSet::with_paths(font, None)
    }

    /// [`GlyphSet::new`], each glyph's outline asked of `paths` when used instead of taken
    /// from `font` (whose glyphs' other fields are used).
    pub fn with_paths(
        font: &'a OutlinedFont,
        paths: Option<&'a dyn GlyphPaths>,
    ) -> Result<Self, OtfError> {
        let notdef = (!font.has_notdef()).then(|| notdef_box(&font.info));
        let count = font.glyphs.len() + usize::from(notdef.is_some());
        if count > usize::from(u16::MAX) {
            return Err(OtfError::TooManyGlyphs(count));
        }
        // The synthesised `.notdef` owns its outline; the font's glyphs lend theirs.
        let notdef = notdef.map(|g| OtGlyph::new(&g, OtPath::Given(Cow::Owned(g.path.clone()))));
        // On every core; the first error in glyph order.
        let each: Vec<Result<OtGlyph<'a>, OtfError>> = font
            .glyphs
            .par_iter()
            .enumerate()
            .map(|(i, g)| {
                let path = match paths {
                    Some(paths) => OtPath::Later(paths, i),
                    None => OtPath::Given(Cow::Borrowed(&g.path)),
                };
                OtGlyph::new(g, path)
            })
            .collect();
        let mut glyphs = notdef
            .into_iter()
            .chain(each)
            .collect::<Result<Vec<_>, _>>()?;
        let names = glyph_names::ps_names(&glyphs);
        for (glyph, name) in glyphs.iter_mut().zip(names) {
            glyph.ps_name = name;
        }
        // At most 65535 glyphs (checked above), so every index fits.
        let ids = glyphs
            .iter()
            .enumerate()
            .map(|(i, g)| (g.model_name.clone(), i as u16))
            .collect();
        Ok(GlyphSet { glyphs, ids })
    }

    /// Glyph id of the glyph with this model name.
    pub fn gid(&self, model_name: &str) -> Option<u16> {
        self.ids.get(model_name).copied()
    }
}

impl<'a> OtGlyph<'a> {
    /// The glyph with its advance on the grid and outline `path`; the PostScript name comes
    /// later.
    fn new(glyph: &OutlinedGlyph, path: OtPath<'a>) -> Result<Self, OtfError> {
        let advance = grid::to_u16(glyph.advance, || format!("advance of '{}'", glyph.name))?;
        Ok(OtGlyph {
            model_name: glyph.name.clone(),
            ps_name: String::new(),
            unicodes: glyph.unicodes.clone(),
            advance,
            path,
            from_components: !glyph.components.is_empty(),
            anchors: glyph.placed_anchors.clone(),
            outline_mark: glyph.outline_mark,
        })
    }
}

/// The font as TrueType (`glyf` outlines, quadratic splines on the integer grid).
pub fn ttf(font: &OutlinedFont) -> Result<Vec<u8>, OtfError> {
    ttf_reusing(font, &Reuse::off(), &OutlineKeys::default())
}

/// [`ttf`], taking each glyph's `glyf` bytes from the last build when it converted
/// the same outline ([`Reuse::data_or_make`]): a rebuild after one edit converts one glyph.
/// `outlines` are `font`'s [`OutlineKeys`] (keys that determine each glyph's path).
pub fn ttf_reusing(
    font: &OutlinedFont,
    reuse: &Reuse,
    outlines: &OutlineKeys,
) -> Result<Vec<u8>, OtfError> {
    ttf_reusing_paths(font, None, reuse, outlines)
}

/// [`ttf_reusing`], each glyph's outline asked of `paths` (when given) instead of taken
/// from `font`, and only when its `glyf` bytes are not in the record; `outlines` are then
/// keys that determine those outlines.
pub fn ttf_reusing_paths(
    font: &OutlinedFont,
    paths: Option<&dyn GlyphPaths>,
    reuse: &Reuse,
    outlines: &OutlineKeys,
) -> Result<Vec<u8>, OtfError> {
    font_reusing_paths(font, paths, reuse, outlines, Flavour::TrueType)
}

/// The font as OpenType/CFF (cubic outlines, points rounded to the integer grid).
pub fn otf(font: &OutlinedFont) -> Result<Vec<u8>, OtfError> {
    otf_reusing(font, &Reuse::off(), &OutlineKeys::default())
}

/// [`otf`], taking each glyph's charstring and box from the last build when it was made
/// from the same outline ([`Reuse::data_or_make`]), as [`ttf_reusing`] does.
pub fn otf_reusing(
    font: &OutlinedFont,
    reuse: &Reuse,
    outlines: &OutlineKeys,
) -> Result<Vec<u8>, OtfError> {
    otf_reusing_paths(font, None, reuse, outlines)
}

/// [`otf_reusing`], each glyph's outline asked of `paths` (when given) instead of taken
/// from `font`, and only when its charstring is not in the record, as
/// [`ttf_reusing_paths`] does.
pub fn otf_reusing_paths(
    font: &OutlinedFont,
    paths: Option<&dyn GlyphPaths>,
    reuse: &Reuse,
    outlines: &OutlineKeys,
) -> Result<Vec<u8>, OtfError> {
    font_reusing_paths(font, paths, reuse, outlines, Flavour::Cff)
}

/// The outlines a static font carries.
#[derive(Clone, Copy)]
enum Flavour {
    /// `glyf`: quadratic splines.
    TrueType,
    /// `CFF `: the cubics.
    Cff,
}

/// [`ttf_reusing_paths`] or [`otf_reusing_paths`], by `flavour`.
fn font_reusing_paths(
    font: &OutlinedFont,
    paths: Option<&dyn GlyphPaths>,
    reuse: &Reuse,
    outlines: &OutlineKeys,
    flavour: Flavour,
) -> Result<Vec<u8>, OtfError> {
    let set = GlyphSet::with_paths(font, paths)?;
    let keys = glyph_keys(font, &set, reuse, outlines);
    let outlines = match flavour {
        Flavour::TrueType => tables::Outlines::TrueType(truetype::glyphs_reusing(
            &set.glyphs,
            font.tolerance,
            reuse,
            &keys,
        )?),
        Flavour::Cff => {
            tables::Outlines::Cff(charstring::glyphs_reusing(&set.glyphs, reuse, &keys)?)
        }
    };
    tables::build_font(font, &set, outlines)
}

/// Per glyph of `set`, the key of its outline when `reuse` is on (none for a synthesised
/// `.notdef`, which `set` puts first).
fn glyph_keys(
    font: &OutlinedFont,
    set: &GlyphSet,
    reuse: &Reuse,
    outlines: &OutlineKeys,
) -> Vec<Option<Key>> {
    if !reuse.is_on() {
        return Vec::new();
    }
    let synthesised = set.glyphs.len() - font.glyphs.len();
    let own = set.glyphs[synthesised..].iter().enumerate();
    std::iter::repeat_n(None, synthesised)
        .chain(own.map(|(i, g)| Some(outlines.key(i).unwrap_or_else(|| outline_key(&g.path())))))
        .collect()
}

/// The font as WOFF2 for the web: the TTF of [`ttf`], Brotli-compressed (tables
/// untransformed; see `woff2.rs`).
pub fn woff2(font: &OutlinedFont) -> Result<Vec<u8>, OtfError> {
    woff2_from_ttf(&ttf(font)?)
}

/// [`woff2`] from the TTF bytes already built by [`ttf`] (saves building it twice).
pub fn woff2_from_ttf(ttf: &[u8]) -> Result<Vec<u8>, OtfError> {
    woff2::woff2(ttf)
}

/// [`woff2_from_ttf`], a large font's slices compressed by `slice(bytes, quality)`, which
/// must give what [`compress_slice`] gives (see `woff2.rs`).
pub fn woff2_from_ttf_with(ttf: &[u8], slice: &CompressSlice<'_>) -> Result<Vec<u8>, OtfError> {
    woff2::woff2_with(ttf, slice)
}

/// The big-endian `u16` at `at` in a font's bytes, if they reach that far.
fn be16(bytes: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_be_bytes(bytes.get(at..at + 2)?.try_into().ok()?))
}

/// The big-endian `u32` at `at` in a font's bytes, if they reach that far.
fn be32(bytes: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_be_bytes(bytes.get(at..at + 4)?.try_into().ok()?))
}

/// One glyph as both fonts hold it (for external checks and reports).
#[derive(Clone, Debug, PartialEq)]
pub struct OrderedGlyph {
    /// The model's name (`.notdef` for a synthesised one).
    pub model_name: String,
    /// The PostScript name in `post` / the CFF charset.
    pub ps_name: String,
    /// Code points mapped to the glyph.
    pub unicodes: Vec<char>,
    /// Advance on the grid, font units.
    pub advance: u16,
}

/// The glyph order, PostScript names, code points and advances both fonts are built with.
pub fn glyph_order(font: &OutlinedFont) -> Result<Vec<OrderedGlyph>, OtfError> {
    let set = GlyphSet::new(font)?;
    Ok(set
        .glyphs
        .into_iter()
        .map(|g| OrderedGlyph {
            model_name: g.model_name,
            ps_name: g.ps_name,
            unicodes: g.unicodes,
            advance: g.advance,
        })
        .collect())
}
