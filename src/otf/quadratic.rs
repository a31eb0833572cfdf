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

use kurbo::{BezPath, CubicBez, ParamCurve, PathEl, Point};

use super::monotone::coord;

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
                match spline_of(&cubic, accuracy) {
                    Some(pts) => {
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

/// The quadratic spline of `cubic` within `accuracy` (its points: start, off-curve points,
/// end), with no quadratic turning back needlessly ([`turns_back_needlessly`]), as far as
/// [`finer_if_needed`] finds one.
fn spline_of(cubic: &CubicBez, accuracy: f64) -> Option<Vec<Point>> {
    finer_if_needed(
        accuracy,
        |accuracy| Some(cubic.approx_spline(accuracy)?.points().to_vec()),
        |points| !turns_back_needlessly(cubic, points),
    )
}

/// The spline `make` gives at `accuracy`, or, when it is not `clean`, the first clean one
/// it gives at a finer accuracy, halving it up to [`FINER`] times; if none is, the first.
///
/// Why: cu2qu's single quadratic has its off-curve point where the end tangents cross.
/// Across an inflection that point lies past the end range, even where the cubic runs one
/// way, so the quadratic has an extreme without a point (the Regular `three` at
/// `--tolerance 2`: an off-curve point 1.2 units past its end, too far for the grid to pull
/// back, and a turn FontForge flags). kurbo's spline of a given piece count is private: a
/// finer accuracy is how to ask for more pieces.
pub(crate) fn finer_if_needed<T>(
    accuracy: f64,
    make: impl Fn(f64) -> Option<T>,
    clean: impl Fn(&T) -> bool,
) -> Option<T> {
    let first = make(accuracy)?;
    if clean(&first) {
        return Some(first);
    }
    let finer = (1..=FINER).find_map(|k| make(accuracy / f64::from(1u32 << k)).filter(&clean));
    Some(finer.unwrap_or(first))
}

/// Most halvings of the accuracy tried by [`finer_if_needed`].
const FINER: u32 = 6;

/// Whether the quadratic spline `points` of `cubic` (start, off-curve points, end) has a
/// quadratic that turns back, by more than [`MENDED`], on an axis where the cubic runs
/// one way.
pub(crate) fn turns_back_needlessly(cubic: &CubicBez, points: &[Point]) -> bool {
    (0..2).any(|axis| spline_turns_back(points, axis) && runs_one_way(cubic, axis))
}

/// Whether `cubic` runs one way on `axis` (within [`SLACK`]): its coordinate there at its
/// start, at each root of its derivative inside, and at its end is a monotone sequence.
fn runs_one_way(cubic: &CubicBez, axis: usize) -> bool {
    let c = [cubic.p0, cubic.p1, cubic.p2, cubic.p3].map(|p| coord(p, axis));
    // The derivative / 3 in Bernstein form, then in powers of t.
    let [d0, d1, d2] = [c[1] - c[0], c[2] - c[1], c[3] - c[2]];
    let mut roots = kurbo::common::solve_quadratic(d0, 2.0 * (d1 - d0), d0 - 2.0 * d1 + d2);
    roots.retain(|t| *t > 0.0 && *t < 1.0);
    roots.sort_by(f64::total_cmp);
    let mut values = vec![c[0]];
    values.extend(roots.iter().map(|&t| coord(cubic.eval(t), axis)));
    values.push(c[3]);
    let mut steps = values.windows(2).map(|w| w[1] - w[0]);
    steps.clone().all(|d| d >= -SLACK) || steps.all(|d| d <= SLACK)
}

/// Whether a quadratic spline (start, off-curve points, end; implied on-curve points
/// halfway between off-curve points) has a quadratic whose off-curve point passes the
/// range of its two ends on `axis` by more than [`MENDED`].
fn spline_turns_back(points: &[Point], axis: usize) -> bool {
    let last = points.len() - 1;
    (1..last).any(|i| {
        let end = |j: usize| {
            if j == 0 || j == last {
                points[j]
            } else {
                points[i].midpoint(points[j])
            }
        };
        let (a, c, b) = (
            coord(end(i - 1), axis),
            coord(points[i], axis),
            coord(end(i + 1), axis),
        );
        c < a.min(b) - MENDED || c > a.max(b) + MENDED
    })
}

/// The farthest an off-curve point may pass its end range, font units, for the grid to
/// mend the turn: rounding moves it up to half a unit on each axis, and the grid may pull
/// it back onto the range within one unit of its exact place
/// (`super::monotone::keep_quadratics`).
const MENDED: f64 = 0.25;

/// Font units below which a step is arithmetic noise (an end tangent meant to
/// be level, met by subdivision to within a few ulps).
const SLACK: f64 = 1e-6;

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
    fn a_spline_does_not_turn_back_where_its_cubic_runs_one_way() {
        // The Regular `three`'s waist at `--tolerance 2` (the SVG font's cubic, y up): it
        // rises all the way to its end, where it turns level in x, past an inflection.
        let cubic = CubicBez::new(
            (436.79, 362.51),
            (410.46, 386.15),
            (400.16, 390.14),
            (400.16, 394.2),
        );
        assert!(runs_one_way(&cubic, 0) && runs_one_way(&cubic, 1));
        // The TrueType accuracy is the font's tolerance.
        let accuracy = 2.0;
        // cu2qu's one quadratic: its off-curve point where the end tangents cross, 1.2
        // units above the end.
        let first = cubic.approx_spline(accuracy).unwrap().points().to_vec();
        assert_eq!(first.len(), 3);
        assert!((first[1].y - 395.4).abs() < 0.05, "{:?}", first[1]);
        assert!(spline_turns_back(&first, 1));
        let points = spline_of(&cubic, accuracy).unwrap();
        assert!(points.len() > 3, "{points:?}");
        for axis in [0, 1] {
            assert!(!spline_turns_back(&points, axis), "{points:?}");
        }
        // Still within the accuracy of the cubic.
        let spline = kurbo::QuadSpline::new(points);
        let worst = spline
            .to_quads()
            .flat_map(|q| (0..=100).map(move |i| q.eval(f64::from(i) / 100.0)))
            .map(|p| cubic.nearest(p, 1e-9).distance_sq.sqrt())
            .fold(0.0, f64::max);
        assert!(worst <= accuracy, "{worst}");
        // A cubic with a real extreme is left as cu2qu gives it.
        let bulge = CubicBez::new((0.0, 0.0), (0.0, 60.0), (100.0, 60.0), (100.0, 0.0));
        assert!(!runs_one_way(&bulge, 1));
        assert_eq!(
            spline_of(&bulge, accuracy).unwrap(),
            bulge.approx_spline(accuracy).unwrap().points()
        );
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
