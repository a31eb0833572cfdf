//! SVG outputs: the glyph set (one standalone SVG per glyph) and the SVG 1.1 font.
//!
//! Both are strings built in memory; writing is the caller's job ([`crate::write`]).
//! Every attribute and text value is escaped ([`xml::escape`]); numbers are rounded to
//! 1/100 font unit ([`xml::num`]), so outputs are deterministic.

pub mod font;
pub mod glyph_set;
pub mod path_data;
pub mod xml;

pub use font::{glyph_elements, svg_font, svg_font_with};
pub use glyph_set::{glyph_set, glyph_svg, svg_glyph_key, GlyphSvg};

use crate::model::FontInfo;

/// The file stem of font-wide outputs: `<Family>-<Style>` with white space removed and
/// characters that are unsafe in file names (path separators, `<>:"|?*`, controls, a
/// leading `.`) replaced by `_`; `"font"` when nothing is left.
pub fn output_stem(info: &FontInfo) -> String {
    let raw = format!("{}-{}", info.family, info.style);
    let mut stem: String = raw
        .chars()
        .filter(|c| !c.is_whitespace())
        .map(|c| {
            if c.is_control() || matches!(c, '/' | '\\' | '<' | '>' | ':' | '"' | '|' | '?' | '*') {
                '_'
            } else {
                c
            }
        })
        .collect();
    if stem.starts_with('.') {
        stem.replace_range(..1, "_");
    }
    if stem.is_empty() || stem == "-" {
        stem = "font".into();
    }
    stem
}
