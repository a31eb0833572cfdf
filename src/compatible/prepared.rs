//! One X-spline segment with what its blending functions take from the shapes `s1` and
//! `s2` computed once, for the many evaluations a span's samples, a gap table's grid or a
//! position's own samples make on one segment.
//!
//! [`Prepared::eval_deriv`] gives the same bits as [`Segment::eval_deriv`]: the same
//! operations in the same order (the blending polynomials of
//! `xspline::weights_with_deriv`, shared docs `xspline.md` §2–3), with only the
//! coefficients that depend on the shapes alone (`d = 1 + s`, `p = 2 d²`, `q = -s / 2` and
//! the polynomials' coefficients and their multiples in the derivative) taken from the
//! preparation instead of being computed at every `t`. The reference curve stays
//! `xspline`'s: a test compares the two bit for bit over every branch (`s < 0`, `s = 0`,
//! `s > 0`, `t` on both sides of the `t < s1` and `t > 1 - s2` switches).

use kurbo::{Point, Vec2};

use crate::xspline::{blend_deriv, blend_point, Segment};

/// The shape-dependent part of one end's two blending functions.
#[derive(Clone, Copy, Debug)]
enum Shape {
    /// `s < 0`: `g(u; q)` and `h(u; q)` with `q = -s / 2`. `g`: its coefficients `c1..c5`
    /// and the derivative's `2 c2, 3 c3, 4 c4` (the fifth stays `(u · 5) · c5`, as
    /// written there).
    Interpolating { q: f64, g: [f64; 5], dg: [f64; 3] },
    /// `s ≥ 0`: `f_p(u)` with `d = 1 + s`, `p = 2 d²`: `s`, `d`, the coefficients
    /// `c3, c4, c5` and the derivative's `3 c3, 4 c4, 5 c5`.
    Approximating {
        s: f64,
        d: f64,
        f: [f64; 3],
        df: [f64; 3],
    },
}

impl Shape {
    fn new(s: f64) -> Shape {
        if s < 0.0 {
            let q = -s / 2.0;
            let (c1, c2, c3, c4, c5) = (q, 2.0 * q, 8.0 - 12.0 * q, 14.0 * q - 11.0, 4.0 - 5.0 * q);
            Shape::Interpolating {
                q,
                g: [c1, c2, c3, c4, c5],
                dg: [2.0 * c2, 3.0 * c3, 4.0 * c4],
            }
        } else {
            let d = 1.0 + s;
            let p = 2.0 * d * d;
            let (c3, c4, c5) = (10.0 - p, 2.0 * p - 15.0, 6.0 - p);
            Shape::Approximating {
                s,
                d,
                f: [c3, c4, c5],
                df: [3.0 * c3, 4.0 * c4, 5.0 * c5],
            }
        }
    }
}

/// `f_p(u)` and its derivative from the prepared coefficients.
#[inline]
fn f_blend(u: f64, f: &[f64; 3], df: &[f64; 3]) -> (f64, f64) {
    let u2 = u * u;
    let value = u2 * u * (f[0] + f[1] * u + f[2] * u2);
    let deriv = u2 * (df[0] + df[1] * u + df[2] * u2);
    (value, deriv)
}

/// `g(u; q)` and its derivative from the prepared coefficients.
#[inline]
fn g_blend(u: f64, g: &[f64; 5], dg: &[f64; 3]) -> (f64, f64) {
    let [c1, c2, c3, c4, c5] = *g;
    let value = u * (c1 + u * (c2 + u * (c3 + u * (c4 + u * c5))));
    let deriv = c1 + u * (dg[0] + u * (dg[1] + u * (dg[2] + u * 5.0 * c5)));
    (value, deriv)
}

/// `h(u; q)` and its derivative.
#[inline]
fn h_blend(u: f64, q: f64) -> (f64, f64) {
    let u2 = u * u;
    let value = q * u * (1.0 + u * (2.0 + u2 * (-2.0 - u)));
    let deriv = q * (1.0 + u * (4.0 + u2 * (-8.0 - 5.0 * u)));
    (value, deriv)
}

/// A segment ready for evaluation (see the module docs).
#[derive(Clone, Copy, Debug)]
pub(super) struct Prepared {
    q: [Point; 4],
    start: Shape,
    end: Shape,
}

impl Prepared {
    pub(super) fn new(segment: &Segment) -> Prepared {
        Prepared {
            q: segment.q,
            start: Shape::new(segment.s1),
            end: Shape::new(segment.s2),
        }
    }

    /// The raw weights `A0..A3` at `t` and their derivatives (`weights_with_deriv`).
    #[inline]
    fn weights(&self, t: f64) -> [(f64, f64); 4] {
        let (a0, a2) = match &self.start {
            Shape::Interpolating { q, g, dg } => {
                let (h, dh) = h_blend(-t, *q);
                ((h, -dh), g_blend(t, g, dg))
            }
            Shape::Approximating { s, d, f, df } => {
                let a0 = if t < *s {
                    let (v, dv) = f_blend((s - t) / d, f, df);
                    (v, -dv / d)
                } else {
                    (0.0, 0.0)
                };
                let (v, dv) = f_blend((t + s) / d, f, df);
                (a0, (v, dv / d))
            }
        };
        let (a1, a3) = match &self.end {
            Shape::Interpolating { q, g, dg } => {
                let (v, dv) = g_blend(1.0 - t, g, dg);
                ((v, -dv), h_blend(t - 1.0, *q))
            }
            Shape::Approximating { s, d, f, df } => {
                let (v, dv) = f_blend((1.0 + s - t) / d, f, df);
                let a3 = if t > 1.0 - s {
                    let (v3, dv3) = f_blend((t - 1.0 + s) / d, f, df);
                    (v3, dv3 / d)
                } else {
                    (0.0, 0.0)
                };
                ((v, -dv / d), a3)
            }
        };
        [a0, a1, a2, a3]
    }

    /// The point at `t`, as [`Segment::eval`] computes it.
    #[inline]
    pub(super) fn eval(&self, t: f64) -> Point {
        blend_point(&self.q, self.weights(t))
    }

    /// Point and first derivative at `t`, as [`Segment::eval_deriv`] computes them.
    #[inline]
    pub(super) fn eval_deriv(&self, t: f64) -> (Point, Vec2) {
        blend_deriv(&self.q, self.weights(t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::xspline::weights_with_deriv;

    /// Every branch of the blending functions, bit for bit: shapes negative, zero and
    /// positive at either end (and `±1`), `t` on a fine grid, at the ends, and just either
    /// side of the switches `t = s1` and `t = 1 - s2`.
    #[test]
    fn prepared_segments_evaluate_to_the_same_bits() {
        let shapes = [
            -1.0, -0.73, -0.5, -0.1, -1e-9, 0.0, 1e-9, 0.1, 0.37, 0.5, 0.9, 1.0,
        ];
        let q = [
            Point::new(-20.0, 80.0),
            Point::new(0.0, 0.0),
            Point::new(100.0, 3.5),
            Point::new(130.0, 70.0),
        ];
        let mut checked = 0;
        for &s1 in &shapes {
            for &s2 in &shapes {
                let segment = Segment { q, s1, s2 };
                let prepared = Prepared::new(&segment);
                let mut ts: Vec<f64> = (0..=200).map(|i| i as f64 / 200.0).collect();
                for edge in [s1, 1.0 - s2] {
                    ts.extend([edge, edge.next_down(), edge.next_up()]);
                }
                for t in ts.into_iter().filter(|t| (0.0..=1.0).contains(t)) {
                    let (p, d) = segment.eval_deriv(t);
                    let (pp, dp) = prepared.eval_deriv(t);
                    let bits = |v: [f64; 4]| v.map(f64::to_bits);
                    assert_eq!(
                        bits([p.x, p.y, d.x, d.y]),
                        bits([pp.x, pp.y, dp.x, dp.y]),
                        "s1 {s1}, s2 {s2}, t {t}"
                    );
                    let (e, ep) = (segment.eval(t), prepared.eval(t));
                    assert_eq!(bits([e.x, e.y, 0.0, 0.0]), bits([ep.x, ep.y, 0.0, 0.0]));
                    let raw = weights_with_deriv(t, s1, s2);
                    let own = prepared.weights(t);
                    for (a, b) in raw.iter().zip(&own) {
                        assert_eq!(a.0.to_bits(), b.0.to_bits(), "s1 {s1}, s2 {s2}, t {t}");
                        assert_eq!(a.1.to_bits(), b.1.to_bits(), "s1 {s1}, s2 {s2}, t {t}");
                    }
                    checked += 1;
                }
            }
        }
        // 144 shape pairs, 201 grid values each, and the switches' neighbours.
        assert!(checked > 144 * 201, "{checked}");
    }
}
