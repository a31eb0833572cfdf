//! `xglyph fmt`: canonical rewrite that keeps the model, idempotence, `--check`, refusal
//! on errors and on comments it would drop; and `xglyph check --format json`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use xglyph::source::load_font;

/// A fresh copy of a fixture folder in the temp dir.
fn copy(fixture: &str, tag: &str) -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join(fixture);
    let dst = std::env::temp_dir().join(format!("xglyph-fmt-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dst);
    std::fs::create_dir_all(&dst).expect("mkdir");
    for entry in std::fs::read_dir(&src).expect("fixture") {
        let path = entry.expect("entry").path();
        if path.is_file() {
            std::fs::copy(&path, dst.join(path.file_name().expect("name"))).expect("copy");
        }
    }
    dst
}

/// Every file of a folder, by name.
fn snapshot(dir: &Path) -> BTreeMap<String, String> {
    std::fs::read_dir(dir)
        .expect("dir")
        .map(|e| e.expect("entry").path())
        .map(|p| {
            let name = p.file_name().expect("name").to_string_lossy().into_owned();
            (name, std::fs::read_to_string(&p).expect("utf-8"))
        })
        .collect()
}

fn xglyph(args: &[&str], dir: &Path) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(args)
        .arg(dir)
        .output()
        .expect("run xglyph");
    assert!(!String::from_utf8_lossy(&out.stderr).contains("panicked"));
    out
}

/// File names printed one per line (full paths on stdout).
fn listed(out: &Output, dir: &Path) -> Vec<String> {
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| l.replace(&format!("{}/", dir.display()), ""))
        .collect()
}

/// load -> fmt -> load gives the same model; the second fmt changes nothing.
fn round_trip(fixture: &str, tag: &str, expect_changed: &[&str]) -> BTreeMap<String, String> {
    let dir = copy(fixture, tag);
    let names_before: Vec<String> = snapshot(&dir).into_keys().collect();
    let (before, _) = load_font(&dir).unwrap_or_else(|d| panic!("{fixture}: {d:?}"));
    let out = xglyph(&["fmt"], &dir);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(listed(&out, &dir), expect_changed);
    let (after, warnings) = load_font(&dir).unwrap_or_else(|d| panic!("formatted: {d:?}"));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(after, before);
    let formatted = snapshot(&dir);
    let names_after: Vec<String> = formatted.keys().cloned().collect();
    assert_eq!(
        names_after, names_before,
        "no file renamed, added or left behind"
    );
    let again = xglyph(&["fmt"], &dir);
    assert_eq!(again.status.code(), Some(0));
    assert_eq!(again.stdout, b"", "second fmt rewrote files");
    assert_eq!(snapshot(&dir), formatted);
    let check = xglyph(&["fmt", "--check"], &dir);
    assert_eq!(check.status.code(), Some(0));
    std::fs::remove_dir_all(&dir).expect("cleanup");
    formatted
}

#[test]
fn mini_round_trips_and_keeps_its_header_comment() {
    let original = snapshot(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini"));
    let formatted = round_trip(
        "tests/fixtures/mini",
        "mini",
        &[
            "A_.toml",
            "V_.toml",
            "_notdef.toml",
            "acutecomb.toml",
            "o.toml",
            "oacute.toml",
            "period.toml",
            "space.toml",
        ],
    );
    // font.toml and kerning.toml were already canonical (the header comment is kept).
    assert_eq!(formatted["font.toml"], original["font.toml"]);
    assert_eq!(formatted["kerning.toml"], original["kerning.toml"]);
    assert_eq!(
        formatted["space.toml"],
        "name = \"space\"\nunicode = 0x0020\nadvance = 260\n"
    );
}

#[test]
fn messy_round_trips_into_the_canonical_layout() {
    let formatted = round_trip(
        "tests/fixtures/messy",
        "messy",
        &[
            "font.toml",
            "a.toml",
            "b.toml",
            "space.toml",
            "kerning.toml",
        ],
    );
    assert_eq!(
        formatted["font.toml"],
        "# Messy on purpose: tests/source_fmt.rs formats a copy and checks that the model is the\n\
         # same before and after. Do not tidy this folder.\n\n\
         family = \"Messy Sans\"\nstyle = \"Regular\"\nunits_per_em = 1000\nascender = 800\n\
         descender = -200\nx_height = 500\ncap_height = 700\ntolerance = 0.25\n\
         designer = \"A. Person\"\n"
    );
    assert_eq!(
        formatted["b.toml"],
        "name = \"b\"\nunicode = [0x0062, 0x0042]\nadvance = 600\n\n\
         [[contour]]\npoints = [\n  [0, 0, 0],\n  [100, 0, 0],\n  [100, 700, 0],\n  [0, 700, 0],\n]\n\n\
         [[contour]]\npoints = [\n  [20, 20, 0.5],\n  [80, 20, 0.5],\n  [50, 60, 0.5],\n]\n\n\
         [[component]]\nbase = \"a\"\noffset = [10.5, 0]\n"
    );
    assert!(formatted["a.toml"].starts_with(
        "# a: keys out of order, floats written as 280.0 and -0.0, decimal code point, no name.\n\
         name = \"a\"\nunicode = 0x0061\nadvance = 560\n\n[[contour]]\npoints = [\n  [280, 0, -1],\n"
    ));
    assert_eq!(
        formatted["kerning.toml"],
        "[[pair]]\nleft = \"a\"\nright = \"b\"\nvalue = -10\n\n\
         [[pair]]\nleft = \"b\"\nright = \"a\"\nvalue = 5\n"
    );
}

#[test]
fn check_flag_lists_files_and_writes_nothing() {
    let dir = copy("tests/fixtures/messy", "check");
    let before = snapshot(&dir);
    let out = xglyph(&["fmt", "--check"], &dir);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        listed(&out, &dir),
        [
            "font.toml",
            "a.toml",
            "b.toml",
            "space.toml",
            "kerning.toml"
        ]
    );
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "fmt --check: 5 files are not formatted\n"
    );
    assert_eq!(snapshot(&dir), before);
    std::fs::remove_dir_all(&dir).expect("cleanup");
}

#[test]
fn sources_with_errors_are_not_touched() {
    let dir = copy("tests/malformed/glyph_several", "errors");
    let before = snapshot(&dir);
    let out = xglyph(&["fmt", "--force"], &dir);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    let want = format!(
        "{}:7:31: error: s = -1.5 is outside [-1, 1]\n",
        dir.join("g.toml").display()
    );
    assert!(stderr.contains(&want), "{stderr}");
    assert!(stderr.ends_with("fmt: the sources have errors; nothing was changed\n"));
    assert_eq!(out.stdout, b"");
    assert_eq!(snapshot(&dir), before);
    std::fs::remove_dir_all(&dir).expect("cleanup");
}

#[test]
fn comments_block_the_rewrite_unless_forced() {
    let dir = copy("tests/fixtures/messy", "comments");
    let b = snapshot(&dir)["b.toml"].clone();
    let b = b.replace("advance = 600\n", "advance = 600 # measured\n# keep me\n");
    std::fs::write(dir.join("b.toml"), &b).expect("write");
    let before = snapshot(&dir);
    let out = xglyph(&["fmt"], &dir);
    assert_eq!(out.status.code(), Some(1));
    let b_path = dir.join("b.toml").display().to_string();
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!(
            "{b_path}:5:15: error: fmt would drop this comment\n\
             {b_path}:6:1: error: fmt would drop this comment\n\
             fmt: only the comment block at the top of a file survives formatting; move these \
             comments there, or run `xglyph fmt --force` to drop them. Nothing was changed.\n"
        )
    );
    assert_eq!(snapshot(&dir), before, "a refused fmt writes nothing");
    let forced = xglyph(&["fmt", "--force"], &dir);
    assert_eq!(forced.status.code(), Some(0));
    let after = snapshot(&dir);
    assert!(!after["b.toml"].contains('#'));
    assert!(after["a.toml"].starts_with("# a: keys out of order"));
    std::fs::remove_dir_all(&dir).expect("cleanup");
}

#[test]
fn check_json_lists_diagnostics_and_counts() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/malformed/empty_glyph");
    let out = xglyph(&["check", "--format", "json"], &dir);
    assert_eq!(out.status.code(), Some(1));
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
    let expected = serde_json::json!({
        "diagnostics": [
            {
                "path": dir.join("a.toml").display().to_string(),
                "line": 1, "column": 1, "severity": "warning",
                "message": "glyph `a` is empty: no contours, no components and advance 0",
            },
            {
                "path": dir.join("b.toml").display().to_string(),
                "line": 2, "column": 11, "severity": "error",
                "message": "invalid code point 0x110000: the largest is 0x10FFFF",
            },
        ],
        "errors": 1,
        "warnings": 1,
    });
    assert_eq!(doc, expected);

    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/malformed/no_font_toml");
    let out = xglyph(&["check", "--format", "json"], &dir);
    assert_eq!(out.status.code(), Some(1));
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
    assert_eq!(doc["diagnostics"][0]["line"], serde_json::Value::Null);
    assert_eq!(doc["diagnostics"][0]["column"], serde_json::Value::Null);

    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/malformed/far_point");
    let out = xglyph(&["check", "--format", "json"], &dir);
    assert_eq!(out.status.code(), Some(0), "warnings only");
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
    assert_eq!(
        (doc["errors"].as_u64(), doc["warnings"].as_u64()),
        (Some(0), Some(1))
    );
    assert_eq!(doc["diagnostics"][0]["line"], 6);
    assert_eq!(doc["diagnostics"][0]["column"], 3);
}

#[test]
fn crlf_files_get_lf_line_ends() {
    let dir = copy("tests/fixtures/messy", "crlf");
    let crlf = "# the space\r\n\r\nname = 'space'\r\nunicode = 32\r\nadvance = 260\r\n";
    std::fs::write(dir.join("space.toml"), crlf).expect("write");
    let (before, _) = load_font(&dir).expect("loads");
    let out = xglyph(&["fmt"], &dir);
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        snapshot(&dir)["space.toml"],
        "# the space\n\nname = \"space\"\nunicode = 0x0020\nadvance = 260\n"
    );
    assert_eq!(load_font(&dir).expect("loads").0, before);
    std::fs::remove_dir_all(&dir).expect("cleanup");
}

/// A glyph file that is a link: fmt writes the formatted text to the link's target and
/// leaves the link a link (issue 13, item 20).
#[cfg(unix)]
#[test]
fn a_linked_source_is_formatted_through_the_link() {
    let plain = copy("tests/fixtures/messy", "link-plain");
    let linked = copy("tests/fixtures/messy", "link");
    let elsewhere = linked.with_extension("target");
    let _ = std::fs::remove_dir_all(&elsewhere);
    std::fs::create_dir_all(&elsewhere).expect("mkdir");
    let target = elsewhere.join("real-a.toml");
    std::fs::rename(linked.join("a.toml"), &target).expect("move");
    std::os::unix::fs::symlink(&target, linked.join("a.toml")).expect("link");

    let out = xglyph(&["fmt"], &plain);
    assert_eq!(out.status.code(), Some(0));
    let out = xglyph(&["fmt"], &linked);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        listed(&out, &linked),
        [
            "font.toml",
            "a.toml",
            "b.toml",
            "space.toml",
            "kerning.toml"
        ]
    );
    let link = std::fs::symlink_metadata(linked.join("a.toml")).expect("stat");
    assert!(link.file_type().is_symlink(), "the link was replaced");
    assert_eq!(
        std::fs::read_link(linked.join("a.toml")).expect("link"),
        target
    );
    let formatted = snapshot(&plain);
    assert_eq!(
        std::fs::read_to_string(&target).expect("target"),
        formatted["a.toml"]
    );
    assert_eq!(snapshot(&linked), formatted);
    for dir in [plain, linked, elsewhere] {
        std::fs::remove_dir_all(&dir).expect("cleanup");
    }
}
