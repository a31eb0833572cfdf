//! Sources: TOML text -> typed [`crate::model::Font`], with spans and diagnostics.
