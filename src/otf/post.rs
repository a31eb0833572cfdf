//! The `post` table: glyph names (format 2, TTF only; CFF carries its own charset, so the
//! OTF uses format 3), underline metrics and the fixed-pitch flag.

use write_fonts::tables::post::Post;
use write_fonts::types::{FWord, Version16Dot16};

use super::OtGlyph;

/// Underline position below the baseline, in ems.
const UNDERLINE_POSITION: f64 = 0.075;
/// Underline thickness, in ems.
const UNDERLINE_THICKNESS: f64 = 0.05;

/// `post` for the glyphs in glyph-id order; `names` writes their PostScript names
/// (format 2), otherwise format 3. Fixed pitch when more than one glyph has an advance
/// and all those advances are equal.
pub fn post(glyphs: &[OtGlyph], units_per_em: u16, names: bool) -> Post {
    let widths: Vec<u16> = glyphs
        .iter()
        .map(|g| g.advance)
        .filter(|&a| a > 0)
        .collect();
    let fixed_pitch = widths.len() > 1 && widths.iter().all(|&w| w == widths[0]);
    let mut post = if names {
        Post::new_v2(glyphs.iter().map(|g| g.ps_name.as_str()))
    } else {
        Post {
            version: Version16Dot16::VERSION_3_0,
            ..Default::default()
        }
    };
    let scaled = |f: f64| (f64::from(units_per_em) * f).round() as i16;
    post.underline_position = FWord::new(-scaled(UNDERLINE_POSITION));
    post.underline_thickness = FWord::new(scaled(UNDERLINE_THICKNESS));
    post.is_fixed_pitch = u32::from(fixed_pitch);
    post
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::otf::tables::tests::ot_glyph;

    #[test]
    fn names_underline_and_pitch() {
        let glyphs = [
            ot_glyph(".notdef", &[], 500),
            ot_glyph("A", &['A'], 600),
            ot_glyph("acutecomb", &['\u{301}'], 0),
        ];
        let post = post(&glyphs, 2048, true);
        assert_eq!(post.version, Version16Dot16::VERSION_2_0);
        assert_eq!(post.num_glyphs, Some(3));
        assert_eq!(post.underline_position, FWord::new(-154));
        assert_eq!(post.underline_thickness, FWord::new(102));
        assert_eq!(post.is_fixed_pitch, 0);
        // Standard Macintosh names by index (.notdef 0, A 36), the rest as strings.
        assert_eq!(post.glyph_name_index.as_deref(), Some(&[0, 36, 258][..]));
        assert_eq!(post.string_data.as_ref().map(|s| s.len()), Some(1));

        let mono = [
            ot_glyph("a", &['a'], 600),
            ot_glyph("b", &['b'], 600),
            ot_glyph("mark", &[], 0),
        ];
        let post3 = super::post(&mono, 1000, false);
        assert_eq!(post3.version, Version16Dot16::VERSION_3_0);
        assert_eq!(post3.glyph_name_index, None);
        assert_eq!(post3.is_fixed_pitch, 1);
        assert_eq!(post3.underline_position, FWord::new(-75));
    }
}
