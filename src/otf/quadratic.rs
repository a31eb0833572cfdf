//! Cubic outlines to TrueType quadratic splines.
//!
//! Each cubic becomes one quadratic B-spline with kurbo's `CubicBez::approx_spline`
//! (the cu2qu method: the fewest evenly split quadratics within `accuracy`); the
//! on-curve points between consecutive off-curve points stay implied, as TrueType allows.
//! Should no spline be found (kurbo gives up after 100 pieces), the cubic falls back to
//! `to_quads`, which always meets the accuracy with explicit on-curve points.
//!
//! Contours are reversed: TrueType wants outer contours clockwise, the outlines arrive
//! counter-clockwise (y up).

use kurbo::{BezPath, CubicBez, PathEl, Point};

/// One TrueType contour point before rounding.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplinePoint {
    pub point: Point,
    pub on_curve: bool,
}

/// The reversed contours of `path` as TrueType point lists (quadratic, implied on-curve
/// points left out), each within `accuracy` font units of the cubic outline.
///
/// The closing point is not repeated: a contour ends with the point before its start.
pub fn truetype_contours(path: &BezPath, accuracy: f64) -> Vec<Vec<SplinePoint>> {
    let reversed = path.reverse_subpaths();
    let mut contours = Vec::new();
    let mut points: Vec<SplinePoint> = Vec::new();
    let mut current = Point::ZERO;
    let on = |point| SplinePoint {
        point,
        on_curve: true,
    };
    let off = |point| SplinePoint {
        point,
        on_curve: false,
    };
    let mut finish = |points: &mut Vec<SplinePoint>| {
        if points.len() > 1 && points.last().map(|p| p.point) == points.first().map(|p| p.point) {
            points.pop();
        }
        if !points.is_empty() {
            contours.push(std::mem::take(points));
        }
    };
    for el in reversed.elements() {
        match *el {
            PathEl::MoveTo(p) => {
                finish(&mut points);
                points.push(on(p));
                current = p;
            }
            PathEl::LineTo(p) => {
                points.push(on(p));
                current = p;
            }
            PathEl::QuadTo(c, p) => {
                points.extend([off(c), on(p)]);
                current = p;
            }
            PathEl::CurveTo(c1, c2, p) => {
                let cubic = CubicBez::new(current, c1, c2, p);
                match cubic.approx_spline(accuracy) {
                    Some(spline) => {
                        let pts = spline.points();
                        // pts = [start, off-curve points..., end]
                        let inner = &pts[1..pts.len().saturating_sub(1)];
                        points.extend(inner.iter().map(|&c| off(c)));
                        points.push(on(p));
                    }
                    None => {
                        for (_, _, quad) in cubic.to_quads(accuracy) {
                            points.extend([off(quad.p1), on(quad.p2)]);
                        }
                    }
                }
                current = p;
            }
            PathEl::ClosePath => finish(&mut points),
        }
    }
    finish(&mut points);
    contours
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{ParamCurve, ParamCurveNearest, QuadBez};

    /// Quadratic segments of a TrueType point list, implied on-curve points restored.
    fn quads(points: &[SplinePoint]) -> Vec<QuadBez> {
        let n = points.len();
        let start = points.iter().position(|p| p.on_curve).unwrap();
        let mut out = Vec::new();
        let mut last_on = points[start].point;
        let mut pending: Option<Point> = None;
        for i in 1..=n {
            let p = points[(start + i) % n];
            match (p.on_curve, pending) {
                (true, None) => {
                    out.push(QuadBez::new(last_on, last_on.midpoint(p.point), p.point));
                    last_on = p.point;
                }
                (true, Some(c)) => {
                    out.push(QuadBez::new(last_on, c, p.point));
                    last_on = p.point;
                    pending = None;
                }
                (false, None) => pending = Some(p.point),
                (false, Some(c)) => {
                    let mid = c.midpoint(p.point);
                    out.push(QuadBez::new(last_on, c, mid));
                    last_on = mid;
                    pending = Some(p.point);
                }
            }
        }
        out
    }

    #[test]
    fn quarter_circle_within_accuracy_and_reversed() {
        // A closed quarter disc, counter-clockwise: (0,0) -> (100,0) -> arc -> (0,100).
        let k = 0.5523 * 100.0;
        let mut path = BezPath::new();
        path.move_to((0.0, 0.0));
        path.line_to((100.0, 0.0));
        path.curve_to((100.0, k), (k, 100.0), (0.0, 100.0));
        path.close_path();
        let cubic = CubicBez::new((100.0, 0.0), (100.0, k), (k, 100.0), (0.0, 100.0));
        for accuracy in [1.0, 0.5, 0.1, 0.01] {
            let contours = truetype_contours(&path, accuracy);
            assert_eq!(contours.len(), 1);
            let pts = &contours[0];
            // Reversed (clockwise): from the arc's end back along it, then along the x axis.
            assert_eq!(pts[0].point, Point::new(0.0, 100.0));
            assert!(!pts[1].on_curve);
            assert_eq!(pts[pts.len() - 2].point, Point::new(100.0, 0.0));
            assert_eq!(pts[pts.len() - 1].point, Point::new(0.0, 0.0));
            let qs = quads(pts);
            // The last two segments are the lines (100,0)-(0,0) and (0,0)-(0,100).
            let mut worst: f64 = 0.0;
            for q in &qs[..qs.len() - 2] {
                for i in 0..=200 {
                    let p = q.eval(f64::from(i) / 200.0);
                    worst = worst.max(cubic.nearest(p, 1e-9).distance_sq.sqrt());
                }
            }
            assert!(worst <= accuracy, "accuracy {accuracy}: {worst}");
            let off = pts.iter().filter(|p| !p.on_curve).count();
            // kurbo's counts (its error bound is conservative: the measured error is
            // about a third of the accuracy).
            let expected_off = match accuracy {
                1.0 => 2,
                0.5 => 3,
                0.1 => 5,
                _ => 11,
            };
            assert_eq!(off, expected_off, "accuracy {accuracy}");
        }
    }
}
