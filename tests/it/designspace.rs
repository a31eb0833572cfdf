//! Designspace export (issue 19, item 2) of the bundled two-master typeface, and anchors
//! through UFO export and import (items 1 and 3).
//!
//! The family is loaded, fitted and its variable outputs rendered once per test run
//! ([`built`]); the tool-backed test builds the designspace with fontmake and fontc once
//! and compares them with xglyph's variable TTF in one `designspace_check.py` run.
//! Tool-backed tests print `skipped: …` and pass when a tool is missing, unless
//! `XGLYPH_REQUIRE_TOOLS=1` (CI).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use kurbo::{BezPath, PathEl, Point};
use xglyph::family::{outline_family, OutlinedFamily};
use xglyph::import::{import_ufo, ImportOptions};
use xglyph::model::Anchor;
use xglyph::pipeline::{self, Loaded, OutputFile};
use xglyph::ufo;

use crate::common::tools;

/// The bundled font loaded, its compatible fit, and the variable outputs of a build
/// written into `dir`.
struct Built {
    dir: PathBuf,
    loaded: Loaded,
    family: OutlinedFamily,
    files: Vec<OutputFile>,
}

fn built() -> &'static Built {
    static BUILT: OnceLock<Built> = OnceLock::new();
    BUILT.get_or_init(|| {
        let glyphs = Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
        let loaded = pipeline::load(&glyphs, None).expect("the bundled font loads");
        let (files, _) = pipeline::variable_outputs(&loaded, None)
            .expect("builds")
            .expect("the bundled font has masters");
        let (family, _) =
            outline_family(&loaded.family, loaded.font.tolerance).expect("fits compatibly");
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("designspace-bundled");
        let _ = std::fs::remove_dir_all(&dir);
        pipeline::write_outputs(&dir, &files).expect("writes");
        Built {
            dir,
            loaded,
            family,
            files,
        }
    })
}

#[test]
fn build_writes_a_ufo_per_master_and_the_designspace_deterministically() {
    let b = built();
    let mut top: Vec<String> = b
        .files
        .iter()
        .filter_map(|(p, _)| p.components().next())
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    top.dedup();
    assert_eq!(
        top,
        [
            "XglyphSans[wght].ttf",
            "XglyphSans[wght].woff2",
            "XglyphSans-Regular.ufo",
            "XglyphSans-Bold.ufo",
            "XglyphSans.designspace",
        ]
    );
    // A second, independent fit gives the same bytes.
    let again = ufo::designspace::output_files(&b.family, &b.loaded.family).expect("exports");
    assert_eq!(again.as_slice(), &b.files[2..]);
    // norad reads the designspace back: the axes, sources and instances of font.toml.
    let doc = norad::designspace::DesignSpaceDocument::load(b.dir.join("XglyphSans.designspace"))
        .expect("norad reads it");
    type AxisRow<'a> = (&'a str, &'a str, Option<f64>, f64, Option<f64>);
    let axes: Vec<AxisRow> = doc
        .axes
        .iter()
        .map(|a| {
            (
                a.tag.as_str(),
                a.name.as_str(),
                a.minimum,
                a.default,
                a.maximum,
            )
        })
        .collect();
    assert_eq!(axes, [("wght", "Weight", Some(400.0), 400.0, Some(700.0))]);
    let sources: Vec<(&str, Option<&str>, Option<f64>)> = doc
        .sources
        .iter()
        .map(|s| {
            (
                s.filename.as_str(),
                s.stylename.as_deref(),
                s.location[0].xvalue,
            )
        })
        .collect();
    assert_eq!(
        sources,
        [
            ("XglyphSans-Regular.ufo", Some("Regular"), Some(400.0)),
            ("XglyphSans-Bold.ufo", Some("Bold"), Some(700.0)),
        ]
    );
    let instances: Vec<(Option<&str>, Option<f64>)> = doc
        .instances
        .iter()
        .map(|i| (i.stylename.as_deref(), i.location[0].xvalue))
        .collect();
    let want: Vec<(Option<&str>, Option<f64>)> = b
        .loaded
        .family
        .designspace
        .instances
        .iter()
        .map(|i| (Some(i.name.as_str()), i.location.0.get("wght").copied()))
        .collect();
    assert_eq!(instances, want);
    assert_eq!(instances.len(), 4);
}

/// The UFO point list of a closed subpath as `build` writes it (each segment's points,
/// the start point last), rounded to 1/1000 unit: an oracle written from the UFO spec.
fn ufo_points(sub: &BezPath) -> Vec<(f64, f64)> {
    let mut start = Point::ZERO;
    let mut points = Vec::new();
    for el in sub.elements() {
        match *el {
            PathEl::MoveTo(p) => start = p,
            PathEl::LineTo(p) => points.push(p),
            PathEl::QuadTo(a, p) => points.extend([a, p]),
            PathEl::CurveTo(a, c, p) => points.extend([a, c, p]),
            PathEl::ClosePath => {}
        }
    }
    if points.last() != Some(&start) {
        points.push(start);
    }
    let round = |v: f64| (v * 1000.0).round() / 1000.0 + 0.0;
    points.iter().map(|p| (round(p.x), round(p.y))).collect()
}

fn subpaths(path: &BezPath) -> Vec<BezPath> {
    let mut out: Vec<BezPath> = Vec::new();
    for el in path.elements() {
        if let PathEl::MoveTo(_) = el {
            out.push(BezPath::new());
        }
        if let Some(last) = out.last_mut() {
            last.push(*el);
        }
    }
    out
}

#[test]
fn master_ufos_hold_the_compatible_cubics_and_each_masters_sources() {
    let b = built();
    let bold_model: HashMap<&str, &xglyph::Glyph> = b.loaded.family.masters[0]
        .glyphs
        .iter()
        .map(|g| (g.name.as_str(), g))
        .collect();
    let mut compared = 0;
    for (m, dir) in ["XglyphSans-Regular.ufo", "XglyphSans-Bold.ufo"]
        .iter()
        .enumerate()
    {
        let font = norad::Font::load(b.dir.join(dir)).expect("norad reads it");
        for (i, g) in b.family.default.glyphs.iter().enumerate() {
            let ufo = font.get_glyph(g.name.as_str()).expect("every glyph");
            let (path, advance) = if m == 0 {
                (&g.path, g.advance)
            } else {
                let mg = &b.family.masters[0].glyphs[i];
                (&mg.path, mg.advance)
            };
            assert_eq!(ufo.width, advance, "{}", g.name);
            // The glyph's own contours are the compatible fit's, point for point.
            let want: Vec<Vec<(f64, f64)>> = subpaths(path)
                .iter()
                .take(ufo.contours.len())
                .map(ufo_points)
                .collect();
            let got: Vec<Vec<(f64, f64)>> = ufo
                .contours
                .iter()
                .map(|c| c.points.iter().map(|p| (p.x, p.y)).collect())
                .collect();
            assert_eq!(got, want, "{dir} {}", g.name);
            compared += got.len();
            // The X-spline lib holds this master's own sources.
            let source = if m == 0 {
                b.loaded.family.default.glyph(&g.name).expect("glyph")
            } else {
                bold_model[g.name.as_str()]
            };
            if let Some(lib) = ufo.lib.get(ufo::lib::XSPLINE_KEY) {
                assert_eq!(
                    ufo::lib::read_xspline(lib).expect("reads"),
                    source.contours,
                    "{}",
                    g.name
                );
            } else {
                assert!(source.contours.is_empty(), "{}", g.name);
            }
            let offsets: Vec<(f64, f64)> = ufo
                .components
                .iter()
                .map(|c| (c.transform.x_offset, c.transform.y_offset))
                .collect();
            let want: Vec<(f64, f64)> = source.components.iter().map(|c| c.offset).collect();
            assert_eq!(offsets, want, "{}", g.name);
        }
        // The kerning is the master's own.
        let kerning = if m == 0 {
            &b.loaded.family.default.kerning
        } else {
            &b.loaded.family.masters[0].kerning
        };
        let k = &kerning[0];
        assert_eq!(
            font.kerning[k.left.as_str()][k.right.as_str()],
            k.value,
            "{dir}"
        );
    }
    assert!(compared > 2 * 100, "{compared}");
    // The Bold master differs from the default: its advances are its own.
    let wider = b.family.masters[0]
        .glyphs
        .iter()
        .zip(&b.family.default.glyphs)
        .filter(|(bold, regular)| bold.advance > regular.advance)
        .count();
    assert!(wider > 100, "{wider}");
}

#[test]
fn the_bold_master_ufo_imports_back_to_the_bold_sources_exactly() {
    let b = built();
    let imported = import_ufo(
        &b.dir.join("XglyphSans-Bold.ufo"),
        &ImportOptions::default(),
    )
    .expect("imports");
    let mut got = imported.font.glyphs.clone();
    let mut want = b.loaded.family.masters[0].glyphs.clone();
    got.sort_by(|a, b| a.name.cmp(&b.name));
    want.sort_by(|a, b| a.name.cmp(&b.name));
    assert!(got.len() >= 155, "{}", got.len());
    assert_eq!(got, want);
    assert_eq!(imported.font.info.style, "Bold");
}

/// The bundled family with anchors on `o` (default and Bold master, at different places)
/// and a mark anchor on `acutecomb`: positions with fractions that only an exact writer
/// keeps.
fn with_anchors(b: &Built) -> (OutlinedFamily, xglyph::model::Family) {
    let mut family = b.family.clone();
    let mut model = b.loaded.family.clone();
    let top = |x: f64, y: f64| Anchor {
        name: "top".into(),
        position: (x, y),
    };
    let set = |glyphs: &mut Vec<xglyph::Glyph>, name: &str, anchors: Vec<Anchor>| {
        glyphs
            .iter_mut()
            .find(|g| g.name == name)
            .expect("glyph")
            .anchors = anchors;
    };
    set(&mut model.default.glyphs, "o", vec![top(270.5, 1.0 / 3.0)]);
    set(&mut model.masters[0].glyphs, "o", vec![top(301.25, 555.0)]);
    let mark = vec![Anchor {
        name: "_top".into(),
        position: (-0.1, 510.0),
    }];
    set(&mut model.masters[0].glyphs, "acutecomb", mark.clone());
    for g in &mut family.default.glyphs {
        if g.name == "o" {
            g.anchors = vec![top(270.5, 1.0 / 3.0)];
        }
    }
    (family, model)
}

#[test]
fn anchors_survive_export_and_import_in_every_master() {
    let b = built();
    let (family, model) = with_anchors(b);
    let files = ufo::designspace::output_files(&family, &model).expect("exports");
    let text = |path: &str| -> String {
        let (_, bytes) = files
            .iter()
            .find(|(p, _)| p == Path::new(path))
            .expect(path);
        String::from_utf8(bytes.clone()).expect("utf-8")
    };
    assert!(
        text("XglyphSans-Regular.ufo/glyphs/o.glif")
            .contains(r#"<anchor name="top" x="270.5" y="0.3333333333333333"/>"#),
        "{}",
        text("XglyphSans-Regular.ufo/glyphs/o.glif")
    );
    assert!(text("XglyphSans-Bold.ufo/glyphs/o.glif")
        .contains(r#"<anchor name="top" x="301.25" y="555"/>"#));
    assert!(text("XglyphSans-Bold.ufo/glyphs/acutecomb.glif")
        .contains(r#"<anchor name="_top" x="-0.1" y="510"/>"#));
    // Written out and imported: the anchors come back exactly, per master.
    let dir = tempfile::tempdir().expect("temp dir");
    pipeline::write_outputs(dir.path(), &files).expect("writes");
    for (ufo_dir, glyph, want) in [
        ("XglyphSans-Regular.ufo", "o", (270.5, 1.0 / 3.0)),
        ("XglyphSans-Bold.ufo", "o", (301.25, 555.0)),
        ("XglyphSans-Bold.ufo", "acutecomb", (-0.1, 510.0)),
    ] {
        let imported =
            import_ufo(&dir.path().join(ufo_dir), &ImportOptions::default()).expect("imports");
        let g = imported.font.glyph(glyph).expect("glyph");
        assert_eq!(g.anchors.len(), 1, "{ufo_dir} {glyph}");
        assert_eq!(g.anchors[0].position, want, "{ufo_dir} {glyph}");
        assert_eq!(g.anchors[0].name.starts_with('_'), glyph == "acutecomb");
    }
}

#[test]
fn an_anchor_name_ufo_cannot_hold_is_an_error_naming_the_glyph() {
    let b = built();
    let mut font = b.loaded.font.clone();
    font.glyphs[3].anchors = vec![Anchor {
        name: "a\u{7}b".into(),
        position: (0.0, 0.0),
    }];
    let name = font.glyphs[3].name.clone();
    let err = ufo::export(&font).expect_err("refused").to_string();
    assert_eq!(
        err,
        format!(
            "UFO export: glyph `{name}` has the anchor name \"a\\u{{7}}b\", which is not a \
             valid UFO name"
        )
    );
}

#[test]
fn fontmake_and_fontc_build_the_designspace_and_match_xglyphs_variable_font() {
    if !tools::designspace_compilers_available() {
        return;
    }
    let b = built();
    let ds = b.dir.join("XglyphSans.designspace");
    // The masters, a named instance between them, and two positions off the instances.
    let report = tools::check_designspace_compilers(
        &ds,
        &b.dir.join("XglyphSans[wght].ttf"),
        &b.dir,
        b.loaded.font.tolerance,
        &["400", "500", "550", "650", "700"],
    );
    println!("{report}");
    // fontTools.designspaceLib finds what font.toml says.
    for line in [
        "axes: wght Weight 400 400 700",
        "sources: XglyphSans-Regular.ufo Regular Weight=400, XglyphSans-Bold.ufo Bold Weight=700",
        "instances: Regular Weight=400, Medium Weight=500, SemiBold Weight=600, Bold Weight=700",
    ] {
        assert!(report.lines().any(|l| l == line), "{line}\n{report}");
    }
    // Every comparison ran: 2 UFOs; per font 5 header checks and 2 per master; outlines
    // at 5 positions for fontmake and fontc.
    let oks = report.lines().filter(|l| l.starts_with("ok ")).count();
    assert_eq!(oks, 2 + 3 * (5 + 2 * 2) + 2 * 5, "{report}");
    assert!(report.contains("designspace_check: all passed"), "{report}");
}

#[test]
fn cli_import_of_the_designspace_gives_back_the_family() {
    let b = built();
    let tmp = tempfile::tempdir().expect("temp dir");
    let out = tmp.path().join("font");
    let ds = b.dir.join("XglyphSans.designspace");
    let (code, stdout, stderr) = crate::common::cli::import(&[ds.to_str().unwrap()], &out);
    assert_eq!((code, stderr.as_str()), (0, ""), "{stdout}");
    assert!(stdout.starts_with("source Regular:\n"), "{stdout}");
    assert!(stdout.contains("\nsource Bold:\n"), "{stdout}");
    // font.toml, features.fea, a file per glyph in each master, and each master's
    // kerning.toml.
    let files = 2 + 2 * (b.loaded.family.default.glyphs.len() + 1);
    assert!(
        stdout.ends_with(&format!("wrote {files} files to {}\n", out.display())),
        "{stdout}"
    );
    // The masters format: font.toml with the axis, the Bold master and the instances, and
    // the Bold folder.
    let toml = std::fs::read_to_string(out.join("font.toml")).expect("font.toml");
    let bundled =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs/font.toml"))
            .expect("bundled font.toml");
    assert_eq!(toml, bundled);
    assert!(out.join("bold/a.toml").is_file());
    // Loaded again, it is the bundled family: every master's glyphs and kerning, exactly.
    let (family, warnings) = xglyph::source::load_family(&out).expect("loads");
    assert!(warnings.is_empty(), "{warnings:?}");
    let want = &b.loaded.family;
    assert_eq!(family.designspace, want.designspace);
    assert_eq!(family.default, want.default);
    assert_eq!(family.masters.len(), 1);
    assert_eq!(family.masters[0].glyphs, want.masters[0].glyphs);
    assert_eq!(family.masters[0].kerning, want.masters[0].kerning);
    assert_eq!(family.masters[0].location, want.masters[0].location);
}

/// A rule condition on an axis the designspace does not declare is left out with a note,
/// as fontTools' `splitInterpolable` (fontmake's way in) leaves it out; the other
/// conditions of its set stay.
#[test]
fn a_rule_condition_on_an_undeclared_axis_is_left_out_with_a_note() {
    let b = built();
    let tmp = tempfile::tempdir().expect("temp dir");
    let text = std::fs::read_to_string(b.dir.join("XglyphSans.designspace")).expect("reads");
    let rules = "</axes>\n  <rules>\n    <rule name=\"alt\">\n      <conditionset>\n        \
                 <condition name=\"Weight\" minimum=\"600\" maximum=\"700\"/>\n        \
                 <condition name=\"serif\" minimum=\"0\" maximum=\"0\"/>\n      \
                 </conditionset>\n      <sub name=\"a\" with=\"b\"/>\n    </rule>\n  </rules>";
    assert!(text.contains("</axes>"), "{text}");
    let ds = b.dir.join("undeclared-axis.designspace");
    std::fs::write(&ds, text.replacen("</axes>", rules, 1)).expect("writes");
    let out = tmp.path().join("font");
    let stdout = crate::common::cli::import_ok(&[ds.to_str().unwrap()], &out);
    assert!(
        stdout.contains(
            "note: rule `alt`: its condition on `serif`, which is not an axis, is left out, as \
             fontmake leaves it out\n"
        ),
        "{stdout}"
    );
    let toml = std::fs::read_to_string(out.join("font.toml")).expect("font.toml");
    assert!(
        toml.contains(
            "[[rule]]\nname = \"alt\"\nconditions = [{ wght = [600, 700] }]\n\
             substitutions = { a = \"b\" }\n"
        ),
        "{toml}"
    );
}

#[test]
fn designspace_import_errors_name_the_file_and_the_problem() {
    let b = built();
    let tmp = tempfile::tempdir().expect("temp dir");
    let text = std::fs::read_to_string(b.dir.join("XglyphSans.designspace")).expect("reads");
    let cases = [
        (
            text.replace(
                r#"xvalue="400"/>
      </location>
    </source>"#,
                r#"xvalue="450"/>
      </location>
    </source>"#,
            ),
            "no source sits at the default of every axis",
        ),
        (
            text.replace("XglyphSans-Bold.ufo", "Missing.ufo"),
            "cannot read the UFO",
        ),
        (
            text.replace("<axes>", "<axes><axis"),
            "cannot read the designspace",
        ),
        // Sources xglyph's masters cannot hold are refused before any UFO is read.
        (
            text.replace(
                r#"xvalue="700"/>
      </location>
    </source>"#,
                r#"xvalue="400"/>
      </location>
    </source>"#,
            ),
            "sources `Regular` and `Bold` both sit at the default of every axis",
        ),
    ];
    for (i, (text, message)) in cases.iter().enumerate() {
        let path = b.dir.join(format!("broken-{i}.designspace"));
        std::fs::write(&path, text).expect("writes");
        let out = tmp.path().join(format!("out-{i}"));
        let err = crate::common::cli::import_fails(&[path.to_str().unwrap()], &out);
        assert!(err.contains(message), "{i}: {err}");
        let named = if i == 1 {
            b.dir.join("Missing.ufo")
        } else {
            path.clone()
        };
        assert!(
            err.starts_with(&format!("error: {}: ", named.display())),
            "{i}: {err}"
        );
    }
    // Another editor's master whose points differ cannot be a master.
    let bold = b.dir.join("XglyphSans-Bold.ufo");
    let mut ufo = norad::Font::load(&bold).expect("reads");
    let o = ufo.get_glyph_mut("o").expect("o");
    o.lib.clear();
    o.contours.truncate(1);
    let edited = tmp.path().join("edited");
    std::fs::create_dir_all(&edited).expect("dir");
    ufo.save(edited.join("XglyphSans-Bold.ufo")).expect("saves");
    norad::Font::load(b.dir.join("XglyphSans-Regular.ufo"))
        .expect("reads")
        .save(edited.join("XglyphSans-Regular.ufo"))
        .expect("saves");
    std::fs::write(edited.join("X.designspace"), &text).expect("writes");
    let err = crate::common::cli::import_fails(
        &[edited.join("X.designspace").to_str().unwrap()],
        &tmp.path().join("out-edited"),
    );
    assert!(
        err.contains("glyph `o`: master `Bold` does not match the default source (1 contours"),
        "{err}"
    );
}
