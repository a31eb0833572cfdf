//! OpenType layout (`otf/features.rs`): `features.fea` compiled by fea-rs with the
//! generated `kern`, `mark`, `mkmk` and GDEF classes, checked from outside: fontTools reads
//! the tables, HarfBuzz (uharfbuzz) shapes, headless Chromium renders, and the fontTools
//! instancer reads the variable font; errors in the file at file:line:col.
//!
//! The test font is the bundled typeface with its anchors and `glyphs/features.fea`
//! (`liga`: f i -> fi, f l -> fl; `ccmp`: i, j -> dotlessi, dotlessj before a top mark),
//! without the precomposed accented letters in cmap (so that shapers keep `a` + U+0301 as
//! two glyphs and position the mark). Expected positions come from the sources' anchors.
//!
//! Tests that need a tool print `skipped: …` and pass when it is missing, unless
//! `XGLYPH_REQUIRE_TOOLS=1` (CI): `python3` with fontTools and uharfbuzz,
//! `/usr/bin/chromium`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use kurbo::Shape;
use serde_json::{json, Value};
use xglyph::designspace::{Axis, Designspace, Location};
use xglyph::family::{MasterGlyph, OutlinedFamily, OutlinedMaster};
use xglyph::model::{Anchor, FeatureFile, Font, GlyphModels, KernPair};
use xglyph::otf::{otf, ttf, variable_ttf_with_anchors};
use xglyph::outline::outline_font;
use xglyph::source::load_font;

use crate::common::cli::xglyph;
use crate::common::tools;
use crate::studio_browser::Browser;

fn anchor(name: &str, x: f64, y: f64) -> Anchor {
    Anchor {
        name: name.into(),
        position: (x, y),
    }
}

/// The bundled typeface (its anchors and `features.fea`), composites out of cmap.
fn test_font() -> Font {
    let (mut font, _) = load_font(Path::new("glyphs")).expect("the bundled typeface loads");
    assert!(font.features.is_some(), "glyphs/features.fea is loaded");
    for g in &mut font.glyphs {
        if !g.components.is_empty() {
            g.unicodes.clear();
        }
    }
    font
}

/// The position of `glyph`'s anchor `name`, from the sources.
fn anchor_at(font: &Font, glyph: &str, name: &str) -> (i64, i64) {
    let g = font.glyphs.iter().find(|g| g.name == glyph).unwrap();
    let a = g
        .anchors
        .iter()
        .find(|a| a.name == name)
        .unwrap_or_else(|| panic!("'{glyph}' has no anchor '{name}'"));
    (a.position.0.round() as i64, a.position.1.round() as i64)
}

/// Per anchor name `N` of the sources: the marks with `_N`, the bases (not marks) with `N`
/// and the marks with `N`, each glyph -> `[x, y]` (what GPOS must hold).
fn expected_anchors(font: &Font) -> BTreeMap<String, [Value; 3]> {
    let mut out: BTreeMap<String, [Value; 3]> = BTreeMap::new();
    for g in &font.glyphs {
        // A composite's anchors include those its components bring (`Font::anchors`).
        for a in &font.anchors(g) {
            let (name, slot) = match a.attaches_to() {
                Some(base) => (base, 0),
                None if g.is_mark() => (a.name.as_str(), 2),
                None => (a.name.as_str(), 1),
            };
            let entry = out
                .entry(name.to_string())
                .or_insert_with(|| [json!({}), json!({}), json!({})]);
            entry[slot][&g.name] =
                json!([a.position.0.round() as i64, a.position.1.round() as i64]);
        }
    }
    out
}

fn advance(font: &Font, name: &str) -> f64 {
    font.glyphs
        .iter()
        .find(|g| g.name == name)
        .map(|g| g.advance)
        .unwrap_or_else(|| panic!("no glyph '{name}'"))
}

/// The test font's TTF and OTF in a temporary folder: `(dir, [ttf, otf])`.
fn built(font: &Font) -> (tempfile::TempDir, [PathBuf; 2]) {
    let outlines = outline_font(font, font.info.tolerance);
    let dir = tempfile::tempdir().unwrap();
    let paths = [dir.path().join("test.ttf"), dir.path().join("test.otf")];
    std::fs::write(&paths[0], ttf(&outlines).expect("TTF builds")).unwrap();
    std::fs::write(&paths[1], otf(&outlines).expect("OTF builds")).unwrap();
    (dir, paths)
}

/// Whether python3 cannot import `modules` (the test is skipped).
fn no_python(modules: &str, install: &str) -> bool {
    !tools::available(tools::python_imports(modules), modules, install)
}

/// fontTools: GDEF glyph classes by name, and every MarkBasePos / MarkMarkPos lookup as
/// `{"type": ..., "marks": {glyph: [x, y]}, "bases": {glyph: [x, y]}}` (one class each).
const READ_LAYOUT: &str = r#"
import json, sys
from fontTools.ttLib import TTFont
out = []
for path in sys.argv[1:]:
    font = TTFont(path)
    classes = font["GDEF"].table.GlyphClassDef.classDefs
    lookups = []
    for lookup in font["GPOS"].table.LookupList.Lookup:
        for st in lookup.SubTable:
            if lookup.LookupType == 4:
                marks, bases = st.MarkCoverage.glyphs, st.BaseCoverage.glyphs
                mark_records = st.MarkArray.MarkRecord
                base_anchors = [r.BaseAnchor for r in st.BaseArray.BaseRecord]
                kind = "mark"
            elif lookup.LookupType == 6:
                marks, bases = st.Mark1Coverage.glyphs, st.Mark2Coverage.glyphs
                mark_records = st.Mark1Array.MarkRecord
                base_anchors = [r.Mark2Anchor for r in st.Mark2Array.Mark2Record]
                kind = "mkmk"
            else:
                continue
            assert st.ClassCount == 1
            lookups.append({
                "type": kind,
                "flag": lookup.LookupFlag,
                "marks": {g: [r.MarkAnchor.XCoordinate, r.MarkAnchor.YCoordinate]
                          for g, r in zip(marks, mark_records)},
                "bases": {g: [a[0].XCoordinate, a[0].YCoordinate]
                          for g, a in zip(bases, base_anchors)},
            })
    features = sorted({(r.FeatureTag) for t in ("GSUB", "GPOS") if t in font
                       for r in font[t].table.FeatureList.FeatureRecord})
    out.append({"classes": classes, "lookups": lookups, "features": features})
print(json.dumps(out))
"#;

#[test]
fn fonttools_reads_gdef_classes_and_mark_anchors() {
    if no_python("fontTools", "pip install fonttools") {
        return;
    }
    let font = test_font();
    let (_dir, paths) = built(&font);
    let read = tools::python_json::<Value>(READ_LAYOUT, &[&paths[0], &paths[1]]);
    for (flavour, layout) in ["TTF", "OTF"].iter().zip(read.as_array().unwrap()) {
        let classes = &layout["classes"];
        // 1 base, 2 ligature, 3 mark (GDEF GlyphClassDef).
        for (glyph, class) in [
            ("a", 1),
            ("f", 1),
            ("dotlessj", 1),
            ("space", 1),
            ("fi", 2),
            ("fl", 2),
            ("acutecomb", 3),
            ("cedillacomb", 3),
        ] {
            assert_eq!(classes[glyph], json!(class), "{flavour}: class of {glyph}");
        }
        assert!(
            classes.get(".notdef").is_none(),
            "{flavour}: .notdef unclassified"
        );
        assert_eq!(
            layout["features"],
            json!(["ccmp", "kern", "liga", "mark", "mkmk"]),
            "{flavour}"
        );
        let lookups = layout["lookups"].as_array().unwrap();
        let expected = expected_anchors(&font);
        let mut checked = 0;
        for (name, [marks, bases, mark_bases]) in &expected {
            // One mark-to-base lookup per anchor name with bases, one mark-to-mark lookup
            // (filtered to the marks: flag 0x10) per anchor name with marks carrying it.
            for (kind, targets, flag) in [("mark", bases, 0), ("mkmk", mark_bases, 0x10)] {
                if targets.as_object().unwrap().is_empty() {
                    continue;
                }
                let lookup = lookups
                    .iter()
                    .find(|l| l["type"] == kind && &l["marks"] == marks)
                    .unwrap_or_else(|| panic!("{flavour}: no {kind} lookup for '{name}'"));
                assert_eq!(&lookup["bases"], targets, "{flavour}: {kind} '{name}'");
                assert_eq!(lookup["flag"], json!(flag), "{flavour}: {kind} '{name}'");
                checked += 1;
            }
        }
        assert_eq!(checked, lookups.len(), "{flavour}: {lookups:?}");
        // top and bottom marks on bases, top marks on top marks at least.
        assert!(checked >= 3, "{flavour}: {lookups:?}");
    }
}

/// HarfBuzz (uharfbuzz): for each text, `[(glyph name, x advance, x offset, y offset)]`.
const SHAPE: &str = r#"
import json, sys
import uharfbuzz as hb
from fontTools.ttLib import TTFont
path, texts = sys.argv[1], json.loads(sys.argv[2])
names = TTFont(path).getGlyphOrder()
face = hb.Face(open(path, "rb").read())
font = hb.Font(face)
out = []
for text in texts:
    buf = hb.Buffer()
    buf.add_str(text)
    buf.guess_segment_properties()
    hb.shape(font, buf, {})
    out.append([[names[i.codepoint], p.x_advance, p.x_offset, p.y_offset]
                for i, p in zip(buf.glyph_infos, buf.glyph_positions)])
print(json.dumps(out))
"#;

fn shape(path: &Path, texts: &[&str]) -> Vec<Vec<(String, i64, i64, i64)>> {
    tools::python_json(SHAPE, &[&path, &json!(texts).to_string()])
}

#[test]
fn harfbuzz_places_marks_on_anchors_and_forms_the_ligature() {
    if no_python("uharfbuzz, fontTools", "pip install uharfbuzz fonttools") {
        return;
    }
    let font = test_font();
    let (_dir, paths) = built(&font);
    let adv = |n: &str| advance(&font, n) as i64;
    for path in &paths {
        let runs = shape(
            path,
            &["a\u{301}", "fi", "i\u{301}", "a\u{301}\u{300}", "AV", "f i"],
        );
        let (a_top, acute, acute_top, grave) = (
            anchor_at(&font, "a", "top"),
            anchor_at(&font, "acutecomb", "_top"),
            anchor_at(&font, "acutecomb", "top"),
            anchor_at(&font, "gravecomb", "_top"),
        );
        // The acute's `_top` on a's `top`: the mark is drawn after a's advance, so it
        // moves back by that.
        let on_a = (a_top.0 - acute.0 - adv("a"), a_top.1 - acute.1);
        assert_eq!(
            runs[0],
            [
                ("a".into(), adv("a"), 0, 0),
                ("acutecomb".into(), 0, on_a.0, on_a.1)
            ],
            "{}",
            path.display()
        );
        // One glyph, the ligature's advance.
        assert_eq!(runs[1], [("fi".into(), adv("fi"), 0, 0)]);
        // ccmp: dotless i before a top mark, the mark on its anchor.
        let i_top = anchor_at(&font, "dotlessi", "top");
        assert_eq!(
            runs[2],
            [
                ("dotlessi".into(), adv("dotlessi"), 0, 0),
                (
                    "acutecomb".into(),
                    0,
                    i_top.0 - acute.0 - adv("dotlessi"),
                    i_top.1 - acute.1
                )
            ]
        );
        // mkmk: the grave's `_top` on the acute's `top`, wherever the acute sits.
        assert_eq!(
            runs[3][2],
            (
                "gravecomb".into(),
                0,
                on_a.0 + acute_top.0 - grave.0,
                on_a.1 + acute_top.1 - grave.1
            )
        );
        // Generated kern merges with the user's features: A V as in kerning.toml.
        let kern = font
            .kerning
            .iter()
            .find(|p| p.left == "A" && p.right == "V")
            .map(|p| p.value as i64)
            .unwrap();
        assert!(kern < 0);
        assert_eq!(runs[4][0], ("A".into(), adv("A") + kern, 0, 0));
        // No ligature across a space.
        assert_eq!(runs[5].len(), 3);
    }
}

#[test]
fn a_kern_feature_of_the_users_replaces_the_generated_one() {
    if no_python("uharfbuzz, fontTools", "pip install uharfbuzz fonttools") {
        return;
    }
    let mut font = test_font();
    font.features = Some(FeatureFile {
        path: PathBuf::from("features.fea"),
        text: "feature kern { pos a v -77; } kern;\n".into(),
    });
    let (_dir, paths) = built(&font);
    let adv = |n: &str| advance(&font, n) as i64;
    for path in &paths {
        let runs = shape(path, &["av", "AV", "a\u{301}"]);
        assert_eq!(runs[0][0], ("a".into(), adv("a") - 77, 0, 0));
        // The generated pairs are left out (ufo2ft's and fontc's "skip" mode)...
        assert_eq!(runs[1][0], ("A".into(), adv("A"), 0, 0));
        // ...the generated `mark` is not.
        let (a_top, acute) = (
            anchor_at(&font, "a", "top"),
            anchor_at(&font, "acutecomb", "_top"),
        );
        assert_eq!(
            runs[2][1],
            (
                "acutecomb".into(),
                0,
                a_top.0 - acute.0 - adv("a"),
                a_top.1 - acute.1
            )
        );
    }
}

#[test]
fn chromium_puts_the_accent_over_the_a_and_draws_the_ligature() {
    let Some(mut browser) = Browser::start() else {
        return;
    };
    let font = test_font();
    let (dir, _) = built(&font);
    // Ink boxes from a canvas: `a`, then `a` + U+0301; the accent's ink is what the second
    // adds. Widths from spans at 1000 px (1 px per unit).
    let html = r#"<!doctype html><style>@font-face { font-family: T; src: url(test.ttf); }
        span { font: 1000px T; white-space: pre; }</style>
        <body><span id="fi">fi</span><br><span id="f_space_i">f i</span>
        <script>
        function ink(text) {
            const c = document.createElement('canvas');
            c.width = 1200; c.height = 1200;
            const ctx = c.getContext('2d');
            ctx.font = '1000px T';
            ctx.fillText(text, 300, 1000);
            return ctx.getImageData(0, 0, c.width, c.height).data;
        }
        function box(data, other) {
            let b = null;
            for (let y = 0; y < 1200; y++) for (let x = 0; x < 1200; x++) {
                const i = (y * 1200 + x) * 4 + 3;
                if (data[i] > 128 && !(other && other[i] > 128)) {
                    b = b ? [Math.min(b[0], x), Math.min(b[1], y), Math.max(b[2], x), Math.max(b[3], y)]
                          : [x, y, x, y];
                }
            }
            return b;
        }
        document.fonts.load('1000px T').then(() => document.fonts.ready).then(() => {
            const a = ink('a'), both = ink('a\u0301');
            window.boxes = { a: box(a, null), accent: box(both, a) };
            document.body.dataset.ready = '1';
        });
        </script>"#;
    std::fs::write(dir.path().join("page.html"), html).unwrap();
    browser.open(&format!(
        "file://{}",
        dir.path().join("page.html").display()
    ));
    let boxes = browser.eval("window.boxes");
    let b = |k: &str, i: usize| boxes[k][i].as_f64().unwrap();
    eprintln!("Chromium ink boxes (x0, y0, x1, y1, px): {boxes}");
    // The accent's ink is above the a's ink (y grows down) and over it horizontally: its
    // centre lies within the a's ink, not after the a's advance (300 + 540).
    assert!(
        b("accent", 3) < b("a", 1),
        "accent not above the a: {boxes}"
    );
    let centre = (b("accent", 0) + b("accent", 2)) / 2.0;
    assert!(
        centre > b("a", 0) && centre < b("a", 2),
        "accent not over the a: {boxes}"
    );
    // The acute's ink centre is where its anchors put it: a's `top` − the acute's `_top`
    // plus the centre of its outline's box, from the canvas origin at 300 px.
    let outlines = outline_font(&font, font.info.tolerance);
    let acute_box = outlines
        .glyphs
        .iter()
        .find(|g| g.name == "acutecomb")
        .unwrap()
        .path
        .bounding_box();
    let (a_top, acute) = (
        anchor_at(&font, "a", "top"),
        anchor_at(&font, "acutecomb", "_top"),
    );
    let expected = 300.0 + (a_top.0 - acute.0) as f64 + (acute_box.x0 + acute_box.x1) / 2.0;
    assert!(
        (centre - expected).abs() <= 2.0,
        "{centre} vs {expected}: {boxes}"
    );
    let mut width = |id: &str| {
        browser
            .eval(&format!(
                "document.getElementById('{id}').getBoundingClientRect().width"
            ))
            .as_f64()
            .unwrap()
    };
    let fi = width("fi");
    assert!(
        (fi - advance(&font, "fi")).abs() <= 0.1,
        "fi is {fi} px, the ligature's advance {}",
        advance(&font, "fi")
    );
    let apart = width("f_space_i");
    assert!(
        (apart - (advance(&font, "f") + advance(&font, "space") + advance(&font, "i"))).abs()
            <= 0.2,
        "{apart}"
    );
}

/// A one-axis family (wght 400..700) of `o` and `acutecomb` with kerning, whose anchors
/// move in the Bold master.
fn variable_family() -> (OutlinedFamily, Vec<Vec<Vec<Anchor>>>) {
    let mut font = test_font();
    font.glyphs
        .retain(|g| ["o", "acutecomb"].contains(&g.name.as_str()));
    for g in &mut font.glyphs {
        g.anchors = match g.name.as_str() {
            "o" => vec![anchor("top", 281.0, 510.0)],
            _ => vec![anchor("_top", 0.0, 500.0), anchor("top", 10.0, 760.0)],
        };
    }
    font.features = None;
    font.kerning = vec![KernPair {
        left: "o".into(),
        right: "o".into(),
        value: -10.0,
    }];
    let default = outline_font(&font, font.info.tolerance);
    let mut designspace = Designspace::default();
    designspace
        .axes
        .push(Axis::linear("wght", "Weight", 400.0, 400.0, 700.0));
    let location = Location(BTreeMap::from([("wght".to_string(), 700.0)]));
    let model = designspace.model(std::slice::from_ref(&location)).unwrap();
    let bold = OutlinedMaster {
        name: "Bold".into(),
        location,
        glyphs: default
            .glyphs
            .iter()
            .map(|g| MasterGlyph {
                advance: g.advance,
                path: g.path.clone(),
                drawn: true,
            })
            .collect(),
        kerning: vec![KernPair {
            left: "o".into(),
            right: "o".into(),
            value: -40.0,
        }],
    };
    let bold_anchors = font
        .glyphs
        .iter()
        .map(|g| match g.name.as_str() {
            "o" => vec![anchor("top", 301.0, 530.0)],
            _ => vec![anchor("_top", 20.0, 520.0), anchor("top", 30.0, 800.0)],
        })
        .collect();
    let models = GlyphModels::full(1, &model, default.glyphs.len());
    let family = OutlinedFamily {
        designspace,
        default,
        masters: vec![bold],
        model,
        models,
    };
    (family, vec![bold_anchors])
}

#[test]
fn variable_anchors_and_kerning_blend_in_the_fonttools_instancer() {
    if no_python("fontTools.varLib.instancer", "pip install fonttools") {
        return;
    }
    let (family, anchors) = variable_family();
    let bytes = variable_ttf_with_anchors(&family, &anchors).expect("variable TTF builds");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("var.ttf");
    std::fs::write(&path, &bytes).unwrap();
    const SCRIPT: &str = r#"
import json, sys
from fontTools.ttLib import TTFont
from fontTools.varLib import instancer
out = []
for w in (400, 550, 700):
    font = instancer.instantiateVariableFont(TTFont(sys.argv[1]), {"wght": w})
    res = {}
    for lookup in font["GPOS"].table.LookupList.Lookup:
        st = lookup.SubTable[0]
        if lookup.LookupType == 2:
            res["kern"] = st.PairSet[0].PairValueRecord[0].Value1.XAdvance
        elif lookup.LookupType == 4:
            m, b = st.MarkArray.MarkRecord[0].MarkAnchor, st.BaseArray.BaseRecord[0].BaseAnchor[0]
            res["mark"] = [m.XCoordinate, m.YCoordinate, b.XCoordinate, b.YCoordinate]
    out.append(res)
print(json.dumps(out))
"#;
    let read = tools::python_json::<Value>(SCRIPT, &[&path]);
    // Default, halfway (the blend is linear on one axis: weight 0.5), Bold.
    assert_eq!(
        read,
        json!([
            {"kern": -10, "mark": [0, 500, 281, 510]},
            {"kern": -25, "mark": [10, 510, 291, 520]},
            {"kern": -40, "mark": [20, 520, 301, 530]},
        ])
    );
}

#[test]
fn errors_in_features_fea_are_at_file_line_col_and_nothing_is_written() {
    let out = tempfile::tempdir().unwrap();
    let out_dir = out.path().join("out");
    for (fixture, expected) in [
        (
            "unknown_glyph",
            "tests/fixtures/features/unknown_glyph/features.fea:4:16: error: glyph 'Aring' is \
             not in the font\n  |     sub A V by Aring;\n  |                ^\n",
        ),
        (
            "bad_syntax",
            "tests/fixtures/features/bad_syntax/features.fea:2:22: error: Expected ';'\n  |     \
             sub o o by oacute\n  |                      ^\n",
        ),
    ] {
        let dir = format!("tests/fixtures/features/{fixture}");
        let (code, stdout, _) = xglyph(&["check", &dir]);
        assert_eq!(code, 1, "{fixture}");
        assert_eq!(
            stdout,
            format!("{expected}1 error, 0 warnings\n"),
            "{fixture}"
        );
        let (code, _, stderr) = xglyph(&["build", &dir, "-o", out_dir.to_str().unwrap()]);
        assert_eq!(code, 1, "{fixture}");
        assert!(stderr.starts_with(expected), "{fixture}: {stderr}");
        assert!(
            stderr.ends_with(&format!("error: 1 error in {dir}; nothing was written\n")),
            "{fixture}: {stderr}"
        );
        assert!(!out_dir.exists(), "{fixture}: output written");
    }
}

#[test]
fn a_precomposed_letter_takes_a_further_accent_on_its_components_anchor() {
    if no_python("uharfbuzz, fontTools", "pip install uharfbuzz fonttools") {
        return;
    }
    // The bundled font as it is (precomposed letters in cmap): HarfBuzz composes e + U+0302
    // to `ecircumflex`, a composite without anchors of its own. Its `top` comes from its
    // components (the circumflex's `top`, moved to where the circumflex sits on the e), so
    // the acute stacks over the circumflex (Vietnamese ế).
    let (font, _) = load_font(Path::new("glyphs")).expect("the bundled typeface loads");
    let (_dir, paths) = built(&font);
    let e_top = anchor_at(&font, "e", "top");
    let (circ, circ_top) = (
        anchor_at(&font, "circumflexcomb", "_top"),
        anchor_at(&font, "circumflexcomb", "top"),
    );
    let acute = anchor_at(&font, "acutecomb", "_top");
    let top = (e_top.0 + circ_top.0 - circ.0, e_top.1 + circ_top.1 - circ.1);
    let adv = advance(&font, "ecircumflex") as i64;
    for path in &paths {
        let runs = shape(path, &["e\u{302}\u{301}"]);
        assert_eq!(
            runs[0],
            [
                ("ecircumflex".into(), adv, 0, 0),
                (
                    "acutecomb".into(),
                    0,
                    top.0 - acute.0 - adv,
                    top.1 - acute.1
                )
            ],
            "{}",
            path.display()
        );
    }
}

/// The `name` text of `id` in `font` (English, or the first record).
fn name_text(font: &skrifa::FontRef, id: skrifa::raw::types::NameId) -> Option<String> {
    use skrifa::MetadataProvider;
    Some(font.localized_strings(id).english_or_first()?.to_string())
}

/// The name of stylistic set `tag` in `font`, through its GSUB feature parameters.
fn stylistic_set_name(font: &skrifa::FontRef, tag: &[u8; 4]) -> Option<String> {
    use skrifa::raw::tables::layout::FeatureParams;
    use skrifa::raw::TableProvider;
    let gsub = font.gsub().ok()?;
    let list = gsub.feature_list().ok()?;
    let record = list
        .feature_records()
        .iter()
        .find(|r| r.feature_tag() == skrifa::raw::types::Tag::new(tag))?;
    let feature = record.feature(list.offset_data()).ok()?;
    match feature.feature_params()?.ok()? {
        FeatureParams::StylisticSet(p) => name_text(font, p.ui_name_id()),
        _ => None,
    }
}

#[test]
fn stylistic_set_names_reach_the_name_table_beside_the_variable_fonts_names() {
    // fea-rs numbers feature names from 256, as `fvar` and `STAT` names are: the layout's
    // come first and the variable font's take the IDs after them. (Before, the names were
    // dropped: GSUB pointed at IDs the name table lacked.)
    let features = FeatureFile {
        path: PathBuf::from("features.fea"),
        text: "feature ss01 {\n    featureNames {\n        name \"Accent \\0022o\\0022\";\n    \
               };\n    sub o by acutecomb;\n} ss01;\n"
            .into(),
    };
    let (mut family, anchors) = variable_family();
    family.default.features = Some(features.clone());
    let variable = variable_ttf_with_anchors(&family, &anchors).expect("variable TTF builds");
    let variable = skrifa::FontRef::new(&variable).unwrap();
    assert_eq!(
        stylistic_set_name(&variable, b"ss01").as_deref(),
        Some("Accent \"o\"")
    );
    use skrifa::raw::TableProvider;
    let fvar = variable.fvar().unwrap();
    let axis = fvar.axes().unwrap()[0].axis_name_id();
    assert_eq!(name_text(&variable, axis).as_deref(), Some("Weight"));
    assert_eq!(axis.to_u16(), 257);

    let mut font = test_font();
    font.features = Some(features);
    let (_dir, paths) = built(&font);
    for path in paths {
        let data = std::fs::read(&path).unwrap();
        let font = skrifa::FontRef::new(&data).unwrap();
        assert_eq!(
            stylistic_set_name(&font, b"ss01").as_deref(),
            Some("Accent \"o\""),
            "{path:?}"
        );
    }
}
