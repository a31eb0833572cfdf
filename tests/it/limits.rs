//! The limits of the outputs, checked at the source (issue 13: B 4–8, C 10–13, E 19, and
//! issue 12.5's diagnostics from the loaded text). Each test builds its hostile font in a
//! temporary folder and asserts the exact diagnostics (file:line:col) and what the binary
//! does. The single-value limits have folders in `tests/malformed/` (see
//! `source_malformed.rs`).

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use xglyph::commands::check;
use xglyph::source::load_font;

use crate::common::fonts::small_font_folder;
use crate::common::temp::TempFolder;
const TRIANGLE: &str =
    "advance = 500\n[[contour]]\npoints = [[0, 0, 0], [100, 0, 0], [0, 100, 0]]\n";

/// A fresh font folder with the small `font.toml` and `files`.
fn font_dir(tag: &str, files: &[(&str, String)]) -> TempFolder {
    small_font_folder(&format!("limits-{tag}"), files)
}

/// Diagnostics as `file:line:col: severity: message`, paths relative to `dir`.
fn diagnostics(dir: &Path) -> Vec<String> {
    let diags = match load_font(dir) {
        Ok((_, warnings)) => warnings,
        Err(diags) => diags,
    };
    diags
        .iter()
        .map(|d| d.to_string().replace(&format!("{}/", dir.display()), ""))
        .collect()
}

/// Runs the binary; `None` when it had not finished after `limit` (it is then killed).
fn xglyph_within(args: &[&str], dir: &Path, limit: Duration) -> Option<Output> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(args)
        .arg(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run xglyph");
    let start = Instant::now();
    while start.elapsed() < limit {
        if child.try_wait().expect("wait").is_some() {
            return Some(child.wait_with_output().expect("output"));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = child.kill();
    let _ = child.wait();
    None
}

fn xglyph(args: &[&str], dir: &Path) -> Output {
    xglyph_within(args, dir, Duration::from_secs(300)).expect("xglyph finished")
}

/// Issue 13.4: 70,000 sharp points in one glyph would wrap the TrueType point count.
#[test]
fn too_many_points_in_a_glyph_are_refused_at_its_contour() {
    let mut text = String::from("advance = 500\n[[contour]]\npoints = [\n");
    for i in 0..70_000 {
        let _ = writeln!(text, "  [{}, {}, 0],", i % 1000, (i / 1000) * 2 + i % 2);
    }
    text.push_str("]\n");
    let dir = font_dir("points", &[("a.toml", text)]);
    assert_eq!(
        diagnostics(&dir),
        ["a.toml:4:3: error: glyph `a` has 70000 points; a TrueType glyph holds at most 65535"]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 13.5: 33,000 contours panicked in write-fonts after minutes; now `check` and
/// `build` stop at the contour that crosses a limit, and `build` writes nothing. With at
/// least 3 points per contour, the point limit (65,535) binds before the contour limit
/// (32,766): at contour 21,846.
#[test]
fn too_many_contours_are_refused_by_check_and_build() {
    let mut text = String::from("advance = 500\n");
    for i in 0..33_000 {
        let (x, y) = ((i % 100) * 10, (i / 100) * 10 - 1000);
        let _ = writeln!(
            text,
            "[[contour]]\npoints = [[{x}, {y}, 0], [{}, {y}, 0], [{x}, {}, 0]]",
            x + 5,
            y + 5
        );
    }
    let dir = font_dir("contours", &[("a.toml", text)]);
    let expected = "a.toml:43693:11: error: glyph `a` has 99000 points; a TrueType glyph \
                    holds at most 65535";
    let diags = diagnostics(&dir);
    assert_eq!(
        diags
            .iter()
            .filter(|d| d.contains("error"))
            .collect::<Vec<_>>(),
        [expected]
    );
    let out_dir = dir.join("out");
    let out = xglyph(&["build", "-o", out_dir.to_str().expect("utf-8")], &dir);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!("{}/{expected}", dir.display())),
        "{stderr}"
    );
    assert!(
        !out_dir.exists(),
        "a refused build wrote {}",
        out_dir.display()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 13.10: `bN` holds two `b(N-1)`: 40 levels would expand to 2^40 contours. Sizes
/// are computed once per glyph, so the check is instant, and the glyph that crosses the
/// limit is named at the component that brings it over.
#[test]
fn doubling_components_stop_where_the_limit_is_crossed() {
    let mut files = vec![("o.toml".to_string(), TRIANGLE.to_string())];
    let mut prev = "o".to_string();
    for i in 1..=40 {
        let name = format!("b{i:02}");
        files.push((
            format!("{name}.toml"),
            format!(
                "advance = 500\n[[component]]\nbase = \"{prev}\"\n[[component]]\n\
                 base = \"{prev}\"\noffset = [1, 1]\n"
            ),
        ));
        prev = name;
    }
    let files: Vec<(&str, String)> = files.iter().map(|(f, t)| (f.as_str(), t.clone())).collect();
    let dir = font_dir("doubling", &files);
    assert_eq!(
        diagnostics(&dir),
        [
            "b15.toml:5:8: error: with component `b14` (16384 contours, 49152 points), glyph \
             `b15` has at least 32768 contours; a TrueType glyph holds at most 32766"
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 13.11: a 4,000-deep chain loads (the cycle check is one pass, not one search per
/// component), and a cycle closed at the far end is reported on exactly its two edges.
#[test]
fn deep_component_chains_load_and_cycles_are_exact() {
    let n = 4000;
    let names: Vec<String> = (0..n).map(|i| format!("g{i:04}.toml")).collect();
    let files: Vec<(&str, String)> = names
        .iter()
        .enumerate()
        .map(|(i, file)| {
            let text = if i == 0 {
                TRIANGLE.to_string()
            } else {
                format!("advance = 500\n[[component]]\nbase = \"g{:04}\"\n", i - 1)
            };
            (file.as_str(), text)
        })
        .collect();
    let dir = font_dir("chain", &files);
    let (font, warnings) = load_font(&dir).expect("the chain loads");
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(font.glyphs.len(), n);
    let last = font.glyph("g3999").expect("last glyph");
    assert_eq!(last.components[0].base, "g3998");

    // Close a cycle between the last two glyphs: only their two components are on it.
    std::fs::write(
        dir.join("g3998.toml"),
        "advance = 500\n[[component]]\nbase = \"g3997\"\n[[component]]\nbase = \"g3999\"\n",
    )
    .expect("write");
    assert_eq!(
        diagnostics(&dir),
        [
            "g3998.toml:5:8: error: component cycle: `g3998` uses `g3999`, which leads back to it",
            "g3999.toml:3:8: error: component cycle: `g3999` uses `g3998`, which leads back to it",
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 13.12: 10,000 errors in one file: the first 100, then one line for the rest; the
/// summary and the JSON counts still count all of them.
#[test]
fn many_errors_in_a_file_list_the_first_hundred() {
    let mut text = String::from("advance = 500\n[[contour]]\npoints = [\n");
    for i in 0..10_000 {
        let _ = writeln!(text, "  [{}, 0, 5],", i % 1000);
    }
    text.push_str("]\n");
    let dir = font_dir("errors", &[("a.toml", text)]);
    let out = xglyph(&["check"], &dir);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let a = format!("{}/a.toml", dir.display());
    let firsts: Vec<&str> = stdout.lines().filter(|l| l.starts_with(&a)).collect();
    assert_eq!(firsts.len(), 101);
    assert_eq!(
        firsts[0],
        format!("{a}:4:10: error: s = 5 is outside [-1, 1]")
    );
    assert_eq!(
        firsts[99],
        format!("{a}:103:11: error: s = 5 is outside [-1, 1]")
    );
    assert_eq!(
        firsts[100],
        format!(
            "{a}: error: … and 9900 more errors in this file (only the first 100 problems of \
             a file are listed)"
        )
    );
    assert!(stdout.ends_with("\n10000 errors, 0 warnings\n"), "{stdout}");

    let out = xglyph(&["check", "--format", "json"], &dir);
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    assert_eq!(doc["errors"], 10_000);
    assert_eq!(doc["diagnostics"].as_array().map(Vec::len), Some(101));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 13.13: a FIFO, a socket, a dangling link and a folder named `*.toml` are
/// skipped with a warning, and nothing blocks (a FIFO would block a plain read forever).
#[cfg(unix)]
#[test]
fn sources_that_are_not_regular_files_are_skipped_with_a_warning() {
    let dir = font_dir("special", &[("a.toml", TRIANGLE.to_string())]);
    let fifo = |path: &Path| {
        Command::new("mkfifo")
            .arg(path)
            .status()
            .is_ok_and(|s| s.success())
    };
    if !fifo(&dir.join("kerning.toml")) || !fifo(&dir.join("f.toml")) {
        println!("skipped: mkfifo is not available here");
        return;
    }
    std::os::unix::fs::symlink(dir.join("missing.txt"), dir.join("link.toml")).expect("link");
    std::os::unix::fs::symlink(dir.join("a.toml"), dir.join("b.toml")).expect("link");
    let _socket = std::os::unix::net::UnixListener::bind(dir.join("s.toml")).expect("socket");
    std::fs::create_dir(dir.join("z.toml")).expect("mkdir");

    let out = xglyph_within(&["check"], &dir, Duration::from_secs(60))
        .expect("check finished instead of blocking on a FIFO");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let shown: Vec<String> = stdout
        .lines()
        .filter(|l| !l.starts_with("  |"))
        .map(|l| l.replace(&format!("{}/", dir.display()), ""))
        .collect();
    assert_eq!(shown, expected_special());
    assert_eq!(out.status.code(), Some(0), "{stdout}");

    // `build` neither blocks: the linked glyph builds, the FIFOs are skipped.
    let out_dir = dir.join("out");
    let out = xglyph_within(
        &["build", "-o", out_dir.to_str().expect("utf-8")],
        &dir,
        Duration::from_secs(120),
    )
    .expect("build finished instead of blocking on a FIFO");
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    // A `font.toml` that is a FIFO is an error, not a wait.
    std::fs::remove_file(dir.join("font.toml")).expect("rm");
    assert!(fifo(&dir.join("font.toml")));
    let out = xglyph_within(&["check"], &dir, Duration::from_secs(60))
        .expect("check finished instead of blocking on font.toml");
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains(&format!(
            "{}/font.toml: error: `font.toml` is a FIFO (named pipe), not a regular file",
            dir.display()
        )),
        "{stdout}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// What `check` prints for the folder of the test above, in file order.
#[cfg(unix)]
fn expected_special() -> Vec<String> {
    [
        "f.toml: warning: a FIFO (named pipe), not a regular file; skipped",
        "link.toml: warning: a dangling symbolic link (its target does not exist), not a \
         regular file; skipped",
        "s.toml: warning: a socket, not a regular file; skipped",
        "z.toml: warning: a folder, not a regular file; skipped",
        "kerning.toml: warning: `kerning.toml` is a FIFO (named pipe), not a regular file; \
         skipped (no kerning)",
        "0 errors, 5 warnings",
    ]
    .map(String::from)
    .to_vec()
}

/// A name with white space around it (an import from an old font ended its copyright with
/// "\r\n") is a warning at the value: FontBakery fails it in the built fonts.
#[test]
fn names_with_white_space_around_them_are_a_warning() {
    let dir = font_dir("names", &[("a.toml", TRIANGLE.to_string())]);
    let info = format!(
        "{}copyright = \"(c) T\\r\\n\"\nversion = \"1.0\"\nlicense = \" OFL\"\n",
        crate::common::fonts::SMALL_FONT
    );
    std::fs::write(dir.join("font.toml"), info).expect("write");
    let warning = |line: usize, key: &str| {
        format!(
            "font.toml:{line}:{}: warning: `{key}` begins or ends with white space, which the \
             fonts' `name` table would carry and FontBakery fails; remove it",
            key.len() + 4
        )
    };
    assert_eq!(
        diagnostics(&dir),
        vec![warning(7, "copyright"), warning(9, "license")]
    );
}

/// Issue 13.6: `fmt` stopped with "internal error: … would not load back the same" on huge
/// numbers; now it refuses with the diagnostic `check` prints and changes nothing.
#[test]
fn fmt_refuses_out_of_range_values_like_check() {
    let text = "advance = 500\n[[contour]]\npoints = [[0, 0, 0], [1e150, 0, 0], [0, 100, 0]]\n";
    let dir = font_dir("fmt", &[("a.toml", text.to_string())]);
    let out = xglyph(&["fmt"], &dir);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!(
            "{}/a.toml:3:23: error: `x` = 1e150 is outside -16384..16384 font units: \
             TrueType stores 16-bit coordinates, and curves may bulge past their points",
            dir.display()
        )),
        "{stderr}"
    );
    assert!(!stderr.contains("internal error"), "{stderr}");
    assert_eq!(
        std::fs::read_to_string(dir.join("a.toml")).expect("read"),
        text
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 13.6: `build` failed late ("image of 217 x 18446744073709551615 px") on a huge
/// advance; now it stops at the source, names the place, and writes nothing.
#[test]
fn build_refuses_out_of_range_values_before_writing() {
    let glyph = TRIANGLE.replace("advance = 500", "advance = 1e19");
    let kerning = "[[pair]]\nleft = \"a\"\nright = \"a\"\nvalue = 40000\n".to_string();
    let dir = font_dir("build", &[("a.toml", glyph), ("kerning.toml", kerning)]);
    let out_dir = dir.join("out");
    let out = xglyph(&["build", "-o", out_dir.to_str().expect("utf-8")], &dir);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    for line in [
        "a.toml:1:11: error: `advance` = 1e19 is more than 32767 font units, the largest \
         advance TrueType's `hmtx` table holds",
        "kerning.toml:4:9: error: `value` = 40000 is outside -32768..32767 font units \
         (kerning is 16-bit in the `kern` and `GPOS` tables)",
    ] {
        assert!(
            stderr.contains(&format!("{}/{line}", dir.display())),
            "{stderr}"
        );
    }
    assert!(!out_dir.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 13.19: names the outputs cannot carry are refused; the post rule's names load.
#[test]
fn glyph_names_follow_the_post_rule() {
    let ok = ["_notdef.toml", "a.sc.toml", "f_f_i.toml", "x2.toml"];
    let names = [".notdef", "a.sc", "f_f_i", "x2"];
    let files: Vec<(&str, String)> = ok
        .iter()
        .zip(names)
        .map(|(f, n)| (*f, format!("name = \"{n}\"\nadvance = 500\n")))
        .collect();
    let dir = font_dir("names", &files);
    let (font, _) = load_font(&dir).expect("valid names load");
    let loaded: Vec<&str> = font.glyphs.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(loaded, [".notdef", "a.sc", "f_f_i", "x2"]);

    // `a,b` would become `<hkern g2="a,b">`, which SVG font readers take as two glyphs.
    std::fs::write(
        dir.join("kerning.toml"),
        "[[pair]]\nleft = \"x2\"\nright = \"a,b\"\nvalue = -20\n",
    )
    .expect("write");
    std::fs::write(dir.join("ab.toml"), "name = \"a,b\"\nadvance = 500\n").expect("write");
    assert_eq!(
        diagnostics(&dir),
        [
            "ab.toml:1:8: error: glyph name `a,b` contains `,`; glyph names are 1 to 63 \
          characters from A-Z a-z 0-9 . _ (the OpenType `post` rule)"
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 12.5: the caret line comes from the text that was loaded, not from the file on
/// disk (which may have changed since, or be gone).
#[test]
fn diagnostics_show_the_text_that_was_loaded() {
    let dir = font_dir("snippet", &[("a.toml", "advance = \"wide\"\n".to_string())]);
    let diags = load_font(&dir).expect_err("an error");
    std::fs::remove_dir_all(&dir).expect("rm");
    assert_eq!(
        check::text(&diags[0]),
        format!(
            "{}/a.toml:1:11: error: `advance` must be a number, found string\n  | advance = \
             \"wide\"\n  |           ^\n",
            dir.display()
        )
    );
}

/// Issue 13.19 and the importer: an SVG file name outside the rule (`arrow-left.svg`, the
/// usual icon name) becomes a glyph name inside it, so imported sources pass `check`.
#[test]
fn imported_svg_names_follow_the_rule() {
    let dir = std::env::temp_dir().join(format!("xglyph-limits-svgname-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("mkdir");
    let svg = dir.join("arrow-left.svg");
    let ring = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/import/ring.svg");
    std::fs::copy(ring, &svg).expect("copy");
    let out_dir = dir.join("font");
    let out = Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .arg("import")
        .arg(&svg)
        .arg("-o")
        .arg(&out_dir)
        .output()
        .expect("run xglyph");
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (font, warnings) = load_font(&out_dir).expect("imported sources pass check");
    assert!(warnings.is_empty(), "{warnings:?}");
    let names: Vec<&str> = font.glyphs.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["arrow_left"]);
    let _ = std::fs::remove_dir_all(&dir);
}
