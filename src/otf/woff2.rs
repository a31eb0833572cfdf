//! WOFF2: the TrueType font compressed for the web, with the `ttf2woff2` crate (pure Rust,
//! Brotli from the `brotli` crate).
//!
//! Limits: tables are stored untransformed (no WOFF2 `glyf`/`loca` transform, the crate's
//! default, which every decoder reads), so files are somewhat larger than the reference
//! encoder's; Brotli runs single-threaded, so the bytes are deterministic. Quality 11 (the
//! smallest files) for a font up to [`LARGE_SFNT`] bytes, quality 9 up to [`HUGE_SFNT`],
//! quality 5 above it: a CJK font of 20,000 glyphs (a 13.5 MB TTF) spent 27 CPU-seconds in
//! Brotli at quality 11 and 5.5 at quality 9, and quality 5 takes 0.7 s for 4 % more bytes
//! (5.89 → 6.15 MB), so that an edit of one glyph rebuilds in seconds.

use ttf2woff2::{encode, BrotliQuality};

use super::OtfError;

/// Fonts larger than this (bytes) are compressed at Brotli quality 9 instead of 11.
pub const LARGE_SFNT: usize = 1 << 20;

/// Fonts larger than this (bytes) are compressed at Brotli quality 5.
pub const HUGE_SFNT: usize = 4 << 20;

/// The WOFF2 file holding the font `sfnt` (a TTF or OTF file).
pub fn woff2(sfnt: &[u8]) -> Result<Vec<u8>, OtfError> {
    let quality = match sfnt.len() {
        n if n > HUGE_SFNT => 5,
        n if n > LARGE_SFNT => 9,
        _ => 11,
    };
    encode(sfnt, BrotliQuality::from(quality)).map_err(|e| OtfError::Table(format!("WOFF2: {e}")))
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
}
