//! Flattening: vertices on the curve, exact sharp points, chords within the tolerance both
//! ways (dense sampling of the true curve), and adaptive vertex counts.

use crate::common::curves;

use curves::{hausdorff, seed, spline};
use kurbo::{BezPath, Line, ParamCurve, ParamCurveNearest, Point};
use proptest::prelude::*;
use xglyph::flatten::{flatten, Polyline};
use xglyph::xspline::XSpline;

/// The closed polyline's edges with the parameter interval each one stands for.
fn edges(spline: &XSpline, poly: &Polyline) -> Vec<(Line, f64, f64)> {
    let n = poly.points.len();
    (0..n)
        .map(|i| {
            let j = (i + 1) % n;
            let tb = if j == 0 {
                spline.segment_count() as f64
            } else {
                poly.params[j]
            };
            (
                Line::new(poly.points[i], poly.points[j]),
                poly.params[i],
                tb,
            )
        })
        .collect()
}

/// Two-sided distance: 400 curve samples per segment against the polyline, and 50 points
/// per edge against the curve on that edge's own interval (2000 samples, then a local
/// scan around the best), which is stricter than against the whole curve.
fn distance(spline: &XSpline, poly: &Polyline) -> f64 {
    let edges = edges(spline, poly);
    let mut err: f64 = 0.0;
    for i in 0..spline.segment_count() * 400 {
        let p = spline.eval(i as f64 / 400.0);
        let d = edges
            .iter()
            .map(|(l, ..)| l.nearest(p, 1e-12).distance_sq.sqrt())
            .fold(f64::INFINITY, f64::min);
        err = err.max(d);
    }
    for (line, ta, tb) in &edges {
        for k in 0..=50 {
            let q = line.eval(k as f64 / 50.0);
            let at = |i: usize, m: usize, lo: f64, hi: f64| lo + (hi - lo) * i as f64 / m as f64;
            let (mut best_t, mut best) = (*ta, f64::INFINITY);
            for i in 0..=2000 {
                let t = at(i, 2000, *ta, *tb);
                let d = spline.eval(t).distance(q);
                if d < best {
                    (best_t, best) = (t, d);
                }
            }
            let h = (tb - ta) / 2000.0;
            for i in 0..=200 {
                let t = at(i, 200, best_t - h, best_t + h).clamp(*ta, *tb);
                best = best.min(spline.eval(t).distance(q));
            }
            err = err.max(best);
        }
    }
    err
}

#[test]
fn sharp_points_are_exact_vertices_and_straight_edges_one_chord() {
    // A "D": a straight stem between two sharp points and an interpolated bowl.
    let d = spline(&[
        (80.0, 0.0, 0.0),
        (330.0, 0.0, -1.0),
        (600.0, 350.0, -1.0),
        (330.0, 700.0, -1.0),
        (80.0, 700.0, 0.0),
    ]);
    let poly = flatten(&d, 0.5);
    assert_eq!(poly.points[0], Point::new(80.0, 0.0));
    let stem_top = poly.params.iter().position(|&t| t == 4.0).unwrap();
    assert_eq!(poly.points[stem_top], Point::new(80.0, 700.0));
    // The stem (T in [4, 5]) is a straight line: no vertex inside it.
    assert_eq!(stem_top, poly.points.len() - 1);
    for (p, &t) in poly.points.iter().zip(&poly.params) {
        assert_eq!(*p, d.eval(t), "vertex off the curve at T = {t}");
    }
    assert!(poly.params.windows(2).all(|w| w[0] < w[1]));
    assert!(distance(&d, &poly) <= 0.5);
}

#[test]
fn vertex_count_follows_the_square_root_law() {
    // A round contour: chords of length h deviate by ~h^2 / (8 r), so a quarter of the
    // tolerance needs about twice the vertices. A fixed step would not change at all.
    let o = spline(&[
        (280.0, -12.0, -1.0),
        (520.0, 250.0, -1.0),
        (280.0, 512.0, -1.0),
        (40.0, 250.0, -1.0),
    ]);
    let coarse = flatten(&o, 0.5).points.len() as f64;
    let fine = flatten(&o, 0.125).points.len() as f64;
    println!("vertices: {coarse} at 0.5, {fine} at 0.125");
    assert!((1.6..=2.5).contains(&(fine / coarse)), "{coarse} -> {fine}");
    assert!(distance(&o, &flatten(&o, 0.125)) <= 0.125);
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 64,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed()),
        .. ProptestConfig::default()
    })]

    #[test]
    fn random_contours_flatten_within_tolerance(contour in curves::random_contour()) {
        let Some((xs, scale)) = contour else {
            return Err(TestCaseError::reject("fewer than three distinct points"));
        };
        let tol = 0.5 * scale / 1000.0;
        let poly = flatten(&xs, tol);
        for (p, &t) in poly.points.iter().zip(&poly.params) {
            prop_assert!(p.is_finite() && *p == xs.eval(t), "vertex {:?} off the curve", p);
        }
        for p in xs.points().iter().filter(|p| p.is_sharp()) {
            prop_assert!(poly.points.contains(&p.pos), "sharp point {:?} is not a vertex", p.pos);
        }
        let mut path = BezPath::new();
        path.move_to(poly.points[0]);
        for p in &poly.points[1..] {
            path.line_to(*p);
        }
        path.close_path();
        let err = hausdorff(&xs, &path, 50);
        prop_assert!(err <= tol, "measured {} > tol {}", err, tol);
    }
}
