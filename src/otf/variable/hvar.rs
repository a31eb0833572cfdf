//! `HVAR`: advance-width deltas per glyph, glyph ids as implicit indices (no mapping).
//!
//! The same deltas as the phantom points of `gvar`; HVAR lets a consumer get advances
//! without reading outlines.

use write_fonts::tables::hvar::Hvar;
use write_fonts::tables::variations::ivs_builder::VariationStoreBuilder;
use write_fonts::tables::variations::{RegionAxisCoordinates, VariationRegion};
use write_fonts::types::F2Dot14;

use crate::designspace::Region;
use crate::otf::OtfError;

/// A region as an item-variation-store region (0, 0, 0 on the axes it does not use).
pub fn variation_region(region: &Region, axis_count: usize) -> VariationRegion {
    VariationRegion::new(
        region_axes(region, axis_count)
            .map(|[start, peak, end]| {
                let f = F2Dot14::from_f32;
                RegionAxisCoordinates::new(f(start), f(peak), f(end))
            })
            .collect(),
    )
}

/// A region's (start, peak, end) per axis, normalized: its tents, zeros on the axes it
/// does not use.
pub(crate) fn region_axes(region: &Region, axis_count: usize) -> impl Iterator<Item = [f32; 3]> {
    region
        .per_axis(axis_count)
        .into_iter()
        .map(|t| t.map(|v| v as f32))
}

/// The `HVAR` table: per glyph, the regions of its masters and the advance's delta for
/// each.
pub fn hvar(axis_count: u16, advance_deltas: &[(&[Region], Vec<i16>)]) -> Result<Hvar, OtfError> {
    let mut builder = VariationStoreBuilder::new_with_implicit_indices(axis_count);
    let ids: Vec<_> = advance_deltas
        .iter()
        .map(|(regions, deltas)| {
            builder.add_deltas(
                regions
                    .iter()
                    .zip(deltas)
                    .map(|(r, &d)| (variation_region(r, usize::from(axis_count)), d))
                    .collect(),
            )
        })
        .collect();
    let (store, map) = builder.build();
    // Implicit indices: the builder keeps one row per glyph, in glyph order.
    for (gid, id) in ids.into_iter().enumerate() {
        let index = map.get(id);
        if index.map(|v| {
            (
                v.delta_set_outer_index,
                usize::from(v.delta_set_inner_index),
            )
        }) != Some((0, gid))
        {
            return Err(OtfError::Table(format!(
                "HVAR: glyph {gid} is not at its implicit index"
            )));
        }
    }
    Ok(Hvar::new(store, None, None, None))
}
