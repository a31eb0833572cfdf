//! SVG glyph set and SVG font.
