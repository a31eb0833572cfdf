//! A large font's WOFF2, which xglyph compresses in slices joined into one Brotli stream and
//! wraps in a container of its own (`src/otf/woff2.rs`): real decoders must read it. OTS
//! must accept it, and fontTools must decode it to the TTF's own tables, byte for byte.
//! Needs pip `fonttools`, `brotli` and `opentype-sanitizer`; skips without them unless
//! `XGLYPH_REQUIRE_TOOLS=1`.

use std::path::Path;

use kurbo::{Affine, Vec2};
use xglyph::otf::{ttf, woff2_from_ttf, LARGE_SFNT};
use xglyph::outline::outline_font;
use xglyph::source::load_font;

use crate::common::tools::{available, python_imports, python_json};

/// Copies of the bundled glyphs: enough for a TTF over [`LARGE_SFNT`] (39 made 1.04 MB).
const COPIES: u32 = 50;

/// Reads both files; OTS on the WOFF2; each TTF table against the WOFF2's.
const CHECK: &str = r#"
import json, sys, ots
from fontTools.ttLib import TTFont
ttf_path, woff2_path, clean = sys.argv[1:4]
run = ots.sanitize(woff2_path, clean, capture_output=True)
ttf, woff2 = TTFont(ttf_path), TTFont(woff2_path)
print(json.dumps({
    "ots": run.returncode,
    "ots_says": (run.stdout + run.stderr).decode(errors="replace"),
    "flavor": woff2.flavor,
    "ttf_tags": sorted(ttf.reader.keys()),
    "woff2_tags": sorted(woff2.reader.keys()),
    "differ": sorted(t for t in ttf.reader.keys() if ttf.reader[t] != woff2.reader[t]),
    "glyphs": len(woff2.getGlyphOrder()),
    "cmap": len(woff2.getBestCmap()),
}))
"#;

#[derive(serde::Deserialize)]
struct Check {
    ots: i32,
    ots_says: String,
    flavor: String,
    ttf_tags: Vec<String>,
    woff2_tags: Vec<String>,
    differ: Vec<String>,
    glyphs: usize,
    cmap: usize,
}

#[test]
fn a_large_fonts_sliced_woff2_is_read_by_ots_and_fonttools() {
    if !available(
        python_imports("fontTools, brotli, ots"),
        "python fontTools, brotli or ots",
        "pip install fonttools brotli opentype-sanitizer",
    ) {
        return;
    }
    // The bundled Regular, its glyphs copied [`COPIES`] times, each copy shifted (so that no two
    // glyphs are the same bytes) and mapped into Supplementary Private Use Area-A: about 8,000 glyphs.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let font = load_font(&dir).expect("the bundled typeface loads").0;
    let mut outlined = outline_font(&font, font.info.tolerance);
    let originals: Vec<_> = outlined
        .glyphs
        .iter()
        .filter(|g| g.name != ".notdef")
        .cloned()
        .collect();
    let mut pua = 0xF_0000u32;
    for copy in 1..=COPIES {
        for g in &originals {
            let mut g = g.clone();
            g.name = format!("{}.copy{copy}", g.name);
            g.unicodes = vec![char::from_u32(pua).expect("a PUA code point")];
            pua += 1;
            g.path
                .apply_affine(Affine::translate(Vec2::new(copy as f64, 2.0 * copy as f64)));
            g.components.clear();
            outlined.glyphs.push(g);
        }
    }
    outlined.kerning.clear();
    let glyphs = outlined.glyphs.len();
    let ttf_bytes = ttf(&outlined).expect("the TTF builds");
    assert!(
        ttf_bytes.len() > LARGE_SFNT,
        "the test font must be over {LARGE_SFNT} bytes to be sliced: {}",
        ttf_bytes.len()
    );
    let woff2_bytes = woff2_from_ttf(&ttf_bytes).expect("the WOFF2 builds");
    // The same bytes again (slices on every core, joined in one order).
    assert_eq!(woff2_from_ttf(&ttf_bytes).expect("again"), woff2_bytes);

    let tmp = tempfile::tempdir().expect("a temporary folder");
    let (ttf_path, woff2_path) = (tmp.path().join("big.ttf"), tmp.path().join("big.woff2"));
    std::fs::write(&ttf_path, &ttf_bytes).expect("write the TTF");
    std::fs::write(&woff2_path, &woff2_bytes).expect("write the WOFF2");
    let check: Check = python_json(
        CHECK,
        &[&ttf_path, &woff2_path, &tmp.path().join("clean.ttf")],
    );
    assert_eq!(check.ots, 0, "OTS rejects the WOFF2: {}", check.ots_says);
    assert!(
        !check.ots_says.contains("Dropping"),
        "OTS drops a table: {}",
        check.ots_says
    );
    assert_eq!(check.flavor, "woff2");
    assert_eq!(check.woff2_tags, check.ttf_tags);
    assert!(check.ttf_tags.iter().any(|t| t == "glyf"));
    assert_eq!(
        check.differ,
        Vec::<String>::new(),
        "tables that decode differently"
    );
    assert_eq!(check.glyphs, glyphs);
    assert!(
        check.cmap >= COPIES as usize * originals.len(),
        "{} mapped",
        check.cmap
    );
}
