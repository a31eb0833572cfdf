//! Designspace import of sources on a UFO layer (fontmake's sparse "support" masters): the
//! source becomes a `sparse = true` master whose folder holds only the glyphs its layer
//! draws, and the variable font built from the import matches fontmake's at the sparse
//! source's place, for the glyph the layer draws and for one it leaves to the full masters.
//!
//! The designspace is made by Python (ufoLib2): `Light` (wght 100, default) and `Bold`
//! (wght 900) draw `O` (two ellipses, the stroke 40 and 200 units) and `H` (three
//! rectangles, stems 40 and 200); the layer `support` of the Light UFO, a source at wght
//! 600, draws `O` with a stroke of 100 (the full masters' blend there: 140) and holds `H`
//! empty, which fontTools takes as not drawn; `O.alt`, a composite of `O` in the full
//! masters only, follows the layer's `O` there (the build blends a composite's outline
//! with its bases' masters too). Tests that need Python, fontmake or fontTools
//! print `skipped: …` when they are missing, unless `XGLYPH_REQUIRE_TOOLS=1`.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;
use std::process::Command;

use crate::common::cli::{import_fails, import_ok, xglyph};
use crate::common::tools::{available, program_runs, python_imports, python_json, run, vf_compare};

/// Writes `sparse.designspace` with its two UFOs into the folder `argv[1]`; with `argv[2]`
/// = "extra", the layer also draws a glyph `X` that the default source lacks.
const MAKE: &str = r#"
import sys, math
from pathlib import Path
import ufoLib2
from fontTools.designspaceLib import DesignSpaceDocument, AxisDescriptor, SourceDescriptor

out = Path(sys.argv[1])
extra = len(sys.argv) > 2 and sys.argv[2] == "extra"
missing = len(sys.argv) > 2 and sys.argv[2] == "missing"
K = 0.5522847498

def ellipse(pen, cx, cy, rx, ry, clockwise):
    pts = [(cx + rx, cy), (cx, cy + ry), (cx - rx, cy), (cx, cy - ry)]
    if clockwise:
        pts = pts[::-1]
    pen.moveTo(pts[0])
    for i in range(4):
        a, b = pts[i], pts[(i + 1) % 4]
        # A quarter arc: the handles along the tangents, K times the other radius.
        A = (a[0] - cx, a[1] - cy)
        B = (b[0] - cx, b[1] - cy)
        c1 = (a[0] + K * B[0], a[1] + K * B[1])
        c2 = (b[0] + K * A[0], b[1] + K * A[1])
        pen.curveTo(c1, c2, b)
    pen.closePath()

def draw_o(glyph, stroke):
    rx, ry = 260 + stroke / 2, 350
    glyph.width = 2 * rx + 100
    pen = glyph.getPen()
    ellipse(pen, glyph.width / 2, 350, rx, ry, False)
    ellipse(pen, glyph.width / 2, 350, rx - stroke, ry - stroke * 0.6, True)

def rect(pen, x0, y0, x1, y1):
    pen.moveTo((x0, y0)); pen.lineTo((x1, y0)); pen.lineTo((x1, y1)); pen.lineTo((x0, y1))
    pen.closePath()

def draw_h(glyph, stem):
    glyph.width = 500 + 2 * stem
    pen = glyph.getPen()
    rect(pen, 50, 0, 50 + stem, 700)
    rect(pen, 450 + stem, 0, 450 + 2 * stem, 700)
    rect(pen, 50 + stem, 330, 450 + stem, 330 + stem * 0.5)

def master(stroke, style, layer_stroke=None):
    f = ufoLib2.Font()
    f.info.familyName = "Sparse Test"
    f.info.styleName = style
    f.info.unitsPerEm = 1000
    f.info.ascender = 800
    f.info.descender = -200
    f.info.xHeight = 500
    f.info.capHeight = 700
    o = f.newGlyph("O"); o.unicodes = [ord("O")]; draw_o(o, stroke)
    h = f.newGlyph("H"); h.unicodes = [ord("H")]; draw_h(h, stroke)
    sp = f.newGlyph("space"); sp.unicodes = [32]; sp.width = 250
    alt = f.newGlyph("O.alt"); alt.width = o.width + 20
    alt.getPointPen().addComponent("O", (1, 0, 0, 1, 10, 0))
    if layer_stroke is not None:
        layer = f.newLayer("support")
        draw_o(layer.newGlyph("O"), layer_stroke)
        layer.newGlyph("H").width = 600
        if extra:
            x = layer.newGlyph("X"); x.width = 500
            rect(x.getPen(), 0, 0, 100, 100)
    return f

if missing:
    # Bold at wght 700 lacks H and kerns O O; the axis runs on to 900 without a source.
    light, bold = master(40, "Light"), master(200, "Bold")
    del bold["H"]
    light.lib["public.glyphOrder"] = ["O", "H", "space", "O.alt"]
    bold.lib["public.glyphOrder"] = ["O", "space", "O.alt"]
    light.kerning[("O", "O")] = -10
    bold.kerning[("O", "O")] = -40
    light.save(out / "Light.ufo", overwrite=True)
    bold.save(out / "Bold.ufo", overwrite=True)
    sources = [("Light.ufo", "Light", 100, None), ("Bold.ufo", "Bold", 700, None)]
else:
    master(40, "Light", 100).save(out / "Light.ufo", overwrite=True)
    master(200, "Bold").save(out / "Bold.ufo", overwrite=True)
    sources = [
        ("Light.ufo", "Light", 100, None),
        ("Bold.ufo", "Bold", 900, None),
        ("Light.ufo", "Support", 600, "support"),
    ]
doc = DesignSpaceDocument()
doc.addAxis(AxisDescriptor(tag="wght", name="Weight", minimum=100, default=100, maximum=900))
for filename, name, wght, layer in sources:
    doc.addSource(SourceDescriptor(filename=filename, styleName=name, name=name,
                                   location={"Weight": wght}, layerName=layer))
doc.write(out / "sparse.designspace")
print("{}")
"#;

fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

/// Whether Python with ufoLib2 and fontTools' instancer, and fontmake, are there.
fn tools() -> bool {
    available(
        python_imports("ufoLib2, numpy, fontTools.designspaceLib, fontTools.varLib.instancer")
            && program_runs("fontmake", &["--help"]),
        "fontmake/fontTools/ufoLib2/numpy",
        "pip install fontmake ufoLib2 numpy",
    )
}

/// The files of `dir`, sorted.
fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .expect("reads the folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[derive(serde::Deserialize, Debug)]
struct Compared {
    distance: f64,
    contours: [usize; 2],
    advance: [f64; 2],
    width: [f64; 2],
}

#[test]
fn a_layer_source_imports_as_a_sparse_master_and_builds_as_fontmake_does() {
    if !tools() {
        return;
    }
    let tmp = tempfile::tempdir().expect("temp dir");
    let src = tmp.path().join("src");
    fs::create_dir(&src).expect("creates");
    let _: serde_json::Value = python_json(MAKE, &[&src]);
    let ds = src.join("sparse.designspace");

    let font = tmp.path().join("font");
    let report = import_ok(&[s(&ds)], &font);
    assert!(
        report.contains("H left out: empty in the layer, drawn in the default source"),
        "{report}"
    );
    let toml = fs::read_to_string(font.join("font.toml")).expect("font.toml");
    assert_eq!(toml.matches("[[master]]").count(), 2, "{toml}");
    assert!(
        toml.contains(
            "[[master]]\nname = \"Bold\"\nfolder = \"bold\"\nlocation = { wght = 900 }\n\n"
        ),
        "{toml}"
    );
    assert!(
        toml.contains(
            "[[master]]\nname = \"Support\"\nfolder = \"support\"\nlocation = { wght = 600 }\n\
             sparse = true\n"
        ),
        "{toml}"
    );
    assert_eq!(toml.matches("sparse = true").count(), 1, "{toml}");
    // The sparse folder holds only what its layer draws: no H (empty there), no space,
    // no kerning.
    assert_eq!(files(&font.join("support")), ["O_.toml"]);
    assert_eq!(
        files(&font.join("bold")),
        ["H_.toml", "O_.alt.toml", "O_.toml", "space.toml"]
    );

    let (code, stdout, stderr) = xglyph(&["check", s(&font)]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let out = tmp.path().join("out");
    let (code, stdout, stderr) = xglyph(&["build", s(&font), "-o", s(&out)]);
    assert_eq!((code, stderr.as_str()), (0, ""), "{stdout}");
    let ours = out.join("SparseTest[wght].ttf");
    assert!(ours.exists(), "{:?}", files(&out));

    let theirs = tmp.path().join("fontmake.ttf");
    run(Command::new("fontmake")
        .arg("-m")
        .arg(&ds)
        .args(["-o", "variable", "--output-path"])
        .arg(&theirs));
    let compared: BTreeMap<String, BTreeMap<String, Compared>> = vf_compare(
        &ours,
        &theirs,
        "wght=600;wght=350;wght=750",
        &["O", "H", "O.alt"],
    );
    // At the sparse source: O as the layer draws it (stroke 100: the width 2 · 310 = 620,
    // where the full masters' blend would give 2 · 330 = 660), H as the full masters
    // blend it (the layer's empty H is not drawn).
    let support = &compared["wght=600"];
    let (o, h) = (&support["O"], &support["H"]);
    assert_eq!(o.contours, [2, 2], "{support:?}");
    assert!(o.distance <= 2.0, "O at wght 600: {support:?}");
    assert!((o.width[0] - 620.0).abs() <= 2.0, "{support:?}");
    assert_eq!(o.advance, [720.0, 720.0], "{support:?}");
    // The composite of O follows the layer's O there, as fontmake's composite does, though
    // the sparse folder does not hold it: its offset and advance are the full masters'
    // blend.
    let alt = &support["O.alt"];
    assert!(alt.distance <= 2.0, "O.alt at wght 600: {support:?}");
    assert!((alt.width[0] - 620.0).abs() <= 2.0, "{support:?}");
    assert_eq!(alt.advance, [780.0, 780.0], "{support:?}");
    assert_eq!(h.contours, [3, 3], "{support:?}");
    assert!(h.distance <= 1.0, "H at wght 600: {support:?}");
    // Stems of 40 + 160 · 500/800 = 140 at wght 600: the advance 500 + 280.
    assert_eq!(h.advance, [780.0, 780.0], "{support:?}");
    // Between the default and the sparse source, and between it and Bold.
    for wght in ["350", "750"] {
        let between = &compared[&format!("wght={wght}")];
        for (name, c) in between {
            assert!(c.distance <= 2.0, "{name} at wght {wght}: {between:?}");
            assert_eq!(c.advance[0], c.advance[1], "{name} at wght {wght}");
        }
    }
}

#[test]
fn a_glyph_only_the_layer_draws_is_refused_with_its_name_and_source() {
    if !available(
        python_imports("ufoLib2, fontTools.designspaceLib"),
        "ufoLib2/fontTools",
        "pip install ufoLib2 fonttools",
    ) {
        return;
    }
    let tmp = tempfile::tempdir().expect("temp dir");
    let _: serde_json::Value = python_json(MAKE, &[&tmp.path(), &"extra"]);
    let ds = tmp.path().join("sparse.designspace");
    let err = import_fails(&[s(&ds)], &tmp.path().join("font"));
    assert_eq!(
        err,
        format!(
            "error: {}: source `Support` draws the glyph `X` in its layer, which the default \
             source lacks\n",
            ds.display()
        )
    );
}

/// A source UFO that lacks a glyph (Bold, at wght 700, has no `H`) comes in as a sparse
/// master that keeps its kerning, and an axis end without a source (900) stays as it is:
/// the rebuild matches fontmake's and fontc's variable fonts of the original designspace,
/// where `H` does not vary and everything returns to Light at wght 900.
#[test]
fn a_source_lacking_a_glyph_and_an_open_axis_end_import_as_fontmake_builds_them() {
    if !tools() || !crate::common::tools::designspace_compilers_available() {
        return;
    }
    let tmp = tempfile::tempdir().expect("temp dir");
    let src = tmp.path().join("src");
    fs::create_dir(&src).expect("creates");
    let _: serde_json::Value = python_json(MAKE, &[&src, &"missing"]);
    let ds = src.join("sparse.designspace");

    let font = tmp.path().join("font");
    import_ok(&[s(&ds)], &font);
    let toml = fs::read_to_string(font.join("font.toml")).expect("font.toml");
    assert!(
        toml.contains(
            "[[master]]\nname = \"Bold\"\nfolder = \"bold\"\nlocation = { wght = 700 }\n\
             sparse = true\n"
        ),
        "{toml}"
    );
    assert_eq!(
        files(&font.join("bold")),
        ["O_.alt.toml", "O_.toml", "kerning.toml", "space.toml"]
    );
    let (code, stdout, stderr) = xglyph(&["check", s(&font)]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert_eq!(
        stdout
            .lines()
            .filter(|l| l.contains(": warning: "))
            .collect::<Vec<_>>(),
        [format!(
            "{}:15:7: warning: axis `wght` ends at max = 900 but no master is there: past \
             master `Bold` (wght = 700) the design blends back to the default, which it \
             reaches at 900, as fontmake and fontc build it; add a `[[master]]` with location \
             {{ wght = 900 }}, or set max to 700",
            font.join("font.toml").display()
        )],
        "{stdout}"
    );
    let out = tmp.path().join("out");
    let (code, stdout, stderr) = xglyph(&["build", s(&font), "-o", s(&out)]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let report = crate::common::tools::check_designspace_compilers(
        &ds,
        &out.join("SparseTest[wght].ttf"),
        tmp.path(),
        0.25,
        &["300", "600", "700", "800", "900"],
    );
    println!("{report}");
    assert!(
        report.contains("ok    Bold.ufo: 3 glyphs (O, O.alt, space), each with"),
        "{report}"
    );
    // Both compilers at 5 places, and the kerning at Bold its own.
    assert_eq!(
        crate::common::tools::outlines_compared(&report),
        10,
        "{report}"
    );
    for compiler in ["fontmake.ttf", "font.ttf"] {
        assert!(
            report.contains(&format!("ok    {compiler}: kerning at wght 700 (1 pairs)")),
            "{report}"
        );
    }
    assert!(report.contains("designspace_check: all passed"), "{report}");
}
