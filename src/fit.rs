//! X-spline -> cubic Béziers within a tolerance, measured against the true curve.
//!
//! A closed contour is cut at its sharp points (`s = 0`) into smooth stretches; a segment
//! between two sharp points is a straight edge and becomes a `LineTo`. Each smooth stretch
//! is covered greedily from its start: the longest parameter span that one cubic fits
//! within the tolerance is found by bisection, then the next span starts there. A cubic
//! keeps the curve's end points and exact end tangent directions (so joins are G1, and at
//! a sharp point the true limit direction is used, which avoids hooks); its two handle
//! lengths are a least-squares fit to samples of the curve, with Newton
//! re-parameterisation (Schneider's method).
//!
//! The error of a candidate is measured both ways by sampling: curve samples projected
//! onto the cubic, and cubic samples projected onto the curve. Candidates are accepted at
//! 95 % of the tolerance to leave room for what sampling can miss; the tests check the
//! bound by dense sampling of the true curve.
//!
//! Limits: a cusp inside a smooth stretch (possible with collinear control points) is
//! fitted, not detected, so it costs extra segments near it.

use kurbo::{
    fit_to_cubic, BezPath, CubicBez, CurveFitSample, ParamCurve, ParamCurveDeriv, ParamCurveFit,
    Point, Vec2,
};

use crate::xspline::XSpline;

/// Curve samples per fitted span (plus one).
const SAMPLES: usize = 32;
/// Fraction of the tolerance a candidate must meet by sampling.
const SAFETY: f64 = 0.95;
/// Bisection steps when searching for the longest span that fits.
const SEARCH_STEPS: usize = 10;

/// A fitted closed contour.
#[derive(Clone, Debug)]
pub struct ContourFit {
    /// One closed subpath: MoveTo, LineTo/CurveTo…, ClosePath.
    pub path: BezPath,
    /// The largest measured (sampled, two-sided) distance to the X-spline.
    pub max_error: f64,
}

/// A piece of a closed contour between sharp points, in global curve parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stretch {
    /// The straight edge between two consecutive sharp points, ending at `T = end`.
    Edge { end: f64 },
    /// A smooth run `[start, end]` (global `T`, `end` may exceed `n`; it wraps), free of
    /// sharp points and cusps inside.
    Smooth { start: f64, end: f64 },
}

/// Cuts a contour at its sharp points and cusps, starting at the first sharp point
/// (or at `T = 0` when it has none); the pieces cover the contour once, in order.
pub fn stretches(spline: &XSpline) -> Vec<Stretch> {
    let n = spline.segment_count();
    let points = spline.points();
    let start = (0..n).find(|&k| points[k].is_sharp()).unwrap_or(0);
    let end = start + n;
    let mut out = Vec::new();
    let mut k = start;
    while k < end {
        if points[k % n].is_sharp() && points[(k + 1) % n].is_sharp() {
            out.push(Stretch::Edge {
                end: (k + 1) as f64,
            });
            k += 1;
            continue;
        }
        let mut stop = k + 1;
        while stop < end && !points[stop % n].is_sharp() {
            stop += 1;
        }
        let mut breaks = cusps(spline, k as f64, stop as f64);
        breaks.insert(0, k as f64);
        breaks.push(stop as f64);
        out.extend(breaks.windows(2).map(|w| Stretch::Smooth {
            start: w[0],
            end: w[1],
        }));
        k = stop;
    }
    out
}

/// Fits one closed X-spline with cubics and lines within `tolerance` (font units).
pub fn fit_contour(spline: &XSpline, tolerance: f64) -> ContourFit {
    let pieces = stretches(spline);
    let mut path = BezPath::new();
    let mut max_error: f64 = 0.0;
    let start = match pieces.first() {
        Some(Stretch::Smooth { start, .. }) => *start,
        Some(Stretch::Edge { end }) => end - 1.0,
        None => 0.0,
    };
    // At a sharp point this is the point itself; elsewhere the curve passes near it.
    path.move_to(spline.eval(start));
    for piece in pieces {
        match piece {
            Stretch::Edge { end } => path.line_to(spline.eval(end)),
            Stretch::Smooth { start, end } => {
                let err = fit_stretch(spline, start, end, tolerance, &mut path);
                max_error = max_error.max(err);
            }
        }
    }
    path.close_path();
    ContourFit { path, max_error }
}

/// A smooth stretch as a [`ParamCurveFit`] source on `[0, 1]`, so kurbo's fitters
/// (`fit_to_bezpath`, `fit_to_bezpath_opt`) can be run on exactly the same curve: the
/// reference for segment counts and speed in the tests and benches.
pub struct StretchSource<'a> {
    pub spline: &'a XSpline,
    pub start: f64,
    pub end: f64,
}

impl ParamCurveFit for StretchSource<'_> {
    fn sample_pt_tangent(&self, t: f64, _sign: f64) -> CurveFitSample {
        let big_t = self.start + (self.end - self.start) * t;
        let p = self.spline.eval(big_t);
        // Exact one-sided directions at the ends (corners have zero speed there); inside a
        // stretch there is no discontinuity, so `sign` is not needed.
        let dir = direction(self.spline, big_t, self.start, self.end);
        CurveFitSample { p, tangent: dir }
    }

    fn sample_pt_deriv(&self, t: f64) -> (Point, Vec2) {
        let big_t = self.start + (self.end - self.start) * t;
        let (p, d) = self.spline.eval_deriv(big_t);
        (p, d * (self.end - self.start))
    }

    fn break_cusp(&self, _range: std::ops::Range<f64>) -> Option<f64> {
        // Stretches are already cut at sharp points and cusps.
        None
    }
}

/// Cusps strictly inside `[t0, t1]`: parameters where the derivative reverses direction
/// between two of 32 samples per segment, located by bisection on that reversal.
fn cusps(spline: &XSpline, t0: f64, t1: f64) -> Vec<f64> {
    let steps = ((t1 - t0) * 32.0).round().max(1.0) as usize;
    let at = |i: usize| t0 + (t1 - t0) * i as f64 / steps as f64;
    let mut found = Vec::new();
    for i in 0..steps {
        let (mut lo, mut hi) = (at(i), at(i + 1));
        let dlo = spline.eval_deriv(lo).1;
        if dlo.dot(spline.eval_deriv(hi).1) >= 0.0 {
            continue;
        }
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if spline.eval_deriv(mid).1.dot(dlo) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let c = 0.5 * (lo + hi);
        if c > t0 + 1e-9 && c < t1 - 1e-9 {
            found.push(c);
        }
    }
    found
}

/// Fits the stretch `[t0, t1]` (global parameters, may exceed `n`; wrapped when evaluated),
/// appending cubics to `path`; returns the largest measured error.
fn fit_stretch(spline: &XSpline, t0: f64, t1: f64, tolerance: f64, path: &mut BezPath) -> f64 {
    let goal = tolerance * SAFETY;
    let mut max_error: f64 = 0.0;
    let mut a = t0;
    while a < t1 {
        // Longest span [a, b] that fits: try the rest, else bisect on b.
        let mut best = None;
        let full = fit_span(spline, a, t1, t0, t1);
        if full.1 <= goal {
            best = Some((t1, full));
        } else {
            let (mut lo, mut hi) = (a, t1);
            for _ in 0..SEARCH_STEPS {
                let mid = 0.5 * (lo + hi);
                let cand = fit_span(spline, a, mid, t0, t1);
                if cand.1 <= goal {
                    best = Some((mid, cand));
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
        }
        // With SEARCH_STEPS bisections a span of (t1 - a) / 1024 always exists in practice;
        // if even that fails (degenerate geometry), keep halving until it fits or is tiny.
        let (b, (cubic, err)) = match best {
            Some(found) => found,
            None => {
                let mut b = a + (t1 - a) / 1024.0;
                loop {
                    let cand = fit_span(spline, a, b, t0, t1);
                    if cand.1 <= goal || b - a < 1e-9 {
                        break (b, cand);
                    }
                    b = a + 0.5 * (b - a);
                }
            }
        };
        path.curve_to(cubic.p1, cubic.p2, cubic.p3);
        max_error = max_error.max(err);
        a = b;
    }
    max_error
}

/// Tangent direction at `t` inside the stretch `[t0, t1]`, one-sided at the stretch ends
/// (where a sharp point may sit and the derivative vanishes).
fn direction(spline: &XSpline, t: f64, t0: f64, t1: f64) -> Vec2 {
    let n = spline.segment_count();
    let at_knot = (t - t.round()).abs() < 1e-12;
    if at_knot && (t - t0).abs() < 1e-12 {
        return spline.segment((t.round() as usize) % n).start_direction();
    }
    if at_knot && (t - t1).abs() < 1e-12 {
        let j = (t.round() as usize + n - 1) % n;
        return spline.segment(j).end_direction();
    }
    let d = spline.eval_deriv(t).1;
    let len = d.hypot();
    let scale = spline.eval(t).to_vec2().hypot() + (spline.eval(t + 0.5) - spline.eval(t)).hypot();
    if len > 1e-6 * scale {
        return d / len;
    }
    // At (or next to) a cusp the derivative vanishes: take the one-sided secant direction
    // into the stretch; the curve leaves a cusp quadratically, so the error is O(h).
    let h = 1e-7;
    if t - t0 < t1 - t {
        (spline.eval(t + h) - spline.eval(t)).normalize()
    } else {
        (spline.eval(t) - spline.eval(t - h)).normalize()
    }
}

/// Fits one cubic to `[a, b]` of the stretch `[t0, t1]`; the cubic and its measured error.
fn fit_span(spline: &XSpline, a: f64, b: f64, t0: f64, t1: f64) -> (CubicBez, f64) {
    let p0 = spline.eval(a);
    let p3 = spline.eval(b);
    let d0 = direction(spline, a, t0, t1);
    let d1 = direction(spline, b, t0, t1);
    let samples: Vec<Point> = (0..=SAMPLES)
        .map(|i| spline.eval(a + (b - a) * i as f64 / SAMPLES as f64))
        .collect();
    // Chord-length parameters as the first guess of each sample's cubic parameter.
    let mut u = vec![0.0; samples.len()];
    for i in 1..samples.len() {
        u[i] = u[i - 1] + samples[i].distance(samples[i - 1]);
    }
    let total = u[SAMPLES];
    let chord = p0.distance(p3);
    if total <= 0.0 {
        let c = CubicBez::new(p0, p0, p3, p3);
        return (c, 0.0);
    }
    u.iter_mut().for_each(|x| *x /= total);
    let mut cubic = handles_least_squares(p0, p3, d0, d1, &samples, &u, chord);
    for _ in 0..2 {
        for (ui, s) in u.iter_mut().zip(&samples) {
            *ui = project_on_cubic(&cubic, *s, *ui).0;
        }
        cubic = handles_least_squares(p0, p3, d0, d1, &samples, &u, chord);
    }
    let err = measure(spline, &cubic, a, b, &samples, &mut u);
    // kurbo's area-and-moment fit is closer to minimax than least squares; measured the
    // same way, the better of the two is kept.
    let source = StretchSource {
        spline,
        start: t0,
        end: t1,
    };
    let (r0, r1) = ((a - t0) / (t1 - t0), (b - t0) / (t1 - t0));
    if let Some((mut alt, _)) = fit_to_cubic(&source, r0..r1, chord.max(1e-9)) {
        // Pin the ends to the exact points (the range mapping can differ by rounding).
        alt.p1 += p0 - alt.p0;
        alt.p2 += p3 - alt.p3;
        alt.p0 = p0;
        alt.p3 = p3;
        let mut v = u.clone();
        let alt_err = measure(spline, &alt, a, b, &samples, &mut v);
        if alt_err < err {
            return (alt, alt_err);
        }
    }
    (cubic, err)
}

/// The cubic with end points `p0`, `p3`, end directions `d0`, `d1` and handle lengths
/// minimising the squared distance to `samples` at parameters `u`.
fn handles_least_squares(
    p0: Point,
    p3: Point,
    d0: Vec2,
    d1: Vec2,
    samples: &[Point],
    u: &[f64],
    chord: f64,
) -> CubicBez {
    let (mut c00, mut c01, mut c11, mut x0, mut x1) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (s, &t) in samples.iter().zip(u) {
        let mt = 1.0 - t;
        let (b0, b1, b2, b3) = (mt * mt * mt, 3.0 * mt * mt * t, 3.0 * mt * t * t, t * t * t);
        let a0 = b1 * d0;
        let a1 = -b2 * d1;
        let r = s.to_vec2() - (b0 + b1) * p0.to_vec2() - (b2 + b3) * p3.to_vec2();
        c00 += a0.dot(a0);
        c01 += a0.dot(a1);
        c11 += a1.dot(a1);
        x0 += a0.dot(r);
        x1 += a1.dot(r);
    }
    let det = c00 * c11 - c01 * c01;
    let fallback = chord / 3.0;
    let (mut alpha, mut beta) = if det.abs() > 1e-12 * (c00 * c11).max(1e-300) {
        ((x0 * c11 - x1 * c01) / det, (c00 * x1 - c01 * x0) / det)
    } else {
        (fallback, fallback)
    };
    // Negative or runaway handles mean the least-squares system is ill-posed here
    // (near-straight spans); fall back to the classic third of the chord.
    let limit = 4.0 * chord.max(1e-9);
    if !(alpha.is_finite() && alpha > 0.0 && alpha < limit) {
        alpha = fallback;
    }
    if !(beta.is_finite() && beta > 0.0 && beta < limit) {
        beta = fallback;
    }
    CubicBez::new(p0, p0 + alpha * d0, p3 - beta * d1, p3)
}

/// Nearest point on `cubic` to `p` by Newton iteration from `u`; `(u, distance)`.
fn project_on_cubic(cubic: &CubicBez, p: Point, mut u: f64) -> (f64, f64) {
    let d1 = cubic.deriv();
    let d2 = d1.deriv();
    for _ in 0..4 {
        let r = cubic.eval(u) - p;
        let t = d1.eval(u).to_vec2();
        let denom = t.dot(t) + r.dot(d2.eval(u).to_vec2());
        if denom.abs() < 1e-300 {
            break;
        }
        u = (u - r.dot(t) / denom).clamp(0.0, 1.0);
    }
    (u, cubic.eval(u).distance(p))
}

/// Two-sided sampled distance between `cubic` and the curve on `[a, b]`.
///
/// `u` holds each curve sample's parameter on the cubic (refined here). Then cubic points
/// at twice the sample density are projected back onto the curve by Gauss-Newton on the
/// curve parameter, started at the curve sample whose cubic parameter is nearest.
fn measure(
    spline: &XSpline,
    cubic: &CubicBez,
    a: f64,
    b: f64,
    samples: &[Point],
    u: &mut [f64],
) -> f64 {
    let mut err: f64 = 0.0;
    for (ui, s) in u.iter_mut().zip(samples) {
        let (nu, d) = project_on_cubic(cubic, *s, *ui);
        *ui = nu;
        err = err.max(d);
    }
    let step = (b - a) / SAMPLES as f64;
    for k in 0..=2 * SAMPLES {
        let v = k as f64 / (2 * SAMPLES) as f64;
        let q = cubic.eval(v);
        let nearest = (0..u.len())
            .min_by(|&i, &j| (u[i] - v).abs().total_cmp(&(u[j] - v).abs()))
            .unwrap_or(0);
        let mut t = a + nearest as f64 * step;
        let mut best = samples[nearest].distance(q);
        for _ in 0..5 {
            let (c, d) = spline.eval_deriv(t);
            best = best.min(c.distance(q));
            let dd = d.dot(d);
            if dd < 1e-300 {
                break;
            }
            t = (t + ((q - c).dot(d) / dd).clamp(-step, step)).clamp(a, b);
        }
        best = best.min(spline.eval(t).distance(q));
        err = err.max(best);
    }
    err
}
