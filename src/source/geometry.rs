//! Geometric checks on control points: contours that enclose no area, points far away.
//!
//! Both work on the control points alone. Every point of an X-spline is a weighted average
//! of its control points (the blending weights are divided by their sum, which never
//! vanishes), so the curve lies in the control points' affine hull: when the control
//! points are collinear the curve is a segment of that line and encloses no area, for any
//! shapes `s`. The converse holds for every contour a designer writes (three or more
//! non-collinear points enclose area for all `s`), so no curve sampling is needed.

use kurbo::{Point, Rect};

use crate::xspline::ControlPoint;

/// A contour is flat when every control point is closer than this fraction of the
/// contour's length to one straight line (1e-6: 0.001 units on a 1000-unit contour).
pub const FLAT_RELATIVE: f64 = 1e-6;

/// Points more than this many ems outside the glyph box get a warning.
pub const FAR_EMS: f64 = 2.0;

/// Whether the contour encloses (almost) no area: all control points on one line.
///
/// The line runs through `a`, the point farthest from the first point, and `b`, the point
/// farthest from `a` (`|ab|` is within a factor 2 of the diameter); the contour is flat
/// when every point lies within `FLAT_RELATIVE * |ab|` of that line. Linear time.
pub fn is_flat(points: &[ControlPoint]) -> bool {
    let Some(first) = points.first() else {
        return true;
    };
    let farthest = |from: Point| {
        points
            .iter()
            .map(|p| p.pos)
            .max_by(|p, q| from.distance(*p).total_cmp(&from.distance(*q)))
            .unwrap_or(from)
    };
    let a = farthest(first.pos);
    let b = farthest(a);
    let ab = b - a;
    let len = ab.hypot();
    if len == 0.0 {
        return true;
    }
    points
        .iter()
        .all(|p| (ab.cross(p.pos - a) / len).abs() <= FLAT_RELATIVE * len)
}

/// The glyph box that [`distance_outside`] measures from: `x` from 0 to the advance, `y`
/// from the descender to the ascender.
pub fn glyph_box(advance: f64, descender: f64, ascender: f64) -> Rect {
    Rect::new(0.0, descender, advance.max(0.0), ascender)
}

/// How far `p` lies outside `bounds` (0 inside).
pub fn distance_outside(p: Point, bounds: Rect) -> f64 {
    let dx = (bounds.x0 - p.x).max(p.x - bounds.x1).max(0.0);
    let dy = (bounds.y0 - p.y).max(p.y - bounds.y1).max(0.0);
    dx.hypot(dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(xy: &[(f64, f64)]) -> Vec<ControlPoint> {
        xy.iter()
            .map(|&(x, y)| ControlPoint::new(x, y, 0.0))
            .collect()
    }

    #[test]
    fn flat_contours() {
        assert!(is_flat(&pts(&[(0.0, 0.0), (100.0, 100.0), (50.0, 50.0)])));
        assert!(is_flat(&pts(&[
            (0.1, 0.1),
            (0.3, 0.3),
            (0.7, 0.7),
            (0.2, 0.2)
        ])));
        // 0.0005 units off a 1000-unit line is flat, 0.01 is not.
        assert!(is_flat(&pts(&[(0.0, 0.0), (1000.0, 0.0), (500.0, 0.0005)])));
        assert!(!is_flat(&pts(&[(0.0, 0.0), (1000.0, 0.0), (500.0, 0.01)])));
        assert!(!is_flat(&pts(&[(0.0, 0.0), (100.0, 0.0), (100.0, 100.0)])));
        // A bow tie has zero signed area but is not flat: it fills two lobes.
        assert!(!is_flat(&pts(&[
            (0.0, 0.0),
            (100.0, 100.0),
            (100.0, 0.0),
            (0.0, 100.0)
        ])));
    }

    #[test]
    fn distance_from_box() {
        let b = glyph_box(500.0, -200.0, 800.0);
        assert_eq!(distance_outside(Point::new(250.0, 0.0), b), 0.0);
        assert_eq!(distance_outside(Point::new(-300.0, 0.0), b), 300.0);
        assert_eq!(distance_outside(Point::new(530.0, 840.0), b), 50.0);
    }
}
