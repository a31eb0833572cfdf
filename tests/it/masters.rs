//! Fonts with masters (issue 16): the loader and its compatibility errors, blending, `fmt`,
//! `check`, `render --at`, named static instances; and the single-master promise: a font
//! without `[[axis]]` builds byte for byte as before masters existed.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use sha2::{Digest, Sha256};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh, empty scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("masters-{name}"));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn xglyph(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(args)
        .output()
        .expect("xglyph runs")
}

/// SHA-256 (hex) of every file under `dir` but the fit cache, by relative path.
fn hashes(dir: &Path, prefix: &str, out: &mut BTreeMap<String, String>) {
    let mut entries: Vec<PathBuf> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let rel = format!("{prefix}/{name}");
        if path.is_dir() {
            hashes(&path, &rel, out);
        } else if name != ".xglyph-cache" {
            let digest = Sha256::digest(fs::read(&path).unwrap());
            let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
            out.insert(rel, hex);
        }
    }
}

/// `tests/fixtures/mini` and `glyphs/` (single-master fonts) build to exactly the bytes
/// they built to before masters were added: the SHA-256 of every output file was recorded
/// from the code of commit 13aa68e in `tests/fixtures/single_master_outputs.sha256`.
#[test]
fn single_master_outputs_are_byte_identical_to_before_masters() {
    let tmp = scratch("golden");
    for (name, dir) in [("mini", "tests/fixtures/mini"), ("glyphs", "glyphs")] {
        let out = tmp.join(name);
        let result = xglyph(&[
            "build",
            root().join(dir).to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(
            result.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&result.stderr)
        );
    }
    let mut got = BTreeMap::new();
    hashes(&tmp.join("mini"), "mini", &mut got);
    hashes(&tmp.join("glyphs"), "glyphs", &mut got);
    let golden =
        fs::read_to_string(root().join("tests/fixtures/single_master_outputs.sha256")).unwrap();
    let want: BTreeMap<String, String> = golden
        .lines()
        .map(|l| {
            let (hash, path) = l.split_once("  ").unwrap();
            (path.to_string(), hash.to_string())
        })
        .collect();
    assert_eq!(want.len(), 177);
    let differ: Vec<&String> = want
        .keys()
        .chain(got.keys())
        .filter(|k| want.get(*k) != got.get(*k))
        .collect();
    assert!(differ.is_empty(), "outputs that changed: {differ:?}");
}
