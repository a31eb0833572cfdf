//! Type 2 charstrings (Adobe TN #5177) for grid-rounded cubic outlines.
//!
//! Only what unhinted outlines need: an optional width, `rmoveto`, `rlineto`, `rrcurveto`
//! and `endchar`; no hints, no subroutines. Runs of lines or curves share one operator,
//! kept under the 48-argument stack limit. Closing is implicit (every `rmoveto` and the
//! `endchar` close the open contour), so the caller's paths carry no closing line.
//! Hand-written: no maintained Rust crate encodes CFF charstrings (write-fonts 0.55 reads
//! but does not write CFF).

use kurbo::{BezPath, PathEl, Point, Shape};
use rayon::prelude::*;

use super::grid::round_path;
use super::tables::GridBox;
use super::{OtGlyph, OtfError};
use crate::reuse::{Key, KeyBuilder, Reuse};

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

/// One glyph for `CFF `: its charstring without the width, and its tight box on the grid.
#[derive(Clone, Debug, PartialEq)]
pub struct CffGlyph {
    /// The box of the curves' extrema (what CFF consumers compute), `None` when empty.
    pub bbox: Option<GridBox>,
    /// [`charstring`] with a width of 0: a width is a leading operand ([`Self::charstring`]).
    pub body: Vec<u8>,
}

impl CffGlyph {
    /// The glyph of `path`, which must be on the integer grid.
    pub fn new(path: &BezPath) -> Self {
        let bbox = (!path.elements().is_empty()).then(|| {
            let r = path.bounding_box();
            (
                r.x0.floor() as i16,
                r.y0.floor() as i16,
                r.x1.ceil() as i16,
                r.y1.ceil() as i16,
            )
        });
        CffGlyph {
            bbox,
            body: charstring(path, 0),
        }
    }

    /// The whole charstring with `width` (see [`charstring`]).
    pub fn charstring(&self, width: i32) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.body.len() + 5);
        // The width is the first operand of the first stack-clearing operator, which in
        // `body` is the first `rmoveto` or the `endchar`: it goes in front.
        if width != 0 {
            encode_charstring_int(width, &mut out);
        }
        out.extend_from_slice(&self.body);
        out
    }
}

/// Every glyph rounded to the grid and as a [`CffGlyph`], on every core (the first error in
/// glyph order reported). Each glyph comes from the last build's record when it was made
/// under the same key ([`Reuse::data_or_make`]); `outlines[i]`, when there is one, must
/// determine glyph `i`'s path (see [`super::truetype::glyphs_reusing`]).
pub fn glyphs_reusing(
    glyphs: &[OtGlyph],
    reuse: &Reuse,
    outlines: &[Option<Key>],
) -> Result<Vec<CffGlyph>, OtfError> {
    let each: Vec<Result<CffGlyph, OtfError>> = glyphs
        .par_iter()
        .enumerate()
        .map(|(i, g)| {
            let make = || Ok(CffGlyph::new(&round_path(&g.path(), &g.model_name)?));
            match outlines.get(i).copied().flatten() {
                Some(outline) => {
                    let key = KeyBuilder::new("cff glyph").key(&outline).finish();
                    reuse.data_or_make(key, encode, decode, make)
                }
                None => make(),
            }
        })
        .collect();
    each.into_iter().collect()
}

/// The record's bytes of a [`CffGlyph`]: 0 for no box, or 1 and the box as four big-endian
/// `i16`; then the body.
fn encode(glyph: &CffGlyph) -> Vec<u8> {
    let mut out = Vec::with_capacity(glyph.body.len() + 9);
    match glyph.bbox {
        None => out.push(0),
        Some((x0, y0, x1, y1)) => {
            out.push(1);
            for v in [x0, y0, x1, y1] {
                out.extend(v.to_be_bytes());
            }
        }
    }
    out.extend_from_slice(&glyph.body);
    out
}

/// [`encode`]'s inverse; `None` unless the bytes are a box and a body that ends the glyph.
fn decode(bytes: &[u8]) -> Option<CffGlyph> {
    let (bbox, body) = match *bytes.first()? {
        0 => (None, &bytes[1..]),
        1 => {
            let v = |i: usize| -> Option<i16> {
                Some(i16::from_be_bytes(
                    bytes.get(1 + 2 * i..3 + 2 * i)?.try_into().ok()?,
                ))
            };
            let bbox = (v(0)?, v(1)?, v(2)?, v(3)?);
            (Some(bbox), bytes.get(9..)?)
        }
        _ => return None,
    };
    (body.last() == Some(&ENDCHAR)).then(|| CffGlyph {
        bbox,
        body: body.to_vec(),
    })
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
    fn a_glyph_is_its_body_after_the_width_and_its_record_bytes_round_trip() {
        let mut path = BezPath::new();
        path.move_to((10.0, 0.0));
        path.line_to((110.0, 0.0));
        path.curve_to((110.0, 200.0), (10.0, 200.0), (10.0, 100.0));
        path.close_path();
        for p in [path, BezPath::new()] {
            let glyph = CffGlyph::new(&p);
            for width in [0, 500, -20, 2000] {
                assert_eq!(glyph.charstring(width), charstring(&p, width));
            }
            assert_eq!(decode(&encode(&glyph)), Some(glyph.clone()));
            let bytes = encode(&glyph);
            // Truncated, or a box flag that is neither 0 nor 1: refused.
            assert_eq!(decode(&bytes[..bytes.len() - 1]), None);
            let mut flag = bytes.clone();
            flag[0] = 2;
            assert_eq!(decode(&flag), None);
        }
        // The tight box: the curve peaks at y = 175, its controls at 200.
        let mut arc = BezPath::new();
        arc.move_to((0.0, 100.0));
        arc.curve_to((0.0, 200.0), (100.0, 200.0), (100.0, 100.0));
        arc.close_path();
        assert_eq!(CffGlyph::new(&arc).bbox, Some((0, 100, 100, 175)));
        assert_eq!(decode(&[0]), None);
        assert_eq!(decode(&[1, 0, 0, 0, 0, 0, 0, 0, ENDCHAR]), None);
        assert_eq!(
            decode(&[1, 0, 0, 0, 0, 0, 1, 0, 1, ENDCHAR]),
            Some(CffGlyph {
                bbox: Some((0, 0, 1, 1)),
                body: vec![ENDCHAR]
            })
        );
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
