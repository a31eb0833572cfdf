//! Shared drawing: font units (y up) to pixels (y down), BezPath to tiny-skia paths.
//!
//! Glyphs are filled with the nonzero rule and anti-aliasing; guides are 1 px lines snapped
//! to pixel centres so they stay crisp.

use kurbo::{BezPath, PathEl, Point};
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, PixmapMut, Stroke, Transform};

/// Where font units land on a pixmap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Pixels per font unit.
    pub scale: f64,
    /// Pixel x of the glyph origin (pen position).
    pub origin_x: f64,
    /// Pixel y of the baseline.
    pub baseline_y: f64,
}

impl Placement {
    /// The font-units-to-pixels transform: scale, flip y, move the origin.
    pub fn transform(&self) -> Transform {
        Transform::from_row(
            self.scale as f32,
            0.0,
            0.0,
            -self.scale as f32,
            self.origin_x as f32,
            self.baseline_y as f32,
        )
    }

    /// A point in font units, in pixels.
    pub fn to_px(&self, p: Point) -> Point {
        Point::new(
            self.origin_x + p.x * self.scale,
            self.baseline_y - p.y * self.scale,
        )
    }

    /// Pixel x of a font-unit x, snapped to a pixel centre.
    pub fn snap_x(&self, x: f64) -> f64 {
        (self.origin_x + x * self.scale).floor() + 0.5
    }

    /// Pixel y of a font-unit y, snapped to a pixel centre.
    pub fn snap_y(&self, y: f64) -> f64 {
        (self.baseline_y - y * self.scale).floor() + 0.5
    }
}

/// The same path for tiny-skia (f32); `None` when it is empty. Quadratics are kept as they
/// are; every subpath is closed as in the source.
pub fn skia_path(path: &BezPath) -> Option<tiny_skia::Path> {
    // Sized up front: a builder grown point by point reallocates its vectors log2(n) times
    // for every fill of a large glyph.
    let points = path
        .elements()
        .iter()
        .map(|el| match el {
            PathEl::MoveTo(_) | PathEl::LineTo(_) => 1,
            PathEl::QuadTo(..) => 2,
            PathEl::CurveTo(..) => 3,
            PathEl::ClosePath => 0,
        })
        .sum();
    let mut pb = PathBuilder::with_capacity(path.elements().len(), points);
    let f = |p: Point| (p.x as f32, p.y as f32);
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => {
                let (x, y) = f(p);
                pb.move_to(x, y);
            }
            PathEl::LineTo(p) => {
                let (x, y) = f(p);
                pb.line_to(x, y);
            }
            PathEl::QuadTo(a, p) => {
                let ((ax, ay), (x, y)) = (f(a), f(p));
                pb.quad_to(ax, ay, x, y);
            }
            PathEl::CurveTo(a, b, p) => {
                let ((ax, ay), (bx, by), (x, y)) = (f(a), f(b), f(p));
                pb.cubic_to(ax, ay, bx, by, x, y);
            }
            PathEl::ClosePath => pb.close(),
        }
    }
    pb.finish()
}

fn paint(color: Color) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color(color);
    paint.anti_alias = true;
    paint
}

/// Fills `path` (font units) at `at`: anti-aliased, nonzero rule.
pub fn fill_glyph(pixmap: &mut PixmapMut<'_>, path: &BezPath, at: Placement, color: Color) {
    if let Some(p) = skia_path(path) {
        fill_skia(pixmap, &p, at, color);
    }
}

/// Fills a tiny-skia `path` (font units) at `at`: anti-aliased, nonzero rule.
pub fn fill_skia(pixmap: &mut PixmapMut<'_>, path: &tiny_skia::Path, at: Placement, color: Color) {
    pixmap.fill_path(path, &paint(color), FillRule::Winding, at.transform(), None);
}

/// Strokes `path` (font units) at `at` with a 1 px line (the width does not scale).
pub fn stroke_glyph(pixmap: &mut PixmapMut<'_>, path: &BezPath, at: Placement, color: Color) {
    let in_px = kurbo::Affine::new([at.scale, 0.0, 0.0, -at.scale, at.origin_x, at.baseline_y])
        * path.clone();
    if let Some(p) = skia_path(&in_px) {
        let stroke = Stroke {
            width: 1.0,
            ..Stroke::default()
        };
        pixmap.stroke_path(&p, &paint(color), &stroke, Transform::identity(), None);
    }
}

/// Strokes a polyline given in pixels, `width` px wide; `closed` joins the ends.
pub fn stroke_px(
    pixmap: &mut PixmapMut<'_>,
    points: &[Point],
    closed: bool,
    width: f32,
    color: Color,
) {
    if let Some(path) = polyline_px(points, closed) {
        let stroke = Stroke {
            width,
            ..Stroke::default()
        };
        pixmap.stroke_path(&path, &paint(color), &stroke, Transform::identity(), None);
    }
}

/// Fills a polygon given in pixels (markers).
pub fn fill_px(pixmap: &mut PixmapMut<'_>, points: &[Point], color: Color) {
    if let Some(path) = polyline_px(points, true) {
        fill_winding(pixmap, &path, color);
    }
}

/// A tiny-skia path through `points` (pixels); `None` when it has fewer than two.
fn polyline_px(points: &[Point], closed: bool) -> Option<tiny_skia::Path> {
    let mut pb = PathBuilder::new();
    for (i, p) in points.iter().enumerate() {
        if i == 0 {
            pb.move_to(p.x as f32, p.y as f32);
        } else {
            pb.line_to(p.x as f32, p.y as f32);
        }
    }
    if closed {
        pb.close();
    }
    pb.finish()
}

/// Fills a circle of `radius` px centred at `c` (pixels).
pub fn fill_circle_px(pixmap: &mut PixmapMut<'_>, c: Point, radius: f64, color: Color) {
    if let Some(path) = PathBuilder::from_circle(c.x as f32, c.y as f32, radius as f32) {
        fill_winding(pixmap, &path, color);
    }
}

/// Fills a path given in pixels, nonzero winding.
fn fill_winding(pixmap: &mut PixmapMut<'_>, path: &tiny_skia::Path, color: Color) {
    pixmap.fill_path(
        path,
        &paint(color),
        FillRule::Winding,
        Transform::identity(),
        None,
    );
}

/// A 1 px line between two pixel points.
pub fn line_px(pixmap: &mut PixmapMut<'_>, a: Point, b: Point, color: Color) {
    stroke_px(pixmap, &[a, b], false, 1.0, color);
}

/// An opaque colour from 8-bit channels.
pub fn rgb([r, g, b]: [u8; 3]) -> Color {
    Color::from_rgba8(r, g, b, 255)
}

/// Puts the opaque image `src` into `dst` with its top left corner at `(x, y)`, clipped to
/// `dst`: a row-by-row copy. For an opaque `src` it gives exactly the pixels of tiny-skia's
/// `draw_pixmap` (source-over with full opacity is the source), which runs every pixel
/// through its high-precision pipeline and took a tenth of a build's CPU for the sheet.
pub fn put_opaque(dst: &mut PixmapMut<'_>, src: &Pixmap, x: u32, y: u32) {
    debug_assert!(src.pixels().iter().all(|p| p.alpha() == u8::MAX));
    let (dw, dh) = (dst.width(), dst.height());
    if x >= dw || y >= dh {
        return;
    }
    let width = src.width().min(dw - x) as usize;
    let rows = src.height().min(dh - y) as usize;
    let (src_stride, dst_stride) = (src.width() as usize * 4, dw as usize * 4);
    let (src_data, dst_data) = (src.data(), dst.data_mut());
    for row in 0..rows {
        let from = row * src_stride;
        let to = (y as usize + row) * dst_stride + x as usize * 4;
        dst_data[to..to + width * 4].copy_from_slice(&src_data[from..from + width * 4]);
    }
}
