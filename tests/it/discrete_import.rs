//! Designspace 5 import at one discrete location (`xglyph import X.designspace --at
//! ital=1`): the family keeps the continuous axes and the sources, instances and rules of
//! that location, as fontTools' `splitInterpolable` cuts it and fontmake builds one
//! variable font per location; the variable font built from each import matches
//! fontmake's of that location.
//!
//! The designspace is made by Python (ufoLib2): a discrete `Italic` axis (values 0 and 1,
//! mapped to design 0 and 100, with labels), `Weight` 100–900 (a map) and `Width` 75–100.
//! Upright: `Light` (the default, its location leaving out Italic), `Bold` and `Narrow`
//! (Width 75); italic (slanted by 0.2): `Light Italic` and `Bold Italic`, with no narrow
//! source, so at ital=1 the Width axis is pinned at its default. Each draws `O` (two
//! ellipses), `H` and `H.alt` (three rectangles); the rule `heavy upright H` (Italic 0,
//! Weight from 650) and `italic H` (Italic 1, Weight from user 400) swap H for H.alt.
//! `alldiscrete.designspace` has the same sources on two discrete axes only. Tests that
//! need Python, fontmake or fontTools print `skipped: …` when they are missing, unless
//! `XGLYPH_REQUIRE_TOOLS=1`.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;
use std::process::Command;

use crate::common::cli::{import, import_fails, import_ok, xglyph};
use crate::common::tools::{available, program_runs, python_imports, python_json, run, vf_compare};

/// Writes `discrete.designspace`, `alldiscrete.designspace` and their five UFOs into the
/// folder `argv[1]`.
const MAKE: &str = r#"
import sys
from pathlib import Path
import ufoLib2
from fontTools.designspaceLib import (DesignSpaceDocument, AxisDescriptor, DiscreteAxisDescriptor,
    AxisLabelDescriptor, SourceDescriptor, InstanceDescriptor, RuleDescriptor)

out = Path(sys.argv[1])
K = 0.5522847498

def ellipse(pen, cx, cy, rx, ry, clockwise, slant):
    P = lambda x, y: (x + slant * y, y)
    pts = [(cx + rx, cy), (cx, cy + ry), (cx - rx, cy), (cx, cy - ry)]
    if clockwise:
        pts = pts[::-1]
    pen.moveTo(P(*pts[0]))
    for i in range(4):
        a, b = pts[i], pts[(i + 1) % 4]
        A = (a[0] - cx, a[1] - cy)
        B = (b[0] - cx, b[1] - cy)
        pen.curveTo(P(a[0] + K * B[0], a[1] + K * B[1]), P(b[0] + K * A[0], b[1] + K * A[1]), P(*b))
    pen.closePath()

def rect(pen, x0, y0, x1, y1, slant):
    P = lambda x, y: (x + slant * y, y)
    pen.moveTo(P(x0, y0)); pen.lineTo(P(x1, y0)); pen.lineTo(P(x1, y1)); pen.lineTo(P(x0, y1))
    pen.closePath()

def master(style, stroke, narrow, slant):
    f = ufoLib2.Font()
    f.info.familyName = "Discrete Test"
    f.info.styleName = style
    f.info.unitsPerEm = 1000
    f.info.ascender = 800
    f.info.descender = -200
    f.info.xHeight = 500
    f.info.capHeight = 700
    o = f.newGlyph("O"); o.unicodes = [ord("O")]
    rx, ry = (260 + stroke / 2) * narrow, 350
    o.width = round(2 * rx + 100)
    pen = o.getPen()
    ellipse(pen, o.width / 2, 350, rx, ry, False, slant)
    ellipse(pen, o.width / 2, 350, rx - stroke, ry - stroke * 0.6, True, slant)
    for name, bar in [("H", 330), ("H.alt", 450)]:
        h = f.newGlyph(name)
        if name == "H":
            h.unicodes = [ord("H")]
        inner = 400 * narrow
        h.width = round(100 + inner + 2 * stroke)
        pen = h.getPen()
        rect(pen, 50, 0, 50 + stroke, 700, slant)
        rect(pen, 50 + stroke + inner, 0, 50 + 2 * stroke + inner, 700, slant)
        rect(pen, 50 + stroke, bar, 50 + stroke + inner, bar + stroke * 0.5, slant)
    sp = f.newGlyph("space"); sp.unicodes = [32]; sp.width = 250
    return f

# (file, style, stroke, narrow, slant, design location)
SOURCES = [
    ("Light.ufo", "Light", 40, 1.0, 0.0, {"Weight": 0, "Width": 100}),
    ("Bold.ufo", "Bold", 200, 1.0, 0.0, {"Weight": 1000, "Italic": 0}),
    ("Narrow.ufo", "Narrow", 40, 0.8, 0.0, {"Weight": 0, "Width": 75}),
    ("Italic.ufo", "Light Italic", 40, 1.0, 0.2, {"Weight": 0, "Italic": 100}),
    ("BoldItalic.ufo", "Bold Italic", 200, 1.0, 0.2, {"Weight": 1000, "Italic": 100}),
]
for filename, style, stroke, narrow, slant, _ in SOURCES:
    master(style, stroke, narrow, slant).save(out / filename, overwrite=True)

def italic_axis():
    return DiscreteAxisDescriptor(tag="ital", name="Italic", values=[0, 1], default=0,
        map=[(0, 0), (1, 100)],
        axisLabels=[AxisLabelDescriptor(name="Upright", userValue=0, elidable=True),
                    AxisLabelDescriptor(name="Italic", userValue=1)])

doc = DesignSpaceDocument()
doc.addAxis(italic_axis())
doc.addAxis(AxisDescriptor(tag="wght", name="Weight", minimum=100, default=100, maximum=900,
    map=[(100, 0), (400, 300), (900, 1000)],
    axisLabels=[AxisLabelDescriptor(name="Light", userValue=100),
                AxisLabelDescriptor(name="Bold", userValue=900)]))
doc.addAxis(AxisDescriptor(tag="wdth", name="Width", minimum=75, default=100, maximum=100))
for filename, style, _, _, _, location in SOURCES:
    doc.addSource(SourceDescriptor(filename=filename, styleName=style, name=style,
                                   familyName="Discrete Test", designLocation=location))
for style, location in [
    ("Light", {"Weight": 100}),
    ("Regular", {"Weight": 400, "Italic": 0}),
    ("Bold", {"Weight": 900}),
    ("Narrow", {"Weight": 100, "Width": 75}),
    ("Italic", {"Weight": 400, "Italic": 1}),
    ("Bold Italic", {"Weight": 900, "Italic": 1}),
    ("Narrow Italic", {"Weight": 100, "Width": 75, "Italic": 1}),
]:
    doc.addInstance(InstanceDescriptor(familyName="Discrete Test", styleName=style,
                                       userLocation=location))
# Conditions are design values: Weight 650 is user 650 (300 + 350/700 of 700 to 1000).
doc.addRule(RuleDescriptor(name="heavy upright H",
    conditionSets=[[{"name": "Italic", "minimum": 0, "maximum": 0},
                    {"name": "Weight", "minimum": 650, "maximum": 1000}]],
    subs=[("H", "H.alt")]))
doc.addRule(RuleDescriptor(name="italic H",
    conditionSets=[[{"name": "Italic", "minimum": 100, "maximum": 100},
                    {"name": "Weight", "minimum": 300}]],
    subs=[("H", "H.alt")]))
doc.write(out / "discrete.designspace")

# Every axis discrete: each location one font.
doc = DesignSpaceDocument()
doc.addAxis(italic_axis())
doc.addAxis(DiscreteAxisDescriptor(tag="wght", name="Weight", values=[100, 900], default=100))
for filename, style, _, _, _, location in SOURCES:
    if filename == "Narrow.ufo":
        continue
    loc = {"Weight": 900 if location["Weight"] else 100, "Italic": location.get("Italic", 0)}
    doc.addSource(SourceDescriptor(filename=filename, styleName=style, name=style,
                                   familyName="Discrete Test", designLocation=loc))
for style, location in [("Light", {"Weight": 100}), ("Bold Italic", {"Weight": 900, "Italic": 1})]:
    doc.addInstance(InstanceDescriptor(familyName="Discrete Test", styleName=style,
                                       userLocation=location))
doc.addRule(RuleDescriptor(name="italic H",
    conditionSets=[[{"name": "Italic", "minimum": 100, "maximum": 100}]],
    subs=[("H", "H.alt")]))
doc.write(out / "alldiscrete.designspace")
print("{}")
"#;

/// Per variable font of `argv[1:]`: its GSUB feature variations, each as the condition box
/// (normalised, by axis tag) and the substitutions it makes.
const FEATURE_VARIATIONS: &str = r#"
import sys, json
from fontTools.ttLib import TTFont
def fv(path):
    f = TTFont(path)
    axes = [a.axisTag for a in f["fvar"].axes]
    out = []
    gsub = f["GSUB"].table
    order = f.getGlyphOrder()
    for rec in (gsub.FeatureVariations.FeatureVariationRecord if gsub.FeatureVariations else []):
        box = {axes[c.AxisIndex]: [round(c.FilterRangeMinValue, 3), round(c.FilterRangeMaxValue, 3)] for c in rec.ConditionSet.ConditionTable}
        subs = {}
        for s in rec.FeatureTableSubstitution.SubstitutionRecord:
            for li in s.Feature.LookupListIndex:
                for st in gsub.LookupList.Lookup[li].SubTable:
                    subs.update(st.mapping)
        out.append([box, subs])
    return out
print(json.dumps([fv(p) for p in sys.argv[1:]]))
"#;

fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

/// Makes the designspaces into `dir`, when ufoLib2 is there (else the skip).
fn make(dir: &Path) -> bool {
    if !available(
        python_imports("ufoLib2, fontTools.designspaceLib"),
        "ufoLib2/fontTools",
        "pip install ufoLib2 fonttools",
    ) {
        return false;
    }
    let _: serde_json::Value = python_json(MAKE, &[&dir]);
    true
}

#[derive(serde::Deserialize, Debug)]
struct Compared {
    distance: f64,
    contours: [usize; 2],
    advance: [f64; 2],
}

/// The `font.toml` text from the first `[[axis]]` on (the font info before it is the
/// default source's).
fn family_part(font: &Path) -> String {
    let toml = fs::read_to_string(font.join("font.toml")).expect("font.toml");
    let at = toml.find("[[axis]]").expect("an axis");
    toml[at..].to_string()
}

/// The summary lines of an import's stdout (not the per-source reports).
fn summary(stdout: &str) -> Vec<&str> {
    stdout
        .lines()
        .filter(|l| l.starts_with("discrete location") || l.starts_with("note:"))
        .collect()
}

const UPRIGHT: &str = r#"[[axis]]
tag = "wght"
name = "Weight"
min = 100
default = 100
max = 900
map = [[100, 0], [400, 300], [900, 1000]]

[[axis]]
tag = "wdth"
name = "Width"
min = 75
default = 100
max = 100

[[master]]
name = "Bold"
folder = "bold"
location = { wght = 900, wdth = 100 }

[[master]]
name = "Narrow"
folder = "narrow"
location = { wght = 100, wdth = 75 }

[[instance]]
name = "Light"
location = { wght = 100, wdth = 100 }

[[instance]]
name = "Regular"
location = { wght = 400, wdth = 100 }

[[instance]]
name = "Bold"
location = { wght = 900, wdth = 100 }

[[instance]]
name = "Narrow"
location = { wght = 100, wdth = 75 }

[[rule]]
name = "heavy upright H"
conditions = [{ wght = [650, 900] }]
substitutions = { H = "H.alt" }
"#;

const ITALIC: &str = r#"[[axis]]
tag = "wght"
name = "Weight"
min = 100
default = 100
max = 900
map = [[100, 0], [400, 300], [900, 1000]]

[[master]]
name = "Bold Italic"
folder = "bolditalic"
location = { wght = 900 }

[[instance]]
name = "Italic"
location = { wght = 400 }

[[instance]]
name = "Bold Italic"
location = { wght = 900 }

[[rule]]
name = "italic H"
conditions = [{ wght = [400, 900] }]
substitutions = { H = "H.alt" }
"#;

#[test]
fn each_discrete_location_imports_its_sources_instances_and_rules() {
    let tmp = tempfile::tempdir().expect("temp dir");
    if !make(tmp.path()) {
        return;
    }
    let ds = tmp.path().join("discrete.designspace");
    // Without --at: the default location, and a notice naming the other.
    let upright = tmp.path().join("upright");
    let (code, stdout, stderr) = import(&[s(&ds)], &upright);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert_eq!(
        stderr,
        "note: axis `Italic` (ital) is discrete, values 0, 1: imported ital=0; `--at ital=1` \
         imports the other\n"
    );
    assert_eq!(
        summary(&stdout),
        [
            "discrete location ital=0: 3 of 5 sources, 4 named instances (of 7 in the \
             designspace)",
            "note: rules that do not apply here left out: italic H",
        ]
    );
    assert_eq!(family_part(&upright), UPRIGHT);
    assert!(fs::read_to_string(upright.join("font.toml"))
        .expect("font.toml")
        .contains("family = \"Discrete Test\"\nstyle = \"Light\"\n"));

    let italic = tmp.path().join("italic");
    let stdout = import_ok(&[s(&ds), "--at", "ital=1"], &italic);
    assert_eq!(
        summary(&stdout),
        [
            "discrete location ital=1: 2 of 5 sources, 2 named instances (of 7 in the \
             designspace)",
            "note: axis `Width` (wdth) left out: no source at ital=1 leaves its default 100",
            "note: named instances off the default of the axes left out, not kept: \
             `Narrow Italic`",
            "note: rules that do not apply here left out: heavy upright H",
        ]
    );
    assert_eq!(family_part(&italic), ITALIC);
    assert!(fs::read_to_string(italic.join("font.toml"))
        .expect("font.toml")
        .contains("family = \"Discrete Test\"\nstyle = \"Light Italic\"\n"));
    // The one master folder holds the slanted Bold Italic drawing: the left stem of H,
    // 200 wide, leans 0.2 · 700 to the right at the top.
    let h = fs::read_to_string(italic.join("bolditalic/H_.toml")).expect("H");
    assert!(
        h.starts_with(
            "name = \"H\"\nadvance = 900\n\n[[contour]]\npoints = [\n  [50, 0, 0],\n  \
             [250, 0, 0],\n  [390, 700, 0],\n  [190, 700, 0],\n]\n"
        ),
        "{h}"
    );
    let mut folders: Vec<String> = fs::read_dir(&italic)
        .expect("reads")
        .filter_map(|e| e.ok())
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    folders.sort();
    assert_eq!(folders, ["bolditalic"]);
}

#[test]
fn each_discrete_location_builds_as_fontmakes_variable_font_of_it() {
    let tmp = tempfile::tempdir().expect("temp dir");
    if !make(tmp.path())
        || !available(
            python_imports("numpy, fontTools.varLib.instancer")
                && program_runs("fontmake", &["--help"]),
            "fontmake/numpy",
            "pip install fontmake numpy",
        )
    {
        return;
    }
    let ds = tmp.path().join("discrete.designspace");
    // fontmake writes one variable font per discrete location.
    let theirs = tmp.path().join("fontmake");
    run(Command::new("fontmake")
        .arg("-m")
        .arg(&ds)
        .args(["-o", "variable", "--output-dir"])
        .arg(&theirs));
    for (ital, ours, fontmake, places) in [
        (
            "0",
            "DiscreteTest[wght,wdth].ttf",
            "discrete-VF-ital0.0.ttf",
            "wght=100;wght=250;wght=400;wght=650;wght=900;wght=100,wdth=75;wght=500,wdth=85;\
             wght=900,wdth=75",
        ),
        (
            "1",
            "DiscreteTest[wght].ttf",
            "discrete-VF-ital1.0.ttf",
            "wght=100;wght=250;wght=400;wght=650;wght=900",
        ),
    ] {
        let font = tmp.path().join(format!("font{ital}"));
        import_ok(&[s(&ds), "--at", &format!("ital={ital}")], &font);
        let out = tmp.path().join(format!("out{ital}"));
        let (code, stdout, stderr) = xglyph(&["build", s(&font), "-o", s(&out)]);
        assert_eq!((code, stderr.as_str()), (0, ""), "{stdout}");
        let ours = out.join(ours);
        let theirs = theirs.join(fontmake);
        let compared: BTreeMap<String, BTreeMap<String, Compared>> =
            vf_compare(&ours, &theirs, places, &["O", "H", "H.alt"]);
        assert_eq!(compared.len(), places.split(';').count(), "{compared:?}");
        for (place, glyphs) in &compared {
            for (name, c) in glyphs {
                let at = format!("{name} at ital={ital},{place}: {c:?}");
                // The bound of the other fontmake comparisons of foreign designspaces
                // (tests/it/sparse_import.rs); measured worst: 1.74 (O at wght 900, wdth 75,
                // where both extrapolate the corner).
                assert!(c.distance <= 2.0, "{at}");
                assert_eq!(c.advance[0], c.advance[1], "{at}");
                assert_eq!(c.contours[0], c.contours[1], "{at}");
            }
        }
        // The rule of this location, with the same box as fontmake's (normalised wght: user
        // 650 is design 650 of 0..1000; user 400 is design 300).
        type Variations = Vec<Vec<(BTreeMap<String, [f64; 2]>, BTreeMap<String, String>)>>;
        let variations: Variations = python_json(FEATURE_VARIATIONS, &[&ours, &theirs]);
        let from = if ital == "0" { 0.65 } else { 0.3 };
        let expected = vec![(
            BTreeMap::from([("wght".to_string(), [from, 1.0])]),
            BTreeMap::from([("H".to_string(), "H.alt".to_string())]),
        )];
        assert_eq!(variations, [expected.clone(), expected], "ital={ital}");
    }
}

#[test]
fn a_designspace_of_discrete_axes_only_imports_one_source_as_a_plain_font() {
    let tmp = tempfile::tempdir().expect("temp dir");
    if !make(tmp.path()) {
        return;
    }
    let ds = tmp.path().join("alldiscrete.designspace");
    let font = tmp.path().join("font");
    let stdout = import_ok(&[s(&ds), "--at", "wght=900,ital=1"], &font);
    assert_eq!(
        summary(&stdout),
        [
            "discrete location ital=1,wght=900: 1 of 4 sources, 0 named instances (of 2 in \
             the designspace)",
            "note: no continuous axis is left at ital=1,wght=900, so the font has one style: \
             its 1 named instances are not kept",
            "note: rules not kept (a font without axes has no rules), though they apply here: \
             italic H",
        ]
    );
    let toml = fs::read_to_string(font.join("font.toml")).expect("font.toml");
    assert!(
        toml.starts_with("family = \"Discrete Test\"\nstyle = \"Bold Italic\"\n"),
        "{toml}"
    );
    for table in [
        "[[axis]]",
        "[[master]]",
        "[[instance]]",
        "[[rule]]",
        "rules_processing",
    ] {
        assert!(!toml.contains(table), "{toml}");
    }
    // Bold Italic's own O: 2 · 360 + 100 wide.
    let o = fs::read_to_string(font.join("O_.toml")).expect("O");
    assert!(o.contains("advance = 820\n"), "{o}");
    let (code, stdout, stderr) = xglyph(&["build", s(&font), "-o", s(&tmp.path().join("out"))]);
    assert_eq!((code, stderr.as_str()), (0, ""), "{stdout}");
    assert!(tmp.path().join("out/DiscreteTest-BoldItalic.ttf").exists());

    // Without --at: each discrete axis at its default, a notice for each.
    let (code, stdout, stderr) = import(&[s(&ds)], &tmp.path().join("light"));
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert_eq!(
        stderr,
        "note: axis `Italic` (ital) is discrete, values 0, 1: imported ital=0; `--at ital=1` \
         imports the other\n\
         note: axis `Weight` (wght) is discrete, values 100, 900: imported wght=100; `--at \
         wght=900` imports the other\n"
    );
    let toml = fs::read_to_string(tmp.path().join("light/font.toml")).expect("font.toml");
    assert!(toml.contains("style = \"Light\"\n"), "{toml}");
}

/// A designspace with a discrete Italic axis whose UFOs need not exist: every error below
/// comes before any UFO is read. At ital=1, the only source is at wght 900, not the default.
const REFUSED: &str = r#"<?xml version='1.0' encoding='UTF-8'?>
<designspace format="5.0">
  <axes>
    <axis tag="ital" name="Italic" values="0 1 2" default="0"/>
    <axis tag="wght" name="Weight" minimum="100" maximum="900" default="100"/>
  </axes>
  <sources>
    <source filename="Light.ufo" name="Light">
      <location><dimension name="Weight" xvalue="100"/></location>
    </source>
    <source filename="Bold.ufo" name="Bold">
      <location><dimension name="Weight" xvalue="900"/></location>
    </source>
    <source filename="BoldItalic.ufo" name="Bold Italic">
      <location>
        <dimension name="Weight" xvalue="900"/><dimension name="Italic" xvalue="1"/>
      </location>
    </source>
  </sources>
</designspace>
"#;

#[test]
fn a_discrete_location_that_cannot_be_imported_is_a_clear_error_writing_nothing() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let ds = tmp.path().join("refused.designspace");
    fs::write(&ds, REFUSED).expect("writes");
    let out = tmp.path().join("font");
    let d = ds.display();
    for (at, message) in [
        (
            "slnt=1",
            "--at slnt=1: `slnt` is not an axis of the designspace; the discrete axes are \
             `ital` (Italic: 0, 1, 2)",
        ),
        (
            "wght=400",
            "--at wght=400: axis `Weight` (wght) is continuous; --at on import picks a \
             discrete location, and continuous axes come whole; the discrete axes are `ital` \
             (Italic: 0, 1, 2)",
        ),
        (
            "ital=0.5",
            "--at ital=0.5: ital = 0.5 is not a value of the discrete axis `Italic`; its \
             values are 0, 1, 2",
        ),
        (
            "ital=1",
            "no source sits at the default of the discrete location ital=1 (wght = 100)",
        ),
        ("ital=2", "no source sits at the discrete location ital=2"),
        (
            "ital",
            "--at ital: expected TAG=VALUE (several separated by commas), such as wght=650; \
             found `ital`",
        ),
    ] {
        let err = import_fails(&[s(&ds), "--at", at], &out);
        assert_eq!(err, format!("error: {d}: {message}\n"), "--at {at}");
    }
    // A designspace without discrete axes.
    let plain = tmp.path().join("plain.designspace");
    fs::write(
        &plain,
        REFUSED.replace(
            r#"<axis tag="ital" name="Italic" values="0 1 2" default="0"/>"#,
            "",
        ),
    )
    .expect("writes");
    let err = import_fails(&[s(&plain), "--at", "ital=1"], &out);
    assert_eq!(
        err,
        format!(
            "error: {}: --at ital=1: `ital` is not an axis of the designspace; the designspace \
             has no discrete axis; leave out --at\n",
            plain.display()
        )
    );
}

#[test]
fn at_is_refused_for_an_input_that_is_not_a_designspace() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let out = tmp.path().join("font");
    let ufo = tmp.path().join("Light.ufo");
    let ttf = tmp.path().join("Light.ttf");
    for (input, what) in [(&ufo, "a UFO"), (&ttf, "a font")] {
        let err = import_fails(&[s(input), "--at", "ital=1"], &out);
        assert_eq!(
            err,
            format!(
                "error: {}: --at applies to a designspace (it picks one location of its \
                 discrete axes), not to {what}\n",
                input.display()
            )
        );
    }
}
