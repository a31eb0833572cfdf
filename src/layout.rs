//! Text layout: characters -> glyphs with advances and kerning, positions in font units.
//!
//! One place for the rule, shared by the text proof and the sheet labels; it reads the
//! outlined font ([`crate::outline`]). Limits: one line at a time, left to right, no shaping (no contextual forms,
//! no mark positioning: a combining mark sits where its own outline puts it), no
//! composition of a base letter and a combining mark into a precomposed glyph.

use std::collections::BTreeMap;

use crate::outline::{notdef_box, OutlinedFont, OutlinedGlyph};

/// One glyph placed on a line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placed {
    /// Index into [`OutlinedFont::glyphs`], or `None` when the font has neither the
    /// character nor a `.notdef`: [`Layout::outline`] then gives the [`notdef_box`].
    pub glyph: Option<usize>,
    /// Pen position of the glyph origin, font units from the line start (kerning included).
    pub x: f64,
    /// Advance of this glyph, font units.
    pub advance: f64,
}

/// A laid-out line: placed glyphs and the total advance width.
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    /// The glyphs, left to right.
    pub glyphs: Vec<Placed>,
    /// Pen position after the last glyph, font units.
    pub width: f64,
}

/// Character and kerning lookups for one font, built once.
#[derive(Clone, Debug)]
pub struct Layout<'a> {
    font: &'a OutlinedFont,
    by_char: BTreeMap<char, usize>,
    kerning: BTreeMap<(usize, usize), f64>,
    notdef: Option<usize>,
    /// The box drawn for characters the font lacks when it has no `.notdef`.
    fallback: OutlinedGlyph,
}

impl<'a> Layout<'a> {
    /// The lookups for `font`.
    pub fn new(font: &'a OutlinedFont) -> Self {
        let index: BTreeMap<&str, usize> = font
            .glyphs
            .iter()
            .enumerate()
            .map(|(i, g)| (g.name.as_str(), i))
            .collect();
        let mut by_char = BTreeMap::new();
        for (i, g) in font.glyphs.iter().enumerate() {
            for &c in &g.unicodes {
                by_char.entry(c).or_insert(i);
            }
        }
        let kerning = font
            .kerning
            .iter()
            .filter_map(|k| {
                Some((
                    (*index.get(k.left.as_str())?, *index.get(k.right.as_str())?),
                    k.value,
                ))
            })
            .collect();
        Layout {
            font,
            by_char,
            kerning,
            notdef: index.get(".notdef").copied(),
            fallback: notdef_box(&font.info),
        }
    }

    /// The glyph index for `c`: its own glyph, else `.notdef`, else `None` (a box).
    pub fn glyph_for(&self, c: char) -> Option<usize> {
        self.by_char.get(&c).copied().or(self.notdef)
    }

    /// Whether the font has a glyph of its own for `c` (not the fallback).
    pub fn covers(&self, c: char) -> bool {
        self.by_char.contains_key(&c)
    }

    /// Kerning between two glyph indices, font units (negative = tighter).
    pub fn kern(&self, left: usize, right: usize) -> f64 {
        self.kerning.get(&(left, right)).copied().unwrap_or(0.0)
    }

    /// The outline to draw for a placed glyph (the [`notdef_box`] for `None`).
    pub fn outline(&self, placed: &Placed) -> &OutlinedGlyph {
        match placed.glyph {
            Some(i) => &self.font.glyphs[i],
            None => &self.fallback,
        }
    }

    /// Lays out one line of text; line breaks are the caller's (a `'\n'` here is just a
    /// character the font lacks).
    pub fn line(&self, text: &str) -> Line {
        let mut glyphs = Vec::new();
        let mut x = 0.0;
        let mut prev: Option<usize> = None;
        for c in text.chars() {
            let glyph = self.glyph_for(c);
            if let (Some(l), Some(r)) = (prev, glyph) {
                x += self.kern(l, r);
            }
            let advance = match glyph {
                Some(i) => self.font.glyphs[i].advance,
                None => self.fallback.advance,
            };
            glyphs.push(Placed { glyph, x, advance });
            x += advance;
            prev = glyph;
        }
        Line { glyphs, width: x }
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
        let line = Layout::new(&f).line("AVA?");
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
        let line = Layout::new(&f).line("A?V");
        assert_eq!(line.glyphs[1].glyph, None);
        assert_eq!(line.glyphs[1].advance, 500.0);
        // No kerning across the box.
        assert_eq!(line.glyphs[2].x, 1100.0);
        let layout = Layout::new(&f);
        let area = layout.outline(&line.glyphs[1]).path.area();
        // Outer 400 x 700 minus inner 300 x 600, positive = counter-clockwise.
        assert_eq!(area, 400.0 * 700.0 - 300.0 * 600.0);
        assert_eq!(layout.outline(&line.glyphs[0]).name, "A");
    }
}
