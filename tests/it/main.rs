//! The integration tests, one binary (one link instead of one per file).
//!
//! Each module tests one area; `common` holds the shared checkers and corpora.

mod common;

mod anchors;
mod axis_map;
mod build;
mod cache;
mod compatible;
mod corners;
mod designspace;
mod discrete_import;
mod extrema;
mod features;
mod fit;
mod fit_count;
mod flatten;
mod grid_extrema;
mod import_bound;
mod import_font;
mod import_malformed;
mod import_output;
mod import_points;
mod import_svg;
mod import_variable;
mod ir;
mod labels;
mod limits;
mod mark_outline;
mod masters;
mod ocr;
mod otf;
mod otf_random;
mod overlap;
mod production;
mod render;
mod reuse;
mod rules;
mod scale;
mod serve;
mod shaping;
mod source_docs;
mod source_emit;
mod source_fmt;
mod source_malformed;
mod sparse;
mod sparse_import;
mod spikes;
mod studio_browser;
mod svg;
mod terminal;
mod ufo;
mod variable;
mod woff2;
mod writes;
mod xspline;
