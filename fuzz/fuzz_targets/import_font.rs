//! Any bytes as a font file for `xglyph import`: the importer never panics, and whatever
//! imports is a valid font model (every contour a valid X-spline, one report row per
//! glyph) that the canonical writer emits and the loader reads back.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use xglyph::import::{import_font, ImportOptions};

fuzz_target!(|data: &[u8]| {
    // A few characters, so a large damaged cmap does not turn each run into a long fit.
    let opts = ImportOptions {
        glyphs: Some("AHOaos一丁".chars().collect()),
        ..ImportOptions::default()
    };
    if let Ok(imported) = import_font(Path::new("fuzz.ttf"), data, &opts) {
        common::check(&imported);
    }
});

#[path = "common.rs"]
mod common;
