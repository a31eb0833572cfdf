//! Malformed sources: for every folder under `tests/malformed/`, the exact diagnostics
//! (file, line, column, message), and the CLI's exit code without a panic; plus a
//! no-panic loop over mutated and random inputs.

use std::path::{Path, PathBuf};
use std::process::Command;

use xglyph::source::{emit, load_font, load_glyph_text, load_info_text};

/// Every malformed case with its expected diagnostics, paths relative to the case folder
/// (`.` for the folder itself).
const CASES: &[(&str, &[&str])] = &[
    (
        "advance_range",
        &[
            "a.toml:1:11: error: `advance` = 70000 is more than 32767 font units, the largest advance TrueType's `hmtx` table holds",
            "b.toml:1:11: error: `advance` = 1e19 is more than 32767 font units, the largest advance TrueType's `hmtx` table holds",
        ],
    ),
    ("asc_desc", &["font.toml:3:12: error: `ascender` must be greater than `descender`"]),
    ("bad_toml", &["a.toml:1:11: error: invalid TOML: extra `=`, expected nothing"]),
    ("coincident", &["a.toml:4:11: error: point 0 coincides with point 2 before it"]),
    (
        "component_doubling",
        &[
            "b15.toml:5:8: error: with component `b14` (16384 contours, 49152 points), glyph `b15` has at least 32768 contours; a TrueType glyph holds at most 32766",
        ],
    ),
    (
        "contour_type",
        &[
            "a.toml:2:12: error: `contour` entries must be tables, found integer",
            "a.toml:2:15: error: `contour` entries must be tables, found integer",
        ],
    ),
    (
        "coord_range",
        &[
            "a.toml:3:23: error: `x` = 40000 is outside -16384..16384 font units: TrueType stores 16-bit coordinates, and curves may bulge past their points",
        ],
    ),
    (
        "cycle",
        &[
            "a.toml:7:8: error: component cycle: `a` uses `b`, which leads back to it",
            "b.toml:7:8: error: component cycle: `b` uses `a`, which leads back to it",
        ],
    ),
    (
        "descender_positive",
        &["font.toml:4:13: error: `descender` must be 0 or negative (y up: below the baseline), found 200"],
    ),
    ("dup_cp", &["b.toml:1:18: error: code point U+0041 is already mapped to `a`"]),
    ("dup_name", &["b.toml:1:8: error: duplicate glyph name `A` (also in DIR/a.toml)"]),
    (
        "empty_dir",
        &[
            ".: warning: no glyph files: add one `<glyph>.toml` per glyph next to `font.toml`",
            "font.toml: error: missing `font.toml`: a font directory needs one with at least `family`, `units_per_em`, `ascender`, `descender`, `x_height` and `cap_height`",
        ],
    ),
    (
        "empty_glyph",
        &[
            "a.toml:1:1: warning: glyph `a` is empty: no contours, no components and advance 0",
            "b.toml:2:11: error: invalid code point 0x110000: the largest is 0x10FFFF",
        ],
    ),
    ("empty_name", &["a.toml:1:8: error: `name` must not be empty; remove it to use the file name"]),
    (
        "family_length",
        &[
            "font.toml:1:10: error: `family` and `style` are 250 bytes together; at most 240, so that the output file name `<family>-<style>.ttf` fits the 255-byte limit of file systems",
        ],
    ),
    (
        "far_point",
        &["a.toml:6:3: warning: point [5000, 0] is 4500 units outside the glyph box x 0..500, y -200..800 (more than 2 em); 1 more point of this contour too"],
    ),
    ("few_points", &["a.toml:4:10: error: a contour needs at least 3 points, found 2"]),
    (
        "flat_decimals",
        &["a.toml:4:10: error: contour encloses no area: its 4 points lie on one straight line"],
    ),
    ("font_bad_toml", &["font.toml:1:12: error: invalid TOML: invalid basic string, expected `\"`"]),
    (
        "font_several",
        &[
            "font.toml:3:1: error: unknown key `famly`; did you mean `family`?",
            "font.toml:3:1: error: missing required key `x_height`; add a line such as `x_height = 500`",
            "font.toml:3:1: error: missing required key `cap_height`; add a line such as `cap_height = 700`",
            "font.toml:4:16: error: `units_per_em` must be an integer, found float",
            "font.toml:5:12: error: `ascender` must be a number, found string",
            "font.toml:7:13: error: `tolerance` must be positive (font units), found 0",
        ],
    ),
    (
        "glyph_name_rule",
        &[
            "a.toml:1:8: error: glyph name `a,b` contains `,`; glyph names are 1 to 63 characters from A-Z a-z 0-9 . _ (the OpenType `post` rule)",
            "c.toml:1:8: error: glyph name `1st` starts with a digit; glyph names are 1 to 63 characters from A-Z a-z 0-9 . _ (the OpenType `post` rule), not starting with a digit",
            "d.toml:1:8: error: glyph name `xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx` has 64 characters; glyph names are 1 to 63 characters from A-Z a-z 0-9 . _ (the OpenType `post` rule)",
            "my-glyph.toml: error: glyph name `my-glyph` (from the file name) contains `-`; glyph names are 1 to 63 characters from A-Z a-z 0-9 . _ (the OpenType `post` rule); add a `name` line that follows it",
        ],
    ),
    (
        "glyph_several",
        &[
            "g.toml:2:12: error: code point U+0041 is already mapped to `a`",
            "g.toml:2:18: error: invalid code point 0xDFFF: surrogates 0xD800..0xDFFF are not characters",
            "g.toml:4:1: error: unknown key `width`; expected one of `name`, `unicode`, `advance`, `contour`, `component`",
            "g.toml:7:31: error: s = -1.5 is outside [-1, 1]",
            "g.toml:7:49: error: `s` must be a finite number",
            "g.toml:10:46: error: a point must be [x, y, s], found 2 values",
            "g.toml:13:8: error: component base `nothing` does not exist",
            "g.toml:14:1: error: unknown key `offst`; did you mean `offset`?",
        ],
    ),
    (
        "huge_integer",
        &[
            "a.toml:1:11: error: `advance` = 100000000000000000000 does not fit a TOML integer (64-bit)",
        ],
    ),
    ("kern_dup", &["kerning.toml:11:1: error: duplicate kerning pair `a` `b` (first written at line 1)"]),
    (
        "kern_missing",
        &[
            "kerning.toml:1:1: error: missing required key `value`; add a line such as `value = -60`",
            "kerning.toml:3:1: error: unknown key `rigth`; did you mean `right`?",
        ],
    ),
    (
        "kern_range",
        &[
            "kerning.toml:4:9: error: `value` = 40000 is outside -32768..32767 font units (kerning is 16-bit in the `kern` and `GPOS` tables)",
            "kerning.toml:9:9: error: `value` = -1e308 is outside -32768..32767 font units (kerning is 16-bit in the `kern` and `GPOS` tables)",
        ],
    ),
    ("kern_unknown", &["kerning.toml:3:9: error: unknown glyph `V`"]),
    ("kern_value", &["kerning.toml:4:9: error: `value` must be a number, found string"]),
    (
        "metric_range",
        &[
            "font.toml:3:12: error: `ascender` = 40000 is outside -32768..32767 font units (a 16-bit field of the `hhea` and `OS/2` tables)",
            "font.toml:6:14: error: `cap_height` = 1e19 is outside -32768..32767 font units (a 16-bit field of the `hhea` and `OS/2` tables)",
            "font.toml:7:13: error: `tolerance` must be at most 1000 font units, found 5000 (at that distance the outlines need not resemble the glyphs)",
        ],
    ),
    (
        "missing_advance",
        &["a.toml:3:1: error: missing required key `advance`; add a line such as `advance = 500`"],
    ),
    ("missing_base", &["a.toml:7:8: error: component base `zz` does not exist"]),
    (
        "missing_family",
        &["font.toml:1:1: error: missing required key `family`; add a line such as `family = \"My Sans\"`"],
    ),
    (
        "missing_points",
        &[
            "a.toml:7:1: error: unknown key `point`; did you mean `points`?",
            "a.toml:9:1: error: missing required key `points`; add a line such as `points = [[0, 0, 0], [100, 0, 0], [50, 100, 0]]`",
        ],
    ),
    ("negative_advance", &["a.toml:1:11: error: `advance` must not be negative, found -500"]),
    (
        "no_font_toml",
        &["font.toml: error: missing `font.toml`: a font directory needs one with at least `family`, `units_per_em`, `ascender`, `descender`, `x_height` and `cap_height`"],
    ),
    ("nonfinite", &["a.toml:4:28: error: `y` must be a finite number"]),
    ("not_utf8", &["a.toml:1:12: error: file is not valid UTF-8 (byte 0xE9); save it as UTF-8"]),
    ("offset_len", &["a.toml:8:10: error: `offset` must be [x, y], found 3 values"]),
    (
        "offset_range",
        &[
            "b.toml:4:11: error: `x` = 1e308 is outside -16384..16384 font units: TrueType stores 16-bit coordinates, and curves may bulge past their points",
            "b.toml:4:18: error: `y` = 1e308 is outside -16384..16384 font units: TrueType stores 16-bit coordinates, and curves may bulge past their points",
            "c.toml:3:8: error: component `a` at offset [16300, 0] reaches x = 16400, outside -16384..16384 font units: TrueType stores 16-bit coordinates",
        ],
    ),
    (
        "out_and_back",
        &["a.toml:4:10: error: contour encloses no area: it runs out and back along itself"],
    ),
    (
        "overflow_triangle",
        &[
            "a.toml:3:23: error: `x` = 1e308 is outside -16384..16384 font units: TrueType stores 16-bit coordinates, and curves may bulge past their points",
            "a.toml:3:41: error: `y` = 1e308 is outside -16384..16384 font units: TrueType stores 16-bit coordinates, and curves may bulge past their points",
        ],
    ),
    ("point_four", &["a.toml:4:35: error: a point must be [x, y, s], found 4 values"]),
    ("point_string", &["a.toml:4:23: error: `x` must be a number, found string"]),
    ("point_two", &["a.toml:4:22: error: a point must be [x, y, s], found 2 values"]),
    ("s_range", &["a.toml:4:31: error: s = 2 is outside [-1, 1]"]),
    ("self_component", &["a.toml:7:8: error: component cycle: `a` uses `a`, which leads back to it"]),
    (
        "surrogate",
        &["a.toml:1:11: error: invalid code point 0xD800: surrogates 0xD800..0xDFFF are not characters"],
    ),
    (
        "text_length",
        &["font.toml:7:13: error: `copyright` is 6000 UTF-16 code units long; at most 5000 fit the font's `name` table"],
    ),
    ("tolerance", &["font.toml:7:13: error: `tolerance` must be positive (font units), found -0.5"]),
    (
        "tolerance_tiny",
        &["font.toml:7:13: error: `tolerance` must be at least 0.0001 font units, found 0.00000001 (no font grid is that fine)"],
    ),
    ("unicode_big", &["a.toml:1:18: error: invalid code point 0x110000: the largest is 0x10FFFF"]),
    ("unicode_float", &["a.toml:1:11: error: `unicode` must be an integer, found float"]),
    ("unicode_negative", &["a.toml:1:11: error: invalid code point -65: code points are 0x0..0x10FFFF"]),
    // A misspelt required key: one error, no "missing `advance`".
    ("unknown_key", &["a.toml:1:1: error: unknown key `advnce`; did you mean `advance`?"]),
    (
        "unknown_key_nomatch",
        &["a.toml:1:1: error: unknown key `weight`; expected one of `name`, `unicode`, `advance`, `contour`, `component`"],
    ),
    ("upm", &["font.toml:2:16: error: `units_per_em` must be an integer in 16..16384"]),
    ("wrong_type", &["a.toml:1:11: error: `advance` must be a number, found string"]),
    (
        "zero_area",
        &["a.toml:4:10: error: contour encloses no area: its 3 points lie on one straight line"],
    ),
];

fn case_dir(case: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/malformed")
        .join(case)
}

/// The diagnostics of a case as `file:line:col: severity: message` (`file:` only when the
/// diagnostic has no position), with paths relative to the case folder.
fn diagnostics(dir: &Path) -> Vec<String> {
    let diags = match load_font(dir) {
        Ok((_, w)) => w,
        Err(d) => d,
    };
    diags
        .iter()
        .map(|d| {
            let rel = d
                .path
                .strip_prefix(dir)
                .unwrap_or(&d.path)
                .display()
                .to_string();
            let rel = if rel.is_empty() { ".".to_string() } else { rel };
            let place = if d.has_position() {
                format!("{rel}:{}:{}", d.line, d.col)
            } else {
                rel
            };
            let text = format!("{place}: {}: {}", d.severity.as_str(), d.message);
            text.replace(&dir.display().to_string(), "DIR")
        })
        .collect()
}

#[test]
fn every_case_folder_is_listed_and_there_are_at_least_30() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/malformed");
    let mut folders: Vec<String> = std::fs::read_dir(&root)
        .expect("tests/malformed")
        .filter_map(|e| e.ok())
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    folders.sort();
    let listed: Vec<&str> = CASES.iter().map(|(c, _)| *c).collect();
    assert_eq!(folders, listed);
    assert!(CASES.len() >= 30, "{} cases", CASES.len());
}

#[test]
fn malformed_cases_report_exact_positions() {
    for (case, expected) in CASES {
        let got = diagnostics(&case_dir(case));
        assert_eq!(got, *expected, "case {case}");
    }
}

/// The binary prints every expected line with the folder's path in front, exits 1 when
/// there is an error (0 for warnings only) and never panics.
#[test]
fn check_binary_prints_the_same_and_exits_1_on_errors() {
    for (case, expected) in CASES {
        let dir = case_dir(case);
        let out = Command::new(env!("CARGO_BIN_EXE_xglyph"))
            .arg("check")
            .arg(&dir)
            .output()
            .expect("run xglyph");
        let stdout = String::from_utf8_lossy(&out.stdout);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("panicked"), "case {case}: {stderr}");
        let errors = expected.iter().filter(|e| e.contains(": error: ")).count();
        let want_code = if errors > 0 { 1 } else { 0 };
        assert_eq!(out.status.code(), Some(want_code), "case {case}");
        for line in *expected {
            let (rel, rest) = line.split_once(':').expect("file: prefix");
            let path = if rel == "." {
                dir.clone()
            } else {
                dir.join(rel)
            };
            let full =
                format!("{}:{rest}", path.display()).replace("DIR", &dir.display().to_string());
            assert!(
                stdout.contains(&full),
                "case {case}: missing {full}\n{stdout}"
            );
        }
        let warnings = expected.len() - errors;
        let noun =
            |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
        let summary = format!(
            "{}, {}",
            noun(errors, "error", "errors"),
            noun(warnings, "warning", "warnings")
        );
        assert!(
            stdout.ends_with(&format!("{summary}\n")),
            "case {case}: {stdout}"
        );
    }
}

#[test]
fn check_caret_points_at_the_column() {
    let dir = case_dir("s_range");
    let out = Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .arg("check")
        .arg(&dir)
        .output()
        .expect("run xglyph");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(
        lines[1..],
        [
            "  | points = [[0, 0, 0], [100, 0, 2], [100, 100, 0]]",
            "  |                               ^",
            "1 error, 0 warnings",
        ]
    );
}

const VALID_FONT: &str = "family = \"T\"\nunits_per_em = 1000\nascender = 800\ndescender = -200\nx_height = 500\ncap_height = 700\n";
const VALID_GLYPH: &str = "name = \"o\"\nunicode = [0x6F, 0x4F]\nadvance = 560\n\n[[contour]]\npoints = [[280, -12, -1], [520, 250, -1], [280, 512, -1], [40, 250, -1]]\n\n[[component]]\nbase = \"o\"\noffset = [1, 2.5]\n";
const VALID_KERNING: &str = "[[pair]]\nleft = \"o\"\nright = \".notdef\"\nvalue = -80\n";

#[test]
fn valid_font_loads() {
    let dir = std::env::temp_dir().join(format!("xglyph-source-valid-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("mkdir");
    std::fs::write(dir.join("font.toml"), VALID_FONT).expect("write");
    std::fs::write(
        dir.join("o.toml"),
        VALID_GLYPH.replace("[[component]]\nbase = \"o\"\noffset = [1, 2.5]\n", ""),
    )
    .expect("write");
    std::fs::write(
        dir.join("_notdef.toml"),
        "name = \".notdef\"\nadvance = 500\n",
    )
    .expect("write");
    std::fs::write(dir.join(".o.toml.swp.toml"), "not = [toml").expect("write");
    std::fs::write(dir.join("kerning.toml"), VALID_KERNING).expect("write");
    let result = load_font(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    let (font, warnings) = result.expect("valid font loads");
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(font.info.style, "Regular");
    assert_eq!(font.info.tolerance, 0.5);
    assert_eq!(font.glyphs.len(), 2, "dot files are ignored");
    assert_eq!(font.glyphs[0].name, ".notdef");
    assert_eq!(font.glyphs[1].unicodes, vec!['o', 'O']);
    assert_eq!(font.glyphs[1].contours[0].points().len(), 4);
    assert_eq!(font.kern("o", ".notdef"), -80.0);
}

/// A tiny deterministic generator (xorshift64), so the loop is the same on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }

    /// `text` with 1 to 4 bytes replaced, removed or inserted from a TOML-ish alphabet.
    fn mutate(&mut self, text: &str) -> Vec<u8> {
        let alphabet = b"[]{}=,.\"'\n -+0123456789xyzabeinfa_#";
        let mut bytes = text.as_bytes().to_vec();
        for _ in 0..1 + self.below(4) {
            let pos = self.below(bytes.len());
            let ch = alphabet[self.below(alphabet.len())];
            match self.below(3) {
                0 if pos < bytes.len() => bytes[pos] = ch,
                1 if pos < bytes.len() => {
                    bytes.remove(pos);
                }
                _ => bytes.insert(pos.min(bytes.len()), ch),
            }
        }
        bytes
    }
}

/// Mutated glyph, font and kerning files, and random byte strings: the loaders never panic,
/// and whenever a mutated glyph loads, its canonical text loads back to the same glyph.
#[test]
fn random_mutations_never_panic() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let label = Path::new("o.toml");
    let mut loaded = 0;
    for _ in 0..2000 {
        let bytes = rng.mutate(VALID_GLYPH);
        let Ok(text) = String::from_utf8(bytes) else {
            continue;
        };
        if let Ok((glyph, _)) = load_glyph_text(label, &text) {
            loaded += 1;
            let again = load_glyph_text(label, &emit::glyph_toml(&glyph));
            assert_eq!(again.map(|(g, _)| g).as_ref(), Ok(&glyph), "{text}");
        }
        let font = String::from_utf8(rng.mutate(VALID_FONT)).unwrap_or_default();
        if let Ok((info, _)) = load_info_text(Path::new("font.toml"), &font) {
            let again = load_info_text(Path::new("font.toml"), &emit::font_toml(&info));
            assert_eq!(again.map(|(i, _)| i).as_ref(), Ok(&info), "{font}");
        }
    }
    // Some mutations keep the glyph valid (a digit changed), so the round trip ran.
    assert!(loaded > 100, "{loaded} mutated glyphs loaded");
    for _ in 0..1000 {
        let len = rng.below(200);
        let bytes: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
        let text = String::from_utf8_lossy(&bytes);
        let _ = load_glyph_text(label, &text);
        let _ = load_info_text(Path::new("font.toml"), &text);
    }
    // Whole folders, so the checks across files and kerning.toml run too.
    let dir = std::env::temp_dir().join(format!("xglyph-source-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("mkdir");
    std::fs::write(dir.join("font.toml"), VALID_FONT).expect("write");
    std::fs::write(
        dir.join("_notdef.toml"),
        "name = \".notdef\"\nadvance = 500\n",
    )
    .expect("write");
    for i in 0..200 {
        std::fs::write(dir.join("o.toml"), rng.mutate(VALID_GLYPH)).expect("write");
        let kerning = if i % 2 == 0 {
            rng.mutate(VALID_KERNING)
        } else {
            (0..rng.below(64)).map(|_| rng.next() as u8).collect()
        };
        std::fs::write(dir.join("kerning.toml"), kerning).expect("write");
        let _ = load_font(&dir);
    }
    let _ = std::fs::remove_dir_all(&dir);
}
