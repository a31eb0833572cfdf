//! Import of a variable font (issue 16, item 6) and compatible import of foreign masters.
//!
//! The bundled family is built once ([`round_trip`]): its variable TTF is imported into a
//! font with masters, which `check` accepts and `build` turns into a variable TTF again;
//! both variable fonts are read with skrifa at the same positions and compared glyph by
//! glyph. The combining marks are left out of the import: a font import does not read
//! GPOS anchors, and `check` wants a `_` anchor on every combining mark.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use skrifa::instance::{LocationRef, Size};
use skrifa::{FontRef, MetadataProvider};

use crate::common::cli::{import, import_fails, xglyph};
use crate::common::fonts::skrifa_outline;
use crate::common::paths;

/// The import tolerance: the default, 1/1000 of the 1000-unit em.
const TOLERANCE: f64 = 1.0;

/// The bundled family's build, its variable TTF imported, and the import built again.
struct RoundTrip {
    dir: tempfile::TempDir,
    /// The bundled family's variable TTF.
    original: PathBuf,
    /// The imported font folder.
    imported: PathBuf,
    /// Its build's variable TTF.
    rebuilt: PathBuf,
    /// The import's report.
    report: String,
}

fn round_trip() -> &'static RoundTrip {
    static TRIP: OnceLock<RoundTrip> = OnceLock::new();
    TRIP.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let built = dir.path().join("built");
        let glyphs = Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
        let (code, _, err) = xglyph(&["build", glyphs.to_str().unwrap(), "-o", s(&built)]);
        assert_eq!(code, 0, "{err}");
        let original = built.join("XglyphSans[wght].ttf");
        // Every character of the family but the combining marks (U+0300–U+036F).
        let data = bytes(&original);
        let glyphs: Vec<String> = FontRef::new(&data)
            .unwrap()
            .charmap()
            .mappings()
            .filter(|(c, _)| !is_mark(*c))
            .map(|(c, _)| format!("U+{c:04X}"))
            .collect();
        let imported = dir.path().join("imported");
        let list = glyphs.join(",");
        let (code, report, err) = import(&[s(&original), "--glyphs", &list], &imported);
        assert_eq!((code, err.as_str()), (0, ""));
        let rebuilt_dir = dir.path().join("rebuilt");
        let (code, _, err) = xglyph(&["build", s(&imported), "-o", s(&rebuilt_dir)]);
        assert_eq!(code, 0, "{err}");
        RoundTrip {
            original,
            imported,
            rebuilt: rebuilt_dir.join("XglyphSans[wght].ttf"),
            report,
            dir,
        }
    })
}

fn is_mark(c: u32) -> bool {
    (0x300..0x370).contains(&c)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn the_imported_family_has_the_axes_instances_and_masters_of_fvar() {
    let trip = round_trip();
    let toml: toml::Table = std::fs::read_to_string(trip.imported.join("font.toml"))
        .unwrap()
        .parse()
        .unwrap();
    let axis = &toml["axis"].as_array().unwrap()[0];
    assert_eq!(
        (
            axis["tag"].as_str(),
            axis["name"].as_str(),
            axis["min"].as_integer(),
            axis["default"].as_integer(),
            axis["max"].as_integer()
        ),
        (
            Some("wght"),
            Some("Weight"),
            Some(400),
            Some(400),
            Some(700)
        )
    );
    let names = |key: &str| -> Vec<String> {
        toml[key]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| format!("{} {}", v["name"].as_str().unwrap(), v["location"]))
            .collect()
    };
    assert_eq!(
        names("instance"),
        [
            "Regular { wght = 400 }",
            "Medium { wght = 500 }",
            "SemiBold { wght = 600 }",
            "Bold { wght = 700 }"
        ]
    );
    assert_eq!(names("master"), ["Bold { wght = 700 }"]);
    assert_eq!(toml["style"].as_str(), Some("Regular"));
    assert!(trip.imported.join("bold/A_.toml").is_file());
    // The report: one table per master, every glyph within the import share (0.75 T).
    assert!(
        trip.report.starts_with("master Regular:\n"),
        "{}",
        trip.report
    );
    assert!(trip.report.contains("\nmaster Bold:\n"));
    for line in trip.report.lines().filter(|l| l.starts_with("total:")) {
        let error: f64 = line.split("max error ").nth(1).unwrap()[..5]
            .parse()
            .unwrap();
        assert!(error <= 0.75 * TOLERANCE, "{line}");
    }
    // The rebuilt variable font has the same axis and named instances.
    let (a, b) = (bytes(&trip.original), bytes(&trip.rebuilt));
    let (a, b) = (FontRef::new(&a).unwrap(), FontRef::new(&b).unwrap());
    assert_eq!(fvar(&a), fvar(&b));
    assert_eq!(fvar(&a).1.len(), 4);
}

#[test]
fn the_imported_family_checks_and_matches_the_original_between_the_masters() {
    let trip = round_trip();
    let (code, out, err) = xglyph(&["check", s(&trip.imported)]);
    assert_eq!(code, 0, "{out}{err}");
    let (a, b) = (bytes(&trip.original), bytes(&trip.rebuilt));
    let (a, b) = (FontRef::new(&a).unwrap(), FontRef::new(&b).unwrap());
    let (mut worst, mut glyphs) = (0.0f64, 0);
    for wght in [400.0, 475.0, 550.0, 625.0, 700.0] {
        let (la, lb) = (
            a.axes().location([("wght", wght)]),
            b.axes().location([("wght", wght)]),
        );
        let (ma, mb) = (
            a.glyph_metrics(Size::unscaled(), LocationRef::from(&la)),
            b.glyph_metrics(Size::unscaled(), LocationRef::from(&lb)),
        );
        for (c, ga) in a.charmap().mappings() {
            if is_mark(c) {
                continue;
            }
            let gb = b.charmap().map(c).expect("every character comes back");
            glyphs += 1;
            assert_eq!(
                ma.advance_width(ga),
                mb.advance_width(gb),
                "U+{c:04X} at wght {wght}"
            );
            let d = paths::two_sided(
                &skrifa_outline(&a, ga, (&la).into()),
                &skrifa_outline(&b, gb, (&lb).into()),
                32,
            );
            // Import and build stay within T of the original; the rebuilt glyf rounds
            // every point to whole units (half a unit per coordinate), and between the
            // masters skrifa adds each font's interpolated deltas rounded to whole units
            // (as FreeType does), another half unit per coordinate in each font.
            let half = 0.5f64.hypot(0.5);
            let bound = TOLERANCE
                + if wght == 400.0 || wght == 700.0 {
                    half
                } else {
                    3.0 * half
                };
            assert!(d <= bound, "U+{c:04X} at wght {wght}: {d} > {bound}");
            worst = worst.max(d);
        }
    }
    eprintln!("{glyphs} glyph outlines at 5 positions: worst distance {worst:.3}");
    assert!(glyphs >= 5 * 140, "{glyphs}");
}

#[test]
fn a_damaged_variable_font_is_an_error_naming_the_file() {
    let trip = round_trip();
    let data = bytes(&trip.original);
    let font = FontRef::new(&data).unwrap();
    // gvar cut short: its table record claims 24 bytes, the header alone.
    let record = font
        .table_directory
        .table_records()
        .iter()
        .position(|r| r.tag() == skrifa::Tag::new(b"gvar"))
        .unwrap();
    let mut truncated = data.clone();
    let length_at = 12 + 16 * record + 12;
    truncated[length_at..length_at + 4].copy_from_slice(&24u32.to_be_bytes());
    let path = trip.dir.path().join("Truncated-VF.ttf");
    std::fs::write(&path, &truncated).unwrap();
    let out = trip.dir.path().join("truncated-out");
    let err = import_fails(&[s(&path)], &out);
    assert!(
        err.starts_with(&format!("error: {}: cannot read the gvar", path.display())),
        "{err}"
    );
    assert!(err.ends_with("the font may be damaged\n"), "{err}");
    // An avar that goes flat: an axis map must increase, to be inverted.
    let mut builder = write_fonts::FontBuilder::new();
    for r in font.table_directory.table_records() {
        builder.add_raw(
            r.tag(),
            font.table_data(r.tag()).unwrap().as_bytes().to_vec(),
        );
    }
    use write_fonts::tables::avar::{Avar, AxisValueMap, SegmentMaps};
    use write_fonts::types::F2Dot14;
    let map = |a: f32, b: f32| AxisValueMap::new(F2Dot14::from_f32(a), F2Dot14::from_f32(b));
    let avar = Avar::new(vec![SegmentMaps::new(vec![
        map(-1.0, -1.0),
        map(0.0, 0.0),
        map(0.5, 0.0),
        map(1.0, 1.0),
    ])]);
    builder.add_table(&avar).unwrap();
    let path = trip.dir.path().join("Avar-VF.ttf");
    std::fs::write(&path, builder.build()).unwrap();
    let out = trip.dir.path().join("avar-out");
    let err = import_fails(&[s(&path)], &out);
    assert_eq!(
        err,
        format!(
            "error: {}: avar maps axis `wght` flat or backwards (0 -> 0, then 0.5 -> 0); \
             xglyph's axis maps must increase, so this font cannot be imported with its \
             masters\n",
            path.display()
        )
    );
}

#[test]
fn a_foreign_designspace_imports_compatibly() {
    let trip = round_trip();
    let built = trip.original.parent().unwrap();
    // The bundled family's UFOs without xglyph's X-spline lib: foreign masters.
    let foreign = trip.dir.path().join("foreign");
    std::fs::create_dir_all(&foreign).unwrap();
    for style in ["Regular", "Bold"] {
        let mut ufo = norad::Font::load(built.join(format!("XglyphSans-{style}.ufo"))).unwrap();
        let names: Vec<_> = ufo
            .default_layer()
            .iter()
            .map(|g| g.name().clone())
            .collect();
        for name in names {
            let g = ufo.default_layer_mut().get_glyph_mut(&name).unwrap();
            g.lib.remove("org.xglyph.xspline");
        }
        ufo.save(foreign.join(format!("XglyphSans-{style}.ufo")))
            .unwrap();
    }
    // An instance without a style name or name, as in fontmake's test designspaces: it is
    // named by its place.
    let doc = std::fs::read_to_string(built.join("XglyphSans.designspace")).unwrap();
    let unnamed = r#"familyname="Xglyph Sans" stylename="SemiBold" name="Xglyph Sans SemiBold""#;
    assert!(doc.contains(unnamed));
    std::fs::write(
        foreign.join("XglyphSans.designspace"),
        doc.replace(unnamed, r#"familyname="Xglyph Sans""#),
    )
    .unwrap();
    // Fitted alone, the two masters come out with different point counts.
    let points = |dir: &Path, glyph: &str| -> Vec<usize> {
        let text = std::fs::read_to_string(dir.join(glyph)).unwrap();
        let value: toml::Table = text.parse().unwrap();
        value["contour"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["points"].as_array().unwrap().len())
            .collect()
    };
    let alone: Vec<PathBuf> = ["Regular", "Bold"]
        .iter()
        .map(|style| {
            let out = trip.dir.path().join(format!("alone-{style}"));
            let ufo = foreign.join(format!("XglyphSans-{style}.ufo"));
            let (code, _, err) = import(&[s(&ufo)], &out);
            assert_eq!(code, 0, "{err}");
            out
        })
        .collect();
    let differ = ["S_.toml", "m.toml", "g.toml", "a.toml", "O_.toml"]
        .iter()
        .filter(|g| points(&alone[0], g) != points(&alone[1], g))
        .count();
    assert!(differ >= 3, "{differ} of 5 glyphs differ when fitted alone");
    // Imported together: one structure, and the family checks.
    let out = trip.dir.path().join("foreign-imported");
    let ds = foreign.join("XglyphSans.designspace");
    let (code, report, err) = import(&[s(&ds)], &out);
    assert_eq!((code, err.as_str()), (0, ""));
    for g in ["S_.toml", "m.toml", "g.toml", "a.toml", "O_.toml"] {
        assert_eq!(points(&out, g), points(&out.join("bold"), g), "{g}");
    }
    for line in report.lines().filter(|l| l.starts_with("total:")) {
        let error: f64 = line.split("max error ").nth(1).unwrap()[..5]
            .parse()
            .unwrap();
        assert!(error <= 0.75 * TOLERANCE, "{line}");
    }
    let info = std::fs::read_to_string(out.join("font.toml")).unwrap();
    assert!(
        info.contains("[[instance]]\nname = \"Weight 600\"\nlocation = { wght = 600 }\n"),
        "{info}"
    );
    let (code, out_text, err) = xglyph(&["check", s(&out)]);
    assert_eq!(code, 0, "{out_text}{err}");
}

fn bytes(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap()
}

/// The axes (tag, min, default, max) and named instances (name, coordinates).
type Fvar = (Vec<(String, f32, f32, f32)>, Vec<(String, Vec<f32>)>);

fn fvar(font: &FontRef) -> Fvar {
    let name = |id| {
        font.localized_strings(id)
            .english_or_first()
            .map(|s| s.chars().collect::<String>())
            .unwrap_or_default()
    };
    (
        font.axes()
            .iter()
            .map(|a| {
                (
                    a.tag().to_string(),
                    a.min_value(),
                    a.default_value(),
                    a.max_value(),
                )
            })
            .collect(),
        font.named_instances()
            .iter()
            .map(|i| (name(i.subfamily_name_id()), i.user_coords().collect()))
            .collect(),
    )
}

#[test]
fn each_master_gets_the_kerning_of_its_location() {
    // The variable TTF's GPOS holds the Regular's pairs plus a variation delta per pair
    // reaching the Bold's at wght 700; the import reads them back exactly per master.
    let trip = round_trip();
    let glyphs = Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    for folder in ["", "bold"] {
        let pairs = |dir: &Path| -> Vec<(String, String, f64)> {
            let text = std::fs::read_to_string(dir.join(folder).join("kerning.toml")).unwrap();
            let table: toml::Table = text.parse().unwrap();
            let mut out: Vec<_> = table["pair"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| {
                    (
                        p["left"].as_str().unwrap().to_string(),
                        p["right"].as_str().unwrap().to_string(),
                        p["value"]
                            .as_float()
                            .or(p["value"].as_integer().map(|v| v as f64))
                            .unwrap(),
                    )
                })
                .collect();
            out.sort_by(|a, b| (&a.0, &a.1).cmp(&(&b.0, &b.1)));
            out
        };
        let (source, imported) = (pairs(&glyphs), pairs(&trip.imported));
        assert_eq!(source.len(), 143, "{folder}");
        assert_eq!(imported, source, "{folder}");
    }
}

/// GDEF's ligature carets of `font`: (ligature glyph name, caret x positions).
fn carets(path: &Path) -> Vec<(String, Vec<i16>)> {
    use skrifa::raw::tables::gdef::CaretValue;
    use skrifa::raw::TableProvider;
    let data = bytes(path);
    let font = FontRef::new(&data).unwrap();
    let names = skrifa::GlyphNames::new(&font);
    let list = font.gdef().unwrap().lig_caret_list().unwrap().unwrap();
    list.coverage()
        .unwrap()
        .iter()
        .zip(list.lig_glyphs().iter())
        .map(|(g, carets)| {
            let at = carets
                .unwrap()
                .caret_values()
                .iter()
                .map(|c| match c.unwrap() {
                    CaretValue::Format1(c) => c.coordinate(),
                    other => panic!("caret format {}", other.caret_value_format()),
                })
                .collect();
            (names.get(g).unwrap().to_string(), at)
        })
        .collect()
}

#[test]
fn the_imported_family_keeps_its_ligatures_and_their_carets() {
    // The family's `liga` (f i, f l) and its ligature carets come in as feature code, with
    // the ligatures themselves (no character maps them), and build back the same.
    let trip = round_trip();
    let features = std::fs::read_to_string(trip.imported.join("features.fea")).unwrap();
    for rule in [
        "sub f i by fi;",
        "sub f l by fl;",
        "LigatureCaretByPos fi 328;",
    ] {
        assert!(features.contains(rule), "{rule}\n{features}");
    }
    assert!(trip.imported.join("fi.toml").is_file());
    let original = carets(&trip.original);
    assert_eq!(
        original,
        [("fi".to_string(), vec![328]), ("fl".to_string(), vec![328])]
    );
    assert_eq!(carets(&trip.rebuilt), original);
}
