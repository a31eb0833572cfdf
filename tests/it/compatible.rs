//! Compatible fitting of masters: one segment structure, within tolerance at every position,
//! checked with the dense two-sided checker of `common/curves.rs` (not the fitter's measure).

use crate::common::{corpus::Rng, curves, masters};

use curves::{hausdorff, seed, spline};
use kurbo::{BezPath, ParamCurve, PathEl, PathSeg, Point};
use proptest::prelude::*;
use xglyph::compatible::{fit_compatible, CompatibleError, CompatibleFit};
use xglyph::fit::fit_contour;
use xglyph::xspline::{ControlPoint, XSpline};

/// The X-spline blended at `weights` (valid in these tests).
fn blend_spline(masters: &[&XSpline], weights: &[f64]) -> XSpline {
    masters::blend(masters, weights).expect("blended test contours are valid")
}

/// The paths blended at `weights`, point by point (they must have the same elements).
fn blend_paths(paths: &[BezPath], weights: &[f64]) -> BezPath {
    let mix = |points: &[Point]| {
        points
            .iter()
            .zip(weights)
            .fold(Point::ZERO, |acc, (p, w)| acc + *w * p.to_vec2())
    };
    let mut out = BezPath::new();
    for i in 0..paths[0].elements().len() {
        let els: Vec<PathEl> = paths.iter().map(|p| p.elements()[i]).collect();
        let at = |f: fn(&PathEl) -> Vec<Point>| -> Vec<Point> {
            let per: Vec<Vec<Point>> = els.iter().map(f).collect();
            (0..per[0].len())
                .map(|j| mix(&per.iter().map(|v| v[j]).collect::<Vec<_>>()))
                .collect()
        };
        let pts = at(|e| match *e {
            PathEl::MoveTo(p) | PathEl::LineTo(p) => vec![p],
            PathEl::QuadTo(a, b) => vec![a, b],
            PathEl::CurveTo(a, b, c) => vec![a, b, c],
            PathEl::ClosePath => vec![],
        });
        out.push(match els[0] {
            PathEl::MoveTo(_) => PathEl::MoveTo(pts[0]),
            PathEl::LineTo(_) => PathEl::LineTo(pts[0]),
            PathEl::QuadTo(..) => PathEl::QuadTo(pts[0], pts[1]),
            PathEl::CurveTo(..) => PathEl::CurveTo(pts[0], pts[1], pts[2]),
            PathEl::ClosePath => PathEl::ClosePath,
        });
    }
    out
}

/// Same element kinds in the same order in every master's path.
fn same_structure(fit: &CompatibleFit) -> bool {
    let kinds = |p: &BezPath| {
        p.elements()
            .iter()
            .map(std::mem::discriminant)
            .collect::<Vec<_>>()
    };
    fit.paths.iter().all(|p| kinds(p) == kinds(&fit.paths[0]))
}

/// Two-master positions: 11 evenly spaced (the masters included) and `random` more.
fn positions(random: usize, rng: &mut Rng) -> Vec<Vec<f64>> {
    let mut out = masters::evenly_spaced(11);
    out.extend((0..random).map(|_| {
        let t = rng.next();
        vec![1.0 - t, t]
    }));
    out
}

/// The worst dense two-sided distance over `positions`, as a fraction of `tolerance`.
fn worst_fraction(
    masters: &[&XSpline],
    fit: &CompatibleFit,
    positions: &[Vec<f64>],
    tolerance: f64,
) -> f64 {
    positions
        .iter()
        .map(|w| {
            let xs = blend_spline(masters, w);
            hausdorff(&xs, &blend_paths(&fit.paths, w), 200) / tolerance
        })
        .fold(0.0, f64::max)
}

fn segments(path: &BezPath) -> usize {
    path.segments().count()
}

/// Every bundled contour with its bold variant (30 units, `s` × 0.9): within tolerance at
/// the masters, at 11 evenly spaced and 4 random positions (dense checker), identical
/// structure; over the set, segments at most 1.25 × the static count of each glyph's most
/// demanding master (per glyph, small glyphs exceed it: 9 segments where 7 would do).
#[test]
fn bundled_glyphs_with_bold_masters() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let (font, _) = xglyph::source::load_font(&dir).unwrap();
    let tolerance = font.info.tolerance;
    let mut rng = Rng(0x00c0_ffee);
    let (mut ours, mut reference, mut contours) = (0, 0, 0);
    let mut worst: f64 = 0.0;
    let mut worst_ratio: (f64, String) = (0.0, String::new());
    let mut over = 0;
    for glyph in &font.glyphs {
        let (mut glyph_ours, mut static_light, mut static_bold) = (0, 0, 0);
        for contour in &glyph.contours {
            let light = contour.spline();
            let bold = masters::bold(light, 30.0, 0.9).expect("the bold variant is valid");
            let masters = [light, &bold];
            let at = positions(4, &mut rng);
            let fit = fit_compatible(&masters, &at, tolerance).unwrap();
            assert!(same_structure(&fit), "{}: structures differ", glyph.name);
            assert_eq!(fit.segments, segments(&fit.paths[0]));
            assert!(
                fit.max_error.iter().all(|e| *e <= tolerance),
                "{}: {:?}",
                glyph.name,
                fit.max_error
            );
            let dense = worst_fraction(&masters, &fit, &at, tolerance);
            assert!(dense <= 1.0, "{}: {dense} of the tolerance", glyph.name);
            worst = worst.max(dense);
            glyph_ours += fit.segments;
            static_light += segments(&fit_contour(light, tolerance).path);
            static_bold += segments(&fit_contour(&bold, tolerance).path);
            contours += 1;
        }
        let demanding = static_light.max(static_bold);
        let ratio = glyph_ours as f64 / demanding.max(1) as f64;
        if ratio > worst_ratio.0 {
            worst_ratio = (ratio, glyph.name.clone());
        }
        if glyph_ours as f64 > 1.25 * demanding as f64 {
            over += 1;
        }
        ours += glyph_ours;
        reference += demanding;
    }
    println!(
        "{contours} contours: {ours} compatible segments vs {reference} static (most demanding \
         master per glyph), ratio {:.3}; {over} glyphs over 1.25, worst {} at {:.3}; worst \
         dense error {:.3} of the tolerance",
        ours as f64 / reference as f64,
        worst_ratio.1,
        worst_ratio.0,
        worst
    );
    assert!(contours > 100, "only {contours} contours");
    // Measured: 1845 vs 1516 (1.217) since handles match at smooth joins (session 8);
    // 1548 vs 1459 (1.061, 143 contours) before.
    assert!(
        ours as f64 <= 1.25 * reference as f64,
        "{ours} segments vs {reference}"
    );
}

#[test]
fn sharp_points_are_exact_and_edges_are_lines_in_every_master() {
    let light = spline(&[
        (0.0, 0.0, 0.0),
        (300.0, 0.0, -1.0),
        (520.0, 350.0, -1.0),
        (300.0, 700.0, -1.0),
        (0.0, 700.0, 0.0),
    ]);
    let bold = spline(&[
        (0.0, 0.0, 0.0),
        (340.0, 0.0, -1.0),
        (600.0, 350.0, -0.9),
        (340.0, 700.0, -1.0),
        (0.0, 700.0, 0.0),
    ]);
    let at = positions(0, &mut Rng(1));
    let fit = fit_compatible(&[&light, &bold], &at, 0.5).unwrap();
    assert!(same_structure(&fit));
    assert!(fit.segments >= 3, "{} segments", fit.segments);
    for (path, master) in fit.paths.iter().zip([&light, &bold]) {
        let els = path.elements();
        assert_eq!(els[0], PathEl::MoveTo(Point::new(0.0, 0.0)));
        // The stem (P4 -> P0) is a line ending exactly at the corner.
        assert_eq!(els[els.len() - 2], PathEl::LineTo(Point::new(0.0, 0.0)));
        let ends: Vec<Point> = path.segments().map(|s| s.end()).collect();
        assert!(ends.contains(&Point::new(0.0, 700.0)));
        // G1 inside the smooth stretch, in each master.
        let segs: Vec<PathSeg> = path.segments().collect();
        for pair in segs.windows(2) {
            let (PathSeg::Cubic(a), PathSeg::Cubic(b)) = (pair[0], pair[1]) else {
                continue;
            };
            let (ta, tb) = ((a.p3 - a.p2).normalize(), (b.p1 - b.p0).normalize());
            assert!(ta.cross(tb).abs() < 1e-9 && ta.dot(tb) > 0.0);
        }
        assert!(hausdorff(master, path, 200) <= 0.5);
    }
    assert!(worst_fraction(&[&light, &bold], &fit, &at, 0.5) <= 1.0);
    assert_eq!(fit.max_error.len(), 11);
    assert!(fit.max_error.iter().all(|e| *e > 0.0 && *e <= 0.5));
}

/// Where `s` changes much between masters, the blended X-spline is no blend of the masters'
/// curves, and no structure with vertices on them reaches it: the fit ends and says so.
#[test]
fn unreachable_positions_are_reported() {
    let light = spline(&[
        (0.0, 0.0, 0.0),
        (300.0, 0.0, -1.0),
        (520.0, 350.0, -1.0),
        (300.0, 700.0, -1.0),
        (0.0, 700.0, 0.0),
    ]);
    let bold = spline(&[
        (0.0, 0.0, 0.0),
        (340.0, 0.0, -0.6),
        (600.0, 350.0, 0.5),
        (340.0, 700.0, -0.6),
        (0.0, 700.0, 0.0),
    ]);
    let at = positions(0, &mut Rng(1));
    let fit = fit_compatible(&[&light, &bold], &at, 0.5).unwrap();
    println!("errors with s from -1 to 0.5: {:?}", fit.max_error);
    assert!(fit.max_error[0] <= 0.5 && fit.max_error[10] <= 0.5);
    assert!(fit.max_error[5] > 0.5, "{:?}", fit.max_error);
    let mid = blend_paths(&fit.paths, &at[5]);
    let dense = hausdorff(&blend_spline(&[&light, &bold], &at[5]), &mid, 200);
    // Never under-reported (far from the curve the measure's local projections can
    // over-estimate: measured 57.0 reported where the dense checker finds 27.8).
    assert!(
        dense > 0.5 && dense <= 1.01 * fit.max_error[5],
        "dense {dense} vs reported {}",
        fit.max_error[5]
    );
}

#[test]
fn incompatible_masters_name_the_point() {
    let a = spline(&[(0.0, 0.0, 0.0), (100.0, 0.0, -1.0), (50.0, 80.0, 0.0)]);
    let b = spline(&[(0.0, 0.0, 0.0), (100.0, 0.0, 0.0), (50.0, 80.0, 0.0)]);
    let c = spline(&[
        (0.0, 0.0, 0.0),
        (100.0, 0.0, -1.0),
        (100.0, 80.0, 0.0),
        (50.0, 80.0, 0.0),
    ]);
    let at = [vec![1.0, 0.0], vec![0.0, 1.0]];
    let err = fit_compatible(&[&a, &b], &at, 0.5).unwrap_err();
    assert_eq!(
        err,
        CompatibleError::Sharpness {
            point: 1,
            master: 1,
            sharp_in_first: false
        }
    );
    assert_eq!(
        err.to_string(),
        "point 1 is sharp (s = 0) in master 1 but not in master 0"
    );
    let err = fit_compatible(&[&a, &c], &at, 0.5).unwrap_err();
    assert_eq!(err.to_string(), "master 1 has 4 points, master 0 has 3");
    let err = fit_compatible(&[&a, &a], &[vec![0.7, 0.7]], 0.5).unwrap_err();
    assert_eq!(
        err.to_string(),
        "position 0 needs one finite weight per master, summing to 1"
    );
    // Two points meet half way: the blended contour is invalid there.
    let d = spline(&[(100.0, 0.0, 0.0), (0.0, 0.0, -1.0), (50.0, 80.0, 0.0)]);
    let err = fit_compatible(&[&a, &d], &[vec![0.5, 0.5]], 0.5).unwrap_err();
    assert_eq!(
        err.to_string(),
        "the contour blended at position 0: points 0 and 1 coincide; remove one of them"
    );
    assert_eq!(
        fit_compatible(&[], &[], 0.5).unwrap_err(),
        CompatibleError::NoMasters
    );
}

/// Random compatible pairs: a contour of the static fitter's proptest distribution and a
/// copy with every point moved by up to 5 % of the scale, `s` kept (where `s` differs, the
/// blend may lie beyond the tolerance of every structure: `unreachable_positions_are_reported`).
fn random_pair() -> impl Strategy<Value = Option<(XSpline, XSpline, f64)>> {
    (
        curves::random_contour(),
        prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 60),
    )
        .prop_map(|(contour, moves)| {
            let (light, scale) = contour?;
            let points = light
                .points()
                .iter()
                .zip(&moves)
                .map(|(p, &(dx, dy))| ControlPoint {
                    pos: p.pos + 0.05 * scale * kurbo::Vec2::new(dx, dy),
                    s: p.s,
                })
                .collect();
            let bold = XSpline::new(points).ok()?;
            Some((light, bold, scale))
        })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 32,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed()),
        .. ProptestConfig::default()
    })]

    #[test]
    fn random_pairs_stay_within_tolerance(pair in random_pair(), t in 0.0..1.0f64) {
        let Some((light, bold, scale)) = pair else {
            return Err(TestCaseError::reject("invalid contour"));
        };
        let tol = 0.5 * scale / 1000.0;
        let masters = [&light, &bold];
        let mut at = masters::evenly_spaced(5);
        at.push(vec![1.0 - t, t]);
        // A blend where two points meet is not a contour: skip such pairs.
        if at.iter().any(|w| {
            let n = light.points().len();
            (0..n).any(|k| {
                let p = |m: &XSpline, k: usize| m.points()[k % n].pos.to_vec2();
                let q = |k| w[0] * p(&light, k) + w[1] * p(&bold, k);
                q(k) == q(k + 1)
            })
        }) {
            return Err(TestCaseError::reject("points meet between the masters"));
        }
        let fit = fit_compatible(&masters, &at, tol).unwrap();
        prop_assert!(same_structure(&fit));
        for (path, master) in fit.paths.iter().zip(masters) {
            for p in master.points().iter().filter(|p| p.is_sharp()) {
                prop_assert!(path.segments().any(|s| s.end() == p.pos), "sharp point {:?}", p.pos);
            }
        }
        let floor = at.iter().map(|w| blend_spline(&masters, w).min_tolerance()).fold(tol, f64::max);
        let worst = worst_fraction(&masters, &fit, &at, floor);
        prop_assert!(worst <= 1.0, "{} of the tolerance", worst);
    }
}

/// The bound for every position between two masters with the same `s`
/// (`CompatibleFit::between_masters`) holds at dense positions (41 along the axis, the
/// dense checker), on curved bundled glyphs with their Bold master (`glyphs/bold/`, same
/// `s` at every point). It covers only some contours (on the whole font 98 of 143, the
/// straight-edged ones among them); the others are guaranteed at the checked positions.
#[test]
fn bound_between_masters_holds_at_dense_positions() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let (family, _) = xglyph::source::load_family(&dir).unwrap();
    let font = &family.default;
    let tolerance = font.info.tolerance;
    let at = masters::evenly_spaced(11);
    let dense = masters::evenly_spaced(41);
    let (mut covered, mut contours) = (0, 0);
    let mut closest: f64 = f64::INFINITY;
    for name in [
        "a",
        "g",
        "S",
        "ampersand",
        "O",
        "R",
        "e",
        "s",
        "two",
        "eight",
    ] {
        let index = font.glyphs.iter().position(|g| g.name == name).unwrap();
        let bold = &family.masters[0].glyphs[index];
        for (light, heavy) in font.glyphs[index].contours.iter().zip(&bold.contours) {
            let masters = [light.spline(), heavy.spline()];
            let fit = fit_compatible(&masters, &at, tolerance).unwrap();
            contours += 1;
            let Some(bound) = fit.between_masters else {
                continue;
            };
            covered += 1;
            assert!(bound <= tolerance, "{name}: bound {bound}");
            for w in &dense {
                let xs = blend_spline(&masters, w);
                let error = hausdorff(&xs, &blend_paths(&fit.paths, w), 200);
                assert!(
                    error <= bound * (1.0 + 1e-9),
                    "{name} at {w:?}: {error} over the bound {bound}"
                );
                closest = closest.min(bound - error);
            }
        }
    }
    println!(
        "{covered} of {contours} contours bounded between the masters; least slack {closest:.4}"
    );
    // Measured: 7 of 19, least slack 0.0002 (the bound is reached at a master).
    assert!(covered >= 7, "{covered} of {contours}");
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 24,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed() ^ 0x5eed),
        .. ProptestConfig::default()
    })]

    /// Random pairs with the same `s` (`random_pair`): where the fit reports a bound for
    /// every position between the masters, 41 dense positions stay within it.
    #[test]
    fn random_pairs_never_exceed_the_bound_between_masters(pair in random_pair()) {
        let Some((light, bold, scale)) = pair else {
            return Err(TestCaseError::reject("invalid contour"));
        };
        let tol = 0.5 * scale / 1000.0;
        let masters = [&light, &bold];
        let dense = masters::evenly_spaced(41);
        if dense.iter().any(|w| masters::blend(&masters, w).is_none()) {
            return Err(TestCaseError::reject("points meet between the masters"));
        }
        let fit = fit_compatible(&masters, &masters::evenly_spaced(11), tol).unwrap();
        if let Some(bound) = fit.between_masters {
            for w in &dense {
                let error = hausdorff(&blend_spline(&masters, w), &blend_paths(&fit.paths, w), 200);
                prop_assert!(error <= bound * (1.0 + 1e-9), "{} over the bound {} at {:?}", error, bound, w);
            }
        }
    }
}

/// The angle (radians) between a join's incoming handle `p - c2` and outgoing handle
/// `c1 - p`; `None` when a handle is shorter than 1e-9 units (no direction).
fn join_angle(c2: Point, p: Point, c1: Point) -> Option<f64> {
    let (a, b) = (p - c2, c1 - p);
    if a.hypot() < 1e-9 || b.hypot() < 1e-9 {
        return None;
    }
    Some(a.cross(b).atan2(a.dot(b)).abs())
}

/// Every join of two cubics in `path` (the closing join too), as (the incoming cubic's
/// second control point, the join point, the outgoing cubic's first control point).
fn cubic_joins(path: &BezPath) -> Vec<(Point, Point, Point)> {
    let els = path.elements();
    let mut out = Vec::new();
    // Consecutive elements that are both cubics (a LineTo between them is a corner).
    for k in 1..els.len() {
        if let (PathEl::CurveTo(_, c2, p), PathEl::CurveTo(c1, ..)) = (els[k - 1], els[k]) {
            out.push((c2, p, c1));
        }
    }
    // The closing join: the last element before ClosePath and the first after MoveTo.
    if let (Some(PathEl::CurveTo(_, c2, p)), Some(PathEl::CurveTo(c1, ..))) =
        (els.get(els.len().wrapping_sub(2)), els.get(1))
    {
        out.push((*c2, *p, *c1));
    }
    out
}

/// Issue 16: at every join of two cubics that is not a sharp point (`s = 0`), the
/// compatible Béziers' handles are collinear in **every master** (G1, from the X-spline's
/// tangent there), and the ratio of the handles' lengths is the same in every master, so
/// the blended handles are collinear at every position too: a smooth point stays smooth at
/// every instance. On the bundled glyphs with their Bold master and with the synthetic
/// bold, at the 11 evenly spaced positions. (Before session 8, when each master kept its
/// own handle lengths: 483 of 13923 blended joins bent by more than 1°, the worst 52.6°.)
#[test]
fn smooth_joins_stay_smooth_at_every_position() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let (family, _) = xglyph::source::load_family(&dir).unwrap();
    let tolerance = family.default.info.tolerance;
    let at = masters::evenly_spaced(11);
    let (mut joins, mut worst_master, mut worst_blend) = (0usize, 0.0f64, 0.0f64);
    let mut blended = 0usize;
    let pairs = family
        .default
        .glyphs
        .iter()
        .zip(&family.masters[0].glyphs)
        .flat_map(|(a, b)| a.contours.iter().zip(&b.contours));
    for (light, heavy) in pairs {
        let light = light.spline();
        let synthetic = masters::bold(light, 30.0, 0.9).unwrap();
        for bold in [heavy.spline(), &synthetic] {
            let splines = [light, bold];
            let fit = fit_compatible(&splines, &at, tolerance).unwrap();
            let per_master: Vec<_> = fit.paths.iter().map(cubic_joins).collect();
            for j in 0..per_master[0].len() {
                let (_, p, _) = per_master[0][j];
                let sharp = splines[0]
                    .points()
                    .iter()
                    .any(|c| c.s == 0.0 && (c.pos - p).hypot() < 1e-9);
                if sharp {
                    continue;
                }
                joins += 1;
                for (m, joints) in per_master.iter().enumerate() {
                    let (c2, p, c1) = joints[j];
                    let angle = join_angle(c2, p, c1).unwrap_or(0.0);
                    assert!(
                        angle < 1e-6,
                        "master {m}: a join at {p:?} bends by {angle} rad"
                    );
                    worst_master = worst_master.max(angle);
                }
                for w in &at[1..at.len() - 1] {
                    let mix = |f: fn(&(Point, Point, Point)) -> Point| -> Point {
                        (w[0] * f(&per_master[0][j]).to_vec2()
                            + w[1] * f(&per_master[1][j]).to_vec2())
                        .to_point()
                    };
                    let angle = join_angle(mix(|t| t.0), mix(|t| t.1), mix(|t| t.2));
                    let angle = angle.unwrap_or(0.0);
                    blended += 1;
                    assert!(
                        angle < 1e-6,
                        "at {w:?} a join at {:?} bends by {angle} rad",
                        per_master[0][j].1
                    );
                    worst_blend = worst_blend.max(angle);
                }
            }
        }
    }
    println!(
        "{joins} smooth joins: worst bend in a master {worst_master:e} rad; at 9 positions \
         between the masters, worst of {blended} blended joins {worst_blend:e} rad"
    );
    assert!(joins > 1000, "{joins}");
    assert!(worst_master < 1e-6);
}

/// Issue 16, as `build` fits them: the bundled family (`glyphs/`, Regular and Bold) and the
/// test family (`tests/fixtures/masters`). At every join of two cubics whose handles are
/// collinear in every master (every smooth point; `smooth_joins_stay_smooth_at_every_position`
/// shows that each smooth join is), the blended handles are collinear at every position the
/// build checks: the masters, the named instances and 11 evenly spaced positions.
#[test]
fn families_have_no_kinks_at_any_checked_position() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for (dir, least) in [("glyphs", 1000), ("tests/fixtures/masters", 20)] {
        let loaded = xglyph::pipeline::load(&root.join(dir), None).unwrap();
        let (outlined, _) =
            xglyph::family::outline_family(&loaded.family, loaded.font.tolerance).unwrap();
        let positions: Vec<Vec<f64>> = xglyph::family::check_locations(&loaded.family)
            .iter()
            .map(|l| outlined.weights(l))
            .collect();
        assert!(
            positions.len() >= 11,
            "{dir}: {} positions",
            positions.len()
        );
        let (mut smooth, mut worst) = (0usize, 0.0f64);
        for (g, glyph) in outlined.default.glyphs.iter().enumerate() {
            let paths: Vec<&BezPath> = std::iter::once(&glyph.path)
                .chain(outlined.masters.iter().map(|m| &m.glyphs[g].path))
                .collect();
            let joins: Vec<Vec<(Point, Point, Point)>> =
                paths.iter().map(|p| subpath_joins(p)).collect();
            for j in 0..joins[0].len() {
                let collinear = joins
                    .iter()
                    .all(|m| join_angle(m[j].0, m[j].1, m[j].2).unwrap_or(0.0) < 1e-6);
                if !collinear {
                    continue;
                }
                smooth += 1;
                for w in &positions {
                    let mix = |f: fn(&(Point, Point, Point)) -> Point| -> Point {
                        joins
                            .iter()
                            .zip(w)
                            .fold(Point::ZERO, |acc, (m, w)| acc + *w * f(&m[j]).to_vec2())
                    };
                    let angle = join_angle(mix(|t| t.0), mix(|t| t.1), mix(|t| t.2));
                    let angle = angle.unwrap_or(0.0);
                    assert!(
                        angle < 1e-6,
                        "{dir}: glyph {} at {w:?}, a join at {:?} bends by {angle} rad",
                        glyph.name,
                        joins[0][j].1
                    );
                    worst = worst.max(angle);
                }
            }
        }
        println!(
            "{dir}: {smooth} smooth joins at {} positions, worst bend {worst:e} rad",
            positions.len()
        );
        assert!(smooth >= least, "{dir}: {smooth} smooth joins");
    }
}

/// [`cubic_joins`] of every subpath of `path` (a glyph's path holds several contours).
fn subpath_joins(path: &BezPath) -> Vec<(Point, Point, Point)> {
    let mut out = Vec::new();
    let mut sub = BezPath::new();
    for el in path.elements() {
        if let PathEl::MoveTo(_) = el {
            if !sub.elements().is_empty() {
                out.extend(cubic_joins(&sub));
            }
            sub = BezPath::new();
        }
        sub.push(*el);
    }
    if !sub.elements().is_empty() {
        out.extend(cubic_joins(&sub));
    }
    out
}

/// Roboto Flex's tilde (`tests/fixtures/flex-tilde`: 84 masters on 13 axes, the same `s`
/// in every master), fitted as `build` fits it, at every position the build checks (2,307):
/// within the tolerance by the fitter's own measure, and by the dense two-sided checker.
/// With one `s` the blended X-spline is exactly the blend of the masters' curves, so every
/// position can be met. The fitter once let the blends go on its shortest spans and
/// reported 1.154 units at opsz 8, wght 1000, GRAD -112.5, wdth 151 (the build warned),
/// where the dense checker, which compares whole contours, finds 0.298 (the measure's
/// projections can over-estimate; see `src/compatible/mod.rs`).
#[test]
fn many_masters_with_one_s_are_within_the_tolerance_at_every_checked_position() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/flex-tilde");
    let (family, _) = xglyph::source::load_family(&dir).expect("the fixture loads");
    let tolerance = family.default.info.tolerance;
    let models = family.glyph_models().expect("a model");
    let gi = family
        .default
        .glyphs
        .iter()
        .position(|g| g.name == "uni02DC")
        .expect("the tilde");
    let k = models.of_glyph[gi];
    let drawing: Vec<&XSpline> = std::iter::once(&family.default.glyphs[gi])
        .chain(
            models.sets[k]
                .0
                .iter()
                .map(|&m| &family.masters[m].glyphs[gi]),
        )
        .map(|g| g.contours[0].spline())
        .collect();
    assert_eq!(drawing.len(), 85);
    let shapes = |s: &XSpline| s.points().iter().map(|p| p.s).collect::<Vec<_>>();
    assert!(drawing.iter().all(|s| shapes(s) == shapes(drawing[0])));
    let locations = xglyph::family::check_locations(&family);
    assert_eq!(locations.len(), 2307);
    let positions: Vec<Vec<f64>> = locations
        .iter()
        .map(|l| family.designspace.weights(&models.sets[k].1, l))
        .collect();
    let fit = fit_compatible(&drawing, &positions, tolerance).expect("one structure");
    let owned: Vec<XSpline> = drawing.iter().map(|s| (*s).clone()).collect();
    let mut worst = (0.0f64, 0);
    for (p, w) in positions.iter().enumerate() {
        // `s` blends to 1 + 1e-16 at some positions: the importer's blend clamps it.
        let spline = xglyph::import::masters::blend_splines(&owned, w).expect("valid");
        let dense = hausdorff(&spline, &blend_paths(&fit.paths, w), 30);
        if dense > worst.0 {
            worst = (dense, p);
        }
    }
    let at = xglyph::family::describe(&family.designspace, &locations[worst.1]);
    println!(
        "flex tilde: {} segments, worst {:.4} at {at}",
        fit.segments, worst.0
    );
    assert!(worst.0 <= tolerance, "{} at {at}", worst.0);
    assert!(fit.max_error.iter().all(|&e| e <= tolerance));
}
