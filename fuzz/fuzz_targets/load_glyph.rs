//! Any bytes as a glyph file: the loader never panics, and whatever loads survives the
//! canonical writer unchanged (load -> emit -> load gives the same glyph).
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use xglyph::source::{emit, load_glyph_text};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = Path::new("fuzz.toml");
    if let Ok((glyph, _)) = load_glyph_text(path, text) {
        let again = load_glyph_text(path, &emit::glyph_toml(&glyph));
        assert_eq!(again.map(|(g, _)| g).as_ref(), Ok(&glyph));
    }
});
