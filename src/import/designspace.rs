//! Designspace import: a `.designspace` (norad) and its source UFOs -> a font with masters
//! (`font.toml` `[[axis]]`/`[[master]]`/`[[instance]]`, one folder per non-default master).
//!
//! Each source UFO is imported on its own ([`super::import_ufo`]): an xglyph export takes
//! its X-splines from the glyph libs, so `build` then import gives the same family back.
//! The source at every axis default becomes the font folder itself; every other source a
//! master whose folder is its style name in lower case without spaces (`bold/`).
//!
//! A source on a UFO layer (`layer="…"`, fontmake's sparse "support" masters) becomes a
//! sparse master ([`Master::sparse`]): it draws only the glyphs its layer has
//! ([`super::import_ufo_layer`]: no kerning, info or features of its own), a glyph its
//! layer holds empty while the default draws it counts as not drawn (as fontTools takes
//! it), and [`Family::fill_sparse`] blends the rest from the masters that draw them; its
//! folder holds only the glyphs it draws ([`family_sources`]). A source on a default layer
//! that lacks some of the default's glyphs is sparse too, as fontmake takes it, and keeps
//! its kerning ([`Master::kerned`]). A default source on a layer is read from that layer as
//! a whole font. An axis end without a source is kept as fontTools blends it: the design
//! returns to the default there.
//!
//! A glyph that every source drawing it fits from its outline (foreign UFOs, without
//! xglyph's lib) is fitted again for those sources at once ([`super::masters`]): one
//! X-spline structure, each source's points fitted to its own outline, and the blend
//! halfway between the default and each other of those sources measured against the
//! blended outlines. Limits: the sources' outlines of such a glyph must have one Bézier
//! structure (else the error names the glyph); a glyph taken from xglyph's lib in one
//! source and fitted in another must come out compatible by itself (else the error names
//! the glyph and master); a glyph in a layer that the default source lacks is an error
//! naming it and the source. Axis maps become the axes' `map`; locations are read as user
//! coordinates (`uservalue`, else `xvalue` through the inverse map); `<rules>` become
//! `[[rule]]`s (conditions in user values; glyph names renamed as the UFO import renames
//! them). A designspace 5 with discrete axes is imported at one discrete location (`--at
//! ital=1`, else each at its default), as fontmake builds one variable font per location:
//! [`super::discrete`] first cuts the document down to that location's sources, instances
//! and rules and its continuous axes. `<mappings>` (avar 2), and sources that xglyph's
//! masters cannot hold (two at one place) are not supported: an error says which, before
//! any UFO is read.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::{Path, PathBuf};

use norad::designspace::{DesignSpaceDocument, Dimension, RuleProcessing};

use rayon::prelude::*;

use super::discrete::{at_discrete_location, DiscreteLocation};
use super::masters::{import_compatible_glyph, Checkpoint};
use super::report::Report;
use super::UfoLayer;
use super::{grid_for, import_ufo_layer, ImportError, ImportOptions, Imported, SourceGlyph};
use crate::designspace::{
    Axis, Designspace, Location, NamedInstance, RegionError, Rule, MAX_RULE_BOXES,
};
use crate::model::{Family, Glyph, Master};

/// A designspace imported: the family and each source's report (default first).
#[derive(Debug)]
pub struct ImportedFamily {
    /// The default master with the others, axes and named instances.
    pub family: Family,
    /// Per source, its style name and import report, the default's first.
    pub reports: Vec<(String, Report)>,
    /// The discrete location imported, when the designspace has discrete axes
    /// ([`super::discrete`]).
    pub discrete: Option<DiscreteLocation>,
}

/// Imports the designspace at `path` and every source UFO it names.
pub fn import_designspace(
    path: &Path,
    opts: &ImportOptions,
) -> Result<ImportedFamily, ImportError> {
    let doc = DesignSpaceDocument::load(path).map_err(|e| {
        ImportError::at(
            path,
            format!(
                "cannot read the designspace: {}",
                crate::ufo::error_chain(&e)
            ),
        )
    })?;
    let fail = |message: String| ImportError::at(path, message);
    let (doc, discrete) = at_discrete_location(doc, opts.at.as_deref()).map_err(fail)?;
    let axes = axes(&doc).map_err(fail)?;
    let mut designspace = Designspace {
        axes,
        instances: Vec::new(),
        rules: Vec::new(),
        rules_last: matches!(doc.rules.processing, RuleProcessing::Last),
    };
    let (rules, rule_notes) = rules(&doc, &designspace.axes).map_err(fail)?;
    designspace.rules = rules;
    let base = path.parent().unwrap_or(Path::new(""));
    let mut sources = Vec::new();
    for s in &doc.sources {
        let style = s
            .stylename
            .clone()
            .or_else(|| s.name.clone())
            .unwrap_or_else(|| s.filename.trim_end_matches(".ufo").to_string());
        let location = location(&designspace, &s.location)
            .map_err(|m| fail(format!("source `{style}`: {m}")))?;
        sources.push(Source {
            style,
            location,
            ufo: base.join(&s.filename),
            layer: s.layer.clone(),
            sparse: false,
        });
    }
    let at_default = |l: &Location| designspace.normalize(l).iter().all(|&v| v == 0.0);
    // The default source: one on a default layer if there is one.
    let default_index = sources
        .iter()
        .position(|s| at_default(&s.location) && s.layer.is_none())
        .or_else(|| sources.iter().position(|s| at_default(&s.location)))
        .ok_or_else(|| fail("no source sits at the default of every axis".into()))?;
    // Every other source on a layer is a sparse master, as in fontmake.
    for (i, s) in sources.iter_mut().enumerate() {
        s.sparse = i != default_index && s.layer.is_some();
    }
    check_regions(&designspace, &sources, default_index).map_err(fail)?;
    distinct_styles(&designspace, &mut sources, default_index).map_err(fail)?;
    let mut imported = Vec::new();
    for s in &sources {
        let layer = s.layer.as_deref().map(|name| {
            if s.sparse {
                UfoLayer::Sparse(name)
            } else {
                UfoLayer::Full(name)
            }
        });
        imported.push((
            s.style.clone(),
            s.location.clone(),
            import_ufo_layer(&s.ufo, layer, opts)?,
        ));
    }
    let drawn_in_default: HashMap<String, bool> = imported[default_index]
        .2
        .font
        .glyphs
        .iter()
        .map(|g| (g.name.clone(), !is_empty(g)))
        .collect();
    for (k, one) in imported.iter_mut().enumerate() {
        if sources[k].sparse {
            leave_out_empty(&mut one.2, &drawn_in_default);
        }
    }
    // A source on a default layer that lacks some of the default's glyphs is sparse for
    // its outlines, as fontmake takes it; its kerning stays its own.
    let sparse: Vec<bool> = imported
        .iter()
        .zip(&sources)
        .map(|((_, _, one), s)| {
            let names: HashSet<&str> = one.font.glyphs.iter().map(|g| g.name.as_str()).collect();
            s.sparse
                || drawn_in_default
                    .keys()
                    .any(|name| !names.contains(name.as_str()))
        })
        .collect();
    let kerned: Vec<bool> = sources.iter().map(|s| !s.sparse).collect();
    let tolerance = super::check_tolerance(
        opts.tolerance,
        imported[default_index].2.font.info.units_per_em,
    )?;
    refit_compatible(&mut imported, &sparse, default_index, tolerance).map_err(fail)?;
    let (style, _, default) = imported.remove(default_index);
    let mut font = default.font;
    font.info.style = style.clone();
    let mut reports = vec![(style, default.report)];
    let mut masters = Vec::new();
    let others = sparse
        .iter()
        .zip(&kerned)
        .enumerate()
        .filter(|&(i, _)| i != default_index)
        .map(|(_, (&s, &k))| (s, k));
    for ((style, location, other), (sparse, kerned)) in imported.into_iter().zip(others) {
        let folder = PathBuf::from(folder_name(&style));
        let (glyphs, drawn) =
            parallel(&font.glyphs, &other.font.glyphs, &style, sparse).map_err(fail)?;
        masters.push(Master {
            name: style.clone(),
            folder,
            location,
            drawn,
            glyphs,
            // A source on a layer has no kerning: the kerned masters' blend
            // ([`Family::fill_sparse`]).
            kerning: if kerned {
                other.font.kerning
            } else {
                Vec::new()
            },
            sparse,
            kerned,
        });
        reports.push((style, other.report));
    }
    // The rules name glyphs as the UFOs do; the import renamed the names outside the
    // OpenType `post` rule (`names::glyph_name_from`), so the rules follow.
    let has = |n: &str| font.glyphs.iter().any(|g| g.name == n);
    for rule in &mut designspace.rules {
        for (from, to) in &mut rule.substitutions {
            for name in [&mut *from, &mut *to] {
                let renamed = crate::names::glyph_name_from(name);
                if !has(name) && has(&renamed) {
                    *name = renamed;
                }
            }
        }
    }
    for rule in &designspace.rules {
        for (from, to) in &rule.substitutions {
            if let Some(missing) = [from, to]
                .into_iter()
                .find(|n| !font.glyphs.iter().any(|g| &g.name == *n))
            {
                return Err(fail(format!(
                    "rule `{}` substitutes glyph `{missing}`, which the default source does \
                     not have",
                    rule.name
                )));
            }
        }
    }
    for i in &doc.instances {
        let given = i
            .stylename
            .clone()
            .or_else(|| i.name.clone())
            .filter(|n| !n.trim().is_empty());
        let location = location(&designspace, &i.location).map_err(|m| {
            fail(format!(
                "instance `{}`: {m}",
                given.as_deref().unwrap_or("")
            ))
        })?;
        // An instance without a style name is named by its place, e.g. `Weight 350`.
        let name = given.unwrap_or_else(|| {
            designspace
                .axes
                .iter()
                .map(|a| {
                    format!(
                        "{} {}",
                        a.name,
                        crate::source::emit::computed_number(location.get(a))
                    )
                })
                .collect::<Vec<_>>()
                .join(" ")
        });
        // The same instance twice (name and place) is one.
        if designspace
            .instances
            .iter()
            .any(|i| i.name == name && i.location == location)
        {
            continue;
        }
        designspace.instances.push(NamedInstance { name, location });
    }
    let mut family = Family {
        default: font,
        designspace,
        masters,
    };
    // What the sparse masters leave out, blended from the masters that draw it.
    family.fill_sparse().map_err(|e| {
        fail(format!(
            "a glyph that a source does not draw cannot be blended there: {e}"
        ))
    })?;
    let parted = super::masters::part_meeting_points(&mut family).map_err(fail)?;
    if let Some((_, report)) = reports.first_mut() {
        report.notes.extend(rule_notes);
        report.notes.extend(parted);
    }
    Ok(ImportedFamily {
        family,
        reports,
        discrete,
    })
}

/// Whether a glyph has no outline: no contours, no components.
fn is_empty(g: &Glyph) -> bool {
    g.contours.is_empty() && g.components.is_empty()
}

/// Leaves out of a sparse source's import the glyphs its layer holds empty while the
/// default source draws them (`drawn_in_default` by name): fontTools takes such a glyph
/// as missing from the sparse master, so it blends from the others there.
fn leave_out_empty(one: &mut Imported, drawn_in_default: &HashMap<String, bool>) {
    let empty: Vec<String> = one
        .font
        .glyphs
        .iter()
        .filter(|g| is_empty(g) && drawn_in_default.get(&g.name).copied().unwrap_or(false))
        .map(|g| g.name.clone())
        .collect();
    if empty.is_empty() {
        return;
    }
    one.font.glyphs.retain(|g| !empty.contains(&g.name));
    one.report.rows.retain(|r| !empty.contains(&r.name));
    for name in &empty {
        one.outlines.remove(name);
    }
    one.report.notes.push(format!(
        "{} left out: empty in the layer, drawn in the default source (taken as not drawn \
         here, as fontTools does)",
        empty.join(", ")
    ));
}

/// One `<source>` of the designspace.
struct Source {
    /// Its style name (else its name, else its file name without `.ufo`).
    style: String,
    /// Where it sits (user coordinates).
    location: Location,
    /// Its UFO folder.
    ufo: PathBuf,
    /// The UFO layer it reads; `None` for the default layer.
    layer: Option<String>,
    /// On a layer, and not the default source: a sparse master, drawing only the glyphs
    /// its layer has.
    sparse: bool,
}

/// Refuses, before any UFO is read, sources that xglyph's masters cannot hold
/// ([`Designspace::model`]): two sources at one place. An axis end without a source is
/// kept as fontTools blends it: past the outermost source the design goes back to the
/// default (`check` and `build` warn about it).
fn check_regions(
    designspace: &Designspace,
    sources: &[Source],
    default_index: usize,
) -> Result<(), String> {
    let others: Vec<&Source> = sources
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != default_index)
        .map(|(_, s)| s)
        .collect();
    let locations: Vec<Location> = others.iter().map(|s| s.location.clone()).collect();
    let place = |l: &Location| {
        designspace
            .axes
            .iter()
            .map(|a| format!("{} = {}", a.tag, crate::source::emit::number(l.get(a))))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match designspace.model(&locations) {
        Ok(_) => Ok(()),
        Err(RegionError::AtDefault { master }) => Err(format!(
            "sources `{}` and `{}` both sit at the default of every axis",
            sources[default_index].style, others[master].style
        )),
        Err(RegionError::Duplicate { first, second }) => Err(format!(
            "sources `{}` and `{}` sit at the same place ({})",
            others[first].style,
            others[second].style,
            place(&others[first].location)
        )),
    }
}

/// Gives each non-default source a style name whose master folder no other takes: a style
/// name already taken by the default or an earlier source (as when one UFO serves at two
/// places) gets the source's place, `Master0 Contrast 100`. Sources whose names still
/// collide are an error, before any UFO is read.
fn distinct_styles(
    designspace: &Designspace,
    sources: &mut [Source],
    default_index: usize,
) -> Result<(), String> {
    let folder = |s: &str| folder_name(s);
    let mut taken = vec![folder(&sources[default_index].style)];
    for (i, source) in sources.iter_mut().enumerate() {
        if i == default_index {
            continue;
        }
        let Source {
            style, location, ..
        } = source;
        if taken.contains(&folder(style)) {
            for a in &designspace.axes {
                let v = location.get(a);
                if v != a.default {
                    style.push_str(&format!(" {} {}", a.name, crate::source::emit::number(v)));
                }
            }
        }
        taken.push(folder(style));
    }
    let mut named: Vec<(String, &str)> = sources
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != default_index)
        .map(|(_, s)| (folder(&s.style), s.style.as_str()))
        .collect();
    named.sort();
    match named.windows(2).find(|w| w[0].0 == w[1].0) {
        Some(w) => Err(format!(
            "sources `{}` and `{}` would share the master folder {}/; give them distinct \
             style names",
            w[0].1, w[1].1, w[0].0
        )),
        None => Ok(()),
    }
}

/// The designspace's `<rules>` as [`Rule`]s: each `<conditionset>` a box in user values
/// (design values through the inverse axis map; an open end, or one beyond the axis, at
/// the axis end), an empty one the whole space; rules without a name are named `rule 1`, ….
/// A condition on an axis the designspace lacks is left out, with a note (returned).
fn rules(doc: &DesignSpaceDocument, axes: &[Axis]) -> Result<(Vec<Rule>, Vec<String>), String> {
    let mut out = Vec::new();
    let mut notes = Vec::new();
    for (k, r) in doc.rules.rules.iter().enumerate() {
        let name = r
            .name
            .clone()
            .filter(|n| !n.trim().is_empty())
            .unwrap_or_else(|| format!("rule {}", k + 1));
        let mut conditions = Vec::new();
        for set in &r.condition_sets {
            let mut ranges = BTreeMap::new();
            for c in &set.conditions {
                // A condition on an axis the designspace lacks is left out, as fontTools'
                // `splitInterpolable` (which fontmake builds through) leaves it out.
                let Some(axis) = axes.iter().find(|a| a.name == c.name || a.tag == c.name) else {
                    notes.push(format!(
                        "rule `{name}`: its condition on `{}`, which is not an axis, is left \
                         out, as fontmake leaves it out",
                        c.name
                    ));
                    continue;
                };
                let user = |design: Option<f64>, end: f64| {
                    design.map_or(end, |d| axis.user(d).clamp(axis.min, axis.max))
                };
                let (min, max) = (user(c.minimum, axis.min), user(c.maximum, axis.max));
                if min > max {
                    return Err(format!(
                        "rule `{name}`: the condition on `{}` runs backwards ({min} > {max})",
                        c.name
                    ));
                }
                ranges.insert(axis.tag.clone(), (min, max));
            }
            if ranges.is_empty() {
                // An empty condition set holds everywhere: the whole first axis.
                if let Some(a) = axes.first() {
                    ranges.insert(a.tag.clone(), (a.min, a.max));
                }
            }
            conditions.push(ranges);
        }
        if conditions.is_empty() {
            continue;
        }
        out.push(Rule {
            name,
            conditions,
            substitutions: r
                .substitutions
                .iter()
                .map(|s| (s.name.to_string(), s.with.to_string()))
                .filter(|(a, b)| a != b)
                .collect(),
        });
    }
    if out.iter().map(|r| r.conditions.len()).sum::<usize>() > MAX_RULE_BOXES {
        return Err(format!(
            "the rules have more than {MAX_RULE_BOXES} condition sets in all, more than xglyph \
             overlays"
        ));
    }
    Ok((out, notes))
}

/// Fits again, with one structure for all sources that draw it
/// ([`import_compatible_glyph`]), every glyph that each of them fitted from its outline
/// (foreign UFOs: fitted one source at a time, the masters matched only by luck). A glyph
/// is drawn by the default, every full source and the sparse sources (`sparse[i]`) whose
/// layer has it; the checkpoints are the halfway blends among those. The glyphs'
/// components, anchors and advances stay as each source's import made them; the report
/// rows are replaced.
fn refit_compatible(
    imported: &mut [(String, Location, Imported)],
    sparse: &[bool],
    default_index: usize,
    tolerance: f64,
) -> Result<(), String> {
    // Per glyph, the sources that draw it, the default first, as the compatible import
    // takes them.
    let drawing = |name: &str| -> Vec<usize> {
        let mut order: Vec<usize> = vec![default_index];
        order.extend((0..imported.len()).filter(|&i| {
            i != default_index
                && (!sparse[i] || imported[i].2.font.glyphs.iter().any(|g| g.name == name))
        }));
        order
    };
    let jobs: Vec<(String, Vec<usize>)> = imported[default_index]
        .2
        .outlines
        .keys()
        .map(|name| (name.clone(), drawing(name)))
        .filter(|(name, order)| {
            order
                .iter()
                .all(|&i| imported[i].2.outlines.contains_key(name))
        })
        .collect();
    let grid = grid_for(tolerance);
    let refits = jobs
        .par_iter()
        .map(|(name, order)| {
            let sources: Vec<SourceGlyph> = order
                .iter()
                .map(|&i| imported[i].2.outlines[name].clone())
                .collect();
            let checkpoints = Checkpoint::halfways(order.len());
            import_compatible_glyph(&sources, &checkpoints, tolerance, grid)
        })
        .collect::<Result<Vec<_>, String>>()?;
    for (fitted, (_, order)) in refits.into_iter().zip(&jobs) {
        for (f, &i) in fitted.into_iter().zip(order) {
            let one = &mut imported[i].2;
            if let Some(g) = one.font.glyphs.iter_mut().find(|g| g.name == f.glyph.name) {
                g.contours = f.glyph.contours;
            }
            if let Some(row) = one.report.rows.iter_mut().find(|r| r.name == f.report.name) {
                *row = f.report;
            }
        }
    }
    Ok(())
}

/// The axes of `doc` (continuous: [`at_discrete_location`] took out the discrete ones), with
/// their maps (`<map input="user" output="design">`).
fn axes(doc: &DesignSpaceDocument) -> Result<Vec<Axis>, String> {
    if doc
        .axis_mappings
        .as_ref()
        .is_some_and(|m| !m.mappings.is_empty())
    {
        return Err("`<mappings>` (avar 2, mapping between axes) are not supported".into());
    }
    doc.axes
        .iter()
        .map(|a| {
            let (Some(min), Some(max)) = (a.minimum, a.maximum) else {
                return Err(format!(
                    "axis `{}` has neither values (a discrete axis) nor a minimum and maximum",
                    a.name
                ));
            };
            let mut axis = Axis::linear(a.tag.clone(), a.name.clone(), min, a.default, max);
            if let Some(map) = a.map.as_ref().filter(|m| !m.is_empty()) {
                axis.map = axis_map(&axis, map)?;
            }
            Ok(axis)
        })
        .collect()
}

/// A designspace axis map as xglyph's: sorted by user value, from the axis `min` to its
/// `max` (an end the map leaves out is placed as fontTools extrapolates it, keeping the
/// nearest entry's offset), design values strictly increasing.
fn axis_map(
    axis: &Axis,
    map: &[norad::designspace::AxisMapping],
) -> Result<Vec<(f64, f64)>, String> {
    let mut pairs: Vec<(f64, f64)> = map.iter().map(|m| (m.input, m.output)).collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    pairs.dedup_by(|a, b| a == b);
    let given = Axis {
        map: pairs.clone(),
        ..axis.clone()
    };
    pairs.retain(|&(u, _)| (axis.min..=axis.max).contains(&u));
    for end in [axis.min, axis.max] {
        if !pairs.iter().any(|&(u, _)| u == end) {
            pairs.push((end, given.design(end)));
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    if let Some(w) = pairs
        .windows(2)
        .find(|w| w[1].0 <= w[0].0 || w[1].1 <= w[0].1)
    {
        return Err(format!(
            "axis `{}` has a map that does not increase (user {} -> design {}, then user {} -> \
             design {}); xglyph's axis maps must increase in both",
            axis.name,
            crate::source::emit::number(w[0].0),
            crate::source::emit::number(w[0].1),
            crate::source::emit::number(w[1].0),
            crate::source::emit::number(w[1].1)
        ));
    }
    Ok(pairs)
}

/// A location by axis tag, in user values; an axis the dimensions leave out is at its
/// default. A dimension's `uservalue` is taken as it is, its `xvalue` (design) through the
/// inverse of the axis map.
fn location(ds: &Designspace, dims: &[Dimension]) -> Result<Location, String> {
    let mut location = Location::default();
    for d in dims {
        let axis = ds
            .axes
            .iter()
            .find(|a| a.name == d.name)
            .ok_or_else(|| format!("the location names the unknown axis `{}`", d.name))?;
        let value = d
            .uservalue
            .or(d.xvalue.map(|x| axis.user(x)))
            .ok_or_else(|| format!("the location on `{}` has no value", d.name))?;
        location.0.insert(axis.tag.clone(), value);
    }
    Ok(location)
}

/// The master folder of a style: lower case, without spaces (`Semi Bold` -> `semibold`).
pub(crate) fn folder_name(style: &str) -> String {
    let name: String = style
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_'))
        .flat_map(char::to_lowercase)
        .collect();
    if name.is_empty() {
        "master".into()
    } else {
        name
    }
}

/// The master's glyphs in the default's order, checked compatible with the default's
/// (glyph set, contour and point counts, sharp points), and which of them it draws. A
/// sparse master may lack glyphs: each holds the default's glyph, not drawn, until
/// [`Family::fill_sparse`] blends it.
fn parallel(
    default: &[Glyph],
    master: &[Glyph],
    style: &str,
    sparse: bool,
) -> Result<(Vec<Glyph>, Vec<bool>), String> {
    let by_name: HashMap<&str, &Glyph> = master.iter().map(|g| (g.name.as_str(), g)).collect();
    if let Some(extra) = master
        .iter()
        .find(|g| !default.iter().any(|d| d.name == g.name))
    {
        return Err(if sparse {
            format!(
                "source `{style}` draws the glyph `{}` in its layer, which the default \
                 source lacks",
                extra.name
            )
        } else {
            format!(
                "master `{style}` has the glyph `{}`, which the default source lacks",
                extra.name
            )
        });
    }
    default
        .iter()
        .map(|d| {
            // A master that lacks the glyph is sparse (see `import_designspace`).
            let Some(m) = by_name.get(d.name.as_str()) else {
                return Ok((d.clone(), false));
            };
            let shape = |g: &Glyph| -> Vec<Vec<bool>> {
                g.contours
                    .iter()
                    .map(|c| c.points().iter().map(|p| p.s == 0.0).collect())
                    .collect()
            };
            if shape(m) != shape(d) {
                return Err(format!(
                    "glyph `{}`: master `{style}` does not match the default source ({} \
                     contours of {:?} points, the default {} of {:?}, or sharp points \
                     elsewhere); the masters do not interpolate as X-splines",
                    d.name,
                    m.contours.len(),
                    m.contours
                        .iter()
                        .map(|c| c.points().len())
                        .collect::<Vec<_>>(),
                    d.contours.len(),
                    d.contours
                        .iter()
                        .map(|c| c.points().len())
                        .collect::<Vec<_>>(),
                ));
            }
            let mut g = (*m).clone();
            g.unicodes = d.unicodes.clone();
            Ok((g, true))
        })
        .collect::<Result<Vec<_>, String>>()
        .map(|v| v.into_iter().unzip())
}

/// Every source file of an imported family as `(relative path, text)`: `font.toml` with the
/// axes, masters and instances, the default master's glyph files and kerning, then each
/// master's folder (`bold/a.toml` …, glyph files without `unicode`, and `bold/kerning.toml`).
/// A sparse master's folder holds only the glyphs it draws, and its kerning only when it
/// has its own ([`Master::kerned`]).
pub fn family_sources(family: &Family) -> Vec<(String, String)> {
    let mut files = crate::source::emit::font_sources(&family.default);
    files[0].1 = crate::source::emit::family_font_toml(
        &family.default.info,
        &family.designspace,
        &family.masters,
    );
    for m in &family.masters {
        let folder = m.folder.to_string_lossy();
        let stems = crate::names::file_stems(m.glyphs.iter().map(|g| g.name.as_str()));
        for (i, (g, stem)) in m.glyphs.iter().zip(stems).enumerate() {
            if !m.drawn.get(i).copied().unwrap_or(true) {
                continue;
            }
            files.push((
                format!("{folder}/{stem}.toml"),
                crate::source::emit::master_glyph_toml(g),
            ));
        }
        // A sparse master with kerning of its own keeps it even when empty: without the
        // file, it would blend the others' kerning.
        if m.kerned && (m.sparse || !m.kerning.is_empty()) {
            files.push((
                format!("{folder}/kerning.toml"),
                crate::source::emit::kerning_toml(&m.kerning),
            ));
        }
    }
    files
}

#[cfg(test)]
mod tests {
    use super::*;
    use norad::designspace::AxisMapping;

    fn weight() -> Axis {
        Axis::linear("wght", "Weight", 100.0, 400.0, 900.0)
    }

    fn mapping(pairs: &[(f64, f64)]) -> Vec<AxisMapping> {
        pairs
            .iter()
            .map(|&(input, output)| AxisMapping { input, output })
            .collect()
    }

    #[test]
    fn a_map_is_sorted_and_extended_to_the_axis_ends_as_fonttools_extrapolates() {
        // fontTools' piecewiseLinearMap keeps the nearest entry's offset beyond the map:
        // 100 -> 100 + (90 - 400) = -210.
        let map = axis_map(&weight(), &mapping(&[(900.0, 190.0), (400.0, 90.0)]));
        assert_eq!(
            map,
            Ok(vec![(100.0, -210.0), (400.0, 90.0), (900.0, 190.0)])
        );
        // Entries outside the axis are left out (the end is interpolated through them).
        let map = axis_map(
            &weight(),
            &mapping(&[(0.0, 0.0), (400.0, 100.0), (900.0, 200.0), (1000.0, 210.0)]),
        );
        assert_eq!(map, Ok(vec![(100.0, 25.0), (400.0, 100.0), (900.0, 200.0)]));
    }

    #[test]
    fn a_map_that_does_not_increase_is_refused() {
        let map = axis_map(
            &weight(),
            &mapping(&[(100.0, 50.0), (400.0, 90.0), (900.0, 90.0)]),
        );
        assert_eq!(
            map,
            Err(
                "axis `Weight` has a map that does not increase (user 400 -> design 90, then \
                 user 900 -> design 90); xglyph's axis maps must increase in both"
                    .to_string()
            )
        );
    }
}
