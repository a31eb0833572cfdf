//! Axis maps (`map` in `[[axis]]`) as a user meets them, on `tests/fixtures/masters` with
//! a non-linear weight map: `check` and `fmt`, the `avar` of the variable TTF and the static
//! instances `build` writes, the designspace export (read by fontmake and fontc), and both
//! ways back in: the variable TTF's `avar` and the designspace's `<map>` come back as the map.
//!
//! Tests that need fontmake/fontc print `skipped: …` and pass when they are missing, unless
//! `XGLYPH_REQUIRE_TOOLS=1` (CI).

use std::fs;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use skrifa::instance::{LocationRef, Size};
use skrifa::raw::TableProvider;
use skrifa::{FontRef, MetadataProvider};

use crate::common::cli::{import_ok, xglyph};
use crate::common::fonts::{glyph_id, skrifa_outline};
use crate::common::{paths, tools};

/// Weight 400..700 whose design values move fast near Regular: Medium (500) is a third of
/// the way in user values and 0.625 of the way in design values.
const MAP: &str = "map = [[400, 80], [500, 130], [700, 160]]";

/// Where the masters blend at each named instance: (style, wght, normalised design value).
const INSTANCES: [(&str, f64, f64); 4] = [
    ("Regular", 400.0, 0.0),
    ("Medium", 500.0, 0.625),
    ("SemiBold", 600.0, 0.8125),
    ("Bold", 700.0, 1.0),
];

struct Built {
    _tmp: tempfile::TempDir,
    font: PathBuf,
    out: PathBuf,
}

/// The fixture with [`MAP`], built once with the CLI.
fn built() -> &'static Built {
    static BUILT: OnceLock<Built> = OnceLock::new();
    BUILT.get_or_init(|| {
        let tmp = tempfile::tempdir().expect("temp dir");
        let font = tmp.path().join("font");
        copy_dir(
            &Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/masters"),
            &font,
        );
        let toml = fs::read_to_string(font.join("font.toml")).expect("font.toml");
        let edited = toml.replacen("max = 700\n", &format!("max = 700\n{MAP}\n"), 1);
        assert_ne!(toml, edited);
        fs::write(font.join("font.toml"), edited).expect("writes");
        let out = tmp.path().join("out");
        let (code, _, stderr) = xglyph(&["build", s(&font), "-o", s(&out)]);
        assert_eq!((code, stderr.as_str()), (0, ""));
        Built {
            _tmp: tmp,
            font,
            out,
        }
    })
}

fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

fn copy_dir(from: &Path, to: &Path) {
    fs::create_dir_all(to).expect("mkdir");
    for entry in fs::read_dir(from).expect("reads") {
        let path = entry.expect("entry").path();
        let dest = to.join(path.file_name().expect("name"));
        if path.is_dir() {
            copy_dir(&path, &dest);
        } else {
            fs::copy(&path, &dest).expect("copies");
        }
    }
}

/// The `avar` segment map of the font's first axis, as (from, to) pairs.
fn avar(bytes: &[u8]) -> Vec<(f32, f32)> {
    let font = FontRef::new(bytes).expect("parses");
    let avar = font.avar().expect("has avar");
    let maps = avar
        .axis_segment_maps()
        .get(0)
        .expect("one axis")
        .expect("reads");
    maps.axis_value_maps()
        .iter()
        .map(|m| (m.from_coordinate().to_f32(), m.to_coordinate().to_f32()))
        .collect()
}

fn variable_font(out: &Path) -> Vec<u8> {
    fs::read(out.join("MastersTest[wght].ttf")).expect("the variable TTF")
}

/// The advance of glyph `name` in `bytes` at `wght` (skrifa applies avar and HVAR).
fn advance_at(bytes: &[u8], name: &str, wght: f32) -> f32 {
    let font = FontRef::new(bytes).expect("parses");
    let location = font.axes().location([("wght", wght)]);
    let gid = glyph_id(&font, name);
    font.glyph_metrics(Size::unscaled(), LocationRef::from(&location))
        .advance_width(gid)
        .expect("advance")
}

#[test]
fn a_mapped_font_checks_formats_and_builds_its_avar() {
    let b = built();
    assert_eq!(
        xglyph(&["check", s(&b.font)]),
        (0, "0 errors, 0 warnings\n".into(), String::new())
    );
    // `fmt` writes the map as it was written: the file is canonical.
    let (code, stdout, stderr) = xglyph(&["fmt", "--check", s(&b.font)]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    // avar: user-normalised 1/3 (Medium) goes to 0.625; the axis has no negative side,
    // and -1 -> -1 is written as every compiler does.
    let vf = variable_font(&b.out);
    let third = skrifa::raw::types::F2Dot14::from_f32(1.0 / 3.0).to_f32();
    assert_eq!(
        avar(&vf),
        [(-1.0, -1.0), (0.0, 0.0), (third, 0.625), (1.0, 1.0)]
    );
    // At each named instance the variable font and the static instance both give the
    // advance of the masters blended at the design position, not at the user one.
    let (family, _) = xglyph::source::load_family(&b.font).expect("loads");
    let n =
        |glyphs: &[xglyph::model::Glyph]| glyphs.iter().find(|g| g.name == "n").expect("n").advance;
    let (regular, bold) = (n(&family.default.glyphs), n(&family.masters[0].glyphs));
    assert!(bold - regular >= 30.0, "{regular} {bold}");
    for (style, wght, t) in INSTANCES {
        let want = (regular.round() + t * (bold.round() - regular.round())).round();
        let linear = regular + (wght - 400.0) / 300.0 * (bold - regular);
        let instance = fs::read(b.out.join(format!("MastersTest-{style}.ttf"))).expect("TTF");
        let static_advance = advance_at(&instance, "n", 0.0);
        let variable_advance = advance_at(&vf, "n", wght as f32);
        eprintln!(
            "n at {style}: variable {variable_advance}, static {static_advance}, blend {want}, \
             linear in user values {linear:.1}"
        );
        assert_eq!(f64::from(variable_advance), want, "{style}");
        assert!((f64::from(static_advance) - want).abs() <= 1.0, "{style}");
        if style == "Medium" || style == "SemiBold" {
            assert!(
                (want - linear).abs() > 3.0,
                "{style}: the map must matter here"
            );
        }
    }
    // The static Medium's outlines are the variable font's at wght 500.
    let instance = fs::read(b.out.join("MastersTest-Medium.ttf")).expect("TTF");
    let (a, v) = (
        FontRef::new(&instance).expect("parses"),
        FontRef::new(&vf).expect("parses"),
    );
    let location = v.axes().location([("wght", 500.0)]);
    for name in ["n", "O", "H"] {
        let d = paths::two_sided(
            &skrifa_outline(&a, glyph_id(&a, name), LocationRef::default()),
            &skrifa_outline(&v, glyph_id(&v, name), LocationRef::from(&location)),
            32,
        );
        // Each is within the tolerance (0.5) of the blend, plus grid rounding.
        assert!(d <= 2.5, "{name}: {d}");
    }
}

#[test]
fn the_variable_font_imports_back_with_its_map() {
    let b = built();
    let tmp = tempfile::tempdir().expect("temp dir");
    let imported = tmp.path().join("imported");
    import_ok(&[s(&b.out.join("MastersTest[wght].ttf"))], &imported);
    // Design values come back on the user scale (avar keeps only the normalised map):
    // 0.625 of the way from 400 to 700 is 587.5.
    let toml = fs::read_to_string(imported.join("font.toml")).expect("font.toml");
    assert!(
        toml.contains("\nmax = 700\nmap = [[400, 400], [500, 587.5], [700, 700]]\n"),
        "{toml}"
    );
    let rebuilt = tmp.path().join("rebuilt");
    let (code, _, stderr) = xglyph(&["build", s(&imported), "-o", s(&rebuilt)]);
    assert_eq!((code, stderr.as_str()), (0, ""));
    let (before, after) = (variable_font(&b.out), variable_font(&rebuilt));
    assert_eq!(avar(&after), avar(&before));
    for wght in [450.0, 500.0, 550.0, 650.0] {
        assert_eq!(
            advance_at(&after, "n", wght),
            advance_at(&before, "n", wght),
            "wght {wght}"
        );
    }
}

#[test]
fn the_designspace_carries_the_map_out_and_back() {
    let b = built();
    let ds = b.out.join("MastersTest.designspace");
    let xml = fs::read_to_string(&ds).expect("designspace");
    for line in [
        r#"<map input="500" output="130"/>"#,
        r#"<dimension name="Weight" xvalue="160"/>"#,
        // SemiBold (600) halfway between the map's 500 and 700.
        r#"<dimension name="Weight" xvalue="145"/>"#,
    ] {
        assert!(xml.contains(line), "{line}\n{xml}");
    }
    let tmp = tempfile::tempdir().expect("temp dir");
    let imported = tmp.path().join("imported");
    import_ok(&[s(&ds)], &imported);
    let (back, _) = xglyph::source::load_family(&imported).expect("loads");
    let (want, _) = xglyph::source::load_family(&b.font).expect("loads");
    assert_eq!(back.designspace, want.designspace);
    assert_eq!(back.masters[0].location, want.masters[0].location);
}

#[test]
fn fontmake_and_fontc_compile_the_same_avar_and_instances() {
    if !tools::designspace_compilers_available() {
        return;
    }
    let b = built();
    let tmp = tempfile::tempdir().expect("temp dir");
    let report = tools::check_designspace_compilers(
        &b.out.join("MastersTest.designspace"),
        &b.out.join("MastersTest[wght].ttf"),
        tmp.path(),
        0.5,
        &["400", "450", "500", "600", "700"],
    );
    println!("{report}");
    for line in [
        "axes: wght Weight 400 400 700",
        "sources: MastersTest-Regular.ufo Regular Weight=80, MastersTest-Bold.ufo Bold Weight=160",
    ] {
        assert!(report.lines().any(|l| l == line), "{line}\n{report}");
    }
    let avars = report
        .lines()
        .filter(|l| l.starts_with("ok ") && l.contains(": avar "))
        .count();
    assert_eq!(avars, 3, "{report}");
    assert!(report.contains("designspace_check: all passed"), "{report}");
}
