//! The integer grid: rounding outlines and metrics for the binary tables.
//!
//! Every control point is rounded on its own (half away from zero), so a rounded Bézier is
//! within √2/2 font units of the exact one everywhere. Segments that collapse to a point
//! after rounding are dropped; a contour that collapses entirely is dropped.

use kurbo::{BezPath, PathEl, Point};

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
                let a = round_point(a, glyph)?;
                let b = round_point(b, glyph)?;
                let p = round_point(p, glyph)?;
                if !(a == current && b == current && p == current) {
                    contour.push(PathEl::CurveTo(a, b, p));
                    current = p;
                }
            }
            PathEl::ClosePath => flush(&mut contour, &mut out),
        }
    }
    flush(&mut contour, &mut out);
    Ok(out)
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
