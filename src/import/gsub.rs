//! A font's GSUB -> `features.fea`, so that an imported font keeps its substitutions
//! (ligatures, alternates, localised forms, contextual and joining forms), and the glyphs
//! those substitutions reach.
//!
//! Written here: read-fonts reads the table and fea-rs compiles feature code, but nothing
//! in the Rust stack turns a compiled table back into feature code (fontTools has no such
//! decompiler either). The mapping is direct, one rule per statement:
//! - every feature of every script and language system, as `script` and
//!   `language … exclude_dflt` statements, so that each language system keeps exactly its
//!   own lookups; a language system's required feature with `required`;
//! - every lookup those features reach, nested ones included, with its flags (a mark
//!   attachment class or mark filtering set becomes a glyph class of its GDEF members);
//! - rules of every kind: single, multiple, alternate, ligature, contextual and chained
//!   contextual (all three formats, as marked glyphs with `lookup` references; class 0 of
//!   a class-based rule is the imported glyphs in no other class; a rule with no lookups
//!   is an `ignore sub`), reverse chaining.
//!
//! The glyphs the substitutions reach from the imported characters come in with them
//! ([`reachable`], read-fonts' closure, as HarfBuzz's subsetter computes it). Rules name
//! only imported glyphs: a rule that needs another glyph is left out (no imported text
//! can reach it); a glyph class keeps its imported members.
//!
//! GDEF's ligature carets come along as `LigatureCaretByPos` (the default master's, in a
//! variable font).
//!
//! `aalt` is written as its glyphs' alternates (the only form feature syntax takes there).
//! fea-rs builds its lookups first in the lookup list, a single substitution before an
//! alternate one; a font with one `aalt` lookup after `liga` (DejaVu) shapes differently
//! with `aalt` turned on.
//!
//! Stylistic set names and character variant parameters come along (`featureNames`,
//! `cvParameters`, English names only).
//!
//! Limits: `size` parameters are not read; a required feature whose tag feature syntax cannot spell (DejaVu's ` RQD`)
//! comes in under its letters (shapers apply it whatever its tag), any other such feature
//! is left out; `aalt` holds only single and alternate lookups; within a lookup, the
//! first subtable that substitutes a glyph keeps it (as a shaper applies them); a lookup
//! that a contextual lookup before it in the lookup list calls is written first (feature
//! syntax needs it defined before use), which changes nothing unless a feature also lists
//! it directly; the 24-bit glyph id formats of the boring-expansion draft are counted and
//! left out.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::fmt::Write as _;

use skrifa::raw::collections::IntSet;
use skrifa::raw::tables::gdef::{CaretValue, Gdef};
use skrifa::raw::tables::gsub::{
    AlternateSubst, ChainedSequenceContext, ClassDef, CoverageTable, Gsub, LigatureSubst,
    MultipleSubst, ReverseChainSingleSubst, SequenceContext, SingleSubst, SubstitutionLookup,
    SubstitutionSubtables,
};
use skrifa::raw::tables::layout::{FeatureParams, LookupFlag, SequenceLookupRecord};
use skrifa::raw::types::{GlyphId, GlyphId16, NameId, Tag};
use skrifa::raw::{ReadError, TableProvider};
use skrifa::{FontRef, MetadataProvider};

/// What [`read_gsub`] gives: the feature code (`None` when nothing came in) and a note on
/// what was left out.
pub(crate) struct ReadGsub {
    pub text: Option<String>,
    pub note: Option<String>,
}

/// The features a shaper applies unasked, whose glyphs a character subset takes along:
/// fontTools' subsetter's default list (`pyftsubset --layout-features`), so that the
/// characters shape as in the font; optional features (`salt`, `dlig`, `smcp`, …) keep
/// only what the subset already holds.
pub(crate) const SHAPING_FEATURES: &[&str] = &[
    "rvrn", "ccmp", "liga", "locl", "mark", "mkmk", "rlig", "frac", "numr", "dnom", "calt", "clig",
    "curs", "kern", "rclt", "valt", "vert", "vkrn", "vpal", "vrt2", "ltra", "ltrm", "rtla", "rtlm",
    "rand", "jalt", "chws", "vchw", "halt", "vhal", "init", "medi", "fina", "isol", "med2", "fin2",
    "fin3", "cswh", "mset", "stch", "ljmo", "vjmo", "tjmo", "abvs", "blws", "nukt", "akhn", "rphf",
    "rkrf", "pref", "blwf", "half", "abvf", "pstf", "cfar", "vatu", "cjct", "pres", "psts", "haln",
    "dist", "abvm", "blwm",
];

/// The glyphs outside `mapped` that the font's substitutions reach from it (in glyph id
/// order), through every feature or only `features`; none when the font has no readable
/// GSUB (its reading then fails in [`read_gsub`], naming the table).
pub(crate) fn reachable(font: &FontRef, mapped: &[u16], features: Option<&[&str]>) -> Vec<u16> {
    let Ok(gsub) = font.gsub() else {
        return Vec::new();
    };
    let num_glyphs = font.maxp().map_or(0, |m| u32::from(m.num_glyphs()));
    let mut glyphs: IntSet<GlyphId> = mapped.iter().map(|&g| GlyphId::from(g)).collect();
    let chosen: IntSet<u16> = match (features, gsub.feature_list()) {
        (None, _) => IntSet::all(),
        (Some(tags), Ok(list)) => {
            let wanted: Vec<Tag> = tags
                .iter()
                .filter_map(|t| Tag::new_checked(t.as_bytes()).ok())
                .collect();
            (0u16..)
                .zip(list.feature_records())
                .filter(|(_, r)| wanted.contains(&r.feature_tag()))
                .map(|(i, _)| i)
                .collect()
        }
        (Some(_), Err(_)) => return Vec::new(),
    };
    let closed = gsub
        .collect_lookups(&chosen)
        .and_then(|lookups| gsub.closure_glyphs_with_num_glyphs(&lookups, &mut glyphs, num_glyphs));
    if closed.is_err() {
        return Vec::new();
    }
    let mapped: BTreeSet<u16> = mapped.iter().copied().collect();
    glyphs
        .iter()
        .filter_map(|g| u16::try_from(g.to_u32()).ok())
        .filter(|g| !mapped.contains(g))
        .collect()
}

/// The font's GSUB as feature code over the imported glyphs (`names`: glyph id -> model
/// name), leaving out the features in `skip`; an error when the table cannot be read.
pub(crate) fn read_gsub(
    font: &FontRef,
    names: &HashMap<u16, String>,
    skip: &[&str],
) -> Result<ReadGsub, ReadError> {
    let Ok(gsub) = font.gsub() else {
        return Ok(ReadGsub {
            text: None,
            note: None,
        });
    };
    let mut w = Writer::new(font, gsub, names);
    let features = w.features(skip)?;
    let listed: BTreeSet<u16> = features
        .iter()
        .flat_map(|(_, systems)| systems.iter().flat_map(|s| s.lookups.iter().copied()))
        .collect();
    // Every lookup the features reach, nested ones included.
    let mut todo: Vec<u16> = listed.iter().rev().copied().collect();
    while let Some(i) = todo.pop() {
        if w.bodies.contains_key(&i) {
            continue;
        }
        let body = w.body(i)?;
        todo.extend(body.nested());
        w.bodies.insert(i, body);
    }
    let mut kept: BTreeSet<u16> = w
        .bodies
        .iter()
        .filter(|(_, b)| !b.rules.is_empty())
        .map(|(&i, _)| i)
        .collect();
    let order = definition_order(&w.bodies, &kept);
    let mut lookups = String::new();
    // Nested lookups come first in `order`: one whose every rule is left out is gone from
    // `kept` before a rule would call it.
    for &i in &order {
        w.write_lookup(i, &mut kept, &mut lookups);
    }
    let mut blocks = String::new();
    w.aalt(&mut blocks)?;
    let mut written = BTreeSet::new();
    for (tag, systems) in &features {
        if write_feature(tag, systems, &kept, w.parameters.get(tag), &mut blocks) {
            written.insert(tag.clone());
        }
    }
    w.respelled.retain(|(_, tag)| written.contains(tag));
    let note = w.note();
    if blocks.is_empty() {
        return Ok(ReadGsub { text: None, note });
    }
    let mut text = String::from(
        "# The font's GSUB table, read by `xglyph import`: lookups in the font's order, then\n\
         # the features that use them, per script and language.\n\n",
    );
    for (script, lang) in &w.systems {
        let _ = writeln!(text, "languagesystem {script} {lang};");
    }
    text.push('\n');
    for (k, glyphs) in w.classes.order.iter().enumerate() {
        let _ = writeln!(text, "@class{k} = [{}];", w.names_of(glyphs).join(" "));
    }
    if !w.classes.order.is_empty() {
        text.push('\n');
    }
    text.push_str(&lookups);
    text.push_str(&blocks);
    text.push_str(&w.ligature_carets()?);
    Ok(ReadGsub {
        text: Some(text),
        note,
    })
}

/// One feature's lookups in one script and language system.
struct System {
    script: String,
    lang: String,
    lookups: Vec<u16>,
    /// The language system's required feature (applied whatever the text asks).
    required: bool,
}

/// A lookup read: its flags and rules.
struct Body {
    flag: LookupFlag,
    filter: Option<u16>,
    rules: Vec<Rule>,
}

impl Body {
    /// The lookups its contextual rules call.
    fn nested(&self) -> Vec<u16> {
        let mut out = Vec::new();
        for rule in &self.rules {
            if let Rule::Context(c) = rule {
                out.extend(c.lookups.iter().map(|&(_, l)| l));
            }
        }
        out
    }
}

enum Rule {
    /// A rule written out already (single, multiple, alternate, ligature).
    Line(String),
    /// Glyph sets per position; the lookups called at input positions.
    Context(ContextRule),
    /// Reverse chaining: sets per position around one input position, whose glyphs become
    /// the substitutes, pair by pair.
    Reverse {
        back: Vec<Vec<u16>>,
        ahead: Vec<Vec<u16>>,
        pairs: Vec<(u16, u16)>,
    },
}

struct ContextRule {
    /// In text order (the table stores backtrack reversed).
    back: Vec<Vec<u16>>,
    input: Vec<Vec<u16>>,
    ahead: Vec<Vec<u16>>,
    /// (input position, lookup index), in the table's order.
    lookups: Vec<(u16, u16)>,
}

/// Named glyph classes (sets of 8 or more glyphs, and every flag class), deduplicated by
/// their members.
#[derive(Default)]
struct Classes {
    order: Vec<Vec<u16>>,
    index: HashMap<Vec<u16>, usize>,
}

impl Classes {
    fn name(&mut self, glyphs: Vec<u16>) -> String {
        let next = self.order.len();
        let k = *self.index.entry(glyphs.clone()).or_insert(next);
        if k == next {
            self.order.push(glyphs);
        }
        format!("@class{k}")
    }
}

/// Glyph sets larger than this are named classes.
const INLINE: usize = 8;

/// Feature syntax keywords a glyph name must escape (`\name`).
const KEYWORDS: &str = "anchor anchorDef anon anonymous by contour cursive device enum enumerate \
     exclude_dflt excludeDFLT feature from ignore IgnoreBaseGlyphs IgnoreLigatures \
     IgnoreMarks include include_dflt includeDFLT language languagesystem lookup \
     lookupflag mark MarkAttachmentType markClass nameid NULL parameters pos position \
     required reversesub RightToLeft rsub script sub substitute subtable table \
     useExtension UseMarkFilteringSet valueRecordDef";

struct Writer<'a> {
    font: FontRef<'a>,
    gsub: Gsub<'a>,
    gdef: Option<Gdef<'a>>,
    names: &'a HashMap<u16, String>,
    /// The imported glyph ids, sorted (class 0 of a class definition is taken from them).
    imported: Vec<u16>,
    bodies: BTreeMap<u16, Body>,
    classes: Classes,
    /// (script, language) pairs, `DFLT dflt` first.
    systems: Vec<(String, String)>,
    /// Subtables in formats not read.
    formats_left: usize,
    /// Ligature carets at contour points (left out).
    carets_left: usize,
    /// Feature tags left out.
    features_left: BTreeSet<String>,
    /// Features with parameters left out (`size`, or names the font lacks).
    params_left: BTreeSet<String>,
    /// Stylistic set names and character variant parameters, by feature tag, as written.
    parameters: BTreeMap<String, String>,
    /// Required features whose tags feature syntax cannot spell: (tag, the tag written).
    respelled: BTreeSet<(String, String)>,
    /// The lookups of `aalt` (written as its alternates, the only form fea-rs takes).
    aalt_lookups: BTreeSet<u16>,
    /// `aalt` lookups of other kinds than single and alternate (left out).
    aalt_left: usize,
}

impl<'a> Writer<'a> {
    fn new(font: &FontRef<'a>, gsub: Gsub<'a>, names: &'a HashMap<u16, String>) -> Self {
        let mut imported: Vec<u16> = names.keys().copied().collect();
        imported.sort_unstable();
        Writer {
            font: font.clone(),
            gsub,
            gdef: font.gdef().ok(),
            names,
            imported,
            bodies: BTreeMap::new(),
            classes: Classes::default(),
            systems: vec![("DFLT".into(), "dflt".into())],
            formats_left: 0,
            carets_left: 0,
            features_left: BTreeSet::new(),
            params_left: BTreeSet::new(),
            parameters: BTreeMap::new(),
            respelled: BTreeSet::new(),
            aalt_lookups: BTreeSet::new(),
            aalt_left: 0,
        }
    }

    /// Per feature tag (in the feature list's order), its lookups per script and language.
    fn features(&mut self, skip: &[&str]) -> Result<Vec<(String, Vec<System>)>, ReadError> {
        let scripts = self.gsub.script_list()?;
        let list = self.gsub.feature_list()?;
        let records = list.feature_records();
        let mut by_tag: Vec<(String, Vec<System>)> = Vec::new();
        for script_record in scripts.script_records() {
            let Some(script) = spelled(script_record.script_tag()) else {
                continue;
            };
            let table = script_record.script(scripts.offset_data())?;
            let mut systems = Vec::new();
            if let Some(default) = table.default_lang_sys() {
                systems.push(("dflt".to_string(), default?));
            }
            for record in table.lang_sys_records() {
                let Some(lang) = spelled(record.lang_sys_tag()) else {
                    continue;
                };
                systems.push((lang, record.lang_sys(table.offset_data())?));
            }
            for (lang, sys) in systems {
                let pair = (script.clone(), lang.clone());
                if !self.systems.contains(&pair) {
                    self.systems.push(pair);
                }
                let required = sys.required_feature_index();
                let indices = (required != 0xFFFF)
                    .then_some(required)
                    .into_iter()
                    .chain(sys.feature_indices().iter().map(|i| i.get()));
                // Lookups per tag in this system (a tag may have several records).
                let mut here: Vec<(String, BTreeSet<u16>, bool)> = Vec::new();
                for index in indices {
                    let is_required = index == required;
                    let Some(record) = records.get(usize::from(index)) else {
                        continue;
                    };
                    let raw_tag = record.feature_tag();
                    // A required feature's tag does not matter to shapers: one that feature
                    // syntax cannot spell comes in under its letters.
                    let respelled = || {
                        let letters: String = raw_tag
                            .to_string()
                            .chars()
                            .filter(char::is_ascii_alphabetic)
                            .collect();
                        (is_required && !letters.is_empty()).then_some(letters)
                    };
                    let Some(tag) = spelled(raw_tag).or_else(|| {
                        let tag = respelled()?;
                        self.respelled.insert((raw_tag.to_string(), tag.clone()));
                        Some(tag)
                    }) else {
                        self.features_left.insert(raw_tag.to_string());
                        continue;
                    };
                    if skip.contains(&tag.as_str()) {
                        continue;
                    }
                    let feature = record.feature(list.offset_data())?;
                    if tag == "aalt" {
                        let lookups = feature.lookup_list_indices().iter().map(|l| l.get());
                        self.aalt_lookups.extend(lookups);
                        continue;
                    }
                    if let Some(params) = feature.feature_params() {
                        match params.ok().and_then(|p| self.parameters(&p)) {
                            Some(text) => {
                                self.parameters.insert(tag.clone(), text);
                            }
                            None => {
                                self.params_left.insert(tag.clone());
                            }
                        }
                    }
                    let lookups = feature.lookup_list_indices().iter().map(|l| l.get());
                    match here.iter_mut().find(|(t, _, _)| *t == tag) {
                        Some((_, set, req)) => {
                            set.extend(lookups);
                            *req |= is_required;
                        }
                        None => here.push((tag, lookups.collect(), is_required)),
                    }
                }
                for (tag, lookups, required) in here {
                    if lookups.is_empty() {
                        continue;
                    }
                    let system = System {
                        script: script.clone(),
                        lang: lang.clone(),
                        lookups: lookups.into_iter().collect(),
                        required,
                    };
                    match by_tag.iter_mut().find(|(t, _)| *t == tag) {
                        Some((_, list)) => list.push(system),
                        None => by_tag.push((tag, vec![system])),
                    }
                }
            }
        }
        Ok(by_tag)
    }

    /// A stylistic set's name or a character variant's parameters as feature code (the
    /// English names, as fea-rs writes them: Windows platform, US English); `None` for
    /// `size` and for a name the font lacks.
    fn parameters(&self, params: &FeatureParams) -> Option<String> {
        let name = |id: NameId| -> Option<String> {
            let text = self
                .font
                .localized_strings(id)
                .english_or_first()?
                .to_string();
            Some(format!("name \"{}\";", fea_string(&text)))
        };
        match params {
            FeatureParams::StylisticSet(p) => Some(format!(
                "    featureNames {{\n        {}\n    }};\n",
                name(p.ui_name_id())?
            )),
            FeatureParams::CharacterVariant(p) => {
                let mut text = String::from("    cvParameters {\n");
                let labels = [
                    ("FeatUILabelNameID", p.feat_ui_label_name_id()),
                    ("FeatUITooltipTextNameID", p.feat_ui_tooltip_text_name_id()),
                    ("SampleTextNameID", p.sample_text_name_id()),
                ];
                let first = p.first_param_ui_label_name_id().to_u16();
                let params = (0..p.num_named_parameters())
                    .map(|k| ("ParamUILabelNameID", NameId::new(first.saturating_add(k))));
                for (key, id) in labels.into_iter().chain(params) {
                    if id.to_u16() != 0 {
                        let _ = writeln!(text, "        {key} {{ {} }};", name(id)?);
                    }
                }
                for c in p.character() {
                    let _ = writeln!(text, "        Character 0x{:04X};", c.get().to_u32());
                }
                text.push_str("    };\n");
                Some(text)
            }
            FeatureParams::Size(_) => None,
        }
    }

    /// Lookup `index` read.
    fn body(&mut self, index: u16) -> Result<Body, ReadError> {
        let list = self.gsub.lookup_list()?;
        let lookup: SubstitutionLookup = list.lookups().get(usize::from(index))?;
        let mut body = Body {
            flag: lookup.lookup_flag(),
            filter: lookup.mark_filtering_set(),
            rules: Vec::new(),
        };
        match lookup.subtables()? {
            SubstitutionSubtables::Single(subtables) => {
                let mut seen = BTreeSet::new();
                for subtable in subtables.iter() {
                    for (from, to) in self.single_pairs(&subtable?)? {
                        if seen.insert(from) {
                            self.line(&mut body, &[from], "by", &[to]);
                        }
                    }
                }
            }
            SubstitutionSubtables::Multiple(subtables) => {
                let mut seen = BTreeSet::new();
                for subtable in subtables.iter() {
                    let MultipleSubst::Format1(t) = subtable? else {
                        self.formats_left += 1;
                        continue;
                    };
                    for (from, seq) in t.coverage()?.iter().zip(t.sequences().iter()) {
                        let from = glyph16(from);
                        let to: Vec<u16> = seq?
                            .substitute_glyph_ids()
                            .iter()
                            .map(|g| g.get().to_u16())
                            .collect();
                        if seen.insert(from) {
                            self.line(&mut body, &[from], "by", &to);
                        }
                    }
                }
            }
            SubstitutionSubtables::Alternate(subtables) => {
                let mut seen = BTreeSet::new();
                for subtable in subtables.iter() {
                    for (from, alternates) in self.alternate_sets(&subtable?)? {
                        let alternates: Vec<u16> = alternates
                            .into_iter()
                            .filter(|g| self.names.contains_key(g))
                            .collect();
                        if !seen.insert(from) {
                            continue;
                        }
                        if let (Some(name), false) = (self.name(from), alternates.is_empty()) {
                            body.rules.push(Rule::Line(format!(
                                "sub {name} from [{}];",
                                self.names_of(&alternates).join(" ")
                            )));
                        }
                    }
                }
            }
            SubstitutionSubtables::Ligature(subtables) => {
                let mut seen = BTreeSet::new();
                for subtable in subtables.iter() {
                    let LigatureSubst::Format1(t) = subtable? else {
                        self.formats_left += 1;
                        continue;
                    };
                    for (first, set) in t.coverage()?.iter().zip(t.ligature_sets().iter()) {
                        for ligature in set?.ligatures().iter() {
                            let ligature = ligature?;
                            let mut components = vec![glyph16(first)];
                            components.extend(
                                ligature
                                    .component_glyph_ids()
                                    .iter()
                                    .map(|g| g.get().to_u16()),
                            );
                            if seen.insert(components.clone()) {
                                let to = ligature.ligature_glyph().to_u16();
                                self.line(&mut body, &components, "by", &[to]);
                            }
                        }
                    }
                }
            }
            SubstitutionSubtables::Contextual(subtables) => {
                for subtable in subtables.iter() {
                    let rules = self.context(&subtable?)?;
                    body.rules.extend(rules.into_iter().map(Rule::Context));
                }
            }
            SubstitutionSubtables::ChainContextual(subtables) => {
                for subtable in subtables.iter() {
                    let rules = self.chain_context(&subtable?)?;
                    body.rules.extend(rules.into_iter().map(Rule::Context));
                }
            }
            SubstitutionSubtables::Reverse(subtables) => {
                for subtable in subtables.iter() {
                    let ReverseChainSingleSubst::Format1(t) = subtable? else {
                        self.formats_left += 1;
                        continue;
                    };
                    let mut back: Vec<Vec<u16>> = Vec::new();
                    for c in t.backtrack_coverages().iter() {
                        back.push(coverage(&c?));
                    }
                    back.reverse();
                    let mut ahead = Vec::new();
                    for c in t.lookahead_coverages().iter() {
                        ahead.push(coverage(&c?));
                    }
                    let pairs: Vec<(u16, u16)> = t
                        .coverage()?
                        .iter()
                        .zip(t.substitute_glyph_ids())
                        .map(|(from, to)| (glyph16(from), to.get().to_u16()))
                        .collect();
                    body.rules.push(Rule::Reverse { back, ahead, pairs });
                }
            }
            SubstitutionSubtables::EmptyExtension => {}
        }
        Ok(body)
    }

    /// The `aalt` feature: each glyph's alternates from its single and alternate
    /// lookups, in lookup order (feature syntax takes `aalt` only as such rules; fea-rs
    /// builds its lookups).
    fn aalt(&mut self, out: &mut String) -> Result<(), ReadError> {
        let mut alternates: BTreeMap<u16, Vec<u16>> = BTreeMap::new();
        let list = self.gsub.lookup_list()?;
        for &i in &self.aalt_lookups.clone() {
            let lookup: SubstitutionLookup = list.lookups().get(usize::from(i))?;
            let mut add = |from: u16, to: &[u16]| {
                let set = alternates.entry(from).or_default();
                for &t in to {
                    if !set.contains(&t) {
                        set.push(t);
                    }
                }
            };
            match lookup.subtables()? {
                SubstitutionSubtables::Single(subtables) => {
                    for subtable in subtables.iter() {
                        for (from, to) in self.single_pairs(&subtable?)? {
                            add(from, &[to]);
                        }
                    }
                }
                SubstitutionSubtables::Alternate(subtables) => {
                    for subtable in subtables.iter() {
                        for (from, to) in self.alternate_sets(&subtable?)? {
                            add(from, &to);
                        }
                    }
                }
                _ => self.aalt_left += 1,
            }
        }
        let mut text = String::from("feature aalt {\n");
        let mut any = false;
        for (from, to) in alternates {
            let to: Vec<u16> = to
                .into_iter()
                .filter(|g| self.names.contains_key(g))
                .collect();
            if let (Some(name), false) = (self.name(from), to.is_empty()) {
                let _ = writeln!(
                    text,
                    "    sub {name} from [{}];",
                    self.names_of(&to).join(" ")
                );
                any = true;
            }
        }
        text.push_str("} aalt;\n\n");
        if any {
            out.push_str(&text);
        }
        Ok(())
    }

    /// (glyph, its alternates) of an alternate-substitution subtable; nothing from the
    /// 24-bit format (counted).
    fn alternate_sets(
        &mut self,
        subtable: &AlternateSubst,
    ) -> Result<Vec<(u16, Vec<u16>)>, ReadError> {
        let AlternateSubst::Format1(t) = subtable else {
            self.formats_left += 1;
            return Ok(Vec::new());
        };
        let mut out = Vec::new();
        for (from, set) in t.coverage()?.iter().zip(t.alternate_sets().iter()) {
            let to = set?.alternate_glyph_ids().iter().map(|g| g.get().to_u16());
            out.push((glyph16(from), to.collect()));
        }
        Ok(out)
    }

    fn single_pairs(&mut self, subtable: &SingleSubst) -> Result<Vec<(u16, u16)>, ReadError> {
        Ok(match subtable {
            SingleSubst::Format1(t) => t
                .coverage()?
                .iter()
                .map(|g| {
                    // The delta wraps modulo 65536 (OpenType, SingleSubstFormat1).
                    let to =
                        (i64::from(g.to_u32()) + i64::from(t.delta_glyph_id())).rem_euclid(65536);
                    (glyph16(g), to as u16)
                })
                .collect(),
            SingleSubst::Format2(t) => t
                .coverage()?
                .iter()
                .zip(t.substitute_glyph_ids())
                .map(|(g, to)| (glyph16(g), to.get().to_u16()))
                .collect(),
            _ => {
                self.formats_left += 1;
                Vec::new()
            }
        })
    }

    /// `sub FROM… KEYWORD TO…;`, or a rule left out when a glyph is not imported. An empty
    /// `to` (a multiple substitution that deletes) is `NULL`.
    fn line(&self, body: &mut Body, from: &[u16], keyword: &str, to: &[u16]) {
        let from: Option<Vec<String>> = from.iter().map(|&g| self.name(g)).collect();
        let to: Option<Vec<String>> = to.iter().map(|&g| self.name(g)).collect();
        if let (Some(from), Some(to)) = (from, to) {
            let to = if to.is_empty() {
                "NULL".to_string()
            } else {
                to.join(" ")
            };
            body.rules.push(Rule::Line(format!(
                "sub {} {keyword} {to};",
                from.join(" ")
            )));
        }
    }

    fn context(&mut self, t: &SequenceContext) -> Result<Vec<ContextRule>, ReadError> {
        let mut out = Vec::new();
        match t {
            SequenceContext::Format1(t) => {
                for (first, set) in t.coverage()?.iter().zip(t.seq_rule_sets().iter()) {
                    let Some(set) = set else { continue };
                    for rule in set?.seq_rules().iter() {
                        let rule = rule?;
                        let mut input = vec![vec![glyph16(first)]];
                        input.extend(rule.input_sequence().iter().map(|g| vec![g.get().to_u16()]));
                        out.push(context_rule(
                            Vec::new(),
                            input,
                            Vec::new(),
                            rule.seq_lookup_records(),
                        ));
                    }
                }
            }
            SequenceContext::Format2(t) => {
                let classes = self.class_members(&t.class_def()?);
                let covered = coverage(&t.coverage()?);
                let class_def = t.class_def()?;
                for (k, set) in t.class_seq_rule_sets().iter().enumerate() {
                    let Some(set) = set else { continue };
                    let first = first_of_class(&covered, &class_def, k);
                    for rule in set?.class_seq_rules().iter() {
                        let rule = rule?;
                        let mut input = vec![first.clone()];
                        input.extend(
                            rule.input_sequence()
                                .iter()
                                .map(|c| member(&classes, c.get())),
                        );
                        out.push(context_rule(
                            Vec::new(),
                            input,
                            Vec::new(),
                            rule.seq_lookup_records(),
                        ));
                    }
                }
            }
            SequenceContext::Format3(t) => {
                let mut input = Vec::new();
                for c in t.coverages().iter() {
                    input.push(coverage(&c?));
                }
                out.push(context_rule(
                    Vec::new(),
                    input,
                    Vec::new(),
                    t.seq_lookup_records(),
                ));
            }
            _ => self.formats_left += 1,
        }
        Ok(out)
    }

    fn chain_context(&mut self, t: &ChainedSequenceContext) -> Result<Vec<ContextRule>, ReadError> {
        let mut out = Vec::new();
        let glyphs = |s: &[skrifa::raw::types::BigEndian<GlyphId16>]| -> Vec<Vec<u16>> {
            s.iter().map(|g| vec![g.get().to_u16()]).collect()
        };
        match t {
            ChainedSequenceContext::Format1(t) => {
                for (first, set) in t.coverage()?.iter().zip(t.chained_seq_rule_sets().iter()) {
                    let Some(set) = set else { continue };
                    for rule in set?.chained_seq_rules().iter() {
                        let rule = rule?;
                        let mut back = glyphs(rule.backtrack_sequence());
                        back.reverse();
                        let mut input = vec![vec![glyph16(first)]];
                        input.extend(glyphs(rule.input_sequence()));
                        let ahead = glyphs(rule.lookahead_sequence());
                        out.push(context_rule(back, input, ahead, rule.seq_lookup_records()));
                    }
                }
            }
            ChainedSequenceContext::Format2(t) => {
                let back_classes = self.class_members(&t.backtrack_class_def()?);
                let input_def = t.input_class_def()?;
                let input_classes = self.class_members(&input_def);
                let ahead_classes = self.class_members(&t.lookahead_class_def()?);
                let covered = coverage(&t.coverage()?);
                for (k, set) in t.chained_class_seq_rule_sets().iter().enumerate() {
                    let Some(set) = set else { continue };
                    let first = first_of_class(&covered, &input_def, k);
                    for rule in set?.chained_class_seq_rules().iter() {
                        let rule = rule?;
                        let mut back: Vec<Vec<u16>> = rule
                            .backtrack_sequence()
                            .iter()
                            .map(|c| member(&back_classes, c.get()))
                            .collect();
                        back.reverse();
                        let mut input = vec![first.clone()];
                        input.extend(
                            rule.input_sequence()
                                .iter()
                                .map(|c| member(&input_classes, c.get())),
                        );
                        let ahead = rule
                            .lookahead_sequence()
                            .iter()
                            .map(|c| member(&ahead_classes, c.get()))
                            .collect();
                        out.push(context_rule(back, input, ahead, rule.seq_lookup_records()));
                    }
                }
            }
            ChainedSequenceContext::Format3(t) => {
                let mut back = Vec::new();
                for c in t.backtrack_coverages().iter() {
                    back.push(coverage(&c?));
                }
                back.reverse();
                let mut input = Vec::new();
                for c in t.input_coverages().iter() {
                    input.push(coverage(&c?));
                }
                let mut ahead = Vec::new();
                for c in t.lookahead_coverages().iter() {
                    ahead.push(coverage(&c?));
                }
                out.push(context_rule(back, input, ahead, t.seq_lookup_records()));
            }
            _ => self.formats_left += 1,
        }
        Ok(out)
    }

    /// The imported members of each class of `def`; class 0 holds the imported glyphs
    /// in no other class.
    fn class_members(&self, def: &ClassDef) -> BTreeMap<u16, Vec<u16>> {
        let mut out: BTreeMap<u16, Vec<u16>> = BTreeMap::new();
        for &g in &self.imported {
            let class = u16::try_from(def.get(GlyphId::from(g))).unwrap_or(0);
            out.entry(class).or_default().push(g);
        }
        out
    }

    fn name(&self, g: u16) -> Option<String> {
        Some(escaped(self.names.get(&g)?))
    }

    fn names_of(&self, glyphs: &[u16]) -> Vec<String> {
        glyphs.iter().filter_map(|&g| self.name(g)).collect()
    }

    /// A position's glyphs as feature code: one name, an inline class, or a named class;
    /// `None` when none of them is imported.
    fn set(&mut self, glyphs: &[u16]) -> Option<String> {
        let mut kept: Vec<u16> = glyphs
            .iter()
            .copied()
            .filter(|g| self.names.contains_key(g))
            .collect();
        kept.sort_unstable();
        kept.dedup();
        match kept.len() {
            0 => None,
            1 => self.name(kept[0]),
            n if n <= INLINE => Some(format!("[{}]", self.names_of(&kept).join(" "))),
            _ => Some(self.classes.name(kept)),
        }
    }

    /// The `lookupflag` statement of `body`, when it has flags.
    fn flag_line(&mut self, body: &Body) -> Option<String> {
        let flag = body.flag;
        let mut words: Vec<String> = Vec::new();
        let mut ignore_marks = flag.contains(LookupFlag::IGNORE_MARKS);
        if flag.contains(LookupFlag::RIGHT_TO_LEFT) {
            words.push("RightToLeft".into());
        }
        if flag.contains(LookupFlag::IGNORE_BASE_GLYPHS) {
            words.push("IgnoreBaseGlyphs".into());
        }
        if flag.contains(LookupFlag::IGNORE_LIGATURES) {
            words.push("IgnoreLigatures".into());
        }
        let mut classes = Vec::new();
        if let Some(k) = flag.mark_attachment_class().filter(|&k| k > 0) {
            let members: Vec<u16> = match self.gdef.as_ref().and_then(|g| g.mark_attach_class_def())
            {
                Some(Ok(def)) => self.class_members(&def).remove(&k).unwrap_or_default(),
                _ => Vec::new(),
            };
            match members.is_empty() {
                // No imported mark is in the class: every mark is skipped.
                true => ignore_marks = true,
                false => classes.push(format!("MarkAttachmentType {}", self.classes.name(members))),
            }
        }
        if let (true, Some(set)) = (
            flag.contains(LookupFlag::USE_MARK_FILTERING_SET),
            body.filter,
        ) {
            let members: Vec<u16> = match self.gdef.as_ref().and_then(|g| g.mark_glyph_sets_def()) {
                Some(Ok(sets)) => match sets.coverages().get(usize::from(set)) {
                    Ok(c) => {
                        let mut m: Vec<u16> = coverage(&c)
                            .into_iter()
                            .filter(|g| self.names.contains_key(g))
                            .collect();
                        m.sort_unstable();
                        m
                    }
                    Err(_) => Vec::new(),
                },
                _ => Vec::new(),
            };
            match members.is_empty() {
                true => ignore_marks = true,
                false => classes.push(format!(
                    "UseMarkFilteringSet {}",
                    self.classes.name(members)
                )),
            }
        }
        if ignore_marks {
            words.push("IgnoreMarks".into());
        }
        words.extend(classes);
        (!words.is_empty()).then(|| format!("    lookupflag {};\n", words.join(" ")))
    }

    /// Writes lookup `index` as a named lookup block; one with no rule left is not
    /// written and leaves `kept`.
    fn write_lookup(&mut self, index: u16, kept: &mut BTreeSet<u16>, out: &mut String) {
        let Some(body) = self.bodies.remove(&index) else {
            return;
        };
        let mut text = format!("lookup gsub{index} {{\n");
        if let Some(flags) = self.flag_line(&body) {
            text.push_str(&flags);
        }
        let mut written = 0;
        for rule in &body.rules {
            let line = match rule {
                Rule::Line(line) => Some(line.clone()),
                Rule::Context(c) => self.context_line(c, kept),
                Rule::Reverse { back, ahead, pairs } => self.reverse_line(back, ahead, pairs),
            };
            if let Some(line) = line {
                let _ = writeln!(text, "    {line}");
                written += 1;
            }
        }
        let _ = writeln!(text, "}} gsub{index};\n");
        if written > 0 {
            out.push_str(&text);
        } else {
            kept.remove(&index);
        }
        self.bodies.insert(index, body);
    }

    fn context_line(&mut self, c: &ContextRule, kept: &BTreeSet<u16>) -> Option<String> {
        let mut parts = Vec::new();
        for glyphs in &c.back {
            parts.push(self.set(glyphs)?);
        }
        let mut any_lookup = false;
        for (i, glyphs) in c.input.iter().enumerate() {
            let mut part = format!("{}'", self.set(glyphs)?);
            for &(at, lookup) in &c.lookups {
                if usize::from(at) == i && kept.contains(&lookup) {
                    let _ = write!(part, " lookup gsub{lookup}");
                    any_lookup = true;
                }
            }
            parts.push(part);
        }
        for glyphs in &c.ahead {
            parts.push(self.set(glyphs)?);
        }
        let keyword = if any_lookup { "sub" } else { "ignore sub" };
        Some(format!("{keyword} {};", parts.join(" ")))
    }

    fn reverse_line(
        &mut self,
        back: &[Vec<u16>],
        ahead: &[Vec<u16>],
        pairs: &[(u16, u16)],
    ) -> Option<String> {
        let mut parts = Vec::new();
        for glyphs in back {
            parts.push(self.set(glyphs)?);
        }
        let (from, to): (Vec<String>, Vec<String>) = pairs
            .iter()
            .filter_map(|&(f, t)| Some((self.name(f)?, self.name(t)?)))
            .unzip();
        if from.is_empty() {
            return None;
        }
        parts.push(format!("[{}]'", from.join(" ")));
        for glyphs in ahead {
            parts.push(self.set(glyphs)?);
        }
        Some(format!("rsub {} by [{}];", parts.join(" "), to.join(" ")))
    }

    /// GDEF's caret positions inside the imported ligatures, as a `table GDEF` block
    /// (empty when there are none). Carets at contour points (format 2) are left out and
    /// counted: the fitted outline has other points.
    fn ligature_carets(&mut self) -> Result<String, ReadError> {
        let Some(list) = self.gdef.as_ref().and_then(|g| g.lig_caret_list()) else {
            return Ok(String::new());
        };
        let list = list?;
        let mut lines = String::new();
        for (g, carets) in list.coverage()?.iter().zip(list.lig_glyphs().iter()) {
            let Some(name) = self.name(glyph16(g)) else {
                continue;
            };
            let mut at = Vec::new();
            for caret in carets?.caret_values().iter() {
                match caret? {
                    CaretValue::Format1(c) => at.push(c.coordinate()),
                    CaretValue::Format3(c) => at.push(c.coordinate()),
                    CaretValue::Format2(_) => self.carets_left += 1,
                }
            }
            if !at.is_empty() {
                let at: Vec<String> = at.iter().map(i16::to_string).collect();
                let _ = writeln!(lines, "    LigatureCaretByPos {name} {};", at.join(" "));
            }
        }
        Ok(match lines.is_empty() {
            true => String::new(),
            false => format!("table GDEF {{\n{lines}}} GDEF;\n"),
        })
    }

    fn note(&self) -> Option<String> {
        let mut parts = Vec::new();
        if !self.features_left.is_empty() {
            let tags: Vec<String> = self
                .features_left
                .iter()
                .map(|t| format!("`{t}`"))
                .collect();
            parts.push(format!(
                "the feature(s) {}, whose tags feature syntax cannot spell",
                tags.join(", ")
            ));
        }
        if !self.params_left.is_empty() {
            let tags: Vec<&str> = self.params_left.iter().map(String::as_str).collect();
            parts.push(format!("the parameters of {}", tags.join(", ")));
        }
        if self.aalt_left > 0 {
            parts.push(format!(
                "{} `aalt` lookup(s) other than single and alternate substitutions",
                self.aalt_left
            ));
        }
        if self.carets_left > 0 {
            parts.push(format!(
                "{} ligature caret(s) at contour points",
                self.carets_left
            ));
        }
        if self.formats_left > 0 {
            parts.push(format!(
                "{} subtable(s) in 24-bit formats",
                self.formats_left
            ));
        }
        let mut sentences: Vec<String> = self
            .respelled
            .iter()
            .map(|(tag, written)| {
                format!(
                    "the required feature `{tag}` comes in as `{written}` (feature syntax \
                     cannot spell its tag; shapers apply a required feature whatever its tag)"
                )
            })
            .collect();
        if !parts.is_empty() {
            sentences.push(format!("left out {}", parts.join("; ")));
        }
        (!sentences.is_empty()).then(|| format!("GSUB: {}", sentences.join("; ")))
    }
}

/// Lookups in index order, each one its rules call written first (feature syntax needs a
/// lookup defined before it is called); a call back into a lookup being written (a cycle,
/// invalid in a font) is not followed.
fn definition_order(bodies: &BTreeMap<u16, Body>, kept: &BTreeSet<u16>) -> Vec<u16> {
    // Depth first with an explicit stack (a damaged font may chain thousands of lookups):
    // a lookup is written once every lookup it calls is.
    let mut seen = BTreeSet::new();
    let mut out = Vec::new();
    for &root in kept {
        if !seen.insert(root) {
            continue;
        }
        let nested = |i: u16| bodies.get(&i).map(Body::nested).unwrap_or_default();
        let mut stack = vec![(root, nested(root), 0usize)];
        while let Some((i, calls, next)) = stack.last_mut() {
            match calls.get(*next).copied() {
                Some(n) => {
                    *next += 1;
                    if kept.contains(&n) && seen.insert(n) {
                        let calls = nested(n);
                        stack.push((n, calls, 0));
                    }
                }
                None => {
                    out.push(*i);
                    stack.pop();
                }
            }
        }
    }
    out
}

/// Writes feature `tag`'s block, `parameters` first; false when none of its lookups is
/// kept (nothing written).
fn write_feature(
    tag: &str,
    systems: &[System],
    kept: &BTreeSet<u16>,
    parameters: Option<&String>,
    out: &mut String,
) -> bool {
    let mut text = format!("feature {tag} {{\n");
    if let Some(p) = parameters {
        text.push_str(p);
    }
    let mut any = false;
    let mut script = "";
    for s in systems {
        let lookups: Vec<u16> = s
            .lookups
            .iter()
            .copied()
            .filter(|l| kept.contains(l))
            .collect();
        if lookups.is_empty() {
            continue;
        }
        if s.script != script {
            let _ = writeln!(text, "    script {};", s.script);
            script = &s.script;
        }
        let required = if s.required { " required" } else { "" };
        match s.lang.as_str() {
            "dflt" => {
                let _ = writeln!(text, "    language dflt{required};");
            }
            lang => {
                let _ = writeln!(text, "    language {lang} exclude_dflt{required};");
            }
        }
        for l in lookups {
            let _ = writeln!(text, "    lookup gsub{l};");
        }
        any = true;
    }
    let _ = writeln!(text, "}} {tag};\n");
    if any {
        out.push_str(&text);
    }
    any
}

fn context_rule(
    back: Vec<Vec<u16>>,
    input: Vec<Vec<u16>>,
    ahead: Vec<Vec<u16>>,
    records: &[SequenceLookupRecord],
) -> ContextRule {
    ContextRule {
        back,
        input,
        ahead,
        lookups: records
            .iter()
            .map(|r| (r.sequence_index(), r.lookup_list_index()))
            .collect(),
    }
}

/// The covered glyphs whose class in `def` is `k` (a class-based rule set's first glyphs).
fn first_of_class(covered: &[u16], def: &ClassDef, k: usize) -> Vec<u16> {
    covered
        .iter()
        .copied()
        .filter(|&g| def.get(GlyphId::from(g)) as usize == k)
        .collect()
}

fn member(classes: &BTreeMap<u16, Vec<u16>>, class: u16) -> Vec<u16> {
    classes.get(&class).cloned().unwrap_or_default()
}

fn coverage(c: &CoverageTable) -> Vec<u16> {
    c.iter().map(glyph16).collect()
}

fn glyph16(g: GlyphId) -> u16 {
    u16::try_from(g.to_u32()).unwrap_or(u16::MAX)
}

/// `text` inside a feature-code `name "…"` string: quotes, backslashes and everything
/// outside printable ASCII as `\XXXX` UTF-16 code units (the Windows-platform escape).
fn fea_string(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_ascii_graphic() && c != '"' && c != '\\' || c == ' ' {
            out.push(c);
        } else {
            let mut units = [0u16; 2];
            for u in c.encode_utf16(&mut units) {
                let _ = write!(out, "\\{u:04X}");
            }
        }
    }
    out
}

/// A glyph name as feature code writes it: a keyword (`mark`, `by`, `NULL`, …) escaped.
fn escaped(name: &str) -> String {
    match KEYWORDS.split_whitespace().any(|k| k == name) {
        true => format!("\\{name}"),
        false => name.to_string(),
    }
}

/// A tag as feature syntax spells it (trailing spaces dropped), when it can.
fn spelled(tag: Tag) -> Option<String> {
    let text = tag.to_string();
    let text = text.trim_end_matches(' ');
    // A tag that starts with a digit reads as a number.
    let ok = text.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && text.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    ok.then(|| text.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tags_and_names_as_feature_code_writes_them() {
        assert_eq!(spelled(Tag::new(b"liga")).as_deref(), Some("liga"));
        assert_eq!(spelled(Tag::new(b"lao ")).as_deref(), Some("lao"));
        assert_eq!(spelled(Tag::new(b"KUR ")).as_deref(), Some("KUR"));
        // DejaVu's required feature.
        assert_eq!(spelled(Tag::new(b" RQD")), None);
        assert_eq!(spelled(Tag::new(b"c-v1")), None);
        assert_eq!(spelled(Tag::new(b"0x12")), None);
        assert_eq!(spelled(Tag::new(b"1234")), None);
        assert_eq!(escaped("mark"), "\\mark");
        assert_eq!(escaped("NULL"), "\\NULL");
        assert_eq!(escaped("by"), "\\by");
        assert_eq!(escaped("f_f_i"), "f_f_i");
        assert_eq!(escaped("markup"), "markup");
        assert_eq!(fea_string("Alternate a"), "Alternate a");
        assert_eq!(
            fea_string("\"ß\" \\ 😀"),
            "\\0022\\00DF\\0022 \\005C \\D83D\\DE00"
        );
    }
}
