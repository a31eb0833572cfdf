//! TrueType glyphs: quadratic contours on the integer grid, then `glyf`/`loca`.

use rayon::prelude::*;
use read_fonts::tables::glyf::CurvePoint;
use write_fonts::tables::glyf::{Bbox, Contour, GlyfLocaBuilder, SimpleGlyph};
use write_fonts::tables::loca::Loca;

use super::quadratic::{truetype_contours, SplinePoint};
use kurbo::Point;

use super::{grid, monotone, spike, OtGlyph, OtfError};
use crate::reuse::{Key, KeyBuilder, Reuse};

/// One glyph ready for `glyf`: its bytes as the table holds them (none for an empty glyph),
/// so that a rebuild copies a kept glyph instead of encoding it again.
pub struct TtGlyph {
    bytes: Vec<u8>,
}

impl TtGlyph {
    /// A glyph without outline.
    pub fn empty() -> Self {
        TtGlyph { bytes: Vec::new() }
    }

    /// `glyph` as `glyf` bytes, encoded by write-fonts (flags, coordinates, padding).
    pub fn new(glyph: &SimpleGlyph) -> Result<Self, OtfError> {
        let mut builder = GlyfLocaBuilder::new();
        builder
            .add_glyph(glyph)
            .map_err(|e| OtfError::Table(format!("glyf: {e}")))?;
        let (glyf, _, _) = builder.build();
        let bytes =
            write_fonts::dump_table(&glyf).map_err(|e| OtfError::Table(format!("glyf: {e}")))?;
        Ok(TtGlyph { bytes })
    }

    /// The glyph's bytes when they are a simple glyph's that `glyf` can hold: a header with
    /// contours, ascending contour ends, and an even length.
    fn from_bytes(bytes: Vec<u8>) -> Option<Self> {
        if bytes.is_empty() {
            return Some(TtGlyph::empty());
        }
        let glyph = TtGlyph { bytes };
        let contours = glyph.num_contours();
        let header = 10 + 2 * contours;
        let ends: Option<Vec<u16>> = (0..contours).map(|i| glyph.be16(10 + 2 * i)).collect();
        let ascending = ends?.windows(2).all(|w| w[0] < w[1]);
        (contours > 0 && ascending && glyph.bytes.len() > header && glyph.bytes.len() % 2 == 0)
            .then_some(glyph)
    }

    fn be16(&self, at: usize) -> Option<u16> {
        super::be16(&self.bytes, at)
    }

    fn be16_or_0(&self, at: usize) -> i16 {
        self.be16(at).unwrap_or(0) as i16
    }

    /// Control-point bounding box (what `glyf` stores), `None` for an empty glyph.
    pub fn bbox(&self) -> Option<Bbox> {
        (!self.bytes.is_empty()).then(|| Bbox {
            x_min: self.be16_or_0(2),
            y_min: self.be16_or_0(4),
            x_max: self.be16_or_0(6),
            y_max: self.be16_or_0(8),
        })
    }

    pub fn num_points(&self) -> usize {
        match self.num_contours() {
            0 => 0,
            n => usize::from(self.be16(10 + 2 * (n - 1)).unwrap_or(0)) + 1,
        }
    }

    pub fn num_contours(&self) -> usize {
        self.be16(0).map_or(0, |n| n.min(i16::MAX as u16) as usize)
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
            let make = || truetype_glyph(g, accuracy);
            match outlines.get(i).copied().flatten() {
                Some(outline) => {
                    let key = KeyBuilder::new("truetype glyph")
                        .f64(accuracy)
                        .key(&outline)
                        .u64(u64::from(g.from_components))
                        .finish();
                    let encode = |g: &TtGlyph| g.bytes.clone();
                    let decode = |bytes: &[u8]| TtGlyph::from_bytes(bytes.to_vec());
                    reuse.data_or_make(key, encode, decode, make)
                }
                None => make(),
            }
        })
        .collect();
    each.into_iter().collect()
}

/// Glyph `g` for `glyf`: [`on_grid`]'s contours as a simple glyph (or an empty one).
fn truetype_glyph(g: &OtGlyph, accuracy: f64) -> Result<TtGlyph, OtfError> {
    let contours: Vec<Contour> = on_grid(g, accuracy)?
        .into_iter()
        .map(Contour::from)
        .collect();
    if contours.is_empty() {
        return Ok(TtGlyph::empty());
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
    TtGlyph::new(&glyph)
}

/// The contours of `g` as TrueType: quadratics within `accuracy`, points on the grid,
/// zero-length segments and contours of fewer than 3 distinct points dropped.
fn on_grid(g: &OtGlyph, accuracy: f64) -> Result<Vec<Vec<CurvePoint>>, OtfError> {
    let mut contours = Vec::new();
    for contour in truetype_contours(&g.path(), accuracy) {
        let mut points: Vec<CurvePoint> = Vec::with_capacity(contour.len());
        for point in round_contour(&contour, &g.model_name)? {
            // A point that rounds onto its on-curve predecessor adds nothing.
            if let Some(prev) = points.last() {
                if prev.on_curve && point.on_curve && (prev.x, prev.y) == (point.x, point.y) {
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

/// A TrueType contour's points on the grid: each rounded on its own, then no quadratic
/// left turning back where the exact one runs one way ([`monotone::keep_quadratics`]) and
/// every spike kept in order ([`spike::keep_spikes`]). A point moved there stays within one
/// unit of its exact place, and every point of a quadratic spline is a convex combination of its
/// points, so the contour stays within one unit: no further bound to check.
pub(super) fn round_contour(
    contour: &[SplinePoint],
    glyph: &str,
) -> Result<Vec<CurvePoint>, OtfError> {
    let exact: Vec<Point> = contour.iter().map(|p| p.point).collect();
    let on_curve: Vec<bool> = contour.iter().map(|p| p.on_curve).collect();
    let mut rounded = exact
        .iter()
        .map(|&p| grid::round_point(p, glyph))
        .collect::<Result<Vec<Point>, OtfError>>()?;
    monotone::keep_quadratics(&exact, &mut rounded, &on_curve);
    spike::keep_spikes(&exact, &mut rounded, &on_curve, |_, _| true);
    Ok(rounded
        .into_iter()
        .zip(on_curve)
        .map(|(q, on)| CurvePoint::new(q.x as i16, q.y as i16, on))
        .collect())
}

/// Removes, around the closed contour, points that make zero-length segments on the grid
/// without changing its shape: an on-curve point equal to the on-curve point before it,
/// an off-curve point between two on-curve points that equals one of them (the quadratic
/// is then the straight line between them), and an off-curve point equal to both its
/// neighbours (every segment it touches, implied on-curve points included, is that one
/// point). Other repeated points are kept: dropping an off-curve point next to a
/// different off-curve one would move the implied on-curve point between them.
fn drop_degenerate(points: &mut Vec<CurvePoint>) {
    // A removal near the end can make the first point redundant against the new last one:
    // go round again until nothing changes.
    loop {
        let before = points.len();
        drop_degenerate_once(points);
        if points.len() == before {
            return;
        }
    }
}

/// One pass of [`drop_degenerate`] around the contour.
fn drop_degenerate_once(points: &mut Vec<CurvePoint>) {
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
pub fn glyf_loca(glyphs: &[TtGlyph]) -> (Vec<u8>, Loca, i16) {
    // What write-fonts' `GlyfLocaBuilder` writes: the glyphs one after another (each
    // already padded to 2 bytes), `loca` their offsets, short when they allow it.
    let mut glyf = Vec::with_capacity(glyphs.iter().map(|g| g.bytes.len()).sum());
    let mut offsets = Vec::with_capacity(glyphs.len() + 1);
    offsets.push(0);
    for g in glyphs {
        glyf.extend_from_slice(&g.bytes);
        offsets.push(glyf.len() as u32);
    }
    let loca = Loca::new(offsets);
    let format = loca.format() as i16;
    (glyf, loca, format)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glyphs_are_glyf_bytes_as_write_fonts_builds_them_and_bad_bytes_are_refused() {
        let pt = |x, y, on| CurvePoint::new(x, y, on);
        let contours = [
            vec![pt(0, 0, true), pt(-300, 700, false), pt(500, -20, true)],
            vec![
                pt(5, 5, false),
                pt(6, 4, false),
                pt(-1, 700, true),
                pt(5, 5, true),
            ],
        ];
        let mut simple = SimpleGlyph {
            contours: contours.iter().cloned().map(Contour::from).collect(),
            overlaps: true,
            ..Default::default()
        };
        simple.recompute_bounding_box();
        let glyph = TtGlyph::new(&simple).unwrap();
        assert_eq!(glyph.num_contours(), 2);
        assert_eq!(glyph.num_points(), 7);
        assert_eq!(glyph.bbox(), Some(simple.bbox));
        assert_eq!(
            (TtGlyph::empty().bbox(), TtGlyph::empty().num_points()),
            (None, 0)
        );
        // glyf and loca as write-fonts' builder makes them, empty glyphs included.
        let glyphs = [
            TtGlyph::empty(),
            glyph,
            TtGlyph::empty(),
            TtGlyph::new(&simple).unwrap(),
        ];
        let (glyf, loca, format) = glyf_loca(&glyphs);
        let mut builder = GlyfLocaBuilder::new();
        for g in [None, Some(&simple), None, Some(&simple)] {
            match g {
                Some(simple) => builder.add_glyph(simple).unwrap(),
                None => builder
                    .add_glyph(&write_fonts::tables::glyf::Glyph::Empty)
                    .unwrap(),
            };
        }
        let (their_glyf, their_loca, their_format) = builder.build();
        assert_eq!(glyf, write_fonts::dump_table(&their_glyf).unwrap());
        assert_eq!(
            write_fonts::dump_table(&loca).unwrap(),
            write_fonts::dump_table(&their_loca).unwrap()
        );
        assert_eq!(format, their_format as i16);
        // A kept glyph's bytes back; truncated, odd or without contours: refused.
        let bytes = glyphs[1].bytes.clone();
        let back = TtGlyph::from_bytes(bytes.clone()).expect("its own bytes");
        assert_eq!(back.bytes, bytes);
        assert!(TtGlyph::from_bytes(bytes[..12].to_vec()).is_none());
        assert!(TtGlyph::from_bytes(bytes[..bytes.len() - 1].to_vec()).is_none());
        let mut none = bytes.clone();
        none[..2].copy_from_slice(&0u16.to_be_bytes());
        assert!(TtGlyph::from_bytes(none).is_none());
        let mut descending = bytes;
        descending[10..12].copy_from_slice(&9u16.to_be_bytes());
        assert!(TtGlyph::from_bytes(descending).is_none());
        assert_eq!(
            TtGlyph::from_bytes(Vec::new()).map(|g| g.bytes),
            Some(Vec::new())
        );
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
        // A sliver at the contour's end (the Bold `braceleft`, 0.14 units before its
        // start point): its off-curve point goes, and then the on-curve point before it
        // equals the first point, across the wrap.
        let mut wrap = vec![
            pt(378, 760, true),
            pt(378, 648, true),
            pt(328, 759, false),
            pt(378, 760, true),
            pt(378, 760, false),
        ];
        drop_degenerate(&mut wrap);
        assert_eq!(
            wrap,
            [pt(378, 648, true), pt(328, 759, false), pt(378, 760, true)]
        );
    }
}
