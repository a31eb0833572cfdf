//! The design overlay on a sheet cell: X-spline control polygons and points, and the
//! on-curve points of the exported Béziers, in the same placement as the outline.
//!
//! Control points are marked by kind, with both a shape and a colour:
//! sharp (`s = 0`) red square, approximating (`s > 0`) blue circle, interpolating (`s < 0`)
//! green diamond. Bézier on-curve points are small orange dots; the control polygon is a thin
//! blue-grey line. Components are drawn resolved (their points at their offsets).

use kurbo::{BezPath, PathEl, Point};
use tiny_skia::PixmapMut;

use super::draw::{fill_circle_px, fill_px, rgb, stroke_px, Placement};
use crate::outline::OutlinedGlyph;

pub const POLYGON: [u8; 3] = [95, 125, 190];
pub const SHARP: [u8; 3] = [215, 40, 40];
pub const APPROXIMATING: [u8; 3] = [40, 90, 225];
pub const INTERPOLATING: [u8; 3] = [20, 150, 60];
pub const ON_CURVE: [u8; 3] = [245, 145, 0];

/// The kind of an X-spline control point, by its shape parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointKind {
    Sharp,
    Approximating,
    Interpolating,
}

impl PointKind {
    pub fn of(s: f64) -> Self {
        if s > 0.0 {
            PointKind::Approximating
        } else if s < 0.0 {
            PointKind::Interpolating
        } else {
            PointKind::Sharp
        }
    }
}

/// The on-curve points of a path: every segment end (a subpath's start included once).
pub fn on_curve_points(path: &BezPath) -> Vec<Point> {
    let mut out = Vec::new();
    let mut start = None;
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => {
                start = Some(p);
                out.push(p);
            }
            PathEl::LineTo(p) | PathEl::QuadTo(_, p) | PathEl::CurveTo(_, _, p) => {
                // The closing segment's end repeats the start: mark it once.
                if Some(p) != start {
                    out.push(p);
                }
            }
            PathEl::ClosePath => {}
        }
    }
    out
}

/// Draws the overlay of `glyph` onto a cell `cell_px` wide.
pub fn draw(img: &mut PixmapMut<'_>, glyph: &OutlinedGlyph, at: Placement, cell_px: f64) {
    let r = (cell_px / 55.0).max(2.0);
    for contour in &glyph.contours {
        let poly: Vec<Point> = contour.points().map(|p| at.to_px(p.pos)).collect();
        stroke_px(img, &poly, true, 1.0, rgb(POLYGON));
    }
    for p in on_curve_points(&glyph.path) {
        fill_circle_px(img, at.to_px(p), r * 0.55, rgb(ON_CURVE));
    }
    for contour in &glyph.contours {
        for p in contour.points() {
            marker(img, at.to_px(p.pos), PointKind::of(p.s), r);
        }
    }
}

fn marker(img: &mut PixmapMut<'_>, c: Point, kind: PointKind, r: f64) {
    match kind {
        PointKind::Sharp => {
            let h = r * 0.9;
            let square = [
                Point::new(c.x - h, c.y - h),
                Point::new(c.x + h, c.y - h),
                Point::new(c.x + h, c.y + h),
                Point::new(c.x - h, c.y + h),
            ];
            fill_px(img, &square, rgb(SHARP));
        }
        PointKind::Approximating => fill_circle_px(img, c, r, rgb(APPROXIMATING)),
        PointKind::Interpolating => {
            let h = r * 1.3;
            let diamond = [
                Point::new(c.x, c.y - h),
                Point::new(c.x + h, c.y),
                Point::new(c.x, c.y + h),
                Point::new(c.x - h, c.y),
            ];
            fill_px(img, &diamond, rgb(INTERPOLATING));
        }
    }
}
