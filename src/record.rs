//! The binary encoding of what a build keeps for the next one: the fit cache
//! ([`crate::cache`]) and the record of outputs ([`crate::reuse`]). Numbers are
//! little-endian, reals are stored as their bits, and a path is its element count followed by
//! tagged elements. The bytes on disk are untrusted, so [`Reader`] checks every read against
//! what remains and refuses non-finite numbers: a damaged file is refused, never trusted.
//!
//! Every such file is framed the same way ([`Header`]): an 8-byte magic, a format version
//! (u32), the body, and a CRC-32 of everything before it. [`Header::open`] is the one
//! place that checks the frame.

use std::fs;
use std::io::{self, Read};
use std::path::Path;

use kurbo::{BezPath, PathEl, Point};

pub(crate) const TAG_MOVE: u8 = 0;
pub(crate) const TAG_LINE: u8 = 1;
pub(crate) const TAG_QUAD: u8 = 2;
pub(crate) const TAG_CUBIC: u8 = 3;
pub(crate) const TAG_CLOSE: u8 = 4;

/// The frame of one kind of file: its magic, its layout's version, and what it is called
/// in the message that refuses another file.
pub(crate) struct Header {
    pub(crate) magic: &'static [u8; 8],
    pub(crate) version: u32,
    /// "it is not …", e.g. "it is not an xglyph cache file".
    pub(crate) not_ours: &'static str,
}

impl Header {
    /// A new file's bytes so far: the magic and the version (the body follows, then
    /// [`Header::seal`]).
    pub(crate) fn start(&self) -> Vec<u8> {
        let mut out = Vec::new();
        out.extend_from_slice(self.magic);
        out.extend_from_slice(&self.version.to_le_bytes());
        out
    }

    /// Appends the CRC-32 of everything written so far.
    pub(crate) fn seal(out: &mut Vec<u8>) {
        let crc = crc32fast::hash(out);
        out.extend_from_slice(&crc.to_le_bytes());
    }

    /// The body of `bytes` (after the version, before the checksum), once the magic, the
    /// checksum and the version are checked, in that order.
    pub(crate) fn open<'a>(&self, bytes: &'a [u8]) -> Result<Reader<'a>, &'static str> {
        let (body, crc) = bytes
            .split_last_chunk::<4>()
            .ok_or("the file is truncated")?;
        if !body.starts_with(self.magic) {
            return Err(self.not_ours);
        }
        if crc32fast::hash(body) != u32::from_le_bytes(*crc) {
            return Err("its checksum does not match (the file is damaged or truncated)");
        }
        let mut r = Reader::new(&body[self.magic.len()..]);
        if r.u32()? != self.version {
            return Err("it was written by another version of xglyph");
        }
        Ok(r)
    }
}

/// What binds a delta file to the file it adds to: that file's length and checksum (its
/// last four bytes). A delta file starts its body with it, and is ignored unless it is the
/// binding of the file beside it: the one a whole rewrite leaves behind no longer is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Binding {
    len: u64,
    crc: u32,
}

impl Binding {
    /// The binding of a framed file's `bytes`.
    pub(crate) fn of(bytes: &[u8]) -> Binding {
        let crc = bytes
            .split_last_chunk::<4>()
            .map_or(0, |(_, crc)| u32::from_le_bytes(*crc));
        Binding {
            len: bytes.len() as u64,
            crc,
        }
    }

    /// Appends it.
    pub(crate) fn put(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.len.to_le_bytes());
        out.extend_from_slice(&self.crc.to_le_bytes());
    }

    /// Reads one, as [`Binding::put`] wrote it.
    pub(crate) fn read(r: &mut Reader<'_>) -> Result<Binding, &'static str> {
        Ok(Binding {
            len: r.u64()?,
            crc: r.u32()?,
        })
    }
}

/// The bytes of the file at `path`, then those of its delta file at `delta` when that one
/// can be read, in one buffer sized once (growing it would copy a CJK font's 100 MB), and
/// the first file's length.
pub(crate) fn read_with_delta(path: &Path, delta: &Path) -> io::Result<(Vec<u8>, usize)> {
    let mut file = fs::File::open(path)?;
    let size = |f: &fs::File| f.metadata().map_or(0, |m| m.len() as usize);
    let delta = fs::File::open(delta).ok();
    let mut bytes = Vec::with_capacity(size(&file).saturating_add(delta.as_ref().map_or(0, size)));
    file.read_to_end(&mut bytes)?;
    let len = bytes.len();
    if let Some(mut delta) = delta {
        if delta.read_to_end(&mut bytes).is_err() {
            bytes.truncate(len);
        }
    }
    Ok((bytes, len))
}

/// Appends `path`: its element count (u32), then per element a tag and its points.
pub(crate) fn put_path(out: &mut Vec<u8>, path: &BezPath) {
    let elements = path.elements();
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
            PathEl::QuadTo(a, b) => put(TAG_QUAD, &[a, b]),
            PathEl::CurveTo(a, b, c) => put(TAG_CUBIC, &[a, b, c]),
            PathEl::ClosePath => put(TAG_CLOSE, &[]),
        }
    }
}

/// A cursor over untrusted bytes: every read is bounds-checked.
pub(crate) struct Reader<'a> {
    bytes: &'a [u8],
}

impl<'a> Reader<'a> {
    pub(crate) fn new(bytes: &'a [u8]) -> Self {
        Reader { bytes }
    }

    /// Whether every byte has been read.
    pub(crate) fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }

    /// How many bytes are left to read.
    pub(crate) fn remaining(&self) -> usize {
        self.bytes.len()
    }

    /// The next `n` bytes.
    pub(crate) fn take(&mut self, n: usize) -> Result<&'a [u8], &'static str> {
        if self.bytes.len() < n {
            return Err("the file is truncated");
        }
        let (head, rest) = self.bytes.split_at(n);
        self.bytes = rest;
        Ok(head)
    }

    pub(crate) fn array<const N: usize>(&mut self) -> Result<[u8; N], &'static str> {
        let (head, rest) = self
            .bytes
            .split_first_chunk::<N>()
            .ok_or("the file is truncated")?;
        self.bytes = rest;
        Ok(*head)
    }

    pub(crate) fn u8(&mut self) -> Result<u8, &'static str> {
        Ok(self.array::<1>()?[0])
    }

    pub(crate) fn u32(&mut self) -> Result<u32, &'static str> {
        Ok(u32::from_le_bytes(self.array()?))
    }

    pub(crate) fn u64(&mut self) -> Result<u64, &'static str> {
        Ok(u64::from_le_bytes(self.array()?))
    }

    /// A finite real.
    pub(crate) fn f64(&mut self) -> Result<f64, &'static str> {
        let v = f64::from_bits(self.u64()?);
        if v.is_finite() {
            Ok(v)
        } else {
            Err("a number is not finite")
        }
    }

    pub(crate) fn point(&mut self) -> Result<Point, &'static str> {
        Ok(Point::new(self.f64()?, self.f64()?))
    }

    /// A count of items of at least `min_size` bytes each, checked against what remains.
    pub(crate) fn count(&mut self, n: u64, min_size: usize) -> Result<usize, &'static str> {
        match usize::try_from(n) {
            Ok(n) if n <= self.bytes.len() / min_size.max(1) => Ok(n),
            _ => Err("a count exceeds the file's size"),
        }
    }

    /// Steps over a path written by [`put_path`] without reading its numbers: its element
    /// count, then each element's tag, which `tag_ok(index, count, tag)` must accept (else
    /// `refused`), and its points. [`Reader::path`] checks the numbers when it reads them.
    /// The element count.
    pub(crate) fn skip_path(
        &mut self,
        tag_ok: impl Fn(usize, usize, u8) -> bool,
        refused: &'static str,
    ) -> Result<usize, &'static str> {
        let count = self.u32()?;
        let count = self.count(u64::from(count), 1)?;
        for k in 0..count {
            let tag = self.u8()?;
            let points = match tag {
                TAG_MOVE | TAG_LINE => 1,
                TAG_QUAD => 2,
                TAG_CUBIC => 3,
                TAG_CLOSE => 0,
                _ => return Err(refused),
            };
            if !tag_ok(k, count, tag) {
                return Err(refused);
            }
            self.take(16 * points)?;
        }
        Ok(count)
    }

    /// A path written by [`put_path`]: closed subpaths of finite points, possibly none.
    pub(crate) fn path(&mut self) -> Result<BezPath, &'static str> {
        let count = self.u32()?;
        let count = self.count(u64::from(count), 1)?;
        // The elements go into a vector of the right size (pushing onto a `BezPath` grows
        // it step by step); each subpath starts with a move, as `BezPath` expects.
        let mut elements = Vec::with_capacity(count);
        let mut open = false;
        for _ in 0..count {
            let tag = self.u8()?;
            elements.push(match (tag, open) {
                (TAG_MOVE, false) => PathEl::MoveTo(self.point()?),
                (TAG_LINE, true) => PathEl::LineTo(self.point()?),
                (TAG_QUAD, true) => PathEl::QuadTo(self.point()?, self.point()?),
                (TAG_CUBIC, true) => PathEl::CurveTo(self.point()?, self.point()?, self.point()?),
                (TAG_CLOSE, true) => PathEl::ClosePath,
                _ => return Err("an outline is not closed subpaths"),
            });
            open = tag != TAG_CLOSE;
        }
        if open {
            return Err("an outline is not closed subpaths");
        }
        Ok(BezPath::from_vec(elements))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEST: Header = Header {
        magic: b"XGLYPHTS",
        version: 7,
        not_ours: "it is not a test file",
    };

    #[test]
    fn the_frame_is_checked_before_the_body_is_read() {
        let mut good = TEST.start();
        good.extend_from_slice(&42u32.to_le_bytes());
        Header::seal(&mut good);
        let mut r = TEST.open(&good).unwrap();
        assert_eq!(r.u32(), Ok(42));
        assert!(r.is_empty());

        let mut other_version = Header { version: 8, ..TEST }.start();
        other_version.extend_from_slice(&42u32.to_le_bytes());
        Header::seal(&mut other_version);
        let mut flipped = good.clone();
        flipped[12] ^= 4;
        for (bytes, why) in [
            (&good[..3], "the file is truncated"),
            (b"PNG\0 other".as_slice(), "it is not a test file"),
            (
                &flipped[..],
                "its checksum does not match (the file is damaged or truncated)",
            ),
            (
                &good[..good.len() - 1],
                "its checksum does not match (the file is damaged or truncated)",
            ),
            (
                &other_version[..],
                "it was written by another version of xglyph",
            ),
        ] {
            assert_eq!(TEST.open(bytes).err(), Some(why));
        }
    }
}
