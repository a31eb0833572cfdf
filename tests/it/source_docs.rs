//! `docs/format.md` stays true: its complete example loads without a diagnostic and is in
//! the canonical layout except for the keys it leaves to their defaults.

use std::path::Path;

use xglyph::source::{emit, load_font};

/// The `(file name, text)` pairs of the "A complete example" section: each code block
/// right after a line that is just `` `name`: `` or `` `name` (...): ``.
fn example_files(doc: &str) -> Vec<(String, String)> {
    let start = doc.find("## A complete example").expect("example section");
    let end = start + doc[start..].find("\n## What").expect("next section");
    let mut files = Vec::new();
    let mut lines = doc[start..end].lines();
    while let Some(line) = lines.next() {
        let Some(rest) = line.strip_prefix('`') else {
            continue;
        };
        let Some((name, _)) = rest.split_once('`') else {
            continue;
        };
        if !name.ends_with(".toml") || lines.next() != Some("```toml") {
            continue;
        }
        let body: Vec<&str> = lines.by_ref().take_while(|l| *l != "```").collect();
        files.push((name.to_string(), body.join("\n") + "\n"));
    }
    files
}

#[test]
fn complete_example_loads() {
    let doc = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/format.md"))
        .expect("docs/format.md");
    let files = example_files(&doc);
    let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "font.toml",
            "o.toml",
            "acutecomb.toml",
            "oacute.toml",
            "kerning.toml"
        ]
    );
    let dir = std::env::temp_dir().join(format!("xglyph-doc-example-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("mkdir");
    for (name, text) in &files {
        std::fs::write(dir.join(name), text).expect("write");
    }
    let result = load_font(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    let (font, warnings) = result.unwrap_or_else(|d| panic!("{d:#?}"));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(font.glyphs.len(), 3);
    assert_eq!(font.info.tolerance, 0.5);
    assert_eq!(font.kern("o", "oacute"), -10.0);
    assert_eq!(
        font.placed_contours(font.glyph("oacute").expect("oacute"))
            .len(),
        3
    );
    // Glyphs that spell out every key are already canonical.
    for (name, text) in &files[1..3] {
        let stem = name.trim_end_matches(".toml");
        assert_eq!(&emit::glyph_toml(font.glyph(stem).expect("glyph")), text);
    }
}
