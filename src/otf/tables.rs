//! The tables both flavours share (head, hhea, hmtx, maxp, cmap, name, OS/2, post,
//! GPOS, kern), assembled with write-fonts' `FontBuilder` around the outline tables.
//!
//! Vertical metrics are the model's ascender and descender everywhere (hhea, OS/2 typo with
//! USE_TYPO_METRICS, line gap 0); OS/2 win ascent/descent additionally cover the union of
//! the glyph boxes so no glyph is clipped on Windows.
//!
//! Limits: OS/2 Unicode ranges cover the Latin, Greek, Cyrillic and punctuation blocks
//! listed in [`UNICODE_RANGES`] plus the supplementary-plane bit; code page ranges mark
//! Latin 1 only. Weight class and style bits are read from the style name's words.

use kurbo::{BezPath, Shape};
use write_fonts::tables::cmap::Cmap;
use write_fonts::tables::head::{Flags, Head, MacStyle};
use write_fonts::tables::hhea::Hhea;
use write_fonts::tables::hmtx::{Hmtx, LongMetric};
use write_fonts::tables::maxp::Maxp;
use write_fonts::tables::name::{Name, NameRecord};
use write_fonts::tables::os2::{Os2, SelectionFlags};
use write_fonts::tables::post::Post;
use write_fonts::types::{
    FWord, Fixed, GlyphId, LongDateTime, NameId, Tag, UfWord, Version16Dot16,
};
use write_fonts::FontBuilder;

use super::cff::{cff_table, CffInfo};
use super::charstring::charstring;
use super::kern::{gpos, kern_pairs, legacy_kern};
use super::truetype::{glyf_loca, TtGlyph};
use super::{GlyphSet, OtfError};
use crate::model::Font;

/// The outline data of one flavour, in glyph order.
pub enum Outlines {
    TrueType(Vec<TtGlyph>),
    /// Cubic paths already on the grid.
    Cff(Vec<BezPath>),
}

/// OS/2 Unicode range bits for the blocks xglyph knows about: (bit, first, last).
const UNICODE_RANGES: &[(u32, u32, u32)] = &[
    (0, 0x0000, 0x007F),  // Basic Latin
    (1, 0x0080, 0x00FF),  // Latin-1 Supplement
    (2, 0x0100, 0x017F),  // Latin Extended-A
    (3, 0x0180, 0x024F),  // Latin Extended-B
    (4, 0x0250, 0x02AF),  // IPA Extensions
    (5, 0x02B0, 0x02FF),  // Spacing Modifier Letters
    (6, 0x0300, 0x036F),  // Combining Diacritical Marks
    (7, 0x0370, 0x03FF),  // Greek and Coptic
    (9, 0x0400, 0x04FF),  // Cyrillic
    (29, 0x1E00, 0x1EFF), // Latin Extended Additional
    (31, 0x2000, 0x206F), // General Punctuation
    (33, 0x20A0, 0x20CF), // Currency Symbols
    (60, 0xE000, 0xF8FF), // Private Use Area
];

/// `head.created` and `head.modified`: a fixed 2020-01-01T00:00:00Z (seconds since
/// 1904), not the build time, so the same model always gives the same bytes. (Zero would
/// do too, but fontTools then warns that the date "seems very low".)
const FIXED_DATE: i64 = 3_660_681_600;

/// Names and style facts derived from `font.toml`.
struct Naming {
    family: String,
    style: String,
    ps_name: String,
    full_name: String,
    version_text: String,
    revision: f64,
    weight: u16,
    italic: bool,
    /// Style is one of Regular, Italic, Bold, Bold Italic.
    ribbi: bool,
}

impl Naming {
    fn new(font: &Font) -> Self {
        let family = font.info.family.trim().to_owned();
        let style = font.info.style.trim().to_owned();
        let (revision, version_text) = parse_version(font.info.version.as_deref());
        let words: Vec<String> = style.split_whitespace().map(str::to_lowercase).collect();
        let compact: String = words.concat();
        let italic = words.iter().any(|w| w == "italic" || w == "oblique");
        const WEIGHTS: &[(&str, u16)] = &[
            ("extralight", 200),
            ("ultralight", 200),
            ("semibold", 600),
            ("demibold", 600),
            ("extrabold", 800),
            ("ultrabold", 800),
            ("thin", 100),
            ("light", 300),
            ("medium", 500),
            ("bold", 700),
            ("black", 900),
            ("heavy", 900),
        ];
        let weight = WEIGHTS
            .iter()
            .find(|(w, _)| compact.contains(w))
            .map_or(400, |&(_, v)| v);
        let ribbi = matches!(
            style.as_str(),
            "Regular" | "Italic" | "Bold" | "Bold Italic"
        );
        Naming {
            ps_name: ps_font_name(&family, &style),
            full_name: format!("{family} {style}"),
            family,
            style,
            version_text,
            revision,
            weight,
            italic,
            ribbi,
        }
    }

    fn bold(&self) -> bool {
        self.ribbi && self.weight == 700
    }
}

/// `(font revision, name ID 5 text)`: `1.2` gives `(1.2, "Version 1.200")`; text that is
/// not a number is kept after a default `Version 1.000; `.
fn parse_version(version: Option<&str>) -> (f64, String) {
    let Some(text) = version.map(str::trim) else {
        return (1.0, "Version 1.000".into());
    };
    let bare = text.strip_prefix("Version ").unwrap_or(text);
    match bare.parse::<f64>() {
        Ok(v) if v.is_finite() && (0.0..32768.0).contains(&v) => (v, format!("Version {v:.3}")),
        _ => (1.0, format!("Version 1.000; {text}")),
    }
}

/// PostScript font name: `Family-Style` without spaces, printable ASCII other than
/// `[](){}<>/%`, at most 63 characters.
fn ps_font_name(family: &str, style: &str) -> String {
    let clean = |s: &str| -> String {
        s.chars()
            .filter(|c| c.is_ascii_graphic() && !"[](){}<>/%".contains(*c))
            .collect()
    };
    let mut family = clean(family);
    if family.is_empty() {
        family = "Untitled".into();
    }
    let style = clean(style);
    let mut name = if style.is_empty() {
        family
    } else {
        format!("{family}-{style}")
    };
    name.truncate(63);
    name
}

/// A glyph's box on the grid: `(x_min, y_min, x_max, y_max)`.
type GridBox = (i16, i16, i16, i16);

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
    let metrics: Vec<LongMetric> = advances
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
        .add_table(&Hmtx::new(metrics, Vec::new()))
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
    // The legacy table only in the TTF: OTS (and with it Chrome and Firefox) drops `kern`
    // from CFF-flavoured fonts, and GPOS carries the same pairs.
    if matches!(outlines, Outlines::TrueType(_)) {
        if let Some(kern) = legacy_kern(&pairs) {
            builder.add_raw(Tag::new(b"kern"), kern);
        }
    }

    // OS/2
    let code_points: Vec<u32> = set
        .glyphs
        .iter()
        .flat_map(|g| g.unicodes.iter().map(|&c| u32::from(c)))
        .collect();
    let mut ranges = [0u32; 4];
    for &(bit, first, last) in UNICODE_RANGES {
        if code_points.iter().any(|&c| (first..=last).contains(&c)) {
            ranges[(bit / 32) as usize] |= 1 << (bit % 32);
        }
    }
    if code_points.iter().any(|&c| c > 0xFFFF) {
        ranges[1] |= 1 << (57 - 32);
    }
    let nonzero: Vec<f64> = advances
        .iter()
        .filter(|&&a| a > 0)
        .map(|&a| f64::from(a))
        .collect();
    let avg_width = if nonzero.is_empty() {
        0
    } else {
        (nonzero.iter().sum::<f64>() / nonzero.len() as f64).round() as i16
    };
    let mut selection = SelectionFlags::USE_TYPO_METRICS;
    if naming.italic {
        selection |= SelectionFlags::ITALIC;
    }
    if naming.bold() {
        selection |= SelectionFlags::BOLD;
    }
    if !naming.italic && !naming.bold() {
        selection |= SelectionFlags::REGULAR;
    }
    let scaled = |f: f64| (em * f).round() as i16;
    let os2 = Os2 {
        x_avg_char_width: avg_width,
        us_weight_class: naming.weight,
        us_width_class: 5,
        fs_type: 0,
        y_subscript_x_size: scaled(0.65),
        y_subscript_y_size: scaled(0.6),
        y_subscript_x_offset: 0,
        y_subscript_y_offset: scaled(0.075),
        y_superscript_x_size: scaled(0.65),
        y_superscript_y_size: scaled(0.6),
        y_superscript_x_offset: 0,
        y_superscript_y_offset: scaled(0.35),
        y_strikeout_size: scaled(0.05),
        y_strikeout_position: (f64::from(x_height) * 0.6).round() as i16,
        s_family_class: 0,
        panose_10: [0; 10],
        ul_unicode_range_1: ranges[0],
        ul_unicode_range_2: ranges[1],
        ul_unicode_range_3: ranges[2],
        ul_unicode_range_4: ranges[3],
        ach_vend_id: Tag::new(b"NONE"),
        fs_selection: selection,
        us_first_char_index: code_points
            .iter()
            .min()
            .map_or(0, |&c| c.min(0xFFFF) as u16),
        us_last_char_index: code_points
            .iter()
            .max()
            .map_or(0, |&c| c.min(0xFFFF) as u16),
        s_typo_ascender: ascender,
        s_typo_descender: descender,
        s_typo_line_gap: 0,
        us_win_ascent: ascender.max(bbox.3).max(0) as u16,
        us_win_descent: (-i32::from(descender.min(bbox.1))).max(0) as u16,
        ul_code_page_range_1: Some(u32::from(
            code_points.iter().any(|&c| (0x20..=0xFF).contains(&c)),
        )),
        ul_code_page_range_2: Some(0),
        sx_height: Some(x_height),
        s_cap_height: Some(cap_height),
        us_default_char: Some(0),
        us_break_char: Some(0x20),
        us_max_context: Some(if pairs.is_empty() { 0 } else { 2 }),
        us_lower_optical_point_size: None,
        us_upper_optical_point_size: None,
    };
    builder.add_table(&os2).map_err(table_err)?;

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
    post.underline_position = FWord::new(-scaled(0.075));
    post.underline_thickness = FWord::new(scaled(0.05));
    post.is_fixed_pitch = u32::from(fixed_pitch);
    builder.add_table(&post).map_err(table_err)?;

    Ok(builder.build())
}

/// Windows (3, 1, en-US) name records, sorted by name ID.
fn name_table(font: &Font, naming: &Naming) -> Name {
    let mut records: Vec<(u16, String)> = Vec::new();
    if let Some(c) = &font.info.copyright {
        records.push((0, c.clone()));
    }
    let (family1, style2) = if naming.ribbi {
        (naming.family.clone(), naming.style.clone())
    } else {
        let rest: Vec<&str> = naming
            .style
            .split_whitespace()
            .filter(|w| !w.eq_ignore_ascii_case("italic"))
            .collect();
        let style2 = if naming.italic { "Italic" } else { "Regular" };
        let family1 = if rest.is_empty() {
            naming.family.clone()
        } else {
            format!("{} {}", naming.family, rest.join(" "))
        };
        (family1, style2.to_owned())
    };
    records.push((1, family1));
    records.push((2, style2));
    let short_version = naming
        .version_text
        .strip_prefix("Version ")
        .unwrap_or(&naming.version_text)
        .split(';')
        .next()
        .unwrap_or("1.000")
        .to_owned();
    records.push((3, format!("{short_version};NONE;{}", naming.ps_name)));
    records.push((4, naming.full_name.clone()));
    records.push((5, naming.version_text.clone()));
    records.push((6, naming.ps_name.clone()));
    if let Some(d) = &font.info.designer {
        records.push((9, d.clone()));
    }
    if !naming.ribbi {
        records.push((16, naming.family.clone()));
        records.push((17, naming.style.clone()));
    }
    Name::new(
        records
            .into_iter()
            .map(|(id, text)| NameRecord::new(3, 1, 0x409, NameId::new(id), text.into()))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn versions() {
        assert_eq!(parse_version(None), (1.0, "Version 1.000".into()));
        assert_eq!(parse_version(Some("1.2")), (1.2, "Version 1.200".into()));
        assert_eq!(
            parse_version(Some("Version 2.015")),
            (2.015, "Version 2.015".into())
        );
        assert_eq!(
            parse_version(Some("beta 3")),
            (1.0, "Version 1.000; beta 3".into())
        );
    }

    #[test]
    fn postscript_font_names() {
        assert_eq!(ps_font_name("Mini Test", "Regular"), "MiniTest-Regular");
        assert_eq!(ps_font_name("A (b) c%", "Bold Italic"), "Abc-BoldItalic");
        assert_eq!(ps_font_name("Größe", ""), "Gre");
        assert_eq!(ps_font_name(&"x".repeat(80), "Regular").len(), 63);
    }
}
