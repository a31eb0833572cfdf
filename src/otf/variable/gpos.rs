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

#[cfg(test)]
mod tests {
    use super::*;
    use read_fonts::tables::gpos::{Gpos as ReadGpos, PairPos as ReadPairPos, PositionSubtables};
    use read_fonts::tables::layout::DeviceOrVariationIndex as ReadDevice;
    use read_fonts::FontRead;
    use write_fonts::dump_table;

    #[test]
    fn a_pair_equal_in_every_master_still_has_a_device() {
        let region = Region {
            axis: 0,
            start: 0.0,
            peak: 1.0,
            end: 1.0,
        };
        let mut default = KernPairs::new();
        default.entry(1).or_default().insert(2, -50);
        default.entry(1).or_default().insert(3, -20);
        let mut bold = KernPairs::new();
        bold.entry(1).or_default().insert(2, -50);
        bold.entry(1).or_default().insert(3, -35);
        let (gpos, gdef) = gpos_gdef(&[default, bold], &[region], 1).unwrap().unwrap();
        let store = gdef.item_var_store.as_ref().expect("a store");
        assert_eq!(store.variation_region_list.variation_regions.len(), 1);
        assert_eq!(store.item_variation_data.len(), 1);
        let bytes = dump_table(&gpos).unwrap();
        let read = ReadGpos::read(bytes.as_slice().into()).unwrap();
        let lookup = read.lookup_list().unwrap().lookups().get(0).unwrap();
        let PositionSubtables::Pair(subtables) = lookup.subtables().unwrap() else {
            panic!("pair lookup expected");
        };
        let ReadPairPos::Format1(pair) = subtables.get(0).unwrap() else {
            panic!("format 1 expected");
        };
        let set = pair.pair_sets().get(0).unwrap();
        // (second glyph, x advance, VariationIndex (outer, inner)) per pair.
        type Read = (u16, Option<i16>, Option<(u16, u16)>);
        let values: Vec<Read> = set
            .pair_value_records()
            .iter()
            .map(|r| {
                let r = r.unwrap();
                let v = r.value_record1();
                (
                    r.second_glyph().to_u16(),
                    v.x_advance(),
                    match v.x_advance_device() {
                        Some(Ok(ReadDevice::VariationIndex(i))) => {
                            Some((i.delta_set_outer_index(), i.delta_set_inner_index()))
                        }
                        _ => None,
                    },
                )
            })
            .collect();
        // The constant pair points at an empty delta set (0 everywhere), the other not.
        assert_eq!(values.len(), 2);
        assert_eq!((values[0].0, values[0].1), (2, Some(-50)));
        assert_eq!((values[1].0, values[1].1), (3, Some(-20)));
        let (Some(constant), Some(varying)) = (values[0].2, values[1].2) else {
            panic!("every pair has a VariationIndex: {values:?}");
        };
        assert_ne!(constant, varying);
    }
}
