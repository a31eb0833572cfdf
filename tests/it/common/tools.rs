//! The external tools some tests drive (Python packages, command-line programs). A missing
//! tool skips the test with a printed notice, unless `XGLYPH_REQUIRE_TOOLS=1` (CI), which
//! turns it into a failure.

use std::ffi::OsStr;
use std::process::Command;

/// `ok`, or the skip: prints that `what` is missing and how to `install` it, or panics
/// under `XGLYPH_REQUIRE_TOOLS=1`.
pub fn available(ok: bool, what: &str, install: &str) -> bool {
    if !ok {
        if std::env::var("XGLYPH_REQUIRE_TOOLS").as_deref() == Ok("1") {
            panic!("XGLYPH_REQUIRE_TOOLS=1 but {what} is missing; {install}");
        }
        println!("skipped: {what} is missing; {install}; XGLYPH_REQUIRE_TOOLS=1 makes this fail");
    }
    ok
}

/// Whether `python3 -c "import <modules>"` succeeds (`modules` comma-separated).
pub fn python_imports(modules: &str) -> bool {
    Command::new("python3")
        .args(["-c", &format!("import {modules}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Whether `program args…` runs and exits 0.
pub fn program_runs(program: &str, args: &[&str]) -> bool {
    Command::new(program)
        .args(args)
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Runs `cmd`, asserts it exits 0, and returns its stdout and stderr.
pub fn run(cmd: &mut Command) -> String {
    let out = cmd.output().expect("runs");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "{cmd:?} failed:\n{text}");
    text
}

/// Runs the Python `script` with `args`, asserts it exits 0, and parses its stdout as JSON.
pub fn python_json<T: serde::de::DeserializeOwned>(script: &str, args: &[&dyn AsRef<OsStr>]) -> T {
    let out = Command::new("python3")
        .arg("-c")
        .arg(script)
        .args(args.iter().map(|a| a.as_ref()))
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "python: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

/// `tests/it/vf_compare.py`: the variable fonts `ours` and `theirs` instanced at each of
/// `places` (`;`-separated, `tag=value,…`), compared glyph by glyph for `glyphs`; per place
/// (as written) and glyph, the script's JSON (distance, contours, advance, width).
pub fn vf_compare<T: serde::de::DeserializeOwned>(
    ours: &std::path::Path,
    theirs: &std::path::Path,
    places: &str,
    glyphs: &[&str],
) -> T {
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/it/vf_compare.py");
    let out = Command::new("python3")
        .arg(&script)
        .arg(ours)
        .arg(theirs)
        .arg(places)
        .args(glyphs)
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "vf_compare.py: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

/// Whether fontmake, fontc, fontTools and ufoLib2 are there (else the skip of
/// [`available`]).
pub fn designspace_compilers_available() -> bool {
    available(
        python_imports("fontTools.designspaceLib, fontTools.varLib.instancer, ufoLib2")
            && ["fontmake", "fontc"]
                .iter()
                .all(|t| program_runs(t, &["--help"])),
        "fontmake/fontc/fontTools/ufoLib2",
        "pip install fontmake fontc ufoLib2",
    )
}

/// The outline comparisons of a [`check_designspace_compilers`] report that passed: one
/// per compiler and position.
pub fn outlines_compared(report: &str) -> usize {
    report
        .lines()
        .filter(|l| l.starts_with("ok ") && l.contains(": outlines at "))
        .count()
}

/// Compiles the designspace `ds` with fontmake and with fontc into `dir`, then runs
/// `tests/it/designspace_check.py` against xglyph's variable font `ours` at the user
/// `positions`; returns the check's report (it exits 0 only when every check holds).
pub fn check_designspace_compilers(
    ds: &std::path::Path,
    ours: &std::path::Path,
    dir: &std::path::Path,
    tolerance: f64,
    positions: &[&str],
) -> String {
    let fontmake = dir.join("fontmake.ttf");
    run(Command::new("fontmake")
        .arg("-m")
        .arg(ds)
        .args(["-o", "variable", "--output-path"])
        .arg(&fontmake));
    let fontc = dir.join("fontc-build");
    run(Command::new("fontc").arg("--build-dir").arg(&fontc).arg(ds));
    let script =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/it/designspace_check.py");
    run(Command::new("python3")
        .arg(&script)
        .arg(ds)
        .arg(ours)
        .arg(&fontmake)
        .arg(fontc.join("font.ttf"))
        .arg(tolerance.to_string())
        .args(positions))
}
