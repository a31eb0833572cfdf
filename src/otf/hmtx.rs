//! Horizontal metrics: `hhea` (font-wide extremes) and `hmtx` (advance and left side
//! bearing per glyph). Side bearings and extents count inked glyphs only.

use write_fonts::tables::hhea::Hhea;
use write_fonts::tables::hmtx::{Hmtx, LongMetric};
use write_fonts::types::{FWord, UfWord};

use super::tables::{GridBox, Metrics};

/// `hmtx`: one long metric per glyph, the left side bearing being the box's x minimum
/// (0 for an empty glyph).
pub fn hmtx(advances: &[u16], boxes: &[Option<GridBox>]) -> Hmtx {
    let metrics = advances
        .iter()
        .zip(boxes)
        .map(|(&adv, b)| LongMetric::new(adv, b.map_or(0, |b| b.0)))
        .collect();
    Hmtx::new(metrics, Vec::new())
}

/// `hhea`: the line box of [`Metrics`] (the same as OS/2 typo), line gap 0, and the
/// extremes of `hmtx`.
pub fn hhea(metrics: &Metrics, advances: &[u16], boxes: &[Option<GridBox>]) -> Hhea {
    let inked = || {
        advances
            .iter()
            .zip(boxes)
            .filter_map(|(&a, b)| b.map(|b| (a, b)))
    };
    let min_lsb = inked().map(|(_, b)| b.0).min().unwrap_or(0);
    let min_rsb = inked()
        .map(|(a, b)| (i32::from(a) - i32::from(b.2)).clamp(-32768, 32767) as i16)
        .min()
        .unwrap_or(0);
    let x_max_extent = inked().map(|(_, b)| b.2).max().unwrap_or(0);
    Hhea::new(
        FWord::new(metrics.line_ascender),
        FWord::new(metrics.line_descender),
        FWord::new(0),
        UfWord::new(advances.iter().copied().max().unwrap_or(0)),
        FWord::new(min_lsb),
        FWord::new(min_rsb),
        FWord::new(x_max_extent),
        1,
        0,
        0,
        // At most 65535 glyphs: the glyph set checks it.
        advances.len().min(usize::from(u16::MAX)) as u16,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::otf::tables::tests::metrics;

    const ADVANCES: [u16; 3] = [500, 600, 0];
    const BOXES: [Option<GridBox>; 3] = [Some((50, 0, 450, 700)), Some((-10, 0, 640, 720)), None];

    #[test]
    fn side_bearings_and_extremes() {
        let hhea = hhea(&metrics(), &ADVANCES, &BOXES);
        assert_eq!(hhea.ascender, FWord::new(800));
        assert_eq!(hhea.descender, FWord::new(-200));
        assert_eq!(hhea.line_gap, FWord::new(0));
        assert_eq!(hhea.advance_width_max, UfWord::new(600));
        // The empty third glyph counts for neither bearing nor extent.
        assert_eq!(hhea.min_left_side_bearing, FWord::new(-10));
        assert_eq!(hhea.min_right_side_bearing, FWord::new(-40));
        assert_eq!(hhea.x_max_extent, FWord::new(640));
        assert_eq!(hhea.number_of_h_metrics, 3);
        assert_eq!(hhea.caret_slope_rise, 1);
    }

    #[test]
    fn one_metric_per_glyph() {
        let hmtx = hmtx(&ADVANCES, &BOXES);
        let got: Vec<(u16, i16)> = hmtx
            .h_metrics
            .iter()
            .map(|m| (m.advance, m.side_bearing))
            .collect();
        assert_eq!(got, [(500, 50), (600, -10), (0, 0)]);
        assert!(hmtx.left_side_bearings.is_empty());
    }
}
