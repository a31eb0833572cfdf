//! Cubic fitting against the true X-spline: two-sided distance by dense sampling.

use crate::common::curves;

use curves::{hausdorff, seed, spline};
use kurbo::{BezPath, ParamCurve, ParamCurveArclen, PathEl, PathSeg, Point, Shape};
use proptest::prelude::*;
use xglyph::fit::{fit_contour, stretches, Stretch};
use xglyph::orient::orient_contours;

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
    let err = hausdorff(&xs, &fit.path, 200);
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
    assert!(hausdorff(&xs, &fit.path, 200) <= 0.2);
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
    assert!(hausdorff(&xs, &fit.path, 200) <= 0.05);
    let PathSeg::Cubic(first) = fit.path.segments().next().unwrap() else {
        panic!()
    };
    let dir = (first.p1 - first.p0).normalize();
    assert!((dir - xs.segment(0).start_direction()).hypot() < 1e-12);
}

/// The Bold `e`'s counter leaves its sharp point (434, 300) upwards and turns left within
/// a few units. Every control point has y >= 300 and x <= 434, and the curve (approximating
/// there) stays inside their hull. The minimax cubic from the corner once had a 24-unit
/// handle at its far end reaching 5.5 units below the corner: the cubic dipped under
/// y = 300 and passed x = 434, and its split at that false extreme, rounded to the grid,
/// crossed the bar's edge (FontForge: self-intersecting). No handle may reach past the
/// other end of its cubic along the chord.
#[test]
fn no_handle_reaches_past_the_other_end_of_its_cubic() {
    let counter = spline(&[
        (183.0, 300.0, 0.0),
        (434.0, 300.0, 0.0),
        (434.0, 312.0, 0.5),
        (432.0, 425.0, 1.0),
        (309.0, 432.0, -1.0),
        (186.0, 422.0, 1.0),
        (183.0, 312.0, 0.5),
    ]);
    let fit = fit_contour(&counter, 0.5);
    assert!(hausdorff(&counter, &fit.path, 200) <= 0.5);
    for seg in fit.path.segments() {
        let PathSeg::Cubic(c) = seg else { continue };
        assert!(!folds(&c), "{c:?}");
    }
    // The cubic leaving the corner keeps inside the control points' hull there.
    let (mut lowest, mut rightmost) = (f64::INFINITY, f64::NEG_INFINITY);
    for seg in fit.path.segments() {
        for k in 0..=1000 {
            let p = seg.eval(f64::from(k) / 1000.0);
            if p.y < 330.0 && p.x > 400.0 {
                lowest = lowest.min(p.y);
                rightmost = rightmost.max(p.x);
            }
        }
    }
    assert!(
        lowest >= 300.0 - 1e-9 && rightmost <= 434.0 + 1e-9,
        "{lowest} {rightmost}"
    );
}

/// Whether a handle of `c` reaches past the other end along the chord (a folded control
/// polygon).
fn folds(c: &kurbo::CubicBez) -> bool {
    let chord = c.p3 - c.p0;
    let reach = (c.p1 - c.p0).dot(chord).max((c.p3 - c.p2).dot(chord));
    reach > chord.hypot2() * (1.0 + 1e-9)
}

/// A span search that stops just short of a stretch's end must not leave a sliver: the
/// tilde (found in the bundled typeface) ended in a cubic 1e-4 units long, written as
/// `C204 814 204 814 204 814` in every output. Every segment of every bundled glyph is
/// now longer than a hundredth of a unit.
#[test]
fn no_sliver_segments() {
    let tilde = spline(&[
        (-154., 659., 0.),
        (-119., 697., -1.),
        (-71., 726., -1.),
        (-15., 712., -1.),
        (23., 675., -1.),
        (50., 648., -1.),
        (59., 643., -1.),
        (76., 657., -1.),
        (106., 690., 0.),
        (154., 645., 0.),
        (119., 607., -1.),
        (71., 578., -1.),
        (15., 592., -1.),
        (-23., 629., -1.),
        (-50., 656., -1.),
        (-59., 661., -1.),
        (-76., 647., -1.),
        (-106., 614., 0.),
    ]);
    let shortest = |path: &BezPath| {
        path.segments()
            .map(|seg| seg.arclen(1e-6))
            .fold(f64::INFINITY, f64::min)
    };
    let fit = fit_contour(&tilde, 0.5);
    assert!(shortest(&fit.path) > 1.0, "{:?}", fit.path);
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let (font, _) = xglyph::source::load_font(&dir).unwrap();
    let outlines = xglyph::outline_font(&font, font.info.tolerance);
    for glyph in &outlines.glyphs {
        let len = shortest(&glyph.path);
        assert!(len > 0.01, "{}: a segment {len} units long", glyph.name);
    }
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
    let err = hausdorff(&xs, &fit.path, 200);
    assert!(err <= tol, "measured {} of the tolerance", err / tol);
}

#[test]
fn unreachable_tolerances_are_raised_to_the_contours_floor() {
    // Zero, negative, NaN or below floating-point resolution: the fit still ends, within
    // the floor (1e-10 of the extent) instead of halving spans forever.
    let xs = spline(&[
        (0.0, 0.0, 1.0),
        (1000.0, 0.0, 0.5),
        (1000.0, 1000.0, -0.5),
        (0.0, 1000.0, 0.0),
    ]);
    let floor = xs.min_tolerance();
    assert_eq!(floor, 1e-10 * 1000.0 * 2f64.sqrt());
    let at_floor = fit_contour(&xs, floor).path;
    for tol in [0.0, -1.0, f64::NAN, 1e-14] {
        let fit = fit_contour(&xs, tol);
        assert_eq!(fit.path, at_floor, "tolerance {tol}");
        assert!(fit.max_error <= floor, "tolerance {tol}: {}", fit.max_error);
    }
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

proptest! {
    // A fixed seed keeps CI reproducible; XGLYPH_PROPTEST_SEED=<u64> replays another.
    // Seed hunts over thousands of fresh contours of this distribution, with the same
    // checker: `cargo run --release --example hunt` (how `thin_spike_tips_are_not_missed`
    // was found).
    #![proptest_config(ProptestConfig {
        cases: 128,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed()),
        .. ProptestConfig::default()
    })]

    #[test]
    fn random_contours_stay_within_tolerance(contour in curves::random_contour()) {
        let Some((xs, scale)) = contour else {
            return Err(TestCaseError::reject("fewer than three distinct points"));
        };
        let tol = 0.5 * scale / 1000.0;
        let fit = fit_contour(&xs, tol);
        // Every point of the path, control points included, is finite.
        for seg in fit.path.segments() {
            let c = seg.to_cubic();
            for p in [c.p0, c.p1, c.p2, c.p3] {
                prop_assert!(p.is_finite(), "non-finite point {:?} in {:?}", p, seg);
            }
        }
        // Every sharp point is an on-curve point, exactly, and the edge between two
        // consecutive sharp points is one line.
        let segs: Vec<PathSeg> = fit.path.segments().collect();
        let pts = xs.points();
        for (k, p) in pts.iter().enumerate().filter(|(_, p)| p.is_sharp()) {
            prop_assert!(segs.iter().any(|s| s.end() == p.pos), "sharp point {:?} is not on the path", p.pos);
            let next = pts[(k + 1) % pts.len()];
            if next.is_sharp() {
                let edge = PathSeg::Line(kurbo::Line::new(p.pos, next.pos));
                prop_assert!(segs.contains(&edge), "no line {:?} -> {:?}", p.pos, next.pos);
            }
        }
        // Joins inside smooth stretches are G1 (where both handles are long enough for
        // their directions to survive rounding of the coordinates).
        let cuts: Vec<Point> = stretches(&xs)
            .iter()
            .map(|piece| match *piece {
                Stretch::Edge { end } | Stretch::Smooth { end, .. } => xs.eval(end),
            })
            .collect();
        let resolved = 1e-6 * xs.extent();
        for pair in segs.windows(2) {
            let (PathSeg::Cubic(a), PathSeg::Cubic(b)) = (pair[0], pair[1]) else {
                continue;
            };
            let (ta, tb) = (a.p3 - a.p2, b.p1 - b.p0);
            if cuts.contains(&a.p3) || ta.hypot().min(tb.hypot()) < resolved {
                continue;
            }
            let sin = ta.cross(tb) / (ta.hypot() * tb.hypot());
            prop_assert!(sin.abs() < 1e-6 && ta.dot(tb) > 0.0, "join at {:?}: {:?} vs {:?}", a.p3, ta, tb);
        }
        // No handle reaches past the other end of its cubic along the chord (a fold).
        for seg in &segs {
            if let PathSeg::Cubic(c) = *seg {
                prop_assert!(!folds(&c), "a handle folds back in {:?}", c);
            }
        }
        let err = hausdorff(&xs, &fit.path, 200);
        prop_assert!(err <= tol, "measured {} > tol {}", err, tol);
    }
}
