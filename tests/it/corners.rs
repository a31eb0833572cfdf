//! Corner masters as a user meets them, on `tests/fixtures/corners`: weight × width with
//! Bold, Condensed and the corner Bold Condensed, which is narrower than the two axes add
//! up to. `check`, `fmt` and `build` through the CLI; the variable TTF read back with
//! skrifa, OTS and fontTools; the blend against the X-splines over the whole plane; the
//! exported designspace compiled by fontmake and fontc; and both imports back.
//!
//! Tests that need OTS, fontTools, fontmake or fontc print `skipped: …` and pass when they
//! are missing, unless `XGLYPH_REQUIRE_TOOLS=1` (CI).

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use kurbo::{Affine, BezPath};
use skrifa::instance::{LocationRef, Size};
use skrifa::raw::TableProvider;
use skrifa::{FontRef, MetadataProvider};
use xglyph::designspace::Location;

use crate::common::cli::{import_ok, xglyph};
use crate::common::fonts::{glyph_id, skrifa_outline};
use crate::common::{paths, tools};

struct Built {
    _tmp: tempfile::TempDir,
    out: PathBuf,
    stdout: String,
}

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/corners")
}

/// The fixture built once with the CLI.
fn built() -> &'static Built {
    static BUILT: OnceLock<Built> = OnceLock::new();
    BUILT.get_or_init(|| {
        let tmp = tempfile::tempdir().expect("temp dir");
        let out = tmp.path().join("out");
        let (code, stdout, stderr) = xglyph(&["build", s(&fixture()), "-o", s(&out)]);
        assert_eq!((code, stderr.as_str()), (0, ""), "{stdout}");
        Built {
            _tmp: tmp,
            out,
            stdout,
        }
    })
}

fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

fn variable_font(out: &Path) -> Vec<u8> {
    fs::read(out.join("CornersTest[wght,wdth].ttf")).expect("the variable TTF")
}

fn at(wght: f64, wdth: f64) -> Location {
    Location(
        [("wght".to_string(), wght), ("wdth".to_string(), wdth)]
            .into_iter()
            .collect(),
    )
}

#[test]
fn a_corner_master_checks_formats_and_builds() {
    let fixture = fixture();
    assert_eq!(
        xglyph(&["check", s(&fixture)]),
        (0, "0 errors, 0 warnings\n".into(), String::new())
    );
    let (code, stdout, stderr) = xglyph(&["fmt", "--check", s(&fixture)]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let b = built();
    // Masters, instances, and the checked positions: 4 masters, 5 instances, 11 along each
    // axis and the 5 × 5 grid over both, 42 once duplicates are left out.
    let line =
        "masters: Regular (wght 400, wdth 100, default), Bold (wght 700, wdth 100), Condensed \
         (wght 400, wdth 75), Bold Condensed (wght 700, wdth 75); named instances: Regular \
         (wght 400, wdth 100), Bold (wght 700, wdth 100), Condensed (wght 400, wdth 75), \
         SemiBold SemiCondensed (wght 600, wdth 87.5), Bold Condensed (wght 700, wdth 75)";
    assert!(b.stdout.lines().any(|l| l == line), "{line}\n{}", b.stdout);
    assert!(
        b.stdout.contains("; checked at 42 positions; worst "),
        "{}",
        b.stdout
    );
    for file in [
        "CornersTest[wght,wdth].ttf",
        "CornersTest-SemiBoldSemiCondensed.ttf",
        "CornersTest-BoldCondensed.otf",
        "CornersTest-BoldCondensed.ufo",
        "CornersTest.designspace",
    ] {
        assert!(b.out.join(file).exists(), "{file}");
    }
}

#[test]
fn the_corner_has_its_own_region_and_deltas() {
    let vf = variable_font(&built().out);
    let font = FontRef::new(&vf).expect("parses");
    // One gvar tuple of `n` peaks at both axes' ends: wght +1 and wdth -1.
    let gvar = font.gvar().expect("gvar");
    let gid = glyph_id(&font, "n");
    let data = gvar
        .glyph_variation_data(gid)
        .expect("reads")
        .expect("n varies");
    let peaks: Vec<Vec<f32>> = data
        .tuples()
        .map(|t| t.peak().values.iter().map(|v| v.get().to_f32()).collect())
        .collect();
    assert_eq!(
        peaks,
        vec![vec![1.0, 0.0], vec![0.0, -1.0], vec![1.0, -1.0]],
        "{peaks:?}"
    );
    // The advance at the corner is the Bold Condensed master's own (its X-spline source
    // rounded), not what the two axes add up to.
    let (family, _) = xglyph::source::load_family(&fixture()).expect("loads");
    let n = |glyphs: &[xglyph::model::Glyph]| {
        glyphs
            .iter()
            .find(|g| g.name == "n")
            .expect("n")
            .advance
            .round()
    };
    let (regular, bold, condensed, corner) = (
        n(&family.default.glyphs),
        n(&family.masters[0].glyphs),
        n(&family.masters[1].glyphs),
        n(&family.masters[2].glyphs),
    );
    let advance = |wght: f32, wdth: f32| {
        let location = font.axes().location([("wght", wght), ("wdth", wdth)]);
        f64::from(
            font.glyph_metrics(Size::unscaled(), LocationRef::from(&location))
                .advance_width(gid)
                .expect("advance"),
        )
    };
    assert_eq!(advance(700.0, 75.0), corner);
    let sum = bold + condensed - regular;
    assert!((corner - sum).abs() >= 10.0, "{corner} against {sum}");
    // Halfway on both axes the corner's delta counts a quarter (a full grid blends
    // bilinearly): HVAR and the phantom points agree.
    let middle = (regular + bold + condensed + corner) / 4.0;
    assert!(
        (advance(550.0, 87.5) - middle).abs() <= 1.0,
        "{} against {middle}",
        advance(550.0, 87.5)
    );
}

/// Each glyph of `family` at `location` as X-spline polylines, components placed.
fn xspline_outline(family: &xglyph::model::Family, location: &Location, name: &str) -> BezPath {
    let font = family.instance_at(location).expect("blends");
    let index = font.index();
    let glyph = font.glyphs.iter().find(|g| g.name == name).expect("glyph");
    let mut path = BezPath::new();
    for (contour, (dx, dy)) in font.placed_contours_in(&index, glyph) {
        let line = paths::xspline_polyline(contour.spline(), 64);
        path.extend((Affine::translate((dx, dy)) * line).iter());
    }
    path
}

#[test]
fn every_position_of_the_plane_stays_within_tolerance() {
    let vf = variable_font(&built().out);
    let font = FontRef::new(&vf).expect("parses");
    let (family, _) = xglyph::source::load_family(&fixture()).expect("loads");
    // The tolerance (0.5), the TrueType quadratics (within the tolerance again), grid
    // rounding of the masters' points (√2/2), and the polylines' chords.
    let bound = 0.5 + 0.5 + std::f64::consts::FRAC_1_SQRT_2 + 0.05;
    let mut worst = (0.0f64, String::new());
    // A 7 × 7 grid, most of it off the positions the build checked (the 5 × 5 grid).
    for i in 0..7 {
        for j in 0..7 {
            let (wght, wdth) = (
                400.0 + 50.0 * f64::from(i),
                75.0 + 25.0 / 6.0 * f64::from(j),
            );
            let location = font
                .axes()
                .location([("wght", wght as f32), ("wdth", wdth as f32)]);
            for name in ["n", "O", "H", "ndot"] {
                let d = paths::two_sided(
                    &skrifa_outline(&font, glyph_id(&font, name), LocationRef::from(&location)),
                    &xspline_outline(&family, &at(wght, wdth), name),
                    32,
                );
                if d > worst.0 {
                    worst = (d, format!("{name} at wght {wght}, wdth {wdth:.2}"));
                }
            }
        }
    }
    eprintln!("worst distance to the X-splines over the plane: {worst:?}");
    assert!(worst.0 <= bound, "{worst:?} > {bound}");
}

#[test]
fn ots_accepts_the_two_axis_font() {
    let ots_on_path = tools::program_runs("ots-sanitize", &["--version"]);
    if !ots_on_path
        && !tools::available(
            tools::python_imports("ots"),
            "OTS",
            "pip install opentype-sanitizer",
        )
    {
        return;
    }
    let b = built();
    let clean = b._tmp.path().join("clean.ttf");
    let mut cmd = if ots_on_path {
        Command::new("ots-sanitize")
    } else {
        let mut c = Command::new("python3");
        c.args(["-m", "ots"]);
        c
    };
    let text = tools::run(
        cmd.arg(b.out.join("CornersTest[wght,wdth].ttf"))
            .arg(&clean),
    );
    assert!(!text.contains("Dropping"), "{text}");
}

#[test]
fn fontmake_and_fontc_blend_the_corner_as_xglyph_does() {
    if !tools::designspace_compilers_available() {
        return;
    }
    let b = built();
    let tmp = tempfile::tempdir().expect("temp dir");
    let report = tools::check_designspace_compilers(
        &b.out.join("CornersTest.designspace"),
        &b.out.join("CornersTest[wght,wdth].ttf"),
        tmp.path(),
        0.5,
        &[
            "wght=700,wdth=75",
            "wght=550,wdth=87.5",
            "wght=650,wdth=80",
            "wght=450,wdth=95",
            "wght=500,wdth=75",
        ],
    );
    println!("{report}");
    assert!(
        report.lines().any(|l| l
            == "sources: CornersTest-Regular.ufo Regular Weight=400 Width=100, \
                CornersTest-Bold.ufo Bold Weight=700 Width=100, CornersTest-Condensed.ufo \
                Condensed Weight=400 Width=75, CornersTest-BoldCondensed.ufo Bold Condensed \
                Weight=700 Width=75"),
        "{report}"
    );
    // Both compilers, 5 positions each.
    assert_eq!(tools::outlines_compared(&report), 10, "{report}");
    assert!(report.contains("designspace_check: all passed"), "{report}");
}

#[test]
fn the_designspace_and_the_variable_font_import_back_with_the_corner() {
    let b = built();
    let (want, _) = xglyph::source::load_family(&fixture()).expect("loads");
    // Each master's user value on every axis, sorted.
    let locations = |f: &xglyph::model::Family| -> Vec<Vec<f64>> {
        let mut all: Vec<Vec<f64>> = f
            .masters
            .iter()
            .map(|m| {
                f.designspace
                    .axes
                    .iter()
                    .map(|a| m.location.get(a))
                    .collect()
            })
            .collect();
        all.sort_by(|a, b| {
            a.iter()
                .zip(b)
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        all
    };
    for source in ["CornersTest.designspace", "CornersTest[wght,wdth].ttf"] {
        let tmp = tempfile::tempdir().expect("temp dir");
        let imported = tmp.path().join("imported");
        import_ok(&[s(&b.out.join(source))], &imported);
        let (back, _) = xglyph::source::load_family(&imported).expect("loads");
        assert_eq!(back.designspace.axes, want.designspace.axes, "{source}");
        assert_eq!(locations(&back), locations(&want), "{source}");
        // Rebuilt, it is the same font at the corner: the advance of every glyph.
        let rebuilt = tmp.path().join("rebuilt");
        let (code, _, stderr) = xglyph(&["build", s(&imported), "-o", s(&rebuilt)]);
        assert_eq!((code, stderr.as_str()), (0, ""), "{source}");
        let (before, after) = (variable_font(&b.out), variable_font(&rebuilt));
        let (before, after) = (
            FontRef::new(&before).expect("parses"),
            FontRef::new(&after).expect("parses"),
        );
        for (wght, wdth) in [(700.0, 75.0), (600.0, 87.5), (450.0, 80.0)] {
            let lb = before.axes().location([("wght", wght), ("wdth", wdth)]);
            let la = after.axes().location([("wght", wght), ("wdth", wdth)]);
            for name in ["n", "O", "H"] {
                let advance = |f: &FontRef, l: &skrifa::instance::Location| {
                    f.glyph_metrics(Size::unscaled(), LocationRef::from(l))
                        .advance_width(glyph_id(f, name))
                        .expect("advance")
                };
                assert!(
                    (advance(&before, &lb) - advance(&after, &la)).abs() <= 1.0,
                    "{source}: {name} at {wght}, {wdth}"
                );
                let d = paths::two_sided(
                    &skrifa_outline(&before, glyph_id(&before, name), LocationRef::from(&lb)),
                    &skrifa_outline(&after, glyph_id(&after, name), LocationRef::from(&la)),
                    32,
                );
                // The import's tolerance and the rebuild's, plus grid rounding in both.
                assert!(d <= 3.0, "{source}: {name} at {wght}, {wdth}: {d}");
            }
        }
    }
}

#[test]
fn one_ufo_at_two_places_comes_in_as_two_masters_named_by_place() {
    // As fontTools' `Build.designspace` does: the Bold UFO serves at the corner too.
    let b = built();
    let tmp = tempfile::tempdir().expect("temp dir");
    let ds = b.out.join("CornersTest.designspace");
    let xml = fs::read_to_string(&ds).expect("designspace");
    let edited = xml.replacen(
        r#"stylename="Bold Condensed" name="master.Bold Condensed" filename="CornersTest-BoldCondensed.ufo""#,
        r#"stylename="Bold" name="master.Bold" filename="CornersTest-Bold.ufo""#,
        1,
    );
    assert_ne!(xml, edited);
    let copy = b.out.join("Shared.designspace");
    fs::write(&copy, edited).expect("writes");
    let imported = tmp.path().join("imported");
    import_ok(&[s(&copy)], &imported);
    let (back, _) = xglyph::source::load_family(&imported).expect("loads");
    let names: Vec<(&str, String)> = back
        .masters
        .iter()
        .map(|m| (m.name.as_str(), m.folder.display().to_string()))
        .collect();
    assert_eq!(
        names,
        [
            ("Bold", "bold".to_string()),
            ("Condensed", "condensed".to_string()),
            (
                "Bold Weight 700 Width 75",
                "boldweight700width75".to_string()
            )
        ]
    );
    // The corner now holds the Bold's outlines: `n` as wide as the Bold's.
    let n = |m: usize| {
        back.masters[m]
            .glyphs
            .iter()
            .find(|g| g.name == "n")
            .expect("n")
            .advance
    };
    assert_eq!(n(2), n(0));
}

/// Two points that meet only where the deltas of two axes add up (wght 700, wdth 75, a
/// corner of the grid the build checks, with no master there): between any two masters
/// the edge keeps its direction (30, 10, 20 and 25 units long), so the import's pairwise
/// fold check cannot see it; `part_meeting_points` sees it as the build does.
#[test]
fn points_that_meet_where_two_axes_add_up_are_parted_in_every_master() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("font");
    let toml = "family = \"Meet\"\nstyle = \"Regular\"\nunits_per_em = 1000\nascender = 800\n\
        descender = -200\nx_height = 500\ncap_height = 700\ntolerance = 0.5\n\n\
        [[axis]]\ntag = \"wght\"\nname = \"Weight\"\nmin = 400\ndefault = 400\nmax = 700\n\n\
        [[axis]]\ntag = \"wdth\"\nname = \"Width\"\nmin = 75\ndefault = 100\nmax = 100\n\n\
        [[master]]\nname = \"Bold\"\nfolder = \"bold\"\nlocation = { wght = 700 }\n\n\
        [[master]]\nname = \"Condensed\"\nfolder = \"condensed\"\nlocation = { wdth = 75 }\n\n\
        [[master]]\nname = \"Middle\"\nfolder = \"middle\"\nlocation = { wght = 550, wdth = 87.5 }\n";
    // The edge from point 0 to point 1 is `w` long: 30 + (10 - 30) + (20 - 30) = 0 at
    // wght 700, wdth 75.
    let glyph = |w: u32| {
        format!(
            "name = \"a\"\nunicode = 0x0061\nadvance = 100\n\n[[contour]]\n\
             points = [[0, 0, 0], [{w}, 0, 0], [60, 100, 0], [0, 100, 0]]\n"
        )
    };
    for (folder, w) in [("", 30), ("bold", 10), ("condensed", 20), ("middle", 25)] {
        let d = dir.join(folder);
        fs::create_dir_all(&d).expect("folder");
        fs::write(d.join("a.toml"), glyph(w)).expect("glyph");
    }
    fs::write(dir.join("font.toml"), toml).expect("font.toml");

    let (code, _, stderr) = xglyph(&["build", s(&dir), "-o", s(&tmp.path().join("out"))]);
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains(
            "glyph `a`, contour 0, blended at wght 700, wdth 75: points 0 and 1 meet there"
        ),
        "{stderr}"
    );

    let (mut family, _) = xglyph::source::load_family(&dir).expect("the family loads");
    let notes = xglyph::import::masters::part_meeting_points(&mut family).expect("parted");
    assert_eq!(
        notes,
        [
            "glyph `a`, contour 0: point 1 removed in every master, as points 0 and 1 met at \
          wght 700, wdth 75 (its error was measured before)"
        ]
    );
    let triangle = |g: &xglyph::model::Glyph| -> Vec<(f64, f64)> {
        g.contours[0]
            .points()
            .iter()
            .map(|p| (p.pos.x, p.pos.y))
            .collect()
    };
    let expected = vec![(0.0, 0.0), (60.0, 100.0), (0.0, 100.0)];
    assert_eq!(triangle(&family.default.glyphs[0]), expected);
    for m in &family.masters {
        assert_eq!(triangle(&m.glyphs[0]), expected, "{}", m.name);
    }
    assert_eq!(xglyph::family::meeting_points(&family), Ok(Vec::new()));
    xglyph::family::outline_family(&family, 0.5).expect("the parted family builds");
}
