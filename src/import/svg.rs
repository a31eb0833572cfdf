//! SVG drawings (usvg) -> one original outline per file, scaled into the em.
//!
//! usvg resolves transforms, shapes, arcs and `use`; we take every visible path that has
//! a fill or a stroke and map the drawing's canvas onto the em as icon-font tools do: the
//! canvas height spans `descender..ascender`, the top of the canvas at the ascender, the
//! canvas width (scaled alike) is the advance.
//!
//! A stroke (of a path, line, polyline, circle, rect…: usvg makes them all paths) becomes
//! its outline with tiny-skia's stroker: its width, joins, caps and miter limit, dashed
//! first when it has a dash array (tiny-skia's dasher), in the path's own coordinates so
//! that a transform scales the stroke as SVG does. The stroker approximates offset curves
//! with quadratics to 1/40 of a font unit (the resolution scale is ten times the path's
//! scale into the em). Each fill is taken by its own fill rule (even-odd through
//! linesweeper), and the fills and stroke outlines are then unioned by the nonzero rule
//! ([`crate::overlap::remove_overlaps`]), so overlapping shapes become one outline.
//!
//! Clip paths cut the ink: each clipped group's ink is intersected (linesweeper) with the
//! union of its clip path's fills, in the group's coordinates and the clip's transform,
//! cut in turn by the clip path's own clip path. A path whose ink lies wholly outside the
//! canvas is left out and counted ([`Drawing::outside`]): no viewer shows it, and
//! exporters leave such shapes behind masks.
//!
//! Limits: masks, opacity, paint order, text and images are ignored (a drawing is its ink,
//! in one colour); ink partly outside the canvas is kept whole (a glyph may overhang its
//! advance); a `vector-effect="non-scaling-stroke"` is scaled like any other stroke;
//! markers are ignored.

use std::path::Path;

use kurbo::{Affine, BezPath, Point, Rect, Shape};
use usvg::tiny_skia_path::{self, PathSegment};
use usvg::{FillRule, Group, Node, Options, Tree};

use super::ImportError;
use crate::overlap::{even_odd_region, intersect_regions, remove_overlaps};

/// Where a drawing goes in the em: vertical extent in font units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmBox {
    /// Top of the drawing's box, font units.
    pub ascender: f64,
    /// Bottom of the drawing's box, font units (negative).
    pub descender: f64,
}

/// One drawing in font units (y up).
#[derive(Clone, Debug)]
pub struct Drawing {
    /// The filled outline.
    pub path: BezPath,
    /// Advance: the drawing's width scaled to the em.
    pub advance: f64,
    /// Paths left out because they lie wholly outside the canvas.
    pub outside: usize,
}

/// How finely the union follows its parts: font units (far below the import tolerance).
const UNION_EPS: f64 = 1e-4;

/// The stroker's resolution scale per unit of the path's scale into the em: it keeps
/// offset curves within about `1 / (4 · res)` user units, so 1/40 of a font unit.
const STROKE_RES: f32 = 10.0;

/// Reads the filled and stroked paths of one SVG file (bytes `data`) into the em box.
pub fn read_svg(path: &Path, data: &[u8], em: EmBox) -> Result<Drawing, ImportError> {
    let tree = Tree::from_data(data, &Options::default())
        .map_err(|e| ImportError::at(path, format!("not a readable SVG drawing ({e})")))?;
    let size = tree.size();
    let (w, h) = (f64::from(size.width()), f64::from(size.height()));
    let scale = (em.ascender - em.descender) / h;
    // Canvas (y down, origin top left) -> font units (y up, top of canvas at the ascender).
    let to_em = Affine::new([scale, 0.0, 0.0, -scale, 0.0, em.ascender]);
    let mut ink = Ink {
        to_em,
        canvas: Rect::new(0.0, em.descender, w * scale, em.ascender),
        parts: BezPath::new(),
        drawn: false,
        outside: 0,
    };
    ink.collect(tree.root());
    if !ink.drawn {
        return Err(ImportError::at(
            path,
            "the drawing has no filled or stroked path (text and images are not imported)",
        ));
    }
    if ink
        .parts
        .elements()
        .iter()
        .flat_map(|el| el.end_point())
        .any(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        return Err(ImportError::at(
            path,
            "the drawing has non-finite coordinates",
        ));
    }
    Ok(Drawing {
        path: remove_overlaps(&ink.parts, UNION_EPS),
        advance: w * scale,
        outside: ink.outside,
    })
}

/// The drawing's ink as it is collected, in font units.
struct Ink {
    /// Canvas (user units of the root, y down) to font units.
    to_em: Affine,
    /// The canvas in font units: what any SVG viewer shows.
    canvas: Rect,
    /// Every visible path's fill region and stroke outline, each on its own turned into
    /// outer contours counter-clockwise and holes clockwise (so that a shape drawn
    /// clockwise cannot cancel another where they overlap); their nonzero fill is the ink.
    parts: BezPath,
    /// Whether there is any fill or stroke.
    drawn: bool,
    /// Paths left out because they lie wholly outside the canvas.
    outside: usize,
}

impl Ink {
    /// Appends the ink of `group`'s children to `self.parts`; a group with a clip path
    /// keeps only what lies inside the clip's region.
    fn collect(&mut self, group: &Group) {
        for node in group.children() {
            match node {
                Node::Group(g) => match g.clip_path() {
                    None => self.collect(g),
                    Some(clip) => {
                        let outer = std::mem::take(&mut self.parts);
                        self.collect(g);
                        let inner = std::mem::replace(&mut self.parts, outer);
                        let region = clip_region(clip, self.to_em * affine(g.abs_transform()));
                        let kept = intersect_regions(&inner, &region, UNION_EPS);
                        self.parts.extend(kept.iter());
                    }
                },
                Node::Path(p) if p.is_visible() => self.path(p),
                _ => {}
            }
        }
    }

    /// One path's fill region and stroke outline, unless they lie wholly outside the
    /// canvas: no viewer shows them (exporters leave such shapes under masks).
    fn path(&mut self, p: &usvg::Path) {
        let full = self.to_em * affine(p.abs_transform());
        let mut ink = BezPath::new();
        if let Some(fill) = p.fill() {
            self.drawn = true;
            ink.extend(fill_region(p.data(), fill.rule(), full).iter());
        }
        if let Some(stroke) = p.stroke() {
            self.drawn = true;
            let res = STROKE_RES * full_scale(full);
            if let Some(outline) = stroke_outline(p.data(), stroke, res) {
                let shape = to_kurbo(&outline, full);
                ink.extend(remove_overlaps(&shape, UNION_EPS).iter());
            }
        }
        if ink.elements().is_empty() {
            return;
        }
        // Non-finite ink is kept, for `read_svg` to refuse.
        let bounds = ink.bounding_box();
        if !bounds.is_finite() || bounds.intersect(self.canvas).area() > 0.0 {
            self.parts.extend(ink.iter());
        } else {
            self.outside += 1;
        }
    }
}

/// The region a fill covers by its rule, oriented as [`Ink::parts`] wants.
fn fill_region(data: &tiny_skia_path::Path, rule: FillRule, m: Affine) -> BezPath {
    let shape = to_kurbo(data, m);
    match rule {
        FillRule::NonZero => remove_overlaps(&shape, UNION_EPS),
        FillRule::EvenOdd => even_odd_region(&shape, UNION_EPS),
    }
}

/// The region a clip path lets through, in font units: the union of its shapes' fills
/// (usvg gives them the `clip-rule`), in the clipped group's coordinates (`base`) then the
/// clip's own transform, cut by the clip path's own clip path. Strokes, and paths without
/// a fill, do not clip, as in resvg.
fn clip_region(clip: &usvg::ClipPath, base: Affine) -> BezPath {
    let mut shapes = BezPath::new();
    clip_shapes(clip.root(), base * affine(clip.transform()), &mut shapes);
    match clip.clip_path() {
        Some(outer) => intersect_regions(&shapes, &clip_region(outer, base), UNION_EPS),
        None => shapes,
    }
}

/// The fills of a clip path's shapes under `group`, whose coordinates `m` maps into font
/// units (inside a clip path, usvg's absolute transforms start at the clip path).
fn clip_shapes(group: &Group, m: Affine, out: &mut BezPath) {
    for node in group.children() {
        match node {
            Node::Group(g) => {
                let m = m * affine(g.transform());
                match g.clip_path() {
                    None => clip_shapes(g, m, out),
                    Some(clip) => {
                        let mut inner = BezPath::new();
                        clip_shapes(g, m, &mut inner);
                        out.extend(
                            intersect_regions(&inner, &clip_region(clip, m), UNION_EPS).iter(),
                        );
                    }
                }
            }
            Node::Path(p) if p.is_visible() => {
                if let Some(fill) = p.fill() {
                    out.extend(fill_region(p.data(), fill.rule(), m).iter());
                }
            }
            _ => {}
        }
    }
}

/// usvg's transform as kurbo's.
fn affine(ts: usvg::Transform) -> Affine {
    Affine::new([
        f64::from(ts.sx),
        f64::from(ts.ky),
        f64::from(ts.kx),
        f64::from(ts.sy),
        f64::from(ts.tx),
        f64::from(ts.ty),
    ])
}

/// The outline of a stroke in the path's own coordinates: dashed first if it has a dash
/// array, then stroked; `None` when nothing is left (a zero width, all gaps).
fn stroke_outline(
    data: &tiny_skia_path::Path,
    stroke: &usvg::Stroke,
    res: f32,
) -> Option<tiny_skia_path::Path> {
    let mut ts = stroke.to_tiny_skia();
    let dash = ts.dash.take();
    match dash {
        Some(dash) => data.dash(&dash, res)?.stroke(&ts, res),
        None => data.stroke(&ts, res),
    }
}

/// The larger of the two scale factors of `m` (for the stroker's resolution).
fn full_scale(m: Affine) -> f32 {
    let [a, b, c, d, _, _] = m.as_coeffs();
    let s = a.hypot(b).max(c.hypot(d));
    if s.is_finite() && s > 0.0 {
        s as f32
    } else {
        1.0
    }
}

/// A tiny-skia path mapped by `m` into a kurbo path. Every subpath is closed: a fill or a
/// stroke outline encloses its region whether or not the SVG closed it.
fn to_kurbo(data: &tiny_skia_path::Path, m: Affine) -> BezPath {
    let pt = |q: tiny_skia_path::Point| m * Point::new(f64::from(q.x), f64::from(q.y));
    let mut out = BezPath::new();
    let mut open = false;
    for seg in data.segments() {
        match seg {
            PathSegment::MoveTo(a) => {
                if open {
                    out.close_path();
                }
                out.move_to(pt(a));
                open = true;
            }
            PathSegment::LineTo(a) => out.line_to(pt(a)),
            PathSegment::QuadTo(a, b) => out.quad_to(pt(a), pt(b)),
            PathSegment::CubicTo(a, b, c) => out.curve_to(pt(a), pt(b), pt(c)),
            PathSegment::Close => {
                out.close_path();
                open = false;
            }
        }
    }
    if open {
        out.close_path();
    }
    out
}
