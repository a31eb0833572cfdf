//! Cubic outlines of all masters to TrueType quadratic contours with the same points.
//!
//! The cubics at one place of every master go through kurbo's
//! `cubics_to_quadratic_splines` together (cu2qu on all masters at once), so each becomes
//! a spline with the same number of off-curve points in every master, each within
//! `accuracy` of its cubic. The on-curve points inside a spline are implied (midpoints of
//! their off-curve neighbours) in every master by construction, so they are left out; every
//! segment end is an explicit on-curve point. Should no common spline exist (kurbo gives
//! up after 100 pieces), the cubics are split in half, all at the same parameter, with an
//! explicit on-curve point at the split.
//!
//! Contours are reversed, as in the static TTF (`otf/quadratic.rs`): TrueType wants outer
//! contours clockwise. Nothing is dropped unless it is dropped in every master: the closing
//! point is left out only when it equals the start point in each master.

use std::mem::discriminant;

use kurbo::{
    cubics_to_quadratic_splines, BezPath, CubicBez, ParamCurve, PathEl, Point, QuadSpline,
};

use crate::otf::quadratic::{finer_if_needed, turns_back_needlessly, SplinePoint};

/// Contour points of one glyph, per master (the default first): `[master][contour][point]`.
pub type MasterContours = Vec<Vec<Vec<SplinePoint>>>;

/// The reversed contours of `paths` (one per master, same elements) as TrueType point
/// lists with the same points in every master, each within `accuracy` of its cubics; or
/// the index of the first path whose elements differ from the first one's.
pub fn compatible_contours(paths: &[&BezPath], accuracy: f64) -> Result<MasterContours, usize> {
    let reversed: Vec<BezPath> = paths.iter().map(|p| p.reverse_subpaths()).collect();
    let count = reversed[0].elements().len();
    if let Some(m) = reversed.iter().position(|p| p.elements().len() != count) {
        return Err(m);
    }
    let masters = reversed.len();
    let mut contours: MasterContours = vec![Vec::new(); masters];
    let mut points: Vec<Vec<SplinePoint>> = vec![Vec::new(); masters];
    let mut current = vec![Point::ZERO; masters];
    let on = |point| SplinePoint {
        point,
        on_curve: true,
    };
    let off = |point| SplinePoint {
        point,
        on_curve: false,
    };
    for i in 0..count {
        let els: Vec<PathEl> = reversed.iter().map(|p| p.elements()[i]).collect();
        if let Some(m) = els
            .iter()
            .position(|e| discriminant(e) != discriminant(&els[0]))
        {
            return Err(m);
        }
        match els[0] {
            PathEl::MoveTo(_) => {
                finish(&mut points, &mut contours);
                for (m, el) in els.iter().enumerate() {
                    if let PathEl::MoveTo(p) = *el {
                        points[m].push(on(p));
                        current[m] = p;
                    }
                }
            }
            PathEl::LineTo(_) => {
                for (m, el) in els.iter().enumerate() {
                    if let PathEl::LineTo(p) = *el {
                        points[m].push(on(p));
                        current[m] = p;
                    }
                }
            }
            PathEl::QuadTo(..) => {
                for (m, el) in els.iter().enumerate() {
                    if let PathEl::QuadTo(c, p) = *el {
                        points[m].extend([off(c), on(p)]);
                        current[m] = p;
                    }
                }
            }
            PathEl::CurveTo(..) => {
                let cubics: Vec<CubicBez> = els
                    .iter()
                    .zip(&current)
                    .map(|(el, &p0)| match *el {
                        PathEl::CurveTo(a, b, p) => CubicBez::new(p0, a, b, p),
                        _ => CubicBez::new(p0, p0, p0, p0),
                    })
                    .collect();
                for (m, spline) in splines(&cubics, accuracy, 0).into_iter().enumerate() {
                    points[m].extend(spline);
                    current[m] = cubics[m].p3;
                }
            }
            PathEl::ClosePath => finish(&mut points, &mut contours),
        }
    }
    finish(&mut points, &mut contours);
    Ok(contours)
}

/// Ends the current contour of every master: the closing point is dropped when it repeats
/// the start point in all of them.
fn finish(points: &mut [Vec<SplinePoint>], contours: &mut MasterContours) {
    let closes = points
        .iter()
        .all(|p| p.len() > 1 && p.last().map(|q| q.point) == p.first().map(|q| q.point));
    for (master, contour) in points.iter_mut().enumerate() {
        if closes {
            contour.pop();
        }
        if !contour.is_empty() {
            contours[master].push(std::mem::take(contour));
        }
    }
}

/// The points after the start of one quadratic spline per cubic (same count for all):
/// off-curve points, then the end point on the curve.
///
/// As in the static TTF, splines with a quadratic that turns back where its master's cubic
/// runs one way are made again finer ([`finer_if_needed`]).
fn splines(cubics: &[CubicBez], accuracy: f64, depth: u32) -> Vec<Vec<SplinePoint>> {
    let found = finer_if_needed(
        accuracy,
        |accuracy| cubics_to_quadratic_splines(cubics, accuracy),
        |splines| {
            let turns = |(c, s): (&CubicBez, &QuadSpline)| turns_back_needlessly(c, s.points());
            !cubics.iter().zip(splines).any(turns)
        },
    );
    if let Some(splines) = found {
        return splines
            .iter()
            .map(|s| {
                let pts = s.points();
                let inner = &pts[1..pts.len().saturating_sub(1)];
                inner
                    .iter()
                    .map(|&point| SplinePoint {
                        point,
                        on_curve: false,
                    })
                    .chain(pts.last().map(|&point| SplinePoint {
                        point,
                        on_curve: true,
                    }))
                    .collect()
            })
            .collect();
    }
    // 100 pieces were not enough (a cusp, or accuracy far below the curve's size): halve
    // every master's cubic at the same parameter. Bounded so that a degenerate input cannot
    // recurse forever; at depth 16 the halves are straight to any accuracy that matters.
    if depth >= 16 {
        return cubics
            .iter()
            .map(|c| {
                vec![SplinePoint {
                    point: c.p3,
                    on_curve: true,
                }]
            })
            .collect();
    }
    let first: Vec<CubicBez> = cubics.iter().map(|c| c.subsegment(0.0..0.5)).collect();
    let second: Vec<CubicBez> = cubics.iter().map(|c| c.subsegment(0.5..1.0)).collect();
    let mut out = splines(&first, accuracy, depth + 1);
    for (m, rest) in splines(&second, accuracy, depth + 1)
        .into_iter()
        .enumerate()
    {
        out[m].extend(rest);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masters_get_the_same_points() {
        // A quarter disc and a wider one: the wide arc needs more quadratics on its own.
        let disc = |w: f64| {
            let k = 0.5523;
            let mut p = BezPath::new();
            p.move_to((0.0, 0.0));
            p.line_to((w, 0.0));
            p.curve_to((w, k * 100.0), (k * w, 100.0), (0.0, 100.0));
            p.close_path();
            p
        };
        let (a, b) = (disc(100.0), disc(900.0));
        let alone = |p: &BezPath| compatible_contours(&[p], 0.1).unwrap()[0][0].len();
        assert!(alone(&a) < alone(&b), "{} {}", alone(&a), alone(&b));
        let both = compatible_contours(&[&a, &b], 0.1).unwrap();
        assert_eq!(both[0][0].len(), alone(&b));
        assert_eq!(both[1][0].len(), alone(&b));
        let kinds = |c: &[SplinePoint]| c.iter().map(|p| p.on_curve).collect::<Vec<_>>();
        assert_eq!(kinds(&both[0][0]), kinds(&both[1][0]));
        // Reversed like the static TTF, closing point dropped in both.
        assert_eq!(both[1][0][0].point, Point::new(0.0, 100.0));
        assert_eq!(both[1][0].last().unwrap().point, Point::new(0.0, 0.0));
    }

    #[test]
    fn other_elements_are_an_error() {
        let mut a = BezPath::new();
        a.move_to((0.0, 0.0));
        a.line_to((10.0, 0.0));
        a.line_to((0.0, 10.0));
        a.close_path();
        let mut b = BezPath::new();
        b.move_to((0.0, 0.0));
        b.line_to((10.0, 0.0));
        b.curve_to((10.0, 5.0), (5.0, 10.0), (0.0, 10.0));
        b.close_path();
        assert_eq!(compatible_contours(&[&a, &a, &b], 0.1), Err(2));
    }
}
