//! The OS/2 table: metrics, weight and style bits, Unicode ranges.
//!
//! Typo and win ascender/descender are both the line box of [`Metrics`] (the model's,
//! widened to the font's ink box), with USE_TYPO_METRICS and line gap 0: browsers, macOS
//! and Windows then space lines alike and clip nothing. The vendor ID is `font.toml`'s
//! `vendor`, default [`crate::model::DEFAULT_VENDOR`]. Sub/superscript and strikeout values
//! are the usual fractions of the em.
//!
//! Limits: Unicode ranges cover the blocks in [`UNICODE_RANGES`] plus the
//! supplementary-plane bit; the code page range marks Latin 1 only.

use write_fonts::tables::os2::{Os2, SelectionFlags};

use super::naming::Naming;
use super::tables::Metrics;
use super::GlyphSet;

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

/// The OS/2 table (version 4) for the glyphs of `set`.
pub fn os2_table(naming: &Naming, metrics: &Metrics, set: &GlyphSet, has_kerning: bool) -> Os2 {
    let Metrics {
        upm,
        line_ascender,
        line_descender,
        x_height,
        cap_height,
        ..
    } = *metrics;
    let em = f64::from(upm);
    let advances: Vec<u16> = set.glyphs.iter().map(|g| g.advance).collect();
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
    Os2 {
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
        ach_vend_id: naming.vendor,
        fs_selection: selection,
        us_first_char_index: code_points
            .iter()
            .min()
            .map_or(0, |&c| c.min(0xFFFF) as u16),
        us_last_char_index: code_points
            .iter()
            .max()
            .map_or(0, |&c| c.min(0xFFFF) as u16),
        s_typo_ascender: line_ascender,
        s_typo_descender: line_descender,
        s_typo_line_gap: 0,
        us_win_ascent: line_ascender.max(0) as u16,
        us_win_descent: (-i32::from(line_descender)).max(0) as u16,
        ul_code_page_range_1: Some(u32::from(
            code_points.iter().any(|&c| (0x20..=0xFF).contains(&c)),
        )),
        ul_code_page_range_2: Some(0),
        sx_height: Some(x_height),
        s_cap_height: Some(cap_height),
        us_default_char: Some(0),
        us_break_char: Some(0x20),
        us_max_context: Some(if has_kerning { 2 } else { 0 }),
        us_lower_optical_point_size: None,
        us_upper_optical_point_size: None,
    }
}
