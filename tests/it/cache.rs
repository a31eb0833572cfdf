//! The fitted-contour cache (`src/cache.rs`): hits give bit-identical fits, static and
//! compatible, and a corrupt, truncated or stale file is ignored (every contour refitted),
//! never trusted; a warm build of a font with masters fits nothing and writes the same
//! bytes; `svg` keeps the cache and the source memo in OUT as `build` does, and shares them
//! with it.

use std::path::{Path, PathBuf};

use crate::common::cli::xglyph;
use xglyph::cache::{FitCache, LoadOutcome, CACHE_FILE};
use xglyph::compatible::{fit_compatible, CompatibleFit};
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
    let before = distinct(&splines);
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
    // The next files hold the contours of this run: the edited one in the delta file, and
    // until the cache file is written whole, the old one.
    warm.save(&path).unwrap();
    assert_eq!(FitCache::load(&path).1, LoadOutcome::Loaded(before + 1));
}

/// `splines` with the first point of each contour numbered in `edited` moved by the
/// smallest step an f64 can take.
fn edited(splines: &[XSpline], edited: &[usize]) -> Vec<XSpline> {
    let mut out = splines.to_vec();
    for &k in edited {
        let mut points = out[k].points().to_vec();
        points[0].pos.x = f64::from_bits(points[0].pos.x.to_bits() + 1);
        out[k] = XSpline::new(points).unwrap();
    }
    out
}

#[test]
fn an_edit_writes_only_a_delta_file_that_the_next_run_trusts_only_whole_and_bound() {
    use xglyph::cache::delta_path;
    // The first 40 distinct contours.
    let mut splines: Vec<XSpline> = Vec::new();
    for s in contours() {
        if splines.len() < 40 && !splines.contains(&s) {
            splines.push(s);
        }
    }
    assert_eq!(distinct(&splines), 40);
    let path = temp_dir("delta").join(".xglyph-cache");
    let delta = delta_path(&path);
    let cold = FitCache::new();
    splines.iter().for_each(|s| drop(cold.fit(s, 0.5)));
    cold.save(&path).unwrap();
    let whole = std::fs::read(&path).unwrap();
    assert!(!delta.exists());

    // One contour edited: 1 new + 1 unused entry is within 1/8 of 40, so only the delta
    // file is written; the cache file keeps its bytes.
    let splines = edited(&splines, &[7]);
    let direct: Vec<ContourFit> = splines.iter().map(|s| fit_contour(s, 0.5)).collect();
    let (warm, _) = FitCache::load(&path);
    fit_all(&warm, &splines, &direct, 0.5);
    assert_eq!(warm.misses(), 1);
    let files = warm.files_to_save(&path);
    assert_eq!(files.iter().map(|f| &f.0).collect::<Vec<_>>(), [&delta]);
    warm.save(&path).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), whole);

    // The next run takes every fit from the two files, bit for bit, and writes nothing.
    let (next, outcome) = FitCache::load(&path);
    assert_eq!(outcome, LoadOutcome::Loaded(41));
    fit_all(&next, &splines, &direct, 0.5);
    assert_eq!((next.hits(), next.misses()), (40, 0));
    assert!(next.files_to_save(&path).is_empty());

    // A damaged or truncated delta file is ignored: its contour is fitted again.
    let good = std::fs::read(&delta).unwrap();
    let mut flipped = good.clone();
    flipped[good.len() / 2] ^= 0x10;
    for damaged in [
        flipped,
        good[..good.len() - 1].to_vec(),
        b"XGLYPHFD".to_vec(),
    ] {
        std::fs::write(&delta, &damaged).unwrap();
        let (cache, outcome) = FitCache::load(&path);
        assert_eq!(outcome, LoadOutcome::Loaded(40));
        fit_all(&cache, &splines, &direct, 0.5);
        assert_eq!((cache.hits(), cache.misses()), (39, 1));
    }

    // Five more edits: 6 new + 6 unused entries pass 1/8 of 40, so the cache file is
    // written whole, with exactly this run's contours; the delta file left behind is bound
    // to the old cache file and ignored.
    std::fs::write(&delta, &good).unwrap();
    let splines = edited(&splines, &[1, 2, 3, 4, 5]);
    let direct: Vec<ContourFit> = splines.iter().map(|s| fit_contour(s, 0.5)).collect();
    let (many, _) = FitCache::load(&path);
    fit_all(&many, &splines, &direct, 0.5);
    assert_eq!((many.hits(), many.misses()), (35, 5));
    let files = many.files_to_save(&path);
    assert_eq!(files.iter().map(|f| &f.0).collect::<Vec<_>>(), [&path]);
    assert_eq!(files[0].1, many.to_bytes());
    many.save(&path).unwrap();
    assert_eq!(std::fs::read(&delta).unwrap(), good);
    let (after, outcome) = FitCache::load(&path);
    assert_eq!(outcome, LoadOutcome::Loaded(40));
    fit_all(&after, &splines, &direct, 0.5);
    assert_eq!((after.hits(), after.misses()), (40, 0));
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
            "it is not an xglyph cache file",
        ),
        (
            "stale fitter",
            stale_fitter,
            "it was written by another version of the fitter",
        ),
        (
            "stale fingerprint",
            stale_fingerprint,
            "it was written by another version of the fitter",
        ),
        (
            "stale format",
            stale_format,
            "it was written by another version of xglyph",
        ),
        (
            "unsigned edit",
            flip(12, 1),
            "its checksum does not match (the file is damaged or truncated)",
        ),
        (
            "trailing byte",
            [&good[..], &[0]].concat(),
            "its checksum does not match (the file is damaged or truncated)",
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
        let cache = load_ignored(&path, &bytes, what, reason);
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

/// Every contour of the bundled Regular with its Bold master (unplaced, as
/// `outline_family` fits them), and the positions a build checks.
fn master_pairs() -> (Vec<(XSpline, XSpline)>, Vec<Vec<f64>>) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let (family, _) = xglyph::source::load_family(&dir).expect("glyphs/ loads");
    let bold = &family.masters[0];
    let pairs = family
        .default
        .glyphs
        .iter()
        .zip(&bold.glyphs)
        .flat_map(|(light, heavy)| light.contours.iter().zip(&heavy.contours))
        .map(|(a, b)| (a.spline().clone(), b.spline().clone()))
        .collect();
    let model = family.model().unwrap();
    let positions = xglyph::family::check_locations(&family)
        .iter()
        .map(|l| family.designspace.weights(&model, l))
        .collect();
    (pairs, positions)
}

fn same_compatible(a: &CompatibleFit, b: &CompatibleFit) -> bool {
    let bits = |v: &[f64]| v.iter().map(|e| e.to_bits()).collect::<Vec<_>>();
    a.paths == b.paths
        && bits(&a.max_error) == bits(&b.max_error)
        && a.between_masters.map(f64::to_bits) == b.between_masters.map(f64::to_bits)
        && a.segments == b.segments
}

#[test]
fn compatible_fits_come_from_the_cache_bit_for_bit_and_an_edit_refits_one() {
    let (mut pairs, positions) = master_pairs();
    pairs.truncate(24);
    // A pair whose `s` differs too (the other way of bounding).
    let bold = crate::common::masters::bold(&pairs[3].0, 30.0, 0.9).unwrap();
    pairs.push((pairs[3].0.clone(), bold));
    let direct: Vec<CompatibleFit> = pairs
        .iter()
        .map(|(a, b)| fit_compatible(&[a, b], &positions, 0.5).unwrap())
        .collect();
    let path = temp_dir("compatible").join(".xglyph-cache");
    let cold = FitCache::new();
    for ((a, b), expected) in pairs.iter().zip(&direct) {
        let fit = cold.fit_compatible(&[a, b], &positions, 0.5).unwrap();
        assert!(same_compatible(&fit, expected));
    }
    let distinct = cold.misses();
    assert_eq!(distinct + cold.reused(), pairs.len());
    cold.save(&path).unwrap();
    let (warm, outcome) = FitCache::load(&path);
    assert_eq!(outcome, LoadOutcome::Loaded(distinct));
    for (k, ((a, b), expected)) in pairs.iter().zip(&direct).enumerate() {
        let fit = warm.fit_compatible(&[a, b], &positions, 0.5).unwrap();
        assert!(same_compatible(&fit, expected), "pair {k}");
    }
    assert_eq!((warm.hits(), warm.misses()), (pairs.len(), 0));
    assert_eq!(warm.to_bytes(), std::fs::read(&path).unwrap());
    // Each part of the key: the smallest change to one point's `s` in the second master,
    // one position fewer, another tolerance: a fit, not a hit.
    let (warm, _) = FitCache::load(&path);
    let (a, b) = &pairs[5];
    let mut points = b.points().to_vec();
    let k = points.iter().position(|p| p.s != 0.0).unwrap();
    points[k].s = f64::from_bits(points[k].s.to_bits() + 1);
    let edited = XSpline::new(points).unwrap();
    let fit = warm.fit_compatible(&[a, &edited], &positions, 0.5).unwrap();
    assert!(same_compatible(
        &fit,
        &fit_compatible(&[a, &edited], &positions, 0.5).unwrap()
    ));
    warm.fit_compatible(&[a, b], &positions[1..], 0.5).unwrap();
    warm.fit_compatible(&[a, b], &positions, 0.25).unwrap();
    assert_eq!((warm.hits(), warm.misses()), (0, 3));
    // The static fit of a master and its compatible fit are separate entries.
    let both = FitCache::new();
    both.fit(a, 0.5);
    both.fit_compatible(&[a, b], &positions, 0.5).unwrap();
    assert_eq!(both.misses(), 2);
    both.save(&path).unwrap();
    assert_eq!(FitCache::load(&path).1, LoadOutcome::Loaded(2));
}

#[test]
fn a_corrupt_or_stale_compatible_entry_is_ignored_and_refitted() {
    let (mut pairs, positions) = master_pairs();
    pairs.truncate(6);
    let direct: Vec<CompatibleFit> = pairs
        .iter()
        .map(|(a, b)| fit_compatible(&[a, b], &positions, 0.5).unwrap())
        .collect();
    let path = temp_dir("compatible-corrupt").join(".xglyph-cache");
    let good = {
        let cache = FitCache::new();
        for (a, b) in &pairs {
            cache.fit_compatible(&[a, b], &positions, 0.5).unwrap();
        }
        cache.to_bytes()
    };
    let n = good.len();
    let resign = |mut b: Vec<u8>| {
        b.truncate(b.len() - 4);
        let crc = crc32fast::hash(&b);
        b.extend_from_slice(&crc.to_le_bytes());
        b
    };
    let flip = |at: usize, mask: u8| {
        let mut b = good.clone();
        b[at] ^= mask;
        b
    };
    // Header: magic 8, format 4, fit version 4 and fingerprint 4, compatible version 4
    // (bytes 20..24) and fingerprint 4 (24..28), orientation version and fingerprint
    // (28..36), no orientation (36..44), no static entry (44..52), then the compatible
    // entries (52..60): the first one's tolerance (60..68) and master count (68..72).
    assert_eq!(&good[36..44], &0u64.to_le_bytes());
    assert_eq!(&good[44..52], &0u64.to_le_bytes());
    assert_eq!(&good[68..72], &2u32.to_le_bytes());
    let word = |at: usize| u32::from_le_bytes(good[at..at + 4].try_into().unwrap()) as usize;
    // Then its point and position counts, its points, its weights, and its segment count.
    let (points, count) = (word(72), word(76));
    assert_eq!(count, positions.len());
    let segments = 80 + 2 * points * 24 + count * 2 * 8;
    let stored_segments = word(segments) as u32;
    assert!(direct
        .iter()
        .any(|f| f.segments == stored_segments as usize));
    let mut cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "stale compatible fitter",
            resign(flip(20, 1)),
            "it was written by another version of the compatible fitter",
        ),
        (
            "stale compatible fingerprint",
            resign(flip(26, 4)),
            "it was written by another version of the compatible fitter",
        ),
        (
            "no masters",
            resign({
                let mut b = good.clone();
                b[68..72].copy_from_slice(&0u32.to_le_bytes());
                b
            }),
            "",
        ),
        (
            "a huge master count",
            resign({
                let mut b = good.clone();
                b[68..72].copy_from_slice(&u32::MAX.to_le_bytes());
                b
            }),
            "a count exceeds the file's size",
        ),
        (
            "a segment count that does not match the paths",
            resign({
                let mut b = good.clone();
                b[segments..segments + 4].copy_from_slice(&(stored_segments + 1).to_le_bytes());
                b
            }),
            "a compatible fit's paths differ in structure",
        ),
    ];
    for cut in [n - 1, n - 5, n - 40, n / 2, 60] {
        cases.push(("truncated", good[..cut].to_vec(), ""));
    }
    for at in (60..n).step_by((n - 60) / 17) {
        cases.push(("one bit flipped", flip(at, 0x08), ""));
    }
    for (what, bytes, reason) in cases {
        let cache = load_ignored(&path, &bytes, what, reason);
        for (k, ((a, b), expected)) in pairs.iter().zip(&direct).enumerate() {
            let fit = cache.fit_compatible(&[a, b], &positions, 0.5).unwrap();
            assert!(same_compatible(&fit, expected), "{what} at {k}");
        }
        assert_eq!(cache.hits(), 0, "{what}: nothing came from the file");
        // Rebuilt: the next save is the good file again.
        cache.save(&path).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), good, "{what}");
    }
}

/// SHA-256 of every file in `dir` but the records for the next run (the fit cache, the
/// output record, the source memo and their delta files), by relative path.
fn output_hashes(dir: &Path) -> std::collections::BTreeMap<String, Vec<u8>> {
    use sha2::{Digest, Sha256};
    let mut out = std::collections::BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if !path
                .file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with(".xglyph-")
            {
                let rel = path
                    .strip_prefix(dir)
                    .unwrap()
                    .to_string_lossy()
                    .into_owned();
                out.insert(rel, Sha256::digest(std::fs::read(&path).unwrap()).to_vec());
            }
        }
    }
    out
}

#[test]
fn a_warm_build_with_masters_fits_nothing_and_writes_the_same_bytes() {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/masters");
    let dir = temp_dir("build-masters");
    let build = |out: &Path| {
        let output = std::process::Command::new(env!("CARGO_BIN_EXE_xglyph"))
            .args([
                "build",
                fixture.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
            ])
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(0), "{output:?}");
        (
            String::from_utf8(output.stdout).unwrap(),
            String::from_utf8(output.stderr).unwrap(),
        )
    };
    let (cold, warm) = (dir.join("cold"), dir.join("warm"));
    let (stdout, _) = build(&cold);
    assert!(!stdout.contains("from the cache"), "{stdout}");
    // The file holds the default master's static fits, each master's static fits for the
    // summary and one compatible fit per contour.
    let (cache, outcome) = FitCache::load(&cold.join(".xglyph-cache"));
    drop(cache);
    let LoadOutcome::Loaded(entries) = outcome else {
        panic!("{outcome:?}")
    };
    std::fs::create_dir_all(&warm).unwrap();
    std::fs::copy(cold.join(".xglyph-cache"), warm.join(".xglyph-cache")).unwrap();
    let (stdout, _) = build(&warm);
    let line = stdout
        .lines()
        .find(|l| l.starts_with("refitted"))
        .unwrap_or_else(|| panic!("{stdout}"));
    // Hits count every fit handed out (a contour placed twice is two hits).
    let hits: usize = line
        .strip_prefix("refitted 0 contours; ")
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{line}"));
    assert!(hits >= entries, "{line}: {entries} entries");
    assert_eq!(output_hashes(&cold), output_hashes(&warm));
    // The same cache written again: the same bytes.
    assert_eq!(
        std::fs::read(cold.join(".xglyph-cache")).unwrap(),
        std::fs::read(warm.join(".xglyph-cache")).unwrap()
    );
    // A cache damaged in its compatible entries (the last bytes before the checksum) is
    // ignored with a note, and the outputs are the same again.
    let mut bytes = std::fs::read(warm.join(".xglyph-cache")).unwrap();
    let at = bytes.len() - 10;
    bytes[at] ^= 0x20;
    std::fs::write(warm.join(".xglyph-cache"), &bytes).unwrap();
    let (stdout, stderr) = build(&warm);
    assert!(
        stderr.contains("note: ignoring the fit cache") && stderr.contains("checksum"),
        "{stderr}"
    );
    assert!(!stdout.contains("from the cache"), "{stdout}");
    assert_eq!(output_hashes(&cold), output_hashes(&warm));
}

/// Writes `bytes` as the cache file at `path` and loads it: the load must ignore the file,
/// for `reason` (any reason when empty). Returns the (empty) cache.
fn load_ignored(path: &std::path::Path, bytes: &[u8], what: &str, reason: &str) -> FitCache {
    std::fs::write(path, bytes).unwrap();
    let (cache, outcome) = FitCache::load(path);
    match (&outcome, reason) {
        (LoadOutcome::Ignored(r), "") => assert!(!r.is_empty()),
        (LoadOutcome::Ignored(r), expected) => assert_eq!(r, expected, "{what}"),
        _ => panic!("{what}: {outcome:?}"),
    }
    cache
}

/// Waits until files written before have settled: the source memo gives a file by its
/// stamp only then (`xglyph::write::settled_meta`), so each load below does the same
/// whatever the machine's speed.
fn settle() {
    std::thread::sleep(xglyph::write::SETTLED * 2);
}

#[test]
fn a_settled_glyph_file_comes_from_the_memo_unread_and_any_change_to_it_is_seen() {
    use xglyph::source::{load_family, load_family_with, SourceMemo};
    let dir = memo_fixture("memo-stamps");
    let path = dir.with_file_name(xglyph::source::MEMO_FILE);
    // `(taken, taken unread, whether the memo is saved again)`, the family and diagnostics
    // being those of a load without memo.
    let load = || {
        let (memo, ignored) = SourceMemo::load(&path);
        assert_eq!(ignored, None);
        assert_eq!(load_family_with(&dir, &memo), load_family(&dir));
        let saved = !memo.files_to_save(&path).is_empty();
        memo.save(&path).unwrap();
        (memo.taken(), memo.taken_unread(), saved)
    };
    assert_eq!(load(), (0, 0, true));
    // The 8 clean files by their stamps (`blank` has a warning: never kept).
    assert_eq!(load(), (8, 8, false));

    // `o` edited to the same length, its modification time set back: its change time
    // moved, so it is read again.
    let o = dir.join("o.toml");
    let text = std::fs::read_to_string(&o).unwrap();
    let modified = std::fs::metadata(&o).unwrap().modified().unwrap();
    let moved = text.replacen("[520, 250, -1]", "[521, 250, -1]", 1);
    assert_eq!((moved.len(), moved != text), (text.len(), true));
    std::fs::write(&o, &moved).unwrap();
    let file = std::fs::File::options().write(true).open(&o).unwrap();
    file.set_modified(modified).unwrap();
    drop(file);
    assert_eq!(std::fs::metadata(&o).unwrap().modified().unwrap(), modified);
    settle();
    assert_eq!(load(), (7, 7, true));
    let (family, _) = load_family(&dir).unwrap();
    let o_glyph = family.default.glyphs.iter().find(|g| g.name == "o");
    assert_eq!(o_glyph.unwrap().contours[0].points()[0].pos.x, 521.0);
    assert_eq!(load(), (8, 8, false));

    // Written again with the same text: read, taken by its text and saved with its new
    // stamp, then unread again.
    std::fs::write(&o, &moved).unwrap();
    settle();
    assert_eq!(load(), (8, 7, true));
    assert_eq!(load(), (8, 8, false));

    // `A` given `oacute`'s code point: the error is at `oacute.toml`, a file the memo gave
    // unread, with its line, column and source line as without the memo (`load` compares).
    let a = dir.join("A_.toml");
    let a_text = std::fs::read_to_string(&a).unwrap();
    std::fs::write(&a, a_text.replacen("unicode = 0x41", "unicode = 0xF3", 1)).unwrap();
    settle();
    let (memo, _) = SourceMemo::load(&path);
    let failed = load_family_with(&dir, &memo).unwrap_err();
    assert_eq!(Err(failed.clone()), load_family(&dir));
    assert_eq!(memo.taken_unread(), 7);
    let at_oacute: Vec<String> = failed
        .iter()
        .filter(|d| d.path == dir.join("oacute.toml"))
        .map(|d| d.to_string())
        .collect();
    assert_eq!(
        at_oacute,
        [format!(
            "{}:2:11: error: code point U+00F3 is already mapped to `A`",
            dir.join("oacute.toml").display()
        )]
    );
}

/// The glyph files of `tests/fixtures/mini` and an empty glyph (a warning), copied.
fn memo_fixture(name: &str) -> PathBuf {
    let dir = temp_dir(name).join("src");
    std::fs::create_dir_all(&dir).unwrap();
    let mini = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini");
    for entry in std::fs::read_dir(mini).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, dir.join(path.file_name().unwrap())).unwrap();
    }
    std::fs::write(dir.join("blank.toml"), "name = \"blank\"\nadvance = 0\n").unwrap();
    settle();
    dir
}

/// Loads `dir` through the memo file `path` (saving it after) and without any memo: both
/// give the same family and diagnostics. Returns how many glyph files the memo gave.
fn load_through_memo(dir: &Path, path: &Path) -> usize {
    use xglyph::source::{load_family, load_family_with, SourceMemo};
    let (mut memo, ignored) = SourceMemo::load(path);
    assert_eq!(ignored, None);
    let through = load_family_with(dir, &memo);
    assert_eq!(through, load_family(dir));
    // As `build` does: the entries not taken are dropped before the save, which must
    // write what it would have written with them.
    let before = memo.files_to_save(path);
    memo.release_unused();
    assert_eq!(memo.files_to_save(path), before);
    memo.save(path).unwrap();
    memo.taken()
}

#[test]
fn an_edited_glyph_file_goes_into_the_memo_delta_and_a_bad_delta_is_ignored() {
    use xglyph::source::{load_family, load_family_with, SourceMemo, MEMO_FILE};
    // Twenty copies of `mini`'s `o`, so that one edit is within 1/8 of the memo.
    let dir = memo_fixture("memo-delta");
    let o = std::fs::read_to_string(dir.join("o.toml")).unwrap();
    for k in 0..20 {
        let copy = o
            .replacen("name = \"o\"", &format!("name = \"o{k}\""), 1)
            .replacen("unicode = 0x6F\n", "", 1);
        assert_ne!(copy, o);
        std::fs::write(dir.join(format!("o{k}.toml")), copy).unwrap();
    }
    settle();
    let path = dir.with_file_name(MEMO_FILE);
    let delta = xglyph::source::memo_delta_path(&path);
    assert_eq!(load_through_memo(&dir, &path), 0);
    assert_eq!(load_through_memo(&dir, &path), 28);
    let whole = std::fs::read(&path).unwrap();
    assert!(!delta.exists());

    // `o3` edited: parsed again, and only the delta file written.
    let o3 = dir.join("o3.toml");
    let text = std::fs::read_to_string(&o3).unwrap();
    let moved = text.replacen("[520, 250, -1]", "[525, 250, -1]", 1);
    assert_ne!(moved, text);
    std::fs::write(&o3, &moved).unwrap();
    settle();
    assert_eq!(load_through_memo(&dir, &path), 27);
    assert_eq!(std::fs::read(&path).unwrap(), whole);
    assert!(delta.exists());
    // Next: all 28 from the memo and its delta, the same family, nothing written.
    let (memo, ignored) = SourceMemo::load(&path);
    assert_eq!(ignored, None);
    assert_eq!(load_family_with(&dir, &memo), load_family(&dir));
    assert_eq!(memo.taken(), 28);
    assert!(memo.files_to_save(&path).is_empty());
    // The same folder spelled another way (`build src`, then `build /abs/path/src`): every
    // file still comes from the memo.
    let respelled = dir.join("..").join(dir.file_name().unwrap());
    let (memo, ignored) = SourceMemo::load(&path);
    assert_eq!(ignored, None);
    assert_eq!(load_family_with(&respelled, &memo), load_family(&respelled));
    assert_eq!(memo.taken(), 28);

    // A damaged delta, or one bound to another memo file, is ignored: `o3` is parsed again.
    let good = std::fs::read(&delta).unwrap();
    let mut flipped = good.clone();
    flipped[good.len() / 2] ^= 0x01;
    let mut rebound = good.clone();
    rebound[12] ^= 0x01; // the memo file's length it is bound to
    let body = rebound.len() - 4;
    let crc = crc32fast::hash(&rebound[..body]);
    rebound[body..].copy_from_slice(&crc.to_le_bytes());
    for damaged in [flipped, rebound] {
        std::fs::write(&delta, &damaged).unwrap();
        let (memo, ignored) = SourceMemo::load(&path);
        assert_eq!(ignored, None);
        assert_eq!(load_family_with(&dir, &memo), load_family(&dir));
        assert_eq!(memo.taken(), 27);
    }
}

#[test]
fn the_source_memo_gives_what_the_loader_gives_and_only_for_unchanged_clean_files() {
    use xglyph::source::{load_family, load_family_with, SourceMemo};
    let dir = memo_fixture("memo");
    let path = dir.with_file_name(xglyph::source::MEMO_FILE);
    assert_eq!(load_through_memo(&dir, &path), 0);
    // The 8 glyph files of `mini` come from the memo; `blank.toml` has a warning, so it is
    // read again (and the warning is there each time: the families and diagnostics match).
    assert_eq!(load_through_memo(&dir, &path), 8);
    let (_, warnings) = load_family(&dir).unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");

    // `o` edited: read again, the rest from the memo.
    let o = dir.join("o.toml");
    let text = std::fs::read_to_string(&o).unwrap();
    let moved = text.replacen("[520, 250, -1]", "[525, 250, -1]", 1);
    assert_ne!(moved, text);
    std::fs::write(&o, &moved).unwrap();
    settle();
    assert_eq!(load_through_memo(&dir, &path), 7);
    let (family, _) = load_family(&dir).unwrap();
    let o_glyph = family
        .default
        .glyphs
        .iter()
        .find(|g| g.name == "o")
        .unwrap();
    assert_eq!(o_glyph.contours[0].points()[0].pos.x, 525.0);

    // `o` broken: the error is reported as without the memo, though `o` was in it.
    std::fs::write(&o, moved.replacen("[525, 250, -1]", "[525, 250, 7]", 1)).unwrap();
    settle();
    let (memo, _) = SourceMemo::load(&path);
    let failed = load_family_with(&dir, &memo).unwrap_err();
    assert_eq!(Err(failed.clone()), load_family(&dir));
    assert!(failed.iter().any(|d| d.path == o), "{failed:?}");
    std::fs::write(&o, &moved).unwrap();
    settle();

    // A damaged, truncated or malformed memo is ignored with the reason; loading is
    // unchanged.
    let bytes = std::fs::read(&path).unwrap();
    let mut flipped = bytes.clone();
    flipped[bytes.len() / 2] ^= 0x01;
    // A byte added after the last entry, with a checksum that matches: refused all the same.
    let mut resealed = bytes[..bytes.len() - 4].to_vec();
    resealed.push(0);
    let crc = crc32fast::hash(&resealed);
    resealed.extend_from_slice(&crc.to_le_bytes());
    for (damaged, why) in [
        (
            flipped,
            "its checksum does not match (the file is damaged or truncated)",
        ),
        (bytes[..3].to_vec(), "the file is truncated"),
        (resealed, "bytes follow the last entry"),
    ] {
        std::fs::write(&path, &damaged).unwrap();
        let (memo, ignored) = SourceMemo::load(&path);
        assert_eq!(ignored.as_deref(), Some(why));
        assert_eq!(load_family_with(&dir, &memo), load_family(&dir));
        assert_eq!(memo.taken(), 0);
    }
}

/// `xglyph <command> <font> -o <out>`, which must succeed: (stdout, stderr).
fn run_in(command: &str, font: &Path, out: &Path) -> (String, String) {
    let args = [command, font.to_str().unwrap(), "-o", out.to_str().unwrap()];
    let (code, stdout, stderr) = xglyph(&args);
    assert_eq!(code, 0, "{args:?}: {stderr}");
    (stdout, stderr)
}

/// The numbers of the line `refitted N contours; M fits from the cache …` in `stdout`:
/// (N, M), if it has the line.
fn fits_line(stdout: &str) -> Option<(usize, usize)> {
    let line = stdout.lines().find(|l| l.starts_with("refitted "))?;
    let words: Vec<&str> = line.split(' ').collect();
    let misses = words[1].parse().unwrap_or_else(|_| panic!("{line}"));
    let hits = words[3].parse().unwrap_or_else(|_| panic!("{line}"));
    Some((misses, hits))
}

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

/// `path` with one byte in its middle changed.
fn damage(path: &Path) {
    let mut bytes = std::fs::read(path).unwrap();
    let at = bytes.len() / 2;
    bytes[at] ^= 0x20;
    std::fs::write(path, bytes).unwrap();
}

#[test]
fn svg_again_takes_every_fit_from_the_cache_and_writes_the_same_bytes() {
    let mini = fixture("mini");
    let dir = temp_dir("svg-again");
    let (out, cold, built) = (dir.join("out"), dir.join("cold"), dir.join("built"));
    let cache_path = out.join(CACHE_FILE);
    let memo_path = out.join(xglyph::source::MEMO_FILE);
    let wrote = format!(
        "wrote 9 files to {} (SVG font and 8 glyph SVGs)\n",
        out.display()
    );
    // The first run fits every contour and leaves the cache and the memo in OUT: the same
    // fits as a build of this font (no masters) leaves, byte for byte.
    assert_eq!(run_in("svg", &mini, &out), (wrote.clone(), String::new()));
    let first = output_hashes(&out);
    assert_eq!(first.len(), 9);
    assert!(memo_path.is_file());
    run_in("build", &mini, &built);
    assert_eq!(
        std::fs::read(&cache_path).unwrap(),
        std::fs::read(built.join(CACHE_FILE)).unwrap()
    );
    let (_, outcome) = FitCache::load(&cache_path);
    let LoadOutcome::Loaded(entries) = outcome else {
        panic!("{outcome:?}")
    };
    assert!(entries >= 8, "{entries}");
    // Again: every fit from the cache, nothing refitted, the same bytes as the first run
    // and as a run without the cache; the cache file is left as it was.
    let cache_bytes = std::fs::read(&cache_path).unwrap();
    let (stdout, stderr) = run_in("svg", &mini, &out);
    assert_eq!(stderr, "");
    let (misses, hits) = fits_line(&stdout).unwrap_or_else(|| panic!("{stdout}"));
    assert_eq!(misses, 0, "{stdout}");
    assert!(hits >= entries, "{stdout}");
    assert_eq!(
        stdout,
        format!(
            "{wrote}refitted 0 contours; {hits} fits from the cache {}\n",
            cache_path.display()
        )
    );
    assert_eq!(output_hashes(&out), first);
    assert_eq!(std::fs::read(&cache_path).unwrap(), cache_bytes);
    run_in("svg", &mini, &cold);
    assert_eq!(output_hashes(&cold), first);
    // A damaged cache is ignored with a note (every contour refitted, the same bytes), and
    // written anew: the next run takes its fits from it again.
    damage(&cache_path);
    let (stdout, stderr) = run_in("svg", &mini, &out);
    assert!(
        stderr.starts_with(&format!(
            "note: ignoring the fit cache {}: ",
            cache_path.display()
        )) && stderr.contains("checksum")
            && stderr.ends_with("; every contour is refitted\n"),
        "{stderr}"
    );
    assert_eq!(stdout, wrote);
    assert_eq!(output_hashes(&out), first);
    assert_eq!(std::fs::read(&cache_path).unwrap(), cache_bytes);
    let (stdout, _) = run_in("svg", &mini, &out);
    assert_eq!(fits_line(&stdout), Some((0, hits)));
    // So is a damaged source memo (every glyph file read anew).
    damage(&memo_path);
    let (stdout, stderr) = run_in("svg", &mini, &out);
    assert!(
        stderr.starts_with(&format!("note: ignoring {}: ", memo_path.display()))
            && stderr.ends_with("; every glyph file is read anew\n"),
        "{stderr}"
    );
    assert_eq!(fits_line(&stdout), Some((0, hits)));
    assert_eq!(output_hashes(&out), first);
    let (_, stderr) = run_in("svg", &mini, &out);
    assert_eq!(stderr, "");
}

#[test]
fn build_after_svg_in_one_out_writes_what_build_alone_writes_and_refits_nothing_svg_kept() {
    for name in ["mini", "masters"] {
        let font = fixture(name);
        let dir = temp_dir(&format!("svg-build-{name}"));
        let (alone, shared) = (dir.join("alone"), dir.join("shared"));
        run_in("build", &font, &alone);
        let expected = output_hashes(&alone);
        // `svg` first: the build takes the default master's fits from it (all of them
        // without masters), and writes what a build alone writes.
        run_in("svg", &font, &shared);
        let (stdout, _) = run_in("build", &font, &shared);
        let (misses, hits) = fits_line(&stdout).unwrap_or_else(|| panic!("{name}: {stdout}"));
        assert!(hits > 0, "{name}: {stdout}");
        assert_eq!(misses == 0, name == "mini", "{name}: {stdout}");
        assert_eq!(output_hashes(&shared), expected, "{name}");
        // `svg` between two builds takes its fits from the build's cache and keeps the
        // entries it does not use (with masters: the compatible fits, the named
        // instances), so the next build fits nothing.
        let (stdout, _) = run_in("svg", &font, &shared);
        assert_eq!(fits_line(&stdout).map(|f| f.0), Some(0), "{name}: {stdout}");
        let (stdout, _) = run_in("build", &font, &shared);
        assert_eq!(fits_line(&stdout).map(|f| f.0), Some(0), "{name}: {stdout}");
        assert_eq!(output_hashes(&shared), expected, "{name}");
    }
}

#[test]
fn svg_of_a_font_without_masters_drops_the_fits_of_an_edited_glyph_as_build_does() {
    let dir = temp_dir("svg-edit");
    let font = dir.join("font");
    std::fs::create_dir_all(&font).unwrap();
    for entry in std::fs::read_dir(fixture("mini")).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, font.join(path.file_name().unwrap())).unwrap();
    }
    let (out, cold) = (dir.join("out"), dir.join("cold"));
    run_in("build", &font, &out);
    let o = font.join("o.toml");
    let text = std::fs::read_to_string(&o).unwrap();
    assert!(text.contains("[520, 250, -1]"));
    std::fs::write(&o, text.replace("[520, 250, -1]", "[530, 250, -1]")).unwrap();
    let (stdout, _) = run_in("svg", &font, &out);
    // The outer contour of `o` refitted (counted twice when two threads fit it at once
    // for `o` and for `oacute`, where it is placed alike).
    let misses = fits_line(&stdout).map(|f| f.0);
    assert!(matches!(misses, Some(1 | 2)), "{stdout}");
    // The cache now holds what a first `svg` of the edited font leaves: the old contour's
    // fit is gone.
    run_in("svg", &font, &cold);
    assert_eq!(
        std::fs::read(out.join(CACHE_FILE)).unwrap(),
        std::fs::read(cold.join(CACHE_FILE)).unwrap()
    );
    // Its SVGs are those of the edited font (`build` left its other outputs beside them).
    let (now, svg_only) = (output_hashes(&out), output_hashes(&cold));
    for (path, hash) in &svg_only {
        assert_eq!(now.get(path), Some(hash), "{path}");
    }
}

#[test]
fn render_takes_its_fits_from_a_build_into_the_same_out_and_draws_the_same_bytes() {
    for name in ["mini", "masters"] {
        let font = fixture(name);
        let dir = temp_dir(&format!("render-cache-{name}"));
        let (shared, cold) = (dir.join("shared"), dir.join("cold"));
        let images = |out: &Path| -> Vec<Vec<u8>> {
            ["sheet.png", "proof.png"]
                .iter()
                .map(|f| std::fs::read(out.join(f)).unwrap())
                .collect()
        };
        // Alone, `render` fits every contour and says nothing of a cache.
        let (stdout, stderr) = run_in("render", &font, &cold);
        assert_eq!(stderr, "", "{name}");
        assert_eq!(fits_line(&stdout), None, "{name}: {stdout}");
        let expected = images(&cold);
        // After a build into the same OUT, every fit of the default master comes from the
        // build's cache; the images are the same bytes.
        run_in("build", &font, &shared);
        let (stdout, stderr) = run_in("render", &font, &shared);
        assert_eq!(stderr, "", "{name}");
        let (misses, hits) = fits_line(&stdout).unwrap_or_else(|| panic!("{name}: {stdout}"));
        assert_eq!(misses, 0, "{name}: {stdout}");
        assert!(hits > 0, "{name}: {stdout}");
        assert_eq!(images(&shared), expected, "{name}");
        // `render` keeps what the build needs: the next build refits nothing.
        let (stdout, _) = run_in("build", &font, &shared);
        assert_eq!(fits_line(&stdout).map(|f| f.0), Some(0), "{name}: {stdout}");
        // A damaged cache is ignored with a note, and the images are the same bytes.
        damage(&shared.join(CACHE_FILE));
        let (stdout, stderr) = run_in("render", &font, &shared);
        assert!(
            stderr.ends_with("; every contour is refitted\n"),
            "{name}: {stderr}"
        );
        assert_eq!(fits_line(&stdout), None, "{name}: {stdout}");
        assert_eq!(images(&shared), expected, "{name}");
    }
}
