//! The IR of a font with masters: one compatible Bézier structure per glyph for every
//! master, what the variable-font backend reads.
//!
//! [`OutlinedFamily::default`] is an ordinary [`OutlinedFont`] (the default master), so
//! every static backend can read it unchanged. Each other master holds, per glyph in the
//! same order, a path with **the same elements** (same number of subpaths, and the same
//! kind of segment at each place: `LineTo` where the default has a `LineTo`, `CurveTo` where
//! it has a `CurveTo`), so that the masters differ only in coordinates. Components are
//! resolved into the paths, as in [`OutlinedFont`].
//!
//! The blend of the masters at a position ([`Designspace::weights`]) is the outline of the
//! variable font there; the compatible fitter guarantees that it lies within the tolerance
//! of the X-spline interpolated at the same position, at every position it checked.

use std::fmt;

use kurbo::{Affine, BezPath, PathEl, Shape, Vec2};
use rayon::prelude::*;

use crate::cache::FitCache;
use crate::compatible::{blend, fit_compatible, CompatibleError, CompatibleFit};
use crate::designspace::{Designspace, Location, RegionError, VariationModel};
use crate::extrema::{apply_plan, split_plan_for};
use crate::fit::fit_contour;
use crate::model::{Contour, Family, Font, GlyphIndex, GlyphModels, KernPair};
use crate::orient::nesting_depths;
use crate::outline::{min_piece, OutlinedFont, OutlinedGlyph, PlacedContour};
use crate::xspline::{XSpline, XSplineError};

/// A font with masters, every glyph fitted compatibly.
#[derive(Clone, Debug)]
pub struct OutlinedFamily {
    /// Axes and named instances.
    pub designspace: Designspace,
    /// The default master (at every axis default), with the compatible paths.
    pub default: OutlinedFont,
    /// The other masters, in `font.toml` order.
    pub masters: Vec<OutlinedMaster>,
    /// How they blend: [`Self::masters`]' regions and deltas.
    pub model: VariationModel,
    /// Which masters blend for each glyph (in [`Self::default`]'s glyph order): with
    /// sparse masters, each glyph's own model.
    pub models: GlyphModels,
}

/// One non-default master's outlines.
#[derive(Clone, Debug)]
pub struct OutlinedMaster {
    /// Master name, e.g. `"Bold"`.
    pub name: String,
    /// Where it sits (user coordinates).
    pub location: Location,
    /// One per glyph of [`OutlinedFamily::default`], in the same order.
    pub glyphs: Vec<MasterGlyph>,
    /// This master's kerning; a pair it lacks has value 0 here.
    pub kerning: Vec<KernPair>,
}

/// A glyph in one non-default master.
#[derive(Clone, Debug)]
pub struct MasterGlyph {
    /// Horizontal advance, font units.
    pub advance: f64,
    /// Same elements as the default master's path for this glyph, other coordinates.
    pub path: BezPath,
    /// Whether the glyph's outline blends with this master: it draws the glyph or one of
    /// the glyph's components. When a sparse master does neither, the advance and path are
    /// the blend of the masters that do, at this master's location.
    pub drawn: bool,
}

impl OutlinedFamily {
    /// The blend weights at `location`: the default master first, then [`Self::masters`].
    pub fn weights(&self, location: &Location) -> Vec<f64> {
        self.designspace.weights(&self.model, location)
    }

    /// The masters with kerning of their own (every one but the sparse ones) and their
    /// model: [`Self::model`] when there is no sparse master.
    pub fn kerning_model(&self) -> (&[usize], &VariationModel) {
        let (set, model) = (&self.models.kerning.0, &self.models.kerning.1);
        if set.len() == self.masters.len() {
            (set, &self.model)
        } else {
            (set, model)
        }
    }

    /// The masters (indices into [`Self::masters`]) that draw glyph `i` of
    /// [`Self::default`], and their model: [`Self::model`] when every master draws it.
    pub fn glyph_model(&self, i: usize) -> (&[usize], &VariationModel) {
        let (set, model) = self.models.of(i);
        if set.len() == self.masters.len() {
            (set, &self.model)
        } else {
            (set, model)
        }
    }
}

/// Why a family could not be outlined compatibly.
#[derive(Clone, Debug, PartialEq)]
pub enum FamilyError {
    /// The masters' locations do not form a valid set (the loader refuses these).
    Regions(RegionError),
    /// A contour's masters cannot share one structure (the loader refuses these).
    Contour {
        /// The glyph.
        glyph: String,
        /// Index of the contour among the glyph's placed contours.
        contour: usize,
        /// Why.
        error: CompatibleError,
        /// Where the blended contour failed, when it failed at one position: the axes
        /// away from their defaults with their user values, e.g. `wght 650`.
        at: Option<String>,
    },
}

impl fmt::Display for FamilyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FamilyError::Regions(e) => write!(f, "the masters cannot be blended: {e:?}"),
            FamilyError::Contour {
                glyph,
                contour,
                error: CompatibleError::Blend { source, .. },
                at: Some(at),
            } => {
                write!(f, "glyph `{glyph}`, contour {contour}, blended at {at}: ")?;
                match source {
                    XSplineError::CoincidentPoints { index, next } => write!(
                        f,
                        "points {index} and {next} meet there (they cross between the masters); \
                         move them in a master so that they stay apart"
                    ),
                    other => write!(f, "{other}"),
                }
            }
            FamilyError::Contour {
                glyph,
                contour,
                error,
                ..
            } => write!(f, "glyph `{glyph}`, contour {contour}: {error}"),
        }
    }
}

impl std::error::Error for FamilyError {}

/// Evenly spaced positions checked along each axis, ends included (the issue asks for 9
/// or more).
pub const AXIS_SAMPLES: usize = 11;

/// Evenly spaced values per axis, ends included, of the grids over corner masters' axes.
pub const CORNER_SAMPLES: usize = 5;

/// The positions every compatible fit is checked at: the default, each master, each named
/// instance, [`AXIS_SAMPLES`] evenly spaced user values along each axis (the others at
/// their defaults), and, for each set of axes a corner master moves on, a grid over those
/// axes: on each, [`CORNER_SAMPLES`] evenly spaced user values, its default, and the
/// corner masters' coordinates. Duplicates are left out; the order is stable.
pub fn check_locations(family: &Family) -> Vec<Location> {
    let ds = &family.designspace;
    let mut out: Vec<Location> = vec![Location::default()];
    out.extend(family.masters.iter().map(|m| m.location.clone()));
    out.extend(ds.instances.iter().map(|i| i.location.clone()));
    for axis in &ds.axes {
        for k in 0..AXIS_SAMPLES {
            let t = k as f64 / (AXIS_SAMPLES - 1) as f64;
            let user = axis.min + t * (axis.max - axis.min);
            out.push(Location([(axis.tag.clone(), user)].into_iter().collect()));
        }
    }
    out.extend(corner_grids(family));
    let mut unique: Vec<Location> = Vec::with_capacity(out.len());
    for loc in out {
        let norm = ds.normalize(&loc);
        if !unique.iter().any(|u| ds.normalize(u) == norm) {
            unique.push(loc);
        }
    }
    unique
}

/// The grids of [`check_locations`] over the axes of the corner masters.
fn corner_grids(family: &Family) -> Vec<Location> {
    let ds = &family.designspace;
    let off = |l: &Location| ds.axes_off_default(l);
    let mut sets: Vec<Vec<usize>> = Vec::new();
    for m in &family.masters {
        let axes = off(&m.location);
        if axes.len() > 1 && !sets.contains(&axes) {
            sets.push(axes);
        }
    }
    let mut out = Vec::new();
    for axes in sets {
        // Per axis of the set, the user values to combine.
        let values: Vec<Vec<f64>> = axes
            .iter()
            .map(|&a| {
                let axis = &ds.axes[a];
                let mut v: Vec<f64> = (0..CORNER_SAMPLES)
                    .map(|k| {
                        let t = k as f64 / (CORNER_SAMPLES - 1) as f64;
                        axis.min + t * (axis.max - axis.min)
                    })
                    .collect();
                v.push(axis.default);
                v.extend(
                    family
                        .masters
                        .iter()
                        .filter(|m| off(&m.location) == axes)
                        .map(|m| m.location.get(axis)),
                );
                v.sort_by(f64::total_cmp);
                v.dedup();
                v
            })
            .collect();
        let mut index = vec![0usize; axes.len()];
        'grid: loop {
            out.push(Location(
                axes.iter()
                    .zip(&index)
                    .enumerate()
                    .map(|(k, (&a, &i))| (ds.axes[a].tag.clone(), values[k][i]))
                    .collect(),
            ));
            // The next combination, the last axis fastest.
            for k in (0..axes.len()).rev() {
                index[k] += 1;
                if index[k] < values[k].len() {
                    continue 'grid;
                }
                index[k] = 0;
            }
            break;
        }
    }
    out
}

/// `e` with the place of a blend that failed at one of `locations` (user values of every
/// axis), so that the message says where rather than which check position.
fn at_location(e: FamilyError, ds: &Designspace, locations: &[Location]) -> FamilyError {
    match e {
        FamilyError::Contour {
            glyph,
            contour,
            error: error @ CompatibleError::Blend { position, .. },
            ..
        } => {
            let at = locations.get(position).map(|l| describe(ds, l));
            FamilyError::Contour {
                glyph,
                contour,
                error,
                at,
            }
        }
        other => other,
    }
}

/// `l` as its axes away from their defaults with their user values, e.g. `wght 650`.
pub fn describe(ds: &Designspace, l: &Location) -> String {
    let off: Vec<String> = ds
        .axes
        .iter()
        .filter(|a| l.get(a) != a.default)
        .map(|a| {
            format!(
                "{} {}",
                a.tag,
                crate::source::emit::computed_number(l.get(a))
            )
        })
        .collect();
    if off.is_empty() {
        "the default location".to_string()
    } else {
        off.join(", ")
    }
}

/// A point of a glyph's own contour that lands on the next one in a blend the build checks
/// ([`check_locations`]): the blended contour is no X-spline there, and
/// [`outline_family`] fails with [`FamilyError::Contour`].
#[derive(Clone, Debug, PartialEq)]
pub struct MeetingPoints {
    /// The glyph's index in the default master.
    pub glyph: usize,
    /// The contour's index among the glyph's own contours.
    pub contour: usize,
    /// The point that meets the next one.
    pub index: usize,
    /// The next point (cyclically).
    pub next: usize,
    /// The first checked position where they meet.
    pub at: Location,
}

/// Per set of masters of `models`, the weights of its own model at each of `locations`.
fn set_weights(
    ds: &Designspace,
    models: &GlyphModels,
    locations: &[Location],
) -> Vec<Vec<Vec<f64>>> {
    models
        .sets
        .iter()
        .map(|(_, model)| locations.iter().map(|l| ds.weights(model, l)).collect())
        .collect()
}

/// Every contour of `family` whose points meet in a blend at [`check_locations`], the
/// first such pair of each, in glyph order: the check [`outline_family`] makes before it
/// fits, without the fitting. Components are checked in their own glyphs.
pub fn meeting_points(family: &Family) -> Result<Vec<MeetingPoints>, RegionError> {
    let models = family.glyph_models()?;
    let ds = &family.designspace;
    let locations = check_locations(family);
    let positions = set_weights(ds, &models, &locations);
    Ok((0..family.default.glyphs.len())
        .into_par_iter()
        .flat_map_iter(|gi| {
            let k = models.of_glyph[gi];
            let drawing: Vec<&crate::model::Glyph> = std::iter::once(&family.default.glyphs[gi])
                .chain(
                    models.sets[k]
                        .0
                        .iter()
                        .map(|&m| &family.masters[m].glyphs[gi]),
                )
                .collect();
            let mut found = Vec::new();
            for c in 0..drawing[0].contours.len() {
                let Some(splines) = drawing
                    .iter()
                    .map(|g| g.contours.get(c).map(Contour::spline))
                    .collect::<Option<Vec<&XSpline>>>()
                else {
                    continue;
                };
                let n = splines[0].points().len();
                if splines.iter().any(|s| s.points().len() != n) {
                    continue;
                }
                let first = positions[k].iter().enumerate().find_map(|(p, weights)| {
                    match blend(&splines, weights) {
                        Err(XSplineError::CoincidentPoints { index, next }) => {
                            Some(MeetingPoints {
                                glyph: gi,
                                contour: c,
                                index,
                                next,
                                at: locations[p].clone(),
                            })
                        }
                        _ => None,
                    }
                });
                found.extend(first);
            }
            found
        })
        .collect())
}

/// How a family's compatible outlines compare with static fits, and how close they come
/// to the tolerance: what a build reports.
#[derive(Clone, Debug, PartialEq)]
pub struct FamilySummary {
    /// Segments of the compatible outlines (per master; the same in every master).
    pub compatible_segments: usize,
    /// Σ over glyphs of the static fitter's segment count for the glyph's most demanding
    /// master.
    pub static_segments: usize,
    /// Positions checked per contour.
    pub positions: usize,
    /// The worst glyph, its position and its error (font units), if any glyph has contours.
    pub worst: Option<(String, Location, f64)>,
    /// The glyphs over the tolerance at some checked position, with their worst error, in
    /// glyph order: where `s` differs between masters or a cusp forms between them, one
    /// structure may not follow the blended X-spline (see [`crate::compatible`]).
    pub over: Vec<(String, f64)>,
}

/// Fits every glyph of `family` with one segment structure for all masters
/// ([`fit_compatible`], contours in parallel), checked at [`check_locations`].
///
/// Each contour is fitted where it was drawn and moved by its component offset in each
/// master (the offsets blend like everything else, and the X-spline commutes with
/// translation). Contours are oriented by the default master's nesting, and every master
/// gets the same reversals, so the structures stay parallel.
pub fn outline_family(
    family: &Family,
    tolerance: f64,
) -> Result<(OutlinedFamily, FamilySummary), FamilyError> {
    outline_family_with(family, tolerance, None)
}

/// [`outline_family`] with fits from `cache`: the compatible fits with their checks at
/// every position, and the static fits of every master for the summary. The result is the
/// same with and without the cache, bit for bit.
pub fn outline_family_with(
    family: &Family,
    tolerance: f64,
    cache: Option<&FitCache>,
) -> Result<(OutlinedFamily, FamilySummary), FamilyError> {
    let mut models = family.glyph_models().map_err(FamilyError::Regions)?;
    // The first set is every master, with the family's model ([`GlyphModels::sets`]).
    let model = models.sets[0].1.clone();
    let ds = &family.designspace;
    let locations = check_locations(family);
    // Per set of masters, the weights of its own model at each position, and at each
    // master's location.
    let positions = set_weights(ds, &models, &locations);
    let master_locations: Vec<Location> =
        family.masters.iter().map(|m| m.location.clone()).collect();
    let at_masters = set_weights(ds, &models, &master_locations);
    // One `Font` per master (default first) so components resolve inside each master.
    let fonts: Vec<Font> = std::iter::once(family.default.clone())
        .chain(family.masters.iter().map(|m| Font {
            info: family.default.info.clone(),
            glyphs: m.glyphs.clone(),
            kerning: m.kerning.clone(),
            features: None,
        }))
        .collect();
    let indexes: Vec<_> = fonts.iter().map(Font::index).collect();
    // The outline order: `.notdef` first, then the model's (as `outline_font`).
    let order: Vec<usize> = (0..family.default.glyphs.len())
        .filter(|&i| family.default.glyphs[i].name == ".notdef")
        .chain(
            (0..family.default.glyphs.len())
                .filter(|&i| family.default.glyphs[i].name != ".notdef"),
        )
        .collect();
    let glyphs: Vec<FittedGlyph> = order
        .par_iter()
        .map(|&gi| {
            let k = models.of_glyph[gi];
            let set = Set {
                masters: &models.sets[k].0,
                positions: &positions[k],
                at_masters: &at_masters[k],
            };
            fit_glyph(&fonts, &indexes, gi, &set, tolerance, cache)
        })
        .collect::<Result<_, _>>()
        .map_err(|e| at_location(e, ds, &locations))?;
    models.of_glyph = order.iter().map(|&gi| models.of_glyph[gi]).collect();
    models.own_of_glyph = order.iter().map(|&gi| models.own_of_glyph[gi]).collect();

    let mut summary = FamilySummary {
        compatible_segments: 0,
        static_segments: 0,
        positions: locations.len(),
        worst: None,
        over: Vec::new(),
    };
    for g in &glyphs {
        summary.compatible_segments += g.fitted_segments;
        summary.static_segments += g.static_segments;
        if let Some((p, &e)) = g
            .errors
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(b.1))
        {
            if summary.worst.as_ref().is_none_or(|w| e > w.2) {
                summary.worst = Some((g.default.name.clone(), locations[p].clone(), e));
            }
            if e > tolerance {
                summary.over.push((g.default.name.clone(), e));
            }
        }
    }
    let default = OutlinedFont {
        info: family.default.info.clone(),
        kerning: family.default.kerning.clone(),
        features: family.default.features.clone(),
        tolerance,
        glyphs: glyphs.iter().map(|g| g.default.clone()).collect(),
    };
    let masters = family
        .masters
        .iter()
        .enumerate()
        .map(|(m, master)| OutlinedMaster {
            name: master.name.clone(),
            location: master.location.clone(),
            glyphs: glyphs.iter().map(|g| g.masters[m].clone()).collect(),
            kerning: master.kerning.clone(),
        })
        .collect();
    Ok((
        OutlinedFamily {
            designspace: ds.clone(),
            default,
            masters,
            model,
            models,
        },
        summary,
    ))
}

/// One glyph fitted in every master.
struct FittedGlyph {
    default: OutlinedGlyph,
    masters: Vec<MasterGlyph>,
    /// Largest error over the glyph's contours, per checked position.
    errors: Vec<f64>,
    /// The compatible fitter's segments (before the splits at extrema), for the summary.
    fitted_segments: usize,
    static_segments: usize,
}

/// The masters that draw one glyph, and how they blend.
struct Set<'a> {
    /// Non-default masters (indices into [`Family::masters`]), ascending.
    masters: &'a [usize],
    /// Per checked position, the weights of the default and [`Self::masters`].
    positions: &'a [Vec<f64>],
    /// Per master of the family, the same weights at its location: how a master that does
    /// not draw the glyph gets its path.
    at_masters: &'a [Vec<f64>],
}

fn fit_glyph(
    fonts: &[Font],
    indexes: &[GlyphIndex<'_>],
    gi: usize,
    set: &Set<'_>,
    tolerance: f64,
    cache: Option<&FitCache>,
) -> Result<FittedGlyph, FamilyError> {
    let positions = set.positions;
    let glyph = &fonts[0].glyphs[gi];
    // The fonts that draw the glyph: the default, then the set's masters.
    let drawing: Vec<usize> = std::iter::once(0)
        .chain(set.masters.iter().map(|&m| m + 1))
        .collect();
    let placed: Vec<Vec<(&Contour, (f64, f64))>> = drawing
        .iter()
        .map(|&f| fonts[f].placed_contours_in(&indexes[f], &fonts[f].glyphs[gi]))
        .collect();
    let contours = placed[0].len();
    let fits: Vec<CompatibleFit> = (0..contours)
        .into_par_iter()
        .map(|c| {
            let splines: Vec<&XSpline> = placed.iter().map(|p| p[c].0.spline()).collect();
            match cache {
                Some(cache) => cache.fit_compatible(&splines, positions, tolerance),
                None => fit_compatible(&splines, positions, tolerance),
            }
            .map_err(|error| FamilyError::Contour {
                glyph: glyph.name.clone(),
                contour: c,
                error,
                at: None,
            })
        })
        .collect::<Result<_, _>>()?;
    // Each master's paths, moved to where they are placed.
    let moved = |m: usize| -> Vec<BezPath> {
        fits.iter()
            .zip(&placed[m])
            .map(|(fit, (_, (dx, dy)))| Affine::translate((*dx, *dy)) * fit.paths[m].clone())
            .collect()
    };
    let default_paths = moved(0);
    let depths = nesting_depths(&default_paths);
    // kurbo's area is positive for counter-clockwise contours in y-up coordinates; outer
    // contours (even depth) run counter-clockwise.
    let reverse: Vec<bool> = default_paths
        .iter()
        .zip(&depths)
        .map(|(p, d)| (p.area() > 0.0) != (d % 2 == 0))
        .collect();
    let join = |paths: Vec<BezPath>| -> BezPath {
        let mut out = BezPath::new();
        for (p, &rev) in paths.iter().zip(&reverse) {
            if rev {
                out.extend(p.reverse_subpaths().iter());
            } else {
                out.extend(p.iter());
            }
        }
        out
    };
    let mut errors = vec![0.0f64; positions.len()];
    for fit in &fits {
        for (e, f) in errors.iter_mut().zip(&fit.max_error) {
            *e = e.max(*f);
        }
    }
    let static_segments = placed
        .iter()
        .map(|p| {
            p.iter()
                .map(|(c, _)| {
                    let fit = match cache {
                        Some(cache) => cache.fit(c.spline(), tolerance),
                        None => fit_contour(c.spline(), tolerance),
                    };
                    segment_count(&fit.path)
                })
                .sum::<usize>()
        })
        .max()
        .unwrap_or(0);
    let fitted_segments = fits.iter().map(|f| f.segments).sum();
    let drawn: Vec<BezPath> = (0..drawing.len()).map(|k| join(moved(k))).collect();
    // Points at the default's extrema, at the same place of each curve in every master:
    // the blend is unchanged ([`crate::extrema`]).
    let plan = split_plan_for(&drawn.iter().collect::<Vec<_>>(), min_piece(&fonts[0].info));
    let drawn: Vec<BezPath> = drawn
        .iter()
        .enumerate()
        .map(|(k, path)| apply_plan(path, &plan, k == 0))
        .collect();
    let masters = (0..fonts.len() - 1)
        .map(|m| match set.masters.iter().position(|&s| s == m) {
            Some(k) => MasterGlyph {
                advance: fonts[m + 1].glyphs[gi].advance,
                path: drawn[k + 1].clone(),
                drawn: true,
            },
            None => {
                let w = &set.at_masters[m];
                MasterGlyph {
                    advance: w
                        .iter()
                        .zip(&drawing)
                        .map(|(w, &f)| w * fonts[f].glyphs[gi].advance)
                        .sum(),
                    path: blend_paths(&drawn, w),
                    drawn: false,
                }
            }
        })
        .collect();
    let default = OutlinedGlyph {
        name: glyph.name.clone(),
        unicodes: glyph.unicodes.clone(),
        advance: glyph.advance,
        components: glyph.components.clone(),
        anchors: glyph.anchors.clone(),
        placed_anchors: fonts[0].anchors_in(&indexes[0], glyph),
        outline_mark: glyph.outline_mark,
        contours: placed[0]
            .iter()
            .map(|(c, (dx, dy))| PlacedContour {
                spline: c.spline().clone(),
                offset: Vec2::new(*dx, *dy),
            })
            .collect(),
        segments: segment_count(&drawn[0]),
        path: drawn[0].clone(),
        max_error: errors.iter().copied().fold(0.0, f64::max),
    };
    Ok(FittedGlyph {
        default,
        masters,
        errors,
        fitted_segments,
        static_segments,
    })
}

/// `Σ weights[k] × paths[k]`, point by point: paths with the same elements.
fn blend_paths(paths: &[BezPath], weights: &[f64]) -> BezPath {
    let zero = kurbo::Point::ZERO;
    let mut out: Vec<PathEl> = paths[0]
        .elements()
        .iter()
        .map(|el| match el {
            PathEl::MoveTo(_) => PathEl::MoveTo(zero),
            PathEl::LineTo(_) => PathEl::LineTo(zero),
            PathEl::QuadTo(..) => PathEl::QuadTo(zero, zero),
            PathEl::CurveTo(..) => PathEl::CurveTo(zero, zero, zero),
            PathEl::ClosePath => PathEl::ClosePath,
        })
        .collect();
    for (path, &w) in paths.iter().zip(weights) {
        for (o, el) in out.iter_mut().zip(path.elements()) {
            match (o, el) {
                (PathEl::MoveTo(a), PathEl::MoveTo(p)) | (PathEl::LineTo(a), PathEl::LineTo(p)) => {
                    *a += p.to_vec2() * w;
                }
                (PathEl::QuadTo(a, b), PathEl::QuadTo(p, q)) => {
                    *a += p.to_vec2() * w;
                    *b += q.to_vec2() * w;
                }
                (PathEl::CurveTo(a, b, c), PathEl::CurveTo(p, q, r)) => {
                    *a += p.to_vec2() * w;
                    *b += q.to_vec2() * w;
                    *c += r.to_vec2() * w;
                }
                _ => {}
            }
        }
    }
    BezPath::from_vec(out)
}

/// Lines and curves in `path`.
fn segment_count(path: &BezPath) -> usize {
    path.elements()
        .iter()
        .filter(|el| {
            matches!(
                el,
                PathEl::LineTo(_) | PathEl::QuadTo(..) | PathEl::CurveTo(..)
            )
        })
        .count()
}
