//! The `head` table: revision, units per em, the font box, style bits and fixed dates.

use write_fonts::tables::head::{Flags, Head, MacStyle};
use write_fonts::types::{Fixed, LongDateTime};

use super::naming::Naming;
use super::tables::Metrics;

/// `head.created` and `head.modified`: a fixed 2020-01-01T00:00:00Z (seconds since
/// 1904), not the build time, so the same model always gives the same bytes. (Zero would
/// do too, but fontTools then warns that the date "seems very low".)
pub const FIXED_DATE: i64 = 3_660_681_600;

/// Smallest readable size in pixels per em.
const LOWEST_REC_PPEM: u16 = 8;

/// `head` for the font; `index_to_loc_format` is `glyf`'s (0 for CFF).
pub fn head(naming: &Naming, metrics: &Metrics, index_to_loc_format: i16) -> Head {
    let mut mac_style = MacStyle::empty();
    if naming.bold() {
        mac_style |= MacStyle::BOLD;
    }
    if naming.italic {
        mac_style |= MacStyle::ITALIC;
    }
    let (x_min, y_min, x_max, y_max) = metrics.bbox;
    Head::new(
        Fixed::from_f64(naming.revision),
        0,
        Flags::BASELINE_AT_Y_0 | Flags::LSB_AT_X_0 | Flags::FORCE_INTEGER_PPEM,
        metrics.upm,
        LongDateTime::new(FIXED_DATE),
        LongDateTime::new(FIXED_DATE),
        x_min,
        y_min,
        x_max,
        y_max,
        mac_style,
        LOWEST_REC_PPEM,
        index_to_loc_format,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::otf::tables::tests::{info, metrics};

    #[test]
    fn fields() {
        let mut font_info = info();
        font_info.style = "Bold Italic".into();
        font_info.version = Some("1.5".into());
        let head = head(&Naming::new(&font_info), &metrics(), 1);
        assert_eq!(head.font_revision, Fixed::from_f64(1.5));
        assert_eq!(head.units_per_em, 1000);
        assert_eq!(
            (head.x_min, head.y_min, head.x_max, head.y_max),
            (-10, -200, 900, 750)
        );
        assert_eq!(head.mac_style, MacStyle::BOLD | MacStyle::ITALIC);
        assert_eq!(head.index_to_loc_format, 1);
        assert_eq!(head.created, LongDateTime::new(3_660_681_600));
        assert_eq!(head.modified, head.created);
        assert_eq!(head.lowest_rec_ppem, 8);
        assert!(head
            .flags
            .contains(Flags::BASELINE_AT_Y_0 | Flags::LSB_AT_X_0));
        let regular = super::head(&Naming::new(&info()), &metrics(), 0);
        assert_eq!(regular.mac_style, MacStyle::empty());
        assert_eq!(regular.font_revision, Fixed::from_f64(1.0));
    }
}
