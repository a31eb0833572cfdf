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
//! The file is not trusted, and it is not decoded whole: [`FitCache::load`] keeps its bytes
//! (and its delta file's after them) and indexes its entries, each by a hash of its key's
//! bytes, as ranges of those bytes. A static fit or an orientation is decoded when a run
//! asks for it (a CJK font's rebuild uses all 121,000 of its fits, but decoding them into
//! maps at load, then cloning each hit, cost a tenth of the rebuild and hundreds of MB of
//! fresh memory). What is checked when:
//! - at load, before any entry is used, the whole file: magic, format version, fitter key,
//!   a CRC-32 of everything before it, every count against the bytes that remain, every
//!   path one closed contour of lines and cubics (its tags: a move, lines and cubics, a
//!   close), every orientation flag 0 or 1, no duplicate key and no trailing byte; and
//!   every compatible entry whole (every number finite, errors not negative, paths of the
//!   same elements, its segment count, one error per position of its key), as it is
//!   decoded there (fonts with masters have few). If anything is wrong the whole file is
//!   ignored (every contour is refitted) and the next [`FitCache::save`] replaces it;
//! - when a static fit is used, its numbers: every one finite and its error not negative
//!   (with the path's structure again, by the same checked reader). A bad entry is a miss:
//!   the contour is refitted, the entry is not marked used, so the next whole file drops
//!   it.
//!
//! A hit compares the key's bytes in full, never only their hash, so two contours whose
//! keys collide each get their own fit. A cached fit is bit-for-bit the fit it stored, so
//! outputs are the same with and without the cache.
//!
//! The file holds the entries used by the last run that wrote it whole (entries of deleted
//! or edited contours are dropped), sorted by key (static keys by tolerance, then the
//! points' bits in order; compatible keys by tolerance, then weights, then points;
//! orientations by digest), so the same input writes the same bytes. An entry loaded and
//! used is written by copying its bytes, not by encoding it again (decoding and encoding
//! keep every bit, so the bytes are the same).
//! A run that used every entry of the files it loaded and fitted nothing new leaves them
//! alone (a CJK font's cache is 100 MB). A run that changed few entries writes only a small
//! delta file beside it ([`DELTA_FILE`], the same layout with its own magic, bound to the
//! cache file by its length and checksum; [`FitCache::files_to_save`]): the entries it made
//! and those of the last delta it used. Limit: until the cache file is written whole again
//! (when the delta and the cache file's unused entries pass 1/8 of its entries), it keeps
//! the entries of edited contours, and the two files depend on the order of the edits, not
//! only on the sources. Each loaded entry carries a flag saying whether this run used it.
//! The files are written atomically ([`crate::write::write_atomic`]). Limit: a
//! deliberately forged file with a valid checksum and finite numbers is trusted; the cache
//! is the user's own file in their output folder, not an input from others.
//!
//! [`FitCache::fit`] may be called from many threads at once.

use std::cmp::Ordering as Order;
use std::hash::Hasher;
use std::io;
use std::ops::Range;
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};

use hashbrown::HashTable;
use kurbo::{Affine, BezPath, PathEl};
use rustc_hash::{FxHashMap, FxHasher};
use sha2::{Digest, Sha256};

use crate::compatible::{fit_compatible, CompatibleError, CompatibleFit};
use crate::fit::{fit_contour, ContourFit};
use crate::orient::{join_reversed, reversals, ORIENT_VERSION};
use crate::outline::PlacedContour;
use crate::record::{
    put_path, read_with_delta, Binding, Header, Reader, TAG_CLOSE, TAG_CUBIC, TAG_LINE, TAG_MOVE,
};
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
pub const FIT_VERSION: u32 = 10;

/// Version of the compatible fitter's output: bump it whenever [`crate::compatible`]
/// changes what it returns (paths, errors or the bound between the masters).
pub const COMPATIBLE_VERSION: u32 = 9;

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

/// The delta file beside the cache file at `path`.
pub fn delta_path(path: &Path) -> std::path::PathBuf {
    path.with_file_name(DELTA_FILE)
}

/// The little-endian word in `bytes` (8 of them).
fn word(bytes: &[u8]) -> u64 {
    let mut w = [0; 8];
    w.copy_from_slice(bytes);
    u64::from_le_bytes(w)
}

/// The bits of a control point as a static key stores them: x, y, s.
fn point_bits(p: &ControlPoint) -> [u64; 3] {
    [p.pos.x.to_bits(), p.pos.y.to_bits(), p.s.to_bits()]
}

/// A static fit's key as the file stores it: the tolerance's bits (u64), the point count
/// (u32) and the points' bits.
fn static_key(tolerance: u64, points: &[ControlPoint]) -> Vec<u8> {
    let mut key = Vec::with_capacity(12 + 24 * points.len());
    key.extend_from_slice(&tolerance.to_le_bytes());
    key.extend_from_slice(&(points.len() as u32).to_le_bytes());
    for v in points.iter().flat_map(point_bits) {
        key.extend_from_slice(&v.to_le_bytes());
    }
    key
}

/// The hash of the static key of `points` at `tolerance` (its bits), without making the
/// key: [`static_key_hash`] of [`static_key`].
fn static_hash(tolerance: u64, points: &[ControlPoint]) -> u64 {
    let mut h = FxHasher::default();
    h.write_u64(tolerance);
    h.write_u64(points.len() as u64);
    for p in points {
        for v in point_bits(p) {
            h.write_u64(v);
        }
    }
    h.finish()
}

/// The hash of a static key's bytes (one that the loader walked: 12 + 24 n bytes).
fn static_key_hash(key: &[u8]) -> u64 {
    let mut h = FxHasher::default();
    h.write_u64(word(&key[..8]));
    h.write_u64(u64::from(u32::from_le_bytes([
        key[8], key[9], key[10], key[11],
    ])));
    for w in key[12..].chunks_exact(8) {
        h.write_u64(word(w));
    }
    h.finish()
}

/// Whether `key` (a static key's bytes) is the key of `points` at `tolerance` (its bits).
fn is_static_key(key: &[u8], tolerance: u64, points: &[ControlPoint]) -> bool {
    key.len() == 12 + 24 * points.len()
        && word(&key[..8]) == tolerance
        && key[8..12] == (points.len() as u32).to_le_bytes()
        && key[12..].chunks_exact(24).zip(points).all(|(stored, p)| {
            let [x, y, s] = point_bits(p);
            word(&stored[..8]) == x && word(&stored[8..16]) == y && word(&stored[16..]) == s
        })
}

/// The hash of a compatible key's or a glyph key's bytes.
fn bytes_hash(key: &[u8]) -> u64 {
    let mut h = FxHasher::default();
    h.write(key);
    h.finish()
}

/// A compatible fit's key as the file stores it: the tolerance's bits (u64), the master,
/// point and position counts (u32 each), every master's points (bits of x, y, s), and per
/// position the bits of its weights. `None` when the masters differ in point count or a
/// position does not have one weight per master (such input is not cached).
fn compatible_key(masters: &[&XSpline], positions: &[Vec<f64>], tolerance: f64) -> Option<Vec<u8>> {
    let points = masters.first()?.points().len();
    if masters.iter().any(|m| m.points().len() != points)
        || positions.iter().any(|w| w.len() != masters.len())
    {
        return None;
    }
    let mut key =
        Vec::with_capacity(20 + 24 * points * masters.len() + 8 * positions.len() * masters.len());
    key.extend_from_slice(&tolerance.to_bits().to_le_bytes());
    for count in [masters.len(), points, positions.len()] {
        key.extend_from_slice(&(count as u32).to_le_bytes());
    }
    for v in masters.iter().flat_map(|m| m.points()).flat_map(point_bits) {
        key.extend_from_slice(&v.to_le_bytes());
    }
    for weight in positions.iter().flatten() {
        key.extend_from_slice(&weight.to_bits().to_le_bytes());
    }
    Some(key)
}

/// `a` and `b` as sequences of little-endian words, compared as `[u64]` slices are.
fn cmp_words(a: &[u8], b: &[u8]) -> Order {
    a.chunks_exact(8).map(word).cmp(b.chunks_exact(8).map(word))
}

/// The order of static keys' bytes: by tolerance, then by the points' bits, as the
/// `(tolerance, Vec<[u64; 3]>)` they hold are ordered.
fn static_order(a: &[u8], b: &[u8]) -> Order {
    cmp_words(&a[..8], &b[..8]).then_with(|| cmp_words(&a[12..], &b[12..]))
}

/// The order of compatible keys' bytes: by tolerance, then the positions' weights, then
/// the masters' points, as the `(tolerance, Vec<Vec<u64>>, Vec<Vec<[u64; 3]>>)` they hold
/// are ordered.
fn compatible_order(a: &[u8], b: &[u8]) -> Order {
    /// The key's masters' points, and its positions' weights, each as one slice per
    /// master or position.
    fn parts(key: &[u8]) -> (impl Iterator<Item = &[u8]>, impl Iterator<Item = &[u8]>) {
        let count =
            |at: usize| u32::from_le_bytes([key[at], key[at + 1], key[at + 2], key[at + 3]]);
        let (masters, points, positions) =
            (count(8) as usize, count(12) as usize, count(16) as usize);
        let (point_bytes, weights) = key[20..].split_at(24 * points * masters);
        let (master, position) = (24 * points, 8 * masters);
        (
            (0..masters).map(move |m| &point_bytes[master * m..master * (m + 1)]),
            (0..positions).map(move |p| &weights[position * p..position * (p + 1)]),
        )
    }
    /// Lists of word sequences, compared as `[Vec<u64>]` are.
    fn cmp_lists<'a>(
        mut a: impl Iterator<Item = &'a [u8]>,
        mut b: impl Iterator<Item = &'a [u8]>,
    ) -> Order {
        loop {
            match (a.next(), b.next()) {
                (Some(x), Some(y)) => match cmp_words(x, y) {
                    Order::Equal => {}
                    other => return other,
                },
                (x, y) => return x.is_some().cmp(&y.is_some()),
            }
        }
    }
    let ((a_masters, a_positions), (b_masters, b_positions)) = (parts(a), parts(b));
    cmp_words(&a[..8], &b[..8])
        .then_with(|| cmp_lists(a_positions, b_positions))
        .then_with(|| cmp_lists(a_masters, b_masters))
}

/// The order of glyph keys: their digests' bytes.
fn glyph_order(a: &[u8], b: &[u8]) -> Order {
    a.cmp(b)
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

/// The entries made in this run (not in the files loaded), by their keys' bytes as the
/// file stores them.
#[derive(Debug, Default)]
struct Made {
    fits: FxHashMap<Vec<u8>, ContourFit>,
    compatible: FxHashMap<Vec<u8>, CompatibleFit>,
    /// Per glyph, which of its contours are reversed.
    orient: FxHashMap<GlyphKey, Vec<bool>>,
}

impl Made {
    fn len(&self) -> usize {
        self.fits.len() + self.compatible.len() + self.orient.len()
    }
}

/// An entry of the cache file (or its delta file): where its bytes are, and whether this
/// run used it.
#[derive(Debug)]
struct Slot<T> {
    /// The hash of its key's bytes.
    hash: u64,
    /// Its key's bytes in the loaded bytes, from `start` to `key_end`, and the whole entry's
    /// to `end`.
    start: usize,
    key_end: usize,
    end: usize,
    used: AtomicBool,
    /// Whether it came from the delta file.
    in_delta: bool,
    /// What the loader decoded of it (a compatible fit), or nothing.
    value: T,
}

impl<T> Slot<T> {
    /// An unused entry whose key is at `key` in the loaded bytes, and which ends at `end`.
    fn new(hash: u64, key: Range<usize>, end: usize, in_delta: bool, value: T) -> Self {
        Slot {
            hash,
            start: key.start,
            key_end: key.end,
            end,
            used: AtomicBool::new(false),
            in_delta,
            value,
        }
    }

    fn key<'a>(&self, bytes: &'a [u8]) -> &'a [u8] {
        &bytes[self.start..self.key_end]
    }
    /// Its bytes after the key.
    fn fit<'a>(&self, bytes: &'a [u8]) -> &'a [u8] {
        &bytes[self.key_end..self.end]
    }
    fn is_used(&self) -> bool {
        self.used.load(Ordering::Relaxed)
    }
}

/// The loaded entries of one kind, found by their keys' hashes (`hashbrown`'s
/// `HashTable`, which takes the hash and the key comparison from the caller: the keys are
/// bytes of the loaded file, compared in place). A slot is taken only when its key's bytes
/// are the key asked for: keys of the same hash cost a comparison, never a wrong fit.
#[derive(Debug)]
struct Index<T> {
    slots: Vec<Slot<T>>,
    table: HashTable<Bucket>,
}

/// An entry of an [`Index`]'s table: a slot's hash and key's place, so that a lookup reads
/// the key's bytes without first reading the slot (one wait for memory fewer per lookup).
#[derive(Clone, Copy, Debug)]
struct Bucket {
    hash: u64,
    key: (usize, usize),
    /// The number of the slot.
    slot: usize,
}

impl<T> Default for Index<T> {
    fn default() -> Self {
        Index {
            slots: Vec::new(),
            table: HashTable::new(),
        }
    }
}

impl<T> Index<T> {
    /// An index sized for `n` slots.
    fn with_capacity(n: usize) -> Self {
        Index {
            slots: Vec::with_capacity(n),
            table: HashTable::with_capacity(n),
        }
    }

    /// The slot whose hash is `hash` and whose key's bytes (in `bytes`) `is_key` accepts.
    fn find(&self, bytes: &[u8], hash: u64, is_key: impl Fn(&[u8]) -> bool) -> Option<&Slot<T>> {
        let bucket = self.table.find(hash, |b| {
            b.hash == hash && bytes.get(b.key.0..b.key.1).is_some_and(&is_key)
        })?;
        self.slots.get(bucket.slot)
    }

    /// Adds `slot` unless a slot of the same key's bytes (in `bytes`) is there; whether it
    /// was added.
    fn insert(&mut self, bytes: &[u8], slot: Slot<T>) -> bool {
        if self
            .find(bytes, slot.hash, |key| key == slot.key(bytes))
            .is_some()
        {
            return false;
        }
        let bucket = Bucket {
            hash: slot.hash,
            key: (slot.start, slot.key_end),
            slot: self.slots.len(),
        };
        self.table.insert_unique(slot.hash, bucket, |b| b.hash);
        self.slots.push(slot);
        true
    }

    fn len(&self) -> usize {
        self.slots.len()
    }

    /// The cache file's entries this run did not use, and the delta file's it used.
    fn usage(&self) -> (usize, usize) {
        self.slots.iter().fold((0, 0), |(unused, delta), s| {
            let used = s.is_used();
            (
                unused + usize::from(!s.in_delta && !used),
                delta + usize::from(s.in_delta && used),
            )
        })
    }

    /// Adds the slots of `other` (over the same `bytes`) whose keys this one lacks; how
    /// many.
    fn merge(&mut self, bytes: &[u8], other: Index<T>) -> usize {
        other
            .slots
            .into_iter()
            .map(|slot| usize::from(self.insert(bytes, slot)))
            .sum()
    }
}

/// The entries of a cache file and its delta file, as indexed.
#[derive(Debug, Default)]
struct Loaded {
    fits: Index<()>,
    compatible: Index<CompatibleFit>,
    orient: Index<()>,
}

impl Loaded {
    fn len(&self) -> usize {
        self.fits.len() + self.compatible.len() + self.orient.len()
    }
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

/// Fitted contours by key: those loaded from the file, and those made in this run.
#[derive(Debug, Default)]
pub struct FitCache {
    /// The bytes of the cache file, then of its delta file when that one is valid:
    /// read-only while fitting.
    bytes: Vec<u8>,
    /// Their entries (read-only while fitting, but for the flags).
    loaded: Loaded,
    /// The file they came from.
    source: Option<std::path::PathBuf>,
    /// That file's binding and entry count, and the entries its delta file added.
    base: Option<(Binding, usize)>,
    delta_entries: usize,
    /// Loaded entries used in this run.
    loaded_used: AtomicUsize,
    /// Fits made in this run (not in the file): with the loaded entries used, what
    /// [`FitCache::save`] writes.
    made: Mutex<Made>,
    hits: AtomicUsize,
    reused: AtomicUsize,
    misses: AtomicUsize,
}

impl FitCache {
    /// An empty cache: every contour is fitted (and remembered for [`FitCache::save`]).
    pub fn new() -> FitCache {
        FitCache::default()
    }

    /// Loads the cache file at `path`, and its delta file ([`DELTA_FILE`]) when that one
    /// is whole and bound to it (otherwise the delta file is ignored, and its contours are
    /// fitted again, as the one a whole rewrite of the cache file leaves behind is); a
    /// missing, unreadable, corrupt or stale cache file gives an empty cache and says why.
    pub fn load(path: &Path) -> (FitCache, LoadOutcome) {
        let (bytes, base_len) = match read_with_delta(path, &delta_path(path)) {
            Ok(read) => read,
            Err(e) if e.kind() == io::ErrorKind::NotFound => {
                return (FitCache::new(), LoadOutcome::Missing)
            }
            Err(e) => return (FitCache::new(), LoadOutcome::Ignored(e.to_string())),
        };
        match FitCache::from_bytes(bytes, base_len) {
            Ok(mut cache) => {
                cache.source = Some(path.to_path_buf());
                let n = cache.loaded.fits.len() + cache.loaded.compatible.len();
                (cache, LoadOutcome::Loaded(n))
            }
            Err(reason) => (FitCache::new(), LoadOutcome::Ignored(reason.into())),
        }
    }

    /// A cache over `bytes`: a cache file's (the first `base_len`), then possibly a delta
    /// file's. The cache file must be whole; the delta file's entries are added when it is
    /// whole and bound to the cache file (an entry in both keeps the cache file's copy),
    /// else its bytes are dropped.
    fn from_bytes(mut bytes: Vec<u8>, base_len: usize) -> Result<FitCache, &'static str> {
        let base = Binding::of(&bytes[..base_len]);
        let mut loaded = index_file(&bytes, 0..base_len, None)?;
        let base_entries = loaded.len();
        let delta_entries = match index_file(&bytes, base_len..bytes.len(), Some(base)) {
            Ok(delta) => {
                loaded.fits.merge(&bytes, delta.fits)
                    + loaded.compatible.merge(&bytes, delta.compatible)
                    + loaded.orient.merge(&bytes, delta.orient)
            }
            Err(_) => {
                bytes.truncate(base_len);
                0
            }
        };
        Ok(FitCache {
            bytes,
            loaded,
            base: Some((base, base_entries)),
            delta_entries,
            ..FitCache::default()
        })
    }

    /// [`fit_contour`]`(spline, tolerance)`, from the cache when it holds this contour.
    pub fn fit(&self, spline: &XSpline, tolerance: f64) -> ContourFit {
        let (bits, points) = (tolerance.to_bits(), spline.points());
        let hash = static_hash(bits, points);
        let stored = self
            .loaded
            .fits
            .find(&self.bytes, hash, |key| is_static_key(key, bits, points));
        if let Some(slot) = stored {
            // An entry whose numbers are not finite is a miss.
            if let Ok(fit) = read_fit(slot.fit(&self.bytes)) {
                self.hit(&slot.used);
                return fit;
            }
        }
        let key = static_key(bits, points);
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
    /// not cached (the loader refuses such masters; they are refitted every time), nor
    /// are masters of different point counts or positions without one weight per master.
    pub fn fit_compatible(
        &self,
        masters: &[&XSpline],
        positions: &[Vec<f64>],
        tolerance: f64,
    ) -> Result<CompatibleFit, CompatibleError> {
        let Some(key) = compatible_key(masters, positions, tolerance) else {
            self.misses.fetch_add(1, Ordering::Relaxed);
            return fit_compatible(masters, positions, tolerance);
        };
        let stored = self
            .loaded
            .compatible
            .find(&self.bytes, bytes_hash(&key), |k| k == key);
        if let Some(slot) = stored {
            self.hit(&slot.used);
            return Ok(slot.value.clone());
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
        let stored = self
            .loaded
            .orient
            .find(&self.bytes, bytes_hash(&key.0), |k| k == key.0);
        if let Some(slot) = stored {
            // The contour count (u32), then one byte per contour, each 0 or 1 (checked at
            // load).
            let flags = &slot.fit(&self.bytes)[4..];
            if flags.len() == fitted.len() {
                self.mark_used(&slot.used);
                let flags: Vec<bool> = flags.iter().map(|&f| f == 1).collect();
                return join_reversed(&fitted, &flags);
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

    /// Marks every loaded entry used, so that what is saved keeps the entries this run did
    /// not ask for: for a run that makes only part of what `build` makes (`xglyph svg` of
    /// a font with masters fits neither the compatible fits nor the named instances), so
    /// that it does not make the next `build` fit them again. Not an entry this run made
    /// anew (one found damaged): no key is written twice. Call it once the fitting is done.
    pub fn keep_unused(&self) {
        let made = self.lock_made();
        let bytes = &self.bytes;
        for slot in &self.loaded.fits.slots {
            if !made.fits.contains_key(slot.key(bytes)) {
                self.mark_used(&slot.used);
            }
        }
        for slot in &self.loaded.compatible.slots {
            if !made.compatible.contains_key(slot.key(bytes)) {
                self.mark_used(&slot.used);
            }
        }
        for slot in &self.loaded.orient.slots {
            let key = <[u8; 32]>::try_from(slot.key(bytes)).map(GlyphKey);
            if !key.is_ok_and(|key| made.orient.contains_key(&key)) {
                self.mark_used(&slot.used);
            }
        }
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

    fn lock_made(&self) -> std::sync::MutexGuard<'_, Made> {
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
        let mut out = HEADER.start();
        self.put_body(&mut out, false);
        Header::seal(&mut out);
        out
    }

    /// Appends the fitters' key and the entries: the loaded ones used in this run (only
    /// the delta file's when `delta_only`), their bytes copied, and those made in this run,
    /// each kind sorted by key (no key is in both: a fit is made only when the files lack
    /// it, or hold it damaged and so unused).
    fn put_body(&self, out: &mut Vec<u8>, delta_only: bool) {
        let made = self.lock_made();
        for v in fitter_key() {
            out.extend_from_slice(&v.to_le_bytes());
        }
        let (bytes, loaded) = (&self.bytes, &self.loaded);
        let orient = made.orient.iter().map(|(k, v)| (&k.0[..], v));
        put_section(
            out,
            bytes,
            &loaded.orient,
            delta_only,
            orient,
            glyph_order,
            |out, flags: &Vec<bool>| put_flags(out, flags),
        );
        let fits = made.fits.iter().map(|(k, v)| (&k[..], v));
        put_section(
            out,
            bytes,
            &loaded.fits,
            delta_only,
            fits,
            static_order,
            put_fit,
        );
        let compatible = made.compatible.iter().map(|(k, v)| (&k[..], v));
        put_section(
            out,
            bytes,
            &loaded.compatible,
            delta_only,
            compatible,
            compatible_order,
            put_compatible_fit,
        );
    }

    /// Whether the file at `path` already holds [`FitCache::to_bytes`]: it is the file this
    /// cache was loaded from, every entry of it was used, and nothing new was fitted.
    fn file_is_current(&self, path: &Path) -> bool {
        self.source.as_deref() == Some(path)
            && self.lock_made().len() == 0
            && self.loaded_used.load(Ordering::Relaxed) == self.loaded.len()
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
            let made_n = self.lock_made().len();
            let (base_unused, delta_used) = [
                self.loaded.fits.usage(),
                self.loaded.compatible.usage(),
                self.loaded.orient.usage(),
            ]
            .iter()
            .fold((0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
            if (base_unused + delta_used + made_n) * DELTA_SHARE <= base_entries {
                // The delta file already holds what it would be given.
                if made_n == 0 && delta_used == self.delta_entries {
                    return Vec::new();
                }
                let mut out = DELTA_HEADER.start();
                base.put(&mut out);
                self.put_body(&mut out, true);
                Header::seal(&mut out);
                return vec![(delta_path(path), out)];
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

// A delta file: magic (8) | format version u32 | the cache file's length u64 and CRC-32 u32
//   | the same body as a cache file (fitter key, entries) | CRC-32 of everything before it

/// Appends one section of a file: its entry count (u64), then the entries sorted by
/// `order` of their keys: the used slots of `index` (only the delta file's when
/// `delta_only`), copied from `bytes`, and those `made` in this run (key, value), each
/// written as its key and what `put` writes of its value.
fn put_section<'a, T, V: 'a>(
    out: &mut Vec<u8>,
    bytes: &'a [u8],
    index: &'a Index<T>,
    delta_only: bool,
    made: impl Iterator<Item = (&'a [u8], &'a V)>,
    order: fn(&[u8], &[u8]) -> Order,
    put: impl Fn(&mut Vec<u8>, &V),
) {
    /// What follows a key: the loaded entry's bytes, or a value made in this run.
    enum Rest<'a, V> {
        Copied(&'a [u8]),
        Made(&'a V),
    }
    let mut all: Vec<(&[u8], Rest<V>)> = index
        .slots
        .iter()
        .filter(|s| s.is_used() && (s.in_delta || !delta_only))
        .map(|s| (s.key(bytes), Rest::Copied(s.fit(bytes))))
        .chain(made.map(|(key, value)| (key, Rest::Made(value))))
        .collect();
    all.sort_unstable_by(|a, b| order(a.0, b.0));
    out.extend_from_slice(&(all.len() as u64).to_le_bytes());
    // Room for the copied entries at least (a CJK font's file is 100 MB).
    out.reserve(
        all.iter()
            .map(|(key, rest)| {
                key.len()
                    + if let Rest::Copied(r) = rest {
                        r.len()
                    } else {
                        0
                    }
            })
            .sum(),
    );
    for (key, rest) in all {
        out.extend_from_slice(key);
        match rest {
            Rest::Copied(rest) => out.extend_from_slice(rest),
            Rest::Made(value) => put(out, value),
        }
    }
}

/// An orientation without its key: the contour count (u32), then one byte per contour.
fn put_flags(out: &mut Vec<u8>, flags: &[bool]) {
    out.extend_from_slice(&(flags.len() as u32).to_le_bytes());
    out.extend(flags.iter().map(|&r| u8::from(r)));
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
}

/// The entries of the file at `range` of `bytes` (a cache file, or with `bound` a delta
/// file bound to that cache file), indexed once the whole file is checked: its frame,
/// the fitters' key, every count, every orientation's flags, every static fit's path's
/// structure, every compatible entry whole, no key twice, nothing after the last entry.
fn index_file(
    bytes: &[u8],
    range: Range<usize>,
    bound: Option<Binding>,
) -> Result<Loaded, &'static str> {
    let header = if bound.is_some() {
        &DELTA_HEADER
    } else {
        &HEADER
    };
    let mut r = header.open(&bytes[range.clone()])?;
    if let Some(base) = bound {
        if Binding::read(&mut r)? != base {
            return Err("it belongs to another cache file");
        }
    }
    // Where the reader is in `bytes`: the body ends before the checksum.
    let body_end = range.end - 4;
    let at = |r: &Reader<'_>| body_end - r.remaining();
    let in_delta = bound.is_some();
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
    let n = r.u64()?;
    // An orientation entry is at least 32 + 4 bytes.
    let n = r.count(n, 36)?;
    let mut orient = Index::with_capacity(n);
    for _ in 0..n {
        let start = at(&r);
        r.take(32)?;
        let count = r.u32()?;
        let count = r.count(u64::from(count), 1)?;
        if r.take(count)?.iter().any(|&flag| flag > 1) {
            return Err("an orientation is malformed");
        }
        let key = start..start + 32;
        let hash = bytes_hash(&bytes[key.clone()]);
        let entry = Slot::new(hash, key.start..key.end, at(&r), in_delta, ());
        if !orient.insert(bytes, entry) {
            return Err("a glyph's orientation is stored twice");
        }
    }
    let n = r.u64()?;
    // A static entry is at least 8 + 4 + 8 + 4 bytes.
    let n = r.count(n, 24)?;
    let mut fits = Index::with_capacity(n);
    for _ in 0..n {
        let start = at(&r);
        r.u64()?;
        let count = r.u32()?;
        let count = r.count(u64::from(count), 24)?;
        r.take(24 * count)?;
        let key_end = at(&r);
        // The error; its value is checked when the fit is read.
        r.u64()?;
        skip_contour(&mut r)?;
        let hash = static_key_hash(&bytes[start..key_end]);
        if !fits.insert(bytes, Slot::new(hash, start..key_end, at(&r), in_delta, ())) {
            return Err("a contour is stored twice");
        }
    }
    let n = r.u64()?;
    // A compatible entry is at least 8 + 3 × 4 + 4 + 1 bytes.
    let n = r.count(n, 25)?;
    let mut compatible = Index::with_capacity(n);
    for _ in 0..n {
        let start = at(&r);
        let (masters, positions) = skip_compatible_key(&mut r)?;
        let key_end = at(&r);
        let fit = read_compatible_fit(&mut r, masters, positions)?;
        let hash = bytes_hash(&bytes[start..key_end]);
        if !compatible.insert(
            bytes,
            Slot::new(hash, start..key_end, at(&r), in_delta, fit),
        ) {
            return Err("a contour is stored twice");
        }
    }
    if !r.is_empty() {
        return Err("bytes follow the last entry");
    }
    Ok(Loaded {
        fits,
        compatible,
        orient,
    })
}

/// Skips a path that is one closed contour of lines and cubics: its element count, and
/// its elements, whose tags are checked (its numbers are when it is read: [`read_path`]).
fn skip_contour(r: &mut Reader<'_>) -> Result<(), &'static str> {
    const NOT_ONE: &str = "a path is not one closed contour";
    let one_contour = |k: usize, count: usize, tag: u8| match tag {
        TAG_MOVE => k == 0,
        TAG_LINE | TAG_CUBIC => k != 0 && k != count - 1,
        TAG_CLOSE => k == count - 1,
        _ => false,
    };
    if r.skip_path(one_contour, NOT_ONE)? < 2 {
        return Err(NOT_ONE);
    }
    Ok(())
}

/// A static fit (the bytes after its key): its error and its path, every number finite.
fn read_fit(bytes: &[u8]) -> Result<ContourFit, &'static str> {
    let mut r = Reader::new(bytes);
    let max_error = r.error()?;
    let path = read_path(&mut r)?;
    if !r.is_empty() {
        return Err("bytes follow the path");
    }
    Ok(ContourFit { path, max_error })
}

/// Skips a compatible entry's key (tolerance, counts, points, weights), checking its
/// counts; its master and position counts.
fn skip_compatible_key(r: &mut Reader<'_>) -> Result<(usize, usize), &'static str> {
    r.u64()?;
    let masters = r.u32()?;
    let masters = r.count(u64::from(masters), 24)?;
    let points = r.u32()?;
    let points = r.count(u64::from(points), 24)?;
    let positions = r.u32()?;
    let positions = r.count(u64::from(positions), 8)?;
    if masters == 0 {
        return Err("a compatible fit without masters");
    }
    let n = r.count((masters as u64).saturating_mul(points as u64), 24)?;
    r.take(24 * n)?;
    let n = r.count((positions as u64).saturating_mul(masters as u64), 8)?;
    r.take(8 * n)?;
    Ok((masters, positions))
}

/// A compatible entry's fit: one error per position and one path per master, all paths of
/// the same elements, as many segments as it says.
fn read_compatible_fit(
    r: &mut Reader<'_>,
    masters: usize,
    positions: usize,
) -> Result<CompatibleFit, &'static str> {
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
    Ok(CompatibleFit {
        paths,
        max_error,
        between_masters,
        segments,
    })
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

    /// The square moved right by `dx`.
    fn moved(dx: f64) -> XSpline {
        let points = square()
            .points()
            .iter()
            .map(|p| ControlPoint::new(p.pos.x + dx, p.pos.y, p.s))
            .collect();
        XSpline::new(points).unwrap()
    }

    /// A cache over a cache file's `bytes` (no delta file).
    fn loaded(bytes: &[u8]) -> Result<FitCache, &'static str> {
        FitCache::from_bytes(bytes.to_vec(), bytes.len())
    }

    /// `bytes` (a cache file) with its checksum made to match again.
    fn resealed(mut bytes: Vec<u8>) -> Vec<u8> {
        bytes.truncate(bytes.len() - 4);
        Header::seal(&mut bytes);
        bytes
    }

    #[test]
    fn a_round_trip_keeps_every_bit() {
        let cache = FitCache::new();
        let fit = cache.fit(&square(), 0.5);
        let bytes = cache.to_bytes();
        let again = loaded(&bytes).unwrap();
        assert_eq!(
            (again.loaded.fits.len(), again.loaded.compatible.len()),
            (1, 0)
        );
        let back = again.fit(&square(), 0.5);
        assert_eq!((again.hits(), again.misses()), (1, 0));
        assert_eq!(back.max_error.to_bits(), fit.max_error.to_bits());
        assert_eq!(back.path, fit.path);
        // Encoding is deterministic, and copying the used entry gives the same bytes.
        assert_eq!(again.to_bytes(), bytes);
        // The hash made from a spline is the one made from its key's bytes.
        let points = square().points().to_vec();
        let key = static_key(0.5f64.to_bits(), &points);
        assert_eq!(
            static_key_hash(&key),
            static_hash(0.5f64.to_bits(), &points)
        );
        assert!(is_static_key(&key, 0.5f64.to_bits(), &points));
        assert!(!is_static_key(&key, 0.25f64.to_bits(), &points));
        assert!(!is_static_key(&key, 0.5f64.to_bits(), &points[1..]));
    }

    #[test]
    fn the_file_is_rewritten_only_when_this_run_changed_its_entries() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(CACHE_FILE);
        let first = FitCache::new();
        first.fit(&moved(0.0), 0.5);
        first.fit(&moved(5.0), 0.5);
        assert!(!first.file_is_current(&path));
        first.save(&path).unwrap();
        let bytes = std::fs::read(&path).unwrap();

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

    /// Where the static entry for `spline` at `tolerance` lies in `cache`'s bytes.
    fn static_slot(cache: &FitCache, spline: &XSpline, tolerance: f64) -> (usize, usize) {
        let (bits, points) = (tolerance.to_bits(), spline.points());
        let slot = cache
            .loaded
            .fits
            .find(&cache.bytes, static_hash(bits, points), |key| {
                is_static_key(key, bits, points)
            })
            .unwrap();
        (slot.key_end, slot.end)
    }

    #[test]
    fn a_corrupt_fit_with_a_valid_checksum_is_refitted_not_used() {
        let good = {
            let cache = FitCache::new();
            cache.fit(&moved(0.0), 0.5);
            cache.fit(&moved(5.0), 0.5);
            cache.to_bytes()
        };
        let (fit_at, _) = static_slot(&loaded(&good).unwrap(), &moved(0.0), 0.5);
        // The error (8 bytes), the element count (4), the move's tag (1), then its x.
        let x_at = fit_at + 8 + 4 + 1;
        assert_eq!(
            good[x_at..x_at + 8],
            fit_contour(&moved(0.0), 0.5).path.elements()[0]
                .end_point()
                .unwrap()
                .x
                .to_bits()
                .to_le_bytes()
        );
        for (what, at, value) in [
            ("a point at infinity", x_at, f64::INFINITY),
            ("a point not a number", x_at, f64::NAN),
            ("a negative error", fit_at, -1.0),
            ("an error not a number", fit_at, f64::NAN),
        ] {
            let mut bad = good.clone();
            bad[at..at + 8].copy_from_slice(&value.to_bits().to_le_bytes());
            let bad = resealed(bad);
            // The file is whole: it loads, and the other contour comes from it.
            let cache = loaded(&bad).unwrap();
            assert_eq!(cache.loaded.fits.len(), 2, "{what}");
            let fit = cache.fit(&moved(0.0), 0.5);
            let direct = fit_contour(&moved(0.0), 0.5);
            assert_eq!(fit.path, direct.path, "{what}");
            assert_eq!(
                fit.max_error.to_bits(),
                direct.max_error.to_bits(),
                "{what}"
            );
            cache.fit(&moved(5.0), 0.5);
            // The bad entry is a miss, again on a second call (from this run's fits), and
            // never marked used: the file written next is the good one.
            cache.fit(&moved(0.0), 0.5);
            assert_eq!(
                (cache.hits(), cache.reused(), cache.misses()),
                (1, 1, 1),
                "{what}"
            );
            assert_eq!(cache.loaded_used.load(Ordering::Relaxed), 1, "{what}");
            assert_eq!(cache.to_bytes(), good, "{what}");
        }
    }

    #[test]
    fn keep_unused_keeps_what_the_run_did_not_ask_for_but_no_key_twice() {
        // A file of three fits and one glyph's orientation, the first fit's x damaged.
        let (placed, fitted) = nested();
        let good = {
            let cache = FitCache::new();
            for dx in [0.0, 5.0, 10.0] {
                cache.fit(&moved(dx), 0.5);
            }
            cache.orient_placed(&placed, 0.5, fitted.clone());
            cache.to_bytes()
        };
        let (fit_at, _) = static_slot(&loaded(&good).unwrap(), &moved(0.0), 0.5);
        let mut bad = good.clone();
        let x_at = fit_at + 8 + 4 + 1;
        bad[x_at..x_at + 8].copy_from_slice(&f64::NAN.to_bits().to_le_bytes());
        let bad = resealed(bad);
        // A run that asks for the damaged fit (refitted) and one other: without
        // `keep_unused` the file drops the third fit and the orientation; with it, they
        // stay, and the refitted one replaces the damaged one (one entry per key: the
        // file written is the good one, which loads whole).
        let run = |keep: bool| {
            let cache = loaded(&bad).unwrap();
            cache.fit(&moved(0.0), 0.5);
            cache.fit(&moved(5.0), 0.5);
            assert_eq!((cache.hits(), cache.misses()), (1, 1));
            if keep {
                cache.keep_unused();
            }
            cache.to_bytes()
        };
        let dropped = run(false);
        assert_eq!(loaded(&dropped).unwrap().loaded.len(), 2);
        assert_eq!(run(true), good);
        assert_eq!(loaded(&good).unwrap().loaded.len(), 4);
        // A run that made nothing and kept the rest leaves the file alone.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(CACHE_FILE);
        std::fs::write(&path, &good).unwrap();
        let (cache, _) = FitCache::load(&path);
        cache.fit(&moved(10.0), 0.5);
        assert!(!cache.files_to_save(&path).is_empty());
        cache.keep_unused();
        assert!(cache.files_to_save(&path).is_empty());
    }

    #[test]
    fn keys_of_one_hash_are_told_apart_by_their_bytes() {
        let (a, b) = (moved(0.0), moved(5.0));
        let bytes = {
            let cache = FitCache::new();
            cache.fit(&a, 0.5);
            cache.fit(&b, 0.5);
            cache.to_bytes()
        };
        let mut cache = loaded(&bytes).unwrap();
        // Give b's entry a's hash, and insert it first: a lookup of a may meet b's entry,
        // with the same hash.
        let hash_a = static_hash(0.5f64.to_bits(), a.points());
        let mut slots = std::mem::take(&mut cache.loaded.fits).slots;
        slots.sort_by_key(|s| s.hash != hash_a);
        slots.reverse();
        let mut index = Index::with_capacity(2);
        for mut slot in slots {
            slot.hash = hash_a;
            assert!(index.insert(&cache.bytes, slot));
        }
        assert_eq!(index.table.len(), 2);
        assert!(!is_static_key(
            index.slots[0].key(&cache.bytes),
            0.5f64.to_bits(),
            a.points()
        ));
        cache.loaded.fits = index;
        // a: its own fit, from the file.
        let fit = cache.fit(&a, 0.5);
        assert_eq!(fit.path, fit_contour(&a, 0.5).path);
        assert_eq!((cache.hits(), cache.misses()), (1, 0));
        // b: its hash no longer finds it, so it is refitted; never a's fit.
        let fit = cache.fit(&b, 0.5);
        assert_eq!(fit.path, fit_contour(&b, 0.5).path);
        assert_ne!(fit.path, fit_contour(&a, 0.5).path);
        assert_eq!((cache.hits(), cache.misses()), (1, 1));
        // Two keys of one hash in an index: each found by its bytes, a third not at all,
        // and the same key twice refused.
        let bytes = b"aaaabbbbcccc";
        let entry = |start| Slot {
            hash: 7,
            start,
            key_end: start + 4,
            end: start + 4,
            used: AtomicBool::new(false),
            in_delta: false,
            value: (),
        };
        let mut index = Index::default();
        assert!(index.insert(bytes, entry(0)));
        assert!(index.insert(bytes, entry(4)));
        assert!(!index.insert(bytes, entry(0)));
        for key in [b"aaaa", b"bbbb"] {
            let found = index.find(bytes, 7, |k| k == key).unwrap();
            assert_eq!(found.key(bytes), key);
        }
        assert!(index.find(bytes, 7, |k| k == b"cccc").is_none());
        assert!(index.find(bytes, 8, |k| k == b"aaaa").is_none());
        // Grown past its first size, it still finds every key.
        let many: Vec<u8> = (0..200u32).flat_map(|k| k.to_le_bytes()).collect();
        let mut index = Index::default();
        for k in 0..200 {
            let slot = Slot {
                hash: (k % 3) as u64,
                ..entry(4 * k)
            };
            assert!(index.insert(&many, slot));
        }
        assert_eq!(index.table.len(), 200);
        for k in 0..200usize {
            let key = &many[4 * k..4 * k + 4];
            assert!(index.find(&many, (k % 3) as u64, |s| s == key).is_some());
        }
    }

    /// A small deterministic generator of words, most of them from a short list (so that
    /// keys share prefixes), some with high bytes set (where the bytes' order is not the
    /// numbers').
    struct Words(u64);

    impl Words {
        fn next(&mut self) -> u64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let r = self.0 >> 33;
            [0, 1, 256, 1 << 56, u64::MAX, r][(r % 6) as usize]
        }
        fn below(&mut self, n: u64) -> usize {
            (self.next() % n) as usize
        }
    }

    #[test]
    fn the_bytes_order_is_the_keys_order() {
        let mut w = Words(1);
        // Static keys: (tolerance, points).
        let keys: Vec<(u64, Vec<[u64; 3]>)> = (0..300)
            .map(|_| {
                let n = w.below(4);
                (
                    w.next() % 3,
                    (0..n).map(|_| [w.next(), w.next() % 2, 0]).collect(),
                )
            })
            .collect();
        let bytes: Vec<Vec<u8>> = keys
            .iter()
            .map(|(tolerance, points)| {
                let mut out = tolerance.to_le_bytes().to_vec();
                out.extend_from_slice(&(points.len() as u32).to_le_bytes());
                for v in points.iter().flatten() {
                    out.extend_from_slice(&v.to_le_bytes());
                }
                out
            })
            .collect();
        same_order(&keys, &bytes, static_order);
        // Compatible keys: (tolerance, positions, masters).
        type Compatible = (u64, Vec<Vec<u64>>, Vec<Vec<[u64; 3]>>);
        let keys: Vec<Compatible> = (0..300)
            .map(|_| {
                let (masters, points, positions) = (1 + w.below(2), w.below(3), w.below(3));
                let weights = (0..positions)
                    .map(|_| (0..masters).map(|_| w.next() % 3).collect())
                    .collect();
                let points = (0..masters)
                    .map(|_| (0..points).map(|_| [w.next(), 0, w.next() % 2]).collect())
                    .collect();
                (w.next() % 2, weights, points)
            })
            .collect();
        let bytes: Vec<Vec<u8>> = keys
            .iter()
            .map(|(tolerance, weights, masters)| {
                let mut out = tolerance.to_le_bytes().to_vec();
                for count in [masters.len(), masters[0].len(), weights.len()] {
                    out.extend_from_slice(&(count as u32).to_le_bytes());
                }
                for v in masters
                    .iter()
                    .flatten()
                    .flatten()
                    .chain(weights.iter().flatten())
                {
                    out.extend_from_slice(&v.to_le_bytes());
                }
                out
            })
            .collect();
        same_order(&keys, &bytes, compatible_order);
    }

    /// Every pair of `keys` compares as `order` compares their encodings `bytes`.
    fn same_order<K: Ord + std::fmt::Debug>(
        keys: &[K],
        bytes: &[Vec<u8>],
        order: impl Fn(&[u8], &[u8]) -> std::cmp::Ordering,
    ) {
        for (a, a_bytes) in keys.iter().zip(bytes) {
            for (b, b_bytes) in keys.iter().zip(bytes) {
                assert_eq!(order(a_bytes, b_bytes), a.cmp(b), "{a:?} {b:?}");
            }
        }
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

    /// A cache file holding only the orientation `flags` of the glyph `key`.
    fn orientation_file(key: GlyphKey, flags: Vec<bool>) -> Vec<u8> {
        let cache = FitCache::new();
        cache.lock_made().orient.insert(key, flags);
        cache.to_bytes()
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
        let warm = loaded(&bytes).unwrap();
        assert_eq!(warm.loaded.orient.len(), 1);
        assert_eq!(warm.orient_placed(&placed, 0.5, fitted.clone()), expected);
        assert_eq!(warm.loaded_used.load(Ordering::Relaxed), 1);
        assert!(warm.lock_made().orient.is_empty());
        assert_eq!(warm.to_bytes(), bytes);
        // Another tolerance or placement is another glyph.
        let moved: Vec<PlacedContour> = placed
            .iter()
            .map(|c| PlacedContour {
                offset: kurbo::Vec2::new(0.0, 1e-9),
                ..c.clone()
            })
            .collect();
        for (other, tolerance) in [(&placed, 0.25), (&moved, 0.5)] {
            warm.orient_placed(other, tolerance, fitted.clone());
        }
        assert_eq!(warm.lock_made().orient.len(), 2);

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
            let cache = loaded(&orientation_file(key, flags)).unwrap();
            assert_eq!(cache.orient_placed(&placed, 0.5, fitted.clone()), want);
        }
        // A flag byte other than 0 or 1 makes the whole file refused.
        let mut bad = orientation_file(key, vec![false, true, false]);
        let at = bad.len() - 4 - 8 - 8 - 2;
        assert_eq!(bad[at], 1);
        bad[at] = 2;
        assert_eq!(
            loaded(&resealed(bad)).err(),
            Some("an orientation is malformed")
        );
    }

    #[test]
    fn structural_checks_reject_what_the_checksum_would_pass() {
        let cache = FitCache::new();
        cache.fit(&square(), 0.5);
        let good = cache.to_bytes();
        // A body whose path's ClosePath tag became a MoveTo (a second contour that never
        // closes), resealed: the CRC matches, the structure does not, and the file is
        // refused at load. The last 8 bytes before the checksum count the compatible
        // entries (none).
        let mut bad = good.clone();
        let last = good.len() - 4 - 8 - 1;
        assert_eq!(bad[last], TAG_CLOSE);
        bad[last] = TAG_MOVE;
        assert_eq!(
            loaded(&resealed(bad)).err(),
            Some("a path is not one closed contour")
        );
        // A quadratic where the first cubic is: refused too.
        let mut bad = good.clone();
        let (start, _) = static_slot(&loaded(&good).unwrap(), &square(), 0.5);
        // The error (8), the element count (4), the move (1 + 16), then the second tag.
        let tag = start + 8 + 4 + 17;
        assert!([TAG_LINE, TAG_CUBIC].contains(&bad[tag]));
        bad[tag] = crate::record::TAG_QUAD;
        assert_eq!(
            loaded(&resealed(bad)).err(),
            Some("a path is not one closed contour")
        );
        // A byte after the last entry.
        let mut bad = good[..good.len() - 4].to_vec();
        bad.push(0);
        Header::seal(&mut bad);
        assert_eq!(loaded(&bad).err(), Some("bytes follow the last entry"));
    }
}
