//! WOFF2: the TrueType font compressed for the web.
//!
//! Limits: tables are stored untransformed (no WOFF2 `glyf`/`loca` transform, which every
//! decoder reads), so files are somewhat larger than the reference encoder's. Quality 11
//! (the smallest files) for a font up to [`LARGE_SFNT`] bytes, quality 9 up to
//! [`HUGE_SFNT`], quality 5 above it: a CJK font of 20,000 glyphs (a 13.5 MB TTF) spent 27
//! CPU-seconds in Brotli at quality 11 and 5.5 at quality 9, and quality 5 takes 0.7 s for
//! 4 % more bytes (5.89 → 6.15 MB).
//!
//! Up to [`LARGE_SFNT`] the `ttf2woff2` crate writes the file (Brotli on one thread). Above
//! it the tables' stream is cut into slices, each compressed alone as a *catable* Brotli
//! stream and the slices joined into one stream (the `brotli` crate's `BroCatli`). The cuts
//! are fixed by the font: at the start and the end of `glyf`, and inside it before every
//! [`GLYPHS_PER_SLICE`]th glyph, so that an edit of one glyph changes one slice of `glyf`
//! and the small one after it (`loca`, `head`, `hmtx`, ...), and
//! [`woff2_with`]'s caller can take the other slices' bytes from the last build. The slices
//! run on every core; the bytes depend on the cuts alone, never on the cores or on what was
//! reused. The cost of the cuts: on the 20,902-glyph CJK font, 2.2 % more bytes than one
//! stream (6.45 MB against 6.31 MB). The container (header and table directory) is written
//! here because `ttf2woff2` takes only a whole font, not a stream made elsewhere; a test
//! compares it with the crate's.

use brotli::concat::{BroCatli, BroCatliResult};
use brotli::enc::backward_references::BrotliEncoderMode;
use brotli::enc::BrotliEncoderParams;
use rayon::prelude::*;
use ttf2woff2::{encode_with_options, BrotliQuality, EncodeOptions};

use super::{be16, be32, OtfError};

/// Fonts larger than this (bytes) are compressed at Brotli quality 9 instead of 11, in
/// slices.
pub const LARGE_SFNT: usize = 1 << 20;

/// Fonts larger than this (bytes) are compressed at Brotli quality 5.
pub const HUGE_SFNT: usize = 4 << 20;

/// Glyphs of `glyf` per slice above [`LARGE_SFNT`] (about 1.3 MB of a CJK font's outlines).
pub const GLYPHS_PER_SLICE: usize = 2048;

/// What compresses one slice: `slice(bytes, quality)` must return what [`compress_slice`]
/// does (or its bytes kept from an earlier build).
pub type CompressSlice<'a> = dyn Fn(&[u8], u32) -> Result<Vec<u8>, OtfError> + Sync + 'a;

/// The WOFF2 file holding the font `sfnt` (a TTF or OTF file).
pub fn woff2(sfnt: &[u8]) -> Result<Vec<u8>, OtfError> {
    woff2_with(sfnt, &compress_slice)
}

/// [`woff2`], each slice of a large font compressed by `slice(bytes, quality)`, which must
/// return what [`compress_slice`] does (from an earlier build, say).
pub fn woff2_with(sfnt: &[u8], slice: &CompressSlice<'_>) -> Result<Vec<u8>, OtfError> {
    if sfnt.len() <= LARGE_SFNT {
        let options = EncodeOptions {
            quality: BrotliQuality::from(11),
            transform_glyf_loca: false,
            threads: None,
        };
        return encode_with_options(sfnt, options)
            .map_err(|e| OtfError::Table(format!("WOFF2: {e}")));
    }
    let quality = if sfnt.len() > HUGE_SFNT { 5 } else { 9 };
    let tables = directory(sfnt)?;
    let mut stream = Vec::with_capacity(tables.iter().map(|t| t.data.len()).sum());
    for t in &tables {
        stream.extend_from_slice(t.data);
    }
    let cuts = cuts(&tables);
    let parts = cuts
        .par_windows(2)
        .map(|w| slice(&stream[w[0]..w[1]], quality))
        .collect::<Result<Vec<_>, _>>()?;
    let compressed = join_streams(&parts)?;
    Ok(container(sfnt, &tables, &compressed))
}

/// `bytes` as a catable Brotli stream at `quality` (the slices of
/// [`crate::otf::woff2_from_ttf_with`]).
pub fn compress_slice(bytes: &[u8], quality: u32) -> Result<Vec<u8>, OtfError> {
    let params = BrotliEncoderParams {
        quality: quality as i32,
        mode: BrotliEncoderMode::BROTLI_MODE_FONT,
        size_hint: bytes.len(),
        catable: true,
        appendable: true,
        magic_number: false,
        ..BrotliEncoderParams::default()
    };
    let mut out = Vec::with_capacity(bytes.len() / 2 + 64);
    brotli::BrotliCompress(&mut &bytes[..], &mut out, &params)
        .map_err(|e| OtfError::Table(format!("WOFF2: Brotli: {e}")))?;
    Ok(out)
}

/// Whether `compressed` is a Brotli stream of `bytes` (a slice kept from an earlier build
/// is checked so before it is used).
pub fn slice_holds(compressed: &[u8], bytes: &[u8]) -> bool {
    let mut out = Vec::with_capacity(bytes.len());
    brotli::BrotliDecompress(&mut &compressed[..], &mut out).is_ok() && out == bytes
}

/// One table of the font, in the WOFF2 directory's order.
struct Table<'a> {
    tag: [u8; 4],
    data: &'a [u8],
}

/// The font's tables sorted by tag, `loca` moved right after `glyf` (as WOFF2 requires).
fn directory(sfnt: &[u8]) -> Result<Vec<Table<'_>>, OtfError> {
    let bad = || OtfError::Table("WOFF2: the font's table directory is damaged".into());
    let count = usize::from(be16(sfnt, 4).ok_or_else(bad)?);
    let mut tables = Vec::with_capacity(count);
    for i in 0..count {
        let record = 12 + 16 * i;
        let tag: [u8; 4] = sfnt
            .get(record..record + 4)
            .and_then(|t| t.try_into().ok())
            .ok_or_else(bad)?;
        let offset = be32(sfnt, record + 8).ok_or_else(bad)? as usize;
        let length = be32(sfnt, record + 12).ok_or_else(bad)? as usize;
        let data = offset
            .checked_add(length)
            .and_then(|end| sfnt.get(offset..end))
            .ok_or_else(bad)?;
        tables.push(Table { tag, data });
    }
    tables.sort_by_key(|t| t.tag);
    if let Some(loca) = position(&tables, b"loca") {
        let loca = tables.remove(loca);
        match position(&tables, b"glyf") {
            Some(glyf) => tables.insert(glyf + 1, loca),
            None => tables.push(loca),
        }
    }
    Ok(tables)
}

fn position(tables: &[Table<'_>], tag: &[u8; 4]) -> Option<usize> {
    tables.iter().position(|t| &t.tag == tag)
}

/// Where the stream of `tables` is cut into slices: its ends, both ends of `glyf`, and
/// inside `glyf` before every [`GLYPHS_PER_SLICE`]th glyph (by `loca`; without a readable
/// `loca`, `glyf` is one slice).
fn cuts(tables: &[Table<'_>]) -> Vec<usize> {
    let total: usize = tables.iter().map(|t| t.data.len()).sum();
    let mut cuts = vec![0, total];
    if let Some(glyf) = position(tables, b"glyf") {
        let start: usize = tables[..glyf].iter().map(|t| t.data.len()).sum();
        let len = tables[glyf].data.len();
        cuts.extend([start, start + len]);
        cuts.extend(
            glyph_starts(tables)
                .into_iter()
                .filter(|&at| at < len)
                .map(|at| start + at),
        );
    }
    cuts.sort_unstable();
    cuts.dedup();
    cuts
}

/// The offsets in `glyf` of glyphs `GLYPHS_PER_SLICE`, `2 × GLYPHS_PER_SLICE`, ... (from
/// `loca` in `head`'s format); none when `head`, `maxp` or `loca` is short.
fn glyph_starts(tables: &[Table<'_>]) -> Vec<usize> {
    let table = |tag: &[u8; 4]| position(tables, tag).map(|i| tables[i].data);
    let (Some(head), Some(maxp), Some(loca)) = (table(b"head"), table(b"maxp"), table(b"loca"))
    else {
        return Vec::new();
    };
    let (Some(format), Some(glyphs)) = (be16(head, 50), be16(maxp, 4)) else {
        return Vec::new();
    };
    (1..)
        .map(|k| k * GLYPHS_PER_SLICE)
        .take_while(|&g| g < usize::from(glyphs))
        .map_while(|g| match format {
            0 => be16(loca, 2 * g).map(|o| 2 * usize::from(o)),
            _ => be32(loca, 4 * g).map(|o| o as usize),
        })
        .collect()
}

/// The Brotli streams `parts` (each from [`compress_slice`]) joined into one.
fn join_streams(parts: &[Vec<u8>]) -> Result<Vec<u8>, OtfError> {
    let failed =
        |r: BroCatliResult| OtfError::Table(format!("WOFF2: joining Brotli slices: {r:?}"));
    let mut out = vec![0; parts.iter().map(Vec::len).sum::<usize>() + 64];
    let mut at = 0;
    let mut cat = BroCatli::new();
    for part in parts {
        cat.new_brotli_file();
        match cat.stream(part, &mut 0, &mut out, &mut at) {
            BroCatliResult::Success | BroCatliResult::NeedsMoreInput => {}
            r => return Err(failed(r)),
        }
    }
    match cat.finish(&mut out, &mut at) {
        BroCatliResult::Success => {}
        r => return Err(failed(r)),
    }
    out.truncate(at);
    Ok(out)
}

/// The WOFF2 file: header, table directory (every table untransformed) and `compressed`,
/// padded to 4 bytes (WOFF2 § 3–5).
fn container(sfnt: &[u8], tables: &[Table<'_>], compressed: &[u8]) -> Vec<u8> {
    let align4 = |n: usize| (n + 3) & !3;
    let mut dir = Vec::new();
    for t in tables {
        // glyf and loca with transform version 3 (the null transform), the rest 0.
        let null_transform = if &t.tag == b"glyf" || &t.tag == b"loca" {
            3 << 6
        } else {
            0
        };
        match KNOWN_TAGS.iter().position(|k| k == &t.tag) {
            Some(i) => dir.push(i as u8 | null_transform),
            None => {
                dir.push(63);
                dir.extend_from_slice(&t.tag);
            }
        }
        push_base128(&mut dir, t.data.len() as u32);
    }
    let sfnt_size =
        12 + 16 * tables.len() + tables.iter().map(|t| align4(t.data.len())).sum::<usize>();
    let length = align4(48 + dir.len() + compressed.len());
    let head = position(tables, b"head").map(|i| tables[i].data);
    let version = |at: usize| head.and_then(|h| be16(h, at)).unwrap_or(0);
    let mut out = Vec::with_capacity(length);
    out.extend_from_slice(b"wOF2");
    out.extend_from_slice(sfnt.get(0..4).unwrap_or(&[0; 4]));
    out.extend_from_slice(&(length as u32).to_be_bytes());
    out.extend_from_slice(&(tables.len() as u16).to_be_bytes());
    out.extend_from_slice(&[0, 0]);
    out.extend_from_slice(&(sfnt_size as u32).to_be_bytes());
    out.extend_from_slice(&(compressed.len() as u32).to_be_bytes());
    // majorVersion, minorVersion: the font's revision from `head`, as ttf2woff2 writes.
    out.extend_from_slice(&version(4).to_be_bytes());
    out.extend_from_slice(&version(6).to_be_bytes());
    // No metadata, no private data.
    out.extend_from_slice(&[0; 20]);
    out.extend_from_slice(&dir);
    out.extend_from_slice(compressed);
    out.resize(length, 0);
    out
}

/// `value` as a WOFF2 UIntBase128: 7 bits a byte, most significant first, no leading zeros.
fn push_base128(out: &mut Vec<u8>, value: u32) {
    let mut bytes = [0u8; 5];
    let mut n = 0;
    let mut v = value;
    loop {
        bytes[n] = (v & 0x7f) as u8;
        n += 1;
        v >>= 7;
        if v == 0 {
            break;
        }
    }
    for i in (0..n).rev() {
        out.push(bytes[i] | if i > 0 { 0x80 } else { 0 });
    }
}

/// The tags a WOFF2 directory writes as an index (WOFF2 § 5.1, table 1).
const KNOWN_TAGS: [[u8; 4]; 63] = [
    *b"cmap", *b"head", *b"hhea", *b"hmtx", *b"maxp", *b"name", *b"OS/2", *b"post", *b"cvt ",
    *b"fpgm", *b"glyf", *b"loca", *b"prep", *b"CFF ", *b"VORG", *b"EBDT", *b"EBLC", *b"gasp",
    *b"hdmx", *b"kern", *b"LTSH", *b"PCLT", *b"VDMX", *b"vhea", *b"vmtx", *b"BASE", *b"GDEF",
    *b"GPOS", *b"GSUB", *b"EBSC", *b"JSTF", *b"MATH", *b"CBDT", *b"CBLC", *b"COLR", *b"CPAL",
    *b"SVG ", *b"sbix", *b"acnt", *b"avar", *b"bdat", *b"bloc", *b"bsln", *b"cvar", *b"fdsc",
    *b"feat", *b"fmtx", *b"fvar", *b"gvar", *b"hsty", *b"just", *b"lcar", *b"mort", *b"morx",
    *b"opbd", *b"prop", *b"trak", *b"Zapf", *b"Silf", *b"Glat", *b"Gloc", *b"Feat", *b"Sill",
];

#[cfg(test)]
mod tests {
    use read_fonts::FontRef;

    use super::*;
    use crate::otf::tables::tests::info;

    #[test]
    fn header_and_table_directory_of_the_bundled_flavours() {
        let font = crate::outline::OutlinedFont {
            info: info(),
            tolerance: 0.5,
            glyphs: Vec::new(),
            kerning: Vec::new(),
            features: None,
        };
        let ttf = crate::otf::ttf(&font).expect("ttf");
        let w = woff2(&ttf).expect("woff2");
        // Signature 'wOF2', flavour 0x00010000 (TrueType), total length in the header.
        assert_eq!(&w[0..4], b"wOF2");
        assert_eq!(&w[4..8], &[0, 1, 0, 0]);
        assert_eq!(
            u32::from_be_bytes([w[8], w[9], w[10], w[11]]) as usize,
            w.len()
        );
        // numTables equals the TTF's.
        let tables = FontRef::new(&ttf)
            .expect("ttf reads")
            .table_directory
            .num_tables();
        assert_eq!(u16::from_be_bytes([w[12], w[13]]), tables);
        assert!(
            w.len() < ttf.len(),
            "{} bytes compressed from {}",
            w.len(),
            ttf.len()
        );
        // Deterministic.
        assert_eq!(woff2(&ttf).expect("again"), w);
        // Not a font: an error, not a panic.
        assert!(woff2(b"not a font").is_err());
    }

    /// A font-like file over [`LARGE_SFNT`]: `head`, `maxp`, long `loca` and `glyf` of
    /// `glyphs` glyphs of 400 to 700 bytes each (repeats and noise), and a `zzzz` table.
    fn large_sfnt(glyphs: usize) -> Vec<u8> {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut glyf = Vec::new();
        let mut loca = Vec::new();
        for g in 0..glyphs {
            loca.extend_from_slice(&(glyf.len() as u32).to_be_bytes());
            for i in 0..400 + g * 37 % 300 {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                glyf.push(if i % 7 < 4 {
                    (i / 8 % 251) as u8
                } else {
                    state as u8 & 0x0f
                });
            }
        }
        loca.extend_from_slice(&(glyf.len() as u32).to_be_bytes());
        let mut head = vec![0u8; 54];
        head[4..8].copy_from_slice(&[0, 2, 0x80, 0]); // fontRevision 2.5
        head[50..52].copy_from_slice(&1u16.to_be_bytes()); // long loca
        let mut maxp = vec![0, 0, 0x50, 0, 0, 0];
        maxp[4..6].copy_from_slice(&(glyphs as u16).to_be_bytes());
        let tables: [(&[u8; 4], Vec<u8>); 5] = [
            (b"zzzz", b"not a known table".to_vec()),
            (b"maxp", maxp),
            (b"loca", loca),
            (b"head", head),
            (b"glyf", glyf),
        ];
        let mut sfnt = Vec::new();
        sfnt.extend_from_slice(&0x0001_0000u32.to_be_bytes());
        sfnt.extend_from_slice(&(tables.len() as u16).to_be_bytes());
        sfnt.extend_from_slice(&[0; 6]);
        let mut offset = 12 + 16 * tables.len();
        for (tag, data) in &tables {
            sfnt.extend_from_slice(*tag);
            sfnt.extend_from_slice(&0u32.to_be_bytes());
            sfnt.extend_from_slice(&(offset as u32).to_be_bytes());
            sfnt.extend_from_slice(&(data.len() as u32).to_be_bytes());
            offset += (data.len() + 3) & !3;
        }
        for (_, data) in &tables {
            sfnt.extend_from_slice(data);
            sfnt.resize((sfnt.len() + 3) & !3, 0);
        }
        sfnt
    }

    /// The slices [`woff2_with`] asks for, in order.
    fn slices(sfnt: &[u8]) -> Vec<Vec<u8>> {
        // Each slice is part of one stream: its address gives its place.
        let asked = std::sync::Mutex::new(Vec::new());
        woff2_with(sfnt, &|bytes, quality| {
            asked
                .lock()
                .unwrap()
                .push((bytes.as_ptr() as usize, bytes.to_vec()));
            compress_slice(bytes, quality)
        })
        .expect("woff2");
        let mut asked = asked.into_inner().unwrap();
        asked.sort();
        asked.into_iter().map(|(_, bytes)| bytes).collect()
    }

    #[test]
    fn a_large_font_in_slices_decodes_to_its_tables_and_only_edited_slices_change() {
        // Two whole slices of glyphs and half of one.
        let g = GLYPHS_PER_SLICE;
        let sfnt = large_sfnt(2 * g + g / 2);
        assert!(sfnt.len() > LARGE_SFNT);
        let w = woff2(&sfnt).expect("woff2");
        // The header and table directory are those ttf2woff2 writes, but for the stream's
        // length (bytes 20..24) and the file's (8..12).
        let theirs = encode_with_options(
            &sfnt,
            EncodeOptions {
                quality: BrotliQuality::from(1),
                transform_glyf_loca: false,
                threads: None,
            },
        )
        .expect("ttf2woff2");
        let tables = directory(&sfnt).expect("tables");
        // A flags byte per table, the custom tag, the base-128 lengths.
        let mut lengths = Vec::new();
        tables
            .iter()
            .for_each(|t| push_base128(&mut lengths, t.data.len() as u32));
        let dir_end = 48 + tables.len() + 4 + lengths.len();
        assert_eq!(w[..8], theirs[..8]);
        assert_eq!(w[12..20], theirs[12..20]);
        assert_eq!(w[24..dir_end], theirs[24..dir_end]);
        assert_eq!(
            &w[24..28],
            &[0, 2, 0x80, 0],
            "major and minor version from head"
        );
        // The stream decodes to the tables in the directory's order (glyf, then loca).
        let compressed = u32::from_be_bytes([w[20], w[21], w[22], w[23]]) as usize;
        assert_eq!(w.len(), (dir_end + compressed + 3) & !3);
        let mut stream = Vec::new();
        brotli::BrotliDecompress(&mut &w[dir_end..dir_end + compressed], &mut stream)
            .expect("brotli");
        let tags: Vec<&[u8; 4]> = tables.iter().map(|t| &t.tag).collect();
        assert_eq!(tags, [b"glyf", b"loca", b"head", b"maxp", b"zzzz"]);
        let joined: Vec<u8> = tables.iter().flat_map(|t| t.data.iter().copied()).collect();
        assert_eq!(stream, joined);
        // Cut before glyphs g and 2g and after glyf: 4 slices.
        let before = slices(&sfnt);
        assert_eq!(before.len(), 4);
        let glyph_g = be32(tables[1].data, 4 * g).unwrap() as usize;
        assert_eq!(before[0].len(), glyph_g);
        let glyf_len: usize = before[..3].iter().map(Vec::len).sum();
        assert_eq!(glyf_len, tables[0].data.len());
        assert_eq!(before[3].len(), joined.len() - glyf_len);
        // The same bytes every time, and with the slices handed back from a store.
        assert_eq!(woff2(&sfnt).expect("again"), w);
        let stored: Vec<Vec<u8>> = before
            .iter()
            .map(|s| compress_slice(s, 9).unwrap())
            .collect();
        let from_store = woff2_with(&sfnt, &|bytes, _| {
            let i = before
                .iter()
                .position(|s| s == bytes)
                .expect("a known slice");
            Ok(stored[i].clone())
        });
        assert_eq!(from_store.expect("woff2"), w);
        assert!(stored.iter().zip(&before).all(|(c, s)| slice_holds(c, s)));
        assert!(!slice_holds(&stored[0], &before[1]));
        assert!(!slice_holds(b"not brotli", &before[1]));
        // An edit of glyph g + g/2 (same length) changes its slice alone.
        let glyf_offset = be32(&sfnt, 12 + 16 * 4 + 8).unwrap() as usize;
        let edit = be32(tables[1].data, 4 * (g + g / 2)).unwrap() as usize;
        let mut edited = sfnt.clone();
        edited[glyf_offset + edit + 10] ^= 0x55;
        let after = slices(&edited);
        let changed: Vec<bool> = before.iter().zip(&after).map(|(a, b)| a != b).collect();
        assert_eq!(changed, [false, true, false, false]);
        // Within 2 % of one stream over the whole.
        let single = ttf2woff2::encode(&sfnt, BrotliQuality::from(9)).expect("one stream");
        assert!(
            (w.len() as f64) < 1.02 * single.len() as f64,
            "{} vs {}",
            w.len(),
            single.len()
        );
    }

    #[test]
    fn base128_is_the_shortest_big_endian_form() {
        let mut out = Vec::new();
        for v in [0u32, 127, 128, 1 << 21, u32::MAX] {
            push_base128(&mut out, v);
        }
        assert_eq!(
            out,
            [0x00, 0x7f, 0x81, 0x00, 0x81, 0x80, 0x80, 0x00, 0x8f, 0xff, 0xff, 0xff, 0x7f]
        );
    }
}
