//! Kerning with variations: the GPOS `kern` pairs of the default master, each with a
//! VariationIndex device table pointing into the item variation store in `GDEF`.
//!
//! A pair is kerned when any master kerns it (a master that lacks it has 0 there). Values
//! are rounded per master, the deltas are rounded master − rounded default, as for points.

use std::collections::BTreeMap;

use write_fonts::tables::gdef::Gdef;
use write_fonts::tables::gpos::{Gpos, PairSet, PairValueRecord, ValueRecord};
use write_fonts::tables::layout::{DeviceOrVariationIndex, VariationIndex};
use write_fonts::tables::variations::ivs_builder::VariationStoreBuilder;
use write_fonts::types::GlyphId16;

use super::hvar::variation_region;
use crate::designspace::Region;
use crate::otf::kern::{kern_gpos, KernPairs};
use crate::otf::OtfError;

/// GPOS and GDEF for the kerning of the default master (`pairs[0]`) and the masters of
/// `regions` (`pairs[1..]`), or `None` when no master kerns.
pub fn gpos_gdef(
    pairs: &[KernPairs],
    regions: &[Region],
    axis_count: u16,
) -> Result<Option<(Gpos, Gdef)>, OtfError> {
    // Every kerned pair: first -> second -> value per master.
    let mut all: BTreeMap<u16, BTreeMap<u16, Vec<i16>>> = BTreeMap::new();
    for (m, master) in pairs.iter().enumerate() {
        for (&left, seconds) in master {
            for (&right, &value) in seconds {
                all.entry(left)
                    .or_default()
                    .entry(right)
                    .or_insert_with(|| vec![0; pairs.len()])[m] = value;
            }
        }
    }
    if all.is_empty() {
        return Ok(None);
    }
    let mut builder = VariationStoreBuilder::new(axis_count);
    let mut ids = Vec::new();
    for seconds in all.values() {
        for values in seconds.values() {
            let deltas = regions
                .iter()
                .zip(&values[1..])
                .map(|(r, &v)| {
                    let delta = i32::from(v) - i32::from(values[0]);
                    (variation_region(r, usize::from(axis_count)), delta)
                })
                .collect();
            ids.push(builder.add_deltas(deltas));
        }
    }
    let (store, map) = builder.build();
    let mut ids = ids.into_iter();
    let mut pair_sets = Vec::with_capacity(all.len());
    for seconds in all.values() {
        let mut records = Vec::with_capacity(seconds.len());
        for (&second, values) in seconds {
            let index = ids
                .next()
                .and_then(|id| map.get(id))
                .ok_or_else(|| OtfError::Table("GDEF: a kerning delta set was lost".into()))?;
            let mut value = ValueRecord::new().with_x_advance(values[0]);
            value.x_advance_device = DeviceOrVariationIndex::VariationIndex(VariationIndex::new(
                index.delta_set_outer_index,
                index.delta_set_inner_index,
            ))
            .into();
            records.push(PairValueRecord::new(
                GlyphId16::new(second),
                value,
                ValueRecord::new(),
            ));
        }
        pair_sets.push(PairSet::new(records));
    }
    let coverage = all.keys().map(|&g| GlyphId16::new(g)).collect();
    let mut gdef = Gdef::new(None, None, None, None);
    gdef.item_var_store = store.into();
    Ok(Some((kern_gpos(coverage, pair_sets), gdef)))
}
