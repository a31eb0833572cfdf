//! Test fonts made in code.

use std::path::Path;

use xglyph::model::{Contour, Font, Glyph};
use xglyph::source::load_font;
use xglyph::xspline::ControlPoint;

/// The mini test font with its glyphs replaced by `n` squares mapped from U+4E00 on, and no
/// kerning: a font without Latin, so no sheet label is in its own glyphs.
pub fn square_ideographs(n: u32) -> Font {
    let mut font = load_font(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini"))
        .expect("mini loads")
        .0;
    let square = Contour::new(
        [(100.0, 0.0), (800.0, 0.0), (800.0, 700.0), (100.0, 700.0)]
            .iter()
            .map(|&(x, y)| ControlPoint::new(x, y, 0.0))
            .collect(),
    )
    .expect("a square is a valid contour");
    font.glyphs = (0..n)
        .map(|i| {
            let c = char::from_u32(0x4E00 + i).expect("U+4E00 + n is a character");
            Glyph {
                name: format!("uni{:04X}", u32::from(c)),
                unicodes: vec![c],
                advance: 1000.0,
                contours: vec![square.clone()],
                components: vec![],
                anchors: Vec::new(),
            }
        })
        .collect();
    font.kerning.clear();
    font
}
