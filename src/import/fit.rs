//! The fitting problem in reverse: an original contour -> X-spline control points.
//!
//! Break points of the original (corners, ends of straight segments) become `s = 0` points
//! fixed at their place; a straight edge between two of them needs nothing more. Each smooth
//! stretch between break points (or a whole contour without break points, a loop) gets
//! interior points, found like this:
//!
//! - For fixed shapes and a fixed curve parameter, an X-spline point is a fixed convex
//!   combination of four control points, so the curve is linear in the positions. Samples
//!   of the original, each assigned a curve parameter, make the best positions a linear
//!   least-squares problem (small dense normal equations).
//! - The curve leaves a sharp point toward its neighbour, so the neighbours of a stretch's
//!   sharp ends are held on the original's tangent rays (one unknown each, at least
//!   1 % of the way to the next point, never behind the corner): the X-spline
//!   leaves every corner in the original's direction. Where that costs a point, the
//!   neighbours at corners (not at smooth joins) are set free ([`FREE_CORNERS`]).
//! - Alternate: solve positions, re-assign parameters by projecting each sample onto the
//!   new curve (damped Newton steps), a few rounds.
//! - Measure the two-sided distance: original samples to the curve (their projections),
//!   and dense curve samples to the original (kurbo `nearest` on the original segments).
//! - Search the point count: doubling, then bisection, for the fewest points that meet the
//!   target (each count fitted from scratch); then [`ALTERNATIVES`] (other shapes, other
//!   spacing) are tried with one point fewer while one of them still meets the target.
//!
//! What works (measured on DejaVu Sans, A–Z a–z 0–9 at 1/1000 em): approximating points
//! (`s = 1`, B-spline-like) need far fewer points than interpolating ones (`s = -1`:
//! 1812 points against 1245 with s = 1 alone); points crowded toward the sharp ends
//! (cosine spacing) save about a fifth, because near an `s = 0` point the X-spline leaves
//! straight and needs short segments to follow a curved original.
//!
//! Masters ([`fit_compatible`], for [`super::masters`]): the same search per stretch for
//! all masters at once, with shared sample places and shared curve parameters, so that a
//! blend of the fitted masters follows the same blend of the originals.
//!
//! Limits: the distances are measured by sampling (dense, but not a proof); the caller
//! re-measures the final rounded contour independently ([`contour_error`]).

use kurbo::{ParamCurve, ParamCurveArclen, ParamCurveNearest, PathSeg, Point, Rect, Shape, Vec2};

use super::contour::{end_tangent, start_tangent, turn_degrees, Cut, Piece, CORNER_DEGREES};

use crate::xspline::{Basis, ControlPoint, XSpline};

/// The settings of the point-count search: approximating points (`s = 1`, B-spline-like)
/// throughout, initial points crowded toward sharp ends.
pub const PRIMARY: Settings = Settings {
    shapes: Shapes {
        inner: 1.0,
        end: 1.0,
    },
    grade: 0.9,
    free_corners: false,
};

/// How far above the target the primary fit with one point fewer may miss for the
/// [`ALTERNATIVES`] to be tried at that count.
const ALTERNATIVES_REACH: f64 = 2.0;

/// Point counts the search walks down one at a time from its first guess before it takes
/// doubling steps.
const DOWN_ONE_BY_ONE: usize = 2;

/// Tried before the [`ALTERNATIVES`], with one point fewer than the search found, where an
/// open stretch has two or more interior points and ends at a corner of the original. A
/// run of two TrueType quadratics mostly needs three held points, and two free ones at
/// shape 0.8 (the best of 0.1 to 1 on the 64 CJK glyphs' runs) come within about 0.45
/// of the held fit's error with two.
pub const FREE_CORNERS: [Settings; 2] = [
    Settings {
        shapes: Shapes {
            inner: 0.8,
            end: 0.8,
        },
        grade: 0.9,
        free_corners: true,
    },
    Settings {
        shapes: Shapes {
            inner: 1.0,
            end: 1.0,
        },
        grade: 0.9,
        free_corners: true,
    },
];

/// Tried after the primary search, each with one point fewer than it found.
pub const ALTERNATIVES: [Settings; 5] = [
    Settings {
        shapes: Shapes {
            inner: 1.0,
            end: 0.75,
        },
        grade: 0.9,
        free_corners: false,
    },
    Settings {
        shapes: Shapes {
            inner: 1.0,
            end: 1.0,
        },
        grade: 0.6,
        free_corners: false,
    },
    Settings {
        shapes: Shapes {
            inner: 1.0,
            end: 0.75,
        },
        grade: 1.0,
        free_corners: false,
    },
    Settings {
        shapes: Shapes {
            inner: 0.75,
            end: 1.0,
        },
        grade: 0.9,
        free_corners: false,
    },
    Settings {
        shapes: Shapes {
            inner: 1.0,
            end: 1.0,
        },
        grade: 0.3,
        free_corners: false,
    },
];

/// Shapes and spacing of a stretch's initial points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Shape values of the initial points.
    pub shapes: Shapes,
    /// How strongly the initial points of an open stretch crowd toward its sharp ends
    /// (0 = even spacing, 1 = cosine spacing), where the X-spline leaves straight and
    /// needs short segments to follow a curved original.
    pub grade: f64,
    /// Whether the neighbour of a sharp end at a corner of the original (not at a smooth
    /// join) is left free instead of held on the original's tangent ray: two more unknowns
    /// per stretch, bought where the held fit needs one point more.
    pub free_corners: bool,
}

/// The shape values of a stretch's interior points: `end` for the two points next to its
/// sharp ends, `inner` for the others (a loop uses `inner` throughout). At a sharp end
/// the curve leaves toward the next control point, which therefore sits on the original's
/// tangent, off the curve: an approximating (`s > 0`) point fits there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shapes {
    /// Shape of the interior points.
    pub inner: f64,
    /// Shape of the two points next to the sharp ends.
    pub end: f64,
}

/// Rounds of (solve positions, re-project parameters) per fit, at most. With the
/// distance measured across the curve ([`TANGENTIAL`]) a fit settles in a few rounds; on
/// the 64 CJK glyphs of `benches/import.sh`, 20 rounds instead of 8 save 2 points of 3285.
const ROUNDS: usize = 8;
/// Weight of the distance along the curve in the least squares after the first round
/// (across it: 1). A sample's parameter is only an estimate of its foot point, so the
/// distance along the curve is mostly a parameter error; counting it in full (1.0) made
/// the rounds creep toward the fit over 20 rounds and more (tangent-distance minimisation,
/// a Gauss-Newton step for the true distance; the small weight keeps it well posed).
/// On the 64 CJK glyphs: 3285 points in 0.19 s against 3321 in 0.29 s with 1.0.
const TANGENTIAL: f64 = 0.003;
/// A fit has converged when no point moved by more than this share of the target in a
/// round: later rounds change the error by far less than the target.
const CONVERGED: f64 = 0.002;
/// Newton steps per projection between rounds (the parameters start from the last round's).
const ROUND_STEPS: usize = 2;
/// Newton steps per projection when measuring.
const NEWTON_STEPS: usize = 6;
/// Samples per original segment: one per four target distances, within these bounds.
/// Quadratic and cubic segments have no detail finer than a sixteenth of their length
/// that the least squares would need to see; the measure's curve side samples anyway.
const SEG_SAMPLES: (usize, usize) = (6, 16);
/// Curve samples per X-spline segment when measuring curve -> original.
const CURVE_SAMPLES: usize = 16;

/// A fitted contour: control points and the measured error during fitting.
#[derive(Clone, Debug)]
pub struct FittedXSpline {
    /// The contour's control points.
    pub points: Vec<ControlPoint>,
    /// Largest sampled distance found while fitting (font units).
    pub fit_error: f64,
}

/// Fits one original contour (as [`super::contour::cut`] cut it) within `target` font
/// units. `None` when the contour encloses nothing (fewer than three points would remain).
pub fn fit_xspline(cut: &Cut, target: f64) -> Option<FittedXSpline> {
    let spacing = (target * 4.0).max(1e-3);
    let mut points = Vec::new();
    let mut fit_error: f64 = 0.0;
    match cut {
        Cut::Loop(segs) => {
            let fit = best_fit(segs, true, spacing, target, [false; 2]);
            fit_error = fit_error.max(fit.error);
            let chain = fit.chain;
            points.extend(chain.pts.iter().zip(&chain.s).map(|(p, &s)| cp(*p, s)));
        }
        Cut::Pieces(pieces) => {
            let count = pieces.len();
            for (k, piece) in pieces.iter().enumerate() {
                match piece {
                    Piece::Edge(line) => points.push(cp(line.p0, 0.0)),
                    Piece::Smooth(segs) => {
                        let before = piece_end_tangent(&pieces[(k + count - 1) % count]);
                        let after = piece_start_tangent(&pieces[(k + 1) % count]);
                        let corners = [
                            turn_degrees(before, start_tangent(segs[0])) > CORNER_DEGREES,
                            turn_degrees(end_tangent(segs[segs.len() - 1]), after) > CORNER_DEGREES,
                        ];
                        let Fit { chain, error } = best_fit(segs, false, spacing, target, corners);
                        fit_error = fit_error.max(error);
                        let n = chain.pts.len();
                        points.extend(
                            chain.pts[..n - 1]
                                .iter()
                                .zip(&chain.s)
                                .map(|(p, &s)| cp(*p, s)),
                        );
                    }
                }
            }
        }
    }
    (points.len() >= 3).then_some(FittedXSpline { points, fit_error })
}

/// Fits one contour of several masters at once, within `target` in each and at each
/// checkpoint (blend weights per master, measured against the same blend of the
/// originals): the cuts have one structure ([`super::contour::cut_at`] at the masters'
/// joint break points), and every smooth stretch gets the same number of interior points
/// with the same shapes in every master (`fit_together`), each master's positions fitted
/// to its own outline with curve parameters shared by all. So the results have the same
/// points with sharp points at the same places, and interpolate as X-splines. `None` when
/// the cuts differ in structure, the contour encloses nothing, or a stretch misses the
/// target somewhere at every count tried.
pub fn fit_compatible(
    cuts: &[Cut],
    target: f64,
    checkpoints: &[Vec<f64>],
) -> Option<Vec<FittedXSpline>> {
    let spacing = (target * 4.0).max(1e-3);
    let mut points: Vec<Vec<ControlPoint>> = vec![Vec::new(); cuts.len()];
    let mut errors = vec![0.0f64; cuts.len()];
    let add = |points: &mut [Vec<ControlPoint>], errors: &mut [f64], fits: Vec<Fit>, open: bool| {
        for ((points, error), fit) in points.iter_mut().zip(errors.iter_mut()).zip(fits) {
            *error = error.max(fit.error);
            let n = fit.chain.pts.len() - usize::from(open);
            points.extend(
                fit.chain.pts[..n]
                    .iter()
                    .zip(&fit.chain.s)
                    .map(|(p, &s)| cp(*p, s)),
            );
        }
    };
    match &cuts[0] {
        Cut::Loop(_) => {
            let stretches = cuts
                .iter()
                .map(|c| match c {
                    Cut::Loop(segs) => Some((segs.as_slice(), [false; 2])),
                    Cut::Pieces(_) => None,
                })
                .collect::<Option<Vec<_>>>()?;
            add(
                &mut points,
                &mut errors,
                fit_together(&stretches, true, spacing, target, checkpoints)?,
                false,
            );
        }
        Cut::Pieces(first) => {
            let all = cuts
                .iter()
                .map(|c| match c {
                    Cut::Pieces(p) if p.len() == first.len() => Some(p.as_slice()),
                    _ => None,
                })
                .collect::<Option<Vec<_>>>()?;
            let count = first.len();
            for k in 0..count {
                if let Piece::Edge(_) = first[k] {
                    for (points, pieces) in points.iter_mut().zip(&all) {
                        let Piece::Edge(line) = pieces[k] else {
                            return None;
                        };
                        points.push(cp(line.p0, 0.0));
                    }
                    continue;
                }
                let stretches = all
                    .iter()
                    .map(|pieces| {
                        let Piece::Smooth(segs) = &pieces[k] else {
                            return None;
                        };
                        let before = piece_end_tangent(&pieces[(k + count - 1) % count]);
                        let after = piece_start_tangent(&pieces[(k + 1) % count]);
                        let corners = [
                            turn_degrees(before, start_tangent(segs[0])) > CORNER_DEGREES,
                            turn_degrees(end_tangent(segs[segs.len() - 1]), after) > CORNER_DEGREES,
                        ];
                        Some((segs.as_slice(), corners))
                    })
                    .collect::<Option<Vec<_>>>()?;
                add(
                    &mut points,
                    &mut errors,
                    fit_together(&stretches, false, spacing, target, checkpoints)?,
                    true,
                );
            }
        }
    }
    (points[0].len() >= 3).then(|| {
        points
            .into_iter()
            .zip(errors)
            .map(|(points, fit_error)| FittedXSpline { points, fit_error })
            .collect()
    })
}

/// One stretch in every master (segments, and whether its ends are corners) fitted with
/// one interior point count and one setting: the [`PRIMARY`] settings from the most that
/// a master needs alone, one more while a master or a checkpoint misses `target`; then
/// the [`ALTERNATIVES`] with one point fewer while one holds.
///
/// The masters share their samples' places (the same parameters of the same original
/// segments) and their curve parameters (each round projects every master and takes the
/// mean), so a blend of the masters' X-splines follows the same blend of the originals:
/// fitted alone, each master's points drift along its curve in its own way, and halfway
/// between two masters fitted within 0.5 units the blend missed by 1.5 to 2.3 (`S`, `m`
/// of the bundled family). Each checkpoint (blend weights per master) is measured like a
/// master, against the blended original.
fn fit_together(
    stretches: &[(&[PathSeg], [bool; 2])],
    closed: bool,
    spacing: f64,
    target: f64,
    checkpoints: &[Vec<f64>],
) -> Option<Vec<Fit>> {
    let nseg = stretches.first()?.0.len();
    let counts: Vec<usize> = (0..nseg)
        .map(|i| {
            stretches
                .iter()
                .map(|(segs, _)| sample_count(&segs[i], spacing))
                .max()
                .unwrap_or(SEG_SAMPLES.0)
        })
        .collect();
    let samples: Vec<StretchSamples> = stretches
        .iter()
        .map(|(segs, corners)| StretchSamples::with_counts(segs, &counts, closed, *corners))
        .collect();
    let blended: Vec<(Vec<PathSeg>, StretchSamples)> = checkpoints
        .iter()
        .map(|weights| {
            let segs = blend_stretch(stretches, weights);
            let samples = StretchSamples::with_counts(&segs, &counts, closed, [false; 2]);
            (segs, samples)
        })
        .collect();
    let mut interior = stretches
        .iter()
        .map(|(segs, corners)| {
            let alone = StretchSamples::new(segs, spacing, closed, *corners);
            fit_stretch(segs, &alone, closed, PRIMARY, target).interior
        })
        .max()?;
    let min_inner = if closed { 3 } else { 0 };
    let max_inner = min_inner + 3 * nseg + 8;
    let holds = |fits: &[Fit]| {
        fits.iter().all(|f| f.error <= target)
            && checkpoints
                .iter()
                .zip(&blended)
                .all(|(weights, (segs, samples))| {
                    let chain = blend_chains(fits, weights);
                    let last = samples.pts.len().saturating_sub(1).max(1) as f64;
                    let mut ts: Vec<f64> = (0..samples.pts.len())
                        .map(|k| k as f64 / last * chain.nseg() as f64)
                        .collect();
                    project(&chain, samples, &mut ts, NEWTON_STEPS, None);
                    stretch_error(&chain, samples, &mut ts, segs) <= target
                })
    };
    let mut best = loop {
        let fits = attempt_together(stretches, &samples, closed, PRIMARY, interior, target);
        if holds(&fits) {
            break fits;
        }
        if interior >= max_inner {
            return None;
        }
        interior += 1;
    };
    // As for one master ([`best_fit`]): the alternatives with one point fewer, while one
    // of them holds in every master and checkpoint.
    let floor = if closed { min_inner } else { 1 };
    while interior > floor {
        let better = ALTERNATIVES
            .iter()
            .map(|&settings| {
                attempt_together(stretches, &samples, closed, settings, interior - 1, target)
            })
            .find(|fits| holds(fits));
        match better {
            Some(fits) => {
                best = fits;
                interior -= 1;
            }
            None => break,
        }
    }
    Some(best)
}

/// One fit of every master with `interior` points and shared curve parameters.
fn attempt_together(
    stretches: &[(&[PathSeg], [bool; 2])],
    samples: &[StretchSamples],
    closed: bool,
    settings: Settings,
    interior: usize,
    target: f64,
) -> Vec<Fit> {
    let mut chains: Vec<Chain> = stretches
        .iter()
        .zip(samples)
        .map(|((segs, _), samples)| initial_chain(samples, segs, closed, interior, settings))
        .collect();
    let nseg = chains[0].nseg() as f64;
    let grade = if closed { 0.0 } else { settings.grade };
    let count = samples[0].pts.len();
    let mut ts: Vec<f64> = (0..count)
        .map(|k| {
            let sum: f64 = samples.iter().map(|s| s.ungraded(grade)[k]).sum();
            sum / samples.len() as f64 * nseg
        })
        .collect();
    let mut bases = Vec::with_capacity(count);
    for round in 0..ROUNDS {
        let tangential = if round == 0 { 1.0 } else { TANGENTIAL };
        let mut moved: f64 = 0.0;
        let mut sum = vec![0.0; count];
        let mut solved = true;
        for (chain, own_samples) in chains.iter_mut().zip(samples) {
            let before = chain.pts.clone();
            if !solve_positions(chain, own_samples, &ts, &mut bases, tangential) {
                solved = false;
                break;
            }
            let mut own = ts.clone();
            project(chain, own_samples, &mut own, ROUND_STEPS, Some(&bases));
            sum.iter_mut().zip(&own).for_each(|(s, t)| *s += t);
            moved = before
                .iter()
                .zip(&chain.pts)
                .map(|(a, b)| (*a - *b).hypot())
                .fold(moved, f64::max);
        }
        if !solved {
            break;
        }
        ts = sum.iter().map(|s| s / chains.len() as f64).collect();
        if moved < CONVERGED * target {
            break;
        }
    }
    fits_of(chains, samples_and_segs(stretches, samples))
}

fn samples_and_segs<'a>(
    stretches: &'a [(&'a [PathSeg], [bool; 2])],
    samples: &'a [StretchSamples],
) -> impl Iterator<Item = (&'a StretchSamples, &'a [PathSeg])> {
    samples.iter().zip(stretches.iter().map(|(segs, _)| *segs))
}

/// Each chain with its own measured error (its own projection of the samples).
fn fits_of<'a>(
    chains: Vec<Chain>,
    originals: impl Iterator<Item = (&'a StretchSamples, &'a [PathSeg])>,
) -> Vec<Fit> {
    chains
        .into_iter()
        .zip(originals)
        .map(|(chain, (samples, segs))| {
            let last = samples.pts.len().saturating_sub(1).max(1) as f64;
            let mut ts: Vec<f64> = (0..samples.pts.len())
                .map(|k| k as f64 / last * chain.nseg() as f64)
                .collect();
            project(&chain, samples, &mut ts, NEWTON_STEPS, None);
            let error = stretch_error(&chain, samples, &mut ts, segs);
            Fit { chain, error }
        })
        .collect()
}

/// The masters' chains blended by `weights` (one structure: the same points and shapes).
fn blend_chains(fits: &[Fit], weights: &[f64]) -> Chain {
    let mut chain = fits[0].chain.clone();
    for (i, p) in chain.pts.iter_mut().enumerate() {
        *p = fits.iter().zip(weights).fold(Point::ZERO, |acc, (f, w)| {
            acc + *w * f.chain.pts[i].to_vec2()
        });
    }
    chain
}

/// One stretch's segments blended by `weights`, as Bézier masters interpolate (every
/// control point; the masters' segments have one kind each).
fn blend_stretch(stretches: &[(&[PathSeg], [bool; 2])], weights: &[f64]) -> Vec<PathSeg> {
    let controls = |seg: PathSeg| -> Vec<Point> {
        match seg {
            PathSeg::Line(l) => vec![l.p0, l.p1],
            PathSeg::Quad(q) => vec![q.p0, q.p1, q.p2],
            PathSeg::Cubic(c) => vec![c.p0, c.p1, c.p2, c.p3],
        }
    };
    (0..stretches[0].0.len())
        .map(|i| {
            let mut mixed = vec![Point::ZERO; controls(stretches[0].0[i]).len()];
            for ((segs, _), w) in stretches.iter().zip(weights) {
                for (m, p) in mixed.iter_mut().zip(controls(segs[i])) {
                    *m += *w * p.to_vec2();
                }
            }
            match mixed.as_slice() {
                [a, b] => PathSeg::Line(kurbo::Line::new(*a, *b)),
                [a, b, c] => PathSeg::Quad(kurbo::QuadBez::new(*a, *b, *c)),
                [a, b, c, d] => PathSeg::Cubic(kurbo::CubicBez::new(*a, *b, *c, *d)),
                _ => unreachable!("a segment has two to four control points"),
            }
        })
        .collect()
}

/// The contour of several masters as polylines of sharp points with one structure: each
/// segment cut at the same parameters in every master, as many as the most curved master
/// needs for `tolerance`. The bound is on the parameter (a chord against the curve at the
/// same `t`: `h² · max|B''| / 8` over a step `h`), and that error interpolates linearly
/// between masters, so every blend of the polylines is within `tolerance` of the same
/// blend of the originals. The importer's last resort for masters.
pub fn compatible_polylines(masters: &[&[PathSeg]], tolerance: f64) -> Vec<Vec<ControlPoint>> {
    let mut out = vec![Vec::new(); masters.len()];
    for i in 0..masters[0].len() {
        let steps = masters
            .iter()
            .map(|segs| {
                let second = match segs[i] {
                    PathSeg::Line(_) => 0.0,
                    PathSeg::Quad(q) => {
                        2.0 * (q.p0 - 2.0 * q.p1.to_vec2() + q.p2.to_vec2())
                            .to_vec2()
                            .hypot()
                    }
                    PathSeg::Cubic(c) => {
                        let a = (c.p0 - 2.0 * c.p1.to_vec2() + c.p2.to_vec2())
                            .to_vec2()
                            .hypot();
                        let b = (c.p1 - 2.0 * c.p2.to_vec2() + c.p3.to_vec2())
                            .to_vec2()
                            .hypot();
                        6.0 * a.max(b)
                    }
                };
                (second / (8.0 * tolerance)).sqrt().ceil().max(1.0) as usize
            })
            .max()
            .unwrap_or(1);
        for (points, segs) in out.iter_mut().zip(masters) {
            points.extend((0..steps).map(|k| cp(segs[i].eval(k as f64 / steps as f64), 0.0)));
        }
    }
    out
}

fn piece_start_tangent(piece: &Piece) -> Vec2 {
    match piece {
        Piece::Edge(line) => start_tangent(PathSeg::Line(*line)),
        Piece::Smooth(segs) => start_tangent(segs[0]),
    }
}

fn piece_end_tangent(piece: &Piece) -> Vec2 {
    match piece {
        Piece::Edge(line) => end_tangent(PathSeg::Line(*line)),
        Piece::Smooth(segs) => end_tangent(segs[segs.len() - 1]),
    }
}

fn cp(p: Point, s: f64) -> ControlPoint {
    ControlPoint::new(p.x, p.y, s)
}

/// The fit with the fewest points: a search over the point count with the primary
/// settings, then each of the [`ALTERNATIVES`] tried with one point fewer, while that holds.
fn best_fit(segs: &[PathSeg], closed: bool, spacing: f64, target: f64, corners: [bool; 2]) -> Fit {
    let samples = StretchSamples::new(segs, spacing, closed, corners);
    let Search {
        fit: mut best,
        mut interior,
        below,
    } = fit_stretch(segs, &samples, closed, PRIMARY, target);
    // The alternatives differ from the primary settings in shapes and spacing, which
    // moves the error by far less than a factor of two: where the primary missed by more
    // with one point fewer, they would too (on the 64 CJK glyphs and DejaVu, skipping them
    // there changes no point count).
    if below > ALTERNATIVES_REACH * target {
        return best;
    }
    let min_inner = if closed { 3 } else { 0 };
    // An open stretch with no interior point is its chord whatever the settings, and the
    // primary search measured that already.
    let floor = if closed { min_inner } else { 1 };
    let free = !closed && (corners[0] || corners[1]);
    while best.error <= target && interior > floor {
        // Free corners first: where they hold, they save the five alternatives' fits
        // (6 % of the instructions on the 64 CJK glyphs, the same point count).
        let relaxed: &[Settings] = if free && interior > 2 {
            &FREE_CORNERS
        } else {
            &[]
        };
        let better = relaxed
            .iter()
            .chain(&ALTERNATIVES)
            .map(|&settings| attempt(segs, &samples, closed, settings, interior - 1, target))
            .find(|fit| fit.error <= target);
        match better {
            Some(fit) => {
                best = fit;
                interior -= 1;
            }
            None => break,
        }
    }
    best
}

/// Dense samples of an original stretch with their arc-length fraction in `[0, 1]`.
struct StretchSamples {
    pts: Vec<Point>,
    /// Whether an open stretch's start and end are corners of the original (else smooth
    /// joins with the neighbouring piece).
    corners: [bool; 2],
    /// Cumulative share in `[0, 1]` of arc length weighted by `1 + sqrt(|curvature| · L)`
    /// (L the stretch length), so tight bends get more of the initial points.
    budget: Vec<f64>,
    /// [`ungrade`] of every budget share, per grade already asked for: the same for every
    /// point count, and each costs a bisection.
    ungraded: std::cell::RefCell<Vec<(f64, std::rc::Rc<[f64]>)>>,
}

impl StretchSamples {
    fn new(segs: &[PathSeg], spacing: f64, closed: bool, corners: [bool; 2]) -> Self {
        let counts: Vec<usize> = segs.iter().map(|seg| sample_count(seg, spacing)).collect();
        Self::with_counts(segs, &counts, closed, corners)
    }

    /// Samples at `counts[i]` even parameter steps of segment `i`: the same counts for
    /// every master of a stretch make sample `j` the same place of the outline in each.
    fn with_counts(segs: &[PathSeg], counts: &[usize], closed: bool, corners: [bool; 2]) -> Self {
        let mut pts = Vec::new();
        for (seg, &k) in segs.iter().zip(counts) {
            pts.extend((0..k).map(|i| seg.eval(i as f64 / k as f64)));
        }
        let last = segs.last().map_or(Point::ZERO, |s| s.end());
        pts.push(last);
        let n = pts.len();
        let length: f64 = pts.windows(2).map(|w| (w[1] - w[0]).hypot()).sum();
        // Turning angle per unit length at each sample (wrapping on a loop).
        let curvature = |k: usize| -> f64 {
            let (prev, next) = match (k, closed) {
                (0, false) => return 0.0,
                (k, false) if k + 1 == n => return 0.0,
                (0, true) => (pts[n - 2], pts[1]),
                (k, true) if k + 1 == n => (pts[n - 2], pts[1]),
                (k, _) => (pts[k - 1], pts[k + 1]),
            };
            let (a, b) = (pts[k] - prev, next - pts[k]);
            let turn = super::contour::turn_degrees(a, b).to_radians();
            turn / (0.5 * (a.hypot() + b.hypot())).max(1e-12)
        };
        let kappa: Vec<f64> = (0..n).map(curvature).collect();
        let mut cum = vec![0.0];
        for k in 1..n {
            let d = (pts[k] - pts[k - 1]).hypot();
            let density = 1.0 + (0.5 * (kappa[k] + kappa[k - 1]) * length).sqrt();
            cum.push(cum[k - 1] + d * density);
        }
        let total = cum[n - 1].max(1e-12);
        let mut budget: Vec<f64> = cum.iter().map(|c| c / total).collect();
        if closed {
            // The end repeats the start on a loop.
            pts.pop();
            budget.pop();
        }
        StretchSamples {
            pts,
            corners,
            budget,
            ungraded: Default::default(),
        }
    }

    /// The samples' parameter shares for the initial spacing `grade` (see [`graded`]).
    fn ungraded(&self, grade: f64) -> std::rc::Rc<[f64]> {
        let mut cache = self.ungraded.borrow_mut();
        if let Some((_, shares)) = cache.iter().find(|(g, _)| *g == grade) {
            return shares.clone();
        }
        let shares: std::rc::Rc<[f64]> = self.budget.iter().map(|&b| ungrade(b, grade)).collect();
        cache.push((grade, shares.clone()));
        shares
    }
}

/// Samples on one original segment: one per four target distances (`spacing`), within
/// [`SEG_SAMPLES`].
fn sample_count(seg: &PathSeg, spacing: f64) -> usize {
    ((seg.arclen(1e-3) / spacing).ceil() as usize).clamp(SEG_SAMPLES.0, SEG_SAMPLES.1)
}

/// One fitted chain and its measured (sampled, two-sided) error.
#[derive(Clone, Debug)]
struct Fit {
    chain: Chain,
    error: f64,
}

/// The result of a point-count search: the fit and its interior point count.
struct Search {
    fit: Fit,
    interior: usize,
    /// The error with one interior point fewer, when that was measured (or bounded from
    /// below); zero when not known.
    below: f64,
}

/// Unit tangents of the original leaving the start of an open stretch and (backward)
/// arriving at its end.
#[derive(Clone, Copy, Debug)]
struct Rays {
    out: Option<Vec2>,
    back: Option<Vec2>,
}

/// An X-spline chain under construction: open (fixed `s = 0` ends) or a closed loop.
#[derive(Clone, Debug)]
struct Chain {
    pts: Vec<Point>,
    s: Vec<f64>,
    closed: bool,
    shapes: Shapes,
    /// Unit tangents of the original leaving the start and (backward) the end of an open
    /// stretch; the neighbours of the sharp ends are held on these rays.
    rays: Option<Rays>,
}

impl Chain {
    fn nseg(&self) -> usize {
        if self.closed {
            self.pts.len()
        } else {
            self.pts.len() - 1
        }
    }

    /// The ray point `i` is held on, if any: only the neighbours of the sharp ends, and
    /// only when they are distinct points (two or more interior points).
    fn ray(&self, i: usize) -> Option<(Point, Vec2)> {
        let Rays { out, back } = self.rays?;
        let n = self.pts.len();
        if self.closed || n < 4 {
            None
        } else if i == 1 {
            out.map(|dir| (self.pts[0], dir))
        } else if i + 2 == n {
            back.map(|dir| (self.pts[n - 1], dir))
        } else {
            None
        }
    }

    fn is_free(&self, i: usize) -> bool {
        self.closed || (i != 0 && i + 1 != self.pts.len())
    }

    /// The blending basis at `T` (an open chain's ends are fixed `s = 0` points).
    fn basis(&self, big_t: f64) -> Basis {
        let n = self.pts.len();
        if self.closed {
            Basis::closed(n, |k| self.s[k], big_t)
        } else {
            Basis::open(n, |k| self.s[k], big_t)
        }
    }

    fn eval_deriv(&self, big_t: f64) -> (Point, Vec2) {
        self.basis(big_t).eval_deriv(&self.pts)
    }

    fn eval(&self, big_t: f64) -> Point {
        self.eval_deriv(big_t).0
    }

    /// Shapes by position: `s = 0` at the fixed ends of an open chain, the end shape next
    /// to them, the inner shape elsewhere.
    fn assign_shapes(&mut self) {
        let n = self.pts.len();
        for i in 0..n {
            self.s[i] = if self.closed {
                self.shapes.inner
            } else if i == 0 || i + 1 == n {
                0.0
            } else if i == 1 || i + 2 == n {
                self.shapes.end
            } else {
                self.shapes.inner
            };
        }
    }
}

/// Searches the fewest interior points meeting `target` with one setting: the fit and its
/// interior point count (the largest tried when none meets it).
fn fit_stretch(
    segs: &[PathSeg],
    samples: &StretchSamples,
    closed: bool,
    settings: Settings,
    target: f64,
) -> Search {
    // The error of every count measured, for `Search::below`.
    let tried = std::cell::RefCell::new(Vec::new());
    let attempt = |interior: usize| {
        let fit = attempt(segs, samples, closed, settings, interior, target);
        tried.borrow_mut().push((interior, fit.error));
        fit
    };
    let below = |interior: usize| -> f64 {
        let tried = tried.borrow();
        let known = tried.iter().find(|(n, _)| n + 1 == interior);
        known.map_or(0.0, |&(_, error)| error)
    };
    // The error falls (nearly) monotonically with the point count: grow the count by
    // doubling steps until the target holds, then bisect down to the fewest that hold.
    let min_inner = if closed { 3 } else { 0 };
    let max_inner = min_inner + 3 * segs.len() + 8;
    // An open stretch without interior points is its chord: skip measuring it when a
    // sample is farther than the target from the chord's line (the error is at least that).
    let chord = if closed { 0.0 } else { off_chord(samples) };
    if chord > target {
        // The chord misses by at least this much.
        tried.borrow_mut().push((min_inner, chord));
    } else {
        let first = attempt(min_inner);
        if first.error <= target {
            return Search {
                fit: first,
                interior: min_inner,
                below: 0.0,
            };
        }
    }
    // A lone quadratic (most curved stretches of a TrueType glyph): try the direct
    // candidate before any least squares.
    if let (false, [PathSeg::Quad(quad)]) = (closed, segs) {
        let fit = direct_quad(*quad, segs, samples, settings);
        if fit.error <= target {
            return Search {
                fit,
                interior: 1,
                below: chord,
            };
        }
    }
    // Start from one interior point per original curve (a TrueType quadratic mostly needs
    // one), walk down while the target holds; else grow by doubling steps, then bisect.
    // `lo` is the largest count known to miss (the count above was measured or skipped).
    let curves = segs
        .iter()
        .filter(|s| !matches!(s, PathSeg::Line(_)))
        .count();
    let guess = curves.clamp(min_inner + 1, max_inner);
    let fit = attempt(guess);
    if fit.error <= target {
        // Down one point at a time (a TrueType stretch mostly stops within two), then by
        // doubling steps: an outline drawn with many short curves (a stroke's round caps
        // and joins, 4 cubics per half turn) needs far fewer points than curves. Then
        // bisect between the fewest that held and the most known to miss.
        let (mut hi, mut hi_fit) = (guess, fit);
        let mut lo = min_inner;
        let mut step = 1;
        let mut walked = 0;
        while hi - 1 > min_inner {
            let m = hi.saturating_sub(step).max(min_inner + 1);
            let lower = attempt(m);
            if lower.error > target {
                lo = m;
                break;
            }
            (hi, hi_fit) = (m, lower);
            walked += 1;
            if walked >= DOWN_ONE_BY_ONE {
                step *= 2;
            }
        }
        while hi - lo > 1 && lo > min_inner {
            let mid = (lo + hi) / 2;
            let fit = attempt(mid);
            if fit.error <= target {
                (hi, hi_fit) = (mid, fit);
            } else {
                lo = mid;
            }
        }
        return Search {
            below: below(hi),
            fit: hi_fit,
            interior: hi,
        };
    }
    let (mut lo, mut step) = (guess, 1);
    let (mut hi, mut hi_fit) = loop {
        let m = (lo + step).min(max_inner);
        let fit = attempt(m);
        if fit.error <= target || m == max_inner {
            break (m, fit);
        }
        lo = m;
        step *= 2;
    };
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        let fit = attempt(mid);
        if fit.error <= target {
            hi = mid;
            hi_fit = fit;
        } else {
            lo = mid;
        }
    }
    Search {
        below: below(hi),
        fit: hi_fit,
        interior: hi,
    }
}

/// The largest distance of an open stretch's samples from the line through its ends.
fn off_chord(samples: &StretchSamples) -> f64 {
    let (Some(&a), Some(&b)) = (samples.pts.first(), samples.pts.last()) else {
        return 0.0;
    };
    let d = b - a;
    let len = d.hypot();
    if len == 0.0 {
        return f64::INFINITY;
    }
    samples
        .pts
        .iter()
        .map(|&p| (p - a).cross(d).abs() / len)
        .fold(0.0, f64::max)
}

/// One interior point for a lone quadratic `P0 C P2` between sharp points, without least
/// squares: `M + k (C - M)`, `M` the chord's midpoint, `k` such that the X-spline passes
/// through the quadratic's midpoint at `T = 1`. Both curves are affine images of their
/// control points, so this is the same construction for every quadratic (the error is
/// measured, as for any other fit; a miss falls back to the point-count search).
fn direct_quad(
    quad: kurbo::QuadBez,
    segs: &[PathSeg],
    samples: &StretchSamples,
    settings: Settings,
) -> Fit {
    let mut chain = initial_chain(samples, segs, false, 1, settings);
    // The X-spline at T = 1 is (1 - w) M + w Q, w the interior point's weight there.
    let w = chain.basis(1.0).weight[1];
    let mid = quad.p0.midpoint(quad.p2);
    chain.pts[1] = mid + (quad.p1 - mid) / (2.0 * w);
    // Samples are at even steps of the quadratic's parameter: start each at twice it.
    let last = (samples.pts.len() - 1).max(1) as f64;
    let mut ts: Vec<f64> = (0..samples.pts.len())
        .map(|i| 2.0 * i as f64 / last)
        .collect();
    let error = stretch_error(&chain, samples, &mut ts, segs);
    Fit { chain, error }
}

/// One fit from scratch with `interior` points: initial spacing, rounds of least squares
/// and projection, and the measured error.
fn attempt(
    segs: &[PathSeg],
    samples: &StretchSamples,
    closed: bool,
    settings: Settings,
    interior: usize,
    target: f64,
) -> Fit {
    let mut chain = initial_chain(samples, segs, closed, interior, settings);
    let nseg = chain.nseg() as f64;
    let grade = if closed { 0.0 } else { settings.grade };
    let mut ts: Vec<f64> = samples.ungraded(grade).iter().map(|&u| u * nseg).collect();
    refine(&mut chain, samples, &mut ts, target);
    let error = stretch_error(&chain, samples, &mut ts, segs);
    Fit { chain, error }
}

/// Interior points at equal steps of the sample budget (arc length weighted by curvature).
fn initial_chain(
    samples: &StretchSamples,
    segs: &[PathSeg],
    closed: bool,
    interior: usize,
    settings: Settings,
) -> Chain {
    let shapes = settings.shapes;
    let start = segs[0].start();
    let end = segs[segs.len() - 1].end();
    let out = start_tangent(segs[0]);
    let back = -end_tangent(segs[segs.len() - 1]);
    let held =
        |corner: bool, dir: Vec2| (!(corner && settings.free_corners)).then(|| dir.normalize());
    let rays = (out.hypot() > 0.0 && back.hypot() > 0.0).then(|| Rays {
        out: held(samples.corners[0], out),
        back: held(samples.corners[1], back),
    });
    let at = |b: f64| -> Point {
        let k = samples
            .budget
            .partition_point(|&x| x < b)
            .min(samples.pts.len() - 1);
        samples.pts[k]
    };
    let pts: Vec<Point> = if closed {
        (0..interior)
            .map(|i| at(i as f64 / interior as f64))
            .collect()
    } else {
        let mut pts = vec![start];
        pts.extend(
            (1..=interior).map(|i| at(graded(i as f64 / (interior + 1) as f64, settings.grade))),
        );
        pts.push(end);
        pts
    };
    let mut chain = Chain {
        s: vec![0.0; pts.len()],
        pts,
        closed,
        shapes,
        rays,
    };
    chain.assign_shapes();
    chain
}

/// Parameter share -> budget share: uniform blended with a cosine spacing (dense at the ends).
fn graded(u: f64, grade: f64) -> f64 {
    (1.0 - grade) * u + grade * 0.5 * (1.0 - (std::f64::consts::PI * u).cos())
}

/// The inverse of [`graded`] (monotone), by bisection.
fn ungrade(b: f64, grade: f64) -> f64 {
    if grade == 0.0 {
        return b;
    }
    let (mut lo, mut hi) = (0.0, 1.0);
    // 24 halvings: 6e-8 of the parameter, far below what the projection then moves.
    for _ in 0..24 {
        let mid = 0.5 * (lo + hi);
        if graded(mid, grade) < b {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Rounds of least-squares positions and parameter projection.
fn refine(chain: &mut Chain, samples: &StretchSamples, ts: &mut [f64], target: f64) {
    let mut bases = Vec::with_capacity(ts.len());
    for round in 0..ROUNDS {
        let before = chain.pts.clone();
        let tangential = if round == 0 { 1.0 } else { TANGENTIAL };
        if !solve_positions(chain, samples, ts, &mut bases, tangential) {
            break;
        }
        project(chain, samples, ts, ROUND_STEPS, Some(&bases));
        let moved = before
            .iter()
            .zip(&chain.pts)
            .map(|(a, b)| (*a - *b).hypot())
            .fold(0.0, f64::max);
        if moved < CONVERGED * target {
            break;
        }
    }
}

/// Least-squares positions of the free points for fixed parameters `ts`; false when the
/// chain has no free point. `bases` receives the chain's basis at each parameter.
fn solve_positions(
    chain: &mut Chain,
    samples: &StretchSamples,
    ts: &[f64],
    bases: &mut Vec<Basis>,
    tangential: f64,
) -> bool {
    let n = chain.pts.len();
    // Unknowns: x and y of a free point; one distance along the ray of a point held on
    // the original's tangent at a sharp end (the curve leaves a sharp point toward its
    // neighbour, so this makes the X-spline leave the corner in the original direction).
    let mut dofs = Vec::with_capacity(n);
    let mut k = 0;
    for i in 0..n {
        let dof = match chain.ray(i) {
            _ if !chain.is_free(i) => Dof::Fixed,
            Some((base, dir)) => {
                k += 1;
                Dof::Ray {
                    column: k - 1,
                    base,
                    dir,
                }
            }
            None => {
                k += 2;
                Dof::Free(k - 2)
            }
        };
        dofs.push(dof);
    }
    if k == 0 {
        return false;
    }
    let mut current = vec![0.0; k];
    for (i, dof) in dofs.iter().enumerate() {
        match *dof {
            Dof::Fixed => {}
            Dof::Free(c) => {
                current[c] = chain.pts[i].x;
                current[c + 1] = chain.pts[i].y;
            }
            Dof::Ray { column, base, dir } => current[column] = (chain.pts[i] - base).dot(dir),
        }
    }
    let mut m = vec![0.0; k * k];
    let mut rhs = vec![0.0; k];
    let mut coefs: Vec<(usize, Vec2)> = Vec::with_capacity(8);
    bases.clear();
    bases.extend(ts.iter().map(|&big_t| chain.basis(big_t)));
    for (p, basis) in samples.pts.iter().zip(bases.iter()) {
        let mut target = p.to_vec2();
        coefs.clear();
        for (&i, &w) in basis.index.iter().zip(&basis.weight) {
            match dofs[i] {
                Dof::Fixed => target -= w * chain.pts[i].to_vec2(),
                Dof::Free(c) => {
                    coefs.push((c, Vec2::new(w, 0.0)));
                    coefs.push((c + 1, Vec2::new(0.0, w)));
                }
                Dof::Ray { column, base, dir } => {
                    target -= w * base.to_vec2();
                    coefs.push((column, w * dir));
                }
            }
        }
        // The metric: full weight across the current curve, `tangential` along it.
        let tangent = basis.eval_deriv(&chain.pts).1;
        let len2 = tangent.hypot2();
        let metric = |a: Vec2, b: Vec2| -> f64 {
            if tangential == 1.0 || len2 < 1e-18 {
                return a.dot(b);
            }
            let (at, bt) = (a.dot(tangent), b.dot(tangent));
            a.dot(b) - (1.0 - tangential) * at * bt / len2
        };
        for &(ca, va) in &coefs {
            rhs[ca] += metric(va, target);
            for &(cb, vb) in &coefs {
                m[ca * k + cb] += metric(va, vb);
            }
        }
    }
    // A light pull toward the current positions keeps points without samples in place.
    let lambda = 1e-6;
    for c in 0..k {
        m[c * k + c] += lambda;
        rhs[c] += lambda * current[c];
    }
    let Some(sol) = solve_dense(&mut m, &mut rhs, k) else {
        return false;
    };
    for (i, dof) in dofs.iter().enumerate() {
        match *dof {
            Dof::Fixed => {}
            Dof::Free(c) => chain.pts[i] = Point::new(sol[c], sol[c + 1]),
            Dof::Ray { column, base, dir } => {
                // Ahead of the corner, never behind it: behind, the X-spline would leave
                // the corner backwards and hook round (a hook within the tolerance, but a
                // self-intersection beside the corner once built, as in Liberation Mono
                // Bold `sigma1`).
                let beyond = if i == 1 {
                    n.min(3) - 1
                } else {
                    n.saturating_sub(3)
                };
                let least = MIN_RAY * (chain.pts[beyond] - base).hypot();
                chain.pts[i] = base + sol[column].max(least) * dir;
            }
        }
    }
    true
}

/// Least distance of a point held on a corner's tangent ray from the corner, as a fraction
/// of the distance to the next point along the stretch.
const MIN_RAY: f64 = 0.01;

/// How a control point enters the least-squares problem.
#[derive(Clone, Copy, Debug)]
enum Dof {
    Fixed,
    /// Columns `c` (x) and `c + 1` (y).
    Free(usize),
    /// One column: the distance from `base` along the unit `dir`.
    Ray {
        column: usize,
        base: Point,
        dir: Vec2,
    },
}

/// Gaussian elimination with partial pivoting on a dense `k × k` system. Written by hand:
/// the systems are tiny (under ~100 unknowns), and this keeps a linear-algebra crate out.
fn solve_dense(m: &mut [f64], rhs: &mut [f64], k: usize) -> Option<Vec<f64>> {
    for c in 0..k {
        let pivot = (c..k).max_by(|&a, &b| m[a * k + c].abs().total_cmp(&m[b * k + c].abs()))?;
        if m[pivot * k + c].abs() < 1e-14 {
            return None;
        }
        if pivot != c {
            for j in 0..k {
                m.swap(c * k + j, pivot * k + j);
            }
            rhs.swap(c, pivot);
        }
        let d = m[c * k + c];
        for r in c + 1..k {
            let f = m[r * k + c] / d;
            if f == 0.0 {
                continue;
            }
            for j in c..k {
                m[r * k + j] -= f * m[c * k + j];
            }
            rhs[r] -= f * rhs[c];
        }
    }
    let mut x = vec![0.0; k];
    for r in (0..k).rev() {
        let mut acc = rhs[r];
        for j in r + 1..k {
            acc -= m[r * k + j] * x[j];
        }
        x[r] = acc / m[r * k + r];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Newton steps moving each sample's parameter to its nearest curve point (fixed ends of
/// an open chain stay at the ends). `bases`, when given, are the chain's bases at `ts`
/// (they depend on the parameters and shapes only, not on the positions).
fn project(
    chain: &Chain,
    samples: &StretchSamples,
    ts: &mut [f64],
    steps: usize,
    bases: Option<&[Basis]>,
) {
    let nf = chain.nseg() as f64;
    let last = ts.len().saturating_sub(1);
    for (k, (p, big_t)) in samples.pts.iter().zip(ts.iter_mut()).enumerate() {
        if !chain.closed && (k == 0 || k == last) {
            continue;
        }
        let basis = bases.map_or_else(|| chain.basis(*big_t), |b| b[k]);
        // The point and derivative at the current parameter, carried over from the
        // accepted backtracking step (the same values a fresh evaluation gives).
        let (mut c, mut d) = basis.eval_deriv(&chain.pts);
        for _ in 0..steps {
            let dd = d.hypot2();
            if dd < 1e-18 {
                break;
            }
            let mut step = ((c - *p).dot(d) / dd).clamp(-0.25, 0.25);
            if step.abs() < 1e-9 {
                // Converged: a smaller step cannot be told from rounding.
                break;
            }
            // Backtrack: near a sharp point the speed vanishes and full steps overshoot.
            let here = (c - *p).hypot2();
            let mut moved = false;
            for _ in 0..6 {
                let mut next = *big_t - step;
                if !chain.closed {
                    next = next.clamp(0.0, nf);
                }
                let (c_next, d_next) = chain.eval_deriv(next);
                if (c_next - *p).hypot2() < here {
                    (*big_t, c, d) = (next, c_next, d_next);
                    moved = true;
                    break;
                }
                step *= 0.5;
            }
            if !moved {
                break;
            }
        }
    }
}

/// Two-sided sampled distance between the chain and the original stretch.
fn stretch_error(chain: &Chain, samples: &StretchSamples, ts: &mut [f64], segs: &[PathSeg]) -> f64 {
    project(chain, samples, ts, NEWTON_STEPS + 2, None);
    let mut worst: f64 = 0.0;
    for (p, &big_t) in samples.pts.iter().zip(ts.iter()) {
        worst = worst.max((chain.eval(big_t) - *p).hypot());
    }
    let boxes: Vec<Rect> = segs.iter().map(|s| s.bounding_box()).collect();
    let mut hint = 0;
    for j in 0..chain.nseg() {
        for i in 1..CURVE_SAMPLES {
            let p = chain.eval(j as f64 + i as f64 / CURVE_SAMPLES as f64);
            worst = worst.max(distance_to(p, segs, &boxes, &mut hint));
        }
    }
    worst
}

/// Distance from `p` to the nearest of `segs`, skipping segments whose bounding box is
/// farther than the best distance so far. The search starts at segment `*hint` (the
/// nearest for a previous, nearby point: its distance then rules out most boxes at once)
/// and leaves the nearest segment's index there; the distance is the same from any start.
pub fn distance_to(p: Point, segs: &[PathSeg], boxes: &[Rect], hint: &mut usize) -> f64 {
    let first = (*hint).min(segs.len().saturating_sub(1));
    let mut best = match segs.get(first) {
        Some(seg) => seg.nearest(p, 1e-6).distance_sq,
        None => return f64::INFINITY,
    };
    *hint = first;
    for (i, (seg, bb)) in segs.iter().zip(boxes).enumerate() {
        if i == first || box_distance_sq(*bb, p) >= best {
            continue;
        }
        let d = seg.nearest(p, 1e-6).distance_sq;
        if d < best {
            (best, *hint) = (d, i);
        }
    }
    best.sqrt()
}

/// Squared distance from `p` to the rectangle `bb` (zero inside).
fn box_distance_sq(bb: Rect, p: Point) -> f64 {
    let dx = (bb.x0 - p.x).max(p.x - bb.x1).max(0.0);
    let dy = (bb.y0 - p.y).max(p.y - bb.y1).max(0.0);
    dx * dx + dy * dy
}

/// The original contour as a polyline of sharp (`s = 0`) points within `tolerance` of it
/// (kurbo's flattening): the importer's last resort when no fit measures within the
/// bound. Many more points than a fit, but its error is known in advance.
pub fn polyline_xspline(segs: &[PathSeg], tolerance: f64) -> Vec<ControlPoint> {
    let path = kurbo::BezPath::from_path_segments(segs.iter().copied());
    let mut points: Vec<ControlPoint> = Vec::new();
    kurbo::flatten(&path, tolerance, |el| match el {
        kurbo::PathEl::MoveTo(p) | kurbo::PathEl::LineTo(p)
            if points.last().map(|q| q.pos) != Some(p) =>
        {
            points.push(cp(p, 0.0));
        }
        _ => {}
    });
    if points.len() > 1 && points.first().map(|q| q.pos) == points.last().map(|q| q.pos) {
        points.pop();
    }
    points
}

/// Samples `(T, point)` of a run of the X-spline and their bounding box.
struct PolyChunk<'a> {
    bounds: Rect,
    samples: &'a [(f64, Point)],
}

impl<'a> PolyChunk<'a> {
    fn new(samples: &'a [(f64, Point)]) -> Self {
        let first = Rect::from_points(samples[0].1, samples[0].1);
        PolyChunk {
            bounds: samples.iter().fold(first, |r, s| r.union_pt(s.1)),
            samples,
        }
    }
}

/// The foot of `p` on the chord from sample `a` to sample `b`: its parameter (linear
/// between theirs) and squared distance.
fn chord_foot(p: Point, a: (f64, Point), b: (f64, Point)) -> (f64, f64) {
    let d = b.1 - a.1;
    let len2 = d.hypot2();
    let u = if len2 > 0.0 {
        ((p - a.1).dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a.0 + u * (b.0 - a.0), (a.1 + u * d - p).hypot2())
}

/// A directed straight edge by the exact bits of its ends.
type EdgeKey = [u64; 4];

fn edge_key(a: Point, b: Point) -> EdgeKey {
    [a.x, a.y, b.x, b.y].map(f64::to_bits)
}

/// Two-sided distance between a finished X-spline and the original contour, measured
/// independently of the fitter: 32 curve samples per X-spline segment projected onto the
/// original (kurbo `nearest`), and 32 samples per original segment projected onto the
/// X-spline (the nearest chord of a 64-sample-per-segment polyline of it, then Newton
/// steps on the exact curve from there). Every distance is to a point on the curve, so
/// between samples the measure can only err high, by the polyline's sagitta at most.
///
/// (Nearest chords, not nearest samples: on a long straight edge the samples are a few
/// units apart, and a nearer sample of another segment, a corner a unit off the edge,
/// sent the Newton steps into that corner's local minimum: 3.46 units measured where the
/// curve passed 0.05 from the point.)
pub fn contour_error(spline: &XSpline, segs: &[PathSeg]) -> f64 {
    const PER_SEG: usize = 32;
    const CHUNK: usize = 8;
    let boxes: Vec<Rect> = segs.iter().map(|s| s.bounding_box()).collect();
    let n = spline.segment_count();
    let mut worst: f64 = 0.0;
    // The closed polyline: the last sample repeats the first at T = n.
    let mut poly = Vec::with_capacity(n * 2 * PER_SEG + 1);
    for k in 0..=n * 2 * PER_SEG {
        let big_t = k as f64 / (2 * PER_SEG) as f64;
        poly.push((big_t, spline.eval(big_t)));
    }
    // Straight edges both contours have: between two sharp points an X-spline is the
    // straight line joining them, so where the original has the same line (same ends, same
    // direction, which the importer's edges keep exactly), both distances along it are
    // zero, and neither side samples it (most of a CJK glyph's outline).
    let points = spline.points();
    let mut spline_edges: Vec<EdgeKey> = (0..n)
        .filter(|&j| points[j].is_sharp() && points[(j + 1) % n].is_sharp())
        .map(|j| edge_key(points[j].pos, points[(j + 1) % n].pos))
        .collect();
    spline_edges.sort_unstable();
    let mut original_edges: Vec<EdgeKey> = segs
        .iter()
        .filter_map(|seg| match seg {
            PathSeg::Line(l) => Some(edge_key(l.p0, l.p1)),
            _ => None,
        })
        .collect();
    original_edges.sort_unstable();
    // Every other polyline sample: T = k / PER_SEG.
    let mut hint = 0;
    for j in 0..n {
        let (a, b) = (points[j].pos, points[(j + 1) % n].pos);
        let straight = points[j].is_sharp() && points[(j + 1) % n].is_sharp();
        if straight && original_edges.binary_search(&edge_key(a, b)).is_ok() {
            continue;
        }
        for &(_, p) in poly[2 * PER_SEG * j..].iter().step_by(2).take(PER_SEG) {
            worst = worst.max(distance_to(p, segs, &boxes, &mut hint));
        }
    }
    // The polyline in two levels of runs with their bounding boxes (one X-spline segment,
    // then 8 chords; a run holds the sample its last chord ends at): a run whose box is
    // no nearer than the best chord so far cannot hold a nearer one, so the search below
    // finds the same chord as a scan of every one, without visiting most. Hand-written:
    // the runs are fixed and tiny, a spatial index crate would cost more to build than it
    // saves.
    let runs = |samples: &'_ [(f64, Point)], len: usize| -> Vec<usize> {
        (0..samples.len() - 1).step_by(len).collect()
    };
    let groups: Vec<(PolyChunk, Vec<PolyChunk>)> = runs(&poly, 2 * PER_SEG)
        .into_iter()
        .map(|g| {
            let run = &poly[g..(g + 2 * PER_SEG + 1).min(poly.len())];
            let chunks = runs(run, CHUNK)
                .into_iter()
                .map(|c| PolyChunk::new(&run[c..(c + CHUNK + 1).min(run.len())]))
                .collect();
            (PolyChunk::new(run), chunks)
        })
        .collect();
    // The search starts from the chord found for the previous original sample (nearby,
    // so most runs are skipped at once); ties keep the earlier candidate either way.
    let mut seed = (poly[0], poly[1]);
    for seg in segs {
        if let PathSeg::Line(l) = seg {
            if spline_edges.binary_search(&edge_key(l.p0, l.p1)).is_ok() {
                continue;
            }
        }
        for i in 0..PER_SEG {
            let p = seg.eval(i as f64 / PER_SEG as f64);
            let (mut big_t, mut best) = chord_foot(p, seed.0, seed.1);
            for (group, chunks) in &groups {
                if box_distance_sq(group.bounds, p) >= best {
                    continue;
                }
                for chunk in chunks {
                    if box_distance_sq(chunk.bounds, p) >= best {
                        continue;
                    }
                    for pair in chunk.samples.windows(2) {
                        let (t, d) = chord_foot(p, pair[0], pair[1]);
                        if d < best {
                            (big_t, best) = (t, d);
                            seed = (pair[0], pair[1]);
                        }
                    }
                }
            }
            // From the chord to the curve: its point at the foot's parameter, then Newton
            // steps while they get nearer.
            best = (spline.eval(big_t) - p).hypot2();
            for _ in 0..8 {
                let (c, d) = spline.eval_deriv(big_t);
                let dd = d.hypot2();
                if dd < 1e-18 {
                    break;
                }
                let next = big_t - ((c - p).dot(d) / dd).clamp(-0.1, 0.1);
                let e = (spline.eval(next) - p).hypot2();
                if e >= best {
                    break;
                }
                big_t = next;
                best = e;
            }
            worst = worst.max(best.sqrt());
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::import::contour::{contours, cut};
    use kurbo::Shape;

    #[test]
    fn circle_becomes_one_smooth_loop() {
        let circle = kurbo::Circle::new((0.0, 0.0), 500.0).to_path(1e-9);
        let contour = &contours(&circle)[0];
        let fitted = fit_xspline(&cut(contour), 1.0).unwrap();
        assert_eq!(fitted.points.len(), 8);
        assert!(fitted.points.iter().all(|p| p.s == 1.0));
        assert!(fitted.fit_error <= 1.0);
        let spline = XSpline::new(fitted.points).unwrap();
        let err = contour_error(&spline, &contour.segs);
        assert!(err <= 1.0 && err > 0.5, "{err}");
    }

    #[test]
    fn between_two_sharp_points_the_xspline_is_their_line() {
        // contour_error skips edges both contours share on this property.
        let p = |x: f64, y: f64, s: f64| ControlPoint::new(x, y, s);
        let spline = XSpline::new(vec![
            p(0.0, 0.0, 0.0),
            p(300.0, 100.0, 0.0),
            p(250.0, 400.0, 1.0),
            p(-50.0, 300.0, 1.0),
        ])
        .unwrap();
        for k in 0..=64 {
            let q = spline.eval(k as f64 / 64.0);
            let off = (q - Point::ZERO).cross(Vec2::new(300.0, 100.0)).abs() / 100f64.hypot(300.0);
            assert!(off < 1e-9 && (0.0..=300.0).contains(&q.x), "{q:?}");
        }
        // And a shared edge costs nothing: the original square against itself.
        let square = kurbo::Rect::new(0.0, 0.0, 100.0, 100.0).to_path(1e-9);
        let segs = &contours(&square)[0].segs;
        let corners = segs.iter().map(|s| cp(s.start(), 0.0)).collect();
        assert_eq!(contour_error(&XSpline::new(corners).unwrap(), segs), 0.0);
    }

    #[test]
    fn rounded_square_keeps_its_edges() {
        // A square with rounded corners: four straight edges (eight sharp points) and four
        // quarter circles between them.
        let shape = kurbo::RoundedRect::new(0.0, 0.0, 1000.0, 1000.0, 200.0).to_path(1e-9);
        let contour = &contours(&shape)[0];
        let fitted = fit_xspline(&cut(contour), 1.0).unwrap();
        let sharp = fitted.points.iter().filter(|p| p.s == 0.0).count();
        assert_eq!(sharp, 8);
        let spline = XSpline::new(fitted.points.clone()).unwrap();
        assert!(contour_error(&spline, &contour.segs) <= 1.0);
        // Each edge is exactly two consecutive sharp points on the original edge.
        let on_edge =
            fitted.points.iter().filter(|p| p.s == 0.0).all(|p| {
                p.pos.x == 0.0 || p.pos.x == 1000.0 || p.pos.y == 0.0 || p.pos.y == 1000.0
            });
        assert!(on_edge);
    }
}
