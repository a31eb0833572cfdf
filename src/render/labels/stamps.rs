//! The built-in face's stamps, cached per thread: the 20,902 labels of a CJK sheet draw
//! 292,628 glyphs of 20 characters at only 3,740 distinct transforms (counted from its
//! labels), so each (glyph, transform) is rasterised once and composited after that
//! ([`crate::render::stamp`], byte-identical to filling it).
//!
//! The key is the exact f32 transform tiny-skia would use (no quantised sub-pixel phase:
//! the stamp must cover the pixels the fill would). A cache is per thread (no locking; a
//! stamp is a pure function of its key, so the bytes do not depend on the thread count)
//! and holds at most [`CACHE_BYTES`]; when full it is emptied and refilled.

use std::cell::RefCell;
use std::collections::HashMap;

use tiny_skia::{Color, Path, PixmapMut, Transform};

use crate::render::stamp::Stamp;

/// Most memory one thread's cache holds, bytes (that CJK sheet's 3,740 stamps of at most
/// about 16 x 17 px: an estimated 1.3 MB).
pub const CACHE_BYTES: usize = 8 << 20;

/// A face glyph (`None` for `.notdef`) and its transform's `sx`, `sy`, `tx`, `ty` bits.
type Key = (Option<char>, [u32; 4]);

#[derive(Default)]
struct Cache {
    stamps: HashMap<Key, Option<Stamp>>,
    bytes: usize,
}

thread_local! {
    static CACHE: RefCell<Cache> = RefCell::default();
}

/// Draws face glyph `glyph` (its outline `path`) under `transform` in `color`: from the
/// thread's cached stamp, or filled by `fill` where a stamp cannot be exact (see
/// [`Stamp::put`]).
pub fn draw(
    img: &mut PixmapMut<'_>,
    glyph: Option<char>,
    path: &Path,
    transform: Transform,
    color: Color,
    fill: impl FnOnce(&mut PixmapMut<'_>),
) {
    let t = transform;
    let key = (glyph, [t.sx, t.sy, t.tx, t.ty].map(f32::to_bits));
    // A skewed transform is not in the key; the label face never skews.
    let stamped = t.kx == 0.0
        && t.ky == 0.0
        && CACHE.with_borrow_mut(|cache| {
            if !cache.stamps.contains_key(&key) {
                let stamp = Stamp::new(path, transform);
                let bytes = stamp.as_ref().map_or(0, Stamp::bytes) + std::mem::size_of::<Key>();
                if cache.bytes + bytes > CACHE_BYTES {
                    cache.stamps.clear();
                    cache.bytes = 0;
                }
                cache.bytes += bytes;
                cache.stamps.insert(key, stamp);
            }
            // `None`: the glyph leaves no pixels there (a space), or cannot be stamped.
            match cache.stamps.get(&key) {
                Some(Some(stamp)) => stamp.put(img, color),
                _ => false,
            }
        });
    if !stamped {
        fill(img);
    }
}
