//! Kerning: GPOS `kern` feature (one PairPosFormat1 lookup) and a legacy `kern` table.
//!
//! Pairs are by glyph, as in the model (no classes). The value adjusts the first glyph's
//! advance, negative = tighter. The legacy table (version 0, one format 0 subtable, TTF
//! only) is for consumers that predate GPOS; it is left out when its pairs overflow the
//! 16-bit subtable length (more than 10 920 pairs), GPOS still carries them all.
//! A GPOS subtable too large for 16-bit offsets is split (and the lookup promoted to
//! Extension) by write-fonts' packer; `tests/it/otf.rs` reads 40 000 pairs back.

use std::collections::BTreeMap;

use write_fonts::tables::gpos::{
    Gpos, PairPos, PairSet, PairValueRecord, PositionLookup, PositionLookupList, ValueRecord,
};
use write_fonts::tables::layout::{
    CoverageFormat1, CoverageTable, Feature, FeatureList, FeatureRecord, LangSys, Lookup,
    LookupFlag, Script, ScriptList, ScriptRecord,
};
use write_fonts::types::{GlyphId16, Tag};

use super::{grid, GlyphSet, OtfError};
use crate::model::KernPair;

/// Kerning by glyph id: first -> (second -> value), sorted, zero values dropped.
pub type KernPairs = BTreeMap<u16, BTreeMap<u16, i16>>;

/// The model's kerning as glyph-id pairs (pairs naming unknown glyphs are skipped).
pub fn kern_pairs(kerning: &[KernPair], set: &GlyphSet) -> Result<KernPairs, OtfError> {
    let mut pairs = KernPairs::new();
    for pair in kerning {
        let (Some(left), Some(right)) = (set.gid(&pair.left), set.gid(&pair.right)) else {
            continue;
        };
        let value = grid::to_i16(pair.value, || {
            format!("kerning {} {}", pair.left, pair.right)
        })?;
        if value != 0 {
            pairs.entry(left).or_default().insert(right, value);
        }
    }
    Ok(pairs)
}

/// GPOS with the `kern` feature for the DFLT and latn scripts, `None` without pairs.
pub fn gpos(pairs: &KernPairs) -> Option<Gpos> {
    if pairs.is_empty() {
        return None;
    }
    let coverage: Vec<GlyphId16> = pairs.keys().map(|&g| GlyphId16::new(g)).collect();
    let pair_sets = pairs
        .values()
        .map(|seconds| {
            PairSet::new(
                seconds
                    .iter()
                    .map(|(&second, &value)| {
                        PairValueRecord::new(
                            GlyphId16::new(second),
                            ValueRecord::new().with_x_advance(value),
                            ValueRecord::new(),
                        )
                    })
                    .collect(),
            )
        })
        .collect();
    Some(kern_gpos(coverage, pair_sets))
}

/// A GPOS with one `kern` lookup (DFLT and latn): pair adjustment format 1, one pair set
/// per first glyph of `coverage`.
pub fn kern_gpos(coverage: Vec<GlyphId16>, pair_sets: Vec<PairSet>) -> Gpos {
    let subtable = PairPos::format_1(
        CoverageTable::Format1(CoverageFormat1::new(coverage)),
        pair_sets,
    );
    let lookup = PositionLookup::Pair(Lookup::new(LookupFlag::empty(), vec![subtable]));
    let script = || Script::new(Some(LangSys::new(vec![0])), Vec::new());
    let scripts = ScriptList::new(vec![
        ScriptRecord::new(Tag::new(b"DFLT"), script()),
        ScriptRecord::new(Tag::new(b"latn"), script()),
    ]);
    let features = FeatureList::new(vec![FeatureRecord::new(
        Tag::new(b"kern"),
        Feature::new(None, vec![0]),
    )]);
    Gpos::new(scripts, features, PositionLookupList::new(vec![lookup]))
}

/// The legacy `kern` table (Apple/Microsoft version 0, one horizontal format 0 subtable),
/// `None` without pairs or when they do not fit.
///
/// Hand-written: write-fonts 0.55 has no `kern` table type.
pub fn legacy_kern(pairs: &KernPairs) -> Option<Vec<u8>> {
    let flat: Vec<(u16, u16, i16)> = pairs
        .iter()
        .flat_map(|(&l, seconds)| seconds.iter().map(move |(&r, &v)| (l, r, v)))
        .collect();
    let n = flat.len();
    let length = 14 + 6 * n;
    if n == 0 || length > usize::from(u16::MAX) {
        return None;
    }
    let entry_selector = n.ilog2();
    let search_range = 6 * (1usize << entry_selector);
    let mut out = Vec::with_capacity(4 + length);
    for v in [
        0u16,                          // table version
        1,                             // number of subtables
        0,                             // subtable version
        length as u16,                 // subtable length
        0x0001,                        // coverage: horizontal, format 0
        n as u16,                      // nPairs
        search_range as u16,           // searchRange
        entry_selector as u16,         // entrySelector
        (6 * n - search_range) as u16, // rangeShift
    ] {
        out.extend(v.to_be_bytes());
    }
    for (l, r, v) in flat {
        out.extend(l.to_be_bytes());
        out.extend(r.to_be_bytes());
        out.extend(v.to_be_bytes());
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn legacy_kern_bytes() {
        let mut pairs = KernPairs::new();
        pairs.entry(1).or_default().insert(5, -60);
        pairs.entry(1).or_default().insert(3, 20);
        pairs.entry(5).or_default().insert(4, -40);
        let bytes = legacy_kern(&pairs).unwrap();
        #[rustfmt::skip]
        let expected: [u8; 4 + 14 + 18] = [
            0, 0, 0, 1,
            0, 0, 0, 32, 0, 1, 0, 3, 0, 12, 0, 1, 0, 6,
            0, 1, 0, 3, 0, 20,
            0, 1, 0, 5, 0xff, 0xc4,
            0, 5, 0, 4, 0xff, 0xd8,
        ];
        assert_eq!(bytes, expected);
        assert_eq!(legacy_kern(&KernPairs::new()), None);
    }
}
