//! The variable TTF (`otf::variable_ttf`) checked from outside, on two families built by
//! hand and the bundled typeface:
//!
//! - the bundled typeface (glyphs/) as the default master with a second master compatible
//!   by construction (every point through one affine map: wider, slanted, a little lower;
//!   advances × 1.15, kerning × 1.5 plus a pair only the Bold kerns);
//! - a tiny `o`/`l` family with four masters on one axis (Light below the default, an
//!   intermediate SemiBold and Bold above), so negative and intermediate regions are used;
//! - and, for OTS and IUP, the bundled typeface with its real Bold master (glyphs/bold/).
//!
//! Checked: OTS accepts the font; IUP (the deltas `gvar` omits) changes no instance;
//! fontTools' `varLib.instancer` at 5 positions per family gives outlines within the
//! quadratic accuracy plus grid rounding of the blended cubic outline, and the advances the rounded masters blend to; skrifa reads outlines (gvar)
//! and advances (HVAR) at several positions; Chromium lays a line out with
//! `font-variation-settings` at each named instance to the blended width; the GPOS pair
//! values at each master are that master's kerning.
//!
//! Tests that need a tool print `skipped: …` and pass when it is missing, unless
//! `XGLYPH_REQUIRE_TOOLS=1` (CI), which makes them fail: `ots-sanitize` (pip
//! `opentype-sanitizer`), `python3` with fontTools, `/usr/bin/chromium`.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;
use std::sync::OnceLock;

use kurbo::{Affine, BezPath, PathEl, Point};
use serde_json::{json, Value};
use skrifa::instance::{LocationRef, Size};
use skrifa::{FontRef, MetadataProvider};
use ttf_parser::{Face, GlyphId};
use xglyph::designspace::{Axis, Designspace, Location, NamedInstance};
use xglyph::family::{MasterGlyph, OutlinedFamily, OutlinedMaster};
use xglyph::import::font::glyph_outline;
use xglyph::model::{FontInfo, GlyphModels, KernPair};
use xglyph::otf::{glyph_order, variable_ttf};
use xglyph::outline::{OutlinedFont, OutlinedGlyph};

use crate::common::fonts::skrifa_outline;
use crate::common::paths;
use crate::common::tools;
use crate::studio_browser::Browser;

/// Largest distance grid rounding can move a point of a Bézier curve (√2/2 units).
const GRID: f64 = std::f64::consts::FRAC_1_SQRT_2;

fn wght(min: f64, default: f64, max: f64) -> Axis {
    Axis::linear("wght", "Weight", min, default, max)
}

fn at(w: f64) -> Location {
    Location([("wght".to_string(), w)].into_iter().collect())
}

fn instance(name: &str, w: f64) -> NamedInstance {
    NamedInstance {
        name: name.into(),
        location: at(w),
    }
}

/// One master to add: name, `wght`, glyphs (in the default's order) and kerning.
type MasterSpec = (&'static str, f64, Vec<MasterGlyph>, Vec<KernPair>);

fn family(
    designspace: Designspace,
    default: OutlinedFont,
    masters: Vec<MasterSpec>,
) -> OutlinedFamily {
    let locations: Vec<Location> = masters.iter().map(|m| at(m.1)).collect();
    let model = designspace.model(&locations).expect("valid masters");
    let models = GlyphModels::full(masters.len(), &model, default.glyphs.len());
    OutlinedFamily {
        designspace,
        default,
        masters: masters
            .into_iter()
            .map(|(name, w, glyphs, kerning)| OutlinedMaster {
                name: name.into(),
                location: at(w),
                glyphs,
                kerning,
            })
            .collect(),
        model,
        models,
    }
}

/// The bundled typeface and a Bold made from it (see the module documentation).
fn bundled() -> &'static OutlinedFamily {
    static FAMILY: OnceLock<OutlinedFamily> = OnceLock::new();
    FAMILY.get_or_init(|| {
        let font = xglyph::pipeline::load(Path::new("glyphs"), None)
            .expect("glyphs/ loads")
            .font;
        let map = Affine::new([1.15, 0.0, 0.05, 0.98, 0.0, 4.0]);
        let glyphs = font
            .glyphs
            .iter()
            .map(|g| MasterGlyph {
                advance: g.advance * 1.15,
                path: map * g.path.clone(),
                drawn: true,
            })
            .collect();
        let mut kerning: Vec<KernPair> = font
            .kerning
            .iter()
            .map(|k| KernPair {
                value: k.value * 1.5,
                ..k.clone()
            })
            .collect();
        kerning.push(KernPair {
            left: "H".into(),
            right: "H".into(),
            value: -40.0,
        });
        let designspace = Designspace {
            axes: vec![wght(400.0, 400.0, 700.0)],
            instances: vec![
                instance("Regular", 400.0),
                instance("Medium", 500.0),
                instance("SemiBold", 600.0),
                instance("Bold", 700.0),
            ],
            rules: Vec::new(),
            rules_last: false,
        };
        family(designspace, font, vec![("Bold", 700.0, glyphs, kerning)])
    })
}

/// The bundled typeface with its own masters (glyphs/ and glyphs/bold/), as `build` fits it.
fn typeface() -> &'static OutlinedFamily {
    static FAMILY: OnceLock<OutlinedFamily> = OnceLock::new();
    FAMILY.get_or_init(|| {
        let loaded = xglyph::pipeline::load(Path::new("glyphs"), None).expect("glyphs/ loads");
        xglyph::family::outline_family(&loaded.family, loaded.font.tolerance)
            .expect("glyphs/ masters are compatible")
            .0
    })
}

/// A ring (two cubic contours, the inner one clockwise) of half-widths `rx`, `ry` and
/// stroke `t`, left edge at `x0`.
fn ring(x0: f64, rx: f64, ry: f64, t: f64) -> BezPath {
    let ellipse = |cx: f64, cy: f64, rx: f64, ry: f64, ccw: bool| {
        let k = 0.5523;
        let mut p = BezPath::new();
        let s = if ccw { 1.0 } else { -1.0 };
        p.move_to((cx + rx, cy));
        p.curve_to(
            (cx + rx, cy + s * k * ry),
            (cx + k * rx, cy + s * ry),
            (cx, cy + s * ry),
        );
        p.curve_to(
            (cx - k * rx, cy + s * ry),
            (cx - rx, cy + s * k * ry),
            (cx - rx, cy),
        );
        p.curve_to(
            (cx - rx, cy - s * k * ry),
            (cx - k * rx, cy - s * ry),
            (cx, cy - s * ry),
        );
        p.curve_to(
            (cx + k * rx, cy - s * ry),
            (cx + rx, cy - s * k * ry),
            (cx + rx, cy),
        );
        p.close_path();
        p
    };
    let (cx, cy) = (x0 + rx, ry);
    let mut p = ellipse(cx, cy, rx, ry, true);
    p.extend(ellipse(cx, cy, rx - t, ry - t * 0.8, false));
    p
}

/// A stem from `x0`, `w` wide, `h` tall (lines only).
fn stem(x0: f64, w: f64, h: f64) -> BezPath {
    let mut p = BezPath::new();
    p.move_to((x0, 0.0));
    p.line_to((x0 + w, 0.0));
    p.line_to((x0 + w, h));
    p.line_to((x0, h));
    p.close_path();
    p
}

fn outlined(name: &str, c: char, advance: f64, path: BezPath) -> OutlinedGlyph {
    OutlinedGlyph {
        name: name.into(),
        unicodes: vec![c],
        advance,
        components: vec![],
        anchors: Vec::new(),
        placed_anchors: Vec::new(),
        outline_mark: false,
        contours: vec![],
        path,
        max_error: 0.0,
        segments: 0,
    }
}

fn kern(left: &str, right: &str, value: f64) -> KernPair {
    KernPair {
        left: left.into(),
        right: right.into(),
        value,
    }
}

/// `o` and `l` with Light (100), Regular (400, default), SemiBold (600), Bold (900).
fn tiny() -> OutlinedFamily {
    let master = |rx: f64, t: f64, stem_w: f64| {
        vec![
            MasterGlyph {
                advance: 2.0 * rx + 80.3,
                path: ring(40.0, rx, 260.0, t),
                drawn: true,
            },
            MasterGlyph {
                advance: stem_w + 120.6,
                path: stem(60.0, stem_w, 720.0),
                drawn: true,
            },
        ]
    };
    let default = OutlinedFont {
        info: FontInfo::with_em("Tiny Var", 1000),
        features: None,
        // `l l` is the same in every master: its deltas are all 0.
        kerning: vec![
            kern("l", "o", -12.0),
            kern("o", "l", -6.0),
            kern("l", "l", -5.0),
        ],
        tolerance: 0.5,
        glyphs: vec![
            outlined("o", 'o', 2.0 * 230.0 + 80.3, ring(40.0, 230.0, 260.0, 70.0)),
            outlined("l", 'l', 80.0 + 120.6, stem(60.0, 80.0, 720.0)),
        ],
    };
    let designspace = Designspace {
        axes: vec![wght(100.0, 400.0, 900.0)],
        instances: vec![
            instance("Light", 100.0),
            instance("Regular", 400.0),
            instance("SemiBold", 600.0),
            instance("Bold", 900.0),
        ],
        rules: Vec::new(),
        rules_last: false,
    };
    family(
        designspace,
        default,
        vec![
            (
                "Light",
                100.0,
                master(215.0, 22.0, 26.0),
                vec![kern("l", "o", -4.0), kern("l", "l", -5.0)],
            ),
            (
                "SemiBold",
                600.0,
                master(255.0, 120.0, 130.0),
                vec![
                    kern("l", "o", -25.0),
                    kern("o", "l", -10.0),
                    kern("l", "l", -5.0),
                ],
            ),
            (
                "Bold",
                900.0,
                master(290.0, 170.0, 190.0),
                vec![
                    kern("l", "o", -40.0),
                    kern("o", "l", -18.0),
                    kern("l", "l", -5.0),
                ],
            ),
        ],
    )
}

/// [`tiny`] with a non-linear axis map, so `avar` is not the identity: between Light and
/// the default the design values run slow, then fast up to SemiBold, slow again to Bold;
/// named instances between the masters (Book, Medium, ExtraBold) sit where the map bends.
fn tiny_mapped() -> OutlinedFamily {
    let mut fam = tiny();
    let ds = &mut fam.designspace;
    ds.axes[0].map = vec![
        (100.0, 0.0),
        (300.0, 15.0),
        (400.0, 40.0),
        (500.0, 90.0),
        (600.0, 100.0),
        (800.0, 125.0),
        (900.0, 130.0),
    ];
    ds.instances.insert(1, instance("Book", 300.0));
    ds.instances.insert(3, instance("Medium", 500.0));
    ds.instances.push(instance("ExtraBold", 760.0));
    fam.default.info.family = "Tiny Mapped".into();
    let locations: Vec<Location> = fam.masters.iter().map(|m| m.location.clone()).collect();
    fam.model = fam.designspace.model(&locations).expect("valid masters");
    fam
}

#[test]
fn the_axis_map_moves_the_blend() {
    // Without this the mapped family's checks could pass with an identity `avar`.
    let (mapped, linear) = (tiny_mapped(), tiny());
    for (w, moved) in [(300.0, true), (500.0, true), (760.0, true), (600.0, false)] {
        let a = &blend(&mapped, &at(w))[0].path;
        let b = &blend(&linear, &at(w))[0].path;
        let d = paths::two_sided(a, b, 48);
        eprintln!("`o` at wght {w}: mapped and linear blends {d:.2} units apart");
        assert_eq!(d > 5.0, moved, "wght {w}: {d}");
    }
}

/// One glyph of the family blended at `location`: the exact cubic outline and the advance
/// the font holds there (each master's advance rounded, then blended).
struct Blended {
    path: BezPath,
    advance: f64,
    exact_advance: f64,
}

fn blend(family: &OutlinedFamily, location: &Location) -> Vec<Blended> {
    let w = family.weights(location);
    family
        .default
        .glyphs
        .iter()
        .enumerate()
        .map(|(i, g)| {
            let paths: Vec<&BezPath> = std::iter::once(&g.path)
                .chain(family.masters.iter().map(|m| &m.glyphs[i].path))
                .collect();
            let advances: Vec<f64> = std::iter::once(g.advance)
                .chain(family.masters.iter().map(|m| m.glyphs[i].advance))
                .collect();
            let mix = |pts: Vec<Point>| {
                let (x, y) = pts
                    .iter()
                    .zip(&w)
                    .fold((0.0, 0.0), |(x, y), (p, w)| (x + w * p.x, y + w * p.y));
                Point::new(x, y)
            };
            let mut path = BezPath::new();
            for (k, el) in g.path.elements().iter().enumerate() {
                let els: Vec<PathEl> = paths.iter().map(|p| p.elements()[k]).collect();
                let pts = |j: usize| {
                    mix(els
                        .iter()
                        .map(|e| match *e {
                            PathEl::MoveTo(p) | PathEl::LineTo(p) => p,
                            PathEl::QuadTo(a, b) => [a, b][j],
                            PathEl::CurveTo(a, b, c) => [a, b, c][j],
                            PathEl::ClosePath => Point::ZERO,
                        })
                        .collect())
                };
                path.push(match el {
                    PathEl::MoveTo(_) => PathEl::MoveTo(pts(0)),
                    PathEl::LineTo(_) => PathEl::LineTo(pts(0)),
                    PathEl::QuadTo(..) => PathEl::QuadTo(pts(0), pts(1)),
                    PathEl::CurveTo(..) => PathEl::CurveTo(pts(0), pts(1), pts(2)),
                    PathEl::ClosePath => PathEl::ClosePath,
                });
            }
            Blended {
                path,
                advance: advances.iter().zip(&w).map(|(a, w)| a.round() * w).sum(),
                exact_advance: advances.iter().zip(&w).map(|(a, w)| a * w).sum(),
            }
        })
        .collect()
}

/// The kerning the font holds at `location`: each master's pairs rounded, then blended.
fn blended_kerning(
    family: &OutlinedFamily,
    location: &Location,
) -> BTreeMap<(String, String), f64> {
    let w = family.weights(location);
    let mut out = BTreeMap::new();
    let kernings =
        std::iter::once(&family.default.kerning).chain(family.masters.iter().map(|m| &m.kerning));
    for (kerning, w) in kernings.zip(&w) {
        for k in kerning {
            *out.entry((k.left.clone(), k.right.clone())).or_insert(0.0) += k.value.round() * w;
        }
    }
    out
}

/// Whether an external tool is there: `None` runs the tests, `Some(notice)` skips them
/// (printed), and `XGLYPH_REQUIRE_TOOLS=1` turns a missing tool into a failure.
fn missing(program: &str, args: &[&str], install: &str) -> bool {
    let ok = Command::new(program)
        .args(args)
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        if std::env::var("XGLYPH_REQUIRE_TOOLS").as_deref() == Ok("1") {
            panic!("XGLYPH_REQUIRE_TOOLS=1 but {program} is missing; {install}");
        }
        println!(
            "skipped: {program} not usable; {install}; XGLYPH_REQUIRE_TOOLS=1 makes this fail"
        );
    }
    !ok
}

fn no_fonttools() -> bool {
    missing(
        "python3",
        &["-c", "import fontTools.varLib.instancer"],
        "pip install fonttools",
    )
}

fn write_temp(bytes: &[u8]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("var.ttf"), bytes).unwrap();
    dir
}

#[test]
fn ots_accepts_the_variable_fonts() {
    // `ots-sanitize` on PATH, or the pip package's copy (as .ci/check-fonts finds it).
    let ots: Vec<&str> = if Command::new("ots-sanitize")
        .arg("--version")
        .output()
        .is_ok()
    {
        vec!["ots-sanitize"]
    } else if missing(
        "python3",
        &["-c", "import ots"],
        "pip install opentype-sanitizer",
    ) {
        return;
    } else {
        vec!["python3", "-m", "ots"]
    };
    for (name, fam) in [
        ("glyphs/", typeface().clone()),
        ("bundled", bundled().clone()),
        ("tiny", tiny()),
        ("tiny mapped", tiny_mapped()),
    ] {
        let bytes = variable_ttf(&fam).unwrap();
        let dir = write_temp(&bytes);
        let out = Command::new(ots[0])
            .args(&ots[1..])
            .arg(dir.path().join("var.ttf"))
            .arg(dir.path().join("clean.ttf"))
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(out.status.success(), "{name}: OTS rejects it: {text}");
        // OTS drops tables it cannot validate and warns; none may be dropped.
        assert!(!text.contains("Dropping"), "{name}: {text}");
        let clean = std::fs::read(dir.path().join("clean.ttf")).unwrap();
        let face = Face::parse(&clean, 0).unwrap();
        let tables = face.raw_face();
        for tag in [
            b"fvar", b"avar", b"gvar", b"HVAR", b"STAT", b"GDEF", b"GPOS",
        ] {
            assert!(
                tables.table(ttf_parser::Tag::from_bytes(tag)).is_some(),
                "{name}: OTS output lacks {}",
                String::from_utf8_lossy(tag)
            );
        }
        eprintln!("{name}: OTS accepts {} bytes, text {text:?}", bytes.len());
    }
}

/// Pair values by (first, second) PostScript glyph name.
type Pairs = BTreeMap<(String, String), i64>;

/// Instantiates the variable font at each location with fontTools; returns per location
/// the static font's bytes and its GPOS pair values.
fn instances(bytes: &[u8], wghts: &[f64]) -> Vec<(Vec<u8>, Pairs)> {
    let dir = write_temp(bytes);
    const SCRIPT: &str = r#"
import json, sys
from fontTools.ttLib import TTFont
from fontTools.varLib import instancer
src, out, locs = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
kerning = []
for i, w in enumerate(locs):
    font = instancer.instantiateVariableFont(TTFont(src), {"wght": w})
    font.save(f"{out}/{i}.ttf")
    pairs = {}
    if "GPOS" in font:
        for lookup in font["GPOS"].table.LookupList.Lookup:
            for st in lookup.SubTable:
                if lookup.LookupType != 2 or st.Format != 1:
                    continue
                for first, ps in zip(st.Coverage.glyphs, st.PairSet):
                    for r in ps.PairValueRecord:
                        pairs[first + " " + r.SecondGlyph] = r.Value1.XAdvance
    kerning.append(pairs)
print(json.dumps(kerning))
"#;
    let kerning: Vec<BTreeMap<String, i64>> = tools::python_json(
        SCRIPT,
        &[
            &dir.path().join("var.ttf"),
            &dir.path(),
            &json!(wghts).to_string(),
        ],
    );
    kerning
        .into_iter()
        .enumerate()
        .map(|(i, pairs)| {
            let bytes = std::fs::read(dir.path().join(format!("{i}.ttf"))).unwrap();
            let pairs = pairs
                .into_iter()
                .map(|(k, v)| {
                    let (l, r) = k.split_once(' ').unwrap();
                    ((l.to_owned(), r.to_owned()), v)
                })
                .collect();
            (bytes, pairs)
        })
        .collect()
}

/// fontTools instances against the blended masters; the worst outline distance.
fn check_instances(family: &OutlinedFamily, wghts: &[f64]) -> f64 {
    let bytes = variable_ttf(family).unwrap();
    let order = glyph_order(&family.default).unwrap();
    let bound = family.default.tolerance + 2.0 * GRID;
    let mut worst: f64 = 0.0;
    for (&w, (static_bytes, _)) in wghts.iter().zip(instances(&bytes, wghts)) {
        let face = Face::parse(&static_bytes, 0).unwrap();
        assert!(
            face.tables().fvar.is_none(),
            "instance at {w} still variable"
        );
        let expected = blend(family, &at(w));
        for (gid, g) in order.iter().enumerate() {
            let Some(i) = family
                .default
                .glyphs
                .iter()
                .position(|o| o.name == g.model_name)
            else {
                continue; // the synthesised .notdef
            };
            let gid = GlyphId(gid as u16);
            let advance = face.glyph_hor_advance(gid).unwrap();
            assert_eq!(
                f64::from(advance),
                expected[i].advance.round(),
                "{} at wght {w}: advance",
                g.model_name
            );
            assert!((expected[i].advance.round() - expected[i].exact_advance).abs() <= 1.0);
            let built = glyph_outline(&face, gid).unwrap_or_default();
            let d = paths::two_sided(&built, &expected[i].path, 48);
            assert!(d <= bound, "{} at wght {w}: {d} > {bound}", g.model_name);
            worst = worst.max(d);
        }
    }
    worst
}

#[test]
fn instancer_outlines_and_advances_match_the_blend() {
    if no_fonttools() {
        return;
    }
    let worst = check_instances(bundled(), &[400.0, 475.0, 550.0, 625.0, 700.0]);
    eprintln!("bundled: worst instancer distance {worst:.3}");
    let worst_tiny = check_instances(&tiny(), &[100.0, 250.0, 400.0, 500.0, 600.0, 750.0, 900.0]);
    eprintln!("tiny: worst instancer distance {worst_tiny:.3}");
    let positions = [100.0, 250.0, 300.0, 450.0, 500.0, 550.0, 760.0, 900.0];
    let worst_mapped = check_instances(&tiny_mapped(), &positions);
    eprintln!("tiny mapped: worst instancer distance {worst_mapped:.3}");
}

#[test]
fn gpos_kerning_varies_with_the_masters() {
    if no_fonttools() {
        return;
    }
    for fam in [bundled().clone(), tiny(), tiny_mapped()] {
        let bytes = variable_ttf(&fam).unwrap();
        let order = glyph_order(&fam.default).unwrap();
        let ps = |model: &str| {
            order
                .iter()
                .find(|g| g.model_name == model)
                .map(|g| g.ps_name.clone())
                .unwrap()
        };
        let mut wghts = vec![fam.designspace.axes[0].default];
        wghts.extend(fam.masters.iter().map(|m| m.location.0["wght"]));
        wghts.extend(
            fam.designspace
                .instances
                .iter()
                .map(|i| i.location.0["wght"]),
        );
        let read = instances(&bytes, &wghts);
        for (&w, (_, pairs)) in wghts.iter().zip(&read) {
            let expected: Pairs = blended_kerning(&fam, &at(w))
                .into_iter()
                .filter(|(_, v)| *v != 0.0)
                .map(|((l, r), v)| ((ps(&l), ps(&r)), v.round() as i64))
                .collect();
            let got: BTreeMap<_, _> = pairs
                .iter()
                .filter(|(_, &v)| v != 0)
                .map(|(k, v)| (k.clone(), *v))
                .collect();
            assert_eq!(got, expected, "kerning at wght {w}");
        }
        // The values really vary: the first pair of the default differs in the last master.
        let k = &fam.default.kerning[0];
        let key = (ps(&k.left), ps(&k.right));
        let values: Vec<i64> = read.iter().map(|(_, p)| p[&key]).collect();
        eprintln!(
            "{}: {} {} at the masters {values:?}",
            fam.default.info.family, k.left, k.right
        );
        assert_ne!(values[0], values[values.len() - 1]);
    }
}

/// skrifa at `wghts`: every glyph's outline (gvar) and advance (HVAR) against the blend;
/// the worst outline distance and advance difference.
fn check_skrifa(family: &OutlinedFamily, wghts: &[f64]) -> (f64, f64) {
    let bytes = variable_ttf(family).unwrap();
    let font = FontRef::new(&bytes).unwrap();
    let axes = font.axes();
    assert_eq!(axes.len(), 1);
    let axis = axes.get(0).unwrap();
    let ds = &family.designspace.axes[0];
    assert_eq!(
        (
            axis.tag().to_string(),
            axis.min_value(),
            axis.default_value(),
            axis.max_value()
        ),
        (
            "wght".to_string(),
            ds.min as f32,
            ds.default as f32,
            ds.max as f32
        )
    );
    let order = glyph_order(&family.default).unwrap();
    let (mut worst, mut worst_advance) = (0.0f64, 0.0f64);
    for &w in wghts {
        let location = axes.location([("wght", w as f32)]);
        let metrics = font.glyph_metrics(Size::unscaled(), LocationRef::from(&location));
        let expected = blend(family, &at(w));
        for (gid, g) in order.iter().enumerate() {
            let Some(i) = family
                .default
                .glyphs
                .iter()
                .position(|o| o.name == g.model_name)
            else {
                continue;
            };
            let id = skrifa::GlyphId::new(gid as u32);
            let advance = f64::from(metrics.advance_width(id).unwrap());
            // skrifa rounds the HVAR delta to whole units, as FreeType does.
            assert_eq!(
                advance,
                expected[i].advance.round(),
                "{} at {w}: HVAR advance {advance}, blend {}",
                g.model_name,
                expected[i].advance
            );
            let da = (advance - expected[i].exact_advance).abs();
            worst_advance = worst_advance.max(da);
            let outline = skrifa_outline(&font, id, LocationRef::from(&location));
            let d = paths::two_sided(&outline, &expected[i].path, 48);
            // skrifa, like FreeType, adds the interpolated delta rounded to whole units
            // (`FT_fixedToInt`), so a point can move by another half unit per coordinate
            // beyond the grid rounding of the masters: twice GRID in all.
            let bound = family.default.tolerance + 2.0 * GRID;
            assert!(d <= bound, "{} at wght {w}: {d} > {bound}", g.model_name);
            worst = worst.max(d);
        }
    }
    (worst, worst_advance)
}

#[test]
fn skrifa_reads_outlines_and_advances_at_positions() {
    let (d, a) = check_skrifa(bundled(), &[400.0, 460.0, 555.5, 640.0, 700.0]);
    eprintln!("bundled: skrifa worst outline distance {d:.3}, advance {a:.4}");
    let (d, a) = check_skrifa(&tiny(), &[100.0, 175.0, 400.0, 480.0, 600.0, 820.0, 900.0]);
    eprintln!("tiny: skrifa worst outline distance {d:.3}, advance {a:.4}");
    let (d, a) = check_skrifa(
        &tiny_mapped(),
        &[100.0, 200.0, 300.0, 350.0, 500.0, 530.0, 760.0, 900.0],
    );
    eprintln!("tiny mapped: skrifa worst outline distance {d:.3}, advance {a:.4}");
}

#[test]
fn names_fvar_and_stat() {
    let bytes = variable_ttf(bundled()).unwrap();
    let font = FontRef::new(&bytes).unwrap();
    let text = |id| {
        font.localized_strings(id)
            .english_or_first()
            .unwrap()
            .to_string()
    };
    let names: Vec<(String, String, Vec<f32>)> = font
        .named_instances()
        .iter()
        .map(|i| {
            (
                text(i.subfamily_name_id()),
                text(i.postscript_name_id().unwrap()),
                i.user_coords().collect(),
            )
        })
        .collect();
    let expected = [
        ("Regular", "XglyphSans-Regular", 400.0),
        ("Medium", "XglyphSans-Medium", 500.0),
        ("SemiBold", "XglyphSans-SemiBold", 600.0),
        ("Bold", "XglyphSans-Bold", 700.0),
    ]
    .map(|(s, p, w)| (s.to_string(), p.to_string(), vec![w]));
    assert_eq!(names, expected);
    assert_eq!(
        text(skrifa::raw::types::NameId::VARIATIONS_POSTSCRIPT_NAME_PREFIX),
        "XglyphSans"
    );
    let axis = font.axes().get(0).unwrap();
    assert_eq!(
        font.localized_strings(axis.name_id())
            .english_or_first()
            .unwrap()
            .to_string(),
        "Weight"
    );
    use skrifa::raw::TableProvider;
    let stat = font.stat().unwrap();
    assert_eq!(
        stat.elided_fallback_name_id(),
        Some(skrifa::raw::types::NameId::new(2))
    );
    let values: Vec<(f32, u16, String)> = stat
        .offset_to_axis_values()
        .unwrap()
        .unwrap()
        .axis_values()
        .iter()
        .map(|v| match v.unwrap() {
            skrifa::raw::tables::stat::AxisValue::Format1(v) => (
                v.value().to_f32(),
                v.flags().bits(),
                font.localized_strings(v.value_name_id())
                    .english_or_first()
                    .unwrap()
                    .to_string(),
            ),
            _ => panic!("format 1 expected"),
        })
        .collect();
    assert_eq!(
        values,
        [
            (400.0, 2, "Regular".to_string()),
            (500.0, 0, "Medium".to_string()),
            (600.0, 0, "SemiBold".to_string()),
            (700.0, 0, "Bold".to_string()),
        ]
    );
    assert_eq!(font.os2().unwrap().us_weight_class(), 400);
    // Deterministic: the same family gives the same bytes.
    assert_eq!(variable_ttf(bundled()).unwrap(), bytes);
    // No legacy kern table: it cannot vary.
    assert!(font.kern().is_err());
}

#[test]
fn chromium_lays_out_each_named_instance_to_the_blended_width() {
    let Some(mut browser) = Browser::start() else {
        return;
    };
    for (fam, text) in [
        (bundled().clone(), "AVATAR WAVE HHH Tokyo"),
        (tiny(), "lolloool"),
        (tiny_mapped(), "lolloool"),
    ] {
        let bytes = variable_ttf(&fam).unwrap();
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("var.ttf"), &bytes).unwrap();
        let spans: String = fam
            .designspace
            .instances
            .iter()
            .enumerate()
            .map(|(i, inst)| {
                format!(
                    "<div><span id=\"s{i}\" style=\"font-variation-settings: 'wght' {}\">{text}</span></div>",
                    inst.location.0["wght"]
                )
            })
            .collect();
        let html = format!(
            "<!doctype html><style>@font-face {{ font-family: V; src: url(var.ttf); }}
             span {{ font: 1000px V; white-space: pre; font-kerning: normal; }}</style>
             <body>{spans}<script>document.fonts.load('1000px V').then(() =>
             document.fonts.ready).then(() => {{ document.body.dataset.ready = '1'; }});</script>"
        );
        std::fs::write(dir.path().join("page.html"), html).unwrap();
        browser.open(&format!(
            "file://{}",
            dir.path().join("page.html").display()
        ));
        assert_eq!(
            browser.eval("document.fonts.check('1000px V')"),
            json!(true)
        );
        let names: BTreeMap<char, String> = fam
            .default
            .glyphs
            .iter()
            .flat_map(|g| g.unicodes.iter().map(move |&c| (c, g.name.clone())))
            .collect();
        for (i, inst) in fam.designspace.instances.iter().enumerate() {
            let width: Value = browser.eval(&format!(
                "document.getElementById('s{i}').getBoundingClientRect().width"
            ));
            let width = width.as_f64().unwrap();
            let blended = blend(&fam, &inst.location);
            let kerning = blended_kerning(&fam, &inst.location);
            let glyphs: Vec<&String> = text.chars().map(|c| &names[&c]).collect();
            let index = |n: &str| fam.default.glyphs.iter().position(|g| g.name == n).unwrap();
            // HarfBuzz applies HVAR and GPOS deltas rounded to whole units.
            let advances: f64 = glyphs
                .iter()
                .map(|n| blended[index(n)].advance.round())
                .sum();
            let kerns: f64 = glyphs
                .windows(2)
                .map(|p| {
                    kerning
                        .get(&(p[0].clone(), p[1].clone()))
                        .map_or(0.0, |k| k.round())
                })
                .sum();
            let expected = advances + kerns;
            eprintln!(
                "{} {}: Chromium {width:.3} px, blended advances {advances:.3} + kerning {kerns:.3} = {expected:.3}",
                fam.default.info.family, inst.name
            );
            // Chromium positions glyphs in 1/64 px steps: allow 0.1 px per glyph, less than
            // the smallest kerning pair (4 units).
            assert!(
                (width - expected).abs() <= 0.1 * glyphs.len() as f64,
                "{} at {}: {width} vs {expected}",
                fam.default.info.family,
                inst.name
            );
        }
    }
}

#[test]
fn incompatible_masters_are_errors_naming_glyph_and_master() {
    let mut fam = tiny();
    // Bold's `l` drawn as a ring: other elements than the default's stem.
    fam.masters[2].glyphs[1].path = ring(60.0, 100.0, 360.0, 90.0);
    assert_eq!(
        variable_ttf(&fam).unwrap_err().to_string(),
        "variable font: glyph 'l' has other path elements in master 'Bold' than in the \
         default master"
    );
    let mut fam = tiny();
    fam.masters[0].glyphs.pop();
    assert_eq!(
        variable_ttf(&fam).unwrap_err().to_string(),
        "variable font: master 'Light' has 1 glyphs, the default 2"
    );
    let mut fam = tiny();
    fam.masters[1].glyphs[0].advance = 40_000.0;
    assert_eq!(
        variable_ttf(&fam).unwrap_err().to_string(),
        "advance of 'o' in master 'SemiBold' is 40000, outside the OpenType range 0..=32767"
    );
}

/// Compares, with fontTools, the IUP-optimized variable font `a` with the one that writes
/// every delta (`b`): per tuple the deltas fontTools infers for `a` against `b`'s, then
/// `varLib.instancer`'s glyf coordinates and advances at each position. Returns the JSON
/// summary (`omitted` deltas, `mismatches`, `gvar` sizes).
fn compare_iup(a: &[u8], b: &[u8], wghts: &[f64]) -> Value {
    const SCRIPT: &str = r#"
import json, sys
from fontTools.ttLib import TTFont
from fontTools.varLib import instancer
a_path, b_path, locs = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
a, b = TTFont(a_path), TTFont(b_path)
mismatches, omitted, tuples = [], 0, 0
glyf = a["glyf"]
for name in a.getGlyphOrder():
    va, vb = a["gvar"].variations.get(name, []), b["gvar"].variations.get(name, [])
    if len(va) != len(vb):
        mismatches.append(f"{name}: {len(va)} tuples, explicit {len(vb)}")
        continue
    coords, controls = glyf._getCoordinatesAndControls(name, a["hmtx"].metrics)
    for ta, tb in zip(va, vb):
        tuples += 1
        omitted += sum(1 for c in ta.coordinates if c is None)
        if ta.axes != tb.axes:
            mismatches.append(f"{name}: regions {ta.axes} != {tb.axes}")
        ta.calcInferredDeltas(coords, controls.endPts)
        if list(ta.coordinates) != [tuple(map(float, c)) for c in tb.coordinates]:
            bad = [i for i, (p, q) in enumerate(zip(ta.coordinates, tb.coordinates)) if tuple(p) != tuple(q)]
            mismatches.append(f"{name}: inferred deltas differ at points {bad[:8]}")
for w in locs:
    ia = instancer.instantiateVariableFont(TTFont(a_path), {"wght": w})
    ib = instancer.instantiateVariableFont(TTFont(b_path), {"wght": w})
    for name in ia.getGlyphOrder():
        ca = list(ia["glyf"][name].getCoordinates(ia["glyf"])[0])
        cb = list(ib["glyf"][name].getCoordinates(ib["glyf"])[0])
        if ca != cb or ia["hmtx"][name] != ib["hmtx"][name]:
            mismatches.append(f"{name} at wght {w}: instances differ")
print(json.dumps({"omitted": omitted, "tuples": tuples, "mismatches": mismatches,
    "gvar": [len(a.reader["gvar"]), len(b.reader["gvar"])]}))
"#;
    let (da, db) = (write_temp(a), write_temp(b));
    tools::python_json(
        SCRIPT,
        &[
            &da.path().join("var.ttf"),
            &db.path().join("var.ttf"),
            &json!(wghts).to_string(),
        ],
    )
}

/// Issue 16 (as fontmake does it): `gvar` omits the deltas that interpolation of untouched
/// points infers, and only those inferred exactly, so fontTools infers every omitted delta
/// as the explicit one and `varLib.instancer` gives the same glyf coordinates and advances
/// with and without IUP, at 6 positions (the masters and between them, halfway included).
#[test]
fn iup_keeps_every_instance_exact() {
    if no_fonttools() {
        return;
    }
    let wghts = [400.0, 437.5, 500.0, 550.0, 625.0, 700.0];
    for (name, fam, wghts) in [
        ("glyphs/", typeface().clone(), &wghts[..]),
        ("bundled", bundled().clone(), &wghts[..]),
        (
            "tiny",
            tiny(),
            &[100.0, 250.0, 400.0, 500.0, 650.0, 900.0][..],
        ),
    ] {
        let optimized = variable_ttf(&fam).unwrap();
        let explicit = xglyph::otf::variable_ttf_explicit_deltas(&fam).unwrap();
        let report = compare_iup(&optimized, &explicit, wghts);
        eprintln!("{name}: {report}");
        assert_eq!(report["mismatches"], json!([]), "{name}");
        let gvar = report["gvar"].as_array().unwrap();
        assert!(gvar[0].as_u64() <= gvar[1].as_u64(), "{name}: {report}");
        if name == "glyphs/" {
            // The real Bold has deltas to infer; the affine Bold of `bundled` leaves none
            // exactly inferable, and `tiny`'s few points pack smaller without.
            assert!(report["omitted"].as_u64().unwrap() > 0, "{name}: {report}");
        }
    }
}

/// The mapped four-master family goes out as a variable TTF and comes back in with every
/// master: Light and Bold at the axis ends, SemiBold where gvar peaks inside the axis, and
/// the axis map; rebuilt, it has the same `avar` and the same outlines along the axis.
#[test]
fn a_variable_font_with_an_intermediate_master_and_a_map_imports_whole() {
    let original = tiny_mapped();
    let bytes = variable_ttf(&original).unwrap();
    let dir = write_temp(&bytes);
    let imported = dir.path().join("imported");
    let report =
        crate::common::cli::import_ok(&[dir.path().join("var.ttf").to_str().unwrap()], &imported);
    assert!(!report.contains("gvar has variations"), "{report}");
    let (family, _) = xglyph::source::load_family(&imported).expect("loads");
    let places: Vec<(String, f64)> = family
        .masters
        .iter()
        .map(|m| (m.name.clone(), m.location.0["wght"]))
        .collect();
    assert_eq!(
        places,
        [
            ("Light".to_string(), 100.0),
            ("SemiBold".to_string(), 600.0),
            ("Bold".to_string(), 900.0)
        ]
    );
    assert_eq!(
        family.designspace.axes[0].map.len(),
        7,
        "{:?}",
        family.designspace.axes
    );
    let rebuilt_dir = dir.path().join("rebuilt");
    let (code, _, stderr) = crate::common::cli::xglyph(&[
        "build",
        imported.to_str().unwrap(),
        "-o",
        rebuilt_dir.to_str().unwrap(),
    ]);
    assert_eq!((code, stderr.as_str()), (0, ""));
    let rebuilt = std::fs::read(rebuilt_dir.join("TinyMapped[wght].ttf")).unwrap();
    let (a, b) = (
        FontRef::new(&bytes).unwrap(),
        FontRef::new(&rebuilt).unwrap(),
    );
    use skrifa::raw::TableProvider;
    let segments = |f: &FontRef| -> Vec<(f32, f32)> {
        f.avar()
            .unwrap()
            .axis_segment_maps()
            .get(0)
            .unwrap()
            .unwrap()
            .axis_value_maps()
            .iter()
            .map(|m| (m.from_coordinate().to_f32(), m.to_coordinate().to_f32()))
            .collect()
    };
    assert_eq!(segments(&b), segments(&a));
    let mut worst: f64 = 0.0;
    for w in [
        100.0, 200.0, 300.0, 450.0, 500.0, 560.0, 600.0, 700.0, 760.0, 900.0,
    ] {
        let (la, lb) = (
            a.axes().location([("wght", w)]),
            b.axes().location([("wght", w)]),
        );
        for c in ['o', 'l'] {
            let (ga, gb) = (a.charmap().map(c).unwrap(), b.charmap().map(c).unwrap());
            let d = paths::two_sided(
                &skrifa_outline(&a, ga, LocationRef::from(&la)),
                &skrifa_outline(&b, gb, LocationRef::from(&lb)),
                48,
            );
            // The import's bound (1/1000 em for this font) and the rebuild's tolerance,
            // plus grid rounding and skrifa's rounded deltas in each font.
            let bound = 1.0 + original.default.tolerance + 4.0 * GRID;
            assert!(d <= bound, "{c} at wght {w}: {d} > {bound}");
            worst = worst.max(d);
        }
    }
    eprintln!("imported and rebuilt: worst distance {worst:.3} along the axis");
}

/// 17 axes with a master at each end: every glyph has 34 variation tuples, more than
/// ttf-parser reads without its `gvar-alloc` feature (32). Such a font (Roboto Flex has 13
/// axes and more tuples) imports, every master within the import bound of its outline.
#[test]
fn a_glyph_with_more_than_32_variations_imports() {
    let base = tiny();
    let axes: Vec<Axis> = (0..17)
        .map(|k| Axis::linear(format!("X{k:03}"), format!("Axis {k}"), -100.0, 0.0, 100.0))
        .collect();
    let mut masters = Vec::new();
    let mut locations = Vec::new();
    for (k, a) in axes.iter().enumerate() {
        for (end, sign) in [(a.min, -1.0), (a.max, 1.0)] {
            let d = sign * (2.0 + k as f64);
            locations.push(Location([(a.tag.clone(), end)].into_iter().collect()));
            masters.push(vec![
                MasterGlyph {
                    advance: 2.0 * (230.0 + d) + 80.3,
                    path: ring(40.0, 230.0 + d, 260.0 - d, 70.0 + d),
                    drawn: true,
                },
                MasterGlyph {
                    advance: 80.0 + d + 120.6,
                    path: stem(60.0, 80.0 + d, 720.0 + d),
                    drawn: true,
                },
            ]);
        }
    }
    let designspace = Designspace {
        axes,
        instances: vec![],
        rules: Vec::new(),
        rules_last: false,
    };
    let model = designspace.model(&locations).expect("valid masters");
    let models = GlyphModels::full(locations.len(), &model, base.default.glyphs.len());
    let family = OutlinedFamily {
        models,
        designspace,
        default: base.default.clone(),
        masters: masters
            .into_iter()
            .zip(locations)
            .enumerate()
            .map(|(k, (glyphs, location))| OutlinedMaster {
                name: format!("M{k}"),
                location,
                glyphs,
                kerning: vec![],
            })
            .collect(),
        model,
    };
    let bytes = variable_ttf(&family).unwrap();
    let dir = write_temp(&bytes);
    let imported = dir.path().join("imported");
    crate::common::cli::import_ok(&[dir.path().join("var.ttf").to_str().unwrap()], &imported);
    let (back, _) = xglyph::source::load_family(&imported).expect("loads");
    assert_eq!(back.designspace.axes.len(), 17);
    assert_eq!(back.masters.len(), 34);
    // The last master (X016 = 100): `l`'s advance is the original's, rounded.
    let last = back
        .masters
        .iter()
        .find(|m| m.location.0.get("X016") == Some(&100.0))
        .unwrap();
    let l = last.glyphs.iter().find(|g| g.unicodes == ['l']).unwrap();
    assert_eq!(l.advance, (80.0f64 + 18.0 + 120.6).round());
}
