//! The integer grid: rounding outlines and metrics for the binary tables.
//!
//! Every control point is rounded on its own (half away from zero), so a rounded Bézier is
//! within √2/2 font units of the exact one everywhere, except where a handle is pulled
//! back onto its cubic's end range to keep a monotone cubic monotone ([`keep_monotone`]:
//! at most 3/4 of a unit more on one axis). Segments that collapse to a point after
//! rounding are dropped; a contour that collapses entirely is dropped.

use kurbo::{BezPath, CubicBez, ParamCurve, ParamCurveExtrema, PathEl, Point};

use super::OtfError;

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
    let mut contour: Vec<PathEl> = Vec::new();
    let flush = |contour: &mut Vec<PathEl>, out: &mut BezPath| {
        let start = match contour.first() {
            Some(PathEl::MoveTo(p)) => *p,
            _ => return,
        };
        if let Some(PathEl::LineTo(p)) = contour.last() {
            if *p == start {
                contour.pop();
            }
        }
        if contour.len() > 1 {
            for el in contour.iter() {
                out.push(*el);
            }
            out.close_path();
        }
        contour.clear();
    };
    let mut current = Point::ZERO;
    let mut exact_current = Point::ZERO;
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => {
                flush(&mut contour, &mut out);
                current = round_point(p, glyph)?;
                contour.push(PathEl::MoveTo(current));
            }
            PathEl::LineTo(p) => {
                let p = round_point(p, glyph)?;
                if p != current {
                    contour.push(PathEl::LineTo(p));
                    current = p;
                }
            }
            PathEl::QuadTo(a, p) => {
                let (a, p) = (round_point(a, glyph)?, round_point(p, glyph)?);
                if !(a == current && p == current) {
                    contour.push(PathEl::QuadTo(a, p));
                    current = p;
                }
            }
            PathEl::CurveTo(a, b, p) => {
                let exact = CubicBez::new(exact_current, a, b, p);
                let mut a = round_point(a, glyph)?;
                let mut b = round_point(b, glyph)?;
                let p = round_point(p, glyph)?;
                keep_monotone(&exact, current, (&mut a, &mut b), p);
                if !(a == current && b == current && p == current) {
                    contour.push(PathEl::CurveTo(a, b, p));
                    current = p;
                }
            }
            PathEl::ClosePath => flush(&mut contour, &mut out),
        }
        if let Some(end) = el.end_point() {
            exact_current = end;
        }
    }
    flush(&mut contour, &mut out);
    Ok(out)
}

/// Farthest a rounded handle is pulled back onto its cubic's end range ([`keep_monotone`]).
const PULL: f64 = 1.0;
/// An exact cubic that passes its end range by less than this (font units) on an axis is
/// taken as monotone there: the extreme is below the grid.
const FAINT: f64 = 0.5;

/// Keeps a cubic that is (within [`FAINT`]) monotone on an axis monotone on the grid.
///
/// Rounding each point on its own can leave a handle a unit past the rounded end range
/// although the exact curve stays inside it (or passes it by a hair): the rounded cubic
/// then turns back just before its end, an extreme without a point that font checkers
/// flag (FontForge's "Missing points at extrema"). Such a handle, at most [`PULL`] outside,
/// is put on the range's edge; with both handles inside the range the cubic is monotone
/// there. The handle moves at most a unit more than rounding moves it, so the curve moves
/// at most 3/4 of a unit more on that axis, and its end tangent turns by as much.
fn keep_monotone(exact: &CubicBez, p0: Point, (a, b): (&mut Point, &mut Point), p3: Point) {
    for axis in [0, 1] {
        let coord = |p: Point| if axis == 0 { p.x } else { p.y };
        let (lo, hi) = (coord(p0).min(coord(p3)), coord(p0).max(coord(p3)));
        let outside = |h: f64| h < lo - PULL || h > hi + PULL;
        let (ha, hb) = (coord(*a), coord(*b));
        let inside = |h: f64| (lo..=hi).contains(&h);
        if (inside(ha) && inside(hb)) || outside(ha) || outside(hb) {
            continue;
        }
        let (elo, ehi) = (
            coord(exact.p0).min(coord(exact.p3)),
            coord(exact.p0).max(coord(exact.p3)),
        );
        let excursion = exact
            .extrema()
            .into_iter()
            .map(|t| {
                let v = coord(exact.eval(t));
                (v - ehi).max(elo - v)
            })
            .fold(0.0, f64::max);
        if excursion >= FAINT {
            continue;
        }
        for h in [&mut *a, &mut *b] {
            let v = coord(*h).clamp(lo, hi);
            if axis == 0 {
                h.x = v;
            } else {
                h.y = v;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
