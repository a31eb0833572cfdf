//! Glyph sheets and text proofs (tiny-skia).
