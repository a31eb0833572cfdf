//! Anchors (`[[anchor]]`): parsing in source order, `fmt` round trip (a component placed by
//! anchors keeps no `offset`), placement of components without `offset` (a mark on a base,
//! a mark stacked on a mark, per master), propagation to composites, and the bundled
//! typeface's composites placed exactly where their anchors say. The error messages are
//! the `tests/malformed/anchor_*` and `mark_*` cases.

use std::path::Path;
use std::process::Command;

use xglyph::model::{propagate_anchors, Anchor, Family, Glyph};
use xglyph::source::{
    is_combining, load_family, load_font, load_glyph_text, offsets_written, place_in_font,
};

use crate::common::fonts::{small_font_folder, SMALL_FONT as FONT};
use crate::common::temp::TempFolder;

/// A fresh font folder with the small `font.toml` and `files`.
fn font_dir(tag: &str, files: &[(&str, &str)]) -> TempFolder {
    small_font_folder(&format!("anchors-{tag}"), files)
}

fn anchor(name: &str, x: f64, y: f64) -> Anchor {
    Anchor {
        name: name.to_string(),
        position: (x, y),
    }
}

const TRIANGLE: &str = "[[contour]]\npoints = [[0, 0, 0], [100, 0, 0], [100, 100, 0]]\n";

/// `A` with `top` and `bottom`, two top marks that stack, a cedilla, and composites.
fn accents() -> Vec<(&'static str, String)> {
    vec![
        (
            "A_.toml",
            format!(
                "name = \"A\"\nadvance = 600\n\n{TRIANGLE}\n[[anchor]]\nname = \"top\"\n\
                 position = [300, 700]\n\n[[anchor]]\nname = \"bottom\"\nposition = [310, 0]\n"
            ),
        ),
        (
            "acutecomb.toml",
            format!(
                "unicode = 0x0301\nadvance = 0\n\n{TRIANGLE}\n[[anchor]]\nname = \"_top\"\n\
                 position = [0, 500]\n\n[[anchor]]\nname = \"top\"\nposition = [4, 720]\n"
            ),
        ),
        (
            "gravecomb.toml",
            format!(
                "unicode = 0x0300\nadvance = 0\n\n{TRIANGLE}\n[[anchor]]\nname = \"_top\"\n\
                 position = [10, 500]\n\n[[anchor]]\nname = \"top\"\nposition = [10, 730]\n"
            ),
        ),
        (
            "cedillacomb.toml",
            format!(
                "unicode = 0x0327\nadvance = 0\n\n{TRIANGLE}\n[[anchor]]\nname = \"_bottom\"\n\
                 position = [-5, 10]\n\n[[anchor]]\nname = \"top\"\nposition = [0, 900]\n"
            ),
        ),
        (
            "A_acute.toml",
            "name = \"Aacute\"\nadvance = 600\n\n[[component]]\nbase = \"A\"\n\n\
             [[component]]\nbase = \"acutecomb\"\n"
                .to_string(),
        ),
        (
            "A_acutegrave.toml",
            "name = \"Aacutegrave\"\nadvance = 600\n\n[[component]]\nbase = \"A\"\n\n\
             [[component]]\nbase = \"acutecomb\"\n\n[[component]]\nbase = \"gravecomb\"\n\
             \n[[component]]\nbase = \"cedillacomb\"\n"
                .to_string(),
        ),
        (
            "A_written.toml",
            "name = \"Awritten\"\nadvance = 600\n\n[[component]]\nbase = \"A\"\n\
             offset = [20, 0]\n\n[[component]]\nbase = \"acutecomb\"\n\n\
             [[component]]\nbase = \"gravecomb\"\noffset = [1, 2]\n"
                .to_string(),
        ),
    ]
}

fn accents_dir(tag: &str) -> TempFolder {
    let files = accents();
    let refs: Vec<(&str, &str)> = files.iter().map(|(n, t)| (*n, t.as_str())).collect();
    font_dir(tag, &refs)
}

fn offsets(glyph: &Glyph) -> Vec<(f64, f64)> {
    glyph.components.iter().map(|c| c.offset).collect()
}

#[test]
fn anchors_parse_in_source_order() {
    let text = "name = \"x\"\nadvance = 500\n\n[[anchor]]\nname = \"top\"\nposition = [270, 540]\n\
                \n[[anchor]]\nname = \"_bottom\"\nposition = [-12.5, 0]\n\n[[anchor]]\n\
                name = \"a\"\nposition = [0x10, -3]\n";
    let (glyph, warnings) = load_glyph_text(Path::new("x.toml"), text).expect("loads");
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(
        glyph.anchors,
        [
            anchor("top", 270.0, 540.0),
            anchor("_bottom", -12.5, 0.0),
            anchor("a", 16.0, -3.0)
        ]
    );
    assert!(glyph.is_mark());
}

#[test]
fn marks_are_placed_on_bases_and_stack() {
    let dir = accents_dir("place");
    let (font, warnings) = load_font(&dir).expect("loads");
    assert!(warnings.is_empty(), "{warnings:?}");
    let glyph = |n: &str| font.glyph(n).expect(n).clone();
    // Aacute: `_top` [0, 500] lands on A's `top` [300, 700].
    assert_eq!(offsets(&glyph("Aacute")), [(0.0, 0.0), (300.0, 200.0)]);
    // The grave stacks on the acute: the acute's `top` [4, 720] moved by [300, 200] is
    // [304, 920]; the grave's `_top` [10, 500] lands there. The cedilla's `_bottom`
    // [-5, 10] lands on A's `bottom` [310, 0], which no top mark replaced.
    assert_eq!(
        offsets(&glyph("Aacutegrave")),
        [(0.0, 0.0), (300.0, 200.0), (294.0, 420.0), (315.0, -10.0)]
    );
    // Written offsets stay; the unwritten acute follows the moved base.
    assert_eq!(
        offsets(&glyph("Awritten")),
        [(20.0, 0.0), (320.0, 200.0), (1.0, 2.0)]
    );
    // Propagation: the grave's `top` [10, 730] + [294, 420]; the cedilla (attached by
    // `_bottom`) does not bring its `top`; A's `bottom` stays.
    assert_eq!(
        font.anchors(&glyph("Aacutegrave")),
        [anchor("top", 304.0, 1150.0), anchor("bottom", 310.0, 0.0)]
    );
    assert_eq!(
        font.anchors(&glyph("Aacute")),
        [anchor("top", 304.0, 920.0), anchor("bottom", 310.0, 0.0)]
    );
    assert_eq!(font.anchors(&glyph("A")), glyph("A").anchors);
}

#[test]
fn propagation_follows_ufo2ft() {
    let base = [anchor("top", 100.0, 500.0), anchor("bottom", 100.0, 0.0)];
    let mark = [
        anchor("_top", 0.0, 450.0),
        anchor("top", 0.0, 700.0),
        anchor("right", 30.0, 600.0),
    ];
    let low = [anchor("_bottom", 0.0, 0.0), anchor("top", 0.0, 50.0)];
    let placed: [((f64, f64), &[Anchor]); 3] = [
        ((10.0, 0.0), &base),
        ((110.0, 50.0), &mark),
        ((110.0, 0.0), &low),
    ];
    // Own anchors win by name; the top mark brings `top` (it has `_top`) but not
    // `right`, which the base lacks; the bottom mark brings nothing (its `top` is not
    // where it attaches).
    let own = [anchor("bottom", 1.0, 2.0)];
    assert_eq!(
        propagate_anchors(&own, placed),
        [anchor("bottom", 1.0, 2.0), anchor("top", 110.0, 750.0)]
    );
    assert_eq!(
        propagate_anchors(&[], placed),
        [anchor("top", 110.0, 750.0), anchor("bottom", 110.0, 0.0)]
    );
}

#[test]
fn fmt_keeps_anchors_and_leaves_placed_offsets_out() {
    let messy = "name=\"Aacute\"\nadvance=600\n[[anchor]]\nname=\"top\"\nposition=[1,2.50]\n\
                 [[component]]\nbase=\"A\"\n[[component]]\nbase=\"acutecomb\"\n";
    let mut files = accents();
    files[4].1 = messy.to_string();
    let refs: Vec<(&str, &str)> = files.iter().map(|(n, t)| (*n, t.as_str())).collect();
    let dir = font_dir("fmt", &refs);
    let before = load_font(&dir).expect("loads").0;
    let out = Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .arg("fmt")
        .arg(&dir)
        .output()
        .expect("run");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(dir.join("A_acute.toml")).expect("read");
    assert_eq!(
        text,
        "name = \"Aacute\"\nadvance = 600\n\n[[component]]\nbase = \"A\"\n\n[[component]]\n\
         base = \"acutecomb\"\n\n[[anchor]]\nname = \"top\"\nposition = [1, 2.5]\n"
    );
    // The model is unchanged.
    assert!(String::from_utf8_lossy(&out.stdout).contains("A_acute.toml"));
    assert_eq!(load_font(&dir).expect("reloads").0, before);
    let again = Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(["fmt", "--check"])
        .arg(&dir)
        .output()
        .expect("run");
    assert!(again.status.success());
}

/// The bundled typeface: `glyphs/` with its Bold master.
fn bundled() -> Family {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    load_family(&dir).expect("the bundled font loads").0
}

/// Where a mark component's anchors put it: its `_x` on the `x` of the components before it.
fn anchor_offset(glyphs: &[Glyph], composite: &Glyph, k: usize) -> (f64, f64) {
    let find = |n: &str| glyphs.iter().find(|g| g.name == n).expect(n);
    let base = find(&composite.components[0].base);
    let mark = find(&composite.components[k].base);
    let attach = mark
        .anchors
        .iter()
        .find_map(|a| a.attaches_to().map(|to| (a, to)));
    let (m, to) = attach.expect("a mark");
    let b = base
        .anchors
        .iter()
        .find(|a| a.name == to)
        .expect("base anchor");
    (b.position.0 - m.position.0, b.position.1 - m.position.1)
}

#[test]
fn bundled_composites_sit_on_their_anchors() {
    let family = bundled();
    let masters: Vec<(&str, &[Glyph])> = std::iter::once(("Regular", &family.default.glyphs[..]))
        .chain(
            family
                .masters
                .iter()
                .map(|m| (m.name.as_str(), &m.glyphs[..])),
        )
        .collect();
    assert_eq!(masters.len(), 2);
    for (name, glyphs) in &masters {
        let mut placed = 0;
        for g in glyphs.iter().filter(|g| g.components.len() == 2) {
            assert_eq!(g.components[0].offset, (0.0, 0.0), "{name} {}", g.name);
            assert_eq!(
                g.components[1].offset,
                anchor_offset(glyphs, g, 1),
                "{name} {}",
                g.name
            );
            placed += 1;
        }
        assert_eq!(placed, 50, "{name}");
    }
    // The hand offsets they replace (Aacute, Ccedilla, ccedilla), and eacute, whose accent
    // moved onto the apex of the `e` (it sat 27 units right, 31 in Bold).
    let offset = |glyphs: &[Glyph], n: &str| {
        glyphs.iter().find(|g| g.name == n).expect(n).components[1].offset
    };
    let (regular, bold) = (masters[0].1, masters[1].1);
    assert_eq!(offset(regular, "Aacute"), (310.0, 200.0));
    assert_eq!(offset(bold, "Aacute"), (349.0, 200.0));
    assert_eq!(offset(regular, "eacute"), (272.0, 0.0));
    assert_eq!(offset(bold, "eacute"), (304.0, 0.0));
    assert_eq!(offset(regular, "Ccedilla"), (385.0, 0.0));
    assert_eq!(offset(bold, "ccedilla"), (314.0, 0.0));
    // Aacute's own `top` is the acute's, raised: a second mark would stack on it.
    let font = &family.default;
    let aacute = font.glyph("Aacute").expect("Aacute");
    assert_eq!(font.anchors(aacute), [anchor("top", 310.0, 897.0)]);
}

#[test]
fn bundled_letters_and_marks_have_anchors() {
    let family = bundled();
    let font = &family.default;
    let mut letters: Vec<String> = ('A'..='Z').chain('a'..='z').map(String::from).collect();
    letters.extend(["dotlessi".to_string(), "dotlessj".to_string()]);
    for l in &letters {
        let g = font.glyph(l).expect(l);
        assert_eq!(g.anchors[0].name, "top", "{l}");
        assert!(!g.is_mark(), "{l}");
    }
    for c in ["C", "c"] {
        let names: Vec<&str> = font
            .glyph(c)
            .expect(c)
            .anchors
            .iter()
            .map(|a| a.name.as_str())
            .collect();
        assert_eq!(names, ["top", "bottom"]);
    }
    let marks: Vec<&Glyph> = font
        .glyphs
        .iter()
        .filter(|g| g.unicodes.iter().any(|&c| is_combining(c)))
        .collect();
    let names: Vec<&str> = marks.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "acutecomb",
            "cedillacomb",
            "circumflexcomb",
            "dieresiscomb",
            "gravecomb",
            "ringcomb",
            "tildecomb"
        ]
    );
    for m in marks {
        let first = &m.anchors[0];
        let want = if m.name == "cedillacomb" {
            "_bottom"
        } else {
            "_top"
        };
        assert_eq!(first.name, want, "{}", m.name);
    }
}

#[test]
fn masters_place_by_their_own_anchors() {
    let mut files = accents();
    files.truncate(5);
    let dir = {
        let refs: Vec<(&str, &str)> = files.iter().map(|(n, t)| (*n, t.as_str())).collect();
        font_dir("masters", &refs)
    };
    let ds = "\n[[axis]]\ntag = \"wght\"\nname = \"Weight\"\nmin = 400\ndefault = 400\nmax = 700\n\
              \n[[master]]\nname = \"Bold\"\nfolder = \"bold\"\nlocation = { wght = 700 }\n";
    std::fs::write(dir.join("font.toml"), format!("{FONT}{ds}")).expect("font.toml");
    std::fs::create_dir_all(dir.join("bold")).expect("mkdir");
    for (name, text) in &files {
        // Bold: A's `top` 40 units right, the acute's `_top` 5 units lower.
        let text = text
            .replace("position = [300, 700]", "position = [340, 700]")
            .replace("position = [0, 500]", "position = [0, 495]");
        std::fs::write(dir.join("bold").join(name), text).expect("write");
    }
    let (family, _) = load_family(&dir).expect("loads");
    let aacute =
        |glyphs: &[Glyph]| offsets(glyphs.iter().find(|g| g.name == "Aacute").expect("Aacute"));
    assert_eq!(aacute(&family.default.glyphs), [(0.0, 0.0), (300.0, 200.0)]);
    assert_eq!(
        aacute(&family.masters[0].glyphs),
        [(0.0, 0.0), (340.0, 205.0)]
    );
}

#[test]
fn a_glyph_read_alone_is_placed_by_the_fonts_anchors() {
    let dir = accents_dir("alone");
    let (font, _) = load_font(&dir).expect("loads");
    let path = dir.join("A_acutegrave.toml");
    let text = std::fs::read_to_string(&path).expect("read");
    let (mut glyph, _) = load_glyph_text(&path, &text).expect("loads alone");
    assert_eq!(offsets(&glyph), [(0.0, 0.0); 4]);
    let written = offsets_written(&path, &text).expect("written");
    assert_eq!(written, [false; 4]);
    place_in_font(&font, &mut glyph, &written);
    assert_eq!(Some(&glyph), font.glyph("Aacutegrave"));
}
