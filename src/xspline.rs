//! Closed X-spline contours (Blanc & Schlick, SIGGRAPH 1995): point and exact derivative.
//!
//! A contour is a cycle of `n ≥ 3` control points `P_k` with a shape parameter
//! `s_k ∈ [-1, 1]`: `s = 0` is a sharp corner through the point, `s > 0` a smooth curve
//! passing near it (approximation, `s = 1` ≈ uniform cubic B-spline), `s < 0` a smooth
//! curve passing through it (interpolation, `s = -1` ≈ Catmull-Rom). Knots are uniform.
//!
//! We follow the paper's convention `q = -s/2` for negative `s` (xfig and R's
//! `grid.xspline` use `q = -s`; their `-0.5` is our `-1`). The blending polynomials are the
//! corrected ones of `docs/xspline.md`; the paper's printed `h` has a sign error in `u^5`.
//!
//! Segment `j` (t ∈ [0, 1]) reads the window `P_{j-1}, P_j, P_{j+1}, P_{j+2}` and only
//! `s_j`, `s_{j+1}`. The whole contour is parameterised by a global `T ∈ [0, n)`,
//! `T = j + t`.
//!
//! Limits: the weight sum never vanishes for `s ∈ [-1, 1]` (minimum 0.875), so evaluation
//! is total on a validated contour; at a sharp point the curve has zero speed (it leaves
//! the corner like `t^3`), so use [`Segment::start_direction`] / [`Segment::end_direction`]
//! for tangents there, not the derivative.

use std::fmt;

use kurbo::{Point, Vec2};

/// [`XSpline::min_tolerance`] as a fraction of the contour's extent.
const MIN_RELATIVE_TOLERANCE: f64 = 1e-10;

/// A control point: position in font units and shape parameter `s ∈ [-1, 1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlPoint {
    /// Position, font units, y up.
    pub pos: Point,
    /// Shape parameter in `[-1, 1]`: 0 sharp, > 0 approximating, < 0 interpolating.
    pub s: f64,
}

impl ControlPoint {
    /// The point `(x, y)` with shape `s`.
    pub const fn new(x: f64, y: f64, s: f64) -> Self {
        ControlPoint {
            pos: Point::new(x, y),
            s,
        }
    }

    /// The point `(x, y)` with shape `s` blended between masters, `s` kept inside
    /// [-1, 1]: a position's weights sum to 1 only up to rounding (masters all at `s = 1`
    /// can blend to 1 + 2⁻⁵²), and sparse corner masters weigh some masters negatively,
    /// which can carry a blend past the range where the X-spline is defined. Every output
    /// and every check of a fit blends the same way, so the clamp is part of the design.
    pub fn blended(x: f64, y: f64, s: f64) -> Self {
        ControlPoint::new(x, y, s.clamp(-1.0, 1.0))
    }

    /// A sharp corner (`s = 0`): the curve passes through it with a G0 joint.
    pub fn is_sharp(&self) -> bool {
        self.s == 0.0
    }
}

/// Why a list of control points is not a valid closed X-spline.
#[derive(Clone, Debug, PartialEq)]
pub enum XSplineError {
    /// A closed contour needs at least three points.
    TooFewPoints {
        /// How many points there are.
        count: usize,
    },
    /// A coordinate or shape value is NaN or infinite.
    NonFinite {
        /// The point's index.
        index: usize,
    },
    /// The shape parameter is outside `[-1, 1]`.
    ShapeOutOfRange {
        /// The point's index.
        index: usize,
        /// Its shape value.
        s: f64,
    },
    /// Point `index` coincides with the next point (cyclically).
    CoincidentPoints {
        /// The first point's index.
        index: usize,
        /// The index of the point it coincides with.
        next: usize,
    },
}

impl fmt::Display for XSplineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            XSplineError::TooFewPoints { count } => {
                write!(f, "a closed contour needs at least 3 points, found {count}")
            }
            XSplineError::NonFinite { index } => {
                write!(f, "point {index} has a non-finite number")
            }
            XSplineError::ShapeOutOfRange { index, s } => {
                write!(
                    f,
                    "point {index} has shape s = {s}, expected a value in [-1, 1]"
                )
            }
            XSplineError::CoincidentPoints { index, next } => {
                write!(f, "points {index} and {next} coincide; remove one of them")
            }
        }
    }
}

impl std::error::Error for XSplineError {}

/// A validated closed X-spline.
#[derive(Clone, Debug, PartialEq)]
pub struct XSpline {
    points: Vec<ControlPoint>,
    /// Diagonal of the control points' bounding box: the contour's length scale.
    extent: f64,
}

impl XSpline {
    /// Validates `points` as a closed contour: `n ≥ 3`, finite numbers, `s ∈ [-1, 1]`,
    /// and no two cyclically consecutive points at the same position.
    pub fn new(points: Vec<ControlPoint>) -> Result<Self, XSplineError> {
        if points.len() < 3 {
            return Err(XSplineError::TooFewPoints {
                count: points.len(),
            });
        }
        for (index, p) in points.iter().enumerate() {
            if !(p.pos.x.is_finite() && p.pos.y.is_finite() && p.s.is_finite()) {
                return Err(XSplineError::NonFinite { index });
            }
            if !(-1.0..=1.0).contains(&p.s) {
                return Err(XSplineError::ShapeOutOfRange { index, s: p.s });
            }
        }
        let n = points.len();
        for index in 0..n {
            let next = (index + 1) % n;
            if points[index].pos == points[next].pos {
                return Err(XSplineError::CoincidentPoints { index, next });
            }
        }
        let bbox = points.iter().skip(1).fold(
            kurbo::Rect::from_points(points[0].pos, points[0].pos),
            |r, p| r.union_pt(p.pos),
        );
        let extent = bbox.size().to_vec2().hypot();
        Ok(XSpline { points, extent })
    }

    /// The control points, as given.
    pub fn points(&self) -> &[ControlPoint] {
        &self.points
    }

    /// The diagonal of the control points' bounding box (never zero: the points are not
    /// all coincident). A length scale for relative thresholds.
    pub fn extent(&self) -> f64 {
        self.extent
    }

    /// The smallest tolerance fitting and flattening honour for this contour, 1e-10 of its
    /// extent: evaluation resolves about 1e-16 of it, and the error measures need room
    /// above that (at 1e-14 the fitter's segment count explodes, below it no fit ends).
    pub fn min_tolerance(&self) -> f64 {
        MIN_RELATIVE_TOLERANCE * self.extent
    }

    /// Number of segments, equal to the number of control points.
    pub fn segment_count(&self) -> usize {
        self.points.len()
    }

    /// Segment `j` (taken modulo the point count), from the `P_j` end to the `P_{j+1}` end.
    pub fn segment(&self, j: usize) -> Segment {
        let n = self.points.len();
        let p = |k: usize| self.points[k % n];
        let (q0, q1, q2, q3) = (p(j + n - 1), p(j), p(j + 1), p(j + 2));
        Segment {
            q: [q0.pos, q1.pos, q2.pos, q3.pos],
            s1: q1.s,
            s2: q2.s,
        }
    }

    /// Splits a global parameter `T` (any real; wrapped into `[0, n)`) into segment and `t`.
    /// The fitters' dense runs call it for every sample, so the common cases skip the
    /// library call: inside `[0, n)` the remainder is `T` itself, and inside `[n, 2n)`
    /// (a stretch that runs past the contour's start) `T - n`, exact there (Sterbenz), so
    /// the same bits as `rem_euclid`.
    pub(crate) fn locate(&self, big_t: f64) -> (usize, f64) {
        let count = self.points.len();
        let n = count as f64;
        let wrapped = if (0.0..n).contains(&big_t) {
            big_t
        } else if (n..2.0 * n).contains(&big_t) {
            big_t - n
        } else {
            big_t.rem_euclid(n)
        };
        // `wrapped >= 0`: truncation is `floor`; through `i64` the same index, more cheaply.
        let j = (wrapped as i64 as usize).min(count - 1);
        (j, wrapped - j as f64)
    }

    /// The point at global parameter `T = j + t`.
    pub fn eval(&self, big_t: f64) -> Point {
        let (j, t) = self.locate(big_t);
        self.segment(j).eval(t)
    }

    /// Point and derivative (with respect to `T`) at global parameter `T`.
    pub fn eval_deriv(&self, big_t: f64) -> (Point, Vec2) {
        let (j, t) = self.locate(big_t);
        self.segment(j).eval_deriv(t)
    }
}

impl XSpline {
    /// The blending basis at global parameter `T` (wrapped into `[0, n)`): which control
    /// points the curve point blends and with what normalised weights.
    pub fn basis(&self, big_t: f64) -> Basis {
        Basis::closed(self.points.len(), |k| self.points[k].s, big_t)
    }
}

/// The X-spline as a linear map of its control points at one parameter: the curve point
/// is `Σ weight[i] · P[index[i]]` and its derivative (with respect to `T`) is
/// `Σ deriv[i] · P[index[i]]`. For fixed shapes and `T` the curve is linear in the
/// positions, which is what least-squares fitting of control points needs.
///
/// Two topologies share the blending functions of [`Segment`]: a closed contour (indices
/// taken cyclically) and an open chain `P_0 .. P_{n-1}` with `n - 1` segments, whose
/// windows repeat the end points at both ends (`P_{-1} = P_0`, `P_n = P_{n-1}`). An open
/// chain whose end points are sharp (`s = 0`) is exactly that stretch of any closed
/// contour containing it, since a sharp end's outer weight is zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Basis {
    /// Indices of the window `Q0..Q3` into the control points.
    pub index: [usize; 4],
    /// Normalised weights (they sum to 1).
    pub weight: [f64; 4],
    /// Derivatives of the normalised weights with respect to `T`.
    pub deriv: [f64; 4],
}

impl Basis {
    /// The basis of a closed contour of `count ≥ 3` points with shapes `shape(k)`, at `T`
    /// (any real; wrapped into `[0, count)`).
    pub fn closed(count: usize, shape: impl Fn(usize) -> f64, big_t: f64) -> Self {
        let wrapped = big_t.rem_euclid(count as f64);
        let j = (wrapped.floor() as usize).min(count - 1);
        let index = [(j + count - 1) % count, j, (j + 1) % count, (j + 2) % count];
        Basis::of_window(index, shape(j), shape((j + 1) % count), wrapped - j as f64)
    }

    /// The basis of an open chain of `count ≥ 2` points with shapes `shape(k)`, at `T`
    /// (clamped to `[0, count - 1]`).
    pub fn open(count: usize, shape: impl Fn(usize) -> f64, big_t: f64) -> Self {
        let segments = count - 1;
        let clamped = big_t.clamp(0.0, segments as f64);
        let j = (clamped.floor() as usize).min(segments - 1);
        let index = [j.saturating_sub(1), j, j + 1, (j + 2).min(count - 1)];
        Basis::of_window(index, shape(j), shape(j + 1), clamped - j as f64)
    }

    /// Normalised weights and their derivatives (quotient rule) of one window.
    fn of_window(index: [usize; 4], s1: f64, s2: f64, t: f64) -> Self {
        let raw = weights_with_deriv(t, s1, s2);
        let total: f64 = raw.iter().map(|a| a.0).sum();
        let dtotal: f64 = raw.iter().map(|a| a.1).sum();
        let mut weight = [0.0; 4];
        let mut deriv = [0.0; 4];
        for i in 0..4 {
            weight[i] = raw[i].0 / total;
            deriv[i] = (raw[i].1 - weight[i] * dtotal) / total;
        }
        Basis {
            index,
            weight,
            deriv,
        }
    }

    /// The curve point and derivative for control point positions `points`.
    pub fn eval_deriv(&self, points: &[Point]) -> (Point, Vec2) {
        let (mut p, mut d) = (Vec2::ZERO, Vec2::ZERO);
        for i in 0..4 {
            let q = points[self.index[i]].to_vec2();
            p += self.weight[i] * q;
            d += self.deriv[i] * q;
        }
        (p.to_point(), d)
    }
}

/// One segment of a closed X-spline: the four-point window and the two shapes it reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// `Q0..Q3 = P_{j-1}, P_j, P_{j+1}, P_{j+2}`.
    pub q: [Point; 4],
    /// Shape at the start point `Q1`.
    pub s1: f64,
    /// Shape at the end point `Q2`.
    pub s2: f64,
}

/// The point the raw weights `w` (with their derivatives, unused here) make of `q`: the
/// weights are normalised before they are summed (see [`Segment::eval`]).
#[inline]
pub(crate) fn blend_point(q: &[Point; 4], w: [(f64, f64); 4]) -> Point {
    let total: f64 = w.iter().map(|(a, _)| a).sum();
    let mut sum = Vec2::ZERO;
    for (q, (a, _)) in q.iter().zip(w) {
        sum += (a / total) * q.to_vec2();
    }
    sum.to_point()
}

/// Point and first derivative the raw weights and their derivatives `w` make of `q`
/// (quotient rule).
#[inline]
pub(crate) fn blend_deriv(q: &[Point; 4], w: [(f64, f64); 4]) -> (Point, Vec2) {
    let den: f64 = w.iter().map(|(a, _)| a).sum();
    let (mut p, mut dnum, mut dden) = (Vec2::ZERO, Vec2::ZERO, 0.0);
    for (q, (a, da)) in q.iter().zip(w) {
        // Normalised first, as in `eval`: exact at interpolated control points.
        p += (a / den) * q.to_vec2();
        dnum += da * q.to_vec2();
        dden += da;
    }
    let d = (dnum - p * dden) / den;
    (p.to_point(), d)
}

impl Segment {
    /// Raw (unnormalised) blending weights `A0..A3` at `t ∈ [0, 1]`.
    pub fn weights(&self, t: f64) -> [f64; 4] {
        let w = weights_with_deriv(t, self.s1, self.s2);
        [w[0].0, w[1].0, w[2].0, w[3].0]
    }

    /// The point at `t ∈ [0, 1]`.
    ///
    /// The weights are normalised before they are summed, so where the curve passes
    /// through a control point (one weight alone) the result is that point exactly, not a
    /// rounding away from it (a sharp point must be an exact vertex of every output).
    pub fn eval(&self, t: f64) -> Point {
        blend_point(&self.q, weights_with_deriv(t, self.s1, self.s2))
    }

    /// Point and exact first derivative at `t` (quotient rule on the weights).
    pub fn eval_deriv(&self, t: f64) -> (Point, Vec2) {
        blend_deriv(&self.q, weights_with_deriv(t, self.s1, self.s2))
    }

    /// Unit direction in which the curve leaves `Q1` (t = 0+), exact also at a sharp point.
    pub fn start_direction(&self) -> Vec2 {
        if self.s1 != 0.0 {
            return unit_or_chord(self.eval_deriv(0.0).1, self.q[2] - self.q[1]);
        }
        // At s1 = 0 the curve leaves Q1 like t^3: C(t) - Q1 ≈ t^3 (8 (Q2-Q1) + c3 (Q3-Q1)) / W,
        // where 8 is the cubic coefficient of A2 = f_2(t) and c3 that of A3 (nonzero only
        // when s2 < 0 or s2 = 1, which tilts the departure toward Q3).
        let c3 = leading_cubic_coefficient(self.s2);
        let dir = 8.0 * (self.q[2] - self.q[1]) + c3 * (self.q[3] - self.q[1]);
        unit_or_chord(dir, self.eval(1e-3) - self.q[1])
    }

    /// Unit direction in which the curve arrives at `Q2` (t = 1-), exact also at a sharp point.
    pub fn end_direction(&self) -> Vec2 {
        if self.s2 != 0.0 {
            return unit_or_chord(self.eval_deriv(1.0).1, self.q[2] - self.q[1]);
        }
        // Mirror image of `start_direction` (A_i(t; s1, s2) = A_{3-i}(1 - t; s2, s1)).
        let c0 = leading_cubic_coefficient(self.s1);
        let back = 8.0 * (self.q[1] - self.q[2]) + c0 * (self.q[0] - self.q[2]);
        -unit_or_chord(back, self.eval(1.0 - 1e-3) - self.q[2])
    }
}

/// The `t^3` coefficient, at a neighbouring sharp point, of the outer weight that a point
/// of shape `s` contributes (A3 for the segment's end shape, A0 for its start shape).
fn leading_cubic_coefficient(s: f64) -> f64 {
    if s < 0.0 {
        // h(t - 1; q) = q (t - 1) t^3 (2 - t)  →  -2q t^3 near t = 0.
        -2.0 * (-s / 2.0)
    } else if s == 1.0 {
        // f_8(t / 2) = (t/2)^3 (2 + ...)  →  t^3 / 4.
        0.25
    } else {
        0.0
    }
}

/// `v` normalised; `fallback` normalised when `v` is (numerically) zero.
fn unit_or_chord(v: Vec2, fallback: Vec2) -> Vec2 {
    let len = v.hypot();
    if len > 1e-12 * (1.0 + fallback.hypot()) {
        v / len
    } else {
        fallback.normalize()
    }
}

/// `f_p(u)` and its derivative: the approximating blend, `u ∈ [0, 1]`.
fn f_blend(u: f64, p: f64) -> (f64, f64) {
    let (c3, c4, c5) = (10.0 - p, 2.0 * p - 15.0, 6.0 - p);
    let u2 = u * u;
    let value = u2 * u * (c3 + c4 * u + c5 * u2);
    let deriv = u2 * (3.0 * c3 + 4.0 * c4 * u + 5.0 * c5 * u2);
    (value, deriv)
}

/// `g(u; q)` and its derivative: the interpolating blend of the inner points, `u ∈ [0, 1]`.
fn g_blend(u: f64, q: f64) -> (f64, f64) {
    let (c1, c2, c3, c4, c5) = (q, 2.0 * q, 8.0 - 12.0 * q, 14.0 * q - 11.0, 4.0 - 5.0 * q);
    let value = u * (c1 + u * (c2 + u * (c3 + u * (c4 + u * c5))));
    let deriv = c1 + u * (2.0 * c2 + u * (3.0 * c3 + u * (4.0 * c4 + u * 5.0 * c5)));
    (value, deriv)
}

/// `h(u; q) = q u (1 + u)^3 (1 - u)` and its derivative, `u ∈ [-1, 0]`.
fn h_blend(u: f64, q: f64) -> (f64, f64) {
    let u2 = u * u;
    let value = q * u * (1.0 + u * (2.0 + u2 * (-2.0 - u)));
    let deriv = q * (1.0 + u * (4.0 + u2 * (-8.0 - 5.0 * u)));
    (value, deriv)
}

/// The four raw weights `A0..A3` at `t` and their derivatives with respect to `t`.
pub fn weights_with_deriv(t: f64, s1: f64, s2: f64) -> [(f64, f64); 4] {
    let (a0, a2) = if s1 < 0.0 {
        let q = -s1 / 2.0;
        let (h, dh) = h_blend(-t, q);
        ((h, -dh), g_blend(t, q))
    } else {
        let d = 1.0 + s1;
        let p = 2.0 * d * d;
        let a0 = if t < s1 {
            let (f, df) = f_blend((s1 - t) / d, p);
            (f, -df / d)
        } else {
            (0.0, 0.0)
        };
        let (f, df) = f_blend((t + s1) / d, p);
        (a0, (f, df / d))
    };
    let (a1, a3) = if s2 < 0.0 {
        let q = -s2 / 2.0;
        let (g, dg) = g_blend(1.0 - t, q);
        ((g, -dg), h_blend(t - 1.0, q))
    } else {
        let d = 1.0 + s2;
        let p = 2.0 * d * d;
        let (f, df) = f_blend((1.0 + s2 - t) / d, p);
        let a3 = if t > 1.0 - s2 {
            let (f3, df3) = f_blend((t - 1.0 + s2) / d, p);
            (f3, df3 / d)
        } else {
            (0.0, 0.0)
        };
        ((f, -df / d), a3)
    };
    [a0, a1, a2, a3]
}
