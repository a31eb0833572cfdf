//! Sources: TOML text -> typed [`crate::model::Font`], with spans and diagnostics.

mod load;

pub use load::{line_col, load_font, Diagnostic, Severity};
