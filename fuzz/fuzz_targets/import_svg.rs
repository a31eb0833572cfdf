//! Any bytes as an SVG drawing for `xglyph import`: the importer never panics, and
//! whatever imports is a valid font model (see `common.rs`).
#![no_main]

use std::path::PathBuf;

use libfuzzer_sys::fuzz_target;
use xglyph::import::{import_svgs, ImportOptions};

fuzz_target!(|data: &[u8]| {
    let files = [(PathBuf::from("glyph.svg"), data.to_vec())];
    if let Ok(imported) = import_svgs(&files, &ImportOptions::default()) {
        common::check(&imported);
    }
});

#[path = "common.rs"]
mod common;
