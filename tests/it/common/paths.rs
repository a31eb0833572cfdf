//! Distances between Bézier paths by dense sampling, shared by the tests that read outlines
//! back (fonts, imports) and by the curve checker in `curves.rs`.
// Each test crate uses a different subset.
#![allow(dead_code)]

use kurbo::{
    BezPath, ParamCurve, ParamCurveExtrema, ParamCurveNearest, PathEl, PathSeg, Point, Rect,
};

/// A closed X-spline as a polyline of `per_segment` chords per spline segment.
pub fn xspline_polyline(spline: &xglyph::xspline::XSpline, per_segment: usize) -> BezPath {
    let mut line = BezPath::new();
    line.move_to(spline.eval(0.0));
    let n = spline.segment_count() * per_segment;
    for k in 1..n {
        line.line_to(spline.eval(k as f64 / per_segment as f64));
    }
    line.close_path();
    line
}

/// The number of cubic segments in `path`.
pub fn cubic_count(path: &BezPath) -> usize {
    path.elements()
        .iter()
        .filter(|e| matches!(e, PathEl::CurveTo(..)))
        .count()
}

/// A path's segments with their bounding boxes, without zero-length lines (a closing line
/// onto the start point, or a single-point contour, which encloses nothing).
pub fn with_boxes(path: &BezPath) -> Vec<(PathSeg, Rect)> {
    path.segments()
        .filter(|s| !matches!(s, PathSeg::Line(l) if l.p0 == l.p1))
        .map(|s| (s, s.bounding_box()))
        .collect()
}

/// Distance from `p` to the nearest of `segments`. `hint`, the index of the nearest one
/// for the previous (nearby) query, is tried first and updated, so that boxes farther than
/// the best distance so far are skipped.
pub fn to_segments(segments: &[(PathSeg, Rect)], p: Point, hint: &mut usize) -> f64 {
    let Some((first, _)) = segments.get(*hint) else {
        return f64::INFINITY;
    };
    let mut best = first.nearest(p, 1e-9).distance_sq.sqrt();
    for (i, (seg, bbox)) in segments.iter().enumerate() {
        let dx = (bbox.x0 - p.x).max(p.x - bbox.x1).max(0.0);
        let dy = (bbox.y0 - p.y).max(p.y - bbox.y1).max(0.0);
        if dx.hypot(dy) >= best {
            continue;
        }
        let d = seg.nearest(p, 1e-9).distance_sq.sqrt();
        if d < best {
            (best, *hint) = (d, i);
        }
    }
    best
}

/// Largest distance from `per` samples on every segment of `a` (ends included) to `b`.
pub fn one_sided(a: &BezPath, b: &BezPath, per: usize) -> f64 {
    let target = with_boxes(b);
    let mut hint = 0;
    let mut worst: f64 = 0.0;
    for (seg, _) in with_boxes(a) {
        for i in 0..=per {
            let p = seg.eval(i as f64 / per as f64);
            worst = worst.max(to_segments(&target, p, &mut hint));
        }
    }
    worst
}

/// Two-sided (Hausdorff) distance between two outlines, `per` samples per segment.
pub fn two_sided(a: &BezPath, b: &BezPath, per: usize) -> f64 {
    one_sided(a, b, per).max(one_sided(b, a, per))
}
