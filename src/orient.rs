//! Contour orientation for the nonzero fill rule.
//!
//! A contour's nesting depth is the number of other contours that contain it (tested with
//! a point on it). Even depth is an outer contour and runs counter-clockwise in y-up font
//! units; odd depth is a counter and runs clockwise, whatever the author's direction.
//!
//! Limits: contours that cross each other have no well-defined nesting; they are
//! oriented by the depth of their first on-curve point.

use kurbo::{BezPath, PathEl, Shape};

/// Orients closed contours (one subpath each) and joins them into one path.
pub fn orient_contours(contours: Vec<BezPath>) -> BezPath {
    let probes: Vec<_> = contours.iter().map(first_point).collect();
    let mut out = BezPath::new();
    for (i, contour) in contours.iter().enumerate() {
        let depth = contours
            .iter()
            .enumerate()
            .filter(|&(j, other)| j != i && probes[i].is_some_and(|p| other.winding(p) != 0))
            .count();
        // kurbo's area is positive for counter-clockwise contours in y-up coordinates.
        let ccw = contour.area() > 0.0;
        let want_ccw = depth % 2 == 0;
        if ccw == want_ccw {
            out.extend(contour.iter());
        } else {
            out.extend(contour.reverse_subpaths().iter());
        }
    }
    out
}

fn first_point(path: &BezPath) -> Option<kurbo::Point> {
    path.elements().iter().find_map(|el| match el {
        PathEl::MoveTo(p) => Some(*p),
        _ => None,
    })
}
