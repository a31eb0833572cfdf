//! Any bytes as `font.toml`: the loader never panics, and whatever loads survives the
//! canonical writer unchanged.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use xglyph::source::{emit, load_info_text};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = Path::new("font.toml");
    if let Ok((info, _)) = load_info_text(path, text) {
        let again = load_info_text(path, &emit::font_toml(&info));
        assert_eq!(again.map(|(i, _)| i).as_ref(), Ok(&info));
    }
});
