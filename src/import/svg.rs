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
//! Limits: clip paths, masks, opacity, paint order, text and images are ignored (a
//! drawing is its ink, in one colour); a `vector-effect="non-scaling-stroke"` is scaled
//! like any other stroke; markers are ignored.

use std::path::Path;

use kurbo::{Affine, BezPath, Point};
use usvg::tiny_skia_path::{self, PathSegment};
use usvg::{FillRule, Group, Node, Options, Tree};

use super::ImportError;
use crate::overlap::{even_odd_region, remove_overlaps};

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
    let mut parts = BezPath::new();
    let mut drawn = false;
    collect(tree.root(), to_em, &mut parts, &mut drawn);
    if !drawn {
        return Err(ImportError::at(
            path,
            "the drawing has no filled or stroked path (text and images are not imported)",
        ));
    }
    if parts
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
        path: remove_overlaps(&parts, UNION_EPS),
        advance: w * scale,
    })
}

/// Appends every visible path's fill region and stroke outline to `out`, each on its own
/// turned into outer contours counter-clockwise and holes clockwise (so that a shape drawn
/// clockwise cannot cancel another where they overlap), and `out`'s nonzero fill is the
/// drawing's ink; `drawn` is set when there is any fill or stroke.
fn collect(group: &Group, to_em: Affine, out: &mut BezPath, drawn: &mut bool) {
    for node in group.children() {
        match node {
            Node::Group(g) => collect(g, to_em, out, drawn),
            Node::Path(p) if p.is_visible() => {
                let ts = p.abs_transform();
                let m = Affine::new([
                    f64::from(ts.sx),
                    f64::from(ts.ky),
                    f64::from(ts.kx),
                    f64::from(ts.sy),
                    f64::from(ts.tx),
                    f64::from(ts.ty),
                ]);
                let full = to_em * m;
                if let Some(fill) = p.fill() {
                    *drawn = true;
                    let shape = to_kurbo(p.data(), full);
                    let region = match fill.rule() {
                        FillRule::NonZero => remove_overlaps(&shape, UNION_EPS),
                        FillRule::EvenOdd => even_odd_region(&shape, UNION_EPS),
                    };
                    out.extend(region.iter());
                }
                if let Some(stroke) = p.stroke() {
                    *drawn = true;
                    let res = STROKE_RES * full_scale(full);
                    if let Some(outline) = stroke_outline(p.data(), stroke, res) {
                        let shape = to_kurbo(&outline, full);
                        out.extend(remove_overlaps(&shape, UNION_EPS).iter());
                    }
                }
            }
            _ => {}
        }
    }
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
