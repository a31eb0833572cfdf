//! Rules (`[[rule]]`: glyph substitutions by place) as a user meets them, on
//! `tests/fixtures/masters` with an `H.alt` (the H at 90 % height) that replaces `H` from
//! wght 550 up. `check` and `fmt`; HarfBuzz shaping the variable TTF across the axis; the
//! static instances, which swap the glyphs as fontmake's do; the exported designspace's
//! `<rules>` compiled by fontmake and fontc and shaped the same; and the designspace
//! imported back.
//!
//! Tests that need uharfbuzz, fontmake or fontc print `skipped: …` and pass when they are
//! missing, unless `XGLYPH_REQUIRE_TOOLS=1` (CI).

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use skrifa::instance::LocationRef;
use skrifa::raw::TableProvider;
use skrifa::{FontRef, MetadataProvider};

use crate::common::cli::{import_ok, xglyph};
use crate::common::fonts::{glyph_id, skrifa_outline};
use crate::common::{paths, tools};

const RULE: &str = "\n[[rule]]\nname = \"short H\"\nconditions = [{ wght = [550, 700] }]\n\
                    substitutions = { H = \"H.alt\" }\n";

struct Built {
    _tmp: tempfile::TempDir,
    font: PathBuf,
    out: PathBuf,
}

fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

/// The masters fixture with `H.alt` in both masters and [`RULE`], in `dir`.
fn rule_font(dir: &Path, rule: &str) -> PathBuf {
    let font = dir.join("font");
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/masters");
    for sub in ["", "bold"] {
        fs::create_dir_all(font.join(sub)).expect("mkdir");
        for entry in fs::read_dir(fixture.join(sub)).expect("reads") {
            let path = entry.expect("entry").path();
            if path.is_file() {
                fs::copy(&path, font.join(sub).join(path.file_name().expect("name")))
                    .expect("copies");
            }
        }
        // H.alt: the H's points at 90 % height, no code point.
        let h = fs::read_to_string(fixture.join(sub).join("H_.toml")).expect("H");
        let mut alt = String::new();
        for line in h.lines() {
            if line.starts_with("unicode") {
                continue;
            }
            let line = line.replace("name = \"H\"", "name = \"H.alt\"");
            let trimmed = line.trim_start();
            if let Some(point) = trimmed.strip_prefix('[').and_then(|p| p.strip_suffix("],")) {
                let v: Vec<f64> = point
                    .split(", ")
                    .map(|x| x.parse().expect("number"))
                    .collect();
                alt.push_str(&format!(
                    "  [{}, {}, {}],\n",
                    v[0],
                    (v[1] * 0.9).round(),
                    v[2]
                ));
            } else {
                alt.push_str(&line);
                alt.push('\n');
            }
        }
        fs::write(font.join(sub).join("H_.alt.toml"), alt).expect("writes");
    }
    let toml = fs::read_to_string(font.join("font.toml")).expect("font.toml");
    fs::write(font.join("font.toml"), toml + rule).expect("writes");
    font
}

/// The font with [`RULE`], built once with the CLI.
fn built() -> &'static Built {
    static BUILT: OnceLock<Built> = OnceLock::new();
    BUILT.get_or_init(|| {
        let tmp = tempfile::tempdir().expect("temp dir");
        let font = rule_font(tmp.path(), RULE);
        let out = tmp.path().join("out");
        let (code, stdout, stderr) = xglyph(&["build", s(&font), "-o", s(&out)]);
        assert_eq!((code, stderr.as_str()), (0, ""), "{stdout}");
        Built {
            _tmp: tmp,
            font,
            out,
        }
    })
}

/// The glyph names HarfBuzz shapes "HOH" to in each font at each wght.
fn shaped(fonts: &[&Path], wghts: &[f64]) -> Vec<Vec<Vec<String>>> {
    let script = r#"
import json, sys
import uharfbuzz as hb
from fontTools.ttLib import TTFont
wghts = json.loads(sys.argv[1])
out = []
for path in sys.argv[2:]:
    names = TTFont(path).getGlyphOrder()
    font = hb.Font(hb.Face(open(path, "rb").read()))
    runs = []
    for w in wghts:
        font.set_variations({"wght": w})
        buf = hb.Buffer()
        buf.add_str("HOH")
        buf.guess_segment_properties()
        hb.shape(font, buf)
        runs.append([names[i.codepoint] for i in buf.glyph_infos])
    out.append(runs)
print(json.dumps(out))
"#;
    let wghts = serde_json::to_string(wghts).expect("json");
    let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![&wghts];
    for f in fonts {
        args.push(f);
    }
    tools::python_json(script, &args)
}

#[test]
fn a_rule_checks_formats_and_writes_back() {
    let b = built();
    assert_eq!(
        xglyph(&["check", s(&b.font)]),
        (0, "0 errors, 0 warnings\n".into(), String::new())
    );
    // The rule as written is canonical, and `fmt` keeps it.
    let (code, stdout, stderr) = xglyph(&["fmt", "--check", s(&b.font)]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    // Two boxes, axes in order, a quoted glyph name as a key, and `rules_processing`.
    let tmp = tempfile::tempdir().expect("temp dir");
    let font = rule_font(
        tmp.path(),
        "\n[[rule]]\nname = \"two\"\nconditions = [{wght=[550,700]},{ wght = [400,420] }]\n\
         substitutions = { \"H\" = \"H.alt\", O = \"H\" }\n",
    );
    let toml = fs::read_to_string(font.join("font.toml")).expect("font.toml");
    fs::write(
        font.join("font.toml"),
        toml.replacen(
            "tolerance = 0.5\n",
            "tolerance = 0.5\nrules_processing = \"last\"\n",
            1,
        ),
    )
    .expect("writes");
    let (code, stdout, stderr) = xglyph(&["fmt", s(&font)]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let toml = fs::read_to_string(font.join("font.toml")).expect("font.toml");
    assert!(
        toml.ends_with(
            "\n[[rule]]\nname = \"two\"\nconditions = [{ wght = [550, 700] }, { wght = [400, \
             420] }]\nsubstitutions = { H = \"H.alt\", O = \"H\" }\n"
        ),
        "{toml}"
    );
    assert!(toml.contains("\nrules_processing = \"last\"\n"), "{toml}");
    // With `last` the rules vary `rclt`.
    let out = tmp.path().join("out");
    let (code, _, stderr) = xglyph(&["build", s(&font), "-o", s(&out)]);
    // The second box takes in the default (wght 400): the build says what that means.
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stderr.contains(
            "font.toml:41:1: warning: rule `two` holds at the default location: the variable \
             font and the instances there substitute, but the default master's own static \
             fonts, sheets and proofs show the glyphs unchanged\n"
        ),
        "{stderr}"
    );
    let vf = fs::read(out.join("MastersTest[wght].ttf")).expect("VF");
    let vf = FontRef::new(&vf).expect("parses");
    let gsub = vf.gsub().expect("GSUB");
    let tags: Vec<String> = gsub
        .feature_list()
        .expect("features")
        .feature_records()
        .iter()
        .map(|r| r.feature_tag().to_string())
        .collect();
    assert_eq!(tags, ["rclt"]);
}

#[test]
fn harfbuzz_substitutes_where_the_rule_holds() {
    if !tools::available(
        tools::python_imports("uharfbuzz, fontTools"),
        "uharfbuzz",
        "pip install uharfbuzz fonttools",
    ) {
        return;
    }
    let b = built();
    let runs = shaped(
        &[&b.out.join("MastersTest[wght].ttf")],
        &[400.0, 500.0, 549.0, 550.0, 600.0, 700.0],
    );
    let plain = ["H", "O", "H"].map(String::from).to_vec();
    let alt = ["H.alt", "O", "H.alt"].map(String::from).to_vec();
    assert_eq!(
        runs[0],
        [
            plain.clone(),
            plain.clone(),
            plain.clone(),
            alt.clone(),
            alt.clone(),
            alt
        ]
    );
}

#[test]
fn static_instances_swap_the_glyphs_where_the_rule_holds() {
    let b = built();
    let vf = fs::read(b.out.join("MastersTest[wght].ttf")).expect("VF");
    let vf = FontRef::new(&vf).expect("parses");
    for (style, wght, holds) in [("Medium", 500.0, false), ("SemiBold", 600.0, true)] {
        let bytes = fs::read(b.out.join(format!("MastersTest-{style}.ttf"))).expect("TTF");
        let font = FontRef::new(&bytes).expect("parses");
        let location = vf.axes().location([("wght", wght as f32)]);
        let at = LocationRef::from(&location);
        let (h, alt) = (
            skrifa_outline(&vf, glyph_id(&vf, "H"), at),
            skrifa_outline(&vf, glyph_id(&vf, "H.alt"), at),
        );
        // The code point's glyph has the alternate's drawing where the rule holds, and the
        // alternate's name holds the H's.
        let (want_h, want_alt) = if holds { (&alt, &h) } else { (&h, &alt) };
        let d = |name: &str, want: &kurbo::BezPath| {
            paths::two_sided(
                &skrifa_outline(&font, glyph_id(&font, name), LocationRef::default()),
                want,
                32,
            )
        };
        // Each is within the tolerance (0.5) of the blend, plus grid rounding.
        assert!(d("H", want_h) <= 2.5, "{style}: H {}", d("H", want_h));
        assert!(
            d("H.alt", want_alt) <= 2.5,
            "{style}: H.alt {}",
            d("H.alt", want_alt)
        );
        // And they differ by far more: 10 % of the cap height.
        assert!(d("H", want_alt) >= 50.0, "{style}: {}", d("H", want_alt));
    }
}

#[test]
fn fontmake_and_fontc_read_the_rules_from_the_designspace() {
    if !tools::designspace_compilers_available()
        || !tools::available(
            tools::python_imports("uharfbuzz"),
            "uharfbuzz",
            "pip install uharfbuzz",
        )
    {
        return;
    }
    let b = built();
    let ds = b.out.join("MastersTest.designspace");
    let xml = fs::read_to_string(&ds).expect("designspace");
    assert!(
        xml.contains(
            "  <rules processing=\"first\">\n    <rule name=\"short H\">\n      <conditionset>\n        \
             <condition name=\"Weight\" minimum=\"550\" maximum=\"700\"/>\n      </conditionset>\n      \
             <sub name=\"H\" with=\"H.alt\"/>\n    </rule>\n  </rules>\n"
        ),
        "{xml}"
    );
    let tmp = tempfile::tempdir().expect("temp dir");
    let fontmake = tmp.path().join("fontmake.ttf");
    tools::run(
        Command::new("fontmake")
            .arg("-m")
            .arg(&ds)
            .args(["-o", "variable", "--output-path"])
            .arg(&fontmake),
    );
    let fontc = tmp.path().join("fontc");
    tools::run(
        Command::new("fontc")
            .arg("--build-dir")
            .arg(&fontc)
            .arg(&ds),
    );
    let wghts = [400.0, 549.0, 550.0, 625.0, 700.0];
    let runs = shaped(
        &[
            &b.out.join("MastersTest[wght].ttf"),
            &fontmake,
            &fontc.join("font.ttf"),
        ],
        &wghts,
    );
    assert_eq!(runs[1], runs[0], "fontmake");
    assert_eq!(runs[2], runs[0], "fontc");
    assert_eq!(runs[0][2][0], "H.alt");
}

#[test]
fn the_designspace_imports_back_with_its_rules() {
    let b = built();
    let tmp = tempfile::tempdir().expect("temp dir");
    let imported = tmp.path().join("imported");
    import_ok(&[s(&b.out.join("MastersTest.designspace"))], &imported);
    let (back, _) = xglyph::source::load_family(&imported).expect("loads");
    let (want, _) = xglyph::source::load_family(&b.font).expect("loads");
    assert_eq!(back.designspace.rules, want.designspace.rules);
    assert!(!back.designspace.rules_last);
}

#[test]
fn the_variable_font_imports_back_with_its_rules() {
    let b = built();
    let tmp = tempfile::tempdir().expect("temp dir");
    let imported = tmp.path().join("imported");
    import_ok(&[s(&b.out.join("MastersTest[wght].ttf"))], &imported);
    let (back, _) = xglyph::source::load_family(&imported).expect("loads");
    let (want, _) = xglyph::source::load_family(&b.font).expect("loads");
    // The feature variation record comes back as one rule (named by its place in the
    // font), and the alternate, which has no code point, comes in with the H.
    let rules: Vec<_> = back
        .designspace
        .rules
        .iter()
        .map(|r| (&r.conditions, &r.substitutions))
        .collect();
    let expected: Vec<_> = want
        .designspace
        .rules
        .iter()
        .map(|r| (&r.conditions, &r.substitutions))
        .collect();
    assert_eq!(rules, expected);
    assert_eq!(back.designspace.rules[0].name, "rule 1");
    let alt = back
        .default
        .glyphs
        .iter()
        .find(|g| g.name == "H.alt")
        .expect("H.alt comes in");
    assert!(alt.unicodes.is_empty());
    // Rebuilt, the rule still holds from 550.
    let rebuilt = tmp.path().join("rebuilt");
    let (code, _, stderr) = xglyph(&["build", s(&imported), "-o", s(&rebuilt)]);
    assert_eq!((code, stderr.as_str()), (0, ""));
    if tools::python_imports("uharfbuzz, fontTools") {
        let runs = shaped(&[&rebuilt.join("MastersTest[wght].ttf")], &[549.0, 550.0]);
        assert_eq!(runs[0][0][0], "H");
        assert_eq!(runs[0][1][0], "H.alt");
    }
}
