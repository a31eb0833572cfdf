//! UFO import: a `.ufo` folder (norad) -> the font model.
//!
//! Per glyph of the default layer:
//! - a glyph whose lib holds `org.xglyph.xspline` ([`crate::ufo::lib`]) with as many
//!   contours as its outline takes those X-splines as they are (an exported xglyph font
//!   comes back exactly), after measuring them against the outline: when another editor
//!   changed the outline and kept the lib, the distance exceeds the tolerance and the
//!   outline is fitted instead (the report says which glyphs);
//! - any other glyph's closed contours are fitted like a font's ([`super::import_glyph`]);
//!   open contours are left out (they fill nothing);
//! - components placed by a translation stay components; a scaled, rotated or skewed one
//!   cannot (the model's components only move), so its outline is drawn into the glyph and
//!   fitted with it.
//!
//! Font info: names, metrics and licence from `fontinfo.plist`, the tolerance and version
//! text from the font lib when an xglyph export wrote them. Kerning: glyph pairs as they are;
//! group pairs (`public.kern1.*`, `public.kern2.*`) are expanded to glyph pairs, a more
//! specific pair winning, as UFO kerning defines. Named anchors come in as they are (an
//! unnamed one is left out and counted in the report); a glyph `public.openTypeCategories`
//! calls "mark" that has no `_` anchor comes in with `mark = "outline"` (the other
//! categories are not read: xglyph classes glyphs itself); `features.fea` comes in (written
//! next to the glyph files; `check` compiles it) with its includes inlined and renamed
//! glyphs renamed ([`super::fea`]). Limits: guidelines, images and other layers are not
//! imported (the model has no place for them; a designspace source on a layer reads that
//! layer, [`import_ufo_layer`]); a glyph name outside the OpenType `post` rule is renamed
//! as SVG file names are (`names::glyph_name_from`), in components, kerning and features
//! too.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use kurbo::{Affine, BezPath};
use rayon::prelude::*;

use super::report::{GlyphReport, Report};
use super::{contour, grid_for, import_glyph, FittedGlyph, ImportError, ImportOptions, Imported};
use super::{SourceGlyph, BUILD_SHARE};
use crate::model::{
    Anchor, Component, FeatureFile, Font, FontInfo, Glyph, KernPair, DEFAULT_VENDOR,
};
use crate::ufo::lib::{
    number, read_kerning_order, read_xspline, KERNING_ORDER_KEY, TOLERANCE_KEY, VERSION_KEY,
    XSPLINE_KEY,
};

/// Component nesting deeper than this is refused (a cycle, or a hostile file).
const MAX_DEPTH: usize = 64;

/// Imports the UFO folder at `path`.
pub fn import_ufo(path: &Path, opts: &ImportOptions) -> Result<Imported, ImportError> {
    import_ufo_layer(path, None, opts)
}

/// Which glyphs of a UFO an import reads ([`import_ufo_layer`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UfoLayer<'a> {
    /// The named layer as a whole font: its glyphs, with the UFO's info, kerning and
    /// features (a designspace's default source on a layer).
    Full(&'a str),
    /// The named layer's glyphs only, as a sparse master draws them (a designspace
    /// source on a layer): no kerning, no features, and the layer may hold any number of
    /// glyphs. A component whose base the layer lacks is resolved in the default layer.
    Sparse(&'a str),
}

/// Imports the UFO folder at `path`, reading its default layer (`layer` `None`, as
/// [`import_ufo`]) or the named layer `layer`. The font info is the UFO's either way.
pub fn import_ufo_layer(
    path: &Path,
    layer: Option<UfoLayer<'_>>,
    opts: &ImportOptions,
) -> Result<Imported, ImportError> {
    let ufo = norad::Font::load(path).map_err(|e| {
        ImportError::at(
            path,
            format!("cannot read the UFO: {}", crate::ufo::error_chain(&e)),
        )
    })?;
    let upm = units_per_em(&ufo).map_err(|m| ImportError::at(path, m))?;
    let tolerance = super::check_tolerance(opts.tolerance, upm)?;
    let info = font_info(&ufo, upm, tolerance, opts);
    let (layers, sparse): (Vec<&norad::Layer>, bool) = match layer {
        None => (vec![ufo.default_layer()], false),
        Some(UfoLayer::Full(name) | UfoLayer::Sparse(name)) => {
            let named = ufo
                .layers
                .get(name)
                .ok_or_else(|| ImportError::at(path, format!("the UFO has no layer {name:?}")))?;
            match layer {
                Some(UfoLayer::Sparse(_)) => (vec![named, ufo.default_layer()], true),
                _ => (vec![named], false),
            }
        }
    };
    let names = glyph_names(&layers).map_err(|m| ImportError::at(path, m))?;
    let glyphs: Vec<&norad::Glyph> = layers[0].iter().collect();
    if glyphs.is_empty() && !sparse {
        // The sources of a font need at least one glyph (`check` refuses an empty folder).
        return Err(ImportError::at(
            path,
            match layer {
                None => "the UFO has no glyphs in its default layer".to_string(),
                Some(UfoLayer::Full(name) | UfoLayer::Sparse(name)) => {
                    format!("the UFO has no glyphs in its layer {name:?}")
                }
            },
        ));
    }
    let grid = grid_for(tolerance);
    // Lib X-splines within this distance of the outline are current: the import
    // tolerance, or the exporting build's tolerance plus the 1/1000-unit rounding of the
    // .glif coordinates when that is larger.
    let bound = tolerance.max(info.tolerance + 0.01);
    let done = AtomicUsize::new(0);
    let mut fitted = glyphs
        .par_iter()
        .map(|g| {
            let one = import_one(&layers, g, &names, (tolerance, bound), grid);
            if let Some(tell) = &opts.progress.0 {
                tell(done.fetch_add(1, Ordering::Relaxed) + 1, glyphs.len());
            }
            one
        })
        .collect::<Result<Vec<_>, String>>()
        .map_err(|m| ImportError::at(path, m))?;
    fitted.sort_by(|a, b| crate::model::glyph_order(&a.fitted.glyph.name, &b.fitted.glyph.name));
    let mut notes = Vec::new();
    let unnamed: usize = glyphs
        .iter()
        .map(|g| g.anchors.iter().filter(|a| a.name.is_none()).count())
        .sum();
    if unnamed > 0 {
        notes.push(format!(
            "{unnamed} anchor(s) without a name left out: xglyph anchors are named"
        ));
    }
    let refitted: Vec<&str> = fitted
        .iter()
        .filter(|f| f.stale_lib)
        .map(|f| f.fitted.glyph.name.as_str())
        .collect();
    if !refitted.is_empty() {
        notes.push(format!(
            "{XSPLINE_KEY} no longer matches the outline of {}; fitted the outline instead",
            refitted.join(", ")
        ));
    }
    if ufo
        .lib
        .get(TOLERANCE_KEY)
        .and_then(number)
        .is_some_and(|t| t > 0.0)
    {
        notes.push(format!(
            "font.toml tolerance {} taken from the UFO's {TOLERANCE_KEY}",
            crate::source::emit::number(info.tolerance)
        ));
    }
    let from_lib = fitted.iter().filter(|f| f.from_lib).count();
    if from_lib > 0 {
        notes.push(format!(
            "{from_lib} glyph(s) taken exactly from their {XSPLINE_KEY} lib"
        ));
    }
    let mut outlines = BTreeMap::new();
    let mut glyphs = Vec::with_capacity(fitted.len());
    let mut rows = Vec::with_capacity(fitted.len());
    for f in fitted {
        if let Some(outline) = f.outline {
            outlines.insert(outline.name.clone(), outline);
        }
        glyphs.push(f.fitted.glyph);
        rows.push(f.fitted.report);
    }
    for g in &glyphs {
        super::check_fitted_limits(g)?;
    }
    let marks = categorised_marks(&ufo, &names);
    for g in glyphs.iter_mut() {
        // A glyph mapped to a combining mark is a mark whatever the lib says (`check`
        // requires it); without a `_` anchor its outline places it.
        let combining = g.unicodes.iter().any(|&c| crate::source::is_combining(c));
        g.outline_mark = (marks.contains(g.name.as_str()) || combining) && !g.attaches_by_anchor();
    }
    // A sparse layer has no kerning or features of its own: the full masters' apply.
    let kerning = if sparse {
        Vec::new()
    } else {
        kerning(&ufo, &names)
    };
    let features = if sparse || ufo.features.trim().is_empty() {
        None
    } else {
        let next_to = path.parent().unwrap_or(Path::new("."));
        let text = super::fea::stand_alone(&ufo.features, &[next_to, path], &names)
            .map_err(|m| ImportError::at(path, m))?;
        Some(FeatureFile {
            path: path.join("features.fea"),
            text,
        })
    };
    Ok(Imported {
        font: Font {
            info,
            glyphs,
            kerning,
            features,
        },
        report: Report {
            rows,
            tolerance,
            notes,
        },
        outlines,
    })
}

/// One imported glyph and how it was made.
struct UfoGlyph {
    fitted: FittedGlyph,
    /// The outline it was fitted from (none when taken from the lib).
    outline: Option<SourceGlyph>,
    from_lib: bool,
    stale_lib: bool,
}

fn units_per_em(ufo: &norad::Font) -> Result<u16, String> {
    let upm = ufo.font_info.units_per_em.map_or(1000.0, |u| u.as_f64());
    if upm.fract() != 0.0 || !(16.0..=16384.0).contains(&upm) {
        return Err(format!(
            "fontinfo.plist: unitsPerEm {upm} is not a whole number in 16..16384"
        ));
    }
    Ok(upm as u16)
}

fn font_info(ufo: &norad::Font, upm: u16, tolerance: f64, opts: &ImportOptions) -> FontInfo {
    let fi = &ufo.font_info;
    let defaults = FontInfo::with_em("Imported", upm);
    let lib_string = |key: &str| {
        ufo.lib
            .get(key)
            .and_then(|v| v.as_string())
            .map(String::from)
    };
    let version = version_text(fi.version_major, fi.version_minor, lib_string(VERSION_KEY));
    // A fontinfo without vertical metrics (or with ones that cross) gets the usual
    // 0.8 / -0.2 em, as a font's damaged hhea does: the sources need ascender > descender.
    let (ascender, descender) = match (fi.ascender, fi.descender) {
        (Some(a), Some(d)) if a > d => (a, d),
        (Some(a), None) if a > defaults.descender => (a, defaults.descender),
        (None, Some(d)) if defaults.ascender > d => (defaults.ascender, d),
        _ => (defaults.ascender, defaults.descender),
    };
    FontInfo {
        family: opts
            .family
            .clone()
            .or_else(|| fi.family_name.clone())
            .unwrap_or(defaults.family),
        style: fi.style_name.clone().unwrap_or(defaults.style),
        units_per_em: upm,
        ascender,
        descender,
        x_height: fi.x_height.unwrap_or(defaults.x_height),
        cap_height: fi.cap_height.unwrap_or(defaults.cap_height),
        tolerance: ufo
            .lib
            .get(TOLERANCE_KEY)
            .and_then(number)
            .filter(|t| *t > 0.0)
            .unwrap_or(BUILD_SHARE * tolerance),
        copyright: fi.copyright.clone(),
        designer: fi.open_type_name_designer.clone(),
        version,
        license: fi.open_type_name_license.clone(),
        license_url: fi.open_type_name_license_url.clone(),
        // xglyph's default vendor is what a font without one is built with.
        vendor: fi
            .open_type_os2_vendor_id
            .clone()
            .filter(|v| v != DEFAULT_VENDOR && !v.trim().is_empty()),
    }
}

/// The version text: the lib's when it still agrees with `versionMajor`/`versionMinor`,
/// else `major.minor` with three digits; none without a version.
fn version_text(major: Option<i32>, minor: Option<u32>, lib: Option<String>) -> Option<String> {
    let numbers = (major.unwrap_or(0), minor.unwrap_or(0));
    if let Some(text) = lib {
        if major.is_none() || crate::ufo::version_numbers(Some(&text)) == numbers {
            return Some(text);
        }
    }
    major.map(|_| format!("{}.{:03}", numbers.0, numbers.1))
}

/// UFO glyph name -> model glyph name over `layers` (a name in several is one glyph),
/// refusing two that would become one.
fn glyph_names(layers: &[&norad::Layer]) -> Result<HashMap<String, String>, String> {
    let mut out = HashMap::new();
    let mut taken: BTreeMap<String, String> = BTreeMap::new();
    for g in layers.iter().flat_map(|l| l.iter()) {
        if out.contains_key(g.name().as_str()) {
            continue;
        }
        let new = crate::names::glyph_name_from(g.name());
        if let Some(other) = taken.insert(new.clone(), g.name().to_string()) {
            return Err(format!(
                "glyphs `{other}` and `{}` would both become `{new}`; rename one",
                g.name()
            ));
        }
        out.insert(g.name().to_string(), new);
    }
    Ok(out)
}

fn import_one(
    layers: &[&norad::Layer],
    g: &norad::Glyph,
    names: &HashMap<String, String>,
    (tolerance, bound): (f64, f64),
    grid: f64,
) -> Result<UfoGlyph, String> {
    let name = names[g.name().as_str()].clone();
    let own = contours_path(g, Affine::IDENTITY);
    let mut components = Vec::new();
    let mut drawn = own.clone();
    for c in &g.components {
        let t = c.transform;
        let translation =
            t.x_scale == 1.0 && t.y_scale == 1.0 && t.xy_scale == 0.0 && t.yx_scale == 0.0;
        match names.get(c.base.as_str()) {
            Some(base) if translation => components.push(Component {
                base: base.clone(),
                offset: (t.x_offset, t.y_offset),
            }),
            Some(_) => {
                let path = resolved_path(layers, &c.base, affine(t), 0)
                    .map_err(|m| format!("glyph `{}`: {m}", g.name()))?;
                drawn.extend(path);
            }
            None => {
                return Err(format!(
                    "glyph `{}` places `{}`, which is not in the UFO",
                    g.name(),
                    c.base
                ))
            }
        }
    }
    let lib = g.lib.get(XSPLINE_KEY);
    let closed = g.contours.iter().filter(|c| c.is_closed()).count();
    let decomposed = drawn.elements().len() != own.elements().len();
    if let (Some(value), false) = (lib, decomposed) {
        let splines = read_xspline(value).map_err(|e| format!("glyph `{}`: {e}", g.name()))?;
        let originals = contour::contours(&own);
        if splines.len() == closed && originals.len() == closed {
            let error = splines
                .iter()
                .zip(&originals)
                .map(|(s, o)| super::fit::contour_error(s.spline(), &o.segs))
                .fold(0.0, f64::max);
            if error <= bound {
                let report = GlyphReport {
                    name: name.clone(),
                    original_points: originals
                        .iter()
                        .map(|o| contour::stored_points(&o.segs))
                        .sum(),
                    xspline_points: splines.iter().map(|s| s.points().len()).sum(),
                    max_error: error,
                    dropped_contours: 0,
                };
                let glyph = Glyph {
                    name,
                    unicodes: g.codepoints.iter().collect(),
                    advance: g.width,
                    contours: splines,
                    components,
                    anchors: anchors(g),
                    outline_mark: false,
                };
                return Ok(UfoGlyph {
                    fitted: FittedGlyph { glyph, report },
                    outline: None,
                    from_lib: true,
                    stale_lib: false,
                });
            }
        }
    }
    let source = SourceGlyph {
        name,
        unicodes: g.codepoints.iter().collect(),
        advance: g.width,
        path: drawn,
    };
    let mut fitted = import_glyph(&source, tolerance, grid);
    fitted.glyph.components = components;
    fitted.glyph.anchors = anchors(g);
    Ok(UfoGlyph {
        fitted,
        outline: Some(source),
        from_lib: false,
        stale_lib: lib.is_some(),
    })
}

/// The model names of the glyphs `public.openTypeCategories` in the font lib calls
/// "mark" (what [`crate::ufo`] writes for a font with a `mark = "outline"` glyph; other
/// values and a malformed key are ignored).
fn categorised_marks<'a>(
    ufo: &norad::Font,
    names: &'a HashMap<String, String>,
) -> std::collections::HashSet<&'a str> {
    let Some(categories) = ufo
        .lib
        .get(crate::ufo::lib::CATEGORIES_KEY)
        .and_then(|v| v.as_dictionary())
    else {
        return Default::default();
    };
    categories
        .iter()
        .filter(|(_, c)| c.as_string() == Some("mark"))
        .filter_map(|(name, _)| names.get(name).map(String::as_str))
        .collect()
}

/// The glyph's named anchors, in file order, at their exact positions (an unnamed one has
/// no place in the model; the report counts them).
fn anchors(g: &norad::Glyph) -> Vec<Anchor> {
    g.anchors
        .iter()
        .filter_map(|a| {
            Some(Anchor {
                name: a.name.as_ref()?.to_string(),
                position: (a.x, a.y),
            })
        })
        .collect()
}

fn affine(t: norad::AffineTransform) -> Affine {
    Affine::new([
        t.x_scale, t.xy_scale, t.yx_scale, t.y_scale, t.x_offset, t.y_offset,
    ])
}

/// The glyph's closed contours as one path, transformed.
fn contours_path(g: &norad::Glyph, transform: Affine) -> BezPath {
    let mut path = BezPath::new();
    for c in g.contours.iter().filter(|c| c.is_closed()) {
        if let Some(sub) = closed_contour(c) {
            path.extend(transform * sub);
        }
    }
    path
}

/// A glyph's whole outline (contours and components, recursively), transformed; each
/// glyph taken from the first of `layers` that has it.
fn resolved_path(
    layers: &[&norad::Layer],
    name: &str,
    transform: Affine,
    depth: usize,
) -> Result<BezPath, String> {
    if depth > MAX_DEPTH {
        return Err(format!(
            "components nest more than {MAX_DEPTH} deep at `{name}` (a cycle?)"
        ));
    }
    let g = layers
        .iter()
        .find_map(|l| l.get_glyph(name))
        .ok_or_else(|| format!("places `{name}`, which is not in the UFO"))?;
    let mut path = contours_path(g, transform);
    for c in &g.components {
        path.extend(resolved_path(
            layers,
            &c.base,
            transform * affine(c.transform),
            depth + 1,
        )?);
    }
    Ok(path)
}

/// A closed UFO contour as a kurbo subpath, or `None` when it has no on-curve point or
/// holds quadratic runs (`qcurve`) with more than one off-curve point per segment end,
/// which are split into quadratics as TrueType does.
fn closed_contour(c: &norad::Contour) -> Option<BezPath> {
    use norad::PointType;
    let pts = &c.points;
    let first_on = pts.iter().position(|p| p.typ != PointType::OffCurve)?;
    let n = pts.len();
    let at = |i: usize| kurbo::Point::new(pts[i % n].x, pts[i % n].y);
    let mut path = BezPath::new();
    path.move_to(at(first_on));
    let mut offs: Vec<kurbo::Point> = Vec::new();
    for k in 1..=n {
        let i = first_on + k;
        let p = &pts[i % n];
        match p.typ {
            PointType::OffCurve => offs.push(at(i)),
            PointType::Curve => {
                match offs.as_slice() {
                    [] => path.line_to(at(i)),
                    [c] => path.quad_to(*c, at(i)),
                    [c1, c2] => path.curve_to(*c1, *c2, at(i)),
                    // More than two off-curve points: UFO says a cubic needs two; keep
                    // the outer two, as some editors do for such input.
                    [c1, .., c2] => path.curve_to(*c1, *c2, at(i)),
                }
                offs.clear();
            }
            PointType::QCurve => {
                // Implied on-curve points halfway between consecutive off-curve points.
                for w in 0..offs.len() {
                    let end = if w + 1 < offs.len() {
                        offs[w].midpoint(offs[w + 1])
                    } else {
                        at(i)
                    };
                    path.quad_to(offs[w], end);
                }
                if offs.is_empty() {
                    path.line_to(at(i));
                }
                offs.clear();
            }
            PointType::Line | PointType::Move => {
                path.line_to(at(i));
                offs.clear();
            }
        }
    }
    path.close_path();
    Some(path)
}

/// Kerning by model glyph name, groups expanded (glyph-glyph beats glyph-group and
/// group-glyph, which beat group-group), in the exported order when the lib has one, then
/// by name.
fn kerning(ufo: &norad::Font, names: &HashMap<String, String>) -> Vec<KernPair> {
    let members = |side: &str, key: &str| -> Vec<String> {
        if key.starts_with(side) {
            ufo.groups
                .get(key)
                .map(|g| g.iter().map(|n| n.to_string()).collect())
                .unwrap_or_default()
        } else {
            vec![key.to_string()]
        }
    };
    let mut entries: Vec<(usize, &str, &str, f64)> = Vec::new();
    for (left, row) in &ufo.kerning {
        for (right, value) in row {
            let groups = usize::from(left.starts_with("public.kern1."))
                + usize::from(right.starts_with("public.kern2."));
            entries.push((groups, left, right, *value));
        }
    }
    // Most general first, so that specific pairs overwrite them.
    entries.sort_by_key(|e| std::cmp::Reverse(e.0));
    let mut pairs: BTreeMap<(String, String), f64> = BTreeMap::new();
    for (_, left, right, value) in entries {
        for l in members("public.kern1.", left) {
            for r in members("public.kern2.", right) {
                if let (Some(l), Some(r)) = (names.get(&l), names.get(&r)) {
                    pairs.insert((l.clone(), r.clone()), value);
                }
            }
        }
    }
    let mut out = Vec::with_capacity(pairs.len());
    if let Some(order) = ufo.lib.get(KERNING_ORDER_KEY) {
        for key in read_kerning_order(order) {
            if let Some(value) = pairs.remove(&key) {
                out.push(KernPair {
                    left: key.0,
                    right: key.1,
                    value,
                });
            }
        }
    }
    out.extend(
        pairs
            .into_iter()
            .map(|((left, right), value)| KernPair { left, right, value }),
    );
    out
}
