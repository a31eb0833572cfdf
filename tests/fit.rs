//! Cubic fitting against the true X-spline: two-sided distance by dense sampling.

use kurbo::{BezPath, ParamCurve, ParamCurveNearest, PathEl, PathSeg, Point, Shape};
use proptest::prelude::*;
use xglyph::fit::fit_contour;
use xglyph::orient::orient_contours;
use xglyph::xspline::{ControlPoint, XSpline};

/// Distance from `p` to the nearest segment of `path`.
fn dist_to_path(path: &BezPath, p: Point) -> f64 {
    path.segments()
        .map(|s| s.nearest(p, 1e-9).distance_sq.sqrt())
        .fold(f64::INFINITY, f64::min)
}

/// Two-sided sampled distance: 200 samples per X-spline segment against the path, and
/// 200 samples per path segment against a dense polyline of the true curve refined by
/// a nested scan of the curve parameter.
fn hausdorff(spline: &XSpline, path: &BezPath) -> f64 {
    let n = spline.segment_count();
    let mut dense: Vec<(f64, Point)> = (0..n * 200)
        .map(|i| {
            let t = i as f64 / 200.0;
            (t, spline.eval(t))
        })
        .collect();
    let gap = dense
        .windows(2)
        .map(|w| w[0].1.distance(w[1].1))
        .fold(0.0, f64::max)
        .max(dense[0].1.distance(dense[dense.len() - 1].1));
    let mut err: f64 = 0.0;
    for (_, p) in &dense {
        err = err.max(dist_to_path(path, *p));
    }
    // Sorted by x, so a query only scans the samples within its distance in x.
    dense.sort_by(|a, b| a.1.x.total_cmp(&b.1.x));
    for seg in path.segments() {
        for i in 0..=200 {
            let q = seg.eval(i as f64 / 200.0);
            err = err.max(dist_to_curve(spline, &dense, gap, q));
        }
    }
    err
}

/// The dense samples (sorted by x) whose x lies within `r` of `q.x`.
fn x_window(dense: &[(f64, Point)], q: Point, r: f64) -> &[(f64, Point)] {
    let lo = dense.partition_point(|(_, p)| p.x < q.x - r);
    let hi = dense.partition_point(|(_, p)| p.x <= q.x + r);
    &dense[lo..hi]
}

/// Distance from `q` to the true curve: on every branch of the curve that comes within one
/// sample gap of the nearest sample's distance (loops and crossings have several), a
/// nested scan of the curve parameter around the branch's closest sample (3 levels of 20
/// steps; no Newton, which can jump between branches).
fn dist_to_curve(spline: &XSpline, dense: &[(f64, Point)], gap: f64, q: Point) -> f64 {
    // Grow the window until it holds a sample; that sample bounds the nearest distance.
    let mut r = gap.max(1e-300);
    let mut nearest = f64::INFINITY;
    loop {
        for (_, p) in x_window(dense, q, r) {
            nearest = nearest.min(p.distance(q));
        }
        if nearest <= r || r > 1e300 {
            break;
        }
        r = nearest.min(r * 4.0);
    }
    // A branch's nearest sample is at most one sample gap farther than its nearest point.
    // Candidates in curve order; every local minimum of the distance along the curve is
    // refined (a branch may dip more than once).
    let mut near: Vec<(f64, f64)> = x_window(dense, q, nearest + gap)
        .iter()
        .map(|(t, p)| (*t, p.distance(q)))
        .filter(|(_, d)| *d <= nearest + gap)
        .collect();
    near.sort_by(|a, b| a.0.total_cmp(&b.0));
    let step = 1.0 / 200.0;
    let mut best = nearest;
    for k in 0..near.len() {
        // A local minimum of the distance along the curve (neighbours in t only).
        let lower = |j: usize| near[j].1 < near[k].1 && (near[j].0 - near[k].0).abs() < 1.5 * step;
        if (k > 0 && lower(k - 1)) || (k + 1 < near.len() && lower(k + 1)) {
            continue;
        }
        let (mut centre, mut half) = (near[k].0, step);
        for _ in 0..3 {
            let mut local = (centre, f64::INFINITY);
            for i in 0..=20 {
                let t = centre - half + 2.0 * half * i as f64 / 20.0;
                let d = spline.eval(t).distance(q);
                if d < local.1 {
                    local = (t, d);
                }
            }
            best = best.min(local.1);
            centre = local.0;
            half /= 10.0;
        }
    }
    best
}

fn spline(points: &[(f64, f64, f64)]) -> XSpline {
    XSpline::new(
        points
            .iter()
            .map(|&(x, y, s)| ControlPoint::new(x, y, s))
            .collect(),
    )
    .unwrap()
}

#[test]
fn glyph_like_contour_within_tolerance_with_exact_corners_and_lines() {
    // A "D"-like contour: a straight stem (two sharp pairs) and a round bowl.
    let xs = spline(&[
        (0.0, 0.0, 0.0),
        (300.0, 0.0, -1.0),
        (520.0, 350.0, -1.0),
        (300.0, 700.0, -1.0),
        (0.0, 700.0, 0.0),
    ]);
    let fit = fit_contour(&xs, 0.5);
    let err = hausdorff(&xs, &fit.path);
    assert!(err <= 0.5, "measured {err}");
    assert!(fit.max_error <= 0.5);
    let els = fit.path.elements();
    assert_eq!(els[0], PathEl::MoveTo(Point::new(0.0, 0.0)));
    assert_eq!(*els.last().unwrap(), PathEl::ClosePath);
    // The stem (P4 -> P0) is a line ending exactly at the corner.
    assert_eq!(els[els.len() - 2], PathEl::LineTo(Point::new(0.0, 0.0)));
    // Every sharp point is an on-curve point.
    let ends: Vec<Point> = fit.path.segments().map(|s| s.end()).collect();
    assert!(ends.contains(&Point::new(0.0, 700.0)));
}

#[test]
fn joins_inside_smooth_stretches_are_g1() {
    let xs = spline(&[
        (0.0, 0.0, -1.0),
        (400.0, -50.0, 1.0),
        (600.0, 300.0, -0.5),
        (350.0, 650.0, 0.5),
        (-100.0, 400.0, -1.0),
    ]);
    let fit = fit_contour(&xs, 0.2);
    let segs: Vec<PathSeg> = fit.path.segments().collect();
    assert!(segs.len() > 5, "{} segments", segs.len());
    for w in 0..segs.len() {
        let (a, b) = (segs[w], segs[(w + 1) % segs.len()]);
        let (PathSeg::Cubic(a), PathSeg::Cubic(b)) = (a, b) else {
            panic!("expected cubics")
        };
        let ta = (a.p3 - a.p2).normalize();
        let tb = (b.p1 - b.p0).normalize();
        assert!(
            ta.cross(tb).abs() < 1e-9 && ta.dot(tb) > 0.0,
            "join {w}: {ta:?} vs {tb:?}"
        );
    }
    assert!(hausdorff(&xs, &fit.path) <= 0.2);
}

#[test]
fn corner_with_interpolating_neighbour_has_no_hook() {
    // s = 0 next to s = -1: the departure tilts toward Q3; a fitted cubic must follow it.
    let xs = spline(&[
        (0.0, 0.0, 0.0),
        (100.0, 0.0, -1.0),
        (100.0, 100.0, 0.5),
        (0.0, 100.0, -1.0),
    ]);
    let fit = fit_contour(&xs, 0.05);
    assert!(hausdorff(&xs, &fit.path) <= 0.05);
    let PathSeg::Cubic(first) = fit.path.segments().next().unwrap() else {
        panic!()
    };
    let dir = (first.p1 - first.p0).normalize();
    assert!((dir - xs.segment(0).start_direction()).hypot() < 1e-12);
}

#[test]
fn thin_spike_tips_are_not_missed() {
    // Found by a random proptest seed: thin spikes (twin points pulled far apart in y),
    // whose tips turn through 180 degrees between two uniform curve samples. The fitter
    // measured 0.94 of the tolerance; the tip at T = 21 was 1.15 of it away.
    let xs = spline(&[
        (
            0.011111381422633161,
            7.246155741526516e-5,
            0.6061189567403473,
        ),
        (0.01111143875041748, 0.07246155746450188, 0.702971246077714),
        (
            0.04049494618157882,
            7.819697533923445e-5,
            -0.8090270456599957,
        ),
        (0.04049504210441912, 0.0581969754591902, 0.31693275800498144),
        (0.07706339883526703, 7.682174252530237e-5, 1.0),
        (0.07706343434391982, 0.03682174262230228, -1.0),
        (
            0.09074767535237986,
            8.438918436026242e-5,
            -0.23616198209965011,
        ),
        (
            0.0907477409984784,
            0.024389184503350484,
            0.11486377495832212,
        ),
        (0.05163070679601189, 0.0001527696938530234, -1.0),
        (0.05163074057492709, 0.07276969400882398, 0.0),
        (
            0.028979368870199508,
            0.00016059725891206476,
            0.19092761680383052,
        ),
        (
            0.028979396305475576,
            0.060597259049691016,
            0.5126851725865331,
        ),
        (0.029438729667439024, 0.0001248072748418119, 1.0),
        (0.02943882247100284, 0.004807275011544732, -0.5),
        (
            0.0661976051648558,
            0.00020427471111410367,
            -0.2220136741608998,
        ),
        (0.06619769465369318, 0.06427471131657514, -1.0),
        (
            0.04728760759454473,
            0.0001708385760990777,
            0.5469856277422473,
        ),
        (0.04728762531593051, 0.010838576300019895, 0.5),
        (
            0.05797776943550131,
            0.0002740049745422053,
            0.05099143544754625,
        ),
        (0.05797780717487736, 0.09400497483156595, 0.3428459225111753),
        (0.06936185554333411, 0.00028853551718564617, 0.5),
        (0.0693619153561112, 0.08853551742881244, 0.5),
        (
            0.06849436182578841,
            0.0002865351302561596,
            0.20911219027662975,
        ),
        (
            0.06849438412971841,
            0.06653513055004352,
            -0.025578625553430046,
        ),
        (0.05124960023527983, 0.00031358194099911885, 0.0),
        (0.05124963685093068, 0.07358194132438366, -0.5),
        (
            0.08554084159238796,
            0.0003203103468624323,
            -0.872945496491571,
        ),
        (
            0.08554092016961616,
            0.060310347160799686,
            -0.3723675196518128,
        ),
        (0.0038332752768712175, 0.00034051177304408945, -0.5),
        (0.0038333226506631086, 0.06051177342719404, 1.0),
        (0.0316245674889688, 0.000393155051944504, 0.0),
        (
            0.03162466330921344,
            0.09315505226327307,
            -0.6825320322879422,
        ),
        (0.012115610741452232, 0.0003656754888473156, -1.0),
        (
            0.012115656411888583,
            0.045675489179273616,
            0.045256838617719675,
        ),
    ]);
    let tol = 5e-5;
    let fit = fit_contour(&xs, tol);
    let err = hausdorff(&xs, &fit.path);
    assert!(err <= tol, "measured {} of the tolerance", err / tol);
}

#[test]
fn orientation_outer_ccw_counter_cw() {
    let outer = spline(&[
        (280.0, -12.0, -1.0),
        (40.0, 250.0, -1.0),
        (280.0, 512.0, -1.0),
        (520.0, 250.0, -1.0),
    ]); // clockwise as written
    let inner = spline(&[
        (280.0, 78.0, -1.0),
        (430.0, 250.0, -1.0),
        (280.0, 422.0, -1.0),
        (130.0, 250.0, -1.0),
    ]); // ccw as written
    let path = orient_contours(vec![
        fit_contour(&outer, 0.5).path,
        fit_contour(&inner, 0.5).path,
    ]);
    let areas: Vec<f64> = subpaths(&path).iter().map(|p| p.area()).collect();
    assert_eq!(areas.len(), 2);
    assert!(areas[0] > 0.0 && areas[1] < 0.0, "{areas:?}");
    assert_eq!(
        path.winding(Point::new(280.0, 250.0)),
        0,
        "counter is a hole under nonzero"
    );
    assert_eq!(path.winding(Point::new(280.0, 30.0)).abs(), 1);
}

fn subpaths(path: &BezPath) -> Vec<BezPath> {
    let mut out: Vec<BezPath> = Vec::new();
    for el in path.elements() {
        if let PathEl::MoveTo(_) = el {
            out.push(BezPath::new());
        }
        out.last_mut().unwrap().push(*el);
    }
    out
}

/// The proptest seed: fixed, unless `XGLYPH_PROPTEST_SEED` names another.
fn seed() -> u64 {
    std::env::var("XGLYPH_PROPTEST_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x5eed_2026)
}

fn shape_strategy() -> impl Strategy<Value = f64> {
    prop_oneof![
        prop::sample::select(vec![-1.0, -0.5, 0.0, 0.5, 1.0]),
        -1.0..=1.0f64,
    ]
}

proptest! {
    // A fixed seed keeps CI reproducible; XGLYPH_PROPTEST_SEED=<u64> replays another
    // (scratch hunts with fresh seeds, 1600 cases each, are how `thin_spike_tips_are_not_missed`
    // was found).
    #![proptest_config(ProptestConfig {
        cases: 128,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed()),
        .. ProptestConfig::default()
    })]

    #[test]
    fn random_contours_stay_within_tolerance(
        raw in prop::collection::vec((0.0..1.0f64, 0.0..1.0f64, shape_strategy()), 3..=60),
        scale_exp in -3i32..=5,
        collinear in any::<bool>(),
        twins in any::<bool>(),
    ) {
        let scale = 10f64.powi(scale_exp);
        let mut pts: Vec<ControlPoint> = raw.iter().enumerate().map(|(i, &(x, y, s))| {
            // Optionally squash onto a near-line to exercise near-collinear input.
            let y = if collinear { y * 1e-3 + i as f64 * 1e-4 } else { y };
            // Optionally pull every odd point next to its predecessor (nearly coincident).
            let (x, y) = if twins && i % 2 == 1 {
                (raw[i - 1].0 + 1e-6 * x, raw[i - 1].1 + 1e-6 * y)
            } else {
                (x, y)
            };
            ControlPoint::new(x * scale, y * scale, s)
        }).collect();
        pts.dedup_by(|a, b| a.pos == b.pos);
        prop_assume!(pts.len() >= 3 && pts[0].pos != pts[pts.len() - 1].pos);
        let xs = XSpline::new(pts).unwrap();
        let tol = 0.5 * scale / 1000.0;
        let fit = fit_contour(&xs, tol);
        // Every point of the path, control points included, is finite.
        for seg in fit.path.segments() {
            let c = seg.to_cubic();
            for p in [c.p0, c.p1, c.p2, c.p3] {
                prop_assert!(p.is_finite(), "non-finite point {:?} in {:?}", p, seg);
            }
        }
        let err = hausdorff(&xs, &fit.path);
        prop_assert!(err <= tol, "measured {} > tol {}", err, tol);
    }
}
