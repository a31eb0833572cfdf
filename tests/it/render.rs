//! Reference-image tests for the glyph sheet and the text proof (tests/fixtures/mini).
//!
//! Each image is compared with `tests/reference/<name>.png`. A pixel differs when any
//! channel differs by more than `CHANNEL_SLACK` (room for float rounding across platforms);
//! the test fails on the first differing pixel and writes `<name>-actual.png` and
//! `<name>-diff.png` (differing pixels red over a faded copy) to the target tmp dir.
//! `XGLYPH_BLESS=1 cargo test --test it render` regenerates the references.

use std::path::{Path, PathBuf};

use tiny_skia::Pixmap;
use xglyph::layout::Layout;
use xglyph::model::Font;
use xglyph::outline::{outline_font, OutlinedFont};
use xglyph::render::{
    default_text, encode_png, render_proof, render_sheet, sheet_order, ProofOptions, RenderError,
    SheetOptions,
};
use xglyph::source::load_font;

/// Largest per-channel difference that still counts as the same pixel.
const CHANNEL_SLACK: u8 = 2;

fn mini() -> (Font, OutlinedFont) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini");
    let (font, warnings) = load_font(&dir).expect("mini loads");
    assert!(warnings.is_empty(), "{warnings:?}");
    let outlines = outline_font(&font, font.info.tolerance);
    (font, outlines)
}

fn reference_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/reference")
        .join(format!("{name}.png"))
}

/// Number of pixels differing by more than `CHANNEL_SLACK` in some channel, and a diff image.
fn diff(actual: &Pixmap, expected: &Pixmap) -> (usize, Pixmap) {
    let mut img = actual.clone();
    let mut count = 0;
    let pairs = actual.pixels().iter().zip(expected.pixels());
    for (out, (a, e)) in img.pixels_mut().iter_mut().zip(pairs) {
        let channels = [
            (a.red(), e.red()),
            (a.green(), e.green()),
            (a.blue(), e.blue()),
            (a.alpha(), e.alpha()),
        ];
        let differs = channels.iter().any(|&(x, y)| x.abs_diff(y) > CHANNEL_SLACK);
        *out = if differs {
            count += 1;
            tiny_skia::PremultipliedColorU8::from_rgba(255, 0, 0, 255).unwrap()
        } else {
            // Fade the image so the red stands out.
            let f = |c: u8| 192 + c / 4;
            tiny_skia::PremultipliedColorU8::from_rgba(f(a.red()), f(a.green()), f(a.blue()), 255)
                .unwrap()
        };
    }
    (count, img)
}

fn check_reference(name: &str, actual: &Pixmap) {
    let path = reference_path(name);
    if std::env::var("XGLYPH_BLESS").as_deref() == Ok("1") {
        std::fs::write(&path, encode_png(actual).unwrap()).unwrap();
        return;
    }
    let expected = Pixmap::load_png(&path).unwrap_or_else(|e| {
        panic!(
            "cannot read {} ({e}); run with XGLYPH_BLESS=1 to create it",
            path.display()
        )
    });
    assert_eq!(
        (actual.width(), actual.height()),
        (expected.width(), expected.height()),
        "{name}: image size differs from the reference"
    );
    let (count, img) = diff(actual, &expected);
    if count > 0 {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
        let actual_path = dir.join(format!("{name}-actual.png"));
        let diff_path = dir.join(format!("{name}-diff.png"));
        std::fs::write(&actual_path, encode_png(actual).unwrap()).unwrap();
        std::fs::write(&diff_path, encode_png(&img).unwrap()).unwrap();
        panic!(
            "{name}: {count} pixels differ from {} (diff: {}, actual: {})",
            path.display(),
            diff_path.display(),
            actual_path.display()
        );
    }
}

/// The sheet of `outlines` in cells of `cell_px` and `columns` columns.
fn sheet(
    outlines: &OutlinedFont,
    cell_px: u32,
    columns: u32,
    overlay: bool,
) -> Result<Pixmap, RenderError> {
    let opts = SheetOptions {
        cell_px,
        columns,
        overlay,
    };
    render_sheet(outlines, &opts)
}

/// Renders mini's sheet at `cell_px` in four columns, checks its size and compares it with
/// the reference `name`.
fn check_sheet(name: &str, cell_px: u32, overlay: bool, size: (u32, u32)) {
    let (_, outlines) = mini();
    let img = sheet(&outlines, cell_px, 4, overlay).unwrap();
    assert_eq!((img.width(), img.height()), size, "{name}");
    check_reference(name, &img);
}

/// Renders mini's proof of `text` (the default text for `None`) at `sizes`, 200 px wide, and
/// compares it with the reference `name`.
fn check_proof(name: &str, text: Option<&str>, sizes: &[f64]) {
    let (_, outlines) = mini();
    let opts = ProofOptions {
        text: text.map(str::to_owned),
        sizes: sizes.to_vec(),
        width_px: 200,
    };
    let img = render_proof(&outlines, &opts).unwrap();
    check_reference(name, &img);
}

#[test]
fn sheet_matches_reference() {
    check_sheet("sheet", 96, false, (384, 192));
}

#[test]
fn overlay_sheet_matches_reference() {
    check_sheet("sheet-overlay", 128, true, (512, 256));
}

#[test]
fn proof_matches_reference() {
    check_proof("proof", None, &[12.0, 20.0, 36.0]);
}

#[test]
fn proof_with_missing_characters_matches_reference() {
    check_proof("proof-fallback", Some("AVo?.\nVo AV x"), &[24.0]);
}

#[test]
fn the_comparison_catches_a_changed_pixel() {
    let (_, outlines) = mini();
    let img = sheet(&outlines, 96, 4, false).unwrap();
    let mut changed = img.clone();
    // Four pixels in the A's cell turned blue.
    for x in 240..244 {
        let i = (70 * changed.width() + x) as usize;
        changed.pixels_mut()[i] = tiny_skia::PremultipliedColorU8::from_rgba(0, 0, 255, 255)
            .expect("opaque colour is valid");
    }
    assert_eq!(diff(&changed, &img).0, 4);
    assert_eq!(diff(&img, &img).0, 0);
}

#[test]
fn sheet_order_and_default_text() {
    let (_, font) = mini();
    let names: Vec<&str> = sheet_order(&font)
        .into_iter()
        .map(|i| font.glyphs[i].name.as_str())
        .collect();
    assert_eq!(
        names,
        [
            "space",
            "period",
            "A",
            "V",
            "o",
            "oacute",
            "acutecomb",
            ".notdef"
        ]
    );
    // Mini covers no candidate line: its characters (no marks, no space), then kerning pairs.
    assert_eq!(default_text(&font), ".AVoó\nAV Vo");
    // The proof's layout: kerning A-V -60 and V-o -40 applied.
    let line = Layout::new(&font).unwrap().line("AVo").unwrap();
    let xs: Vec<f64> = line.glyphs.iter().map(|p| p.x).collect();
    assert_eq!(xs, [0.0, 580.0, 1140.0]);
}

#[test]
fn a_tall_sheet_gets_more_columns() {
    let (mut font, _) = mini();
    // 400 glyphs of 2048 px: one column would be 819,200 px tall; 14 rows fit in 30,000.
    let template = font.glyph("A").unwrap().clone();
    font.glyphs = (0..400)
        .map(|i| {
            let mut g = template.clone();
            g.name = format!("g{i:03}");
            g.unicodes = vec![];
            g
        })
        .collect();
    font.kerning.clear();
    let outlines = outline_font(&font, 0.5);
    let err = sheet(&outlines, 2048, 1, false).unwrap_err();
    // 400 / 14 = 29 columns: too wide as well, so a clear size error instead of a panic.
    assert_eq!(
        err,
        RenderError::Size {
            width: 29 * 2048,
            height: 14 * 2048
        }
    );
    let img = sheet(&outlines, 256, 1, false).unwrap();
    // 117 rows of 256 px fit in 30,000 px: 4 columns of 100 rows.
    assert_eq!((img.width(), img.height()), (4 * 256, 100 * 256));
}

#[test]
fn bad_options_are_errors_not_panics() {
    let (_, outlines) = mini();
    assert_eq!(
        sheet(&outlines, 8, 4, false).err(),
        Some(RenderError::Option(
            "cell size 8 px is out of range 32..=2048".into()
        ))
    );
    assert_eq!(
        sheet(&outlines, 64, 0, false).err(),
        Some(RenderError::Option("columns must be at least 1".into()))
    );
    let proof = |sizes: Vec<f64>, width_px| {
        render_proof(
            &outlines,
            &ProofOptions {
                text: Some("A".into()),
                sizes,
                width_px,
            },
        )
        .err()
    };
    assert_eq!(
        proof(vec![f64::NAN], 100),
        Some(RenderError::Option(
            "size NaN px is out of range 1..=1000".into()
        ))
    );
    assert_eq!(
        proof(vec![12.0], 0),
        Some(RenderError::Size {
            width: 0,
            height: 53
        })
    );
}

/// `xglyph render` with `flags` on `font` into a scratch folder: (exit code, stderr, whether
/// the folder was created).
fn render_cli(tag: &str, font: &Path, flags: &[&str]) -> (Option<i32>, String, bool) {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("render-flags-{tag}"));
    let _ = std::fs::remove_dir_all(&out);
    let result = std::process::Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .arg("render")
        .arg(font)
        .arg("-o")
        .arg(&out)
        .args(flags)
        .output()
        .expect("xglyph runs");
    let stderr = String::from_utf8_lossy(&result.stderr).into_owned();
    (result.status.code(), stderr, out.exists())
}

/// Issue 13, item 21: a flag out of range, or one that makes the image too large, is named
/// in the error; nothing is written.
#[test]
fn the_flag_at_fault_is_named() {
    let mini = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini");
    let sizes = ["12,16,24,36,48,72"; 167].join(",");
    let cases: [(&str, &[&str], &str); 6] = [
        (
            "width",
            &["--width", "0"],
            "--width 0: the proof width must be 1..=30000 px",
        ),
        (
            "cell",
            &["--cell", "0"],
            "--cell 0: the cell size must be 32..=2048 px",
        ),
        (
            "columns",
            &["--columns", "0"],
            "--columns 0: at least 1 column is needed",
        ),
        (
            "small-size",
            &["--sizes", "12,0.5"],
            "--sizes: 0.5 px per em is out of range 1..=1000",
        ),
        (
            "sizes",
            &["--sizes", &sizes],
            "--sizes: 1002 sizes make an image of 217 x 101902 px; at most 30000 px a side and \
             100000000 px in all (give fewer or smaller sizes, or a shorter --text)",
        ),
        (
            "width-with-only-sheet",
            &["--only", "sheet", "--width", "0"],
            "--width 0: the proof width must be 1..=30000 px",
        ),
    ];
    for (tag, flags, message) in cases {
        let (code, stderr, created) = render_cli(tag, &mini, flags);
        assert_eq!(code, Some(1), "{tag}");
        assert_eq!(stderr, format!("error: {message}\n"), "{tag}");
        assert!(!created, "{tag}: the output folder was created");
    }

    // A sheet too wide: 18 glyphs, 18 cells of 2048 px in a row.
    let font = Path::new(env!("CARGO_TARGET_TMPDIR")).join("render-flags-font");
    let _ = std::fs::remove_dir_all(&font);
    std::fs::create_dir_all(&font).unwrap();
    for entry in std::fs::read_dir(&mini).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, font.join(path.file_name().unwrap())).unwrap();
    }
    for k in 0..10 {
        let glyph =
            "advance = 500\n[[contour]]\npoints = [[0, 0, 0], [100, 0, 0], [100, 100, 0]]\n";
        std::fs::write(font.join(format!("extra{k}.toml")), glyph).unwrap();
    }
    let (code, stderr, created) = render_cli(
        "sheet",
        &font,
        &["--only", "sheet", "--cell", "2048", "--columns", "18"],
    );
    assert_eq!(code, Some(1));
    assert_eq!(
        stderr,
        "error: --cell 2048 --columns 18: the sheet would be 36864 x 2048 px; at most 30000 px \
         a side and 100000000 px in all (use a smaller --cell or fewer --columns)\n"
    );
    assert!(!created);
}
