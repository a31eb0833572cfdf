//! Labels in the built-in face are drawn from cached coverage stamps
//! (`src/render/labels/stamps.rs`, `src/render/stamp.rs`): the pixels must be those of
//! filling each glyph with tiny-skia, whatever the background, placement, cache state or
//! thread count. The face's generated data is checked in `scale.rs`.

use std::path::Path;

use tiny_skia::{Color, Pixmap, PixmapMut};
use xglyph::render::draw::fill_glyph;
use xglyph::render::labels::{draw_line, LabelFace};

use crate::scale::{output_files, run};

/// Largest per-channel difference allowed between a stamped and a filled label: none, the
/// stamps are exact (measured: 0 on every case below).
const STAMP_SLACK: u8 = 0;

/// `text` drawn the way labels were drawn before the stamps: each glyph filled by tiny-skia.
fn fill_line(
    img: &mut PixmapMut<'_>,
    text: &str,
    top_left: (f64, f64),
    em_px: f64,
    room_px: f64,
    color: Color,
) {
    for glyph in LabelFace::get().placements(text, top_left, em_px, room_px) {
        fill_glyph(img, glyph.path, glyph.at, color);
    }
}

/// An opaque background that is not flat, so blending over it is checked too.
fn background(width: u32, height: u32) -> Pixmap {
    let mut img = Pixmap::new(width, height).unwrap();
    for (i, px) in img.data_mut().chunks_exact_mut(4).enumerate() {
        let (x, y) = (i as u32 % width, i as u32 / width);
        px.copy_from_slice(&[(x * 7) as u8, (y * 5) as u8, ((x + y) * 3) as u8, 255]);
    }
    img
}

/// Pixels that differ by more than [`STAMP_SLACK`], and the largest channel difference.
fn compare(a: &Pixmap, b: &Pixmap) -> (usize, u8) {
    let mut count = 0;
    let mut worst = 0;
    for (p, q) in a.data().chunks_exact(4).zip(b.data().chunks_exact(4)) {
        let most = p
            .iter()
            .zip(q)
            .map(|(x, y)| x.abs_diff(*y))
            .max()
            .unwrap_or(0);
        worst = worst.max(most);
        count += usize::from(most > STAMP_SLACK);
    }
    (count, worst)
}

#[test]
fn stamped_labels_are_the_bytes_of_filled_labels() {
    let texts = [
        "uni4E00 U+4E00",
        "A U+0041",
        "The quick brown fox jumps over the lazy dog 0123456789",
        "!\"#$%&'()*+,-./:;<=>?@[\\]^_`{|}~",
        "\u{4E00}\u{E9} .notdef \u{FFFF}",
    ];
    let colors = [
        Color::from_rgba8(70, 70, 70, 255),
        Color::from_rgba8(0x44, 0x55, 0x99, 0xFF),
        Color::BLACK,
        // Translucent: not stamped, filled (the stamps only match opaque fills).
        Color::from_rgba8(200, 30, 30, 128),
    ];
    let (mut stamped, mut filled) = (background(420, 300), background(420, 300));
    let mut k = 0u32;
    for (t, text) in texts.iter().enumerate() {
        for em in [7.0, 13.0, 24.0, 41.5] {
            // Fractional corners, some over the left, top, right or bottom edge (clipped:
            // filled, not stamped), and a room that narrows the longer lines.
            for corner in [(5.0, 5.0), (3.37, 17.81), (-4.6, 60.25), (300.125, 290.5)] {
                let color = colors[(k % 4) as usize];
                let at = (corner.0 + f64::from(t as u32) * 11.3, corner.1 + em * 1.7);
                let room = 150.0 + f64::from(k % 5) * 40.0;
                // Twice: the second draws from the cache, over the first.
                for _ in 0..2 {
                    draw_line(&mut stamped.as_mut(), text, at, em, room, color);
                    fill_line(&mut filled.as_mut(), text, at, em, room, color);
                }
                k += 1;
            }
        }
    }
    let (count, worst) = compare(&stamped, &filled);
    assert_eq!(
        (count, worst),
        (0, 0),
        "{count} pixels of stamped labels differ from filled ones (largest channel \
         difference {worst})"
    );
    // Ink was drawn at all.
    assert!(stamped.data() != background(420, 300).data());

    // Wider than tiny-skia fills in one piece (it tiles from 8,192 px): filled, the same.
    let (mut stamped, mut filled) = (background(8200, 40), background(8200, 40));
    for x in [3.3, 8100.7] {
        draw_line(
            &mut stamped.as_mut(),
            "U+4E00",
            (x, 5.0),
            24.0,
            90.0,
            colors[0],
        );
        fill_line(
            &mut filled.as_mut(),
            "U+4E00",
            (x, 5.0),
            24.0,
            90.0,
            colors[0],
        );
    }
    assert_eq!(compare(&stamped, &filled), (0, 0), "tiled pixmap");
}

/// A font folder of `n` square ideographs from U+4E00, which lack every label character.
fn ideograph_folder(dir: &Path, n: u32) {
    std::fs::create_dir_all(dir).unwrap();
    let mini = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini/font.toml");
    std::fs::copy(mini, dir.join("font.toml")).unwrap();
    for i in 0..n {
        let code = 0x4E00 + i;
        let glyph = format!(
            "name = \"uni{code:04X}\"\nunicode = 0x{code:04X}\nadvance = 1000\n\n[[contour]]\n\
             points = [[100, 0, 0], [{}, 0, 0], [800, 700, 0], [100, 700, 0]]\n",
            800 - i % 300
        );
        std::fs::write(dir.join(format!("uni{code:04X}.toml")), glyph).unwrap();
    }
}

#[test]
fn built_in_labels_are_the_same_bytes_on_1_and_4_threads() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("labels-threads");
    let _ = std::fs::remove_dir_all(&tmp);
    let font = tmp.join("font");
    // Two sheet pages (512 cells a page), their rows drawn in parallel.
    ideograph_folder(&font, 700);
    let outs: Vec<_> = [1, 4]
        .iter()
        .map(|&threads| {
            let out = tmp.join(format!("out-{threads}"));
            run(
                threads,
                &[
                    "render".as_ref(),
                    font.as_os_str(),
                    "--only".as_ref(),
                    "sheet".as_ref(),
                    "-o".as_ref(),
                    out.as_os_str(),
                ],
            );
            output_files(&out)
        })
        .collect();
    let names: Vec<&String> = outs[0].keys().collect();
    assert_eq!(names, ["sheet-1.png", "sheet-2.png"]);
    assert!(
        outs[0] == outs[1],
        "the sheet pages differ between 1 and 4 threads"
    );
}
