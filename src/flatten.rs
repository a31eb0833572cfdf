//! X-spline -> polyline within a distance bound, by adaptive subdivision.
//!
//! Every knot `T = k` is a vertex (so every sharp point, which the curve passes through at
//! its knot, is an exact vertex); each segment between knots is split in halves until every
//! chord is within the tolerance of the curve. All vertices lie on the curve.
//!
//! The bound is checked on samples: a chord is accepted when `PROBES` (8) curve points
//! inside its parameter interval are within 90 % of the tolerance of it, and the curve's
//! direction turns by less than `MAX_TURN` (0.5 radians) across the interval (so the piece
//! is a graph over its chord and the sampled distance cannot hide a loop). Limit: a feature
//! narrower than the probe spacing of the first, whole-segment interval can be missed; the
//! tests check the bound by dense sampling on random contours.

use kurbo::{Line, ParamCurveNearest, Point, Vec2};

use crate::xspline::XSpline;

/// Interior curve samples checked against each candidate chord.
const PROBES: usize = 8;
/// Largest direction change (radians) across one chord's interval.
const MAX_TURN: f64 = 0.5;
/// Fraction of the tolerance the probes must meet: room for a maximum between probes.
const SAFETY: f64 = 0.9;
/// Subdivision depth limit (2^-30 of a segment), against degenerate input.
const MAX_DEPTH: u32 = 30;

/// A closed polyline on the curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    /// The vertices, in curve order, starting at `T = 0`; the closing edge is implied.
    pub points: Vec<Point>,
    /// The curve parameter of each vertex.
    pub params: Vec<f64>,
}

/// Flattens a closed X-spline so that every chord is within `tolerance` of the curve. A
/// tolerance below [`XSpline::min_tolerance`] (zero, negative and NaN included) is raised
/// to it.
pub fn flatten(spline: &XSpline, tolerance: f64) -> Polyline {
    let tolerance = tolerance.max(spline.min_tolerance());
    let mut out = Polyline {
        points: Vec::new(),
        params: Vec::new(),
    };
    for k in 0..spline.segment_count() {
        let a = k as f64;
        out.points.push(spline.eval(a));
        out.params.push(a);
        subdivide(spline, a, a + 1.0, tolerance, 0, &mut out);
    }
    out
}

/// Appends the interior vertices of `[a, b]` (not `a`, not `b`).
fn subdivide(spline: &XSpline, a: f64, b: f64, tolerance: f64, depth: u32, out: &mut Polyline) {
    if depth >= MAX_DEPTH || chord_fits(spline, a, b, tolerance) {
        return;
    }
    let mid = 0.5 * (a + b);
    subdivide(spline, a, mid, tolerance, depth + 1, out);
    out.points.push(spline.eval(mid));
    out.params.push(mid);
    subdivide(spline, mid, b, tolerance, depth + 1, out);
}

/// Whether the chord of `[a, b]` stays within `tolerance` of the curve there.
fn chord_fits(spline: &XSpline, a: f64, b: f64, tolerance: f64) -> bool {
    let chord = Line::new(spline.eval(a), spline.eval(b));
    let limit = SAFETY * tolerance;
    let mut first: Option<Vec2> = None;
    for i in 0..=PROBES + 1 {
        let t = a + (b - a) * i as f64 / (PROBES + 1) as f64;
        let (p, d) = spline.eval_deriv(t);
        if i > 0 && i <= PROBES && chord.nearest(p, 1e-12).distance_sq > limit * limit {
            return false;
        }
        // Zero speed (a sharp point at an end) has no direction; skip it.
        if d.hypot2() > 0.0 {
            match first {
                None => first = Some(d),
                Some(f) => {
                    if f.cross(d).atan2(f.dot(d)).abs() > MAX_TURN {
                        return false;
                    }
                }
            }
        }
    }
    true
}
