//! A cache of fitted contours, so that a rebuild refits only the contours that changed.
//!
//! Three kinds of entries:
//! - a static fit ([`FitCache::fit`], [`fit_contour`]), keyed by everything it depends on:
//!   the contour's control points as placed (the exact bits of every `x`, `y` and `s`) and
//!   the tolerance (its bits);
//! - a compatible fit of a font with masters ([`FitCache::fit_compatible`],
//!   [`fit_compatible`]), keyed by every master's control points (bits of `x`, `y`, `s`),
//!   the positions checked (the bits of every blend weight) and the tolerance. Its entry
//!   holds the paths of every master and the error measured at every position, so a hit
//!   neither fits nor checks;
//! - a glyph's orientation ([`FitCache::orient_placed`], [`crate::orient::reversals`]):
//!   which of its fitted contours are reversed, keyed by the SHA-256 of the tolerance and
//!   every contour's control points and placement (what the fits, and so their nesting,
//!   depend on), for glyphs of two contours or more. A rebuild orients only the glyphs
//!   that changed (orienting a CJK font's 136,000 contours took a tenth of its rebuild).
//!
//! The whole file is further keyed by the fitters: [`FIT_VERSION`],
//! [`COMPATIBLE_VERSION`] and [`ORIENT_VERSION`], and a fingerprint of each one's output on a
//! fixed probe contour (and a bold master of it, and nested copies of it), so that a changed fitter invalidates the cache even
//! when nobody bumped a version. The cache lives in the output folder ([`CACHE_FILE`] in
//! OUT), never beside the sources.
//!
//! The file is not trusted. It is read whole and checked before any entry is used: magic,
//! format version, fitter key, a CRC-32 of everything before it, every count against the
//! bytes that remain, every number finite, every path one closed contour of lines and
//! cubics, a compatible fit's paths all of the same elements with its segment count and one
//! error per position of its key, no duplicate key and no trailing byte. If anything is wrong the whole file is
//! ignored (every contour is refitted) and the next [`FitCache::save`] replaces it. A cached
//! fit is bit-for-bit the fit it stored, so outputs are the same with and without the cache.
//!
//! The file holds the entries used by the last run that wrote it whole (entries of deleted
//! or edited contours are dropped), sorted by key, so the same input writes the same bytes.
//! A run that used every entry of the files it loaded and fitted nothing new leaves them
//! alone (a CJK font's cache is 100 MB). A run that changed few entries writes only a small
//! delta file beside it ([`DELTA_FILE`], the same layout with its own magic, bound to the
//! cache file by its length and checksum; [`FitCache::files_to_save`]): the entries it made
//! and those of the last delta it used. Limit: until the cache file is written whole again
//! (when the delta and the cache file's unused entries pass 1/8 of its entries), it keeps
//! the entries of edited contours, and the two files depend on the order of the edits, not
//! only on the sources. A hit is not copied into a second map: each
//! loaded entry carries a flag saying whether this run used it. It is
//! written atomically ([`crate::write::write_atomic`]). Limit: a deliberately forged file
//! with a valid checksum is trusted; the cache is the user's own file in their output
//! folder, not an input from others.
//!
//! [`FitCache::fit`] may be called from many threads at once.

use std::collections::BTreeMap;
use std::fs;
use std::io;
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};

use kurbo::{Affine, BezPath, PathEl};
use rustc_hash::FxHashMap;
use sha2::{Digest, Sha256};

use crate::compatible::{fit_compatible, CompatibleError, CompatibleFit};
use crate::fit::{fit_contour, ContourFit};
use crate::orient::{join_reversed, reversals, ORIENT_VERSION};
use crate::outline::PlacedContour;
use crate::record::{put_path, Header, Reader};
use crate::xspline::{ControlPoint, XSpline};

/// Name of the cache file in the output folder.
pub const CACHE_FILE: &str = ".xglyph-cache";

/// Name of the delta file beside it: the entries made since the cache file was last
/// written whole ([`FitCache::files_to_save`]).
pub const DELTA_FILE: &str = ".xglyph-cache-delta";

/// The delta file may hold at most this fraction (1 / n) of the cache file's entry count,
/// counting with it the cache file's entries no longer used; beyond, the cache file is
/// written whole again.
const DELTA_SHARE: usize = 8;

/// Version of the fitter's output: bump it whenever [`crate::fit`] changes what it returns.
/// (The fingerprint catches most changes anyway; the version makes the intent explicit.)
pub const FIT_VERSION: u32 = 5;

/// Version of the compatible fitter's output: bump it whenever [`crate::compatible`]
/// changes what it returns (paths, errors or the bound between the masters).
pub const COMPATIBLE_VERSION: u32 = 5;

/// Layout of the file itself.
const FORMAT_VERSION: u32 = 4;
/// The frame of a cache file.
const HEADER: Header = Header {
    magic: b"XGLYPHFC",
    version: FORMAT_VERSION,
    not_ours: "it is not an xglyph cache file",
};
/// The frame of a delta file.
const DELTA_HEADER: Header = Header {
    magic: b"XGLYPHFD",
    version: FORMAT_VERSION,
    not_ours: "it is not an xglyph cache delta file",
};

/// What binds a delta file to its cache file: the cache file's length and checksum.
#[derive(Clone, Copy, Debug, PartialEq)]
struct BaseFile {
    len: u64,
    crc: u32,
}

impl BaseFile {
    /// The binding of a cache file's `bytes` (its last four bytes are its checksum).
    fn of(bytes: &[u8]) -> BaseFile {
        let crc = bytes
            .split_last_chunk::<4>()
            .map_or(0, |(_, crc)| u32::from_le_bytes(*crc));
        BaseFile {
            len: bytes.len() as u64,
            crc,
        }
    }
}

/// The delta file beside the cache file at `path`.
pub fn delta_path(path: &Path) -> std::path::PathBuf {
    path.with_file_name(DELTA_FILE)
}

/// What a fit depends on: the control points (bits of x, y, s) and the tolerance (bits).
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
struct Key {
    tolerance: u64,
    points: Vec<[u64; 3]>,
}

impl Key {
    fn new(spline: &XSpline, tolerance: f64) -> Key {
        Key {
            tolerance: tolerance.to_bits(),
            points: spline
                .points()
                .iter()
                .map(|p| [p.pos.x.to_bits(), p.pos.y.to_bits(), p.s.to_bits()])
                .collect(),
        }
    }
}

/// What a compatible fit depends on: the tolerance, the positions (bits of every weight)
/// and every master's control points (bits of x, y, s).
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
struct CompatibleKey {
    tolerance: u64,
    positions: Vec<Vec<u64>>,
    masters: Vec<Vec<[u64; 3]>>,
}

impl CompatibleKey {
    fn new(masters: &[&XSpline], positions: &[Vec<f64>], tolerance: f64) -> CompatibleKey {
        CompatibleKey {
            tolerance: tolerance.to_bits(),
            positions: positions
                .iter()
                .map(|w| w.iter().map(|v| v.to_bits()).collect())
                .collect(),
            masters: masters
                .iter()
                .map(|m| Key::new(m, tolerance).points)
                .collect(),
        }
    }
}

/// What a glyph's orientation depends on: the SHA-256 of the tolerance and of each
/// contour's control points (bits of x, y, s) and placement (bits of the offset), in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
struct GlyphKey([u8; 32]);

impl GlyphKey {
    fn new(contours: &[PlacedContour], tolerance: f64) -> GlyphKey {
        let points: usize = contours.iter().map(|c| c.spline.points().len()).sum();
        let mut buf = Vec::with_capacity(16 + contours.len() * 20 + points * 24);
        buf.extend_from_slice(&tolerance.to_bits().to_le_bytes());
        buf.extend_from_slice(&(contours.len() as u64).to_le_bytes());
        for c in contours {
            buf.extend_from_slice(&c.offset.x.to_bits().to_le_bytes());
            buf.extend_from_slice(&c.offset.y.to_bits().to_le_bytes());
            buf.extend_from_slice(&(c.spline.points().len() as u32).to_le_bytes());
            for p in c.spline.points() {
                for v in [p.pos.x, p.pos.y, p.s] {
                    buf.extend_from_slice(&v.to_bits().to_le_bytes());
                }
            }
        }
        GlyphKey(Sha256::digest(&buf).into())
    }
}

/// The entries of a cache file, or of one run.
#[derive(Debug, Default)]
struct Entries {
    fits: BTreeMap<Key, ContourFit>,
    compatible: BTreeMap<CompatibleKey, CompatibleFit>,
    /// Per glyph, which of its contours are reversed.
    orient: BTreeMap<GlyphKey, Vec<bool>>,
}

/// The entries of a cache file or delta file as loaded, by key, none used yet.
#[derive(Debug, Default)]
struct Loaded {
    fits: FxHashMap<Key, FromFile<ContourFit>>,
    compatible: FxHashMap<CompatibleKey, FromFile<CompatibleFit>>,
    orient: FxHashMap<GlyphKey, FromFile<Vec<bool>>>,
}

/// What happened to the cache file when it was loaded.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadOutcome {
    /// There was no cache file: every contour is fitted.
    Missing,
    /// The file was valid; it held this many entries (static and compatible fits), with
    /// those of its delta file ([`DELTA_FILE`]).
    Loaded(usize),
    /// The file was unreadable, corrupt or stale, and is ignored; the reason.
    Ignored(String),
}

/// An entry of the cache file (or its delta file), and whether this run used it.
#[derive(Debug)]
struct FromFile<T> {
    fit: T,
    used: AtomicBool,
    /// Whether it came from the delta file.
    in_delta: bool,
}

impl<T> FromFile<T> {
    fn new(fit: T) -> Self {
        FromFile {
            fit,
            used: AtomicBool::new(false),
            in_delta: false,
        }
    }
}

/// Fitted contours by key: those loaded from the file, and those made in this run.
#[derive(Debug, Default)]
pub struct FitCache {
    /// From the file, read-only while fitting (but for the flags).
    loaded: FxHashMap<Key, FromFile<ContourFit>>,
    loaded_compatible: FxHashMap<CompatibleKey, FromFile<CompatibleFit>>,
    loaded_orient: FxHashMap<GlyphKey, FromFile<Vec<bool>>>,
    /// The file they came from.
    source: Option<std::path::PathBuf>,
    /// That file's binding and entry count, and the entries its delta file added.
    base: Option<(BaseFile, usize)>,
    delta_entries: usize,
    /// Loaded entries used in this run.
    loaded_used: AtomicUsize,
    /// Fits made in this run (not in the file): with the loaded entries used, what
    /// [`FitCache::save`] writes.
    made: Mutex<Entries>,
    hits: AtomicUsize,
    reused: AtomicUsize,
    misses: AtomicUsize,
}

impl FitCache {
    /// An empty cache: every contour is fitted (and remembered for [`FitCache::save`]).
    pub fn new() -> FitCache {
        FitCache::default()
    }

    /// Loads the cache file at `path`; a missing, unreadable, corrupt or stale file gives
    /// an empty cache and says why.
    pub fn load(path: &Path) -> (FitCache, LoadOutcome) {
        let bytes = match fs::read(path) {
            Ok(bytes) => bytes,
            Err(e) if e.kind() == io::ErrorKind::NotFound => {
                return (FitCache::new(), LoadOutcome::Missing)
            }
            Err(e) => return (FitCache::new(), LoadOutcome::Ignored(e.to_string())),
        };
        match decode(&bytes) {
            Ok(entries) => {
                let base = BaseFile::of(&bytes);
                drop(bytes);
                let all = entries.fits.len() + entries.compatible.len() + entries.orient.len();
                let mut cache = FitCache {
                    loaded: entries.fits,
                    loaded_compatible: entries.compatible,
                    loaded_orient: entries.orient,
                    source: Some(path.to_path_buf()),
                    base: Some((base, all)),
                    ..FitCache::default()
                };
                cache.add_delta(path, base);
                let n = cache.loaded.len() + cache.loaded_compatible.len();
                (cache, LoadOutcome::Loaded(n))
            }
            Err(reason) => (FitCache::new(), LoadOutcome::Ignored(reason.into())),
        }
    }

    /// Adds the entries of the delta file beside `path` when it is whole and bound to the
    /// cache file `base`; otherwise it is ignored (its contours are fitted again), as the
    /// one a whole rewrite of the cache file leaves behind is. An entry already loaded
    /// keeps the cache file's copy.
    fn add_delta(&mut self, path: &Path, base: BaseFile) {
        let Ok(bytes) = fs::read(delta_path(path)) else {
            return;
        };
        let Ok(entries) = decode_delta(&bytes, base) else {
            return;
        };
        fn merge<K: std::hash::Hash + Eq, T>(
            into: &mut FxHashMap<K, FromFile<T>>,
            from: FxHashMap<K, FromFile<T>>,
        ) -> usize {
            let mut added = 0;
            for (k, entry) in from {
                if let std::collections::hash_map::Entry::Vacant(v) = into.entry(k) {
                    v.insert(FromFile {
                        in_delta: true,
                        ..entry
                    });
                    added += 1;
                }
            }
            added
        }
        self.delta_entries = merge(&mut self.loaded, entries.fits)
            + merge(&mut self.loaded_compatible, entries.compatible)
            + merge(&mut self.loaded_orient, entries.orient);
    }

    /// [`fit_contour`]`(spline, tolerance)`, from the cache when it holds this contour.
    pub fn fit(&self, spline: &XSpline, tolerance: f64) -> ContourFit {
        let key = Key::new(spline, tolerance);
        if let Some(entry) = self.loaded.get(&key) {
            self.hit(&entry.used);
            return entry.fit.clone();
        }
        // The same contour placed twice in this run (a component at the same offset).
        if let Some(fit) = self.lock_made().fits.get(&key) {
            self.reused.fetch_add(1, Ordering::Relaxed);
            return fit.clone();
        }
        self.misses.fetch_add(1, Ordering::Relaxed);
        // Fitted outside the lock; two threads fitting the same new contour at once both
        // get the same (deterministic) fit.
        let fit = fit_contour(spline, tolerance);
        self.lock_made().fits.insert(key, fit.clone());
        fit
    }

    /// [`fit_compatible`]`(masters, positions, tolerance)`, from the cache when it holds
    /// these masters at these positions; counted with the static fits in
    /// [`FitCache::hits`], [`FitCache::reused`] and [`FitCache::misses`]. An error is
    /// not cached (the loader refuses such masters; they are refitted every time).
    pub fn fit_compatible(
        &self,
        masters: &[&XSpline],
        positions: &[Vec<f64>],
        tolerance: f64,
    ) -> Result<CompatibleFit, CompatibleError> {
        let key = CompatibleKey::new(masters, positions, tolerance);
        if let Some(entry) = self.loaded_compatible.get(&key) {
            self.hit(&entry.used);
            return Ok(entry.fit.clone());
        }
        if let Some(fit) = self.lock_made().compatible.get(&key) {
            self.reused.fetch_add(1, Ordering::Relaxed);
            return Ok(fit.clone());
        }
        self.misses.fetch_add(1, Ordering::Relaxed);
        let fit = fit_compatible(masters, positions, tolerance)?;
        self.lock_made().compatible.insert(key, fit.clone());
        Ok(fit)
    }

    /// `fitted` (the fits of `placed`, in order) oriented and joined as
    /// [`crate::orient::orient_contours`] does, with the reversals from the cache when it
    /// holds this glyph (a glyph of two contours or more; one contour is oriented by its
    /// area alone).
    pub fn orient_placed(
        &self,
        placed: &[PlacedContour],
        tolerance: f64,
        fitted: Vec<BezPath>,
    ) -> BezPath {
        if fitted.len() < 2 || fitted.len() != placed.len() {
            return crate::orient::orient_contours(fitted);
        }
        let key = GlyphKey::new(placed, tolerance);
        if let Some(entry) = self.loaded_orient.get(&key) {
            if entry.fit.len() == fitted.len() {
                self.mark_used(&entry.used);
                return join_reversed(&fitted, &entry.fit);
            }
        }
        if let Some(flags) = self.lock_made().orient.get(&key) {
            if flags.len() == fitted.len() {
                return join_reversed(&fitted, flags);
            }
        }
        let flags = reversals(&fitted);
        let path = join_reversed(&fitted, &flags);
        self.lock_made().orient.insert(key, flags);
        path
    }

    /// Counts a hit on a loaded entry whose flag is `used`.
    fn hit(&self, used: &AtomicBool) {
        self.hits.fetch_add(1, Ordering::Relaxed);
        self.mark_used(used);
    }

    /// Marks a loaded entry used (counted once).
    fn mark_used(&self, used: &AtomicBool) {
        if !used.swap(true, Ordering::Relaxed) {
            self.loaded_used.fetch_add(1, Ordering::Relaxed);
        }
    }

    fn lock_made(&self) -> std::sync::MutexGuard<'_, Entries> {
        // A poisoned lock only means another thread panicked; every entry in the map was
        // inserted whole.
        self.made.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Contours served from the cache file so far.
    pub fn hits(&self) -> usize {
        self.hits.load(Ordering::Relaxed)
    }

    /// Contours served from a fit made earlier in this run (the same contour placed twice).
    pub fn reused(&self) -> usize {
        self.reused.load(Ordering::Relaxed)
    }

    /// Contours fitted so far (neither in the cache file nor fitted earlier in this run).
    pub fn misses(&self) -> usize {
        self.misses.load(Ordering::Relaxed)
    }

    /// The cache file's bytes: every fit used in this run, sorted by key.
    pub fn to_bytes(&self) -> Vec<u8> {
        let made = self.lock_made();
        let fits = used_and_made(&self.loaded, &made.fits);
        let compatible = used_and_made(&self.loaded_compatible, &made.compatible);
        let orient = used_and_made(&self.loaded_orient, &made.orient);
        encode(&fits, &compatible, &orient)
    }

    /// Whether the file at `path` already holds [`FitCache::to_bytes`]: it is the file this
    /// cache was loaded from, every entry of it was used, and nothing new was fitted.
    fn file_is_current(&self, path: &Path) -> bool {
        let made = self.lock_made();
        self.source.as_deref() == Some(path)
            && made.fits.is_empty()
            && made.compatible.is_empty()
            && made.orient.is_empty()
            && self.loaded_used.load(Ordering::Relaxed)
                == self.loaded.len() + self.loaded_compatible.len() + self.loaded_orient.len()
    }

    /// Writes the fits used in this run to `path` (or only its delta file:
    /// [`FitCache::files_to_save`]), atomically; nothing when the files there already
    /// hold them.
    pub fn save(&self, path: &Path) -> io::Result<()> {
        for (path, bytes) in self.files_to_save(path) {
            crate::write::write_atomic(&path, &bytes)?;
        }
        Ok(())
    }

    /// What [`FitCache::save`] writes: nothing when the files at `path` hold every entry
    /// this run used and nothing new was made; only the delta file ([`DELTA_FILE`]: the
    /// entries made in this run and those of the last delta file it used, bound to the
    /// cache file) when the cache file at `path` is the one loaded and its unused entries
    /// and the delta's together are at most one eighth of its entries, so that an
    /// edit of one glyph does not rewrite a CJK font's 100 MB; else the cache file whole
    /// ([`FitCache::to_bytes`]), which leaves any delta file bound to the old one.
    pub fn files_to_save(&self, path: &Path) -> Vec<(std::path::PathBuf, Vec<u8>)> {
        if self.file_is_current(path) {
            return Vec::new();
        }
        if let (Some((base, base_entries)), true) =
            (self.base, self.source.as_deref() == Some(path))
        {
            let made = self.lock_made();
            let made_n = made.fits.len() + made.compatible.len() + made.orient.len();
            let (base_unused, delta_used) = [
                usage(&self.loaded),
                usage(&self.loaded_compatible),
                usage(&self.loaded_orient),
            ]
            .iter()
            .fold((0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
            if (base_unused + delta_used + made_n) * DELTA_SHARE <= base_entries {
                // The delta file already holds what it would be given.
                if made_n == 0 && delta_used == self.delta_entries {
                    return Vec::new();
                }
                let fits = used_and_made_delta(&self.loaded, &made.fits);
                let compatible = used_and_made_delta(&self.loaded_compatible, &made.compatible);
                let orient = used_and_made_delta(&self.loaded_orient, &made.orient);
                let bytes = encode_delta(base, &fits, &compatible, &orient);
                return vec![(delta_path(path), bytes)];
            }
        }
        vec![(path.to_path_buf(), self.to_bytes())]
    }

    /// What [`FitCache::save`] would write to `path`, as the whole file: `None` when the
    /// file there already holds it.
    pub fn bytes_to_save(&self, path: &Path) -> Option<Vec<u8>> {
        (!self.file_is_current(path)).then(|| self.to_bytes())
    }
}

/// The fitters' key: each fitter's version and the bits of its fit of a fixed probe: a
/// contour of mixed sharp, approximating and interpolating points at a tolerance that needs
/// several cubics, and for the compatible fitter that contour with a bold master of the
/// same `s` and one of other `s` values (its two ways of bounding).
fn fitter_key() -> [u32; 6] {
    static KEY: OnceLock<[u32; 6]> = OnceLock::new();
    *KEY.get_or_init(|| {
        let contour = |points: &[(f64, f64, f64)]| {
            XSpline::new(
                points
                    .iter()
                    .map(|&(x, y, s)| ControlPoint::new(x, y, s))
                    .collect(),
            )
        };
        let light = [
            (0.0, 0.0, 0.0),
            (400.0, -30.0, 1.0),
            (620.0, 250.0, -1.0),
            (450.0, 700.0, 0.5),
            (120.0, 640.0, -0.4),
            (60.0, 320.0, 0.0),
        ];
        let bold = |s_scale: f64| -> Vec<(f64, f64, f64)> {
            light
                .iter()
                .map(|&(x, y, s)| (1.1 * x - 20.0, 1.05 * y - 10.0, s_scale * s))
                .collect()
        };
        // A probe that XSpline's rules ever reject still gives a key that differs from any
        // earlier one.
        let probe = contour(&light)
            .ok()
            .map(|spline| fit_contour(&spline, 0.25));
        let static_print = match &probe {
            Some(fit) => {
                let mut bytes = Vec::new();
                put_fit(&mut bytes, fit);
                crc32fast::hash(&bytes)
            }
            None => u32::MAX,
        };
        // Orientation: the probe, a smaller copy inside it, one inside that, and a copy
        // beside it crossing its edge, all in the probe's direction.
        let orient_print = match &probe {
            Some(fit) => {
                let copies = [
                    Affine::IDENTITY,
                    Affine::translate((150.0, 150.0)) * Affine::scale(0.5),
                    Affine::translate((220.0, 220.0)) * Affine::scale(0.25),
                    Affine::translate((500.0, 0.0)),
                ];
                let contours: Vec<BezPath> = copies.iter().map(|&a| a * fit.path.clone()).collect();
                reversals(&contours)
                    .iter()
                    .fold(0u32, |bits, &r| (bits << 1) | u32::from(r))
            }
            None => u32::MAX,
        };
        let positions: Vec<Vec<f64>> = [0.0, 0.3, 1.0].iter().map(|t| vec![1.0 - t, *t]).collect();
        let mut bytes = Vec::new();
        for s_scale in [1.0, 0.8] {
            match (contour(&light), contour(&bold(s_scale))) {
                (Ok(a), Ok(b)) => match fit_compatible(&[&a, &b], &positions, 0.25) {
                    Ok(fit) => put_compatible_fit(&mut bytes, &fit),
                    Err(_) => bytes.push(0xFF),
                },
                _ => bytes.push(0xFE),
            }
        }
        [
            FIT_VERSION,
            static_print,
            COMPATIBLE_VERSION,
            crc32fast::hash(&bytes),
            ORIENT_VERSION,
            orient_print,
        ]
    })
}

// File layout, little-endian:
//   magic (8) | format version u32 | fit version u32 | fit fingerprint u32
//   | compatible version u32 | compatible fingerprint u32
//   | orientation version u32 | orientation fingerprint u32
//   | orientation entry count u64 | orientation entries
//   | static entry count u64 | static entries | compatible entry count u64 | compatible entries
//   | CRC-32 of everything before it, u32
// An orientation entry: glyph key (32) | contour count u32 | one byte per contour (1:
//   reversed, 0: kept)
// A static entry: tolerance u64 | point count u32 | points (x, y, s as u64 bits) | fit
// A fit: max_error f64 | path
// A path: element count u32 | elements (tag u8, points as f64 bits)
// A compatible entry: tolerance u64 | master count u32 | point count u32 | position count u32
//   | points (per master, x, y, s as u64 bits) | weights (per position, one per master)
//   | segments u32 | between_masters (u8 0, or u8 1 and f64) | max_error (f64 per position)
//   | one path per master

/// The loaded entries this run used and those it made, sorted by key (no key is in both:
/// a fit is made only when the file lacks it).
fn used_and_made<'a, K: Ord + std::hash::Hash, T>(
    loaded: &'a FxHashMap<K, FromFile<T>>,
    made: &'a BTreeMap<K, T>,
) -> Vec<(&'a K, &'a T)> {
    let mut all: Vec<(&K, &T)> = loaded
        .iter()
        .filter(|(_, e)| e.used.load(Ordering::Relaxed))
        .map(|(k, e)| (k, &e.fit))
        .chain(made.iter())
        .collect();
    all.sort_unstable_by(|a, b| a.0.cmp(b.0));
    all
}

/// Of `loaded`: the cache file's entries this run did not use, and the delta file's it
/// used.
fn usage<K, T>(loaded: &FxHashMap<K, FromFile<T>>) -> (usize, usize) {
    loaded.values().fold((0, 0), |(unused, delta), e| {
        let used = e.used.load(Ordering::Relaxed);
        (
            unused + usize::from(!e.in_delta && !used),
            delta + usize::from(e.in_delta && used),
        )
    })
}

/// The delta file's entries this run used and the entries it made, sorted by key.
fn used_and_made_delta<'a, K: Ord + std::hash::Hash, T>(
    loaded: &'a FxHashMap<K, FromFile<T>>,
    made: &'a BTreeMap<K, T>,
) -> Vec<(&'a K, &'a T)> {
    let mut all: Vec<(&K, &T)> = loaded
        .iter()
        .filter(|(_, e)| e.in_delta && e.used.load(Ordering::Relaxed))
        .map(|(k, e)| (k, &e.fit))
        .chain(made.iter())
        .collect();
    all.sort_unstable_by(|a, b| a.0.cmp(b.0));
    all
}

/// The cache file's bytes holding these entries.
fn encode(
    fits: &[(&Key, &ContourFit)],
    compatible: &[(&CompatibleKey, &CompatibleFit)],
    orient: &[(&GlyphKey, &Vec<bool>)],
) -> Vec<u8> {
    let mut out = HEADER.start();
    encode_body(&mut out, fits, compatible, orient);
    Header::seal(&mut out);
    out
}

/// The delta file's bytes holding these entries, bound to the cache file `base` (its
/// length and checksum).
fn encode_delta(
    base: BaseFile,
    fits: &[(&Key, &ContourFit)],
    compatible: &[(&CompatibleKey, &CompatibleFit)],
    orient: &[(&GlyphKey, &Vec<bool>)],
) -> Vec<u8> {
    let mut out = DELTA_HEADER.start();
    out.extend_from_slice(&base.len.to_le_bytes());
    out.extend_from_slice(&base.crc.to_le_bytes());
    encode_body(&mut out, fits, compatible, orient);
    Header::seal(&mut out);
    out
}

/// Appends the fitters' key and the entries.
fn encode_body(
    out: &mut Vec<u8>,
    fits: &[(&Key, &ContourFit)],
    compatible: &[(&CompatibleKey, &CompatibleFit)],
    orient: &[(&GlyphKey, &Vec<bool>)],
) {
    for v in fitter_key() {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&(orient.len() as u64).to_le_bytes());
    for &(key, flags) in orient {
        out.extend_from_slice(&key.0);
        out.extend_from_slice(&(flags.len() as u32).to_le_bytes());
        out.extend(flags.iter().map(|&r| u8::from(r)));
    }
    out.extend_from_slice(&(fits.len() as u64).to_le_bytes());
    for &(key, fit) in fits {
        out.extend_from_slice(&key.tolerance.to_le_bytes());
        out.extend_from_slice(&(key.points.len() as u32).to_le_bytes());
        put_points(out, &key.points);
        put_fit(out, fit);
    }
    out.extend_from_slice(&(compatible.len() as u64).to_le_bytes());
    for &(key, fit) in compatible {
        out.extend_from_slice(&key.tolerance.to_le_bytes());
        let points = key.masters.first().map_or(0, Vec::len);
        for count in [key.masters.len(), points, key.positions.len()] {
            out.extend_from_slice(&(count as u32).to_le_bytes());
        }
        for master in &key.masters {
            put_points(out, master);
        }
        for weight in key.positions.iter().flatten() {
            out.extend_from_slice(&weight.to_le_bytes());
        }
        put_compatible_fit(out, fit);
    }
}

fn put_points(out: &mut Vec<u8>, points: &[[u64; 3]]) {
    for v in points.iter().flatten() {
        out.extend_from_slice(&v.to_le_bytes());
    }
}

fn put_fit(out: &mut Vec<u8>, fit: &ContourFit) {
    out.extend_from_slice(&fit.max_error.to_bits().to_le_bytes());
    put_path(out, &fit.path);
}

/// A compatible fit without its key (whose counts give the number of errors and paths).
fn put_compatible_fit(out: &mut Vec<u8>, fit: &CompatibleFit) {
    out.extend_from_slice(&(fit.segments as u32).to_le_bytes());
    match fit.between_masters {
        None => out.push(0),
        Some(bound) => {
            out.push(1);
            out.extend_from_slice(&bound.to_bits().to_le_bytes());
        }
    }
    for e in &fit.max_error {
        out.extend_from_slice(&e.to_bits().to_le_bytes());
    }
    for path in &fit.paths {
        put_path(out, path);
    }
}

// The fit cache's own reads, on the shared cursor.
impl Reader<'_> {
    /// A finite, non-negative error or bound.
    fn error(&mut self) -> Result<f64, &'static str> {
        let v = self.f64()?;
        if v < 0.0 {
            return Err("a negative error");
        }
        Ok(v)
    }
    /// `count` control points (x, y, s as bits).
    fn points(&mut self, count: usize) -> Result<Vec<[u64; 3]>, &'static str> {
        // Pushed: collecting through `Result` would grow the vector step by step.
        let mut points = Vec::with_capacity(count);
        for _ in 0..count {
            points.push([self.u64()?, self.u64()?, self.u64()?]);
        }
        Ok(points)
    }
}

fn decode(bytes: &[u8]) -> Result<Loaded, &'static str> {
    let mut r = HEADER.open(bytes)?;
    decode_body(&mut r)
}

/// The entries of a delta file, if it is bound to the cache file `base`.
fn decode_delta(bytes: &[u8], base: BaseFile) -> Result<Loaded, &'static str> {
    let mut r = DELTA_HEADER.open(bytes)?;
    if (r.u64()?, r.u32()?) != (base.len, base.crc) {
        return Err("it belongs to another cache file");
    }
    decode_body(&mut r)
}

/// The fitters' key (checked) and the entries, to the last byte.
fn decode_body(r: &mut Reader<'_>) -> Result<Loaded, &'static str> {
    let key = fitter_key();
    if [r.u32()?, r.u32()?] != [key[0], key[1]] {
        return Err("it was written by another version of the fitter");
    }
    if [r.u32()?, r.u32()?] != [key[2], key[3]] {
        return Err("it was written by another version of the compatible fitter");
    }
    if [r.u32()?, r.u32()?] != [key[4], key[5]] {
        return Err("it was written by another version of the orientation");
    }
    let mut entries = Loaded::default();
    let n = r.u64()?;
    // An orientation entry is at least 32 + 4 bytes.
    let n = r.count(n, 36)?;
    entries.orient.reserve(n);
    for _ in 0..n {
        let key = GlyphKey(r.array()?);
        let count = r.u32()?;
        let count = r.count(u64::from(count), 1)?;
        let flags = r
            .take(count)?
            .iter()
            .map(|&b| match b {
                0 => Ok(false),
                1 => Ok(true),
                _ => Err("an orientation is malformed"),
            })
            .collect::<Result<Vec<bool>, _>>()?;
        if entries.orient.insert(key, FromFile::new(flags)).is_some() {
            return Err("a glyph's orientation is stored twice");
        }
    }
    let n = r.u64()?;
    // A static entry is at least 8 + 4 + 8 + 4 bytes.
    let n = r.count(n, 24)?;
    entries.fits.reserve(n);
    for _ in 0..n {
        let tolerance = r.u64()?;
        let count = r.u32()?;
        let count = r.count(u64::from(count), 24)?;
        let points = r.points(count)?;
        let max_error = r.error()?;
        let path = read_path(r)?;
        let fit = ContourFit { path, max_error };
        if entries
            .fits
            .insert(Key { tolerance, points }, FromFile::new(fit))
            .is_some()
        {
            return Err("a contour is stored twice");
        }
    }
    let n = r.u64()?;
    // A compatible entry is at least 8 + 3 × 4 + 4 + 1 bytes.
    let n = r.count(n, 25)?;
    for _ in 0..n {
        let (key, fit) = read_compatible(r)?;
        if entries.compatible.insert(key, FromFile::new(fit)).is_some() {
            return Err("a contour is stored twice");
        }
    }
    if !r.is_empty() {
        return Err("bytes follow the last entry");
    }
    Ok(entries)
}

/// A compatible entry: its key, then a fit with one error per position and one path per
/// master, all paths of the same elements, as many segments as it says.
fn read_compatible(r: &mut Reader<'_>) -> Result<(CompatibleKey, CompatibleFit), &'static str> {
    let tolerance = r.u64()?;
    let masters = r.u32()?;
    let masters = r.count(u64::from(masters), 24)?;
    let points = r.u32()?;
    let points = r.count(u64::from(points), 24)?;
    let positions = r.u32()?;
    let positions = r.count(u64::from(positions), 8)?;
    if masters == 0 {
        return Err("a compatible fit without masters");
    }
    r.count((masters as u64).saturating_mul(points as u64), 24)?;
    let master_points = (0..masters)
        .map(|_| r.points(points))
        .collect::<Result<Vec<_>, _>>()?;
    r.count((positions as u64).saturating_mul(masters as u64), 8)?;
    let weights = (0..positions)
        .map(|_| (0..masters).map(|_| r.u64()).collect())
        .collect::<Result<Vec<Vec<u64>>, _>>()?;
    let segments = r.u32()? as usize;
    let between_masters = match r.u8()? {
        0 => None,
        1 => Some(r.error()?),
        _ => return Err("a compatible fit is malformed"),
    };
    r.count(positions as u64, 8)?;
    let max_error = (0..positions)
        .map(|_| r.error())
        .collect::<Result<Vec<_>, _>>()?;
    let paths = (0..masters)
        .map(|_| read_path(r))
        .collect::<Result<Vec<_>, _>>()?;
    let kinds = |p: &BezPath| -> Vec<std::mem::Discriminant<PathEl>> {
        p.elements().iter().map(std::mem::discriminant).collect()
    };
    let first = kinds(&paths[0]);
    if paths[1..].iter().any(|p| kinds(p) != first) || first.len() != segments + 2 {
        return Err("a compatible fit's paths differ in structure");
    }
    let key = CompatibleKey {
        tolerance,
        positions: weights,
        masters: master_points,
    };
    let fit = CompatibleFit {
        paths,
        max_error,
        between_masters,
        segments,
    };
    Ok((key, fit))
}

/// One closed contour of lines and cubics.
fn read_path(r: &mut Reader<'_>) -> Result<BezPath, &'static str> {
    let path = r.path()?;
    let elements = path.elements();
    let last = elements.len().saturating_sub(1);
    let one_contour = elements.len() >= 2
        && elements.iter().enumerate().all(|(k, el)| match el {
            PathEl::MoveTo(_) => k == 0,
            PathEl::LineTo(_) | PathEl::CurveTo(..) => k != 0 && k != last,
            PathEl::ClosePath => k == last,
            PathEl::QuadTo(..) => false,
        });
    if !one_contour {
        return Err("a path is not one closed contour");
    }
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::{TAG_CLOSE, TAG_MOVE};

    fn square() -> XSpline {
        let points = [
            (0.0, 0.0, 0.0),
            (10.0, 0.0, 1.0),
            (10.0, 10.0, -1.0),
            (0.0, 10.0, 0.0),
        ]
        .iter()
        .map(|&(x, y, s)| ControlPoint::new(x, y, s))
        .collect();
        XSpline::new(points).unwrap()
    }

    #[test]
    fn a_round_trip_keeps_every_bit() {
        let cache = FitCache::new();
        let fit = cache.fit(&square(), 0.5);
        let bytes = cache.to_bytes();
        let loaded = decode(&bytes).unwrap();
        assert_eq!((loaded.fits.len(), loaded.compatible.len()), (1, 0));
        let back = &loaded.fits.values().next().unwrap().fit;
        assert_eq!(back.max_error.to_bits(), fit.max_error.to_bits());
        assert_eq!(back.path, fit.path);
        // Encoding is deterministic.
        let again = FitCache {
            loaded: loaded.fits,
            ..FitCache::default()
        };
        again.fit(&square(), 0.5);
        assert_eq!((again.hits(), again.misses()), (1, 0));
        assert_eq!(again.to_bytes(), bytes);
    }

    #[test]
    fn the_file_is_rewritten_only_when_this_run_changed_its_entries() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(CACHE_FILE);
        let moved = |dx: f64| {
            let points = square()
                .points()
                .iter()
                .map(|p| ControlPoint::new(p.pos.x + dx, p.pos.y, p.s))
                .collect();
            XSpline::new(points).unwrap()
        };
        let first = FitCache::new();
        first.fit(&moved(0.0), 0.5);
        first.fit(&moved(5.0), 0.5);
        assert!(!first.file_is_current(&path));
        first.save(&path).unwrap();
        let bytes = fs::read(&path).unwrap();

        // Every entry used, nothing fitted: current, and `save` leaves the file alone.
        let (all, outcome) = FitCache::load(&path);
        assert_eq!(outcome, LoadOutcome::Loaded(2));
        all.fit(&moved(5.0), 0.5);
        all.fit(&moved(0.0), 0.5);
        all.fit(&moved(0.0), 0.5);
        assert_eq!((all.hits(), all.misses()), (3, 0));
        assert!(all.file_is_current(&path));
        assert_eq!(all.to_bytes(), bytes);
        // (Elsewhere it is written.)
        assert!(!all.file_is_current(&dir.path().join("other")));

        // One entry unused: the file must drop it.
        let (some, _) = FitCache::load(&path);
        some.fit(&moved(0.0), 0.5);
        assert!(!some.file_is_current(&path));
        let only = FitCache::new();
        only.fit(&moved(0.0), 0.5);
        assert_eq!(some.to_bytes(), only.to_bytes());

        // One contour new: the file must gain it, in key order with the loaded ones.
        let (more, _) = FitCache::load(&path);
        for dx in [0.0, 5.0, -5.0] {
            more.fit(&moved(dx), 0.5);
        }
        assert_eq!((more.hits(), more.misses()), (2, 1));
        assert!(!more.file_is_current(&path));
        let fresh = FitCache::new();
        for dx in [-5.0, 5.0, 0.0] {
            fresh.fit(&moved(dx), 0.5);
        }
        assert_eq!(more.to_bytes(), fresh.to_bytes());
    }

    /// Two nested squares and one beside them, all counter-clockwise, as placed contours
    /// and their fits.
    fn nested() -> (Vec<PlacedContour>, Vec<BezPath>) {
        let square = |x: f64, side: f64| {
            let p = |x, y| ControlPoint::new(x, y, 0.0);
            XSpline::new(vec![
                p(x, x),
                p(x + side, x),
                p(x + side, x + side),
                p(x, x + side),
            ])
            .unwrap()
        };
        let placed: Vec<PlacedContour> =
            [square(0.0, 100.0), square(20.0, 60.0), square(200.0, 10.0)]
                .into_iter()
                .map(|spline| PlacedContour {
                    spline,
                    offset: kurbo::Vec2::ZERO,
                })
                .collect();
        let fitted = placed
            .iter()
            .map(|c| fit_contour(&c.spline, 0.5).path)
            .collect();
        (placed, fitted)
    }

    #[test]
    fn orientations_come_from_the_cache_and_are_what_orient_gives() {
        let (placed, fitted) = nested();
        let expected = crate::orient::orient_contours(fitted.clone());
        assert_eq!(reversals(&fitted), [false, true, false]);
        let cache = FitCache::new();
        assert_eq!(cache.orient_placed(&placed, 0.5, fitted.clone()), expected);
        // Made in this run: taken again without orienting (the same path).
        assert_eq!(cache.orient_placed(&placed, 0.5, fitted.clone()), expected);
        let bytes = cache.to_bytes();
        let entries = decode(&bytes).unwrap();
        assert_eq!(entries.orient.len(), 1);
        let loaded = FitCache {
            loaded_orient: entries.orient,
            ..FitCache::default()
        };
        assert_eq!(loaded.orient_placed(&placed, 0.5, fitted.clone()), expected);
        assert_eq!(loaded.loaded_used.load(Ordering::Relaxed), 1);
        assert!(loaded.lock_made().orient.is_empty());
        // Another tolerance or placement is another glyph.
        let moved: Vec<PlacedContour> = placed
            .iter()
            .map(|c| PlacedContour {
                offset: kurbo::Vec2::new(0.0, 1e-9),
                ..c.clone()
            })
            .collect();
        for (other, tolerance) in [(&placed, 0.25), (&moved, 0.5)] {
            loaded.orient_placed(other, tolerance, fitted.clone());
        }
        assert_eq!(loaded.lock_made().orient.len(), 2);

        // The stored flags are what a hit uses: a file resealed with the inner square's
        // flag cleared gives that square unreversed (a forged file is trusted: the limit
        // the module states), and flags of another length are not used at all.
        let key = GlyphKey::new(&placed, 0.5);
        for (flags, want) in [
            (
                vec![false, false, false],
                crate::orient::join_reversed(&fitted, &[false; 3]),
            ),
            (vec![false, true], expected.clone()),
        ] {
            let forged = encode(&[], &[], &[(&key, &flags)]);
            let cache = FitCache {
                loaded_orient: decode(&forged).unwrap().orient,
                ..FitCache::default()
            };
            assert_eq!(cache.orient_placed(&placed, 0.5, fitted.clone()), want);
        }
        // A flag byte other than 0 or 1 makes the whole file refused.
        let mut bad = encode(&[], &[], &[(&key, &vec![false, true, false])]);
        let at = bad.len() - 4 - 8 - 8 - 2;
        assert_eq!(bad[at], 1);
        bad[at] = 2;
        bad.truncate(bad.len() - 4);
        Header::seal(&mut bad);
        assert_eq!(decode(&bad).err(), Some("an orientation is malformed"));
    }

    #[test]
    fn structural_checks_reject_what_the_checksum_would_pass() {
        let cache = FitCache::new();
        cache.fit(&square(), 0.5);
        let good = cache.to_bytes();
        // Re-sign a body whose path's ClosePath tag became a MoveTo (a second contour that
        // never closes): the CRC matches, the structure does not.
        // The last 8 bytes before the checksum count the compatible entries (none).
        let mut body = good[..good.len() - 12].to_vec();
        let last = body.len() - 1;
        assert_eq!(body[last], TAG_CLOSE);
        body[last] = TAG_MOVE;
        body.extend_from_slice(&0u64.to_le_bytes());
        let crc = crc32fast::hash(&body);
        body.extend_from_slice(&crc.to_le_bytes());
        assert_eq!(
            decode(&body).err(),
            Some("an outline is not closed subpaths")
        );
    }
}
