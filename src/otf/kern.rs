//! Kerning by glyph id, for the GPOS `kern` feature (generated in `features.rs`) and a
//! legacy `kern` table.
//!
//! Pairs are by glyph, as in the model (no classes). The value adjusts the first glyph's
//! advance, negative = tighter. The legacy table (version 0, one format 0 subtable, TTF
//! only) is for consumers that predate GPOS; it is left out when its pairs overflow the
//! 16-bit subtable length (more than 10 920 pairs), GPOS still carries them all.

use std::collections::BTreeMap;

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
