//! A cache of fitted contours, so that a rebuild refits only the contours that changed.
//!
//! An entry is keyed by everything a fit depends on: the contour's control points as placed
//! (the exact bits of every `x`, `y` and `s`) and the tolerance (its bits). The whole file
//! is further keyed by the fitter: [`FIT_VERSION`] and a fingerprint of the fitter's output
//! on a fixed probe contour, so that a changed fitter invalidates the cache even when
//! nobody bumped the version. The cache lives in the output folder
//! ([`CACHE_FILE`] in OUT), never beside the sources.
//!
//! The file is not trusted. It is read whole and checked before any entry is used: magic,
//! format version, fitter key, a CRC-32 of everything before it, every count against the
//! bytes that remain, every number finite, every path one closed contour of lines and
//! cubics, no duplicate key and no trailing byte. If anything is wrong the whole file is
//! ignored (every contour is refitted) and the next [`FitCache::save`] replaces it. A cached
//! fit is bit-for-bit the fit it stored, so outputs are the same with and without the cache.
//!
//! The file holds exactly the entries used by the last run (entries of deleted or edited
//! contours are dropped), sorted by key, so the same input writes the same bytes. It is
//! written atomically ([`crate::write::write_atomic`]). Limit: a deliberately forged file
//! with a valid checksum is trusted; the cache is the user's own file in their output
//! folder, not an input from others.
//!
//! [`FitCache::fit`] may be called from many threads at once.

use std::collections::{BTreeMap, HashMap};
use std::fs;
use std::io;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};

use kurbo::{BezPath, PathEl, Point};

use crate::fit::{fit_contour, ContourFit};
use crate::xspline::{ControlPoint, XSpline};

/// Name of the cache file in the output folder.
pub const CACHE_FILE: &str = ".xglyph-cache";

/// Version of the fitter's output: bump it whenever [`crate::fit`] changes what it returns.
/// (The fingerprint catches most changes anyway; the version makes the intent explicit.)
pub const FIT_VERSION: u32 = 1;

/// First bytes of a cache file.
const MAGIC: &[u8; 8] = b"XGLYPHFC";
/// Layout of the file itself.
const FORMAT_VERSION: u32 = 1;

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

/// What happened to the cache file when it was loaded.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadOutcome {
    /// There was no cache file: every contour is fitted.
    Missing,
    /// The file was valid; it held this many entries.
    Loaded(usize),
    /// The file was unreadable, corrupt or stale, and is ignored; the reason.
    Ignored(String),
}

/// Fitted contours by key: those loaded from the file, and those used in this run.
#[derive(Debug, Default)]
pub struct FitCache {
    /// From the file, read-only while fitting.
    loaded: HashMap<Key, ContourFit>,
    /// Every fit handed out in this run (hits and misses): what [`FitCache::save`] writes.
    used: Mutex<BTreeMap<Key, ContourFit>>,
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
            Ok(loaded) => {
                let n = loaded.len();
                let cache = FitCache {
                    loaded,
                    ..FitCache::default()
                };
                (cache, LoadOutcome::Loaded(n))
            }
            Err(reason) => (FitCache::new(), LoadOutcome::Ignored(reason.into())),
        }
    }

    /// [`fit_contour`]`(spline, tolerance)`, from the cache when it holds this contour.
    pub fn fit(&self, spline: &XSpline, tolerance: f64) -> ContourFit {
        let key = Key::new(spline, tolerance);
        if let Some(fit) = self.loaded.get(&key) {
            self.hits.fetch_add(1, Ordering::Relaxed);
            self.lock_used().insert(key, fit.clone());
            return fit.clone();
        }
        // The same contour placed twice in this run (a component at the same offset).
        if let Some(fit) = self.lock_used().get(&key) {
            self.reused.fetch_add(1, Ordering::Relaxed);
            return fit.clone();
        }
        self.misses.fetch_add(1, Ordering::Relaxed);
        // Fitted outside the lock; two threads fitting the same new contour at once both
        // get the same (deterministic) fit.
        let fit = fit_contour(spline, tolerance);
        self.lock_used().insert(key, fit.clone());
        fit
    }

    fn lock_used(&self) -> std::sync::MutexGuard<'_, BTreeMap<Key, ContourFit>> {
        // A poisoned lock only means another thread panicked; every entry in the map was
        // inserted whole.
        self.used.lock().unwrap_or_else(|e| e.into_inner())
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
        encode(&self.lock_used())
    }

    /// Writes the fits used in this run to `path`, atomically.
    pub fn save(&self, path: &Path) -> io::Result<()> {
        crate::write::write_atomic(path, &self.to_bytes())
    }
}

/// The fitter's key: its version and the bits of its fit of a fixed probe contour (mixed
/// sharp, approximating and interpolating points, at a tolerance that needs several cubics).
fn fitter_key() -> (u32, u32) {
    static KEY: OnceLock<(u32, u32)> = OnceLock::new();
    *KEY.get_or_init(|| {
        let probe = [
            (0.0, 0.0, 0.0),
            (400.0, -30.0, 1.0),
            (620.0, 250.0, -1.0),
            (450.0, 700.0, 0.5),
            (120.0, 640.0, -0.4),
            (60.0, 320.0, 0.0),
        ];
        let points = probe
            .iter()
            .map(|&(x, y, s)| ControlPoint::new(x, y, s))
            .collect();
        let fingerprint = match XSpline::new(points) {
            Ok(spline) => {
                let fit = fit_contour(&spline, 0.25);
                let mut hasher = crc32fast::Hasher::new();
                let mut bytes = Vec::new();
                put_fit(&mut bytes, &fit);
                hasher.update(&bytes);
                hasher.finalize()
            }
            // The probe is a valid contour; if XSpline's rules ever reject it, the key
            // still differs from any earlier one.
            Err(_) => u32::MAX,
        };
        (FIT_VERSION, fingerprint)
    })
}

// File layout, little-endian:
//   magic (8) | format version u32 | fit version u32 | fingerprint u32 | entry count u64
//   entries, each: tolerance u64 | point count u32 | points (x, y, s as u64 bits)
//                  | max_error f64 | element count u32 | elements (tag u8, points)
//   CRC-32 of everything before it, u32

const TAG_MOVE: u8 = 0;
const TAG_LINE: u8 = 1;
const TAG_CUBIC: u8 = 2;
const TAG_CLOSE: u8 = 3;

fn encode(entries: &BTreeMap<Key, ContourFit>) -> Vec<u8> {
    let (version, fingerprint) = fitter_key();
    let mut out = Vec::new();
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(&fingerprint.to_le_bytes());
    out.extend_from_slice(&(entries.len() as u64).to_le_bytes());
    for (key, fit) in entries {
        out.extend_from_slice(&key.tolerance.to_le_bytes());
        out.extend_from_slice(&(key.points.len() as u32).to_le_bytes());
        for p in &key.points {
            p.iter()
                .for_each(|v| out.extend_from_slice(&v.to_le_bytes()));
        }
        put_fit(&mut out, fit);
    }
    let crc = crc32fast::hash(&out);
    out.extend_from_slice(&crc.to_le_bytes());
    out
}

fn put_fit(out: &mut Vec<u8>, fit: &ContourFit) {
    out.extend_from_slice(&fit.max_error.to_bits().to_le_bytes());
    let elements = fit.path.elements();
    out.extend_from_slice(&(elements.len() as u32).to_le_bytes());
    let mut put = |tag: u8, points: &[Point]| {
        out.push(tag);
        for p in points {
            out.extend_from_slice(&p.x.to_bits().to_le_bytes());
            out.extend_from_slice(&p.y.to_bits().to_le_bytes());
        }
    };
    for el in elements {
        match *el {
            PathEl::MoveTo(p) => put(TAG_MOVE, &[p]),
            PathEl::LineTo(p) => put(TAG_LINE, &[p]),
            PathEl::CurveTo(a, b, c) => put(TAG_CUBIC, &[a, b, c]),
            PathEl::ClosePath => put(TAG_CLOSE, &[]),
            // The fitter writes no quadratics; an unknown tag makes the file unreadable,
            // so this entry is refitted next time instead of trusted.
            PathEl::QuadTo(..) => put(u8::MAX, &[]),
        }
    }
}

/// A cursor over untrusted bytes: every read is bounds-checked.
struct Reader<'a> {
    bytes: &'a [u8],
}

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> Result<[u8; N], &'static str> {
        let (head, rest) = self
            .bytes
            .split_first_chunk::<N>()
            .ok_or("the file is truncated")?;
        self.bytes = rest;
        Ok(*head)
    }
    fn u8(&mut self) -> Result<u8, &'static str> {
        Ok(self.take::<1>()?[0])
    }
    fn u32(&mut self) -> Result<u32, &'static str> {
        Ok(u32::from_le_bytes(self.take()?))
    }
    fn u64(&mut self) -> Result<u64, &'static str> {
        Ok(u64::from_le_bytes(self.take()?))
    }
    fn f64(&mut self) -> Result<f64, &'static str> {
        let v = f64::from_bits(self.u64()?);
        if v.is_finite() {
            Ok(v)
        } else {
            Err("a number is not finite")
        }
    }
    fn point(&mut self) -> Result<Point, &'static str> {
        Ok(Point::new(self.f64()?, self.f64()?))
    }
    /// A count of items of at least `min_size` bytes each, checked against what remains.
    fn count(&mut self, n: u64, min_size: usize) -> Result<usize, &'static str> {
        match usize::try_from(n) {
            Ok(n) if n <= self.bytes.len() / min_size => Ok(n),
            _ => Err("a count exceeds the file's size"),
        }
    }
}

fn decode(bytes: &[u8]) -> Result<HashMap<Key, ContourFit>, &'static str> {
    let (body, crc) = bytes
        .split_last_chunk::<4>()
        .ok_or("the file is truncated")?;
    if !body.starts_with(MAGIC) {
        return Err("not an xglyph cache file");
    }
    if crc32fast::hash(body) != u32::from_le_bytes(*crc) {
        return Err("the checksum does not match (corrupt or truncated)");
    }
    let mut r = Reader {
        bytes: &body[MAGIC.len()..],
    };
    if r.u32()? != FORMAT_VERSION {
        return Err("written by another version of xglyph");
    }
    if (r.u32()?, r.u32()?) != fitter_key() {
        return Err("written by another version of the fitter");
    }
    let n = r.u64()?;
    // An entry is at least 8 + 4 + 8 + 4 bytes.
    let n = r.count(n, 24)?;
    let mut entries = HashMap::with_capacity(n);
    for _ in 0..n {
        let tolerance = r.u64()?;
        let count = r.u32()?;
        let count = r.count(u64::from(count), 24)?;
        let points = (0..count)
            .map(|_| Ok([r.u64()?, r.u64()?, r.u64()?]))
            .collect::<Result<Vec<_>, &'static str>>()?;
        let fit = read_fit(&mut r)?;
        if entries.insert(Key { tolerance, points }, fit).is_some() {
            return Err("a contour is stored twice");
        }
    }
    if !r.bytes.is_empty() {
        return Err("bytes follow the last entry");
    }
    Ok(entries)
}

/// A fit: its error, then one closed contour of lines and cubics.
fn read_fit(r: &mut Reader<'_>) -> Result<ContourFit, &'static str> {
    let max_error = r.f64()?;
    if max_error < 0.0 {
        return Err("a negative error");
    }
    let count = r.u32()?;
    let count = r.count(u64::from(count), 1)?;
    if count < 2 {
        return Err("an empty path");
    }
    let mut path = BezPath::new();
    for k in 0..count {
        let tag = r.u8()?;
        let (first, last) = (k == 0, k + 1 == count);
        match tag {
            TAG_MOVE if first => path.move_to(r.point()?),
            TAG_LINE if !first && !last => path.line_to(r.point()?),
            TAG_CUBIC if !first && !last => path.curve_to(r.point()?, r.point()?, r.point()?),
            TAG_CLOSE if last => path.close_path(),
            _ => return Err("a path is not one closed contour"),
        }
    }
    Ok(ContourFit { path, max_error })
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert_eq!(loaded.len(), 1);
        let back = loaded.values().next().unwrap();
        assert_eq!(back.max_error.to_bits(), fit.max_error.to_bits());
        assert_eq!(back.path, fit.path);
        // Encoding is deterministic.
        let again = FitCache {
            loaded,
            ..FitCache::default()
        };
        again.fit(&square(), 0.5);
        assert_eq!((again.hits(), again.misses()), (1, 0));
        assert_eq!(again.to_bytes(), bytes);
    }

    #[test]
    fn structural_checks_reject_what_the_checksum_would_pass() {
        let cache = FitCache::new();
        cache.fit(&square(), 0.5);
        let good = cache.to_bytes();
        // Re-sign a body whose path lost its ClosePath tag (3 -> 1): the CRC matches, the
        // structure does not.
        let mut body = good[..good.len() - 4].to_vec();
        let last = body.len() - 1;
        assert_eq!(body[last], TAG_CLOSE);
        body[last] = TAG_LINE;
        let crc = crc32fast::hash(&body);
        body.extend_from_slice(&crc.to_le_bytes());
        assert_eq!(
            decode(&body).err(),
            Some("a path is not one closed contour")
        );
    }
}
