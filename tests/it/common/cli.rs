//! Running the `xglyph` binary from the integration tests.

use std::path::Path;
use std::process::Command;

/// `xglyph <args>` with extra environment variables: (exit code, -1 when killed by a
/// signal; stdout; stderr).
pub fn xglyph_env(args: &[&str], env: &[(&str, &str)]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(args)
        .envs(env.iter().copied())
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `xglyph <args>`: (exit code, stdout, stderr).
pub fn xglyph(args: &[&str]) -> (i32, String, String) {
    xglyph_env(args, &[])
}

/// `xglyph import <args> -o <out>`: (exit code, stdout, stderr).
pub fn import(args: &[&str], out: &Path) -> (i32, String, String) {
    let mut all = vec!["import"];
    all.extend_from_slice(args);
    all.extend(["-o", out.to_str().unwrap()]);
    xglyph(&all)
}

/// `xglyph import <args> -o <out>`, which must succeed with nothing on stderr: its stdout.
pub fn import_ok(args: &[&str], out: &Path) -> String {
    let (code, stdout, err) = import(args, out);
    assert_eq!((code, err.as_str()), (0, ""), "import {args:?}");
    stdout
}

/// `xglyph import <args> -o <out>`, which must fail: exit code 1, nothing on stdout, and
/// `out` not created when it did not exist. Its stderr.
pub fn import_fails(args: &[&str], out: &Path) -> String {
    let existed = out.exists();
    let (code, stdout, err) = import(args, out);
    assert_eq!((code, stdout.as_str()), (1, ""), "import {args:?}: {err}");
    assert!(
        existed || !out.exists(),
        "import {args:?}: {} was created",
        out.display()
    );
    err
}
