//! Broken inputs to `xglyph import`: exact error messages, no panic, no partial output.
//!
//! Fonts: garbage, truncations of DejaVu Sans at many lengths, and deterministic byte
//! corruptions; each import either fails with a message naming the file or succeeds with
//! sources that load without errors. SVGs: truncated XML, no filled or stroked path, zero size, not
//! UTF-8. The command line: exit code 1, the message on stderr, nothing written.

use std::path::{Path, PathBuf};

use crate::common::cli::{import_fails, import_ok, xglyph};

use xglyph::import::font::parse_glyph_list;
use xglyph::import::{import_font, import_svgs, ImportOptions};
use xglyph::source::emit::font_sources;
use xglyph::source::load_font;

/// A copy of Debian fonts-dejavu-core 2.37 (license next to it), so the numbers are fixed.
const DEJAVU: &str = "tests/fixtures/import/DejaVuSans.ttf";
const FIXTURES: &str = "tests/fixtures/import";

fn dejavu() -> Vec<u8> {
    std::fs::read(DEJAVU).unwrap_or_else(|e| panic!("{DEJAVU} is needed (fonts-dejavu-core): {e}"))
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("xglyph-import-bad-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn small_list() -> ImportOptions {
    ImportOptions {
        glyphs: Some(parse_glyph_list("A,o,g").unwrap()),
        ..ImportOptions::default()
    }
}

/// Imports `data`; on success the sources must load back without errors.
fn import_checked(data: &[u8], label: &str, dir: &Path) -> Result<(), String> {
    let path = Path::new("broken.ttf");
    match import_font(path, data, &small_list()) {
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.starts_with("broken.ttf: "), "{label}: {msg}");
            Err(msg)
        }
        Ok(imp) => {
            let _ = std::fs::remove_dir_all(dir);
            std::fs::create_dir_all(dir).unwrap();
            for (name, text) in font_sources(&imp.font) {
                std::fs::write(dir.join(name), text).unwrap();
            }
            if let Err(diags) = load_font(dir) {
                panic!("{label}: imported sources do not load: {diags:?}");
            }
            Ok(())
        }
    }
}

#[test]
fn garbage_font_exact_message() {
    let err = import_font(Path::new("x.ttf"), b"hello", &ImportOptions::default()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "x.ttf: not a readable TrueType/OpenType font (unknown magic)"
    );
    let err = import_font(Path::new("e.otf"), b"", &ImportOptions::default()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "e.otf: not a readable TrueType/OpenType font (unknown magic)"
    );
}

#[test]
fn truncated_fonts_fail_cleanly() {
    let data = dejavu();
    let dir = temp_dir("trunc");
    let lengths = [4, 12, 100, 1000, 2000, 10_000, 100_000, data.len() / 2];
    for len in lengths {
        // The tables DejaVu needs (head, hhea, maxp, cmap, glyf) are not all inside any of
        // these prefixes, so every one is an error, not a silent empty font.
        assert!(
            import_checked(&data[..len], &format!("truncated to {len}"), &dir).is_err(),
            "truncated to {len}"
        );
    }
    // Without its last byte (inside a table the import does not read) the font imports.
    assert_eq!(
        import_checked(&data[..data.len() - 1], "last byte", &dir),
        Ok(())
    );
    let msg = import_checked(&data[..2000], "2000", &dir).unwrap_err();
    assert_eq!(
        msg,
        "broken.ttf: not a readable TrueType/OpenType font (the head table is missing or malformed)"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn corrupted_fonts_never_panic() {
    let data = dejavu();
    let dir = temp_dir("corrupt");
    // A fixed linear congruential sequence: the same corruptions every run.
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 33) as usize
    };
    let (mut ok, mut err) = (0, 0);
    for round in 0..24 {
        let mut bytes = data.clone();
        // Corrupt the table directory and headers in some rounds, the body in others.
        let span = if round % 2 == 0 { 4096 } else { bytes.len() };
        for _ in 0..8 {
            let at = next() % span;
            bytes[at] = (next() & 0xFF) as u8;
        }
        match import_checked(&bytes, &format!("round {round}"), &dir) {
            Ok(()) => ok += 1,
            Err(_) => err += 1,
        }
    }
    assert_eq!(ok + err, 24);
    eprintln!("corrupted fonts: {ok} imported, {err} refused");
    let _ = std::fs::remove_dir_all(&dir);
}

fn svg_error(name: &str, data: &[u8]) -> String {
    let files = vec![(Path::new(FIXTURES).join(name), data.to_vec())];
    import_svgs(&files, &ImportOptions::default())
        .unwrap_err()
        .to_string()
}

fn fixture(name: &str) -> Vec<u8> {
    std::fs::read(Path::new(FIXTURES).join(name)).unwrap()
}

#[test]
fn broken_svgs_exact_messages() {
    assert_eq!(
        svg_error("truncated.svg", &fixture("truncated.svg")),
        "tests/fixtures/import/truncated.svg: not a readable SVG drawing (SVG data parsing \
         failed cause the root node was opened but never closed)"
    );
    assert_eq!(
        svg_error("nofill.svg", &fixture("nofill.svg")),
        "tests/fixtures/import/nofill.svg: the drawing has no filled or stroked path (text and \
         images are not imported)"
    );
    assert_eq!(
        svg_error(
            "zero.svg",
            br#"<svg xmlns="http://www.w3.org/2000/svg" width="0" height="0"/>"#
        ),
        "tests/fixtures/import/zero.svg: not a readable SVG drawing (SVG has an invalid size)"
    );
    assert_eq!(
        svg_error("latin1.svg", b"<svg>\xff\xfe</svg>"),
        "tests/fixtures/import/latin1.svg: not a readable SVG drawing (provided data has not \
         an UTF-8 encoding)"
    );
    let tag = svg_error(
        "tag.svg",
        b"<svg xmlns=\"http://www.w3.org/2000/svg\">\n  <path d=\"M0 0\"></g>\n</svg>",
    );
    assert!(tag.starts_with("tests/fixtures/import/tag.svg: not a readable SVG drawing (SVG data parsing failed cause "), "{tag}");
    assert!(tag.contains("2:"), "the XML error names its line: {tag}");
    // Every prefix of a good drawing: an error or a glyph, never a panic.
    let good = fixture("drop.svg");
    for len in (0..good.len()).step_by(7) {
        let files = vec![(PathBuf::from("drop.svg"), good[..len].to_vec())];
        if let Err(e) = import_svgs(&files, &ImportOptions::default()) {
            assert!(e.to_string().starts_with("drop.svg: "), "{e}");
        }
    }
}

#[test]
fn svg_name_and_code_point_conflicts() {
    let ring = fixture("ring.svg");
    let files = vec![
        (PathBuf::from("a/ring.svg"), ring.clone()),
        (PathBuf::from("b/ring.svg"), ring.clone()),
    ];
    assert_eq!(
        import_svgs(&files, &ImportOptions::default())
            .unwrap_err()
            .to_string(),
        "b/ring.svg: two drawings would both become glyph `ring`; rename one file"
    );
    let mut opts = ImportOptions::default();
    opts.codepoints.insert("house".into(), 'h');
    let files = vec![(PathBuf::from("ring.svg"), ring)];
    assert_eq!(
        import_svgs(&files, &opts).unwrap_err().to_string(),
        "the code point map names `house`, but no drawing has that file name"
    );
}

#[test]
fn command_line_errors_write_nothing() {
    let dir = temp_dir("cli");
    let out = dir.join("out");
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.ttf");
    std::fs::write(&bad, b"not a font at all").unwrap();
    let ring = format!("{FIXTURES}/ring.svg");
    // Each refused with exit code 1, its message on stderr and nothing written.
    let refused: [(&[&str], String); 4] = [
        (
            &[bad.to_str().unwrap()],
            format!(
                "error: {}: not a readable TrueType/OpenType font (unknown magic)\n",
                bad.display()
            ),
        ),
        (
            &[DEJAVU, &ring],
            "error: import one font at a time, and fonts and SVG drawings separately\n".into(),
        ),
        (
            &[DEJAVU, "--glyphs", "Z-A"],
            "error: glyph list: range `Z-A` runs backwards (write `A-Z`)\n".into(),
        ),
        (
            &["notes.txt"],
            "error: notes.txt: unknown input type; expected a font (.ttf, .otf, .ttc, .otc, \
             .woff, .woff2), a .svg or .designspace file or a .ufo folder\n"
                .into(),
        ),
    ];
    for (args, message) in refused {
        assert_eq!(import_fails(args, &out), message, "import {args:?}");
    }

    // A good import, then the same into the now non-empty directory: refused, untouched.
    let stdout = import_ok(&[&ring], &out);
    assert!(
        stdout.starts_with("glyph  original   xspline  max error\nring         24        16  "),
        "{stdout}"
    );
    assert!(
        stdout.ends_with(&format!("wrote 2 files to {}\n", out.display())),
        "{stdout}"
    );
    let before = std::fs::read(out.join("ring.toml")).unwrap();
    assert_eq!(
        import_fails(&[&ring, "--tolerance", "5"], &out),
        format!(
            "error: {}: the output directory is not empty; choose another or pass --force\n",
            out.display()
        )
    );
    assert_eq!(std::fs::read(out.join("ring.toml")).unwrap(), before);
    let (code, stdout, _) = xglyph(&["check", out.to_str().unwrap()]);
    assert_eq!((code, stdout.as_str()), (0, "0 errors, 0 warnings\n"));
    import_ok(&[&ring, "--tolerance", "5", "--force"], &out);
    assert_ne!(std::fs::read(out.join("ring.toml")).unwrap(), before);
    assert_eq!(
        import_fails(&[&ring, "--tolerance=-1"], &dir.join("o2")),
        "error: --tolerance must be a number of at least 0.0001 font units, got -1\n"
    );
    let map = dir.join("map.toml");
    let with_map = [ring.as_str(), "--codepoints", map.to_str().unwrap()];
    std::fs::write(&map, "ring = 0xE001\nhouse = [1, 2]\n").unwrap();
    assert_eq!(
        import_fails(&with_map, &dir.join("o3")),
        format!(
            "error: {}: `house`: expected a code point (0xE001) or one character (\"h\")\n",
            map.display()
        )
    );
    std::fs::write(&map, "ring = 0xE001\nhouse = \n").unwrap();
    let err = import_fails(&with_map, &dir.join("o3"));
    assert!(
        err.starts_with(&format!("error: {}:2:9: invalid TOML: ", map.display())),
        "{err}"
    );
    assert!(!dir.join("o3").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Found by the `import_svg` fuzz target: a path that runs far outside its viewBox scales
/// to X-spline points beyond what the sources hold; the import is refused (before, it wrote
/// sources that `check` then rejected).
#[test]
fn drawings_beyond_the_source_limits_are_refused() {
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 64 48">
  <path d="M3220 13 0 0 1 12 32 C 12 22 32 2 32 2 Z"/></svg>"#;
    let files = vec![(PathBuf::from("far.svg"), svg.as_bytes().to_vec())];
    let err = import_svgs(&files, &ImportOptions::default()).unwrap_err();
    let text = err.to_string();
    assert!(
        text.starts_with("far.svg: glyph `far` needs a control point at "),
        "{text}"
    );
    assert!(
        text.ends_with(
            "outside the -16384..16384 font units xglyph sources hold; scale the drawing down"
        ),
        "{text}"
    );
}
