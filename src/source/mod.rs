//! Sources: TOML text -> typed [`crate::model::Font`], with spans and diagnostics; and the
//! canonical text back ([`emit`]) for `fmt` and `import`.

pub mod emit;
mod load;

pub use load::{line_col, load_font, Diagnostic, Severity};
