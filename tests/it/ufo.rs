//! UFO 3 export and import (issue 19): the bundled font exported, read back by norad,
//! imported again exactly; a foreign UFO fitted; and, with the Python tools installed
//! (fontmake, fontc, ufoLib2, fontTools, fontbakery), the export compiled by fontmake and
//! fontc and compared with xglyph's own TTF by `ufo_check.py`.
//!
//! Tool-backed tests print `skipped: …` and pass when a tool is missing, unless
//! `XGLYPH_REQUIRE_TOOLS=1` (CI), which makes them fail.

use std::path::{Path, PathBuf};
use std::process::Command;

use kurbo::{BezPath, Shape};
use xglyph::import::{import_ufo, ImportOptions};
use xglyph::outline::OutlinedFont;
use xglyph::source::emit::font_sources;
use xglyph::ufo;

use crate::common::paths::two_sided;
use crate::common::tools;

fn glyphs_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs")
}

fn bundled() -> OutlinedFont {
    xglyph::pipeline::load(&glyphs_dir(), None)
        .expect("the bundled font loads")
        .font
}

/// The bundled font exported into a fresh folder under `dir`.
fn exported(dir: &Path) -> (OutlinedFont, PathBuf) {
    let font = bundled();
    let path = dir.join(ufo::ufo_dir_name(&font));
    ufo::save(&font, &path).expect("exports");
    (font, path)
}

#[test]
fn export_then_import_gives_the_same_sources_byte_for_byte() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (_, path) = exported(dir.path());
    let (original, _) = xglyph::load_font(&glyphs_dir()).expect("loads");
    let imported = import_ufo(&path, &ImportOptions::default()).expect("imports");
    let want = font_sources(&original);
    let got = font_sources(&imported.font);
    assert_eq!(got.len(), want.len());
    for ((gn, gt), (wn, wt)) in got.iter().zip(&want) {
        assert_eq!(gn, wn);
        assert_eq!(gt, wt, "{gn}");
    }
    assert_eq!(imported.font, original);
    // Every glyph came from its lib; the measured distance to the .glif outline is the
    // build's fitting error (tolerance 0.5) plus the 1/1000-unit rounding.
    let drawn = original
        .glyphs
        .iter()
        .filter(|g| !g.contours.is_empty())
        .count();
    let note = format!("{drawn} glyph(s) taken exactly");
    assert!(
        imported.report.notes.iter().any(|n| n.starts_with(&note)),
        "{:?}",
        imported.report.notes
    );
    assert!(imported.report.max_error() <= 0.5 + 0.001);
    assert!(imported.report.max_error() > 0.01);
    // The emitted file names are the bundled files' names, but for one bundled file that
    // does not follow the UFO rule of src/names.rs (nor norad's): `uni00A0.toml`, which the
    // rule names `uni00A_0.toml`.
    for (name, _) in &got {
        let bundled = if name == "uni00A_0.toml" {
            "uni00A0.toml"
        } else {
            name
        };
        assert!(glyphs_dir().join(bundled).is_file(), "{name}");
    }
}

#[test]
fn export_is_deterministic_and_holds_what_the_sources_say() {
    let font = bundled();
    let a = ufo::output_files(&font).expect("exports");
    let b = ufo::output_files(&font).expect("exports");
    assert_eq!(a, b);
    let file = |name: &str| -> String {
        let (_, bytes) = a
            .iter()
            .find(|(p, _)| p == Path::new("XglyphSans-Regular.ufo").join(name).as_path())
            .unwrap_or_else(|| panic!("{name} exported"));
        String::from_utf8(bytes.clone()).expect("utf-8")
    };
    let names: Vec<String> = a
        .iter()
        .map(|(p, _)| p.to_string_lossy().into_owned())
        .filter(|p| !p.contains("/glyphs/"))
        .collect();
    assert_eq!(
        names,
        [
            "XglyphSans-Regular.ufo/features.fea",
            "XglyphSans-Regular.ufo/fontinfo.plist",
            "XglyphSans-Regular.ufo/kerning.plist",
            "XglyphSans-Regular.ufo/layercontents.plist",
            "XglyphSans-Regular.ufo/lib.plist",
            "XglyphSans-Regular.ufo/metainfo.plist",
        ]
    );
    // norad's UFO file names are the source files' stems (src/names.rs), glyph for glyph.
    let mut glifs: Vec<String> = a
        .iter()
        .filter_map(|(p, _)| {
            let name = p.strip_prefix("XglyphSans-Regular.ufo/glyphs").ok()?;
            Some(name.to_string_lossy().strip_suffix(".glif")?.to_string())
        })
        .collect();
    let (sources, _) = xglyph::load_font(&glyphs_dir()).expect("loads");
    let mut stems: Vec<String> = font_sources(&sources)
        .into_iter()
        .filter_map(|(n, _)| Some(n.strip_suffix(".toml")?.to_string()))
        .filter(|n| n != "font" && n != "kerning")
        .collect();
    glifs.sort();
    stems.sort();
    assert_eq!(glifs, stems);
    let aacute = file("glyphs/A_acute.glif");
    assert!(aacute.contains(r#"<advance width="620"/>"#), "{aacute}");
    assert!(aacute.contains(r#"<unicode hex="00C1"/>"#), "{aacute}");
    assert!(aacute.contains(r#"<component base="A"/>"#), "{aacute}");
    assert!(
        aacute.contains(r#"<component base="acutecomb" xOffset="310" yOffset="200"/>"#),
        "{aacute}"
    );
    assert!(!aacute.contains("<contour"), "{aacute}");
    let a_glif = file("glyphs/a.glif");
    assert!(a_glif.contains("<key>org.xglyph.xspline</key>"), "{a_glif}");
    // The first X-spline point of `a` as written in glyphs/a.toml.
    assert!(
        a_glif.contains("<array>\n\t\t\t\t\t\t<real>398</real>\n\t\t\t\t\t\t<real>0</real>"),
        "{a_glif}"
    );
    let info = file("fontinfo.plist");
    for want in [
        "<key>familyName</key>\n\t<string>Xglyph Sans</string>",
        "<key>unitsPerEm</key>\n\t<integer>1000</integer>",
        "<key>xHeight</key>\n\t<integer>510</integer>",
        "<key>versionMinor</key>\n\t<integer>100</integer>",
        "<key>openTypeOS2VendorID</key>\n\t<string>XGLY</string>",
    ] {
        assert!(info.contains(want), "{want} in {info}");
    }
    let kerning = file("kerning.plist");
    assert!(
        kerning.contains("<key>A</key>\n\t<dict>\n\t\t<key>C</key>\n\t\t<integer>-20</integer>"),
        "{kerning}"
    );
    let lib = file("lib.plist");
    assert!(
        lib.contains("<key>org.xglyph.tolerance</key>\n\t<real>0.5</real>"),
        "{lib}"
    );
    assert!(
        lib.contains("<key>public.glyphOrder</key>\n\t<array>\n\t\t<string>.notdef</string>"),
        "{lib}"
    );
    // No `mark = "outline"` glyph: no categories (compilers infer classes from anchors).
    assert!(!lib.contains("public.openTypeCategories"), "{lib}");
}

/// The glyph's own outline as the UFO holds it (norad reading the written files).
fn ufo_outline(glyph: &norad::Glyph) -> BezPath {
    let mut path = BezPath::new();
    for c in &glyph.contours {
        let n = c.points.len();
        let start = c
            .points
            .iter()
            .position(|p| p.typ != norad::PointType::OffCurve)
            .expect("an on-curve point");
        let pt = |i: usize| kurbo::Point::new(c.points[i % n].x, c.points[i % n].y);
        path.move_to(pt(start));
        let mut offs = Vec::new();
        for k in 1..=n {
            let p = &c.points[(start + k) % n];
            match p.typ {
                norad::PointType::OffCurve => offs.push(pt(start + k)),
                norad::PointType::Curve => {
                    assert_eq!(offs.len(), 2, "cubics only");
                    path.curve_to(offs[0], offs[1], pt(start + k));
                    offs.clear();
                }
                norad::PointType::Line => path.line_to(pt(start + k)),
                ref other => panic!("unexpected point type {other:?}"),
            }
        }
        path.close_path();
    }
    path
}

#[test]
fn exported_outlines_are_the_builds_own_contours() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (font, path) = exported(dir.path());
    let ufo = norad::Font::load(&path).expect("norad reads it back");
    assert_eq!(ufo.glyph_count(), font.glyphs.len());
    let mut compared = 0;
    for g in &font.glyphs {
        let u = ufo.get_glyph(&g.name).expect("every glyph exported");
        assert_eq!(u.width, g.advance, "{}", g.name);
        let cps: Vec<char> = u.codepoints.iter().collect();
        assert_eq!(cps, g.unicodes, "{}", g.name);
        assert_eq!(u.components.len(), g.components.len(), "{}", g.name);
        if !g.components.is_empty() {
            assert!(u.contours.is_empty(), "{}: no own contours", g.name);
            continue;
        }
        let mine = ufo_outline(u);
        // Same contours, same direction (signed area), points within the 1/1000 rounding.
        assert!(
            (mine.area() - g.path.area()).abs() <= 1e-3 * g.path.perimeter(0.1),
            "{}",
            g.name
        );
        let d = two_sided(&mine, &g.path, 16);
        assert!(d <= 0.0008, "{}: {d}", g.name);
        compared += 1;
    }
    assert!(compared > 100, "{compared}");
}

#[test]
fn a_foreign_ufo_is_fitted_with_components_groups_and_transforms() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (font, path) = exported(dir.path());
    let mut ufo = norad::Font::load(&path).expect("reads");
    // Another editor's UFO: no xglyph lib, a group kerning pair, an anchor, and a
    // component that is scaled.
    for g in ufo.default_layer_mut().iter_mut() {
        g.lib.clear();
    }
    ufo.lib.clear();
    let o = ufo.get_glyph_mut("o").expect("o");
    o.anchors.push(norad::Anchor::new(
        270.0,
        520.0,
        Some(norad::Name::new("top").expect("name")),
        None,
        None,
    ));
    // An anchor without a name, which the model has no place for.
    o.anchors
        .push(norad::Anchor::new(10.0, 20.0, None, None, None));
    let mut small = norad::Glyph::new("osmall");
    small.width = 300.0;
    small.components.push(norad::Component::new(
        norad::Name::new("o").expect("name"),
        norad::AffineTransform {
            x_scale: 0.5,
            y_scale: 0.5,
            ..Default::default()
        },
        None,
    ));
    ufo.default_layer_mut().insert_glyph(small);
    ufo.groups.insert(
        norad::Name::new("public.kern1.round").expect("name"),
        vec![
            norad::Name::new("o").expect("name"),
            norad::Name::new("osmall").expect("name"),
        ],
    );
    ufo.kerning
        .entry(norad::Name::new("public.kern1.round").expect("name"))
        .or_default()
        .insert(norad::Name::new("v").expect("name"), -42.0);
    let foreign = dir.path().join("Foreign.ufo");
    ufo.save(&foreign).expect("saves");

    let imported = import_ufo(&foreign, &ImportOptions::default()).expect("imports");
    let f = &imported.font;
    // Fitted within the import budget: 0.75 of 1/1000 em.
    assert!(imported.report.over_budget().is_empty());
    assert!(imported.report.max_error() <= 0.75);
    assert!(
        imported
            .report
            .notes
            .contains(&"1 anchor(s) without a name left out: xglyph anchors are named".to_string()),
        "{:?}",
        imported.report.notes
    );
    // The named anchors come in with the fitted glyph, at their exact positions: the
    // bundled `o`'s and the one added here.
    let mut want = font.glyph("o").expect("o").anchors.clone();
    want.push(xglyph::model::Anchor {
        name: "top".into(),
        position: (270.0, 520.0),
    });
    assert_eq!(f.glyph("o").expect("o").anchors, want);
    // The build tolerance without the lib: a quarter of the import tolerance.
    assert_eq!(f.info.tolerance, 0.25);
    assert_eq!(f.info.family, "Xglyph Sans");
    assert_eq!(f.info.version.as_deref(), Some("0.100"));
    assert_eq!(f.info.vendor, None);
    let aacute = f.glyph("Aacute").expect("Aacute");
    assert!(aacute.contours.is_empty());
    assert_eq!(aacute.components[1].base, "acutecomb");
    assert_eq!(aacute.components[1].offset, (310.0, 200.0));
    // The scaled component is drawn in, fitted: half the area of o.
    let osmall = f.glyph("osmall").expect("osmall");
    assert!(osmall.components.is_empty());
    assert_eq!(osmall.contours.len(), 2);
    let area = |g: &xglyph::Glyph| -> f64 {
        g.contours
            .iter()
            .map(|c| xglyph::fit::fit_contour(c.spline(), 0.1).path.area().abs())
            .sum()
    };
    let o_area = area(f.glyph("o").expect("o"));
    assert!(
        (area(osmall) / o_area - 0.25).abs() < 0.01,
        "{}",
        area(osmall) / o_area
    );
    // The group pair is expanded; a glyph pair of the original stays.
    assert_eq!(f.kern("o", "v"), -42.0);
    assert_eq!(f.kern("osmall", "v"), -42.0);
    assert_eq!(f.kern("A", "V"), font.kern("A", "V"));
    assert_eq!(f.kern("A", "V"), -85.0);
}

#[test]
fn a_broken_ufo_is_an_error_naming_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (_, path) = exported(dir.path());
    std::fs::write(
        path.join("glyphs/a.glif"),
        "<glyph name=\"a\" format=\"2\"><advance",
    )
    .expect("write");
    let err = import_ufo(&path, &ImportOptions::default()).unwrap_err();
    let text = err.to_string();
    assert!(
        text.starts_with(&format!("{}: cannot read the UFO: ", path.display())),
        "{text}"
    );
    assert!(text.contains("a.glif"), "{text}");
}

/// Whether fontmake, fontc, FontBakery, fontTools, ufoLib2 and defcon are there.
fn tools_available() -> bool {
    tools::available(
        tools::python_imports("fontTools, ufoLib2, defcon")
            && ["fontmake", "fontc", "fontbakery"]
                .iter()
                .all(|t| tools::program_runs(t, &["--help"])),
        "fontmake/fontc/ufoLib2/fontbakery",
        "pip install fontmake fontc ufoLib2 fontbakery",
    )
}

#[test]
fn fontmake_and_fontc_build_the_export_and_match_xglyphs_ttf() {
    if !tools_available() {
        return;
    }
    let dir = tempfile::tempdir().expect("temp dir");
    let (font, path) = exported(dir.path());
    let ours = dir.path().join("xglyph.ttf");
    std::fs::write(&ours, xglyph::otf::ttf(&font).expect("builds")).expect("write");
    let fontmake = dir.path().join("fontmake.ttf");
    tools::run(
        Command::new("fontmake")
            .arg("-u")
            .arg(&path)
            .args(["-o", "ttf", "--output-path"])
            .arg(&fontmake),
    );
    let fontc = dir.path().join("fontc.ttf");
    tools::run(Command::new("fontc").arg(&path).arg("-o").arg(&fontc));
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/it/ufo_check.py");
    let report = tools::run(
        Command::new("python3")
            .arg(&script)
            .arg(&path)
            .arg(&ours)
            .arg(&fontmake)
            .arg(&fontc)
            .arg(font.tolerance.to_string()),
    );
    println!("{report}");
    assert!(report.contains("ufo_check: all passed"), "{report}");
}

/// FontBakery 1.x has no `check-ufo-sources` command any more: its UFO checks run from
/// the universal profile on a `.ufo` argument. `-c ufo` selects them (ufolint and every
/// `ufo_*` check); the profile's family checks (which compare binary fonts) are left out.
#[test]
fn fontbakery_ufo_checks_pass() {
    if !tools_available() {
        return;
    }
    let dir = tempfile::tempdir().expect("temp dir");
    let (_, path) = exported(dir.path());
    let out = Command::new("fontbakery")
        .args([
            "check-universal",
            "-c",
            "ufo",
            "--succinct",
            "--loglevel",
            "PASS",
        ])
        .arg(&path)
        .output()
        .expect("runs");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    println!("{text}");
    assert!(
        out.status.success(),
        "fontbakery failed:\n{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for check in [
        "ufolint",
        "ufo_required_fields",
        "ufo_recommended_fields",
        "ufo_unnecessary_fields",
    ] {
        assert!(
            text.contains(&format!("{check}: PASS")),
            "{check} in {text}"
        );
    }
    assert!(text.contains("FAIL: 0 WARN: 0"), "{text}");
    assert!(text.contains("ERROR: 0 FATAL: 0"), "{text}");
}

/// The files of a font directory: name -> text, leading comment lines dropped (the model
/// has no comments, so an import cannot bring them back; `fmt` keeps them).
fn sources_without_leading_comments(dir: &Path) -> std::collections::BTreeMap<String, String> {
    std::fs::read_dir(dir)
        .expect("lists")
        .map(|e| {
            let path = e.expect("entry").path();
            let text = std::fs::read_to_string(&path).expect("reads");
            let body: String = text
                .split_inclusive('\n')
                .skip_while(|l| l.starts_with('#') || l.trim().is_empty())
                .collect();
            let name = path
                .file_name()
                .expect("a name")
                .to_string_lossy()
                .into_owned();
            (name, body)
        })
        .collect()
}

#[test]
fn cli_import_of_the_export_equals_the_formatted_sources() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (_, ufo_path) = exported(dir.path());
    // The bundled sources as `fmt` leaves them.
    let formatted = dir.path().join("formatted");
    std::fs::create_dir(&formatted).expect("mkdir");
    // The default master's files (master folders such as bold/ are a designspace's job).
    for e in std::fs::read_dir(glyphs_dir()).expect("lists") {
        let path = e.expect("entry").path();
        if path.is_file() {
            std::fs::copy(&path, formatted.join(path.file_name().expect("name"))).expect("copies");
        }
    }
    // A single UFO holds one master: the default, without the design space.
    let info = std::fs::read_to_string(formatted.join("font.toml")).expect("reads");
    let single = info.split("\n[[axis]]").next().expect("text").trim_end();
    std::fs::write(formatted.join("font.toml"), format!("{single}\n")).expect("writes");
    let bin = env!("CARGO_BIN_EXE_xglyph");
    tools::run(Command::new(bin).arg("fmt").arg(&formatted));
    let out = dir.path().join("imported");
    let report = tools::run(
        Command::new(bin)
            .arg("import")
            .arg(&ufo_path)
            .arg("-o")
            .arg(&out),
    );
    // Every glyph with contours of its own comes from its lib.
    let (bundled, _) = xglyph::load_font(&glyphs_dir()).expect("loads");
    let drawn = bundled
        .glyphs
        .iter()
        .filter(|g| !g.contours.is_empty())
        .count();
    assert!(drawn >= 102, "{drawn}");
    assert!(
        report.contains(&format!(
            "{drawn} glyph(s) taken exactly from their org.xglyph.xspline lib"
        )),
        "{report}"
    );
    let mut want = sources_without_leading_comments(&formatted);
    // The one bundled file whose name does not follow the file-name rule (see above).
    let nbsp = want.remove("uni00A0.toml").expect("bundled");
    want.insert("uni00A_0.toml".into(), nbsp);
    // The import writes every component offset; the sources leave out the ones their
    // anchors give (`oacute`). Apart from those lines the files are the same, and the two
    // folders load as the same font, offsets included.
    let strip = |files: std::collections::BTreeMap<String, String>| {
        files
            .into_iter()
            .map(|(name, text)| {
                let kept: Vec<&str> = text
                    .lines()
                    .filter(|l| !l.starts_with("offset = "))
                    .collect();
                (name, kept.join("\n"))
            })
            .collect::<std::collections::BTreeMap<_, _>>()
    };
    assert_eq!(strip(sources_without_leading_comments(&out)), strip(want));
    let (imported, _) = xglyph::load_font(&out).expect("loads");
    let (formatted_font, _) = xglyph::load_font(&formatted).expect("loads");
    assert_eq!(imported, formatted_font);
    // Flags that do not apply are refused, naming the flag.
    let refused = Command::new(bin)
        .arg("import")
        .arg(&ufo_path)
        .args(["--glyphs", "A-Z", "-o"])
        .arg(dir.path().join("other"))
        .output()
        .expect("runs");
    assert_eq!(refused.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&refused.stderr).contains(
        "--glyphs does not apply to a UFO (it imports every glyph of its default layer)"
    ));
    assert!(!dir.path().join("other").exists());
}

/// A UFO as other tools leave them (from ufo2ft's and fontmake's test data): zero vertical
/// metrics, a hyphenated glyph name, a combining mark without anchors, and features that
/// include a file next to the UFO. The import writes sources that `check` accepts.
#[test]
fn a_sparse_foreign_ufo_comes_in_as_sources_that_check() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut ufo = norad::Font::new();
    ufo.font_info.units_per_em =
        Some(norad::fontinfo::NonNegativeIntegerOrFloat::new(1000.0).unwrap());
    ufo.font_info.family_name = Some("Sparse".into());
    // Zero metrics, as fontTools' defaults leave them in test UFOs.
    ufo.font_info.ascender = Some(0.0);
    ufo.font_info.descender = Some(0.0);
    let mut beh = norad::Glyph::new("beh-ar");
    beh.width = 500.0;
    beh.codepoints.insert('\u{0628}');
    let pt =
        |x: f64, y: f64| norad::ContourPoint::new(x, y, norad::PointType::Line, false, None, None);
    beh.contours.push(norad::Contour::new(
        vec![
            pt(50.0, 0.0),
            pt(450.0, 0.0),
            pt(450.0, 100.0),
            pt(50.0, 100.0),
        ],
        None,
    ));
    let mut cgj = norad::Glyph::new("cgj");
    cgj.codepoints.insert('\u{034F}');
    ufo.default_layer_mut().insert_glyph(beh);
    ufo.default_layer_mut().insert_glyph(cgj);
    ufo.features = "include(shared.fea);\nfeature ss01 { sub beh-ar by beh-ar; } ss01;\n".into();
    let path = dir.path().join("Sparse.ufo");
    ufo.save(&path).expect("saves");
    std::fs::write(dir.path().join("shared.fea"), "@arabic = [beh-ar];\n").unwrap();

    let src = dir.path().join("src");
    let (code, _, err) = crate::common::cli::xglyph(&[
        "import",
        path.to_str().unwrap(),
        "-o",
        src.to_str().unwrap(),
    ]);
    assert_eq!((code, err.as_str()), (0, ""));
    let info = std::fs::read_to_string(src.join("font.toml")).unwrap();
    assert!(
        info.contains("\nascender = 800\ndescender = -200\n"),
        "{info}"
    );
    assert_eq!(
        std::fs::read_to_string(src.join("features.fea")).unwrap(),
        "@arabic = [beh_ar];\n\nfeature ss01 { sub beh_ar by beh_ar; } ss01;\n"
    );
    assert!(std::fs::read_to_string(src.join("cgj.toml"))
        .unwrap()
        .contains("mark = \"outline\""));
    let (code, out, err) = crate::common::cli::xglyph(&["check", src.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");

    // A UFO without glyphs cannot become sources: refused, naming it.
    let empty = dir.path().join("Empty.ufo");
    norad::Font::new().save(&empty).expect("saves");
    let (code, out, err) = crate::common::cli::xglyph(&[
        "import",
        empty.to_str().unwrap(),
        "-o",
        dir.path().join("empty-src").to_str().unwrap(),
    ]);
    assert_eq!((code, out.as_str()), (1, ""));
    assert_eq!(
        err,
        format!(
            "error: {}: the UFO has no glyphs in its default layer\n",
            empty.display()
        )
    );
}
