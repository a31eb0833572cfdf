//! Interpolation of untouched points (IUP): which of a tuple's point deltas `gvar` may omit
//! because every consumer infers them exactly.
//!
//! write-fonts' optimizer (the fontTools algorithm fontmake and fontc use) picks the points
//! to encode. fontmake lets inferred deltas be off by up to 0.5 units; xglyph's instances
//! are meant to be exact, so the optimizer runs at [`OPTIMIZER_TOLERANCE`] and its choice is
//! then checked in exact integer arithmetic ([`exactly_inferred`]): an omitted delta must be
//! the one the spec's inference gives, and it must come out exactly in any evaluation order
//! of binary floating point or 16.16 fixed point (fontTools, FreeType, skrifa). Where it
//! would not, the point is encoded again. So an instance blends the same deltas with and
//! without IUP, and its coordinates are the same.
//!
//! The check is hand-written (write-fonts has no exact mode): about 60 lines, tested below.

use write_fonts::tables::gvar::iup::iup_delta_optimize;
use write_fonts::tables::gvar::GlyphDelta;

/// The optimizer's tolerance, font units: far below the smallest nonzero gap between an
/// inferred rational delta and an integer (1 / the largest coordinate span), so it only
/// absorbs floating-point noise; [`exactly_inferred`] decides.
const OPTIMIZER_TOLERANCE: f64 = 1e-6;

/// Largest power-of-two denominator of an interpolation slope we accept: its products with
/// coordinates stay exact in f32 and in 16.16 fixed point.
const MAX_SLOPE_DENOMINATOR: i64 = 1 << 10;

/// One tuple's deltas with `required` set where a consumer cannot infer them exactly.
///
/// `coords` are the default glyph's points, `contour_ends` the index of each contour's
/// last point; both without the 4 phantom points, which `deltas` (and the result) end with.
/// Each phantom point is inferred on its own (as one-point contours).
pub fn optimize(
    deltas: &[(i16, i16)],
    coords: &[(i16, i16)],
    contour_ends: &[usize],
) -> Vec<GlyphDelta> {
    let mut points: Vec<kurbo::Point> = coords
        .iter()
        .map(|&(x, y)| kurbo::Point::new(f64::from(x), f64::from(y)))
        .collect();
    points.extend([kurbo::Point::ZERO; 4]);
    let vectors = deltas
        .iter()
        .map(|&(x, y)| kurbo::Vec2::new(f64::from(x), f64::from(y)))
        .collect();
    let mut out = match iup_delta_optimize(vectors, points, OPTIMIZER_TOLERANCE, contour_ends) {
        Ok(d) => d,
        // Inconsistent lengths (not made here, see the caller): encode everything.
        Err(_) => deltas
            .iter()
            .map(|&(x, y)| GlyphDelta::required(x, y))
            .collect(),
    };
    let n = deltas.len();
    let mut all_ends = contour_ends.to_vec();
    all_ends.extend(n.saturating_sub(4)..n);
    let mut all_coords = coords.to_vec();
    all_coords.resize(n, (0, 0));
    require_exact(&mut out, &all_coords, &all_ends);
    out
}

/// Sets `required` on omitted deltas until every omitted one is [`exactly_inferred`] from the
/// encoded ones around it. Encoding a point only moves its neighbours' references closer,
/// so this ends (at worst with every point encoded).
fn require_exact(deltas: &mut [GlyphDelta], coords: &[(i16, i16)], contour_ends: &[usize]) {
    let mut start = 0;
    for &end in contour_ends {
        if end < start || end >= deltas.len() {
            continue;
        }
        let range = start..end + 1;
        start = end + 1;
        loop {
            let contour = &deltas[range.clone()];
            let encoded: Vec<usize> = (0..contour.len())
                .filter(|&i| contour[i].required)
                .collect();
            let bad = (0..contour.len()).find(|&i| {
                let d = contour[i];
                if d.required {
                    return false;
                }
                match encoded.as_slice() {
                    // No reference: the consumer infers zero.
                    [] => d.x != 0 || d.y != 0,
                    // One reference: every point moves with it.
                    [only] => (d.x, d.y) != (contour[*only].x, contour[*only].y),
                    _ => {
                        let next = *encoded.iter().find(|&&e| e > i).unwrap_or(&encoded[0]);
                        let prev = *encoded
                            .iter()
                            .rev()
                            .find(|&&e| e < i)
                            .unwrap_or(&encoded[encoded.len() - 1]);
                        let (c, p, q) = (
                            coords[range.start + i],
                            coords[range.start + prev],
                            coords[range.start + next],
                        );
                        let (dp, dq) = (contour[prev], contour[next]);
                        !(exactly_inferred(c.0, p.0, q.0, d.x, dp.x, dq.x)
                            && exactly_inferred(c.1, p.1, q.1, d.y, dp.y, dq.y))
                    }
                }
            });
            match bad {
                Some(i) => deltas[range.start + i].required = true,
                None => break,
            }
        }
    }
}

/// Whether the spec's inference of one axis gives `d` exactly for a point at `c` between
/// references at `c1`, `c2` with deltas `d1`, `d2`, whatever the arithmetic.
///
/// Outside the references' span the nearer reference's delta is copied; inside it the delta
/// is interpolated linearly, which we accept only when the result is the integer `d` and the
/// slope has a small power-of-two denominator. References at the same coordinate are
/// accepted only with equal deltas (implementations differ there otherwise).
fn exactly_inferred(c: i16, c1: i16, c2: i16, d: i16, d1: i16, d2: i16) -> bool {
    let [c, c1, c2, d, d1, d2] = [c, c1, c2, d, d1, d2].map(i64::from);
    if c1 == c2 {
        return d1 == d2 && d == d1;
    }
    let ((lo, dlo), (hi, dhi)) = if c1 < c2 {
        ((c1, d1), (c2, d2))
    } else {
        ((c2, d2), (c1, d1))
    };
    if c <= lo {
        return d == dlo;
    }
    if c >= hi {
        return d == dhi;
    }
    if dlo == dhi {
        return d == dlo;
    }
    let (rise, run) = (dhi - dlo, hi - lo);
    let denominator = run / gcd(rise.abs(), run);
    (c - lo) * rise == (d - dlo) * run
        && denominator.count_ones() == 1
        && denominator <= MAX_SLOPE_DENOMINATOR
}

fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outside_the_span_copies_the_nearer_reference() {
        assert!(exactly_inferred(-5, 0, 10, 3, 3, 7));
        assert!(exactly_inferred(15, 0, 10, 7, 3, 7));
        assert!(!exactly_inferred(15, 0, 10, 3, 3, 7));
    }

    #[test]
    fn inside_the_span_needs_an_exact_dyadic_slope() {
        // Slope 4/8 = 1/2 at 4 units in: 3 + 2 = 5.
        assert!(exactly_inferred(4, 0, 8, 5, 3, 7));
        // Slope 3/9 = 1/3 at 3 units in: 1 exactly in rationals, not in every float order.
        assert!(!exactly_inferred(3, 0, 9, 1, 0, 3));
        // 4/10 at 5 units in is 2, but 0.4 is not dyadic.
        assert!(!exactly_inferred(5, 0, 10, 2, 0, 4));
        // Not the interpolated value at all.
        assert!(!exactly_inferred(4, 0, 8, 6, 3, 7));
    }

    #[test]
    fn references_at_one_coordinate_need_equal_deltas() {
        assert!(exactly_inferred(5, 5, 5, 2, 2, 2));
        assert!(!exactly_inferred(5, 5, 5, 0, 2, 4));
        assert!(!exactly_inferred(4, 5, 5, 2, 2, 4));
    }

    #[test]
    fn a_translated_contour_needs_one_encoded_point() {
        // A square moved by (10, -4): one point and the zero phantoms suffice.
        let coords = [(0, 0), (100, 0), (100, 100), (0, 100)];
        let mut deltas = vec![(10, -4); 4];
        deltas.extend([(0, 0), (30, 0), (0, 0), (0, 0)]);
        let out = optimize(&deltas, &coords, &[3]);
        assert_eq!(out.iter().take(4).filter(|d| d.required).count(), 1);
        let phantoms: Vec<bool> = out[4..].iter().map(|d| d.required).collect();
        assert_eq!(phantoms, [false, true, false, false]);
        assert!(out.iter().zip(&deltas).all(|(o, d)| (o.x, o.y) == *d));
    }

    #[test]
    fn inexact_inference_is_encoded() {
        // The middle point's delta 1 is (0 + 3) / 3 exactly in rationals, a non-dyadic slope:
        // encoded, though fontTools' optimizer at 0.5 units would drop it.
        let coords = [(0, 0), (3, 0), (9, 0), (9, 10)];
        let mut deltas = vec![(0, 0), (1, 0), (3, 0), (3, 0)];
        deltas.extend([(0, 0); 4]);
        let out = optimize(&deltas, &coords, &[3]);
        assert!(out[1].required, "{out:?}");
    }
}
