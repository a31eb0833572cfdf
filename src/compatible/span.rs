//! The search's trial fit of one span: a cubic per master, with the handles at a smooth
//! join with an already fitted neighbour tied to it, polished jointly.
//!
//! At a join the handles of every master must be one common multiple of the neighbour's
//! (so the blended handles stay collinear at every position). Instead of polishing each
//! master's cubic alone and then moving its handles to a common ratio (which undoes part
//! of the polish and needed a refit of the other handle), the ratio is one unknown shared
//! by the masters and the free handles are the others; one Gauss-Newton polish with
//! Lawson's re-weighting moves all of them towards the cubics whose largest sample
//! distance, over every master, is least.
//!
//! The curve's samples come from a grid per stretch and master ([`StretchGrid`]): the
//! search tries several spans from one start, and the next span's trials run over the
//! same curve, so most samples were taken before. The masters' parts and the polish's
//! arrays are kept from one trial to the next and, on each thread, from one contour to the
//! next ([`TrialBuffers`]), as the static fitter keeps its own.
//!
//! Limits: the polish sees samples only (10 per X-spline segment, more on short spans), so
//! its error is a lower bound; the span is taken on the measure of `super::JointSamples`,
//! never on this one.

use kurbo::{CubicBez, Point, Vec2};

use super::Run;
use crate::fit;
use crate::power::{PowerCubic, NEWTON_DONE};
use crate::xspline::XSpline;

/// Grid points per X-spline segment at the coarsest level.
const GRID_PER_SEGMENT: f64 = 10.0;
/// A span gets at least this many grid steps (a finer level is taken for short spans).
const MIN_STEPS: usize = 4;
/// Finest level: spacing `1 / (GRID_PER_SEGMENT * 2^MAX_LEVEL)`.
const MAX_LEVEL: usize = 12;
/// Most polish rounds.
const ROUNDS: usize = 6;
/// Rounds of plain least squares before Lawson's re-weighting starts.
const LAWSON_FROM: usize = 2;
/// A round that improves the best error by less than this factor ends the polish.
const STALL: f64 = 0.9;
/// After the first round, an error above this multiple of the goal ends the polish (the
/// span is far too long; the search only needs to know that).
const HOPELESS: f64 = 10.0;
/// Once re-weighting has run, an error above this multiple of the goal ends it.
const HOPELESS_LATE: f64 = 2.0;
/// Handles are kept at least this fraction of the chord (a vanishing handle takes the end
/// tangent from the other handle: a hook; a negative one a loop).
const MIN_HANDLE: f64 = 1e-4;
/// Newton steps projecting a sample onto the cubic per round (parameters carry over).
const PROJECT_STEPS: usize = 2;

/// Curve samples of one smooth stretch of one master on uniform grids from its start, each
/// grid point evaluated once per level.
pub(super) struct StretchGrid<'a> {
    run: Run<'a>,
    t0: f64,
    /// Per level: the index of the first point held, and the points from there.
    levels: Vec<(usize, Vec<Option<Point>>)>,
    /// The last span start evaluated: its parameter, point and derivative.
    start: Option<(f64, Point, Vec2)>,
}

/// A span's samples in one master: parameters and points, the span's ends first and
/// last, and the derivatives at the two ends.
#[derive(Default)]
pub(super) struct SpanSamples {
    t: Vec<f64>,
    p: Vec<Point>,
    start: Vec2,
    end: Vec2,
}

impl<'a> StretchGrid<'a> {
    pub(super) fn new(spline: &'a XSpline, t0: f64) -> StretchGrid<'a> {
        StretchGrid {
            run: Run::new(spline),
            t0,
            levels: Vec::new(),
            start: None,
        }
    }

    /// The samples of `[a, b]`, written to `out`: its ends, and the grid points of the
    /// coarsest level with at least [`MIN_STEPS`] steps in the span, except those within a
    /// quarter step of an end.
    pub(super) fn samples(&mut self, a: f64, b: f64, out: &mut SpanSamples) {
        // The search's trials share their start.
        let (pa, start) = match self.start {
            Some((at, p, d)) if at == a => (p, d),
            _ => {
                let (p, d) = self.run.eval_deriv(a);
                self.start = Some((a, p, d));
                (p, d)
            }
        };
        let h = b - a;
        let level = (0..=MAX_LEVEL)
            .find(|&l| h * GRID_PER_SEGMENT * (1u64 << l) as f64 >= MIN_STEPS as f64);
        let (t, p) = (&mut out.t, &mut out.p);
        t.clear();
        p.clear();
        t.push(a);
        p.push(pa);
        match level {
            Some(level) => {
                let per = GRID_PER_SEGMENT * (1u64 << level) as f64;
                let first = ((a - self.t0) * per + 0.25).ceil().max(0.0) as usize;
                let last = ((b - self.t0) * per - 0.25).floor().max(0.0) as usize;
                if self.levels.len() <= level {
                    self.levels.resize_with(level + 1, || (0, Vec::new()));
                }
                let (origin, points) = &mut self.levels[level];
                // The window moves forward with the search; a jump back starts it again.
                if points.is_empty() || first < *origin || first > *origin + points.len() {
                    *origin = first;
                    points.clear();
                }
                if last + 1 > *origin + points.len() {
                    points.resize(last + 1 - *origin, None);
                }
                for k in first..=last {
                    let at = self.t0 + k as f64 / per;
                    let run = &mut self.run;
                    let point = *points[k - *origin].get_or_insert_with(|| run.eval_deriv(at).0);
                    t.push(at);
                    p.push(point);
                }
            }
            None => {
                // Shorter than the finest grid resolves: uniform samples of its own.
                for i in 1..MIN_STEPS {
                    let at = a + h * i as f64 / MIN_STEPS as f64;
                    t.push(at);
                    p.push(self.run.eval_deriv(at).0);
                }
            }
        }
        let (pb, end) = self.run.eval_deriv(b);
        t.push(b);
        p.push(pb);
        (out.start, out.end) = (start, end);
    }
}

/// One handle of one master's cubic: its unit direction (out of the start, or into the
/// end) and how its length is set.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Handle {
    pub(super) direction: Vec2,
    /// `None`: free; `Some(unit)`: the length is a factor shared by every master times
    /// `unit` (the neighbour's handle length in this master).
    pub(super) shared: Option<f64>,
    /// The length to start from.
    pub(super) length: f64,
}

/// One master's part of a joint span fit.
#[derive(Default)]
pub(super) struct Part {
    pub(super) samples: SpanSamples,
    pub(super) start: Handle,
    pub(super) end: Handle,
}

impl SpanSamples {
    /// The curve's derivative at the span's start and end.
    pub(super) fn end_derivs(&self) -> (Vec2, Vec2) {
        (self.start, self.end)
    }

    /// The span's end points.
    fn ends(&self) -> (Point, Point) {
        (self.p[0], self.p[self.p.len() - 1])
    }
}

/// The unknowns of a joint fit: one per free handle, one per shared factor; and where
/// each master's handle lengths come from.
#[derive(Default)]
struct Unknowns {
    values: Vec<f64>,
    /// Lower bound of each unknown.
    floors: Vec<f64>,
    /// Upper bound of each unknown: no master's handle reaches past the other end of its
    /// cubic along the chord ([`fit::handle_ceiling`]).
    ceilings: Vec<f64>,
    /// Per master, (unknown, scale) of its start and its end handle.
    slots: Vec<[(usize, f64); 2]>,
}

impl Unknowns {
    /// The unknowns of `parts`, written over `self`'s.
    fn set(&mut self, parts: &[Part]) {
        self.values.clear();
        self.floors.clear();
        self.ceilings.clear();
        self.slots.clear();
        // The shared factor of each side, once created.
        let mut shared: [Option<usize>; 2] = [None, None];
        for part in parts {
            let (p0, p3) = part.samples.ends();
            let floor = MIN_HANDLE * p0.distance(p3);
            let mut slot = [(0, 1.0); 2];
            for (side, handle) in [part.start, part.end].iter().enumerate() {
                let cap = fit::handle_ceiling(handle.direction, p3 - p0);
                slot[side] = match handle.shared {
                    None => {
                        self.values.push(handle.length);
                        self.floors.push(floor);
                        self.ceilings.push(cap);
                        (self.values.len() - 1, 1.0)
                    }
                    Some(unit) => {
                        let k = *shared[side].get_or_insert_with(|| {
                            self.values.push(0.0);
                            self.floors.push(0.0);
                            self.ceilings.push(f64::INFINITY);
                            self.values.len() - 1
                        });
                        if unit > 0.0 {
                            // Every master's start length is the factor times its unit.
                            self.values[k] = handle.length / unit;
                            self.floors[k] = self.floors[k].max(floor / unit);
                            self.ceilings[k] = self.ceilings[k].min(cap / unit);
                        }
                        (k, unit)
                    }
                };
            }
            self.slots.push(slot);
        }
        for k in 0..self.values.len() {
            self.values[k] = self.bounded(k, self.values[k]);
        }
    }

    /// `value` within unknown `k`'s bounds (its floor wins where the masters' bounds cross).
    fn bounded(&self, k: usize, value: f64) -> f64 {
        value.min(self.ceilings[k]).max(self.floors[k])
    }

    fn cubic(&self, part: &Part, j: usize, values: &[f64]) -> CubicBez {
        let (p0, p3) = part.samples.ends();
        let [(ka, sa), (kb, sb)] = self.slots[j];
        CubicBez::new(
            p0,
            p0 + part.start.direction * (values[ka] * sa),
            p3 - part.end.direction * (values[kb] * sb),
            p3,
        )
    }
}

/// The buffers of the search's trials: the masters' parts and the polish's arrays, kept
/// from one trial to the next and, on each thread, from one contour to the next
/// ([`TrialBuffers::take`], [`TrialBuffers::keep`]). Only their capacity carries over:
/// each is cleared or overwritten before it is read.
#[derive(Default)]
pub(super) struct TrialBuffers {
    /// One part per master, filled by the caller before [`TrialBuffers::fit_joint`].
    pub(super) parts: Vec<Part>,
    unknowns: Unknowns,
    params: Vec<f64>,
    weights: Vec<f64>,
    values: Vec<f64>,
    normal: Vec<f64>,
    rhs: Vec<f64>,
    best: Vec<f64>,
    step: Vec<f64>,
}

thread_local! {
    static TRIAL_BUFFERS: std::cell::RefCell<TrialBuffers> = std::cell::RefCell::default();
}

impl TrialBuffers {
    /// This thread's buffers of the last contour (empty on a thread's first).
    pub(super) fn take() -> TrialBuffers {
        TRIAL_BUFFERS.with(|b| b.take())
    }

    /// Hands the buffers back to this thread, for the next contour.
    pub(super) fn keep(self) {
        TRIAL_BUFFERS.with(|b| b.replace(self));
    }

    /// Fits one cubic per master to the parts' samples (exact ends, the given handle
    /// directions), the lengths polished towards the least largest sample distance over all
    /// masters. Returns the cubics and that distance (a lower bound of the error). The
    /// polish stops early after a round whose error is below `low` (the span is clearly
    /// short), far above `goal`, or no longer improving.
    pub(super) fn fit_joint(&mut self, goal: f64, low: f64) -> (Vec<CubicBez>, f64) {
        let TrialBuffers {
            parts,
            unknowns,
            params,
            weights,
            values,
            normal,
            rhs,
            best,
            step,
        } = self;
        unknowns.set(parts);
        let n = unknowns.values.len();
        // Per sample of every master in turn: its cubic parameter (carried over between
        // rounds) and its weight.
        let total: usize = parts.iter().map(|p| p.samples.t.len()).sum();
        params.clear();
        for part in parts.iter() {
            let t = &part.samples.t;
            let (a, b) = (t[0], t[t.len() - 1]);
            params.extend(t.iter().map(|x| (x - a) / (b - a)));
        }
        weights.clear();
        weights.resize(total, 1.0 / total as f64);
        values.clear();
        values.extend_from_slice(&unknowns.values);
        normal.clear();
        normal.resize(n * n, 0.0);
        rhs.clear();
        rhs.resize(n, 0.0);
        // The best values so far, their error and the Gauss-Newton step from them.
        best.clear();
        best.extend_from_slice(values);
        let mut best_error = f64::INFINITY;
        step.clear();
        step.resize(n, 0.0);
        let mut damping = 1.0;
        for round in 0..ROUNDS {
            normal.fill(0.0);
            rhs.fill(0.0);
            // The worst squared sample distance: the plain rounds need no square root.
            let mut worst2: f64 = 0.0;
            let mut sum = 0.0;
            let mut offset = 0;
            for (j, part) in parts.iter().enumerate() {
                let poly = PowerCubic::new(&unknowns.cubic(part, j, values));
                let [(ka, sa), (kb, sb)] = unknowns.slots[j];
                let (da, db) = (part.start.direction, part.end.direction);
                let count = part.samples.p.len();
                let inner = offset + 1..offset + count - 1;
                // This master's terms, added in the same order as into the system itself.
                let (mut ra, mut rb) = (rhs[ka], rhs[kb]);
                let [mut naa, mut nab, mut nba, mut nbb] = [
                    normal[ka * n + ka],
                    normal[ka * n + kb],
                    normal[kb * n + ka],
                    normal[kb * n + kb],
                ];
                let samples = &part.samples.p[1..count - 1];
                let weights = &mut weights[inner.clone()];
                // Interleaved ([`PowerCubic::project_all`]); summed in the samples' order.
                let newton = (PROJECT_STEPS, NEWTON_DONE);
                poly.project_all(
                    &mut params[inner],
                    |k| samples[k],
                    newton,
                    |k, u, r| {
                        let dist2 = r.hypot2();
                        worst2 = worst2.max(dist2);
                        let weight = &mut weights[k];
                        if round >= LAWSON_FROM {
                            *weight *= dist2.sqrt();
                        }
                        sum += *weight;
                        if dist2 <= 0.0 {
                            return;
                        }
                        // How the distance changes with each handle length (along the residual
                        // `r / |r|`), times `|r|` so that no root is taken: `j = g / |r|`, and
                        // the sums are `w j j = (w / |r|^2) g g` and `w j |r| = w g`.
                        let v = 1.0 - u;
                        let ga = 3.0 * v * v * u * r.dot(da) * sa;
                        let gb = -3.0 * v * u * u * r.dot(db) * sb;
                        let w = *weight;
                        let scaled = w / dist2;
                        ra += w * ga;
                        rb += w * gb;
                        naa += scaled * ga * ga;
                        nab += scaled * ga * gb;
                        nba += scaled * gb * ga;
                        nbb += scaled * gb * gb;
                    },
                );
                (rhs[ka], rhs[kb]) = (ra, rb);
                normal[ka * n + ka] = naa;
                normal[ka * n + kb] = nab;
                normal[kb * n + ka] = nba;
                normal[kb * n + kb] = nbb;
                offset += count;
            }
            let worst = worst2.sqrt();
            if round >= LAWSON_FROM && sum > 0.0 {
                weights.iter_mut().for_each(|w| *w /= sum);
            }
            if worst < best_error {
                let stalled = best_error.is_finite() && worst > STALL * best_error;
                let hopeless = (round >= 1 && worst > HOPELESS * goal)
                    || (round > LAWSON_FROM && worst > HOPELESS_LATE * goal);
                solve(normal, rhs, n, step);
                best.copy_from_slice(values);
                best_error = worst;
                damping = 1.0;
                if stalled || hopeless || (round >= 1 && worst < low) {
                    break;
                }
            } else {
                damping *= 0.25;
            }
            for k in 0..n {
                values[k] = unknowns.bounded(k, best[k] - damping * step[k]);
            }
        }
        let cubics = parts
            .iter()
            .enumerate()
            .map(|(j, part)| unknowns.cubic(part, j, best))
            .collect();
        (cubics, best_error)
    }
}

/// Solves the small symmetric system `a x = b` (`n` × `n`, row-major) by Gaussian
/// elimination with partial pivoting; an unknown whose pivot vanishes gets 0.
/// (Hand-written: at most a few unknowns, and no linear-algebra crate is a dependency.)
fn solve(a: &mut [f64], b: &mut [f64], n: usize, x: &mut [f64]) {
    let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let tiny = 1e-14 * scale;
    // Columns whose pivot vanished: bit `col` set.
    let mut skipped = 0u64;
    for col in 0..n {
        let row = (col..n)
            .max_by(|&r, &s| a[r * n + col].abs().total_cmp(&a[s * n + col].abs()))
            .unwrap_or(col);
        if a[row * n + col].abs() <= tiny {
            skipped |= 1 << col.min(63);
            continue;
        }
        if row != col {
            for k in 0..n {
                a.swap(row * n + k, col * n + k);
            }
            b.swap(row, col);
        }
        for r in col + 1..n {
            let f = a[r * n + col] / a[col * n + col];
            if f != 0.0 {
                for k in col..n {
                    a[r * n + k] -= f * a[col * n + k];
                }
                b[r] -= f * b[col];
            }
        }
    }
    for col in (0..n).rev() {
        if skipped & (1 << col.min(63)) != 0 {
            x[col] = 0.0;
            continue;
        }
        let mut v = b[col];
        for k in col + 1..n {
            v -= a[col * n + k] * x[k];
        }
        x[col] = v / a[col * n + col];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_small_system_and_skips_a_vanishing_pivot() {
        let mut a = vec![4.0, 1.0, 1.0, 3.0];
        let mut b = vec![1.0, 2.0];
        let mut x = [0.0; 2];
        solve(&mut a, &mut b, 2, &mut x);
        assert!((x[0] - 1.0 / 11.0).abs() < 1e-15 && (x[1] - 7.0 / 11.0).abs() < 1e-15);
        let mut a = vec![2.0, 0.0, 0.0, 0.0];
        let mut b = vec![4.0, 1.0];
        solve(&mut a, &mut b, 2, &mut x);
        assert_eq!(x, [2.0, 0.0]);
    }
}
