//! The `cmap` table: every code point of every glyph to its glyph id.

use write_fonts::tables::cmap::{Cmap, CmapSubtable, EncodingRecord, PlatformId};
use write_fonts::types::GlyphId;

use super::{OtGlyph, OtfError};

/// `cmap` for the glyphs in glyph-id order (write-fonts picks the subtable formats);
/// [`OtfError::CmapConflict`] when two glyphs claim one code point.
///
/// A font whose glyphs map no code point still gets a format 4 subtable (holding only its
/// closing segment) for the Unicode and Windows platforms: write-fonts would write a `cmap`
/// without subtables, which OTS refuses (UFOs of unencoded glyphs build such fonts).
pub fn cmap(glyphs: &[OtGlyph]) -> Result<Cmap, OtfError> {
    let mappings = glyphs.iter().enumerate().flat_map(|(gid, g)| {
        g.unicodes
            .iter()
            .map(move |&c| (c, GlyphId::new(gid as u32)))
    });
    let cmap = Cmap::from_mappings(mappings).map_err(|e| OtfError::CmapConflict(e.to_string()))?;
    if !cmap.encoding_records.is_empty() {
        return Ok(cmap);
    }
    let closing =
        || CmapSubtable::format_4(0, vec![0xFFFF], vec![0xFFFF], vec![1], vec![0], vec![]);
    Ok(Cmap::new(vec![
        EncodingRecord::new(PlatformId::Unicode, 3, closing()),
        EncodingRecord::new(PlatformId::Windows, 1, closing()),
    ]))
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
    fn glyphs_without_code_points_still_get_a_subtable() {
        let glyphs = [ot_glyph(".notdef", &[], 500), ot_glyph("a.alt", &[], 600)];
        let bytes = write_fonts::dump_table(&cmap(&glyphs).expect("no conflict")).expect("cmap");
        let table = read_fonts::tables::cmap::Cmap::read(FontData::new(&bytes)).expect("read");
        let formats: Vec<(u16, u16, u16)> = table
            .encoding_records()
            .iter()
            .map(|r| {
                let sub = r.subtable(table.offset_data()).expect("subtable");
                (r.platform_id() as u16, r.encoding_id(), sub.format())
            })
            .collect();
        assert_eq!(formats, [(0, 3, 4), (3, 1, 4)]);
        assert_eq!(table.map_codepoint('A'), None);
        assert_eq!(table.map_codepoint('\u{FFFF}').map(|g| g.to_u32()), Some(0));
    }

    #[test]
    fn two_glyphs_for_one_code_point() {
        let glyphs = [ot_glyph("A", &['A'], 600), ot_glyph("A.alt", &['A'], 600)];
        assert!(matches!(cmap(&glyphs), Err(OtfError::CmapConflict(_))));
    }
}
