//! Overlap removal: a glyph's closed contours -> the outline of their nonzero union.
//!
//! Fonts ship without overlapping contours (rasterisers with even-odd or dropout quirks,
//! variable-font interpolation and FontBakery's overlap checks all want it), while sources
//! are drawn with overlaps: composites place an accent over its base, strokes cross. This
//! module replaces the outline of a glyph by the boundary of the region its contours fill
//! under the nonzero rule, with linesweeper (a robust Bentley–Ottmann sweep on kurbo paths).
//!
//! What the sweep keeps: every output segment is a piece of an input segment, so lines stay
//! lines and cubics stay cubics (`CubicBez::subsegment` of the original, split at
//! intersections and at y extrema, pieces of one cubic joined back where nothing cuts
//! them). Only the pieces' end points move, to the computed crossings, by about the
//! accuracy `eps` the sweep is given, with the inner control points moved alongside; and
//! the sweep's "really correct" mode perturbs pieces by up to `eps / 4` where it must to
//! keep its order decisions exact. Measured (`tests/it/overlap.rs`, every bundled glyph over
//! a shifted copy of itself, and every composite with its accent lowered into its base, at
//! `eps` = 0.0005 units): the union's boundary lies within 0.0036 units of the input's, and
//! the input's remaining boundary within 0.0037 of the union's (the ends of pieces near a
//! horizontal tangent move more than `eps`). [`remove_overlaps_font`] gives the sweep
//! [`UNION_SHARE`] of the font's tolerance; the fitter keeps its paths within 0.96 (at most
//! 0.99) of the tolerance, so fit plus union stays within it (the test checks each glyph).
//!
//! A glyph whose contours neither cross nor touch along an edge, and whose winding is
//! already 0 or 1 everywhere, is returned unchanged (same start points, same segments);
//! the sweep tells this exactly: no segment was split or merged, and every segment has
//! winding 1 on one side and 0 on the other.
//!
//! Output: contours in the sweep's order, outer contours counter-clockwise and holes
//! clockwise (y up, as [`crate::orient`] leaves them), each `MoveTo … ClosePath` with its
//! last segment ending on its first point. Limits: two contours may still touch at a single
//! point (a hole touching its outer contour at a vertex stays a separate contour); a sliver
//! thinner than `eps` may be dropped or joined; segments shorter than `eps` that the sweep
//! leaves are dropped; the union can have more segments than the input (a cubic crossed by
//! another contour becomes two pieces, and the sweep may leave an extra vertex on an edge
//! where it cut it). The accents of the bundled typeface clear their bases and no contour
//! crosses another, so its glyphs are all returned unchanged.

use std::borrow::Cow;
use std::collections::{BTreeMap, HashMap};

use kurbo::{BezPath, PathEl, Shape};
use linesweeper::sweep::Correctness::ReallyCorrect;
use linesweeper::topology::Topology;
use linesweeper::SegIdx;

mod disjoint;
mod guard;

use crate::orient::orient_contours;
use crate::outline::{OutlinedFont, OutlinedGlyph};
use crate::reuse::{outline_key, Key, KeyBuilder, OutlineKeys, Reuse};

/// The share of the font's tolerance the union may move a boundary by.
pub const UNION_SHARE: f64 = 1e-3;

/// The outline of the nonzero union of `path`'s closed subpaths, boundaries within about
/// `tolerance` font units of the input's (see the module docs); `path` itself when its
/// contours neither overlap nor touch along an edge.
///
/// A path that is not made of closed subpaths, or has non-finite coordinates, is returned
/// unchanged (the IR only holds closed, finite subpaths), and so is one the sweep cannot
/// resolve even with its coordinates snapped to a grid of `tolerance` (see `guard`).
pub fn remove_overlaps(path: &BezPath, tolerance: f64) -> BezPath {
    region(path, tolerance, |winding| winding != 0)
}

/// The outline of the region `path` fills by the even-odd rule, as [`remove_overlaps`]
/// gives the nonzero one: outer contours counter-clockwise, holes clockwise (y up), so that
/// its nonzero fill is the same region. For SVG drawings with `fill-rule="evenodd"`.
pub fn even_odd_region(path: &BezPath, tolerance: f64) -> BezPath {
    region(path, tolerance, |winding| winding % 2 != 0)
}

fn region(path: &BezPath, tolerance: f64, inside: impl Fn(i32) -> bool) -> BezPath {
    if path.elements().is_empty() {
        return path.clone();
    }
    let eps = tolerance.max(1e-9);
    // Most glyphs have nothing to remove: proven in microseconds, without the sweep.
    if disjoint::is_disjoint(path, eps) {
        return path.clone();
    }
    swept(path, eps, inside)
}

/// [`region`] by linesweeper's sweep.
fn swept(path: &BezPath, eps: f64, inside: impl Fn(i32) -> bool) -> BezPath {
    // The default ("good enough") positioning re-solves a piece's ends from their height,
    // which is ill-conditioned where a curve runs nearly horizontally: measured 0.048 units
    // off on the bundled `ograve` with its accent lowered, against 0.0011 here.
    let sweep = |grid: Option<f64>| {
        let snapped = grid.map(|grid| guard::snapped(path, grid));
        let paths = std::iter::once((snapped.as_ref().unwrap_or(path), ()));
        let topology =
            Topology::<i32>::from_paths_with_correctness(paths, eps, ReallyCorrect).ok()?;
        if is_simple(&topology, eps) {
            return None;
        }
        let contours = topology.contours(|winding| inside(*winding));
        Some(oriented(&contours, eps))
    };
    guard::guarded(eps, sweep)
        .flatten()
        .unwrap_or_else(|| path.clone())
}

/// The intersection of the regions `a` and `b` fill by the nonzero rule, oriented as
/// [`remove_overlaps`] leaves a union; boundaries within about `tolerance` of the inputs'.
/// Empty when they do not meet; `a` unchanged when either is not made of closed, finite
/// subpaths, or the sweep cannot resolve them (as [`remove_overlaps`]). For SVG clip paths.
pub fn intersect_regions(a: &BezPath, b: &BezPath, tolerance: f64) -> BezPath {
    use linesweeper::topology::{BinaryWindingNumber, OneOfTwo};
    if a.elements().is_empty() || b.elements().is_empty() {
        return BezPath::new();
    }
    let eps = tolerance.max(1e-9);
    let sweep = |grid: Option<f64>| {
        let snapped = grid.map(|grid| (guard::snapped(a, grid), guard::snapped(b, grid)));
        let (a, b) = snapped.as_ref().map_or((a, b), |(a, b)| (a, b));
        let paths = [(a, OneOfTwo::A), (b, OneOfTwo::B)];
        let topology =
            Topology::<BinaryWindingNumber>::from_paths_with_correctness(paths, eps, ReallyCorrect)
                .ok()?;
        let contours = topology.contours(|w| w.shape_a != 0 && w.shape_b != 0);
        Some(oriented(&contours, eps))
    };
    guard::guarded(eps, sweep)
        .flatten()
        .unwrap_or_else(|| a.clone())
}

/// The sweep's contours as one path: outer contours counter-clockwise, holes clockwise,
/// without slivers.
///
/// linesweeper walks every contour with the region on the same hand, the loops it splits
/// off where a contour touches itself included, so one sign of area marks every outer
/// contour and the other every hole. Its `outer` flag is not used: where a hole touches
/// itself at a vertex (remixicon's `ruler-2-line`: a ruler's teeth), it marks the larger
/// loop outer, and trusting the flag filled that hole. The sign is read from the contour of
/// largest area, which is outer whatever the convention (a hole lies inside a larger one).
fn oriented(contours: &linesweeper::topology::Contours, eps: f64) -> BezPath {
    let with_area: Vec<(&BezPath, f64)> = contours
        .contours()
        .map(|contour| (&contour.path, contour.path.area()))
        .filter(|&(_, area)| area != 0.0)
        .collect();
    let outer_sign = with_area
        .iter()
        .map(|&(_, area)| area)
        .max_by(|a, b| a.abs().total_cmp(&b.abs()))
        .map_or(1.0, f64::signum);
    let mut out = BezPath::new();
    for (path, _) in with_area {
        if outer_sign > 0.0 {
            push_without_slivers(&mut out, path, eps);
        } else {
            push_without_slivers(&mut out, &path.reverse_subpaths(), eps);
        }
    }
    out
}

/// Whether the sweep left the input as it was: each output segment has the filled side
/// (winding 1) on one hand and the outside (0) on the other, and each input segment (cut at
/// its y extrema) is still covered over its whole height (its width, when horizontal) by
/// the output segments cut from it, so none was removed as coincident with another. Splits
/// alone (where the sweep cuts a segment at a point near another) change nothing.
fn is_simple(topology: &Topology<i32>, eps: f64) -> bool {
    let extent = |a: &linesweeper::Point, b: &linesweeper::Point, horizontal: bool| {
        if horizontal {
            (b.x - a.x).abs()
        } else {
            (b.y - a.y).abs()
        }
    };
    let mut covered: BTreeMap<SegIdx, f64> = BTreeMap::new();
    for idx in topology.segment_indices() {
        let (start, end) = (idx.first_half(), idx.second_half());
        let sides = (
            *topology.winding_clockwise(start),
            *topology.winding_counter_clockwise(start),
        );
        // A piece shorter than `eps` may carry a stray winding: where a cubic ends with an
        // exactly horizontal tangent on a vertical line (the fitter's limit direction at a
        // sharp point), the sweep splits it at a y extremum one rounding step before its
        // end, and the sliver left runs along the line (measured on the bundled `R`).
        let length = topology.point(start).to_kurbo() - topology.point(end).to_kurbo();
        let tiny = length.hypot() <= eps;
        if !matches!(sides, (0, 1) | (1, 0)) && !tiny {
            return false;
        }
        let input = topology.orig_seg[idx];
        let horizontal = topology.segments[input].is_horizontal();
        *covered.entry(input).or_default() +=
            extent(topology.point(start), topology.point(end), horizontal);
    }
    topology.segments.indices().all(|input| {
        let seg = &topology.segments[input];
        let full = extent(&seg.start(), &seg.end(), seg.is_horizontal());
        covered.get(&input).copied().unwrap_or(0.0) >= full - eps
    })
}

/// Appends `contour` (one closed subpath) without its segments that stay within `eps` of
/// their start (the sweep leaves slivers of 1e-14 units where a cubic's end tangent is
/// horizontal); the last segment still ends on the first point.
fn push_without_slivers(out: &mut BezPath, contour: &BezPath, eps: f64) {
    let els = contour.elements();
    let Some(PathEl::MoveTo(first)) = els.first() else {
        return;
    };
    let start = out.elements().len();
    out.move_to(*first);
    let mut last = *first;
    for el in &els[1..] {
        let (tiny, end) = match *el {
            PathEl::LineTo(p) => (last.distance(p) <= eps, p),
            PathEl::QuadTo(a, p) => (last.distance(a).max(last.distance(p)) <= eps, p),
            PathEl::CurveTo(a, b, p) => (
                last.distance(a).max(last.distance(b)).max(last.distance(p)) <= eps,
                p,
            ),
            PathEl::MoveTo(_) | PathEl::ClosePath => continue,
        };
        if !tiny {
            out.push(*el);
            last = end;
        }
    }
    if out.elements().len() - start < 3 {
        // Nothing (or a line there and back) is left: no contour.
        out.truncate(start);
        return;
    }
    if let Some(el) = out.elements_mut().last_mut() {
        match el {
            PathEl::LineTo(p) | PathEl::QuadTo(_, p) | PathEl::CurveTo(_, _, p) => *p = *first,
            PathEl::MoveTo(_) | PathEl::ClosePath => {}
        }
    }
    out.close_path();
}

/// The font with every glyph's outline replaced by the union of its parts at
/// [`UNION_SHARE`] of the font's tolerance; segment counts updated, everything else kept.
///
/// The parts are the glyph's own contours and each component's (recursively), each set
/// oriented on its own by [`orient_contours`] before the union: the IR orients a glyph's
/// contours by their nesting in the whole glyph, so an accent lowered into its base's ink
/// would be a hole there, while the union must add it. A glyph without components is
/// unioned as it is.
pub fn remove_overlaps_font(font: &OutlinedFont) -> OutlinedFont {
    remove_overlaps_font_with(font, &Reuse::off(), &OutlineKeys::default())
}

/// [`remove_overlaps_font`], taking each glyph's union from the last build when its parts
/// are the same ([`Reuse::path_or_make`]): a rebuild after one edit unions one glyph.
/// `outlines` are the font's [`OutlineKeys`].
pub fn remove_overlaps_font_with(
    font: &OutlinedFont,
    reuse: &Reuse,
    outlines: &OutlineKeys,
) -> OutlinedFont {
    use rayon::prelude::*;
    let paths = Unions::new(font, reuse, outlines).into_paths();
    let glyphs = font
        .glyphs
        .par_iter()
        .zip(paths)
        .map(|(glyph, path)| with_path(glyph, path))
        .collect();
    // Field by field: `..font.clone()` would copy every glyph only to drop the copies.
    OutlinedFont {
        info: font.info.clone(),
        kerning: font.kerning.clone(),
        features: font.features.clone(),
        tolerance: font.tolerance,
        glyphs,
    }
}

/// Each glyph's union of a font, for the OpenType builders, which take most glyphs' data
/// from the record by the union's key ([`crate::otf::ttf_reusing_paths`]): a union the last
/// build recorded is kept for the next build but decoded only when asked for
/// ([`crate::otf::GlyphPaths::path`]); the others are made at once. A CJK rebuild after
/// one edit then decodes no union at all instead of 20,000 (and their 130 MB of fresh
/// memory).
pub struct Unions<'a> {
    font: &'a OutlinedFont,
    by_name: HashMap<&'a str, &'a OutlinedGlyph>,
    eps: f64,
    reuse: &'a Reuse,
    /// Per glyph: its union made now, or `None` when the record holds it (under its key).
    made: Vec<Option<BezPath>>,
    /// Per glyph, the union's key (none when `reuse` is off).
    keys: OutlineKeys,
}

impl<'a> Unions<'a> {
    /// The unions of `font`'s glyphs at [`UNION_SHARE`] of its tolerance, as
    /// [`remove_overlaps_font_with`] makes them (`outlines`: the font's [`OutlineKeys`]).
    pub fn new(font: &'a OutlinedFont, reuse: &'a Reuse, outlines: &OutlineKeys) -> Self {
        use rayon::prelude::*;
        let eps = UNION_SHARE * font.tolerance;
        let by_name: HashMap<&str, &OutlinedGlyph> =
            font.glyphs.iter().map(|g| (g.name.as_str(), g)).collect();
        let (made, keys): (Vec<Option<BezPath>>, Vec<Option<Key>>) = font
            .glyphs
            .par_iter()
            .enumerate()
            .map(|(i, glyph)| {
                let parts = parts(glyph, &by_name);
                let input = parts.as_ref().unwrap_or(&glyph.path);
                if !reuse.is_on() {
                    return (Some(remove_overlaps(input, eps)), None);
                }
                let input_key = match &parts {
                    Some(parts) => outline_key(parts),
                    None => outlines.get(i, &glyph.path),
                };
                let key = union_key(eps, &input_key);
                if reuse.keeps_path(key) {
                    return (None, Some(key));
                }
                let path = reuse.path_or_make(key, input, || remove_overlaps(input, eps));
                (Some(path), Some(key))
            })
            .unzip();
        let keys: Option<Vec<Key>> = keys.into_iter().collect();
        Unions {
            font,
            by_name,
            eps,
            reuse,
            made,
            keys: OutlineKeys::from_keys(keys.unwrap_or_default()),
        }
    }

    /// Per glyph, a key that determines its union (none when `reuse` is off).
    pub fn keys(&self) -> &OutlineKeys {
        &self.keys
    }

    /// Every glyph's union, in order: those made now moved out, the others decoded.
    fn into_paths(mut self) -> Vec<BezPath> {
        use rayon::prelude::*;
        let made = std::mem::take(&mut self.made);
        // With `made` empty, `path` decodes (or makes) every union not moved out here.
        made.into_par_iter()
            .enumerate()
            .map(|(i, path)| {
                path.unwrap_or_else(|| crate::otf::GlyphPaths::path(&self, i).into_owned())
            })
            .collect()
    }
}

impl crate::otf::GlyphPaths for Unions<'_> {
    /// The union of the glyph at `index`: made, or decoded from the record now (made again
    /// if its entry does not decode).
    fn path(&self, index: usize) -> Cow<'_, BezPath> {
        if let Some(Some(path)) = self.made.get(index) {
            return Cow::Borrowed(path);
        }
        let glyph = &self.font.glyphs[index];
        let parts = parts(glyph, &self.by_name);
        let input = parts.as_ref().unwrap_or(&glyph.path);
        let make = || remove_overlaps(input, self.eps);
        Cow::Owned(match self.keys.key(index) {
            Some(key) => self.reuse.path_or_make(key, input, make),
            None => make(),
        })
    }
}

/// The key of a union at accuracy `eps` of the outline whose key is `input`.
fn union_key(eps: f64, input: &Key) -> Key {
    KeyBuilder::new("union").f64(eps).key(input).finish()
}

/// `glyph` with its outline replaced by `path` (its segments counted again).
fn with_path(glyph: &OutlinedGlyph, path: BezPath) -> OutlinedGlyph {
    let segments = path
        .elements()
        .iter()
        .filter(|el| !matches!(el, PathEl::MoveTo(_) | PathEl::ClosePath))
        .count();
    // Field by field, so that the old path is not copied.
    OutlinedGlyph {
        name: glyph.name.clone(),
        unicodes: glyph.unicodes.clone(),
        advance: glyph.advance,
        components: glyph.components.clone(),
        anchors: glyph.anchors.clone(),
        placed_anchors: glyph.placed_anchors.clone(),
        outline_mark: glyph.outline_mark,
        contours: glyph.contours.clone(),
        path,
        max_error: glyph.max_error,
        segments,
    }
}

/// A composite's path with each part (its own contours, each component's own) oriented on
/// its own; `None` for a glyph without components, or when the path's subpaths do not
/// match its contours one to one (then the IR's orientation is kept).
fn parts(glyph: &OutlinedGlyph, by_name: &HashMap<&str, &OutlinedGlyph>) -> Option<BezPath> {
    if glyph.components.is_empty() {
        return None;
    }
    // The contours are the glyph's own, then each component's, depth first (as
    // `Font::placed_contours_in` lists them); a stack, since chains can be long.
    let mut sizes = Vec::new();
    let mut stack = vec![glyph];
    while let Some(g) = stack.pop() {
        let bases: Vec<&OutlinedGlyph> = g
            .components
            .iter()
            .filter_map(|c| by_name.get(c.base.as_str()).copied())
            .collect();
        let from_bases: usize = bases.iter().map(|b| b.contours.len()).sum();
        sizes.push(g.contours.len().checked_sub(from_bases)?);
        stack.extend(bases.into_iter().rev());
    }
    let subpaths: Vec<BezPath> = glyph
        .path
        .elements()
        .split_inclusive(|el| matches!(el, PathEl::ClosePath))
        .map(|els| BezPath::from_vec(els.to_vec()))
        .collect();
    if sizes.iter().sum::<usize>() != subpaths.len() {
        return None;
    }
    let mut out = BezPath::new();
    let mut rest = subpaths.into_iter();
    for size in sizes {
        let part: Vec<BezPath> = rest.by_ref().take(size).collect();
        out.extend(orient_contours(part).iter());
    }
    Some(out)
}
#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::Rect;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> BezPath {
        Rect::new(x0, y0, x1, y1).to_path(0.1)
    }

    fn subpaths(path: &BezPath) -> Vec<BezPath> {
        path.elements()
            .split_inclusive(|e| matches!(e, PathEl::ClosePath))
            .map(|els| BezPath::from_vec(els.to_vec()))
            .collect()
    }

    #[test]
    fn bundled_glyphs_are_proven_disjoint_and_the_sweep_agrees() {
        // Every bundled glyph is its own union (module docs): the quick proof must find
        // that for each, and the sweep must leave each as it is; each glyph over a copy of
        // itself shifted by 7 units (its contours crossing) must not be proven.
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
        let loaded = crate::pipeline::load(&dir, None).expect("the bundled typeface loads");
        let font = &loaded.font;
        let eps = UNION_SHARE * font.tolerance;
        let mut checked = 0;
        for glyph in font.glyphs.iter().filter(|g| !g.path.elements().is_empty()) {
            let path = parts(glyph, &HashMap::new()).unwrap_or_else(|| glyph.path.clone());
            assert!(disjoint::is_disjoint(&path, eps), "{}", glyph.name);
            assert_eq!(swept(&path, eps, |w| w != 0), path, "{}", glyph.name);
            let mut doubled = path.clone();
            doubled.extend(kurbo::Affine::translate((7.0, 7.0)) * path.clone());
            assert!(
                !disjoint::is_disjoint(&doubled, eps),
                "{} doubled",
                glyph.name
            );
            checked += 1;
        }
        assert!(checked > 100, "{checked} glyphs");
    }

    /// Where the region `a` and the region `b` differ on a grid of `step` over `area`,
    /// leaving out points within `margin` of either boundary.
    fn differences(a: &BezPath, b: &BezPath, area: kurbo::Rect, step: f64, margin: f64) -> usize {
        let near = |path: &BezPath, p: kurbo::Point| {
            path.segments().any(|seg| {
                use kurbo::ParamCurveNearest;
                seg.nearest(p, 1e-9).distance_sq <= margin * margin
            })
        };
        let mut differ = 0;
        let mut y = area.y0;
        while y <= area.y1 {
            let mut x = area.x0;
            while x <= area.x1 {
                let p = kurbo::Point::new(x, y);
                let inside = |path: &BezPath| crate::orient::winding(path.elements(), p) != 0;
                if !near(a, p) && !near(b, p) && inside(a) != inside(b) {
                    differ += 1;
                }
                x += step;
            }
            y += step;
        }
        differ
    }

    #[test]
    fn a_path_that_makes_the_sweep_panic_is_swept_on_the_grid() {
        // linesweeper 0.5 panics on this path (minimised from the stroke outline of an
        // icon set's `bold.svg`: vertices 6e-5 apart at y = 300.2083, and a contour that
        // runs there and back); the guard sweeps it again snapped to a grid of `eps`.
        let path = BezPath::from_svg(
            "M281,-12 Q594,300 562,300.2084 L250,300.20834 Z M281,347 L281.2,284 Z \
             M312,331 L281,300 Q299,331 312,331 Z",
        )
        .expect("a valid path");
        let eps = 1e-4;
        let paths = std::iter::once((&path, ()));
        let direct = std::panic::catch_unwind(|| {
            Topology::<i32>::from_paths_with_correctness(paths, eps, ReallyCorrect).is_ok()
        });
        assert!(direct.is_err(), "linesweeper fixed? then the guard can go");
        let union = remove_overlaps(&path, eps);
        assert_ne!(
            union, path,
            "the sweep ran: the overlapping triangles were merged"
        );
        assert!(!subpaths(&union).is_empty());
        let area = path.bounding_box().inflate(5.0, 5.0);
        assert_eq!(differences(&union, &path, area, 0.5, 0.01), 0);
        let clipped = intersect_regions(&path, &rect(0.0, 0.0, 400.0, 320.0), eps);
        let expected = rect(0.0, 0.0, 400.0, 320.0);
        let mut both = 0;
        for (x, y) in (0..600).map(|i| (250.0 + (i % 30) as f64 * 11.0, (i / 30) as f64 * 17.0)) {
            let p = kurbo::Point::new(x, y);
            let inside = |path: &BezPath| crate::orient::winding(path.elements(), p) != 0;
            let want = inside(&path) && inside(&expected);
            if (inside(&clipped) != want) && y != 300.0 {
                panic!("({x}, {y}): clipped {} against {want}", inside(&clipped));
            }
            both += usize::from(want);
        }
        assert!(both > 50, "the probes reach the intersection ({both})");
    }

    #[test]
    fn a_hole_touching_itself_at_a_vertex_stays_a_hole() {
        // A square with a comb-shaped hole (clockwise) that passes through (30, 70) twice:
        // the small square above-left of it is a loop of the hole, and the two squares
        // beside that loop are teeth of the outer. A bar overlapping the square's bottom
        // edge makes the sweep's output the result.
        let path = BezPath::from_svg(
            "M0,0 L100,0 L100,100 L0,100 Z \
             M10,10 L10,50 L30,50 L30,70 L10,70 L10,90 L30,90 L30,70 L50,70 L50,90 \
             L90,90 L90,10 Z M60,-10 L120,-10 L120,5 L60,5 Z",
        )
        .expect("a valid path");
        let union = remove_overlaps(&path, 1e-4);
        let areas: Vec<f64> = subpaths(&union).iter().map(|p| p.area()).collect();
        let filled: f64 = areas.iter().filter(|a| **a > 0.0).sum();
        let holes: f64 = areas.iter().filter(|a| **a < 0.0).sum();
        // The square and the bar's 700 outside it; the hole's 80 x 80 less two teeth.
        assert!((filled - 10_700.0).abs() < 1e-6, "{areas:?}");
        assert!((holes + 5_600.0).abs() < 1e-6, "{areas:?}");
        let area = path.bounding_box().inflate(5.0, 5.0);
        assert_eq!(differences(&union, &path, area, 0.5, 0.01), 0);
    }

    #[test]
    fn overlapping_squares_become_one_contour() {
        let mut path = rect(0.0, 0.0, 10.0, 10.0);
        path.extend(rect(5.0, 5.0, 15.0, 15.0).iter());
        let union = remove_overlaps(&path, 1e-6);
        let parts = subpaths(&union);
        assert_eq!(parts.len(), 1);
        assert_eq!(union.area(), 175.0);
        assert_eq!(union.bounding_box(), Rect::new(0.0, 0.0, 15.0, 15.0));
    }

    #[test]
    fn separate_squares_are_kept_as_they_are() {
        let mut path = rect(0.0, 0.0, 10.0, 10.0);
        path.extend(rect(20.0, 0.0, 30.0, 10.0).iter());
        assert_eq!(remove_overlaps(&path, 1e-6), path);
    }

    #[test]
    fn squares_sharing_an_edge_merge() {
        let mut path = rect(0.0, 0.0, 10.0, 10.0);
        path.extend(rect(10.0, 0.0, 20.0, 10.0).iter());
        let union = remove_overlaps(&path, 1e-6);
        assert_eq!(union.area(), 200.0);
    }

    #[test]
    fn a_clockwise_square_is_turned_counter_clockwise() {
        let path = rect(0.0, 0.0, 10.0, 10.0).reverse_subpaths();
        assert_eq!(path.area(), -100.0);
        assert_eq!(remove_overlaps(&path, 1e-6).area(), 100.0);
    }
}
