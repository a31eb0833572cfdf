//! The font file: the outline tables of one flavour and the tables both share, assembled
//! with write-fonts' `FontBuilder`. One builder per table, each in its own module:
//! [`super::head`], [`super::hmtx`] (hhea, hmtx), [`super::maxp`], [`super::cmap`],
//! [`super::post`], [`super::os2`], [`super::naming`] (name), [`super::features`] (GSUB, GPOS, GDEF), [`super::kern`] (legacy kern),
//! [`super::truetype`] (glyf, loca), [`super::prep`] and [`super::gasp`] (TTF only) and
//! [`super::cff`].
//!
//! Vertical metrics are one line box everywhere (hhea, OS/2 typo with USE_TYPO_METRICS and
//! win, line gap 0; see [`super::os2`]): the model's ascender and descender, widened to the
//! font's ink box when glyphs reach beyond them (accents on capitals), as FontBakery and the
//! Google Fonts vertical-metrics guide expect. Names come from [`super::naming`].
//! Glyph boxes: the control box of the points for `glyf` (what TrueType stores), the tight
//! box for CFF (what CFF consumers compute); `hmtx` side bearings are their x minimum.

use write_fonts::tables::name::NameRecord;
use write_fonts::types::{NameId, Tag};
use write_fonts::{BuilderError, FontBuilder};

use super::cff::{cff_table, CffInfo};
use super::charstring::CffGlyph;
use super::cmap::cmap;
use super::features::{layout_tables, LayoutSource, LayoutTables};
use super::gasp::gasp;
use super::grid::to_i16;
use super::head::head;
use super::hmtx::{hhea, hmtx};
use super::kern::{kern_pairs, legacy_kern};
use super::maxp::{cff_maxp, truetype_maxp};
use super::naming::{name_table, Naming};
use super::os2::os2_table;
use super::post::post;
use super::prep::SMART_DROPOUT_CONTROL;
use super::truetype::{glyf_loca, TtGlyph};
use super::{GlyphSet, OtfError};
use crate::model::FontInfo;
use crate::outline::OutlinedFont;

/// The outline data of one flavour, in glyph order.
pub enum Outlines {
    /// Quadratic glyphs on the grid, for `glyf`.
    TrueType(Vec<TtGlyph>),
    /// Charstrings of cubic paths on the grid, with their boxes.
    Cff(Vec<CffGlyph>),
}

/// Vertical metrics on the grid and the union of the glyph boxes (head, hhea, OS/2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Metrics {
    pub upm: u16,
    /// `font.toml`'s ascender, on the grid.
    pub ascender: i16,
    /// `font.toml`'s descender, on the grid.
    pub descender: i16,
    /// The line box every table states (hhea, OS/2 typo and win): the ascender raised to
    /// the top of the highest ink, so accented capitals are never clipped.
    pub line_ascender: i16,
    /// The descender lowered to the bottom of the lowest ink.
    pub line_descender: i16,
    pub x_height: i16,
    pub cap_height: i16,
    pub bbox: GridBox,
}

/// A box on the grid: `(x_min, y_min, x_max, y_max)`.
pub type GridBox = (i16, i16, i16, i16);

impl Metrics {
    /// The font's metrics on the grid and the union of `boxes` (all zero without ink).
    pub fn new(info: &FontInfo, boxes: &[Option<GridBox>]) -> Result<Self, OtfError> {
        let bbox = boxes
            .iter()
            .flatten()
            .copied()
            .reduce(|a, b| (a.0.min(b.0), a.1.min(b.1), a.2.max(b.2), a.3.max(b.3)))
            .unwrap_or((0, 0, 0, 0));
        let ascender = to_i16(info.ascender, || "ascender".into())?;
        let descender = to_i16(info.descender, || "descender".into())?;
        Ok(Metrics {
            upm: info.units_per_em,
            ascender,
            descender,
            line_ascender: ascender.max(bbox.3),
            line_descender: descender.min(bbox.1),
            x_height: to_i16(info.x_height, || "x_height".into())?,
            cap_height: to_i16(info.cap_height, || "cap_height".into())?,
            bbox,
        })
    }
}

/// Per glyph, its box on the grid (`None` when empty).
fn glyph_boxes(outlines: &Outlines) -> Vec<Option<GridBox>> {
    match outlines {
        Outlines::TrueType(glyphs) => glyphs
            .iter()
            .map(|g| g.bbox().map(|b| (b.x_min, b.y_min, b.x_max, b.y_max)))
            .collect(),
        Outlines::Cff(glyphs) => glyphs.iter().map(|g| g.bbox).collect(),
    }
}

/// The `CFF ` table: the charset of PostScript names and one charstring per glyph.
fn cff(
    info: &FontInfo,
    naming: &Naming,
    set: &GlyphSet,
    glyphs: &[CffGlyph],
    bbox: GridBox,
) -> Vec<u8> {
    let names: Vec<&str> = set.glyphs.iter().map(|g| g.ps_name.as_str()).collect();
    let charstrings: Vec<Vec<u8>> = glyphs
        .iter()
        .zip(&set.glyphs)
        .map(|(c, g)| c.charstring(i32::from(g.advance)))
        .collect();
    let version = format!("{:.3}", naming.revision);
    cff_table(
        &CffInfo {
            ps_name: &naming.ps_name,
            version: &version,
            copyright: info.copyright.as_deref(),
            full_name: &naming.full_name,
            family_name: &naming.family,
            units_per_em: info.units_per_em,
            bbox: [bbox.0, bbox.1, bbox.2, bbox.3],
        },
        &names,
        &charstrings,
    )
}

/// The whole font file: `set` with the outline tables of `outlines`.
pub fn build_font(
    font: &OutlinedFont,
    set: &GlyphSet,
    outlines: Outlines,
) -> Result<Vec<u8>, OtfError> {
    let layout = layout_tables(&LayoutSource {
        names: set.glyphs.iter().map(|g| g.model_name.as_str()).collect(),
        unicodes: set.glyphs.iter().map(|g| g.unicodes.as_slice()).collect(),
        outline_marks: set.glyphs.iter().map(|g| g.outline_mark).collect(),
        anchors: vec![set.glyphs.iter().map(|g| g.anchors.as_slice()).collect()],
        kerning: vec![kern_pairs(&font.kerning, set)?],
        model: None,
        rules: &[],
        rules_feature: *b"rvrn",
        axis_count: 0,
        features: font.features.as_ref(),
    })?;
    Ok(font_builder(font, set, outlines, &layout, None)?.build())
}

/// What a variable font changes in the shared tables (see `super::variable`).
pub(crate) struct VariableShared {
    /// `OS/2.usWeightClass`: the default master's weight on the `wght` axis.
    pub weight_class: Option<u16>,
    /// Extra `name` records (axis, instance and STAT names, IDs from 256).
    pub names: Vec<(u16, String)>,
}

/// [`build_font`]'s tables, not yet assembled, with the `layout` tables (GSUB, GPOS,
/// GDEF). With `variable`, the legacy `kern` table is left out (it cannot vary) and the
/// weight class and names are the variable font's.
pub(crate) fn font_builder(
    font: &OutlinedFont,
    set: &GlyphSet,
    outlines: Outlines,
    layout: &LayoutTables,
    variable: Option<&VariableShared>,
) -> Result<FontBuilder<'static>, OtfError> {
    let info = &font.info;
    let naming = Naming::new(info);
    let boxes = glyph_boxes(&outlines);
    let metrics = Metrics::new(info, &boxes)?;
    let advances: Vec<u16> = set.glyphs.iter().map(|g| g.advance).collect();
    let pairs = kern_pairs(&font.kerning, set)?;
    let truetype = matches!(outlines, Outlines::TrueType(_));

    let mut builder = FontBuilder::new();
    let table_err = |e: BuilderError| OtfError::Table(e.to_string());
    let index_to_loc_format = match &outlines {
        Outlines::TrueType(glyphs) => {
            let (glyf, loca, format) = glyf_loca(glyphs);
            builder.add_raw(Tag::new(b"glyf"), glyf);
            builder.add_table(&loca).map_err(table_err)?;
            builder
                .add_table(&truetype_maxp(glyphs))
                .map_err(table_err)?;
            // Unhinted, but with smart dropout control and a gasp table, as fontmake and
            // gftools ship unhinted TrueType.
            builder.add_raw(Tag::new(b"prep"), SMART_DROPOUT_CONTROL.to_vec());
            builder.add_table(&gasp()).map_err(table_err)?;
            format
        }
        Outlines::Cff(glyphs) => {
            let table = cff(info, &naming, set, glyphs, metrics.bbox);
            builder.add_raw(Tag::new(b"CFF "), table);
            // At most 65535 glyphs: the glyph set checks it.
            builder
                .add_table(&cff_maxp(set.glyphs.len() as u16))
                .map_err(table_err)?;
            0
        }
    };
    builder
        .add_table(&head(&naming, &metrics, index_to_loc_format))
        .map_err(table_err)?;
    builder
        .add_table(&hhea(&metrics, &advances, &boxes))
        .map_err(table_err)?;
    builder
        .add_table(&hmtx(&advances, &boxes))
        .map_err(table_err)?;
    builder.add_table(&cmap(&set.glyphs)?).map_err(table_err)?;
    for (tag, table) in [
        (b"GSUB", &layout.gsub),
        (b"GPOS", &layout.gpos),
        (b"GDEF", &layout.gdef),
    ] {
        if let Some(bytes) = table {
            builder.add_raw(Tag::new(tag), bytes.clone());
        }
    }
    // The legacy table only in the TTF: OTS (the sanitizer in Chrome and Firefox) drops
    // `kern` from fonts without `glyf` ("this table is not for CFF fonts"), and GPOS
    // carries the same pairs.
    if truetype && variable.is_none() {
        if let Some(kern) = legacy_kern(&pairs) {
            builder.add_raw(Tag::new(b"kern"), kern);
        }
    }
    let mut os2 = os2_table(&naming, &metrics, set, !pairs.is_empty());
    let mut name = name_table(info, &naming);
    name.name_record.extend(
        layout
            .names
            .iter()
            .map(|(platform, encoding, language, id, text)| {
                NameRecord::new(
                    *platform,
                    *encoding,
                    *language,
                    NameId::new(*id),
                    text.clone().into(),
                )
            }),
    );
    name.name_record.sort();
    if let Some(variable) = variable {
        if let Some(weight) = variable.weight_class {
            os2.us_weight_class = weight;
        }
        name.name_record.extend(
            variable.names.iter().map(|(id, text)| {
                NameRecord::new(3, 1, 0x409, NameId::new(*id), text.clone().into())
            }),
        );
        name.name_record.sort();
    }
    builder.add_table(&os2).map_err(table_err)?;
    builder.add_table(&name).map_err(table_err)?;
    builder
        .add_table(&post(&set.glyphs, info.units_per_em, truetype))
        .map_err(table_err)?;
    Ok(builder)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::otf::OtGlyph;
    use kurbo::BezPath;

    pub(crate) use crate::model::test_info as info;

    /// [`info`]'s metrics with the box `(-10, -200, 900, 750)`.
    pub(crate) fn metrics() -> Metrics {
        Metrics::new(&info(), &[Some((-10, -200, 900, 750))]).expect("metrics in range")
    }

    /// A glyph with an empty outline and its name as PostScript name.
    pub(crate) fn ot_glyph(name: &str, unicodes: &[char], advance: u16) -> OtGlyph<'static> {
        OtGlyph {
            model_name: name.into(),
            ps_name: name.into(),
            unicodes: unicodes.to_vec(),
            advance,
            path: crate::otf::OtPath::Given(std::borrow::Cow::Owned(BezPath::new())),
            from_components: false,
            anchors: Vec::new(),
            outline_mark: false,
        }
    }

    #[test]
    fn metrics_on_the_grid_and_the_union_of_boxes() {
        let mut font_info = info();
        font_info.x_height = 499.6;
        let boxes = [Some((0, -5, 400, 700)), None, Some((-20, 0, 300, 720))];
        let m = Metrics::new(&font_info, &boxes).expect("in range");
        assert_eq!(
            m,
            Metrics {
                upm: 1000,
                ascender: 800,
                descender: -200,
                line_ascender: 800,
                line_descender: -200,
                x_height: 500,
                cap_height: 700,
                bbox: (-20, -5, 400, 720),
            }
        );
        // An accent above the ascender and a tail below the descender widen the line box.
        let tall = Metrics::new(&font_info, &[Some((0, -230, 500, 935))]).expect("in range");
        assert_eq!((tall.ascender, tall.descender), (800, -200));
        assert_eq!((tall.line_ascender, tall.line_descender), (935, -230));
        assert_eq!(
            Metrics::new(&font_info, &[None]).expect("in range").bbox,
            (0, 0, 0, 0)
        );
        font_info.ascender = 40_000.0;
        assert!(matches!(
            Metrics::new(&font_info, &boxes),
            Err(OtfError::OutOfRange { .. })
        ));
    }

    #[test]
    fn cff_boxes_are_tight_truetype_boxes_hold_the_points() {
        let mut arc = BezPath::new();
        arc.move_to((0.0, 0.0));
        arc.curve_to((0.0, 100.0), (100.0, 100.0), (100.0, 0.0));
        arc.close_path();
        // The curve peaks at y = 75; its control points reach 100.
        let boxes = glyph_boxes(&Outlines::Cff(vec![
            CffGlyph::new(&arc),
            CffGlyph::new(&BezPath::new()),
        ]));
        assert_eq!(boxes, [Some((0, 0, 100, 75)), None]);
    }
}
