//! The tables both flavours share (head, hhea, hmtx, maxp, cmap, name, OS/2, post,
//! GPOS, kern), assembled with write-fonts' `FontBuilder` around the outline tables.
//!
//! Vertical metrics are the model's ascender and descender everywhere (hhea, OS/2 typo with
//! USE_TYPO_METRICS, line gap 0; see [`super::os2`]); names come from [`super::naming`].
//! Glyph boxes: the control box of the points for `glyf` (what TrueType stores), the tight
//! box for CFF (what CFF consumers compute); `hmtx` side bearings are their x minimum.

use kurbo::{BezPath, Shape};
use write_fonts::tables::cmap::Cmap;
use write_fonts::tables::head::{Flags, Head, MacStyle};
use write_fonts::tables::hhea::Hhea;
use write_fonts::tables::hmtx::{Hmtx, LongMetric};
use write_fonts::tables::maxp::Maxp;
use write_fonts::tables::post::Post;
use write_fonts::types::{FWord, Fixed, GlyphId, LongDateTime, Tag, UfWord, Version16Dot16};
use write_fonts::FontBuilder;

use super::cff::{cff_table, CffInfo};
use super::charstring::charstring;
use super::kern::{gpos, kern_pairs, legacy_kern};
use super::naming::{name_table, Naming};
use super::os2::os2_table;
use super::truetype::{glyf_loca, TtGlyph};
use super::{GlyphSet, OtfError};
use crate::model::Font;

/// The outline data of one flavour, in glyph order.
pub enum Outlines {
    TrueType(Vec<TtGlyph>),
    /// Cubic paths already on the grid.
    Cff(Vec<BezPath>),
}

/// Vertical metrics on the grid and the union of the glyph boxes (head, hhea, OS/2).
#[derive(Clone, Copy, Debug)]
pub struct Metrics {
    pub upm: u16,
    pub ascender: i16,
    pub descender: i16,
    pub x_height: i16,
    pub cap_height: i16,
    pub bbox: GridBox,
}

/// `head.created` and `head.modified`: a fixed 2020-01-01T00:00:00Z (seconds since
/// 1904), not the build time, so the same model always gives the same bytes. (Zero would
/// do too, but fontTools then warns that the date "seems very low".)
const FIXED_DATE: i64 = 3_660_681_600;

/// A box on the grid: `(x_min, y_min, x_max, y_max)`.
pub type GridBox = (i16, i16, i16, i16);

fn glyph_boxes(outlines: &Outlines) -> Vec<Option<GridBox>> {
    match outlines {
        Outlines::TrueType(glyphs) => glyphs
            .iter()
            .map(|g| g.bbox().map(|b| (b.x_min, b.y_min, b.x_max, b.y_max)))
            .collect(),
        Outlines::Cff(paths) => paths
            .iter()
            .map(|p| {
                if p.elements().is_empty() {
                    return None;
                }
                // Tight bounds (curve extrema), as CFF consumers compute them.
                let r = p.bounding_box();
                Some((
                    r.x0.floor() as i16,
                    r.y0.floor() as i16,
                    r.x1.ceil() as i16,
                    r.y1.ceil() as i16,
                ))
            })
            .collect(),
    }
}

/// The whole font file.
pub fn build_font(font: &Font, set: &GlyphSet, outlines: Outlines) -> Result<Vec<u8>, OtfError> {
    let naming = Naming::new(font);
    let info = &font.info;
    let upm = info.units_per_em;
    let em = f64::from(upm);
    let ascender = super::grid::to_i16(info.ascender, || "ascender".into())?;
    let descender = super::grid::to_i16(info.descender, || "descender".into())?;
    let x_height = super::grid::to_i16(info.x_height, || "x_height".into())?;
    let cap_height = super::grid::to_i16(info.cap_height, || "cap_height".into())?;

    let boxes = glyph_boxes(&outlines);
    let bbox = boxes
        .iter()
        .flatten()
        .copied()
        .reduce(|a, b| (a.0.min(b.0), a.1.min(b.1), a.2.max(b.2), a.3.max(b.3)))
        .unwrap_or((0, 0, 0, 0));
    let metrics = Metrics {
        upm,
        ascender,
        descender,
        x_height,
        cap_height,
        bbox,
    };
    let advances: Vec<u16> = set.glyphs.iter().map(|g| g.advance).collect();

    let mut builder = FontBuilder::new();
    let table_err = |e: write_fonts::BuilderError| OtfError::Table(e.to_string());

    // Outline tables.
    let index_to_loc_format = match &outlines {
        Outlines::TrueType(glyphs) => {
            let (glyf, loca, format) = glyf_loca(glyphs)?;
            builder.add_table(&glyf).map_err(table_err)?;
            builder.add_table(&loca).map_err(table_err)?;
            let max_points = glyphs.iter().map(TtGlyph::num_points).max().unwrap_or(0);
            let max_contours = glyphs.iter().map(TtGlyph::num_contours).max().unwrap_or(0);
            let maxp = Maxp {
                num_glyphs: set.glyphs.len() as u16,
                max_points: Some(max_points.min(usize::from(u16::MAX)) as u16),
                max_contours: Some(max_contours.min(usize::from(u16::MAX)) as u16),
                max_composite_points: Some(0),
                max_composite_contours: Some(0),
                max_zones: Some(2),
                max_twilight_points: Some(0),
                max_storage: Some(0),
                max_function_defs: Some(0),
                max_instruction_defs: Some(0),
                max_stack_elements: Some(0),
                max_size_of_instructions: Some(0),
                max_component_elements: Some(0),
                max_component_depth: Some(0),
            };
            builder.add_table(&maxp).map_err(table_err)?;
            format
        }
        Outlines::Cff(paths) => {
            let names: Vec<&str> = set.glyphs.iter().map(|g| g.ps_name.as_str()).collect();
            let charstrings: Vec<Vec<u8>> = paths
                .iter()
                .zip(&advances)
                .map(|(p, &w)| charstring(p, i32::from(w)))
                .collect();
            let version = format!("{:.3}", naming.revision);
            let cff = cff_table(
                &CffInfo {
                    ps_name: &naming.ps_name,
                    version: &version,
                    copyright: info.copyright.as_deref(),
                    full_name: &naming.full_name,
                    family_name: &naming.family,
                    units_per_em: upm,
                    bbox: [bbox.0, bbox.1, bbox.2, bbox.3],
                },
                &names,
                &charstrings,
            );
            builder.add_raw(Tag::new(b"CFF "), cff);
            builder
                .add_table(&Maxp::new(set.glyphs.len() as u16))
                .map_err(table_err)?;
            0
        }
    };

    // head
    let mut mac_style = MacStyle::empty();
    if naming.bold() {
        mac_style |= MacStyle::BOLD;
    }
    if naming.italic {
        mac_style |= MacStyle::ITALIC;
    }
    let head = Head::new(
        Fixed::from_f64(naming.revision),
        0,
        Flags::BASELINE_AT_Y_0 | Flags::LSB_AT_X_0 | Flags::FORCE_INTEGER_PPEM,
        upm,
        LongDateTime::new(FIXED_DATE),
        LongDateTime::new(FIXED_DATE),
        bbox.0,
        bbox.1,
        bbox.2,
        bbox.3,
        mac_style,
        8,
        index_to_loc_format,
    );
    builder.add_table(&head).map_err(table_err)?;

    // hhea + hmtx
    let h_metrics: Vec<LongMetric> = advances
        .iter()
        .zip(&boxes)
        .map(|(&adv, b)| LongMetric::new(adv, b.map_or(0, |b| b.0)))
        .collect();
    let inked = || {
        advances
            .iter()
            .zip(&boxes)
            .filter_map(|(&a, b)| b.map(|b| (a, b)))
    };
    let min_lsb = inked().map(|(_, b)| b.0).min().unwrap_or(0);
    let min_rsb = inked()
        .map(|(a, b)| (i32::from(a) - i32::from(b.2)).clamp(-32768, 32767) as i16)
        .min()
        .unwrap_or(0);
    let x_max_extent = inked().map(|(_, b)| b.2).max().unwrap_or(0);
    let hhea = Hhea::new(
        FWord::new(ascender),
        FWord::new(descender),
        FWord::new(0),
        UfWord::new(advances.iter().copied().max().unwrap_or(0)),
        FWord::new(min_lsb),
        FWord::new(min_rsb),
        FWord::new(x_max_extent),
        1,
        0,
        0,
        set.glyphs.len() as u16,
    );
    builder.add_table(&hhea).map_err(table_err)?;
    builder
        .add_table(&Hmtx::new(h_metrics, Vec::new()))
        .map_err(table_err)?;

    // cmap
    let mappings = set.glyphs.iter().enumerate().flat_map(|(gid, g)| {
        g.unicodes
            .iter()
            .map(move |&c| (c, GlyphId::new(gid as u32)))
    });
    let cmap = Cmap::from_mappings(mappings).map_err(|e| OtfError::CmapConflict(e.to_string()))?;
    builder.add_table(&cmap).map_err(table_err)?;

    // kerning
    let pairs = kern_pairs(font, set)?;
    if let Some(gpos) = gpos(&pairs) {
        builder.add_table(&gpos).map_err(table_err)?;
    }
    // The legacy table only in the TTF: OTS (the sanitizer in Chrome and Firefox) drops
    // `kern` from fonts without `glyf` ("this table is not for CFF fonts"), and GPOS
    // carries the same pairs.
    if matches!(outlines, Outlines::TrueType(_)) {
        if let Some(kern) = legacy_kern(&pairs) {
            builder.add_raw(Tag::new(b"kern"), kern);
        }
    }

    builder
        .add_table(&os2_table(&naming, &metrics, set, !pairs.is_empty()))
        .map_err(table_err)?;

    // name
    builder
        .add_table(&name_table(font, &naming))
        .map_err(table_err)?;

    // post
    let widths: Vec<u16> = advances.iter().copied().filter(|&a| a > 0).collect();
    let fixed_pitch = widths.len() > 1 && widths.iter().all(|&w| w == widths[0]);
    let mut post = match outlines {
        Outlines::TrueType(_) => Post::new_v2(set.glyphs.iter().map(|g| g.ps_name.as_str())),
        Outlines::Cff(_) => Post {
            version: Version16Dot16::VERSION_3_0,
            ..Default::default()
        },
    };
    let scaled = |f: f64| (em * f).round() as i16;
    post.underline_position = FWord::new(-scaled(0.075));
    post.underline_thickness = FWord::new(scaled(0.05));
    post.is_fixed_pitch = u32::from(fixed_pitch);
    builder.add_table(&post).map_err(table_err)?;

    Ok(builder.build())
}
