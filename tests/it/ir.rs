//! The outlined-font IR: one glyph list for every backend, the one `.notdef` box, single-glyph
//! refits, and the pipeline's data-only errors.

use std::path::{Path, PathBuf};

use ttf_parser::{Face, GlyphId, OutlineBuilder};
use xglyph::model::Font;
use xglyph::otf::ttf;
use xglyph::outline::{notdef_box, outline_font, outline_glyph};
use xglyph::pipeline::{self, PipelineError};
use xglyph::render::{render_proof, ProofOptions};
use xglyph::source::{load_font, Severity};
use xglyph::svg::svg_font;

fn mini_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini")
}

fn mini() -> Font {
    load_font(&mini_dir()).expect("mini loads").0
}

/// Path data in the SVG font's notation (`M x y L x y … Z`, y up).
#[derive(Default)]
struct PathText(String);

impl OutlineBuilder for PathText {
    fn move_to(&mut self, x: f32, y: f32) {
        self.0.push_str(&format!("M{x} {y}"));
    }
    fn line_to(&mut self, x: f32, y: f32) {
        self.0.push_str(&format!("L{x} {y}"));
    }
    fn quad_to(&mut self, _: f32, _: f32, x: f32, y: f32) {
        self.0.push_str(&format!("Q{x} {y}"));
    }
    fn curve_to(&mut self, _: f32, _: f32, _: f32, _: f32, x: f32, y: f32) {
        self.0.push_str(&format!("C{x} {y}"));
    }
    fn close(&mut self) {
        self.0.push('Z');
    }
}

fn missing_glyph(svg: &str) -> (String, String) {
    let doc = roxmltree::Document::parse(svg).expect("SVG font parses");
    let node = doc
        .descendants()
        .find(|n| n.has_tag_name("missing-glyph"))
        .expect("a missing-glyph");
    (
        node.attribute("horiz-adv-x").unwrap_or_default().to_owned(),
        node.attribute("d").unwrap_or_default().to_owned(),
    )
}

#[test]
fn svg_missing_glyph_and_ttf_notdef_are_one_box() {
    let mut font = mini();
    font.glyphs.retain(|g| g.name != ".notdef");
    let outlined = outline_font(&font, font.info.tolerance);
    assert!(!outlined.has_notdef());

    let (advance, d) = missing_glyph(&svg_font(&outlined));
    assert_eq!(advance, "500");
    // Outer box clockwise, counter counter-clockwise (y up): TrueType's directions.
    assert_eq!(
        d,
        "M50 700L450 700L450 0L50 0ZM400 50L400 650L100 650L100 50Z"
    );

    let bytes = ttf(&outlined).expect("TTF builds");
    let face = Face::parse(&bytes, 0).expect("TTF parses");
    assert_eq!(face.glyph_hor_advance(GlyphId(0)), Some(500));
    let mut text = PathText::default();
    face.outline_glyph(GlyphId(0), &mut text)
        .expect("an outline");
    // The same two rectangles, each reversed for TrueType (outer clockwise), as ttf-parser
    // reads them back (starting at a corner's successor, closing explicitly).
    assert_eq!(
        text.0,
        "M50 700L450 700L450 0L50 0L50 700ZM400 50L400 650L100 650L100 50L400 50Z"
    );
    assert_eq!(notdef_box(&outlined.info).path, outlined.notdef().path);
}

#[test]
fn the_proof_draws_the_same_box_for_a_missing_character() {
    let mut font = mini();
    font.glyphs.retain(|g| g.name != ".notdef");
    let outlined = outline_font(&font, font.info.tolerance);
    let opts = ProofOptions {
        text: Some("?".into()),
        sizes: vec![100.0],
        width_px: 200,
    };
    let img = render_proof(&outlined, &opts).expect("renders");
    // 100 px per 1000-unit em: the box is 40 x 70 px with 5 px stems. Take the 31st row
    // that crosses exactly two stems (10 dark pixels) and check where they are.
    let dark = |x: u32, y: u32| img.pixel(x, y).is_some_and(|p| p.red() < 128);
    let row = (0..img.height())
        .filter(|&y| (0..img.width()).filter(|&x| dark(x, y)).count() == 10)
        .nth(30)
        .expect("a row through both stems of the box");
    let xs: Vec<u32> = (0..img.width()).filter(|&x| dark(x, row)).collect();
    // Left stem from x = 16 + 5 = 21, right stem ends at 16 + 45 = 61.
    assert_eq!(xs, [21, 22, 23, 24, 25, 56, 57, 58, 59, 60]);
}

#[test]
fn one_glyph_refits_to_the_same_outline() {
    let font = mini();
    let outlined = outline_font(&font, 0.25);
    for glyph in &font.glyphs {
        let single = outline_glyph(&font, glyph, 0.25);
        let whole = outlined.glyph(&glyph.name).expect("in the font");
        assert_eq!(single.path, whole.path, "{}", glyph.name);
        assert_eq!(single.max_error, whole.max_error);
        assert_eq!(single.segments, whole.segments);
    }
    // oacute places acutecomb: its own o contours and the accent's, offset.
    let oacute = outlined.glyph("oacute").expect("oacute");
    assert_eq!(oacute.components.len(), 2);
    assert_eq!(oacute.contours.len(), 3);
    assert!(oacute.max_error <= 0.25);
}

#[test]
fn notdef_is_first_whatever_the_model_order() {
    let mut font = mini();
    font.glyphs.reverse();
    let names: Vec<String> = outline_font(&font, 0.5)
        .glyphs
        .into_iter()
        .map(|g| g.name)
        .collect();
    assert_eq!(
        names,
        [
            ".notdef",
            "space",
            "period",
            "oacute",
            "o",
            "acutecomb",
            "V",
            "A"
        ]
    );
}

#[test]
fn pipeline_errors_are_data() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/malformed/coincident");
    let Err(PipelineError::Sources { diagnostics, .. }) = pipeline::load(&dir, None) else {
        panic!("coincident points must fail");
    };
    let errors: Vec<String> = diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .map(|d| format!("{}:{}: {}", d.line, d.col, d.message))
        .collect();
    assert_eq!(errors, ["4:11: point 0 coincides with point 2 before it"]);
    let err = pipeline::load(&dir, None).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!("1 error in {}; nothing was written", dir.display())
    );
    let err = pipeline::load(&mini_dir(), Some(f64::NAN)).unwrap_err();
    assert!(matches!(err, PipelineError::Tolerance(_)), "{err}");

    // The numbers `xglyph build tests/fixtures/mini` prints.
    let loaded = pipeline::load(&mini_dir(), None).expect("mini loads");
    assert!(loaded.warnings.is_empty());
    let summary = pipeline::Summary::new(&loaded.font);
    assert_eq!(
        (summary.glyphs, summary.contours, summary.segments),
        (8, 12, 82)
    );
    assert_eq!(summary.tolerance, 0.5);
    let (name, error) = summary.worst.expect("a worst glyph");
    assert_eq!(name, "period");
    assert_eq!(format!("{error:.3}"), "0.473");
}
