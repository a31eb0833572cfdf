//! X-spline -> cubic Béziers within a tolerance, measured against the true curve.
//!
//! A closed contour is cut at its sharp points (`s = 0`) and cusps into smooth stretches; a
//! segment between two sharp points is a straight edge and becomes a `LineTo`. Each smooth
//! stretch is covered greedily from its start with the longest span one cubic fits; the
//! span is predicted from the error law `err ~ h^p` rather than bisected, on the cheap
//! sampled error of each trial; only the candidate about to be taken is measured (below),
//! and one that fails the measure counts as a span that does not fit. The trials of a
//! stretch sample the curve on shared grids (each point evaluated once), and the measure
//! takes a trial's samples as every second one of its own, with their projections from
//! the polish. A join that falls within a few tolerances of an x or y extreme of the curve
//! is moved onto it, or back from it so that the extrema pass can split the next cubic
//! there: a sliver between a join and an extreme is too short to split off, and its rounded
//! handle would turn the curve back. A cubic keeps the curve's end points and exact end
//! tangent directions (G1 joins; at a sharp point the true
//! limit direction, which avoids hooks). It starts as the span's Hermite cubic and its two
//! handle lengths are taken towards the minimax fit by Gauss-Newton on orthogonal
//! distances with Lawson re-weighting, each between a floor (no vanishing handle) and a
//! ceiling (none reaching past the other end along the chord: a folded control polygon
//! dips behind the end, a hook once on the grid).
//!
//! The error of a candidate is bounded both ways at once: each curve sample is projected
//! onto the cubic, and between samples the curve's Hermite piece is paired with the cubic
//! run between the two projections; the largest gap of the pairs (a cubic polynomial,
//! bounded with its exact second derivative) bounds the distance in both directions. Where
//! that bound is over the goal, the old estimate decides: every near-maximal sampled peak
//! refined between samples by golden sections, in both directions. The top peaks are
//! re-checked on the true curve. The curve samples are uniform in the parameter and refined
//! where the curve turns fast, so a narrow spike cannot hide between two of them.
//! Candidates are accepted at 96 % of the tolerance; the tests check the bound by dense
//! sampling.
//!
//! Limits: the bound is proven against the samples' Hermite interpolant, whose own error
//! (O(h^4) at 20 samples per segment) is covered only by the spot checks on the true curve,
//! not proven. Seed hunts over 4,000 random contours of the proptest's distribution
//! (`cargo run --release --example hunt -- 2000 SEED`, seeds 8120261 and 5550402),
//! checked with the tests' dense two-sided checker, measured at most 0.9600 of the
//! tolerance at this acceptance (earlier builds: at most 0.961; 0.990 when accepting at
//! 99 %).

use kurbo::{BezPath, CubicBez, CurveFitSample, ParamCurveFit, Point, Vec2};

use crate::power::{PowerCubic, LANES, NEWTON_DONE};
use crate::xspline::{Segment, XSpline};

/// Curve samples per unit of parameter (one X-spline segment) when measuring a span.
pub(crate) const SAMPLES_PER_SEGMENT: f64 = 20.0;
/// Fewest curve samples per measured span.
pub(crate) const MIN_SAMPLES: usize = 12;
/// Most the curve may turn (radians) between two samples before one is added between them.
pub(crate) const MAX_TURN: f64 = 0.35;
/// Shortest handle, as a fraction of the cubic's chord.
const MIN_HANDLE: f64 = 1e-4;
/// Most bisections of one sample step when the curve turns fast.
pub(crate) const MAX_REFINE: usize = 8;
/// Fraction of the tolerance a candidate must meet by measurement.
pub(crate) const SAFETY: f64 = 0.96;
/// The span search stops when the longest fitting span is known within this ratio.
const SPAN_PRECISION: f64 = 1.05;
/// A fitting span whose error is at least this fraction of the goal is taken as the
/// longest (with err ~ h^5 it is within about 1 % of it).
const NEAR_GOAL: f64 = 0.5;
/// Most fits tried per output cubic before falling back to halving.
pub(crate) const MAX_TRIES: usize = 12;
/// Sampled error peaks at least this fraction of the largest are refined between samples.
const PEAK: f64 = 0.6;
/// Refined peaks at least this fraction of the largest are also checked on the true curve.
const EXACT_PEAK: f64 = 0.9;
/// Gauss-Newton rounds when polishing a cubic's handles.
const POLISH_ROUNDS: usize = 6;
/// Curve samples per unit of parameter when polishing a candidate (the measure takes
/// [`SAMPLES_PER_SEGMENT`]).
const POLISH_SAMPLES_PER_SEGMENT: f64 = 10.0;
/// Fewest grid steps per trial span of [`fit_contour`]'s search: polishing costs in
/// proportion to the samples, and most spans are short enough that this minimum sets their
/// number (6 cost 3 % more instructions on the corpus, for the same cubic count).
const MIN_GRID_STEPS: usize = 4;
/// A trial span short of the stretch's end whose worst sample distance falls below this
/// fraction of [`NEAR_GOAL`] (after [`LOW_ROUND`] rounds) stops polishing: it fits, but is
/// too short to be taken, and only steers the span search (the polish only lowers it).
const LOW_EXIT: f64 = 0.8;
/// Polish rounds before a short trial may stop by [`LOW_EXIT`].
const LOW_ROUND: usize = 1;
/// The next cubic's first span is the last one scaled by `(target / err)^GUESS_POWER`
/// (the error law `err ~ h^5`, aimed at the search's target), within [`GUESS_RANGE`].
const GUESS_POWER: f64 = 0.2;
/// Bounds of that scale.
const GUESS_RANGE: (f64, f64) = (0.8, 1.25);
/// Projections for pairings ([`project_loose`]) stop when a Newton step moves the
/// parameter less than this (the distance is then off by about its square).
const PAIRING_NEWTON_DONE: f64 = 1e-5;
/// [`fit_contour`]'s trials stop projecting a sample once a Newton step moves it less than
/// this: Newton converges quadratically, so the parameter is then within about its square
/// (1e-10), and the distance, stationary there, within far less (on the corpus, 2 % fewer
/// instructions and the same cubic count).
const TRIAL_NEWTON_DONE: f64 = 1e-5;
/// Rounds of plain least squares before Lawson's minimax re-weighting starts.
const LAWSON_AFTER: usize = 3;
/// The polish of [`fit_contour`]'s trials stops when a better round still leaves the worst
/// sample distance above this fraction of the best before it (progress has stalled; on the
/// corpus 0.90 against 0.97 saves 3 % of instructions for 2 more cubics; 0.8 made 14 more).
const TRIAL_STALLED: f64 = 0.90;
/// The polish gives up on a span whose worst sample distance is still this many goals
/// after the first Gauss-Newton step (far out of reach: a shorter span is needed).
const HOPELESS_START: f64 = 10.0;
/// The polish gives up on a span whose worst sample distance is still this many goals
/// once the minimax re-weighting starts (on the corpus, 1.5 from round 2 cost 2 % more
/// cubics).
const HOPELESS_MINIMAX: f64 = 2.0;

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
    Edge {
        /// Global parameter of the sharp point the edge ends at.
        end: f64,
    },
    /// A smooth run `[start, end]` (global `T`, `end` may exceed `n`; it wraps), free of
    /// sharp points and cusps inside.
    Smooth {
        /// Global parameter where the run starts.
        start: f64,
        /// Global parameter where the run ends.
        end: f64,
    },
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

/// Fits one closed X-spline with cubics and lines within `tolerance` (font units). A
/// tolerance below [`XSpline::min_tolerance`] (zero, negative and NaN included) is raised
/// to it.
pub fn fit_contour(spline: &XSpline, tolerance: f64) -> ContourFit {
    let tolerance = tolerance.max(spline.min_tolerance());
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
    // The first span tried is the last one that fitted (curvature changes slowly); on a
    // new contour, one segment (the whole stretch as a first try cost a trial per contour).
    let mut guess = 1.0;
    let mut fit = StretchFit::with_thread_buffers(spline, tolerance * SAFETY);
    for piece in pieces {
        match piece {
            Stretch::Edge { end } => path.line_to(spline.eval(end)),
            Stretch::Smooth { start, end } => {
                let err = fit_stretch(&mut fit, start, end, &mut guess, &mut path);
                max_error = max_error.max(err);
            }
        }
    }
    fit.keep_buffers();
    path.close_path();
    ContourFit { path, max_error }
}

/// A smooth stretch as a [`ParamCurveFit`] source on `[0, 1]`, so kurbo's fitters
/// (`fit_to_bezpath`, `fit_to_bezpath_opt`) can be run on exactly the same curve: the
/// reference for segment counts and speed in the tests and benches.
pub struct StretchSource<'a> {
    /// The contour.
    pub spline: &'a XSpline,
    /// Global parameter of the stretch's start (maps to 0).
    pub start: f64,
    /// Global parameter of the stretch's end (maps to 1).
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
///
/// The 32 per segment are taken only where the curve turns: the derivative is first
/// sampled at every [`CUSP_COARSE`]-th of them, and only a coarse step over which it turns
/// by more than [`CUSP_TURN`] (or vanishes at an end) is sampled finely. A reversal
/// within a coarse step that the coarse samples do not see would need the derivative to
/// turn by more than 90° and back by 45° within an eighth of a segment: a tight S-bend, not
/// a cusp, which the full scan took for two (on 200,000 random contours of up to 43 points,
/// with mixed `s`, near-coincident and near-collinear points, 121 gave other cusps than the
/// full scan, each missing such a pair). Such a bend is then fitted through, within the
/// same measured bound.
fn cusps(spline: &XSpline, t0: f64, t1: f64) -> Vec<f64> {
    let steps = ((t1 - t0) * 32.0).round().max(1.0) as usize;
    let at = |i: usize| t0 + (t1 - t0) * i as f64 / steps as f64;
    let mut found = Vec::new();
    let mut cursor = Cursor::new(spline);
    let cos = CUSP_TURN.cos();
    let mut coarse = 0;
    let mut dcoarse = cursor.eval_deriv(at(0)).1;
    while coarse < steps {
        let next = (coarse + CUSP_COARSE).min(steps);
        let dnext = cursor.eval_deriv(at(next)).1;
        let norms = dcoarse.hypot() * dnext.hypot();
        let (dstart, dend) = (dcoarse, dnext);
        let range = (coarse, next);
        (coarse, dcoarse) = (next, dnext);
        if norms > 0.0 && dstart.dot(dend) >= cos * norms {
            continue;
        }
        let mut dhi = dstart;
        for i in range.0..range.1 {
            let (mut lo, mut hi) = (at(i), at(i + 1));
            let dlo = dhi;
            dhi = if i + 1 == range.1 {
                dend
            } else {
                cursor.eval_deriv(hi).1
            };
            if dlo.dot(dhi) >= 0.0 {
                continue;
            }
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if cursor.eval_deriv(mid).1.dot(dlo) > 0.0 {
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
    }
    found
}

/// Fine cusp-scan steps per coarse step of [`cusps`].
const CUSP_COARSE: usize = 4;
/// Turn of the derivative over a coarse step of [`cusps`] (radians) above which the step
/// is scanned finely.
const CUSP_TURN: f64 = std::f64::consts::FRAC_PI_4;

/// Fits the stretch `[t0, t1]` (global parameters, may exceed `n`; wrapped when evaluated),
/// appending cubics to `path`; returns the largest measured error.
///
/// Each cubic covers the longest span from the current start that fits ([`SpanSearch`]).
/// The search runs on the polish's sampled error (a lower bound); only a candidate about
/// to be taken is measured ([`measure`]), and one that fails the measure counts as a span
/// that does not fit.
fn fit_stretch(fit: &mut StretchFit, t0: f64, t1: f64, guess: &mut f64, path: &mut BezPath) -> f64 {
    fit.stretch(t0, t1);
    let (spline, goal) = (fit.spline, fit.goal);
    let mut max_error: f64 = 0.0;
    let mut a = t0;
    // The direction at the start of the next cubic (the previous one's end direction).
    let mut d0 = direction(spline, a, t0, t1);
    while t1 - a > 1e-12 * (1.0 + t1.abs()) {
        let rest = t1 - a;
        // A stretch at most [`WHOLE_FIRST`] spans long is tried whole first: between two
        // corners the whole stretch is usually one cubic, and a first try at `guess` would
        // cost a trial and could settle on a span just short of the end (two cubics).
        let first = if a == t0 && rest <= WHOLE_FIRST * guess.max(1.0) {
            rest
        } else {
            guess.min(rest)
        };
        // The longest span that fitted: (span, trial, error, whether it was measured).
        let mut fits: Option<(f64, Trial, f64, bool)> = None;
        let mut search = SpanSearch::new(first, rest, goal);
        for _ in 0..MAX_TRIES {
            let h = search.span();
            let trial = fit.trial(a, a + h, d0, search.low());
            let taken = search.takes(trial.sampled);
            let err = if taken {
                fit.measure(&trial)
            } else {
                trial.sampled
            };
            if err <= goal {
                if let Some((.., old, _, _)) = fits.replace((h, trial, err, taken)) {
                    fit.recycle(old);
                }
                if taken {
                    break;
                }
            } else {
                fit.recycle(trial);
            }
            if search.next(err).is_none() {
                break;
            }
        }
        let (h, fails) = (search.span(), search.fails());
        let (h, cubic, err) = match fits {
            Some((h, trial, err, true)) => (h, fit.recycle(trial), err),
            Some((h, trial, _, false)) => {
                let err = fit.measure(&trial);
                let cubic = fit.recycle(trial);
                if err <= goal {
                    (h, cubic, err)
                } else {
                    fit.shortest(a, 0.5 * h, d0)
                }
            }
            None => fit.shortest(a, h, d0),
        };
        let (h, cubic, err) = if h < rest && rest - h < SLIVER * rest {
            fit.whole_rest(a, d0).unwrap_or((h, cubic, err))
        } else {
            (h, cubic, err)
        };
        // A join that fell within a few tolerances of an extreme moves onto it.
        let (h, cubic, err, level) = if h < rest {
            fit.at_extreme(a, a + h, d0, fails)
                .unwrap_or((h, cubic, err, None))
        } else {
            (h, cubic, err, None)
        };
        path.curve_to(cubic.p1, cubic.p2, cubic.p3);
        max_error = max_error.max(err);
        // A span cut short by the stretch's end says nothing about the next one. Otherwise
        // the next first try is this span, corrected by the error law for how far its
        // error was from the search's target.
        if h < rest || h > *guess {
            let target = SpanSearch::target(goal);
            *guess = if err > 0.0 {
                h * (target / err)
                    .powf(GUESS_POWER)
                    .clamp(GUESS_RANGE.0, GUESS_RANGE.1)
            } else {
                h
            };
        }
        a += h;
        d0 = direction(spline, a, t0, t1);
        if let Some(axis) = level {
            d0 = level_direction(d0, axis);
        }
    }
    max_error
}

/// The search for the longest span from a start that one cubic fits, trial by trial (the
/// static fitter's, and the compatible fitter's on its joint error): each trial's error
/// predicts the next span from the error law `err ~ h^p` (`p` from the last two trials, 5
/// before that), aimed a little inside the goal, and kept between the longest span that
/// fitted and the shortest that did not (halving between them where the prediction leaves
/// that bracket). It stops once the two are within [`SPAN_PRECISION`] of each other, or
/// the next prediction lies within its square root above the longest that fitted. The
/// caller tries each span, measures those [`SpanSearch::takes`], and stops at the first
/// measured span that fits.
pub(crate) struct SpanSearch {
    /// The span to try.
    h: f64,
    /// The rest of the stretch from the start: the longest span there is.
    rest: f64,
    goal: f64,
    /// The longest span that fitted, the shortest that did not.
    fits: Option<f64>,
    fails: Option<f64>,
    /// The last trial's span and error.
    last: Option<(f64, f64)>,
}

impl SpanSearch {
    /// A search starting with span `h` (at most `rest`) for error `goal`.
    pub(crate) fn new(h: f64, rest: f64, goal: f64) -> SpanSearch {
        SpanSearch {
            h,
            rest,
            goal,
            fits: None,
            fails: None,
            last: None,
        }
    }

    /// The error the search aims each prediction at: between [`NEAR_GOAL`] and the goal,
    /// so that it lands on the fitting side.
    pub(crate) fn target(goal: f64) -> f64 {
        0.5 * (1.0 + NEAR_GOAL) * goal
    }

    /// The span to try next (after the search, the last one tried or predicted).
    pub(crate) fn span(&self) -> f64 {
        self.h
    }

    /// The shortest span that did not fit, if any.
    pub(crate) fn fails(&self) -> Option<f64> {
        self.fails
    }

    /// The sampled error below which the trial's polish may stop ([`LOW_EXIT`]): a span
    /// short of the rest with an error that low is too short to be taken; the whole rest
    /// is polished fully.
    pub(crate) fn low(&self) -> f64 {
        if self.h < self.rest {
            LOW_EXIT * NEAR_GOAL * self.goal
        } else {
            0.0
        }
    }

    /// Whether a trial of sampled error `sampled` is to be measured (and taken if it fits):
    /// within the goal and either the whole rest or close to the goal, which with
    /// `err ~ h^5` means close to the longest span.
    pub(crate) fn takes(&self, sampled: f64) -> bool {
        sampled <= self.goal && (self.h >= self.rest || sampled >= NEAR_GOAL * self.goal)
    }

    /// Records the error of the span just tried (measured, or sampled); the next span to
    /// try, or `None` when the longest span that fits is known well enough.
    pub(crate) fn next(&mut self, err: f64) -> Option<f64> {
        let h = self.h;
        if err <= self.goal {
            self.fits = Some(h);
        } else {
            self.fails = Some(h);
        }
        if let (Some(lo), Some(hi)) = (self.fits, self.fails) {
            if hi <= lo * SPAN_PRECISION {
                return None;
            }
        }
        let power = match self.last {
            Some((h0, e0)) if e0 > 0.0 && err > 0.0 && (h / h0 - 1.0).abs() > 1e-3 => {
                ((err / e0).ln() / (h / h0).ln()).clamp(2.0, 8.0)
            }
            _ => 5.0,
        };
        self.last = Some((h, err));
        let mut next = if err > 0.0 {
            h * (SpanSearch::target(self.goal) / err).powf(1.0 / power)
        } else {
            2.0 * h
        };
        next = next.min(self.rest);
        let lo = self.fits.unwrap_or(0.0);
        let hi = self.fails.unwrap_or(f64::INFINITY);
        if !(next > lo && next < hi) {
            next = if hi.is_finite() {
                0.5 * (lo + hi)
            } else {
                self.rest
            };
        }
        if self.fits.is_some() && next <= lo * SPAN_PRECISION.sqrt() {
            return None;
        }
        self.h = next;
        Some(next)
    }
}

/// `d` (a unit vector) made exactly level across `axis` (0: vertical, the tangent at an x
/// extreme; 1: horizontal), so that the handles at a join on an extreme lie exactly on its
/// vertical or horizontal, as the extrema pass sets its own.
fn level_direction(d: Vec2, axis: usize) -> Vec2 {
    if axis == 0 {
        Vec2::new(0.0, d.y.signum())
    } else {
        Vec2::new(d.x.signum(), 0.0)
    }
}

/// How near (in tolerances) a join must be to an extreme of the curve to move onto it:
/// the extrema pass splits a cubic at an extreme only where both pieces are at least
/// `extrema::MIN_PIECE` long, which is 2 to 4 tolerances at the usual 1/2000 to 1/4000 em.
/// Nearer, the extreme was left inside the cubic, a fraction of a unit from its end: a
/// handle past the end's range that FontForge reports as a missing extreme once rounded.
/// The window is half as wide again as that at 1/4000 em: the pass sees the cubic's
/// extreme, which lies up to a tolerance from the X-spline's (at four tolerances, the
/// imported Lato's `e` kept a join 2.0 units past its extreme, whose cubic had it 1.9 units
/// from the end: 30 OTF glyphs flagged).
const NEAR_EXTREME: f64 = 6.0;
/// Largest component across its axis of the unit tangent at a found extreme: beyond, the
/// derivative changed sign by a jump rather than through zero, and the join stays. Within
/// it, setting the handle level moves it by at most this fraction of its length.
const LEVEL: f64 = 1e-9;

/// The root of `f` in `[x0, x1]`, where `f` changes sign (`f0`, `f1` its values at the
/// ends), within 1e-12 of the interval's width (or the parameters' precision): kurbo's ITP
/// solver (bracketed, at most as many steps as bisection and superlinear on smooth
/// functions), which takes `f` rising.
fn root(mut f: impl FnMut(f64) -> f64, (x0, f0): (f64, f64), (x1, f1): (f64, f64)) -> f64 {
    let width = x1 - x0;
    // Never below the parameters' own precision, where the solver would not stop.
    let epsilon = (1e-12 * width).max(8.0 * f64::EPSILON * x0.abs().max(x1.abs()));
    let k1 = 0.2 / width;
    if f0 < 0.0 {
        kurbo::common::solve_itp(f, x0, x1, epsilon, 1, k1, f0, f1)
    } else {
        kurbo::common::solve_itp(|t| -f(t), x0, x1, epsilon, 1, k1, -f0, -f1)
    }
}

/// A stretch up to this many times the expected span (the guess, at least one segment) is
/// tried whole first. Measured on a tenth of the CJK block (13,564 contours, mostly short
/// stretches between corners): 15 % fewer trials and 4 % fewer cubics than trying the
/// guess first; the bench corpus (long smooth stretches) is unchanged at 461 cubics.
const WHOLE_FIRST: f64 = 2.0;

/// A span that ends within this fraction of the stretch's end would leave a sliver: a
/// cubic a millionth of a unit long, which rounds to a zero-length segment in every output.
pub(crate) const SLIVER: f64 = 0.05;

/// The smooth stretch `[t0, t1]` of a contour being fitted: the curve, the polish's shared
/// sample grid and the goal. Every trial of [`fit_stretch`]'s search goes through
/// [`StretchFit::trial`].
///
/// It also keeps the buffers of finished trials and of the measure for reuse, from one
/// stretch to the next: allocating them afresh for each of the thousands of trials was
/// 5 % of the fitter's time.
struct StretchFit<'a> {
    spline: &'a XSpline,
    grid: Grid<'a>,
    t0: f64,
    t1: f64,
    goal: f64,
    spare: Vec<Trial>,
    measure: MeasureBuffers,
}

/// The buffers a [`StretchFit`] grows, kept from one contour to the next on each thread:
/// growing them afresh for every contour was 3 % of the fitter's instructions on the bench
/// corpus (45 contours; a font fits thousands).
#[derive(Default)]
struct FitBuffers {
    spare: Vec<Trial>,
    measure: MeasureBuffers,
    levels: Vec<(usize, Vec<Option<Sample>>)>,
}

thread_local! {
    static FIT_BUFFERS: std::cell::RefCell<FitBuffers> = std::cell::RefCell::default();
}

impl<'a> StretchFit<'a> {
    /// Fitting `spline` within `goal` with this thread's buffers of the last contour (give
    /// them back with [`StretchFit::keep_buffers`]); call [`StretchFit::stretch`] before the
    /// trials. Only the buffers' capacity carries over: each is cleared or overwritten
    /// before it is read.
    fn with_thread_buffers(spline: &'a XSpline, goal: f64) -> StretchFit<'a> {
        let buffers = FIT_BUFFERS.with(|b| b.take());
        Self::with_buffers(spline, goal, buffers)
    }

    /// Fitting `spline` within `goal`, growing `buffers`.
    fn with_buffers(spline: &'a XSpline, goal: f64, buffers: FitBuffers) -> StretchFit<'a> {
        let mut grid = Grid::new(spline, 0.0);
        grid.levels = buffers.levels;
        grid.restart(0.0);
        StretchFit {
            spline,
            grid,
            t0: 0.0,
            t1: 0.0,
            goal,
            spare: buffers.spare,
            measure: buffers.measure,
        }
    }

    /// Hands the buffers back to this thread, for the next contour.
    fn keep_buffers(self) {
        let buffers = FitBuffers {
            spare: self.spare,
            measure: self.measure,
            levels: self.grid.levels,
        };
        FIT_BUFFERS.with(|b| b.replace(buffers));
    }

    /// Moves on to the stretch `[t0, t1]`.
    fn stretch(&mut self, t0: f64, t1: f64) {
        (self.t0, self.t1) = (t0, t1);
        self.grid.restart(t0);
    }

    /// The polished cubic on `[a, b]`, leaving `a` in direction `d0`, sampled on the grid;
    /// `low` as in [`polish`]. Give it back with [`StretchFit::recycle`].
    fn trial(&mut self, a: f64, b: f64, d0: Vec2, low: f64) -> Trial {
        let mut trial = self.spare.pop().unwrap_or_default();
        self.grid.samples(a, b, &mut trial.samples);
        let (t0, t1) = (self.t0, self.t1);
        fit_span_sampled(self.spline, (a, b), &mut trial, d0, t0, t1, self.goal, low);
        trial
    }

    /// Keeps a trial's buffers for the next one; returns its cubic.
    fn recycle(&mut self, trial: Trial) -> CubicBez {
        let cubic = trial.cubic;
        self.spare.push(trial);
        cubic
    }

    /// [`measure_within`] of a trial's cubic.
    fn measure(&mut self, trial: &Trial) -> f64 {
        measure_within(self.spline, trial, self.goal, &mut self.measure)
    }

    /// The cubic for the whole rest `[a, t1]` of the stretch, if it passes the measure.
    fn whole_rest(&mut self, a: f64, d0: Vec2) -> Option<(f64, CubicBez, f64)> {
        let (cubic, err) = self.fits(a, self.t1, d0)?;
        Some((self.t1 - a, cubic, err))
    }

    /// A join `b` that fell within [`NEAR_EXTREME`] tolerances of an x or y extreme `e` of
    /// the curve (inside the stretch, farther than that from both its ends) moves onto it:
    /// the cubic on `[a, e]` when it fits, its handle at `e` set exactly level (the
    /// direction there is level up to the rounding of `e`). Otherwise the join moves back,
    /// twice that distance before `e`, so that the extreme lies far enough inside the next
    /// cubic for the extrema pass to split it there. Returns the span, the cubic, its error
    /// and the axis of a join on an extreme; `None` leaves the join where it is. `failed`
    /// is the shortest span from `a` known not to fit: no longer one is tried.
    fn at_extreme(
        &mut self,
        a: f64,
        b: f64,
        d0: Vec2,
        failed: Option<f64>,
    ) -> Option<(f64, CubicBez, f64, Option<usize>)> {
        let (spline, t1) = (self.spline, self.t1);
        let near = NEAR_EXTREME * self.goal / SAFETY;
        let (pb, db) = spline.eval_deriv(b);
        let speed = db.hypot();
        if speed.is_nan() || speed <= 0.0 {
            return None;
        }
        let (lo, hi) = ((b - near / speed).max(a), (b + near / speed).min(t1));
        let coord = |v: Vec2, axis: usize| if axis == 0 { v.x } else { v.y };
        let mut cursor = Cursor::new(spline);
        let (dlo, dhi) = (cursor.eval_deriv(lo).1, cursor.eval_deriv(hi).1);
        // The root of the derivative's component nearest `b` on either side.
        let mut best: Option<(f64, usize)> = None;
        for axis in [0, 1] {
            let at_b = coord(db, axis);
            for (x0, x1, f0, f1) in [
                (lo, b, coord(dlo, axis), at_b),
                (b, hi, at_b, coord(dhi, axis)),
            ] {
                if f0 == 0.0 || f1 == 0.0 || (f0 > 0.0) == (f1 > 0.0) {
                    continue;
                }
                let e = root(|t| coord(cursor.eval_deriv(t).1, axis), (x0, f0), (x1, f1));
                if best.is_none_or(|(f, _)| (e - b).abs() < (f - b).abs()) {
                    best = Some((e, axis));
                }
            }
        }
        let (e, axis) = best?;
        // A true extreme: the derivative passes through level there. (It may also change
        // sign by a jump where nearly coincident points make the curve nearly sharp.)
        let (pe, de) = cursor.eval_deriv(e);
        if coord(de, axis).abs() > LEVEL * de.hypot() {
            return None;
        }
        let pa = spline.eval(a);
        let far = |p: Point, q: Point| (p - q).hypot() > near;
        if !(far(pa, pe) && far(spline.eval(t1), pe) && !far(pb, pe)) {
            return None;
        }
        let on = if failed.is_some_and(|f| f <= e - a) {
            None
        } else {
            self.fits(a, e, d0)
        };
        if let Some((cubic, err)) = on {
            let mut cubic = cubic;
            if axis == 0 {
                cubic.p2.x = cubic.p3.x;
            } else {
                cubic.p2.y = cubic.p3.y;
            }
            return Some((e - a, cubic, err, Some(axis)));
        }
        let back = e - 2.0 * near / speed;
        if back <= a || !far(pa, spline.eval(back)) {
            return None;
        }
        let (cubic, err) = self.fits(a, back, d0)?;
        Some((back - a, cubic, err, None))
    }

    /// The cubic on `[a, b]` and its measured error, if it fits.
    fn fits(&mut self, a: f64, b: f64, d0: Vec2) -> Option<(CubicBez, f64)> {
        let (cubic, err) = self.measured(a, b, d0);
        (err <= self.goal).then_some((cubic, err))
    }

    /// The polished cubic on `[a, b]` and its error: measured when its samples are within
    /// the goal, else their distance (a lower bound, already over the goal).
    fn measured(&mut self, a: f64, b: f64, d0: Vec2) -> (CubicBez, f64) {
        let trial = self.trial(a, b, d0, 0.0);
        let err = if trial.sampled <= self.goal {
            self.measure(&trial)
        } else {
            trial.sampled
        };
        (self.recycle(trial), err)
    }

    /// Last resort for degenerate geometry: halve the span from `h` until it fits or is
    /// tiny.
    fn shortest(&mut self, a: f64, mut h: f64, d0: Vec2) -> (f64, CubicBez, f64) {
        loop {
            let (cubic, err) = self.measured(a, a + h, d0);
            if err <= self.goal || h < 1e-9 {
                return (h, cubic, err);
            }
            h *= 0.5;
        }
    }
}

/// Tangent direction at `t` inside the stretch `[t0, t1]`, one-sided at the stretch ends
/// (where a sharp point may sit and the derivative vanishes). Always a finite unit vector.
pub(crate) fn direction(spline: &XSpline, t: f64, t0: f64, t1: f64) -> Vec2 {
    direction_with(spline, t, t0, t1, || spline.eval_deriv(t).1)
}

/// [`direction`], with the curve's derivative at `t` from `deriv` (a sample's, when the
/// caller has one: the same value).
fn direction_with(
    spline: &XSpline,
    t: f64,
    t0: f64,
    t1: f64,
    deriv: impl FnOnce() -> Vec2,
) -> Vec2 {
    let n = spline.segment_count();
    let at_knot = (t - t.round()).abs() < 1e-12;
    let exact = if at_knot && (t - t0).abs() < 1e-12 {
        spline.segment((t.round() as usize) % n).start_direction()
    } else if at_knot && (t - t1).abs() < 1e-12 {
        spline
            .segment((t.round() as usize + n - 1) % n)
            .end_direction()
    } else {
        let d = deriv();
        let len = d.hypot();
        if len > 1e-9 * spline.extent() {
            d / len
        } else {
            Vec2::ZERO
        }
    };
    if exact.is_finite() && exact != Vec2::ZERO {
        return exact;
    }
    // At (or next to) a cusp or a sharp point the derivative vanishes: take the one-sided
    // secant direction into the stretch (the curve leaves a cusp quadratically, a sharp
    // point cubically, so a tiny step can move nothing in floating point: widen it).
    let forward = t - t0 < t1 - t;
    for h in [1e-7, 1e-5, 1e-3, 1e-1] {
        let v = if forward {
            spline.eval(t + h) - spline.eval(t)
        } else {
            spline.eval(t) - spline.eval(t - h)
        };
        let len = v.hypot();
        if len > 0.0 && len.is_finite() {
            return v / len;
        }
    }
    let chord = spline.eval(t1) - spline.eval(t0);
    if chord.hypot() > 0.0 {
        chord.normalize()
    } else {
        Vec2::new(1.0, 0.0)
    }
}

/// Evaluates a contour at increasing parameters, keeping the current segment: the same
/// arithmetic as [`XSpline::eval_deriv`] (so the same values, bit for bit) without
/// locating and assembling the segment again for every point of a dense run.
struct Cursor<'a> {
    spline: &'a XSpline,
    index: usize,
    segment: Segment,
}

impl<'a> Cursor<'a> {
    fn new(spline: &'a XSpline) -> Cursor<'a> {
        Cursor {
            spline,
            index: 0,
            segment: spline.segment(0),
        }
    }

    /// Point and derivative at global `T`, wrapped into `[0, n)` like `XSpline::eval`.
    fn eval_deriv(&mut self, big_t: f64) -> (Point, Vec2) {
        let (j, t) = self.spline.locate(big_t);
        if j != self.index {
            self.index = j;
            self.segment = self.spline.segment(j);
        }
        self.segment.eval_deriv(t)
    }
}

/// A curve point and the derivative there.
type Sample = (Point, Vec2);

/// Curve samples of one stretch for the polish, on uniform grids from the stretch's start
/// (one per number of samples per unit), each grid point evaluated once: the span search
/// tries several spans from one start, and the next cubic's trials cover the same curve,
/// so most of a trial's samples were already taken.
struct Grid<'a> {
    cursor: Cursor<'a>,
    t0: f64,
    /// Per level `j` (spacing `1 / (POLISH_SAMPLES_PER_SEGMENT * 2^j)`), the points taken:
    /// a window of grid indices from the first, restarted where a span lands past it (so
    /// a fine level used at two far places of a long stretch holds only one of them).
    levels: Vec<(usize, Vec<Option<Sample>>)>,
    /// The last span start sampled.
    start: Option<(f64, Point, Vec2)>,
}

impl<'a> Grid<'a> {
    fn new(spline: &'a XSpline, t0: f64) -> Grid<'a> {
        Grid {
            cursor: Cursor::new(spline),
            t0,
            levels: Vec::new(),
            start: None,
        }
    }

    /// Forgets the points taken, for a stretch starting at `t0` (keeping the buffers).
    fn restart(&mut self, t0: f64) {
        self.t0 = t0;
        self.start = None;
        for (_, points) in &mut self.levels {
            points.clear();
        }
    }

    /// The polish's samples of `[a, b]`: its two ends (exact curve points), and between
    /// them the points of the coarsest grid that puts at least [`MIN_GRID_STEPS`]
    /// steps in the span, leaving out those within a quarter step of an end (so at least
    /// [`MIN_GRID_STEPS`] steps, the two at the ends at most 1.25 grid steps long).
    fn samples(&mut self, a: f64, b: f64, samples: &mut Samples) {
        samples.clear();
        let h = b - a;
        let mut level = 0;
        let mut per = POLISH_SAMPLES_PER_SEGMENT;
        while h * per < MIN_GRID_STEPS as f64 && level < MAX_GRID_LEVEL {
            level += 1;
            per *= 2.0;
        }
        if h * per < MIN_GRID_STEPS as f64 {
            // Shorter than the finest grid resolves: uniform samples.
            *samples = Samples::new(
                self.cursor.spline,
                a,
                b,
                POLISH_SAMPLES_PER_SEGMENT,
                MIN_GRID_STEPS,
                false,
            );
            return;
        }
        if self.levels.len() <= level {
            self.levels.resize_with(level + 1, || (0, Vec::new()));
        }
        let first = ((a - self.t0) * per + 0.25).ceil().max(0.0) as usize;
        let last = ((b - self.t0) * per - 0.25).floor().max(0.0) as usize;
        // The cursor's point is `XSpline::eval`'s, bit for bit; a span's start is shared by
        // the trials of one search.
        let start = match self.start {
            Some(start) if start.0 == a => start,
            _ => {
                let (p, d) = self.cursor.eval_deriv(a);
                (a, p, d)
            }
        };
        self.start = Some(start);
        samples.push(start);
        let (origin, points) = &mut self.levels[level];
        if points.is_empty() || first < *origin || first > *origin + points.len() {
            *origin = first;
            points.clear();
        }
        if points.len() <= last - *origin {
            points.resize(last - *origin + 1, None);
        }
        for k in first..=last {
            let t = self.t0 + k as f64 / per;
            let (p, d) = *points[k - *origin].get_or_insert_with(|| self.cursor.eval_deriv(t));
            samples.push((t, p, d));
        }
        let (p, d) = self.cursor.eval_deriv(b);
        samples.push((b, p, d));
    }
}

/// Finest polish grid: spacing `1 / (POLISH_SAMPLES_PER_SEGMENT * 2^MAX_GRID_LEVEL)`.
const MAX_GRID_LEVEL: usize = 12;

/// Samples of the curve on one span, with derivatives: enough to measure a cubic against
/// (between samples the curve is taken as the cubic Hermite interpolant, whose error is
/// O(h^4) in the sample step, far below any useful tolerance at this density).
///
/// Uniform in the curve parameter, refined where the curve turns fast: a narrow spike or
/// a tight turn can fit between two uniform samples and hide an error peak there (random
/// contours with thin spikes were fitted 15 % over the tolerance before this). Between
/// consecutive samples the curve turns by less than [`MAX_TURN`].
#[derive(Default)]
struct Samples {
    t: Vec<f64>,
    p: Vec<Point>,
    d: Vec<Vec2>,
}

impl Samples {
    /// Samples `[a, b]` at `per_segment` per unit of parameter, at least `min`; `refined`
    /// adds samples where the curve turns fast (the measure needs them; the polish, whose
    /// error is only a lower bound, does not).
    fn new(
        spline: &XSpline,
        a: f64,
        b: f64,
        per_segment: f64,
        min: usize,
        refined: bool,
    ) -> Samples {
        let n = (((b - a) * per_segment).ceil() as usize).max(min);
        let mut samples = Samples {
            t: Vec::with_capacity(n + 1),
            p: Vec::with_capacity(n + 1),
            d: Vec::with_capacity(n + 1),
        };
        let mut previous: Option<(f64, Point, Vec2)> = None;
        let mut cursor = Cursor::new(spline);
        for i in 0..=n {
            let t = a + (b - a) * i as f64 / n as f64;
            let (mut p, d) = cursor.eval_deriv(t);
            // The ends are exact curve points (no rounding drift in `a + (b - a)`).
            if i == 0 {
                p = spline.eval(a);
            } else if i == n {
                p = spline.eval(b);
            }
            if let Some(start) = previous.filter(|_| refined) {
                samples.refine(&mut cursor, start, (t, p, d), MAX_REFINE);
            }
            samples.push((t, p, d));
            previous = Some((t, p, d));
        }
        samples
    }

    /// The measure's samples from the polish's: each step of the polish's samples cut in
    /// two, or in more where it is longer than `1 / SAMPLES_PER_SEGMENT` (at a span's ends
    /// the grid's step can be a quarter longer), so at most that far apart and at least
    /// [`MIN_SAMPLES`] in all; then refined where the curve turns fast. They are written
    /// to `samples`, and where each of `coarse`'s samples is among them to `at`.
    fn doubled(spline: &XSpline, coarse: &Samples, samples: &mut Samples, at: &mut Vec<usize>) {
        let m = coarse.len() - 1;
        samples.clear();
        at.clear();
        let mut cursor = Cursor::new(spline);
        let mut previous = (coarse.t[0], coarse.p[0], coarse.d[0]);
        samples.push(previous);
        at.push(0);
        for k in 0..m {
            let (t0, t1) = (coarse.t[k], coarse.t[k + 1]);
            // Rounding must not add a piece to a step of exactly the grid's length.
            // At least two, and enough for [`MIN_SAMPLES`] in all (a span of
            // [`MIN_GRID_STEPS`] steps takes three each).
            let pieces = (((t1 - t0) * SAMPLES_PER_SEGMENT - 1e-9).ceil() as usize)
                .max(MIN_SAMPLES.div_ceil(m))
                .max(2);
            for j in 1..=pieces {
                let next = if j == pieces {
                    (t1, coarse.p[k + 1], coarse.d[k + 1])
                } else {
                    let t = t0 + (t1 - t0) * j as f64 / pieces as f64;
                    let (p, d) = cursor.eval_deriv(t);
                    (t, p, d)
                };
                samples.refine(&mut cursor, previous, next, MAX_REFINE);
                samples.push(next);
                previous = next;
            }
            at.push(samples.len() - 1);
        }
    }

    fn clear(&mut self) {
        self.t.clear();
        self.p.clear();
        self.d.clear();
    }

    fn push(&mut self, (t, p, d): (f64, Point, Vec2)) {
        self.t.push(t);
        self.p.push(p);
        self.d.push(d);
    }

    /// Adds the samples strictly between `start` and `end` (already pushed / to be pushed)
    /// that keep the turn between neighbours below [`MAX_TURN`], bisecting at most
    /// `depth` times.
    fn refine(
        &mut self,
        cursor: &mut Cursor,
        start: (f64, Point, Vec2),
        end: (f64, Point, Vec2),
        depth: usize,
    ) {
        if depth == 0 || !turns_fast(start.1, start.2, end.1, end.2) {
            return;
        }
        let t = 0.5 * (start.0 + end.0);
        let (p, d) = cursor.eval_deriv(t);
        let mid = (t, p, d);
        self.refine(cursor, start, mid, depth - 1);
        self.push(mid);
        self.refine(cursor, mid, end, depth - 1);
    }

    fn len(&self) -> usize {
        self.p.len()
    }

    /// The Hermite interpolant between samples `i` and `i + 1` as a cubic Bézier.
    fn piece(&self, i: usize) -> CubicBez {
        let h = (self.t[i + 1] - self.t[i]) / 3.0;
        CubicBez::new(
            self.p[i],
            self.p[i] + self.d[i] * h,
            self.p[i + 1] - self.d[i + 1] * h,
            self.p[i + 1],
        )
    }
}

/// Whether the curve between two samples (points and derivatives) may turn by more than
/// [`MAX_TURN`]: the angle between either derivative and the chord, or between the two
/// derivatives, exceeds it. A vanishing vector says nothing (the derivative at a sharp
/// point at the span's end; stretches are cut at cusps, so there is none inside).
pub(crate) fn turns_fast(p0: Point, d0: Vec2, p1: Point, d1: Vec2) -> bool {
    let chord = p1 - p0;
    let cos = MAX_TURN.cos();
    let apart = |u: Vec2, v: Vec2| {
        let norms = u.hypot() * v.hypot();
        norms > 0.0 && u.dot(v) < cos * norms
    };
    apart(d0, chord) || apart(chord, d1) || apart(d0, d1)
}

/// A polished cubic on a span, with what the measure can take from the polish.
struct Trial {
    cubic: CubicBez,
    /// The largest distance of the polish's samples to `cubic`: a lower bound of the error.
    sampled: f64,
    /// The polish's curve samples (the span's ends first and last).
    samples: Samples,
    /// The samples' parameters on the polish's last cubic (their projections; the ends
    /// are 0 and 1).
    u: Vec<f64>,
    /// Whether that last cubic is `cubic`, so that `u` are its projections.
    projected: bool,
    /// The polish's Lawson weights (a buffer).
    w: Vec<f64>,
}

impl Default for Trial {
    fn default() -> Trial {
        Trial {
            cubic: CubicBez::new(Point::ORIGIN, Point::ORIGIN, Point::ORIGIN, Point::ORIGIN),
            sampled: f64::INFINITY,
            samples: Samples::default(),
            u: Vec::new(),
            projected: false,
            w: Vec::new(),
        }
    }
}

/// Fits one cubic to `span` of the stretch `[t0, t1]`, leaving the span's start in
/// direction `d0`, on `trial`'s samples of it (the span's ends first and last), filling in
/// the rest of `trial`: the cubic and its largest sample distance, a lower bound of the
/// error that [`measure`] establishes; [`measure_within`] takes the samples as every second
/// one of its own, with their projections. The span's Hermite cubic is the start;
/// [`polish`] takes its handles towards the minimax ones (measured on the test corpus: a
/// least-squares start on chord-length parameters needs 5 % more segments; kurbo's
/// area-and-moment `fit_to_cubic` as a second start saves a few percent of segments at
/// twice the time).
#[allow(clippy::too_many_arguments)]
fn fit_span_sampled(
    spline: &XSpline,
    span: (f64, f64),
    trial: &mut Trial,
    d0: Vec2,
    t0: f64,
    t1: f64,
    goal: f64,
    low: f64,
) {
    let samples = &trial.samples;
    let last = samples.len() - 1;
    let (a, b) = span;
    let (p0, p3) = (samples.p[0], samples.p[last]);
    // The grid's last sample is at `b` exactly; `Samples::new`'s may be off by rounding.
    let d1 = direction_with(spline, b, t0, t1, || {
        if samples.t[last] == b {
            samples.d[last]
        } else {
            spline.eval_deriv(b).1
        }
    });
    if samples.p.iter().all(|p| *p == p0) {
        // The span is a single point (a cusp's tip): nothing to fit.
        trial.cubic = CubicBez::new(p0, p0, p3, p3);
        trial.sampled = 0.0;
        trial.projected = false;
        return;
    }
    // The Hermite cubic of the span: handles from the curve's own derivatives; its
    // parameter runs with the curve's, so the samples' parameters start uniform.
    let third = (b - a) / 3.0;
    let alpha = samples.d[0].dot(d0) * third;
    let beta = samples.d[last].dot(d1) * third;
    trial.u.clear();
    trial.u.extend(samples.t.iter().map(|t| (t - a) / (b - a)));
    let (cubic, sampled, projected) = polish(
        samples,
        p0,
        p3,
        (d0, d1),
        (alpha, beta),
        (&mut trial.u, &mut trial.w),
        goal,
        low,
    );
    trial.cubic = cubic;
    trial.sampled = sampled;
    trial.projected = projected;
}

/// Moves the handle lengths towards the minimax fit of the samples: Gauss-Newton on the
/// orthogonal distances, with Lawson's re-weighting after the first rounds (which turns the
/// least-squares optimum into the minimax one). `u` holds the samples' starting cubic
/// parameters, and the last round's projections on return; `w` is a buffer. The span's two
/// end samples are the cubic's own ends (at distance zero, or a rounding of it), so they
/// are not projected and have no weight. Besides its round limit and a hopeless span, the
/// polish stops when progress stalls ([`TRIAL_STALLED`]) and, for a trial short of the
/// stretch's end, once the worst sample distance is below `low` (see [`LOW_EXIT`]; zero
/// polishes fully). Returns the best cubic seen, its largest sample distance, and whether
/// the last round was that cubic's.
#[allow(clippy::too_many_arguments)]
fn polish(
    samples: &Samples,
    p0: Point,
    p3: Point,
    (d0, d1): (Vec2, Vec2),
    (alpha, beta): (f64, f64),
    (u, w): (&mut [f64], &mut Vec<f64>),
    goal: f64,
    low: f64,
) -> (CubicBez, f64, bool) {
    let n = samples.len();
    // The samples strictly inside the span.
    let polished = 1..n.max(2) - 1;
    // Handles never vanish (a zero handle would take the end's tangent from the other
    // handle instead of the curve's: a hook at a sharp point), nor reverse (a loop).
    let floor = MIN_HANDLE * p0.distance(p3);
    let ceiling = |d: Vec2| handle_ceiling(d, p3 - p0).max(floor);
    let (cap0, cap1) = (ceiling(d0), ceiling(d1));
    let (mut alpha, mut beta) = (alpha.clamp(floor, cap0), beta.clamp(floor, cap1));
    w.clear();
    w.resize(n, 1.0 / n as f64);
    // The ends have no weight (in the Lawson rounds theirs would be their distance).
    w[0] = 0.0;
    w[n - 1] = 0.0;
    let cubic_of = |alpha: f64, beta: f64| CubicBez::new(p0, p0 + alpha * d0, p3 - beta * d1, p3);
    // (alpha, beta, worst sample distance, Gauss-Newton step) of the best cubic so far.
    let mut best: Option<(f64, f64, f64, f64, f64)> = None;
    let mut damping = 1.0;
    // Whether `u` holds the projections onto the best cubic.
    let mut current = false;
    for round in 0..POLISH_ROUNDS {
        let poly = PowerCubic::new(&cubic_of(alpha, beta));
        let (mut c00, mut c01, mut c11, mut x0, mut x1) = (0.0, 0.0, 0.0, 0.0, 0.0);
        // The worst squared sample distance: the plain rounds need no square root.
        let mut worst2: f64 = 0.0;
        let lawson = round >= LAWSON_AFTER;
        let inside = &samples.p[polished.clone()];
        let ws = &mut w[polished.clone()];
        // Parameters carry over between rounds, so a couple of steps suffice (interleaved:
        // [`PowerCubic::project_all`]); the sums are added in the samples' order.
        let newton = (3, TRIAL_NEWTON_DONE);
        poly.project_all(
            &mut u[polished.clone()],
            |k| inside[k],
            newton,
            |k, ui, r| {
                let dist2 = r.hypot2();
                worst2 = worst2.max(dist2);
                let w = &mut ws[k];
                if lawson {
                    *w *= dist2.sqrt();
                }
                if dist2 <= 0.0 {
                    return;
                }
                // The Jacobian of the distance along the normal `-r / |r|`, times `|r|` (so
                // that no root is taken): `j = g / |r|`, and the normal equations' sums are
                // `w j j = (w / |r|^2) g g` and `w j |r| = w g`.
                let mt = 1.0 - ui;
                let g0 = -3.0 * mt * mt * ui * r.dot(d0);
                let g1 = 3.0 * mt * ui * ui * r.dot(d1);
                let w = *w;
                let scaled = w / dist2;
                c00 += scaled * g0 * g0;
                c01 += scaled * g0 * g1;
                c11 += scaled * g1 * g1;
                x0 += w * g0;
                x1 += w * g1;
            },
        );
        let worst = worst2.sqrt();
        if round >= LAWSON_AFTER {
            let sum: f64 = w.iter().sum();
            if sum > 0.0 {
                w.iter_mut().for_each(|x| *x /= sum);
            }
        }
        let det = c00 * c11 - c01 * c01;
        let step = if det.abs() > 1e-300 {
            ((x0 * c11 - x1 * c01) / det, (c00 * x1 - c01 * x0) / det)
        } else {
            (0.0, 0.0)
        };
        current = best.is_none_or(|b| worst < b.2);
        if current {
            // Stop when progress stalls, or when the span is clearly out of reach.
            let stalled = best.is_some_and(|b| worst > TRIAL_STALLED * b.2);
            let hopeless = (round >= 1 && worst > HOPELESS_START * goal)
                || (round >= LAWSON_AFTER && worst > HOPELESS_MINIMAX * goal);
            best = Some((alpha, beta, worst, step.0, step.1));
            damping = 1.0;
            if stalled || hopeless || (round >= LOW_ROUND && worst < low) {
                break;
            }
        } else {
            // Worse: step back to the best cubic and take a shorter step from there.
            damping *= 0.25;
        }
        let Some((ba, bb, _, da, db)) = best else {
            break;
        };
        alpha = (ba + damping * da).clamp(floor, cap0);
        beta = (bb + damping * db).clamp(floor, cap1);
    }
    match best {
        Some(b) => (cubic_of(b.0, b.1), b.2, current),
        None => (cubic_of(alpha, beta), f64::INFINITY, false),
    }
}

/// The longest handle in unit `direction` (out of a cubic's start, or into its end) that
/// does not reach past the other end along `chord`: a longer one folds the control polygon
/// back, and the cubic dips behind its own end (a hook once on the grid). Unbounded when
/// the handle does not point along the chord.
pub(crate) fn handle_ceiling(direction: Vec2, chord: Vec2) -> f64 {
    let along = direction.dot(chord);
    if along > 0.0 {
        chord.hypot2() / along
    } else {
        f64::INFINITY
    }
}

/// [`PowerCubic::project`], stopping at a step below [`PAIRING_NEWTON_DONE`]: for
/// pairings, where any parameter gives a valid bound and a near one a tight bound.
fn project_loose(poly: &PowerCubic, p: Point, u: f64) -> (f64, f64) {
    let (u, r) = poly.residual_steps(p, u, 6, PAIRING_NEWTON_DONE);
    (u, r.hypot())
}

/// Sub-steps per sample interval at which [`gap_bound`] evaluates the gap polynomial.
const GAP_STEPS: usize = 4;

/// Two-sided distance between `cubic` and the sampled curve for a candidate that must be
/// within `goal`: a proven upper bound ([`gap_bound`]) when that bound is within `goal`,
/// otherwise [`measure`]'s golden-section estimate (the two-sided bound can be loose
/// where the samples' projections jump, and must not turn away what [`measure`] accepts).
///
/// Why the bound holds. Let `H` be the Hermite interpolant of the samples (the curve
/// [`measure`] refines on) and `B` the cubic. Each sample `i` has its cubic parameter
/// `u_i` (its projection; the first and last are set to 0 and 1). On the interval between
/// samples `i` and `i + 1`, pair the Hermite point `H_i(s)` with the cubic point
/// `B(u_i + s (u_{i+1} - u_i))`; their difference `g_i(s)` is a cubic polynomial in `s`,
/// built exactly. Then:
/// - curve to cubic: the distance from `H_i(s)` to the cubic is at most `|g_i(s)|`;
/// - cubic to curve: the paired parameters run continuously from 0 to 1 over the
///   intervals, so every cubic point `B(v)` is paired with some `H_i(s)` (intermediate
///   values), and its distance to the curve is at most `|g_i(s)|`.
///
/// So the largest `|g_i|` bounds both directions (a Fréchet bound, which is stronger than
/// the Hausdorff distance [`measure`] estimates). [`gap_bound`] bounds `|g_i|` on each
/// interval from its values at [`GAP_STEPS`] sub-steps and the exact bound of its second
/// derivative (linear in `s`), with no search that could miss a peak: where it accepts,
/// [`measure`]'s golden sections, which only estimate the peaks between samples, would
/// have found at most this. As in [`measure`], the top peaks are then also checked
/// against the true curve, in both directions (the Hermite pieces' own error, O(h^4)).
/// Rounding in the bound is relative 1e-13, far inside the acceptance's 4 % margin.
fn measure_within(spline: &XSpline, trial: &Trial, goal: f64, buffers: &mut MeasureBuffers) -> f64 {
    let MeasureBuffers {
        samples,
        at,
        u,
        near,
        pieces,
        gaps,
    } = buffers;
    Samples::doubled(spline, &trial.samples, samples, at);
    let samples = &*samples;
    let poly = PowerCubic::new(&trial.cubic);
    if trial.projected {
        project_samples_between(samples, &poly, at, &trial.u, u, near);
    } else {
        project_samples_ahead(samples, &poly, u, near);
    }
    hermite_pieces(samples, pieces);
    let (u, pieces) = (&*u, &*pieces);
    let n = samples.len();
    let paired = |i: usize| match i {
        0 => 0.0,
        i if i == n - 1 => 1.0,
        i => u[i],
    };
    // (bound, where) on each interval.
    gaps.clear();
    gaps.extend((0..n - 1).map(|i| {
        paired_gap(
            &pieces[i],
            &poly,
            paired(i),
            paired(i + 1),
            goal,
            GAP_SPLITS,
        )
    }));
    let top = gaps.iter().map(|g| g.0).fold(0.0, f64::max);
    if top > goal {
        return measure_golden(spline, samples, &poly, pieces, u, near);
    }
    // The exact checks, at the interval maxima near the top (as `measure` checks its
    // refined peaks): the true curve point against the cubic, and the cubic point
    // against the true curve (Newton on the curve parameter from the paired point).
    let (lo, hi) = (samples.t[0], samples.t[n - 1]);
    let mut err = top;
    let mut cursor = Cursor::new(spline);
    for (i, &(gap, s)) in gaps.iter().enumerate() {
        let local = (i == 0 || gaps[i - 1].0 <= gap) && (i + 2 == n || gaps[i + 1].0 <= gap);
        if !local || gap < EXACT_PEAK * top {
            continue;
        }
        let t = samples.t[i] + (samples.t[i + 1] - samples.t[i]) * s;
        let v = paired(i) + (paired(i + 1) - paired(i)) * s;
        err = err.max(poly.project(cursor.eval_deriv(t).0, v).1);
        let q = poly.eval(v).to_point();
        let curve = |t| cursor.eval_deriv(t);
        err = err.max(distance_to_curve_by(curve, q, t, (lo, hi), 4));
    }
    err
}

/// The parameter of `cubic` nearest `p`: `steps` Newton steps from `guess` within `[0, 1]`
/// (stopping early when a step is below 1e-10).
pub(crate) fn project_onto(cubic: &CubicBez, p: Point, guess: f64, steps: usize) -> f64 {
    PowerCubic::new(cubic).project_steps(p, guess, steps).0
}

/// [`project_onto`] for many points on one cubic, each `u[k]` from its own start to the
/// parameter of `point(k)`: the power form built once, the projections in lanes of
/// [`LANES`] (the same values as one by one).
pub(crate) fn project_each(
    cubic: &CubicBez,
    u: &mut [f64],
    point: impl Fn(usize) -> Point,
    steps: usize,
) {
    let newton = (steps, NEWTON_DONE);
    PowerCubic::new(cubic).project_all(u, point, newton, |_, _, _| {});
}

/// The distance from `q` to the true curve near parameter `t`: `steps` Newton steps on the
/// curve parameter within `[lo, hi]`, keeping the nearest point seen. Every distance taken
/// is to a real curve point, so the result never underestimates the distance there.
pub(crate) fn distance_to_curve(
    spline: &XSpline,
    q: Point,
    t: f64,
    (lo, hi): (f64, f64),
    steps: usize,
) -> f64 {
    distance_to_curve_by(|t| spline.eval_deriv(t), q, t, (lo, hi), steps)
}

/// [`distance_to_curve`] with the curve's point and derivative from `curve` (a
/// [`Cursor`]'s, or [`XSpline::eval_deriv`]'s: the same values).
pub(crate) fn distance_to_curve_by(
    mut curve: impl FnMut(f64) -> (Point, Vec2),
    q: Point,
    mut t: f64,
    (lo, hi): (f64, f64),
    steps: usize,
) -> f64 {
    // `eval_deriv`'s point is `eval`'s, bit for bit: one evaluation per step.
    let mut nearest = f64::INFINITY;
    for _ in 0..steps {
        let (c, d) = curve(t);
        nearest = nearest.min(c.distance(q));
        let dd = d.dot(d);
        if dd <= 0.0 {
            return nearest;
        }
        t = (t + (q - c).dot(d) / dd).clamp(lo, hi);
    }
    nearest.min(curve(t).0.distance(q))
}

/// [`gap_bound`] of the Hermite piece `piece` paired with `cubic` on `[u0, u1]` (both
/// linear in `s`), and where it is reached. Over `goal`, the piece is halved (at most
/// `splits` times) and its midpoint paired with its projection onto the cubic: near a
/// sharp point the curve's speed changes fast, and a linear pairing drifts along the cubic
/// by more than the distance itself. Any pairing is a valid bound; a closer one is tighter.
fn paired_gap(
    piece: &PowerCubic,
    cubic: &PowerCubic,
    u0: f64,
    u1: f64,
    goal: f64,
    splits: usize,
) -> (f64, f64) {
    let (gap, at) = gap_bound(&piece.minus(&cubic.along(u0, u1 - u0)));
    if gap <= goal || splits == 0 {
        return (gap, at);
    }
    let um = project_loose(cubic, piece.eval(0.5).to_point(), 0.5 * (u0 + u1)).0;
    let left = paired_gap(&piece.along(0.0, 0.5), cubic, u0, um, goal, splits - 1);
    let right = paired_gap(&piece.along(0.5, 0.5), cubic, um, u1, goal, splits - 1);
    if left.0 >= right.0 {
        (left.0, 0.5 * left.1)
    } else {
        (right.0, 0.5 + 0.5 * right.1)
    }
}

/// Most halvings of one sample interval by [`paired_gap`].
const GAP_SPLITS: usize = 3;

/// An upper bound of `|g(s)|` on `[0, 1]` for a cubic `g`, and where it is reached.
///
/// On each of [`GAP_STEPS`] sub-steps of width `w`, with `|g|` equal to `a` and `b` at its
/// ends and `|g''| <= m` inside (`g''` is linear, so `m` is the larger of its two end
/// values), `|g|` at fraction `x` is at most `(1 - x) a + x b + x (1 - x) w^2 m / 2`: the
/// chord of `g` (whose length is at most the chord of `|g|`, by convexity of the norm) plus
/// the linear interpolation remainder. That concave quadratic's maximum is taken exactly.
fn gap_bound(g: &PowerCubic) -> (f64, f64) {
    let w = 1.0 / GAP_STEPS as f64;
    let second = |s: f64| (2.0 * g.c2 + 6.0 * s * g.c3).hypot();
    let (mut a, mut ma) = (g.c0.hypot(), second(0.0));
    let mut best = (a, 0.0);
    for k in 1..=GAP_STEPS {
        let s = k as f64 * w;
        let (b, mb) = (g.eval(s).hypot(), second(s));
        let m = ma.max(mb) * w * w;
        let x = if m > 0.0 {
            (0.5 + (b - a) / m).clamp(0.0, 1.0)
        } else if b > a {
            1.0
        } else {
            0.0
        };
        let bound = a + x * (b - a) + 0.5 * m * x * (1.0 - x);
        if bound > best.0 {
            best = (bound, s - w + x * w);
        }
        (a, ma) = (b, mb);
    }
    best
}

/// Two-sided distance between `cubic` and the sampled curve.
///
/// Curve to cubic: every sample projected onto the cubic. Cubic to curve: cubic points at
/// twice the sample density projected onto the Hermite piece between the samples that
/// bracket them (a screen). In both directions every sampled peak within [`PEAK`] of the
/// largest is then refined by a golden-section search between its neighbours, and the
/// distance at the maximum found is taken again against the true curve (exact curve
/// points; Newton on the curve parameter), so neither a maximum between samples nor the
/// Hermite pieces' own error can hide an excess.
///
/// The fitter takes [`measure_within`], which falls back to this estimate's core; this whole
/// form is the reference the bound is tested against, and the compatible fitter's measure.
pub(crate) fn measure(spline: &XSpline, a: f64, b: f64, cubic: &CubicBez) -> f64 {
    let samples = &Samples::new(spline, a, b, SAMPLES_PER_SEGMENT, MIN_SAMPLES, true);
    let poly = PowerCubic::new(cubic);
    let (u, near) = project_samples(samples, &poly);
    let mut pieces = Vec::new();
    hermite_pieces(samples, &mut pieces);
    measure_golden(spline, samples, &poly, &pieces, &u, &near)
}

/// Every sample projected onto the cubic: each one's cubic parameter and distance.
fn project_samples(samples: &Samples, poly: &PowerCubic) -> (Vec<f64>, Vec<f64>) {
    let n = samples.len();
    let mut u = vec![0.0; n];
    let mut near = vec![0.0; n];
    let mut guess = 0.0;
    let mut largest: f64 = 0.0;
    for i in 0..n {
        // Start from the previous sample's parameter: the curve and the cubic run alike.
        let (mut ui, mut d) = poly.project(samples.p[i], guess);
        if i > 0 && d > largest {
            // A poor start can stall at a clamp; retry from the sample's share of the span.
            let share = (samples.t[i] - samples.t[0]) / (samples.t[n - 1] - samples.t[0]);
            let alt = poly.project(samples.p[i], share);
            if alt.1 < d {
                (ui, d) = alt;
            }
        }
        u[i] = ui;
        near[i] = d;
        largest = largest.max(d);
        guess = ui;
    }
    (u, near)
}

/// [`project_samples`] for [`measure_within`], whose bound holds for any pairing of
/// samples with cubic parameters (a closer projection only makes it tighter): each sample
/// starts from the parameters of the two before it, extrapolated in proportion to the
/// curve parameter, which the cubic follows closely; the retry from the sample's share of
/// the span only where Newton stopped at a clamp. (Samples that coincide in floating point
/// start from the previous parameter.)
fn project_samples_ahead(
    samples: &Samples,
    poly: &PowerCubic,
    u: &mut Vec<f64>,
    near: &mut Vec<f64>,
) {
    let n = samples.len();
    u.clear();
    u.resize(n, 0.0);
    near.clear();
    near.resize(n, 0.0);
    let mut largest: f64 = 0.0;
    let span = samples.t[n - 1] - samples.t[0];
    for i in 0..n {
        let guess = match i {
            0 => 0.0,
            1 => (samples.t[1] - samples.t[0]) / span,
            _ => {
                let (dt0, dt1) = (
                    samples.t[i - 1] - samples.t[i - 2],
                    samples.t[i] - samples.t[i - 1],
                );
                u[i - 1] + (u[i - 1] - u[i - 2]) * (dt1 / dt0)
            }
        };
        let guess = if guess.is_finite() {
            guess.clamp(0.0, 1.0)
        } else if i > 0 {
            u[i - 1]
        } else {
            0.0
        };
        let (mut ui, mut d) = project_loose(poly, samples.p[i], guess);
        if i > 0 && i + 1 < n && d > largest && (ui <= 0.0 || ui >= 1.0) {
            let share = (samples.t[i] - samples.t[0]) / span;
            let alt = project_loose(poly, samples.p[i], share);
            if alt.1 < d {
                (ui, d) = alt;
            }
        }
        u[i] = ui;
        near[i] = d;
        largest = largest.max(d);
    }
}

/// [`project_samples_ahead`] when the samples at `at` already have their projections
/// (`known`, the polish's, onto this cubic): those are taken as they are, and each sample
/// between two of them starts from their parameters interpolated in proportion to the
/// curve parameter.
fn project_samples_between(
    samples: &Samples,
    poly: &PowerCubic,
    at: &[usize],
    known: &[f64],
    u: &mut Vec<f64>,
    near: &mut Vec<f64>,
) {
    let n = samples.len();
    u.clear();
    u.resize(n, 0.0);
    near.clear();
    near.resize(n, 0.0);
    for (&i, &ui) in at.iter().zip(known) {
        u[i] = ui;
        near[i] = (poly.eval(ui) - samples.p[i].to_vec2()).hypot();
    }
    // Every other sample starts from its share between its two known neighbours, so their
    // projections are independent: they run in lanes of [`LANES`] (the same bits).
    let mut lane = [0; LANES];
    let mut filled = 0;
    for pair in at.windows(2) {
        let (i0, i1) = (pair[0], pair[1]);
        let (t0, dt, u0, du) = (
            samples.t[i0],
            samples.t[i1] - samples.t[i0],
            u[i0],
            u[i1] - u[i0],
        );
        for i in i0 + 1..i1 {
            u[i] = (u0 + du * ((samples.t[i] - t0) / dt)).clamp(0.0, 1.0);
            lane[filled] = i;
            filled += 1;
            if filled == LANES {
                let points = lane.map(|i| samples.p[i]);
                let starts = lane.map(|i| u[i]);
                let done = poly.residual_lanes(&points, &starts, 6, PAIRING_NEWTON_DONE);
                for (&i, (ui, r)) in lane.iter().zip(done) {
                    (u[i], near[i]) = (ui, r.hypot());
                }
                filled = 0;
            }
        }
    }
    for &i in &lane[..filled] {
        (u[i], near[i]) = project_loose(poly, samples.p[i], u[i]);
    }
}

/// The Hermite pieces between samples, in power form, each built once, into `pieces`.
fn hermite_pieces(samples: &Samples, pieces: &mut Vec<PowerCubic>) {
    pieces.clear();
    pieces.extend((0..samples.len() - 1).map(|i| PowerCubic::new(&samples.piece(i))));
}

/// The buffers of [`measure_within`], kept between measures.
#[derive(Default)]
struct MeasureBuffers {
    samples: Samples,
    /// Where the polish's samples are among `samples`.
    at: Vec<usize>,
    u: Vec<f64>,
    near: Vec<f64>,
    pieces: Vec<PowerCubic>,
    /// (bound, where) on each interval.
    gaps: Vec<(f64, f64)>,
}

/// The rest of [`measure`], from the samples' projections onto the cubic: the sampled
/// distances, refined by golden sections at their peaks in both directions.
fn measure_golden(
    spline: &XSpline,
    samples: &Samples,
    poly: &PowerCubic,
    pieces: &[PowerCubic],
    u: &[f64],
    near: &[f64],
) -> f64 {
    let n = samples.len();
    let poly = *poly;
    let param =
        |piece: usize, s: f64| samples.t[piece] + (samples.t[piece + 1] - samples.t[piece]) * s;
    let start = |piece: usize, s: f64| u[piece] + (u[piece + 1] - u[piece]) * s;
    let hermite_at = |piece: usize, s: f64| {
        let point = pieces[piece].eval(s).to_point();
        poly.project(point, start(piece, s)).1
    };
    let curve_at = |piece: usize, s: f64| {
        poly.project(spline.eval(param(piece, s)), start(piece, s))
            .1
    };
    let mut err = refine_peaks(near, hermite_at, curve_at);
    // Cubic to curve. `rising` makes the samples' cubic parameters monotone for bracketing.
    let mut rising = u.to_vec();
    for i in 1..n {
        rising[i] = rising[i].max(rising[i - 1]);
    }
    // Distance from the cubic at `v` to the Hermite pieces (a cheap screen), and the curve
    // parameter of the nearest point found.
    let to_pieces = |v: f64| {
        let q = poly.eval(v).to_point();
        let piece = rising
            .partition_point(|&x| x <= v)
            .saturating_sub(1)
            .min(n - 2);
        let span = rising[piece + 1] - rising[piece];
        let start = if span > 0.0 {
            ((v - rising[piece]) / span).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let (s, d) = pieces[piece].project(q, start);
        let mut best = (d, param(piece, s));
        // Clamped at a piece's end: the nearest point may lie on the neighbour.
        if s <= 0.0 && piece > 0 {
            let (s, d) = pieces[piece - 1].project(q, 1.0);
            if d < best.0 {
                best = (d, param(piece - 1, s));
            }
        }
        if s >= 1.0 && piece + 2 < n {
            let (s, d) = pieces[piece + 1].project(q, 0.0);
            if d < best.0 {
                best = (d, param(piece + 1, s));
            }
        }
        (q, best)
    };
    // The same on the true curve: Newton on the curve parameter from the pieces' answer.
    // Every distance taken is to a real curve point, so the result never underestimates.
    let (lo, hi) = (samples.t[0], samples.t[n - 1]);
    let to_curve = |v: f64| {
        let (q, (_, t)) = to_pieces(v);
        distance_to_curve(spline, q, t, (lo, hi), 4)
    };
    let steps = 2 * (n - 1);
    let back: Vec<f64> = (0..=steps)
        .map(|j| to_pieces(j as f64 / steps as f64).1 .0)
        .collect();
    let step = 1.0 / steps as f64;
    err = err.max(refine_peaks(
        &back,
        |j, s| to_pieces((j as f64 + s) * step).1 .0,
        |j, s| to_curve((j as f64 + s) * step),
    ));
    err
}

/// The largest of `values` (sampled distances), with every local peak within [`PEAK`] of
/// it refined by a golden-section search of `between(i, s)`, the (cheap, approximate)
/// distance at fraction `s` of the way from sample `i` to sample `i + 1`, and checked there
/// with `exact(i, s)` against the true curve.
fn refine_peaks(
    values: &[f64],
    between: impl Fn(usize, f64) -> f64,
    exact: impl Fn(usize, f64) -> f64,
) -> f64 {
    let sampled = values.iter().copied().fold(0.0, f64::max);
    let mut err = sampled;
    let n = values.len();
    let mut peaks = Vec::new();
    for i in 0..n {
        let v = values[i];
        let peak = (i == 0 || values[i - 1] <= v) && (i + 1 == n || values[i + 1] <= v);
        if !peak || v < PEAK * sampled {
            continue;
        }
        for piece in [i.wrapping_sub(1), i] {
            if piece < n.saturating_sub(1) {
                let (value, at) = golden_max(|s| between(piece, s));
                err = err.max(value);
                peaks.push((value, piece, at));
            }
        }
    }
    // The exact check is dearer: only where the approximate maximum is nearly reached.
    let top = err;
    for (value, piece, at) in peaks {
        if value >= EXACT_PEAK * top {
            err = err.max(exact(piece, at));
        }
    }
    err
}

/// The maximum of `f` on `[0, 1]` and where it is, by golden-section search (f unimodal there, in practice:
/// the interval is one sample step around a sampled maximum).
fn golden_max(f: impl Fn(f64) -> f64) -> (f64, f64) {
    const R: f64 = 0.618_033_988_749_894_9;
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    let mut x1 = hi - R * (hi - lo);
    let mut x2 = lo + R * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..8 {
        if f1 > f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - R * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + R * (hi - lo);
            f2 = f(x2);
        }
    }
    // The ends are samples, already counted by the caller.
    if f1 > f2 {
        (f1, x1)
    } else {
        (f2, x2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::xspline::ControlPoint;

    /// Newton's projection one point at a time, written out as it was before the lanes: the
    /// reference the lanes must equal bit for bit.
    fn one_by_one(
        poly: &PowerCubic,
        p: Point,
        mut u: f64,
        steps: usize,
        done_below: f64,
    ) -> (f64, Vec2) {
        let p = p.to_vec2();
        for _ in 0..steps {
            let r = poly.eval(u) - p;
            let d1 = poly.c1 + u * (2.0 * poly.c2 + 3.0 * u * poly.c3);
            let d2 = 2.0 * poly.c2 + 6.0 * u * poly.c3;
            let denom = d1.dot(d1) + r.dot(d2);
            if denom <= 1e-300 {
                break;
            }
            let next = (u - r.dot(d1) / denom).clamp(0.0, 1.0);
            let done = (next - u).abs() < done_below;
            u = next;
            if done {
                break;
            }
        }
        (u, poly.eval(u) - p)
    }

    /// Projections in lanes (the polish's, the measure's, `project_each`) give the bits of
    /// one-by-one Newton: points near and far, starts at and off the answer, clamped at
    /// either end, every lane stopping at a different step, and a cubic collapsed to a
    /// point (no step at all).
    #[test]
    fn projections_in_lanes_give_the_one_by_one_bits() {
        let cubics = [
            CubicBez::new((0.0, 0.0), (30.0, 90.0), (80.0, -40.0), (120.0, 10.0)),
            CubicBez::new((0.0, 0.0), (0.0, 0.0), (50.0, 50.0), (50.0, 50.0)),
            CubicBez::new((7.0, 7.0), (7.0, 7.0), (7.0, 7.0), (7.0, 7.0)),
        ];
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut compared = 0;
        for cubic in &cubics {
            let poly = PowerCubic::new(cubic);
            for (steps, done_below) in [(1, 1e-5), (3, 1e-5), (6, 1e-5), (6, 1e-10), (2, 0.0)] {
                for _ in 0..50 {
                    let points: [Point; LANES] = std::array::from_fn(|_| {
                        Point::new(200.0 * next() - 40.0, 160.0 * next() - 60.0)
                    });
                    let starts: [f64; LANES] = std::array::from_fn(|_| 1.4 * next() - 0.2);
                    let starts = starts.map(|u: f64| u.clamp(0.0, 1.0));
                    let lanes = poly.residual_lanes(&points, &starts, steps, done_below);
                    let mut each = starts;
                    project_each(cubic, &mut each, |k| points[k], steps);
                    for k in 0..LANES {
                        let (u, r) = one_by_one(&poly, points[k], starts[k], steps, done_below);
                        assert_eq!(lanes[k].0.to_bits(), u.to_bits(), "{cubic:?} {k}");
                        assert_eq!(lanes[k].1.x.to_bits(), r.x.to_bits());
                        assert_eq!(lanes[k].1.y.to_bits(), r.y.to_bits());
                        let single = poly.residual_steps(points[k], starts[k], steps, done_below);
                        assert_eq!(single.0.to_bits(), u.to_bits());
                        if done_below == 1e-10 {
                            assert_eq!(each[k].to_bits(), u.to_bits());
                        }
                        compared += 1;
                    }
                }
            }
        }
        assert_eq!(compared, 3 * 5 * 50 * LANES);
    }

    /// The gap bound is never below the gap's largest value (dense samples), and at most
    /// its second-derivative allowance above it.
    #[test]
    fn gap_bound_covers_the_peak_tightly() {
        let cases = [
            // A parabola peaking on a sub-step: the bound is exact.
            (
                Vec2::ZERO,
                Vec2::new(0.0, 2.0),
                Vec2::new(0.0, -2.0),
                Vec2::ZERO,
                0.5,
            ),
            // Peaks between sub-steps, in both coordinates.
            (
                Vec2::new(0.1, -0.2),
                Vec2::new(1.3, 0.7),
                Vec2::new(-4.0, 0.5),
                Vec2::new(2.9, -1.1),
                f64::NAN,
            ),
            (
                Vec2::new(-0.3, 0.0),
                Vec2::new(0.0, 3.1),
                Vec2::new(0.4, -7.7),
                Vec2::new(0.0, 4.4),
                f64::NAN,
            ),
        ];
        for (c0, c1, c2, c3, exact) in cases {
            let g = PowerCubic { c0, c1, c2, c3 };
            let dense = (0..=100_000)
                .map(|i| g.eval(i as f64 / 100_000.0).hypot())
                .fold(0.0, f64::max);
            let (bound, at) = gap_bound(&g);
            let allowance = (2.0 * c2).hypot().max((2.0 * c2 + 6.0 * c3).hypot())
                / (8.0 * (GAP_STEPS * GAP_STEPS) as f64);
            assert!(bound >= dense - 1e-12, "{bound} < {dense}");
            assert!(
                bound <= dense + allowance,
                "{bound} > {dense} + {allowance}"
            );
            assert!((0.0..=1.0).contains(&at));
            if !exact.is_nan() {
                assert_eq!((bound, at), (exact, 0.5));
            }
        }
    }

    /// The bowl of the tests below: a stem's sharp corners and a bowl of mixed shapes.
    fn bowl() -> XSpline {
        let point = |x: f64, y: f64, s: f64| ControlPoint {
            pos: Point::new(x, y),
            s,
        };
        XSpline::new(vec![
            point(0.0, 0.0, 0.0),
            point(400.0, 0.0, 1.0),
            point(600.0, 350.0, -0.6),
            point(380.0, 700.0, 1.0),
            point(0.0, 700.0, 0.0),
        ])
        .unwrap()
    }

    /// On fits of a bowl from a sharp point, of growing length: the measure never reports
    /// less than the golden-section estimate it replaces (beyond the Hermite pieces' own
    /// error), accepts whatever that estimate accepts, and takes the proven bound (not the
    /// fallback) in most cases, also when the goal is only 5 % above the estimate.
    #[test]
    fn bound_dominates_the_golden_estimate() {
        let spline = bowl();
        let (mut compared, mut bounded) = (0, 0);
        for stretch in stretches(&spline) {
            let Stretch::Smooth { start, end } = stretch else {
                continue;
            };
            let a = start;
            for h in [0.2, 0.3, 0.4, 0.6, 0.9, 1.2] {
                let b = (a + h).min(end);
                let d0 = direction(&spline, a, start, end);
                let mut fit = StretchFit::with_buffers(&spline, 0.48, FitBuffers::default());
                fit.stretch(start, end);
                let trial = fit.trial(a, b, d0, 0.0);
                let golden = measure(&spline, a, b, &trial.cubic);
                for goal in [0.48, 1.05 * golden] {
                    let err = measure_within(&spline, &trial, goal, &mut fit.measure);
                    assert!(err >= golden * (1.0 - 1e-6), "{err} < {golden}");
                    if golden <= goal {
                        assert!(err <= goal, "{err} > {goal} >= {golden}");
                    }
                    if err != golden {
                        bounded += 1;
                    }
                    compared += 1;
                }
            }
        }
        assert!(
            compared >= 12 && 2 * bounded > compared,
            "{bounded} of {compared}"
        );
    }

    /// The root is found to the interval's precision, from either sign at the left end.
    #[test]
    fn root_is_found_to_the_precision() {
        let sqrt2 = root(|t| t * t - 2.0, (1.0, -1.0), (2.0, 2.0));
        assert!((sqrt2 - 2f64.sqrt()).abs() < 1e-12, "{sqrt2}");
        let cbrt = root(|t| 0.5 - t * t * t, (0.0, 0.5), (1.0, -0.5));
        assert!((cbrt - 0.5f64.cbrt()).abs() < 1e-12, "{cbrt}");
    }

    /// The bundled `B`'s outer contour at SemiBold (the masters blended at wght 600): the
    /// curve turns round its waist within a unit. A join used to fall a fraction of a unit
    /// from the waist's extreme, which the extrema pass cannot split off; now every extreme
    /// left inside a cubic is at least a unit (the extrema pass's smallest piece at 1000
    /// per em) from both its ends.
    #[test]
    fn a_join_near_an_extreme_moves_onto_it() {
        use kurbo::{ParamCurve, ParamCurveArclen, ParamCurveExtrema, PathSeg};
        let regular = [
            (72.0, 0.0, 0.0),
            (72.0, 700.0, 0.0),
            (290.0, 700.0, 0.6),
            (533.0, 684.0, 0.9),
            (560.0, 544.0, -1.0),
            (533.0, 404.0, 0.9),
            (430.0, 385.0, 0.7),
            (581.0, 366.0, 0.9),
            (612.0, 192.0, -1.0),
            (581.0, 19.0, 0.9),
            (300.0, 0.0, 0.6),
        ];
        let bold = [
            (76.0, 0.0),
            (76.0, 700.0),
            (335.0, 700.0),
            (610.0, 683.0),
            (641.0, 533.0),
            (611.0, 385.0),
            (573.0, 386.0),
            (659.0, 382.0),
            (693.0, 201.0),
            (659.0, 20.0),
            (345.0, 0.0),
        ];
        // As the instance blends them: weights 1/3 and 2/3.
        let (w0, w1) = (1.0 - 200.0 / 300.0, 200.0 / 300.0);
        let spline = XSpline::new(
            regular
                .iter()
                .zip(&bold)
                .map(|(&(x, y, s), &(bx, by))| {
                    ControlPoint::new(w0 * x + w1 * bx, w0 * y + w1 * by, s)
                })
                .collect(),
        )
        .unwrap();
        let fit = fit_contour(&spline, 0.5);
        let cubics: Vec<CubicBez> = fit
            .path
            .segments()
            .filter_map(|s| match s {
                PathSeg::Cubic(c) => Some(c),
                _ => None,
            })
            .collect();
        for c in &cubics {
            for t in c.extrema() {
                let (before, after) = (c.subsegment(0.0..t), c.subsegment(t..1.0));
                let near = before.arclen(1e-9).min(after.arclen(1e-9));
                // (An end's own level tangent is a root at the end: the join itself.)
                assert!(
                    !(1e-6..1.0).contains(&near),
                    "an extreme {near} from an end of {c:?}"
                );
            }
        }
    }
}
