//! Outlining: the model through [`crate::fit`] and [`crate::orient`] into the one IR that
//! every output reads.
//!
//! [`OutlinedFont`] is all a backend needs (render, svg, otf, layout, specimen): the font's
//! metrics and kerning, and per glyph its name, code points, advance, the X-spline contours
//! as placed, and the fitted [`BezPath`] in font units (y up, outer contours
//! counter-clockwise for the nonzero rule) with its measured error. No backend goes back to
//! the [`Font`] model, so the two cannot drift apart.
//!
//! The glyph order is decided here, once: `.notdef` first when the font has one, then the
//! model's order (the loader sorts by [`crate::model::glyph_order`]). A font without
//! `.notdef` gets the box of [`notdef_box`] wherever a missing glyph is drawn or stored.
//!
//! [`outline_font`] fits the glyphs in parallel (rayon, one task per glyph); the result does
//! not depend on the thread count, since each glyph is fitted on its own and the glyphs are
//! collected in order. [`outline_font_with`] can also take fits from a [`FitCache`] (a
//! rebuild refits only the contours that changed, and orients only the glyphs that changed)
//! and count finished glyphs for a progress display.
//!
//! The fitted paths get on-curve points at their extrema ([`crate::extrema`]): exact
//! splits, so the measured error is the fit's.
//!
//! Each glyph is outlined on its own by [`outline_glyph`], a pure function of the model, the
//! glyph and the tolerance: glyphs can be fitted in any order or in parallel, cached, or
//! refitted one at a time. Outlines at another design-space position (masters) are the
//! same type: outline the model instantiated there.

use std::borrow::Cow;
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};

use kurbo::{Affine, BezPath, PathEl, Rect, Shape, Vec2};

use rayon::prelude::*;

use crate::cache::FitCache;
use crate::extrema::{add_extrema, MIN_PIECE};
use crate::fit::fit_contour;
use crate::model::{Anchor, Component, FeatureFile, Font, FontInfo, Glyph, GlyphIndex, KernPair};
use crate::orient::orient_contours;
use crate::xspline::{ControlPoint, XSpline};

/// A font with every glyph fitted: what every output reads.
#[derive(Clone, Debug)]
pub struct OutlinedFont {
    /// Names and metrics (`font.toml`).
    pub info: FontInfo,
    /// Kerning pairs by glyph name.
    pub kerning: Vec<KernPair>,
    /// The font's own feature code (`features.fea`), if any.
    pub features: Option<FeatureFile>,
    /// The tolerance the outlines were fitted to (font units).
    pub tolerance: f64,
    /// Every glyph: `.notdef` first when the font has one, then the model's order.
    pub glyphs: Vec<OutlinedGlyph>,
}

/// One glyph ready for output.
#[derive(Clone, Debug)]
pub struct OutlinedGlyph {
    /// Glyph name.
    pub name: String,
    /// Code points mapped to the glyph (may be empty).
    pub unicodes: Vec<char>,
    /// Horizontal advance, font units.
    pub advance: f64,
    /// The components the glyph places (their contours are in `contours` and `path`).
    pub components: Vec<Component>,
    /// The glyph's own anchors, as in the source (see [`crate::model::Anchor`]): what the
    /// UFO export writes.
    pub anchors: Vec<Anchor>,
    /// Its own anchors and those its components bring ([`Font::anchors`]): what mark
    /// positioning reads, so a precomposed `ecircumflex` takes a further accent.
    pub placed_anchors: Vec<Anchor>,
    /// A mark its outline places ([`Glyph::outline_mark`]): GDEF class Mark, no anchors.
    pub outline_mark: bool,
    /// The X-spline contours the path was fitted to: the glyph's own, then its components'.
    pub contours: Vec<PlacedContour>,
    /// Closed subpaths (MoveTo … ClosePath), components resolved, oriented.
    pub path: BezPath,
    /// Largest measured distance between the path and the true X-splines (font units).
    pub max_error: f64,
    /// Number of segments (lines and cubics) in the path.
    pub segments: usize,
}

/// An X-spline contour as written in its own glyph, and where it is placed.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedContour {
    /// The contour in the coordinates of the glyph that draws it.
    pub spline: XSpline,
    /// The summed component offsets (zero for the glyph's own contours), font units.
    pub offset: Vec2,
}

impl PlacedContour {
    /// The control points where they are placed.
    pub fn points(&self) -> impl Iterator<Item = ControlPoint> + '_ {
        let (dx, dy) = (self.offset.x, self.offset.y);
        self.spline
            .points()
            .iter()
            .map(move |p| ControlPoint::new(p.pos.x + dx, p.pos.y + dy, p.s))
    }
}

impl OutlinedFont {
    /// The glyph with this name.
    pub fn glyph(&self, name: &str) -> Option<&OutlinedGlyph> {
        self.glyphs.iter().find(|g| g.name == name)
    }

    /// The glyph mapped to code point `c` (a linear search: to look up many characters,
    /// build [`OutlinedFont::char_map`] once).
    pub fn glyph_for_char(&self, c: char) -> Option<&OutlinedGlyph> {
        self.glyphs.iter().find(|g| g.unicodes.contains(&c))
    }

    /// Every mapped code point and its glyph: the one [`OutlinedFont::glyph_for_char`]
    /// finds (the first in glyph order when two glyphs claim a code point).
    pub fn char_map(&self) -> HashMap<char, &OutlinedGlyph> {
        let mut map = HashMap::with_capacity(self.glyphs.len());
        for g in &self.glyphs {
            for &c in &g.unicodes {
                map.entry(c).or_insert(g);
            }
        }
        map
    }

    /// Kerning value between two glyph names (0 when there is no pair; a linear search).
    pub fn kern(&self, left: &str, right: &str) -> f64 {
        self.kerning
            .iter()
            .find(|k| k.left == left && k.right == right)
            .map_or(0.0, |k| k.value)
    }

    /// Whether the font has a `.notdef` of its own (then it is `glyphs[0]`).
    pub fn has_notdef(&self) -> bool {
        self.glyphs.first().is_some_and(|g| g.name == ".notdef")
    }

    /// The glyph for characters the font lacks: its own `.notdef`, else [`notdef_box`].
    pub fn notdef(&self) -> Cow<'_, OutlinedGlyph> {
        match self.glyphs.first() {
            Some(g) if g.name == ".notdef" => Cow::Borrowed(g),
            _ => Cow::Owned(notdef_box(&self.info)),
        }
    }

    /// Largest measured fitting error over all glyphs.
    pub fn max_error(&self) -> f64 {
        self.glyphs.iter().map(|g| g.max_error).fold(0.0, f64::max)
    }

    /// The ink box of every non-empty glyph outline together, if there is any ink.
    pub fn ink_bounds(&self) -> Option<Rect> {
        self.glyphs
            .iter()
            .filter(|g| !g.path.elements().is_empty())
            .map(|g| g.path.bounding_box())
            .reduce(|a, b| a.union(b))
    }
}

/// How [`outline_font_with`] fits: with a cache, and counting finished glyphs.
#[derive(Clone, Copy, Debug, Default)]
pub struct OutlineOptions<'a> {
    /// Fits to reuse (keyed by the contour's points and the tolerance); new fits are added.
    pub cache: Option<&'a FitCache>,
    /// Glyphs to fit and glyphs fitted so far, updated as glyphs finish (from any thread).
    pub progress: Option<&'a Progress>,
}

/// A progress count another thread can read while [`outline_font_with`] runs.
#[derive(Debug, Default)]
pub struct Progress {
    /// Glyphs to fit (set when fitting starts).
    pub total: AtomicUsize,
    /// Glyphs fitted so far.
    pub done: AtomicUsize,
}

/// Fits every glyph of `font` within `tolerance` font units ([`outline_glyph`] each, in
/// parallel).
pub fn outline_font(font: &Font, tolerance: f64) -> OutlinedFont {
    outline_font_with(font, tolerance, OutlineOptions::default())
}

/// [`outline_font`] with a fit cache and a progress counter.
pub fn outline_font_with(font: &Font, tolerance: f64, opts: OutlineOptions<'_>) -> OutlinedFont {
    let notdef = font.glyphs.iter().filter(|g| g.name == ".notdef");
    let rest = font.glyphs.iter().filter(|g| g.name != ".notdef");
    let order: Vec<&Glyph> = notdef.chain(rest).collect();
    if let Some(progress) = opts.progress {
        progress.total.store(order.len(), Ordering::Relaxed);
    }
    let index = font.index();
    OutlinedFont {
        info: font.info.clone(),
        kerning: font.kerning.clone(),
        features: font.features.clone(),
        tolerance,
        glyphs: order
            .par_iter()
            // Small pieces, so that no core is left idle while the other fits a long run
            // of glyphs at the end.
            .with_max_len(16)
            .map(|glyph| {
                let outlined = outline_glyph_with(font, &index, glyph, tolerance, opts.cache);
                if let Some(progress) = opts.progress {
                    progress.done.fetch_add(1, Ordering::Relaxed);
                }
                outlined
            })
            .collect(),
    }
}

/// Fits one glyph of `font` (its contours and its components') within `tolerance`.
pub fn outline_glyph(font: &Font, glyph: &Glyph, tolerance: f64) -> OutlinedGlyph {
    outline_glyph_with(font, &font.index(), glyph, tolerance, None)
}

fn outline_glyph_with<'a>(
    font: &'a Font,
    index: &GlyphIndex<'a>,
    glyph: &'a Glyph,
    tolerance: f64,
    cache: Option<&FitCache>,
) -> OutlinedGlyph {
    let contours: Vec<PlacedContour> = font
        .placed_contours_in(index, glyph)
        .into_iter()
        .map(|(contour, offset)| PlacedContour {
            spline: contour.spline().clone(),
            offset: Vec2::new(offset.0, offset.1),
        })
        .collect();
    // The contours of one glyph are fitted in parallel too (a glyph of thousands of
    // contours would otherwise run on one core); collected in order, so the result does not
    // depend on the thread count.
    let fits: Vec<(BezPath, f64)> = contours
        .par_iter()
        .map(|placed| fit_placed(placed, tolerance, cache))
        .collect();
    let max_error = fits.iter().map(|f| f.1).fold(0.0, f64::max);
    let fitted = fits.into_iter().map(|f| f.0).collect();
    let path = match cache {
        Some(cache) => cache.orient_placed(&contours, tolerance, fitted),
        None => orient_contours(fitted),
    };
    let path = add_extrema(&path, min_piece(&font.info));
    let segments = path
        .elements()
        .iter()
        .filter(|el| {
            matches!(
                el,
                PathEl::LineTo(_) | PathEl::QuadTo(..) | PathEl::CurveTo(..)
            )
        })
        .count();
    OutlinedGlyph {
        name: glyph.name.clone(),
        unicodes: glyph.unicodes.clone(),
        advance: glyph.advance,
        components: glyph.components.clone(),
        anchors: glyph.anchors.clone(),
        placed_anchors: font.anchors_in(index, glyph),
        outline_mark: glyph.outline_mark,
        contours,
        path,
        max_error,
        segments,
    }
}

/// The shortest piece a split at an extreme may leave ([`crate::extrema`]), font units.
pub(crate) fn min_piece(info: &FontInfo) -> f64 {
    MIN_PIECE * f64::from(info.units_per_em)
}

/// Fits a contour where it was drawn and moves the fitted path to where it is placed.
///
/// Fitting commutes with translation (up to rounding far below the tolerance's margin), so
/// a component is the same outline as its base glyph, moved: one fit serves every glyph that
/// places the contour (and the cache and the studio share it), and moving can never make two
/// points coincide by rounding.
fn fit_placed(placed: &PlacedContour, tolerance: f64, cache: Option<&FitCache>) -> (BezPath, f64) {
    let fit = match cache {
        Some(cache) => cache.fit(&placed.spline, tolerance),
        None => fit_contour(&placed.spline, tolerance),
    };
    let path = if placed.offset == Vec2::ZERO {
        fit.path
    } else {
        Affine::translate(placed.offset) * fit.path
    };
    (path, fit.max_error)
}

/// The missing glyph of a font that has no `.notdef`: a hollow box half an em wide
/// (rounded) and cap-height tall (ascender when the cap height is 0), inset by a twentieth
/// of an em, with a stem of a twentieth of an em (at least 1 unit); outer contour
/// counter-clockwise, the counter clockwise. Used by the TTF/OTF `.notdef`, the SVG font's
/// `<missing-glyph>` and the PNG outputs, so all of them show the same box.
pub fn notdef_box(info: &FontInfo) -> OutlinedGlyph {
    let upm = f64::from(info.units_per_em);
    let advance = (upm / 2.0).round();
    let height = if info.cap_height > 0.0 {
        info.cap_height
    } else {
        info.ascender
    };
    let margin = (upm / 20.0).round();
    let stem = (upm / 20.0).round().max(1.0);
    let (x0, x1) = (margin, advance - margin);
    let mut path = BezPath::new();
    rectangle(&mut path, [x0, 0.0, x1, height], true);
    rectangle(
        &mut path,
        [x0 + stem, stem, x1 - stem, height - stem],
        false,
    );
    OutlinedGlyph {
        name: ".notdef".into(),
        unicodes: Vec::new(),
        advance,
        components: Vec::new(),
        anchors: Vec::new(),
        placed_anchors: Vec::new(),
        outline_mark: false,
        contours: Vec::new(),
        path,
        max_error: 0.0,
        segments: 8,
    }
}

/// Appends the rectangle `[x0, y0, x1, y1]` starting at `(x0, y0)`, counter-clockwise
/// (y up) or clockwise.
fn rectangle(path: &mut BezPath, [x0, y0, x1, y1]: [f64; 4], ccw: bool) {
    path.move_to((x0, y0));
    if ccw {
        path.line_to((x1, y0));
        path.line_to((x1, y1));
        path.line_to((x0, y1));
    } else {
        path.line_to((x0, y1));
        path.line_to((x1, y1));
        path.line_to((x1, y0));
    }
    path.close_path();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{test_info as info, Contour};

    fn square(x0: f64, y0: f64, side: f64) -> Contour {
        let p = |x, y| ControlPoint::new(x, y, 0.0);
        Contour::new(vec![
            p(x0, y0),
            p(x0 + side, y0),
            p(x0 + side, y0 + side),
            p(x0, y0 + side),
        ])
        .expect("a square is a valid contour")
    }

    fn glyph(name: &str, contours: Vec<Contour>, components: Vec<Component>) -> Glyph {
        Glyph {
            name: name.into(),
            unicodes: Vec::new(),
            advance: 500.0,
            contours,
            components,
            anchors: Vec::new(),
            outline_mark: false,
        }
    }

    #[test]
    fn notdef_box_geometry() {
        let g = notdef_box(&info());
        assert_eq!(g.advance, 500.0);
        // Outer 50..450 x 0..700, inner 100..400 x 50..650, counter clockwise.
        let area = g.path.area();
        assert_eq!(area, 400.0 * 700.0 - 300.0 * 600.0);
        assert_eq!(g.path.bounding_box(), Rect::new(50.0, 0.0, 450.0, 700.0));
        assert_eq!(g.segments, g.path.segments().count());
    }

    #[test]
    fn notdef_first_components_placed_and_counted() {
        let font = Font {
            info: info(),
            features: None,
            glyphs: vec![
                glyph("dot", vec![square(0.0, 0.0, 100.0)], vec![]),
                glyph(
                    "two",
                    vec![square(200.0, 0.0, 100.0)],
                    vec![Component {
                        base: "dot".into(),
                        offset: (10.0, 20.0),
                    }],
                ),
                glyph(".notdef", vec![square(50.0, 0.0, 400.0)], vec![]),
            ],
            kerning: Vec::new(),
        };
        let out = outline_font(&font, 0.5);
        let names: Vec<&str> = out.glyphs.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, [".notdef", "dot", "two"]);
        assert!(out.has_notdef());
        assert_eq!(out.notdef().path, out.glyphs[0].path);
        let two = out.glyph("two").expect("two");
        assert_eq!(two.segments, 8);
        assert_eq!(two.contours.len(), 2);
        assert_eq!(two.contours[1].offset, Vec2::new(10.0, 20.0));
        let first = two.contours[1].points().next().expect("a point");
        assert_eq!((first.pos.x, first.pos.y), (10.0, 20.0));
        assert_eq!(two.path.bounding_box(), Rect::new(10.0, 0.0, 300.0, 120.0));
        // Squares of sharp points are exact: lines only.
        assert_eq!(out.max_error(), 0.0);
    }

    #[test]
    fn the_char_map_finds_what_the_search_finds() {
        let mapped = |name: &str, unicodes: &[char]| Glyph {
            unicodes: unicodes.to_vec(),
            ..glyph(name, vec![square(0.0, 0.0, 10.0)], vec![])
        };
        let font = Font {
            info: info(),
            features: None,
            glyphs: vec![mapped("a", &['a', 'A']), mapped("alt", &['a', 'b'])],
            kerning: Vec::new(),
        };
        let out = outline_font(&font, 0.5);
        let map = out.char_map();
        assert_eq!(map.len(), 3);
        for c in ['a', 'A', 'b', 'z'] {
            let by_map = map.get(&c).map(|g| g.name.as_str());
            assert_eq!(by_map, out.glyph_for_char(c).map(|g| g.name.as_str()));
        }
        assert_eq!(map[&'a'].name, "a");
        assert_eq!(map[&'b'].name, "alt");
    }

    #[test]
    fn a_placement_that_rounds_points_together_is_fitted_in_place() {
        // 1 + 1e-17 == 1: moved by 1, the first two points would coincide.
        let tiny = Contour::new(vec![
            ControlPoint::new(0.0, 0.0, 0.0),
            ControlPoint::new(1e-17, 0.0, 0.0),
            ControlPoint::new(100.0, 50.0, 0.0),
            ControlPoint::new(0.0, 100.0, 0.0),
        ])
        .expect("distinct points");
        let font = Font {
            info: info(),
            features: None,
            glyphs: vec![
                glyph("base", vec![tiny], vec![]),
                glyph(
                    "user",
                    vec![],
                    vec![Component {
                        base: "base".into(),
                        offset: (1.0, 0.0),
                    }],
                ),
            ],
            kerning: Vec::new(),
        };
        let out = outline_font(&font, 0.5);
        let user = out.glyph("user").expect("user");
        let base = out.glyph("base").expect("base");
        assert_eq!(user.path, Affine::translate((1.0, 0.0)) * base.path.clone());
        assert_eq!(user.path.area(), 5000.0);
        assert!(!out.has_notdef());
        assert_eq!(out.notdef().path, notdef_box(&out.info).path);
    }
}
