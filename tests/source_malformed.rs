//! Malformed sources: exact diagnostics, CLI exit codes, and a no-panic mutation loop.

use std::path::Path;
use std::process::Command;

use xglyph::source::load_font;

fn diagnostics(case: &str) -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/malformed")
        .join(case);
    let diags = match load_font(&dir) {
        Ok((_, w)) => w,
        Err(d) => d,
    };
    diags
        .iter()
        .map(|d| {
            let file = d.path.file_name().map(|f| f.to_string_lossy().into_owned());
            let sev = match d.severity {
                xglyph::source::Severity::Error => "error",
                xglyph::source::Severity::Warning => "warning",
            };
            format!(
                "{}:{}:{}: {}: {}",
                file.unwrap_or_default(),
                d.line,
                d.col,
                sev,
                d.message
            )
        })
        .collect()
}

#[test]
fn malformed_cases_report_exact_positions() {
    let cases: &[(&str, &[&str])] = &[
        (
            "asc_desc",
            &["font.toml:3:12: error: `ascender` must be greater than `descender`"],
        ),
        (
            "bad_toml",
            &["a.toml:1:11: error: invalid TOML: extra `=`, expected nothing"],
        ),
        (
            "coincident",
            &["a.toml:4:11: error: point 0 coincides with point 2 before it"],
        ),
        (
            "cycle",
            &[
                "a.toml:7:8: error: component cycle: `a` uses `b`, which leads back to it",
                "b.toml:7:8: error: component cycle: `b` uses `a`, which leads back to it",
            ],
        ),
        (
            "dup_cp",
            &["b.toml:1:18: error: code point U+0041 is already mapped to `a`"],
        ),
        (
            "dup_name",
            &["b.toml:1:8: error: duplicate glyph name `A` (also in DIR/a.toml)"],
        ),
        (
            "empty_glyph",
            &[
                "a.toml:1:1: warning: glyph `a` is empty: no contours, no components and advance 0",
                "b.toml:2:11: error: invalid code point 0x110000",
            ],
        ),
        (
            "few_points",
            &["a.toml:4:10: error: a contour needs at least 3 points, found 2"],
        ),
        (
            "kern_unknown",
            &["kerning.toml:3:9: error: unknown glyph `V`"],
        ),
        (
            "missing_advance",
            &["a.toml:1:1: error: missing required key `advance`"],
        ),
        (
            "missing_base",
            &["a.toml:7:8: error: component base `zz` does not exist"],
        ),
        (
            "missing_family",
            &["font.toml:1:1: error: missing required key `family`"],
        ),
        (
            "nonfinite",
            &["a.toml:4:28: error: `y` must be a finite number"],
        ),
        ("s_range", &["a.toml:4:31: error: s = 2 is outside [-1, 1]"]),
        (
            "surrogate",
            &["a.toml:1:11: error: invalid code point 0xD800"],
        ),
        (
            "unknown_key",
            &[
                "a.toml:1:1: error: unknown key `advnce`; did you mean `advance`?",
                "a.toml:1:1: error: missing required key `advance`",
            ],
        ),
        (
            "upm",
            &["font.toml:2:16: error: `units_per_em` must be an integer in 16..16384"],
        ),
        (
            "wrong_type",
            &["a.toml:1:11: error: `advance` must be a number, found string"],
        ),
    ];
    assert!(cases.len() >= 15);
    for (case, expected) in cases {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/malformed")
            .join(case);
        let got: Vec<String> = diagnostics(case)
            .into_iter()
            .map(|s| s.replace(&dir.display().to_string(), "DIR"))
            .collect();
        let expected: Vec<String> = expected.iter().map(|s| s.to_string()).collect();
        assert_eq!(got, expected, "case {case}");
    }
}

#[test]
fn check_binary_exits_1_on_errors() {
    for case in ["cycle", "s_range", "bad_toml"] {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/malformed")
            .join(case);
        let out = Command::new(env!("CARGO_BIN_EXE_xglyph"))
            .arg("check")
            .arg(&dir)
            .output()
            .expect("run xglyph");
        assert_eq!(out.status.code(), Some(1), "case {case}");
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(stdout.contains(": error: "), "case {case}: {stdout}");
        assert!(stdout.contains("errors, "), "case {case}: {stdout}");
    }
}

const VALID_FONT: &str = "family = \"T\"\nunits_per_em = 1000\nascender = 800\ndescender = -200\nx_height = 500\ncap_height = 700\n";
const VALID_GLYPH: &str = "name = \"o\"\nunicode = [0x6F, 0x4F]\nadvance = 560\n\n[[contour]]\npoints = [[280, -12, -1], [520, 250, -1], [280, 512, -1], [40, 250, -1]]\n\n[[component]]\nbase = \"o\"\noffset = [1, 2.5]\n";

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
    std::fs::write(
        dir.join("kerning.toml"),
        "[[pair]]\nleft = \"o\"\nright = \".notdef\"\nvalue = -80\n",
    )
    .expect("write");
    let result = load_font(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    let (font, warnings) = result.expect("valid font loads");
    assert!(warnings.is_empty());
    assert_eq!(font.info.style, "Regular");
    assert_eq!(font.glyphs[0].name, ".notdef");
    assert_eq!(font.glyphs[1].unicodes, vec!['o', 'O']);
    assert_eq!(font.glyphs[1].contours[0].points.len(), 4);
    assert_eq!(font.kern("o", ".notdef"), -80.0);
}

#[test]
fn random_mutations_never_panic() {
    let dir = std::env::temp_dir().join(format!("xglyph-source-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("mkdir");
    std::fs::write(dir.join("font.toml"), VALID_FONT).expect("write");
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let alphabet = b"[]{}=,.\"\n -0123456789xyzabinfa_#";
    for _ in 0..300 {
        let mut bytes = VALID_GLYPH.as_bytes().to_vec();
        for _ in 0..(1 + next() % 4) {
            let len = bytes.len().max(1) as u64;
            let pos = (next() % len) as usize;
            let ch = alphabet[(next() % alphabet.len() as u64) as usize];
            match next() % 3 {
                0 if pos < bytes.len() => bytes[pos] = ch,
                1 if pos < bytes.len() => {
                    bytes.remove(pos);
                }
                _ => bytes.insert(pos.min(bytes.len()), ch),
            }
        }
        std::fs::write(dir.join("o.toml"), &bytes).expect("write");
        let _ = load_font(&dir);
    }
    let _ = std::fs::remove_dir_all(&dir);
}
