//! xglyph: a vector font outline designer built on X-splines.
//!
//! The modules follow the pipeline, one direction:
//!
//! ```text
//! source (TOML text) -> model (typed Font, validated X-splines)
//!     -> outline: xspline -> fit + orient + extrema, per glyph -> OutlinedFont (the one IR)
//!     -> render (PNG) | svg (glyph set, SVG font) | otf (TTF/OTF, specimen)
//! pipeline: the steps above as calls that return data (the CLI prints them)
//! import: existing outlines -> X-spline sources
//! ```
//!
//! The usual entry points are re-exported here: [`pipeline::load`] a font directory into an
//! [`OutlinedFont`], then hand it to any backend, or to [`pipeline::outputs`] for every
//! build output at once. The curve core ([`xspline`], [`fit`], [`flatten`], [`orient`])
//! works on its own; `power` holds the cubic in power form that both fitters project onto.

#![warn(missing_docs)]

pub mod cache;
#[doc(hidden)]
pub mod cli;
#[doc(hidden)]
pub mod commands;
pub mod compatible;
pub mod designspace;
pub mod extrema;
pub mod family;
pub mod fit;
pub mod flatten;
pub mod import;
pub mod instance;
pub mod layout;
pub mod model;
mod names;
pub mod orient;
pub mod otf;
pub mod outline;
pub mod overlap;
pub mod pipeline;
mod power;
mod record;
pub mod render;
pub mod reuse;
pub mod serve;
pub mod source;
pub mod svg;
pub mod terminal;
pub mod ufo;
pub mod write;
pub mod xspline;

pub use model::{Anchor, Component, Contour, FeatureFile, Font, FontInfo, Glyph, KernPair};
pub use outline::{
    outline_font, outline_font_with, outline_glyph, OutlineOptions, OutlinedFont, OutlinedGlyph,
    PlacedContour, Progress,
};
pub use pipeline::{BuildOptions, Loaded, PipelineError, Summary};
pub use source::{load_font, Diagnostic, Severity};
pub use xspline::{ControlPoint, XSpline, XSplineError};
