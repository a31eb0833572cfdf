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
//! them). Only the pieces' end points may move, horizontally, by at most the accuracy
//! `eps` the sweep is given, with the inner control points moved alongside; so the union's
//! boundary stays within about `eps` of the input's. [`remove_overlaps_font`] gives the
//! sweep [`UNION_SHARE`] of the font's tolerance: the fitter keeps its paths within 0.96
//! (at most 0.99) of the tolerance of the X-splines, so fit plus union stays within it.
//! `tests/it/overlap.rs` measures the distance on every bundled glyph.
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
//! thinner than `eps` may be dropped or joined; the union can have more segments than the
//! input (a cubic crossed by another contour becomes two pieces).

use kurbo::{BezPath, PathEl, Shape};
use linesweeper::topology::Topology;

use crate::outline::{OutlinedFont, OutlinedGlyph};

/// The share of the font's tolerance the union may move a boundary by.
pub const UNION_SHARE: f64 = 1e-3;

/// The outline of the nonzero union of `path`'s closed subpaths, boundaries within about
/// `tolerance` font units of the input's (see the module docs); `path` itself when its
/// contours neither overlap nor touch along an edge.
///
/// A path that is not made of closed subpaths, or has non-finite coordinates, is returned
/// unchanged (the IR only holds closed, finite subpaths).
pub fn remove_overlaps(path: &BezPath, tolerance: f64) -> BezPath {
    if path.elements().is_empty() {
        return path.clone();
    }
    let eps = tolerance.max(1e-9);
    let Ok(topology) = Topology::<i32>::from_path(path, eps) else {
        return path.clone();
    };
    if is_simple(&topology) {
        return path.clone();
    }
    let contours = topology.contours(|winding| *winding != 0);
    let mut out = BezPath::new();
    for contour in contours.contours() {
        // linesweeper's orientation agrees with kurbo's: positive area for an outer
        // contour. Checked per contour, so a change of convention cannot flip the font.
        let area = contour.path.area();
        if area == 0.0 {
            continue;
        }
        if (area > 0.0) == contour.outer {
            out.extend(contour.path.iter());
        } else {
            out.extend(contour.path.reverse_subpaths().iter());
        }
    }
    out
}

/// Whether the sweep left the input as it was: every input segment (cut at its y extrema)
/// is one output segment, none split at a crossing nor merged with a coincident one, and
/// each has the filled side (winding 1) on one hand and the outside (0) on the other.
fn is_simple(topology: &Topology<i32>) -> bool {
    let mut count = 0;
    for idx in topology.segment_indices() {
        count += 1;
        let half = idx.first_half();
        let sides = (
            *topology.winding_clockwise(half),
            *topology.winding_counter_clockwise(half),
        );
        if !matches!(sides, (0, 1) | (1, 0)) {
            return false;
        }
    }
    count == topology.segments.len()
}

/// The font with every glyph's outline replaced by [`remove_overlaps`] at
/// [`UNION_SHARE`] of the font's tolerance; segment counts updated, everything else kept.
pub fn remove_overlaps_font(font: &OutlinedFont) -> OutlinedFont {
    use rayon::prelude::*;
    let eps = UNION_SHARE * font.tolerance;
    OutlinedFont {
        glyphs: font
            .glyphs
            .par_iter()
            .map(|glyph| remove_glyph_overlaps(glyph, eps))
            .collect(),
        ..font.clone()
    }
}

fn remove_glyph_overlaps(glyph: &OutlinedGlyph, eps: f64) -> OutlinedGlyph {
    let path = remove_overlaps(&glyph.path, eps);
    let segments = path
        .elements()
        .iter()
        .filter(|el| !matches!(el, PathEl::MoveTo(_) | PathEl::ClosePath))
        .count();
    OutlinedGlyph {
        path,
        segments,
        ..glyph.clone()
    }
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
        assert_eq!(subpaths(&union).len(), 1);
        assert_eq!(union.area(), 200.0);
    }

    #[test]
    fn a_clockwise_square_is_turned_counter_clockwise() {
        let path = rect(0.0, 0.0, 10.0, 10.0).reverse_subpaths();
        assert_eq!(path.area(), -100.0);
        assert_eq!(remove_overlaps(&path, 1e-6).area(), 100.0);
    }
}
