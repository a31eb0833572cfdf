//! WOFF2: the TrueType font compressed for the web, with the `ttf2woff2` crate (pure Rust,
//! Brotli from the `brotli` crate).
//!
//! Limits: tables are stored untransformed (no WOFF2 `glyf`/`loca` transform, the crate's
//! default, which every decoder reads), so files are somewhat larger than the reference
//! encoder's. Quality 11 (the smallest files) for a font up to [`LARGE_SFNT`] bytes,
//! quality 9 up to [`HUGE_SFNT`], quality 5 above it: a CJK font of 20,000 glyphs (a
//! 13.5 MB TTF) spent 27 CPU-seconds in Brotli at quality 11 and 5.5 at quality 9, and
//! quality 5 takes 0.7 s for 4 % more bytes (5.89 → 6.15 MB), so that an edit of one glyph
//! rebuilds in seconds.
//!
//! Up to [`LARGE_SFNT`] Brotli runs on one thread. Above it the data is cut into
//! [`SLICES`] equal slices compressed on threads of their own and joined into one Brotli
//! stream (the `brotli` crate's catable streams, through `ttf2woff2`): the bytes depend on
//! the fixed slice count, never on the machine's cores, and the stream is a few bytes to
//! 0.5 % longer than one thread's. Limit: those threads are not rayon's, so
//! `RAYON_NUM_THREADS` does not bound them.

use std::num::NonZeroUsize;

use ttf2woff2::{encode_with_options, BrotliQuality, EncodeOptions};

use super::OtfError;

/// Fonts larger than this (bytes) are compressed at Brotli quality 9 instead of 11.
pub const LARGE_SFNT: usize = 1 << 20;

/// Fonts larger than this (bytes) are compressed at Brotli quality 5.
pub const HUGE_SFNT: usize = 4 << 20;

/// The number of slices Brotli compresses on threads of their own above [`LARGE_SFNT`].
pub const SLICES: usize = 2;

/// The WOFF2 file holding the font `sfnt` (a TTF or OTF file).
pub fn woff2(sfnt: &[u8]) -> Result<Vec<u8>, OtfError> {
    let quality = match sfnt.len() {
        n if n > HUGE_SFNT => 5,
        n if n > LARGE_SFNT => 9,
        _ => 11,
    };
    let options = EncodeOptions {
        quality: BrotliQuality::from(quality),
        transform_glyf_loca: false,
        threads: NonZeroUsize::new(if sfnt.len() > LARGE_SFNT { SLICES } else { 1 }),
    };
    let mut woff2 =
        encode_with_options(sfnt, options).map_err(|e| OtfError::Table(format!("WOFF2: {e}")))?;
    // The sliced encoder writes into a buffer as long as the font: held until the commit.
    woff2.shrink_to_fit();
    Ok(woff2)
}

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

    /// A font file of one table (`zzzz`) holding `data`.
    fn one_table_sfnt(data: &[u8]) -> Vec<u8> {
        let mut sfnt = Vec::new();
        sfnt.extend_from_slice(&0x0001_0000u32.to_be_bytes());
        sfnt.extend_from_slice(&1u16.to_be_bytes());
        sfnt.extend_from_slice(&[0; 6]);
        sfnt.extend_from_slice(b"zzzz");
        sfnt.extend_from_slice(&0u32.to_be_bytes());
        sfnt.extend_from_slice(&28u32.to_be_bytes());
        sfnt.extend_from_slice(&(data.len() as u32).to_be_bytes());
        sfnt.extend_from_slice(data);
        sfnt
    }

    #[test]
    fn a_large_font_in_slices_decodes_to_its_table_and_is_deterministic() {
        // 2 MiB of font-like data: repeats at several distances, and noise.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let data: Vec<u8> = (0..(2usize << 20))
            .map(|i| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                if i % 7 < 4 {
                    (i / 64 % 251) as u8
                } else {
                    state as u8 & 0x0f
                }
            })
            .collect();
        let sfnt = one_table_sfnt(&data);
        assert!(sfnt.len() > LARGE_SFNT);
        let w = woff2(&sfnt).expect("woff2");
        // One table: its flags byte (63: an arbitrary tag), the tag, then origLength as
        // UIntBase128 (2^21: 0x81 0x80 0x80 0x00), and the one Brotli stream.
        let compressed = u32::from_be_bytes([w[20], w[21], w[22], w[23]]) as usize;
        assert_eq!(&w[48..53], &[63, b'z', b'z', b'z', b'z']);
        assert_eq!(&w[53..57], &[0x81, 0x80, 0x80, 0x00]);
        let mut stream = Vec::new();
        brotli::BrotliDecompress(&mut &w[57..57 + compressed], &mut stream).expect("brotli");
        assert_eq!(stream, data);
        // The slices are fixed, not the machine's threads: the same bytes every time.
        assert_eq!(woff2(&sfnt).expect("again"), w);
        // Within half a percent of the one-thread stream.
        let single = ttf2woff2::encode(&sfnt, BrotliQuality::from(9)).expect("one thread");
        assert_ne!(single, w);
        assert!(
            (w.len() as f64) < 1.005 * single.len() as f64,
            "{} vs {}",
            w.len(),
            single.len()
        );
    }
}
