//! WOFF2: the TrueType font compressed for the web, with the `ttf2woff2` crate (pure Rust,
//! Brotli from the `brotli` crate).
//!
//! Limits: tables are stored untransformed (no WOFF2 `glyf`/`loca` transform, the crate's
//! default, which every decoder reads), so files are somewhat larger than the reference
//! encoder's; Brotli runs single-threaded, so the bytes are deterministic. Quality 11 (the
//! smallest files) for a font up to [`LARGE_SFNT`] bytes; above it quality 9: a CJK font of
//! 20,000 glyphs spent 27 CPU-seconds in Brotli at quality 11, more than the whole build's
//! target, and quality 9 is several times faster for a few per cent more bytes.

use ttf2woff2::{encode, BrotliQuality};

use super::OtfError;

/// Fonts larger than this (bytes) are compressed at Brotli quality 9 instead of 11.
pub const LARGE_SFNT: usize = 1 << 20;

/// The WOFF2 file holding the font `sfnt` (a TTF or OTF file).
pub fn woff2(sfnt: &[u8]) -> Result<Vec<u8>, OtfError> {
    let quality = if sfnt.len() > LARGE_SFNT { 9 } else { 11 };
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
