//! Original outlines -> closed contours, cut into straight edges and smooth stretches.
//!
//! A contour's joins are classified by the angle between the incoming and outgoing
//! tangent: above [`CORNER_DEGREES`] (and at cusps) the join is a corner. Both ends of a
//! straight segment are always break points, so a straight edge becomes exactly two
//! consecutive `s = 0` points in the X-spline (which is a straight line). Between break
//! points lies either one straight edge or a smooth run of curves.
//!
//! Limits: zero-length segments are dropped; curves whose control points lie on their chord
//! become lines; collinear consecutive lines are merged. A contour that encloses nothing
//! (fewer than three distinct break points and no curve) is dropped by the caller.

use kurbo::{BezPath, Line, ParamCurve, PathEl, PathSeg, Point, Vec2};

/// Joins that turn by more than this are corners (`s = 0` points). TrueType smooth points
/// stored on an integer grid deviate by well under a degree for normal handle lengths.
pub const CORNER_DEGREES: f64 = 4.0;

/// Segments shorter than this (font units) are dropped.
const MIN_LENGTH: f64 = 1e-6;

/// One closed contour of the original outline: segments end to end, the last ending where
/// the first starts.
#[derive(Clone, Debug)]
pub struct SourceContour {
    /// The contour's segments, in order.
    pub segs: Vec<PathSeg>,
}

/// A piece of a contour between two break points.
#[derive(Clone, Debug)]
pub enum Piece {
    /// A straight edge (its start is a break point).
    Edge(Line),
    /// A smooth run of curves from one break point to the next.
    Smooth(Vec<PathSeg>),
}

/// How a contour is cut: a cycle of pieces starting at a break point, or one smooth loop
/// when the contour has no break point at all.
#[derive(Clone, Debug)]
pub enum Cut {
    /// Pieces between corners (sharp points).
    Pieces(Vec<Piece>),
    /// A smooth closed loop with no corner.
    Loop(Vec<PathSeg>),
}

/// Closed contours of `path` (open subpaths are closed by a line, as filling does).
pub fn contours(path: &BezPath) -> Vec<SourceContour> {
    raw_contours(path)
        .into_iter()
        .map(|segs| SourceContour { segs: clean(segs) })
        .filter(|c| !c.segs.is_empty())
        .collect()
}

/// The subpaths of `path` as segment lists, each closed by a line back to its start when
/// it does not end there, not yet cleaned.
fn raw_contours(path: &BezPath) -> Vec<Vec<PathSeg>> {
    let mut out = Vec::new();
    let mut segs: Vec<PathSeg> = Vec::new();
    let mut start = Point::ZERO;
    let mut last = Point::ZERO;
    let mut finish = |segs: &mut Vec<PathSeg>, last: Point, start: Point| {
        if segs.is_empty() {
            return;
        }
        if last != start {
            segs.push(PathSeg::Line(Line::new(last, start)));
        }
        out.push(std::mem::take(segs));
    };
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => {
                finish(&mut segs, last, start);
                start = p;
                last = p;
            }
            PathEl::LineTo(p) => {
                segs.push(PathSeg::Line(Line::new(last, p)));
                last = p;
            }
            PathEl::QuadTo(c, p) => {
                segs.push(PathSeg::Quad(kurbo::QuadBez::new(last, c, p)));
                last = p;
            }
            PathEl::CurveTo(c1, c2, p) => {
                segs.push(PathSeg::Cubic(kurbo::CubicBez::new(last, c1, c2, p)));
                last = p;
            }
            PathEl::ClosePath => {
                finish(&mut segs, last, start);
                last = start;
            }
        }
    }
    finish(&mut segs, last, start);
    out
}

/// The closed contours of several masters' outlines of one glyph, cleaned alike so that
/// they keep one structure: contour `i` has the same segment kinds in every master. A
/// curve becomes a line only where it is straight in every master; a segment is dropped
/// where it is degenerate in one master and no longer than `tiny` in all (a closing line
/// a TrueType contour has at one location and not at another); collinear lines merge only
/// where they are collinear in every master. `Err` says how the outlines differ (they do
/// not interpolate as Béziers either).
pub fn compatible_contours(
    paths: &[&BezPath],
    tiny: f64,
) -> Result<Vec<Vec<SourceContour>>, String> {
    let raw: Vec<Vec<Vec<PathSeg>>> = paths.iter().map(|p| raw_contours(p)).collect();
    let count = raw[0].len();
    if let Some((m, other)) = raw.iter().enumerate().find(|(_, r)| r.len() != count) {
        return Err(format!(
            "master {m} has {} contours, the default {count}",
            other.len()
        ));
    }
    let mut out: Vec<Vec<SourceContour>> = vec![Vec::new(); paths.len()];
    for c in 0..count {
        // A contour closed by a line in one master and not in another (its last point on
        // its first there): the missing line is a zero-length line.
        let len = raw.iter().map(|r| r[c].len()).max().unwrap_or(0);
        let mut masters: Vec<Vec<PathSeg>> = Vec::with_capacity(raw.len());
        for r in &raw {
            let mut segs = r[c].clone();
            if segs.len() + 1 == len && len > 1 {
                let p = segs[0].start();
                segs.push(PathSeg::Line(Line::new(p, p)));
            }
            masters.push(segs);
        }
        let kinds = |segs: &[PathSeg]| segs.iter().map(kind).collect::<Vec<_>>();
        let first = kinds(&masters[0]);
        if let Some(m) = masters.iter().position(|s| kinds(s) != first) {
            return Err(format!(
                "contour {c}: master {m} has other segments than the default ({} against {})",
                describe(&masters[m]),
                describe(&masters[0])
            ));
        }
        for (out, segs) in out.iter_mut().zip(clean_joint(masters, tiny)) {
            if !segs.is_empty() {
                out.push(SourceContour { segs });
            }
        }
    }
    Ok(out)
}

/// 0 for a line, 1 for a quadratic, 2 for a cubic.
fn kind(seg: &PathSeg) -> u8 {
    match seg {
        PathSeg::Line(_) => 0,
        PathSeg::Quad(_) => 1,
        PathSeg::Cubic(_) => 2,
    }
}

/// `L`, `Q`, `C` per segment, for messages.
fn describe(segs: &[PathSeg]) -> String {
    segs.iter()
        .map(|s| ["L", "Q", "C"][usize::from(kind(s))])
        .collect()
}

/// [`clean`] for one contour in several masters at once, deciding every step for all.
fn clean_joint(masters: Vec<Vec<PathSeg>>, tiny: f64) -> Vec<Vec<PathSeg>> {
    let n = masters[0].len();
    let mut keep = Vec::with_capacity(n);
    let mut lines = Vec::with_capacity(n);
    for i in 0..n {
        let straight = masters
            .iter()
            .all(|m| matches!(flatten_if_straight(m[i]), PathSeg::Line(_)));
        lines.push(straight);
        let extent = |seg: PathSeg| chord(seg).hypot().max(max_control_offset(seg));
        let degenerate = masters.iter().any(|m| extent(m[i]) < MIN_LENGTH);
        let small = masters.iter().all(|m| extent(m[i]) <= tiny);
        keep.push(!(degenerate && small));
    }
    let mut out: Vec<Vec<PathSeg>> = masters
        .into_iter()
        .map(|m| {
            let mut segs: Vec<PathSeg> = m
                .into_iter()
                .zip(&lines)
                .zip(&keep)
                .filter(|(_, &k)| k)
                .map(|((seg, &line), _)| {
                    if line {
                        PathSeg::Line(Line::new(seg.start(), seg.end()))
                    } else {
                        seg
                    }
                })
                .collect();
            let n = segs.len();
            for i in 0..n {
                let end = segs[i].end();
                set_start(&mut segs[(i + 1) % n], end);
            }
            segs
        })
        .collect();
    // Merge lines collinear in every master.
    let mut changed = true;
    while changed && out[0].len() > 1 {
        changed = false;
        let n = out[0].len();
        let collinear = |segs: &[PathSeg], i: usize| match (segs[i], segs[(i + 1) % n]) {
            (PathSeg::Line(a), PathSeg::Line(b)) => turn_degrees(a.p1 - a.p0, b.p1 - b.p0) < 1e-6,
            _ => false,
        };
        if let Some(i) = (0..n).find(|&i| out.iter().all(|m| collinear(m, i))) {
            let j = (i + 1) % n;
            for segs in &mut out {
                if let (PathSeg::Line(a), PathSeg::Line(b)) = (segs[i], segs[j]) {
                    segs[i] = PathSeg::Line(Line::new(a.p0, b.p1));
                    segs.remove(j);
                }
            }
            changed = true;
        }
    }
    out
}

/// Stored points of a contour as a font file counts them: on-curve plus off-curve points,
/// where a quadratic's end point that is the midpoint of its control and the next
/// quadratic's control is implied (TrueType does not store it).
pub fn stored_points(segs: &[PathSeg]) -> usize {
    let n = segs.len();
    let mut count = 0;
    for (i, seg) in segs.iter().enumerate() {
        count += match seg {
            PathSeg::Line(l) => usize::from(l.p0 != l.p1),
            PathSeg::Cubic(_) => 3,
            PathSeg::Quad(q) => {
                let implied = match segs[(i + 1) % n] {
                    PathSeg::Quad(next) if n > 1 => {
                        let mid = q.p1.midpoint(next.p1);
                        (mid - q.p2).hypot() <= 1e-9 * (1.0 + mid.to_vec2().hypot())
                    }
                    _ => false,
                };
                if implied {
                    1
                } else {
                    2
                }
            }
        };
    }
    count
}

/// Drops zero-length segments, turns flat curves into lines, merges collinear lines.
fn clean(segs: Vec<PathSeg>) -> Vec<PathSeg> {
    let mut out: Vec<PathSeg> = Vec::new();
    for seg in segs {
        let seg = flatten_if_straight(seg);
        if chord(seg).hypot() < MIN_LENGTH && max_control_offset(seg) < MIN_LENGTH {
            continue;
        }
        out.push(seg);
    }
    // Re-link the ends after dropping pieces so the chain stays closed.
    let n = out.len();
    for i in 0..n {
        let end = out[i].end();
        let next = (i + 1) % n;
        set_start(&mut out[next], end);
    }
    merge_collinear(out)
}

fn merge_collinear(mut segs: Vec<PathSeg>) -> Vec<PathSeg> {
    let mut changed = true;
    while changed && segs.len() > 1 {
        changed = false;
        let n = segs.len();
        for i in 0..n {
            let j = (i + 1) % n;
            if let (PathSeg::Line(a), PathSeg::Line(b)) = (segs[i], segs[j]) {
                let (da, db) = (a.p1 - a.p0, b.p1 - b.p0);
                if turn_degrees(da, db) < 1e-6 {
                    segs[i] = PathSeg::Line(Line::new(a.p0, b.p1));
                    segs.remove(j);
                    changed = true;
                    break;
                }
            }
        }
    }
    segs
}

fn set_start(seg: &mut PathSeg, p: Point) {
    match seg {
        PathSeg::Line(l) => l.p0 = p,
        PathSeg::Quad(q) => q.p0 = p,
        PathSeg::Cubic(c) => c.p0 = p,
    }
}

fn chord(seg: PathSeg) -> Vec2 {
    seg.end() - seg.start()
}

/// Largest distance of a control point from the segment's start (zero for lines).
fn max_control_offset(seg: PathSeg) -> f64 {
    match seg {
        PathSeg::Line(_) => 0.0,
        PathSeg::Quad(q) => (q.p1 - q.p0).hypot(),
        PathSeg::Cubic(c) => (c.p1 - c.p0).hypot().max((c.p2 - c.p0).hypot()),
    }
}

/// A curve whose control points lie on its chord (between its ends) is a line.
fn flatten_if_straight(seg: PathSeg) -> PathSeg {
    let controls: Vec<Point> = match seg {
        PathSeg::Line(_) => return seg,
        PathSeg::Quad(q) => vec![q.p1],
        PathSeg::Cubic(c) => vec![c.p1, c.p2],
    };
    let (a, b) = (seg.start(), seg.end());
    let d = b - a;
    let len2 = d.hypot2();
    if len2 == 0.0 {
        return seg;
    }
    let straight = controls.iter().all(|&c| {
        let v = c - a;
        let along = v.dot(d) / len2;
        let off = v.cross(d).abs() / len2.sqrt();
        (0.0..=1.0).contains(&along) && off <= 1e-9 * (1.0 + len2.sqrt())
    });
    if straight {
        PathSeg::Line(Line::new(a, b))
    } else {
        seg
    }
}

/// Angle in degrees between two directions (0 = straight on, 180 = reversal).
pub fn turn_degrees(a: Vec2, b: Vec2) -> f64 {
    let (la, lb) = (a.hypot(), b.hypot());
    if la == 0.0 || lb == 0.0 {
        return 180.0;
    }
    (a.dot(b) / (la * lb)).clamp(-1.0, 1.0).acos().to_degrees()
}

/// Unit-free direction in which a segment leaves its start (first non-coincident control).
pub fn start_tangent(seg: PathSeg) -> Vec2 {
    let pts: Vec<Point> = match seg {
        PathSeg::Line(l) => vec![l.p0, l.p1],
        PathSeg::Quad(q) => vec![q.p0, q.p1, q.p2],
        PathSeg::Cubic(c) => vec![c.p0, c.p1, c.p2, c.p3],
    };
    pts[1..]
        .iter()
        .map(|&p| p - pts[0])
        .find(|v| v.hypot() > MIN_LENGTH)
        .unwrap_or(Vec2::ZERO)
}

/// Direction in which a segment arrives at its end.
pub fn end_tangent(seg: PathSeg) -> Vec2 {
    -start_tangent(seg.reverse())
}

/// Cuts a contour into edges and smooth stretches at corners and line ends.
pub fn cut(contour: &SourceContour) -> Cut {
    cut_at(contour, &breaks(contour))
}

/// Whether the join at the start of each segment is a break point: an end of a straight
/// segment, or a turn above [`CORNER_DEGREES`].
pub fn breaks(contour: &SourceContour) -> Vec<bool> {
    turns(contour)
        .into_iter()
        .map(|t| t > CORNER_DEGREES)
        .collect()
}

/// The turn in degrees at the start of each segment; 180 at an end of a straight segment
/// (always a break point).
fn turns(contour: &SourceContour) -> Vec<f64> {
    let segs = &contour.segs;
    let n = segs.len();
    (0..n)
        .map(|i| {
            let prev = segs[(i + n - 1) % n];
            let cur = segs[i];
            if matches!(prev, PathSeg::Line(_)) || matches!(cur, PathSeg::Line(_)) {
                180.0
            } else {
                turn_degrees(end_tangent(prev), start_tangent(cur))
            }
        })
        .collect()
}

/// The break points of one contour in several masters (one structure): a join whose
/// turn, averaged over the masters, is above [`CORNER_DEGREES`], or that turns by more
/// than three times that in some master (a corner there, whatever the others do). Not
/// simply a corner in any master: quadratic outlines rounded to integers kink smooth
/// joins by a few degrees here and there (two joins of the bundled Bold `O`'s counter turn
/// by 5.3° and 4.1°, the Regular's by 0.6° and 0.1°), and a sharp point at each such kink
/// splits a smooth loop into stretches that need more points.
///
/// With `every_corner`, a corner in any master is a break point (the importer's second
/// choice, when a kink the first choice smooths over cannot be followed).
pub fn compatible_breaks(masters: &[&SourceContour], every_corner: bool) -> Vec<bool> {
    let all: Vec<Vec<f64>> = masters.iter().map(|c| turns(c)).collect();
    (0..all[0].len())
        .map(|i| {
            let mean = all.iter().map(|t| t[i]).sum::<f64>() / all.len() as f64;
            let most = all.iter().map(|t| t[i]).fold(0.0, f64::max);
            let limit = if every_corner { 1.0 } else { 3.0 };
            mean > CORNER_DEGREES || most > limit * CORNER_DEGREES
        })
        .collect()
}

/// Cuts a contour at the given break points (`breaks[i]`: at the start of segment `i`;
/// the ends of every line must be among them). Masters cut at the union of their break
/// points get the same pieces.
pub fn cut_at(contour: &SourceContour, breaks: &[bool]) -> Cut {
    let segs = &contour.segs;
    let n = segs.len();
    let Some(first) = breaks.iter().position(|&b| b) else {
        return Cut::Loop(segs.clone());
    };
    let mut pieces = Vec::new();
    let mut run: Vec<PathSeg> = Vec::new();
    for k in 0..n {
        let i = (first + k) % n;
        if breaks[i] && !run.is_empty() {
            pieces.push(Piece::Smooth(std::mem::take(&mut run)));
        }
        match segs[i] {
            PathSeg::Line(l) => pieces.push(Piece::Edge(l)),
            seg => run.push(seg),
        }
    }
    if !run.is_empty() {
        pieces.push(Piece::Smooth(run));
    }
    Cut::Pieces(pieces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::Shape;

    #[test]
    fn truetype_point_counts() {
        // On (0,0), off (100,0), off (100,100) [implied on (100,50)], on (0,100), line back.
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.quad_to((100.0, 0.0), (100.0, 50.0));
        p.quad_to((100.0, 100.0), (0.0, 100.0));
        p.line_to((0.0, 0.0));
        p.close_path();
        let c = contours(&p);
        assert_eq!(c.len(), 1);
        assert_eq!(stored_points(&c[0].segs), 4);
        match cut(&c[0]) {
            Cut::Pieces(pieces) => {
                assert_eq!(pieces.len(), 2);
                assert!(matches!(pieces[0], Piece::Smooth(ref s) if s.len() == 2));
                assert!(matches!(pieces[1], Piece::Edge(_)));
            }
            Cut::Loop(_) => panic!("has corners"),
        }
    }

    #[test]
    fn cleaning_and_cutting() {
        // Collinear lines merge, zero-length lines go; a rectangle is four edges.
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.line_to((50.0, 0.0));
        p.line_to((100.0, 0.0));
        p.line_to((100.0, 0.0));
        p.line_to((100.0, 80.0));
        p.line_to((0.0, 80.0));
        p.close_path();
        let c = contours(&p);
        assert_eq!(c[0].segs.len(), 4);
        assert!(matches!(cut(&c[0]), Cut::Pieces(ref v) if v.len() == 4));
        // A circle has no break point; a lone point is no contour.
        let circle = kurbo::Circle::new((0.0, 0.0), 10.0).to_path(1e-9);
        assert!(matches!(cut(&contours(&circle)[0]), Cut::Loop(_)));
        let mut dot = BezPath::new();
        dot.move_to((5.0, 5.0));
        dot.line_to((5.0, 5.0));
        dot.close_path();
        assert!(contours(&dot).is_empty());
        assert_eq!(turn_degrees(Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)), 90.0);
    }
}
