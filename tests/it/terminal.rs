//! Output hygiene (issue 13, item 18): control characters in family names, file names and
//! source lines are printed as `\u{..}` escapes by every command, never raw.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A copy of the mini font whose family name holds a terminal title sequence, a bell and a
/// screen clear, in a scratch folder.
fn hostile_font(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("terminal-{name}"));
    let _ = fs::remove_dir_all(&dir);
    let font = dir.join("font");
    fs::create_dir_all(&font).unwrap();
    let mini = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini");
    for entry in fs::read_dir(mini).unwrap() {
        let path = entry.unwrap().path();
        fs::copy(&path, font.join(path.file_name().unwrap())).unwrap();
    }
    let info = fs::read_to_string(font.join("font.toml")).unwrap();
    let info = info.replace(
        "family = \"Mini Test\"",
        "family = \"A\\u001b]0;pwned\\u0007\\u001b[2J\"",
    );
    fs::write(font.join("font.toml"), info).unwrap();
    font
}

fn run(args: &[&Path]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(args)
        .output()
        .expect("xglyph runs")
}

/// Neither stream holds a control character other than newline.
fn assert_clean(out: &Output) {
    for (stream, bytes) in [("stdout", &out.stdout), ("stderr", &out.stderr)] {
        let text = String::from_utf8_lossy(bytes);
        let bad: Vec<char> = text
            .chars()
            .filter(|&c| c.is_control() && c != '\n')
            .collect();
        assert!(bad.is_empty(), "{stream} holds {bad:?}: {text}");
    }
}

#[test]
fn build_escapes_the_family_name() {
    let font = hostile_font("build");
    let out = font.with_file_name("out");
    let result = run(&[Path::new("build"), &font, Path::new("-o"), &out]);
    assert_eq!(result.status.code(), Some(0));
    assert_clean(&result);
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert_eq!(
        stdout.lines().next(),
        Some("built A\\u{1b}]0;pwned\\u{7}\\u{1b}[2J Regular: 8 glyphs, 12 contours, 82 segments")
    );
}

#[test]
fn file_names_and_source_lines_are_escaped_in_check_fmt_svg_and_render() {
    let font = hostile_font("names");
    let bad = font.join("bad\u{1b}[31m.toml");
    fs::write(&bad, "advance = \"wide\u{7}\"\n").unwrap();
    let result = run(&[Path::new("check"), &font]);
    assert_eq!(result.status.code(), Some(1));
    assert_clean(&result);
    let shown = format!("{}/bad\\u{{1b}}[31m.toml", font.display());
    assert_eq!(
        String::from_utf8_lossy(&result.stdout)
            .lines()
            .take(2)
            .collect::<Vec<_>>(),
        [
            format!(
                "{shown}:1:16: error: invalid TOML: invalid basic string, expected \
                 non-double-quote visible characters, `\\`"
            ),
            "  | advance = \"wide\\u{7}\"".to_string(),
        ]
    );

    // The same file, valid: fmt lists it by its name. (It needs a `name` line: a glyph
    // name taken from this file name would break the glyph-name rule.)
    fs::write(&bad, "name = \"bad\"\nadvance   = 100\n").unwrap();
    let result = run(&[Path::new("fmt"), &font]);
    assert_eq!(result.status.code(), Some(0));
    assert_clean(&result);
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(stdout.lines().any(|l| l == shown), "{stdout}");

    // An output folder with a bell in its name.
    let out = font.with_file_name("out\u{7}");
    let shown_out = format!("{}\\u{{7}}", font.with_file_name("out").display());
    let result = run(&[Path::new("svg"), &font, Path::new("-o"), &out]);
    assert_eq!(result.status.code(), Some(0));
    assert_clean(&result);
    assert_eq!(
        String::from_utf8_lossy(&result.stdout),
        format!("wrote 10 files to {shown_out} (SVG font and 9 glyph SVGs)\n")
    );
    let result = run(&[
        Path::new("render"),
        &font,
        Path::new("-o"),
        &out,
        Path::new("--only"),
        Path::new("sheet"),
    ]);
    assert_eq!(result.status.code(), Some(0));
    assert_clean(&result);
    // The fits come from the cache `svg` left in OUT; its path is escaped too.
    assert_eq!(
        String::from_utf8_lossy(&result.stdout),
        format!(
            "wrote {shown_out}/sheet.png\n\
             refitted 0 contours; 12 fits from the cache {shown_out}/.xglyph-cache\n"
        )
    );

    // An error message quoting a path (printed by the command line itself).
    let missing = font.with_file_name("gone\u{1b}[2J");
    let result = run(&[Path::new("build"), &missing]);
    assert_eq!(result.status.code(), Some(1));
    assert_clean(&result);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(stderr.contains("gone\\u{1b}[2J"), "{stderr}");
}
