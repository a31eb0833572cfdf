//! Text layout: characters -> positioned glyphs, shaped by HarfRust on the font's own TTF.
//!
//! The one layout rule of the images (the text proof, `render --text` and the sheet labels):
//! the TTF that [`crate::otf::ttf`] builds from the outlined font, in memory, is shaped with
//! [HarfRust](https://docs.rs/harfrust) (the Rust port of HarfBuzz), so kerning (GPOS),
//! ligatures and mark positioning in the PNGs are what a browser does with that font.
//! HarfRust's glyph ids are mapped back to [`OutlinedFont::glyphs`] through the fonts' glyph
//! order ([`crate::otf::glyph_order`]) and drawn from the fitted outlines.
//!
//! Limits: one line at a time, positions in font units on the TTF's integer grid (advances
//! are rounded as the fonts store them); the script and direction are guessed from the text
//! (left to right when it has no strong script); no font features beyond the shaper's
//! defaults.

use std::collections::BTreeMap;
use std::fmt;

use harfrust::{Buffer, Direction, ShapeOptions, ShaperFont};
use skrifa::raw::types::Tag;

use crate::otf::{self, OtfError};
use crate::outline::{notdef_box, OutlinedFont, OutlinedGlyph};

/// One glyph placed on a line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placed {
    /// Index into [`OutlinedFont::glyphs`], or `None` for the [`notdef_box`] the fonts put
    /// first when the font has no `.notdef` ([`Layout::outline`] gives it).
    pub glyph: Option<usize>,
    /// Pen position of the glyph origin, font units from the line start (kerning and mark
    /// offsets included).
    pub x: f64,
    /// Vertical offset of the glyph origin from the baseline, font units, y up (marks).
    pub y: f64,
    /// Advance of this glyph, font units (0 for a mark placed on its base).
    pub advance: f64,
}

/// A laid-out line: placed glyphs and the total advance width.
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    /// The glyphs in visual order, left to right.
    pub glyphs: Vec<Placed>,
    /// Pen position after the last glyph, font units.
    pub width: f64,
}

/// Why text could not be laid out.
#[derive(Debug)]
pub enum LayoutError {
    /// The font cannot be built as a TTF (see [`otf::ttf`]).
    Font(OtfError),
    /// The built TTF did not read back, or HarfRust refused the text.
    Shape(String),
}

impl fmt::Display for LayoutError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LayoutError::Font(e) => write!(f, "cannot build the font to shape text with: {e}"),
            LayoutError::Shape(msg) => write!(f, "text shaping failed: {msg}"),
        }
    }
}

impl std::error::Error for LayoutError {}

/// The shaper for one font, built once (the TTF is built here).
pub struct Layout<'a> {
    font: &'a OutlinedFont,
    by_char: BTreeMap<char, usize>,
    /// The TTF of `font`, as HarfRust reads it (owned; its caches live with it).
    shaping: harfrust::Font,
    /// Glyph id -> index into `font.glyphs`; `None` for the synthesised `.notdef`.
    by_gid: Vec<Option<usize>>,
    /// The box drawn for glyph id 0 when the font has no `.notdef`.
    fallback: OutlinedGlyph,
}

impl<'a> Layout<'a> {
    /// The shaper for `font`: builds its TTF in memory.
    pub fn new(font: &'a OutlinedFont) -> Result<Self, LayoutError> {
        Self::with_ttf(font, otf::ttf(font).map_err(LayoutError::Font)?)
    }

    /// The shaper for `font` from its TTF already built by [`otf::ttf`] (or that TTF with
    /// tables changed): its glyph ids must follow [`otf::glyph_order`].
    pub fn with_ttf(font: &'a OutlinedFont, ttf: Vec<u8>) -> Result<Self, LayoutError> {
        let shaping = harfrust::Font::new(ttf, 0)
            .ok_or_else(|| LayoutError::Shape("the built TTF does not read back".into()))?;
        let index: BTreeMap<&str, usize> = font
            .glyphs
            .iter()
            .enumerate()
            .map(|(i, g)| (g.name.as_str(), i))
            .collect();
        // The synthesised `.notdef` (when the font has none) is the only name the order
        // has that the font lacks.
        let by_gid = otf::glyph_order(font)
            .map_err(LayoutError::Font)?
            .iter()
            .map(|g| index.get(g.model_name.as_str()).copied())
            .collect();
        let mut by_char = BTreeMap::new();
        for (i, g) in font.glyphs.iter().enumerate() {
            for &c in &g.unicodes {
                by_char.entry(c).or_insert(i);
            }
        }
        Ok(Layout {
            font,
            by_char,
            shaping,
            by_gid,
            fallback: notdef_box(&font.info),
        })
    }

    /// The outlined font this shaper draws.
    pub fn font(&self) -> &'a OutlinedFont {
        self.font
    }

    /// Whether the font has a glyph of its own for `c` (not the fallback).
    pub fn covers(&self, c: char) -> bool {
        self.by_char.contains_key(&c)
    }

    /// The outline to draw for a placed glyph (the [`notdef_box`] for `None`).
    pub fn outline(&self, placed: &Placed) -> &OutlinedGlyph {
        match placed.glyph {
            Some(i) => &self.font.glyphs[i],
            None => &self.fallback,
        }
    }

    /// Shapes one line of text; line breaks are the caller's (a `'\n'` here is just a
    /// character the font lacks).
    pub fn line(&self, text: &str) -> Result<Line, LayoutError> {
        let shaper = ShaperFont::new(&self.shaping);
        let mut buffer = Buffer::new();
        buffer.push_str(text);
        buffer.guess_segment_properties();
        if buffer.direction() == Direction::Invalid {
            buffer.set_direction(Direction::LeftToRight);
        }
        harfrust::shape(&shaper, &mut buffer, ShapeOptions::new())
            .map_err(|e| LayoutError::Shape(e.to_string()))?;
        let mut pen = 0.0;
        let mut glyphs = Vec::with_capacity(buffer.len());
        for (info, pos) in buffer.glyph_infos().iter().zip(buffer.glyph_positions()) {
            let glyph = self
                .by_gid
                .get(info.glyph_id as usize)
                .copied()
                .ok_or_else(|| {
                    LayoutError::Shape(format!("glyph id {} is not in the font", info.glyph_id))
                })?;
            glyphs.push(Placed {
                glyph,
                x: pen + f64::from(pos.x_offset),
                y: f64::from(pos.y_offset),
                advance: f64::from(pos.x_advance),
            });
            pen += f64::from(pos.x_advance);
        }
        Ok(Line { glyphs, width: pen })
    }
}

/// The OpenType script tag of `c`'s script, or `None` for characters of no one script
/// (punctuation, digits, combining marks), which a shaper's text takes into the run around
/// them. The Unicode script comes from HarfRust's
/// tables; its ISO 15924 tag in lower case is the OpenType tag for the scripts whose
/// shapers do not differ (Indic scripts' newer `xxx2` tags are not tried).
pub fn strong_script(c: char) -> Option<Tag> {
    let mut buffer = harfrust::Buffer::new();
    buffer.push_str(c.encode_utf8(&mut [0; 4]));
    buffer.guess_segment_properties();
    let iso = buffer.script()?.tag().to_be_bytes();
    match &iso {
        b"Zyyy" | b"Zinh" | b"Zzzz" => None,
        b"Hira" | b"Kana" => Some(Tag::new(b"kana")),
        _ => Some(Tag::new(&iso.map(|b| b.to_ascii_lowercase()))),
    }
}

#[cfg(test)]
mod tests {
    use kurbo::Shape;

    use super::*;
    use crate::model::{test_info, Font, Glyph, KernPair};
    use crate::outline::outline_font;

    fn glyph(name: &str, c: Option<char>, advance: f64) -> Glyph {
        Glyph {
            name: name.into(),
            unicodes: c.into_iter().collect(),
            advance,
            contours: vec![],
            components: vec![],
            anchors: vec![],
            outline_mark: false,
        }
    }

    fn font(with_notdef: bool) -> OutlinedFont {
        outline_font(&model(with_notdef), 0.5)
    }

    fn model(with_notdef: bool) -> Font {
        let mut glyphs = vec![glyph("A", Some('A'), 600.0), glyph("V", Some('V'), 580.0)];
        if with_notdef {
            glyphs.insert(0, glyph(".notdef", None, 500.0));
        }
        Font {
            info: test_info(),
            features: None,
            glyphs,
            kerning: vec![KernPair {
                left: "A".into(),
                right: "V".into(),
                value: -60.0,
            }],
        }
    }

    #[test]
    fn advances_and_kerning() {
        let f = font(true);
        let line = Layout::new(&f).unwrap().line("AVA?").unwrap();
        let xs: Vec<f64> = line.glyphs.iter().map(|p| p.x).collect();
        // A at 0; V after 600 - 60; A after V's 580 (no V-A pair); '?' is .notdef.
        assert_eq!(xs, [0.0, 540.0, 1120.0, 1720.0]);
        assert_eq!(
            line.glyphs.iter().map(|p| p.glyph).collect::<Vec<_>>(),
            [Some(1), Some(2), Some(1), Some(0)]
        );
        assert_eq!(line.width, 2220.0);
    }

    #[test]
    fn missing_without_notdef_is_a_box() {
        let f = font(false);
        let layout = Layout::new(&f).unwrap();
        let line = layout.line("A?V").unwrap();
        assert_eq!(line.glyphs[1].glyph, None);
        assert_eq!(line.glyphs[1].advance, 500.0);
        // No kerning across the box.
        assert_eq!(line.glyphs[2].x, 1100.0);
        let area = layout.outline(&line.glyphs[1]).path.area();
        // Outer 400 x 700 minus inner 300 x 600, positive = counter-clockwise.
        assert_eq!(area, 400.0 * 700.0 - 300.0 * 600.0);
        assert_eq!(layout.outline(&line.glyphs[0]).name, "A");
    }
}
