//! The `maxp` table: the glyph count, and for TrueType the outline maxima (no glyph
//! programs, no composite glyphs, so those fields are 0; the stack holds what the `prep`
//! program of [`super::prep`] pushes).

use write_fonts::tables::maxp::Maxp;

use super::prep;
use super::truetype::TtGlyph;

/// `maxp` version 0.5, for CFF outlines.
pub fn cff_maxp(num_glyphs: u16) -> Maxp {
    Maxp::new(num_glyphs)
}

/// `maxp` version 1.0 for `glyf` outlines.
pub fn truetype_maxp(glyphs: &[TtGlyph]) -> Maxp {
    let clamp = |n: usize| n.min(usize::from(u16::MAX)) as u16;
    let max_points = glyphs.iter().map(TtGlyph::num_points).max().unwrap_or(0);
    let max_contours = glyphs.iter().map(TtGlyph::num_contours).max().unwrap_or(0);
    Maxp {
        num_glyphs: clamp(glyphs.len()),
        max_points: Some(clamp(max_points)),
        max_contours: Some(clamp(max_contours)),
        max_composite_points: Some(0),
        max_composite_contours: Some(0),
        max_zones: Some(2),
        max_twilight_points: Some(0),
        max_storage: Some(0),
        max_function_defs: Some(0),
        max_instruction_defs: Some(0),
        max_stack_elements: Some(prep::STACK_DEPTH),
        max_size_of_instructions: Some(0),
        max_component_elements: Some(0),
        max_component_depth: Some(0),
    }
}

#[cfg(test)]
mod tests {
    use kurbo::{BezPath, Rect, Shape};

    use super::*;
    use crate::otf::tables::tests::ot_glyph;
    use crate::otf::truetype;

    #[test]
    fn truetype_maxima() {
        let mut boxes = ot_glyph("boxes", &['o'], 600);
        let mut path: BezPath = Rect::new(0.0, 0.0, 100.0, 100.0)
            .path_elements(0.1)
            .collect();
        path.extend(Rect::new(200.0, 0.0, 300.0, 100.0).path_elements(0.1));
        boxes.path = crate::otf::OtPath::Given(std::borrow::Cow::Owned(path));
        let glyphs = [ot_glyph(".notdef", &[], 500), boxes];
        let tt = truetype::glyphs_reusing(&glyphs, 0.5, &crate::reuse::Reuse::off(), &[])
            .expect("glyphs");
        let maxp = truetype_maxp(&tt);
        assert_eq!(maxp.num_glyphs, 2);
        // Two rectangles: 8 points in 2 contours.
        assert_eq!(maxp.max_points, Some(8));
        assert_eq!(maxp.max_contours, Some(2));
        assert_eq!(maxp.max_zones, Some(2));
        assert_eq!(maxp.max_component_depth, Some(0));
        assert_eq!(maxp.max_stack_elements, Some(1));
        let cff = cff_maxp(2);
        assert_eq!(cff.num_glyphs, 2);
        assert_eq!(cff.max_points, None);
    }
}
