//! The typed font model: what the sources mean, after parsing and validation.
//!
//! Everything downstream of [`crate::source`] works on these types only; it never sees
//! TOML and never re-validates: a [`Contour`] holds a validated [`XSpline`], so a model
//! can only be built from curves that evaluate. Coordinates are font units, y up.

use std::cmp::Ordering;
use std::collections::{HashMap, HashSet};
use std::path::PathBuf;

use crate::designspace::{Designspace, Location, RegionError, VariationModel};

use crate::xspline::{ControlPoint, XSpline, XSplineError};

/// A whole font: metrics, glyphs and kerning.
#[derive(Clone, Debug, PartialEq)]
pub struct Font {
    /// `font.toml`.
    pub info: FontInfo,
    /// Glyphs; the loader and the importer sort them by [`glyph_order`].
    pub glyphs: Vec<Glyph>,
    /// `kerning.toml`.
    pub kerning: Vec<KernPair>,
    /// `features.fea`, when the font folder has one.
    pub features: Option<FeatureFile>,
}

/// The font's own OpenType feature code (`features.fea` in the font folder), compiled
/// together with the features generated from the sources (kerning, anchors).
///
/// Two feature files are equal when their texts are: the path only says where the text
/// was read, for diagnostics (an imported or copied font has the same features).
#[derive(Clone, Debug)]
pub struct FeatureFile {
    /// The file, for diagnostics at file:line:col.
    pub path: PathBuf,
    /// Its text, as read.
    pub text: String,
}

impl PartialEq for FeatureFile {
    fn eq(&self, other: &Self) -> bool {
        self.text == other.text
    }
}

/// A font with masters: the default master (an ordinary [`Font`]), the design space, and
/// the other masters. A single-master font has no axes and no masters.
///
/// The loader guarantees that every master is compatible with the default: glyph `i` of a
/// master is glyph `i` of [`Family::default`], with the same contours, point counts, sharp
/// points and components; and that the master locations form a valid set
/// ([`Designspace::model`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Family {
    /// The default master: the font folder itself, at every axis default.
    pub default: Font,
    /// Axes and named instances (`font.toml`).
    pub designspace: Designspace,
    /// The other masters, in `font.toml` order.
    pub masters: Vec<Master>,
}

/// A non-default master (`[[master]]` in `font.toml`).
#[derive(Clone, Debug, PartialEq)]
pub struct Master {
    /// Master name, e.g. `"Bold"`.
    pub name: String,
    /// Its folder, as written in `font.toml` (relative to the font folder).
    pub folder: PathBuf,
    /// Where it sits (user coordinates).
    pub location: Location,
    /// Parallel to the default master's glyphs (same order, names and code points). A
    /// glyph a sparse master does not draw holds the blend of the glyph's other masters at
    /// this location ([`Family::fill_sparse`]).
    pub glyphs: Vec<Glyph>,
    /// This master's kerning; a pair it lacks is 0 here. A sparse master without kerning
    /// of its own holds the blend of the kerned masters' kerning at its location.
    pub kerning: Vec<KernPair>,
    /// A sparse master (`sparse = true`): it draws only some glyphs, as a designspace
    /// source on a UFO layer, or a source UFO that lacks some glyphs.
    pub sparse: bool,
    /// Whether [`Self::kerning`] is the master's own: always for a full master; for a
    /// sparse master, when its folder has a `kerning.toml`.
    pub kerned: bool,
    /// Per glyph (parallel to [`Self::glyphs`]), whether this master draws it: always for
    /// a full master.
    pub drawn: Vec<bool>,
}

/// Which masters blend for each glyph, and how: fontTools' sub-models. A glyph that a
/// sparse master does not draw blends from the default and the masters that draw it
/// (their own [`VariationModel`]); kerning blends from the kerned masters
/// ([`Master::kerned`]).
#[derive(Clone, Debug)]
pub struct GlyphModels {
    /// Each distinct set of non-default masters (indices into [`Family::masters`],
    /// ascending) with its model; the first is every master.
    pub sets: Vec<(Vec<usize>, VariationModel)>,
    /// Per glyph, the set its outline blends with: the masters that draw it or any glyph
    /// it places as a component.
    pub of_glyph: Vec<usize>,
    /// Per glyph, the set its own numbers (points, offsets, advance, anchors) blend with:
    /// the masters that draw it.
    pub own_of_glyph: Vec<usize>,
    /// The masters with kerning of their own ([`Master::kerned`]) and their model.
    pub kerning: (Vec<usize>, VariationModel),
}

impl GlyphModels {
    /// Every glyph drawn by all `masters` non-default masters, which blend with `model`.
    pub fn full(masters: usize, model: &VariationModel, glyphs: usize) -> GlyphModels {
        let all: Vec<usize> = (0..masters).collect();
        GlyphModels {
            sets: vec![(all.clone(), model.clone())],
            of_glyph: vec![0; glyphs],
            own_of_glyph: vec![0; glyphs],
            kerning: (all, model.clone()),
        }
    }

    /// The masters glyph `gi`'s outline blends from and their model.
    pub fn of(&self, gi: usize) -> (&[usize], &VariationModel) {
        let (set, model) = &self.sets[self.of_glyph[gi]];
        (set, model)
    }

    /// The masters that draw glyph `gi` and their model.
    pub fn own(&self, gi: usize) -> (&[usize], &VariationModel) {
        let (set, model) = &self.sets[self.own_of_glyph[gi]];
        (set, model)
    }

    /// The weights of `set` under `model` at `location`, spread over every master (default
    /// first, then [`Family::masters`]), 0 for the masters outside `set`.
    pub fn spread(
        designspace: &Designspace,
        masters: usize,
        (set, model): (&[usize], &VariationModel),
        location: &Location,
    ) -> Vec<f64> {
        let own = designspace.weights(model, location);
        if set.len() == masters {
            return own;
        }
        let mut w = vec![0.0; masters + 1];
        w[0] = own[0];
        for (k, &m) in set.iter().enumerate() {
            w[m + 1] = own[k + 1];
        }
        w
    }
}

impl Family {
    /// A single-master family: `font` with no axes.
    pub fn single(font: Font) -> Family {
        Family {
            default: font,
            designspace: Designspace::default(),
            masters: Vec::new(),
        }
    }

    /// Whether the family has axes (a variable font).
    pub fn is_variable(&self) -> bool {
        !self.designspace.axes.is_empty()
    }

    /// How the masters blend (regions in [`Family::masters`] order).
    pub fn model(&self) -> Result<VariationModel, RegionError> {
        let locations: Vec<Location> = self.masters.iter().map(|m| m.location.clone()).collect();
        self.designspace.model(&locations)
    }

    /// Whether any master is sparse.
    pub fn has_sparse(&self) -> bool {
        self.masters.iter().any(|m| m.sparse)
    }

    /// The model of the default master and the masters `set` (indices, ascending).
    fn model_of(&self, set: &[usize]) -> Result<VariationModel, RegionError> {
        let locations: Vec<Location> = set
            .iter()
            .map(|&m| self.masters[m].location.clone())
            .collect();
        self.designspace.model(&locations)
    }

    /// Each glyph's masters and model ([`GlyphModels`]). Without sparse masters there is
    /// one set, every master, with [`Family::model`].
    pub fn glyph_models(&self) -> Result<GlyphModels, RegionError> {
        let all: Vec<usize> = (0..self.masters.len()).collect();
        let full_model = self.model()?;
        let mut sets = vec![(all.clone(), full_model.clone())];
        let mut find = |set: Vec<usize>| -> Result<usize, RegionError> {
            Ok(match sets.iter().position(|(s, _)| *s == set) {
                Some(k) => k,
                None => {
                    let model = self.model_of(&set)?;
                    sets.push((set, model));
                    sets.len() - 1
                }
            })
        };
        let drawn = |m: usize, gi: usize| self.masters[m].drawn.get(gi).copied().unwrap_or(true);
        // A glyph's outline changes wherever one of its components' does: the masters
        // that draw it or any glyph it places (recursively; the loader refuses cycles).
        let index: HashMap<&str, usize> = (0..self.default.glyphs.len())
            .map(|gi| (self.default.glyphs[gi].name.as_str(), gi))
            .collect();
        let mut outline_sets: Vec<Option<Vec<usize>>> = vec![None; self.default.glyphs.len()];
        fn outline_set(
            family: &Family,
            index: &HashMap<&str, usize>,
            memo: &mut [Option<Vec<usize>>],
            gi: usize,
            depth: usize,
        ) -> Vec<usize> {
            if let Some(set) = &memo[gi] {
                return set.clone();
            }
            let mut set: Vec<usize> = (0..family.masters.len())
                .filter(|&m| family.masters[m].drawn.get(gi).copied().unwrap_or(true))
                .collect();
            if depth < 64 {
                for c in &family.default.glyphs[gi].components {
                    if let Some(&base) = index.get(c.base.as_str()) {
                        set.extend(outline_set(family, index, memo, base, depth + 1));
                    }
                }
            }
            set.sort_unstable();
            set.dedup();
            memo[gi] = Some(set.clone());
            set
        }
        let mut of_glyph = Vec::with_capacity(self.default.glyphs.len());
        let mut own_of_glyph = Vec::with_capacity(self.default.glyphs.len());
        for gi in 0..self.default.glyphs.len() {
            let own: Vec<usize> = all.iter().copied().filter(|&m| drawn(m, gi)).collect();
            let outline = outline_set(self, &index, &mut outline_sets, gi, 0);
            of_glyph.push(find(outline)?);
            own_of_glyph.push(find(own)?);
        }
        let kerned: Vec<usize> = all
            .iter()
            .copied()
            .filter(|&m| self.masters[m].kerned)
            .collect();
        let k = find(kerned.clone())?;
        let kerning = (kerned, sets[k].1.clone());
        Ok(GlyphModels {
            sets,
            of_glyph,
            own_of_glyph,
            kerning,
        })
    }
}

/// The one glyph order of sources and outputs: `.notdef` first, then by name.
pub fn glyph_order(a: &str, b: &str) -> Ordering {
    (a != ".notdef", a).cmp(&(b != ".notdef", b))
}

/// Font-wide metadata and vertical metrics (`font.toml`).
#[derive(Clone, Debug, PartialEq)]
pub struct FontInfo {
    /// Family name, e.g. `"Xglyph Sans"`.
    pub family: String,
    /// Default `"Regular"`.
    pub style: String,
    /// Font units per em.
    pub units_per_em: u16,
    /// Font units above the baseline (positive).
    pub ascender: f64,
    /// Font units below the baseline (negative, y-up).
    pub descender: f64,
    /// Height of flat lowercase letters (`x`), font units.
    pub x_height: f64,
    /// Height of flat capitals (`H`), font units.
    pub cap_height: f64,
    /// Maximum distance, in font units, between the X-splines and the exported Béziers.
    pub tolerance: f64,
    /// Optional free-form metadata (copyright, designer, ...), written into outputs.
    pub copyright: Option<String>,
    /// The designer's name.
    pub designer: Option<String>,
    /// Version text, e.g. `"1.002"`.
    pub version: Option<String>,
    /// Licence description, e.g. `"This Font Software is licensed under the SIL Open Font
    /// License, Version 1.1."` (OpenType name ID 13).
    pub license: Option<String>,
    /// Where the licence can be read (name ID 14).
    pub license_url: Option<String>,
    /// Four-character vendor ID for OS/2 `achVendID` (1 to 4 printable ASCII characters;
    /// shorter ones are padded with spaces). `None` writes [`DEFAULT_VENDOR`].
    pub vendor: Option<String>,
}

/// The vendor ID written when `font.toml` has no `vendor`: xglyph's own, not the
/// placeholder `NONE` that font checkers flag.
pub const DEFAULT_VENDOR: &str = "XGLY";

/// One glyph: its own contours plus components placed from other glyphs.
#[derive(Clone, Debug, PartialEq)]
pub struct Glyph {
    /// Glyph name (unique in the font).
    pub name: String,
    /// Code points mapped to this glyph (may be empty, e.g. accents or `.notdef`).
    pub unicodes: Vec<char>,
    /// Horizontal advance in font units.
    pub advance: f64,
    /// The glyph's own contours.
    pub contours: Vec<Contour>,
    /// Other glyphs placed into this one.
    pub components: Vec<Component>,
    /// Named attachment points (`[[anchor]]`), in source order. A name starting with `_`
    /// makes the glyph a mark that attaches by it (`_top` to a base's `top`).
    pub anchors: Vec<Anchor>,
    /// `mark = "outline"`: a mark (GDEF class Mark) that its own outline places, drawn
    /// where it lands after a zero or small advance; it has no `_` anchor, so the `mark`
    /// and `mkmk` features never attach it.
    pub outline_mark: bool,
}

/// A named attachment point of a glyph, font units (`[[anchor]]` in the glyph file).
///
/// Bases carry `top`, `bottom`, …; marks carry `_top`, … (where they attach), and may carry
/// `top` too, for a mark stacked on them (`mkmk`).
#[derive(Clone, Debug, PartialEq)]
pub struct Anchor {
    /// Anchor name, e.g. `"top"` or `"_top"`.
    pub name: String,
    /// Position `(x, y)`, font units.
    pub position: (f64, f64),
}

impl Anchor {
    /// For a mark's anchor (`_top`), the base anchor it attaches to (`top`).
    pub fn attaches_to(&self) -> Option<&str> {
        self.name.strip_prefix('_')
    }
}

/// A composite's effective anchors, as ufo2ft's propagate-anchors filter makes them: the
/// glyph's `own` anchors, then, for each name it lacks, the anchors carried by its
/// components. `placed` gives each component's offset and effective anchors, in component
/// order.
///
/// A component that is not a mark (no `_` anchor) brings its anchors moved by its offset
/// (a later one replaces an earlier one of the same name). A mark brings its `x` where it
/// also has `_x` and `x` is already there: the mark is attached there, and a mark stacked
/// on it then attaches to its own `x` (`acutecomb`'s `top` becomes `Aacute`'s `top`).
/// Underscore anchors never propagate, so a composite is a mark only by its own anchors.
///
/// Limits: no ligature anchors (`top_1`, `top_2` for several bases, as ufo2ft makes them);
/// no transforms other than offsets (the model has none).
pub fn propagate_anchors<'a>(
    own: &[Anchor],
    placed: impl IntoIterator<Item = ((f64, f64), &'a [Anchor])>,
) -> Vec<Anchor> {
    let mut found: Vec<Anchor> = Vec::new();
    for ((dx, dy), anchors) in placed {
        let mark = anchors.iter().any(|a| a.attaches_to().is_some());
        for a in anchors.iter().filter(|a| a.attaches_to().is_none()) {
            let moved = Anchor {
                name: a.name.clone(),
                position: (a.position.0 + dx, a.position.1 + dy),
            };
            let slot = found.iter_mut().find(|f| f.name == a.name);
            let attached = anchors.iter().any(|m| m.attaches_to() == Some(&a.name));
            match slot {
                Some(slot) if !mark || attached => *slot = moved,
                None if !mark => found.push(moved),
                _ => {}
            }
        }
    }
    let mut out = own.to_vec();
    out.extend(
        found
            .into_iter()
            .filter(|f| own.iter().all(|o| o.name != f.name)),
    );
    out
}

/// Whether a glyph is in GDEF's Mark class (and a "mark" in a UFO's
/// `public.openTypeCategories`): it attaches by a `_` anchor, its outline places it
/// (`mark = "outline"`), or it is mapped to a combining code point, a mark with or without
/// anchors (as glyphsLib's categories make it; FontBakery's `gdef_mark_chars`).
pub fn classed_mark(unicodes: &[char], anchors: &[Anchor], outline_mark: bool) -> bool {
    outline_mark
        || anchors.iter().any(|a| a.attaches_to().is_some())
        || unicodes.iter().any(|&c| crate::source::is_combining(c))
}

impl Glyph {
    /// Whether the glyph is a mark: it has an anchor whose name starts with `_`, or its
    /// outline places it ([`Glyph::outline_mark`]).
    pub fn is_mark(&self) -> bool {
        self.outline_mark || self.attaches_by_anchor()
    }

    /// Whether the glyph is a mark that attaches by an anchor (one whose name starts
    /// with `_`).
    pub fn attaches_by_anchor(&self) -> bool {
        self.anchors.iter().any(|a| a.attaches_to().is_some())
    }
}

/// One closed X-spline contour, as written (direction is fixed on output).
///
/// It holds a validated [`XSpline`]: [`Contour::new`] is the only check, and the loader
/// turns its [`XSplineError`] into a diagnostic at the point's place in the source.
#[derive(Clone, Debug, PartialEq)]
pub struct Contour {
    spline: XSpline,
}

impl Contour {
    /// Validates `points` as a closed X-spline ([`XSpline::new`]).
    pub fn new(points: Vec<ControlPoint>) -> Result<Self, XSplineError> {
        XSpline::new(points).map(Contour::from)
    }

    /// The control points, as written.
    pub fn points(&self) -> &[ControlPoint] {
        self.spline.points()
    }

    /// The validated curve.
    pub fn spline(&self) -> &XSpline {
        &self.spline
    }
}

impl From<XSpline> for Contour {
    fn from(spline: XSpline) -> Self {
        Contour { spline }
    }
}

/// A font's glyphs by name ([`Font::index`]); the first glyph wins if names repeat, as
/// with [`Font::glyph`].
#[derive(Clone, Debug, Default)]
pub struct GlyphIndex<'a>(HashMap<&'a str, &'a Glyph>);

impl<'a> GlyphIndex<'a> {
    /// The glyph with this name.
    pub fn get(&self, name: &str) -> Option<&'a Glyph> {
        self.0.get(name).copied()
    }
}

/// Another glyph's outline placed into this one, translated by `offset`.
#[derive(Clone, Debug, PartialEq)]
pub struct Component {
    /// Name of the placed glyph.
    pub base: String,
    /// Translation `(x, y)`, font units.
    pub offset: (f64, f64),
}

/// A kerning pair by glyph name; `value` in font units, negative = tighter.
#[derive(Clone, Debug, PartialEq)]
pub struct KernPair {
    /// Name of the first glyph.
    pub left: String,
    /// Name of the second glyph.
    pub right: String,
    /// Adjustment of the first glyph's advance, font units.
    pub value: f64,
}

impl FontInfo {
    /// Metadata for `family` on an em of `units_per_em`, style Regular: ascender 0.8 em,
    /// descender -0.2 em, x-height 0.5 em, cap height 0.7 em, tolerance 1/2000 em, and no
    /// optional text. What the importers and tests start from.
    pub fn with_em(family: impl Into<String>, units_per_em: u16) -> FontInfo {
        let em = f64::from(units_per_em);
        FontInfo {
            family: family.into(),
            style: "Regular".to_string(),
            units_per_em,
            ascender: 0.8 * em,
            descender: -0.2 * em,
            x_height: 0.5 * em,
            cap_height: 0.7 * em,
            tolerance: em / 2000.0,
            copyright: None,
            designer: None,
            version: None,
            license: None,
            license_url: None,
            vendor: None,
        }
    }
}

impl Font {
    /// The glyph with this name.
    pub fn glyph(&self, name: &str) -> Option<&Glyph> {
        self.glyphs.iter().find(|g| g.name == name)
    }

    /// The glyph mapped to code point `c`.
    pub fn glyph_for_char(&self, c: char) -> Option<&Glyph> {
        self.glyphs.iter().find(|g| g.unicodes.contains(&c))
    }

    /// Every contour of `glyph` with the offset that places it: its own contours at
    /// `(0, 0)`, then each component's contours (recursively) at the summed offsets.
    ///
    /// Builds a [`GlyphIndex`] when the glyph has components; to place many glyphs, build
    /// one index and call [`Font::placed_contours_in`].
    pub fn placed_contours<'a>(&'a self, glyph: &'a Glyph) -> Vec<(&'a Contour, (f64, f64))> {
        if glyph.components.is_empty() {
            return glyph.contours.iter().map(|c| (c, (0.0, 0.0))).collect();
        }
        self.placed_contours_in(&self.index(), glyph)
    }

    /// [`Font::placed_contours`] with base glyphs looked up in `index`.
    ///
    /// The model is validated, so bases exist and there are no cycles; a missing base
    /// is skipped and recursion is bounded by the glyph count as a safety net. The work is
    /// linear in the placed contours (a 4,000-deep chain of components resolves in
    /// 4,000 look-ups, not 4,000 scans of the glyph list).
    pub fn placed_contours_in<'a>(
        &'a self,
        index: &GlyphIndex<'a>,
        glyph: &'a Glyph,
    ) -> Vec<(&'a Contour, (f64, f64))> {
        let mut out = Vec::new();
        // An explicit stack rather than recursion: chains can be thousands deep.
        let mut stack = vec![(glyph, (0.0, 0.0), self.glyphs.len())];
        while let Some((glyph, offset, depth)) = stack.pop() {
            out.extend(glyph.contours.iter().map(|c| (c, offset)));
            if depth == 0 {
                continue;
            }
            // Reversed so that components come out in source order.
            for comp in glyph.components.iter().rev() {
                if let Some(base) = index.get(&comp.base) {
                    let off = (offset.0 + comp.offset.0, offset.1 + comp.offset.1);
                    stack.push((base, off, depth - 1));
                }
            }
        }
        out
    }

    /// A glyph's effective anchors ([`propagate_anchors`]): its own, and for the names it
    /// lacks the ones its components bring, recursively. Builds a [`GlyphIndex`]; for many
    /// glyphs, build one and call [`Font::anchors_in`].
    pub fn anchors(&self, glyph: &Glyph) -> Vec<Anchor> {
        if glyph.components.is_empty() {
            return glyph.anchors.clone();
        }
        self.anchors_in(&self.index(), glyph)
    }

    /// [`Font::anchors`] with base glyphs looked up in `index`.
    ///
    /// Each glyph below `glyph` is resolved once, bases first, with an explicit stack (a
    /// chain of components thousands deep needs no deep call stack). The model has no
    /// cycles; as a safety net a base on a cycle brings its own anchors only, and a missing
    /// base brings none.
    pub fn anchors_in<'a>(&'a self, index: &GlyphIndex<'a>, glyph: &'a Glyph) -> Vec<Anchor> {
        let mut done: HashMap<&str, Vec<Anchor>> = HashMap::new();
        let mut open: HashSet<&str> = HashSet::new();
        let mut stack = vec![glyph];
        while let Some(&g) = stack.last() {
            if done.contains_key(g.name.as_str()) {
                stack.pop();
                continue;
            }
            if open.insert(&g.name) {
                // First visit: resolve the bases first.
                for c in &g.components {
                    if let Some(b) = index.get(&c.base) {
                        if !done.contains_key(b.name.as_str()) && !open.contains(b.name.as_str()) {
                            stack.push(b);
                        }
                    }
                }
                continue;
            }
            stack.pop();
            let placed: Vec<((f64, f64), &[Anchor])> = g
                .components
                .iter()
                .map(|c| {
                    let anchors = match done.get(c.base.as_str()) {
                        Some(a) => a.as_slice(),
                        None => index.get(&c.base).map_or(&[][..], |b| &b.anchors),
                    };
                    (c.offset, anchors)
                })
                .collect();
            let anchors = propagate_anchors(&g.anchors, placed);
            done.insert(&g.name, anchors);
        }
        done.remove(glyph.name.as_str()).unwrap_or_default()
    }

    /// Glyphs by name, for many look-ups (the list itself is searched linearly).
    pub fn index(&self) -> GlyphIndex<'_> {
        GlyphIndex(
            self.glyphs
                .iter()
                .rev()
                .map(|g| (g.name.as_str(), g))
                .collect(),
        )
    }

    /// Kerning value between two glyph names (0 when there is no pair).
    pub fn kern(&self, left: &str, right: &str) -> f64 {
        self.kerning
            .iter()
            .find(|k| k.left == left && k.right == right)
            .map_or(0.0, |k| k.value)
    }
}

/// The OpenType weight class (100..900) a style name stands for: `"Bold Italic"` -> 700,
/// `"Semi-Bold"` -> 600; 400 when it names no weight. Used by the SVG font (CSS weight) and
/// the OS/2 table, so both read the style the same way.
pub fn weight_class(style: &str) -> u16 {
    const WEIGHTS: &[(&str, u16)] = &[
        // Compound names first: "extralight" also contains "light".
        ("extralight", 200),
        ("ultralight", 200),
        ("semibold", 600),
        ("demibold", 600),
        ("extrabold", 800),
        ("ultrabold", 800),
        ("thin", 100),
        ("light", 300),
        ("medium", 500),
        ("bold", 700),
        ("black", 900),
        ("heavy", 900),
    ];
    let compact: String = style
        .chars()
        .filter(|c| c.is_alphanumeric())
        .flat_map(char::to_lowercase)
        .collect();
    WEIGHTS
        .iter()
        .find(|(name, _)| compact.contains(name))
        .map_or(400, |&(_, weight)| weight)
}

/// A 1000-unit em with typical metrics, for unit tests across the crate.
#[cfg(test)]
pub(crate) fn test_info() -> FontInfo {
    FontInfo::with_em("Test", 1000)
}

#[cfg(test)]
mod tests {
    use super::weight_class;

    #[test]
    fn style_names_to_weight_classes() {
        assert_eq!(weight_class("Regular"), 400);
        assert_eq!(weight_class("Bold Italic"), 700);
        assert_eq!(weight_class("Semi-Bold"), 600);
        assert_eq!(weight_class("ExtraLight"), 200);
        assert_eq!(weight_class("Light Oblique"), 300);
        assert_eq!(weight_class("Black"), 900);
        assert_eq!(weight_class("Condensed"), 400);
    }
}
