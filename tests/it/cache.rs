//! The fitted-contour cache (`src/cache.rs`): hits give bit-identical fits, and a corrupt,
//! truncated or stale file is ignored (every contour refitted), never trusted.

use std::path::{Path, PathBuf};

use xglyph::cache::{FitCache, LoadOutcome};
use xglyph::fit::{fit_contour, ContourFit};
use xglyph::source::load_font;
use xglyph::xspline::{ControlPoint, XSpline};

fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("cache-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every contour of the bundled typeface, components placed.
fn contours() -> Vec<XSpline> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let (font, _) = load_font(&dir).expect("glyphs/ loads");
    font.glyphs
        .iter()
        .flat_map(|g| font.placed_contours(g))
        .map(|(c, (dx, dy))| {
            let points = c
                .points()
                .iter()
                .map(|p| ControlPoint::new(p.pos.x + dx, p.pos.y + dy, p.s));
            XSpline::new(points.collect()).unwrap()
        })
        .collect()
}

/// Number of distinct contours (by the bits of their points).
fn distinct(splines: &[XSpline]) -> usize {
    let keys: std::collections::HashSet<Vec<u64>> = splines
        .iter()
        .map(|s| {
            s.points()
                .iter()
                .flat_map(|p| [p.pos.x.to_bits(), p.pos.y.to_bits(), p.s.to_bits()])
                .collect()
        })
        .collect();
    keys.len()
}

fn same(a: &ContourFit, b: &ContourFit) -> bool {
    a.path == b.path && a.max_error.to_bits() == b.max_error.to_bits()
}

/// Fits every contour through `cache` and checks each against a direct fit.
fn fit_all(cache: &FitCache, splines: &[XSpline], direct: &[ContourFit], tolerance: f64) {
    for (k, (spline, expected)) in splines.iter().zip(direct).enumerate() {
        assert!(same(&cache.fit(spline, tolerance), expected), "contour {k}");
    }
}

#[test]
fn a_warm_cache_gives_the_same_fits_without_fitting() {
    let splines = contours();
    let direct: Vec<ContourFit> = splines.iter().map(|s| fit_contour(s, 0.5)).collect();
    let path = temp_dir("warm").join(".xglyph-cache");
    let (cold, outcome) = FitCache::load(&path);
    assert_eq!(outcome, LoadOutcome::Missing);
    fit_all(&cold, &splines, &direct, 0.5);
    // Accented letters share their base's contours: distinct contours only are fitted.
    let distinct = distinct(&splines);
    assert_eq!(cold.misses(), distinct);
    assert_eq!((cold.hits(), cold.reused()), (0, splines.len() - distinct));
    assert!(distinct > 150 && distinct < splines.len(), "{distinct}");
    cold.save(&path).unwrap();
    let (warm, outcome) = FitCache::load(&path);
    assert_eq!(outcome, LoadOutcome::Loaded(distinct));
    fit_all(&warm, &splines, &direct, 0.5);
    assert_eq!((warm.hits(), warm.misses()), (splines.len(), 0));
    // The same fits written again are the same bytes.
    assert_eq!(warm.to_bytes(), std::fs::read(&path).unwrap());
    // Another tolerance is another key: nothing from the cache.
    let (other, _) = FitCache::load(&path);
    let fit = other.fit(&splines[0], 0.25);
    assert!(same(&fit, &fit_contour(&splines[0], 0.25)));
    assert_eq!((other.hits(), other.misses()), (0, 1));
}

#[test]
fn an_edited_contour_is_refitted_and_the_rest_come_from_the_cache() {
    let mut splines = contours();
    splines.truncate(40);
    let path = temp_dir("edit").join(".xglyph-cache");
    let cold = FitCache::new();
    splines.iter().for_each(|s| drop(cold.fit(s, 0.5)));
    cold.save(&path).unwrap();
    // Move one point of contour 7 by the smallest step an f64 can take.
    let mut points = splines[7].points().to_vec();
    points[0].pos.x = f64::from_bits(points[0].pos.x.to_bits() + 1);
    splines[7] = XSpline::new(points).unwrap();
    let direct: Vec<ContourFit> = splines.iter().map(|s| fit_contour(s, 0.5)).collect();
    let (warm, _) = FitCache::load(&path);
    fit_all(&warm, &splines, &direct, 0.5);
    assert_eq!(warm.misses(), 1);
    assert_eq!(warm.hits(), splines.len() - 1);
    // The next file holds the contours of this run: the edited one, not the old one.
    warm.save(&path).unwrap();
    assert_eq!(
        FitCache::load(&path).1,
        LoadOutcome::Loaded(distinct(&splines))
    );
}

#[test]
fn a_corrupt_or_stale_cache_is_ignored_and_rebuilt() {
    let mut splines = contours();
    splines.truncate(30);
    let direct: Vec<ContourFit> = splines.iter().map(|s| fit_contour(s, 0.5)).collect();
    let dir = temp_dir("corrupt");
    let path = dir.join(".xglyph-cache");
    let good = {
        let cache = FitCache::new();
        fit_all(&cache, &splines, &direct, 0.5);
        cache.to_bytes()
    };
    let n = good.len();
    let flip = |at: usize, mask: u8| {
        let mut b = good.clone();
        b[at] ^= mask;
        b
    };
    // The fitter version (bytes 12..16), flipped and the checksum made to match again.
    let resign = |mut b: Vec<u8>| {
        b.truncate(b.len() - 4);
        let crc = crc32fast::hash(&b);
        b.extend_from_slice(&crc.to_le_bytes());
        b
    };
    let stale_fitter = resign(flip(12, 1));
    let stale_format = resign(flip(8, 1));
    let stale_fingerprint = resign(flip(16, 1));
    let mut cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("empty", vec![], "the file is truncated"),
        ("three bytes", good[..3].to_vec(), "the file is truncated"),
        (
            "not ours",
            b"PNG\0 something else entirely".to_vec(),
            "not an xglyph cache file",
        ),
        (
            "stale fitter",
            stale_fitter,
            "written by another version of the fitter",
        ),
        (
            "stale fingerprint",
            stale_fingerprint,
            "written by another version of the fitter",
        ),
        (
            "stale format",
            stale_format,
            "written by another version of xglyph",
        ),
        (
            "unsigned edit",
            flip(12, 1),
            "the checksum does not match (corrupt or truncated)",
        ),
        (
            "trailing byte",
            [&good[..], &[0]].concat(),
            "the checksum does not match (corrupt or truncated)",
        ),
    ];
    for cut in [n - 1, n - 4, n - 5, n / 2, 30, 9] {
        cases.push(("truncated", good[..cut].to_vec(), ""));
    }
    for at in [8, 20, 28, 40, n / 3, n / 2, n - 20, n - 1] {
        cases.push(("one bit flipped", flip(at, 0x10), ""));
    }
    let unique = distinct(&splines);
    for (what, bytes, reason) in cases {
        std::fs::write(&path, &bytes).unwrap();
        let (cache, outcome) = FitCache::load(&path);
        match (&outcome, reason) {
            (LoadOutcome::Ignored(r), "") => assert!(!r.is_empty()),
            (LoadOutcome::Ignored(r), expected) => assert_eq!(r, expected, "{what}"),
            _ => panic!("{what}: {outcome:?}"),
        }
        fit_all(&cache, &splines, &direct, 0.5);
        assert_eq!(cache.misses(), unique, "{what}: nothing came from the file");
        // Rebuilt: the next save is the good file again.
        cache.save(&path).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), good, "{what}");
    }
    // A folder where the file should be: ignored too (and not replaced by save).
    std::fs::remove_file(&path).unwrap();
    std::fs::create_dir(&path).unwrap();
    let (cache, outcome) = FitCache::load(&path);
    assert!(matches!(outcome, LoadOutcome::Ignored(_)), "{outcome:?}");
    fit_all(&cache, &splines, &direct, 0.5);
}
