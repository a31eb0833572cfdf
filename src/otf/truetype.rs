//! TrueType glyphs: quadratic contours on the integer grid, then `glyf`/`loca`.

use rayon::prelude::*;
use read_fonts::tables::glyf::CurvePoint;
use write_fonts::tables::glyf::{Bbox, Contour, GlyfLocaBuilder, Glyph, SimpleGlyph};

use super::quadratic::truetype_contours;
use super::{grid, OtGlyph, OtfError};
use crate::reuse::{Key, KeyBuilder, Reuse};

/// One glyph ready for `glyf`: no outline (`None`) or a simple glyph with its box.
pub struct TtGlyph {
    pub glyph: Option<SimpleGlyph>,
}

impl TtGlyph {
    /// Control-point bounding box (what `glyf` stores), `None` for an empty glyph.
    pub fn bbox(&self) -> Option<Bbox> {
        self.glyph.as_ref().map(|g| g.bbox)
    }

    pub fn num_points(&self) -> usize {
        self.glyph
            .as_ref()
            .map_or(0, |g| g.contours.iter().map(|c| c.len()).sum())
    }

    pub fn num_contours(&self) -> usize {
        self.glyph.as_ref().map_or(0, |g| g.contours.len())
    }
}

/// Every glyph as TrueType, quadratics within `accuracy` before grid rounding; on every
/// core (rayon), the first error in glyph order reported, so the result does not depend on
/// the thread count. Each glyph's contours come from the last build's record when it made
/// them under the same key ([`Reuse::data_or_make`]); `outlines[i]`, when there is one,
/// must determine glyph `i`'s path (e.g. [`crate::reuse::outline_key`]).
pub fn glyphs_reusing(
    glyphs: &[OtGlyph],
    accuracy: f64,
    reuse: &Reuse,
    outlines: &[Option<Key>],
) -> Result<Vec<TtGlyph>, OtfError> {
    let each: Vec<Result<TtGlyph, OtfError>> = glyphs
        .par_iter()
        .enumerate()
        .map(|(i, g)| {
            let make = || on_grid(g, accuracy);
            let contours = match outlines.get(i).copied().flatten() {
                Some(outline) => {
                    let key = KeyBuilder::new("truetype contours")
                        .f64(accuracy)
                        .key(&outline)
                        .finish();
                    reuse.data_or_make(key, encode, decode, make)?
                }
                None => make()?,
            };
            let contours: Vec<Contour> = contours.into_iter().map(Contour::from).collect();
            if contours.is_empty() {
                return Ok(TtGlyph { glyph: None });
            }
            // The source checks bound control points and contours; fitting can add points.
            let points: usize = contours.iter().map(|c: &Contour| c.len()).sum();
            if points > usize::from(u16::MAX) || contours.len() >= i16::MAX as usize {
                return Err(OtfError::OutOfRange {
                    what: format!(
                        "glyph '{}' as TrueType ({} contours): its point count",
                        g.model_name,
                        contours.len()
                    ),
                    value: points as f64,
                    range: "0..=65535 points, at most 32766 contours",
                });
            }
            // Resolved components may overlap each other: set OVERLAP_SIMPLE so rasterizers
            // that need the hint (macOS) fill the overlap without dropouts.
            let mut glyph = SimpleGlyph {
                contours,
                overlaps: g.from_components,
                ..Default::default()
            };
            glyph.recompute_bounding_box();
            Ok(TtGlyph { glyph: Some(glyph) })
        })
        .collect();
    each.into_iter().collect()
}

/// The contours of `g` as TrueType: quadratics within `accuracy`, points on the grid,
/// zero-length segments and contours of fewer than 3 distinct points dropped.
fn on_grid(g: &OtGlyph, accuracy: f64) -> Result<Vec<Vec<CurvePoint>>, OtfError> {
    let mut contours = Vec::new();
    for contour in truetype_contours(&g.path, accuracy) {
        let mut points: Vec<CurvePoint> = Vec::with_capacity(contour.len());
        for p in contour {
            let q = grid::round_point(p.point, &g.model_name)?;
            let point = CurvePoint::new(q.x as i16, q.y as i16, p.on_curve);
            // A point that rounds onto its on-curve predecessor adds nothing.
            if let Some(prev) = points.last() {
                if prev.on_curve && point.on_curve && (prev.x, prev.y) == (q.x as i16, q.y as i16) {
                    continue;
                }
            }
            points.push(point);
        }
        drop_degenerate(&mut points);
        let distinct = points
            .iter()
            .any(|p| (p.x, p.y) != (points[0].x, points[0].y));
        if points.len() >= 3 && distinct {
            contours.push(points);
        }
    }
    Ok(contours)
}

/// The record's bytes of [`on_grid`]'s contours (about 2 bytes a point, where a plain
/// list would take 5: a CJK font's record holds 2 million points). Per contour its point
/// count, then per point its step from the last point (the first from the origin) as
/// LEB128 numbers: `zigzag(dx) * 2 + on_curve`, then `zigzag(dy)`.
fn encode(contours: &Vec<Vec<CurvePoint>>) -> Vec<u8> {
    let points: usize = contours.iter().map(Vec::len).sum();
    let mut out = Vec::with_capacity(2 * contours.len() + 3 * points);
    let (mut x, mut y) = (0i32, 0i32);
    for contour in contours {
        put_varint(&mut out, contour.len() as u64);
        for p in contour {
            let (dx, dy) = (i32::from(p.x) - x, i32::from(p.y) - y);
            (x, y) = (i32::from(p.x), i32::from(p.y));
            put_varint(&mut out, zigzag(dx) << 1 | u64::from(p.on_curve));
            put_varint(&mut out, zigzag(dy));
        }
    }
    out
}

/// [`encode`]'s contours back, or `None` when `bytes` are not such a list (each contour of
/// at least 3 points, every coordinate an `i16`, every byte used).
fn decode(mut bytes: &[u8]) -> Option<Vec<Vec<CurvePoint>>> {
    let mut contours = Vec::new();
    let (mut x, mut y) = (0i64, 0i64);
    while !bytes.is_empty() {
        let n = take_varint(&mut bytes)?;
        // Each point takes at least 2 bytes.
        if n < 3 || n > bytes.len() as u64 / 2 {
            return None;
        }
        let mut contour = Vec::with_capacity(n as usize);
        for _ in 0..n {
            let first = take_varint(&mut bytes)?;
            x += unzigzag(first >> 1);
            y += unzigzag(take_varint(&mut bytes)?);
            let (px, py) = (i16::try_from(x).ok()?, i16::try_from(y).ok()?);
            contour.push(CurvePoint::new(px, py, first & 1 == 1));
        }
        contours.push(contour);
    }
    Some(contours)
}

fn zigzag(v: i32) -> u64 {
    u64::from(((v << 1) ^ (v >> 31)) as u32)
}

fn unzigzag(v: u64) -> i64 {
    (v >> 1) as i64 ^ -((v & 1) as i64)
}

/// Appends `v` as LEB128 (7 bits a byte, low first).
fn put_varint(out: &mut Vec<u8>, mut v: u64) {
    while v >= 0x80 {
        out.push((v as u8) | 0x80);
        v >>= 7;
    }
    out.push(v as u8);
}

/// Reads a LEB128 number of at most 5 bytes (enough for [`encode`]'s numbers).
fn take_varint(bytes: &mut &[u8]) -> Option<u64> {
    let mut v = 0u64;
    for shift in (0..35).step_by(7) {
        let (&b, rest) = bytes.split_first()?;
        *bytes = rest;
        v |= u64::from(b & 0x7f) << shift;
        if b < 0x80 {
            return Some(v);
        }
    }
    None
}

/// Removes, around the closed contour, points that make zero-length segments on the grid
/// without changing its shape: an on-curve point equal to the on-curve point before it,
/// an off-curve point between two on-curve points that equals one of them (the quadratic
/// is then the straight line between them), and an off-curve point equal to both its
/// neighbours (every segment it touches, implied on-curve points included, is that one
/// point). Other repeated points are kept: dropping an off-curve point next to a
/// different off-curve one would move the implied on-curve point between them.
fn drop_degenerate(points: &mut Vec<CurvePoint>) {
    let same = |a: &CurvePoint, b: &CurvePoint| (a.x, a.y) == (b.x, b.y);
    let mut i = 0;
    while points.len() > 1 && i < points.len() {
        let n = points.len();
        let (prev, point, next) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
        let redundant = if point.on_curve {
            prev.on_curve && same(&prev, &point)
        } else {
            (prev.on_curve && next.on_curve && (same(&prev, &point) || same(&point, &next)))
                || (same(&prev, &point) && same(&point, &next))
        };
        if redundant {
            points.remove(i);
            // The previous point may now be redundant against its new neighbour.
            i = i.saturating_sub(1);
        } else {
            i += 1;
        }
    }
}

/// The `glyf` and `loca` tables, and `head.indexToLocFormat` (0 short, 1 long).
pub fn glyf_loca(
    glyphs: &[TtGlyph],
) -> Result<
    (
        write_fonts::tables::glyf::Glyf,
        write_fonts::tables::loca::Loca,
        i16,
    ),
    OtfError,
> {
    let mut builder = GlyfLocaBuilder::new();
    for g in glyphs {
        let result = match &g.glyph {
            Some(simple) => builder.add_glyph(simple),
            None => builder.add_glyph(&Glyph::Empty),
        };
        result.map_err(|e| OtfError::Table(format!("glyf: {e}")))?;
    }
    let (glyf, loca, format) = builder.build();
    Ok((glyf, loca, format as i16))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recorded_contours_read_back_exactly_and_bad_bytes_are_refused() {
        let pt = |x, y, on| CurvePoint::new(x, y, on);
        let contours = vec![
            vec![
                pt(0, 0, true),
                pt(-32768, 32767, false),
                pt(32767, -32768, true),
            ],
            vec![
                pt(5, 5, false),
                pt(6, 4, false),
                pt(-1, 700, true),
                pt(5, 5, true),
            ],
        ];
        let bytes = encode(&contours);
        assert_eq!(decode(&bytes), Some(contours.clone()));
        // Small steps take one byte per number: 2 per point plus the counts.
        let small = vec![vec![pt(10, 10, true), pt(40, 10, true), pt(40, 40, false)]];
        assert_eq!(encode(&small).len(), 1 + 3 * 2);
        // Truncated, extended, too few points, a coordinate off the i16 range: refused.
        assert_eq!(decode(&bytes[..bytes.len() - 1]), None);
        assert_eq!(decode(&[bytes.as_slice(), &[0]].concat()), None);
        assert_eq!(
            decode(&encode(&[vec![pt(1, 1, true), pt(2, 2, true)]].to_vec())),
            None
        );
        let mut far = encode(&contours);
        far.extend_from_slice(&encode(&vec![vec![pt(32767, 0, true); 3]]));
        assert_eq!(decode(&far), None);
    }

    #[test]
    fn zero_length_segments_are_dropped_shape_kept() {
        let pt = |x, y, on| CurvePoint::new(x, y, on);
        // On A, off A, on A (a quadratic collapsed onto A), on B, off C, off D, on A.
        let mut points = vec![
            pt(0, 0, true),
            pt(0, 0, false),
            pt(0, 0, true),
            pt(100, 0, true),
            pt(100, 100, false),
            pt(0, 100, false),
            pt(0, 0, true),
        ];
        drop_degenerate(&mut points);
        assert_eq!(
            points,
            [
                pt(100, 0, true),
                pt(100, 100, false),
                pt(0, 100, false),
                pt(0, 0, true),
            ]
        );
        // An off-curve point equal to its on-curve neighbour but followed by another
        // off-curve point is kept: it places the implied on-curve point.
        let mut kept = vec![
            pt(0, 0, true),
            pt(0, 0, false),
            pt(50, 50, false),
            pt(90, 0, true),
        ];
        drop_degenerate(&mut kept);
        assert_eq!(kept.len(), 4);
        // A run of off-curve points collapsed onto its on-curve ends (seen in 'P').
        let mut run = vec![
            pt(162, 270, true),
            pt(162, 270, false),
            pt(162, 270, false),
            pt(162, 270, true),
            pt(162, 0, true),
            pt(280, 270, false),
        ];
        drop_degenerate(&mut run);
        assert_eq!(
            run,
            [pt(162, 270, true), pt(162, 0, true), pt(280, 270, false)]
        );
    }
}
