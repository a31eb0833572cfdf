//! Malformed sources: for every folder under `tests/malformed/`, the exact diagnostics
//! (file, line, column, message), and the CLI's exit code without a panic; plus a
//! no-panic loop over mutated and random inputs.

use std::path::{Path, PathBuf};
use std::process::Command;

use xglyph::source::{emit, load_font, load_glyph_text, load_info_text};

/// The folder of the malformed cases, one folder a case.
fn malformed_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/malformed")
}

fn case_dir(case: &str) -> PathBuf {
    malformed_root().join(case)
}

/// Every case folder (sorted) with the diagnostics it must give, read from its
/// `expected.txt`: one `file:line:col: severity: message` a line (`file:` alone when the
/// diagnostic has no position), paths relative to the case folder (`.` for the folder
/// itself, `DIR` for its path in a message); lines starting with `#` are comments.
fn cases() -> Vec<(String, Vec<String>)> {
    let mut folders: Vec<String> = std::fs::read_dir(malformed_root())
        .expect("tests/malformed")
        .filter_map(|e| e.ok())
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    folders.sort();
    folders
        .into_iter()
        .map(|case| {
            let path = case_dir(&case).join("expected.txt");
            let text = std::fs::read_to_string(&path)
                .unwrap_or_else(|e| panic!("case {case}: {} ({e})", path.display()));
            let expected = text
                .lines()
                .filter(|line| !line.starts_with('#'))
                .map(str::to_owned)
                .collect();
            (case, expected)
        })
        .collect()
}

/// `xglyph check <dir>`.
fn check(dir: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .arg("check")
        .arg(dir)
        .output()
        .expect("run xglyph")
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
fn every_case_folder_has_its_diagnostics_and_there_are_at_least_30() {
    let cases = cases();
    for (case, expected) in &cases {
        assert!(
            !expected.is_empty(),
            "case {case}: expected.txt lists nothing"
        );
    }
    assert!(cases.len() >= 30, "{} cases", cases.len());
}

#[test]
fn malformed_cases_report_exact_positions() {
    for (case, expected) in cases() {
        let got = diagnostics(&case_dir(&case));
        assert_eq!(got, expected, "case {case}");
    }
}

/// The binary prints every expected line with the folder's path in front, exits 1 when
/// there is an error (0 for warnings only) and never panics.
#[test]
fn check_binary_prints_the_same_and_exits_1_on_errors() {
    for (case, expected) in cases() {
        let dir = case_dir(&case);
        let out = check(&dir);
        let stdout = String::from_utf8_lossy(&out.stdout);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("panicked"), "case {case}: {stderr}");
        let errors = expected.iter().filter(|e| e.contains(": error: ")).count();
        let want_code = if errors > 0 { 1 } else { 0 };
        assert_eq!(out.status.code(), Some(want_code), "case {case}");
        for line in &expected {
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
    let out = check(&case_dir("s_range"));
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
