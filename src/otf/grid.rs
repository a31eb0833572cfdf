//! The integer grid: rounding outlines and metrics for the binary tables.
//!
//! Every control point is rounded on its own (half away from zero), so a rounded Bézier is
//! within √2/2 font units of the exact one everywhere, except where a handle is moved to
//! keep a monotone cubic monotone ([`monotone`]) or off its own end point
//! ([`keep_handles`]), or a point is moved to keep a notch's sides in order ([`spike`]):
//! within one unit ([`PULLED`]). Segments that collapse to a point after rounding are
//! dropped; a contour that collapses entirely is dropped.

use kurbo::{BezPath, CubicBez, ParamCurve, PathEl, Point, Vec2};

use super::{monotone, spike, OtfError};

/// A value as a signed 16-bit table field, or an error naming it.
pub fn to_i16(value: f64, what: impl FnOnce() -> String) -> Result<i16, OtfError> {
    let rounded = value.round();
    if rounded.is_finite() && (f64::from(i16::MIN)..=f64::from(i16::MAX)).contains(&rounded) {
        Ok(rounded as i16)
    } else {
        Err(OtfError::OutOfRange {
            what: what(),
            value,
            range: "-32768..=32767",
        })
    }
}

/// A value as an unsigned 16-bit table field (advances), or an error naming it.
///
/// Advances are limited to 0..=32767 although the field is unsigned: several consumers
/// read it as signed.
pub fn to_u16(value: f64, what: impl FnOnce() -> String) -> Result<u16, OtfError> {
    let rounded = value.round();
    if rounded.is_finite() && (0.0..=f64::from(i16::MAX)).contains(&rounded) {
        Ok(rounded as u16)
    } else {
        Err(OtfError::OutOfRange {
            what: what(),
            value,
            range: "0..=32767",
        })
    }
}

/// A point on the grid, checked against the 16-bit coordinate range.
pub fn round_point(p: Point, glyph: &str) -> Result<Point, OtfError> {
    let x = to_i16(p.x, || format!("x coordinate in glyph '{glyph}'"))?;
    let y = to_i16(p.y, || format!("y coordinate in glyph '{glyph}'"))?;
    Ok(Point::new(f64::from(x), f64::from(y)))
}

/// `path` with every point on the grid and collapsed segments removed.
///
/// Each contour is `MoveTo`, segments, `ClosePath`; a final line back to the start point
/// is dropped (closing is implicit in both `glyf` and CFF).
pub fn round_path(path: &BezPath, glyph: &str) -> Result<BezPath, OtfError> {
    let mut out = BezPath::new();
    // The contour on the grid, and each of its elements as it was before rounding.
    let mut contour: Vec<PathEl> = Vec::new();
    let mut exact_contour: Vec<PathEl> = Vec::new();
    let flush = |contour: &mut Vec<PathEl>, exact: &mut Vec<PathEl>, out: &mut BezPath| {
        let start = match contour.first() {
            Some(PathEl::MoveTo(p)) => *p,
            _ => return,
        };
        if let Some(PathEl::LineTo(p)) = contour.last() {
            if *p == start {
                contour.pop();
                exact.pop();
            }
        }
        if contour.len() > 1 {
            keep_handles(contour, exact);
            monotone::keep_joins(contour, exact);
            keep_contour_spikes(contour, exact);
            for el in contour.iter() {
                out.push(*el);
            }
            out.close_path();
        }
        contour.clear();
        exact.clear();
    };
    let mut current = Point::ZERO;
    let mut exact_current = Point::ZERO;
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => {
                flush(&mut contour, &mut exact_contour, &mut out);
                current = round_point(p, glyph)?;
                contour.push(PathEl::MoveTo(current));
                exact_contour.push(*el);
            }
            PathEl::LineTo(p) => {
                let p = round_point(p, glyph)?;
                if p != current {
                    contour.push(PathEl::LineTo(p));
                    exact_contour.push(*el);
                    current = p;
                }
            }
            PathEl::QuadTo(a, p) => {
                let (a, p) = (round_point(a, glyph)?, round_point(p, glyph)?);
                if !(a == current && p == current) {
                    contour.push(PathEl::QuadTo(a, p));
                    exact_contour.push(*el);
                    current = p;
                }
            }
            PathEl::CurveTo(a, b, p) => {
                let exact = CubicBez::new(exact_current, a, b, p);
                let mut a = round_point(a, glyph)?;
                let mut b = round_point(b, glyph)?;
                let p = round_point(p, glyph)?;
                monotone::keep_cubic(&exact, current, (&mut a, &mut b), p);
                if !(a == current && b == current && p == current) {
                    contour.push(PathEl::CurveTo(a, b, p));
                    exact_contour.push(*el);
                    current = p;
                }
            }
            PathEl::ClosePath => flush(&mut contour, &mut exact_contour, &mut out),
        }
        if let Some(end) = el.end_point() {
            exact_current = end;
        }
    }
    flush(&mut contour, &mut exact_contour, &mut out);
    Ok(out)
}

/// [`spike::keep_spikes`] on one rounded contour (`MoveTo`, then segments, no closing
/// line), with `exact` its elements before rounding; a cubic with a moved point must stay
/// within [`PULLED`] of its exact cubic ([`distance_bound`]), as a pulled one does.
fn keep_contour_spikes(contour: &mut [PathEl], exact: &[PathEl]) {
    // The control points in order, each with the index of its element.
    let points = 3 * contour.len();
    let mut exact_points = Vec::with_capacity(points);
    let mut rounded = Vec::with_capacity(points);
    let mut on_curve = Vec::with_capacity(points);
    let mut element = Vec::with_capacity(points);
    // Where each element's points start in the lists.
    let mut first = Vec::with_capacity(contour.len());
    for (k, (el, ex)) in contour.iter().zip(exact).enumerate() {
        first.push(rounded.len());
        let ((points, count), (exact, _)) = (element_points(el), element_points(ex));
        for (m, (p, e)) in points.into_iter().zip(exact).take(count).enumerate() {
            rounded.push(p);
            exact_points.push(e);
            on_curve.push(m + 1 == count);
            element.push(k);
        }
    }
    let cubic = |points: &[Point], k: usize| -> Option<CubicBez> {
        let start = points[first[k].checked_sub(1).unwrap_or(points.len() - 1)];
        let i = first[k];
        matches!(contour[k], PathEl::CurveTo(..))
            .then(|| CubicBez::new(start, points[i], points[i + 1], points[i + 2]))
    };
    // The elements a moved point belongs to: its own, and the next when it ends one.
    let moved = spike::keep_spikes(&exact_points, &mut rounded, &on_curve, |now, j| {
        let k = element[j];
        let next = (on_curve[j] && k + 1 < contour.len()).then_some(k + 1);
        [Some(k), next].into_iter().flatten().all(|k| {
            match (cubic(&exact_points, k), cubic(now, k)) {
                (Some(e), Some(r)) => distance_bound(&e, &r) <= PULLED,
                _ => true,
            }
        })
    });
    if moved == 0 {
        return;
    }
    for (k, el) in contour.iter_mut().enumerate() {
        let p = &rounded[first[k]..];
        *el = match *el {
            PathEl::MoveTo(_) => PathEl::MoveTo(p[0]),
            PathEl::LineTo(_) => PathEl::LineTo(p[0]),
            PathEl::QuadTo(..) => PathEl::QuadTo(p[0], p[1]),
            PathEl::CurveTo(..) => PathEl::CurveTo(p[0], p[1], p[2]),
            PathEl::ClosePath => PathEl::ClosePath,
        };
    }
}

/// The control points of a path element, its end point last: the first `count` of the
/// array (no allocation: this runs on every contour of every CFF glyph).
fn element_points(el: &PathEl) -> ([Point; 3], usize) {
    match *el {
        PathEl::MoveTo(p) | PathEl::LineTo(p) => ([p, p, p], 1),
        PathEl::QuadTo(a, p) => ([a, p, p], 2),
        PathEl::CurveTo(a, b, p) => ([a, b, p], 3),
        PathEl::ClosePath => ([Point::ZERO; 3], 0),
    }
}

/// Keeps the handles of a rounded contour off their own end points: a handle that rounds
/// onto its end is moved to the neighbouring grid point nearest its exact direction (of
/// the eight), when that keeps at least half the corner's exact opening there (the angle
/// between the handle and the contour's other side) and the cubic within [`PULLED`] of the
/// exact one, turning back on no axis where it did not. A cubic shorter than
/// [`MIN_CHORD`], or with both handles on their ends (a line on the grid), is left, and so
/// is a handle whose end meets a segment shorter than that: a unit's move among
/// unit-long pieces can loop. `contour` is on the grid and `exact` holds its
/// elements before rounding; both start with the `MoveTo` and have no closing line.
///
/// The fit never makes a handle shorter than `fit::MIN_HANDLE`, so a zero one is
/// rounding's alone, and checkers misread it: FontForge's validation reports such a
/// contour as self-intersecting where the next segment goes on in the curve's direction,
/// or turns back along it (FreeSans `s` and STIX `g`, imported and built). The opening
/// rule keeps the handle from swinging across the other side of a narrow notch.
fn keep_handles(contour: &mut [PathEl], exact: &[PathEl]) {
    let n = contour.len();
    let Some(PathEl::MoveTo(start)) = exact.first().copied() else {
        return;
    };
    let end = |k: usize| exact[k].end_point().unwrap_or(start);
    let closed_by_curve = end(n - 1) == start;
    // The exact directions at an element's ends; the implicit closing line is element n.
    let from = |k: usize| if k == 1 { start } else { end(k - 1) };
    let leaving = |k: usize| match exact.get(k) {
        Some(&PathEl::CurveTo(a, b, p)) => [a, b, p]
            .into_iter()
            .map(|q| q - from(k))
            .find(|v| v.hypot() > 0.0),
        Some(el) => el.end_point().map(|p| p - from(k)),
        None => Some(start - end(n - 1)),
    };
    let arriving = |k: usize| match exact.get(k) {
        Some(&PathEl::CurveTo(a, b, p)) => [b, a, from(k)]
            .into_iter()
            .map(|q| p - q)
            .find(|v| v.hypot() > 0.0),
        Some(el) => el.end_point().map(|p| p - from(k)),
        None => Some(start - end(n - 1)),
    };
    let before = |k: usize| {
        if k > 1 {
            k - 1
        } else if closed_by_curve {
            n - 1
        } else {
            n
        }
    };
    let after = |k: usize| {
        if k + 1 < n {
            k + 1
        } else if closed_by_curve {
            1
        } else {
            n
        }
    };
    // Whether `moved` keeps half the opening between `handle` and the `other` side.
    let opening = |u: Vec2, v: Vec2| u.cross(v).atan2(u.dot(v));
    let keeps_opening = |handle: Vec2, moved: Vec2, other: Option<Vec2>| {
        other.is_some_and(|other| {
            let (was, now) = (opening(handle, other), opening(moved, other));
            // Past a right angle the sign of a near-straight opening means nothing.
            (was * now > 0.0 || was.abs() > std::f64::consts::FRAC_PI_2)
                && now.abs() >= was.abs() / 2.0
        })
    };
    let step = |direction: Vec2| {
        let eighth = std::f64::consts::FRAC_PI_4;
        let angle = (direction.atan2() / eighth).round() * eighth;
        Vec2::new(angle.cos().round(), angle.sin().round())
    };
    let in_range = |p: Point| {
        let range = f64::from(i16::MIN)..=f64::from(i16::MAX);
        range.contains(&p.x) && range.contains(&p.y)
    };
    for k in 1..n {
        let (PathEl::CurveTo(ea, eb, ep), PathEl::CurveTo(a, b, p)) = (exact[k], contour[k]) else {
            continue;
        };
        let Some(p0) = contour[k - 1].end_point() else {
            continue;
        };
        // Both handles on their ends make a line; a short cubic could twist with unit ones.
        if (a == p0 && b == p) || (p - p0).hypot() < MIN_CHORD {
            continue;
        }
        let exact_cubic = CubicBez::new(from(k), ea, eb, ep);
        // The rounded chord of the segment on the other side of a handle's end.
        let chord = |j: usize| {
            let (s, e) = match contour.get(j) {
                Some(el) => (contour[j - 1].end_point(), el.end_point()),
                None => (contour[n - 1].end_point(), contour[0].end_point()),
            };
            s.zip(e).map_or(0.0, |(s, e)| (e - s).hypot())
        };
        // A move must not make the cubic turn back where it did not.
        let turned = monotone::turns_back(&CubicBez::new(p0, a, b, p));
        let fine = |c: CubicBez| {
            let now = monotone::turns_back(&c);
            distance_bound(&exact_cubic, &c) <= PULLED && (0..2).all(|i| turned[i] || !now[i])
        };
        let (mut a, mut b) = (a, b);
        if a == p0 && ea != from(k) {
            let (handle, other) = (ea - from(k), arriving(before(k)).map(|v| -v));
            let moved = p0 + step(handle);
            if in_range(moved)
                && chord(before(k)) >= MIN_CHORD
                && keeps_opening(handle, moved - p0, other)
                && fine(CubicBez::new(p0, moved, b, p))
            {
                a = moved;
            }
        }
        if b == p && eb != ep {
            let (handle, other) = (eb - ep, leaving(after(k)));
            let moved = p + step(handle);
            if in_range(moved)
                && chord(after(k)) >= MIN_CHORD
                && keeps_opening(handle, moved - p, other)
                && fine(CubicBez::new(p0, a, moved, p))
            {
                b = moved;
            }
        }
        contour[k] = PathEl::CurveTo(a, b, p);
    }
}

/// Shortest cubic (chord, font units) whose handles [`keep_handles`] moves off its ends,
/// and shortest segment beside the end.
const MIN_CHORD: f64 = 4.0;

/// Farthest a cubic with a pulled or moved point may be from the exact one, font units
/// (rounding alone keeps it within √2/2).
pub const PULLED: f64 = 1.0;

/// An upper bound of the distance between two cubics at equal parameters: their difference
/// is a cubic, which lies in the hull of its control points, piece by piece.
pub(super) fn distance_bound(c: &CubicBez, d: &CubicBez) -> f64 {
    const PIECES: u32 = 8;
    let diff = CubicBez::new(
        (d.p0 - c.p0).to_point(),
        (d.p1 - c.p1).to_point(),
        (d.p2 - c.p2).to_point(),
        (d.p3 - c.p3).to_point(),
    );
    (0..PIECES)
        .map(|k| {
            let piece = diff
                .subsegment(f64::from(k) / f64::from(PIECES)..f64::from(k + 1) / f64::from(PIECES));
            [piece.p0, piece.p1, piece.p2, piece.p3]
                .iter()
                .map(|p| p.to_vec2().hypot())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::ParamCurveExtrema;

    #[test]
    fn rounding_drops_collapsed_segments_and_closing_line() {
        let mut path = BezPath::new();
        path.move_to((0.2, 0.1));
        path.line_to((0.4, -0.3)); // collapses onto the start
        path.line_to((10.6, 0.0));
        path.curve_to((10.7, 5.2), (5.0, 10.49), (0.0, 10.0));
        path.line_to((0.0, 0.0)); // closing line
        path.close_path();
        let rounded = round_path(&path, "g").unwrap();
        assert_eq!(rounded.to_svg(), "M0,0 L11,0 C11,5 5,10 0,10 Z");
    }

    /// The Medium `J`'s hook: the exact cubic rises monotonically in x to 301.33 (its
    /// derivative has no real root), with a handle at 301.52. Rounded on its own, that
    /// handle lands on 302, past the rounded end at 301, and the rounded cubic turns back
    /// at t = 0.95, an extreme FontForge flags.
    #[test]
    fn a_faint_turn_back_made_by_rounding_is_pulled_onto_the_grid_range() {
        let mut path = BezPath::new();
        path.move_to((261.27, 96.15));
        path.curve_to((301.52, 129.32), (301.25, 203.31), (301.33, 547.02));
        path.line_to((200.0, 547.0));
        path.close_path();
        let rounded = round_path(&path, "J").unwrap();
        assert_eq!(
            rounded.to_svg(),
            "M261,96 C301,129 301,203 301,547 L200,547 Z"
        );
        // Without the pull the handle is 302.
        assert_eq!(
            round_point(Point::new(301.52, 129.32), "J").unwrap().x,
            302.0
        );
    }

    /// Two units are pulled on a long handle (DejaVu Sans Bold's `h` shoulder meeting its
    /// stem, 2048 units per em), not on a short one, which would turn by 11 degrees.
    #[test]
    fn a_two_unit_pull_only_turns_a_long_handle_a_little() {
        let excursion = |c: &CubicBez| {
            c.extrema()
                .iter()
                .map(|&t| (c.eval(t).x - c.p0.x.max(c.p3.x)).max(c.p0.x.min(c.p3.x) - c.eval(t).x))
                .fold(0.0, f64::max)
        };
        let shoulder = CubicBez::new(
            (831.2, 866.1),
            (939.6, 827.2),
            (938.3, 733.4),
            (938.0, 520.2),
        );
        assert!(excursion(&shoulder) < 0.5, "{}", excursion(&shoulder));
        let short = CubicBez::new((100.0, 0.0), (98.4, 10.0), (150.0, 40.0), (200.0, 40.0));
        assert!(excursion(&short) < 0.5, "{}", excursion(&short));
        let svg = |c: CubicBez| {
            let mut path = BezPath::new();
            path.move_to(c.p0);
            path.curve_to(c.p1, c.p2, c.p3);
            path.close_path();
            round_path(&path, "h").unwrap().to_svg()
        };
        // 940 would be 2 units past the stem's 938, on a 116-unit handle: pulled.
        assert_eq!(svg(shoulder), "M831,866 C938,827 938,733 938,520 Z");
        // 98 is 2 units before 100 on a 10-unit handle: kept (the extreme stays unsplit).
        assert_eq!(svg(short), "M100,0 C98,10 150,40 200,40 Z");
    }

    /// A real extreme (half a unit or more past the end range) keeps its rounded handles,
    /// although they are only a unit outside.
    #[test]
    fn a_real_extreme_keeps_its_rounded_handles() {
        let cubic = CubicBez::new((100.0, 0.0), (101.4, 30.0), (101.4, 70.0), (100.0, 100.0));
        // 0.75 × 1.4 past x = 100, at t = 1/2.
        assert!((cubic.eval(0.5).x - 101.05).abs() < 1e-9);
        let mut path = BezPath::new();
        path.move_to(cubic.p0);
        path.curve_to(cubic.p1, cubic.p2, cubic.p3);
        path.line_to((0.0, 100.0));
        path.close_path();
        let rounded = round_path(&path, "bowl").unwrap();
        assert_eq!(rounded.to_svg(), "M100,0 C101,30 101,70 100,100 L0,100 Z");
    }

    /// FreeSans `s`: a line meets a cubic whose first handle is 0.41 units long; rounded on
    /// its own, the handle lands on the corner, and FontForge then reports the contour as
    /// self-intersecting (the line goes on in the curve's direction).
    #[test]
    fn a_handle_rounded_onto_its_end_is_kept_a_unit_off_it() {
        let mut path = BezPath::new();
        path.move_to((213.0, 228.0));
        path.line_to((291.0, 209.0));
        path.curve_to((291.394, 208.896), (327.978, 199.933), (343.263, 189.631));
        path.line_to((300.0, 100.0));
        path.close_path();
        assert_eq!(
            round_point(Point::new(291.394, 208.896), "s").unwrap(),
            Point::new(291.0, 209.0)
        );
        let rounded = round_path(&path, "s").unwrap();
        assert_eq!(
            rounded.to_svg(),
            "M213,228 L291,209 C292,209 328,200 343,190 L300,100 Z"
        );
    }

    #[test]
    fn out_of_range_coordinate_is_an_error() {
        let mut path = BezPath::new();
        path.move_to((0.0, 0.0));
        path.line_to((40000.0, 0.0));
        path.line_to((0.0, 10.0));
        path.close_path();
        let err = round_path(&path, "wide").unwrap_err();
        assert_eq!(
            err.to_string(),
            "x coordinate in glyph 'wide' is 40000, outside the OpenType range -32768..=32767"
        );
    }
}
