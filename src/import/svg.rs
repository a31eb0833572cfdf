//! SVG drawings (usvg) -> one original outline per file, scaled into the em.
//!
//! usvg resolves transforms, shapes, arcs and `use`; we take every visible path that has
//! a fill (stroke-only paths are skipped) and map the drawing's canvas onto the em as
//! icon-font tools do: the canvas height spans `descender..ascender`, the top of the
//! canvas at the ascender, the canvas width (scaled alike) is the advance.
//!
//! Limits: fill rules are not converted (contours are re-oriented by nesting on output, so
//! even-odd drawings whose holes are nested import right; overlapping even-odd shapes do
//! not); clip paths, masks, text and images are ignored.

use std::path::Path;

use kurbo::{Affine, BezPath, Point};
use usvg::tiny_skia_path::PathSegment;
use usvg::{Group, Node, Options, Tree};

use super::ImportError;

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

/// Reads the filled paths of one SVG file (bytes `data`) into the em box.
pub fn read_svg(path: &Path, data: &[u8], em: EmBox) -> Result<Drawing, ImportError> {
    let tree = Tree::from_data(data, &Options::default())
        .map_err(|e| ImportError::at(path, format!("not a readable SVG drawing ({e})")))?;
    let size = tree.size();
    let (w, h) = (f64::from(size.width()), f64::from(size.height()));
    let scale = (em.ascender - em.descender) / h;
    // Canvas (y down, origin top left) -> font units (y up, top of canvas at the ascender).
    let to_em = Affine::new([scale, 0.0, 0.0, -scale, 0.0, em.ascender]);
    let mut out = BezPath::new();
    collect(tree.root(), to_em, &mut out);
    if out.elements().is_empty() {
        return Err(ImportError::at(
            path,
            "the drawing has no filled path (stroke-only paths, text and images are not imported)",
        ));
    }
    if out
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
        path: out,
        advance: w * scale,
    })
}

fn collect(group: &Group, to_em: Affine, out: &mut BezPath) {
    for node in group.children() {
        match node {
            Node::Group(g) => collect(g, to_em, out),
            Node::Path(p) if p.is_visible() && p.fill().is_some() => {
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
                let pt = |q: usvg::tiny_skia_path::Point| {
                    full * Point::new(f64::from(q.x), f64::from(q.y))
                };
                for seg in p.data().segments() {
                    match seg {
                        PathSegment::MoveTo(a) => out.move_to(pt(a)),
                        PathSegment::LineTo(a) => out.line_to(pt(a)),
                        PathSegment::QuadTo(a, b) => out.quad_to(pt(a), pt(b)),
                        PathSegment::CubicTo(a, b, c) => out.curve_to(pt(a), pt(b), pt(c)),
                        PathSegment::Close => out.close_path(),
                    }
                }
            }
            _ => {}
        }
    }
}
