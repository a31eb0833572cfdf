//! Shaping in the proof (`src/layout.rs`): HarfRust on the font's own TTF.
//!
//! - positions equal HarfBuzz's (uharfbuzz, PyPI) on the same TTF bytes;
//! - a kerned pair in the proof PNG differs from the same pair without kerning exactly where
//!   the kern moves the right glyph;
//! - the shaper reads GPOS: a mark-to-base lookup written here puts the accent over the `x`,
//!   in the shaper's positions and in the proof's pixels. (The font xglyph builds has no
//!   `mark` feature yet; when it has, the same checks apply to it directly.)

use std::path::Path;
use std::process::Command;

use tiny_skia::Pixmap;
use write_fonts::tables::gpos::{
    AnchorTable, BaseArray, BaseRecord, Gpos, MarkArray, MarkBasePos, MarkBasePosFormat1,
    MarkRecord, PositionLookup, PositionLookupList,
};
use write_fonts::tables::layout::{
    Feature, FeatureList, FeatureRecord, LangSys, Lookup, LookupFlag, Script, ScriptList,
    ScriptRecord,
};
use write_fonts::types::{GlyphId16, Tag};
use write_fonts::FontBuilder;
use xglyph::layout::{Layout, Line};
use xglyph::model::Font;
use xglyph::otf::{glyph_order, ttf};
use xglyph::outline::{outline_font, OutlinedFont};
use xglyph::render::{render_proof, render_proof_with, ProofOptions};
use xglyph::source::load_font;

use crate::common::tools;

fn load(dir: &str) -> (Font, OutlinedFont) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
    let (font, _) = load_font(&dir).expect("font loads");
    let outlines = outline_font(&font, font.info.tolerance);
    (font, outlines)
}

/// `name@x,y+advance` per glyph, the form the uharfbuzz script prints.
fn describe(layout: &Layout<'_>, line: &Line) -> String {
    line.glyphs
        .iter()
        .map(|p| format!("{}@{},{}+{}", layout.outline(p).name, p.x, p.y, p.advance))
        .collect::<Vec<_>>()
        .join(" ")
}

/// Whether uharfbuzz is there.
fn uharfbuzz_available() -> bool {
    tools::available(
        tools::python_imports("uharfbuzz"),
        "uharfbuzz",
        "pip install uharfbuzz",
    )
}

/// Shapes each text with HarfBuzz and prints one line per text in [`describe`]'s form.
const HB_SCRIPT: &str = r#"
import sys, uharfbuzz as hb
font = hb.Font(hb.Face(hb.Blob.from_file_path(sys.argv[1])))
for text in sys.argv[2:]:
    buf = hb.Buffer()
    buf.add_str(text)
    buf.guess_segment_properties()
    hb.shape(font, buf, {})
    pen, out = 0, []
    for info, pos in zip(buf.glyph_infos, buf.glyph_positions):
        name = font.glyph_to_string(info.codepoint)
        out.append(f"{name}@{pen + pos.x_offset},{pos.y_offset}+{pos.x_advance}")
        pen += pos.x_advance
    print(" ".join(out))
"#;

#[test]
fn positions_equal_harfbuzz_on_the_same_ttf() {
    if !uharfbuzz_available() {
        return;
    }
    let (_, font) = load("glyphs");
    let bytes = ttf(&font).expect("the bundled font builds");
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("font.ttf");
    std::fs::write(&path, &bytes).expect("write the TTF");
    let texts = [
        "AVATAR Tower LT Yo Wave",
        "Type P.A.W. \"F,\" Fa r. y.",
        "Où est la forêt? Äpfel",
        "fi fl ﬁ ﬂ ı ȷ",
    ];
    let out = Command::new("python3")
        .arg("-c")
        .arg(HB_SCRIPT)
        .arg(&path)
        .args(texts)
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let harfbuzz = String::from_utf8(out.stdout).expect("UTF-8");
    let layout = Layout::with_ttf(&font, bytes).expect("shapes");
    let advances = |line: &Line| line.glyphs.iter().map(|p| p.advance).sum::<f64>();
    for (text, expected) in texts.iter().zip(harfbuzz.lines()) {
        let line = layout.line(text).expect("shapes");
        assert_eq!(describe(&layout, &line), expected, "{text:?}");
        assert_eq!(line.width, advances(&line));
    }
    // The first text is kerned: A-V -85 moves the V 85 units left of A's advance.
    let line = layout.line("AV").expect("shapes");
    let a = font.glyph("A").expect("A").advance;
    assert_eq!(line.glyphs[1].x, a - 85.0);
}

/// The proof of `text` at 200 px per em (scale 0.2, so the A-V kern of -85 units is
/// exactly 17 px).
fn proof(font: &OutlinedFont, text: &str) -> Pixmap {
    let opts = ProofOptions {
        text: Some(text.into()),
        sizes: vec![200.0],
        width_px: 2000,
    };
    render_proof(font, &opts).expect("renders")
}

fn column_differs(a: &Pixmap, ca: u32, b: &Pixmap, cb: u32) -> bool {
    (0..a.height().min(b.height())).any(|y| {
        let pa = a.pixel(ca, y).expect("inside");
        let pb = b.pixel(cb, y).expect("inside");
        [
            pa.red().abs_diff(pb.red()),
            pa.green().abs_diff(pb.green()),
            pa.blue().abs_diff(pb.blue()),
        ]
        .iter()
        .any(|&d| d > 2)
    })
}

#[test]
fn a_kerned_pair_differs_from_the_unkerned_one_only_where_the_kern_moves_the_v() {
    let (mut model, font) = load("glyphs");
    model.kerning.clear();
    let unkerned_font = outline_font(&model, model.info.tolerance);
    let kerned = proof(&font, "AV");
    let unkerned = proof(&unkerned_font, "AV");
    assert_eq!(unkerned.width() - kerned.width(), 17);
    let scale = 0.2;
    let margin = 16.0;
    let a = font.glyph("A").expect("A");
    let v = font.glyph("V").expect("V");
    let (a_ink, v_ink) = (
        kurbo::Shape::bounding_box(&a.path),
        kurbo::Shape::bounding_box(&v.path),
    );
    // Pixel columns: the kerned V's ink starts here; the A's ink ends here.
    let v_left = (margin + (a.advance - 85.0 + v_ink.x0) * scale).floor() as u32;
    let a_right = (margin + a_ink.x1 * scale).ceil() as u32;
    assert!(v_left < a_right, "the kern tucks the V under the A");
    // Left of the moved V, the images are the same pixel for pixel.
    for c in 0..v_left {
        assert!(!column_differs(&kerned, c, &unkerned, c), "column {c}");
    }
    // Right of the A, the kerned image is the unkerned one moved 17 px left.
    for c in a_right + 1..kerned.width() {
        assert!(!column_differs(&kerned, c, &unkerned, c + 17), "column {c}");
    }
    // And the kern does change the image where the V moved.
    let changed = (v_left..kerned.width())
        .filter(|&c| column_differs(&kerned, c, &unkerned, c))
        .count();
    assert!(changed > 100, "{changed} columns changed");
}

/// The TTF of `font` with a GPOS holding one mark-to-base lookup (`mark` feature, DFLT and
/// latn): `mark`'s anchor at `mark_at` onto `base`'s anchor at `base_at`.
fn with_mark_gpos(
    font: &OutlinedFont,
    base: &str,
    base_at: (i16, i16),
    mark: &str,
    mark_at: (i16, i16),
) -> Vec<u8> {
    let bytes = ttf(font).expect("builds");
    let order = glyph_order(font).expect("order");
    let gid = |name: &str| {
        GlyphId16::new(
            order
                .iter()
                .position(|g| g.model_name == name)
                .expect("glyph") as u16,
        )
    };
    let subtable = MarkBasePosFormat1::new(
        vec![gid(mark)].into(),
        vec![gid(base)].into(),
        MarkArray::new(vec![MarkRecord::new(
            0,
            AnchorTable::format_1(mark_at.0, mark_at.1),
        )]),
        BaseArray::new(vec![BaseRecord::new(vec![Some(AnchorTable::format_1(
            base_at.0, base_at.1,
        ))])]),
    );
    let lookup = PositionLookup::MarkToBase(Lookup::new(
        LookupFlag::empty(),
        vec![MarkBasePos::Format1(subtable)],
    ));
    let feature = FeatureRecord::new(Tag::new(b"mark"), Feature::new(None, vec![0]));
    let lang = LangSys::new(vec![0]);
    let scripts = [Tag::new(b"DFLT"), Tag::new(b"latn")]
        .into_iter()
        .map(|tag| ScriptRecord::new(tag, Script::new(Some(lang.clone()), vec![])))
        .collect();
    let gpos = Gpos::new(
        ScriptList::new(scripts),
        FeatureList::new(vec![feature]),
        PositionLookupList::new(vec![lookup]),
    );
    let read = read_fonts::FontRef::new(&bytes).expect("reads");
    let mut builder = FontBuilder::new();
    builder.add_table(&gpos).expect("GPOS");
    // Keep every other table; the legacy kern table too (GPOS wins over it in HarfBuzz).
    builder.copy_missing_tables(read);
    builder.build()
}

/// The font's TTF with a hand-made `mark` lookup: a base anchor over the x's middle at 520,
/// and the acute's own anchor at its ink's bottom middle, 500, so that the accent's ink is
/// centred over the x and moved up 20 units. Returns the two middles and the TTF.
fn acute_centred_over_x(font: &OutlinedFont) -> (i16, i16, Vec<u8>) {
    let x = font.glyph("x").expect("x");
    let acute = font.glyph("acutecomb").expect("acutecomb");
    let x_mid = (x.advance / 2.0).round() as i16;
    let acute_ink = kurbo::Shape::bounding_box(&acute.path);
    let acute_mid = ((acute_ink.x0 + acute_ink.x1) / 2.0).round() as i16;
    let bytes = with_mark_gpos(font, "x", (x_mid, 520), "acutecomb", (acute_mid, 500));
    (x_mid, acute_mid, bytes)
}

#[test]
fn shaping_reads_gpos_marks_go_on_their_base() {
    let (_, font) = load("glyphs");
    // `x` has no precomposed accented form, so x + U+0301 stays two glyphs.
    let (x, acute) = (
        font.glyph("x").expect("x"),
        font.glyph("acutecomb").expect("acute"),
    );
    let (x_mid, acute_mid, bytes) = acute_centred_over_x(&font);
    let layout = Layout::with_ttf(&font, bytes).expect("shapes");
    let line = layout.line("x\u{301}").expect("shapes");
    let names: Vec<&str> = line
        .glyphs
        .iter()
        .map(|p| layout.outline(p).name.as_str())
        .collect();
    assert_eq!(names, ["x", "acutecomb"]);
    let mark = line.glyphs[1];
    assert_eq!((mark.x, mark.y), (f64::from(x_mid - acute_mid), 20.0));
    assert_eq!((mark.advance, line.width), (0.0, x.advance));
    // The font xglyph builds has its own `mark` feature, from the sources' anchors: the
    // accent's `_top` lands on the x's `top`.
    let anchor = |g: &xglyph::OutlinedGlyph, name: &str| {
        g.anchors
            .iter()
            .find(|a| a.name == name)
            .map(|a| a.position)
            .expect("anchor")
    };
    let (top, mark_top) = (anchor(x, "top"), anchor(acute, "_top"));
    let built = Layout::new(&font).expect("shapes");
    let line = built.line("x\u{301}").expect("shapes");
    assert_eq!(
        (line.glyphs[1].x, line.glyphs[1].y),
        (top.0 - mark_top.0, top.1 - mark_top.1)
    );
}

/// The ink's pixel rows, in runs separated by blank rows, each with its leftmost and
/// rightmost inked column (a pixel darker than mid grey).
fn ink_runs(img: &Pixmap) -> Vec<(u32, u32)> {
    let mut runs = Vec::new();
    let mut current: Option<(u32, u32)> = None;
    for y in 0..img.height() {
        let inked: Vec<u32> = (0..img.width())
            .filter(|&x| img.pixel(x, y).expect("inside").red() < 128)
            .collect();
        match (inked.first(), inked.last(), current) {
            (Some(&l), Some(&r), Some((cl, cr))) => current = Some((cl.min(l), cr.max(r))),
            (Some(&l), Some(&r), None) => current = Some((l, r)),
            (None, _, Some(run)) => {
                runs.push(run);
                current = None;
            }
            _ => {}
        }
    }
    runs.extend(current);
    runs
}

#[test]
fn the_proof_draws_a_gpos_positioned_accent_over_its_base() {
    let (_, font) = load("glyphs");
    let (x_mid, acute_mid, bytes) = acute_centred_over_x(&font);
    let opts = ProofOptions {
        text: Some("x\u{301}".into()),
        sizes: vec![200.0],
        width_px: 2000,
    };
    let centre = |(l, r): (u32, u32)| f64::from(l + r) / 2.0;
    // Two runs of ink, top to bottom: the accent, then the x (the accent clears the
    // x-height).
    let shaped = render_proof_with(&Layout::with_ttf(&font, bytes).expect("shapes"), &opts)
        .expect("renders");
    let [accent, base] = ink_runs(&shaped)[..] else {
        panic!("{:?}", ink_runs(&shaped));
    };
    assert!(
        accent.0 >= base.0 && accent.1 <= base.1,
        "{accent:?} over {base:?}"
    );
    assert!(
        (centre(accent) - centre(base)).abs() <= 2.0,
        "{accent:?} {base:?}"
    );
    // The font xglyph builds places the accent by its own anchors (`mark` from the x's
    // `top` and the accent's `_top`): over the x as well.
    let built = render_proof(&font, &opts).expect("renders");
    let [accent, base] = ink_runs(&built)[..] else {
        panic!("{:?}", ink_runs(&built));
    };
    assert!(
        accent.0 >= base.0 && accent.1 <= base.1,
        "{accent:?} over {base:?}"
    );
    // The check can fail: the same proof from a font whose `mark` anchor on the x sits 150
    // units (30 px) right of its middle puts the accent off centre.
    let bytes = with_mark_gpos(
        &font,
        "x",
        (x_mid + 150, 520),
        "acutecomb",
        (acute_mid, 500),
    );
    let moved = render_proof_with(&Layout::with_ttf(&font, bytes).expect("shapes"), &opts)
        .expect("renders");
    let [accent, base] = ink_runs(&moved)[..] else {
        panic!("{:?}", ink_runs(&moved));
    };
    assert!(centre(accent) - centre(base) > 20.0, "{accent:?} {base:?}");
}
