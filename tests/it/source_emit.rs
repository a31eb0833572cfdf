//! The canonical writer is the loader's inverse: load -> emit -> load gives the same model.

use std::path::Path;

use xglyph::source::{emit, load_font};

fn round_trip(dir: &Path) {
    let (font, _) = load_font(dir).unwrap_or_else(|d| panic!("fixture has errors: {d:?}"));
    let tmp = std::env::temp_dir().join(format!(
        "xglyph-emit-{}-{}",
        std::process::id(),
        dir.file_name().unwrap_or_default().to_string_lossy()
    ));
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let files = emit::font_sources(&font);
    for (name, text) in &files {
        std::fs::write(tmp.join(name), text).unwrap();
    }
    let (again, warnings) = load_font(&tmp).unwrap_or_else(|d| panic!("emitted has errors: {d:?}"));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(again, font);
    // Emitting the re-loaded model gives the same bytes.
    assert_eq!(emit::font_sources(&again), files);
    std::fs::remove_dir_all(&tmp).unwrap();
}

#[test]
fn mini_round_trips() {
    round_trip(Path::new("tests/fixtures/mini"));
}

#[test]
fn glyph_layout_is_canonical() {
    let (font, _) = load_font(Path::new("tests/fixtures/mini")).unwrap();
    let oacute = font.glyph("oacute").unwrap();
    assert_eq!(
        emit::glyph_toml(oacute),
        "name = \"oacute\"\nunicode = 0x00F3\nadvance = 560\n\n[[component]]\nbase = \"o\"\noffset = [0, 0]\n\n[[component]]\nbase = \"acutecomb\"\noffset = [0, 0]\n"
    );
    let period = font.glyph("period").unwrap();
    assert_eq!(
        emit::glyph_toml(period),
        "name = \"period\"\nunicode = 0x002E\nadvance = 260\n\n[[contour]]\npoints = [\n  [130, -10, 1],\n  [200, 60, 1],\n  [130, 130, 1],\n  [60, 60, 1],\n]\n"
    );
    let names: Vec<_> = emit::font_sources(&font)
        .into_iter()
        .map(|(n, _)| n)
        .collect();
    assert_eq!(
        names,
        [
            "font.toml",
            "_notdef.toml",
            "A_.toml",
            "V_.toml",
            "acutecomb.toml",
            "o.toml",
            "oacute.toml",
            "period.toml",
            "space.toml",
            "kerning.toml"
        ]
    );
}
