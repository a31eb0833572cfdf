//! `mark = "outline"`: a mark its own outline places (no `_` anchor). `check` accepts it
//! on a combining code point; `fmt` and the emitter keep it after `advance`; the build
//! classes it a mark in GDEF (with or without a code point), attaches nothing to it but
//! stacks a mark on its anchor `top` (`mkmk`), and kerning skips it; the UFO export lists
//! the categories so that ufo2ft and fontc class it too. Its error messages are the
//! `tests/malformed/mark_*` cases; the DejaVu import of one is in `import_font.rs`.

use std::path::{Path, PathBuf};
use std::process::Command;

use skrifa::raw::TableProvider;
use skrifa::FontRef;
use xglyph::layout::Layout;
use xglyph::outline::outline_font;
use xglyph::source::emit::{glyph_toml, master_glyph_toml};
use xglyph::source::{load_family, load_font, load_glyph_text};

use crate::common::fonts::{small_font_folder, SMALL_FONT as FONT};
use crate::common::temp::TempFolder;

const TRIANGLE: &str = "[[contour]]\npoints = [[0, 0, 0], [100, 0, 0], [100, 100, 0]]\n";

/// The overlay tilde as `fmt` writes it: on U+0334, placed by its outline, with a `top`
/// for a mark stacked on it.
fn overlay() -> String {
    const OVERLAY: &str =
        "name = \"tildeoverlaycomb\"\nunicode = 0x0334\nadvance = 0\nmark = \"outline\"\n\n\
         [[contour]]\npoints = [\n  [-300, 250, 0],\n  [-100, 250, 0],\n  [-100, 300, 0],\n]\n\n\
         [[anchor]]\nname = \"top\"\nposition = [-250, 800]\n";
    OVERLAY.to_string()
}

/// `n` (anchor `top`, kerned -50 against itself), `x`, the overlay, an acute that
/// attaches by `_top`, and an unencoded ring placed by its outline.
fn files() -> Vec<(&'static str, String)> {
    vec![
        (
            "n.toml",
            format!(
                "unicode = 0x006E\nadvance = 500\n\n{TRIANGLE}\n[[anchor]]\nname = \"top\"\n\
                 position = [250, 500]\n"
            ),
        ),
        (
            "x.toml",
            format!("unicode = 0x0078\nadvance = 400\n\n{TRIANGLE}"),
        ),
        ("tildeoverlaycomb.toml", overlay()),
        (
            "acutecomb.toml",
            format!(
                "unicode = 0x0301\nadvance = 0\n\n{TRIANGLE}\n[[anchor]]\nname = \"_top\"\n\
                 position = [0, 500]\n"
            ),
        ),
        (
            "ringoverlay.toml",
            format!("advance = 0\nmark = \"outline\"\n\n{TRIANGLE}"),
        ),
        (
            "kerning.toml",
            "[[pair]]\nleft = \"n\"\nright = \"n\"\nvalue = -50\n".to_string(),
        ),
    ]
}

/// A fresh font folder with the small `font.toml` and `files`.
fn font_dir(tag: &str, files: &[(&str, String)]) -> TempFolder {
    small_font_folder(&format!("mark-{tag}"), files)
}

fn xglyph(args: &[&str], dir: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(args)
        .arg(dir)
        .output()
        .expect("run xglyph")
}

#[test]
fn the_key_loads_and_check_accepts_a_combining_mark_with_it() {
    let (glyph, warnings) =
        load_glyph_text(Path::new("tildeoverlaycomb.toml"), &overlay()).expect("loads");
    assert!(warnings.is_empty(), "{warnings:?}");
    assert!(glyph.outline_mark && glyph.is_mark() && !glyph.attaches_by_anchor());
    let dir = font_dir("check", &files());
    let (font, warnings) = load_font(&dir).expect("check passes");
    assert!(warnings.is_empty(), "{warnings:?}");
    let marks: Vec<&str> = font
        .glyphs
        .iter()
        .filter(|g| g.outline_mark)
        .map(|g| g.name.as_str())
        .collect();
    assert_eq!(marks, ["ringoverlay", "tildeoverlaycomb"]);

    // Without the key the combining glyph is refused, and the message offers it.
    let without = overlay().replace("mark = \"outline\"\n", "");
    std::fs::write(dir.join("tildeoverlaycomb.toml"), without).expect("write");
    let errors = load_font(&dir).expect_err("check fails");
    let shown: Vec<String> = errors
        .iter()
        .map(|d| format!("{}:{}: {}", d.line, d.col, d.message))
        .collect();
    assert_eq!(
        shown,
        [
            "2:11: glyph `tildeoverlaycomb` is mapped to U+0334, a combining mark, but has no `_` \
          anchor to attach by; add one, e.g. `[[anchor]]` with name = \"_top\", or write \
          mark = \"outline\" if its outline places it"
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_later_component_placed_by_its_outline_needs_an_offset() {
    let mut files = files();
    files.push((
        "nring.toml",
        "advance = 500\n\n[[component]]\nbase = \"n\"\n\n[[component]]\n\
         base = \"ringoverlay\"\n"
            .to_string(),
    ));
    let dir = font_dir("component", &files);
    let errors = load_font(&dir).expect_err("check fails");
    let shown: Vec<String> = errors
        .iter()
        .map(|d| format!("{}:{}:{}: {}", d.path.display(), d.line, d.col, d.message))
        .collect();
    let file = dir.join("nring.toml");
    assert_eq!(
        shown,
        [format!(
            "{}:7:8: component `ringoverlay` has no `offset`, and it is a mark placed by its \
             outline (`mark = \"outline\"`), which no anchor places: write `offset = [x, y]` \
             (`[0, 0]` to overlay it where its outline is drawn)",
            file.display()
        )]
    );
    // With an offset it builds into the composite where its outline is drawn.
    let with_offset = files[files.len() - 1].1.clone() + "offset = [0, 0]\n";
    std::fs::write(&file, with_offset).expect("write");
    let (font, _) = load_font(&dir).expect("check passes");
    let nring = font
        .glyphs
        .iter()
        .find(|g| g.name == "nring")
        .expect("nring");
    assert_eq!(nring.components[1].offset, (0.0, 0.0));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fmt_keeps_the_key_after_advance_and_the_emitter_writes_it() {
    let mut files = files();
    // The key before `unicode`, spaced oddly: `fmt` puts it after `advance`.
    files[2].1 = overlay()
        .replace("mark = \"outline\"\n", "")
        .replace("unicode = 0x0334\n", "mark=\"outline\"\nunicode = 0x0334\n");
    let dir = font_dir("fmt", &files);
    let before = load_font(&dir).expect("loads").0;
    let out = xglyph(&["fmt"], &dir);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let path = dir.join("tildeoverlaycomb.toml");
    assert_eq!(std::fs::read_to_string(&path).expect("read"), overlay());
    assert_eq!(load_font(&dir).expect("reloads").0, before);
    // Canonical now: a second `fmt` leaves every file byte for byte.
    let texts = |dir: &Path| -> Vec<(PathBuf, Vec<u8>)> {
        let mut all: Vec<_> = std::fs::read_dir(dir)
            .expect("list")
            .map(|e| e.expect("entry").path())
            .map(|p| (p.clone(), std::fs::read(&p).expect("read")))
            .collect();
        all.sort();
        all
    };
    let formatted = texts(&dir);
    assert!(xglyph(&["fmt"], &dir).status.success());
    assert!(xglyph(&["fmt", "--check"], &dir).status.success());
    assert_eq!(texts(&dir), formatted);

    let glyph = before
        .glyphs
        .iter()
        .find(|g| g.name == "tildeoverlaycomb")
        .expect("the overlay");
    assert_eq!(glyph_toml(glyph), overlay());
    // A master's file leaves the default's keys out.
    assert_eq!(
        master_glyph_toml(glyph),
        overlay()
            .replace("unicode = 0x0334\n", "")
            .replace("mark = \"outline\"\n", "")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn masters_take_the_default_masters_key_and_fmt_keeps_each_file_as_written() {
    let mut files = files();
    let ds = "\n[[axis]]\ntag = \"wght\"\nname = \"Weight\"\nmin = 400\ndefault = 400\nmax = 700\n\
              \n[[master]]\nname = \"Bold\"\nfolder = \"bold\"\nlocation = { wght = 700 }\n";
    files.retain(|(n, _)| *n != "kerning.toml");
    let dir = font_dir("masters", &files);
    std::fs::write(dir.join("font.toml"), format!("{FONT}{ds}")).expect("font.toml");
    std::fs::create_dir_all(dir.join("bold")).expect("mkdir");
    for (name, text) in &files {
        // Bold's overlay leaves the key out; its ring writes it, as the default does.
        let text = if *name == "tildeoverlaycomb.toml" {
            text.replace("mark = \"outline\"\n", "")
        } else {
            text.clone()
        };
        std::fs::write(dir.join("bold").join(name), text).expect("write");
    }
    let (family, warnings) = load_family(&dir).expect("check passes");
    assert!(warnings.is_empty(), "{warnings:?}");
    let marks = |glyphs: &[xglyph::Glyph]| -> Vec<String> {
        let marks = glyphs.iter().filter(|g| g.outline_mark);
        marks.map(|g| g.name.clone()).collect()
    };
    assert_eq!(
        marks(&family.default.glyphs),
        ["ringoverlay", "tildeoverlaycomb"]
    );
    assert_eq!(
        marks(&family.masters[0].glyphs),
        marks(&family.default.glyphs)
    );
    let bold = |name: &str| std::fs::read_to_string(dir.join("bold").join(name)).expect("read");
    let overlay_before = bold("tildeoverlaycomb.toml");
    let out = xglyph(&["fmt"], &dir);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // The overlay was canonical without the key and stays so; the ring keeps it.
    assert_eq!(bold("tildeoverlaycomb.toml"), overlay_before);
    assert!(!overlay_before.contains("mark ="));
    assert!(bold("ringoverlay.toml")
        .starts_with("name = \"ringoverlay\"\nadvance = 0\nmark = \"outline\"\n\n"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// GDEF glyph class of each glyph of `names` in `ttf` (0: not in the class table).
fn gdef_classes(ttf: &[u8], names: &[&str], order: &[xglyph::otf::OrderedGlyph]) -> Vec<u32> {
    let font = FontRef::new(ttf).expect("reads");
    let classes = font
        .gdef()
        .expect("a GDEF")
        .glyph_class_def()
        .expect("glyph classes")
        .expect("readable");
    names
        .iter()
        .map(|n| {
            let gid = order
                .iter()
                .position(|g| g.model_name == *n)
                .expect("in the font");
            classes.get(skrifa::GlyphId::new(gid as u32))
        })
        .collect()
}

#[test]
fn the_build_classes_it_a_mark_stacks_on_it_and_kerns_across_it() {
    let dir = font_dir("build", &files());
    let (font, _) = load_font(&dir).expect("loads");
    let outlined = outline_font(&font, font.info.tolerance);
    let ttf = xglyph::otf::ttf(&outlined).expect("builds");
    let order = xglyph::otf::glyph_order(&outlined).expect("order");
    let names = ["n", "x", "tildeoverlaycomb", "acutecomb", "ringoverlay"];
    assert_eq!(gdef_classes(&ttf, &names, &order), [1, 1, 3, 3, 3]);

    let layout = Layout::with_ttf(&outlined, ttf).expect("shapes");
    let placed = |text: &str| -> Vec<(String, f64, f64, f64)> {
        let line = layout.line(text).expect("shapes");
        let glyphs = line.glyphs.iter();
        glyphs
            .map(|p| (layout.outline(p).name.clone(), p.x, p.y, p.advance))
            .collect()
    };
    let at = |name: &str, x: f64, y: f64, advance: f64| (name.to_string(), x, y, advance);
    // Not moved: its outline places it.
    assert_eq!(
        placed("n\u{334}"),
        [
            at("n", 0.0, 0.0, 500.0),
            at("tildeoverlaycomb", 500.0, 0.0, 0.0)
        ]
    );
    // The acute stacks on the overlay's `top` (mkmk), at (500 - 250, 800) less its `_top`,
    // not on the `n`'s `top` (which would put it at y = 0).
    assert_eq!(
        placed("n\u{334}\u{301}"),
        [
            at("n", 0.0, 0.0, 500.0),
            at("tildeoverlaycomb", 500.0, 0.0, 0.0),
            at("acutecomb", 250.0, 300.0, 0.0)
        ]
    );
    // The n-n kern (-50) skips the mark between them (IgnoreMarks).
    assert_eq!(placed("n\u{334}n")[2], at("n", 450.0, 0.0, 500.0));
    assert_eq!(placed("nn")[1], at("n", 450.0, 0.0, 500.0));
    assert_eq!(placed("xn")[1], at("n", 400.0, 0.0, 500.0));

    // The UFO lists every glyph's category (ufo2ft and fontc take GDEF classes from it).
    let files = xglyph::ufo::output_files(&outlined).expect("exports");
    let (_, lib) = files
        .iter()
        .find(|(p, _)| p.ends_with("lib.plist"))
        .expect("lib.plist");
    let lib = String::from_utf8(lib.clone()).expect("utf-8");
    let categories = "<key>public.openTypeCategories</key>\n\t<dict>\n\
                      \t\t<key>acutecomb</key>\n\t\t<string>mark</string>\n\
                      \t\t<key>n</key>\n\t\t<string>base</string>\n\
                      \t\t<key>ringoverlay</key>\n\t\t<string>mark</string>\n\
                      \t\t<key>tildeoverlaycomb</key>\n\t\t<string>mark</string>\n\
                      \t\t<key>x</key>\n\t\t<string>base</string>\n\t</dict>";
    assert!(lib.contains(categories), "{lib}");
    let _ = std::fs::remove_dir_all(&dir);
}
