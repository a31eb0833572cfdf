//! Point counts of the importer on a CJK glyph, against the original's stored points.
//!
//! The fixture is U+4E0D (不) of WenQuanYi Zen Hei (Debian fonts-wqy-zenhei 0.9.45, first
//! font of the .ttc, 1024-unit em; GPL-2 with the font embedding exception), as SVG path
//! data in font units, y up, written by fontTools' `SVGPathPen`. Its stroke ends are runs
//! of two TrueType quadratics between corners: with both neighbours of the corners held on
//! the original's tangents they needed three X-spline points, with the neighbours free
//! ([`xglyph::import::fit::FREE_CORNERS`]) two.

use kurbo::BezPath;
use xglyph::import::contour::contours;
use xglyph::import::{grid_for, import_glyph, SourceGlyph, IMPORT_SHARE};

use crate::common::paths;

const FIXTURE: &str = "tests/fixtures/import/wqy-zenhei-uni4E0D.path";
/// The default import tolerance: 1/1000 of the 1024-unit em.
const T: f64 = 1.024;

#[test]
fn free_corners_save_points_within_the_bound() {
    let text = std::fs::read_to_string(FIXTURE).unwrap();
    let path = BezPath::from_svg(text.trim()).unwrap();
    let source = SourceGlyph {
        name: "uni4E0D".to_string(),
        unicodes: vec!['\u{4E0D}'],
        advance: 1024.0,
        path: path.clone(),
    };
    let fitted = import_glyph(&source, T, grid_for(T));
    // 41 stored points in the font; the importer before free corners wrote 44.
    assert_eq!(fitted.report.original_points, 41);
    assert_eq!(fitted.report.xspline_points, 42);
    let originals = contours(&path);
    assert_eq!(fitted.glyph.contours.len(), originals.len());
    // Each X-spline as a fine polyline against its own original contour, measured here.
    let bound = IMPORT_SHARE * T;
    let mut worst: f64 = 0.0;
    for (contour, original) in fitted.glyph.contours.iter().zip(&originals) {
        let line = paths::xspline_polyline(contour.spline(), 256);
        let original = BezPath::from_path_segments(original.segs.iter().copied());
        worst = worst.max(paths::two_sided(&line, &original, 32));
    }
    assert!(worst <= bound + 1e-3, "{worst} > {bound}");
    assert!(
        (worst - fitted.report.max_error).abs() < 0.02,
        "measured here {worst}, reported {}",
        fitted.report.max_error
    );
}
