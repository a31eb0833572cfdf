//! PNG outputs rasterized with tiny-skia: the glyph sheet and the text proof.
//!
//! Everything renders into memory ([`tiny_skia::Pixmap`]) and is encoded with [`encode_png`];
//! writing files is the caller's job (see [`crate::write`]). Images are opaque (white
//! background), glyphs are anti-aliased and filled with the nonzero rule.

pub mod draw;
pub mod labels;
mod overlay;
pub mod proof;
pub mod sheet;
mod stamp;

use std::fmt;

use tiny_skia::Pixmap;

pub use proof::{
    default_text, render_instances_proof, render_instances_proof_with, render_proof,
    render_proof_with, InstancesProof, ProofOptions,
};
pub use sheet::{
    page_file_names, render_sheet, render_sheet_page, render_sheet_page_with, sheet_order,
    sheet_pages, sheet_png_files, sheet_png_files_reusing, sheet_png_files_with, SheetOptions,
};

/// Largest image side we allocate, in pixels.
pub const MAX_SIDE: u32 = 30_000;
/// Largest image area we allocate, in pixels (400 MB of RGBA).
pub const MAX_AREA: u64 = 100_000_000;

/// Why an image could not be rendered.
#[derive(Clone, Debug, PartialEq)]
pub enum RenderError {
    /// The font has no glyphs, so there is nothing to draw.
    NoGlyphs,
    /// The requested image is too large (or has a zero side).
    Size {
        /// Width asked for, pixels.
        width: u64,
        /// Height asked for, pixels.
        height: u64,
    },
    /// An option is out of range.
    Option(String),
    /// PNG encoding failed.
    Png(String),
    /// The text could not be shaped ([`crate::layout::LayoutError`], as text).
    Layout(String),
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::NoGlyphs => write!(f, "the font has no glyphs to draw"),
            RenderError::Size { width, height } => write!(
                f,
                "image of {width} x {height} px is not possible (each side 1..={MAX_SIDE} px, \
                 at most {MAX_AREA} px in all); use a smaller cell size or text"
            ),
            RenderError::Option(msg) => write!(f, "{msg}"),
            RenderError::Png(msg) => write!(f, "PNG encoding failed: {msg}"),
            RenderError::Layout(msg) => write!(f, "{msg}"),
        }
    }
}

impl std::error::Error for RenderError {}

impl From<crate::layout::LayoutError> for RenderError {
    fn from(e: crate::layout::LayoutError) -> Self {
        RenderError::Layout(e.to_string())
    }
}

/// A white pixmap of the given size, or [`RenderError::Size`].
pub fn white_pixmap(width: u64, height: u64) -> Result<Pixmap, RenderError> {
    white_pixmap_in(Vec::new(), width, height)
}

/// [`white_pixmap`] in the memory of `spare` (the data of a pixmap drawn before, from
/// [`Pixmap::take`]). A CJK sheet page is 52 MB: each one allocated anew came from the
/// kernel as fresh zeroed pages, a sixth of the sheet's CPU time.
pub fn white_pixmap_in(mut spare: Vec<u8>, width: u64, height: u64) -> Result<Pixmap, RenderError> {
    let err = RenderError::Size { width, height };
    if width == 0 || height == 0 || width > u64::from(MAX_SIDE) || height > u64::from(MAX_SIDE) {
        return Err(err);
    }
    if width * height > MAX_AREA {
        return Err(err);
    }
    let size = tiny_skia::IntSize::from_wh(width as u32, height as u32).ok_or(err.clone())?;
    // Opaque white premultiplied is every byte 255.
    spare.clear();
    spare.resize(width as usize * height as usize * 4, u8::MAX);
    Pixmap::from_vec(spare, size).ok_or(err)
}

/// PNG bytes of a pixmap (deterministic: no time stamps or text chunks).
///
/// Encoded with the `png` crate's fast setting (fdeflate, adaptive row filters) rather than
/// tiny-skia's `encode_png` (miniz at its default level), which took a fifth of a build's
/// CPU. Our images are opaque and have few colours (anti-aliased black on white, a few
/// guide colours), so an image of at most 256 colours is written with a palette, one byte
/// a pixel: on the bundled typeface's sheet and proofs that is 4 to 10 times faster than
/// tiny-skia's encoder and the files are 15 to 20 % smaller. Other opaque images are RGB;
/// an image with a translucent pixel is RGBA, un-premultiplied.
pub fn encode_png(pixmap: &Pixmap) -> Result<Vec<u8>, RenderError> {
    let (color, palette, data) = match palette_indices(pixmap) {
        Some((palette, indices)) => (png::ColorType::Indexed, Some(palette), indices),
        None if pixmap.pixels().iter().all(|p| p.alpha() == u8::MAX) => {
            let rgb = pixmap
                .pixels()
                .iter()
                .flat_map(|p| [p.red(), p.green(), p.blue()])
                .collect();
            (png::ColorType::Rgb, None, rgb)
        }
        None => {
            let rgba = pixmap
                .pixels()
                .iter()
                .flat_map(|p| {
                    let c = p.demultiply();
                    [c.red(), c.green(), c.blue(), c.alpha()]
                })
                .collect();
            (png::ColorType::Rgba, None, rgba)
        }
    };
    let png_err = |e: png::EncodingError| RenderError::Png(e.to_string());
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, pixmap.width(), pixmap.height());
    encoder.set_color(color);
    encoder.set_depth(png::BitDepth::Eight);
    if let Some(palette) = palette {
        encoder.set_palette(palette);
    }
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header().map_err(png_err)?;
    writer.write_image_data(&data).map_err(png_err)?;
    writer.finish().map_err(png_err)?;
    Ok(bytes)
}

/// The palette (RGB triples, in order of first appearance) and each pixel's index into it,
/// when the image is opaque and has at most 256 colours; `None` otherwise.
fn palette_indices(pixmap: &Pixmap) -> Option<(Vec<u8>, Vec<u8>)> {
    let mut palette = Vec::new();
    // Fx, not the default SipHash: the lookups were a third of a CJK sheet page's encoding.
    let mut index_of = rustc_hash::FxHashMap::default();
    let mut indices = Vec::with_capacity(pixmap.pixels().len());
    // Runs of one colour are long (the white background): look up only on a change.
    let mut last: Option<(tiny_skia::PremultipliedColorU8, u8)> = None;
    for &p in pixmap.pixels() {
        let index = match last {
            Some((color, index)) if color == p => index,
            _ => {
                if p.alpha() != u8::MAX {
                    return None;
                }
                let rgb = [p.red(), p.green(), p.blue()];
                let next = index_of.len();
                let index = *index_of
                    .entry(u32::from_le_bytes([rgb[0], rgb[1], rgb[2], 0]))
                    .or_insert(next);
                if index == next {
                    palette.extend_from_slice(&rgb);
                }
                let index = u8::try_from(index).ok()?;
                last = Some((p, index));
                index
            }
        };
        indices.push(index);
    }
    Some((palette, indices))
}
