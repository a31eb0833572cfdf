//! Contour orientation for the nonzero fill rule.
//!
//! A contour's nesting depth is the number of other contours that contain it wholly: each
//! of its on-curve points and segment midpoints has a nonzero winding number in the other.
//! Even depth is an outer contour and runs counter-clockwise in y-up font units; odd depth
//! is a counter and runs clockwise, whatever the author's direction. Contours that cross
//! (some of their points inside the other, some outside) do not nest: both keep the depth
//! of their surroundings, so two overlapping strokes are both filled and their overlap too,
//! as a type designer draws them before overlap removal.
//!
//! Finding the containers: a contour can only contain a point inside its bounding box, so
//! the exact winding test runs only on contours whose box holds the point. The boxes are
//! found by a sweep in x (boxes sorted by left edge enter, and leave once the sweep is past
//! their right edge), so a glyph of n separate contours costs O(n log n) plus the boxes that
//! share an x range with each point, instead of n² winding tests. Limits: contours nested
//! k deep still cost k winding tests each (a stack of 8,000 concentric rings is quadratic,
//! as the answer itself is). A container found by the first point is confirmed on the
//! contour's other points, so the extra winding tests are paid only by nested contours. The
//! test samples points, not the whole boundary: a contour that leaves its container only
//! between two samples (a crossing narrower than half a segment) counts as nested.

use kurbo::{BezPath, ParamCurve, PathEl, Point, Rect, Shape};

/// Version of what [`reversals`] returns: bump it whenever orientation changes (the fit
/// cache stores each glyph's reversals under it).
pub const ORIENT_VERSION: u32 = 1;

/// Orients closed contours (one subpath each) and joins them into one path.
pub fn orient_contours(contours: Vec<BezPath>) -> BezPath {
    let reversed = reversals(&contours);
    join_reversed(&contours, &reversed)
}

/// Which contours [`orient_contours`] reverses: those whose direction disagrees with their
/// nesting depth (even depth counter-clockwise, odd clockwise).
pub fn reversals(contours: &[BezPath]) -> Vec<bool> {
    let depths = nesting_depths(contours);
    contours
        .iter()
        .zip(depths)
        .map(|(contour, depth)| {
            // kurbo's area is positive for counter-clockwise contours in y-up coordinates.
            let ccw = contour.area() > 0.0;
            let want_ccw = depth % 2 == 0;
            ccw != want_ccw
        })
        .collect()
}

/// The contours joined into one path, each flagged in `reversed` turned around (a contour
/// without a flag is kept as it is).
pub fn join_reversed(contours: &[BezPath], reversed: &[bool]) -> BezPath {
    // One allocation of the final length: a CJK font joins 20,902 glyphs on every build.
    let len = contours.iter().map(|c| c.elements().len()).sum();
    let mut out = Vec::with_capacity(len);
    for (k, contour) in contours.iter().enumerate() {
        if reversed.get(k).copied().unwrap_or(false) {
            out.extend_from_slice(contour.reverse_subpaths().elements());
        } else {
            out.extend_from_slice(contour.elements());
        }
    }
    BezPath::from_vec(out)
}

/// For each contour, how many of the others contain it wholly: a nonzero winding number
/// around each of its on-curve points and segment midpoints (0 for a contour without points).
pub fn nesting_depths(contours: &[BezPath]) -> Vec<usize> {
    let boxes: Vec<Rect> = contours.iter().map(padded_box).collect();
    let mut by_left: Vec<usize> = (0..contours.len()).collect();
    by_left.sort_by(|&a, &b| boxes[a].x0.total_cmp(&boxes[b].x0));
    let mut probes: Vec<(usize, Point)> = contours
        .iter()
        .enumerate()
        .filter_map(|(i, c)| Some((i, first_point(c)?)))
        .collect();
    let contains = |j: usize, i: usize| {
        probe_points(&contours[i]).all(|p| boxes[j].contains(p) && contours[j].winding(p) != 0)
    };
    probes.sort_by(|a, b| a.1.x.total_cmp(&b.1.x));

    let mut depths = vec![0; contours.len()];
    let mut entering = by_left.into_iter().peekable();
    let mut active: Vec<usize> = Vec::new();
    for (i, p) in probes {
        while let Some(j) = entering.next_if(|&j| boxes[j].x0 <= p.x) {
            active.push(j);
        }
        active.retain(|&j| boxes[j].x1 >= p.x);
        depths[i] = active
            .iter()
            .filter(|&&j| j != i && boxes[j].y0 <= p.y && p.y <= boxes[j].y1)
            .filter(|&&j| contours[j].winding(p) != 0 && contains(j, i))
            .count();
    }
    depths
}

/// The contour's bounding box, grown by a hair so that rounding in the box (computed from
/// curve extrema) never excludes a point the winding test would count.
fn padded_box(path: &BezPath) -> Rect {
    let r = path.bounding_box();
    let size = r.x0.abs().max(r.x1.abs()).max(r.y0.abs()).max(r.y1.abs());
    r.inflate(1e-9 * (1.0 + size), 1e-9 * (1.0 + size))
}

/// The points that decide whether a contour lies inside another: each segment's end point
/// and midpoint.
fn probe_points(path: &BezPath) -> impl Iterator<Item = Point> + '_ {
    path.segments()
        .flat_map(|seg| [seg.eval(0.5), seg.eval(1.0)])
}

fn first_point(path: &BezPath) -> Option<Point> {
    path.elements().iter().find_map(|el| match el {
        PathEl::MoveTo(p) => Some(*p),
        _ => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definition, every pair tested: the reference for the sweep.
    fn depths_by_definition(contours: &[BezPath]) -> Vec<usize> {
        contours
            .iter()
            .enumerate()
            .map(|(i, c)| {
                if first_point(c).is_none() {
                    return 0;
                }
                contours
                    .iter()
                    .enumerate()
                    .filter(|&(j, other)| j != i && probe_points(c).all(|p| other.winding(p) != 0))
                    .count()
            })
            .collect()
    }

    fn square(x: f64, y: f64, side: f64) -> BezPath {
        let mut p = BezPath::new();
        p.move_to((x, y));
        p.line_to((x + side, y));
        p.line_to((x + side, y + side));
        p.line_to((x, y + side));
        p.close_path();
        p
    }

    fn circle(cx: f64, cy: f64, r: f64) -> BezPath {
        kurbo::Circle::new((cx, cy), r).to_path(0.1)
    }

    #[test]
    fn rings_and_dots_match_the_definition() {
        // Concentric rings, dots inside and outside, shapes touching at box edges, and a
        // curve whose box is set by its extrema (circles), in a shuffled order.
        let mut contours = vec![
            square(0.0, 0.0, 100.0),
            circle(50.0, 50.0, 40.0),
            circle(50.0, 50.0, 30.0),
            square(45.0, 45.0, 10.0),
            square(100.0, 0.0, 10.0),
            square(-20.0, -20.0, 5.0),
            circle(150.0, 50.0, 20.0),
            square(140.0, 40.0, 20.0),
            square(10.0, 10.0, 0.0),
        ];
        contours.push(BezPath::new());
        let depths = nesting_depths(&contours);
        assert_eq!(depths, depths_by_definition(&contours));
        // A point on another contour's corner is outside it (kurbo's winding rule).
        assert_eq!(depths, [0, 1, 2, 3, 0, 0, 0, 1, 1, 0]);
    }

    #[test]
    fn a_grid_of_contours_matches_the_definition() {
        // 20 x 20 cells, each two rings around a dot; every third cell has a third ring
        // that overlaps its neighbours.
        let mut contours = Vec::new();
        for i in 0..20 {
            for j in 0..20 {
                let (x, y) = (f64::from(i) * 30.0, f64::from(j) * 30.0);
                if (i + j) % 3 == 0 {
                    contours.push(circle(x, y, 25.0));
                }
                contours.push(circle(x, y, 12.0));
                contours.push(circle(x, y, 8.0));
                contours.push(square(x - 2.0, y - 2.0, 4.0));
            }
        }
        let depths = nesting_depths(&contours);
        assert_eq!(depths, depths_by_definition(&contours));
        assert_eq!(depths.iter().max(), Some(&3));
    }

    #[test]
    fn crossing_contours_do_not_nest() {
        // An X of two bars (each has a corner inside the other), a bar through a ring's
        // counter, and a dot inside the crossing: only wholly enclosed contours nest.
        let bar = |x0: f64, y0: f64, x1: f64, y1: f64| {
            let mut p = BezPath::new();
            p.move_to((x0, y0));
            p.line_to((x1, y0));
            p.line_to((x1, y1));
            p.line_to((x0, y1));
            p.close_path();
            p
        };
        let contours = vec![
            bar(0.0, 40.0, 100.0, 60.0),
            bar(40.0, 0.0, 60.0, 100.0),
            square(48.0, 48.0, 4.0),
            circle(300.0, 50.0, 40.0),
            circle(300.0, 50.0, 30.0),
            bar(250.0, 45.0, 350.0, 55.0),
        ];
        let depths = nesting_depths(&contours);
        assert_eq!(depths, depths_by_definition(&contours));
        assert_eq!(depths, [0, 0, 2, 0, 1, 0]);
        // Both bars counter-clockwise: the overlap is filled twice under nonzero.
        let path = orient_contours(contours[..2].to_vec());
        assert_eq!(path.winding(Point::new(50.0, 50.0)), 2);
    }

    #[test]
    fn orientation_follows_depth() {
        // Both given clockwise: the outer one is turned counter-clockwise, the hole kept.
        let outer = square(0.0, 0.0, 10.0).reverse_subpaths();
        let hole = square(2.0, 2.0, 6.0).reverse_subpaths();
        let path = orient_contours(vec![outer, hole]);
        let areas: Vec<f64> = path
            .elements()
            .split_inclusive(|e| matches!(e, PathEl::ClosePath))
            .map(|els| BezPath::from_vec(els.to_vec()).area())
            .collect();
        assert_eq!(areas, [100.0, -36.0]);
    }
}
