//! GPOS mark attachment (the `mark` and `mkmk` features) -> named anchors of the imported
//! glyphs, so that an imported font keeps its mark positioning and its combining marks pass
//! `check` (which asks each of them for a `_` anchor).
//!
//! Read by hand from read-fonts' tables, like the kerning ([`super::kerning`]): no crate
//! turns GPOS mark classes into named anchors. Each class of a mark-to-base or mark-to-mark
//! subtable becomes one anchor name: its marks get `_name` at their mark anchor, its bases
//! (or, mark to mark, the marks they stack on) get `name`. A class is named by where its
//! base anchors sit: `top` when their median is above a quarter of the em, else `bottom`;
//! mark-to-base classes are named before mark-to-mark ones, and the classes with the most
//! glyphs first. Classes share a name when no glyph would get that name at two different
//! positions, so a font whose above-marks attach the same way in every lookup comes in with
//! one `top`; a class that cannot share gets the next free name (`top2`, `top3`, …). A
//! DejaVu Sans mark above attaches to bases and to other marks at different points, so its
//! mark-to-mark class comes in as `_top2` and `top2`, beside `_top`. xglyph makes one
//! lookup per name, so glyphs of two classes that share a name attach to each other even
//! where the font's own lookups kept them apart (a Latin mark on a Cyrillic base).
//!
//! A mark that no `mark` or `mkmk` lookup attaches (no `_` anchor comes in) is one the font
//! places by its outline (DejaVu Sans's U+0334 and U+20DD: zero advance, drawn where they
//! land): a glyph mapped to a combining code point, or classed a mark by `GDEF`
//! ([`gdef_marks`]), comes in with `mark = "outline"`, and the report names them
//! ([`outline_marks_note`]).
//!
//! Limits: anchor positions are the default's (a variable font's anchor deltas and
//! hinting device tables are not read); mark-to-ligature lookups, lookup flags, mark
//! filtering sets, language systems and the 24-bit glyph id formats are not read (the
//! mark-to-ligature ones are counted in the report's note).

use std::collections::{BTreeMap, HashMap, HashSet};

use skrifa::raw::tables::gpos::{
    AnchorTable, ExtensionSubtable, Gpos, MarkArray, MarkBasePos, MarkLigPos, MarkMarkPos,
    PositionLookup,
};
use skrifa::raw::tables::layout::CoverageTable;
use skrifa::raw::types::{GlyphId, Tag};
use skrifa::raw::{ReadError, TableProvider};
use skrifa::FontRef;

use crate::model::Anchor;

/// The anchors read from a font.
pub struct Anchors {
    /// Per glyph id, its anchors in the order named.
    pub by_glyph: HashMap<u16, Vec<Anchor>>,
    /// Mark-to-ligature subtables left out that have a mark and a ligature among the
    /// glyphs, for the report.
    pub ligature_subtables: usize,
}

/// One class of one mark attachment subtable: where its marks attach (`_name`) and where
/// its bases, or the marks it stacks on, take them (`name`).
struct Class {
    marks: Vec<(u16, (f64, f64))>,
    bases: Vec<(u16, (f64, f64))>,
    /// A mark-to-mark class (its bases are marks).
    on_marks: bool,
}

/// Reads the mark attachment of the `mark` and `mkmk` features (every script and language
/// system) among `glyphs` (glyph ids). A font without `GPOS` has none; a damaged table is
/// an error.
pub fn read_anchors(
    font: &FontRef,
    glyphs: &[u16],
    units_per_em: u16,
) -> Result<Anchors, ReadError> {
    let mut out = Anchors {
        by_glyph: HashMap::new(),
        ligature_subtables: 0,
    };
    let gpos = match font.gpos() {
        Ok(gpos) => gpos,
        Err(ReadError::TableIsMissing(_)) => return Ok(out),
        Err(e) => return Err(e),
    };
    let wanted: HashSet<u16> = glyphs.iter().copied().collect();
    let list = gpos.lookup_list()?;
    let mut classes = Vec::new();
    for index in mark_lookups(&gpos)? {
        let mut bases = Vec::new();
        let mut marks = Vec::new();
        match list.lookups().get(usize::from(index))? {
            PositionLookup::MarkToBase(lookup) => {
                for s in lookup.subtables().iter() {
                    bases.push(s?);
                }
            }
            PositionLookup::MarkToMark(lookup) => {
                for s in lookup.subtables().iter() {
                    marks.push(s?);
                }
            }
            PositionLookup::MarkToLig(lookup) => {
                for s in lookup.subtables().iter() {
                    out.ligature_subtables += usize::from(touches(&s?, &wanted)?);
                }
            }
            PositionLookup::Extension(lookup) => {
                for s in lookup.subtables().iter() {
                    match s? {
                        ExtensionSubtable::MarkToBase(ext) => bases.push(ext.extension()?),
                        ExtensionSubtable::MarkToMark(ext) => marks.push(ext.extension()?),
                        ExtensionSubtable::MarkToLig(ext) => {
                            out.ligature_subtables +=
                                usize::from(touches(&ext.extension()?, &wanted)?);
                        }
                        _ => {}
                    }
                }
            }
            _ => continue,
        }
        for subtable in &bases {
            classes.extend(base_classes(subtable, &wanted)?);
        }
        for subtable in &marks {
            classes.extend(mark_classes(subtable, &wanted)?);
        }
    }
    name_classes(classes, f64::from(units_per_em), &mut out.by_glyph);
    Ok(out)
}

/// The lookups of every `mark` and `mkmk` feature record, in lookup order.
fn mark_lookups(gpos: &Gpos) -> Result<Vec<u16>, ReadError> {
    let features = gpos.feature_list()?;
    let mut lookups = Vec::new();
    for record in features.feature_records() {
        if [Tag::new(b"mark"), Tag::new(b"mkmk")].contains(&record.feature_tag()) {
            let feature = record.feature(features.offset_data())?;
            lookups.extend(feature.lookup_list_indices().iter().map(|i| i.get()));
        }
    }
    lookups.sort_unstable();
    lookups.dedup();
    Ok(lookups)
}

/// Whether a mark-to-ligature subtable has a mark and a ligature among `wanted`.
fn touches(subtable: &MarkLigPos, wanted: &HashSet<u16>) -> Result<bool, ReadError> {
    let MarkLigPos::Format1(t) = subtable else {
        return Ok(false);
    };
    let any = |coverage: CoverageTable| coverage.iter().any(|g| wanted_id(g, wanted).is_some());
    Ok(any(t.mark_coverage()?) && any(t.ligature_coverage()?))
}

fn point(anchor: &AnchorTable) -> (f64, f64) {
    let (x, y) = match anchor {
        AnchorTable::Format1(a) => (a.x_coordinate(), a.y_coordinate()),
        AnchorTable::Format2(a) => (a.x_coordinate(), a.y_coordinate()),
        AnchorTable::Format3(a) => (a.x_coordinate(), a.y_coordinate()),
    };
    (f64::from(x), f64::from(y))
}

/// Puts each `wanted` mark of `coverage` into its class, at its mark anchor.
fn add_marks(
    classes: &mut [Class],
    coverage: CoverageTable,
    array: &MarkArray,
    wanted: &HashSet<u16>,
) -> Result<(), ReadError> {
    for (gid, record) in coverage.iter().zip(array.mark_records()) {
        let class = classes.get_mut(usize::from(record.mark_class()));
        if let (Some(gid), Some(class)) = (wanted_id(gid, wanted), class) {
            let anchor = record.mark_anchor(array.offset_data())?;
            class.marks.push((gid, point(&anchor)));
        }
    }
    Ok(())
}

/// Puts the base (or, mark to mark, the second mark) `gid` into each class it has an
/// anchor for: `anchors` holds one per class, in class order (a null one for a class it
/// does not take).
fn add_base<'a>(
    classes: &mut [Class],
    gid: u16,
    anchors: impl Iterator<Item = Option<Result<AnchorTable<'a>, ReadError>>>,
) -> Result<(), ReadError> {
    for (class, anchor) in classes.iter_mut().zip(anchors) {
        if let Some(anchor) = anchor.transpose()? {
            class.bases.push((gid, point(&anchor)));
        }
    }
    Ok(())
}

/// `gid` as a 16-bit id when it is among `wanted`.
fn wanted_id(gid: GlyphId, wanted: &HashSet<u16>) -> Option<u16> {
    u16::try_from(gid.to_u32())
        .ok()
        .filter(|g| wanted.contains(g))
}

/// The classes of a mark-to-base subtable, restricted to `wanted` glyphs.
fn base_classes(subtable: &MarkBasePos, wanted: &HashSet<u16>) -> Result<Vec<Class>, ReadError> {
    let MarkBasePos::Format1(t) = subtable else {
        return Ok(Vec::new());
    };
    let count = usize::from(t.mark_class_count());
    let mut classes: Vec<Class> = (0..count).map(|_| Class::new(false)).collect();
    add_marks(&mut classes, t.mark_coverage()?, &t.mark_array()?, wanted)?;
    let base_array = t.base_array()?;
    let records = base_array.base_records();
    for (gid, record) in t.base_coverage()?.iter().zip(records.iter()) {
        if let Some(gid) = wanted_id(gid, wanted) {
            let anchors = record?.base_anchors(base_array.offset_data());
            add_base(&mut classes, gid, anchors.iter())?;
        }
    }
    Ok(classes)
}

/// The classes of a mark-to-mark subtable: its second marks are the bases.
fn mark_classes(subtable: &MarkMarkPos, wanted: &HashSet<u16>) -> Result<Vec<Class>, ReadError> {
    let MarkMarkPos::Format1(t) = subtable else {
        return Ok(Vec::new());
    };
    let count = usize::from(t.mark_class_count());
    let mut classes: Vec<Class> = (0..count).map(|_| Class::new(true)).collect();
    add_marks(&mut classes, t.mark1_coverage()?, &t.mark1_array()?, wanted)?;
    let array = t.mark2_array()?;
    let records = array.mark2_records();
    for (gid, record) in t.mark2_coverage()?.iter().zip(records.iter()) {
        if let Some(gid) = wanted_id(gid, wanted) {
            let anchors = record?.mark2_anchors(array.offset_data());
            add_base(&mut classes, gid, anchors.iter())?;
        }
    }
    Ok(classes)
}

impl Class {
    fn new(on_marks: bool) -> Class {
        Class {
            marks: Vec::new(),
            bases: Vec::new(),
            on_marks,
        }
    }

    /// `top` or `bottom`: where the median base anchor sits against a quarter of the em.
    fn side(&self, em: f64) -> &'static str {
        let mut ys: Vec<f64> = self.bases.iter().map(|(_, p)| p.1).collect();
        ys.sort_by(f64::total_cmp);
        match ys.get(ys.len() / 2) {
            Some(&y) if y < 0.25 * em => "bottom",
            _ => "top",
        }
    }
}

/// Most names of one side (`top`, `top2`, …) tried for a class.
const MAX_NAMES: usize = 1000;

/// Names every class that has both marks and bases among the wanted glyphs (see the module
/// docs) and gives its glyphs their anchors.
fn name_classes(classes: Vec<Class>, em: f64, by_glyph: &mut HashMap<u16, Vec<Anchor>>) {
    // Mark-to-base classes are named first, those with the most glyphs first, so that the
    // font's main classes get the plain names (`top`, `bottom`) and a mark-to-mark class
    // joins the name its marks attach by to bases; ties keep the lookup order.
    let mut classes = classes;
    classes.sort_by_key(|c| (c.on_marks, std::cmp::Reverse(c.marks.len() + c.bases.len())));
    // Per anchor name, the position each glyph has it at.
    let mut taken: BTreeMap<String, HashMap<u16, (f64, f64)>> = BTreeMap::new();
    for class in classes {
        if class.marks.is_empty() || class.bases.is_empty() {
            continue;
        }
        let side = class.side(em);
        let entries = |name: &str| {
            let mark_name = format!("_{name}");
            class
                .marks
                .iter()
                .map(move |&(g, p)| (mark_name.clone(), g, p))
                .chain(class.bases.iter().map(|&(g, p)| (name.to_string(), g, p)))
                .collect::<Vec<_>>()
        };
        let fits = |entries: &[(String, u16, (f64, f64))], taken: &BTreeMap<_, HashMap<u16, _>>| {
            let mut mine: HashMap<(&str, u16), (f64, f64)> = HashMap::new();
            entries.iter().all(|(name, g, p)| {
                let earlier = taken
                    .get(name.as_str())
                    .and_then(|m: &HashMap<u16, _>| m.get(g));
                let here = *mine.entry((name.as_str(), *g)).or_insert(*p);
                earlier.is_none_or(|q| q == p) && here == *p
            })
        };
        // A fresh name always fits unless the class itself repeats a glyph at two places
        // (a damaged coverage table): such a class is left out.
        let chosen = (1..=MAX_NAMES).find_map(|k| {
            let name = if k == 1 {
                side.to_string()
            } else {
                format!("{side}{k}")
            };
            let candidate = entries(&name);
            fits(&candidate, &taken).then_some(candidate)
        });
        let Some(chosen) = chosen else { continue };
        for (name, g, p) in chosen {
            let glyphs = taken.entry(name.clone()).or_default();
            if glyphs.insert(g, p).is_none() {
                by_glyph
                    .entry(g)
                    .or_default()
                    .push(Anchor { name, position: p });
            }
        }
    }
}

/// The glyphs among `glyphs` (glyph ids) that the font's `GDEF` classes as marks (class
/// 3). A font without `GDEF` or without glyph classes has none; a damaged table is an
/// error.
pub fn gdef_marks(font: &FontRef, glyphs: &[u16]) -> Result<HashSet<u16>, ReadError> {
    let gdef = match font.gdef() {
        Ok(gdef) => gdef,
        Err(ReadError::TableIsMissing(_)) => return Ok(HashSet::new()),
        Err(e) => return Err(e),
    };
    let Some(classes) = gdef.glyph_class_def().transpose()? else {
        return Ok(HashSet::new());
    };
    Ok(glyphs
        .iter()
        .copied()
        .filter(|&g| classes.get(GlyphId::from(g)) == 3)
        .collect())
}

/// Whether an imported glyph is a mark its outline places: a mark (`GDEF`'s, `in_gdef`, or
/// by a combining code point) that came in without a `_` anchor.
pub fn placed_by_outline(glyph: &crate::model::Glyph, in_gdef: bool) -> bool {
    let combining = glyph
        .unicodes
        .iter()
        .any(|&c| crate::source::is_combining(c));
    (in_gdef || combining) && !glyph.attaches_by_anchor()
}

/// A note naming the marks that came in with `mark = "outline"` (no `_` anchor in the
/// font's GPOS: the font places them by their outlines).
pub fn outline_marks_note(glyphs: &[crate::model::Glyph]) -> Option<String> {
    let names: Vec<&str> = glyphs
        .iter()
        .filter(|g| g.outline_mark)
        .map(|g| g.name.as_str())
        .collect();
    let shown: Vec<String> = names.iter().take(8).map(|n| format!("`{n}`")).collect();
    let more = if names.len() > shown.len() {
        ", …"
    } else {
        ""
    };
    (!names.is_empty()).then(|| {
        format!(
            "{} mark(s) with no `_` anchor in the font's GPOS came in with mark = \"outline\" \
             (their outlines place them): {}{more}",
            names.len(),
            shown.join(", ")
        )
    })
}
