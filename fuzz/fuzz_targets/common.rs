//! The checks shared by the importer targets.

use xglyph::import::Imported;

/// Every control point is finite (the model's contours are validated X-splines by type),
/// the report has one row per glyph, and the font directory the importer would write loads
/// back with the same glyphs.
pub fn check(imported: &Imported) {
    let font = &imported.font;
    assert_eq!(imported.report.rows.len(), font.glyphs.len());
    for glyph in &font.glyphs {
        for contour in &glyph.contours {
            assert!(
                contour.points().iter().all(|p| p.pos.is_finite() && p.s.is_finite()),
                "{}",
                glyph.name
            );
        }
    }
    let dir = std::env::temp_dir().join(format!("xglyph-fuzz-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in xglyph::source::emit::font_sources(font) {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let loaded = xglyph::source::load_font(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    let loaded = loaded.unwrap_or_else(|e| panic!("the imported font does not load: {e:?}"));
    assert_eq!(loaded.0.glyphs.len(), font.glyphs.len());
}
