//! Sparse masters as a user meets them, on `tests/fixtures/sparse`: the two-master weight
//! font of `tests/fixtures/masters` with a sparse master `O 550` (`sparse = true`) that
//! draws only `O`, with a narrower counter and a wider advance than the blend gives there.
//! `check`, `fmt` and `build` through the CLI; the variable TTF read back with skrifa
//! (tuples per glyph, advances, outlines against the blended X-splines); the static
//! instances; the exported designspace (a layer of the default UFO) compiled by fontmake
//! and fontc; and the errors a sparse master can have.
//!
//! Tests that need fontmake or fontc print `skipped: …` and pass when they are missing,
//! unless `XGLYPH_REQUIRE_TOOLS=1` (CI).

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use kurbo::BezPath;
use skrifa::instance::{LocationRef, Size};
use skrifa::raw::TableProvider;
use skrifa::{FontRef, MetadataProvider};
use xglyph::designspace::Location;
use xglyph::model::Family;

use crate::common::cli::xglyph;
use crate::common::fonts::{glyph_id, skrifa_outline};
use crate::common::{paths, tools};

struct Built {
    _tmp: tempfile::TempDir,
    out: PathBuf,
    stdout: String,
}

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/sparse")
}

fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

/// `fixture` built once with the CLI.
fn build(fixture: &Path) -> Built {
    let tmp = tempfile::tempdir().expect("temp dir");
    let out = tmp.path().join("out");
    let (code, stdout, stderr) = xglyph(&["build", s(fixture), "-o", s(&out)]);
    assert_eq!((code, stderr.as_str()), (0, ""), "{stdout}");
    Built {
        _tmp: tmp,
        out,
        stdout,
    }
}

fn built() -> &'static Built {
    static BUILT: OnceLock<Built> = OnceLock::new();
    BUILT.get_or_init(|| build(&fixture()))
}

fn family() -> &'static Family {
    static FAMILY: OnceLock<Family> = OnceLock::new();
    FAMILY.get_or_init(|| xglyph::source::load_family(&fixture()).expect("loads").0)
}

fn wght(v: f64) -> Location {
    Location([("wght".to_string(), v)].into_iter().collect())
}

fn variable_font(out: &Path) -> Vec<u8> {
    fs::read(out.join("MastersTest[wght].ttf")).expect("the variable TTF")
}

/// The glyph `name` of `font`.
fn glyph<'a>(font: &'a xglyph::model::Font, name: &str) -> &'a xglyph::model::Glyph {
    font.glyphs.iter().find(|g| g.name == name).expect("glyph")
}

/// A glyph's X-spline contours as one dense polyline path (the true curve, sampled).
fn xspline_path(g: &xglyph::model::Glyph) -> BezPath {
    let mut out = BezPath::new();
    for c in &g.contours {
        out.extend(paths::xspline_polyline(c.spline(), 64).iter());
    }
    out
}

#[test]
fn the_fixture_checks_clean_is_canonical_and_reports_the_sparse_master() {
    let (code, out, err) = xglyph(&["check", s(&fixture())]);
    assert_eq!(
        (code, out.as_str(), err.as_str()),
        (0, "0 errors, 0 warnings\n", "")
    );
    let (code, out, err) = xglyph(&["fmt", "--check", s(&fixture())]);
    assert_eq!(code, 0, "{out}{err}");
    let b = built();
    assert!(
        b.stdout.contains(
            "masters: Regular (wght 400, default), Bold (wght 700), O 550 (wght 550, sparse: 1 \
             glyph); named instances:"
        ),
        "{}",
        b.stdout
    );
    assert!(b.stdout.contains("checked at 13 positions"), "{}", b.stdout);
    // The loader fills what the sparse master leaves out, and knows what it draws.
    let f = family();
    let sparse = &f.masters[1];
    assert!(sparse.sparse && !f.masters[0].sparse);
    let drawn: Vec<&str> = f
        .default
        .glyphs
        .iter()
        .zip(&sparse.drawn)
        .filter(|(_, &d)| d)
        .map(|(g, _)| g.name.as_str())
        .collect();
    assert_eq!(drawn, ["O"]);
}

#[test]
fn each_glyph_varies_with_its_own_masters() {
    let vf = variable_font(&built().out);
    let font = FontRef::new(&vf).expect("parses");
    let gvar = font.gvar().expect("gvar");
    let peaks = |name: &str| -> Vec<[f32; 3]> {
        gvar.glyph_variation_data(glyph_id(&font, name))
            .expect("reads")
            .expect("varies")
            .tuples()
            .map(|t| {
                let peak = t.peak().values[0].get().to_f32();
                let (lo, hi) = t
                    .intermediate_start()
                    .zip(t.intermediate_end())
                    .map_or((0.0, 0.0), |(a, b)| {
                        (a.values[0].get().to_f32(), b.values[0].get().to_f32())
                    });
                [lo, peak, hi]
            })
            .collect()
    };
    // `O`: Bold from the sparse master outwards, and the sparse master's own tent.
    assert_eq!(peaks("O"), [[0.5, 1.0, 1.0], [0.0, 0.5, 1.0]]);
    // The others: Bold alone, over the whole axis, as without the sparse master.
    for name in ["n", "H", "ndot"] {
        assert_eq!(peaks(name).len(), 1, "{name}");
        assert_eq!(peaks(name)[0][1], 1.0, "{name}");
    }
}

#[test]
fn the_variable_font_follows_the_blended_x_splines_of_each_glyphs_own_model() {
    let b = built();
    let vf = variable_font(&b.out);
    let font = FontRef::new(&vf).expect("parses");
    let f = family();
    // Tolerance 0.5, plus the quadratic conversion (0.5) and the grid (two roundings of
    // at most sqrt(2)/2), as in tests/it/corners.rs.
    let bound = 0.5 + 0.5 + 2.0 * std::f64::consts::FRAC_1_SQRT_2;
    let mut worst: f64 = 0.0;
    for w in [400.0, 450.0, 500.0, 550.0, 600.0, 650.0, 700.0] {
        let at = wght(w);
        let instance = f.instance_at(&at).expect("blends");
        let location = font.axes().location([("wght", w as f32)]);
        for name in ["O", "n", "H"] {
            let gid = glyph_id(&font, name);
            let mine = skrifa_outline(&font, gid, LocationRef::from(&location));
            let want = xspline_path(glyph(&instance, name));
            let d = paths::two_sided(&mine, &want, 16);
            worst = worst.max(d);
            assert!(d <= bound, "{name} at wght {w}: {d} > {bound}");
            let advance = font
                .glyph_metrics(Size::unscaled(), LocationRef::from(&location))
                .advance_width(gid)
                .expect("advance");
            assert!(
                (f64::from(advance) - glyph(&instance, name).advance).abs() <= 0.5,
                "{name} at wght {w}: advance {advance}"
            );
        }
    }
    println!("worst distance to the blended X-splines: {worst:.3}");
    // At 550 `O` is the sparse master's own drawing: its advance, and its counter (the
    // inner contour's leftmost point), not the blend of Regular and Bold.
    let at550 = f.instance_at(&wght(550.0)).expect("blends");
    let o = glyph(&at550, "O");
    assert_eq!(o.advance, 750.0);
    assert_eq!(o.contours[1].points()[4].pos.x, 169.1);
    let bold_o = f.masters[0]
        .glyphs
        .iter()
        .find(|g| g.name == "O")
        .expect("O");
    assert_eq!(
        (glyph(&f.default, "O").advance + bold_o.advance) / 2.0,
        740.0
    );
    // `n` there is exactly the blend of Regular and Bold.
    let n = glyph(&at550, "n");
    assert_eq!(n.advance, 575.0);
}

#[test]
fn a_glyph_the_sparse_master_does_not_draw_is_the_same_as_without_it() {
    let with = variable_font(&built().out);
    let without = build(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/masters"));
    let without = variable_font(&without.out);
    let (a, b) = (
        FontRef::new(&with).expect("parses"),
        FontRef::new(&without).expect("parses"),
    );
    for w in [450.0, 550.0, 625.0] {
        let (la, lb) = (
            a.axes().location([("wght", w)]),
            b.axes().location([("wght", w)]),
        );
        for name in ["n", "H", "ndot", "dotcomb"] {
            let pa = skrifa_outline(&a, glyph_id(&a, name), LocationRef::from(&la));
            let pb = skrifa_outline(&b, glyph_id(&b, name), LocationRef::from(&lb));
            assert_eq!(pa, pb, "{name} at wght {w}");
        }
    }
}

#[test]
fn the_static_instances_blend_o_through_the_sparse_master() {
    let b = built();
    let medium = fs::read(b.out.join("MastersTest-Medium.ttf")).expect("Medium");
    let font = FontRef::new(&medium).expect("parses");
    let advance = |name: &str| {
        font.glyph_metrics(Size::unscaled(), LocationRef::default())
            .advance_width(glyph_id(&font, name))
            .expect("advance")
    };
    // wght 500 is two thirds of the way from Regular (720) to the sparse master (750);
    // Regular to Bold alone would give 733.
    assert_eq!(advance("O"), 740.0);
    assert_eq!(advance("n"), 570.0);
}

#[test]
fn the_designspace_puts_the_sparse_master_on_a_layer_that_fontmake_and_fontc_read() {
    let b = built();
    let layer = b.out.join("MastersTest-Regular.ufo/glyphs.O_ 550");
    let mut files: Vec<String> = fs::read_dir(&layer)
        .expect("the layer's folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(files, ["O_.glif", "contents.plist"]);
    assert!(!b.out.join("MastersTest-O550.ufo").exists());
    let ds = fs::read_to_string(b.out.join("MastersTest.designspace")).expect("designspace");
    assert!(
        ds.contains(
            "<source familyname=\"Masters Test\" stylename=\"O 550\" name=\"master.O 550\" \
             filename=\"MastersTest-Regular.ufo\" layer=\"O 550\">"
        ),
        "{ds}"
    );
    if !tools::designspace_compilers_available() {
        return;
    }
    let tmp = tempfile::tempdir().expect("temp dir");
    let report = tools::check_designspace_compilers(
        &b.out.join("MastersTest.designspace"),
        &b.out.join("MastersTest[wght].ttf"),
        tmp.path(),
        0.5,
        &["450", "500", "550", "600", "650"],
    );
    println!("{report}");
    assert!(
        report.contains("ok    MastersTest-Regular.ufo layer O 550: 1 glyphs (O), each with"),
        "{report}"
    );
    // Both compilers, 5 positions each, and the advances at the sparse master.
    assert_eq!(tools::outlines_compared(&report), 10, "{report}");
    for compiler in ["fontmake.ttf", "font.ttf"] {
        assert!(
            report.contains(&format!("ok    {compiler}: advances at wght 550")),
            "{report}"
        );
    }
    assert!(report.contains("designspace_check: all passed"), "{report}");
}

/// `check` of the fixture with `edit` applied: exit code and output.
fn check_edited(test: &str, edit: impl FnOnce(&Path)) -> (i32, String) {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("sparse-{test}"));
    let _ = fs::remove_dir_all(&tmp);
    let font = tmp.join("font");
    copy_dir(&fixture(), &font);
    edit(&font);
    let out = Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(["check", "font"])
        .current_dir(&tmp)
        .output()
        .expect("runs");
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    (out.status.code().unwrap_or(-1), text)
}

fn copy_dir(from: &Path, to: &Path) {
    fs::create_dir_all(to).expect("mkdir");
    for entry in fs::read_dir(from).expect("read_dir") {
        let path = entry.expect("entry").path();
        let dest = to.join(path.file_name().expect("name"));
        if path.is_dir() {
            copy_dir(&path, &dest);
        } else {
            fs::copy(&path, &dest).expect("copy");
        }
    }
}

fn replace(path: &Path, old: &str, new: &str) {
    let text = fs::read_to_string(path).expect("read");
    assert!(text.contains(old), "{} has no {old:?}", path.display());
    fs::write(path, text.replacen(old, new, 1)).expect("write");
}

/// A change to the fixture's copy.
type Edit = Box<dyn FnOnce(&Path)>;

#[test]
fn sparse_master_errors_name_the_place_to_fix() {
    let cases: Vec<(&str, Edit, &str)> = vec![
        (
            "not a boolean",
            Box::new(|f: &Path| replace(&f.join("font.toml"), "sparse = true", "sparse = \"yes\"")),
            "font/font.toml:29:10: error: `sparse` must be true or false, found string",
        ),
        (
            "glyph only in the sparse master",
            Box::new(|f: &Path| {
                fs::write(
                    f.join("w550/x.toml"),
                    "name = \"x\"\nadvance = 500\n\n[[contour]]\npoints = [[0, 0, 0], [100, 0, 0], [50, 100, 0]]\n",
                )
                .expect("write")
            }),
            "font/w550/x.toml:1:8: error: glyph `x` is not in the default master; add it there \
             too, or remove this file",
        ),
    ];
    for (test, edit, error) in cases {
        let (code, out) = check_edited(test, edit);
        assert_eq!(code, 1, "{test}: {out}");
        let errors: Vec<&str> = out.lines().filter(|l| l.contains(": error: ")).collect();
        assert_eq!(errors, [error], "{test}: {out}");
    }
}

/// A sparse master alone at an axis end is allowed, with a warning at the end's `max`:
/// the glyphs it does not draw blend back to the default there.
#[test]
fn a_sparse_master_alone_at_an_axis_end_is_a_warning() {
    let (code, out) = check_edited("only sparse at the end", |f: &Path| {
        replace(
            &f.join("font.toml"),
            "location = { wght = 550 }",
            "location = { wght = 700 }",
        );
        replace(
            &f.join("font.toml"),
            "location = { wght = 700 }\n\n[[master]]",
            "location = { wght = 600 }\n\n[[master]]",
        );
    });
    assert_eq!(code, 0, "{out}");
    let warnings: Vec<&str> = out.lines().filter(|l| l.contains(": warning: ")).collect();
    assert_eq!(
        warnings,
        [
            "font/font.toml:18:7: warning: axis `wght` ends at max = 700 where only sparse master \
          `O 550` is: a glyph it does not draw blends back to the default there, past the \
          outermost master that draws it"
        ],
        "{out}"
    );
    assert!(out.ends_with("0 errors, 1 warning\n"), "{out}");
}

/// A sparse master with a `kerning.toml` kerns with its own pairs: `H O` -25 at wght 550
/// where the full masters blend to -20, and `n O` (a pair it lacks) 0 there instead of -8.
/// Its export is a UFO of its own holding only `O` (a layer has no kerning), which fontmake
/// and fontc read as sparse for outlines and kerned.
#[test]
fn a_sparse_master_with_kerning_of_its_own_kerns_with_it() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("sparse-kerned");
    let _ = fs::remove_dir_all(&tmp);
    let font = tmp.join("font");
    copy_dir(&fixture(), &font);
    fs::write(
        font.join("w550/kerning.toml"),
        "[[pair]]\nleft = \"H\"\nright = \"O\"\nvalue = -25\n\n\
         [[pair]]\nleft = \"O\"\nright = \"H\"\nvalue = -16\n",
    )
    .expect("write");
    let (code, stdout, stderr) = xglyph(&["check", s(&font)]);
    assert_eq!(
        (code, stdout.as_str()),
        (0, "0 errors, 0 warnings\n"),
        "{stderr}"
    );
    let out = tmp.join("out");
    let (code, stdout, stderr) = xglyph(&["build", s(&font), "-o", s(&out)]);
    assert_eq!((code, stderr.as_str()), (0, ""), "{stdout}");
    let mut files: Vec<String> = fs::read_dir(out.join("MastersTest-O550.ufo/glyphs"))
        .expect("the sparse master's own UFO")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(files, ["O_.glif", "contents.plist"]);
    assert!(!out.join("MastersTest-Regular.ufo/glyphs.O_ 550").exists());
    if !tools::designspace_compilers_available() {
        return;
    }
    let vf = out.join("MastersTest[wght].ttf");
    let here = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/it");
    let kerning: BTreeMap<String, BTreeMap<String, i64>> =
        tools::python_json(KERNING_AT, &[&vf, &"400,475,550,700", &here]);
    let at = |w: &str| {
        kerning[w]
            .iter()
            .map(|(k, v)| format!("{k} {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    assert_eq!(at("550"), "H O -25, O H -16");
    assert_eq!(at("700"), "H O -30, O H -20, n O -16");
    assert_eq!(at("400"), "H O -10, O H -12");
    // Halfway to the sparse master: (-10 - 25) / 2 = -17.5, which the instancer rounds
    // up (`otRound`), and (-12 - 16) / 2.
    assert_eq!(at("475"), "H O -17, O H -14");

    let report = tools::check_designspace_compilers(
        &out.join("MastersTest.designspace"),
        &vf,
        &tmp,
        0.5,
        &["450", "550", "650"],
    );
    println!("{report}");
    assert!(
        report.contains("ok    MastersTest-O550.ufo: 1 glyphs (O), each with"),
        "{report}"
    );
    assert_eq!(tools::outlines_compared(&report), 6, "{report}");
    for compiler in ["fontmake.ttf", "font.ttf"] {
        assert!(
            report.contains(&format!("ok    {compiler}: kerning at wght 550 (2 pairs)")),
            "{report}"
        );
    }
    assert!(report.contains("designspace_check: all passed"), "{report}");
}

/// The GPOS kerning of the variable font `argv[1]` at each `wght` of `argv[2]`
/// (comma-separated), by fontTools' instancer and `argv[3]/ufo_check.py`:
/// `{wght: {"left right": value}}`.
const KERNING_AT: &str = r#"
import sys, json
sys.path.insert(0, sys.argv[3])
from fontTools.ttLib import TTFont
from fontTools.varLib.instancer import instantiateVariableFont
from ufo_check import kerning
out = {}
for w in sys.argv[2].split(","):
    font = instantiateVariableFont(TTFont(sys.argv[1]), {"wght": float(w)})
    out[w] = {f"{l} {r}": v for (l, r), v in kerning(font).items()}
print(json.dumps(out))
"#;

/// `tests/fixtures/corners` (weight × width, with the corner Bold Condensed) and a sparse
/// master in the middle of the plane, `{ wght = 550, wdth = 87.5 }`, that draws only `n`:
/// 60 units wider than the default's, with its `top` anchor 30 units to the right.
fn corners_with_a_sparse_middle(dir: &Path) -> PathBuf {
    let font = dir.join("font");
    copy_dir(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/corners"),
        &font,
    );
    let toml = fs::read_to_string(font.join("font.toml")).expect("font.toml");
    let at = toml.find("\n[[instance]]").expect("an instance");
    let master = "\n[[master]]\nname = \"Middle\"\nfolder = \"middle\"\nlocation = { wght = \
                  550, wdth = 87.5 }\nsparse = true\n";
    fs::write(
        font.join("font.toml"),
        format!("{}{master}{}", &toml[..at], &toml[at..]),
    )
    .expect("write");
    fs::create_dir(font.join("middle")).expect("mkdir");
    let n = fs::read_to_string(font.join("n.toml")).expect("n");
    let mut out = String::new();
    for line in n.lines() {
        if line.starts_with("unicode") {
            continue;
        }
        let line = match line {
            "advance = 560" => "advance = 620".to_string(),
            "position = [290, 500]" => "position = [350, 500]".to_string(),
            l if l.starts_with("  [") => {
                let v: Vec<f64> = l
                    .trim()
                    .trim_start_matches('[')
                    .trim_end_matches("],")
                    .split(", ")
                    .map(|x| x.parse().expect("a number"))
                    .collect();
                format!("  [{}, {}, {}],", v[0] * 60.0 / 56.0, v[1], v[2])
            }
            l => l.to_string(),
        };
        out.push_str(&line);
        out.push('\n');
    }
    fs::write(font.join("middle/n.toml"), out).expect("write");
    font
}

#[test]
fn a_sparse_master_off_the_axes_blends_with_fonttools_sub_models() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let font = corners_with_a_sparse_middle(tmp.path());
    let (code, out, err) = xglyph(&["check", s(&font)]);
    assert_eq!(
        (code, out.as_str(), err.as_str()),
        (0, "0 errors, 0 warnings\n", "")
    );
    let b = build(&font);
    let (f, _) = xglyph::source::load_family(&font).expect("loads");
    let vf = fs::read(b.out.join("CornersTest[wght,wdth].ttf")).expect("the variable TTF");
    let vf = FontRef::new(&vf).expect("parses");
    let bound = 0.5 + 0.5 + 2.0 * std::f64::consts::FRAC_1_SQRT_2;
    let mut worst: f64 = 0.0;
    for wg in [400.0, 475.0, 550.0, 625.0, 700.0] {
        for wd in [75.0, 81.25, 87.5, 93.75, 100.0] {
            let at = Location(
                [("wght".to_string(), wg), ("wdth".to_string(), wd)]
                    .into_iter()
                    .collect(),
            );
            let instance = f.instance_at(&at).expect("blends");
            let location = vf
                .axes()
                .location([("wght", wg as f32), ("wdth", wd as f32)]);
            for name in ["n", "O", "H"] {
                let gid = glyph_id(&vf, name);
                let mine = skrifa_outline(&vf, gid, LocationRef::from(&location));
                let d = paths::two_sided(&mine, &xspline_path(glyph(&instance, name)), 16);
                worst = worst.max(d);
                assert!(d <= bound, "{name} at {wg}, {wd}: {d}");
                let advance = vf
                    .glyph_metrics(Size::unscaled(), LocationRef::from(&location))
                    .advance_width(gid)
                    .expect("advance");
                // The variable font rounds each master's advance and the blend of their
                // deltas: within 1 unit of the exact blend.
                assert!(
                    (f64::from(advance) - glyph(&instance, name).advance).abs() <= 1.0,
                    "{name} at {wg}, {wd}: advance {advance}, blend {}",
                    glyph(&instance, name).advance
                );
            }
        }
    }
    println!("worst distance to the blended X-splines over the grid: {worst:.3}");
    // In the middle `n` is the sparse master's own.
    let middle = f
        .instance_at(&Location(
            [("wght".to_string(), 550.0), ("wdth".to_string(), 87.5)]
                .into_iter()
                .collect(),
        ))
        .expect("blends");
    assert_eq!(glyph(&middle, "n").advance, 620.0);
    assert_eq!(glyph(&middle, "n").anchors[0].position, (350.0, 500.0));
    if !tools::designspace_compilers_available() {
        return;
    }
    let dir = tempfile::tempdir().expect("temp dir");
    let report = tools::check_designspace_compilers(
        &b.out.join("CornersTest.designspace"),
        &b.out.join("CornersTest[wght,wdth].ttf"),
        dir.path(),
        0.5,
        &[
            "wght=550,wdth=87.5",
            "wght=500,wdth=90",
            "wght=620,wdth=80",
            "wght=700,wdth=75",
            "wght=450,wdth=95",
        ],
    );
    println!("{report}");
    assert!(
        report.contains("ok    CornersTest-Regular.ufo layer Middle: 1 glyphs (n), each with"),
        "{report}"
    );
    assert_eq!(tools::outlines_compared(&report), 10, "{report}");
    assert!(report.contains("designspace_check: all passed"), "{report}");
}

#[test]
fn the_exported_designspace_imports_back_with_the_sparse_master() {
    let b = built();
    let tmp = tempfile::tempdir().expect("temp dir");
    let imported = tmp.path().join("imported");
    crate::common::cli::import_ok(&[s(&b.out.join("MastersTest.designspace"))], &imported);
    let (back, _) = xglyph::source::load_family(&imported).expect("loads");
    let f = family();
    let masters = |f: &Family| -> Vec<(String, f64, bool, usize)> {
        f.masters
            .iter()
            .map(|m| {
                let drawn = m.drawn.iter().filter(|&&d| d).count();
                (m.name.clone(), m.location.0["wght"], m.sparse, drawn)
            })
            .collect()
    };
    assert_eq!(masters(&back), masters(f));
    let folder = &back.masters[1].folder;
    let mut files: Vec<String> = fs::read_dir(imported.join(folder))
        .expect("the sparse folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(files, ["O_.toml"]);
    // The X-spline sources come back from the UFO lib: the sparse master's O exactly.
    let o = |f: &Family| {
        let i = f
            .default
            .glyphs
            .iter()
            .position(|g| g.name == "O")
            .expect("O");
        f.masters[1].glyphs[i].clone()
    };
    assert_eq!(o(&back).contours, o(f).contours);
    assert_eq!(o(&back).advance, 750.0);
}

#[test]
fn the_variable_font_imports_back_with_a_sparse_master_at_its_peak() {
    let b = built();
    let tmp = tempfile::tempdir().expect("temp dir");
    let imported = tmp.path().join("imported");
    crate::common::cli::import_ok(&[s(&b.out.join("MastersTest[wght].ttf"))], &imported);
    let (back, _) = xglyph::source::load_family(&imported).expect("loads");
    // The peak of O's own tuple at 550 (sparse, drawing O), and Bold at the axis end.
    let masters: Vec<(String, f64, bool)> = back
        .masters
        .iter()
        .map(|m| (m.name.clone(), m.location.0["wght"], m.sparse))
        .collect();
    assert_eq!(
        masters,
        [
            ("Weight 550".to_string(), 550.0, true),
            ("Bold".to_string(), 700.0, false)
        ]
    );
    let mut files: Vec<String> = fs::read_dir(imported.join(&back.masters[0].folder))
        .expect("the sparse folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(files, ["O_.toml"]);
    // Rebuilt, it is the same font: outlines and advances at and around the peak.
    let rebuilt = tmp.path().join("rebuilt");
    let (code, _, stderr) = xglyph(&["build", s(&imported), "-o", s(&rebuilt)]);
    assert_eq!((code, stderr.as_str()), (0, ""));
    let before = variable_font(&b.out);
    let after = fs::read(rebuilt.join("Imported[wght].ttf"))
        .or_else(|_| fs::read(rebuilt.join("MastersTest[wght].ttf")))
        .expect("the rebuilt variable TTF");
    let (before, after) = (
        FontRef::new(&before).expect("parses"),
        FontRef::new(&after).expect("parses"),
    );
    for w in [450.0, 550.0, 650.0] {
        let (lb, la) = (
            before.axes().location([("wght", w)]),
            after.axes().location([("wght", w)]),
        );
        for name in ["O", "n", "H"] {
            let advance = |f: &FontRef, l: &skrifa::instance::Location| {
                f.glyph_metrics(Size::unscaled(), LocationRef::from(l))
                    .advance_width(glyph_id(f, name))
                    .expect("advance")
            };
            assert_eq!(advance(&before, &lb), advance(&after, &la), "{name} at {w}");
            let d = paths::two_sided(
                &skrifa_outline(&before, glyph_id(&before, name), LocationRef::from(&lb)),
                &skrifa_outline(&after, glyph_id(&after, name), LocationRef::from(&la)),
                16,
            );
            assert!(d <= 2.0, "{name} at {w}: {d}");
        }
    }
}
