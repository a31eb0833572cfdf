//! OpenType layout (GSUB, GPOS, GDEF): the font's `features.fea` compiled by fea-rs
//! together with the features generated from the sources, for the static fonts and the
//! variable TTF alike.
//!
//! Generated, as ufo2ft's feature writers and fontc do it:
//! - `kern`: one pair-adjustment lookup (IgnoreMarks) from the kerning, by glyph;
//! - `mark`: per anchor name `N`, one mark-to-base lookup: marks carry `_N`, bases `N`;
//! - `mkmk`: per anchor name `N`, one mark-to-mark lookup: marks with `_N` on marks with
//!   `N`, filtered to those marks (UseMarkFilteringSet);
//! - GDEF glyph classes: fea-rs's own inference from the GPOS lookups (`markClass`
//!   members are marks), the outputs of ligature substitutions ligatures, every glyph with
//!   a `_` anchor, a combining code point (U+0300…) or `mark = "outline"` a mark, every
//!   other glyph but `.notdef` a base. No component class: components are
//!   resolved into outlines. A `mark = "outline"` glyph is in no `mark` lookup (it has no
//!   `_` anchor); an anchor `x` on it takes marks in `mkmk`, as on any mark.
//!
//! The user's features and the generated ones merge (fea-rs's [`FeatureProvider`]); where
//! the user's file has its own `kern`, `mark` or `mkmk` feature, that feature is theirs
//! and the generated one is left out (ufo2ft's "skip" mode, fontc's default); a
//! `table GDEF` with `GlyphClassDef` in the file replaces the generated classes (ufo2ft's
//! GDEF writer skips too).
//!
//! With masters, every generated value (kerning, anchor x and y) is rounded per master
//! and the deltas (rounded master − rounded default) go through fea-rs into GDEF's item
//! variation store (VariationIndex devices, anchor format 3). The user's file has no
//! variable syntax here (no axis is known to fea-rs).
//!
//! fea-rs 1.0 is built on write-fonts 0.52 and the rest of `otf` on 0.55, so the three
//! tables cross over as bytes. Glyph names in the file are the model's glyph names.
//! Limits: no mark-to-ligature (`mark` on ligature components) and no `curs`.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use fea_rs::compile::{
    self, FeatureBuilder, FeatureProvider, NopVariationInfo, Opts, PendingLookup, VariationInfo,
};
use fea_rs::parse::{SourceLoadError, SourceResolver};
use fea_rs::typed::AstNode;
use fea_rs::{DiagnosticSet, GlyphMap, Level, ParseTree};
use fea_write_fonts::tables::gdef::{Gdef, GlyphClassDef};
use fea_write_fonts::tables::gpos::builders::{
    AnchorBuilder, MarkToBaseBuilder, MarkToMarkBuilder, PairPosBuilder, ValueRecordBuilder,
};
use fea_write_fonts::tables::gsub::builders::SingleSubBuilder;
use fea_write_fonts::tables::layout::builders::DeviceOrDeltas;
use fea_write_fonts::tables::layout::{ClassDef, ConditionFormat1, ConditionSet, LookupFlag};
use fea_write_fonts::tables::variations::{RegionAxisCoordinates, VariationRegion};
use fea_write_fonts::types::{F2Dot14, GlyphId16, Tag};

use super::kern::KernPairs;
use super::{grid, OtfError};
use crate::designspace::{Region, VariationModel};
use crate::model::{Anchor, FeatureFile};
use crate::source::{line_col, Diagnostic, Severity, Snippet};

/// What the layout tables are generated from: the glyph order and, per master (the
/// default first), each glyph's anchors and the kerning.
pub(crate) struct LayoutSource<'a> {
    /// Model glyph names in glyph order (`.notdef` first).
    pub names: Vec<&'a str>,
    /// Each glyph's code points (combining marks are GDEF marks without anchors too).
    pub unicodes: Vec<&'a [char]>,
    /// Per glyph, whether it is a mark its outline places (`mark = "outline"`).
    pub outline_marks: Vec<bool>,
    /// Per master, per glyph (glyph order), its anchors.
    pub anchors: Vec<Vec<&'a [Anchor]>>,
    /// Per master, its kerning by glyph id.
    pub kerning: Vec<KernPairs>,
    /// How the masters blend (`None` for a static font).
    pub model: Option<LayoutModels<'a>>,
    /// The rules as `rvrn` feature variations: per box (normalised ranges by axis index,
    /// the first that holds deciding), the glyph ids it substitutes.
    pub rules: &'a [RuleRegion],
    /// The feature the rules vary: `rvrn`, or `rclt` when they apply last.
    pub rules_feature: [u8; 4],
    /// Number of axes (0 for a static font).
    pub axis_count: u16,
    /// The font's own `features.fea`.
    pub features: Option<&'a FeatureFile>,
}

/// Which masters blend for each value of a variable font's layout: per glyph (glyph
/// order) for its anchors, and the full masters for kerning. Each is a set of non-default
/// masters (indices into the per-master lists, the default not counted) and its model.
pub(crate) struct LayoutModels<'a> {
    /// Per glyph, the masters that draw it and their model.
    pub glyphs: Vec<(&'a [usize], &'a VariationModel)>,
    /// The masters with kerning of their own and their model.
    pub kerning: (&'a [usize], &'a VariationModel),
}

/// A box of the design space (per constrained axis: index, normalised min and max) and
/// the (glyph id, alternate id) substitutions inside it.
pub type RuleRegion = (Vec<(usize, f64, f64)>, Vec<(u16, u16)>);

/// The compiled layout tables, as bytes for write-fonts 0.55's builder.
#[derive(Default)]
pub(crate) struct LayoutTables {
    pub gsub: Option<Vec<u8>>,
    pub gpos: Option<Vec<u8>>,
    pub gdef: Option<Vec<u8>>,
    /// The `name` records the layout refers to (stylistic set names, character variant
    /// labels: IDs from 256, as fea-rs numbers them), as (platform, encoding, language,
    /// ID, text). A variable font's own names take the IDs after them.
    pub names: Vec<(u16, u16, u16, u16, String)>,
}

impl LayoutTables {
    /// The first name ID after the layout's own.
    pub(crate) fn next_name_id(&self) -> u16 {
        self.names
            .iter()
            .map(|r| r.3 + 1)
            .max()
            .unwrap_or(256)
            .max(256)
    }
}

/// Compiles the layout of `source`: `features.fea` and the generated features.
///
/// Errors in the file are [`OtfError::Features`] diagnostics at its file:line:col.
pub(crate) fn layout_tables(source: &LayoutSource) -> Result<LayoutTables, OtfError> {
    let glyph_map = glyph_map(&source.names)?;
    let fea_path = source
        .features
        .map(|f| f.path.clone())
        .unwrap_or_else(|| PathBuf::from("features.fea"));
    let text = source.features.map(|f| f.text.as_str()).unwrap_or("");
    let tree = parse(&fea_path, text, &glyph_map)?;
    let user_features = user_feature_tags(&tree);

    let var_info = Axes(source.axis_count);
    // fea-rs's compiler assumes a validated tree (it panics on an unknown glyph name in a
    // class definition): validate first, so a bad file is an error, never a panic.
    let invalid = if source.axis_count > 0 {
        compile::validate(&tree, &glyph_map, Some(&var_info))
    } else {
        compile::validate::<NopVariationInfo>(&tree, &glyph_map, None)
    };
    if invalid.has_errors() {
        return Err(OtfError::Features(diagnostics(&tree, &invalid)));
    }
    let generated = Generated::new(source, &user_features)?;
    let (compilation, _warnings) = if source.axis_count > 0 {
        compile::compile(
            &tree,
            &glyph_map,
            Some(&var_info),
            Some(&generated),
            Opts::new(),
        )
    } else {
        compile::compile::<NopVariationInfo, _>(
            &tree,
            &glyph_map,
            None,
            Some(&generated),
            Opts::new(),
        )
    }
    .map_err(|errors| OtfError::Features(diagnostics(&tree, &errors)))?;

    let table_err = |what: &str, e: fea_write_fonts::error::Error| {
        OtfError::Table(format!("{what} from features.fea: {e}"))
    };
    let mut out = LayoutTables::default();
    // Names of the user's file for standard IDs (a `table name` block) are not taken: the
    // font's own come from font.toml.
    if let Some(name) = &compilation.name {
        out.names = name
            .name_record
            .iter()
            .filter(|r| r.name_id.to_u16() >= 256)
            .map(|r| {
                let text: &str = &r.string;
                (
                    r.platform_id,
                    r.encoding_id,
                    r.language_id,
                    r.name_id.to_u16(),
                    text.to_string(),
                )
            })
            .collect();
    }
    if let Some(gsub) = &compilation.gsub {
        out.gsub = Some(fea_write_fonts::dump_table(gsub).map_err(|e| table_err("GSUB", e))?);
    }
    if let Some(gpos) = &compilation.gpos {
        out.gpos = Some(fea_write_fonts::dump_table(gpos).map_err(|e| table_err("GPOS", e))?);
    }
    let ligatures = match &out.gsub {
        Some(gsub) => ligature_glyphs(gsub)
            .map_err(|e| OtfError::Table(format!("GSUB from features.fea: {e}")))?,
        None => BTreeSet::new(),
    };
    let mut gdef = compilation.gdef.clone();
    let wanted =
        gdef.is_some() || generated.has_marks() || !ligatures.is_empty() || out.gsub.is_some();
    if compilation.gdef_classes.is_none() && wanted {
        let gdef = gdef.get_or_insert_with(Gdef::default);
        let mut inferred = inferred_classes(gdef)?;
        for g in ligatures {
            inferred.insert(g, GlyphClassDef::Ligature as u16);
        }
        gdef.glyph_class_def = glyph_classes(source, &generated.marks, &inferred).into();
    }
    if let Some(gdef) = &gdef {
        out.gdef = Some(fea_write_fonts::dump_table(gdef).map_err(|e| table_err("GDEF", e))?);
    }
    Ok(out)
}

/// Checks `features.fea` against the glyph names of a font (syntax, unknown glyphs and
/// everything else fea-rs validates), without building anything.
pub fn check_features(features: &FeatureFile, glyph_names: &[&str]) -> Vec<Diagnostic> {
    let mut names = vec![".notdef"];
    names.extend(glyph_names.iter().filter(|n| **n != ".notdef"));
    let glyph_map = match glyph_map(&names) {
        Ok(map) => map,
        Err(OtfError::Features(d)) => return d,
        Err(e) => {
            return vec![Diagnostic::whole(
                &features.path,
                Severity::Error,
                e.to_string(),
            )]
        }
    };
    let tree = match parse(&features.path, &features.text, &glyph_map) {
        Ok(tree) => tree,
        Err(OtfError::Features(d)) => return d,
        Err(e) => {
            return vec![Diagnostic::whole(
                &features.path,
                Severity::Error,
                e.to_string(),
            )]
        }
    };
    let errors = compile::validate::<NopVariationInfo>(&tree, &glyph_map, None);
    let mut out = diagnostics(&tree, &errors);
    if out.is_empty() {
        // Compilation finds what validation does not (e.g. overlapping rules).
        if let Err(errors) = compile::compile::<NopVariationInfo, compile::NopFeatureProvider>(
            &tree,
            &glyph_map,
            None,
            None,
            Opts::new(),
        ) {
            out = diagnostics(&tree, &errors);
        }
    }
    out
}

/// The glyph order for fea-rs.
fn glyph_map(names: &[&str]) -> Result<GlyphMap, OtfError> {
    GlyphMap::new(names.iter().copied())
        .map_err(|e| OtfError::Table(format!("features.fea: glyph order: {e}")))
}

/// Hands fea-rs the file's text as loaded (never re-read; `include` reads next to it).
struct Loaded {
    path: PathBuf,
    text: Arc<str>,
}

impl SourceResolver for Loaded {
    fn get_contents(&self, path: &Path) -> Result<Arc<str>, SourceLoadError> {
        if path == self.path {
            return Ok(self.text.clone());
        }
        std::fs::read_to_string(path)
            .map(Into::into)
            .map_err(|e| SourceLoadError::new(path.to_path_buf(), e))
    }

    fn resolve_raw_path(&self, path: &Path, included_from: Option<&Path>) -> PathBuf {
        if path == self.path {
            return path.to_path_buf();
        }
        let base = included_from
            .and_then(Path::parent)
            .or_else(|| self.path.parent())
            .unwrap_or(Path::new(""));
        base.join(path)
    }
}

/// Parses the file; syntax errors are diagnostics.
fn parse(path: &Path, text: &str, glyph_map: &GlyphMap) -> Result<ParseTree, OtfError> {
    let resolver = Loaded {
        path: path.to_path_buf(),
        text: text.into(),
    };
    let (tree, diags) =
        fea_rs::parse::parse_root(path.to_path_buf(), Some(glyph_map), Box::new(resolver))
            .map_err(|e| {
                OtfError::Features(vec![Diagnostic::whole(
                    path,
                    Severity::Error,
                    e.to_string(),
                )])
            })?;
    let errors = diagnostics(&tree, &diags);
    if errors.is_empty() {
        Ok(tree)
    } else {
        Err(OtfError::Features(errors))
    }
}

/// fea-rs's errors (warnings dropped) as the project's diagnostics, at file:line:col.
fn diagnostics(tree: &ParseTree, set: &DiagnosticSet) -> Vec<Diagnostic> {
    set.diagnostics()
        .iter()
        .filter(|d| d.level == Level::Error)
        .map(|d| {
            let Some(source) = tree.get_source(d.message.file) else {
                return Diagnostic::whole(Path::new("features.fea"), Severity::Error, d.text());
            };
            let text = source.text();
            let (line, col) = line_col(text, d.span().start);
            let line_text = text.lines().nth(line - 1).unwrap_or("").to_string();
            // fea-rs says "glyph not in font"; name the glyph.
            let message = match (d.text(), text.get(d.span())) {
                ("glyph not in font", Some(name)) if !name.is_empty() => {
                    format!("glyph '{name}' is not in the font")
                }
                (message, _) => message.to_string(),
            };
            Diagnostic {
                path: source.path().to_path_buf(),
                line,
                col,
                severity: Severity::Error,
                message,
                snippet: Some(Snippet {
                    text: line_text,
                    caret: col,
                }),
                count: 1,
            }
        })
        .collect()
}

/// Tags of the features the file defines at the top level.
fn user_feature_tags(tree: &ParseTree) -> BTreeSet<[u8; 4]> {
    tree.typed_root()
        .statements()
        .filter_map(fea_rs::typed::Feature::cast)
        .map(|f| f.tag().to_raw().into_bytes())
        .collect()
}

/// A variable font's axes as fea-rs needs them: only their count (the item variation
/// store's width); the file cannot name axes.
struct Axes(u16);

/// The file used variable syntax (fea-rs asks [`Axes`] to resolve it).
#[derive(Debug)]
struct NoAxes;

impl std::fmt::Display for NoAxes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("variable values in features.fea are not supported")
    }
}

impl std::error::Error for NoAxes {}

impl VariationInfo for Axes {
    type Error = NoAxes;

    fn axis_count(&self) -> u16 {
        self.0
    }

    fn axis(&self, _: Tag) -> Option<(usize, &fontdrasil::types::Axis)> {
        None
    }

    fn resolve_variable_metric(
        &self,
        _: &HashMap<fontdrasil::coords::NormalizedLocation, i16>,
    ) -> Result<(i16, Vec<(VariationRegion, i16)>), Self::Error> {
        Err(NoAxes)
    }

    fn resolve_glyphs_number_value(
        &self,
        _: &str,
    ) -> Result<HashMap<fontdrasil::coords::NormalizedLocation, f64>, Self::Error> {
        Err(NoAxes)
    }
}

/// A value per master: the default's, and the deltas of the others (only when one is
/// not zero).
#[derive(Clone, Debug, PartialEq)]
struct Varying {
    default: i16,
    deltas: Vec<(VariationRegion, i16)>,
}

impl Varying {
    fn device(&self) -> Option<DeviceOrDeltas> {
        (!self.deltas.is_empty()).then(|| DeviceOrDeltas::Deltas(self.deltas.clone()))
    }
}

/// The generated features, ready for fea-rs.
struct Generated {
    /// `(first, second)` -> x advance of the first.
    kerning: BTreeMap<(u16, u16), Varying>,
    /// Anchor name (without `_`) -> mark glyph -> its `_name` anchor.
    marks: BTreeMap<String, BTreeMap<u16, (Varying, Varying)>>,
    /// Anchor name -> glyph -> its `name` anchor (bases and marks alike).
    attach: BTreeMap<String, BTreeMap<u16, (Varying, Varying)>>,
    /// Glyph ids of the marks (a `_` anchor, or `mark = "outline"`).
    mark_glyphs: BTreeSet<u16>,
    skip_kern: bool,
    skip_mark: bool,
    skip_mkmk: bool,
    /// The rules' boxes and substitutions, and the feature they vary.
    rules: Vec<RuleRegion>,
    rules_feature: [u8; 4],
}

impl Generated {
    fn new(source: &LayoutSource, user: &BTreeSet<[u8; 4]>) -> Result<Self, OtfError> {
        let axes = usize::from(source.axis_count);
        // A value in every master (default first), blended by the masters of `set`.
        let vary = |set: Option<(&[usize], &VariationModel)>, values: &[i16]| Varying {
            default: values[0],
            deltas: set.map_or_else(Vec::new, |(masters, model)| {
                let values: Vec<i32> = std::iter::once(values[0])
                    .chain(masters.iter().map(|&m| values[m + 1]))
                    .map(i32::from)
                    .collect();
                model
                    .regions
                    .iter()
                    .zip(model.int_deltas(&values))
                    .filter(|&(_, d)| d != 0)
                    // Wrapping as i16 arithmetic would (the values are i16 already).
                    .map(|(r, d)| (variation_region(r, axes), d as i16))
                    .collect()
            }),
        };
        let kerning_set = source.model.as_ref().map(|m| m.kerning);
        let glyph_set = |gid: u16| source.model.as_ref().map(|m| m.glyphs[usize::from(gid)]);
        let masters = source.kerning.len();
        let mut pairs: BTreeMap<(u16, u16), Vec<i16>> = BTreeMap::new();
        for (m, kerning) in source.kerning.iter().enumerate() {
            for (&left, seconds) in kerning {
                for (&right, &value) in seconds {
                    pairs
                        .entry((left, right))
                        .or_insert_with(|| vec![0; masters])[m] = value;
                }
            }
        }
        let kerning = pairs
            .iter()
            .map(|(&k, v)| (k, vary(kerning_set, v)))
            .collect();

        let mut marks: BTreeMap<String, BTreeMap<u16, (Varying, Varying)>> = BTreeMap::new();
        let mut attach: BTreeMap<String, BTreeMap<u16, (Varying, Varying)>> = BTreeMap::new();
        // Marks placed by their outlines are marks too: an anchor `x` on one is a mark's.
        let mut mark_glyphs: BTreeSet<u16> = (0u16..)
            .zip(&source.outline_marks)
            .filter_map(|(gid, &mark)| mark.then_some(gid))
            .collect();
        let default = &source.anchors[0];
        for (gid, anchors) in default.iter().enumerate() {
            let gid = gid as u16;
            for (i, anchor) in anchors.iter().enumerate() {
                let name = source.names[usize::from(gid)];
                let mut xs = Vec::with_capacity(source.anchors.len());
                let mut ys = Vec::with_capacity(source.anchors.len());
                for master in &source.anchors {
                    // Masters are compatible: same anchors in the same order; a master
                    // that lacks one has the default's.
                    let a = master[usize::from(gid)]
                        .iter()
                        .find(|a| a.name == anchor.name)
                        .or(anchors.get(i))
                        .unwrap_or(anchor);
                    let what = || format!("anchor '{}' of '{name}'", a.name);
                    xs.push(grid::to_i16(a.position.0, what)?);
                    ys.push(grid::to_i16(a.position.1, what)?);
                }
                let value = (vary(glyph_set(gid), &xs), vary(glyph_set(gid), &ys));
                match anchor.attaches_to() {
                    Some(base) => {
                        mark_glyphs.insert(gid);
                        marks
                            .entry(base.to_string())
                            .or_default()
                            .insert(gid, value);
                    }
                    None => {
                        attach
                            .entry(anchor.name.clone())
                            .or_default()
                            .insert(gid, value);
                    }
                }
            }
        }
        let has = |tag: &[u8; 4]| user.contains(tag);
        Ok(Generated {
            kerning,
            marks,
            attach,
            mark_glyphs,
            skip_kern: has(b"kern"),
            skip_mark: has(b"mark"),
            skip_mkmk: has(b"mkmk"),
            rules: source.rules.to_vec(),
            rules_feature: source.rules_feature,
        })
    }

    fn has_marks(&self) -> bool {
        !self.mark_glyphs.is_empty()
    }
}

fn anchor((x, y): &(Varying, Varying)) -> AnchorBuilder {
    let mut a = AnchorBuilder::new(x.default, y.default);
    if let Some(d) = x.device() {
        a = a.with_x_device(d);
    }
    if let Some(d) = y.device() {
        a = a.with_y_device(d);
    }
    a
}

impl FeatureProvider for Generated {
    fn add_features(&self, builder: &mut FeatureBuilder) {
        if !self.rules.is_empty() {
            // One single-substitution lookup per box, in the order the boxes decide.
            let conditions = self
                .rules
                .iter()
                .map(|(ranges, subs)| {
                    let mut lookup = SingleSubBuilder::default();
                    for &(from, to) in subs {
                        lookup.insert(GlyphId16::new(from), GlyphId16::new(to));
                    }
                    let id = builder.add_lookup(PendingLookup::new(
                        vec![lookup],
                        LookupFlag::empty(),
                        None,
                    ));
                    let f = |v: f64| F2Dot14::from_f32(v as f32);
                    let set = ConditionSet::new(
                        ranges
                            .iter()
                            .map(|&(axis, min, max)| {
                                ConditionFormat1::new(axis as u16, f(min), f(max)).into()
                            })
                            .collect(),
                    );
                    (set, vec![id])
                })
                .collect();
            builder.add_feature_variations(vec![Tag::new(&self.rules_feature)], conditions);
        }
        if !self.kerning.is_empty() && !self.skip_kern {
            let mut pairs = PairPosBuilder::default();
            for (&(left, right), value) in &self.kerning {
                let mut record = ValueRecordBuilder::new().with_x_advance(value.default);
                if let Some(d) = value.device() {
                    record = record.with_x_advance_device(d);
                }
                pairs.insert_pair(
                    GlyphId16::new(left),
                    record,
                    GlyphId16::new(right),
                    ValueRecordBuilder::new(),
                );
            }
            let id = builder.add_lookup(PendingLookup::new(
                vec![pairs],
                LookupFlag::IGNORE_MARKS,
                None,
            ));
            builder.add_to_default_language_systems(Tag::new(b"kern"), &[id]);
        }
        let mut mark_lookups = Vec::new();
        let mut mkmk_lookups = Vec::new();
        for (name, marks) in &self.marks {
            let Some(targets) = self.attach.get(name) else {
                continue;
            };
            let bases: Vec<_> = targets
                .iter()
                .filter(|(g, _)| !self.mark_glyphs.contains(g))
                .collect();
            let mark_bases: Vec<_> = targets
                .iter()
                .filter(|(g, _)| self.mark_glyphs.contains(g))
                .collect();
            if !bases.is_empty() && !self.skip_mark {
                let mut b = MarkToBaseBuilder::default();
                for (&g, value) in marks {
                    // One class per lookup: a glyph cannot be in two.
                    let _ = b.insert_mark(GlyphId16::new(g), name, anchor(value));
                }
                for (&g, value) in &bases {
                    b.insert_base(GlyphId16::new(g), name, anchor(value));
                }
                mark_lookups.push(builder.add_lookup(PendingLookup::new(
                    vec![b],
                    LookupFlag::empty(),
                    None,
                )));
            }
            if !mark_bases.is_empty() && !self.skip_mkmk {
                let mut b = MarkToMarkBuilder::default();
                for (&g, value) in marks {
                    let _ = b.insert_mark1(GlyphId16::new(g), name, anchor(value));
                }
                for (&g, value) in &mark_bases {
                    b.insert_mark2(GlyphId16::new(g), name, anchor(value));
                }
                let filter: fea_rs::GlyphSet = marks
                    .keys()
                    .chain(mark_bases.iter().map(|(g, _)| *g))
                    .map(|&g| GlyphId16::new(g))
                    .collect();
                let flags = LookupFlag::USE_MARK_FILTERING_SET;
                mkmk_lookups.push(builder.add_lookup(PendingLookup::new(
                    vec![b],
                    flags,
                    Some(filter),
                )));
            }
        }
        if !mark_lookups.is_empty() {
            builder.add_to_default_language_systems(Tag::new(b"mark"), &mark_lookups);
        }
        if !mkmk_lookups.is_empty() {
            builder.add_to_default_language_systems(Tag::new(b"mkmk"), &mkmk_lookups);
        }
    }
}

/// The glyph classes fea-rs inferred from the lookups (read back from its table).
fn inferred_classes(gdef: &Gdef) -> Result<BTreeMap<u16, u16>, OtfError> {
    let Some(class_def) = gdef.glyph_class_def.as_ref() else {
        return Ok(BTreeMap::new());
    };
    let bytes = fea_write_fonts::dump_table(class_def)
        .map_err(|e| OtfError::Table(format!("GDEF classes: {e}")))?;
    let read = <read_fonts::tables::layout::ClassDef as read_fonts::FontRead>::read(
        read_fonts::FontData::new(&bytes),
    )
    .map_err(|e| OtfError::Table(format!("GDEF classes: {e}")))?;
    Ok(read
        .iter()
        .map(|(g, c)| (g.to_u32() as u16, c as u16))
        .collect())
}

/// The outputs of the ligature substitutions (GDEF class 2; fea-rs infers classes from
/// GPOS only).
fn ligature_glyphs(gsub: &[u8]) -> Result<BTreeSet<u16>, read_fonts::ReadError> {
    use read_fonts::tables::gsub::{Gsub, LigatureSubst, SubstitutionSubtables};
    use read_fonts::FontRead;
    let gsub = Gsub::read(read_fonts::FontData::new(gsub))?;
    let mut out = BTreeSet::new();
    for lookup in gsub.lookup_list()?.lookups().iter() {
        if let SubstitutionSubtables::Ligature(subtables) = lookup?.subtables()? {
            for subtable in subtables.iter() {
                // Format 2 is for 24-bit glyph ids, which a font of ours never has.
                let LigatureSubst::Format1(subtable) = subtable? else {
                    continue;
                };
                for set in subtable.ligature_sets().iter() {
                    for ligature in set?.ligatures().iter() {
                        out.insert(ligature?.ligature_glyph().to_u16());
                    }
                }
            }
        }
    }
    Ok(out)
}

/// The GDEF glyph classes: fea-rs's inference, the ligatures of GSUB, the marks of the anchors, and every other
/// glyph (but `.notdef`) a base.
fn glyph_classes(
    source: &LayoutSource,
    marks: &BTreeMap<String, BTreeMap<u16, (Varying, Varying)>>,
    inferred: &BTreeMap<u16, u16>,
) -> ClassDef {
    let mark = GlyphClassDef::Mark as u16;
    let base = GlyphClassDef::Base as u16;
    let mut classes = inferred.clone();
    for g in marks.values().flat_map(BTreeMap::keys) {
        classes.insert(*g, mark);
    }
    for (gid, unicodes) in source.unicodes.iter().enumerate() {
        let anchors = source.anchors[0].get(gid).copied().unwrap_or_default();
        let outline_mark = source.outline_marks.get(gid).copied().unwrap_or(false);
        if crate::model::classed_mark(unicodes, anchors, outline_mark) {
            classes.insert(gid as u16, mark);
        }
    }
    for (gid, name) in source.names.iter().enumerate() {
        if *name != ".notdef" {
            classes.entry(gid as u16).or_insert(base);
        }
    }
    classes
        .into_iter()
        .map(|(g, c)| (GlyphId16::new(g), c))
        .collect()
}

/// A master's tent as an item-variation region (fea-rs's write-fonts, an older release than
/// the one `hvar` builds with, hence its own types; the numbers come from one place).
fn variation_region(region: &Region, axis_count: usize) -> VariationRegion {
    VariationRegion::new(
        crate::otf::variable::region_axes(region, axis_count)
            .map(|[start, peak, end]| {
                let f = F2Dot14::from_f32;
                RegionAxisCoordinates::new(f(start), f(peak), f(end))
            })
            .collect(),
    )
}
