//! TrueType glyphs: quadratic contours on the integer grid, then `glyf`/`loca`.

use rayon::prelude::*;
use read_fonts::tables::glyf::CurvePoint;
use write_fonts::tables::glyf::{Bbox, Contour, GlyfLocaBuilder, Glyph, SimpleGlyph};

use super::quadratic::truetype_contours;
use super::{grid, OtGlyph, OtfError};

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
/// the thread count.
pub fn glyphs(glyphs: &[OtGlyph], accuracy: f64) -> Result<Vec<TtGlyph>, OtfError> {
    let each: Vec<Result<TtGlyph, OtfError>> = glyphs
        .par_iter()
        .map(|g| {
            let mut contours = Vec::new();
            for contour in truetype_contours(&g.path, accuracy) {
                let mut points: Vec<CurvePoint> = Vec::with_capacity(contour.len());
                for p in contour {
                    let q = grid::round_point(p.point, &g.model_name)?;
                    let point = CurvePoint::new(q.x as i16, q.y as i16, p.on_curve);
                    // A point that rounds onto its on-curve predecessor adds nothing.
                    if let Some(prev) = points.last() {
                        if prev.on_curve
                            && point.on_curve
                            && (prev.x, prev.y) == (q.x as i16, q.y as i16)
                        {
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
                    contours.push(points.into());
                }
            }
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

/// The `glyf` and `loca` tables, and `head.indexToLocFormat` (0 short, 1 long).
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
