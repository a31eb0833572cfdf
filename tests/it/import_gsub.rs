//! `xglyph import` of a font's substitutions (GSUB -> `features.fea`): the built font
//! shapes as the original does, in HarfBuzz.

use std::path::Path;

use xglyph::import::{import_font, ImportOptions};
use xglyph::source::emit::font_sources;
use xglyph::source::load_font;

/// A copy of Debian fonts-dejavu-core 2.37, and its layout subset: the characters of
/// [`CHARS`] and N'Ko (U+07C0–U+07FA, whose required feature ` RQD` feature syntax cannot
/// spell), and every glyph any feature reaches from them, made with
/// `pyftsubset DejaVuSans.ttf --unicodes=… --layout-features='*' --glyph-names
/// --notdef-outline --name-IDs='*' --name-languages='*' --legacy-kern --no-hinting`:
/// single, ligature, alternate and class-based chained contextual lookups, `locl` per
/// language, Arabic joining forms, `aalt`.
const DEJAVU: &str = "tests/fixtures/import/DejaVuSans.ttf";
const LAYOUT: &str = "tests/fixtures/import/DejaVuSans-layout.ttf";

/// The space, `!` and `?`, Latin, the Sami and Serbian letters `locl` changes, marks that
/// make `i` dotless (`ccmp`, chained contextual), `¡¿` (`case`), Arabic letters and marks
/// (joining forms, the lam-alef ligatures in `rlig`), Hebrew letters and points.
const CHARS: &str = "U+0020,U+0021,U+003F,A-Z,a-z,0-9,¡,¿,Ŋ,ŋ,б,г,д,п,т,U+0300-U+0308,\
                     U+0621-U+064A,U+064B-U+0652,U+0670,U+05D0-U+05EA,U+05B0-U+05BC,U+05C1,U+05C2";

/// The texts shaped, each in every language of `HB_SUBSTITUTIONS`.
const TEXTS: [&str; 10] = [
    "fijord office",
    "¡HOLA! ¿QUE?",
    "ŊAŊ ŋaŋ",
    "бгдпт",
    "i\u{307}\u{301} j\u{308}",
    "العربية كتاب لا إله",
    "بِسْمِ ٱللَّٰهِ",
    "שָׁלוֹם עֲרֵב",
    "0123456789",
    "ߒߞߏ ߞߊ߲ߜߍ",
];

/// For each text, language and feature set (`argv[4]`, JSON): whether the built font
/// (`argv[2]`) shapes to the same glyph names and clusters as the original (`argv[1]`),
/// and whether the original substituted anything (its glyphs differ from the characters'
/// own glyphs).
const HB_SUBSTITUTIONS: &str = r#"
import json, sys, uharfbuzz as hb
from fontTools.ttLib import TTFont
def load(path):
    tt = TTFont(path)
    return hb.Font(hb.Face(hb.Blob.from_file_path(path))), tt.getGlyphOrder(), tt.getBestCmap()
fonts = [load(p) for p in sys.argv[1:3]]
out = {"shaped": 0, "differ": [], "substituted": 0}
for text in sys.argv[3].split("|"):
    for lang in [None, "se", "sr", "mk", "ur", "tr"]:
        for feats in json.loads(sys.argv[4]):
            runs = []
            for font, order, _ in fonts:
                buf = hb.Buffer()
                buf.add_str(text)
                buf.guess_segment_properties()
                if lang:
                    buf.language = lang
                hb.shape(font, buf, feats)
                runs.append([(order[i.codepoint], i.cluster) for i in buf.glyph_infos])
            out["shaped"] += 1
            if runs[0] != runs[1]:
                out["differ"].append([text, lang, str(feats), str(runs[0]), str(runs[1])])
            plain = [fonts[0][2].get(ord(c), ".notdef") for c in text]
            if [name for name, _ in runs[0]] != plain:
                out["substituted"] += 1
print(json.dumps(out))
"#;

#[derive(serde::Deserialize)]
struct Shaped {
    shaped: usize,
    differ: Vec<Vec<Option<String>>>,
    substituted: usize,
}

/// Imports `font` (`glyphs`: a character subset), checks and builds the sources; the
/// import and the built TTF and OTF (`None` when HarfBuzz is not installed).
fn import_and_build(
    case: &str,
    font: &str,
    glyphs: Option<&str>,
) -> (xglyph::import::Imported, Option<[std::path::PathBuf; 2]>) {
    let data = std::fs::read(font).expect("the DejaVu fixtures");
    let opts = ImportOptions {
        glyphs: glyphs.map(|g| xglyph::import::font::parse_glyph_list(g).unwrap()),
        ..ImportOptions::default()
    };
    let imp = import_font(Path::new(font), &data, &opts).unwrap();
    let dir = std::env::temp_dir().join(format!("xglyph-gsub-{}-{case}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in font_sources(&imp.font) {
        std::fs::write(dir.join(name), text).unwrap();
    }
    assert!(dir.join("features.fea").is_file());
    let (_, warnings) = load_font(&dir).expect("the imported sources pass check");
    assert!(warnings.is_empty(), "{warnings:?}");
    let out = dir.join("out");
    let (code, _, stderr) =
        crate::common::cli::xglyph(&["build", dir.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    let harfbuzz = crate::common::tools::available(
        crate::common::tools::python_imports("uharfbuzz"),
        "uharfbuzz",
        "pip install uharfbuzz",
    );
    let built = ["DejaVuSans-Book.ttf", "DejaVuSans-Book.otf"].map(|f| out.join(f));
    (imp, harfbuzz.then_some(built))
}

fn shaped(original: &str, built: &Path, texts: &[&str], feature_sets: &str) -> Shaped {
    crate::common::tools::python_json(
        HB_SUBSTITUTIONS,
        &[&original, &built, &texts.join("|"), &feature_sets],
    )
}

fn unmapped(imp: &xglyph::import::Imported) -> Vec<&str> {
    let glyphs = imp.font.glyphs.iter().filter(|g| g.unicodes.is_empty());
    glyphs.map(|g| g.name.as_str()).collect()
}

#[test]
fn a_fonts_substitutions_come_in_and_the_built_font_shapes_as_the_original() {
    let (imp, built) = import_and_build("whole", LAYOUT, None);
    let features = imp.font.features.as_ref().expect("the GSUB comes in");
    // Every glyph of the font but `.notdef` comes in, with every rule on them, except 26
    // that are only components of others (xglyph resolves components into outlines).
    assert_eq!(imp.font.glyphs.len(), 487 - 26);
    for name in [
        "dotlessi",
        "Eng.alt",
        "uniF6C5",
        "exclamdown.case",
        "uniFEDF",
        "uniFEFB",
    ] {
        assert!(unmapped(&imp).contains(&name), "{name} is not imported");
        assert!(features.text.contains(name), "{name} is in no rule");
    }
    // N'Ko's required feature comes in under a tag feature syntax can spell.
    let note: Vec<&String> = imp
        .report
        .notes
        .iter()
        .filter(|n| n.contains("GSUB"))
        .collect();
    assert_eq!(
        note,
        [
            "GSUB: the required feature ` RQD` comes in as `RQD` (feature syntax cannot spell \
          its tag; shapers apply a required feature whatever its tag)"
        ]
    );
    let Some(built) = built else { return };
    // `aalt` is left out of the comparison: fea-rs, as feaLib, puts its lookups first,
    // where DejaVu has them after `liga`, so with it on `ffl` becomes `ff` `l.alt`.
    let sets = r#"[{}, {"liga": false}, {"case": true}, {"dlig": true}, {"salt": true},
                   {"hlig": true}, {"fina": true}, {"medi": true}]"#;
    for font in &built {
        let shaped = shaped(LAYOUT, font, &TEXTS, sets);
        assert_eq!(shaped.shaped, TEXTS.len() * 6 * 8);
        assert!(
            shaped.differ.is_empty(),
            "{font:?}: {:?}",
            &shaped.differ[..1]
        );
        // The texts exercise the substitutions: the original substitutes in most of them
        // (without the GSUB, every one of these would differ).
        assert!(shaped.substituted >= 200, "{}", shaped.substituted);
    }
}

#[test]
fn a_character_subset_takes_the_glyphs_default_shaping_reaches() {
    let (imp, built) = import_and_build("subset", DEJAVU, Some(CHARS));
    // Default shaping's ligatures, dotless forms, localised and joining forms come in; the
    // optional features' glyphs (`case`, `salt`, `dlig`) do not, as with pyftsubset.
    let reached = unmapped(&imp);
    for name in ["dotlessi", "Eng.alt", "uniF6C5", "fi", "uniFEDF", "uniFEFB"] {
        assert!(reached.contains(&name), "{name} is not imported");
    }
    for name in ["exclamdown.case", "I.alt", "uni2121"] {
        assert!(!reached.contains(&name), "{name} is imported");
    }
    let note = imp.report.notes.iter().find(|n| n.starts_with("GSUB"));
    assert!(note.is_none(), "{note:?}");
    let Some(built) = built else { return };
    for font in &built {
        // The texts of CHARS' characters (not N'Ko).
        let shaped = shaped(DEJAVU, font, &TEXTS[..9], r#"[{}, {"liga": false}]"#);
        assert!(
            shaped.differ.is_empty(),
            "{font:?}: {:?}",
            &shaped.differ[..1]
        );
        assert!(shaped.substituted >= 60, "{}", shaped.substituted);
    }
}

#[test]
fn a_mutated_gsub_imports_or_is_refused_naming_its_table() {
    // The layout fixture with bytes of its GSUB or GDEF overwritten (a fixed pseudo-random
    // sequence): each import either succeeds with feature code fea-rs compiles, or fails
    // naming the damaged table; none panics. (Found this way: tags that start with a digit.)
    let original = std::fs::read(LAYOUT).unwrap();
    let table = |tag: &[u8; 4]| {
        let count = usize::from(u16::from_be_bytes([original[4], original[5]]));
        let record = (0..count)
            .map(|i| 12 + 16 * i)
            .find(|&r| &original[r..r + 4] == tag)
            .unwrap();
        let at = |k: usize| u32::from_be_bytes(original[k..k + 4].try_into().unwrap()) as usize;
        (at(record + 8), at(record + 12))
    };
    let tables = [table(b"GSUB"), table(b"GSUB"), table(b"GDEF")];
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = |n: usize| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 33) as usize) % n
    };
    let opts = ImportOptions {
        glyphs: Some(xglyph::import::font::parse_glyph_list("f,i,l,ŋ,б,U+0644,U+0627").unwrap()),
        ..ImportOptions::default()
    };
    let (mut imported, mut refused) = (0, 0);
    for _ in 0..60 {
        let mut data = original.clone();
        let (offset, length) = tables[next(3)];
        for _ in 0..1 + next(6) {
            let reach = if next(2) == 0 {
                length.min(400)
            } else {
                length
            };
            data[offset + next(reach)] = next(256) as u8;
        }
        match import_font(Path::new(LAYOUT), &data, &opts) {
            Ok(imp) => {
                imported += 1;
                let refused_note = imp
                    .report
                    .notes
                    .iter()
                    .find(|n| n.contains("does not compile"));
                assert!(refused_note.is_none(), "{refused_note:?}");
                if let Some(features) = &imp.font.features {
                    let names: Vec<&str> =
                        imp.font.glyphs.iter().map(|g| g.name.as_str()).collect();
                    let errors = xglyph::otf::check_features(features, &names);
                    assert!(errors.is_empty(), "{errors:?}");
                }
            }
            Err(e) => {
                refused += 1;
                assert!(
                    ["GSUB", "GDEF", "GPOS"]
                        .iter()
                        .any(|t| e.message.starts_with(&format!("damaged {t} table: "))),
                    "{e}"
                );
            }
        }
    }
    // Both outcomes occur.
    assert!(
        imported >= 10 && refused >= 10,
        "{imported} imported, {refused} refused"
    );
}
