//! Reuse of the files an earlier build wrote, when what they are made from is unchanged:
//! a rebuild after one edit does not rasterise every sheet page again, nor run Brotli on a
//! font whose bytes did not change.
//!
//! Each reusable output is made under a [`Key`]: a SHA-256 of everything its bytes depend
//! on (for a sheet page: its glyphs' outlines, names and advances, the font's metrics, the
//! options; for a WOFF2: the TTF's bytes), plus the identity of the running program (its
//! executable's stamp, so a changed renderer never reuses an old file).
//! After a successful build, [`Reuse::save`] records in [`REUSE_FILE`] (in OUT, beside the fit
//! cache) each output's path, key and the SHA-256 of the bytes written.
//!
//! A rebuild that changed few entries writes only a delta file beside the record
//! ([`DELTA_FILE`]: the entries the record file lacks as they are now, bound to it by its
//! length and checksum), so that an edit of one glyph does not rewrite a CJK font's 90 MB;
//! the record file is written whole again when the delta and the record file's unused
//! entries pass an eighth of its entries ([`Reuse::files_to_save`]). Limit: until then the
//! record file keeps the entries of edited glyphs, and the two files depend on the order
//! of the edits, not only on the sources.
//!
//! Nothing is trusted. The record file is checked whole (magic, version, CRC-32, counts,
//! paths, no duplicate, no trailing byte) or ignored; so is the delta file, which is also
//! ignored when it is bound to another record file (the one a whole rewrite leaves
//! behind). A union's outline is decoded when a build uses it, and one that does not
//! decode whole is made anew. A file is reused only when the
//! record's key equals the new key *and* the file in OUT still holds the recorded bytes
//! (read and hashed again): a file edited, truncated or replaced since is made anew. The
//! sources stay the only source of truth; no modification time is read. Outputs are
//! therefore byte-identical with and without this record.
//!
//! The same record holds outlines made from outlines: each glyph's union of overlapping
//! contours ([`crate::overlap`]), keyed by its input outline and the union's setting, so
//! that a rebuild unions only the glyphs that changed. A union equal to its input (a glyph
//! without overlaps) is recorded as such, not stored again. It holds, the same way, data
//! made from one glyph's outline for a font's tables: its `glyf` bytes and its CFF
//! charstring ([`crate::otf`]), so that a rebuild converts one glyph, not 20,000; and the
//! Brotli slices of a large font's WOFF2.
//!
//! It also holds each output file's [`FileStamp`] after the commit (its metadata and the
//! SHA-256 of its bytes), so that the next commit need not read back the ~42,000 files of a
//! CJK build to find those that did not change ([`crate::write`]): a file whose metadata
//! changed is read and compared as before.
//!
//! Outputs of one file per glyph (the SVG glyph set, the UFO's `.glif`s) go further
//! ([`Reuse::kept_or_make`]): when the record says the file in OUT holds the bytes made under
//! the same key, and the file still has the [`FileStamp`] recorded for it (metadata only,
//! not read), the bytes are not made at all and the file is left as it is. A CJK rebuild
//! after one edit makes two such files instead of 42,000.
//!
//! Limit: a key is as complete as the code that builds it; an output depends only on what
//! its key lists (see the callers: [`crate::pipeline`], [`crate::render::sheet`]).

use std::collections::HashMap;
use std::fs;
use std::io;
use std::ops::Range;
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};

use kurbo::BezPath;
use rustc_hash::FxHashMap;

use crate::outline::{OutlinedFont, OutlinedGlyph};
use crate::record::{put_path, read_with_delta, Binding, Header, Reader};
use crate::write::FileStamp;
use sha2::{Digest, Sha256};

/// Name of the record file in the output folder.
pub const REUSE_FILE: &str = ".xglyph-outputs";

/// First bytes of the record file.
const HEADER: Header = Header {
    magic: b"XGLYPHOR",
    version: FORMAT_VERSION,
    not_ours: "it is not an xglyph output record",
};
/// Layout of the record file.
const FORMAT_VERSION: u32 = 3;

/// Name of the delta file beside it: the entries of the builds since the record file was
/// last written whole ([`Reuse::files_to_save`]).
pub const DELTA_FILE: &str = ".xglyph-outputs-delta";

/// The frame of a delta file.
const DELTA_HEADER: Header = Header {
    magic: b"XGLYPHOD",
    version: FORMAT_VERSION,
    not_ours: "it is not an xglyph output record delta",
};

/// The delta file may hold at most this fraction (1 / n) of the record file's entry count,
/// counting with it the record file's entries no longer used; beyond, the record file is
/// written whole again.
const DELTA_SHARE: usize = 8;

/// What an output's bytes are made from, hashed (SHA-256).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Key([u8; 32]);

impl Key {
    /// The hash's bytes.
    pub fn to_bytes(self) -> [u8; 32] {
        self.0
    }
}

/// Whether the running program's identity is known (its executable could be read): keys
/// made without it would not tell two programs apart, so nothing is reused then.
pub fn program_is_known() -> bool {
    program_identity().is_some()
}

/// Builds a [`Key`]: every input goes in with its length or its kind, so that two
/// different input lists never hash the same bytes.
#[derive(Clone)]
pub struct KeyBuilder(Sha256);

impl KeyBuilder {
    /// A key for an output of kind `kind` (e.g. `"sheet page"`), made by this program.
    pub fn new(kind: &str) -> Self {
        let mut b = KeyBuilder(Sha256::new());
        b.0.update(program_identity().unwrap_or(&[0; 32]));
        b.str(kind);
        b
    }

    /// Adds bytes (length first).
    pub fn bytes(&mut self, bytes: &[u8]) -> &mut Self {
        self.0.update((bytes.len() as u64).to_le_bytes());
        self.0.update(bytes);
        self
    }

    /// Adds a string.
    pub fn str(&mut self, s: &str) -> &mut Self {
        self.bytes(s.as_bytes())
    }

    /// Adds a number (its bits).
    pub fn f64(&mut self, v: f64) -> &mut Self {
        self.0.update(v.to_bits().to_le_bytes());
        self
    }

    /// Adds a count or an index.
    pub fn u64(&mut self, v: u64) -> &mut Self {
        self.0.update(v.to_le_bytes());
        self
    }

    /// Adds another key.
    pub fn key(&mut self, key: &Key) -> &mut Self {
        self.0.update(key.0);
        self
    }

    /// Adds a path: every element's kind and the bits of its points.
    pub fn path(&mut self, path: &BezPath) -> &mut Self {
        // One buffer, one update: hashing element by element costs more than the hash.
        let mut buf = Vec::with_capacity(path.elements().len() * 40);
        put_path(&mut buf, path);
        self.bytes(&buf)
    }

    /// The key.
    pub fn finish(&self) -> Key {
        Key(self.0.clone().finalize().into())
    }
}

/// The SHA-256 of `bytes`.
fn digest(bytes: &[u8]) -> [u8; 32] {
    Sha256::digest(bytes).into()
}

/// The running program's identity (read once), or `None` when its executable cannot be
/// read; then nothing is reused.
///
/// An executable that has settled ([`crate::write::settled_meta`]) is known by its stamp:
/// length, inode, modification and change times. Any relink, copy or rewrite moves the
/// change time, so two programs never share a stamp; reading the 20 MB file instead cost a
/// short build 15 to 20 ms on one core. A file changed in the last moments is known by its
/// length and CRC-32, as it could still change within one tick of its clock.
fn program_identity() -> Option<&'static [u8; 32]> {
    static ID: OnceLock<Option<[u8; 32]>> = OnceLock::new();
    ID.get_or_init(|| file_identity(&std::env::current_exe().ok()?))
        .as_ref()
}

/// The identity of the file at `path` as [`program_identity`] takes it.
fn file_identity(path: &Path) -> Option<[u8; 32]> {
    let mut id = Sha256::new();
    match fs::metadata(path)
        .ok()
        .as_ref()
        .and_then(crate::write::settled_meta)
    {
        Some(stamp) => {
            id.update(b"stamp");
            stamp.iter().for_each(|word| id.update(word.to_le_bytes()));
        }
        None => {
            let (len, crc) = file_crc(path)?;
            id.update(b"crc");
            id.update(len.to_le_bytes());
            id.update(crc.to_le_bytes());
        }
    }
    Some(id.finalize().into())
}

/// The length and CRC-32 of the file at `path`, read in pieces through one small buffer
/// (reading a 20 MB executable whole costs mostly the kernel handing out fresh pages).
fn file_crc(path: &Path) -> Option<(u64, u32)> {
    let mut file = fs::File::open(path).ok()?;
    let mut crc = crc32fast::Hasher::new();
    let mut buf = vec![0; 1 << 16];
    let mut len = 0u64;
    loop {
        match io::Read::read(&mut file, &mut buf) {
            Ok(0) => break,
            Ok(n) => {
                crc.update(&buf[..n]);
                len += n as u64;
            }
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(_) => return None,
        }
    }
    Some((len, crc.finalize()))
}

/// One output as recorded: its key and the SHA-256 of its bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Record {
    key: Key,
    bytes: [u8; 32],
}

/// An entry of the last build's record, and whether it came from the delta file.
#[derive(Clone, Debug)]
struct Earlier<T> {
    value: T,
    in_delta: bool,
}

impl<T> Earlier<T> {
    fn new(value: T, in_delta: bool) -> Self {
        Earlier { value, in_delta }
    }
}

/// The outputs of the last build of an output folder, and those of this one.
#[derive(Debug, Default)]
pub struct Reuse {
    /// The output folder (`None`: reuse nothing, record nothing).
    out: Option<PathBuf>,
    /// The last build's records, by path relative to `out`.
    earlier: FxHashMap<PathBuf, Earlier<Record>>,
    /// This build's records (sorted when saved).
    now: Mutex<FxHashMap<PathBuf, Record>>,
    reused: AtomicUsize,
    /// Outlines made from outlines (a glyph's contours unioned) by the last build, by key:
    /// where each entry (a tag, then the outline unless it was its input unchanged, as for
    /// most glyphs: no overlap) lies in `earlier_bytes`. Decoded only when used.
    earlier_paths: FxHashMap<Key, Earlier<Range<usize>>>,
    /// Those of this build, as entries; `None`: the last build's, unchanged (not copied).
    now_paths: Mutex<FxHashMap<Key, Option<Vec<u8>>>>,
    /// Glyph data made by the last build ([`Reuse::data_or_make`]), by key: where it lies
    /// in `earlier_bytes`.
    earlier_data: FxHashMap<Key, Earlier<Range<usize>>>,
    /// The last build's record file, then its delta file, which those ranges index (the
    /// data is not copied out: a CJK font keeps 85 MB of it).
    earlier_bytes: Vec<u8>,
    /// Those of this build; `None`: the last build's, unchanged (not copied).
    now_data: Mutex<FxHashMap<Key, Option<Vec<u8>>>>,
    /// The output files as the last build's commit left them, by path relative to `out`.
    earlier_files: FxHashMap<PathBuf, Earlier<FileStamp>>,
    /// As this build's commit left them (sorted when saved).
    now_files: Mutex<FxHashMap<PathBuf, FileStamp>>,
    /// Outputs left in OUT unmade ([`Reuse::kept_or_make`]), by path relative to `out`.
    kept: Mutex<Vec<PathBuf>>,
    /// The record file loaded: its binding and entry count; and where the delta file loaded
    /// with it lies in `earlier_bytes`.
    base: Option<(Binding, usize)>,
    delta: Option<Range<usize>>,
}

impl Reuse {
    /// Reuses nothing: every output is made.
    pub fn off() -> Self {
        Reuse::default()
    }

    /// The records of the output folder `out` (the record file and its delta file), and why
    /// they were ignored, if they were (a missing file is not a reason: a first build has
    /// none; a delta file that is damaged or bound to another record file is ignored
    /// silently, as the one a whole rewrite leaves behind is).
    pub fn load(out: &Path) -> (Self, Option<String>) {
        let mut reuse = Reuse {
            out: Some(out.to_path_buf()),
            ..Reuse::default()
        };
        if program_identity().is_none() {
            reuse.out = None;
            return (reuse, Some("the program's own file cannot be read".into()));
        }
        // Both files in one buffer, so that every range indexes it.
        let (mut bytes, base_len) =
            match read_with_delta(&out.join(REUSE_FILE), &out.join(DELTA_FILE)) {
                Ok(read) => read,
                Err(e) if e.kind() == io::ErrorKind::NotFound => return (reuse, None),
                Err(e) => return (reuse, Some(crate::write::reason(&e))),
            };
        let base = Binding::of(&bytes[..base_len]);
        let mut parsed = match HEADER
            .open(&bytes[..base_len])
            .and_then(|mut r| parse(&mut r, &bytes, false))
        {
            Ok(parsed) => parsed,
            Err(why) => return (reuse, Some(why.to_string())),
        };
        reuse.base = Some((base, parsed.entries()));
        if bytes.len() > base_len {
            match parse_delta(&bytes, base_len, base) {
                Ok(delta) => {
                    parsed.merge(delta);
                    reuse.delta = Some(base_len..bytes.len());
                }
                Err(_) => bytes.truncate(base_len),
            }
        }
        reuse.earlier = parsed.records;
        reuse.earlier_paths = parsed.paths;
        reuse.earlier_data = parsed.data;
        reuse.earlier_files = parsed.files;
        reuse.earlier_bytes = bytes;
        (reuse, None)
    }

    /// The bytes of the output `path` (relative to OUT): the file in OUT when the last build
    /// made it under the same `key` and it still holds the bytes recorded, else `make()`.
    pub fn get_or_make<E>(
        &self,
        path: &Path,
        key: Key,
        make: impl FnOnce() -> Result<Vec<u8>, E>,
    ) -> Result<Vec<u8>, E> {
        let Some(out) = &self.out else {
            return make();
        };
        let earlier = self.earlier.get(path).map(|e| &e.value);
        if let Some(earlier) = earlier.filter(|r| r.key == key) {
            if let Ok(bytes) = fs::read(out.join(path)) {
                if digest(&bytes) == earlier.bytes {
                    self.reused.fetch_add(1, Ordering::Relaxed);
                    self.record(path, *earlier);
                    return Ok(bytes);
                }
            }
        }
        let bytes = make()?;
        let record = Record {
            key,
            bytes: digest(&bytes),
        };
        self.record(path, record);
        Ok(bytes)
    }

    /// The bytes of the output `path` (relative to OUT), or `None` when OUT's file holds them
    /// already: the last build made it under the same `key`, and the file still has the
    /// stamp its commit recorded (length, inode, times; not read), with the recorded hash.
    /// Then nothing is made, the output is not to be written, and its record and stamp are
    /// carried into this build's ([`Reuse::kept_paths`] lists it). Otherwise `make()`.
    pub fn kept_or_make<E>(
        &self,
        path: &Path,
        key: Key,
        make: impl FnOnce() -> Result<Vec<u8>, E>,
    ) -> Result<Option<Vec<u8>>, E> {
        let Some(out) = &self.out else {
            return make().map(Some);
        };
        let earlier = self.earlier.get(path).map(|e| &e.value);
        if let Some(earlier) = earlier.filter(|r| r.key == key) {
            let stamp = self
                .earlier_files
                .get(path)
                .map(|e| &e.value)
                .filter(|s| s.sha256 == earlier.bytes);
            if let Some(stamp) = stamp.filter(|s| s.matches(&out.join(path))) {
                self.record(path, *earlier);
                if let Ok(mut files) = self.now_files.lock() {
                    files.insert(path.to_path_buf(), *stamp);
                }
                if let Ok(mut kept) = self.kept.lock() {
                    kept.push(path.to_path_buf());
                }
                return Ok(None);
            }
        }
        let bytes = make()?;
        self.record(
            path,
            Record {
                key,
                bytes: digest(&bytes),
            },
        );
        Ok(Some(bytes))
    }

    /// The outputs [`Reuse::kept_or_make`] left in OUT, sorted.
    pub fn kept_paths(&self) -> Vec<PathBuf> {
        let mut kept = self.kept.lock().map(|k| k.clone()).unwrap_or_default();
        kept.sort();
        kept
    }

    /// The outline `make()` computes from `input` under `key` (which must cover `input`
    /// and every setting `make` reads): from the last build when it made it, else made now.
    /// Kept for the next build either way.
    pub fn path_or_make(
        &self,
        key: Key,
        input: &BezPath,
        make: impl FnOnce() -> BezPath,
    ) -> BezPath {
        if self.out.is_none() {
            return make();
        }
        let earlier = self.earlier_paths.get(&key).and_then(|e| {
            let entry = self.earlier_bytes.get(e.value.clone())?;
            union_from_entry(entry, input)
        });
        let (path, entry) = match earlier {
            Some(path) => (path, None),
            None => {
                let path = make();
                let entry = union_entry(&path, input);
                (path, Some(entry))
            }
        };
        if let Ok(mut now) = self.now_paths.lock() {
            now.insert(key, entry);
        }
        path
    }

    /// Whether the last build recorded an outline under `key` ([`Reuse::path_or_make`]);
    /// if so it is kept for the next build as it is, and [`Reuse::path_or_make`] decodes it
    /// when this build needs it (the entry is checked then: one that does not decode whole
    /// is made anew).
    pub fn keeps_path(&self, key: Key) -> bool {
        if self.out.is_none() || !self.earlier_paths.contains_key(&key) {
            return false;
        }
        if let Ok(mut now) = self.now_paths.lock() {
            now.entry(key).or_insert(None);
        }
        true
    }

    /// The value `make()` computes under `key` (which must cover every input `make` reads),
    /// kept as bytes: the last build's when it made one under `key` and `decode` accepts its
    /// bytes, else made now. Kept for the next build either way. Without an output folder,
    /// `make()`.
    pub fn data_or_make<T, E>(
        &self,
        key: Key,
        encode: impl FnOnce(&T) -> Vec<u8>,
        decode: impl FnOnce(&[u8]) -> Option<T>,
        make: impl FnOnce() -> Result<T, E>,
    ) -> Result<T, E> {
        if self.out.is_none() {
            return make();
        }
        let earlier = self
            .earlier_data
            .get(&key)
            .and_then(|e| decode(self.earlier_bytes.get(e.value.clone())?));
        let (value, bytes) = match earlier {
            Some(value) => (value, None),
            None => {
                let value = make()?;
                let bytes = encode(&value);
                (value, Some(bytes))
            }
        };
        if let Ok(mut now) = self.now_data.lock() {
            now.insert(key, bytes);
        }
        Ok(value)
    }

    fn record(&self, path: &Path, record: Record) {
        if let Ok(mut now) = self.now.lock() {
            now.insert(path.to_path_buf(), record);
        }
    }

    /// The stamps of OUT's files as the last build left them (paths under OUT), for
    /// [`crate::write::OutputSet::trusting`].
    pub fn file_stamps(&self) -> HashMap<PathBuf, FileStamp> {
        match &self.out {
            Some(out) => self
                .earlier_files
                .iter()
                .map(|(path, stamp)| (out.join(path), stamp.value))
                .collect(),
            None => HashMap::new(),
        }
    }

    /// Keeps the stamps this build's commit returned (paths under OUT) for
    /// [`Reuse::save`].
    pub fn files_written(&self, stamps: HashMap<PathBuf, FileStamp>) {
        let Some(out) = &self.out else { return };
        if let Ok(mut now) = self.now_files.lock() {
            now.extend(stamps.into_iter().filter_map(|(path, stamp)| {
                Some((path.strip_prefix(out).ok()?.to_path_buf(), stamp))
            }));
        }
    }

    /// Whether outputs may come from OUT (false for [`Reuse::off`]).
    pub fn is_on(&self) -> bool {
        self.out.is_some()
    }

    /// How many outputs came from OUT instead of being made.
    pub fn reused(&self) -> usize {
        self.reused.load(Ordering::Relaxed)
    }

    /// Writes this build's records into OUT (atomically; [`Reuse::files_to_save`]); call it
    /// once every output is written. Nothing without an output folder.
    pub fn save(&self) -> io::Result<()> {
        for (path, bytes) in self.files_to_save()? {
            crate::write::write_atomic(&path, &bytes)?;
        }
        Ok(())
    }

    /// What [`Reuse::save`] writes into OUT (none without an output folder): nothing when
    /// the files there hold this build's records already; only the delta file
    /// ([`DELTA_FILE`]: the entries not in the record file as they are now, bound to it by
    /// its length and checksum) when the record file is the one loaded and the delta's
    /// entries with the record file's unused ones are at most 1/8 of its entries, so that an
    /// edit of one glyph does not rewrite a CJK font's 90 MB; else [`REUSE_FILE`] whole,
    /// which leaves any delta file bound to the old one.
    pub fn files_to_save(&self) -> io::Result<Vec<(PathBuf, Vec<u8>)>> {
        let Some(out) = &self.out else {
            return Ok(Vec::new());
        };
        let poisoned = || io::Error::other("a build thread panicked");
        let now = self.now.lock().map_err(|_| poisoned())?;
        let paths = self.now_paths.lock().map_err(|_| poisoned())?;
        let data = self.now_data.lock().map_err(|_| poisoned())?;
        let files = self.now_files.lock().map_err(|_| poisoned())?;
        // Each entry with whether the record file holds it as it is now; sorted only when
        // it is written (a delta's few entries, or the whole file's).
        let records: Vec<(&str, Record, bool)> = now
            .iter()
            .filter_map(|(path, r)| {
                let e = self.earlier.get(path);
                Some((
                    path.to_str()?,
                    *r,
                    e.is_some_and(|e| !e.in_delta && e.value == *r),
                ))
            })
            .collect();
        let stamps: Vec<(&str, FileStamp, bool)> = files
            .iter()
            .filter_map(|(path, s)| {
                let e = self.earlier_files.get(path);
                Some((
                    path.to_str()?,
                    *s,
                    e.is_some_and(|e| !e.in_delta && e.value == *s),
                ))
            })
            .collect();
        let mut whole = Sections {
            records,
            paths: self.entries(&paths, &self.earlier_paths),
            data: self.entries(&data, &self.earlier_data),
            files: stamps,
        };
        if let Some((binding, base_entries)) = self.base {
            let mut delta = whole.not_in_base();
            let unused = base_entries.saturating_sub(whole.len() - delta.len());
            if (unused + delta.len()) * DELTA_SHARE <= base_entries {
                if delta.len() == 0 && self.delta.is_none() {
                    return Ok(Vec::new());
                }
                let mut bytes = DELTA_HEADER.start();
                binding.put(&mut bytes);
                delta.sort();
                delta.encode(&mut bytes);
                Header::seal(&mut bytes);
                let loaded = self
                    .delta
                    .as_ref()
                    .and_then(|r| self.earlier_bytes.get(r.clone()));
                if loaded == Some(&bytes[..]) {
                    return Ok(Vec::new());
                }
                return Ok(vec![(out.join(DELTA_FILE), bytes)]);
            }
        }
        let mut body = HEADER.start();
        // About the last record's size: growing a 90 MB vector by doubling copies it.
        body.reserve(self.earlier_bytes.len() + self.earlier_bytes.len() / 16);
        whole.sort();
        whole.encode(&mut body);
        Header::seal(&mut body);
        Ok(vec![(out.join(REUSE_FILE), body)])
    }

    /// This build's entries of one kind (`now`; `None` stands for the last build's entry in
    /// `before`), each with whether the record file holds it.
    fn entries<'a>(
        &'a self,
        now: &'a FxHashMap<Key, Option<Vec<u8>>>,
        before: &FxHashMap<Key, Earlier<Range<usize>>>,
    ) -> Vec<(Key, &'a [u8], bool)> {
        let mut entries = Vec::with_capacity(now.len());
        for (key, bytes) in now {
            match (bytes, before.get(key)) {
                (Some(bytes), _) => entries.push((*key, bytes.as_slice(), false)),
                (None, Some(e)) => {
                    if let Some(bytes) = self.earlier_bytes.get(e.value.clone()) {
                        entries.push((*key, bytes, !e.in_delta));
                    }
                }
                (None, None) => {}
            }
        }
        entries
    }
}

/// A record's four kinds of entries, each with whether the record file holds it as it is.
struct Sections<'a> {
    records: Vec<(&'a str, Record, bool)>,
    paths: Vec<(Key, &'a [u8], bool)>,
    data: Vec<(Key, &'a [u8], bool)>,
    files: Vec<(&'a str, FileStamp, bool)>,
}

impl Sections<'_> {
    fn len(&self) -> usize {
        self.records.len() + self.paths.len() + self.data.len() + self.files.len()
    }

    /// Sorts each kind (by name or by key), as a file holds them.
    fn sort(&mut self) {
        // Names by their bytes: the order of `Path`'s own, component by component, costs
        // several times more on 40,000 names.
        self.records.sort_unstable_by(|a, b| a.0.cmp(b.0));
        self.paths.sort_unstable_by_key(|e| e.0);
        self.data.sort_unstable_by_key(|e| e.0);
        self.files.sort_unstable_by(|a, b| a.0.cmp(b.0));
    }

    /// The entries the record file does not hold as they are (a delta file's).
    fn not_in_base(&self) -> Sections<'_> {
        fn new<T: Copy>(entries: &[T], in_base: impl Fn(&T) -> bool) -> Vec<T> {
            entries.iter().filter(|e| !in_base(e)).copied().collect()
        }
        Sections {
            records: new(&self.records, |e| e.2),
            paths: new(&self.paths, |e| e.2),
            data: new(&self.data, |e| e.2),
            files: new(&self.files, |e| e.2),
        }
    }

    /// Appends the four sections, as [`parse`] reads them.
    fn encode(&self, body: &mut Vec<u8>) {
        body.extend_from_slice(&(self.records.len() as u32).to_le_bytes());
        for (name, record, _) in &self.records {
            body.extend_from_slice(&(name.len() as u32).to_le_bytes());
            body.extend_from_slice(name.as_bytes());
            body.extend_from_slice(&record.key.0);
            body.extend_from_slice(&record.bytes);
        }
        // A union's entry is its tag and outline ([`union_entry`]); a datum's is its length
        // and bytes.
        body.extend_from_slice(&(self.paths.len() as u32).to_le_bytes());
        for (key, entry, _) in &self.paths {
            body.extend_from_slice(&key.0);
            body.extend_from_slice(entry);
        }
        body.extend_from_slice(&(self.data.len() as u32).to_le_bytes());
        for (key, bytes, _) in &self.data {
            body.extend_from_slice(&key.0);
            body.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
            body.extend_from_slice(bytes);
        }
        body.extend_from_slice(&(self.files.len() as u32).to_le_bytes());
        for (name, stamp, _) in &self.files {
            body.extend_from_slice(&(name.len() as u32).to_le_bytes());
            body.extend_from_slice(name.as_bytes());
            for v in stamp.meta {
                body.extend_from_slice(&v.to_le_bytes());
            }
            body.extend_from_slice(&stamp.sha256);
        }
    }
}

/// A union's entry: 0 when it is its input unchanged (a glyph without overlaps), else 1
/// and the outline.
fn union_entry(path: &BezPath, input: &BezPath) -> Vec<u8> {
    if path == input {
        return vec![0];
    }
    let mut entry = Vec::with_capacity(5 + path.elements().len() * 40);
    entry.push(1);
    put_path(&mut entry, path);
    entry
}

/// The union an entry holds (`input` for 0); `None` when it does not decode whole.
fn union_from_entry(entry: &[u8], input: &BezPath) -> Option<BezPath> {
    let mut r = Reader::new(entry);
    let union = match r.u8().ok()? {
        0 => input.clone(),
        1 => r.path().ok()?,
        _ => return None,
    };
    r.is_empty().then_some(union)
}

/// What a record file (or its delta file) holds; the ranges index the buffer it was read
/// into.
struct Parsed {
    records: FxHashMap<PathBuf, Earlier<Record>>,
    paths: FxHashMap<Key, Earlier<Range<usize>>>,
    data: FxHashMap<Key, Earlier<Range<usize>>>,
    files: FxHashMap<PathBuf, Earlier<FileStamp>>,
}

impl Parsed {
    fn entries(&self) -> usize {
        self.records.len() + self.paths.len() + self.data.len() + self.files.len()
    }

    /// Adds a delta file's entries, which replace those of the same name or key.
    fn merge(&mut self, delta: Parsed) {
        self.records.extend(delta.records);
        self.paths.extend(delta.paths);
        self.data.extend(delta.data);
        self.files.extend(delta.files);
    }
}

/// The delta file at `all[start..]`, when it is whole and bound to the record file `base`.
fn parse_delta(all: &[u8], start: usize, base: Binding) -> Result<Parsed, &'static str> {
    let mut r = DELTA_HEADER.open(&all[start..])?;
    if Binding::read(&mut r)? != base {
        return Err("the delta file belongs to another record file");
    }
    parse(&mut r, all, true)
}

/// The four sections at `r`, which reads from `all`, to its end, or what is wrong with
/// them. Unions are stepped over, not decoded ([`union_range`]).
fn parse(r: &mut Reader<'_>, all: &[u8], in_delta: bool) -> Result<Parsed, &'static str> {
    let offset = |part: &[u8]| part.as_ptr() as usize - all.as_ptr() as usize;
    let count = r.u32()?;
    let count = r.count(u64::from(count), 4 + 32 + 32)?;
    let mut records = FxHashMap::with_capacity_and_hasher(count, Default::default());
    for _ in 0..count {
        let path = relative_path(r)?;
        let key = Key(r.array()?);
        let bytes = r.array()?;
        if records
            .insert(path, Earlier::new(Record { key, bytes }, in_delta))
            .is_some()
        {
            return Err("a path is recorded twice");
        }
    }
    let count = r.u32()?;
    let count = r.count(u64::from(count), 32 + 1)?;
    let mut paths = FxHashMap::with_capacity_and_hasher(count, Default::default());
    for _ in 0..count {
        let key = Key(r.array()?);
        let entry = union_range(r, offset)?;
        if paths.insert(key, Earlier::new(entry, in_delta)).is_some() {
            return Err("an outline is recorded twice");
        }
    }
    let count = r.u32()?;
    let count = r.count(u64::from(count), 32 + 4)?;
    let mut data = FxHashMap::with_capacity_and_hasher(count, Default::default());
    for _ in 0..count {
        let key = Key(r.array()?);
        let len = r.u32()? as usize;
        let start = offset(r.take(len)?);
        if data
            .insert(key, Earlier::new(start..start + len, in_delta))
            .is_some()
        {
            return Err("glyph data is recorded twice");
        }
    }
    let count = r.u32()?;
    let count = r.count(u64::from(count), 4 + 48 + 32)?;
    let mut files = FxHashMap::with_capacity_and_hasher(count, Default::default());
    for _ in 0..count {
        let path = relative_path(r)?;
        let mut meta = [0; 6];
        for v in &mut meta {
            *v = r.u64()?;
        }
        let sha256 = r.array()?;
        if files
            .insert(path, Earlier::new(FileStamp { meta, sha256 }, in_delta))
            .is_some()
        {
            return Err("a file is recorded twice");
        }
    }
    if !r.is_empty() {
        return Err("bytes follow the last record");
    }
    Ok(Parsed {
        records,
        paths,
        data,
        files,
    })
}

/// Steps over a union's entry ([`union_entry`]): its tag, and unless 0 the outline's
/// elements stepped over ([`Reader::skip_path`]; decoded only when a build uses it:
/// [`union_from_entry`]). Its range, from `offset` of the parts read.
fn union_range(
    r: &mut Reader<'_>,
    offset: impl Fn(&[u8]) -> usize,
) -> Result<Range<usize>, &'static str> {
    const MALFORMED: &str = "an outline record is malformed";
    let tag = r.take(1)?;
    let start = offset(tag);
    match tag[0] {
        0 => return Ok(start..start + 1),
        1 => {}
        _ => return Err(MALFORMED),
    }
    r.skip_path(|_, _, _| true, MALFORMED)?;
    // The end: where the next read starts.
    let end = offset(r.take(0)?);
    Ok(start..end)
}

/// A path relative to OUT (its length, then UTF-8): plain names only, never leaving OUT.
fn relative_path(r: &mut Reader<'_>) -> Result<PathBuf, &'static str> {
    let len = r.u32()? as usize;
    let name = std::str::from_utf8(r.take(len)?).map_err(|_| "a path is not UTF-8")?;
    let path = PathBuf::from(name);
    if name.is_empty() || !path.components().all(|c| matches!(c, Component::Normal(_))) {
        return Err("a path leaves the output folder");
    }
    Ok(path)
}

/// Each glyph's outline of a font, hashed once ([`KeyBuilder::path`]), or another key that
/// determines it (the same key never comes with two outlines). The keys of the
/// outputs made from the font (the union, each glyph's SVG and `.glif`, the sheet pages,
/// the proof) take it instead of hashing the path again each: a CJK font's outlines are
/// about 130 MB of numbers, and five keys read them.
#[derive(Clone, Debug, Default)]
pub struct OutlineKeys(Vec<Key>);

impl OutlineKeys {
    /// The keys of `font`'s glyphs, hashed on every core; none when `reuse` is off (then
    /// [`OutlineKeys::get`] hashes a path when asked).
    pub fn new(font: &OutlinedFont, reuse: &Reuse) -> Self {
        use rayon::prelude::*;
        if !reuse.is_on() {
            return OutlineKeys::default();
        }
        OutlineKeys(
            font.glyphs
                .par_iter()
                .map(|g| outline_key(&g.path))
                .collect(),
        )
    }

    /// Keys made elsewhere, one per glyph, each determining its glyph's outline (e.g. a
    /// union's key, [`crate::overlap`]); none: every key hashed when asked.
    pub(crate) fn from_keys(keys: Vec<Key>) -> Self {
        OutlineKeys(keys)
    }

    /// The key of `path`, the outline of the glyph at `index` of the font these keys were
    /// made for; hashed now when they were not made.
    pub fn get(&self, index: usize, path: &BezPath) -> Key {
        self.key(index).unwrap_or_else(|| outline_key(path))
    }

    /// The key of the outline of the glyph at `index`, when these keys were made.
    pub fn key(&self, index: usize) -> Option<Key> {
        self.0.get(index).copied()
    }
}

/// The key of one outline (every element's kind and the bits of its points).
pub fn outline_key(path: &BezPath) -> Key {
    KeyBuilder::new("outline").path(path).finish()
}

/// The key of one glyph as drawn: name, code points, advance and outline (`outline`, its
/// [`outline_key`]), and with `contours` its X-spline contours too (the sheet's overlay
/// draws them).
pub fn glyph_key(glyph: &OutlinedGlyph, outline: &Key, contours: bool) -> Key {
    let mut k = KeyBuilder::new("glyph");
    k.str(&glyph.name).f64(glyph.advance).key(outline);
    k.u64(glyph.unicodes.len() as u64);
    for &c in &glyph.unicodes {
        k.u64(u64::from(c));
    }
    if contours {
        // Debug prints every number so that it reads back exactly: a lossless key.
        k.str(&format!("{:?}", glyph.contours));
    }
    k.finish()
}

/// The key of everything a drawing of `font` through its TTF `ttf` can depend on: the
/// TTF's bytes (shaping, metrics), the font's info, and every glyph as drawn
/// ([`glyph_key`], hashed in parallel; `outlines` are the font's [`OutlineKeys`]).
pub fn font_key(font: &OutlinedFont, ttf: &[u8], outlines: &OutlineKeys) -> Key {
    use rayon::prelude::*;
    let glyphs: Vec<Key> = font
        .glyphs
        .par_iter()
        .enumerate()
        .map(|(i, g)| glyph_key(g, &outlines.get(i, &g.path), false))
        .collect();
    let mut k = KeyBuilder::new("font");
    k.bytes(ttf)
        .str(&format!("{:?}", font.info))
        .f64(font.tolerance)
        .u64(glyphs.len() as u64);
    for g in &glyphs {
        k.key(g);
    }
    k.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Waits until the files at `paths` have settled ([`crate::write::settled_meta`]).
    fn settle(paths: &[&Path]) {
        for _ in 0..100 {
            let settled = paths.iter().all(|p| {
                fs::metadata(p)
                    .ok()
                    .as_ref()
                    .and_then(crate::write::settled_meta)
                    .is_some()
            });
            if settled {
                return;
            }
            std::thread::sleep(crate::write::SETTLED);
        }
        panic!("the files did not settle in 5 s");
    }

    #[test]
    #[cfg(unix)]
    fn a_settled_program_is_known_by_its_stamp_so_a_new_copy_is_another_program() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let (a, b) = (dir.path().join("a"), dir.path().join("b"));
        fs::write(&a, b"program").expect("write a");
        fs::write(&b, b"program").expect("write b");
        settle(&[&a, &b]);
        let id_a = file_identity(&a).expect("a is read");
        // The same file again: the same identity.
        assert_eq!(file_identity(&a), Some(id_a));
        // The same bytes in another file: another identity (its inode and times differ).
        assert_ne!(file_identity(&b), Some(id_a));
        // The file written again with the same bytes: another identity (its times moved).
        fs::write(&a, b"program").expect("rewrite a");
        settle(&[&a]);
        assert_ne!(file_identity(&a), Some(id_a));
        // A file that cannot be read has none.
        assert_eq!(file_identity(&dir.path().join("missing")), None);
    }
}
