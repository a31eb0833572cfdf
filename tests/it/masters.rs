//! Fonts with masters (issue 16): the loader and its compatibility errors, blending, `fmt`,
//! `check`, `render --at`, named static instances; and the single-master promise: a font
//! without `[[axis]]` builds byte for byte as before masters existed.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use sha2::{Digest, Sha256};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh, empty scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("masters-{name}"));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn xglyph(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(args)
        .output()
        .expect("xglyph runs")
}

/// SHA-256 (hex) of every file under `dir` but the fit cache and the reuse record, by
/// relative path.
fn hashes(dir: &Path, prefix: &str, out: &mut BTreeMap<String, String>) {
    let mut entries: Vec<PathBuf> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let rel = format!("{prefix}/{name}");
        if path.is_dir() {
            hashes(&path, &rel, out);
        } else if name != ".xglyph-cache"
            && name != xglyph::reuse::REUSE_FILE
            && name != xglyph::source::MEMO_FILE
        {
            let digest = Sha256::digest(fs::read(&path).unwrap());
            let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
            out.insert(rel, hex);
        }
    }
}

/// `tests/fixtures/mini` and `glyphs/` (single-master fonts) build to exactly the bytes
/// they built to before masters were added: the SHA-256 of every output file was recorded
/// from the code of commit 13aa68e in `tests/fixtures/single_master_outputs.sha256`.
/// `XGLYPH_BLESS=1` rewrites the list, for a change meant to alter those outputs.
#[test]
fn single_master_outputs_are_byte_identical_to_before_masters() {
    let tmp = scratch("golden");
    for (name, dir) in [("mini", "tests/fixtures/mini"), ("glyphs", "glyphs")] {
        let out = tmp.join(name);
        let result = xglyph(&[
            "build",
            root().join(dir).to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(
            result.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&result.stderr)
        );
    }
    let mut got = BTreeMap::new();
    hashes(&tmp.join("mini"), "mini", &mut got);
    hashes(&tmp.join("glyphs"), "glyphs", &mut got);
    let list = root().join("tests/fixtures/single_master_outputs.sha256");
    if std::env::var_os("XGLYPH_BLESS").is_some() {
        // Only for a change meant to alter single-master outputs (say so in the commit).
        let text: String = got.iter().map(|(p, h)| format!("{h}  {p}\n")).collect();
        fs::write(&list, text).unwrap();
    }
    let golden = fs::read_to_string(&list).unwrap();
    let want: BTreeMap<String, String> = golden
        .lines()
        .map(|l| {
            let (hash, path) = l.split_once("  ").unwrap();
            (path.to_string(), hash.to_string())
        })
        .collect();
    // 15 files of mini, 162 of glyphs/ when the list was made; more glyphs, more files.
    assert!(want.len() >= 177, "{}", want.len());
    // Once `glyphs/` has masters, its build adds the named instances' files; the default
    // master's files stay as they were.
    let has_masters = |dir: &str| {
        fs::read_to_string(root().join(dir).join("font.toml"))
            .unwrap()
            .contains("[[axis]]")
    };
    let extra_allowed = |k: &str| k.starts_with("glyphs/") && has_masters("glyphs");
    let differ: Vec<&String> = want
        .keys()
        .chain(got.keys())
        .filter(|k| want.get(*k) != got.get(*k))
        .filter(|k| want.contains_key(*k) || !extra_allowed(k))
        .collect();
    assert!(differ.is_empty(), "outputs that changed: {differ:?}");
}

fn fixture() -> PathBuf {
    root().join("tests/fixtures/masters")
}

/// Copies the fixture to `<scratch>/font`, applies `edit` (relative path, old text, new
/// text; an empty new text with old `"*"` deletes the file), runs `xglyph check font` in
/// the scratch folder and returns (exit code, stdout).
fn check_edited(test: &str, edits: &[(&str, &str, &str)]) -> (Option<i32>, String) {
    let tmp = scratch(test);
    let font = tmp.join("font");
    copy_dir(&fixture(), &font);
    for (file, old, new) in edits {
        let path = font.join(file);
        if *old == "*" {
            if new.is_empty() {
                fs::remove_file(&path).unwrap();
            } else {
                fs::write(&path, new).unwrap();
            }
            continue;
        }
        let text = fs::read_to_string(&path).unwrap();
        assert!(text.contains(old), "{file} has no {old:?}");
        fs::write(&path, text.replacen(old, new, 1)).unwrap();
    }
    let out = Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(["check", "font"])
        .current_dir(&tmp)
        .output()
        .unwrap();
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    (out.status.code(), text)
}

fn copy_dir(from: &Path, to: &Path) {
    fs::create_dir_all(to).unwrap();
    for entry in fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        let dest = to.join(path.file_name().unwrap());
        if path.is_dir() {
            copy_dir(&path, &dest);
        } else {
            fs::copy(&path, &dest).unwrap();
        }
    }
}

/// `check` fails (exit 1) with exactly this one error line among its output.
fn assert_one_error(test: &str, edits: &[(&str, &str, &str)], error: &str) {
    let (code, out) = check_edited(test, edits);
    assert_eq!(code, Some(1), "{out}");
    let errors: Vec<&str> = out.lines().filter(|l| l.contains(": error: ")).collect();
    assert_eq!(errors, [error], "{out}");
    assert!(out.ends_with("1 error, 0 warnings\n"), "{out}");
}

/// `check` passes (exit 0) with exactly these warning lines among its output.
fn assert_warnings(test: &str, edits: &[(&str, &str, &str)], warnings: &[&str]) {
    let (code, out) = check_edited(test, edits);
    assert_eq!(code, Some(0), "{out}");
    let got: Vec<&str> = out.lines().filter(|l| l.contains(": warning: ")).collect();
    assert_eq!(got, warnings, "{out}");
    let tail = match warnings.len() {
        1 => "0 errors, 1 warning\n".to_string(),
        n => format!("0 errors, {n} warnings\n"),
    };
    assert!(out.ends_with(&tail), "{out}");
}

#[test]
fn the_fixture_checks_clean_and_is_canonical() {
    let (code, out) = check_edited("clean", &[]);
    assert_eq!((code, out.as_str()), (Some(0), "0 errors, 0 warnings\n"));
    let fmt = xglyph(&["fmt", "--check", fixture().to_str().unwrap()]);
    assert_eq!(fmt.status.code(), Some(0), "{fmt:?}");
}

#[test]
fn a_glyph_missing_from_a_master_is_reported_at_its_folder() {
    assert_one_error(
        "missing",
        &[("bold/n.toml", "*", "")],
        "font/font.toml:21:10: error: master `Bold` has no glyph `n`; add bold/n.toml (a copy \
         of font/n.toml with this master's coordinates)",
    );
}

#[test]
fn an_extra_glyph_in_a_master_is_reported() {
    assert_one_error(
        "extra",
        &[(
            "bold/x.toml",
            "*",
            "name = \"x\"\nadvance = 500\n\n[[contour]]\npoints = [[0, 0, 0], [100, 0, 0], [50, 100, 0]]\n",
        )],
        "font/bold/x.toml:1:8: error: glyph `x` is not in the default master; add it there \
         too, or remove this file",
    );
}

#[test]
fn a_missing_contour_is_reported_with_what_the_default_has() {
    let bold_o = fs::read_to_string(fixture().join("bold/O_.toml")).unwrap();
    let first_contour = &bold_o[..bold_o.rfind("\n[[contour]]").unwrap() + 1];
    assert_one_error(
        "contours",
        &[("bold/O_.toml", "*", first_contour)],
        "font/bold/O_.toml:6:3: error: this master has 1 contour, the default master has 2; \
         add contour 1 (8 points in the default)",
    );
}

#[test]
fn an_extra_contour_is_reported_at_its_first_point() {
    assert_one_error(
        "extra-contour",
        &[(
            "bold/H_.toml",
            "[70, 700, 0],\n]\n",
            "[70, 700, 0],\n]\n\n[[contour]]\npoints = [[0, 0, 0], [10, 0, 0], [5, 10, 0]]\n",
        )],
        "font/bold/H_.toml:21:11: error: contour 1 is not in the default master, which has 1 \
         contour; remove it (or add it to every master)",
    );
}

#[test]
fn a_missing_point_is_reported_with_both_counts() {
    assert_one_error(
        "points",
        &[("bold/H_.toml", "  [70, 700, 0],\n", "")],
        "font/bold/H_.toml:16:3: error: contour 0 has 11 points here, the default master has \
         12; add 1 point after point 10",
    );
}

#[test]
fn an_extra_point_is_reported_at_the_first_extra_one() {
    assert_one_error(
        "points-extra",
        &[(
            "bold/H_.toml",
            "  [70, 700, 0],\n",
            "  [70, 700, 0],\n  [60, 400, 0],\n",
        )],
        "font/bold/H_.toml:18:3: error: contour 0 has 13 points here, the default master has \
         12; point 12 and after are extra; remove 1",
    );
}

#[test]
fn a_point_sharp_in_one_master_only_is_reported_with_both_values() {
    assert_one_error(
        "sharp",
        &[("bold/n.toml", "[200, 330, 1]", "[200, 330, 0]")],
        "font/bold/n.toml:8:3: error: point 2 of contour 0 is sharp (s = 0) here but s = 1 in \
         the default master; a sharp point must be sharp in every master (a corner cannot \
         appear mid-axis): make it s = 0 in every master, or non-zero here",
    );
    assert_one_error(
        "smooth",
        &[("bold/n.toml", "[60, 0, 0]", "[60, 0, 0.25]")],
        "font/bold/n.toml:6:3: error: point 0 of contour 0 has s = 0.25 here but is sharp \
         (s = 0) in the default master; a sharp point must be sharp in every master (a corner \
         cannot appear mid-axis): make it s = 0 here",
    );
}

#[test]
fn different_components_are_reported() {
    assert_one_error(
        "components",
        &[("bold/ndot.toml", "base = \"n\"", "base = \"H\"")],
        "font/bold/ndot.toml:5:8: error: component 0 is `H` here but `n` in the default \
         master, whose components are `n`, `dotcomb`; masters need the same components in the \
         same order",
    );
}

#[test]
fn a_master_unicode_must_match_the_default() {
    assert_one_error(
        "unicode",
        &[(
            "bold/n.toml",
            "advance = 590",
            "unicode = 0x006D\nadvance = 590",
        )],
        "font/bold/n.toml:2:11: error: `unicode` 0x006D differs from the default master's \
         0x006E; leave it out (a master has the default's code points) or make it the same",
    );
}

#[test]
fn font_toml_axis_master_and_instance_errors() {
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "tag",
            "tag = \"wght\"",
            "tag = \"weight\"",
            "font/font.toml:13:7: error: `tag` must be 1 to 4 printable ASCII characters (an \
             OpenType axis tag such as \"wght\"), found \"weight\"",
        ),
        (
            "default-range",
            "default = 400",
            "default = 800",
            "font/font.toml:16:11: error: `default` = 800 is outside the axis range 400..700",
        ),
        (
            "unknown-axis",
            "location = { wght = 700 }",
            "location = { wdth = 700 }",
            "font/font.toml:22:14: error: unknown axis `wdth` in `location`; the axes are `wght`",
        ),
        (
            "master-range",
            "location = { wght = 700 }",
            "location = { wght = 750 }",
            "font/font.toml:22:21: error: wght = 750 is outside the axis range 400..700",
        ),
        (
            "instance-range",
            "location = { wght = 500 }",
            "location = { wght = 300 }",
            "font/font.toml:30:21: error: wght = 300 is outside the axis range 400..700",
        ),
        (
            "dotdot",
            "folder = \"bold\"",
            "folder = \"../bold\"",
            "font/font.toml:21:10: error: `folder` must stay inside the font folder (no `..`), \
             found \"../bold\"",
        ),
        (
            "absolute",
            "folder = \"bold\"",
            "folder = \"/bold\"",
            "font/font.toml:21:10: error: `folder` must be relative to the font folder, found \
             \"/bold\"",
        ),
        (
            "no-folder",
            "folder = \"bold\"",
            "folder = \"heavy\"",
            "font/font.toml:21:10: error: master folder font/heavy not found",
        ),
        (
            "at-default",
            "location = { wght = 700 }",
            "location = { wght = 400 }",
            "font/font.toml:22:12: error: master `Bold` is at the default location (wght = \
             400), where the font folder itself is the default master; move it along an axis",
        ),
    ];
    for (name, old, new, error) in cases {
        assert_one_error(name, &[("font.toml", old, new)], error);
    }
    assert_one_error(
        "dup-tag",
        &[(
            "font.toml",
            "\n[[master]]",
            "\n[[axis]]\ntag = \"wght\"\nname = \"W\"\nmin = 0\ndefault = 0\nmax = 0\n\n[[master]]",
        )],
        "font/font.toml:20:7: error: duplicate axis tag `wght` (first written at line 13)",
    );
    assert_one_error(
        "two-at-one-place",
        &[(
            "font.toml",
            "location = { wght = 700 }\n",
            "location = { wght = 700 }\n\n[[master]]\nname = \"Heavy\"\nfolder = \"bold\"\nlocation = { wght = 700 }\n",
        )],
        "font/font.toml:27:12: error: master `Heavy` is at the same location as master `Bold` \
         (wght = 700)",
    );
    // An axis end without a master is a warning: the design blends back to the default
    // there, as fontmake and fontc build it.
    assert_warnings(
        "uncovered",
        &[(
            "font.toml",
            "location = { wght = 700 }",
            "location = { wght = 600 }",
        )],
        &[
            "font/font.toml:17:7: warning: axis `wght` ends at max = 700 but no master is there: \
           past master `Bold` (wght = 600) the design blends back to the default, which it \
           reaches at 700, as fontmake and fontc build it; add a `[[master]]` with location \
           { wght = 700 }, or set max to 600",
        ],
    );
    assert_warnings(
        "a corner master alone",
        &[
            (
                "font.toml",
                "max = 700\n",
                "max = 700\n\n[[axis]]\ntag = \"wdth\"\nname = \"Width\"\nmin = 75\ndefault = 100\nmax = 100\n",
            ),
            ("font.toml", "location = { wght = 700 }", "location = { wght = 700, wdth = 75 }"),
        ],
        &[
            "font/font.toml:17:7: warning: axis `wght` ends at max = 700 but no master is there: \
             no master on this axis alone is on that side, so along the axis the design stays \
             the default there (only corner master `Bold`, which blends from the masters on \
             each of its axes); add a `[[master]]` with location { wght = 700 }, or set max to \
             the default",
            "font/font.toml:22:7: warning: axis `wdth` ends at min = 75 but no master is there: \
             no master on this axis alone is on that side, so along the axis the design stays \
             the default there (only corner master `Bold`, which blends from the masters on \
             each of its axes); add a `[[master]]` with location { wdth = 75 }, or set min to \
             the default",
        ],
    );
    // Axis maps: each error at the entry to fix (line 18 is the inserted `map`).
    let map_cases: &[(&str, &str, &str)] = &[
        (
            "map-shape",
            "map = [[400, 0], [550], [700, 100]]",
            "font/font.toml:18:18: error: `map` must be a list of [user, design] pairs such as \
             [[400, 0], [550, 70], [700, 100]], found an array of 1 values",
        ),
        (
            "map-user-order",
            "map = [[400, 0], [550, 70], [500, 80], [700, 100]]",
            "font/font.toml:18:29: error: `map` user values must increase: 500 follows 550",
        ),
        (
            "map-design-order",
            "map = [[400, 0], [550, 70], [600, 60], [700, 100]]",
            "font/font.toml:18:29: error: `map` design values must increase: 60 follows 70",
        ),
        (
            "map-start",
            "map = [[450, 0], [700, 100]]",
            "font/font.toml:18:8: error: `map` must start at the axis `min` = 400, found user \
             value 450",
        ),
        (
            "map-end",
            "map = [[400, 0], [650, 100]]",
            "font/font.toml:18:18: error: `map` must end at the axis `max` = 700, found user \
             value 650",
        ),
        (
            "map-number",
            "map = [[400, 0], [700, \"heavy\"]]",
            "font/font.toml:18:24: error: `map` must be a number, found string",
        ),
        (
            "map-empty",
            "map = []",
            "font/font.toml:18:7: error: `map` must be a list of [user, design] pairs such as \
             [[400, 0], [550, 70], [700, 100]], found an empty list; leave it out for a linear \
             axis",
        ),
    ];
    for (name, map, error) in map_cases {
        let edit = format!("max = 700\n{map}\n");
        assert_one_error(name, &[("font.toml", "max = 700\n", &edit)], error);
    }
    assert_one_error(
        "dup-instance",
        &[("font.toml", "name = \"Medium\"", "name = \"Regular\"")],
        "font/font.toml:29:8: error: duplicate instance name `Regular`",
    );
}

fn at(wght: f64) -> xglyph::designspace::Location {
    xglyph::designspace::Location([("wght".to_string(), wght)].into_iter().collect())
}

/// Every blended number of a glyph, in one list: x, y, s of each point, the advance,
/// component offsets.
fn numbers(g: &xglyph::model::Glyph) -> Vec<f64> {
    let mut out = vec![g.advance];
    for c in &g.contours {
        for p in c.points() {
            out.extend([p.pos.x, p.pos.y, p.s]);
        }
    }
    for c in &g.components {
        out.extend([c.offset.0, c.offset.1]);
    }
    out
}

fn kern(k: &[xglyph::model::KernPair], l: &str, r: &str) -> f64 {
    k.iter()
        .find(|p| p.left == l && p.right == r)
        .map_or(0.0, |p| p.value)
}

#[test]
fn the_blend_is_each_master_at_its_location_and_the_mean_halfway() {
    let (family, warnings) = xglyph::source::load_family(&fixture()).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(family.masters.len(), 1);
    let bold = &family.masters[0];
    let regular = family.instance_at(&at(400.0)).unwrap();
    assert_eq!(
        regular, family.default,
        "the default location is the default master"
    );
    let at700 = family.instance_at(&at(700.0)).unwrap();
    let mid = family.instance_at(&at(550.0)).unwrap();
    assert_eq!(at700.glyphs.len(), 7);
    let mut compared = 0;
    for (i, g) in at700.glyphs.iter().enumerate() {
        assert_eq!(numbers(g), numbers(&bold.glyphs[i]), "{}", g.name);
        let (d, b, m) = (
            numbers(&family.default.glyphs[i]),
            numbers(&bold.glyphs[i]),
            numbers(&mid.glyphs[i]),
        );
        for k in 0..d.len() {
            assert_eq!(m[k], (d[k] + b[k]) / 2.0, "{} number {k}", g.name);
            compared += 1;
        }
    }
    // 7 advances, 8 + 12 + 16 + 12 + 4 points x 3, 2 component offsets x 2.
    assert_eq!(compared, 7 + 3 * (8 + 12 + 16 + 12 + 4) + 4);
    // Spot values: H's first point and advance, the dot's offset.
    let h = mid.glyphs.iter().find(|g| g.name == "H").unwrap();
    assert_eq!((h.advance, h.contours[0].points()[0].pos.x), (670.0, 75.0));
    let ndot = mid.glyphs.iter().find(|g| g.name == "ndot").unwrap();
    assert_eq!(ndot.components[1].offset, (17.5, 0.0));
    // Kerning: each master's values at its location, the mean between, a pair only the
    // Bold master has blended from 0.
    for (l, r, d, b) in [
        ("H", "O", -10.0, -30.0),
        ("O", "H", -12.0, -20.0),
        ("n", "O", 0.0, -16.0),
    ] {
        assert_eq!(kern(&regular.kerning, l, r), d);
        assert_eq!(kern(&at700.kerning, l, r), b);
        assert_eq!(kern(&mid.kerning, l, r), (d + b) / 2.0);
    }
    assert_eq!(
        regular.kerning.len(),
        2,
        "the Bold-only pair is 0 at the default"
    );
    assert_eq!(at700.kerning.len(), 3);
}

#[test]
fn render_at_a_position_draws_the_blend() {
    let tmp = scratch("render-at");
    let font = fixture();
    let mut inked = Vec::new();
    for wght in ["400", "550", "700"] {
        let out = tmp.join(wght);
        let result = xglyph(&[
            "render",
            font.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--only",
            "proof",
            "--text",
            "HOn",
            "--sizes",
            "100",
            "--at",
            &format!("wght={wght}"),
        ]);
        assert_eq!(result.status.code(), Some(0), "{result:?}");
        let img = image_ink(&out.join("proof.png"));
        inked.push(img);
    }
    // Heavier is darker: the ink grows with the weight, and 550 lies strictly between.
    assert!(inked[0] < inked[1] && inked[1] < inked[2], "{inked:?}");
    let (plain, at_default) = (tmp.join("plain"), tmp.join("400"));
    let result = xglyph(&[
        "render",
        font.to_str().unwrap(),
        "-o",
        plain.to_str().unwrap(),
        "--only",
        "proof",
        "--text",
        "HOn",
        "--sizes",
        "100",
    ]);
    assert_eq!(result.status.code(), Some(0));
    assert_eq!(
        fs::read(plain.join("proof.png")).unwrap(),
        fs::read(at_default.join("proof.png")).unwrap(),
        "--at the default location renders the default master"
    );
}

/// Sum of (255 - red) over the PNG's pixels.
fn image_ink(path: &Path) -> u64 {
    let png = fs::read(path).unwrap();
    let pixmap = resvg::tiny_skia::Pixmap::decode_png(&png).unwrap();
    pixmap
        .pixels()
        .iter()
        .map(|p| 255 - u64::from(p.red()))
        .sum()
}

#[test]
fn bad_at_flags_are_clear_errors() {
    let font = fixture();
    let mini = root().join("tests/fixtures/mini");
    let tmp = scratch("bad-at");
    for (dir, at, message) in [
        (&font, "wght=800", "error: --at wght=800: wght = 800 is outside the axis range 400..700\n"),
        (&font, "wdth=80", "error: --at wdth=80: unknown axis `wdth`; the font's axes are `wght` (400..700)\n"),
        (&font, "wght", "error: --at wght: expected TAG=VALUE (several separated by commas), such as wght=650; found `wght`\n"),
        (&font, "wght=heavy", "error: --at wght=heavy: `heavy` is not a number (the wght value)\n"),
        (&font, "wght=500,wght=600", "error: --at wght=500,wght=600: axis `wght` is given twice\n"),
        (&mini, "wght=500", "error: --at wght=500: the font has no axes (no `[[axis]]` in font.toml), so it has one position only; leave out --at\n"),
    ] {
        let out = tmp.join("out");
        let result = xglyph(&[
            "render",
            dir.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--at",
            at,
        ]);
        assert_eq!(result.status.code(), Some(1));
        assert_eq!(String::from_utf8_lossy(&result.stderr), message);
        assert!(!out.exists(), "nothing written");
    }
}

#[test]
fn build_writes_each_named_instance_and_their_proof() {
    let tmp = scratch("build");
    let out = tmp.join("out");
    let result = xglyph(&[
        "build",
        fixture().to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(result.status.code(), Some(0), "{result:?}");
    let mut names: Vec<String> = fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("MastersTest-") || n.starts_with("proof"))
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "MastersTest-Bold.otf",
            "MastersTest-Bold.svg",
            "MastersTest-Bold.ttf",
            "MastersTest-Bold.ufo",
            "MastersTest-Medium.otf",
            "MastersTest-Medium.svg",
            "MastersTest-Medium.ttf",
            "MastersTest-Regular.otf",
            "MastersTest-Regular.svg",
            "MastersTest-Regular.ttf",
            "MastersTest-Regular.ufo",
            "MastersTest-Regular.woff2",
            "MastersTest-SemiBold.otf",
            "MastersTest-SemiBold.svg",
            "MastersTest-SemiBold.ttf",
            "proof-instances.png",
            "proof.png",
        ]
    );
    // And the variable font, for the web too.
    assert!(out.join("MastersTest[wght].ttf").is_file());
    assert!(out.join("MastersTest[wght].woff2").is_file());
    // Each static instance carries the instance's advances: read hmtx back with read-fonts.
    use read_fonts::{FontRef, TableProvider};
    let (family, _) = xglyph::source::load_family(&fixture()).unwrap();
    for (style, wght, weight_class) in [
        ("Medium", 500.0, 500),
        ("SemiBold", 600.0, 600),
        ("Bold", 700.0, 700),
    ] {
        let bytes = fs::read(out.join(format!("MastersTest-{style}.ttf"))).unwrap();
        let ttf = FontRef::new(&bytes).unwrap();
        let want = family.instance_at(&at(wght)).unwrap();
        let hmtx = ttf.hmtx().unwrap();
        let h = want.glyphs.iter().position(|g| g.name == "H").unwrap();
        assert_eq!(
            f64::from(
                hmtx.advance(read_fonts::types::GlyphId::new(h as u32))
                    .unwrap()
            ),
            want.glyphs[h].advance.round(),
            "{style}"
        );
        assert_eq!(ttf.os2().unwrap().us_weight_class(), weight_class);
    }
    // The instances proof stacks four labelled blocks; heavier blocks hold more ink.
    let proof = fs::read(out.join("proof-instances.png")).unwrap();
    let pixmap = resvg::tiny_skia::Pixmap::decode_png(&proof).unwrap();
    let single =
        resvg::tiny_skia::Pixmap::decode_png(&fs::read(out.join("proof.png")).unwrap()).unwrap();
    assert!(pixmap.height() > 4 * 100, "{}", pixmap.height());
    let quarter = pixmap.height() as usize / 4;
    let w = pixmap.width() as usize;
    let ink: Vec<u64> = (0..4)
        .map(|b| {
            pixmap.pixels()[b * quarter * w..(b + 1) * quarter * w]
                .iter()
                .map(|p| 255 - u64::from(p.red()))
                .sum()
        })
        .collect();
    assert!(
        ink[0] < ink[1] && ink[1] < ink[2] && ink[2] < ink[3],
        "{ink:?}"
    );
    assert!(single.height() > 0);
    // `svg --at` a named instance's position writes that instance's SVG font, byte for byte.
    let svg_out = tmp.join("svg");
    let result = xglyph(&[
        "svg",
        fixture().to_str().unwrap(),
        "-o",
        svg_out.to_str().unwrap(),
        "--at",
        "wght=600",
    ]);
    assert_eq!(result.status.code(), Some(0), "{result:?}");
    assert_eq!(
        fs::read(svg_out.join("MastersTest-SemiBold.svg")).unwrap(),
        fs::read(out.join("MastersTest-SemiBold.svg")).unwrap()
    );
}

#[test]
fn fmt_rewrites_the_masters_keys_and_master_files_canonically() {
    let tmp = scratch("fmt");
    let font = tmp.join("font");
    copy_dir(&fixture(), &font);
    let edit = |file: &str, old: &str, new: &str| {
        let path = font.join(file);
        let text = fs::read_to_string(&path).unwrap();
        assert!(text.contains(old), "{file}: {old:?}");
        fs::write(&path, text.replacen(old, new, 1)).unwrap();
    };
    // Keys out of order, an inline location written as a sub-table, a master file with
    // its (matching) unicode and points on one line, a master kerning value as a float.
    edit(
        "font.toml",
        "tag = \"wght\"\nname = \"Weight\"",
        "name = \"Weight\"\ntag = \"wght\"",
    );
    edit(
        "font.toml",
        "name = \"Bold\"\nfolder = \"bold\"\nlocation = { wght = 700 }",
        "folder = \"bold\"\nname = \"Bold\"\nlocation.wght = 700.0",
    );
    edit(
        "bold/dotcomb.toml",
        "advance = 0",
        "unicode = 0x0307\nadvance = 0",
    );
    edit(
        "bold/dotcomb.toml",
        "points = [\n  [220, 570, 0],\n  [340, 570, 0],\n  [340, 690, 0],\n  [220, 690, 0],\n]",
        "points = [[220, 570, 0], [340, 570, 0], [340, 690, 0], [220, 690, 0]]",
    );
    edit("bold/kerning.toml", "value = -16", "value = -16.0");
    let check = xglyph(&["fmt", "--check", font.to_str().unwrap()]);
    assert_eq!(check.status.code(), Some(1));
    let listed = String::from_utf8_lossy(&check.stdout);
    for file in ["font.toml", "bold/dotcomb.toml", "bold/kerning.toml"] {
        assert!(listed.contains(&format!("font/{file}")), "{listed}");
    }
    let result = xglyph(&["fmt", font.to_str().unwrap()]);
    assert_eq!(result.status.code(), Some(0), "{result:?}");
    for file in ["font.toml", "bold/dotcomb.toml", "bold/kerning.toml"] {
        let mut want = fs::read_to_string(fixture().join(file)).unwrap();
        if file == "bold/dotcomb.toml" {
            // A master file keeps its `unicode` (it matches the default's).
            want = want.replacen("advance = 0", "unicode = 0x0307\nadvance = 0", 1);
        }
        assert_eq!(fs::read_to_string(font.join(file)).unwrap(), want, "{file}");
    }
}

/// A font with masters and `count` named instances `W<wght>` every 5 units from `from`,
/// built into `<scratch>/out`; the output folder.
fn build_with_instances(test: &str, from: u32, count: u32) -> PathBuf {
    let tmp = scratch(test);
    let font = tmp.join("font");
    copy_dir(&fixture(), &font);
    let toml = fs::read_to_string(font.join("font.toml")).unwrap();
    let mut toml = toml[..toml.find("[[instance]]").unwrap()].to_string();
    for k in 0..count {
        let w = from + 5 * k;
        toml += &format!("[[instance]]\nname = \"W{w}\"\nlocation = {{ wght = {w} }}\n\n");
    }
    fs::write(font.join("font.toml"), toml).unwrap();
    let out = tmp.join("out");
    // One text for every page (the default text follows the first instance's kerning).
    let result = xglyph(&[
        "build",
        font.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--text",
        "HOn OH\\nnO HO\\nOHn",
    ]);
    assert_eq!(result.status.code(), Some(0), "{result:?}");
    out
}

fn png_size(path: &Path) -> (u32, u32) {
    let pixmap = resvg::tiny_skia::Pixmap::decode_png(&fs::read(path).unwrap()).unwrap();
    (pixmap.width(), pixmap.height())
}

/// 61 instances' blocks are taller than one image may be: the proof comes in pages, each
/// within the limits, and the last page is exactly the proof of its instances alone.
#[test]
fn many_named_instances_page_the_instances_proof() {
    let out = build_with_instances("many-instances", 400, 61);
    assert!(!out.join("proof-instances.png").exists());
    let pages: Vec<(u32, u32)> = (1..=2)
        .map(|k| png_size(&out.join(format!("proof-instances-{k}.png"))))
        .collect();
    assert!(!out.join("proof-instances-3.png").exists());
    eprintln!("pages: {pages:?}");
    for &(w, h) in &pages {
        assert!(
            h <= xglyph::render::MAX_SIDE
                && u64::from(w) * u64::from(h) <= xglyph::render::MAX_AREA
        );
    }
    // Every block is the same height here: 61 of them over the two pages, as many on the
    // first as fit.
    let block = (pages[0].1 + pages[1].1) / 61;
    let (first, rest) = (pages[0].1 / block, pages[1].1 / block);
    assert_eq!(
        (first * block, rest * block, first + rest),
        (pages[0].1, pages[1].1, 61)
    );
    assert!(
        (first + 1) * block > xglyph::render::MAX_SIDE,
        "{first} blocks of {block} px"
    );
    let last = build_with_instances("last-instances", 400 + 5 * first, rest);
    let same = fs::read(last.join("proof-instances.png")).unwrap()
        == fs::read(out.join("proof-instances-2.png")).unwrap();
    assert!(
        same,
        "the last page differs from the proof of its instances alone"
    );
}

/// Two neighbouring points that trade places between the masters meet halfway: the build
/// stops and says where, in user values, and which points; nothing is written.
#[test]
fn points_that_meet_between_the_masters_are_named_with_the_place() {
    let tmp = scratch("meet");
    let font = tmp.join("font");
    copy_dir(&fixture(), &font);
    let bold = font.join("bold/H_.toml");
    let text = fs::read_to_string(&bold).unwrap();
    // Regular has (160, 320) and (480, 320); halfway to these both are at (270, 307.5).
    let edited = text.replacen(
        "  [220, 295, 0],\n  [480, 295, 0],",
        "  [380, 295, 0],\n  [60, 295, 0],",
        1,
    );
    assert_ne!(edited, text);
    fs::write(&bold, edited).unwrap();
    let out = tmp.join("out");
    let result = xglyph(&["build", font.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(result.status.code(), Some(1));
    assert_eq!(
        String::from_utf8_lossy(&result.stderr),
        "error: glyph `H`, contour 0, blended at wght 550: points 2 and 3 meet there (they \
         cross between the masters); move them in a master so that they stay apart\n"
    );
    assert!(!out.exists(), "nothing written");
}

/// A `[[rule]]` appended to the fixture's `font.toml` (its header at line 40).
fn with_rule(rule: &str) -> String {
    format!("name = \"Bold\"\nlocation = {{ wght = 700 }}\n\n[[rule]]\n{rule}")
}

#[test]
fn rule_errors_name_the_entry_to_fix() {
    let at_end = "name = \"Bold\"\nlocation = { wght = 700 }\n";
    let cases: &[(&str, &str, &str)] = &[
        (
            "unknown axis",
            "name = \"r\"\nconditions = [{ wdth = [75, 80] }]\nsubstitutions = { n = \"H\" }\n",
            "font/font.toml:42:17: error: unknown axis `wdth` in `conditions`; the axes are `wght`",
        ),
        (
            "backwards",
            "name = \"r\"\nconditions = [{ wght = [650, 550] }]\nsubstitutions = { n = \"H\" }\n",
            "font/font.toml:42:30: error: the range of `wght` runs backwards: 550 comes after 650",
        ),
        (
            "outside the axis",
            "name = \"r\"\nconditions = [{ wght = [600, 900] }]\nsubstitutions = { n = \"H\" }\n",
            "font/font.toml:42:24: error: wght 600..900 reaches outside the axis range 400..700",
        ),
        (
            "not a range",
            "name = \"r\"\nconditions = [{ wght = 600 }]\nsubstitutions = { n = \"H\" }\n",
            "font/font.toml:42:24: error: `wght` in a condition must be a range [min, max] such \
             as [600, 700], found integer",
        ),
        (
            "no conditions",
            "name = \"r\"\nconditions = []\nsubstitutions = { n = \"H\" }\n",
            "font/font.toml:42:14: error: `conditions` is empty, so the rule never holds; add a \
             box such as { wght = [600, 700] }",
        ),
        (
            "unknown glyph",
            "name = \"r\"\nconditions = [{ wght = [600, 700] }]\nsubstitutions = { n = \"n.alt\" }\n",
            "font/font.toml:43:23: error: rule `r` names glyph `n.alt`, which the font does not \
             have",
        ),
        (
            "by itself",
            "name = \"r\"\nconditions = [{ wght = [600, 700] }]\nsubstitutions = { n = \"n\" }\n",
            "font/font.toml:43:23: error: `n` is substituted by itself",
        ),
        (
            "no substitutions",
            "name = \"r\"\nconditions = [{ wght = [600, 700] }]\n",
            "font/font.toml:40:1: error: missing required key `substitutions`; add a line such as \
             `substitutions = { dollar = \"dollar.nostroke\" }`",
        ),
    ];
    for (test, rule, error) in cases {
        assert_one_error(test, &[("font.toml", at_end, &with_rule(rule))], error);
    }
    assert_one_error(
        "processing",
        &[(
            "font.toml",
            "tolerance = 0.5\n",
            "tolerance = 0.5\nrules_processing = \"later\"\n",
        )],
        "font/font.toml:11:20: error: `rules_processing` must be \"first\" or \"last\", found \
         \"later\"",
    );
}
