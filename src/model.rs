//! The typed font model: what the sources mean, after parsing and validation.
//!
//! Everything downstream of [`crate::source`] works on these types only; it never sees
//! TOML and never re-validates. Coordinates are font units, y up.

use crate::xspline::ControlPoint;

/// A whole font: metrics, glyphs in source order, and kerning.
#[derive(Clone, Debug, PartialEq)]
pub struct Font {
    pub info: FontInfo,
    /// Glyphs, sorted by name for determinism (`.notdef` first when present).
    pub glyphs: Vec<Glyph>,
    pub kerning: Vec<KernPair>,
}

/// Font-wide metadata and vertical metrics (`font.toml`).
#[derive(Clone, Debug, PartialEq)]
pub struct FontInfo {
    pub family: String,
    /// Default `"Regular"`.
    pub style: String,
    pub units_per_em: u16,
    /// Font units above the baseline (positive).
    pub ascender: f64,
    /// Font units below the baseline (negative, y-up).
    pub descender: f64,
    pub x_height: f64,
    pub cap_height: f64,
    /// Maximum distance, in font units, between the X-splines and the exported Béziers.
    pub tolerance: f64,
    /// Optional free-form metadata (copyright, designer, ...), written into outputs.
    pub copyright: Option<String>,
    pub designer: Option<String>,
    pub version: Option<String>,
}

/// One glyph: its own contours plus components placed from other glyphs.
#[derive(Clone, Debug, PartialEq)]
pub struct Glyph {
    pub name: String,
    /// Code points mapped to this glyph (may be empty, e.g. accents or `.notdef`).
    pub unicodes: Vec<char>,
    /// Horizontal advance in font units.
    pub advance: f64,
    pub contours: Vec<Contour>,
    pub components: Vec<Component>,
}

/// One closed X-spline contour, as written (direction is fixed on output).
#[derive(Clone, Debug, PartialEq)]
pub struct Contour {
    pub points: Vec<ControlPoint>,
}

/// Another glyph's outline placed into this one, translated by `offset`.
#[derive(Clone, Debug, PartialEq)]
pub struct Component {
    pub base: String,
    pub offset: (f64, f64),
}

/// A kerning pair by glyph name; `value` in font units, negative = tighter.
#[derive(Clone, Debug, PartialEq)]
pub struct KernPair {
    pub left: String,
    pub right: String,
    pub value: f64,
}

impl Font {
    /// The glyph with this name.
    pub fn glyph(&self, name: &str) -> Option<&Glyph> {
        self.glyphs.iter().find(|g| g.name == name)
    }

    /// The glyph mapped to code point `c`.
    pub fn glyph_for_char(&self, c: char) -> Option<&Glyph> {
        self.glyphs.iter().find(|g| g.unicodes.contains(&c))
    }

    /// All contours of `glyph` with components resolved (recursively) and offsets applied.
    ///
    /// The model is validated, so bases exist and there are no cycles; a missing base
    /// is skipped and recursion is bounded by the glyph count as a safety net.
    pub fn resolved_contours(&self, glyph: &Glyph) -> Vec<Contour> {
        let mut out = Vec::new();
        self.collect_contours(glyph, (0.0, 0.0), self.glyphs.len(), &mut out);
        out
    }

    fn collect_contours(
        &self,
        glyph: &Glyph,
        offset: (f64, f64),
        depth: usize,
        out: &mut Vec<Contour>,
    ) {
        out.extend(glyph.contours.iter().map(|c| {
            Contour {
                points: c
                    .points
                    .iter()
                    .map(|p| ControlPoint::new(p.pos.x + offset.0, p.pos.y + offset.1, p.s))
                    .collect(),
            }
        }));
        if depth == 0 {
            return;
        }
        for comp in &glyph.components {
            if let Some(base) = self.glyph(&comp.base) {
                let off = (offset.0 + comp.offset.0, offset.1 + comp.offset.1);
                self.collect_contours(base, off, depth - 1, out);
            }
        }
    }

    /// Kerning value between two glyph names (0 when there is no pair).
    pub fn kern(&self, left: &str, right: &str) -> f64 {
        self.kerning
            .iter()
            .find(|k| k.left == left && k.right == right)
            .map_or(0.0, |k| k.value)
    }
}

/// The OpenType weight class (100..900) a style name stands for: `"Bold Italic"` -> 700,
/// `"Semi-Bold"` -> 600; 400 when it names no weight. Used by the SVG font (CSS weight) and
/// the OS/2 table, so both read the style the same way.
pub fn weight_class(style: &str) -> u16 {
    const WEIGHTS: &[(&str, u16)] = &[
        // Compound names first: "extralight" also contains "light".
        ("extralight", 200),
        ("ultralight", 200),
        ("semibold", 600),
        ("demibold", 600),
        ("extrabold", 800),
        ("ultrabold", 800),
        ("thin", 100),
        ("light", 300),
        ("medium", 500),
        ("bold", 700),
        ("black", 900),
        ("heavy", 900),
    ];
    let compact: String = style
        .chars()
        .filter(|c| c.is_alphanumeric())
        .flat_map(char::to_lowercase)
        .collect();
    WEIGHTS
        .iter()
        .find(|(name, _)| compact.contains(name))
        .map_or(400, |&(_, weight)| weight)
}

#[cfg(test)]
mod tests {
    use super::weight_class;

    #[test]
    fn style_names_to_weight_classes() {
        assert_eq!(weight_class("Regular"), 400);
        assert_eq!(weight_class("Bold Italic"), 700);
        assert_eq!(weight_class("Semi-Bold"), 600);
        assert_eq!(weight_class("ExtraLight"), 200);
        assert_eq!(weight_class("Light Oblique"), 300);
        assert_eq!(weight_class("Black"), 900);
        assert_eq!(weight_class("Condensed"), 400);
    }
}
