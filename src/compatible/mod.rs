//! Compatible fitting: one Bézier segment structure for every master of a contour, within
//! the tolerance at every checked position of the design space.
//!
//! Masters with matching points interpolate as X-splines: at blend weights `w` the
//! contour's control points are `Σ w_i · (x_i, y_i, s_i)`. A variable font interpolates the
//! Béziers instead, coordinate by coordinate. This module fits one cubic per master per
//! span, on spans shared by all masters, and measures the interpolated Béziers against the
//! interpolated X-spline at every position asked for.
//!
//! The contour is cut as [`fit::fit_contour`] cuts it: at the sharp points (the same in every
//! master, so their parameters are shared) and at every master's cusps. An edge between
//! two sharp points is a `LineTo` in every master. A smooth stretch is covered greedily
//! with the longest span, in X-spline parameter, that fits jointly: each master gets a
//! cubic with the span's exact end points and end tangent directions, the handle lengths
//! polished jointly towards the least largest sample distance over the masters (`span`),
//! and the span fits when every
//! master and the masters' centroid fit, searched on the cheap sampled errors and measured
//! (two-sided, [`fit`]'s measure) for the span about to be taken. Once the contour is
//! covered, every span is measured at every other position; a span that fails anywhere is
//! covered again by the same search with the failing positions added to its checks.
//!
//! Measuring is mostly bounding: each span is sampled once in every master at common
//! parameters (`JointSamples`). When all masters have the same `s`, the X-spline is
//! linear in its points, and one bound from the masters alone covers every position
//! between them. Otherwise that bound plus how far each position's curve strays from the
//! blend of the masters' curves (a table per contour and position, filled per X-spline
//! segment when first needed, `Fitter::gap_segment`) covers the position, and where that
//! misses the goal the position gets a bound from its own samples. With two masters the
//! blend is quadratic in the position instead, through the masters' curves and their
//! centroid's (sampled with the span): exact at those three
//! and far closer than the linear blend elsewhere, so one bound covers the search's probes
//! and the gap tables add little at the others. Only where a
//! bound misses the goal does the two-sided measure decide. A bound within the goal accepts
//! a span the measure (an estimate, which can over-estimate where its projections stall)
//! might have turned away, so outputs can differ slightly from measuring everywhere: on the
//! bundled font only the variable TTF changed.
//!
//! Limits:
//! - The guarantee holds at the positions given, and at every position between the masters
//!   where [`CompatibleFit::between_masters`] says so (same `s` everywhere and the bound for
//!   all of them within the goal on every span); otherwise between the positions given it
//!   is not checked (callers pass the masters, the instances and a grid).
//! - Where `s` differs between masters, the blended X-spline is not the blend of the
//!   masters' curves (the blending functions depend on `s`), and every vertex of the blended
//!   Béziers lies on that blend. Where the two are farther apart than the tolerance, no
//!   structure of this kind meets it: the fit does not cut without end there, it keeps the
//!   spans and reports the error in `max_error` (above the tolerance). With the same `s` in
//!   every master the blend is exact.
//! - Joins inside a smooth stretch are G1 in every master, and G1 at every position: at
//!   each such join the in-handle is the same multiple of the out-handle in every master
//!   (each span shares one factor times the neighbour's handles, polished with the free
//!   handles), so the blended handles are collinear at any weights. On the bundled glyphs
//!   with the synthetic bold: 1628 against 1520 static segments of the more demanding
//!   master (1.07×; the issue allows 1.25×; 1.22× when the handles were matched after
//!   polishing each master alone). A join at a cusp of only some masters (a cut shared
//!   by all) is not smooth in those and is left as it is.
//! - A cusp that appears only between the masters is not a cut: the spans around it are
//!   refitted as long as that helps.

use std::cell::{OnceCell, RefCell};
use std::fmt;

use kurbo::{BezPath, CubicBez, ParamCurve, ParamCurveDeriv, Point, Vec2};

use crate::fit::{self, turns_fast, Stretch, MAX_REFINE, MIN_SAMPLES, SAMPLES_PER_SEGMENT};

mod prepared;
mod span;

use crate::power::PowerCubic;
use crate::xspline::{ControlPoint, Segment, XSpline, XSplineError};
use prepared::Prepared;
use span::{Handle, Part, StretchGrid, TrialBuffers};

/// Largest deviation of a position's weight sum from 1.
const WEIGHT_SUM_SLACK: f64 = 1e-9;
/// Most rounds of refitting a span that fails verification.
const MAX_REFITS: usize = 3;
/// Spans are not shortened below this (in X-spline segments) for a blend's sake.
const SHORTEST_BLEND_SPAN: f64 = 1.0 / 32.0;
/// A refit is kept only if it takes the error at the failing probes below this fraction.
const REFIT_GAIN: f64 = 0.5;
/// The first span tried when refitting a span, as a fraction of it.
const REFIT_GUESS: f64 = 0.6;
/// The outputs' coordinate grid (font units): a segment shorter than this can round to
/// zero length.
const GRID_UNIT: f64 = 1.0;
/// Grid steps per X-spline segment of [`Fitter::gap_segment`].
const GAP_GRID_PER_SEGMENT: usize = 10;
/// The same, from the curve quadratic in the position ([`Fitter::middle`]): what it leaves
/// is small and smooth (on the bundled glyphs with the synthetic bold, at most 0.05 of the
/// goal), so a coarser grid serves.
const GAP_GRID_MIDDLE: usize = 4;
// `Fitter::gap_segment` keeps a segment's grid in an array of the larger size.
const _: () = assert!(GAP_GRID_MIDDLE <= GAP_GRID_PER_SEGMENT);
/// Samples per X-spline segment when measuring how far a blend's curve lies from the blend
/// of the masters' curves.
const GAP_SAMPLES_PER_SEGMENT: usize = 8;
/// Newton steps of [`blend_gap`] towards the probe's nearest curve point.
const BLEND_GAP_STEPS: usize = 3;
/// A blend's goal is at least this multiple of that distance (the cubics between vertices
/// add their own error).
const VERTEX_MARGIN: f64 = 1.25;

/// One glyph contour fitted for every master with one segment structure.
#[derive(Clone, Debug)]
pub struct CompatibleFit {
    /// One closed path per master (same order as the input), all with the same elements:
    /// the same MoveTo start, and LineTo / CurveTo at the same places.
    pub paths: Vec<BezPath>,
    /// Largest two-sided distance at each checked position (same order as `positions`):
    /// the smallest of the span's bounds that meets the goal (`JointSamples`), else the
    /// two-sided measure. Never below the measure, up to the bounds' limits.
    pub max_error: Vec<f64>,
    /// When every master has the same `s` at every point and the span bound for all
    /// positions between the masters meets the goal on every span: that bound (font units),
    /// which holds at **every** position with non-negative weights, not only the checked
    /// ones. `None` otherwise (the guarantee is then at the checked positions).
    pub between_masters: Option<f64>,
    /// Segments per path.
    pub segments: usize,
}

/// Why a set of masters (or positions) cannot be fitted compatibly.
#[derive(Clone, Debug, PartialEq)]
pub enum CompatibleError {
    /// No master was given.
    NoMasters,
    /// A master has a different number of points from the first.
    PointCount {
        /// The master's index.
        master: usize,
        /// Points in master 0.
        expected: usize,
        /// Points in this master.
        found: usize,
    },
    /// A point is sharp (`s = 0`) in one master and not in another: a corner that appears
    /// mid-axis has no fixed Bézier structure.
    Sharpness {
        /// The point's index.
        point: usize,
        /// The master that differs from master 0.
        master: usize,
        /// Whether the point is sharp in master 0.
        sharp_in_first: bool,
    },
    /// A position does not have one finite weight per master summing to 1.
    Weights {
        /// The position's index.
        position: usize,
    },
    /// The X-spline blended at a position is not a valid contour (for example two points
    /// meet there, or an extrapolated `s` leaves `[-1, 1]`).
    Blend {
        /// The position's index.
        position: usize,
        /// What is wrong with the blended contour.
        source: XSplineError,
    },
}

impl fmt::Display for CompatibleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CompatibleError::NoMasters => write!(f, "no masters to fit"),
            CompatibleError::PointCount {
                master,
                expected,
                found,
            } => write!(
                f,
                "master {master} has {found} points, master 0 has {expected}"
            ),
            CompatibleError::Sharpness {
                point,
                master,
                sharp_in_first,
            } => {
                let (sharp, smooth) = if *sharp_in_first {
                    (0, *master)
                } else {
                    (*master, 0)
                };
                write!(
                    f,
                    "point {point} is sharp (s = 0) in master {sharp} but not in master {smooth}"
                )
            }
            CompatibleError::Weights { position } => write!(
                f,
                "position {position} needs one finite weight per master, summing to 1"
            ),
            CompatibleError::Blend { position, source } => {
                write!(f, "the contour blended at position {position}: {source}")
            }
        }
    }
}

impl std::error::Error for CompatibleError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            CompatibleError::Blend { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// Fits compatible masters of one contour (same point count, same sharp points) with one
/// segment structure, so that at every blend-weight vector in `positions` the blended
/// Béziers are within `tolerance` of the blended X-spline (two-sided, [`fit`]'s measure).
/// A tolerance below any master's or position's [`XSpline::min_tolerance`] is raised to it.
pub fn fit_compatible(
    masters: &[&XSpline],
    positions: &[Vec<f64>],
    tolerance: f64,
) -> Result<CompatibleFit, CompatibleError> {
    check_compatible(masters)?;
    let mut blends = Vec::with_capacity(positions.len());
    for (position, weights) in positions.iter().enumerate() {
        if weights.len() != masters.len()
            || !weights.iter().all(|w| w.is_finite())
            || (weights.iter().sum::<f64>() - 1.0).abs() > WEIGHT_SUM_SLACK
        {
            return Err(CompatibleError::Weights { position });
        }
        let spline = blend(masters, weights)
            .map_err(|source| CompatibleError::Blend { position, source })?;
        blends.push((weights.clone(), spline));
    }
    let fitter = Fitter::new(masters, blends, tolerance);
    let pieces = joint_stretches(masters);
    let mut spans = Vec::new();
    let mut guess = 1.0;
    let searched: Vec<usize> = (0..fitter.searched).collect();
    // The contour's last smooth piece ends where its first starts (no edge between).
    let closes = match (pieces.first(), pieces.last()) {
        (Some(Stretch::Smooth { start, .. }), Some(Stretch::Smooth { end, .. })) => {
            fitter.joins(*end, *start)
        }
        _ => false,
    };
    let last_smooth = pieces
        .iter()
        .rposition(|p| matches!(p, Stretch::Smooth { .. }));
    for (k, piece) in pieces.iter().enumerate() {
        if let Stretch::Smooth { start, end } = *piece {
            let before = spans
                .last()
                .filter(|s: &&Span| fitter.joins(s.b, start))
                .map(|s| s.cubics.clone());
            let after = if closes && Some(k) == last_smooth {
                Closing::First
            } else {
                Closing::Open
            };
            fitter.cover(
                (start, end),
                (start, end),
                &searched,
                &mut guess,
                &mut spans,
                before,
                after,
            );
        }
    }
    let spans = fitter.verify(spans, closes);
    let fit = fitter.assemble(&pieces, &spans, positions.len());
    fitter.keep_buffers();
    Ok(fit)
}

/// Same point count and the same sharp points in every master.
fn check_compatible(masters: &[&XSpline]) -> Result<(), CompatibleError> {
    let first = masters.first().ok_or(CompatibleError::NoMasters)?;
    for (master, spline) in masters.iter().enumerate().skip(1) {
        let (expected, found) = (first.segment_count(), spline.segment_count());
        if found != expected {
            return Err(CompatibleError::PointCount {
                master,
                expected,
                found,
            });
        }
        let pairs = first.points().iter().zip(spline.points());
        if let Some((point, (p, _))) = pairs
            .enumerate()
            .find(|(_, (p, q))| p.is_sharp() != q.is_sharp())
        {
            return Err(CompatibleError::Sharpness {
                point,
                master,
                sharp_in_first: p.is_sharp(),
            });
        }
    }
    Ok(())
}

/// The X-spline at blend weights `weights`: x, y and s interpolated.
pub(crate) fn blend(masters: &[&XSpline], weights: &[f64]) -> Result<XSpline, XSplineError> {
    let count = masters[0].segment_count();
    let points = (0..count)
        .map(|k| {
            let (mut x, mut y, mut s) = (0.0, 0.0, 0.0);
            for (spline, w) in masters.iter().zip(weights) {
                let p = spline.points()[k];
                x += w * p.pos.x;
                y += w * p.pos.y;
                s += w * p.s;
            }
            ControlPoint::blended(x, y, s)
        })
        .collect();
    XSpline::new(points)
}

/// The cubic at blend weights `weights`, coordinate-wise.
fn blend_cubic(cubics: &[CubicBez], weights: &[f64]) -> CubicBez {
    let mut sum = [Vec2::ZERO; 4];
    for (c, w) in cubics.iter().zip(weights) {
        for (acc, p) in sum.iter_mut().zip([c.p0, c.p1, c.p2, c.p3]) {
            *acc += *w * p.to_vec2();
        }
    }
    CubicBez::new(
        sum[0].to_point(),
        sum[1].to_point(),
        sum[2].to_point(),
        sum[3].to_point(),
    )
}

/// The cuts every master shares: master 0's stretches, each smooth one cut again at every
/// other master's cusps (sharp points are the same in all, so edges coincide).
fn joint_stretches(masters: &[&XSpline]) -> Vec<Stretch> {
    let first = fit::stretches(masters[0]);
    let others = masters[1..]
        .iter()
        .flat_map(|spline| fit::stretches(spline));
    let mut cuts: Vec<f64> = first
        .iter()
        .copied()
        .chain(others)
        .filter_map(|piece| match piece {
            Stretch::Smooth { start, .. } => Some(start),
            Stretch::Edge { .. } => None,
        })
        .collect();
    cuts.sort_by(f64::total_cmp);
    let mut out = Vec::new();
    for piece in first {
        let Stretch::Smooth { start, end } = piece else {
            out.push(piece);
            continue;
        };
        let mut from = start;
        for &cut in &cuts {
            if cut > from + 1e-9 && cut < end - 1e-9 {
                out.push(Stretch::Smooth {
                    start: from,
                    end: cut,
                });
                from = cut;
            }
        }
        out.push(Stretch::Smooth { start: from, end });
    }
    out
}

/// One span of a smooth stretch, `[a, b]` in X-spline parameter, with its cubic in every
/// master and its measured error at every probe (`NaN`: not measured yet).
struct Span {
    a: f64,
    b: f64,
    /// The enclosing stretch (for one-sided tangents at its ends).
    stretch: (f64, f64),
    cubics: Vec<CubicBez>,
    errors: Vec<f64>,
    /// The span sampled in every master (taken when it is first measured).
    samples: Option<JointSamples>,
    /// Its [`JointSamples::hull_bound`], once computed (masters with the same `s` only).
    hull: Option<f64>,
}

/// A contour at which fits are measured: its blend weights and blended X-spline.
struct Probe {
    weights: Vec<f64>,
    spline: XSpline,
}

/// One probe's [`Fitter::gap`] per interval of its grid, and which segments are filled.
#[derive(Default)]
struct GapTable {
    values: Vec<f64>,
    done: Vec<bool>,
}

/// The masters, the probes and the goal of one compatible fit.
struct Fitter<'a> {
    masters: &'a [&'a XSpline],
    /// The masters, then (when it differs from them) their centroid, then every other
    /// position; the first `searched` are checked while spans are searched.
    probes: Vec<Probe>,
    searched: usize,
    /// For every position, its probe.
    position_probe: Vec<usize>,
    goal: f64,
    /// The goal at each probe, computed when first needed ([`Fitter::goal_at`]).
    goals: Vec<OnceCell<f64>>,
    /// Every master has the same `s` at every point: every blend is the blend of the
    /// masters' curves, and [`JointSamples::hull_bound`] applies.
    same_shape: bool,
    /// Where `s` differs: per probe, how far its curve strays from the blend of the
    /// masters' curves at the same parameter, per interval of a grid on the contour
    /// ([`Fitter::gap_segment`]), computed segment by segment when first needed (the
    /// segments of edges never are).
    gap_tables: Vec<RefCell<GapTable>>,
    /// The masters' points and derivatives on that grid, per segment: per master, then
    /// (when `middle` is set) the middle probe's; empty until first needed.
    master_grid: RefCell<Vec<Vec<(Point, Vec2)>>>,
    /// Two masters whose `s` differs, and their centroid a probe of its own: its index.
    /// Then the curve is taken as quadratic in the position, through the masters and the
    /// middle ([`JointSamples::segment_bound`]), and each probe's gap is measured from
    /// that interpolant ([`Fitter::gap_segment`]).
    middle: Option<usize>,
    /// The search's trial buffers (this thread's, handed back by [`Fitter::keep_buffers`]).
    buffers: RefCell<TrialBuffers>,
}

impl<'a> Fitter<'a> {
    fn new(
        masters: &'a [&'a XSpline],
        blends: Vec<(Vec<f64>, XSpline)>,
        tolerance: f64,
    ) -> Fitter<'a> {
        let count = masters.len();
        let mut probes: Vec<Probe> = masters
            .iter()
            .enumerate()
            .map(|(i, spline)| Probe {
                weights: (0..count).map(|j| if i == j { 1.0 } else { 0.0 }).collect(),
                spline: (*spline).clone(),
            })
            .collect();
        let add = |probes: &mut Vec<Probe>, weights: Vec<f64>, spline: XSpline| match probes
            .iter()
            .position(|p| p.spline == spline)
        {
            Some(k) => k,
            None => {
                probes.push(Probe { weights, spline });
                probes.len() - 1
            }
        };
        let centre = vec![1.0 / count as f64; count];
        if let Ok(spline) = blend(masters, &centre) {
            add(&mut probes, centre, spline);
        }
        let searched = probes.len();
        let position_probe = blends
            .into_iter()
            .map(|(weights, spline)| add(&mut probes, weights, spline))
            .collect();
        let floor = probes
            .iter()
            .map(|p| p.spline.min_tolerance())
            .fold(0.0, f64::max);
        let goal = tolerance.max(floor) * fit::SAFETY;
        let goals = probes.iter().map(|_| OnceCell::new()).collect();
        let same_shape = masters.iter().all(|m| {
            m.points()
                .iter()
                .zip(masters[0].points())
                .all(|(p, q)| p.s == q.s)
        });
        let gap_tables = probes.iter().map(|_| RefCell::default()).collect();
        let middle = (count == 2 && !same_shape && searched == 3).then_some(2);
        Fitter {
            masters,
            probes,
            searched,
            position_probe,
            goal,
            goals,
            same_shape,
            gap_tables,
            master_grid: RefCell::default(),
            middle,
            buffers: RefCell::new(TrialBuffers::take()),
        }
    }

    /// Hands the trial buffers back to this thread, for the next contour.
    fn keep_buffers(self) {
        self.buffers.into_inner().keep();
    }

    /// One cubic per master for `[a, b]` of the stretch `[t0, t1]`, and the largest sample
    /// distance over the masters (a lower bound of the error): the search's cheap error. The
    /// other probes are only measured (their sampled error costs nearly a measure and saved
    /// no trials).
    ///
    /// At a smooth join with a span already fitted (`ends`), the handles there are one
    /// factor, shared by every master, times the neighbour's ([`share_start`],
    /// [`share_end`]), and the polish moves that factor with the free handles
    /// ([`span::fit_joint`]). `low`: an error below it may end the polish early (the span
    /// is clearly short of the longest; 0 polishes fully).
    fn trial(
        &self,
        grids: &mut [StretchGrid<'_>],
        (a, b): (f64, f64),
        (t0, t1): (f64, f64),
        ends: Ends<'_>,
        low: f64,
    ) -> (Vec<CubicBez>, f64) {
        let third = (b - a) / 3.0;
        let mut buffers = self.buffers.borrow_mut();
        let parts = &mut buffers.parts;
        parts.resize_with(self.masters.len(), Part::default);
        for ((spline, grid), part) in self.masters.iter().zip(grids.iter_mut()).zip(&mut *parts) {
            grid.samples(a, b, &mut part.samples);
            let (start, end) = part.samples.end_derivs();
            // The span's Hermite cubic: handle lengths from the curve's derivatives.
            let d0 = heading(spline, a, (t0, t1), start);
            let d1 = heading(spline, b, (t0, t1), end);
            part.start = Handle {
                direction: d0,
                shared: None,
                length: start.dot(d0) * third,
            };
            part.end = Handle {
                direction: d1,
                shared: None,
                length: end.dot(d1) * third,
            };
        }
        if let Some(before) = ends.before {
            share_start(parts, before);
        }
        if let Some(after) = ends.after {
            share_end(parts, after);
        }
        buffers.fit_joint(self.goal, low)
    }

    /// Measures the span's blended cubic at each probe in `probes`; the largest error as a
    /// multiple of [`Fitter::goal`] relative to each probe's own goal (at most `goal` when
    /// the span meets every probe's goal).
    ///
    /// Each probe's error is the cheapest bound that meets its goal: the span's
    /// [`JointSamples::hull_bound`] (every position between the masters at once, when all
    /// masters have the same `s`), else [`JointSamples::bound`] at the probe, else
    /// [`fit`]'s two-sided measure. A bound within the goal is an upper bound of the
    /// distance the measure estimates, so accepting on it is never weaker.
    /// The goal at probe `k`: `goal`, or at a blend whose curve lies farther than that from
    /// the blend of the masters' curves (`s` interpolates non-linearly), that distance with
    /// a margin: no structure with vertices on the masters' curves gets closer. (Computed
    /// only for a probe where a span misses `goal`: it costs a pass over the contour.)
    fn goal_at(&self, k: usize) -> f64 {
        if k < self.masters.len() || self.same_shape {
            return self.goal;
        }
        *self.goals[k].get_or_init(|| {
            let probe = &self.probes[k];
            // The distance at the same parameter bounds the nearest one from above: where
            // it leaves the goal as it is, the Newton steps would too.
            if VERTEX_MARGIN * blend_gap(self.masters, probe, 0) <= self.goal {
                return self.goal;
            }
            self.goal
                .max(VERTEX_MARGIN * blend_gap(self.masters, probe, BLEND_GAP_STEPS))
        })
    }

    fn measure(&self, span: &mut Span, probes: impl IntoIterator<Item = usize>) -> f64 {
        let mut worst: f64 = 0.0;
        for k in probes {
            let probe = &self.probes[k];
            let goal = self.goal;
            let middle = self.middle.map(|m| &self.probes[m].spline);
            let samples = span.samples.get_or_insert_with(|| {
                JointSamples::new(self.masters, middle, (span.a, span.b), &span.cubics, goal)
            });
            // The bound for every position between the masters at once: exact for the
            // blend of the masters' curves, which is the blended curve when `s` is the
            // same; otherwise for the curve interpolated in the position (linearly, or
            // through the middle too), and the blended curve's distance from that is added.
            let hull = *span
                .hull
                .get_or_insert_with(|| samples.hull_bound(&span.cubics, self.goal));
            let convex = probe.weights.iter().all(|w| *w >= 0.0);
            let gap = if !convex || hull > goal {
                f64::INFINITY
            } else if self.same_shape || k < self.masters.len() || Some(k) == self.middle {
                0.0
            } else {
                self.gap(k, span.a, span.b)
            };
            let err = if hull + gap <= goal {
                hull + gap
            } else {
                // At a master its own samples are the probe's (bit for bit): no evaluation.
                let from = if self.same_shape || k < self.masters.len() {
                    Source::Blend
                } else if Some(k) == self.middle {
                    Source::Middle
                } else {
                    Source::Own
                };
                let bound = samples.bound(&span.cubics, probe, from, goal);
                if bound <= goal {
                    bound
                } else {
                    let cubic = blend_cubic(&span.cubics, &probe.weights);
                    fit::measure(&probe.spline, span.a, span.b, &cubic)
                }
            };
            span.errors[k] = err;
            if err > goal {
                worst = worst.max(err * goal / self.goal_at(k));
            } else {
                worst = worst.max(err);
            }
        }
        worst
    }

    /// An upper bound of `|X_k(T) - Σ w_j X_j(T)|` over `T` in `[a, b]`: the curve of probe
    /// `k` against the blend of the masters' curves at its weights `w`, at the same
    /// parameter (so also of the Fréchet distance between the two); with
    /// [`Fitter::middle`], against the curve quadratic in the position through the masters'
    /// and the middle's curves instead ([`quadratic_weights`]). With the bound of the
    /// masters' blend from the blended cubic ([`JointSamples::hull_bound`]), it bounds the
    /// probe's error without sampling the probe's curve for every span.
    fn gap(&self, k: usize, a: f64, b: f64) -> f64 {
        let steps = self.gap_steps();
        let per = steps as f64;
        let mut table = self.gap_tables[k].borrow_mut();
        if table.done.is_empty() {
            let count = self.masters[0].segment_count();
            table.values = vec![0.0; count * steps];
            table.done = vec![false; count];
        }
        let len = table.values.len() as i64;
        let first = (a * per).floor();
        let last = (b * per).ceil() as i64 - 1;
        let mut worst: f64 = 0.0;
        let mut i = first as i64;
        while i <= last {
            let at = i.rem_euclid(len) as usize;
            let j = at / steps;
            if !table.done[j] {
                self.gap_segment(k, j, &mut table.values[j * steps..(j + 1) * steps]);
                table.done[j] = true;
            }
            worst = worst.max(table.values[at]);
            i += 1;
        }
        worst
    }

    /// Steps per X-spline segment of [`Fitter::gap_segment`].
    fn gap_steps(&self) -> usize {
        match self.middle {
            Some(_) => GAP_GRID_MIDDLE,
            None => GAP_GRID_PER_SEGMENT,
        }
    }

    /// [`Fitter::gap`] on segment `j`, per interval of a grid of [`Fitter::gap_steps`]
    /// steps (into `out`): the difference of the two curves is taken as its cubic Hermite
    /// interpolant between grid points (as every bound here takes the curves), and its
    /// Bézier control points bound it on the interval (convex hull). Both ends of an
    /// interval are evaluated in its own segment.
    fn gap_segment(&self, k: usize, j: usize, out: &mut [f64]) {
        let steps = self.gap_steps();
        let mut grids = self.master_grid.borrow_mut();
        if grids.is_empty() {
            grids.resize_with(self.masters[0].segment_count(), Vec::new);
        }
        let grid = &mut grids[j];
        if grid.is_empty() {
            let middle = self.middle.map(|m| &self.probes[m].spline);
            grid.reserve_exact((self.masters.len() + 1) * (steps + 1));
            for m in self.masters.iter().copied().chain(middle) {
                let segment = Prepared::new(&m.segment(j));
                grid.extend((0..=steps).map(|i| segment.eval_deriv(i as f64 / steps as f64)));
            }
        }
        let probe = &self.probes[k];
        let quadratic = self.middle.map(|_| quadratic_weights(probe.weights[1]));
        let coefficients: &[f64] = match &quadratic {
            Some(weights) => weights,
            None => &probe.weights,
        };
        let segment = Prepared::new(&probe.spline.segment(j));
        let mut diff = [(Vec2::ZERO, Vec2::ZERO); GAP_GRID_PER_SEGMENT + 1];
        for (i, slot) in diff.iter_mut().enumerate().take(steps + 1) {
            let (p, d) = segment.eval_deriv(i as f64 / steps as f64);
            let (mut p, mut d) = (p.to_vec2(), d);
            for (m, w) in coefficients.iter().enumerate() {
                let (q, e) = grid[m * (steps + 1) + i];
                p -= *w * q.to_vec2();
                d -= *w * e;
            }
            *slot = (p, d);
        }
        let third = 1.0 / (3.0 * steps as f64);
        for (i, hull) in out.iter_mut().enumerate() {
            let (p0, d0) = diff[i];
            let (p1, d1) = diff[i + 1];
            *hull = longest(&[p0, p0 + d0 * third, p1 - d1 * third, p1]);
        }
    }

    fn span(&self, a: f64, b: f64, stretch: (f64, f64), cubics: Vec<CubicBez>) -> Span {
        Span {
            a,
            b,
            stretch,
            cubics,
            errors: vec![f64::NAN; self.probes.len()],
            samples: None,
            hull: None,
        }
    }

    /// The span `[a, a + h]` fitted and measured at the probes `checks`, if it fits there.
    fn fitted(
        &self,
        grids: &mut [StretchGrid<'_>],
        a: f64,
        h: f64,
        stretch: (f64, f64),
        checks: &[usize],
        ends: Ends<'_>,
    ) -> Result<Span, f64> {
        let (cubics, sampled) = self.trial(grids, (a, a + h), stretch, ends, 0.0);
        if sampled > self.goal {
            return Err(sampled);
        }
        let mut span = self.span(a, a + h, stretch, cubics);
        let err = self.measure(&mut span, checks.iter().copied());
        if err <= self.goal {
            Ok(span)
        } else {
            Err(err)
        }
    }

    /// Covers `[from, to]` of the smooth stretch `stretch` greedily with the longest spans
    /// that fit at the probes `checks`, appending them to `spans`.
    ///
    /// The search is [`fit::fit_contour`]'s ([`fit::SpanSearch`]), on the joint error: on
    /// sampled errors, and only a span about to be taken is measured.
    ///
    /// `before`: the cubics of the span that ends at `from`, if it joins there smoothly;
    /// `after`: those of the span that starts at `to`. Every span's handles are matched at
    /// its joins (see [`Fitter::trial`]): with `before` or the span just taken at its start,
    /// with `after` (or, for `Closing::First`, the first span in `spans`) at `to`.
    #[allow(clippy::too_many_arguments)]
    fn cover(
        &self,
        (from, t1): (f64, f64),
        stretch: (f64, f64),
        checks: &[usize],
        guess: &mut f64,
        spans: &mut Vec<Span>,
        before: Option<Vec<CubicBez>>,
        after: Closing,
    ) {
        let goal = self.goal;
        let mut a = from;
        let mut before = before;
        let mut grids: Vec<StretchGrid> = self
            .masters
            .iter()
            .map(|spline| StretchGrid::new(spline, stretch.0))
            .collect();
        while t1 - a > 1e-12 * (1.0 + t1.abs()) {
            let rest = t1 - a;
            let after: Option<Vec<CubicBez>> = match &after {
                Closing::Open => None,
                Closing::Given(cubics) => Some(cubics.clone()),
                Closing::First => spans.first().map(|s| s.cubics.clone()),
            };
            // The neighbours a span `[a, a + h]` matches at its ends.
            let ends = |h: f64| Ends {
                before: before.as_deref(),
                after: if h >= rest { after.as_deref() } else { None },
            };
            // The longest span that fitted, measured if it was taken.
            let mut fits: Option<(f64, Vec<CubicBez>, Option<Span>)> = None;
            let mut search = fit::SpanSearch::new(guess.min(rest), rest, goal);
            for _ in 0..fit::MAX_TRIES {
                let h = search.span();
                let (cubics, sampled) =
                    self.trial(&mut grids, (a, a + h), stretch, ends(h), search.low());
                let mut err = sampled;
                let mut measured = None;
                if search.takes(sampled) {
                    let mut span = self.span(a, a + h, stretch, cubics.clone());
                    err = self.measure(&mut span, checks.iter().copied());
                    measured = Some(span);
                }
                if err <= goal {
                    let done = measured.is_some();
                    fits = Some((h, cubics, measured));
                    if done {
                        break;
                    }
                }
                if search.next(err).is_none() {
                    break;
                }
            }
            let h = search.span();
            let span = match fits {
                Some((_, _, Some(span))) => span,
                Some((h, cubics, None)) => {
                    let mut span = self.span(a, a + h, stretch, cubics);
                    if self.measure(&mut span, checks.iter().copied()) <= goal {
                        span
                    } else {
                        self.shortest(&mut grids, a, 0.5 * h, stretch, checks, ends(0.5 * h))
                    }
                }
                None => self.shortest(&mut grids, a, h, stretch, checks, ends(h)),
            };
            let h = span.b - span.a;
            // No sliver at the stretch's end (see `fit::SLIVER`), nor a rest whose ends lie
            // within the goal (or one font unit, the outputs' grid) of each other in every
            // master: near a sharp point an X-spline
            // slows down, so a fair share of the parameter can be a fraction of a unit long,
            // which rounds to a zero-length segment.
            let short = |h: f64| {
                self.masters
                    .iter()
                    .all(|m| m.eval(a + h).distance(m.eval(t1)) < goal.max(GRID_UNIT))
            };
            let span = if h < rest && (rest - h < fit::SLIVER * rest || short(h)) {
                match self.fitted(&mut grids, a, rest, stretch, checks, ends(rest)) {
                    Ok(whole) => whole,
                    // The rest does not fit whole: two spans are needed anyway, so cut it
                    // where the curve is halfway (by distance to the end in master 0),
                    // leaving no sliver, when the first half fits.
                    Err(_) if short(h) => {
                        let half = self.halfway(a, t1);
                        self.fitted(&mut grids, a, half - a, stretch, checks, ends(half - a))
                            .unwrap_or(span)
                    }
                    Err(_) => span,
                }
            } else {
                span
            };
            let h = span.b - span.a;
            if h < rest || h > *guess {
                *guess = h;
            }
            a = span.b;
            before = Some(span.cubics.clone());
            spans.push(span);
        }
    }

    /// The parameter in `[a, t1]` where master 0's curve is as far from its point at `t1`
    /// as half the distance from `a` (by bisection; the curve near a stretch's end runs
    /// towards it).
    fn halfway(&self, a: f64, t1: f64) -> f64 {
        let spline = self.masters[0];
        let end = spline.eval(t1);
        let target = 0.5 * spline.eval(a).distance(end);
        let (mut lo, mut hi) = (a, t1);
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if spline.eval(mid).distance(end) > target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// Last resort for degenerate geometry: halve the span until it fits or is tiny.
    ///
    /// Where `s` differs between masters, below [`SHORTEST_BLEND_SPAN`] only the masters
    /// bind: a blend that still fails is one whose curve strays from the blend of the
    /// masters' curves, which no shorter span mends (verification reports it). With the same
    /// `s` in every master the blend is exact, and every position binds down to the last
    /// halving, so that each position's measured error is within the goal (the full Roboto
    /// Flex, 84 masters: with the blends let go, 7 glyphs were measured over the tolerance
    /// at some of 2,307 positions, up to 1.29 units; with them, none, and 3 fewer segments.
    /// Where the tilde's 1.154 was reported the tests' dense checker, which compares whole
    /// contours, finds 0.298: the measure's projections can stall and over-estimate, as
    /// the module docs say, and seem to have done so there).
    /// `ends` applies to `[a, a + h]`; a shorter span matches only the start.
    fn shortest(
        &self,
        grids: &mut [StretchGrid<'_>],
        a: f64,
        mut h: f64,
        stretch: (f64, f64),
        checks: &[usize],
        ends: Ends<'_>,
    ) -> Span {
        let masters: Vec<usize> = (0..self.masters.len()).collect();
        let mut checks = checks;
        let mut ends = ends;
        loop {
            match self.fitted(grids, a, h, stretch, checks, ends) {
                Ok(span) => return span,
                Err(_)
                    if h < SHORTEST_BLEND_SPAN
                        && checks.len() > masters.len()
                        && !self.same_shape =>
                {
                    checks = &masters;
                }
                Err(_) if h < 1e-9 => {
                    // Nothing fits: take the joint trial's cubics and report their error.
                    let cubics = self.trial(grids, (a, a + h), stretch, ends, 0.0).0;
                    let mut span = self.span(a, a + h, stretch, cubics);
                    self.measure(&mut span, checks.iter().copied());
                    return span;
                }
                Err(_) => {
                    h *= 0.5;
                    ends.after = None;
                }
            }
        }
    }

    /// Measures every span at the probes it was not measured at (see [`Fitter::verify_span`]).
    ///
    /// A refit matches its neighbours' handles at its ends, as the cover did: the span
    /// verified before it and the one still to verify after it (around the contour when
    /// `closes`: the last span before the first, the first verified after the last).
    fn verify(&self, spans: Vec<Span>, closes: bool) -> Vec<Span> {
        let mut out: Vec<Span> = Vec::with_capacity(spans.len());
        let last = spans
            .last()
            .filter(|_| closes)
            .map(|s| (s.b, s.cubics.clone()));
        let mut queue = spans.into_iter().peekable();
        while let Some(span) = queue.next() {
            let before = match out.last() {
                Some(p) => self.joins(p.b, span.a).then(|| p.cubics.clone()),
                None => last
                    .as_ref()
                    .filter(|(b, _)| self.joins(*b, span.a))
                    .map(|(_, c)| c.clone()),
            };
            let after = match queue.peek() {
                Some(next) => self.joins(span.b, next.a).then(|| next.cubics.clone()),
                None if closes => out
                    .first()
                    .filter(|f| self.joins(span.b, f.a))
                    .map(|f| f.cubics.clone()),
                None => None,
            };
            self.verify_span(span, 0, before, after, &mut out);
        }
        out
    }

    /// Whether a span ending at `b` and one starting at `a` meet (the same parameter, up
    /// to whole turns of the contour).
    fn joins(&self, b: f64, a: f64) -> bool {
        let n = self.masters[0].segment_count() as f64;
        let d = (b - a).rem_euclid(n);
        d < 1e-9 || n - d < 1e-9
    }

    /// Measures `span` at the probes it was not measured at; if it fails at some, covers it
    /// again by the search with those probes added to the checks, and verifies the new spans
    /// in turn. The refit is kept if it meets their goals or at least halves the error:
    /// where it does not, the blend strays from the masters' curves by more than the goal
    /// and no cut mends it, so the span stays and `max_error` reports it. At most
    /// [`MAX_REFITS`] rounds; where `s` differs between masters, spans shorter than twice
    /// [`SHORTEST_BLEND_SPAN`] stay (see [`Fitter::shortest`]).
    ///
    /// `before` and `after`: the neighbours' cubics the refit matches at its ends.
    fn verify_span(
        &self,
        mut span: Span,
        round: usize,
        before: Option<Vec<CubicBez>>,
        after: Option<Vec<CubicBez>>,
        out: &mut Vec<Span>,
    ) {
        let count = self.probes.len();
        let unmeasured: Vec<usize> = (0..count).filter(|&k| span.errors[k].is_nan()).collect();
        let err = self.measure(&mut span, unmeasured);
        let short = span.b - span.a < 2.0 * SHORTEST_BLEND_SPAN && !self.same_shape;
        if err <= self.goal || round == MAX_REFITS || short {
            out.push(span);
            return;
        }
        let failing: Vec<usize> = (self.searched..count)
            .filter(|&k| span.errors[k] > self.goal_at(k))
            .collect();
        let checks: Vec<usize> = (0..self.searched).chain(failing.iter().copied()).collect();
        let mut pieces = Vec::new();
        let mut guess = REFIT_GUESS * (span.b - span.a);
        self.cover(
            (span.a, span.b),
            span.stretch,
            &checks,
            &mut guess,
            &mut pieces,
            before.clone(),
            after.clone().map_or(Closing::Open, Closing::Given),
        );
        // The worst error at the failing probes, as a multiple of their goals.
        let worst = |s: &Span| {
            failing
                .iter()
                .map(|&k| s.errors[k] / self.goal_at(k))
                .fold(0.0, f64::max)
        };
        let refit = pieces.iter().map(worst).fold(0.0, f64::max);
        if failing.is_empty() || (refit > 1.0 && refit > REFIT_GAIN * worst(&span)) {
            out.push(span);
            return;
        }
        let mut queue = pieces.into_iter().enumerate().peekable();
        while let Some((i, piece)) = queue.next() {
            // The previous piece as verified (or its refit's last piece).
            let before = match i {
                0 => before.clone(),
                _ => out.last().map(|p| p.cubics.clone()),
            };
            let after = match queue.peek() {
                Some((_, next)) => Some(next.cubics.clone()),
                None => after.clone(),
            };
            self.verify_span(piece, round + 1, before, after, out);
        }
    }

    /// One path per master from the cuts and the verified spans, and the errors per
    /// position.
    fn assemble(&self, pieces: &[Stretch], spans: &[Span], positions: usize) -> CompatibleFit {
        let start = match pieces.first() {
            Some(Stretch::Smooth { start, .. }) => *start,
            Some(Stretch::Edge { end }) => end - 1.0,
            None => 0.0,
        };
        let mut paths: Vec<BezPath> = self
            .masters
            .iter()
            .map(|spline| {
                let mut path = BezPath::new();
                path.move_to(spline.eval(start));
                path
            })
            .collect();
        let mut queue = spans.iter().peekable();
        let mut segments = 0;
        for piece in pieces {
            match *piece {
                Stretch::Edge { end } => {
                    for (path, spline) in paths.iter_mut().zip(self.masters) {
                        path.line_to(spline.eval(end));
                    }
                    segments += 1;
                }
                Stretch::Smooth { end, .. } => {
                    while let Some(span) = queue.next_if(|s| s.a < end) {
                        for (path, c) in paths.iter_mut().zip(&span.cubics) {
                            path.curve_to(c.p1, c.p2, c.p3);
                        }
                        segments += 1;
                    }
                }
            }
        }
        for path in &mut paths {
            path.close_path();
        }
        let max_error = (0..positions)
            .map(|k| {
                let probe = self.position_probe[k];
                spans.iter().map(|s| s.errors[probe]).fold(0.0, f64::max)
            })
            .collect();
        let mut hulls = spans.iter().map(|s| s.hull.filter(|h| *h <= self.goal));
        let between_masters = if self.same_shape {
            hulls.try_fold(0.0, |acc: f64, h| Some(acc.max(h?)))
        } else {
            None
        };
        CompatibleFit {
            paths,
            max_error,
            segments,
            between_masters,
        }
    }
}

/// The cubics of the spans next to a span, whose handles it matches at their joins.
#[derive(Clone, Copy, Default)]
struct Ends<'n> {
    /// The span ending where this one starts.
    before: Option<&'n [CubicBez]>,
    /// The span starting where this one ends.
    after: Option<&'n [CubicBez]>,
}

/// What the last span of a cover matches at its end.
enum Closing {
    /// Nothing (the stretch ends at a cut, or its neighbour is not fitted yet).
    Open,
    /// These cubics (a refit's neighbour).
    Given(Vec<CubicBez>),
    /// The first span of the contour (a contour smooth all round).
    First,
}

/// Handles shorter than this (font units) have no direction of their own.
const SHORT_HANDLE: f64 = 1e-9;
/// Largest sine of the angle between two handles that count as collinear.
const COLLINEAR: f64 = 1e-7;

/// [`fit::direction`] at `t` of the stretch `(t0, t1)`, from the curve's derivative
/// there when the caller has it: inside the stretch, where the derivative does not vanish,
/// that is the same value (one evaluation fewer per span end and trial).
fn heading(spline: &XSpline, t: f64, (t0, t1): (f64, f64), deriv: Vec2) -> Vec2 {
    let inside = (t - t0).abs() >= 1e-12 && (t - t1).abs() >= 1e-12;
    let length = deriv.hypot();
    if inside && length > 1e-9 * spline.extent() && length.is_finite() {
        deriv / length
    } else {
        fit::direction(spline, t, t0, t1)
    }
}

/// Ties the start handles of `parts` to the in-handles of `before` at their join: every
/// master's out-handle becomes one shared factor times its in-handle (same direction), so
/// the blend of the handles at any weights is that factor times the blended in-handle,
/// collinear (a smooth point stays smooth at every position, not only at the masters). The
/// factor starts where [`matched`] puts it. Nothing changes at a join that is not smooth
/// in every master (a cusp, or a sharp point), or where every handle is short.
fn share_start(parts: &mut [Part], before: &[CubicBez]) {
    let ins: Vec<Vec2> = before.iter().map(|c| c.p3 - c.p2).collect();
    let outs: Vec<Vec2> = parts
        .iter()
        .map(|p| p.start.direction * p.start.length)
        .collect();
    let Some(lengths) = matched(&ins, &outs, false) else {
        return;
    };
    for ((part, handle), length) in parts.iter_mut().zip(&ins).zip(lengths) {
        part.start = Handle {
            direction: unit(*handle),
            shared: Some(handle.hypot()),
            length,
        };
    }
}

/// [`share_start`] at the end of `parts`, against the start handles of `after`.
fn share_end(parts: &mut [Part], after: &[CubicBez]) {
    let outs: Vec<Vec2> = after.iter().map(|c| c.p1 - c.p0).collect();
    let ins: Vec<Vec2> = parts
        .iter()
        .map(|p| p.end.direction * p.end.length)
        .collect();
    let Some(lengths) = matched(&ins, &outs, true) else {
        return;
    };
    for ((part, handle), length) in parts.iter_mut().zip(&outs).zip(lengths) {
        part.end = Handle {
            direction: unit(*handle),
            shared: Some(handle.hypot()),
            length,
        };
    }
}

/// The new lengths of the handles on one side of a join (`outs` unless `set_ins`) for one
/// ratio `|in| / |out|` in every master; `None` when the join is not smooth in every master
/// or no master has two handles to take a ratio from.
///
/// The ratio moves the handles being set least in the least-squares sense, in font units
/// (a cubic's error grows with how far a handle moves, not by what factor: a ratio from
/// relative changes lets a master with a nearly vanishing handle pull the others' far).
fn matched(ins: &[Vec2], outs: &[Vec2], set_ins: bool) -> Option<Vec<f64>> {
    // Σ |i|·|o|, and Σ |fixed side|² (`ins` fixed: out = |i| / r; `outs` fixed: in = r |o|).
    let (mut cross, mut fixed) = (0.0, 0.0);
    for (i, o) in ins.iter().zip(outs) {
        let (li, lo) = (i.hypot(), o.hypot());
        if li > SHORT_HANDLE
            && lo > SHORT_HANDLE
            && (i.dot(*o) <= 0.0 || i.cross(*o).abs() > COLLINEAR * li * lo)
        {
            return None;
        }
        cross += li * lo;
        fixed += if set_ins { lo * lo } else { li * li };
    }
    if cross <= 0.0 || fixed <= 0.0 {
        return None;
    }
    // Setting outs: |o'| = q |i| with q = Σ|i||o| / Σ|i|²; setting ins: |i'| = r |o| with
    // r = Σ|i||o| / Σ|o|².
    let scale = cross / fixed;
    Some(
        ins.iter()
            .zip(outs)
            .map(|(i, o)| scale * if set_ins { o.hypot() } else { i.hypot() })
            .collect(),
    )
}

/// `v` scaled to length 1 (zero stays zero).
fn unit(v: Vec2) -> Vec2 {
    let length = v.hypot();
    if length > 0.0 {
        v / length
    } else {
        v
    }
}

// [`JointSamples`] samples each master as [`fit`]'s measure samples its curve: the same
// density, fewest samples, refinement depth and turn limit (`fit::SAMPLES_PER_SEGMENT`,
// `MIN_SAMPLES`, `MAX_REFINE`, `MAX_TURN`).
/// Most halvings of a gap polynomial when its control points bound it above the goal.
const GAP_HALVINGS: usize = 2;
/// A net whose coefficients reach this multiple of the goal is not halved: on the bundled
/// glyphs with the synthetic bold, halving never brought one from over 1.5 times the goal to
/// within it (1934 nets), and each costs 21 nets' coefficients. A bound over the goal is as
/// valid as any: the interval is halved with a fresh pairing, or the position bounded alone.
const NET_HOPELESS: f64 = 1.5;
/// With the middle's samples, one bound for the whole axis is taken where it is below this
/// fraction of the goal (room for [`Fitter::gap`]); else the two halves are bounded.
const WHOLE_AXIS: f64 = 0.9;
/// Newton steps when moving a blended pairing to a blended cubic's nearest points.
const REPROJECT_STEPS: usize = 2;
/// Most halvings of an interval with a fresh pairing at its midpoint ([`paired_bound`]).
const PAIR_SPLITS: usize = 3;
/// Newton steps when projecting a sample onto a master's cubic (from the previous two
/// samples' parameters, extrapolated; any pairing gives a valid bound, a closer one a
/// tighter bound).
const PROJECT_STEPS: usize = 4;

/// One span sampled in every master at common curve parameters, each sample paired with
/// a parameter of its master's cubic: what bounds the span's error at every position
/// without measuring each.
///
/// # The bound
///
/// Between samples `i` and `i + 1` take each master's curve as its cubic Hermite
/// interpolant `H_j(s)` (from the samples' points and derivatives; the curve [`fit`]'s
/// measure works on), and pair it with the cubic run linearly between two parameters,
/// `B_j(u_i + s (u_{i+1} - u_i))`, with `u_0 = 0` and `u_n = 1`. At a position with blend
/// weights `w`:
/// - The blended cubic is `B_w = Σ w_j B_j`. When every master has the same `s`, the
///   X-spline's blending functions are the same in every master (they depend on `s` and the
///   parameter only), so the blended curve is `X_w(t) = Σ w_j X_j(t)` with the same
///   derivatives, and its Hermite interpolant on the same samples is `Σ w_j H_j`
///   (interpolation is linear in the data). With the pairing shared by the masters, the
///   gap of the blend is `g_w(s) = Σ w_j g_j(s)`: affine in the weights.
/// - Each `g_j` is a cubic polynomial in `s`; as a cubic Bézier its control points `c_jk`
///   bound it (convex hull): `|g_w(s)| ≤ max_k |Σ_j w_j c_jk| ≤ max_{j,k} |c_jk|` when the
///   weights are non-negative (they sum to 1). Halving by de Casteljau tightens it.
/// - As in [`fit`]'s bound, the largest `|g_w|` over the intervals bounds the two-sided
///   distance: every curve point `H_w(s)` is that close to the cubic point it is paired with,
///   and the paired cubic parameters run continuously from 0 to 1, so every cubic point is
///   paired with a curve point that close (a Fréchet bound, stronger than the Hausdorff
///   distance the measure estimates).
///
/// So [`JointSamples::hull_bound`], computed from the masters alone, bounds the error at
/// every position between them, not only the sampled ones. Where `s` differs the blend is
/// not affine in the weights. With two masters and the middle's samples the bound is then
/// that of the curve taken as quadratic in the position through the masters' and the
/// middle's curves (exact at those three; [`Fitter::gap`] adds how far another position's
/// curve lies from it). [`JointSamples::bound`] takes the blended contour's own samples at
/// one position (same bound, one position) where that misses the goal.
///
/// Limits: as in [`fit`], the bound is proven against the samples' Hermite interpolants,
/// whose own error (O(h^4) at 20 samples per segment, refined where a curve turns fast) is
/// not bounded here. With two masters the pairing moves with the position
/// ([`JointSamples::segment_bound`]); with more it is the masters' projections averaged,
/// which is loose where their cubics run at different speeds along their curves. A loose
/// bound costs a per-position bound or a measure, never a wrong answer. On the bundled
/// glyphs with their Bold master the bound between the masters meets the goal on 98 of
/// 143 contours.
struct JointSamples {
    t: Vec<f64>,
    /// Masters.
    count: usize,
    /// Per sample, then per master: the curve point and derivative (one row of `count`
    /// per sample, pushed as it is evaluated; [`JointSamples::at`]).
    rows: Vec<(Point, Vec2)>,
    /// Per master: the cubic parameter at each sample.
    u: Vec<Vec<f64>>,
    /// The middle position's curve point and derivative at each sample, when the fit has
    /// one ([`Fitter::middle`]).
    middle: Option<(Vec<Point>, Vec<Vec2>, Vec<f64>)>,
}

impl JointSamples {
    /// Samples `[a, b]` in every master (uniform, refined where any master turns fast) and
    /// projects each master's samples onto its cubic.
    fn new(
        masters: &[&XSpline],
        middle: Option<&XSpline>,
        (a, b): (f64, f64),
        cubics: &[CubicBez],
        goal: f64,
    ) -> JointSamples {
        let n = (((b - a) * SAMPLES_PER_SEGMENT).ceil() as usize).max(MIN_SAMPLES);
        let count = masters.len();
        // Room for the refinement's samples too (most spans get a few).
        let room = n + 1 + n / 2;
        let mut out = JointSamples {
            t: Vec::with_capacity(room),
            count,
            rows: Vec::with_capacity(room * count),
            u: (0..count).map(|_| Vec::with_capacity(room)).collect(),
            middle: None,
        };
        let mut runs: Vec<Run> = masters.iter().map(|m| Run::new(m)).collect();
        // The rows of samples still to push (one point and derivative per master), as a
        // stack: the next uniform sample's, then the refinement's midpoints.
        let mut stack: Vec<(Point, Vec2)> = Vec::with_capacity(count * (MAX_REFINE + 1));
        for i in 0..=n {
            let t = if i == n {
                b
            } else {
                a + (b - a) * i as f64 / n as f64
            };
            stack.extend(runs.iter_mut().map(|r| r.eval_deriv(t)));
            if i > 0 {
                out.refine(&mut runs, &mut stack, t, MAX_REFINE);
            }
            out.push(t, &stack);
            stack.clear();
        }
        let last = out.t.len() - 1;
        let powers: Vec<PowerCubic> = cubics.iter().map(PowerCubic::new).collect();
        for u in &mut out.u {
            u.push(0.0);
        }
        // Sample by sample, each master in turn: a master's projections form a chain (each
        // starts from the last ones), and the masters' chains, side by side, overlap in the
        // processor. Each master's operations are the same in either order.
        for i in 1..last {
            for (j, power) in powers.iter().enumerate() {
                let (t, u) = (&out.t, &mut out.u[j]);
                // From the last two samples' parameters, extrapolated (Newton then needs
                // a step or two).
                let guess = match i {
                    1 => u[0],
                    _ => {
                        let slope = (u[i - 1] - u[i - 2]) / (t[i - 1] - t[i - 2]);
                        (u[i - 1] + slope * (t[i] - t[i - 1])).clamp(0.0, 1.0)
                    }
                };
                let point = out.rows[i * count + j].0;
                let (near, far) = power.project_steps(point, guess, PROJECT_STEPS);
                let next = if far <= goal {
                    near
                } else {
                    // A poor start can stall at a clamp or a far branch: retry from the
                    // sample's share of the span.
                    let share = (t[i] - a) / (b - a);
                    let (alt, other) = power.project_steps(point, share, PROJECT_STEPS);
                    if other < far {
                        alt
                    } else {
                        near
                    }
                };
                u.push(next);
            }
        }
        for u in &mut out.u {
            u.push(1.0);
        }
        // The middle at the masters' samples (it does not refine them), paired with the
        // masters' cubics blended there, from the masters' pairings blended.
        if let (Some(spline), [c0, c1]) = (middle, cubics) {
            let mut run = Run::new(spline);
            let (p, d): (Vec<Point>, Vec<Vec2>) = out.t.iter().map(|&t| run.eval_deriv(t)).unzip();
            let cubic = blend_cubic(&[*c0, *c1], &[0.5, 0.5]);
            let mut u: Vec<f64> = (0..=last)
                .map(|i| 0.5 * (out.u[0][i] + out.u[1][i]))
                .collect();
            fit::project_each(&cubic, &mut u[1..last], |k| p[k + 1], REPROJECT_STEPS);
            out.middle = Some((p, d, u));
        }
        out
    }

    fn push(&mut self, t: f64, row: &[(Point, Vec2)]) {
        self.t.push(t);
        self.rows.extend_from_slice(row);
    }

    /// Master `j`'s curve point and derivative at sample `i`.
    fn at(&self, j: usize, i: usize) -> (Point, Vec2) {
        self.rows[i * self.count + j]
    }

    /// Master `j`'s curve between samples `i` and `i + 1` as a Hermite piece
    /// ([`JointSamples::hermite`]).
    fn piece(&self, j: usize, i: usize) -> [Vec2; 4] {
        let ((p0, d0), (p1, d1)) = (self.at(j, i), self.at(j, i + 1));
        self.hermite(i, [p0, p1], [d0, d1])
    }

    /// Adds the samples strictly between the last pushed and the row on top of `stack`
    /// (at `t`) that keep every master's turn between neighbours below [`fit::MAX_TURN`],
    /// bisecting at most `depth` times. The stack is as it was on return.
    fn refine(&mut self, runs: &mut [Run], stack: &mut Vec<(Point, Vec2)>, t: f64, depth: usize) {
        let count = runs.len();
        let last = self.t.len() - 1;
        let end = &stack[stack.len() - count..];
        let fast = (0..count).any(|j| {
            let (p1, d1) = end[j];
            let (p0, d0) = self.at(j, last);
            turns_fast(p0, d0, p1, d1)
        });
        if depth == 0 || !fast {
            return;
        }
        let mid = 0.5 * (self.t[last] + t);
        stack.extend(runs.iter_mut().map(|r| r.eval_deriv(mid)));
        self.refine(runs, stack, mid, depth - 1);
        self.push(mid, &stack[stack.len() - count..]);
        stack.truncate(stack.len() - count);
        self.refine(runs, stack, t, depth - 1);
    }

    /// The Hermite piece of interval `i` from its end points and derivatives, as Bézier
    /// control points.
    fn hermite(&self, i: usize, points: [Point; 2], derivs: [Vec2; 2]) -> [Vec2; 4] {
        let third = (self.t[i + 1] - self.t[i]) / 3.0;
        [
            points[0].to_vec2(),
            points[0].to_vec2() + derivs[0] * third,
            points[1].to_vec2() - derivs[1] * third,
            points[1].to_vec2(),
        ]
    }

    /// An upper bound of the two-sided distance between the blend of `cubics` at every
    /// position with non-negative weights and the X-spline blended there, when every master
    /// has the same `s` (see the type's docs). Above `goal` it stops at the first interval
    /// that exceeds it: the value then only says "over the goal".
    fn hull_bound(&self, cubics: &[CubicBez], goal: f64) -> f64 {
        if let [first, second] = cubics {
            return self.segment_bound([first, second], goal);
        }
        let count = cubics.len();
        let n = self.t.len();
        let u: Vec<f64> = (0..n)
            .map(|i| {
                let mean = self.u.iter().map(|u| u[i]).sum::<f64>() / count as f64;
                if i == 0 || i == n - 1 {
                    mean
                } else {
                    let points: Vec<Point> = (0..count).map(|j| self.at(j, i).0).collect();
                    project_jointly(cubics, &points, mean)
                }
            })
            .collect();
        let mut worst: f64 = 0.0;
        for i in 0..n - 1 {
            let pieces: Vec<[Vec2; 4]> = (0..count).map(|j| self.piece(j, i)).collect();
            let bound = paired_bound(&pieces, cubics, (u[i], u[i + 1]), goal, PAIR_SPLITS);
            worst = worst.max(bound);
            if worst > goal {
                // Over the goal is all the caller needs to know (it measures instead).
                break;
            }
        }
        worst
    }

    /// [`JointSamples::hull_bound`] for two masters, with a pairing that moves with the
    /// position: at weights `(1 - λ, λ)` sample `i` pairs with `(1 - λ) u_0i + λ u_1i`,
    /// each master's own projection at its end of the axis. Then the gap of interval `i` is
    /// a polynomial of degree 3 in `s` and 4 in `λ` (the cubics are cubic in the pairing,
    /// which is linear in `λ`, and the blend multiplies by `λ` once more); its Bernstein
    /// coefficients on `[0, 1]²`, found from its values at five positions, bound it at every
    /// position between the masters (convex hull again), and the pairing suits both ends.
    fn segment_bound(&self, cubics: [&CubicBez; 2], goal: f64) -> f64 {
        let n = self.t.len();
        let powers = cubics.map(PowerCubic::new);
        // The blended cubics at the nets' five positions, per range of the axis.
        let whole_axis = &along_axis(&powers, (0.0, 1.0));
        let halves = self
            .middle
            .as_ref()
            .map(|_| [(0.0, 0.5), (0.5, 1.0)].map(|range| along_axis(&powers, range)));
        let mut worst: f64 = 0.0;
        for i in 0..n - 1 {
            let pieces: [[Vec2; 4]; 2] = std::array::from_fn(|j| self.piece(j, i));
            let ends = |j: usize| (self.u[j][i], self.u[j][i + 1]);
            let bound = match &self.middle {
                None => {
                    let curve = Curve {
                        pieces,
                        middle: None,
                    };
                    let ends = [ends(0), ends(1)];
                    interval_net_bound(
                        curve,
                        cubics,
                        whole_axis,
                        (0.0, 1.0),
                        ends,
                        [None, None],
                        goal,
                        PAIR_SPLITS,
                    )
                }
                Some((p, d, u)) => {
                    // The whole axis paired linearly between the masters' projections;
                    // where that misses the goal, two halves of the axis, each paired
                    // linearly between its ends' projections (the middle's own at λ = 1/2).
                    // The nets' columns at λ = 0 and 1 (the same pairing in the whole axis
                    // and its half) and at λ = 1/2 (in both halves) are computed once.
                    let middle = Some(self.hermite(i, [p[i], p[i + 1]], [d[i], d[i + 1]]));
                    let curve = Curve { pieces, middle };
                    let whole = [ends(0), ends(1)];
                    let first_column = net_column(&curve, &whole_axis[0], 0.0, ends(0));
                    let last_column = net_column(&curve, &whole_axis[4], 1.0, ends(1));
                    let once = interval_net_bound(
                        curve,
                        cubics,
                        whole_axis,
                        (0.0, 1.0),
                        whole,
                        [Some(first_column), Some(last_column)],
                        goal,
                        0,
                    );
                    if once <= WHOLE_AXIS * goal {
                        once
                    } else {
                        let centre = (u[i], u[i + 1]);
                        let low = [ends(0), centre];
                        let high = [centre, ends(1)];
                        let [low_axis, high_axis] = halves.as_ref().expect("with the middle");
                        let centre_column = net_column(&curve, &low_axis[4], 0.5, centre);
                        let first = interval_net_bound(
                            curve,
                            cubics,
                            low_axis,
                            (0.0, 0.5),
                            low,
                            [Some(first_column), Some(centre_column)],
                            goal,
                            PAIR_SPLITS,
                        );
                        if first > goal {
                            first
                        } else {
                            let second = interval_net_bound(
                                curve,
                                cubics,
                                high_axis,
                                (0.5, 1.0),
                                high,
                                [Some(centre_column), Some(last_column)],
                                goal,
                                PAIR_SPLITS,
                            );
                            first.max(second)
                        }
                    }
                }
            };
            worst = worst.max(bound);
            if worst > goal {
                break;
            }
        }
        worst
    }

    /// The same bound at one position (`probe`), with the pairing blended by its weights.
    /// `from`: where the probe's curve samples come from ([`Source`]); from its own X-spline
    /// (or the middle's samples), the blended cubic's ends, on the blend of the masters'
    /// curves, may lie off it: the bound counts that gap too. Above `goal` it stops as
    /// [`JointSamples::hull_bound`] does.
    fn bound(&self, cubics: &[CubicBez], probe: &Probe, from: Source, goal: f64) -> f64 {
        let w = &probe.weights;
        let n = self.t.len();
        let u: Vec<f64> = (0..n)
            .map(|i| match i {
                0 => 0.0,
                i if i == n - 1 => 1.0,
                i => w
                    .iter()
                    .zip(&self.u)
                    .map(|(w, u)| w * u[i])
                    .sum::<f64>()
                    .clamp(0.0, 1.0),
            })
            .collect();
        let mut run = Run::new(&probe.spline);
        let sample = |i: usize| -> (Point, Vec2) {
            match (from, &self.middle) {
                (Source::Blend, _) => {
                    let mut p = Vec2::ZERO;
                    let mut d = Vec2::ZERO;
                    for (j, wj) in w.iter().enumerate() {
                        let (pj, dj) = self.at(j, i);
                        p += *wj * pj.to_vec2();
                        d += *wj * dj;
                    }
                    (p.to_point(), d)
                }
                (Source::Middle, Some((p, d, _))) => (p[i], d[i]),
                _ => run.eval_deriv(self.t[i]),
            }
        };
        let cubic = blend_cubic(cubics, w);
        let samples: Vec<(Point, Vec2)> = (0..n).map(sample).collect();
        // The blended pairing, moved to the blended cubic's nearest points (from there the
        // Newton steps are few).
        let mut u = u.to_vec();
        fit::project_each(
            &cubic,
            &mut u[1..n - 1],
            |k| samples[k + 1].0,
            REPROJECT_STEPS,
        );
        let mut worst: f64 = 0.0;
        for i in 0..n - 1 {
            let (left, right) = (samples[i], samples[i + 1]);
            let piece = self.hermite(i, [left.0, right.0], [left.1, right.1]);
            let bound = paired_bound(&[piece], &[cubic], (u[i], u[i + 1]), goal, PAIR_SPLITS);
            worst = worst.max(bound);
            if worst > goal {
                break;
            }
        }
        worst
    }
}

/// Where [`JointSamples::bound`] takes a position's curve samples from.
#[derive(Clone, Copy)]
enum Source {
    /// The blend of the masters' samples: every master has the same `s` (or the position
    /// is a master).
    Blend,
    /// The middle position's samples, taken with the masters' ([`Fitter::middle`]).
    Middle,
    /// The position's own X-spline, evaluated at every sample.
    Own,
}

/// Bounds the gaps between the curve pieces `pieces` (one per cubic, Bézier control
/// points) and `cubics` run from `u0` to `u1`, for every convex combination of the pairs
/// ([`hull_of_gaps`]). Over `goal`, each piece is halved and its midpoint paired with the
/// cubics' parameter nearest it (averaged over the cubics), at most `splits` times: where a
/// curve's speed changes fast, a linear pairing drifts along the cubic by more than the
/// distance itself. Any pairing gives a valid bound; a closer one a tighter bound.
fn paired_bound(
    pieces: &[[Vec2; 4]],
    cubics: &[CubicBez],
    (u0, u1): (f64, f64),
    goal: f64,
    splits: usize,
) -> f64 {
    let gap = |(piece, cubic): (&[Vec2; 4], &CubicBez)| -> [Vec2; 4] {
        let run = cubic.subsegment(u0..u1);
        let paired = [run.p0, run.p1, run.p2, run.p3];
        std::array::from_fn(|k| piece[k] - paired[k].to_vec2())
    };
    let bound = if let ([piece], [cubic]) = (pieces, cubics) {
        // One pair (a single position): no allocation.
        hull_of_gaps(&[gap((piece, cubic))], goal, GAP_HALVINGS)
    } else {
        let gaps: Vec<[Vec2; 4]> = pieces.iter().zip(cubics).map(gap).collect();
        hull_of_gaps(&gaps, goal, GAP_HALVINGS)
    };
    if bound <= goal || splits == 0 {
        return bound;
    }
    let (left, right): (Vec<_>, Vec<_>) = pieces.iter().map(halve).unzip();
    let um = left
        .iter()
        .zip(cubics)
        .map(|(half, cubic)| {
            fit::project_onto(cubic, half[3].to_point(), 0.5 * (u0 + u1), PROJECT_STEPS)
        })
        .sum::<f64>()
        / cubics.len() as f64;
    paired_bound(&left, cubics, (u0, um), goal, splits - 1).max(paired_bound(
        &right,
        cubics,
        (um, u1),
        goal,
        splits - 1,
    ))
}

/// [`JointSamples::segment_bound`] on one interval: the curve pieces `pieces` (one per
/// master) paired with `cubics` from `ends[j].0` to `ends[j].1` in master `j`, the pairing
/// blended with the position. Over `goal`, the interval is halved and its midpoint paired
/// with each master's nearest cubic parameter, at most `splits` times (as [`paired_bound`]).
/// `known`: the net's columns at `l0` and `l1` ([`net_column`]) when the caller has them.
#[allow(clippy::too_many_arguments)]
fn interval_net_bound(
    curve: Curve,
    cubics: [&CubicBez; 2],
    blends: &[PowerCubic; 5],
    (l0, l1): (f64, f64),
    ends: [(f64, f64); 2],
    known: [Option<[Vec2; 4]>; 2],
    goal: f64,
    splits: usize,
) -> f64 {
    // The gap's control points in `s` at μ = 0, 1/4, ..., 1 (λ = l0 + μ (l1 - l0)), one
    // column per μ (built in place: zeroed arrays cost a `memset` per call).
    let columns: [[Vec2; 4]; 5] = std::array::from_fn(|m| {
        let given = match m {
            0 => known[0],
            4 => known[1],
            _ => None,
        };
        given.unwrap_or_else(|| {
            let mu = m as f64 / 4.0;
            let lambda = l0 + mu * (l1 - l0);
            let u0 = (1.0 - mu) * ends[0].0 + mu * ends[1].0;
            let u1 = (1.0 - mu) * ends[0].1 + mu * ends[1].1;
            net_column(&curve, &blends[m], lambda, (u0, u1))
        })
    });
    let net: [[Vec2; 5]; 4] =
        std::array::from_fn(|k| lambda_bernstein(&std::array::from_fn(|m| columns[m][k])));
    let bound = net_bound(&net, goal, GAP_HALVINGS);
    if bound <= goal || splits == 0 {
        return bound;
    }
    let (left, right) = curve.halve();
    // The midpoint's pairing at each end of the range: the nearest parameter of the cubic
    // there (a master's own, else the blend).
    let mid = |e: usize, lambda: f64| {
        let (a, b) = ends[e];
        let guess = 0.5 * (a + b);
        if lambda == 0.0 || lambda == 1.0 {
            let j = lambda as usize;
            let point = left.pieces[j][3].to_point();
            fit::project_onto(cubics[j], point, guess, PROJECT_STEPS)
        } else {
            let point = left.at(lambda)[3].to_point();
            let cubic = blend_cubic(&[*cubics[0], *cubics[1]], &[1.0 - lambda, lambda]);
            fit::project_onto(&cubic, point, guess, PROJECT_STEPS)
        }
    };
    let (m0, m1) = (mid(0, l0), mid(1, l1));
    let left = interval_net_bound(
        left,
        cubics,
        blends,
        (l0, l1),
        [(ends[0].0, m0), (ends[1].0, m1)],
        [None, None],
        goal,
        splits - 1,
    );
    if left > goal {
        return left;
    }
    let right = interval_net_bound(
        right,
        cubics,
        blends,
        (l0, l1),
        [(m0, ends[0].1), (m1, ends[1].1)],
        [None, None],
        goal,
        splits - 1,
    );
    left.max(right)
}

/// One column of [`interval_net_bound`]'s values: the gap's control points in `s` at
/// position `lambda` between the curve there and `blend` (the cubics blended there) run
/// from `u0` to `u1`.
fn net_column(curve: &Curve, blend: &PowerCubic, lambda: f64, (u0, u1): (f64, f64)) -> [Vec2; 4] {
    let paired = blend.subsegment(u0, u1);
    let at = curve.at(lambda);
    std::array::from_fn(|k| at[k] - paired[k])
}

/// The blend of two masters' cubics (power form) at the five positions
/// `λ = l0 + μ (l1 - l0)`, `μ = 0, 1/4, ..., 1`, where [`interval_net_bound`] takes the gap.
fn along_axis(powers: &[PowerCubic; 2], (l0, l1): (f64, f64)) -> [PowerCubic; 5] {
    std::array::from_fn(|m| {
        let mu = m as f64 / 4.0;
        let lambda = l0 + mu * (l1 - l0);
        // At a master the blend is its cubic (the same values, without the sums).
        match lambda {
            0.0 => powers[0],
            1.0 => powers[1],
            _ => powers[0].blend(&powers[1], lambda),
        }
    })
}

/// One interval of the curve at every position between two masters, as Hermite pieces
/// (Bézier control points): linear in the position through the masters' pieces, or, with
/// the middle position's piece, quadratic through the three.
#[derive(Clone, Copy)]
struct Curve {
    pieces: [[Vec2; 4]; 2],
    middle: Option<[Vec2; 4]>,
}

impl Curve {
    /// Both halves (de Casteljau in `s`, every piece).
    fn halve(&self) -> (Curve, Curve) {
        let (left0, right0) = halve(&self.pieces[0]);
        let (left1, right1) = halve(&self.pieces[1]);
        let halves = self.middle.as_ref().map(halve);
        (
            Curve {
                pieces: [left0, left1],
                middle: halves.map(|h| h.0),
            },
            Curve {
                pieces: [right0, right1],
                middle: halves.map(|h| h.1),
            },
        )
    }

    /// The piece at position `λ` (weights `(1 - λ, λ)`).
    #[inline]
    fn at(&self, lambda: f64) -> [Vec2; 4] {
        let [a, b] = &self.pieces;
        // Where the weights are 1 and 0, the piece as it is (the same values, without the
        // sums; up to the sign of a zero).
        match (&self.middle, lambda) {
            (_, 0.0) => return *a,
            (_, 1.0) => return *b,
            (Some(m), 0.5) => return *m,
            _ => {}
        }
        match &self.middle {
            None => std::array::from_fn(|k| (1.0 - lambda) * a[k] + lambda * b[k]),
            Some(m) => {
                let [wa, wb, wm] = quadratic_weights(lambda);
                std::array::from_fn(|k| wa * a[k] + wb * b[k] + wm * m[k])
            }
        }
    }
}

/// Bernstein coefficients (degree 4) from values at `λ = 0, 1/4, 1/2, 3/4, 1`: the inverse
/// of the basis evaluated there. The end coefficients are the end values; the inner rows
/// are `[-13/12, 4, -3, 4/3, -1/4]`, `[13/18, -32/9, 20/3, -32/9, 13/18]` and the first
/// reversed (written out: a loop over the matrix cost three times as many instructions).
fn lambda_bernstein(v: &[Vec2; 5]) -> [Vec2; 5] {
    let (outer, inner) = (v[0] + v[4], v[1] + v[3]);
    [
        v[0],
        -13.0 / 12.0 * v[0] + 4.0 * v[1] - 3.0 * v[2] + 4.0 / 3.0 * v[3] - 0.25 * v[4],
        13.0 / 18.0 * outer - 32.0 / 9.0 * inner + 20.0 / 3.0 * v[2],
        -0.25 * v[0] + 4.0 / 3.0 * v[1] - 3.0 * v[2] + 4.0 * v[3] - 13.0 / 12.0 * v[4],
        v[4],
    ]
}

/// The largest coefficient length of a tensor-product Bézier net (degree 3 in `s`, 4 in
/// `λ`), which bounds it on the unit square; halved in both directions up to `halvings`
/// times while it exceeds `goal`, unless it exceeds [`NET_HOPELESS`] times the goal.
fn net_bound(net: &[[Vec2; 5]; 4], goal: f64, halvings: usize) -> f64 {
    let bound = longest(net.iter().flatten());
    if bound <= goal || halvings == 0 || bound > NET_HOPELESS * goal {
        return bound;
    }
    // In `s`: each column's four control points; in `λ`: each row's five.
    let mut halves = [[[Vec2::ZERO; 5]; 4]; 2];
    for m in 0..5 {
        let (left, right) = halve(&[net[0][m], net[1][m], net[2][m], net[3][m]]);
        for k in 0..4 {
            halves[0][k][m] = left[k];
            halves[1][k][m] = right[k];
        }
    }
    let mut worst: f64 = 0.0;
    for half in &halves {
        let mut quarters = [[[Vec2::ZERO; 5]; 4]; 2];
        for k in 0..4 {
            let (low, high) = halve_quartic(&half[k]);
            quarters[0][k] = low;
            quarters[1][k] = high;
        }
        for quarter in &quarters {
            worst = worst.max(net_bound(quarter, goal, halvings - 1));
            if worst > goal && halvings == 1 {
                return worst;
            }
        }
    }
    worst
}

/// The largest length of `vectors` (0 for none): one square root, of the largest squared
/// length (the same value as the largest of the lengths: the root is monotone and
/// correctly rounded).
fn longest<'v>(vectors: impl IntoIterator<Item = &'v Vec2>) -> f64 {
    vectors
        .into_iter()
        .fold(0.0, |m: f64, v| m.max(v.hypot2()))
        .sqrt()
}

/// De Casteljau at one half, degree 4.
fn halve_quartic(c: &[Vec2; 5]) -> ([Vec2; 5], [Vec2; 5]) {
    let mut rows = *c;
    let mut left = [Vec2::ZERO; 5];
    let mut right = [Vec2::ZERO; 5];
    for level in 0..5 {
        left[level] = rows[0];
        right[4 - level] = rows[4 - level];
        for k in 0..4 - level {
            rows[k] = (rows[k] + rows[k + 1]) * 0.5;
        }
    }
    (left, right)
}

/// The largest control-point length of the cubic Béziers `gaps` (which bounds every convex
/// combination of them, at every parameter), halved by de Casteljau up to `halvings` times
/// while it exceeds `goal`.
fn hull_of_gaps(gaps: &[[Vec2; 4]], goal: f64, halvings: usize) -> f64 {
    let bound = longest(gaps.iter().flatten());
    if bound <= goal || halvings == 0 {
        return bound;
    }
    let (left, right): (Vec<_>, Vec<_>) = gaps.iter().map(halve).unzip();
    hull_of_gaps(&left, goal, halvings - 1).max(hull_of_gaps(&right, goal, halvings - 1))
}

/// Evaluates a contour at mostly increasing parameters, keeping the current segment (the
/// same values as [`XSpline::eval_deriv`], which locates and assembles the segment for
/// every point).
struct Run<'a> {
    spline: &'a XSpline,
    /// The segment last evaluated, prepared ([`Prepared`]), and its index (`usize::MAX`
    /// before the first).
    current: (usize, Prepared),
}

impl<'a> Run<'a> {
    fn new(spline: &'a XSpline) -> Run<'a> {
        let none = Segment {
            q: [Point::ZERO; 4],
            s1: 0.0,
            s2: 0.0,
        };
        Run {
            spline,
            current: (usize::MAX, Prepared::new(&none)),
        }
    }

    fn eval_deriv(&mut self, big_t: f64) -> (Point, Vec2) {
        let (j, t) = self.spline.locate(big_t);
        if self.current.0 != j {
            self.current = (j, Prepared::new(&self.spline.segment(j)));
        }
        self.current.1.eval_deriv(t)
    }
}

/// The Lagrange weights of the masters and their middle (in that order) at position `λ`
/// of two masters: the quadratic in `λ` through them.
fn quadratic_weights(lambda: f64) -> [f64; 3] {
    [
        (1.0 - lambda) * (1.0 - 2.0 * lambda),
        lambda * (2.0 * lambda - 1.0),
        4.0 * lambda * (1.0 - lambda),
    ]
}

/// De Casteljau at one half.
fn halve(c: &[Vec2; 4]) -> ([Vec2; 4], [Vec2; 4]) {
    let m01 = (c[0] + c[1]) * 0.5;
    let m12 = (c[1] + c[2]) * 0.5;
    let m23 = (c[2] + c[3]) * 0.5;
    let a = (m01 + m12) * 0.5;
    let b = (m12 + m23) * 0.5;
    let mid = (a + b) * 0.5;
    ([c[0], m01, a, mid], [mid, b, m23, c[3]])
}

/// The parameter at which `cubics` come nearest `points` in the least-squares sense (one
/// point per cubic), by Newton's method from `guess` within `[0, 1]`.
fn project_jointly(cubics: &[CubicBez], points: &[Point], guess: f64) -> f64 {
    let mut u = guess;
    for _ in 0..PROJECT_STEPS {
        let (mut slope, mut curvature) = (0.0, 0.0);
        for (cubic, p) in cubics.iter().zip(points) {
            let r = cubic.eval(u) - *p;
            let v = cubic.deriv().eval(u).to_vec2();
            let a = cubic.deriv().deriv().eval(u).to_vec2();
            slope += r.dot(v);
            curvature += v.dot(v) + r.dot(a);
        }
        if curvature <= 1e-300 {
            break;
        }
        let next = (u - slope / curvature).clamp(0.0, 1.0);
        let done = (next - u).abs() < 1e-10;
        u = next;
        if done {
            break;
        }
    }
    u
}

/// How far the blend of the masters' curve points, `Σ w_i C_i(T)`, strays from the blended
/// X-spline's curve (the largest distance over samples of `T`, each the nearest curve point
/// found by `steps` Newton steps from `T`; with none, the distance at `T`, never less).
/// Zero when all masters have the same `s`; a span's vertices lie on the masters' curves,
/// so at the probe they are this far off at worst.
fn blend_gap(masters: &[&XSpline], probe: &Probe, steps: usize) -> f64 {
    let spline = &probe.spline;
    if masters.iter().all(|m| {
        m.points()
            .iter()
            .zip(spline.points())
            .all(|(p, q)| p.s == q.s)
    }) {
        return 0.0;
    }
    // Segment by segment (the masters' segments assembled once each, the probe's kept by
    // a `Run`): the same values as `XSpline::eval` and `fit::distance_to_curve`.
    let mut run = Run::new(spline);
    let mut segments: Vec<Prepared> = Vec::with_capacity(masters.len());
    let mut gap: f64 = 0.0;
    for j in 0..spline.segment_count() {
        segments.clear();
        segments.extend(masters.iter().map(|m| Prepared::new(&m.segment(j))));
        for i in 0..GAP_SAMPLES_PER_SEGMENT {
            let t = (j * GAP_SAMPLES_PER_SEGMENT + i) as f64 / GAP_SAMPLES_PER_SEGMENT as f64;
            let local = t - j as f64;
            let q = segments
                .iter()
                .zip(&probe.weights)
                .fold(Vec2::ZERO, |acc, (m, w)| acc + *w * m.eval(local).to_vec2())
                .to_point();
            // Newton on the curve parameter towards the nearest point, from the same `T`.
            let unbounded = (f64::NEG_INFINITY, f64::INFINITY);
            let curve = |t: f64| run.eval_deriv(t);
            gap = gap.max(fit::distance_to_curve_by(curve, q, t, unbounded, steps));
        }
    }
    gap
}

#[cfg(test)]
mod tests {
    use super::*;

    fn contour(points: &[(f64, f64, f64)]) -> XSpline {
        XSpline::new(
            points
                .iter()
                .map(|&(x, y, s)| ControlPoint::new(x, y, s))
                .collect(),
        )
        .unwrap()
    }

    #[test]
    fn blends_are_exact_at_the_masters_and_linear_with_equal_shapes() {
        let a = contour(&[(0., 0., 0.), (300., 0., -1.), (150., 260., 1.)]);
        let b = contour(&[(10., 0., 0.), (330., 20., -1.), (150., 300., 1.)]);
        assert_eq!(blend(&[&a, &b], &[1.0, 0.0]).unwrap(), a);
        assert_eq!(blend(&[&a, &b], &[0.0, 1.0]).unwrap(), b);
        let mid = blend(&[&a, &b], &[0.5, 0.5]).unwrap();
        let probe = Probe {
            weights: vec![0.5, 0.5],
            spline: mid.clone(),
        };
        assert_eq!(blend_gap(&[&a, &b], &probe, BLEND_GAP_STEPS), 0.0);
        // Same `s`: the blended curve is the blend of the curves, point for point.
        let t = 1.37;
        let expected = (a.eval(t).to_vec2() + b.eval(t).to_vec2()) * 0.5;
        assert!((mid.eval(t).to_vec2() - expected).hypot() < 1e-12);
        // Different `s`: it is not, and the gap says by how much.
        let c = contour(&[(10., 0., 0.), (330., 20., 0.5), (150., 300., 1.)]);
        let mid = blend(&[&a, &c], &[0.5, 0.5]).unwrap();
        let gap = blend_gap(
            &[&a, &c],
            &Probe {
                weights: vec![0.5, 0.5],
                spline: mid,
            },
            BLEND_GAP_STEPS,
        );
        assert!(gap > 1.0 && gap < 100.0, "{gap}");
    }

    /// Two masters whose `s` differs everywhere, and positions between them.
    fn different_shapes() -> (XSpline, XSpline, Vec<(Vec<f64>, XSpline)>) {
        let a = contour(&[
            (0., 0., 0.5),
            (300., 0., -0.5),
            (320., 250., 1.),
            (60., 300., 0.3),
        ]);
        let b = contour(&[
            (-20., -30., 0.),
            (340., -20., 0.4),
            (350., 290., 0.2),
            (40., 340., -0.8),
        ]);
        let blends = [0.1, 0.3, 0.7, 0.9]
            .iter()
            .map(|&l| {
                let weights = vec![1.0 - l, l];
                let spline = blend(&[&a, &b], &weights).unwrap();
                (weights, spline)
            })
            .collect();
        (a, b, blends)
    }

    #[test]
    fn the_goal_at_a_blend_is_the_same_with_the_short_cut() {
        let (a, b, blends) = different_shapes();
        let masters = [&a, &b];
        // A small tolerance (the blend gap exceeds the goal: Newton decides) and a large one
        // (the distance at the same parameter settles it).
        let (mut newton, mut short) = (0, 0);
        for tolerance in [0.05, 1.0, 50.0] {
            let fitter = Fitter::new(&masters, blends.clone(), tolerance);
            for k in masters.len()..fitter.probes.len() {
                let probe = &fitter.probes[k];
                let same = blend_gap(&masters, probe, 0);
                let nearest = blend_gap(&masters, probe, BLEND_GAP_STEPS);
                assert!(nearest > 0.0 && nearest <= same, "{nearest} {same}");
                let expected = fitter.goal.max(VERTEX_MARGIN * nearest);
                assert_eq!(fitter.goal_at(k), expected);
                if VERTEX_MARGIN * same <= fitter.goal {
                    short += 1;
                } else {
                    newton += 1;
                }
            }
        }
        assert!(newton > 0 && short > 0, "{newton} {short}");
    }

    #[test]
    fn gap_tables_filled_segment_by_segment_agree_in_any_order() {
        let (a, b, blends) = different_shapes();
        let masters = [&a, &b];
        let forward = Fitter::new(&masters, blends.clone(), 1.0);
        let backward = Fitter::new(&masters, blends, 1.0);
        assert_eq!(forward.middle, Some(2));
        let n = a.segment_count();
        let steps = forward.gap_steps();
        for k in 3..forward.probes.len() {
            let ahead: Vec<f64> = (0..n)
                .map(|j| forward.gap(k, j as f64, (j + 1) as f64))
                .collect();
            let behind: Vec<f64> = (0..n)
                .rev()
                .map(|j| backward.gap(k, j as f64, (j + 1) as f64))
                .collect();
            assert!(ahead.iter().eq(behind.iter().rev()));
            // Around the contour's start, and the whole contour.
            let around = forward.gap(k, n as f64 - 0.5, n as f64 + 0.5);
            assert_eq!(around, backward.gap(k, -0.5, 0.5));
            let whole = forward.gap(k, 0.0, n as f64);
            assert_eq!(whole, ahead.iter().copied().fold(0.0, f64::max));
            // Each segment's value bounds the difference from the quadratic interpolant at
            // its grid points (the hull's end points), computed here directly.
            let [wa, wb, wm] = quadratic_weights(forward.probes[k].weights[1]);
            let middle = &forward.probes[2].spline;
            for (j, value) in ahead.iter().enumerate() {
                let mut worst: f64 = 0.0;
                for i in 0..=steps {
                    let t = j as f64 + i as f64 / steps as f64;
                    let t = if i == steps { t - 1e-12 } else { t };
                    let quadratic = wa * a.eval(t).to_vec2()
                        + wb * b.eval(t).to_vec2()
                        + wm * middle.eval(t).to_vec2();
                    let own = forward.probes[k].spline.eval(t).to_vec2();
                    worst = worst.max((own - quadratic).hypot());
                }
                assert!(worst > 0.0 && worst <= value + 1e-9, "{worst} {value}");
            }
        }
    }

    #[test]
    fn longest_and_a_run_give_the_values_they_replace() {
        // One root of the largest squared length: the largest length, bit for bit.
        let vectors: Vec<Vec2> = (0..210)
            .map(|i| {
                let x = (i as f64 * 0.37).sin() * 10f64.powi(i % 7 - 3);
                let y = (i as f64 * 1.91).cos() * 10f64.powi(i % 5 - 2);
                Vec2::new(x, y)
            })
            .collect();
        for chunk in vectors.chunks(7) {
            let expected = chunk.iter().map(|v| v.hypot()).fold(0.0, f64::max);
            assert_eq!(longest(chunk).to_bits(), expected.to_bits());
        }
        assert_eq!(longest(&[] as &[Vec2]), 0.0);
        // A run over the contour and around it again, forwards and back: the values of
        // `XSpline::eval_deriv`.
        let (a, _, _) = different_shapes();
        let n = a.segment_count() as f64;
        let mut run = Run::new(&a);
        for i in (0..=80).chain((0..=80).rev()) {
            let t = -1.0 + i as f64 * (2.0 * n + 1.0) / 80.0;
            assert_eq!(run.eval_deriv(t), a.eval_deriv(t), "{t}");
        }
    }

    #[test]
    fn a_net_with_its_end_columns_given_is_the_net_without() {
        let c0 = CubicBez::new((0., 0.), (40., 90.), (160., 110.), (200., 0.));
        let c1 = CubicBez::new((10., -20.), (30., 120.), (190., 150.), (230., -10.));
        let powers = [PowerCubic::new(&c0), PowerCubic::new(&c1)];
        let piece = |dx: f64, dy: f64| -> [Vec2; 4] {
            [
                Vec2::new(dx, dy),
                Vec2::new(20.0 + dx, 50.0 - dy),
                Vec2::new(60.0 - dx, 70.0 + dy),
                Vec2::new(95.0 + dx, 85.0),
            ]
        };
        let curve = Curve {
            pieces: [piece(0.3, -0.2), piece(7.0, -19.0)],
            middle: Some(piece(4.0, -10.0)),
        };
        let ends = [(0.0, 0.41), (0.02, 0.45)];
        let mut seen = (false, false);
        for (range, goal) in [((0.0, 0.5), 0.5), ((0.5, 1.0), 2.0), ((0.0, 1.0), 40.0)] {
            let blends = along_axis(&powers, range);
            let known = [
                Some(net_column(&curve, &blends[0], range.0, ends[0])),
                Some(net_column(&curve, &blends[4], range.1, ends[1])),
            ];
            let cubics = [&c0, &c1];
            let args = (curve, cubics, &blends, range, ends);
            let without =
                interval_net_bound(args.0, args.1, args.2, args.3, args.4, [None; 2], goal, 3);
            let with = interval_net_bound(args.0, args.1, args.2, args.3, args.4, known, goal, 3);
            assert_eq!(with.to_bits(), without.to_bits());
            seen = (seen.0 || with <= goal, seen.1 || with > goal);
        }
        // Both a net within the goal and one over it (halved with fresh pairings).
        assert_eq!(seen, (true, true));
    }
}
