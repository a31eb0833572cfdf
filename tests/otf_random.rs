//! Random star-shaped glyphs through both exporters: every outline read back with
//! ttf-parser stays within the stated bounds of the fitted BezPaths (dense two-sided
//! sampling), and both fonts keep the glyph's advance and code point.

use kurbo::{BezPath, ParamCurve, ParamCurveNearest, PathSeg};
use proptest::prelude::*;
use ttf_parser::{Face, GlyphId};
use xglyph::model::{Contour, Font, FontInfo, Glyph};
use xglyph::otf::{otf, ttf};
use xglyph::outline::outline_font;
use xglyph::xspline::ControlPoint;

const GRID: f64 = std::f64::consts::FRAC_1_SQRT_2;

struct PathPen(BezPath);

impl ttf_parser::OutlineBuilder for PathPen {
    fn move_to(&mut self, x: f32, y: f32) {
        self.0.move_to((f64::from(x), f64::from(y)));
    }
    fn line_to(&mut self, x: f32, y: f32) {
        self.0.line_to((f64::from(x), f64::from(y)));
    }
    fn quad_to(&mut self, x1: f32, y1: f32, x: f32, y: f32) {
        self.0
            .quad_to((f64::from(x1), f64::from(y1)), (f64::from(x), f64::from(y)));
    }
    fn curve_to(&mut self, x1: f32, y1: f32, x2: f32, y2: f32, x: f32, y: f32) {
        self.0.curve_to(
            (f64::from(x1), f64::from(y1)),
            (f64::from(x2), f64::from(y2)),
            (f64::from(x), f64::from(y)),
        );
    }
    fn close(&mut self) {
        self.0.close_path();
    }
}

fn one_sided(a: &BezPath, b: &BezPath) -> f64 {
    let targets: Vec<PathSeg> = b.segments().collect();
    let mut worst: f64 = 0.0;
    for seg in a.segments() {
        for i in 0..=48 {
            let p = seg.eval(f64::from(i) / 48.0);
            let d = targets
                .iter()
                .map(|t| t.nearest(p, 1e-9).distance_sq)
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d.sqrt());
        }
    }
    worst
}

fn font_with(glyph: Glyph, tolerance: f64) -> Font {
    Font {
        info: FontInfo {
            family: "Random".into(),
            style: "Regular".into(),
            units_per_em: 1000,
            ascender: 800.0,
            descender: -200.0,
            x_height: 500.0,
            cap_height: 700.0,
            tolerance,
            copyright: None,
            designer: None,
            version: None,
        },
        glyphs: vec![glyph],
        kerning: Vec::new(),
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
            contours: vec![Contour { points }],
            components: Vec::new(),
        };
        let font = font_with(glyph, tolerance);
        let outlines = outline_font(&font, tolerance).unwrap();
        let exact = &outlines.glyphs[0].path;
        for (bytes, bound) in [
            (ttf(&font, &outlines).unwrap(), tolerance + GRID),
            (otf(&font, &outlines).unwrap(), GRID),
        ] {
            let face = Face::parse(&bytes, 0).unwrap();
            prop_assert_eq!(face.glyph_index('x'), Some(GlyphId(1)));
            prop_assert_eq!(face.glyph_hor_advance(GlyphId(1)), Some(advance));
            let mut pen = PathPen(BezPath::new());
            face.outline_glyph(GlyphId(1), &mut pen);
            let d = one_sided(&pen.0, exact).max(one_sided(exact, &pen.0));
            prop_assert!(d <= bound, "distance {} > bound {}", d, bound);
        }
    }
}
