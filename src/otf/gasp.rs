//! The `gasp` table: how rasterizers should grid-fit and smooth the TrueType outlines.
//!
//! xglyph does not hint, so one range covers every size and turns everything on (grid
//! fitting, greyscale, and their ClearType "symmetric" forms): with no glyph programs,
//! grid fitting only applies the dropout control of [`super::prep`], and the smoothing
//! flags ask for antialiasing at every size. This is what fontmake and gftools write for
//! unhinted fonts.

use write_fonts::tables::gasp::{Gasp, GaspRange, GaspRangeBehavior};

/// `gasp` version 1 with one range up to 65535 ppem, all four behaviours set.
pub fn gasp() -> Gasp {
    let all = GaspRangeBehavior::GASP_GRIDFIT
        | GaspRangeBehavior::GASP_DOGRAY
        | GaspRangeBehavior::GASP_SYMMETRIC_GRIDFIT
        | GaspRangeBehavior::GASP_SYMMETRIC_SMOOTHING;
    Gasp::new(
        1,
        1,
        vec![GaspRange {
            range_max_ppem: u16::MAX,
            range_gasp_behavior: all,
        }],
    )
}

#[cfg(test)]
mod tests {
    use write_fonts::dump_table;

    use super::*;

    #[test]
    fn one_range_with_every_behaviour() {
        let bytes = dump_table(&gasp()).expect("gasp compiles");
        // version 1, one range, up to ppem 0xFFFF, flags 0x000F.
        assert_eq!(bytes, [0, 1, 0, 1, 0xFF, 0xFF, 0, 0x0F]);
    }
}
