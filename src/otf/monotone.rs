//! Monotone curves stay monotone on the grid: no extreme without a point is made by rounding.
//!
//! The fitted outline has an on-curve point at each of its extrema (`crate::extrema`), so
//! every curve runs one way in x and one way in y. Rounding each control point on its own
//! can break that by a unit: a handle that rounds onto its end's coordinate while the other
//! handle lies past it, or a handle a unit past its end range, makes the rounded curve
//! turn back just before its end. That is an extreme without a point, which font checkers
//! flag (FontForge's "Missing points at extrema": a curve longer than em/32 whose handles
//! leave its end range and whose derivative has a root inside it).
//!
//! Here such a curve's off-curve points are moved on the grid, on that axis only, a unit
//! or two, until the curve runs one way again:
//! - a cubic (CFF, [`keep_cubic`]): its handles clamped into the end range when allowed,
//!   otherwise the smallest move of the two that leaves no root; the cubic stays within
//!   [`PULLED`] of the exact one (a bound, not a sample);
//! - a TrueType quadratic spline ([`keep_quadratics`]): an off-curve point moved onto its
//!   quadratic's end range, the implied on-curve points beside it moving with it; the point
//!   stays within [`PULLED`] of its exact place, so the spline, a convex combination of its
//!   points, stays within one unit.
//!
//! Only a curve that the exact outline has monotone (passing its end range by less than
//! [`FAINT`]) is touched: a real extreme that the extrema pass left unsplit (a piece below
//! `extrema::MIN_PIECE`) keeps its rounded points. Limits: a move that would turn a short
//! handle by more than [`PULL_TURN`], or leave the bound, is not made, and the extreme stays.

use kurbo::{CubicBez, ParamCurveExtrema, PathEl, Point, QuadBez, Vec2};

use super::grid::{distance_bound, PULLED};

/// Farthest a rounded handle is moved on one axis, font units.
const PULL: f64 = 2.0;
/// Most a move of more than one unit may turn a handle (radians, as the ratio of the move
/// to the handle's length): a short handle at a smooth join keeps its direction, or the
/// join would kink. One unit, rounding's own scale, is always allowed.
const PULL_TURN: f64 = 0.05;
/// An exact curve that passes its end range by less than this (font units) on an axis is
/// taken as monotone there: the extreme is below the grid.
const FAINT: f64 = 0.5;
/// A derivative root this close to an end (in the parameter) is the end's own: FontForge
/// does not count it either.
const AT_END: f64 = 1e-6;

/// The moves tried for a cubic's two handles on one axis after the clamp, smallest first
/// (total, then largest single move): every pair in `-2..=2` but `(0, 0)`.
const MOVES: [(i8, i8); 24] = [
    (-1, 0),
    (0, -1),
    (0, 1),
    (1, 0),
    (-1, -1),
    (-1, 1),
    (1, -1),
    (1, 1),
    (-2, 0),
    (0, -2),
    (0, 2),
    (2, 0),
    (-2, -1),
    (-2, 1),
    (-1, -2),
    (-1, 2),
    (1, -2),
    (1, 2),
    (2, -1),
    (2, 1),
    (-2, -2),
    (-2, 2),
    (2, -2),
    (2, 2),
];

/// The coordinate of `p` on `axis` (0 is x, 1 is y).
pub(super) fn coord(p: Point, axis: usize) -> f64 {
    if axis == 0 {
        p.x
    } else {
        p.y
    }
}

/// `p` with its coordinate on `axis` moved by `by`.
fn moved(p: Point, axis: usize, by: f64) -> Point {
    if axis == 0 {
        Point::new(p.x + by, p.y)
    } else {
        Point::new(p.x, p.y + by)
    }
}

/// Whether the cubic with coordinates `c` on one axis turns back inside its span: a handle
/// leaves the end range and the derivative has a root strictly inside (0, 1), the test of
/// FontForge's validation.
fn cubic_turns_back(c: [f64; 4]) -> bool {
    let (lo, hi) = (c[0].min(c[3]), c[0].max(c[3]));
    if (lo..=hi).contains(&c[1]) && (lo..=hi).contains(&c[2]) {
        return false;
    }
    // The derivative over 3 in Bernstein form, d0 (1-t)² + 2 d1 t(1-t) + d2 t², as a
    // power series a t² + b t + k; exact on the grid's integers.
    let (d0, d1, d2) = (c[1] - c[0], c[2] - c[1], c[3] - c[2]);
    let (a, b, k) = (d0 - 2.0 * d1 + d2, 2.0 * (d1 - d0), d0);
    let inside = |t: f64| t > AT_END && t < 1.0 - AT_END;
    if a == 0.0 {
        return b != 0.0 && inside(-k / b);
    }
    let disc = b * b - 4.0 * a * k;
    if disc < 0.0 {
        return false;
    }
    let root = disc.sqrt();
    inside((-b - root) / (2.0 * a)) || inside((-b + root) / (2.0 * a))
}

/// Whether a cubic turns back inside its span in x and in y ([`cubic_turns_back`]).
pub(super) fn turns_back(c: &CubicBez) -> [bool; 2] {
    [0, 1].map(|axis| {
        cubic_turns_back([
            coord(c.p0, axis),
            coord(c.p1, axis),
            coord(c.p2, axis),
            coord(c.p3, axis),
        ])
    })
}

/// How far an exact curve passes its end range on `axis` (0 when it is monotone there).
fn excursion(exact: &impl ParamCurveExtrema, axis: usize) -> f64 {
    let (e0, e1) = (coord(exact.start(), axis), coord(exact.end(), axis));
    let (lo, hi) = (e0.min(e1), e0.max(e1));
    exact
        .extrema()
        .into_iter()
        .map(|t| {
            let v = coord(exact.eval(t), axis);
            (v - hi).max(lo - v)
        })
        .fold(0.0, f64::max)
}

/// Whether a move of `by` units on a handle `handle` long is small enough (see [`PULL`]).
fn small(by: f64, handle: Vec2) -> bool {
    by <= 1.0 || (by <= PULL && by <= PULL_TURN * handle.hypot())
}

/// Keeps a rounded cubic (`p0`, handles `a` and `b`, `p3`, all on the grid) from turning
/// back on an axis where the exact cubic does not (within [`FAINT`]).
///
/// The handles are first clamped into the end range (the cubic then lies in its hull
/// there, and an extreme handle keeps its axis-aligned direction); where that moves a
/// handle too far, the smallest of [`MOVES`] that leaves no root is taken. Either must keep
/// the cubic within [`PULLED`] of the exact one.
pub(super) fn keep_cubic(exact: &CubicBez, p0: Point, (a, b): (&mut Point, &mut Point), p3: Point) {
    for axis in [0, 1] {
        let on_axis = |a: Point, b: Point| {
            [
                coord(p0, axis),
                coord(a, axis),
                coord(b, axis),
                coord(p3, axis),
            ]
        };
        if !cubic_turns_back(on_axis(*a, *b)) || excursion(exact, axis) >= FAINT {
            continue;
        }
        let (lo, hi) = (
            coord(p0, axis).min(coord(p3, axis)),
            coord(p0, axis).max(coord(p3, axis)),
        );
        let clamp = |p: Point| coord(p, axis).clamp(lo, hi) - coord(p, axis);
        let clamped = (clamp(*a), clamp(*b));
        let tries = std::iter::once(clamped)
            .chain(MOVES.iter().map(|&(i, j)| (f64::from(i), f64::from(j))));
        for (by_a, by_b) in tries {
            if !small(by_a.abs(), *a - p0) || !small(by_b.abs(), *b - p3) {
                continue;
            }
            let (na, nb) = (moved(*a, axis, by_a), moved(*b, axis, by_b));
            if cubic_turns_back(on_axis(na, nb)) {
                continue;
            }
            if distance_bound(exact, &CubicBez::new(p0, na, nb, p3)) <= PULLED {
                (*a, *b) = (na, nb);
                break;
            }
        }
    }
}

/// Most the exact handles at a join may bend from a straight line for the join to count as
/// smooth (radians, as a sine).
const SMOOTH: f64 = 0.02;

/// The cubic of element `k` of a contour (`MoveTo`, then segments), if it is one.
fn cubic_of(contour: &[PathEl], k: usize) -> Option<CubicBez> {
    let start = contour.get(k.checked_sub(1)?)?.end_point()?;
    match contour[k] {
        PathEl::CurveTo(a, b, p) => Some(CubicBez::new(start, a, b, p)),
        _ => None,
    }
}

/// Levels a smooth join of two cubics where the rounded outline turns back beside it on an
/// axis and the exact one passes the join by less than [`FAINT`]: both handles are put on
/// the join's coordinate there, so the join becomes the extreme, with a level (or plumb)
/// tangent on both sides.
///
/// This is the extreme the extrema pass leaves unsplit because it lies within
/// `extrema::MIN_PIECE` of the join: the exact curve turns a fraction of a unit before it,
/// and on the grid that becomes a turn with the handle a unit or two past the join (EB
/// Garamond `X`, `k`, `oe`, imported and built). A handle too short to clamp on its own
/// ([`keep_cubic`]) can be levelled here, since its partner turns with it. Both cubics must
/// stay within [`PULLED`] of the exact ones, no handle may land on the join, and neither
/// cubic may turn back on the axis afterwards. `contour` is on the grid and `exact` holds
/// its elements before rounding; both start with the `MoveTo` and have no closing line.
pub(super) fn keep_joins(contour: &mut [PathEl], exact: &[PathEl]) {
    let n = contour.len();
    let Some(PathEl::MoveTo(start)) = contour.first().copied() else {
        return;
    };
    for k in 1..n {
        // The segment after element k: the next, or round the contour's start.
        let next = if k + 1 < n {
            k + 1
        } else if contour[k].end_point() == Some(start) && n > 2 {
            1
        } else {
            continue;
        };
        let (Some(c1), Some(c2)) = (cubic_of(contour, k), cubic_of(contour, next)) else {
            continue;
        };
        let (Some(e1), Some(e2)) = (cubic_of(exact, k), cubic_of(exact, next)) else {
            continue;
        };
        let (u, v) = (e1.p2 - e1.p3, e2.p1 - e2.p0);
        let smooth = u.dot(v) < 0.0 && u.cross(v).abs() <= SMOOTH * u.hypot() * v.hypot();
        if !smooth {
            continue;
        }
        for axis in [0, 1] {
            let on_axis = |c: &CubicBez| {
                [
                    coord(c.p0, axis),
                    coord(c.p1, axis),
                    coord(c.p2, axis),
                    coord(c.p3, axis),
                ]
            };
            let (c1, c2) = (
                cubic_of(contour, k).unwrap_or(c1),
                cubic_of(contour, next).unwrap_or(c2),
            );
            if !(cubic_turns_back(on_axis(&c1)) || cubic_turns_back(on_axis(&c2)))
                || excursion(&e1, axis) >= FAINT
                || excursion(&e2, axis) >= FAINT
            {
                continue;
            }
            let join = coord(c1.p3, axis);
            let (mut l1, mut l2) = (c1, c2);
            l1.p2 = moved(c1.p2, axis, join - coord(c1.p2, axis));
            l2.p1 = moved(c2.p1, axis, join - coord(c2.p1, axis));
            let fine = l1.p2 != l1.p3
                && l2.p1 != l2.p0
                && !cubic_turns_back(on_axis(&l1))
                && !cubic_turns_back(on_axis(&l2))
                && distance_bound(&e1, &l1) <= PULLED
                && distance_bound(&e2, &l2) <= PULLED;
            if fine {
                contour[k] = PathEl::CurveTo(l1.p1, l1.p2, l1.p3);
                contour[next] = PathEl::CurveTo(l2.p1, l2.p2, l2.p3);
            }
        }
    }
}

/// The quadratic of the off-curve point `i` of a closed TrueType contour: from the
/// on-curve point before it (or the implied one, halfway to the off-curve point before
/// it) to the one after it.
fn quadratic(points: &[Point], on_curve: &[bool], i: usize) -> QuadBez {
    let n = points.len();
    let (before, after) = ((i + n - 1) % n, (i + 1) % n);
    let end = |j: usize| {
        if on_curve[j] {
            points[j]
        } else {
            points[i].midpoint(points[j])
        }
    };
    QuadBez::new(end(before), points[i], end(after))
}

/// Whether a quadratic turns back on `axis`: its off-curve point leaves the end range.
fn quadratic_turns_back(q: &QuadBez, axis: usize) -> bool {
    let (c0, c1, c2) = (coord(q.p0, axis), coord(q.p1, axis), coord(q.p2, axis));
    c1 < c0.min(c2) || c1 > c0.max(c2)
}

/// Keeps the rounded quadratics of a closed TrueType contour (`rounded`, on the grid, with
/// `exact` its points before rounding) from turning back where the exact ones do not
/// (within [`FAINT`]).
///
/// An off-curve point whose quadratic turns back is moved a unit on that axis toward the
/// end range when it stays within [`PULLED`] of its exact place and the move lowers the
/// number of turns among its own quadratic and its two neighbours' (whose implied end
/// points move with it). Returns the number of points moved.
pub(super) fn keep_quadratics(exact: &[Point], rounded: &mut [Point], on_curve: &[bool]) -> usize {
    let n = rounded.len();
    // The turns that count: the off-curve points around `i` whose rounded quadratic turns
    // back on an axis where the exact one is monotone.
    let turns_near = |points: &[Point], i: usize| -> usize {
        [(i + n - 1) % n, i, (i + 1) % n]
            .into_iter()
            .filter(|&j| !on_curve[j])
            .map(|j| {
                let (q, e) = (
                    quadratic(points, on_curve, j),
                    quadratic(exact, on_curve, j),
                );
                (0..2)
                    .filter(|&axis| quadratic_turns_back(&q, axis) && excursion(&e, axis) < FAINT)
                    .count()
            })
            .sum()
    };
    let mut count = 0;
    for i in 0..n {
        if on_curve[i] || n < 3 {
            continue;
        }
        for axis in [0, 1] {
            let q = quadratic(rounded, on_curve, i);
            if !quadratic_turns_back(&q, axis)
                || excursion(&quadratic(exact, on_curve, i), axis) >= FAINT
            {
                continue;
            }
            // Toward the end range: down when past its top, up when below its bottom.
            let by = if coord(q.p1, axis) > coord(q.p0, axis).max(coord(q.p2, axis)) {
                -1.0
            } else {
                1.0
            };
            let before = turns_near(rounded, i);
            let was = rounded[i];
            rounded[i] = moved(was, axis, by);
            if (rounded[i] - exact[i]).hypot() > PULLED || turns_near(rounded, i) >= before {
                rounded[i] = was;
            } else {
                count += 1;
            }
        }
    }
    count
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_turn_is_a_root_inside_with_a_handle_outside() {
        // Liberation Sans `braceleft` on the grid: handle one past the end's x = 417, handle
        // two on it; the derivative's roots are t = 1 and t = 98/108.
        assert!(cubic_turns_back([324.0, 422.0, 417.0, 417.0]));
        // Its exact cubic: the same handle outside, but no root (25 < 97.9 × 0.271).
        assert!(!cubic_turns_back([323.835, 421.726, 416.729, 417.0]));
        // Handles in the range never turn.
        assert!(!cubic_turns_back([0.0, 0.0, 10.0, 10.0]));
        // A plain bulge does.
        assert!(cubic_turns_back([0.0, 5.0, 5.0, 0.0]));
    }

    fn rounded(exact: CubicBez) -> CubicBez {
        let r = |p: Point| Point::new(p.x.round(), p.y.round());
        let (p0, mut a, mut b, p3) = (r(exact.p0), r(exact.p1), r(exact.p2), r(exact.p3));
        keep_cubic(&exact, p0, (&mut a, &mut b), p3);
        CubicBez::new(p0, a, b, p3)
    }

    /// Liberation Sans `braceleft` and Liberation Mono Bold `D` (2048 units per em): the
    /// exact cubics run one way; rounded on their own they turn back just after their
    /// start or before their end, with the other handle too far out to clamp.
    #[test]
    fn a_handle_rounded_onto_its_end_is_moved_a_unit() {
        let brace = CubicBez::new(
            (323.835, 580.825),
            (421.726, 659.528),
            (416.729, 771.24),
            (417.0, 784.0),
        );
        let kept = rounded(brace);
        assert_eq!(
            [kept.p1, kept.p2],
            [Point::new(422.0, 660.0), Point::new(416.0, 771.0)]
        );
        let xs = |c: &CubicBez| [c.p0.x, c.p1.x, c.p2.x, c.p3.x];
        assert!(!cubic_turns_back(xs(&kept)));
        assert!(distance_bound(&brace, &kept) <= PULLED);
        // The bowl's start (`het`): the handle onto the start's y, the other past it.
        let het = CubicBez::new(
            (695.336, 1056.261),
            (701.705, 1056.041),
            (875.594, 1059.801),
            (944.073, 957.476),
        );
        let kept = rounded(het);
        let ys = |c: &CubicBez| [c.p0.y, c.p1.y, c.p2.y, c.p3.y];
        assert!(cubic_turns_back([1056.0, 1056.0, 1060.0, 957.0]));
        assert!(!cubic_turns_back(ys(&kept)), "{kept:?}");
        assert_eq!(kept.p1, Point::new(702.0, 1055.0));
        assert!(distance_bound(&het, &kept) <= PULLED);
    }

    /// EB Garamond `k`: a smooth join whose exact tangent leans 5 degrees off the vertical,
    /// with the curve's x extreme 0.3 units after it. On the grid the second cubic's handle
    /// is 2 units right of the join, too short a handle (16 units) to clamp on its own; the
    /// join is levelled instead, both handles onto its x.
    #[test]
    fn a_smooth_join_beside_a_faint_extreme_is_levelled() {
        let exact = [
            PathEl::MoveTo(Point::new(191.908, -3.31)),
            PathEl::CurveTo(
                Point::new(204.199, -3.31),
                Point::new(212.522, -1.114),
                Point::new(213.19, 6.225),
            ),
            PathEl::CurveTo(
                Point::new(214.648, 22.261),
                Point::new(173.085, 23.932),
                Point::new(161.978, 39.592),
            ),
            PathEl::LineTo(Point::new(100.0, 0.0)),
        ];
        let r = |p: Point| Point::new(p.x.round(), p.y.round());
        let mut contour: Vec<PathEl> = exact
            .iter()
            .map(|el| match *el {
                PathEl::MoveTo(p) => PathEl::MoveTo(r(p)),
                PathEl::LineTo(p) => PathEl::LineTo(r(p)),
                PathEl::CurveTo(a, b, p) => PathEl::CurveTo(r(a), r(b), r(p)),
                other => other,
            })
            .collect();
        let xs = |c: CubicBez| [c.p0.x, c.p1.x, c.p2.x, c.p3.x];
        let before = cubic_of(&contour, 2).unwrap();
        assert!(cubic_turns_back(xs(before)));
        keep_joins(&mut contour, &exact);
        let (first, second) = (
            cubic_of(&contour, 1).unwrap(),
            cubic_of(&contour, 2).unwrap(),
        );
        assert_eq!(first.p2, Point::new(213.0, -1.0));
        assert_eq!(second.p1, Point::new(213.0, 22.0));
        assert!(!cubic_turns_back(xs(first)) && !cubic_turns_back(xs(second)));
        for (k, c) in [(1, first), (2, second)] {
            assert!(distance_bound(&cubic_of(&exact, k).unwrap(), &c) <= PULLED);
        }
    }

    /// A quadratic whose off-curve point rounds a unit past the start's x (Liberation Sans
    /// `bullet`): moved back onto it; the implied end point moves half a unit with it.
    #[test]
    fn a_quadratic_handle_rounded_past_its_end_is_moved_back() {
        let exact = [
            Point::new(636.9, 683.2),
            Point::new(637.6, 639.3),
            Point::new(610.2, 555.1),
            Point::new(560.0, 540.0),
        ];
        let on_curve = [true, false, false, true];
        let mut points: Vec<Point> = exact
            .iter()
            .map(|p| Point::new(p.x.round(), p.y.round()))
            .collect();
        assert!(quadratic_turns_back(&quadratic(&points, &on_curve, 1), 0));
        assert_eq!(keep_quadratics(&exact, &mut points, &on_curve), 1);
        assert_eq!(points[1], Point::new(637.0, 639.0));
        assert!(!quadratic_turns_back(&quadratic(&points, &on_curve, 1), 0));
        // A real extreme (the exact point 0.6 past) is left.
        let bulge = [
            Point::new(0.0, 0.0),
            Point::new(1.2, 50.0),
            Point::new(0.0, 100.0),
            Point::new(-50.0, 50.0),
        ];
        let on_curve = [true, false, true, true];
        let mut points: Vec<Point> = bulge
            .iter()
            .map(|p| Point::new(p.x.round(), p.y.round()))
            .collect();
        assert_eq!(keep_quadratics(&bulge, &mut points, &on_curve), 0);
        assert_eq!(points[1], Point::new(1.0, 50.0));
    }
}
