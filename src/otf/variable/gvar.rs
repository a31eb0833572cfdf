//! `gvar`: per glyph and master, the point deltas (phantom points last).

use write_fonts::tables::gvar::{GlyphDeltas, GlyphVariations, Gvar, Tent};
use write_fonts::types::{F2Dot14, GlyphId};

use super::MasterDeltas;
use crate::designspace::Region;
use crate::otf::OtfError;

/// A region as one tent per axis: peak 0 (no effect) on the axes it does not use.
fn tents(region: &Region, axis_count: usize) -> Vec<Tent> {
    region
        .per_axis(axis_count)
        .into_iter()
        .map(|[lower, peak, upper]| {
            if peak == 0.0 {
                Tent::new(F2Dot14::ZERO, None)
            } else {
                let f = |v: f64| F2Dot14::from_f32(v as f32);
                Tent::new(f(peak), Some((f(lower), f(upper))))
            }
        })
        .collect()
}

/// The `gvar` table: per glyph, the regions of its masters (its model's: with sparse
/// masters, each glyph has its own) and `deltas[master]`, the glyph's point deltas (outline
/// points, then the four phantom points) for the master of `regions[master]`, those a
/// consumer infers marked optional ([`super::iup`]). A master whose deltas are all zero
/// for a glyph adds no tuple.
pub fn gvar(axis_count: u16, glyphs: &[(&[Region], MasterDeltas)]) -> Result<Gvar, OtfError> {
    let variations = glyphs
        .iter()
        .enumerate()
        .map(|(gid, (regions, masters))| {
            let tuples = masters
                .iter()
                .zip(regions.iter())
                .filter(|(d, _)| d.iter().any(|d| d.x != 0 || d.y != 0))
                .map(|(d, region)| {
                    GlyphDeltas::new(tents(region, usize::from(axis_count)), d.clone())
                })
                .collect();
            GlyphVariations::new(GlyphId::new(gid as u32), tuples)
        })
        .collect();
    Gvar::new(variations, axis_count).map_err(|e| OtfError::Table(format!("gvar: {e}")))
}
