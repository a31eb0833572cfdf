//! Coverage stamps: a path's anti-aliased fill rasterised once into a small coverage mask,
//! then composited wherever the same fill recurs, giving exactly the bytes tiny-skia's
//! `fill_path` gives (nonzero rule, anti-aliased, opaque solid colour).
//!
//! Why it is exact: tiny-skia maps the path to pixels in f32 and truncates each coordinate
//! to 1/256 px; from there on its scan conversion is integer arithmetic, which moves with
//! the path by whole pixels. The stamp takes the very f32 points of the fill and subtracts
//! whole pixels (exact in f32 below 2^24), so it covers exactly the pixels the fill would,
//! each by the same alpha, and [`Stamp::put`] blends them with the same integer formula as
//! tiny-skia's low-precision pipeline. `tests/it/labels.rs` checks the bytes against the
//! fill. Limits: only where the fill would be neither clipped nor tiled (the stamp lies
//! inside the pixmap and its sides are below 8,192 px) and the colour is opaque: elsewhere
//! [`Stamp::put`] draws nothing and says so, and the caller fills the path itself. Checked
//! on polygons (what the built-in label face draws), not on curves.

use tiny_skia::{Color, FillRule, Mask, Path, PixmapMut, Transform};

/// Pixmaps at least this wide or tall are filled tile by tile by tiny-skia (its
/// `DrawTiler`), which moves the path in f32 and so rounds differently: no stamping there.
const TILED_SIDE: u32 = 8192 - 1;

/// A fill's coverage, one byte a pixel, at whole-pixel position `(left, top)`.
#[derive(Clone, Debug)]
pub struct Stamp {
    left: u32,
    top: u32,
    width: u32,
    height: u32,
    /// Row by row, `width` bytes a row.
    coverage: Vec<u8>,
}

impl Stamp {
    /// The coverage of `path` filled under `transform`. `None` when the fill leaves no
    /// pixels, or reaches left of or above the origin (there tiny-skia's truncation
    /// rounds the other way, so a stamp would not be exact).
    pub fn new(path: &Path, transform: Transform) -> Option<Stamp> {
        // The same f32 arithmetic as `fill_path` under a non-identity transform.
        let placed = path.clone().transform(transform)?;
        let bounds = placed.bounds();
        if bounds.left() < 0.0 || bounds.top() < 0.0 {
            return None;
        }
        let (left, top) = (bounds.left().floor(), bounds.top().floor());
        let (right, bottom) = (bounds.right().ceil(), bounds.bottom().ceil());
        if right > TILED_SIDE as f32 || bottom > TILED_SIDE as f32 {
            return None;
        }
        // Whole pixels off: exact, so the mask sees the fill's own coordinates, moved.
        let local = placed.transform(Transform::from_translate(-left, -top))?;
        let (width, height) = ((right - left) as u32, (bottom - top) as u32);
        let mut mask = Mask::new(width, height)?;
        mask.fill_path(&local, FillRule::Winding, true, Transform::identity());
        Some(Stamp {
            left: left as u32,
            top: top as u32,
            width,
            height,
            coverage: mask.data().to_vec(),
        })
    }

    /// Memory the stamp holds, bytes.
    pub fn bytes(&self) -> usize {
        self.coverage.len() + std::mem::size_of::<Stamp>()
    }

    /// Composites the stamp in `color` onto `pixmap` as tiny-skia's fill would, and says
    /// so; `false`, drawing nothing, when that fill would have been clipped or tiled or the
    /// colour is translucent (see the module's limits).
    pub fn put(&self, pixmap: &mut PixmapMut<'_>, color: Color) -> bool {
        let (pw, ph) = (pixmap.width(), pixmap.height());
        let inside = self.left + self.width <= pw && self.top + self.height <= ph;
        if !color.is_opaque() || pw > TILED_SIDE || ph > TILED_SIDE || !inside {
            return false;
        }
        let c = color.premultiply().to_color_u8();
        let bytes = [c.red(), c.green(), c.blue(), c.alpha()];
        let src = bytes.map(u16::from);
        let stride = pw as usize * 4;
        let (x, y, w) = (self.left as usize, self.top as usize, self.width as usize);
        let data = pixmap.data_mut();
        // Hand-written rather than tiny-skia's per-pixel pipeline: this loop is the point
        // of the stamp. Full coverage writes the colour (tiny-skia's memset); partial
        // coverage is its low-precision lerp, (d * (255 - a) + s * a + 255) >> 8.
        for (row, alphas) in self.coverage.chunks_exact(w).enumerate() {
            let start = (y + row) * stride + x * 4;
            let pixels = data[start..start + w * 4].chunks_exact_mut(4);
            for (px, &alpha) in pixels.zip(alphas) {
                match alpha {
                    0 => {}
                    u8::MAX => px.copy_from_slice(&bytes),
                    a => {
                        let (a, keep) = (u16::from(a), 255 - u16::from(a));
                        for (d, s) in px.iter_mut().zip(src) {
                            *d = ((u16::from(*d) * keep + s * a + 255) >> 8) as u8;
                        }
                    }
                }
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use tiny_skia::{Paint, PathBuilder, Pixmap};

    use super::*;

    /// A star with a hole (nonzero, crossing edges) and slanted sides.
    fn star() -> Path {
        let mut pb = PathBuilder::new();
        let points = [
            (50.0, 0.0),
            (79.0, 90.0),
            (2.0, 35.0),
            (98.0, 35.0),
            (21.0, 90.0),
        ];
        pb.move_to(points[0].0, points[0].1);
        points[1..].iter().for_each(|&(x, y)| pb.line_to(x, y));
        pb.close();
        pb.finish().expect("a star is a path")
    }

    fn gradient() -> Pixmap {
        let mut img = Pixmap::new(64, 64).expect("64 px");
        for (i, px) in img.data_mut().chunks_exact_mut(4).enumerate() {
            px.copy_from_slice(&[(i * 3) as u8, (i / 64 * 4) as u8, 90, 255]);
        }
        img
    }

    #[test]
    fn a_stamp_puts_the_bytes_of_the_fill() {
        let color = Color::from_rgba8(20, 120, 240, 255);
        let mut paint = Paint::default();
        paint.set_color(color);
        paint.anti_alias = true;
        for k in 0..40u8 {
            let s = 0.1 + f32::from(k) * 0.01;
            let t = Transform::from_row(s, 0.0, 0.0, -s, 1.3 + f32::from(k) * 0.3, 50.17);
            let (mut stamped, mut filled) = (gradient(), gradient());
            let stamp = Stamp::new(&star(), t).expect("inside the pixmap");
            assert!(stamp.put(&mut stamped.as_mut(), color), "{k}: not stamped");
            filled.fill_path(&star(), &paint, FillRule::Winding, t, None);
            assert!(stamped.data() == filled.data(), "{k}: bytes differ");
        }
    }

    #[test]
    fn a_stamp_declines_where_it_would_not_be_exact() {
        let t = Transform::from_row(0.5, 0.0, 0.0, 0.5, 10.25, 3.5);
        let stamp = Stamp::new(&star(), t).expect("a stamp");
        let mut img = gradient();
        let translucent = Color::from_rgba8(20, 120, 240, 200);
        assert!(!stamp.put(&mut img.as_mut(), translucent));
        let mut small = Pixmap::new(40, 40).expect("40 px");
        assert!(!stamp.put(&mut small.as_mut(), Color::BLACK), "clipped");
        let mut tiled = Pixmap::new(8200, 1).expect("8200 px");
        assert!(!stamp.put(&mut tiled.as_mut(), Color::BLACK), "tiled");
        assert!(img.data() == gradient().data(), "declined, yet drew");
        // Left of the origin: no stamp.
        let left = Transform::from_row(0.5, 0.0, 0.0, 0.5, -1.25, 3.5);
        assert!(Stamp::new(&star(), left).is_none());
    }
}
