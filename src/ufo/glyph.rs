//! One outlined glyph as a UFO glyph: its own fitted contours, its components, code points,
//! advance, anchors (named, at their exact positions), and its X-spline contours in the lib.
//!
//! The outlined glyph's path holds its own contours first, then its components' (see
//! [`crate::outline::OutlinedGlyph`]), each subpath already oriented by the build; the own
//! ones are taken as they are, so the UFO's outlines are the build's (only rounded to
//! 1/1000 unit). Components are written as components instead of their resolved contours.

use kurbo::{BezPath, PathEl, Point};
use norad::{AffineTransform, ContourPoint, PointType};

use super::lib::XSPLINE_KEY;
use super::{name, UfoError};
use crate::outline::OutlinedGlyph;
use crate::reuse::{Key, KeyBuilder};

/// Coordinates are rounded to this many parts of a font unit.
const GRID: f64 = 1000.0;

/// The UFO glyph of `g`, whose first `own` contours are its own.
pub fn glyph(g: &OutlinedGlyph, own: usize) -> Result<norad::Glyph, UfoError> {
    name(&g.name)?;
    let mut ufo = norad::Glyph::new(&g.name);
    ufo.width = g.advance + 0.0;
    ufo.codepoints = g.unicodes.iter().copied().collect();
    ufo.contours = subpaths(&g.path).take(own).map(|p| contour(&p)).collect();
    for c in &g.components {
        let transform = AffineTransform {
            x_offset: c.offset.0 + 0.0,
            y_offset: c.offset.1 + 0.0,
            ..AffineTransform::default()
        };
        ufo.components
            .push(norad::Component::new(name(&c.base)?, transform, None));
    }
    for a in &g.anchors {
        let anchor_name = norad::Name::new(&a.name).map_err(|_| UfoError::AnchorName {
            glyph: g.name.clone(),
            anchor: a.name.clone(),
        })?;
        let (x, y) = a.position;
        ufo.anchors.push(norad::Anchor::new(
            x + 0.0,
            y + 0.0,
            Some(anchor_name),
            None,
            None,
        ));
    }
    if own > 0 {
        let splines: Vec<crate::model::Contour> = g.contours[..own]
            .iter()
            .map(|c| crate::model::Contour::from(c.spline.clone()))
            .collect();
        ufo.lib
            .insert(XSPLINE_KEY.into(), super::lib::xspline_value(&splines));
    }
    Ok(ufo)
}

/// What [`glyph`] reads of `g` (whose first `own` contours are its own), as a [`Key`]:
/// name, advance, code points, outline (`outline`, its [`crate::reuse::outline_key`]),
/// components, anchors and the own X-splines.
pub fn key(g: &OutlinedGlyph, own: usize, outline: &Key) -> Key {
    let mut k = KeyBuilder::new("glif");
    k.str(&g.name).f64(g.advance).u64(g.unicodes.len() as u64);
    for &c in &g.unicodes {
        k.u64(u64::from(c));
    }
    k.key(outline).u64(g.components.len() as u64);
    for c in &g.components {
        k.str(&c.base).f64(c.offset.0).f64(c.offset.1);
    }
    k.u64(g.anchors.len() as u64);
    for a in &g.anchors {
        k.str(&a.name).f64(a.position.0).f64(a.position.1);
    }
    let own = &g.contours[..own.min(g.contours.len())];
    k.u64(own.len() as u64);
    for c in own {
        let points = c.spline.points();
        k.u64(points.len() as u64);
        for p in points {
            k.f64(p.pos.x).f64(p.pos.y).f64(p.s);
        }
    }
    k.finish()
}

/// The closed subpaths of `path` (MoveTo … ClosePath each).
fn subpaths(path: &BezPath) -> impl Iterator<Item = BezPath> + '_ {
    let mut current: Option<BezPath> = None;
    let mut els = path.elements().iter();
    std::iter::from_fn(move || loop {
        match els.next() {
            Some(PathEl::MoveTo(p)) => {
                let mut next = BezPath::new();
                next.move_to(*p);
                if let Some(done) = current.replace(next) {
                    if done.elements().len() > 1 {
                        return Some(done);
                    }
                }
            }
            Some(el) => {
                if let Some(c) = current.as_mut() {
                    c.push(*el);
                }
            }
            None => return current.take().filter(|c| c.elements().len() > 1),
        }
    })
}

/// A closed subpath as a cyclic UFO point list: each segment's off-curve points then its
/// end point, typed `line` or `curve`; the start point is the last segment's end (a
/// closing line is added when the path does not return to it). An on-curve point where
/// the curve turns smoothly (tangents within 0.1°) is marked smooth.
fn contour(path: &BezPath) -> norad::Contour {
    let mut start = Point::ZERO;
    // (point, type) with `None` for off-curve.
    let mut points: Vec<(Point, Option<PointType>)> = Vec::new();
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => start = p,
            PathEl::LineTo(p) => points.push((p, Some(PointType::Line))),
            PathEl::QuadTo(c, p) => {
                points.push((c, None));
                points.push((p, Some(PointType::QCurve)));
            }
            PathEl::CurveTo(c1, c2, p) => {
                points.push((c1, None));
                points.push((c2, None));
                points.push((p, Some(PointType::Curve)));
            }
            PathEl::ClosePath => {}
        }
    }
    if points.last().map(|p| p.0) != Some(start) {
        points.push((start, Some(PointType::Line)));
    }
    let n = points.len();
    let out = (0..n)
        .map(|i| {
            let (p, typ) = points[i];
            let smooth = typ.is_some() && {
                let before = p - points[(i + n - 1) % n].0;
                let after = points[(i + 1) % n].0 - p;
                let (a, b) = (before.hypot(), after.hypot());
                a > 0.0 && b > 0.0 && before.dot(after) > 0.0 && {
                    let sin = before.cross(after) / (a * b);
                    sin.abs() < (0.1f64).to_radians().sin()
                }
            };
            ContourPoint::new(
                round(p.x),
                round(p.y),
                typ.unwrap_or(PointType::OffCurve),
                smooth,
                None,
                None,
            )
        })
        .collect();
    norad::Contour::new(out, None)
}

fn round(v: f64) -> f64 {
    (v * GRID).round() / GRID + 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_closed_path_becomes_a_cyclic_point_list() {
        let mut path = BezPath::new();
        path.move_to((0.0, 0.0));
        path.line_to((100.0, 0.0));
        path.curve_to((100.0, 50.0), (50.0, 100.0), (0.0, 100.0));
        path.close_path();
        path.move_to((10.0, 10.0));
        path.line_to((20.0, 10.0));
        path.line_to((10.0 / 3.0, 20.0));
        path.line_to((10.0, 10.0));
        path.close_path();
        let subs: Vec<BezPath> = subpaths(&path).collect();
        assert_eq!(subs.len(), 2);
        let first = contour(&subs[0]);
        let text: Vec<(f64, f64, PointType)> =
            first.points.iter().map(|p| (p.x, p.y, p.typ)).collect();
        assert_eq!(
            text,
            [
                (100.0, 0.0, PointType::Line),
                (100.0, 50.0, PointType::OffCurve),
                (50.0, 100.0, PointType::OffCurve),
                (0.0, 100.0, PointType::Curve),
                (0.0, 0.0, PointType::Line),
            ]
        );
        // The closing point is the start: no duplicate, and 10/3 is rounded.
        let second = contour(&subs[1]);
        assert_eq!(second.points.len(), 3);
        assert_eq!(second.points[1].x, 3.333);
        assert_eq!(second.points[2].x, 10.0);
    }

    #[test]
    fn smooth_where_tangents_continue() {
        let mut path = BezPath::new();
        path.move_to((0.0, 0.0));
        path.curve_to((0.0, 50.0), (50.0, 100.0), (100.0, 100.0));
        path.curve_to((150.0, 100.0), (200.0, 50.0), (200.0, 0.0));
        path.close_path();
        let c = contour(&path);
        let smooth: Vec<bool> = c.points.iter().map(|p| p.smooth).collect();
        // (100, 100) joins two curves along one tangent; the corners at y = 0 do not.
        assert_eq!(smooth, [false, false, true, false, false, false, false]);
    }
}
