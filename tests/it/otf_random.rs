//! Random star-shaped glyphs through both exporters: every outline read back with
//! ttf-parser stays within the stated bounds of the fitted BezPaths (dense two-sided
//! sampling), and both fonts keep the glyph's advance and code point.

use crate::common::paths;

use proptest::prelude::*;
use ttf_parser::{Face, GlyphId};
use xglyph::import::font::glyph_outline;
use xglyph::model::{Contour, Font, FontInfo, Glyph};
use xglyph::otf::{otf, ttf, PULLED};
use xglyph::outline::outline_font;
use xglyph::xspline::ControlPoint;

fn font_with(glyph: Glyph, tolerance: f64) -> Font {
    Font {
        info: FontInfo {
            tolerance,
            ..FontInfo::with_em("Random", 1000)
        },
        glyphs: vec![glyph],
        kerning: Vec::new(),
        features: None,
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, .. ProptestConfig::default() })]

    #[test]
    fn random_glyphs_read_back_within_bounds(
        raw in prop::collection::vec((0.0..1.0f64, 0.0..1.0f64, -1.0..=1.0f64), 3..14),
        tolerance in prop::sample::select(vec![0.1, 0.5, 1.0]),
        advance in 0u16..2000,
    ) {
        // Star-shaped around (500, 300): angles sorted, so the contour is simple.
        let n = raw.len() as f64;
        let points: Vec<ControlPoint> = raw.iter().enumerate().map(|(i, &(a, r, s))| {
            let angle = (i as f64 + 0.8 * a) / n * std::f64::consts::TAU;
            let radius = 80.0 + 420.0 * r;
            ControlPoint::new(500.0 + radius * angle.cos(), 300.0 + radius * angle.sin(), s)
        }).collect();
        let glyph = Glyph {
            name: "x".into(),
            unicodes: vec!['x'],
            advance: f64::from(advance),
            contours: vec![Contour::new(points).expect("a valid contour")],
            components: Vec::new(),
            anchors: Vec::new(),
            outline_mark: false,
        };
        let font = font_with(glyph, tolerance);
        let outlines = outline_font(&font, tolerance);
        let exact = &outlines.glyphs[0].path;
        for (bytes, bound) in [
            // Grid rounding: √2/2, or a unit where a point moves at a notch (`PULLED`).
            (ttf(&outlines).unwrap(), tolerance + PULLED),
            (otf(&outlines).unwrap(), PULLED),
        ] {
            let face = Face::parse(&bytes, 0).unwrap();
            prop_assert_eq!(face.glyph_index('x'), Some(GlyphId(1)));
            prop_assert_eq!(face.glyph_hor_advance(GlyphId(1)), Some(advance));
            let read = glyph_outline(&face, GlyphId(1)).unwrap_or_default();
            let d = paths::two_sided(&read, exact, 48);
            prop_assert!(d <= bound, "distance {} > bound {}", d, bound);
        }
    }
}
