//! The `cmap` table: every code point of every glyph to its glyph id.

use write_fonts::tables::cmap::Cmap;
use write_fonts::types::GlyphId;

use super::{OtGlyph, OtfError};

/// `cmap` for the glyphs in glyph-id order (write-fonts picks the subtable formats);
/// [`OtfError::CmapConflict`] when two glyphs claim one code point.
pub fn cmap(glyphs: &[OtGlyph]) -> Result<Cmap, OtfError> {
    let mappings = glyphs.iter().enumerate().flat_map(|(gid, g)| {
        g.unicodes
            .iter()
            .map(move |&c| (c, GlyphId::new(gid as u32)))
    });
    Cmap::from_mappings(mappings).map_err(|e| OtfError::CmapConflict(e.to_string()))
}

#[cfg(test)]
mod tests {
    use read_fonts::{FontData, FontRead};

    use super::*;
    use crate::otf::tables::tests::ot_glyph;

    #[test]
    fn code_points_to_glyph_ids() {
        let glyphs = [
            ot_glyph(".notdef", &[], 500),
            ot_glyph("A", &['A', 'Á'], 600),
            ot_glyph("smile", &['\u{1F600}'], 1000),
        ];
        let bytes = write_fonts::dump_table(&cmap(&glyphs).expect("no conflict")).expect("cmap");
        let table = read_fonts::tables::cmap::Cmap::read(FontData::new(&bytes)).expect("read");
        let gid = |c: char| table.map_codepoint(c).map(|g| g.to_u32());
        assert_eq!(gid('A'), Some(1));
        assert_eq!(gid('Á'), Some(1));
        assert_eq!(gid('\u{1F600}'), Some(2));
        assert_eq!(gid('B'), None);
    }

    #[test]
    fn two_glyphs_for_one_code_point() {
        let glyphs = [ot_glyph("A", &['A'], 600), ot_glyph("A.alt", &['A'], 600)];
        assert!(matches!(cmap(&glyphs), Err(OtfError::CmapConflict(_))));
    }
}
