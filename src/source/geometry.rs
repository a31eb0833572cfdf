//! Geometric checks on control points: contours that enclose no area, points far away.
//!
//! A contour encloses no area in two ways, both checked by [`no_area`]:
//!
//! 1. Its control points are collinear. Every point of an X-spline is a weighted average of
//!    its control points (the blending weights are divided by their sum, which never
//!    vanishes), so the curve lies in the control points' affine hull: on their line, for
//!    any shapes `s`.
//! 2. It runs out and back along itself (a spike such as `[0,0] [100,0] [100,100] [100,0]`
//!    with sharp points): the sampled curve has (almost) zero signed area *and* no point of
//!    a 64 × 64 grid over its bounding box has a nonzero winding number. Zero signed area
//!    alone is not enough: a bow tie has it but fills two lobes.
//!
//! Limit: a figure-eight whose lobes are both thinner than the grid spacing (1/64 of the
//! bounding box) would count as having no area.

use kurbo::{Point, Rect};

use crate::xspline::{ControlPoint, XSpline};

/// A contour is flat when every control point is closer than this fraction of the
/// contour's length to one straight line (1e-6: 0.001 units on a 1000-unit contour).
pub const FLAT_RELATIVE: f64 = 1e-6;

/// Samples per segment for the signed area and winding tests of [`no_area`].
const SAMPLES_PER_SEGMENT: usize = 16;

/// Grid points per side for the winding test of [`no_area`].
const GRID: usize = 64;

/// Why a contour encloses no area.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoArea {
    /// All control points on one straight line.
    Collinear,
    /// The curve goes out and back along itself: zero signed area, no inside.
    OutAndBack,
}

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

/// Whether and why a validated contour encloses no area; see the module docs.
pub fn no_area(curve: &XSpline) -> Option<NoArea> {
    let points = curve.points();
    if is_flat(points) {
        return Some(NoArea::Collinear);
    }
    let samples = polyline(curve);
    let steps = samples.len();
    let bounds = samples
        .iter()
        .fold(Rect::from_points(samples[0], samples[0]), |r, p| {
            r.union_pt(*p)
        });
    let diagonal2 = bounds.width().powi(2) + bounds.height().powi(2);
    let signed_area = 0.5
        * (0..steps)
            .map(|i| {
                samples[i]
                    .to_vec2()
                    .cross(samples[(i + 1) % steps].to_vec2())
            })
            .sum::<f64>();
    if signed_area.abs() > FLAT_RELATIVE * diagonal2 {
        return None;
    }
    let inside = (0..GRID * GRID).any(|k| {
        let p = Point::new(
            bounds.x0
                + (k % GRID) as f64 * bounds.width() / GRID as f64
                + bounds.width() / (2 * GRID) as f64,
            bounds.y0
                + (k / GRID) as f64 * bounds.height() / GRID as f64
                + bounds.height() / (2 * GRID) as f64,
        );
        winding(&samples, p) != 0
    });
    (!inside).then_some(NoArea::OutAndBack)
}

/// The closed polyline of [`no_area`]: [`SAMPLES_PER_SEGMENT`] points per segment, from its
/// start, except on a segment between two sharp points, which is its straight chord (the
/// outer points' weights vanish there) and needs only its start. The same points as
/// `curve.eval(k / SAMPLES_PER_SEGMENT)`, bit for bit; a CJK font's contours are mostly
/// such chords, and sampling them was a fifth of the CPU of loading its 20,902 glyphs.
fn polyline(curve: &XSpline) -> Vec<Point> {
    let points = curve.points();
    let n = points.len();
    let mut samples = Vec::with_capacity(n * SAMPLES_PER_SEGMENT);
    for j in 0..n {
        let segment = curve.segment(j);
        let count = if points[j].is_sharp() && points[(j + 1) % n].is_sharp() {
            1
        } else {
            SAMPLES_PER_SEGMENT
        };
        samples.extend((0..count).map(|k| segment.eval(k as f64 / SAMPLES_PER_SEGMENT as f64)));
    }
    samples
}

/// Winding number of the closed polyline `poly` around `p` (crossings of the ray to +x).
fn winding(poly: &[Point], p: Point) -> i32 {
    let n = poly.len();
    let mut w = 0;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let side = (b - a).cross(p - a);
        if a.y <= p.y && b.y > p.y && side > 0.0 {
            w += 1;
        } else if a.y > p.y && b.y <= p.y && side < 0.0 {
            w -= 1;
        }
    }
    w
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

    fn spline(points: Vec<ControlPoint>) -> XSpline {
        XSpline::new(points).expect("a valid contour")
    }

    fn pts(xy: &[(f64, f64)]) -> Vec<ControlPoint> {
        xy.iter()
            .map(|&(x, y)| ControlPoint::new(x, y, 0.0))
            .collect()
    }

    #[test]
    fn polyline_samples_curves_and_takes_chords_by_their_ends() {
        let curve = spline(vec![
            ControlPoint::new(0.0, 0.0, 0.0),
            ControlPoint::new(400.0, 0.0, 0.0),
            ControlPoint::new(500.0, 300.0, 1.0),
            ControlPoint::new(100.0, 400.0, -0.5),
        ]);
        let poly = polyline(&curve);
        let per = SAMPLES_PER_SEGMENT;
        let dense: Vec<Point> = (0..4 * per)
            .map(|k| curve.eval(k as f64 / per as f64))
            .collect();
        // Segment 0 runs between two sharp points: its start only; the others in full.
        assert_eq!(poly.len(), 1 + 3 * per);
        assert_eq!(poly[0], dense[0]);
        assert_eq!(&poly[1..], &dense[per..]);
        // What it leaves out lies on the chord from (0, 0) to (400, 0).
        for p in &dense[1..per] {
            assert!(p.y.abs() < 1e-9 && p.x > 0.0 && p.x < 400.0, "{p:?}");
        }
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
    fn out_and_back_contours() {
        let spike = pts(&[(0.0, 0.0), (100.0, 0.0), (100.0, 100.0), (100.0, 0.0)]);
        assert_eq!(no_area(&spline(spike.clone())), Some(NoArea::OutAndBack));
        let line = pts(&[(0.0, 0.0), (100.0, 100.0), (50.0, 50.0)]);
        assert_eq!(no_area(&spline(line)), Some(NoArea::Collinear));
        let bow_tie = pts(&[(0.0, 0.0), (100.0, 100.0), (100.0, 0.0), (0.0, 100.0)]);
        assert_eq!(no_area(&spline(bow_tie)), None);
        // A thin but real sliver (1 unit over 1000) has area.
        let sliver = pts(&[(0.0, 0.0), (1000.0, 0.0), (500.0, 1.0)]);
        assert_eq!(no_area(&spline(sliver)), None);
        // With smooth points the spike still retraces itself: reversing a contour gives the
        // same curve, and this one is its own reverse from the tip on.
        let smooth: Vec<ControlPoint> = spike
            .iter()
            .map(|p| ControlPoint::new(p.pos.x, p.pos.y, -1.0))
            .collect();
        assert_eq!(no_area(&spline(smooth)), Some(NoArea::OutAndBack));
        // Coming back 10 units to the side encloses a thin triangle.
        let thin = pts(&[(0.0, 0.0), (100.0, 0.0), (100.0, 100.0), (90.0, 0.0)]);
        assert_eq!(no_area(&spline(thin)), None);
    }

    #[test]
    fn distance_from_box() {
        let b = glyph_box(500.0, -200.0, 800.0);
        assert_eq!(distance_outside(Point::new(250.0, 0.0), b), 0.0);
        assert_eq!(distance_outside(Point::new(-300.0, 0.0), b), 300.0);
        assert_eq!(distance_outside(Point::new(530.0, 840.0), b), 50.0);
    }
}
