//! The X-spline model against the golden vectors of docs/xspline.md (q = -s/2).

use kurbo::Point;
use xglyph::xspline::{weights_with_deriv, Basis, ControlPoint, XSpline, XSplineError};

fn square(s: [f64; 4]) -> XSpline {
    let p = [(0.0, 0.0), (100.0, 0.0), (100.0, 100.0), (0.0, 100.0)];
    XSpline::new(
        (0..4)
            .map(|i| ControlPoint::new(p[i].0, p[i].1, s[i]))
            .collect(),
    )
    .unwrap()
}

/// Shapes `s0..s3` and the expected segment-0 points at t = 0, 1/4, 1/2, 3/4.
type SquareRow = ([f64; 4], [(f64, f64); 4]);

#[test]
fn square_golden_vectors() {
    let table: [SquareRow; 7] = [
        (
            [1.0; 4],
            [
                (16.666666666667, 16.666666666667),
                (31.008333333333, 7.816666666667),
                (50.0, 4.619565217391),
                (68.991666666667, 7.816666666667),
            ],
        ),
        (
            [0.0; 4],
            [
                (0.0, 0.0),
                (9.243697478992, 0.0),
                (50.0, 0.0),
                (90.756302521008, 0.0),
            ],
        ),
        (
            [-1.0; 4],
            [
                (0.0, 0.0),
                (19.43359375, -7.6171875),
                (50.0, -9.375),
                (80.56640625, -7.6171875),
            ],
        ),
        (
            [0.5; 4],
            [
                (10.679611650485, 10.679611650485),
                (28.240109140518, 1.652266181598),
                (50.0, 0.0),
                (71.759890859482, 1.652266181598),
            ],
        ),
        (
            [-0.5; 4],
            [
                (0.0, 0.0),
                (14.524291497976, -3.947368421053),
                (50.0, -5.0),
                (85.475708502024, -3.947368421053),
            ],
        ),
        (
            [1.0, -1.0, 0.0, 0.5],
            [
                (16.666666666667, 16.666666666667),
                (30.936641483516, 7.044127747253),
                (52.403846153846, -1.121794871795),
                (79.991807116105, -5.928136704120),
            ],
        ),
        (
            [-1.0, 1.0, -0.5, 0.0],
            [
                (0.0, 0.0),
                (20.008192883895, -5.928136704120),
                (47.596153846154, -1.121794871795),
                (69.063358516484, 7.044127747253),
            ],
        ),
    ];
    for (s, expected) in table {
        let xs = square(s);
        for (i, e) in expected.iter().enumerate() {
            // Golden values have 12 decimals; compare at 1e-9.
            let p = xs.segment(0).eval(i as f64 / 4.0);
            assert!(
                (p.x - e.0).abs() < 1e-9 && (p.y - e.1).abs() < 1e-9,
                "s={s:?} t={i}/4: {p:?} != {e:?}"
            );
        }
    }
}

#[test]
fn pentagon_golden_vectors() {
    let p = [
        (0.0, 0.0),
        (100.0, 0.0),
        (130.0, 70.0),
        (60.0, 120.0),
        (-20.0, 80.0),
    ];
    let s = [0.7, -0.6, 1.0, -1.0, 0.3];
    let xs = XSpline::new(
        (0..5)
            .map(|i| ControlPoint::new(p[i].0, p[i].1, s[i]))
            .collect(),
    )
    .unwrap();
    let expected = [
        [
            (11.360324911513, 11.360324911513),
            (29.544557371108, 3.388296743263),
            (54.866427728123, -1.279463798778),
            (83.347250842349, -2.728144690086),
        ],
        [
            (100.0, 0.0),
            (108.323298929664, 11.243788226300),
            (113.887434554974, 32.840314136126),
            (115.558048039757, 51.935739922695),
        ],
        [
            (113.333333333333, 66.666666666667),
            (106.591689560440, 80.321085164835),
            (95.576923076923, 95.833333333333),
            (78.944288389513, 112.249531835206),
        ],
        [
            (60.0, 120.0),
            (39.442560201397, 115.211078138608),
            (16.941554982055, 102.118585956003),
            (-2.110645005379, 89.684448828400),
        ],
        [
            (-14.666612130588, 77.866644852235),
            (-15.313337398795, 61.363721231519),
            (-10.063890621214, 42.218107634253),
            (-1.542341409436, 24.352780990371),
        ],
    ];
    for (j, row) in expected.iter().enumerate() {
        for (i, e) in row.iter().enumerate() {
            let p = xs.eval(j as f64 + i as f64 / 4.0);
            assert!(
                (p.x - e.0).abs() < 1e-9 && (p.y - e.1).abs() < 1e-9,
                "seg {j} t={i}/4: {p:?} != {e:?}"
            );
        }
    }
}

#[test]
fn basis_reproduces_the_pentagon_golden_vectors() {
    // The pentagon's segment-1 golden points, through the closed and the open basis.
    let p: Vec<Point> = [
        (0.0, 0.0),
        (100.0, 0.0),
        (130.0, 70.0),
        (60.0, 120.0),
        (-20.0, 80.0),
    ]
    .iter()
    .map(|&q| q.into())
    .collect();
    let s = [0.7, -0.6, 1.0, -1.0, 0.3];
    let expected = [
        (100.0, 0.0),
        (108.323298929664, 11.243788226300),
        (113.887434554974, 32.840314136126),
        (115.558048039757, 51.935739922695),
    ];
    let xs = XSpline::new(
        (0..5)
            .map(|i| ControlPoint::new(p[i].x, p[i].y, s[i]))
            .collect(),
    )
    .unwrap();
    for (i, e) in expected.iter().enumerate() {
        let big_t = 1.0 + i as f64 / 4.0;
        let b = Basis::closed(5, |k| s[k], big_t);
        assert_eq!(b, xs.basis(big_t));
        assert_eq!(b.index, [0, 1, 2, 3]);
        assert!((b.weight.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        let (q, d) = b.eval_deriv(&p);
        assert!(
            (q.x - e.0).abs() < 1e-9 && (q.y - e.1).abs() < 1e-9,
            "{q:?} != {e:?}"
        );
        // The derivative is the exact one of XSpline::eval_deriv.
        let (q2, d2) = xs.eval_deriv(big_t);
        assert!(
            (q - q2).hypot() < 1e-12 && (d - d2).hypot() < 1e-9,
            "{d:?} != {d2:?}"
        );
        // Wrapping: T + 5 is the same point.
        assert_eq!(Basis::closed(5, |k| s[k], big_t + 5.0).index, b.index);
    }
    // An open chain with sharp ends is that stretch of a closed contour: points 0..=2 of
    // the square with shapes (0, 1, 0), against the closed triangle (0, 1, 0).
    let chain = [p[0], p[1], p[2]];
    let shapes = [0.0, 1.0, 0.0];
    let closed = XSpline::new(
        (0..3)
            .map(|i| ControlPoint::new(p[i].x, p[i].y, shapes[i]))
            .collect(),
    )
    .unwrap();
    for k in 0..=20 {
        let big_t = k as f64 * 0.1;
        let b = Basis::open(3, |k| shapes[k], big_t);
        assert!(b.index.iter().all(|&i| i < 3));
        let (q, _) = b.eval_deriv(&chain);
        assert!((q - closed.eval(big_t)).hypot() < 1e-9, "T = {big_t}");
    }
    // The open basis clamps: before the start is the start, past the end the end.
    assert_eq!(
        Basis::open(3, |k| shapes[k], -1.0).eval_deriv(&chain).0,
        p[0]
    );
    assert_eq!(
        Basis::open(3, |k| shapes[k], 7.0).eval_deriv(&chain).0,
        p[2]
    );
}

#[test]
fn raw_weights() {
    let cases: [(f64, f64, f64, [f64; 4]); 6] = [
        (0.0, 1.0, 1.0, [0.25, 1.0, 0.25, 0.0]),
        (
            0.5,
            1.0,
            1.0,
            [17.0 / 512.0, 351.0 / 512.0, 351.0 / 512.0, 17.0 / 512.0],
        ),
        (0.5, 0.0, 0.0, [0.0, 7.0 / 16.0, 7.0 / 16.0, 0.0]),
        (
            0.5,
            -1.0,
            -1.0,
            [-3.0 / 64.0, 35.0 / 64.0, 35.0 / 64.0, -3.0 / 64.0],
        ),
        (
            0.25,
            0.5,
            -0.5,
            [109.0 / 5184.0, 3513.0 / 4096.0, 23.0 / 64.0, -21.0 / 4096.0],
        ),
        (
            0.75,
            -0.5,
            0.5,
            [-21.0 / 4096.0, 23.0 / 64.0, 3513.0 / 4096.0, 109.0 / 5184.0],
        ),
    ];
    for (t, s1, s2, expected) in cases {
        let w = weights_with_deriv(t, s1, s2);
        for i in 0..4 {
            assert!(
                (w[i].0 - expected[i]).abs() < 1e-12,
                "t={t} s=({s1},{s2}) A{i}: {} != {}",
                w[i].0,
                expected[i]
            );
        }
    }
}

const SHAPES: [f64; 7] = [-1.0, -0.6, -0.25, 0.0, 0.3, 0.75, 1.0];

#[test]
fn weight_sum_never_below_seven_eighths_and_symmetry() {
    for &s1 in &SHAPES {
        for &s2 in &SHAPES {
            for i in 0..=64 {
                let t = i as f64 / 64.0;
                let w = weights_with_deriv(t, s1, s2);
                let sum: f64 = w.iter().map(|x| x.0).sum();
                assert!(sum >= 0.875 - 1e-12, "sum {sum} at t={t} s=({s1},{s2})");
                let m = weights_with_deriv(1.0 - t, s2, s1);
                for k in 0..4 {
                    assert!(
                        (w[k].0 - m[3 - k].0).abs() < 1e-12,
                        "symmetry A{k} t={t} s=({s1},{s2})"
                    );
                }
            }
        }
    }
}

#[test]
fn derivative_matches_finite_differences() {
    for &s1 in &SHAPES {
        for &s2 in &SHAPES {
            let xs = square([0.2, s1, s2, -0.4]);
            let seg = xs.segment(1);
            for i in 1..32 {
                let t = i as f64 / 32.0;
                let h = 1e-6;
                let fd = (seg.eval(t + h) - seg.eval(t - h)) / (2.0 * h);
                let d = seg.eval_deriv(t).1;
                assert!(
                    (d - fd).hypot() < 1e-4 * (1.0 + d.hypot()),
                    "s=({s1},{s2}) t={t}: {d:?} vs {fd:?}"
                );
            }
        }
    }
}

#[test]
fn joins_are_c2_between_smooth_points() {
    let p = [
        (0.0, 0.0),
        (100.0, 10.0),
        (140.0, 90.0),
        (50.0, 130.0),
        (-30.0, 70.0),
    ];
    for &s in &[-1.0, -0.5, 0.4, 1.0] {
        let xs = XSpline::new(
            (0..5)
                .map(|i| ControlPoint::new(p[i].0, p[i].1, s))
                .collect(),
        )
        .unwrap();
        for j in 1..5 {
            let t = j as f64;
            // One-sided differences of the exact derivative, Richardson-extrapolated
            // (error O(h^2)): the second derivative from each side agrees, i.e. C2.
            let d = |x: f64| xs.eval_deriv(x).1;
            let left = |h: f64| (d(t) - d(t - h)) / h;
            let right = |h: f64| (d(t + h) - d(t)) / h;
            let h = 1e-3;
            let d2l = 2.0 * left(h / 2.0) - left(h);
            let d2r = 2.0 * right(h / 2.0) - right(h);
            assert!(
                (d2l - d2r).hypot() < 1e-3 * (1.0 + d2l.hypot()),
                "s={s} join {j}: {d2l:?} vs {d2r:?}"
            );
            let (pl, dl) = xs.segment(j - 1).eval_deriv(1.0);
            let (pr, dr) = xs.segment(j).eval_deriv(0.0);
            assert!(
                (pl - pr).hypot() < 1e-9 && (dl - dr).hypot() < 1e-9,
                "C0/C1 at join {j}"
            );
        }
    }
}

#[test]
fn sharp_points_are_interpolated_and_straight_between_two() {
    let xs = square([0.0, 0.0, 1.0, -1.0]);
    let seg = xs.segment(0);
    assert_eq!(seg.eval(0.0), Point::new(0.0, 0.0));
    assert_eq!(seg.eval(1.0), Point::new(100.0, 0.0));
    for i in 0..=16 {
        assert!(
            seg.eval(i as f64 / 16.0).y.abs() < 1e-12,
            "edge between two sharp points is straight"
        );
    }
}

#[test]
fn sharp_points_are_exact_to_the_bit() {
    // Found by a random flattening test: with the weights summed first and divided after,
    // this corner came out one unit in the last place off (980.7387269841226).
    let xs = XSpline::new(vec![
        ControlPoint::new(0.0, 0.0, -1.0),
        ControlPoint::new(7250.653562890337, 0.0, -1.0),
        ControlPoint::new(980.7387269841225, 0.0, 0.0),
        ControlPoint::new(0.0, 5101.522537701239, -0.9530157444650398),
    ])
    .unwrap();
    let corner = Point::new(980.7387269841225, 0.0);
    assert_eq!(xs.eval(2.0), corner);
    assert_eq!(xs.eval_deriv(2.0).0, corner);
    assert_eq!(xs.segment(1).eval(1.0), corner);
}

#[test]
fn corner_tangent_tilts_toward_q3_when_next_shape_is_negative() {
    // s1 = 0, s2 = -1: departure direction 8 (Q2 - Q1) - 2q (Q3 - Q1) with q = 1/2.
    let xs = square([0.5, 0.0, -1.0, 0.5]);
    let seg = xs.segment(1); // Q0..Q3 = P0, P1, P2, P3
    let dir = seg.start_direction();
    let expected =
        (8.0 * kurbo::Vec2::new(0.0, 100.0) - 1.0 * kurbo::Vec2::new(-100.0, 100.0)).normalize();
    assert!((dir - expected).hypot() < 1e-12, "{dir:?} vs {expected:?}");
    let numeric = (seg.eval(1e-4) - seg.eval(0.0)).normalize();
    assert!(
        (dir - numeric).hypot() < 1e-3,
        "{dir:?} vs finite {numeric:?}"
    );
    let back = xs.segment(0).end_direction();
    let numeric_back = (xs.segment(0).eval(1.0) - xs.segment(0).eval(1.0 - 1e-4)).normalize();
    assert!(
        (back - numeric_back).hypot() < 1e-3,
        "{back:?} vs {numeric_back:?}"
    );
}

#[test]
fn invalid_contours_are_rejected() {
    let ok = |x, y, s| ControlPoint::new(x, y, s);
    assert_eq!(
        XSpline::new(vec![ok(0.0, 0.0, 0.0), ok(1.0, 0.0, 0.0)]),
        Err(XSplineError::TooFewPoints { count: 2 })
    );
    assert_eq!(
        XSpline::new(vec![
            ok(0.0, 0.0, 0.0),
            ok(1.0, f64::NAN, 0.0),
            ok(0.0, 1.0, 0.0)
        ]),
        Err(XSplineError::NonFinite { index: 1 })
    );
    assert_eq!(
        XSpline::new(vec![
            ok(0.0, 0.0, 0.0),
            ok(1.0, 0.0, 1.5),
            ok(0.0, 1.0, 0.0)
        ]),
        Err(XSplineError::ShapeOutOfRange { index: 1, s: 1.5 })
    );
    assert_eq!(
        XSpline::new(vec![
            ok(0.0, 0.0, 0.0),
            ok(1.0, 0.0, 0.0),
            ok(0.0, 0.0, 0.0)
        ]),
        Err(XSplineError::CoincidentPoints { index: 2, next: 0 })
    );
}
