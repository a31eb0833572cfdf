//! Spikes on the grid: a sharp corner whose two sides leave it at an acute angle keeps its
//! sides in the same order after rounding.
//!
//! Where a curve meets a line in a narrow notch (the `r` of C059 Bold Italic: its arm's
//! curve arrives at the stem at 34° from the vertical, the stem's edge leaves at 14°), the
//! handle at the corner is a unit or so long, and rounding it on its own can swing it
//! past the other side: the rounded contour then crosses itself just beside the corner,
//! which font checkers flag (FontForge's "self-intersecting"). The point that sets that
//! side's direction (the handle, or the end of a segment shorter than a unit), or else the
//! corner itself, is moved to another grid point within one unit of its exact place: the
//! nearest that puts the sides back in order, breaks no corner nearby, folds no segment
//! back, and leaves the two sides' control polygons apart.
//!
//! Limits: the rounded order is that of the sides' first control points, so two sides that
//! leave in nearly the same direction (an imported sliver a tenth of a unit wide) can keep
//! it at the corner and still cross a few units on; a corner whose sides leave it in
//! exactly the same direction has no order to keep; a side's exact direction is taken a
//! unit out, so a hook below the grid (a handle a fraction of a unit long turning back) is
//! rounded away as before, not kept.

use kurbo::{Point, Vec2};

/// Farthest a point is moved from its exact place, font units: each point of a curve is
/// a convex combination of its control points, so the rounded curve stays within this of
/// the exact one ([`super::PULLED`]; within √2/2 where nothing moves).
pub const MOVE: f64 = super::PULLED;

/// Keeps every spike of a closed contour in order: `exact` and `rounded` are its points
/// before and after rounding (in order), `on_curve` tells on-curve points from handles.
/// `allowed(rounded, j)` says whether point `j` may take the value it has in `rounded` (for
/// a further bound the caller keeps); a move is tried only within [`MOVE`] of the exact
/// point. Returns how many points moved.
pub fn keep_spikes(
    exact: &[Point],
    rounded: &mut [Point],
    on_curve: &[bool],
    allowed: impl Fn(&[Point], usize) -> bool,
) -> usize {
    let n = exact.len();
    if n < 3 || rounded.len() != n || on_curve.len() != n {
        return 0;
    }
    // Broken points (corners, or any control point folded back) within `NEAR` of `j`,
    // around the contour.
    let broken_near = |rounded: &[Point], j: usize| {
        (0..=2 * NEAR.min((n - 1) / 2))
            .map(|k| (j + n - NEAR.min((n - 1) / 2) + k) % n)
            .filter(|&c| broken(exact, rounded, c).is_some())
            .count()
    };
    let mut moved = 0;
    for i in 0..n {
        // A corner whose rounded sides overlap (a sliver under a unit wide, rounded flat)
        // is left as rounding made it: moving a point there only moves the overlap.
        if !on_curve[i] || broken(exact, rounded, i) != Some(Broken::Reversed) {
            continue;
        }
        // The points that set the sides' rounded directions, handles first, each nearest
        // to the corner first; then the corner itself.
        let mut movable: Vec<usize> = [side(rounded, i, false), side(rounded, i, true)]
            .into_iter()
            .flatten()
            .map(|(j, _)| j)
            .collect();
        movable.sort_by(|&j, &k| {
            let d = |m: usize| (exact[m] - exact[i]).hypot();
            on_curve[j].cmp(&on_curve[k]).then(d(j).total_cmp(&d(k)))
        });
        movable.push(i);
        'fix: for j in movable {
            // An on-curve point moves with its twin (the same exact point next to it: a
            // contour's start repeated at its end).
            let twin = [(j + 1) % n, (j + n - 1) % n]
                .into_iter()
                .find(|&k| k != j && on_curve[j] && on_curve[k] && exact[k] == exact[j]);
            let group = [Some(j), twin];
            let kept = rounded[j];
            let before = broken_near(rounded, j);
            for candidate in candidates(exact[j]) {
                // Never onto a point two or fewer away (nor, for a side's point, onto the
                // corner): a segment would collapse or fold back on itself.
                let neighbours = (1..=2).flat_map(|d| [(j + d) % n, (j + n - d) % n]);
                if candidate == kept
                    || neighbours
                        .chain([i])
                        .any(|k| k != j && Some(k) != twin && rounded[k] == candidate)
                {
                    continue;
                }
                for k in group.into_iter().flatten() {
                    rounded[k] = candidate;
                }
                // The corner mended, no corner near the moved point broken instead, and
                // the caller's bound kept.
                if broken(exact, rounded, i).is_none()
                    && !sides_cross(rounded, i)
                    && broken_near(rounded, j) < before
                    && group.into_iter().flatten().all(|k| allowed(rounded, k))
                {
                    moved += 1;
                    break 'fix;
                }
            }
            for k in group.into_iter().flatten() {
                rounded[k] = kept;
            }
        }
    }
    moved
}

/// The direction of a side of point `c` at the grid's scale: towards the first point of
/// that side at least [`SCALE`] from `c` (within [`NEAR`] points; else the farthest). A
/// handle a fraction of a unit long that turns back (a hook the fit left below the grid)
/// does not make a spike of a plain corner.
fn reach(points: &[Point], c: usize, forward: bool) -> Option<Vec2> {
    let n = points.len();
    let mut far: Option<Vec2> = None;
    for k in 1..=NEAR.min(n - 1) {
        let j = if forward {
            (c + k) % n
        } else {
            (c + n - k) % n
        };
        let d = points[j] - points[c];
        if d.hypot() >= SCALE {
            return Some(d);
        }
        if d.hypot() > far.map_or(1e-9, Vec2::hypot) {
            far = Some(d);
        }
    }
    far
}

/// The grid's scale, font units: a side's direction is taken this far from its corner.
const SCALE: f64 = 1.0;

/// Whether the control polygons of the two sides of corner `i` (up to [`NEAR`] points
/// each way) cross: a curve lies in its polygon's hull, so sides whose first points are
/// in order but whose polygons cross within a unit may still cross.
fn sides_cross(points: &[Point], i: usize) -> bool {
    let n = points.len();
    let reach = NEAR.min((n - 1) / 2);
    let chain = |forward: bool| -> Vec<Point> {
        (0..=reach)
            .map(|k| {
                points[if forward {
                    (i + k) % n
                } else {
                    (i + n - k) % n
                }]
            })
            .collect()
    };
    let (back, ahead) = (chain(false), chain(true));
    let cross = |o: Point, a: Point, b: Point| (a - o).cross(b - o);
    back.windows(2).any(|e| {
        ahead.windows(2).any(|f| {
            let (d1, d2) = (cross(f[0], f[1], e[0]), cross(f[0], f[1], e[1]));
            let (d3, d4) = (cross(e[0], e[1], f[0]), cross(e[0], e[1], f[1]));
            d1 * d2 < 0.0 && d3 * d4 < 0.0
        })
    })
}

/// How far (in points along the contour) a moved point's effect on corners is checked.
const NEAR: usize = 4;

/// How rounding broke a point of the contour (of its control polygon).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Broken {
    /// The exact sides leave less than a right angle apart; the rounded ones turn the
    /// other way (or run straight on).
    Reversed,
    /// The rounded sides leave in the same direction: they overlap.
    Overlapping,
    /// The rounded sides leave less than a right angle apart, the exact ones not: the
    /// polygon folds back where it did not (a segment turned back on itself).
    Folded,
}

/// Whether, and how, rounding broke point `c` (see [`Broken`]). Where the exact sides
/// leave `c` less than a right angle apart, in an order ([`reach`]), the rounded sides
/// (their first points) must turn the same way, however wide they open; elsewhere they
/// must not overlap or fold back.
fn broken(exact: &[Point], rounded: &[Point], c: usize) -> Option<Broken> {
    let (_, ra) = side(rounded, c, false)?;
    let (_, rb) = side(rounded, c, true)?;
    let turn = ra.cross(rb);
    let overlapping = turn == 0.0 && ra.dot(rb) > 0.0;
    let ea = reach(exact, c, false)?;
    let eb = reach(exact, c, true)?;
    let order = ea.cross(eb);
    let acute = ea.dot(eb) > 0.0;
    let spike = acute && order.abs() > 1e-9 * ea.hypot() * eb.hypot();
    if overlapping {
        Some(Broken::Overlapping)
    } else if spike && turn * order <= 0.0 {
        Some(Broken::Reversed)
    } else if !acute && ra.dot(rb) > 0.0 {
        Some(Broken::Folded)
    } else {
        None
    }
}

/// The first point from `i` that differs from it, walking `forward` or back around the
/// contour: its index and its direction from `i`.
fn side(points: &[Point], i: usize, forward: bool) -> Option<(usize, Vec2)> {
    let n = points.len();
    (1..n).find_map(|k| {
        let j = if forward {
            (i + k) % n
        } else {
            (i + n - k) % n
        };
        let d = points[j] - points[i];
        (d.hypot() > 1e-9).then_some((j, d))
    })
}

/// Grid points within [`MOVE`] of `p` and in the 16-bit range of the tables, nearest
/// first (ties in a fixed order).
fn candidates(p: Point) -> Vec<Point> {
    let range = f64::from(i16::MIN)..=f64::from(i16::MAX);
    let mut out = Vec::with_capacity(9);
    let (x0, y0) = (p.x.floor() - 1.0, p.y.floor() - 1.0);
    for dx in 0..4 {
        for dy in 0..4 {
            let q = Point::new(x0 + f64::from(dx), y0 + f64::from(dy));
            if (q - p).hypot() <= MOVE && range.contains(&q.x) && range.contains(&q.y) {
                out.push(q);
            }
        }
    }
    out.sort_by(|a, b| (*a - p).hypot().total_cmp(&(*b - p).hypot()));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(v: &[(f64, f64)]) -> Vec<Point> {
        v.iter().map(|&(x, y)| Point::new(x, y)).collect()
    }

    /// A generated notch (tests/it/spikes.rs, `n44`, CFF order): the curve reaches the
    /// corner with handles under a unit long, both of which round onto the corner's grid
    /// point or beside it on the wrong side of the line; no handle within a unit mends it,
    /// so the corner itself moves, 0.72 units.
    #[test]
    fn a_corner_moves_when_no_handle_can() {
        let exact = pts(&[
            (245.56508783777036, 354.4464995902567),
            (286.0049460572568, 457.7143532552541),
            (36.0, 457.7),
            (246.64536377136767, 355.33431783315086),
            (245.95302251165754, 354.7857109125441),
            (245.59234792246414, 354.470869102049),
        ]);
        let on = [true, true, true, true, false, false];
        let mut rounded: Vec<Point> = exact.iter().map(|p| p.round()).collect();
        assert_eq!(broken(&exact, &rounded, 0), Some(Broken::Reversed));
        assert_eq!(keep_spikes(&exact, &mut rounded, &on, |_, _| true), 1);
        assert_eq!(rounded[0], Point::new(245.0, 354.0));
        assert_eq!(
            &rounded[1..],
            &pts(&[
                (286.0, 458.0),
                (36.0, 458.0),
                (247.0, 355.0),
                (246.0, 355.0),
                (246.0, 354.0)
            ])[..]
        );
        assert!((rounded[0] - exact[0]).hypot() <= MOVE);
        assert_eq!(broken(&exact, &rounded, 0), None);
    }

    /// C059 Bold Italic's smiling face: the exact handle at the corner has length 0, so
    /// the side's direction is the next handle's, which rounding swings past the other side.
    #[test]
    fn a_handle_on_the_corner_is_looked_past() {
        let exact = pts(&[
            (736.96, 405.32),
            (737.84, 409.25),
            (738.0, 410.0),
            (738.0, 410.0),
            (732.04, 344.13),
            (725.34, 253.47),
            (643.45, 188.78),
        ]);
        let on = [true, false, false, true, false, false, true];
        let mut rounded: Vec<Point> = exact.iter().map(|p| p.round()).collect();
        assert_eq!(broken(&exact, &rounded, 3), Some(Broken::Reversed));
        assert_eq!(keep_spikes(&exact, &mut rounded, &on, |_, _| true), 1);
        assert_eq!(rounded[1], Point::new(737.0, 409.0));
    }

    /// A corner that opens wider than a right angle, and a spike already in order, are
    /// left alone; so is a move the caller's bound refuses.
    #[test]
    fn wide_corners_kept_spikes_and_refused_moves_stay() {
        let square = pts(&[(0.0, 0.0), (0.4, 10.0), (10.0, 10.0), (10.0, 0.0)]);
        let on = [true, false, true, true];
        let mut rounded: Vec<Point> = square.iter().map(|p| p.round()).collect();
        assert_eq!(keep_spikes(&square, &mut rounded, &on, |_, _| true), 0);
        let exact = pts(&[
            (285.0, 478.0),
            (254.0, 350.0),
            (254.6, 350.9),
            (257.3, 355.2),
        ]);
        let on = [true, true, false, true];
        let mut rounded: Vec<Point> = exact.iter().map(|p| p.round()).collect();
        assert_eq!(rounded[2], Point::new(255.0, 351.0));
        assert_eq!(keep_spikes(&exact, &mut rounded, &on, |_, _| true), 0);
        rounded[2] = Point::new(254.0, 351.0);
        assert_eq!(keep_spikes(&exact, &mut rounded, &on, |_, _| false), 0);
        assert_eq!(rounded[2], Point::new(254.0, 351.0));
    }
}
