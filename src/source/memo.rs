//! Glyph files as the last build loaded them, so that a rebuild neither parses nor checks
//! again a glyph file that did not change: a CJK font's 20,902 files cost a quarter of an
//! edited build's CPU time in TOML parsing and the area checks of every contour.
//!
//! Each entry is keyed by a SHA-256 of the program's identity, the file's name and its
//! text ([`crate::reuse::KeyBuilder`]): the loader reads nothing else of a glyph file, and
//! the folder's own path is left out, so that `build src` and `build /abs/path/src` share
//! the memo. It holds what [`super::glyph::load_glyph`] made of
//! it: the glyph and where its parts were written. Only files that loaded complete and
//! without any diagnostic are kept, so a memo hit gives what the loader would, and there is
//! no message to replay. The checks across files (names, components, anchors, limits) still
//! run on every build.
//!
//! An entry also holds the file's stamp when it was read: a SHA-256 of the program's
//! identity, the file's name and its metadata ([`crate::write::settled_meta`]: length,
//! inode, modification and change times to the nanosecond, taken before the read, and only
//! once the file has settled). A file whose metadata give the same stamp is taken without
//! being read at all: the change time cannot be set back, so its text is the one of the
//! entry. (Reading and hashing a CJK font's 20,902 files was a tenth of an edited build.)
//! A file whose text is that of an entry but whose stamp is not (touched, checked out
//! again) is taken by its text and its entry saved again with the new stamp.
//!
//! The file ([`MEMO_FILE`] in OUT) is not trusted: it is read whole and checked before any
//! entry is used (magic, version, CRC-32, every count against the bytes that remain, every
//! number finite, every contour a valid X-spline, no duplicate key, no trailing byte), or
//! ignored. It holds the entries the last build that wrote it whole used or made, sorted by
//! key, and is not rewritten when a build used every entry and made none. A build that
//! parsed few files writes only a delta file beside it ([`DELTA_FILE`]: the same layout with
//! its own magic, bound to the memo file by its length and checksum, holding the entries
//! made and those of the last delta used), as the fit cache does, until the delta and the
//! memo's unused entries pass 1/8 of its entries; a CJK font's memo is 77 MB. Outputs are
//! the same with and without it. Limit: as with the fit cache, a forged file with a valid
//! checksum is trusted.

use std::fs;
use std::io;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use rustc_hash::FxHashMap;

use super::glyph::GlyphSpans;
use crate::model::{Anchor, Component, Contour, Glyph};
use crate::record::{Binding, Header, Reader};
use crate::reuse::KeyBuilder;
use crate::xspline::ControlPoint;

/// Name of the memo file in the output folder.
pub const MEMO_FILE: &str = ".xglyph-sources";

/// Name of the delta file beside it ([`SourceMemo::files_to_save`]).
pub const DELTA_FILE: &str = ".xglyph-sources-delta";

/// The delta may hold at most 1 / this of the memo file's entries, counting with it the
/// memo's unused entries; beyond, the memo is written whole.
const DELTA_SHARE: usize = 8;

const HEADER: Header = Header {
    magic: b"XGLYPHSM",
    version: 3,
    not_ours: "it is not an xglyph source memo",
};

const DELTA_HEADER: Header = Header {
    magic: b"XGLYPHSD",
    version: 3,
    not_ours: "it is not an xglyph source memo delta",
};

/// An entry of the last build's file.
struct Slot {
    /// Its bytes in [`SourceMemo::bytes`] (kept as they are for the next file): the stamp,
    /// then the glyph.
    range: Range<usize>,
    /// The stamp of the file it was made from ([`SourceMemo::stamp`]; zeros: none).
    stamp: [u8; 32],
    /// The decoded glyph until this build takes it or [`SourceMemo::release_unused`] drops it.
    glyph: Mutex<Option<(Glyph, GlyphSpans)>>,
    /// Whether this build took it.
    used: std::sync::atomic::AtomicBool,
    /// Whether it came from the delta file (its bytes are in [`SourceMemo::delta_bytes`]).
    in_delta: bool,
}

impl Slot {
    fn used(&self) -> bool {
        self.used.load(Ordering::Relaxed)
    }
}

/// The glyph files the last build loaded, and those this build loads.
#[derive(Default)]
pub struct SourceMemo {
    /// Off: nothing looked up, nothing kept.
    on: bool,
    bytes: Vec<u8>,
    delta_bytes: Vec<u8>,
    /// The memo file's binding (length, checksum) and entry count, when one was loaded.
    base: Option<(Binding, usize)>,
    /// Entries the delta file added.
    delta_entries: usize,
    earlier: FxHashMap<[u8; 32], Slot>,
    /// The key of the entry with each stamp.
    stamped: FxHashMap<[u8; 32], [u8; 32]>,
    made: Mutex<Vec<([u8; 32], Vec<u8>)>>,
    taken: AtomicUsize,
    /// How many of them by their stamp, unread.
    by_stamp: AtomicUsize,
}

impl std::fmt::Debug for SourceMemo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "SourceMemo({} entries)", self.earlier.len())
    }
}

impl SourceMemo {
    /// No memo: every file is parsed.
    pub fn off() -> Self {
        SourceMemo::default()
    }

    /// The memo at `path`, and why it was ignored if it was (a missing file is no reason).
    pub fn load(path: &Path) -> (Self, Option<String>) {
        if !crate::reuse::program_is_known() {
            let why = "the program's own file cannot be read";
            return (SourceMemo::off(), Some(why.into()));
        }
        let mut memo = SourceMemo {
            on: true,
            ..SourceMemo::default()
        };
        let bytes = match fs::read(path) {
            Ok(bytes) => bytes,
            Err(e) if e.kind() == io::ErrorKind::NotFound => return (memo, None),
            Err(e) => return (memo, Some(crate::write::reason(&e))),
        };
        match decode(&HEADER, &bytes, None, false) {
            Ok(earlier) => {
                let binding = Binding::of(&bytes);
                memo.base = Some((binding, earlier.len()));
                memo.earlier = earlier;
                memo.bytes = bytes;
                memo.add_delta(path, binding);
                memo.stamped = memo
                    .earlier
                    .iter()
                    .filter(|(_, slot)| slot.stamp != NO_STAMP)
                    .map(|(key, slot)| (slot.stamp, *key))
                    .collect();
                (memo, None)
            }
            Err(why) => (memo, Some(why.to_string())),
        }
    }

    /// Adds the entries of the delta file beside `path` when it is whole and bound to the
    /// memo file (`binding`); otherwise it is ignored (those files are parsed again). The
    /// delta is newer: its entry of a key replaces the memo file's (a new stamp).
    fn add_delta(&mut self, path: &Path, binding: Binding) {
        let Ok(bytes) = fs::read(delta_path(path)) else {
            return;
        };
        let Ok(entries) = decode(&DELTA_HEADER, &bytes, Some(binding), true) else {
            return;
        };
        self.delta_entries = entries.len();
        self.earlier.extend(entries);
        self.delta_bytes = bytes;
    }

    /// Whether it looks files up and keeps them.
    pub(super) fn is_on(&self) -> bool {
        self.on
    }

    /// The stamp of the glyph file `path` whose metadata are `meta`
    /// ([`crate::write::settled_meta`]), taken before it is read.
    pub(super) fn stamp(path: &Path, meta: &[u64; 6]) -> [u8; 32] {
        let name = path.file_name().unwrap_or(path.as_os_str());
        let mut k = KeyBuilder::new("glyph file stamp");
        k.bytes(name.as_encoded_bytes());
        for &m in meta {
            k.u64(m);
        }
        k.finish().to_bytes()
    }

    /// What the last build loaded from the file of `stamp`, if it did (the file is then
    /// the one it read, unchanged).
    pub(super) fn take_stamped(&self, stamp: &[u8; 32]) -> Option<(Glyph, GlyphSpans)> {
        let key = self.stamped.get(stamp)?;
        let slot = self.earlier.get(key).filter(|slot| slot.stamp == *stamp)?;
        let taken = self.take_slot(slot)?;
        self.by_stamp.fetch_add(1, Ordering::Relaxed);
        Some(taken)
    }

    /// The key of the glyph file `path` holding `text`: its name (the glyph's name comes
    /// from it) and text.
    pub(super) fn key(path: &Path, text: &str) -> [u8; 32] {
        let name = path.file_name().unwrap_or(path.as_os_str());
        let mut k = KeyBuilder::new("glyph source");
        k.bytes(name.as_encoded_bytes()).str(text);
        k.finish().to_bytes()
    }

    /// What the last build loaded from the file of `key`, if it did; the file's stamp
    /// now is `stamp` (`None`: not settled). An entry of another stamp is saved again
    /// with this one.
    pub(super) fn take(
        &self,
        key: &[u8; 32],
        stamp: Option<[u8; 32]>,
    ) -> Option<(Glyph, GlyphSpans)> {
        let slot = self.earlier.get(key)?;
        let Some(stamp) = stamp.filter(|s| *s != slot.stamp) else {
            return self.take_slot(slot);
        };
        let taken = slot.glyph.lock().ok()?.take()?;
        self.taken.fetch_add(1, Ordering::Relaxed);
        // Left unused, so that only the restamped copy is saved.
        let from = if slot.in_delta {
            &self.delta_bytes
        } else {
            &self.bytes
        };
        let mut body = stamp.to_vec();
        body.extend_from_slice(&from[slot.range.start + STAMP_LEN..slot.range.end]);
        if let Ok(mut made) = self.made.lock() {
            made.push((*key, body));
        }
        Some(taken)
    }

    /// Takes `slot`'s glyph (once) and marks it used.
    fn take_slot(&self, slot: &Slot) -> Option<(Glyph, GlyphSpans)> {
        let taken = slot.glyph.lock().ok()?.take();
        if taken.is_some() {
            slot.used.store(true, Ordering::Relaxed);
            self.taken.fetch_add(1, Ordering::Relaxed);
        }
        taken
    }

    /// Drops the decoded glyphs this build did not take, once the sources are loaded: after
    /// a new `xglyph` binary no entry applies, and a CJK font's 20,902 decoded glyphs (some
    /// 250 MB) would otherwise stay while every output is made again. What is saved is
    /// unchanged: only taken entries' bytes are written.
    pub fn release_unused(&mut self) {
        for slot in self.earlier.values_mut() {
            if !slot.used() {
                if let Ok(glyph) = slot.glyph.get_mut() {
                    *glyph = None;
                }
            }
        }
        if self.taken() == 0 {
            // No entry's bytes will be written again.
            self.bytes = Vec::new();
            self.delta_bytes = Vec::new();
        }
    }

    /// How many glyph files came from the memo.
    pub fn taken(&self) -> usize {
        self.taken.load(Ordering::Relaxed)
    }

    /// How many of them came by their stamp, without being read.
    pub fn taken_unread(&self) -> usize {
        self.by_stamp.load(Ordering::Relaxed)
    }

    /// Keeps what the loader made of the file of `key` and `stamp` (complete, no
    /// diagnostic).
    pub(super) fn keep(
        &self,
        key: [u8; 32],
        stamp: Option<[u8; 32]>,
        glyph: &Glyph,
        spans: &GlyphSpans,
    ) {
        if !self.on {
            return;
        }
        // Sized once: 32 bytes a point (three reals and an offset), a little for the rest.
        let points: usize = glyph.contours.iter().map(|c| c.points().len()).sum();
        let parts = glyph.unicodes.len() + glyph.components.len() + glyph.anchors.len();
        let mut body = Vec::with_capacity(160 + glyph.name.len() + 32 * (points + parts));
        body.extend_from_slice(&stamp.unwrap_or(NO_STAMP));
        put_entry(&mut body, glyph, spans);
        if let Ok(mut made) = self.made.lock() {
            made.push((key, body));
        }
    }

    /// Writes the entries this build used or made to `path`, or only its delta file
    /// ([`SourceMemo::files_to_save`]), atomically; nothing when they are those of the
    /// files it loaded.
    pub fn save(&self, path: &Path) -> io::Result<()> {
        for (path, bytes) in self.files_to_save(path) {
            crate::write::write_atomic(&path, &bytes)?;
        }
        Ok(())
    }

    /// What [`SourceMemo::save`] writes, the memo having been loaded from `path`: nothing
    /// (off, or every entry used and none made); only the delta file when the memo file's
    /// unused entries, the delta's used ones and the new ones together are at most
    /// one eighth of the memo file's entries; else the memo file whole
    /// ([`SourceMemo::bytes_to_save`]).
    pub fn files_to_save(&self, path: &Path) -> Vec<(PathBuf, Vec<u8>)> {
        if !self.on {
            return Vec::new();
        }
        if let Some((binding, base_entries)) = self.base {
            let Ok(made) = self.made.lock() else {
                return Vec::new();
            };
            let (mut base_unused, mut delta_used) = (0, 0);
            for slot in self.earlier.values() {
                let used = slot.used();
                base_unused += usize::from(!slot.in_delta && !used);
                delta_used += usize::from(slot.in_delta && used);
            }
            if (base_unused + delta_used + made.len()) * DELTA_SHARE <= base_entries {
                if made.is_empty() && delta_used == self.delta_entries {
                    return Vec::new();
                }
                let mut entries: Vec<([u8; 32], &[u8])> =
                    made.iter().map(|(k, b)| (*k, &b[..])).collect();
                for (key, slot) in &self.earlier {
                    if slot.in_delta && slot.used() {
                        entries.push((*key, &self.delta_bytes[slot.range.clone()]));
                    }
                }
                let mut out = DELTA_HEADER.start();
                binding.put(&mut out);
                put_entries(&mut out, entries);
                return vec![(delta_path(path), out)];
            }
        }
        self.bytes_to_save()
            .map(|bytes| vec![(path.to_path_buf(), bytes)])
            .unwrap_or_default()
    }

    /// The bytes [`SourceMemo::save`] writes; `None` when there is nothing to write (the
    /// memo is off, or this build used every entry of the file and made none).
    pub fn bytes_to_save(&self) -> Option<Vec<u8>> {
        if !self.on {
            return None;
        }
        let made = self.made.lock().ok()?;
        let mut entries: Vec<([u8; 32], &[u8])> = made.iter().map(|(k, b)| (*k, &b[..])).collect();
        let mut all_used = true;
        for (key, slot) in &self.earlier {
            let used = slot.used();
            if used {
                let from = if slot.in_delta {
                    &self.delta_bytes
                } else {
                    &self.bytes
                };
                entries.push((*key, &from[slot.range.clone()]));
            }
            all_used &= used;
        }
        if made.is_empty() && all_used && self.delta_entries == 0 {
            return None;
        }
        let mut out = HEADER.start();
        put_entries(&mut out, entries);
        Some(out)
    }
}

/// An entry's stamp when its file had none (not settled when read).
const NO_STAMP: [u8; 32] = [0; 32];

/// The length of an entry's stamp.
const STAMP_LEN: usize = 32;

/// The delta file beside the memo file at `path`.
pub fn delta_path(path: &Path) -> PathBuf {
    path.with_file_name(DELTA_FILE)
}

/// Appends the entries sorted by key, and the checksum. Two files of one name and text (a
/// glyph the same in two masters) make one key: it is written once.
fn put_entries(out: &mut Vec<u8>, mut entries: Vec<([u8; 32], &[u8])>) {
    entries.sort_by_key(|(key, _)| *key);
    entries.dedup_by_key(|(key, _)| *key);
    out.extend_from_slice(&(entries.len() as u32).to_le_bytes());
    for (key, body) in entries {
        out.extend_from_slice(&key);
        out.extend_from_slice(&(body.len() as u32).to_le_bytes());
        out.extend_from_slice(body);
    }
    Header::seal(out);
}

/// Every entry of a memo file (or, with `bound`, of a delta file bound to the memo file of
/// that length and checksum), decoded and checked, or what is wrong with it.
fn decode(
    header: &Header,
    bytes: &[u8],
    bound: Option<Binding>,
    in_delta: bool,
) -> Result<FxHashMap<[u8; 32], Slot>, &'static str> {
    let mut r = header.open(bytes)?;
    if let Some(binding) = bound {
        if Binding::read(&mut r)? != binding {
            return Err("it belongs to another memo file");
        }
    }
    let count = r.u32()?;
    let count = r.count(u64::from(count), 36 + STAMP_LEN)?;
    let mut earlier = FxHashMap::with_capacity_and_hasher(count, Default::default());
    for _ in 0..count {
        let key = r.array()?;
        let len = r.u32()? as usize;
        let body = r.take(len)?;
        // Where the body lies in `bytes` (it is a part of it).
        let start = body.as_ptr() as usize - bytes.as_ptr() as usize;
        let mut e = Reader::new(body);
        let stamp: [u8; STAMP_LEN] = e.array()?;
        let glyph = read_entry(&mut e)?;
        if !e.is_empty() {
            return Err("an entry has bytes after its end");
        }
        let slot = Slot {
            range: start..start + len,
            stamp,
            glyph: Mutex::new(Some(glyph)),
            used: std::sync::atomic::AtomicBool::new(false),
            in_delta,
        };
        if earlier.insert(key, slot).is_some() {
            return Err("a file is recorded twice");
        }
    }
    if !r.is_empty() {
        return Err("bytes follow the last entry");
    }
    Ok(earlier)
}

fn put_u32(out: &mut Vec<u8>, v: usize) {
    out.extend_from_slice(&(v as u32).to_le_bytes());
}

fn put_f64(out: &mut Vec<u8>, v: f64) {
    out.extend_from_slice(&v.to_bits().to_le_bytes());
}

fn put_str(out: &mut Vec<u8>, s: &str) {
    put_u32(out, s.len());
    out.extend_from_slice(s.as_bytes());
}

fn put_offsets(out: &mut Vec<u8>, offsets: &[usize]) {
    put_u32(out, offsets.len());
    for &o in offsets {
        out.extend_from_slice(&(o as u64).to_le_bytes());
    }
}

fn put_entry(out: &mut Vec<u8>, g: &Glyph, spans: &GlyphSpans) {
    put_str(out, &g.name);
    put_u32(out, g.unicodes.len());
    for &c in &g.unicodes {
        put_u32(out, c as usize);
    }
    put_f64(out, g.advance);
    put_u32(out, g.contours.len());
    for c in &g.contours {
        put_u32(out, c.points().len());
        for p in c.points() {
            put_f64(out, p.pos.x);
            put_f64(out, p.pos.y);
            put_f64(out, p.s);
        }
    }
    put_u32(out, g.components.len());
    for c in &g.components {
        put_str(out, &c.base);
        put_f64(out, c.offset.0);
        put_f64(out, c.offset.1);
    }
    put_u32(out, g.anchors.len());
    for a in &g.anchors {
        put_str(out, &a.name);
        put_f64(out, a.position.0);
        put_f64(out, a.position.1);
    }
    out.push(u8::from(g.outline_mark));
    put_offsets(out, &[spans.start, spans.name, spans.mark]);
    put_offsets(out, &spans.unicodes);
    put_offsets(out, &spans.bases);
    put_u32(out, spans.offsets.len());
    for o in &spans.offsets {
        match o {
            Some(o) => {
                out.push(1);
                out.extend_from_slice(&(*o as u64).to_le_bytes());
            }
            None => out.push(0),
        }
    }
    put_offsets(out, &spans.anchors);
    put_u32(out, spans.points.len());
    for p in &spans.points {
        put_offsets(out, p);
    }
}

fn read_str(r: &mut Reader<'_>) -> Result<String, &'static str> {
    let len = r.u32()? as usize;
    let bytes = r.take(len)?;
    String::from_utf8(bytes.to_vec()).map_err(|_| "a name is not UTF-8")
}

/// A count of items of at least `min_size` bytes each.
fn read_count(r: &mut Reader<'_>, min_size: usize) -> Result<usize, &'static str> {
    let n = r.u32()?;
    r.count(u64::from(n), min_size)
}

fn read_offsets(r: &mut Reader<'_>) -> Result<Vec<usize>, &'static str> {
    let n = read_count(r, 8)?;
    // Pushed into a vector of the right size: collecting through `Result` would grow it
    // step by step (its size hint is lost).
    let mut offsets = Vec::with_capacity(n);
    for _ in 0..n {
        offsets.push(usize::try_from(r.u64()?).map_err(|_| "an offset is too large")?);
    }
    Ok(offsets)
}

fn read_entry(r: &mut Reader<'_>) -> Result<(Glyph, GlyphSpans), &'static str> {
    let name = read_str(r)?;
    let n = read_count(r, 4)?;
    let unicodes = (0..n)
        .map(|_| char::from_u32(r.u32()?).ok_or("a code point is not a character"))
        .collect::<Result<Vec<char>, _>>()?;
    let advance = r.f64()?;
    let n = read_count(r, 4)?;
    let mut contours = Vec::with_capacity(n);
    for _ in 0..n {
        let count = read_count(r, 24)?;
        let mut points = Vec::with_capacity(count);
        for _ in 0..count {
            points.push(ControlPoint::new(r.f64()?, r.f64()?, r.f64()?));
        }
        contours.push(Contour::new(points).map_err(|_| "a contour is not a valid X-spline")?);
    }
    let n = read_count(r, 20)?;
    let mut components = Vec::with_capacity(n);
    for _ in 0..n {
        let base = read_str(r)?;
        let offset = (r.f64()?, r.f64()?);
        components.push(Component { base, offset });
    }
    let n = read_count(r, 20)?;
    let mut anchors = Vec::with_capacity(n);
    for _ in 0..n {
        let name = read_str(r)?;
        let position = (r.f64()?, r.f64()?);
        anchors.push(Anchor { name, position });
    }
    let outline_mark = match r.u8()? {
        0 => false,
        1 => true,
        _ => return Err("an entry's mark is malformed"),
    };
    let head = read_offsets(r)?;
    let [start, name_at, mark_at] = head[..] else {
        return Err("an entry's spans are malformed");
    };
    let span_unicodes = read_offsets(r)?;
    let bases = read_offsets(r)?;
    let n = read_count(r, 1)?;
    let mut offsets = Vec::with_capacity(n);
    for _ in 0..n {
        offsets.push(match r.u8()? {
            0 => None,
            1 => Some(usize::try_from(r.u64()?).map_err(|_| "an offset is too large")?),
            _ => return Err("an entry's spans are malformed"),
        });
    }
    let span_anchors = read_offsets(r)?;
    let n = read_count(r, 4)?;
    let mut points = Vec::with_capacity(n);
    for _ in 0..n {
        points.push(read_offsets(r)?);
    }
    let glyph = Glyph {
        name,
        unicodes,
        advance,
        contours,
        components,
        anchors,
        outline_mark,
    };
    let spans = GlyphSpans {
        start,
        name: name_at,
        mark: mark_at,
        unicodes: span_unicodes,
        bases,
        offsets,
        anchors: span_anchors,
        points,
    };
    // The spans go with the glyph's parts, one each.
    let counts_match = spans.unicodes.len() == glyph.unicodes.len()
        && spans.bases.len() == glyph.components.len()
        && spans.offsets.len() == glyph.components.len()
        && spans.anchors.len() == glyph.anchors.len()
        && spans.points.len() == glyph.contours.len()
        && spans
            .points
            .iter()
            .zip(&glyph.contours)
            .all(|(s, c)| s.len() == c.points().len());
    if !counts_match {
        return Err("an entry's spans do not match its glyph");
    }
    Ok((glyph, spans))
}
