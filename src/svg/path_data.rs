//! SVG path data from a BezPath: absolute `M L C Z` only, compact numbers.
//!
//! A line back to the subpath's start right before `Z` is left out (`Z` draws it), so
//! consumers do not see a doubled point. Quadratic segments (the fitter never makes them) are written as the equal cubic, so
//! consumers that accept only `M L C Z` (SVG fonts in FontForge, svg2ttf) read every path.

use kurbo::{Affine, BezPath, PathEl, Point};

use super::xml::push_num;

/// Path data of `path` after `transform` (e.g. a y flip), like `M20 0L280 700C…Z`.
pub fn path_data(path: &BezPath, transform: Affine) -> String {
    let elements = path.elements();
    // A cubic takes about 36 bytes, a line 12.
    let mut d = String::with_capacity(elements.len() * 32);
    let mut current = Point::ORIGIN;
    let mut start = Point::ORIGIN;
    let pt = |d: &mut String, p: Point| {
        let p = transform * p;
        if !d.is_empty() && !d.ends_with(char::is_alphabetic) {
            d.push(' ');
        }
        push_num(d, p.x);
        d.push(' ');
        push_num(d, p.y);
    };
    for (i, el) in elements.iter().enumerate() {
        match *el {
            PathEl::MoveTo(p) => {
                d.push('M');
                pt(&mut d, p);
                current = p;
                start = p;
            }
            PathEl::LineTo(p)
                if p == start && matches!(elements.get(i + 1), Some(PathEl::ClosePath)) =>
            {
                current = p;
            }
            PathEl::LineTo(p) => {
                d.push('L');
                pt(&mut d, p);
                current = p;
            }
            PathEl::QuadTo(q, p) => {
                let a = current + (q - current) * (2.0 / 3.0);
                let b = p + (q - p) * (2.0 / 3.0);
                d.push('C');
                pt(&mut d, a);
                pt(&mut d, b);
                pt(&mut d, p);
                current = p;
            }
            PathEl::CurveTo(a, b, p) => {
                d.push('C');
                pt(&mut d, a);
                pt(&mut d, b);
                pt(&mut d, p);
                current = p;
            }
            PathEl::ClosePath => d.push('Z'),
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commands_and_numbers() {
        let mut p = BezPath::new();
        p.move_to((20.0, 0.0));
        p.line_to((280.004, 700.0));
        p.curve_to((1.0, -2.5), (3.0, 4.0), (20.0, 0.0));
        p.line_to((20.0, 0.0));
        p.close_path();
        p.move_to((5.0, 5.0));
        p.line_to((6.0, 5.0));
        p.line_to((5.0, 6.0));
        p.line_to((5.0, 5.0));
        p.close_path();
        p.move_to((0.0, 0.0));
        p.quad_to((30.0, 30.0), (60.0, 0.0));
        p.close_path();
        assert_eq!(
            path_data(&p, Affine::IDENTITY),
            "M20 0L280 700C1 -2.5 3 4 20 0ZM5 5L6 5L5 6ZM0 0C20 20 40 20 60 0Z"
        );
        assert_eq!(
            path_data(&p, Affine::FLIP_Y),
            "M20 0L280 -700C1 2.5 3 -4 20 0ZM5 -5L6 -5L5 -6ZM0 0C20 -20 40 -20 60 0Z"
        );
    }
}
