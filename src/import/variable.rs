//! Variable fonts (fvar with gvar, or CFF2) -> a font with X-spline masters.
//!
//! ```text
//! font.rs (ttf-parser): names, metrics, code points, glyph names at the default
//! skrifa: each glyph's outline and advance at every master location (gvar/CFF2, HVAR)
//!   -> masters.rs: one X-spline structure per glyph for all masters
//!   -> a model::Family (axes and named instances from fvar, one folder per master)
//! ```
//!
//! Masters: the default location, per axis each end that differs from the default
//! (`wght` 100..400..900 gives Thin, Regular and Black), each place inside an axis where a
//! `gvar` variation peaks (an intermediate master, as Noto Sans has at Bold), and each
//! peak of a variation on several axes at once (a corner master, as Inter's `opsz` ×
//! `wght` has). A master at a peak is sparse when only some glyphs vary there
//! (`drawn_per_glyph`); it keeps kerning of its own where that is not the full masters'
//! blend (`kerned_masters`). Each glyph is fitted in the masters it varies at. The masters' outlines are measured
//! against their originals, and the midpoint between the default and each other master
//! against the blend of their Bézier outlines.
//!
//! Axis maps: `avar` becomes each axis's `map`, in user units (`read_axis_maps`).
//!
//! Limits: an `avar` that does not increase is refused; the cross-axis mappings of `avar`
//! 2 are not read (a note says so); variation regions other than those the masters give
//! (fontTools' model, [`crate::designspace::VariationModel`]) are not reproduced, and such a
//! font is reported with a note; CFF2 fonts get masters at the axis ends only. Kerning comes from GPOS at each master's location
//! ([`super::kerning`]).

use std::path::Path;

use kurbo::BezPath;
use rayon::prelude::*;
use skrifa::instance::{LocationRef, Size};
use skrifa::outline::{DrawSettings, OutlinePen};
use skrifa::raw::types::F2Dot14;
use skrifa::raw::TableProvider;
use skrifa::{FontRef, MetadataProvider};

use super::designspace::{folder_name, ImportedFamily};
use super::masters::{import_compatible_glyph, Checkpoint};
use super::report::{GlyphReport, Report};
use super::{font, grid_for, ImportError, ImportOptions, SourceGlyph, BUILD_SHARE};
use crate::designspace::{Axis, Designspace, Location, NamedInstance};
use crate::model::{Family, Font, FontInfo, Glyph, Master};

/// Whether the font bytes (font `index` of a collection) have variation axes (`fvar`).
pub fn is_variable(data: &[u8], index: u32) -> bool {
    FontRef::from_index(data, index).is_ok_and(|f| !f.axes().is_empty())
}

/// One master to read: its name and location (user and skrifa's normalised).
struct MasterAt {
    name: String,
    location: Location,
    coords: skrifa::instance::Location,
    /// For a master at a `gvar` peak (inside an axis, or a corner): that peak, per axis in
    /// F2Dot14 units (0 where unused). `None` for the default and the axis ends.
    peak: Option<Vec<i16>>,
}

/// Imports a variable font: axes, named instances and one master per axis end.
pub fn import_variable_font(
    path: &Path,
    data: &[u8],
    opts: &ImportOptions,
) -> Result<ImportedFamily, ImportError> {
    let fail = |m: String| ImportError::at(path, m);
    let font = FontRef::from_index(data, opts.face)
        .map_err(|e| fail(format!("not a readable TrueType/OpenType font ({e})")))?;
    let name = |id| {
        font.localized_strings(id)
            .english_or_first()
            .map(|s| s.chars().collect::<String>())
    };
    let mut axes: Vec<Axis> = font
        .axes()
        .iter()
        .map(|a| {
            Axis::linear(
                a.tag().to_string(),
                name(a.name_id()).unwrap_or_else(|| a.tag().to_string()),
                f64::from(a.min_value()),
                f64::from(a.default_value()),
                f64::from(a.max_value()),
            )
        })
        .collect();
    read_axis_maps(&font, &mut axes).map_err(fail)?;
    let instances: Vec<NamedInstance> = font
        .named_instances()
        .iter()
        .map(|i| NamedInstance {
            name: name(i.subfamily_name_id()).unwrap_or_else(|| "Instance".into()),
            location: Location(
                axes.iter()
                    .zip(i.user_coords())
                    .map(|(a, v)| (a.tag.clone(), f64::from(v)))
                    .collect(),
            ),
        })
        .collect();
    let mut designspace = Designspace {
        axes,
        instances,
        rules: Vec::new(),
        rules_last: false,
    };
    // The rules' alternates and the glyphs the substitutions reach come in with the glyphs
    // that reach them (see `import_font`).
    let rules = super::rules::read_rules(&font);
    let shaping = opts.glyphs.as_ref().map(|_| super::gsub::SHAPING_FEATURES);
    let source = font::read_font(path, data, opts.face, opts.glyphs.as_deref(), |mapped| {
        let mut extra = rules.alternates(mapped);
        extra.extend(super::gsub::reachable(&font, mapped, shaping));
        extra.sort_unstable();
        extra.dedup();
        extra
    })?;
    if source.glyphs.is_empty() {
        return Err(fail(
            "none of the requested characters has a glyph in this font".into(),
        ));
    }
    let tolerance = super::check_tolerance(opts.tolerance, source.info.units_per_em)?;
    check_gvar(&font, &source).map_err(fail)?;
    let names: std::collections::HashMap<skrifa::GlyphId, String> = source
        .ids
        .iter()
        .zip(&source.glyphs)
        .map(|(&id, g)| (skrifa::GlyphId::new(u32::from(id)), g.name.clone()))
        .collect();
    designspace.rules_last = rules.last;
    let rules_note = rules.note.clone();
    designspace.rules = rules.into_rules(&designspace.axes, &names, user_at_peak);
    let peaks = gvar_peaks(&font, designspace.axes.len());
    let masters = master_locations(&font, &designspace, &peaks);
    let corners_reproduced = corners_reproduced(&designspace, &masters, &peaks.corner_regions);
    // Read before the glyphs are fitted: a damaged GPOS fails at once.
    let locations: Vec<&[skrifa::raw::types::F2Dot14]> =
        masters.iter().map(|m| m.coords.coords()).collect();
    let kerning = super::read_font_kerning(path, data, opts.face, &source, &locations)?;
    let anchors = super::read_font_anchors(path, data, opts.face, &source)?;
    // The feature the rules vary is generated from them, not read again.
    let varied: &[&str] = match (designspace.rules.is_empty(), designspace.rules_last) {
        (true, _) => &[],
        (false, false) => &["rvrn"],
        (false, true) => &["rclt"],
    };
    let substitutions = super::read_font_gsub(path, data, opts.face, &source, varied)?;
    let style_of = |m: &MasterAt| m.name.clone();
    // Every glyph in every master, read first (a damaged gvar is an error naming the file).
    let mut per_glyph: Vec<Vec<SourceGlyph>> = Vec::with_capacity(source.glyphs.len());
    for (g, &gid) in source.glyphs.iter().zip(&source.ids) {
        let mut versions = Vec::with_capacity(masters.len());
        for m in &masters {
            let (path_at, advance) = outline_at(&font, gid, &m.coords)
                .map_err(|e| fail(format!("glyph `{}` at {}: {e}", g.name, style_of(m))))?;
            versions.push(SourceGlyph {
                name: g.name.clone(),
                unicodes: g.unicodes.clone(),
                advance,
                path: path_at,
            });
        }
        per_glyph.push(versions);
    }
    // Per glyph, the masters it varies at (sparse masters where a glyph has no tuple of
    // its own); the masters whose kerning is their own.
    let drawn = drawn_per_glyph(&font, &source.ids, &masters);
    let kerned_peaks = kerned_masters(&designspace, &masters, &kerning.pairs);
    let grid = grid_for(tolerance);
    let done = std::sync::atomic::AtomicUsize::new(0);
    let mut fitted = per_glyph
        .par_iter()
        .zip(&drawn)
        .map(|(versions, drawn)| {
            let mine: Vec<SourceGlyph> = versions
                .iter()
                .zip(drawn)
                .filter(|(_, &d)| d)
                .map(|(v, _)| v.clone())
                .collect();
            let checkpoints = Checkpoint::halfways(mine.len());
            let one = import_compatible_glyph(&mine, &checkpoints, tolerance, grid);
            if let Some(tell) = &opts.progress.0 {
                let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                tell(n, per_glyph.len());
            }
            one.map(|fits| (fits, drawn.clone()))
        })
        .collect::<Result<Vec<_>, String>>()
        .map_err(fail)?;
    fitted.sort_by(|a, b| crate::model::glyph_order(&a.0[0].glyph.name, &b.0[0].glyph.name));
    let mut glyphs: Vec<Vec<Glyph>> = vec![Vec::new(); masters.len()];
    let mut rows: Vec<Vec<GlyphReport>> = vec![Vec::new(); masters.len()];
    let mut drawn: Vec<Vec<bool>> = vec![Vec::new(); masters.len()];
    for (versions, present) in fitted {
        let default = versions[0].clone();
        let mut versions = versions.into_iter();
        for (k, &here) in present.iter().enumerate() {
            drawn[k].push(here);
            // A master that does not draw the glyph holds the default's until
            // `fill_sparse` blends it.
            let f = match here {
                true => versions.next().unwrap_or_else(|| default.clone()),
                false => default.clone(),
            };
            super::check_fitted_limits(&f.glyph)?;
            glyphs[k].push(f.glyph);
            if here {
                rows[k].push(f.report);
            }
        }
    }
    let mut drawn = drawn.into_iter().skip(1);
    // Every master gets the default's anchors (anchor variations are not read), so the
    // masters keep the same anchor names in the same order.
    anchors.give(glyphs.iter_mut().flatten());
    let outline_marks = glyphs
        .first()
        .and_then(|g| super::anchors::outline_marks_note(g));
    let mut glyphs = glyphs.into_iter();
    let mut rows = rows.into_iter();
    let mut notes = source.notes();
    if !peaks.reproduced || !corners_reproduced {
        notes.push(
            "gvar has variation regions that the masters at their peaks do not give back \
             (regions spanning other positions than the masters', or corners cut otherwise \
             than fontTools cuts them); between the masters the blend differs from the font's"
                .to_string(),
        );
    }
    if font
        .avar()
        .is_ok_and(|a| a.version().major >= 2 && a.var_store().is_some())
    {
        notes.push(
            "avar 2 maps axes by other axes; only its per-axis maps are read, so positions \
             away from the axes differ from the font's"
                .to_string(),
        );
    }
    notes.extend(rules_note);
    notes.extend(substitutions.note);
    notes.extend(kerning.note);
    notes.extend(super::gpos_unread_note(data, opts.face));
    notes.extend(anchors.note);
    notes.extend(outline_marks);
    let mut kerning = kerning.pairs.into_iter();
    let default_name = masters[0].name.clone();
    let info = FontInfo {
        family: opts.family.clone().unwrap_or(source.info.family.clone()),
        style: default_name.clone(),
        tolerance: BUILD_SHARE * tolerance,
        ..source.info
    };
    let default = Font {
        info,
        glyphs: glyphs.next().unwrap_or_default(),
        kerning: kerning.next().unwrap_or_default(),
        features: substitutions.features,
    };
    let report = |rows: Vec<GlyphReport>, notes: Vec<String>| Report {
        rows,
        tolerance,
        notes,
    };
    let mut reports = vec![(default_name, report(rows.next().unwrap_or_default(), notes))];
    let mut others = Vec::new();
    for (k, m) in masters.into_iter().enumerate().skip(1) {
        reports.push((
            m.name.clone(),
            report(rows.next().unwrap_or_default(), Vec::new()),
        ));
        let glyphs: Vec<Glyph> = glyphs.next().unwrap_or_default();
        let drawn = drawn.next().unwrap_or_default();
        let sparse = drawn.iter().any(|&d| !d);
        let kerning = kerning.next().unwrap_or_default();
        let kerned = !sparse || kerned_peaks.contains(&k);
        others.push(Master {
            folder: folder_name(&m.name).into(),
            name: m.name,
            location: m.location,
            drawn,
            glyphs,
            kerning: if kerned { kerning } else { Vec::new() },
            sparse,
            kerned,
        });
    }
    let mut family = Family {
        default,
        designspace,
        masters: others,
    };
    family.fill_sparse().map_err(|e| {
        fail(format!(
            "a glyph without variations at a peak cannot be blended there: {e}"
        ))
    })?;
    let parted = super::masters::part_meeting_points(&mut family).map_err(fail)?;
    if let Some((_, report)) = reports.first_mut() {
        report.notes.extend(parted);
    }
    Ok(ImportedFamily {
        family,
        reports,
        discrete: None,
    })
}

/// Per glyph (in `ids` order), per master: whether the glyph varies there in its own
/// right. The default and the axis ends always count; a master at a `gvar` peak counts
/// for a glyph with a variation tuple peaking there, or with a region that starts or ends
/// there on one of its axes (a glyph whose regions are cut at it), and for a composite
/// when one of its components counts. A glyph that does not count at a peak blends there
/// from its other masters, as fontTools' sub-models do for a sparse master.
fn drawn_per_glyph(font: &FontRef, ids: &[u16], masters: &[MasterAt]) -> Vec<Vec<bool>> {
    let Ok(gvar) = font.gvar() else {
        return vec![vec![true; masters.len()]; ids.len()];
    };
    let axes = font.axes().len();
    // Per glyph id, each tuple's (start, peak, end) per axis, in F2Dot14 units.
    let tuples = |gid: u16| -> Vec<Vec<[i16; 3]>> {
        let Ok(Some(data)) = gvar.glyph_variation_data(skrifa::GlyphId::new(u32::from(gid))) else {
            return Vec::new();
        };
        data.tuples()
            .map(|t| {
                let peak = t.peak();
                (0..axes)
                    .map(|a| {
                        let p = peak.values.get(a).map_or(0, |v| v.get().to_bits());
                        let bound = |tuple: Option<skrifa::raw::tables::variations::Tuple>,
                                     implied: i16| {
                            tuple
                                .and_then(|t| t.values.get(a).map(|v| v.get().to_bits()))
                                .unwrap_or(implied)
                        };
                        [
                            bound(t.intermediate_start(), p.min(0)),
                            p,
                            bound(t.intermediate_end(), p.max(0)),
                        ]
                    })
                    .collect()
            })
            .collect()
    };
    let own = |gid: u16| -> Vec<bool> {
        let tuples = tuples(gid);
        masters
            .iter()
            .map(|m| match &m.peak {
                None => true,
                Some(peak) => tuples.iter().any(|t| {
                    t.iter().zip(peak).all(|(r, &p)| r[1] == p)
                        || t.iter()
                            .zip(peak)
                            .any(|(r, &p)| p != 0 && (r[0] == p || r[2] == p))
                }),
            })
            .collect()
    };
    // A composite varies wherever one of its components does (its outline is read whole).
    let components = |gid: u16| -> Vec<u16> {
        let (Ok(loca), Ok(glyf)) = (font.loca(None), font.glyf()) else {
            return Vec::new();
        };
        match loca.get_glyf(skrifa::GlyphId::new(u32::from(gid)), &glyf) {
            Ok(Some(skrifa::raw::tables::glyf::Glyph::Composite(c))) => c
                .components()
                .filter_map(|c| u16::try_from(c.glyph.to_u32()).ok())
                .collect(),
            _ => Vec::new(),
        }
    };
    fn with_components(
        gid: u16,
        own: &dyn Fn(u16) -> Vec<bool>,
        components: &dyn Fn(u16) -> Vec<u16>,
        depth: usize,
    ) -> Vec<bool> {
        let mut drawn = own(gid);
        if depth < 16 {
            for c in components(gid) {
                for (d, c) in drawn
                    .iter_mut()
                    .zip(with_components(c, own, components, depth + 1))
                {
                    *d |= c;
                }
            }
        }
        drawn
    }
    ids.iter()
        .map(|&gid| with_components(gid, &own, &components, 0))
        .collect()
}

/// The masters at `gvar` peaks whose kerning is not what the full masters (the default
/// and the axis ends) blend to there, within a unit: such a master keeps its kerning
/// ([`Master::kerned`]), sparse or not.
fn kerned_masters(
    designspace: &Designspace,
    masters: &[MasterAt],
    pairs: &[Vec<crate::model::KernPair>],
) -> Vec<usize> {
    let full: Vec<usize> = (1..masters.len())
        .filter(|&m| masters[m].peak.is_none())
        .collect();
    let locations: Vec<Location> = full.iter().map(|&m| masters[m].location.clone()).collect();
    let Ok(model) = designspace.model(&locations) else {
        return (1..masters.len()).collect();
    };
    let value = |m: usize, left: &str, right: &str| -> f64 {
        pairs
            .get(m)
            .and_then(|p| p.iter().find(|k| k.left == left && k.right == right))
            .map_or(0.0, |k| k.value)
    };
    (1..masters.len())
        .filter(|&m| masters[m].peak.is_some())
        .filter(|&m| {
            let w = designspace.weights(&model, &masters[m].location);
            let sources = std::iter::once(0).chain(full.iter().copied());
            let keys: std::collections::BTreeSet<(&str, &str)> = std::iter::once(m)
                .chain(sources.clone())
                .filter_map(|k| pairs.get(k))
                .flatten()
                .map(|k| (k.left.as_str(), k.right.as_str()))
                .collect();
            keys.into_iter().any(|(l, r)| {
                let blend: f64 = w
                    .iter()
                    .zip(sources.clone())
                    .map(|(w, k)| w * value(k, l, r))
                    .sum();
                (blend - value(m, l, r)).abs() > 1.0
            })
        })
        .collect()
}

/// The default location, then each axis end other than the default, then each peak
/// inside an axis (`peaks.inner`, per axis), then each corner peak (`peaks.corners`), named
/// after the named instance there when there is one (else `Weight 900` or
/// `Weight 900 Width 75`).
fn master_locations(font: &FontRef, ds: &Designspace, peaks: &Peaks) -> Vec<MasterAt> {
    let at = |location: Location| {
        let settings: Vec<(skrifa::Tag, f32)> = ds
            .axes
            .iter()
            .filter_map(|a| {
                let tag = skrifa::Tag::new_checked(a.tag.as_bytes()).ok()?;
                Some((tag, location.get(a) as f32))
            })
            .collect();
        font.axes().location(settings)
    };
    let named = |location: &Location| {
        ds.instances
            .iter()
            .find(|i| ds.axes.iter().all(|a| i.location.get(a) == location.get(a)))
            .map(|i| i.name.clone())
    };
    let default = Location::default();
    let mut out = vec![MasterAt {
        name: named(&default).unwrap_or_else(|| "Regular".into()),
        coords: at(default.clone()),
        location: default,
        peak: None,
    }];
    let axes = ds.axes.len();
    // Each place (axis and user value per axis it is on) and its peak.
    type Place<'a> = (Vec<(&'a Axis, f64)>, Option<Vec<i16>>);
    let mut places: Vec<Place> = Vec::new();
    for (k, (a, inner)) in ds.axes.iter().zip(&peaks.inner).enumerate() {
        let mut users: Vec<(f64, Option<Vec<i16>>)> = [a.min, a.max]
            .into_iter()
            .filter(|&end| end != a.default)
            .map(|end| (end, None))
            .chain(inner.iter().map(|&p| {
                let mut peak = vec![0; axes];
                peak[k] = p.to_bits();
                (user_at_peak(a, p), Some(peak))
            }))
            .collect();
        users.sort_by(|x, y| x.0.total_cmp(&y.0));
        places.extend(users.into_iter().map(|(u, peak)| (vec![(a, u)], peak)));
    }
    for corner in &peaks.corners {
        places.push((
            ds.axes
                .iter()
                .zip(corner)
                .filter(|(_, p)| p.to_bits() != 0)
                .map(|(a, &p)| (a, user_at_peak(a, p)))
                .collect(),
            Some(corner.iter().map(|p| p.to_bits()).collect()),
        ));
    }
    for (place, peak) in places {
        let location = Location(place.iter().map(|(a, u)| (a.tag.clone(), *u)).collect());
        let name = named(&location).unwrap_or_else(|| {
            place
                .iter()
                .map(|(a, u)| format!("{} {}", a.name, crate::source::emit::number(*u)))
                .collect::<Vec<_>>()
                .join(" ")
        });
        out.push(MasterAt {
            name,
            coords: at(location.clone()),
            location,
            peak,
        });
    }
    out
}

/// Whether the masters' model cuts every corner region of the font as the font does (in
/// F2Dot14 units): then the blend between the masters is the font's.
fn corners_reproduced(
    ds: &Designspace,
    masters: &[MasterAt],
    font_regions: &[Vec<[i16; 3]>],
) -> bool {
    if font_regions.is_empty() {
        return true;
    }
    let locations: Vec<Location> = masters.iter().skip(1).map(|m| m.location.clone()).collect();
    let Ok(model) = ds.model(&locations) else {
        return false;
    };
    let f = |v: f64| F2Dot14::from_f32(v as f32).to_bits();
    let ours: Vec<Vec<[i16; 3]>> = model
        .regions
        .iter()
        .filter(|r| r.tents.len() > 1)
        .map(|r| {
            r.per_axis(ds.axes.len())
                .into_iter()
                .map(|t| t.map(f))
                .collect()
        })
        .collect();
    font_regions.iter().all(|r| ours.contains(r))
}

/// The user value on `axis` whose normalised design coordinate is `peak` (after the axis
/// map), with the fewest decimals that give back the same F2Dot14 coordinate.
fn user_at_peak(axis: &Axis, peak: F2Dot14) -> f64 {
    let p = f64::from(peak.to_f32());
    let (lo, default, hi) = (
        axis.design(axis.min),
        axis.design(axis.default),
        axis.design(axis.max),
    );
    let design = if p < 0.0 {
        default + p * (default - lo)
    } else {
        default + p * (hi - default)
    };
    fewest_decimals(axis.user(design), |u| {
        F2Dot14::from_f32(axis.normalize(u) as f32) == peak
    })
}

/// A glyph's outline (font units, y up) and advance at `coords`.
pub(super) fn outline_at(
    font: &FontRef,
    gid: u16,
    coords: &skrifa::instance::Location,
) -> Result<(BezPath, f64), String> {
    let id = skrifa::GlyphId::new(u32::from(gid));
    let location = LocationRef::from(coords);
    let mut advance = font
        .glyph_metrics(Size::unscaled(), location)
        .advance_width(id)
        .ok_or("no horizontal advance (damaged hmtx or HVAR table)")?;
    let mut pen = Pen(BezPath::new());
    // skrifa gives no glyph (rather than an error) for glyf data it cannot read; an empty
    // glyph is a glyph that draws nothing.
    let glyph = font
        .outline_glyphs()
        .get(id)
        .ok_or("cannot read the outline; the font may be damaged")?;
    let adjusted = glyph
        .draw(DrawSettings::unhinted(Size::unscaled(), location), &mut pen)
        .map_err(|e| format!("cannot read the outline ({e}); the font may be damaged"))?;
    // Without HVAR, the advance varies by gvar's phantom points, which drawing applies.
    if font.hvar().is_err() {
        advance = adjusted.advance_width.unwrap_or(advance);
    }
    if !pen.0.is_finite() {
        return Err("non-finite coordinates".into());
    }
    if pen.0.elements().is_empty() && font.glyf().is_ok() && !font::stores_no_outline(font, gid) {
        return Err("cannot read the outline; the font may be damaged".into());
    }
    Ok((pen.0, f64::from(advance)))
}

/// Refuses a `gvar` table that does not parse, or whose data for a glyph of `source` does not:
/// skrifa draws the default outline when it cannot read gvar, which would import every
/// master as the default.
fn check_gvar(font: &FontRef, source: &font::SourceFont) -> Result<(), String> {
    if font.table_data(skrifa::Tag::new(b"gvar")).is_none() {
        return Ok(());
    }
    let gvar = font
        .gvar()
        .map_err(|e| format!("cannot read the gvar table ({e}); the font may be damaged"))?;
    for (g, &gid) in source.glyphs.iter().zip(&source.ids) {
        gvar.glyph_variation_data(skrifa::GlyphId::new(u32::from(gid)))
            .map_err(|e| {
                format!(
                    "cannot read the gvar data of glyph `{}` ({e}); the font may be damaged",
                    g.name
                )
            })?;
    }
    Ok(())
}

/// The axis maps of `avar`, in the axes' user units: each segment map's pairs become
/// `(user, design)` pairs whose design values use the user scale (an axis end maps to
/// itself), written with the fewest decimals that give back the same F2Dot14 coordinates,
/// so that a rebuild writes the same `avar`. An axis whose map is the identity gets none;
/// a map that is not strictly increasing is refused (xglyph's maps must invert).
fn read_axis_maps(font: &FontRef, axes: &mut [Axis]) -> Result<(), String> {
    let Ok(avar) = font.avar() else {
        return Ok(());
    };
    for (i, maps) in avar.axis_segment_maps().iter().enumerate() {
        let maps = maps.map_err(|e| format!("cannot read the avar table ({e})"))?;
        let Some(axis) = axes.get_mut(i) else {
            break;
        };
        let pairs: Vec<(F2Dot14, F2Dot14)> = maps
            .axis_value_maps()
            .iter()
            .map(|m| (m.from_coordinate(), m.to_coordinate()))
            .collect();
        if pairs.iter().all(|(from, to)| from == to) {
            continue;
        }
        let mut map: Vec<(f64, f64)> = Vec::with_capacity(pairs.len() + 2);
        let mut previous: Option<(F2Dot14, F2Dot14)> = None;
        for (from, to) in pairs {
            let (user, design) = (nicest(axis, from), nicest(axis, to));
            match map.last() {
                // -1 -> -1 on an axis whose min is its default lands on 0 -> 0.
                Some(&last) if last == (user, design) => {
                    previous = Some((from, to));
                    continue;
                }
                Some(&(u, d)) if user <= u || design <= d => {
                    let (f0, t0) = previous.unwrap_or((from, to));
                    return Err(format!(
                        "avar maps axis `{}` flat or backwards ({} -> {}, then {} -> {}); \
                         xglyph's axis maps must increase, so this font cannot be imported \
                         with its masters",
                        axis.tag,
                        f0.to_f32(),
                        t0.to_f32(),
                        from.to_f32(),
                        to.to_f32()
                    ));
                }
                _ => {}
            }
            map.push((user, design));
            previous = Some((from, to));
        }
        let ends = [(axis.min, axis.min), (axis.max, axis.max)];
        if map.first().is_some_and(|&(u, _)| u > axis.min) {
            map.insert(0, ends[0]);
        }
        if map.last().is_some_and(|&(u, _)| u < axis.max) {
            map.push(ends[1]);
        }
        axis.map = map;
    }
    Ok(())
}

/// The user value of the normalised coordinate `v` on `axis` (before any map) with the
/// fewest decimals that normalises back to `v`.
fn nicest(axis: &Axis, v: F2Dot14) -> f64 {
    let x = f64::from(v.to_f32());
    let exact = if x < 0.0 {
        axis.default + x * (axis.default - axis.min)
    } else {
        axis.default + x * (axis.max - axis.default)
    };
    fewest_decimals(exact, |u| {
        F2Dot14::from_f32(axis.normalize_user(u) as f32) == v
    })
}

/// `exact` rounded to the fewest decimals (up to 6) for which `same` holds; `exact` when
/// none does. Font tables store F2Dot14 coordinates, so the values a designer wrote come
/// back from them only this way.
fn fewest_decimals(exact: f64, same: impl Fn(f64) -> bool) -> f64 {
    (0..=6)
        .map(|digits| {
            let scale = 10f64.powi(digits);
            (exact * scale).round() / scale
        })
        .find(|&u| same(u))
        .unwrap_or(exact)
}

/// What `gvar`'s variation regions need as masters.
struct Peaks {
    /// Per axis, the peaks strictly inside it (normalised, sorted): intermediate masters.
    inner: Vec<Vec<F2Dot14>>,
    /// Whether masters at the axis ends and at `inner` reproduce every single-axis region:
    /// its start, peak and end are all master positions (or 0), so that it is linear
    /// between neighbouring masters.
    reproduced: bool,
    /// The peaks of the regions on several axes (one value per axis, 0 where unused,
    /// sorted): corner masters.
    corners: Vec<Vec<F2Dot14>>,
    /// Those regions as (lower, peak, upper) per axis, in F2Dot14 units (zeros where
    /// unused), to compare with the masters' model.
    corner_regions: Vec<Vec<[i16; 3]>>,
}

/// The single-axis peaks of every glyph's `gvar` tuples and whether masters there
/// reproduce the font ([`Peaks`]). Without `gvar` (CFF2): no inner peaks.
fn gvar_peaks(font: &FontRef, axis_count: usize) -> Peaks {
    let mut peaks = Peaks {
        inner: vec![Vec::new(); axis_count],
        reproduced: true,
        corners: Vec::new(),
        corner_regions: Vec::new(),
    };
    let mut corner_regions: std::collections::BTreeSet<Vec<[i16; 3]>> = Default::default();
    let (Ok(gvar), Ok(maxp)) = (font.gvar(), font.maxp()) else {
        return peaks;
    };
    // (axis, start, peak, end) of every single-axis region, in F2Dot14 units.
    let mut regions: std::collections::BTreeSet<(usize, i16, i16, i16)> = Default::default();
    for g in 0..maxp.num_glyphs() {
        let Ok(Some(data)) = gvar.glyph_variation_data(skrifa::GlyphId::new(u32::from(g))) else {
            continue;
        };
        for t in data.tuples() {
            let peak = t.peak();
            let on: Vec<(usize, F2Dot14)> = peak
                .values
                .iter()
                .map(|v| v.get())
                .enumerate()
                .filter(|(_, v)| v.to_bits() != 0)
                .collect();
            let zero = F2Dot14::from_bits(0);
            let tent = |axis: usize, p: F2Dot14| {
                let bound = |tuple: Option<skrifa::raw::tables::variations::Tuple>,
                             implied: F2Dot14| {
                    tuple
                        .and_then(|t| t.values.get(axis).map(|v| v.get()))
                        .unwrap_or(implied)
                };
                let start = bound(t.intermediate_start(), p.min(zero));
                let end = bound(t.intermediate_end(), p.max(zero));
                [start.to_bits(), p.to_bits(), end.to_bits()]
            };
            match on[..] {
                [] => {}
                [(axis, p)] => {
                    let [start, p, end] = tent(axis, p);
                    regions.insert((axis, start, p, end));
                }
                _ => {
                    let mut region = vec![[0i16; 3]; axis_count];
                    for &(axis, p) in &on {
                        if let Some(r) = region.get_mut(axis) {
                            *r = tent(axis, p);
                        }
                    }
                    corner_regions.insert(region);
                }
            }
        }
    }
    let one = F2Dot14::from_f32(1.0).to_bits();
    for &(axis, _, p, _) in &regions {
        if p.abs() != one
            && axis < axis_count
            && !peaks.inner[axis].iter().any(|q| q.to_bits() == p)
        {
            peaks.inner[axis].push(F2Dot14::from_bits(p));
        }
    }
    for inner in &mut peaks.inner {
        inner.sort_by_key(|p| p.to_bits());
    }
    let corners: std::collections::BTreeSet<Vec<i16>> = corner_regions
        .iter()
        .map(|r| r.iter().map(|t| t[1]).collect())
        .collect();
    peaks.corners = corners
        .into_iter()
        .map(|c| c.into_iter().map(F2Dot14::from_bits).collect())
        .collect();
    peaks.corner_regions = corner_regions.into_iter().collect();
    peaks.reproduced &= regions.iter().all(|&(axis, start, _, end)| {
        let at_master = |v: i16| {
            v == 0
                || v.abs() == one
                || peaks
                    .inner
                    .get(axis)
                    .is_some_and(|i| i.iter().any(|q| q.to_bits() == v))
        };
        at_master(start) && at_master(end)
    });
    peaks
}

/// A skrifa pen into a kurbo path.
struct Pen(BezPath);

impl OutlinePen for Pen {
    fn move_to(&mut self, x: f32, y: f32) {
        self.0.move_to(point(x, y));
    }
    fn line_to(&mut self, x: f32, y: f32) {
        self.0.line_to(point(x, y));
    }
    fn quad_to(&mut self, cx0: f32, cy0: f32, x: f32, y: f32) {
        self.0.quad_to(point(cx0, cy0), point(x, y));
    }
    fn curve_to(&mut self, cx0: f32, cy0: f32, cx1: f32, cy1: f32, x: f32, y: f32) {
        self.0
            .curve_to(point(cx0, cy0), point(cx1, cy1), point(x, y));
    }
    fn close(&mut self) {
        self.0.close_path();
    }
}

fn point(x: f32, y: f32) -> kurbo::Point {
    kurbo::Point::new(f64::from(x), f64::from(y))
}
