//! xglyph: a vector font outline designer built on X-splines.
//!
//! The modules follow the pipeline, one direction:
//!
//! ```text
//! source (TOML text) -> model (typed Font) -> xspline (exact curves)
//!     -> fit + orient (BezPath within tolerance) -> outline (per glyph)
//!     -> render (PNG) | svg (glyph set, SVG font) | otf (TTF/OTF)
//! import: existing outlines -> X-spline sources
//! ```

pub mod cli;
pub mod commands;
pub mod fit;
pub mod flatten;
pub mod import;
pub mod layout;
pub mod model;
pub mod names;
pub mod orient;
pub mod otf;
pub mod outline;
pub mod render;
pub mod serve;
pub mod source;
pub mod svg;
pub mod terminal;
pub mod write;
pub mod xspline;
