//! WOFF and WOFF2 files unpacked to the OpenType font they carry, before the font import.
//!
//! Web fonts are often all a designer has of a font (icon sets ship only `.woff2`), and
//! xglyph writes WOFF2 itself, so it reads both back. wuff does the unpacking, WOFF2's glyf
//! and loca transforms included; the decompressors are the ones xglyph already builds
//! (`brotli`'s decoder, `flate2` for WOFF's zlib streams). A file is told by its signature
//! (`wOFF`, `wOF2`), not its name; anything else is returned as it is.
//!
//! Limits: each compressed stream may unpack to at most the size its header states, so a
//! file cannot inflate without bound; wuff refuses a WOFF2 font larger than 128 MiB. wuff
//! reports every failure alike, so the message cannot say what is damaged.

use std::error::Error;
use std::io::Read;

const WOFF: &[u8; 4] = b"wOFF";
const WOFF2: &[u8; 4] = b"wOF2";

/// The OpenType font (or collection) in `data`: unpacked when it is WOFF or WOFF2, `data`
/// itself otherwise. The error is a message for the file's name to precede.
pub fn unpacked(data: Vec<u8>) -> Result<Vec<u8>, String> {
    let (kind, unpack) = match data.get(..4) {
        Some(sig) if sig == WOFF => (
            "WOFF",
            wuff::decompress_woff1_with_custom_z(&data, &mut inflate),
        ),
        Some(sig) if sig == WOFF2 => (
            "WOFF2",
            wuff::decompress_woff2_with_custom_brotli(&data, &mut unbrotli),
        ),
        _ => return Ok(data),
    };
    unpack.map_err(|_| format!("cannot unpack this {kind} file; it may be damaged"))
}

/// One zlib stream of a WOFF file, at most `size` bytes.
fn inflate(stream: &[u8], size: usize) -> Result<Vec<u8>, Box<dyn Error>> {
    bounded(flate2::read::ZlibDecoder::new(stream), size)
}

/// The Brotli stream of a WOFF2 file, at most `size` bytes.
fn unbrotli(stream: &[u8], size: usize) -> Result<Vec<u8>, Box<dyn Error>> {
    bounded(brotli::Decompressor::new(stream, 4096), size)
}

/// All of `reader`, which must give at most `size` bytes.
fn bounded(reader: impl Read, size: usize) -> Result<Vec<u8>, Box<dyn Error>> {
    let mut out = Vec::with_capacity(size);
    reader.take(size as u64 + 1).read_to_end(&mut out)?;
    if out.len() > size {
        return Err("the stream unpacks to more than its stated size".into());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn other_data_is_passed_through_untouched() {
        let data = b"\0\x01\0\0 not a web font".to_vec();
        assert_eq!(unpacked(data.clone()), Ok(data));
    }

    #[test]
    fn a_damaged_file_is_refused_by_kind() {
        let err =
            unpacked(b"wOF2\0\x01\0\0 truncated".to_vec()).expect_err("not a whole WOFF2 file");
        assert_eq!(err, "cannot unpack this WOFF2 file; it may be damaged");
        let err =
            unpacked(b"wOFF\0\x01\0\0 truncated".to_vec()).expect_err("not a whole WOFF file");
        assert_eq!(err, "cannot unpack this WOFF file; it may be damaged");
    }

    #[test]
    fn a_stream_may_not_unpack_past_its_stated_size() {
        let zeros = vec![0u8; 1000];
        let mut packed = Vec::new();
        let mut encoder = flate2::write::ZlibEncoder::new(&mut packed, Default::default());
        std::io::Write::write_all(&mut encoder, &zeros).expect("in memory");
        encoder.finish().expect("in memory");
        assert_eq!(inflate(&packed, 1000).expect("exactly its size"), zeros);
        let err = inflate(&packed, 999).expect_err("one byte over");
        assert_eq!(
            err.to_string(),
            "the stream unpacks to more than its stated size"
        );
    }
}
