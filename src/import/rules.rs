//! A variable font's GSUB feature variations (`rvrn` or `rclt`) -> `[[rule]]`s.
//!
//! Each feature variation record becomes one rule, in the font's order: its axis ranges
//! (normalised, read back to user values through the axis maps) as one box, and the single
//! substitutions of the lookups its alternate feature adds as the glyphs it swaps. A
//! compiler writes the overlaps of its rules as records of their own, first; read back as
//! rules in that order they give the same glyphs everywhere, unless substitutions chain
//! (`a` -> `b` in one rule and `b` -> `c` in another).
//!
//! Limits: only single substitutions in `rvrn` or `rclt`, and axis-range conditions, are
//! read; anything else is left out with a note. Glyphs outside the import's selection drop
//! out of the substitutions.

use std::collections::{BTreeMap, HashMap};

use skrifa::raw::tables::gsub::{SingleSubst, SubstitutionSubtables};
use skrifa::raw::tables::layout::Condition;
use skrifa::raw::types::F2Dot14;
use skrifa::raw::TableProvider;
use skrifa::{FontRef, GlyphId};

use crate::designspace::{Axis, Rule};

/// One feature variation record: its axis ranges (axis index, normalised min and max) and
/// the (glyph, substitute) ids of its single substitutions.
type Record = (Vec<(usize, F2Dot14, F2Dot14)>, Vec<(GlyphId, GlyphId)>);

/// The font's feature variation records as read: per record its axis ranges (axis index,
/// normalised min and max) and the glyph ids it substitutes; whether they apply last
/// (`rclt`), and a note on what was left out.
pub(super) struct ReadRules {
    records: Vec<Record>,
    pub last: bool,
    pub note: Option<String>,
}

impl ReadRules {
    /// The glyphs the substitutions reach from `start` (the imported glyphs), not in it:
    /// the alternates to import too, in glyph id order.
    pub fn alternates(&self, start: &[u16]) -> Vec<u16> {
        let mut have: std::collections::BTreeSet<u32> =
            start.iter().map(|&g| u32::from(g)).collect();
        let mut added = Vec::new();
        loop {
            let before = added.len();
            for (_, pairs) in &self.records {
                for (from, to) in pairs {
                    if have.contains(&from.to_u32()) && have.insert(to.to_u32()) {
                        added.push(to.to_u32());
                    }
                }
            }
            if added.len() == before {
                break;
            }
        }
        let mut out: Vec<u16> = added
            .into_iter()
            .filter_map(|g| u16::try_from(g).ok())
            .collect();
        out.sort_unstable();
        out
    }

    /// The records as rules, one each in order, named `rule 1`, …: the ranges in user values
    /// (`user_at` reads a normalised coordinate back), the glyphs by `names` (a pair with a
    /// glyph not imported drops out, and so does a rule left without pairs).
    pub fn into_rules(
        self,
        axes: &[Axis],
        names: &HashMap<GlyphId, String>,
        user_at: impl Fn(&Axis, F2Dot14) -> f64,
    ) -> Vec<Rule> {
        let mut out = Vec::new();
        for (k, (ranges, pairs)) in self.records.into_iter().enumerate() {
            let mut boxed = BTreeMap::new();
            for (axis, min, max) in ranges {
                let Some(a) = axes.get(axis) else {
                    continue;
                };
                let (lo, hi) = (user_at(a, min), user_at(a, max));
                boxed.insert(a.tag.clone(), (lo.max(a.min), hi.min(a.max)));
            }
            let mut substitutions: Vec<(String, String)> = pairs
                .iter()
                .filter_map(|(from, to)| Some((names.get(from)?.clone(), names.get(to)?.clone())))
                .filter(|(a, b)| a != b)
                .collect();
            substitutions.dedup();
            if boxed.is_empty() || substitutions.is_empty() {
                continue;
            }
            out.push(Rule {
                name: format!("rule {}", k + 1),
                conditions: vec![boxed],
                substitutions,
            });
        }
        out
    }
}

/// Reads the feature variation records of `font` (see the module docs).
pub(super) fn read_rules(font: &FontRef) -> ReadRules {
    let mut out = ReadRules {
        records: Vec::new(),
        last: false,
        note: None,
    };
    let mut left_out: Vec<&str> = Vec::new();
    let Ok(gsub) = font.gsub() else {
        return out;
    };
    let Some(Ok(variations)) = gsub.feature_variations() else {
        return out;
    };
    let (Ok(features), Ok(lookups)) = (gsub.feature_list(), gsub.lookup_list()) else {
        return out;
    };
    let data = variations.offset_data();
    let mut tags = Vec::new();
    for record in variations.feature_variation_records() {
        let Some(Ok(set)) = record.condition_set(data) else {
            continue;
        };
        let mut ranges = Vec::new();
        let mut readable = true;
        for condition in set.conditions().iter() {
            match condition {
                Ok(Condition::Format1AxisRange(c)) => ranges.push((
                    usize::from(c.axis_index()),
                    c.filter_range_min_value(),
                    c.filter_range_max_value(),
                )),
                _ => readable = false,
            }
        }
        if !readable || ranges.is_empty() {
            left_out.push("conditions other than axis ranges");
            continue;
        }
        let Some(Ok(substitution)) = record.feature_table_substitution(data) else {
            continue;
        };
        let mut pairs: Vec<(GlyphId, GlyphId)> = Vec::new();
        for s in substitution.substitutions() {
            let Some(tag) = features
                .feature_records()
                .get(usize::from(s.feature_index()))
                .map(|r| r.feature_tag())
            else {
                continue;
            };
            if tag != "rvrn" && tag != "rclt" {
                left_out.push("feature variations of other features");
                continue;
            }
            tags.push(tag);
            let Ok(feature) = s.alternate_feature(substitution.offset_data()) else {
                continue;
            };
            for index in feature.lookup_list_indices() {
                let Ok(lookup) = lookups.lookups().get(usize::from(index.get())) else {
                    continue;
                };
                match lookup.subtables() {
                    Ok(SubstitutionSubtables::Single(subtables)) => {
                        for i in 0..subtables.len() {
                            if let Ok(subtable) = subtables.get(i) {
                                single_pairs(&subtable, &mut pairs);
                            }
                        }
                    }
                    _ => left_out.push("substitutions other than single ones"),
                }
            }
        }
        if !pairs.is_empty() {
            out.records.push((ranges, pairs));
        }
    }
    out.last = tags.iter().any(|t| *t == "rclt") && !tags.iter().any(|t| *t == "rvrn");
    left_out.sort_unstable();
    left_out.dedup();
    if !left_out.is_empty() {
        out.note = Some(format!(
            "GSUB feature variations: {} are not read",
            left_out.join(", ")
        ));
    }
    out
}

/// The (glyph, substitute) ids of one single-substitution subtable.
fn single_pairs(subtable: &SingleSubst, pairs: &mut Vec<(GlyphId, GlyphId)>) {
    let mut add = |from: GlyphId, to: GlyphId| pairs.push((from, to));
    match subtable {
        SingleSubst::Format1(t) => {
            if let Ok(coverage) = t.coverage() {
                for g in coverage.iter() {
                    // The delta wraps modulo 65536 (OpenType, SingleSubstFormat1).
                    let to =
                        (i64::from(g.to_u32()) + i64::from(t.delta_glyph_id())).rem_euclid(65536);
                    add(g, GlyphId::new(to as u32));
                }
            }
        }
        SingleSubst::Format2(t) => {
            if let Ok(coverage) = t.coverage() {
                for (g, to) in coverage.iter().zip(t.substitute_glyph_ids()) {
                    add(g, GlyphId::from(to.get()));
                }
            }
        }
        _ => {}
    }
}
