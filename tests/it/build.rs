//! `xglyph build` end to end: the file list and summary, byte-identical rebuilds, and a
//! failing build that prints file:line:col and writes nothing.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn mini_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini")
}

/// A fresh, empty scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("build-{name}"));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn xglyph(args: &[&Path]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(args)
        .output()
        .expect("xglyph runs")
}

fn build(font_dir: &Path, out: &Path) -> Output {
    xglyph(&[Path::new("build"), font_dir, Path::new("-o"), out])
}

/// Every file under `dir`, by relative path (forward slashes), with its bytes.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<String, Vec<u8>>) {
        for entry in fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(root, &path, out);
            } else {
                let rel = path.strip_prefix(root).unwrap();
                let rel: Vec<String> = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                out.insert(rel.join("/"), fs::read(&path).unwrap());
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

#[test]
fn build_writes_every_output_and_a_summary() {
    let tmp = scratch("ok");
    let out = tmp.join("out");
    let result = build(&mini_dir(), &out);
    let stdout = String::from_utf8_lossy(&result.stdout);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(0), "{stdout}\n{stderr}");
    assert_eq!(stderr, "");
    let written = files(&out);
    let names: Vec<&str> = written.keys().map(String::as_str).collect();
    assert_eq!(
        names,
        [
            // The fit cache (src/cache.rs): not an output, not counted in the summary.
            ".xglyph-cache",
            // What a rebuild may reuse (src/reuse.rs): not an output either.
            ".xglyph-outputs",
            // The glyph files as loaded (src/source/memo.rs): nor this.
            ".xglyph-sources",
            "MiniTest-Regular.otf",
            "MiniTest-Regular.svg",
            "MiniTest-Regular.ttf",
            "MiniTest-Regular.ufo/fontinfo.plist",
            "MiniTest-Regular.ufo/glyphs/A_.glif",
            "MiniTest-Regular.ufo/glyphs/V_.glif",
            "MiniTest-Regular.ufo/glyphs/_notdef.glif",
            "MiniTest-Regular.ufo/glyphs/acutecomb.glif",
            "MiniTest-Regular.ufo/glyphs/contents.plist",
            "MiniTest-Regular.ufo/glyphs/o.glif",
            "MiniTest-Regular.ufo/glyphs/oacute.glif",
            "MiniTest-Regular.ufo/glyphs/period.glif",
            "MiniTest-Regular.ufo/glyphs/space.glif",
            "MiniTest-Regular.ufo/kerning.plist",
            "MiniTest-Regular.ufo/layercontents.plist",
            "MiniTest-Regular.ufo/lib.plist",
            "MiniTest-Regular.ufo/metainfo.plist",
            "MiniTest-Regular.woff2",
            "proof.png",
            "sheet.png",
            "specimen.html",
            "svg/A_.svg",
            "svg/V_.svg",
            "svg/_notdef.svg",
            "svg/acutecomb.svg",
            "svg/o.svg",
            "svg/oacute.svg",
            "svg/period.svg",
            "svg/space.svg",
        ]
    );
    // No temporary files left behind by the atomic writes.
    assert!(names.iter().all(|n| !n.contains(".tmp")));
    let expected = format!(
        "built Mini Test Regular: 8 glyphs, 12 contours, 82 segments\n\
         worst error against the X-splines: 0.473 font units (glyph `period`), tolerance 0.5\n\
         wrote 29 files to {}: MiniTest-Regular.svg, sheet.png, proof.png, MiniTest-Regular.ttf, MiniTest-Regular.otf, MiniTest-Regular.woff2, specimen.html, MiniTest-Regular.ufo/ (14 files), svg/ (8 glyph SVGs)\n",
        out.display()
    );
    assert_eq!(stdout, expected);
    // The PNGs are real images of the expected size (sheet: 8 cells of 160 px in one row).
    let sheet = tiny_skia::Pixmap::decode_png(&written["sheet.png"]).unwrap();
    assert_eq!((sheet.width(), sheet.height()), (1280, 160));
    let proof = tiny_skia::Pixmap::decode_png(&written["proof.png"]).unwrap();
    // As wide as the longest line at 72 px: "AV Vo" is 2560 units = 184.32 px, plus 2 x 16.
    assert_eq!(proof.width(), 217);
}

#[test]
fn tolerance_flag_overrides_font_toml() {
    let tmp = scratch("tolerance");
    let out = tmp.join("out");
    let result = xglyph(&[
        Path::new("build"),
        &mini_dir(),
        Path::new("-o"),
        &out,
        Path::new("--tolerance"),
        Path::new("0.05"),
    ]);
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert_eq!(result.status.code(), Some(0));
    let second = stdout.lines().nth(1).unwrap();
    assert!(second.ends_with(", tolerance 0.05"), "{second}");
    let worst: f64 = second
        .split("X-splines: ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap();
    assert!(worst <= 0.05, "{worst}");

    // Negative, or finer than any grid (refused up front rather than fitted with a
    // million cubics): an error, nothing written.
    for (flag, shown) in [
        ("--tolerance=-1", "-1"),
        ("--tolerance=1e-9", "0.000000001"),
    ] {
        let out = tmp.join("bad");
        let bad = xglyph(&[
            Path::new("build"),
            &mini_dir(),
            Path::new("-o"),
            &out,
            Path::new(flag),
        ]);
        assert_eq!(bad.status.code(), Some(1));
        assert_eq!(
            String::from_utf8_lossy(&bad.stderr),
            format!(
                "error: --tolerance must be a number of at least 0.0001 font units, got {shown}\n"
            )
        );
        assert!(!out.exists());
    }
}

#[test]
fn two_builds_are_byte_identical() {
    let tmp = scratch("twice");
    let (a, b) = (tmp.join("a"), tmp.join("b"));
    assert_eq!(build(&mini_dir(), &a).status.code(), Some(0));
    assert_eq!(build(&mini_dir(), &b).status.code(), Some(0));
    let (fa, fb) = (files(&a), files(&b));
    // 29 outputs (WOFF2 and the 14 files of the UFO included), the fit cache, the reuse
    // record and the source memo.
    assert_eq!(fa.len(), 32);
    assert_eq!(fa.keys().collect::<Vec<_>>(), fb.keys().collect::<Vec<_>>());
    for (name, bytes) in &fa {
        // The record stamps each output with its inode and times, which differ.
        if name == xglyph::reuse::REUSE_FILE {
            continue;
        }
        assert!(bytes == &fb[name], "{name} differs between builds");
    }
}

#[test]
fn a_failing_build_reports_the_place_and_writes_nothing() {
    let tmp = scratch("broken");
    let font_dir = tmp.join("font");
    fs::create_dir_all(&font_dir).unwrap();
    for entry in fs::read_dir(mini_dir()).unwrap() {
        let path = entry.unwrap().path();
        fs::copy(&path, font_dir.join(path.file_name().unwrap())).unwrap();
    }
    let a = font_dir.join("A_.toml");
    let text = fs::read_to_string(&a).unwrap();
    fs::write(&a, text.replace("advance = 640", "advance = \"wide\"")).unwrap();
    let out = tmp.join("out");
    let result = build(&font_dir, &out);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(1), "{stderr}");
    assert_eq!(String::from_utf8_lossy(&result.stdout), "");
    let first = stderr.lines().next().unwrap();
    assert_eq!(
        first,
        format!(
            "{}:3:11: error: `advance` must be a number, found string",
            a.display()
        )
    );
    assert!(
        stderr.contains("  | advance = \"wide\"\n  |           ^\n"),
        "{stderr}"
    );
    assert!(
        stderr.ends_with(&format!(
            "error: 1 error in {}; nothing was written\n",
            font_dir.display()
        )),
        "{stderr}"
    );
    assert!(!out.exists(), "a failed build created {}", out.display());
    // The sources are untouched.
    assert!(fs::read_to_string(&a)
        .unwrap()
        .contains("advance = \"wide\""));
}

#[test]
fn a_font_without_glyphs_gets_a_clear_message() {
    let tmp = scratch("empty");
    let font_dir = tmp.join("font");
    fs::create_dir_all(&font_dir).unwrap();
    fs::copy(mini_dir().join("font.toml"), font_dir.join("font.toml")).unwrap();
    let out = tmp.join("out");
    let result = build(&font_dir, &out);
    assert_eq!(result.status.code(), Some(1));
    assert_eq!(
        String::from_utf8_lossy(&result.stderr),
        format!(
            "error: {} has no glyph files yet (only font.toml); add one TOML file per glyph\n",
            font_dir.display()
        )
    );
    assert!(!out.exists());
}

#[test]
fn render_and_svg_write_their_outputs_only() {
    let tmp = scratch("single");
    let svg_out = tmp.join("svg-out");
    let result = xglyph(&[Path::new("svg"), &mini_dir(), Path::new("-o"), &svg_out]);
    assert_eq!(result.status.code(), Some(0));
    let names: Vec<String> = files(&svg_out).into_keys().collect();
    // The fit cache and the source memo for the next run (as `build` keeps them), then the
    // outputs.
    assert_eq!(names.len(), 11);
    assert_eq!(names[..2], [".xglyph-cache", ".xglyph-sources"]);
    assert_eq!(names[2], "MiniTest-Regular.svg");
    assert!(names[3..].iter().all(|n| n.starts_with("svg/")));

    let png_out = tmp.join("png-out");
    let result = xglyph(&[
        Path::new("render"),
        &mini_dir(),
        Path::new("-o"),
        &png_out,
        Path::new("--overlay"),
        Path::new("--cell"),
        Path::new("64"),
        Path::new("--columns"),
        Path::new("3"),
    ]);
    assert_eq!(result.status.code(), Some(0));
    let written = files(&png_out);
    // The fit cache and the source memo for the next run, as `svg` keeps them.
    assert_eq!(
        written.keys().collect::<Vec<_>>(),
        [
            ".xglyph-cache",
            ".xglyph-sources",
            "proof.png",
            "sheet-overlay.png"
        ]
    );
    let sheet = tiny_skia::Pixmap::decode_png(&written["sheet-overlay.png"]).unwrap();
    // 8 glyphs in rows of 3: 3 x 3 cells of 64 px.
    assert_eq!((sheet.width(), sheet.height()), (192, 192));

    let help = xglyph(&[Path::new("build"), Path::new("--help")]);
    let help = String::from_utf8_lossy(&help.stdout);
    assert!(help.contains("Examples:\n  xglyph build "), "{help}");
}
