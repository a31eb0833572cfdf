//! The variable TTF: the default master as a static TrueType font (the shared tables of
//! `otf/tables.rs`), plus the variation tables, one module each:
//!
//! - `glyf` from the compatible quadratics of all masters ([`quadratic`]), `gvar`
//!   ([`gvar`]) with the point deltas of each master and the phantom-point deltas of its
//!   advances;
//! - `HVAR` ([`hvar`]) with the same advance deltas;
//! - `fvar` ([`fvar`]) with the axes and named instances, `STAT` ([`stat`]) and their names
//!   ([`naming`]) in `name`; `avar` ([`avar`]) with the axis maps (the identity for a
//!   linear axis);
//! - the layout of `otf/features.rs` (fea-rs): kerning and mark anchors with
//!   VariationIndex devices into `GDEF`'s item variation store.
//!
//! Grid rounding as fontmake does it: the default master's points are rounded, and each
//! master's deltas are its rounded points minus the rounded default's, so every master
//! comes out exactly as its own rounded outline. Between the masters a consumer blends
//! those; the result is within grid rounding (√2/2 units) plus the quadratic accuracy of the
//! blended cubic outline.
//!
//! `gvar` omits the deltas that interpolation of untouched points infers exactly ([`iup`]),
//! so instances are the same as with every delta written.
//!
//! Limits: no legacy `kern` table (it cannot vary); the OS/2 weight class is the default's `wght`.

mod avar;
mod fvar;
mod gvar;
mod hvar;
mod iup;
pub(crate) use hvar::region_axes;
mod naming;
mod quadratic;
mod stat;

use kurbo::BezPath;
use read_fonts::tables::glyf::CurvePoint;
use write_fonts::tables::glyf::{Contour, SimpleGlyph};
use write_fonts::tables::gvar::GlyphDelta;
use write_fonts::types::Tag;
use write_fonts::BuilderError;

use super::features::{layout_tables, LayoutModels, LayoutSource, RuleRegion};
use super::kern::kern_pairs;
use super::tables::{font_builder, Outlines, VariableShared};
use super::truetype::{self, TtGlyph};
use super::{grid, GlyphSet, OtfError};
use crate::designspace::{Designspace, VariationModel};
use crate::family::OutlinedFamily;
use crate::model::Anchor;
use naming::VariableNames;

/// Per non-default master, one glyph's deltas (outline points then 4 phantom points), those
/// that IUP infers optional.
pub(crate) type MasterDeltas = Vec<Vec<GlyphDelta>>;

/// An axis tag as OpenType wants it: 1 to 4 printable ASCII characters, space-padded.
fn tag(text: &str) -> Result<Tag, OtfError> {
    Tag::new_checked(text.as_bytes())
        .map_err(|_| OtfError::Table(format!("axis tag '{text}' is not 1 to 4 ASCII letters")))
}

/// The family as a variable TrueType font: the default master's tables, its outlines and
/// the variations of every other master (see the module documentation). Anchors are the
/// default master's in every master; [`variable_ttf_with_anchors`] varies them.
pub fn variable_ttf(family: &OutlinedFamily) -> Result<Vec<u8>, OtfError> {
    variable_ttf_with_anchors(family, &[])
}

/// [`variable_ttf`] with the anchors of the non-default masters: per master of
/// [`OutlinedFamily::masters`], per glyph of the default (same order), its anchors (the
/// model's `Master::glyphs`; the outlined masters carry none). A master left out, or with
/// another glyph count, has the default's anchors.
pub fn variable_ttf_with_anchors(
    family: &OutlinedFamily,
    master_anchors: &[Vec<Vec<Anchor>>],
) -> Result<Vec<u8>, OtfError> {
    build(family, master_anchors, Deltas::Optimized)
}

/// [`variable_ttf`] with every point delta written (no IUP): the reference the optimized
/// `gvar` is tested against (its instances must be the same).
pub fn variable_ttf_explicit_deltas(family: &OutlinedFamily) -> Result<Vec<u8>, OtfError> {
    build(family, &[], Deltas::Explicit)
}

/// Which point deltas `gvar` writes.
#[derive(Clone, Copy, PartialEq)]
enum Deltas {
    /// Those a consumer cannot infer exactly ([`iup`]).
    Optimized,
    /// All of them.
    Explicit,
}

fn build(
    family: &OutlinedFamily,
    master_anchors: &[Vec<Vec<Anchor>>],
    kind: Deltas,
) -> Result<Vec<u8>, OtfError> {
    let font = &family.default;
    let designspace = &family.designspace;
    if designspace.axes.is_empty() {
        return Err(OtfError::Table("variable font: no axes".into()));
    }
    let axis_count = u16::try_from(designspace.axes.len())
        .map_err(|_| OtfError::Table("variable font: too many axes".into()))?;
    for master in &family.masters {
        if master.glyphs.len() != font.glyphs.len() {
            return Err(OtfError::Table(format!(
                "variable font: master '{}' has {} glyphs, the default {}",
                master.name,
                master.glyphs.len(),
                font.glyphs.len()
            )));
        }
    }
    let model = &family.model;
    let set = GlyphSet::new(font)?;
    // A synthesised .notdef comes first and is the same in every master.
    let synthesised = set.glyphs.len() - font.glyphs.len();

    let mut tt_glyphs = Vec::with_capacity(set.glyphs.len());
    let mut point_deltas = Vec::with_capacity(set.glyphs.len());
    let mut advance_deltas = Vec::with_capacity(set.glyphs.len());
    for (gid, glyph) in set.glyphs.iter().enumerate() {
        let source = gid.checked_sub(synthesised);
        let own = glyph.path();
        let mut paths: Vec<&BezPath> = vec![own.as_ref()];
        let mut advances = vec![glyph.advance];
        // The glyph's own masters and model (every master but sparse ones that do not
        // draw it).
        let (drawing, model) = match source {
            Some(i) => family.glyph_model(i),
            None => (&family.models.sets[0].0[..], model),
        };
        for master in drawing.iter().map(|&m| &family.masters[m]) {
            let Some(g) = source.map(|i| &master.glyphs[i]) else {
                paths.push(own.as_ref());
                advances.push(glyph.advance);
                continue;
            };
            paths.push(&g.path);
            advances.push(grid::to_u16(g.advance, || {
                format!(
                    "advance of '{}' in master '{}'",
                    glyph.model_name, master.name
                )
            })?);
        }
        let (tt, deltas) = glyph_variations(model, &paths, &advances, font.tolerance, glyph, kind)
            .map_err(|e| match e {
                Incompatible::Master(m) => OtfError::Table(format!(
                    "variable font: glyph '{}' has other path elements in master '{}' than in \
                     the default master",
                    glyph.model_name,
                    family.masters[drawing[m - 1]].name
                )),
                Incompatible::Otf(e) => e,
            })?;
        tt_glyphs.push(tt);
        point_deltas.push((&model.regions[..], deltas));
        advance_deltas.push((&model.regions[..], advance_deltas_of(model, &advances)));
    }

    let mut kerning = vec![kern_pairs(&font.kerning, &set)?];
    for master in &family.masters {
        kerning.push(kern_pairs(&master.kerning, &set)?);
    }
    let default_anchors: Vec<&[Anchor]> = set.glyphs.iter().map(|g| g.anchors.as_slice()).collect();
    let mut anchors = vec![default_anchors.clone()];
    for m in 0..family.masters.len() {
        anchors.push(match master_anchors.get(m) {
            Some(glyphs) if glyphs.len() == font.glyphs.len() => (0..set.glyphs.len())
                .map(|gid| {
                    gid.checked_sub(synthesised)
                        .map_or(&[][..], |i| glyphs[i].as_slice())
                })
                .collect(),
            _ => default_anchors.clone(),
        });
    }
    let rules = rule_regions(designspace, &set)?;
    let layout = layout_tables(&LayoutSource {
        names: set.glyphs.iter().map(|g| g.model_name.as_str()).collect(),
        unicodes: set.glyphs.iter().map(|g| g.unicodes.as_slice()).collect(),
        outline_marks: set.glyphs.iter().map(|g| g.outline_mark).collect(),
        anchors,
        kerning,
        model: Some(LayoutModels {
            glyphs: (0..set.glyphs.len())
                .map(|gid| match gid.checked_sub(synthesised) {
                    Some(i) => family.glyph_model(i),
                    None => (&family.models.sets[0].0[..], model),
                })
                .collect(),
            kerning: family.kerning_model(),
        }),
        rules: &rules,
        rules_feature: if designspace.rules_last {
            *b"rclt"
        } else {
            *b"rvrn"
        },
        axis_count,
        features: font.features.as_ref(),
    })?;
    // The axis and instance names take the IDs after the layout's (stylistic set names).
    let names = VariableNames::new(designspace, &font.info.family, layout.next_name_id());
    let weight_class = designspace
        .axes
        .iter()
        .find(|a| a.tag == "wght")
        .map(|a| a.default.round().clamp(1.0, 1000.0) as u16);
    let shared = VariableShared {
        weight_class,
        names: names.records.clone(),
    };
    let mut builder = font_builder(
        font,
        &set,
        Outlines::TrueType(tt_glyphs),
        &layout,
        Some(&shared),
    )?;
    let table_err = |e: BuilderError| OtfError::Table(e.to_string());
    builder
        .add_table(&fvar::fvar(designspace, &names)?)
        .map_err(table_err)?;
    builder
        .add_table(&stat::stat(designspace, &names)?)
        .map_err(table_err)?;
    builder
        .add_table(&avar::avar(&designspace.axes))
        .map_err(table_err)?;
    builder
        .add_table(&gvar::gvar(axis_count, &point_deltas)?)
        .map_err(table_err)?;
    builder
        .add_table(&hvar::hvar(axis_count, &advance_deltas)?)
        .map_err(table_err)?;
    Ok(builder.build())
}

/// The rules' boxes with glyph ids ([`Designspace::rule_regions`]).
fn rule_regions(designspace: &Designspace, set: &GlyphSet) -> Result<Vec<RuleRegion>, OtfError> {
    let regions = designspace.rule_regions().map_err(|count| {
        OtfError::Table(format!(
            "variable font: the rules have {count} condition boxes, more than the {} that can \
             be overlaid",
            crate::designspace::MAX_RULE_BOXES
        ))
    })?;
    let gid = |name: &str| -> Result<u16, OtfError> {
        set.glyphs
            .iter()
            .position(|g| g.model_name == name)
            .and_then(|i| u16::try_from(i).ok())
            .ok_or_else(|| {
                OtfError::Table(format!(
                    "variable font: a rule names glyph '{name}', which is not in the font"
                ))
            })
    };
    regions
        .into_iter()
        .map(|(ranges, subs)| {
            let subs = subs
                .iter()
                .map(|(from, to)| Ok((gid(from)?, gid(to)?)))
                .collect::<Result<Vec<_>, OtfError>>()?;
            Ok((ranges, subs))
        })
        .collect()
}

/// Why one glyph has no variations.
enum Incompatible {
    /// The path of this master (1 = the first non-default one) has other elements.
    Master(usize),
    /// A value out of the OpenType range.
    Otf(OtfError),
}

impl From<OtfError> for Incompatible {
    fn from(e: OtfError) -> Self {
        Incompatible::Otf(e)
    }
}

/// Per non-default master, the advance's delta ([`VariationModel::int_deltas`] of the
/// rounded advances; out-of-range deltas wrap as i16 arithmetic does).
fn advance_deltas_of(model: &VariationModel, advances: &[u16]) -> Vec<i16> {
    let values: Vec<i32> = advances.iter().map(|&a| i32::from(a)).collect();
    model
        .int_deltas(&values)
        .into_iter()
        .map(|d| d as i16)
        .collect()
}

/// One glyph's default outline for `glyf` and, per other master, its deltas: the model's
/// deltas of the rounded points (for masters on the axes, rounded master points minus
/// rounded default points), then the phantom points (only the advance point moves).
fn glyph_variations(
    model: &VariationModel,
    paths: &[&BezPath],
    advances: &[u16],
    accuracy: f64,
    glyph: &super::OtGlyph,
    kind: Deltas,
) -> Result<(TtGlyph, MasterDeltas), Incompatible> {
    let name = &glyph.model_name;
    let masters = quadratic::compatible_contours(paths, accuracy).map_err(Incompatible::Master)?;
    let mut rounded: Vec<Vec<Vec<CurvePoint>>> = Vec::with_capacity(masters.len());
    for contours in &masters {
        let mut out = Vec::with_capacity(contours.len());
        for contour in contours {
            out.push(truetype::round_contour(contour, name)?);
        }
        rounded.push(out);
    }
    let default = &rounded[0];
    let points: usize = default.iter().map(Vec::len).sum();
    if points > usize::from(u16::MAX) || default.len() >= i16::MAX as usize {
        return Err(Incompatible::Otf(OtfError::OutOfRange {
            what: format!(
                "glyph '{name}' as TrueType ({} contours): its point count",
                default.len()
            ),
            value: points as f64,
            range: "0..=65535 points, at most 32766 contours",
        }));
    }
    let coords: Vec<(i16, i16)> = default.iter().flatten().map(|p| (p.x, p.y)).collect();
    let contour_ends: Vec<usize> = default
        .iter()
        .scan(0, |end, c| {
            *end += c.len();
            Some(*end - 1)
        })
        .collect();
    // Per non-default master, its point deltas, point by point across the masters.
    let flat: Vec<Vec<&CurvePoint>> = rounded
        .iter()
        .map(|m| m.iter().flatten().collect())
        .collect();
    let mut per_master: Vec<Vec<(i16, i16)>> =
        vec![Vec::with_capacity(points + 4); rounded.len() - 1];
    let mut xs = vec![0i32; rounded.len()];
    let mut ys = vec![0i32; rounded.len()];
    for p in 0..points {
        for (m, master) in flat.iter().enumerate() {
            xs[m] = i32::from(master[p].x);
            ys[m] = i32::from(master[p].y);
        }
        for ((d, dx), dy) in per_master
            .iter_mut()
            .zip(model.int_deltas(&xs))
            .zip(model.int_deltas(&ys))
        {
            d.push((dx as i16, dy as i16));
        }
    }
    let deltas = per_master
        .into_iter()
        .zip(advance_deltas_of(model, advances))
        .map(|(mut d, advance_delta)| {
            d.extend([(0, 0), (advance_delta, 0), (0, 0), (0, 0)]);
            match kind {
                Deltas::Optimized => iup::optimize(&d, &coords, &contour_ends),
                Deltas::Explicit => d.iter().map(|&(x, y)| GlyphDelta::required(x, y)).collect(),
            }
        })
        .collect();
    let tt = if points == 0 {
        TtGlyph::empty()
    } else {
        let contours: Vec<Contour> = default.iter().map(|c| c.clone().into()).collect();
        let mut simple = SimpleGlyph {
            contours,
            overlaps: glyph.from_components,
            ..Default::default()
        };
        simple.recompute_bounding_box();
        TtGlyph::new(&simple)?
    };
    Ok((tt, deltas))
}
