//! On-curve points at the extrema: every fitted cubic that turns back in x or in y inside
//! its span is split there, so the outline has a point at each horizontal and vertical
//! extreme, as type designers draw them and as font tools check them (FontForge's
//! "Missing points at extrema", Adobe's and Google Fonts' production guides; TrueType
//! rasterisers and autohinters rely on them).
//!
//! A split is exact: the two pieces are the same curve (de Casteljau), so no error is
//! added to the fit. The handles on both sides of a new point are set exactly on its
//! vertical (an x extreme) or horizontal (a y extreme), so that rounding to the font's
//! grid keeps them there.
//!
//! A family splits every master at the default master's extrema, at the same parameter
//! ([`split_plan_for`], [`apply_plan`]): splitting is linear in the control points, so the
//! blend of the split masters is exactly the split blend, and every instance keeps the
//! outline the compatible fitter checked. The default master (and so the static fonts
//! built from it) has its points exactly at its extrema; another master has them at the
//! same place of each curve, near its own extrema.
//!
//! Limits: an extreme closer than [`MIN_PIECE`] em to a cubic's end is not split off (the
//! piece would round to nothing on the grid; its overshoot past that end is smaller
//! still). The static fitter moves a join that falls that near an extreme onto it
//! (`crate::fit`), so such an extreme is left only beside a sharp point or a cusp, or where
//! the moved cubic would not fit. In a family, a split that would leave such a piece in
//! any master, or a piece running the other way, is not made (the compatible fitter does
//! not move its joins). Rounding to the grid can still give a monotone curve a faint
//! extreme (a handle rounded a unit past its end point).

use kurbo::{BezPath, CubicBez, ParamCurve, ParamCurveDeriv, PathEl, Point};

/// Smallest piece a split may leave, as a fraction of the em (1 unit at 1000 per em).
pub const MIN_PIECE: f64 = 1e-3;

/// Where one element of a path is split: its index in the path's elements and the
/// parameters of the splits, ascending in (0, 1).
pub type Split = (usize, Vec<f64>);

/// `path` with every cubic split at its interior extrema (pieces at least `min_piece`
/// font units long).
pub fn add_extrema(path: &BezPath, min_piece: f64) -> BezPath {
    let plan = split_plan(path, min_piece);
    if plan.is_empty() {
        return path.clone();
    }
    apply_plan(path, &plan, true)
}

/// Where [`add_extrema`] splits `path`'s cubics.
pub fn split_plan(path: &BezPath, min_piece: f64) -> Vec<Split> {
    split_plan_for(&[path], min_piece)
}

/// Where to split masters of one structure: at the extrema of `paths[0]` (the default
/// master), where every master's pieces are at least `min_piece` long and run the same way
/// as the default's (so that no blend of them folds a piece to a point).
pub fn split_plan_for(paths: &[&BezPath], min_piece: f64) -> Vec<Split> {
    let Some(first) = paths.first() else {
        return Vec::new();
    };
    let cubics = |path: &BezPath, i: usize| -> Option<CubicBez> {
        let els = path.elements();
        let PathEl::CurveTo(p1, p2, p3) = *els.get(i)? else {
            return None;
        };
        Some(CubicBez::new(
            els.get(..i)?.last()?.end_point()?,
            p1,
            p2,
            p3,
        ))
    };
    let mut plan = Vec::new();
    for (i, el) in first.elements().iter().enumerate() {
        if !matches!(el, PathEl::CurveTo(..)) {
            continue;
        }
        let Some(all) = paths
            .iter()
            .map(|p| cubics(p, i))
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let ts = keep_whole_pieces(&all, extrema(&all[0]), min_piece);
        if !ts.is_empty() {
            plan.push((i, ts));
        }
    }
    plan
}

/// The splits of `candidates` (ascending) that leave no piece shorter than `min_piece`
/// (chord) in any of `cubics`, nor one that runs the other way than in `cubics[0]`.
fn keep_whole_pieces(cubics: &[CubicBez], candidates: Vec<f64>, min_piece: f64) -> Vec<f64> {
    let mut kept: Vec<f64> = Vec::with_capacity(candidates.len());
    let mut from = 0.0;
    let fits = |c: &CubicBez, c0: &CubicBez, a: f64, b: f64| {
        let chord = c.eval(b) - c.eval(a);
        let chord0 = c0.eval(b) - c0.eval(a);
        chord.hypot() >= min_piece && chord.dot(chord0) > 0.0
    };
    for t in candidates {
        if cubics
            .iter()
            .all(|c| fits(c, &cubics[0], from, t) && fits(c, &cubics[0], t, 1.0))
        {
            kept.push(t);
            from = t;
        }
    }
    kept
}

/// `path` with the cubics of `plan` split at its parameters. `path` must have the
/// elements `plan` was made from (another master of the same structure). With `snap`,
/// the handles at each new point are put on its tangent's axis (the path the plan was made
/// from, whose new points are its extrema).
pub fn apply_plan(path: &BezPath, plan: &[Split], snap: bool) -> BezPath {
    let els = path.elements();
    let mut out = Vec::with_capacity(els.len() + plan.iter().map(|s| s.1.len()).sum::<usize>());
    let mut next = plan.iter().peekable();
    let mut last = Point::ZERO;
    for (i, el) in els.iter().enumerate() {
        match (*el, next.peek()) {
            (PathEl::CurveTo(p1, p2, p3), Some((at, ts))) if *at == i => {
                let cubic = CubicBez::new(last, p1, p2, p3);
                let mut t0 = 0.0;
                let mut pieces: Vec<CubicBez> = Vec::with_capacity(ts.len() + 1);
                for &t in ts.iter().chain(std::iter::once(&1.0)) {
                    pieces.push(cubic.subsegment(t0..t));
                    t0 = t;
                }
                if snap {
                    for k in 1..pieces.len() {
                        snap_join(&cubic, ts[k - 1], &mut pieces, k);
                    }
                }
                out.extend(pieces.iter().map(|c| PathEl::CurveTo(c.p1, c.p2, c.p3)));
                next.next();
                last = p3;
            }
            (el, _) => {
                match el {
                    PathEl::MoveTo(p) | PathEl::LineTo(p) | PathEl::QuadTo(_, p) => last = p,
                    PathEl::CurveTo(_, _, p) => last = p,
                    PathEl::ClosePath => {}
                }
                out.push(el);
            }
        }
    }
    BezPath::from_vec(out)
}

/// Puts the handles on both sides of the join between `pieces[k - 1]` and `pieces[k]`
/// (at `t` of `cubic`) exactly on the join's vertical or horizontal, whichever its
/// tangent is closer to. The change is the rounding error of the split (the tangent's
/// other component is zero there up to rounding).
fn snap_join(cubic: &CubicBez, t: f64, pieces: &mut [CubicBez], k: usize) {
    let d = cubic.deriv().eval(t);
    let join = pieces[k].p0;
    if d.x.abs() <= d.y.abs() {
        pieces[k - 1].p2.x = join.x;
        pieces[k].p1.x = join.x;
    } else {
        pieces[k - 1].p2.y = join.y;
        pieces[k].p1.y = join.y;
    }
    pieces[k - 1].p3 = join;
}

/// The parameters in (0, 1) where `c` turns back in x or in y (a simple root of the
/// derivative's component: a tangent that only touches the axis is no extreme), ascending.
fn extrema(c: &CubicBez) -> Vec<f64> {
    let mut ts: Vec<f64> = Vec::new();
    for axis in [0, 1] {
        let coord = |p: Point| if axis == 0 { p.x } else { p.y };
        let (p0, p1, p2, p3) = (coord(c.p0), coord(c.p1), coord(c.p2), coord(c.p3));
        // Within the end points' range, the handles cannot make an extreme (and rounding
        // could make a faint one).
        let (lo, hi) = (p0.min(p3), p0.max(p3));
        if (lo..=hi).contains(&p1) && (lo..=hi).contains(&p2) {
            continue;
        }
        // The derivative / 3 = a t² + b t + c.
        let a = -p0 + 3.0 * p1 - 3.0 * p2 + p3;
        let b = 2.0 * (p0 - 2.0 * p1 + p2);
        let cc = p1 - p0;
        for t in kurbo::common::solve_quadratic(cc, b, a) {
            let slope = 2.0 * a * t + b;
            let scale = a.abs() + b.abs() + cc.abs();
            if t > 0.0 && t < 1.0 && slope.abs() > 1e-9 * scale {
                ts.push(t);
            }
        }
    }
    ts.sort_by(f64::total_cmp);
    ts
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::ParamCurveExtrema;

    fn bowl() -> BezPath {
        // A quarter-circle-like bowl whose x extreme is inside the cubic.
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.curve_to((300.0, 0.0), (400.0, 300.0), (100.0, 500.0));
        p.line_to((0.0, 500.0));
        p.close_path();
        p
    }

    #[test]
    fn a_bowl_gets_a_point_at_its_right_extreme_on_the_same_curve() {
        let path = bowl();
        let split = add_extrema(&path, 1.0);
        let els = split.elements();
        assert_eq!(els.len(), 5, "{els:?}");
        let (PathEl::CurveTo(_, h0, e), PathEl::CurveTo(h1, _, _)) = (els[1], els[2]) else {
            panic!("{els:?}")
        };
        // The new point is the curve's rightmost point, with vertical handles.
        let cubic = CubicBez::new((0.0, 0.0), (300.0, 0.0), (400.0, 300.0), (100.0, 500.0));
        let t = cubic.extrema()[0];
        let right = cubic.eval(t);
        assert!((e - right).hypot() < 1e-12, "{e:?} {right:?}");
        let xmax = (0..=10_000)
            .map(|k| cubic.eval(f64::from(k) / 10_000.0).x)
            .fold(f64::MIN, f64::max);
        // The true maximum; dense samples come within their spacing squared of it.
        assert!(e.x >= xmax && e.x - xmax < 1e-5, "{} {xmax}", e.x);
        assert_eq!((h0.x, h1.x), (e.x, e.x));
        // Both pieces trace the original curve.
        let PathEl::CurveTo(a1, ..) = els[1] else {
            unreachable!()
        };
        let PathEl::CurveTo(_, b2, b3) = els[2] else {
            unreachable!()
        };
        let (a, b) = (cubic.subsegment(0.0..t), cubic.subsegment(t..1.0));
        let (on_a, on_b) = (
            CubicBez::new(cubic.p0, a1, h0, e),
            CubicBez::new(e, h1, b2, b3),
        );
        for k in 0..=100 {
            let u = f64::from(k) / 100.0;
            assert!((on_a.eval(u) - a.eval(u)).hypot() < 1e-9);
            assert!((on_b.eval(u) - b.eval(u)).hypot() < 1e-9);
        }
    }

    #[test]
    fn a_monotone_cubic_and_a_touching_tangent_are_left_alone() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.curve_to((100.0, 0.0), (200.0, 100.0), (200.0, 300.0));
        // Inflection with a vertical tangent that does not turn back: x' = 3(1-2t)²·k ≥ 0.
        p.curve_to((200.0, 400.0), (200.0, 500.0), (400.0, 600.0));
        assert_eq!(add_extrema(&p, 1.0), p);
    }

    #[test]
    fn an_extreme_near_an_end_is_not_split_off() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        // Leaves going slightly left, then turns right: the x minimum is within a unit.
        p.curve_to((-1.0, 100.0), (300.0, 200.0), (400.0, 200.0));
        assert_eq!(add_extrema(&p, 1.0), p);
        assert_eq!(split_plan(&p, 0.001).len(), 1);
    }

    #[test]
    fn masters_split_at_the_default_plan_blend_exactly() {
        let regular = bowl();
        let bold = Affine::scale_non_uniform(1.3, 0.9) * bowl();
        let plan = split_plan(&regular, 1.0);
        let (r, b) = (
            apply_plan(&regular, &plan, true),
            apply_plan(&bold, &plan, false),
        );
        assert_eq!(r.elements().len(), b.elements().len());
        // Halfway, the blend of the split masters is the split of the blend.
        let mid = |p: Point, q: Point| p.midpoint(q);
        let blend = BezPath::from_vec(
            regular
                .elements()
                .iter()
                .zip(bold.elements())
                .map(|(x, y)| match (*x, *y) {
                    (PathEl::CurveTo(a, b, c), PathEl::CurveTo(d, e, f)) => {
                        PathEl::CurveTo(mid(a, d), mid(b, e), mid(c, f))
                    }
                    (PathEl::MoveTo(a), PathEl::MoveTo(d)) => PathEl::MoveTo(mid(a, d)),
                    (PathEl::LineTo(a), PathEl::LineTo(d)) => PathEl::LineTo(mid(a, d)),
                    (el, _) => el,
                })
                .collect(),
        );
        let split_blend = apply_plan(&blend, &plan, false);
        for (x, (y, z)) in split_blend
            .elements()
            .iter()
            .zip(r.elements().iter().zip(b.elements()))
        {
            if let (PathEl::CurveTo(_, _, p), PathEl::CurveTo(_, _, q), PathEl::CurveTo(_, _, s)) =
                (*x, *y, *z)
            {
                assert!((p - mid(q, s)).hypot() < 1e-9, "{p:?} {q:?} {s:?}");
            }
        }
    }

    use kurbo::Affine;
}
