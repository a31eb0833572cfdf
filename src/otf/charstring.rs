//! Type 2 charstrings (Adobe TN #5177) for grid-rounded cubic outlines.
//!
//! Only what unhinted outlines need: an optional width, `rmoveto`, `rlineto`, `rrcurveto`
//! and `endchar`; no hints, no subroutines. Runs of lines or curves share one operator,
//! kept under the 48-argument stack limit. Closing is implicit (every `rmoveto` and the
//! `endchar` close the open contour), so the caller's paths carry no closing line.
//! Hand-written: no maintained Rust crate encodes CFF charstrings (write-fonts 0.55 reads
//! but does not write CFF).

use kurbo::{BezPath, PathEl, Point};

const RLINETO: u8 = 5;
const RRCURVETO: u8 = 8;
const ENDCHAR: u8 = 14;
const RMOVETO: u8 = 21;

/// Largest operand count a Type 2 interpreter must accept.
const MAX_STACK: usize = 48;

/// A charstring integer operand (−32768..=32767).
pub fn encode_charstring_int(v: i32, out: &mut Vec<u8>) {
    match v {
        -107..=107 => out.push((v + 139) as u8),
        108..=1131 => {
            let w = v - 108;
            out.extend([(w / 256 + 247) as u8, (w % 256) as u8]);
        }
        -1131..=-108 => {
            let w = -v - 108;
            out.extend([(w / 256 + 251) as u8, (w % 256) as u8]);
        }
        _ => {
            let w = v.clamp(i32::from(i16::MIN), i32::from(i16::MAX)) as i16;
            out.push(28);
            out.extend(w.to_be_bytes());
        }
    }
}

/// The charstring of one glyph: `width` is written as the first operand (relative to a
/// `nominalWidthX` of 0) unless it equals the `defaultWidthX` of 0.
///
/// `path` must be on the integer grid (see [`super::grid::round_path`]); deltas are taken
/// between rounded absolute points, so no error accumulates.
pub fn charstring(path: &BezPath, width: i32) -> Vec<u8> {
    let mut out = Vec::new();
    let mut pending_width = (width != 0).then_some(width);
    let mut current = Point::ZERO;
    // The operator of the run in `args`, and its operands.
    let mut run: Option<u8> = None;
    let mut args: Vec<i32> = Vec::new();
    let flush = |out: &mut Vec<u8>, run: &mut Option<u8>, args: &mut Vec<i32>| {
        if let Some(op) = run.take() {
            for &a in args.iter() {
                encode_charstring_int(a, out);
            }
            out.push(op);
        }
        args.clear();
    };
    let delta = |from: Point, to: Point| [(to.x - from.x) as i32, (to.y - from.y) as i32];
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => {
                flush(&mut out, &mut run, &mut args);
                if let Some(w) = pending_width.take() {
                    encode_charstring_int(w, &mut out);
                }
                for a in delta(current, p) {
                    encode_charstring_int(a, &mut out);
                }
                out.push(RMOVETO);
                current = p;
            }
            PathEl::LineTo(p) => {
                if run != Some(RLINETO) || args.len() + 2 > MAX_STACK {
                    flush(&mut out, &mut run, &mut args);
                    run = Some(RLINETO);
                }
                args.extend(delta(current, p));
                current = p;
            }
            PathEl::QuadTo(c, p) => {
                // Degree elevation: exact, and only reached for paths not from the fitter.
                let c1 = current + (c - current) * (2.0 / 3.0);
                let c2 = p + (c - p) * (2.0 / 3.0);
                let (c1, c2) = (
                    Point::new(c1.x.round(), c1.y.round()),
                    Point::new(c2.x.round(), c2.y.round()),
                );
                curve(&mut out, &mut run, &mut args, current, c1, c2, p, flush);
                current = p;
            }
            PathEl::CurveTo(c1, c2, p) => {
                curve(&mut out, &mut run, &mut args, current, c1, c2, p, flush);
                current = p;
            }
            PathEl::ClosePath => {}
        }
    }
    flush(&mut out, &mut run, &mut args);
    if let Some(w) = pending_width {
        encode_charstring_int(w, &mut out);
    }
    out.push(ENDCHAR);
    out
}

#[allow(clippy::too_many_arguments)]
fn curve(
    out: &mut Vec<u8>,
    run: &mut Option<u8>,
    args: &mut Vec<i32>,
    from: Point,
    c1: Point,
    c2: Point,
    to: Point,
    flush: impl Fn(&mut Vec<u8>, &mut Option<u8>, &mut Vec<i32>),
) {
    if *run != Some(RRCURVETO) || args.len() + 6 > MAX_STACK {
        flush(out, run, args);
        *run = Some(RRCURVETO);
    }
    for (a, b) in [(from, c1), (c1, c2), (c2, to)] {
        args.push((b.x - a.x) as i32);
        args.push((b.y - a.y) as i32);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn int_bytes(v: i32) -> Vec<u8> {
        let mut out = Vec::new();
        encode_charstring_int(v, &mut out);
        out
    }

    #[test]
    fn integer_encodings_from_tn5177() {
        assert_eq!(int_bytes(0), [0x8b]);
        assert_eq!(int_bytes(107), [0xf6]);
        assert_eq!(int_bytes(-107), [0x20]);
        assert_eq!(int_bytes(108), [0xf7, 0x00]);
        assert_eq!(int_bytes(1000), [0xfa, 0x7c]);
        assert_eq!(int_bytes(1131), [0xfa, 0xff]);
        assert_eq!(int_bytes(-1000), [0xfe, 0x7c]);
        assert_eq!(int_bytes(-1131), [0xfe, 0xff]);
        assert_eq!(int_bytes(1132), [28, 0x04, 0x6c]);
        assert_eq!(int_bytes(-10000), [28, 0xd8, 0xf0]);
    }

    #[test]
    fn square_with_width() {
        let mut path = BezPath::new();
        path.move_to((10.0, 0.0));
        path.line_to((110.0, 0.0));
        path.line_to((110.0, 100.0));
        path.curve_to((80.0, 120.0), (40.0, 120.0), (10.0, 100.0));
        path.close_path();
        let cs = charstring(&path, 500);
        assert_eq!(
            cs,
            [
                0xf8, 0x88, // 500 (width)
                0x95, 0x8b, RMOVETO, // 10 0
                0xef, 0x8b, 0x8b, 0xef, RLINETO, // 100 0 0 100
                0x6d, 0x9f, 0x63, 0x8b, 0x6d, 0x77, RRCURVETO, // -30 20 -40 0 -30 -20
                ENDCHAR
            ]
        );
    }

    #[test]
    fn quadratic_segments_are_degree_elevated() {
        let mut path = BezPath::new();
        path.move_to((0.0, 0.0));
        path.quad_to((30.0, 60.0), (90.0, 0.0));
        path.close_path();
        // Controls (20, 40) and (50, 40): deltas 20 40, 30 0, 40 -40.
        assert_eq!(
            charstring(&path, 0),
            [0x8b, 0x8b, RMOVETO, 0x9f, 0xb3, 0xa9, 0x8b, 0xb3, 0x63, RRCURVETO, ENDCHAR]
        );
    }

    #[test]
    fn empty_glyph_is_width_and_endchar() {
        assert_eq!(charstring(&BezPath::new(), 260), [0xf7, 0x98, ENDCHAR]);
        assert_eq!(charstring(&BezPath::new(), 0), [ENDCHAR]);
    }

    #[test]
    fn long_runs_respect_the_stack_limit() {
        let mut path = BezPath::new();
        path.move_to((0.0, 0.0));
        for i in 1..=30 {
            path.line_to((f64::from(i), f64::from(i % 2)));
        }
        path.close_path();
        let cs = charstring(&path, 0);
        // 24 pairs (48 operands) in the first rlineto, 6 in the second.
        let ops: Vec<usize> = cs
            .iter()
            .enumerate()
            .filter(|(_, &b)| b == RLINETO)
            .map(|(i, _)| i)
            .collect();
        assert_eq!(ops.len(), 2);
        assert_eq!(ops[0], 3 + 48);
        assert_eq!(ops[1], ops[0] + 1 + 12);
    }
}
