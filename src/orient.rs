//! Contour orientation for the nonzero fill rule.
//!
//! A contour's nesting depth is the number of other contours that contain it wholly: each
//! of its on-curve points and segment midpoints has a nonzero winding number in the other
//! or lies on it (a counter may touch its outer contour at a corner). A contour that runs
//! the other way round from another may also reach outside it by [`SLACK`] of its size and
//! still nest: a counter drawn touching its outer contour that fitting moved across it.
//! Even depth is an outer contour and runs counter-clockwise in y-up font units; odd depth
//! is a counter and runs clockwise, whatever the author's direction (which only decides
//! whether the slack applies). Contours that cross
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

use kurbo::{
    BezPath, CubicBez, ParamCurve, ParamCurveNearest, PathEl, PathSeg, Point, Rect, Shape,
};

/// Version of what [`reversals`] returns: bump it whenever orientation changes (the fit
/// cache stores each glyph's reversals under it).
pub const ORIENT_VERSION: u32 = 3;

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

/// How far outside another contour, as a share of that contour's size (the larger side of
/// its box), a contour may reach and still nest in it when it runs the other way round: a
/// counter drawn touching its outer contour that the fitting moved across it by a hair.
/// Found on an SVG icon (Font Awesome's `buy-n-large`: the B, a counter, touches the
/// ellipse around it, and after the import's fit one corner lay 0.3 units outside it, so
/// the B was filled). 1e-3 of a CJK glyph's 1,000-unit box is one unit.
pub const SLACK: f64 = 1e-3;

/// For each contour, how many of the others contain it: a nonzero winding number around
/// each of its on-curve points and segment midpoints (0 for a contour without points), or,
/// for a contour running the other way round, around each of them or within [`SLACK`] of
/// the other's boundary.
pub fn nesting_depths(contours: &[BezPath]) -> Vec<usize> {
    let boxes: Vec<Rect> = contours.iter().map(padded_box).collect();
    let slacks: Vec<f64> = boxes
        .iter()
        .map(|b| SLACK * b.width().max(b.height()))
        .collect();
    let reach: Vec<Rect> = boxes
        .iter()
        .zip(&slacks)
        .map(|(b, &slack)| b.inflate(slack, slack))
        .collect();
    let mut by_left: Vec<usize> = (0..contours.len()).collect();
    by_left.sort_by(|&a, &b| reach[a].x0.total_cmp(&reach[b].x0));
    let mut probes: Vec<(usize, Point)> = contours
        .iter()
        .enumerate()
        .filter_map(|(i, c)| Some((i, first_point(c)?)))
        .collect();
    // kurbo's area is positive for counter-clockwise contours in y-up coordinates.
    let ccw: Vec<bool> = contours.iter().map(|c| c.area() > 0.0).collect();
    let inside = |j: usize, p: Point| boxes[j].contains(p) && encloses(&contours[j], p);
    let contains = |j: usize, i: usize| {
        if probe_points(&contours[i]).all(|p| inside(j, p)) {
            return true;
        }
        // Only a counter (the other direction) may reach out by the slack, and only one that
        // lies inside somewhere (not a sliver beside the other, within the slack of it). A
        // point on the boundary is within the slack.
        if ccw[i] == ccw[j] {
            return false;
        }
        let mut inside_somewhere = false;
        let within = probe_points(&contours[i]).all(|p| {
            let strictly = boxes[j].contains(p) && winding(contours[j].elements(), p) != 0;
            inside_somewhere |= strictly;
            strictly || near(&contours[j], p, slacks[j])
        });
        within && inside_somewhere
    };
    probes.sort_by(|a, b| a.1.x.total_cmp(&b.1.x));

    let mut depths = vec![0; contours.len()];
    let mut entering = by_left.into_iter().peekable();
    let mut active: Vec<usize> = Vec::new();
    for (i, p) in probes {
        while let Some(j) = entering.next_if(|&j| reach[j].x0 <= p.x) {
            active.push(j);
        }
        active.retain(|&j| reach[j].x1 >= p.x);
        depths[i] = active
            .iter()
            .filter(|&&j| j != i && reach[j].y0 <= p.y && p.y <= reach[j].y1)
            .filter(|&&j| contains(j, i))
            .count();
    }
    depths
}

/// Whether `p` lies within `distance` of the contour `path`'s boundary.
fn near(path: &BezPath, p: Point, distance: f64) -> bool {
    path.segments().any(|seg| {
        seg.bounding_box().inflate(distance, distance).contains(p)
            && seg.nearest(p, 1e-9).distance_sq <= distance * distance
    })
}

/// The winding number of the path `path` (its elements) around `p`: +1 inside a
/// counter-clockwise contour (y up), as kurbo's `Shape::winding`, but exact at the
/// segments' ends.
///
/// Written here rather than taken from kurbo: kurbo cuts each segment at its extrema with
/// `subsegment`, which evaluates the ends again (`p0 + (p1 - p0) · 1` need not be `p1`),
/// so a point level with a vertex can be counted by neither or by both of the segments
/// that meet there. Measured: an SVG icon's counter, whose corner lies at y = 0.6 level
/// with a corner of the outer contour, got winding 0 and was filled. Here a segment keeps
/// its own ends, is cut only at its interior y extrema, and a crossing counts when
/// `p.y` lies in `[low, high)` of the piece.
pub fn winding(path: &[PathEl], p: Point) -> i32 {
    kurbo::segments(path.iter().copied())
        .map(|seg| segment_winding(seg, p))
        .sum()
}

/// One segment's share of [`winding`]: a sum over its pieces monotonic in y.
fn segment_winding(seg: PathSeg, p: Point) -> i32 {
    let cubic = match seg {
        PathSeg::Line(line) => {
            let (a, b) = (line.p0, line.p1);
            let hull = (a.x.min(b.x), a.x.max(b.x));
            return piece_winding(a, b, hull, p, || {
                a.x + (b.x - a.x) * ((p.y - a.y) / (b.y - a.y))
            });
        }
        PathSeg::Quad(quad) => quad.raise(),
        PathSeg::Cubic(cubic) => cubic,
    };
    let xs = [cubic.p0.x, cubic.p1.x, cubic.p2.x, cubic.p3.x];
    let hull = (
        xs.iter().copied().fold(f64::INFINITY, f64::min),
        xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    );
    // The y extrema inside (0, 1): roots of the derivative's y, a quadratic in t.
    let (y0, y1, y2, y3) = (cubic.p0.y, cubic.p1.y, cubic.p2.y, cubic.p3.y);
    let (a, b, c) = (
        3.0 * (-y0 + 3.0 * y1 - 3.0 * y2 + y3),
        6.0 * (y0 - 2.0 * y1 + y2),
        3.0 * (y1 - y0),
    );
    // At most two roots, kept in place: no allocation per segment on this hot path.
    let mut cuts = kurbo::common::solve_quadratic(c, b, a);
    cuts.retain(|t| *t > 0.0 && *t < 1.0);
    cuts.sort_by(f64::total_cmp);
    let mut total = 0;
    let mut start = (0.0, cubic.p0);
    for end in cuts
        .into_iter()
        .map(|t| (t, cubic.eval(t)))
        .chain(std::iter::once((1.0, cubic.p3)))
    {
        total += piece_winding(start.1, end.1, hull, p, || {
            crossing_x(&cubic, start, end, p.y)
        });
        start = end;
    }
    total
}

/// The winding around `p` of one piece monotonic in y, from `a` to `b` (the curve's own
/// points), whose x lies within `hull`; `x_at` gives its x at `p.y`.
fn piece_winding(
    a: Point,
    b: Point,
    hull: (f64, f64),
    p: Point,
    x_at: impl FnOnce() -> f64,
) -> i32 {
    let (sign, low, high) = if b.y > a.y {
        (-1, a.y, b.y)
    } else if b.y < a.y {
        (1, b.y, a.y)
    } else {
        return 0;
    };
    if !(low <= p.y && p.y < high) || p.x < hull.0 {
        return 0;
    }
    if p.x >= hull.1 || p.x >= x_at() {
        sign
    } else {
        0
    }
}

/// The x where the cubic, monotonic in y between `start` and `end` (parameter, point),
/// reaches `y` (within that y range): bisection on the parameter, to the last bit.
fn crossing_x(cubic: &CubicBez, start: (f64, Point), end: (f64, Point), y: f64) -> f64 {
    let rising = end.1.y > start.1.y;
    let (mut lo, mut hi) = (start.0, end.0);
    for _ in 0..64 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if (cubic.eval(mid).y < y) == rising {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    cubic.eval(0.5 * (lo + hi)).x
}

/// Whether `p` lies inside the contour `path` or on it (within a billionth of the
/// coordinates' size): a counter whose corner touches its outer contour (frequent in CJK
/// fonts) still nests. On the boundary the winding number is undefined, and a point there
/// would otherwise be decided by rounding.
fn encloses(path: &BezPath, p: Point) -> bool {
    if winding(path.elements(), p) != 0 {
        return true;
    }
    let eps = 1e-9 * (1.0 + p.x.abs().max(p.y.abs()));
    path.segments().any(|seg| {
        seg.bounding_box().inflate(eps, eps).contains(p)
            && seg.nearest(p, 1e-12).distance_sq <= eps * eps
    })
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
                    .filter(|&(j, other)| {
                        let slack = SLACK * {
                            let b = padded_box(other);
                            b.width().max(b.height())
                        };
                        let counter = (c.area() > 0.0) != (other.area() > 0.0);
                        j != i
                            && (probe_points(c).all(|p| encloses(other, p))
                                || counter
                                    && probe_points(c)
                                        .all(|p| encloses(other, p) || near(other, p, slack))
                                    && probe_points(c).any(|p| winding(other.elements(), p) != 0))
                    })
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
    fn winding_agrees_with_kurbo_away_from_vertex_levels() {
        // Lines, quadratics and cubics with S-bends and loops, probed on a grid whose rows
        // are at no vertex's height: there kurbo's winding is exact too.
        let mut path = BezPath::new();
        path.move_to((0.0, 0.0));
        path.curve_to((300.0, -200.0), (-100.0, 400.0), (200.0, 300.0));
        path.quad_to((400.0, 500.0), (250.0, 100.0));
        path.curve_to((500.0, 300.0), (100.0, -150.0), (320.0, 20.0));
        path.line_to((150.0, -60.0));
        path.close_path();
        path.extend(circle(120.0, 120.0, 50.0).reverse_subpaths());
        let mut nonzero = 0;
        for i in 0..=80 {
            for j in 0..=80 {
                let p = Point::new(
                    -60.0 + 7.3 * f64::from(i),
                    -160.0 + 8.1 * f64::from(j) + 0.0137,
                );
                assert_eq!(winding(path.elements(), p), path.winding(p), "{p:?}");
                nonzero += usize::from(path.winding(p) != 0);
            }
        }
        assert!(nonzero > 1000, "{nonzero}");
    }

    #[test]
    fn a_point_level_with_a_vertex_is_counted_once() {
        // The outer contour of an imported icon (decimal coordinates): a point level with
        // its corners at y = 0.6, where cutting the left edge at its ends moved its end to
        // y = 0.6000000000000227, was outside by kurbo's winding and is inside here.
        let mut outer = BezPath::new();
        outer.move_to((0.0, 661.9));
        outer.line_to((0.0, 0.6));
        outer.curve_to((0.45, -15.02), (1.2, -31.51), (11.75, -54.3));
        outer.line_to((987.53, -55.84));
        outer.curve_to((998.92, -31.85), (999.55, -14.91), (1000.0, 0.6));
        outer.line_to((1000.0, 661.9));
        outer.close_path();
        for x in [0.5, 125.0, 500.0, 875.0, 999.5] {
            assert_eq!(winding(outer.elements(), Point::new(x, 0.6)), 1, "x = {x}");
        }
        assert_eq!(winding(outer.elements(), Point::new(-1.0, 0.6)), 0);
        assert_eq!(winding(outer.elements(), Point::new(1001.0, 0.6)), 0);
        // A counter with a corner on that level nests in it, and is turned clockwise.
        let hole = square(125.0, 0.6, 500.0);
        assert_eq!(nesting_depths(&[outer.clone(), hole.clone()]), [0, 1]);
        let path = orient_contours(vec![outer, hole]);
        let turns: Vec<bool> = path
            .elements()
            .split_inclusive(|e| matches!(e, PathEl::ClosePath))
            .map(|els| BezPath::from_vec(els.to_vec()).area() > 0.0)
            .collect();
        assert_eq!(turns, [true, false]);
    }

    #[test]
    fn a_counter_touching_its_outer_contour_at_a_corner_nests() {
        // As in WenQuanYi's U+9007: the counter's corner lies on a vertex of the outer
        // contour, where a line and a cubic meet; and a second counter touches an edge.
        let mut outer = BezPath::new();
        outer.move_to((0.0, 0.0));
        outer.line_to((100.0, 0.0));
        outer.curve_to((100.0, 20.0), (90.0, 40.0), (100.0, 50.0));
        outer.line_to((100.0, 100.0));
        outer.line_to((0.0, 100.0));
        outer.close_path();
        let mut corner = BezPath::new();
        corner.move_to((60.0, 40.0));
        corner.line_to((100.0, 50.0));
        corner.line_to((60.0, 60.0));
        corner.close_path();
        let mut edge = BezPath::new();
        edge.move_to((10.0, 70.0));
        edge.line_to((0.0, 80.0));
        edge.line_to((10.0, 90.0));
        edge.close_path();
        let contours = vec![outer, corner, edge];
        let depths = nesting_depths(&contours);
        assert_eq!(depths, depths_by_definition(&contours));
        assert_eq!(depths, [0, 1, 1]);
    }

    #[test]
    fn a_counter_reaching_out_by_less_than_the_slack_nests() {
        // The outer square is 100 units: the slack is 0.1. A clockwise counter whose right
        // edge lies 0.05 outside nests; counter-clockwise (an overlapping stroke), or 0.5
        // outside, it crosses and does not.
        let rect = |x1: f64| kurbo::Rect::new(10.0, 10.0, x1, 50.0).to_path(0.1);
        let clockwise = |x1: f64| rect(x1).reverse_subpaths();
        assert!(
            rect(100.05).area() > 0.0,
            "kurbo's rectangles run counter-clockwise"
        );
        let cases = [
            (clockwise(100.05), [0, 1]),
            (rect(100.05), [0, 0]),
            (clockwise(100.5), [0, 0]),
            (clockwise(99.0), [0, 1]),
            // Wholly outside, within the slack of the right edge: a sliver, not a counter.
            (
                kurbo::Rect::new(100.02, 10.0, 100.08, 50.0)
                    .to_path(0.1)
                    .reverse_subpaths(),
                [0, 0],
            ),
        ];
        for (counter, want) in cases {
            let contours = vec![square(0.0, 0.0, 100.0), counter];
            assert_eq!(nesting_depths(&contours), want, "{}", contours[1].to_svg());
            assert_eq!(depths_by_definition(&contours), want);
        }
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
