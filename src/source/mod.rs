//! Sources: TOML text -> typed [`crate::model::Font`], with spans and diagnostics; and the
//! canonical text back ([`emit`]) for `fmt` and `import`.
//!
//! The format is documented in `docs/format.md`. One file per job: `load` reads a
//! directory and runs the checks across files; `info`, `glyph` and `kerning` read one file
//! each; `value` reads typed TOML values; `geometry` holds the point checks; [`limits`]
//! holds the limits of the outputs; `anchors` places components by anchors and checks the
//! marks; `components` resolves the component graph (bases,
//! cycles, an order for sizes computed once per glyph); `format` plans the rewrite that
//! `xglyph fmt` performs. For a font with masters, `designspace` reads `font.toml`'s
//! `[[axis]]`, `[[master]]` and `[[instance]]` tables, and `compat` compares each master
//! folder's glyphs with the default master's.

mod anchors;
mod compat;
mod components;
mod designspace;
mod diagnostic;
pub mod emit;
pub mod format;
mod geometry;
mod glyph;
mod info;
mod kerning;
pub mod limits;
mod load;
mod memo;
mod value;

pub use anchors::{is_combining, place_in_font, COMBINING_BLOCKS};
pub use designspace::load_designspace_text;
pub use diagnostic::{line_col, Diagnostic, Severity, Snippet, MAX_PER_FILE};
pub use geometry::{no_area, NoArea, FAR_EMS, FLAT_RELATIVE};
pub use glyph::{load_glyph_text, offsets_written};
pub use info::{check_tolerance_flag, load_info_text, DEFAULT_TOLERANCE, MIN_TOLERANCE};
pub use kerning::load_kerning_text;
pub use load::{
    load_family, load_family_with, load_font, load_sources, LoadedFont, SourceFile, SourceKind,
};
pub use memo::{delta_path as memo_delta_path, SourceMemo, MEMO_FILE};
