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

use std::fmt;

use tiny_skia::Pixmap;

pub use proof::{
    default_text, render_instances_proof, render_proof, render_proof_with, ProofOptions,
};
pub use sheet::{
    page_file_names, render_sheet, render_sheet_page, sheet_order, sheet_pages, sheet_png_files,
    SheetOptions,
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
    let err = RenderError::Size { width, height };
    if width == 0 || height == 0 || width > u64::from(MAX_SIDE) || height > u64::from(MAX_SIDE) {
        return Err(err);
    }
    if width * height > MAX_AREA {
        return Err(err);
    }
    let mut pixmap = Pixmap::new(width as u32, height as u32).ok_or(err)?;
    pixmap.fill(tiny_skia::Color::WHITE);
    Ok(pixmap)
}

/// PNG bytes of a pixmap (deterministic: no time stamps or text chunks).
pub fn encode_png(pixmap: &Pixmap) -> Result<Vec<u8>, RenderError> {
    pixmap
        .encode_png()
        .map_err(|e| RenderError::Png(e.to_string()))
}
