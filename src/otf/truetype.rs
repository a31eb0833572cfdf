//! TrueType glyphs: quadratic contours on the integer grid, then `glyf`/`loca`.

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

/// Every glyph as TrueType, quadratics within `accuracy` before grid rounding.
pub fn glyphs(glyphs: &[OtGlyph], accuracy: f64) -> Result<Vec<TtGlyph>, OtfError> {
    glyphs
        .iter()
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
                while points.len() > 1 {
                    let (first, last) = (points[0], points[points.len() - 1]);
                    if first.on_curve && last.on_curve && (first.x, first.y) == (last.x, last.y) {
                        points.pop();
                    } else {
                        break;
                    }
                }
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
        .collect()
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
