//! Cubic Béziers in power form, `c0 + c1 u + c2 u² + c3 u³`, for the fitters' inner loops:
//! the static fitter ([`crate::fit`]) and the compatible one ([`crate::compatible`])
//! evaluate cubics and project curve samples onto them thousands of times per contour.
//!
//! Projection is Newton's method on the squared distance, from a start the caller gives
//! (local: it finds the nearest point near the start, not the global one), clamped to
//! `[0, 1]`. Several points can be projected at once ([`PowerCubic::residual_lanes`]):
//! each point's Newton steps are a chain of dependent divisions, and independent chains,
//! interleaved, overlap in the processor with the same bits as one by one.
//!
//! (Hand-written rather than kurbo's `ParamCurveNearest`: kurbo finds the global nearest
//! point by solving a quintic, far more work than a few Newton steps from a near start.)

use kurbo::{CubicBez, Point, Vec2};

/// A cubic in power form: `c0 + c1 u + c2 u² + c3 u³`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PowerCubic {
    pub(crate) c0: Vec2,
    pub(crate) c1: Vec2,
    pub(crate) c2: Vec2,
    pub(crate) c3: Vec2,
}

/// Points projected interleaved by [`PowerCubic::project_all`]: lanes of 2 gained 4–7 %
/// of the static fitter's time, lanes of 4 15–22 %, lanes of 8 nothing more.
pub(crate) const LANES: usize = 4;

/// A Newton step below this ends a projection of [`PowerCubic::project_steps`]: the
/// parameter is then within about its square of the answer.
pub(crate) const NEWTON_DONE: f64 = 1e-10;

impl PowerCubic {
    pub(crate) fn new(c: &CubicBez) -> PowerCubic {
        let (p0, p1, p2, p3) = (
            c.p0.to_vec2(),
            c.p1.to_vec2(),
            c.p2.to_vec2(),
            c.p3.to_vec2(),
        );
        PowerCubic {
            c0: p0,
            c1: 3.0 * (p1 - p0),
            c2: 3.0 * (p2 - 2.0 * p1 + p0),
            c3: p3 - p0 + 3.0 * (p1 - p2),
        }
    }

    /// The point at `u`.
    pub(crate) fn eval(&self, u: f64) -> Vec2 {
        self.c0 + u * (self.c1 + u * (self.c2 + u * self.c3))
    }

    /// The derivative at `u`.
    pub(crate) fn deriv(&self, u: f64) -> Vec2 {
        self.c1 + u * (2.0 * self.c2 + 3.0 * u * self.c3)
    }

    /// `self(u0 + s du)` as a cubic in `s` (expanded about `u0`).
    pub(crate) fn along(&self, u0: f64, du: f64) -> PowerCubic {
        let d2 = self.c2 + 3.0 * u0 * self.c3;
        PowerCubic {
            c0: self.eval(u0),
            c1: self.deriv(u0) * du,
            c2: d2 * (du * du),
            c3: self.c3 * (du * du * du),
        }
    }

    /// `self(s) - other(s)`.
    pub(crate) fn minus(&self, other: &PowerCubic) -> PowerCubic {
        PowerCubic {
            c0: self.c0 - other.c0,
            c1: self.c1 - other.c1,
            c2: self.c2 - other.c2,
            c3: self.c3 - other.c3,
        }
    }

    /// `(1 - λ) self + λ other`, coefficient by coefficient: the blend of the two cubics'
    /// control points, in power form.
    pub(crate) fn blend(&self, other: &PowerCubic, lambda: f64) -> PowerCubic {
        let mix = |a: Vec2, b: Vec2| (1.0 - lambda) * a + lambda * b;
        PowerCubic {
            c0: mix(self.c0, other.c0),
            c1: mix(self.c1, other.c1),
            c2: mix(self.c2, other.c2),
            c3: mix(self.c3, other.c3),
        }
    }

    /// The Bézier control points of the cubic run from `u0` to `u1` (as kurbo's
    /// `subsegment`: the end points and the end derivatives scaled to the run).
    pub(crate) fn subsegment(&self, u0: f64, u1: f64) -> [Vec2; 4] {
        let (p0, p3) = (self.eval(u0), self.eval(u1));
        let third = (u1 - u0) * (1.0 / 3.0);
        [
            p0,
            p0 + third * self.deriv(u0),
            p3 - third * self.deriv(u1),
            p3,
        ]
    }

    /// The parameter nearest `p` by at most `steps` Newton steps from `u`, and the distance
    /// there.
    pub(crate) fn project_steps(&self, p: Point, u: f64, steps: usize) -> (f64, f64) {
        let (u, r) = self.residual_steps(p, u, steps, NEWTON_DONE);
        (u, r.hypot())
    }

    /// [`PowerCubic::project_steps`] with six steps (enough from a near start).
    pub(crate) fn project(&self, p: Point, u: f64) -> (f64, f64) {
        self.project_steps(p, u, 6)
    }

    /// At most `steps` Newton steps from `u` towards the parameter nearest `p`, stopping
    /// at a step below `done_below`: that parameter and the residual `self(u) - p`.
    pub(crate) fn residual_steps(
        &self,
        p: Point,
        u: f64,
        steps: usize,
        done_below: f64,
    ) -> (f64, Vec2) {
        let [projected] = self.residual_lanes(&[p], &[u], steps, done_below);
        projected
    }

    /// [`PowerCubic::residual_steps`] of every parameter in `params` (projecting
    /// `point(k)` from `params[k]`), in lanes of [`LANES`] and the rest one by one: the
    /// same bits either way. Each parameter is replaced by its projection, then
    /// `each(k, u, residual)` is called, in the parameters' order. Always inlined: the
    /// polishes' sums in `each` then stay in registers (the static fitter took 2–4 % longer
    /// on `examples/fit_corpus` when it was not).
    #[inline(always)]
    pub(crate) fn project_all(
        &self,
        params: &mut [f64],
        point: impl Fn(usize) -> Point,
        (steps, done_below): (usize, f64),
        mut each: impl FnMut(usize, f64, Vec2),
    ) {
        let mut chunks = params.chunks_exact_mut(LANES);
        let mut k = 0;
        for chunk in &mut chunks {
            let points: [Point; LANES] = std::array::from_fn(|lane| point(k + lane));
            let starts = std::array::from_fn(|lane| chunk[lane]);
            let lanes = self.residual_lanes(&points, &starts, steps, done_below);
            for ((u, r), param) in lanes.into_iter().zip(chunk) {
                *param = u;
                each(k, u, r);
                k += 1;
            }
        }
        for param in chunks.into_remainder() {
            let (u, r) = self.residual_steps(point(k), *param, steps, done_below);
            *param = u;
            each(k, u, r);
            k += 1;
        }
    }

    /// [`PowerCubic::residual_steps`] of `N` points at once, their Newton steps
    /// interleaved: the same operations on each, so the same bits as one by one (a step
    /// below `done_below` ends a point's steps, a vanishing curvature term too). In lanes
    /// of four the static fitter takes 15–22 % less time on its benchmarks (BENCHMARKS.md,
    /// session 38).
    pub(crate) fn residual_lanes<const N: usize>(
        &self,
        points: &[Point; N],
        starts: &[f64; N],
        steps: usize,
        done_below: f64,
    ) -> [(f64, Vec2); N] {
        let mut u = *starts;
        let mut done = [false; N];
        for _ in 0..steps {
            for k in 0..N {
                if done[k] {
                    continue;
                }
                let r = self.eval(u[k]) - points[k].to_vec2();
                let d1 = self.deriv(u[k]);
                let d2 = 2.0 * self.c2 + 6.0 * u[k] * self.c3;
                let denom = d1.dot(d1) + r.dot(d2);
                if denom <= 1e-300 {
                    done[k] = true;
                    continue;
                }
                let next = (u[k] - r.dot(d1) / denom).clamp(0.0, 1.0);
                done[k] = (next - u[k]).abs() < done_below;
                u[k] = next;
            }
            if done.iter().all(|&d| d) {
                break;
            }
        }
        std::array::from_fn(|k| (u[k], self.eval(u[k]) - points[k].to_vec2()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{ParamCurve, ParamCurveDeriv};

    /// The power form gives kurbo's points, derivatives and sub-segments, and its blend is
    /// the power form of the blended control points (to rounding).
    #[test]
    fn agrees_with_kurbo() {
        let a = CubicBez::new((0.0, 0.0), (30.0, 90.0), (80.0, -40.0), (120.0, 10.0));
        let b = CubicBez::new((10.0, 5.0), (20.0, 70.0), (95.0, -10.0), (100.0, 40.0));
        let (pa, pb) = (PowerCubic::new(&a), PowerCubic::new(&b));
        let close = |v: Vec2, w: Vec2| (v - w).hypot() < 1e-11;
        for i in 0..=20 {
            let u = i as f64 / 20.0;
            assert!(close(pa.eval(u), a.eval(u).to_vec2()), "{u}");
            assert!(close(pa.deriv(u), a.deriv().eval(u).to_vec2()), "{u}");
        }
        let run = a.subsegment(0.2..0.7);
        let ours = pa.subsegment(0.2, 0.7);
        for (p, q) in [run.p0, run.p1, run.p2, run.p3].iter().zip(ours) {
            assert!(close(p.to_vec2(), q));
        }
        let lambda = 0.3;
        let mixed = |p: Point, q: Point| p.lerp(q, lambda);
        let blended = PowerCubic::new(&CubicBez::new(
            mixed(a.p0, b.p0),
            mixed(a.p1, b.p1),
            mixed(a.p2, b.p2),
            mixed(a.p3, b.p3),
        ));
        let ours = pa.blend(&pb, lambda);
        for i in 0..=10 {
            let u = i as f64 / 10.0;
            assert!(close(ours.eval(u), blended.eval(u)), "{u}");
        }
        // Along a run, expanded about its start.
        let along = pa.along(0.25, 0.5);
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            assert!(close(along.eval(s), pa.eval(0.25 + 0.5 * s)), "{s}");
        }
    }

    /// A projection lands on the nearest point: the residual is normal to the curve there,
    /// and the distance is that of a point placed at a known normal offset.
    #[test]
    fn projects_onto_the_nearest_point() {
        let cubic = CubicBez::new((0.0, 0.0), (30.0, 90.0), (80.0, -40.0), (120.0, 10.0));
        let poly = PowerCubic::new(&cubic);
        for u in [0.1, 0.35, 0.6, 0.9] {
            let normal = poly.deriv(u).turn_90().normalize();
            let p = (poly.eval(u) + 0.75 * normal).to_point();
            let (found, distance) = poly.project(p, u + 0.05);
            assert!((found - u).abs() < 1e-9, "{found} against {u}");
            assert!((distance - 0.75).abs() < 1e-9, "{distance}");
        }
        // Beyond an end, from a start near it: clamped there.
        let (found, distance) = poly.project(Point::new(-3.0, -4.0), 0.02);
        assert_eq!(found, 0.0);
        assert!((distance - 5.0).abs() < 1e-12);
    }
}
