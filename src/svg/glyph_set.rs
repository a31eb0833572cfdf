//! The SVG glyph set: one standalone SVG file per glyph.
//!
//! Coordinates are font units, y down with the glyph upright (path data is y-flipped, no
//! transform). The viewBox spans the em vertically (ascender at the top, descender at the
//! bottom) and horizontally the advance, widened to include ink outside it (a zero-advance
//! mark shows its ink; an empty zero-advance glyph gets half an em). Ink above the
//! ascender or below the descender is outside the viewBox.

use kurbo::{Affine, Shape};

use super::path_data::path_data;
use super::xml::{escape, num};
use crate::model::FontInfo;
use crate::names::file_stems;
use crate::outline::{OutlinedFont, OutlinedGlyph};
use crate::reuse::{Key, KeyBuilder};

/// One file of the glyph set: its stem (`crate::names` rule) and its text.
#[derive(Clone, Debug, PartialEq)]
pub struct GlyphSvg {
    /// File stem, unique in the set (case-insensitively).
    pub stem: String,
    /// The SVG document.
    pub svg: String,
}

/// The horizontal extent of a glyph's viewBox, font units: `(x, width)`, whole units.
pub fn horizontal_extent(info: &FontInfo, glyph: &OutlinedGlyph) -> (f64, f64) {
    let (mut x0, mut x1) = (0.0f64, glyph.advance.max(0.0));
    if !glyph.path.elements().is_empty() {
        let ink = glyph.path.bounding_box();
        x0 = x0.min(ink.x0);
        x1 = x1.max(ink.x1);
    }
    let (x0, x1) = (x0.floor(), x1.ceil());
    if x1 > x0 {
        (x0, x1 - x0)
    } else {
        (x0, (f64::from(info.units_per_em) / 2.0).ceil())
    }
}

/// One standalone SVG document for `glyph`.
pub fn glyph_svg(info: &FontInfo, glyph: &OutlinedGlyph) -> String {
    let (x, width) = horizontal_extent(info, glyph);
    let top = -info.ascender.ceil();
    let height = -info.descender.floor() - top;
    let view_box = format!("{} {} {} {}", num(x), num(top), num(width), num(height));
    let d = path_data(&glyph.path, Affine::FLIP_Y);
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    s.push_str(&format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"{view_box}\">\n",
        num(width),
        num(height)
    ));
    s.push_str(&format!("<title>{}</title>\n", escape(&glyph.name)));
    if !d.is_empty() {
        s.push_str(&format!("<path fill-rule=\"nonzero\" d=\"{d}\"/>\n"));
    }
    s.push_str("</svg>\n");
    s
}

/// What [`glyph_svg`] reads, as a [`Key`]: the em's metrics, the glyph's name, advance and
/// path (`outline`, its [`crate::reuse::outline_key`]).
pub fn svg_glyph_key(info: &FontInfo, glyph: &OutlinedGlyph, outline: &Key) -> Key {
    KeyBuilder::new("svg glyph")
        .f64(info.ascender)
        .f64(info.descender)
        .u64(u64::from(info.units_per_em))
        .str(&glyph.name)
        .f64(glyph.advance)
        .key(outline)
        .finish()
}

/// The whole glyph set, in the font's glyph order.
pub fn glyph_set(font: &OutlinedFont) -> Vec<GlyphSvg> {
    let stems = file_stems(font.glyphs.iter().map(|g| g.name.as_str()));
    font.glyphs
        .iter()
        .zip(stems)
        .map(|(glyph, stem)| GlyphSvg {
            stem,
            svg: glyph_svg(&font.info, glyph),
        })
        .collect()
}
