//! GPOS pair kerning (the `kern` feature) -> glyph-pair kerning of the imported glyphs.
//!
//! Read by hand from read-fonts' tables: no crate flattens GPOS pair lookups to glyph
//! pairs, and shaping every pair would cost a shaping call per pair.
//!
//! What a shaper applies to two neighbours is what comes in: every lookup of the `kern`
//! feature of the pair's script (its default language system) in lookup order, each
//! lookup's first subtable that matches the pair, the values of different lookups added.
//! A format-2 (class) subtable matches every pair whose first glyph it covers, so a later
//! subtable of the same lookup never sees those pairs. Class pairs are expanded to glyph
//! pairs, as the UFO import expands groups. In a variable font each value is the
//! default's plus its `GDEF` variation delta at the master's location.
//!
//! A font whose GPOS has no `kern` feature (or that has no GPOS) is kerned by its legacy
//! `kern` table, as HarfBuzz does it: its horizontal format-0 subtables, values added (an
//! override subtable replacing the sum), the same at every location.
//!
//! Limits: only the first glyph's x-advance is read (left-to-right kerning); a pair that
//! places a glyph or moves the second one is left out and counted in a note. Not read:
//! feature variations, language systems other than a script's default, hinting device
//! tables, the 24-bit glyph id formats, and the legacy table's cross-stream, minimum and
//! Apple formats 1–3 (counted in a note).

use std::collections::{BTreeMap, HashMap, HashSet};

use skrifa::raw::tables::gpos::{ExtensionSubtable, Gpos, PairPos, PositionLookup, ValueRecord};
use skrifa::raw::tables::kern::{Subtable, SubtableKind};
use skrifa::raw::tables::layout::{ClassDef, DeviceOrVariationIndex};
use skrifa::raw::tables::variations::{DeltaSetIndex, ItemVariationStore};
use skrifa::raw::types::{F2Dot14, GlyphId16, Tag};
use skrifa::raw::{ReadError, TableProvider};
use skrifa::FontRef;

use crate::model::KernPair;

/// The kerning read from a font, one list per location asked for.
pub struct Kerning {
    /// Per location, the pairs by name, sorted by the names; no zero value.
    pub pairs: Vec<Vec<KernPair>>,
    /// Pairs left out (placement or second-glyph values), for the report.
    pub skipped: usize,
    /// Read from the legacy `kern` table: the number of its subtables left out.
    pub legacy: Option<usize>,
}

/// An imported glyph: id, name and code points.
pub struct KernGlyph<'a> {
    /// Glyph id in the font.
    pub id: u16,
    /// Name in the imported font.
    pub name: &'a str,
    /// Code points; the first decides the glyph's script.
    pub unicodes: &'a [char],
}

/// A table [`read_kerning`] could not read: its tag and read-fonts' error.
#[derive(Debug)]
pub struct DamagedTable(pub &'static str, pub ReadError);

/// Reads the `kern` feature's pair kerning among `glyphs` at each of `locations`
/// (normalised coordinates; an empty slice is the default), or, when GPOS has none, the
/// legacy `kern` table's. A font with neither has no kerning; a damaged table is an error.
pub fn read_kerning(
    font: &FontRef,
    glyphs: &[KernGlyph],
    locations: &[&[F2Dot14]],
) -> Result<Kerning, DamagedTable> {
    let names: HashMap<u16, &str> = glyphs.iter().map(|g| (g.id, g.name)).collect();
    if let Some(kerning) =
        gpos_kerning(font, glyphs, &names, locations).map_err(|e| DamagedTable("GPOS", e))?
    {
        return Ok(kerning);
    }
    // Shapers apply the legacy table when GPOS has no `kern` feature; it cannot vary, so
    // every location gets the same values.
    let (values, skipped) = legacy_kerning(font, &names).map_err(|e| DamagedTable("kern", e))?;
    let sums = values
        .into_iter()
        .map(|(pair, value)| (pair, vec![value; locations.len()]))
        .collect();
    Ok(Kerning {
        pairs: by_name(sums, &names, locations.len()),
        skipped: 0,
        legacy: Some(skipped),
    })
}

/// The GPOS `kern` feature's pairs, as [`read_kerning`] describes them; `None` when the
/// font has no GPOS or its GPOS no `kern` feature.
fn gpos_kerning(
    font: &FontRef,
    glyphs: &[KernGlyph],
    names: &HashMap<u16, &str>,
    locations: &[&[F2Dot14]],
) -> Result<Option<Kerning>, ReadError> {
    let gpos = match font.gpos() {
        Ok(gpos) => gpos,
        Err(ReadError::TableIsMissing(_)) => return Ok(None),
        Err(e) => return Err(e),
    };
    let by_script = kern_lookups(&gpos)?;
    if by_script.values().all(Vec::is_empty) {
        return Ok(None);
    }
    let store = match font.gdef() {
        Ok(gdef) => gdef.item_var_store().transpose()?,
        Err(ReadError::TableIsMissing(_)) => None,
        Err(e) => return Err(e),
    };
    let scripts: HashMap<u16, Option<Tag>> = glyphs
        .iter()
        .map(|g| {
            (
                g.id,
                g.unicodes
                    .first()
                    .and_then(|&c| crate::layout::strong_script(c)),
            )
        })
        .collect();
    let lookups_for = |script: Option<Tag>| -> &[u16] {
        let tags =
            script
                .into_iter()
                .chain([Tag::new(b"DFLT"), Tag::new(b"dflt"), Tag::new(b"latn")]);
        tags.filter_map(|t| by_script.get(&t))
            .next()
            .map_or(&[], Vec::as_slice)
    };
    // Each pair is shaped with the lookups of its script: the first glyph's, else the
    // second's (a run of two characters takes the first strong script), else the default.
    // Two different scripts are two runs, which a shaper never kerns across.
    let pair_lookups = |l: u16, r: u16| match (scripts[&l], scripts[&r]) {
        (Some(a), Some(b)) if a != b => &[],
        (a, b) => lookups_for(a.or(b)),
    };
    let mut all: Vec<u16> = by_script.values().flatten().copied().collect();
    all.sort_unstable();
    all.dedup();
    let list = gpos.lookup_list()?;
    // (left, right) -> value per location, summed over lookups.
    let mut sums: BTreeMap<(u16, u16), Vec<f64>> = BTreeMap::new();
    let mut skipped = 0;
    for index in all {
        let mut subtables = Vec::new();
        match list.lookups().get(usize::from(index))? {
            PositionLookup::Pair(lookup) => {
                for s in lookup.subtables().iter() {
                    subtables.push(s?);
                }
            }
            PositionLookup::Extension(lookup) => {
                for s in lookup.subtables().iter() {
                    if let ExtensionSubtable::Pair(ext) = s? {
                        subtables.push(ext.extension()?);
                    }
                }
            }
            _ => continue,
        }
        let applies = |l: u16, r: u16| pair_lookups(l, r).contains(&index);
        let mut lookup = LookupPairs {
            names,
            applies: &applies,
            store: store.as_ref(),
            locations,
            taken: HashSet::new(),
            left_done: HashSet::new(),
            sums: &mut sums,
            skipped: 0,
        };
        for subtable in &subtables {
            lookup.add(subtable)?;
        }
        skipped += lookup.skipped;
    }
    Ok(Some(Kerning {
        pairs: by_name(sums, names, locations.len()),
        skipped,
        legacy: None,
    }))
}

/// The pairs of `sums` by glyph name, one list per location, sorted by the names; no zero
/// value.
fn by_name(
    sums: BTreeMap<(u16, u16), Vec<f64>>,
    names: &HashMap<u16, &str>,
    locations: usize,
) -> Vec<Vec<KernPair>> {
    let mut out = vec![Vec::new(); locations];
    for ((left, right), values) in sums {
        for (k, value) in values.into_iter().enumerate() {
            if value != 0.0 {
                out[k].push(KernPair {
                    left: names[&left].to_string(),
                    right: names[&right].to_string(),
                    value,
                });
            }
        }
    }
    for pairs in &mut out {
        pairs.sort_by(|a, b| (&a.left, &a.right).cmp(&(&b.left, &b.right)));
    }
    out
}

/// Kerning values by (first, second) glyph id.
type GlyphPairs = BTreeMap<(u16, u16), f64>;

/// The legacy `kern` table's horizontal pairs among `names`, as HarfBuzz applies them
/// when GPOS has no `kern` feature: the format-0 subtables in order, each value added to
/// the pair's (an override subtable's replacing it). Also returns how many subtables were
/// left out: vertical, cross-stream, minimum and variable ones, and the state-machine and
/// class formats (1 to 3, Apple's; read-fonts reads them, but no font seen so far needed
/// them).
fn legacy_kerning(
    font: &FontRef,
    names: &HashMap<u16, &str>,
) -> Result<(GlyphPairs, usize), ReadError> {
    let kern = match font.kern() {
        Ok(kern) => kern,
        Err(ReadError::TableIsMissing(_)) => return Ok((GlyphPairs::new(), 0)),
        Err(e) => return Err(e),
    };
    /// OpenType `kern` coverage bits: minimum values, override.
    const MINIMUM: u16 = 1 << 1;
    const OVERRIDE: u16 = 1 << 3;
    let mut values = GlyphPairs::new();
    let mut skipped = 0;
    for subtable in kern.subtables() {
        let subtable = subtable?;
        let coverage = match &subtable {
            Subtable::Ot(t) => t.coverage(),
            Subtable::Aat(_) => 0,
        };
        let usable = subtable.is_horizontal()
            && !subtable.is_cross_stream()
            && !subtable.is_variable()
            && coverage & MINIMUM == 0;
        let SubtableKind::Format0(table) = subtable.kind()? else {
            skipped += 1;
            continue;
        };
        if !usable {
            skipped += 1;
            continue;
        }
        // read-fonts gives no pairs at all when the count runs past the data.
        if table.pairs().len() != usize::from(table.n_pairs()) {
            return Err(ReadError::OutOfBounds);
        }
        // A pair listed twice in one subtable counts once (a shaper's search finds one).
        let mut seen = HashSet::new();
        for pair in table.pairs() {
            let (left, right) = (pair.left().to_u16(), pair.right().to_u16());
            let ours = names.contains_key(&left) && names.contains_key(&right);
            if !ours || !seen.insert((left, right)) {
                continue;
            }
            let value = f64::from(pair.value());
            let sum = values.entry((left, right)).or_insert(0.0);
            *sum = if coverage & OVERRIDE != 0 {
                value
            } else {
                *sum + value
            };
        }
    }
    Ok((values, skipped))
}

/// The `kern` lookups of each script's default language system, by OpenType script tag.
fn kern_lookups(gpos: &Gpos) -> Result<HashMap<Tag, Vec<u16>>, ReadError> {
    let features = gpos.feature_list()?;
    let scripts = gpos.script_list()?;
    let mut out = HashMap::new();
    for record in scripts.script_records() {
        let script = record.script(scripts.offset_data())?;
        let Some(langsys) = script.default_lang_sys() else {
            continue;
        };
        let mut lookups = Vec::new();
        for index in langsys?.feature_indices() {
            let Some(feature) = features.feature_records().get(usize::from(index.get())) else {
                continue;
            };
            if feature.feature_tag() == Tag::new(b"kern") {
                let feature = feature.feature(features.offset_data())?;
                lookups.extend(feature.lookup_list_indices().iter().map(|i| i.get()));
            }
        }
        lookups.sort_unstable();
        lookups.dedup();
        out.insert(record.script_tag(), lookups);
    }
    Ok(out)
}

/// One lookup's subtables, applied in order to the pairs of imported glyphs.
struct LookupPairs<'a> {
    names: &'a HashMap<u16, &'a str>,
    /// Whether this lookup shapes the pair (its script's `kern` feature has it).
    applies: &'a dyn Fn(u16, u16) -> bool,
    store: Option<&'a ItemVariationStore<'a>>,
    locations: &'a [&'a [F2Dot14]],
    /// Glyph pairs an earlier subtable of this lookup matched.
    taken: HashSet<(u16, u16)>,
    /// First glyphs an earlier class subtable covered: it matched all their pairs.
    left_done: HashSet<u16>,
    sums: &'a mut BTreeMap<(u16, u16), Vec<f64>>,
    skipped: usize,
}

/// A pair's value at each location, or why it has none.
enum Cell {
    /// The first glyph's advance changes by these (one per location).
    Advance(Vec<f64>),
    /// Nothing changes.
    Zero,
    /// Placement or the second glyph: left out.
    Other,
}

impl LookupPairs<'_> {
    fn add(&mut self, subtable: &PairPos) -> Result<(), ReadError> {
        match subtable {
            PairPos::Format1(t) => {
                let sets = t.pair_sets();
                for (i, left) in t.coverage()?.iter().enumerate() {
                    let Some(left) = self.wanted(left.to_u32()) else {
                        continue;
                    };
                    for record in sets.get(i)?.pair_value_records().iter() {
                        let record = record?;
                        let right = record.second_glyph().to_u16();
                        let ours = self.names.contains_key(&right) && (self.applies)(left, right);
                        if ours && self.taken.insert((left, right)) {
                            let cell = self.cell(record.value_record1(), record.value_record2())?;
                            self.put(left, &[right], &cell);
                        }
                    }
                }
            }
            PairPos::Format2(t) => {
                let (class1, class2) = (t.class_def1()?, t.class_def2()?);
                let class = |def: &ClassDef, g: u16| usize::try_from(def.get(GlyphId16::new(g)));
                // The imported glyphs by their second-glyph class (class 0: every glyph
                // the class table leaves out).
                let mut by_class: BTreeMap<usize, Vec<u16>> = BTreeMap::new();
                for &g in self.names.keys() {
                    if let Ok(c) = class(&class2, g) {
                        by_class.entry(c).or_default().push(g);
                    }
                }
                for members in by_class.values_mut() {
                    members.sort_unstable();
                }
                let rows = t.class1_records();
                for left in t.coverage()?.iter() {
                    let Some(left) = self.wanted(left.to_u32()) else {
                        continue;
                    };
                    let Ok(c1) = class(&class1, left) else {
                        continue;
                    };
                    let row = rows.get(c1)?;
                    for (&c2, members) in &by_class {
                        let record = row.class2_records().get(c2)?;
                        let cell = self.cell(record.value_record1(), record.value_record2())?;
                        let free: Vec<u16> = members
                            .iter()
                            .copied()
                            .filter(|&r| {
                                (self.applies)(left, r) && !self.taken.contains(&(left, r))
                            })
                            .collect();
                        self.put(left, &free, &cell);
                    }
                    // The subtable matched every pair starting with `left`.
                    self.left_done.insert(left);
                }
            }
            // The 24-bit glyph id formats: for fonts beyond 65,535 glyphs, which the
            // importer does not read (glyph ids are u16 throughout).
            _ => {}
        }
        Ok(())
    }

    /// `gid` as an imported first glyph that no earlier class subtable of this lookup
    /// matched.
    fn wanted(&self, gid: u32) -> Option<u16> {
        let gid = u16::try_from(gid).ok()?;
        (self.names.contains_key(&gid) && !self.left_done.contains(&gid)).then_some(gid)
    }

    /// What a pair's two value records do, at every location.
    fn cell(&self, first: &ValueRecord, second: &ValueRecord) -> Result<Cell, ReadError> {
        let nonzero = |v: Option<i16>| v.is_some_and(|v| v != 0);
        let moves_other = nonzero(first.x_placement())
            || nonzero(first.y_placement())
            || nonzero(first.y_advance())
            || nonzero(second.x_placement())
            || nonzero(second.y_placement())
            || nonzero(second.x_advance())
            || nonzero(second.y_advance());
        if moves_other {
            return Ok(Cell::Other);
        }
        let base = f64::from(first.x_advance().unwrap_or(0));
        let index = match first.x_advance_device() {
            Some(Ok(DeviceOrVariationIndex::VariationIndex(v))) => Some(DeltaSetIndex::from(v)),
            Some(Err(e)) => return Err(e),
            _ => None,
        };
        let values: Vec<f64> = self
            .locations
            .iter()
            .map(|coords| {
                let delta = match (index, self.store) {
                    (Some(i), Some(store)) => {
                        store.compute_delta(i, coords).map_or(0.0, |d| d.to_f64())
                    }
                    _ => 0.0,
                };
                base + delta
            })
            .collect();
        Ok(if values.iter().all(|&v| v == 0.0) {
            Cell::Zero
        } else {
            Cell::Advance(values)
        })
    }

    /// Adds `cell` to the pairs of `left` with each of `rights`.
    fn put(&mut self, left: u16, rights: &[u16], cell: &Cell) {
        match cell {
            Cell::Zero => {}
            Cell::Other => self.skipped += rights.len(),
            Cell::Advance(values) => {
                for &right in rights {
                    let sums = self
                        .sums
                        .entry((left, right))
                        .or_insert_with(|| vec![0.0; values.len()]);
                    for (sum, v) in sums.iter_mut().zip(values) {
                        *sum += v;
                    }
                }
            }
        }
    }
}
